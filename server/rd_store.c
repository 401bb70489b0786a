/*
 * rd_store — jobs in SQLite (rd_store.h).
 *
 * The file is created with auto_vacuum=INCREMENTAL, and the pages of
 * deleted rows are returned after each retention pass, so the file shrinks
 * with what it keeps.
 *
 * Every public function takes `mu`, runs its statements on the one
 * connection and releases it; multi-statement changes run in one
 * transaction (BEGIN IMMEDIATE ... COMMIT, ROLLBACK on any failure).  Every
 * sqlite3_* return is checked; a failure becomes RD_EINTERNAL with SQLite's
 * message (RD_ENOMEM for SQLITE_NOMEM).
 */
#include "rd_store.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <sqlite3.h>
#include <zlib.h>

#include "rd_store_check.h"

/* A writer waits this long for a lock held by another process (a second
 * server on the same directory) before failing. */
#define BUSY_TIMEOUT_MS 5000

/* Statements of the per-job path (insert, update, read, delete) are
 * prepared once and kept, reset after each use: preparing costs about as
 * much as running them. */
#define KEPT_MAX 8

struct rd_store {
    sqlite3 *db;
    int lock_fd; /* DIR/jobs.lock, write-locked while we live; -1 for :memory: */
    pthread_mutex_t mu;
    struct {
        const char *sql; /* the literal's address is the key */
        sqlite3_stmt *st;
    } kept[KEPT_MAX];
    int nkept;
    /* What the start found (rd_store_get_report): the WAL, a file moved
     * aside, sweep rows left out. */
    char report[3][1500];
    char report_all[4600];
};

static const char schema[] =
    "CREATE TABLE IF NOT EXISTS jobs ("
    " seq INTEGER PRIMARY KEY AUTOINCREMENT,"
    " id TEXT NOT NULL UNIQUE,"
    " analysis TEXT NOT NULL,"
    " status TEXT NOT NULL,"
    " progress REAL NOT NULL DEFAULT 0,"
    " created_ns INTEGER NOT NULL DEFAULT 0,"
    " started_ns INTEGER NOT NULL DEFAULT 0,"
    " finished_ns INTEGER NOT NULL DEFAULT 0,"
    " scene TEXT,"
    " error TEXT,"
    " body BLOB,"
    " body_len INTEGER NOT NULL DEFAULT 0,"
    " name TEXT, cache_key TEXT, idem_key TEXT, idem_hash TEXT, body_crc INTEGER);"
    /* jobs_retain below serves every query on finished_ns; a second index
     * on it only cost a page write per job (dropped from older stores). */
    "DROP INDEX IF EXISTS jobs_finished;"
    /* Covers the retention query (select_expired), which runs whenever a job
     * ends: read from the table, each row's columns after `body` would cost
     * a walk through the body's overflow pages. */
    "CREATE INDEX IF NOT EXISTS jobs_retain ON jobs (finished_ns, seq, status, body_len, id);"
    /* Finished sweeps (rd_sweeps): written once when final, never changed. */
    "CREATE TABLE IF NOT EXISTS sweeps ("
    " seq INTEGER PRIMARY KEY AUTOINCREMENT,"
    " id TEXT NOT NULL UNIQUE,"
    " meta TEXT NOT NULL,"
    " body TEXT NOT NULL,"
    " csv TEXT NOT NULL,"
    " crc INTEGER);";

/* Columns added after the first release, for stores an older server wrote:
 * table, column, type.  A NULL crc (a row an older server wrote) is not
 * verified. */
static const char *const added_columns[][3] = {
    {"jobs", "name", "TEXT"},      {"jobs", "cache_key", "TEXT"},   {"jobs", "idem_key", "TEXT"},
    {"jobs", "idem_hash", "TEXT"}, {"jobs", "body_crc", "INTEGER"}, {"sweeps", "crc", "INTEGER"},
};

static const char delete_sql[] = "DELETE FROM jobs WHERE id = ?";

static int db_fail(sqlite3 *db, int src, const char *what, rd_error *err)
{
    return rd_error_set(err, src == SQLITE_NOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                        "Job store: %s failed: %s.", what,
                        db ? sqlite3_errmsg(db) : sqlite3_errstr(src));
}

static int exec(sqlite3 *db, const char *sql, rd_error *err)
{
    int rc = sqlite3_exec(db, sql, NULL, NULL, NULL);
    return rc == SQLITE_OK ? RD_OK : db_fail(db, rc, sql, err);
}

/* Adds the columns of added_columns that an older store lacks (TEXT, NULL). */
static int add_columns(sqlite3 *db, rd_error *err)
{
    for (size_t i = 0; i < sizeof added_columns / sizeof added_columns[0]; i++) {
        char sql[128];
        snprintf(sql, sizeof sql, "SELECT 1 FROM pragma_table_info('%s') WHERE name = '%s'",
                 added_columns[i][0], added_columns[i][1]);
        sqlite3_stmt *st;
        int rc = sqlite3_prepare_v2(db, sql, -1, &st, NULL);
        if (rc != SQLITE_OK)
            return db_fail(db, rc, "table_info", err);
        rc = sqlite3_step(st);
        sqlite3_finalize(st);
        if (rc == SQLITE_ROW)
            continue;
        if (rc != SQLITE_DONE)
            return db_fail(db, rc, "table_info", err);
        snprintf(sql, sizeof sql, "ALTER TABLE %s ADD COLUMN %s %s", added_columns[i][0],
                 added_columns[i][1], added_columns[i][2]);
        int status = exec(db, sql, err);
        if (status != RD_OK)
            return status;
    }
    return RD_OK;
}

/* mkdir -p with mode 0700 for the directories it creates. */
static int make_dirs(const char *dir, rd_error *err)
{
    char path[4096];
    if (snprintf(path, sizeof path, "%s", dir) >= (int)sizeof path)
        return rd_error_set(err, RD_EINVAL, "", "--data %s: path too long.", dir);
    for (char *p = path + 1;; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char c = *p;
        *p = '\0';
        if (mkdir(path, 0700) != 0 && errno != EEXIST)
            return rd_error_set(err, RD_EINVAL, "", "--data %s: cannot create %s: %s.", dir, path,
                                strerror(errno));
        *p = c;
        if (c == '\0')
            break;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return rd_error_set(err, RD_EINVAL, "",
                            "--data %s is not a directory: give the directory that holds (or "
                            "will hold) jobs.sqlite3.",
                            dir);
    return RD_OK;
}

/* One server per store: two would each mark the other's running jobs
 * interrupted at start.  A POSIX record lock on DIR/jobs.lock, released by
 * the kernel when the process ends however it ends. */
static int lock_dir(const char *dir, int *fd_out, rd_error *err)
{
    char path[4200];
    *fd_out = -1;
    if (snprintf(path, sizeof path, "%s/jobs.lock", dir) >= (int)sizeof path)
        return rd_error_set(err, RD_EINVAL, "", "--data %s: path too long.", dir);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0600);
    if (fd < 0)
        return rd_error_set(err, RD_EINVAL, "", "--data %s: cannot open %s: %s.", dir, path,
                            strerror(errno));
    struct flock lk = {.l_type = F_WRLCK, .l_whence = SEEK_SET};
    if (fcntl(fd, F_SETLK, &lk) != 0) {
        int e = errno;
        close(fd);
        if (e == EACCES || e == EAGAIN)
            return rd_error_set(err, RD_EINVAL, "",
                                "--data %s is in use by another ringdyn-server; give each server "
                                "its own directory.",
                                dir);
        return rd_error_set(err, RD_EINVAL, "", "--data %s: cannot lock %s: %s.", dir, path,
                            strerror(e));
    }
    *fd_out = fd;
    return RD_OK;
}

/* The pragmas and the schema.  WAL: readers never block the writer, and a
 * crash is recovered at the next open; NORMAL: no fsync per commit (see
 * rd_store.h). */
static int set_up(sqlite3 *db, int memory, rd_error *err)
{
    int status;
    if ((status = exec(db, "PRAGMA auto_vacuum=INCREMENTAL", err)) ||
        (status =
             exec(db, memory ? "PRAGMA journal_mode=MEMORY" : "PRAGMA journal_mode=WAL", err)) ||
        (status = exec(db, "PRAGMA synchronous=NORMAL", err)) || (status = exec(db, schema, err)))
        return status;
    return add_columns(db, err);
}

/* PRAGMA quick_check: 1 in *corrupt (and SQLite's first finding in `why`)
 * when the file is damaged; reads every page, and replays the WAL. */
static int quick_check(sqlite3 *db, int *corrupt, char *why, size_t n, rd_error *err)
{
    sqlite3_stmt *st;
    int rc = sqlite3_prepare_v2(db, "PRAGMA quick_check(1)", -1, &st, NULL);
    if (rc == SQLITE_OK && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        const char *text = (const char *)sqlite3_column_text(st, 0);
        *corrupt = !text || strcmp(text, "ok") != 0;
        snprintf(why, n, "SQLite's quick_check: %s", text ? text : "no answer");
        rc = SQLITE_DONE;
    } else if ((rc & 0xff) == SQLITE_CORRUPT || (rc & 0xff) == SQLITE_NOTADB) {
        *corrupt = 1;
        snprintf(why, n, "SQLite's quick_check: %s", sqlite3_errmsg(db));
        rc = SQLITE_DONE;
    }
    for (char *c = why; *c; c++) /* one log line */
        *c = *c == '\n' ? ' ' : *c;
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? RD_OK : db_fail(db, rc, "quick_check", err);
}

/* Opens `file` as the store: quick_check (a file), then the pragmas and the
 * schema.  *corrupt = 1, with the reason in `why`, when SQLite finds the
 * file damaged (not for other failures: a busy or unreadable file is no
 * reason to move it aside). */
static int open_db(rd_store *s, const char *file, int memory, int *corrupt, char *why, size_t n,
                   rd_error *err)
{
    *corrupt = 0;
    int rc = sqlite3_open_v2(
        file, &s->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX, NULL);
    if (rc != SQLITE_OK)
        return rd_error_set(err, RD_EINVAL, "", "--data: cannot open %s: %s.", file,
                            s->db ? sqlite3_errmsg(s->db) : sqlite3_errstr(rc));
    if ((rc = sqlite3_busy_timeout(s->db, BUSY_TIMEOUT_MS)) != SQLITE_OK)
        return db_fail(s->db, rc, "busy_timeout", err);
    int status = memory ? RD_OK : quick_check(s->db, corrupt, why, n, err);
    if (status == RD_OK && !*corrupt)
        status = set_up(s->db, memory, err);
    int code = sqlite3_errcode(s->db) & 0xff;
    if (status != RD_OK && (code == SQLITE_CORRUPT || code == SQLITE_NOTADB)) {
        *corrupt = 1;
        snprintf(why, n, "%s", err->message);
    }
    return status;
}

/* Opens the store file, moving a damaged one aside once (rd_store.h). */
static int open_checked(rd_store *s, const char *file, int memory, rd_error *err)
{
    char why[600];
    struct stat st;
    if (!memory && stat(file, &st) == 0 && S_ISREG(st.st_mode) && st.st_size == 0) {
        /* SQLite would take it for a new, empty store: a silent loss. */
        int rc = rd_store_quarantine(file, "it is 0 bytes long: truncated, or never written",
                                     s->report[1], sizeof s->report[1], err);
        if (rc != RD_OK)
            return rc;
    } else if (!memory) {
        rd_store_check_wal(file, s->report[0], sizeof s->report[0]);
    }
    for (int attempt = 0;; attempt++) {
        int corrupt = 0;
        int status = open_db(s, file, memory, &corrupt, why, sizeof why, err);
        if (status == RD_OK && !corrupt)
            return RD_OK;
        if (!corrupt || attempt > 0)
            return status != RD_OK
                       ? status
                       : rd_error_set(err, RD_EINTERNAL, "",
                                      "job store %s: a new store is damaged: %s", file, why);
        sqlite3_close(s->db);
        s->db = NULL;
        rd_error_init(err);
        status = rd_store_quarantine(file, why, s->report[1], sizeof s->report[1], err);
        if (status != RD_OK)
            return status;
    }
}

int rd_store_create(const char *dir, rd_store **out, rd_error *err)
{
    *out = NULL;
    char file[4200];
    int memory = strcmp(dir, ":memory:") == 0;
    if (memory)
        snprintf(file, sizeof file, ":memory:");
    else if (make_dirs(dir, err) != RD_OK)
        return err->code;
    else if (snprintf(file, sizeof file, "%s/jobs.sqlite3", dir) >= (int)sizeof file)
        return rd_error_set(err, RD_EINVAL, "", "--data %s: path too long.", dir);
    rd_store *s = calloc(1, sizeof *s);
    if (!s)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    s->lock_fd = -1;
    if (!memory && lock_dir(dir, &s->lock_fd, err) != RD_OK) {
        free(s);
        return err->code;
    }
    int status = open_checked(s, file, memory, err);
    if (status == RD_OK) {
        int e = pthread_mutex_init(&s->mu, NULL);
        if (e != 0)
            status = rd_error_set(err, RD_EINTERNAL, "", "pthread_mutex_init: %s.", strerror(e));
    }
    if (status != RD_OK) {
        sqlite3_close(s->db);
        if (s->lock_fd >= 0)
            close(s->lock_fd);
        free(s);
        return status;
    }
    *out = s;
    return RD_OK;
}

const char *rd_store_get_report(rd_store *store)
{
    char *at = store->report_all, *end = at + sizeof store->report_all;
    *at = '\0';
    for (int k = 0; k < 3; k++)
        if (store->report[k][0] && at < end - 1)
            at += snprintf(at, (size_t)(end - at), "%s%s", at == store->report_all ? "" : "\n",
                           store->report[k]);
    return store->report_all;
}

void rd_store_free(rd_store *store)
{
    if (!store)
        return;
    for (int i = 0; i < store->nkept; i++)
        sqlite3_finalize(store->kept[i].st);
    sqlite3_close(store->db); /* every other statement is finalized where it is used */
    if (store->lock_fd >= 0)
        close(store->lock_fd);
    pthread_mutex_destroy(&store->mu);
    free(store);
}

/* Prepares `sql` or fails with its text. */
static int prepare(sqlite3 *db, const char *sql, sqlite3_stmt **st, rd_error *err)
{
    int rc = sqlite3_prepare_v2(db, sql, -1, st, NULL);
    return rc == SQLITE_OK ? RD_OK : db_fail(db, rc, sql, err);
}

/* Steps a statement that returns no rows, then finalizes it. */
static int run(sqlite3 *db, sqlite3_stmt *st, const char *what, int bind_rc, rd_error *err)
{
    int rc = bind_rc == SQLITE_OK ? sqlite3_step(st) : bind_rc;
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? RD_OK : db_fail(db, rc, what, err);
}

/* A kept statement for the string literal `sql` (mu held): prepared on its
 * first use; give it back with done_kept, never finalize it. */
static int prepare_kept(rd_store *store, const char *sql, sqlite3_stmt **st, rd_error *err)
{
    for (int i = 0; i < store->nkept; i++)
        if (store->kept[i].sql == sql) {
            *st = store->kept[i].st;
            return RD_OK;
        }
    if (store->nkept == KEPT_MAX)
        return rd_error_set(err, RD_EINTERNAL, "", "Job store: too many kept statements.");
    int rc = sqlite3_prepare_v3(store->db, sql, -1, SQLITE_PREPARE_PERSISTENT, st, NULL);
    if (rc != SQLITE_OK)
        return db_fail(store->db, rc, sql, err);
    store->kept[store->nkept].sql = sql;
    store->kept[store->nkept++].st = *st;
    return RD_OK;
}

/* Ready for the next use: no row in progress, no bound pointer left behind. */
static void done_kept(sqlite3_stmt *st)
{
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
}

/* run() for a kept statement. */
static int run_kept(sqlite3 *db, sqlite3_stmt *st, const char *what, int bind_rc, rd_error *err)
{
    int rc = bind_rc == SQLITE_OK ? sqlite3_step(st) : bind_rc;
    done_kept(st);
    return rc == SQLITE_DONE ? RD_OK : db_fail(db, rc, what, err);
}

/* CRC-32 (zlib) of a stored text: written with it, checked when it is read,
 * so a damaged page is an error, never a wrong answer. */
static sqlite3_int64 body_crc(const char *data, size_t len)
{
    uLong c = crc32(0L, Z_NULL, 0);
    while (len > 0) { /* crc32 takes a uInt length */
        uInt n = len > (1u << 30) ? 1u << 30 : (uInt)len;
        c = crc32(c, (const Bytef *)data, n);
        data += n;
        len -= n;
    }
    return (sqlite3_int64)c;
}

static int bind_text(sqlite3_stmt *st, int i, const char *s)
{
    return s ? sqlite3_bind_text(st, i, s, -1, SQLITE_STATIC) : sqlite3_bind_null(st, i);
}

int rd_store_insert(rd_store *store, const rd_store_row *row, const char *scene, const char *body,
                    rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare_kept(store,
                              "INSERT INTO jobs (id, analysis, status, progress, created_ns, "
                              "started_ns, scene, name, cache_key, idem_key, idem_hash, "
                              "finished_ns, error, body, body_len, body_crc) "
                              "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                              &st, err);
    if (status == RD_OK) {
        int b = sqlite3_bind_text(st, 1, row->id, -1, SQLITE_STATIC);
        b = b ? b : sqlite3_bind_text(st, 2, row->analysis, -1, SQLITE_STATIC);
        b = b ? b : sqlite3_bind_text(st, 3, row->status, -1, SQLITE_STATIC);
        b = b ? b : sqlite3_bind_double(st, 4, row->progress);
        b = b ? b : sqlite3_bind_int64(st, 5, row->created_ns);
        b = b ? b : sqlite3_bind_int64(st, 6, row->started_ns);
        b = b ? b : bind_text(st, 7, scene);
        b = b ? b : bind_text(st, 8, row->name);
        b = b ? b : bind_text(st, 9, row->cache_key);
        b = b ? b : bind_text(st, 10, row->idem_key);
        b = b ? b : bind_text(st, 11, row->idem_hash);
        b = b ? b : sqlite3_bind_int64(st, 12, row->finished_ns);
        b = b ? b : bind_text(st, 13, row->error);
        b = b      ? b
            : body ? sqlite3_bind_blob64(st, 14, body, row->body_len, SQLITE_STATIC)
                   : sqlite3_bind_null(st, 14);
        b = b ? b : sqlite3_bind_int64(st, 15, body ? (sqlite3_int64)row->body_len : 0);
        b = b      ? b
            : body ? sqlite3_bind_int64(st, 16, body_crc(body, row->body_len))
                   : sqlite3_bind_null(st, 16);
        status = run_kept(store->db, st, "insert", b, err);
    }
    pthread_mutex_unlock(&store->mu);
    return status;
}

int rd_store_update(rd_store *store, const rd_store_row *row, const char *body, rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status =
        prepare_kept(store,
                     body ? "UPDATE jobs SET status = ?, progress = ?, started_ns = ?, "
                            "finished_ns = ?, error = ?, body = ?, body_len = ?, body_crc = ? "
                            "WHERE id = ?"
                          : "UPDATE jobs SET status = ?, progress = ?, started_ns = ?, "
                            "finished_ns = ?, error = ? WHERE id = ?",
                     &st, err);
    if (status == RD_OK) {
        int b = sqlite3_bind_text(st, 1, row->status, -1, SQLITE_STATIC);
        b = b ? b : sqlite3_bind_double(st, 2, row->progress);
        b = b ? b : sqlite3_bind_int64(st, 3, row->started_ns);
        b = b ? b : sqlite3_bind_int64(st, 4, row->finished_ns);
        b = b ? b : bind_text(st, 5, row->error);
        int next = 6;
        if (body) {
            b = b ? b : sqlite3_bind_blob64(st, 6, body, row->body_len, SQLITE_STATIC);
            b = b ? b : sqlite3_bind_int64(st, 7, (sqlite3_int64)row->body_len);
            b = b ? b : sqlite3_bind_int64(st, 8, body_crc(body, row->body_len));
            next = 9;
        }
        b = b ? b : sqlite3_bind_text(st, next, row->id, -1, SQLITE_STATIC);
        status = run_kept(store->db, st, "update", b, err);
    }
    pthread_mutex_unlock(&store->mu);
    return status;
}

int rd_store_mark(rd_store *store, const char *from_a, const char *from_b, const char *to,
                  int64_t finished_ns, const char *error, int *changed, rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare(store->db,
                         "UPDATE jobs SET status = ?, finished_ns = ?, error = ? "
                         "WHERE status IN (?, ?)",
                         &st, err);
    if (status == RD_OK) {
        int b = sqlite3_bind_text(st, 1, to, -1, SQLITE_STATIC);
        b = b ? b : sqlite3_bind_int64(st, 2, finished_ns);
        b = b ? b : bind_text(st, 3, error);
        b = b ? b : sqlite3_bind_text(st, 4, from_a, -1, SQLITE_STATIC);
        b = b ? b : sqlite3_bind_text(st, 5, from_b, -1, SQLITE_STATIC);
        status = run(store->db, st, "mark", b, err);
        if (changed)
            *changed = status == RD_OK ? sqlite3_changes(store->db) : 0;
    }
    pthread_mutex_unlock(&store->mu);
    return status;
}

static void copy_text(char *dst, size_t n, const unsigned char *src)
{
    snprintf(dst, n, "%s", src ? (const char *)src : "");
}

int rd_store_load(rd_store *store, int (*each)(void *ctx, const rd_store_row *row), void *ctx,
                  rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare(store->db,
                         "SELECT id, analysis, status, progress, created_ns, started_ns, "
                         "finished_ns, error, body_len, name, cache_key, idem_key, idem_hash "
                         "FROM jobs ORDER BY seq",
                         &st, err);
    int rc = SQLITE_DONE;
    while (status == RD_OK && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        rd_store_row row;
        memset(&row, 0, sizeof row);
        copy_text(row.id, sizeof row.id, sqlite3_column_text(st, 0));
        copy_text(row.analysis, sizeof row.analysis, sqlite3_column_text(st, 1));
        row.status = (const char *)sqlite3_column_text(st, 2);
        row.progress = sqlite3_column_double(st, 3);
        row.created_ns = sqlite3_column_int64(st, 4);
        row.started_ns = sqlite3_column_int64(st, 5);
        row.finished_ns = sqlite3_column_int64(st, 6);
        row.error = (const char *)sqlite3_column_text(st, 7);
        row.body_len = (size_t)sqlite3_column_int64(st, 8);
        row.name = (const char *)sqlite3_column_text(st, 9);
        row.cache_key = (const char *)sqlite3_column_text(st, 10);
        row.idem_key = (const char *)sqlite3_column_text(st, 11);
        row.idem_hash = (const char *)sqlite3_column_text(st, 12);
        if (!row.status) {
            status = rd_error_set(err, RD_EINTERNAL, "", "Job store: a row without a status.");
            break;
        }
        status = each(ctx, &row);
    }
    if (status == RD_OK && rc != SQLITE_DONE)
        status = db_fail(store->db, rc, "load", err);
    sqlite3_finalize(st);
    pthread_mutex_unlock(&store->mu);
    return status;
}

int rd_store_delete(rd_store *store, const char *id, rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare_kept(store, delete_sql, &st, err);
    if (status == RD_OK)
        status =
            run_kept(store->db, st, "delete", sqlite3_bind_text(st, 1, id, -1, SQLITE_STATIC), err);
    pthread_mutex_unlock(&store->mu);
    return status;
}

/* The CRC of column `col` against `data`: RD_OK when they agree or the row
 * has none (an older server wrote it); RD_EINTERNAL naming what is damaged. */
static int verify(sqlite3_stmt *st, int col, const char *data, size_t n, const char *what,
                  const char *id, rd_error *err)
{
    if (sqlite3_column_type(st, col) == SQLITE_NULL)
        return RD_OK;
    sqlite3_int64 want = sqlite3_column_int64(st, col), got = body_crc(data, n);
    if (got == want)
        return RD_OK;
    return rd_error_set(err, RD_EINTERNAL, "",
                        "Job store: %s %s is damaged on disk (CRC-32 %08llx, written as %08llx; "
                        "%zu bytes): it is not served.  Submit the scene again (README: The job "
                        "store).",
                        what, id, (unsigned long long)got, (unsigned long long)want, n);
}

int rd_store_read_body(rd_store *store, const char *id, char **body, size_t *len, rd_error *err)
{
    *body = NULL;
    *len = 0;
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare_kept(
        store, "SELECT body, body_crc FROM jobs WHERE id = ? AND body IS NOT NULL", &st, err);
    if (status == RD_OK) {
        int rc = sqlite3_bind_text(st, 1, id, -1, SQLITE_STATIC);
        rc = rc ? rc : sqlite3_step(st);
        if (rc == SQLITE_ROW) {
            size_t n = (size_t)sqlite3_column_bytes(st, 0);
            const void *data = sqlite3_column_blob(st, 0);
            *body = malloc(n + 1);
            if (!*body || (!data && n > 0)) {
                free(*body);
                *body = NULL;
                status = rd_error_set(err, RD_ENOMEM, "", "Out of memory reading job %s.", id);
            } else {
                if (n > 0)
                    memcpy(*body, data, n);
                (*body)[n] = '\0';
                *len = n;
                status = verify(st, 1, *body, n, "the stored result of job", id, err);
                if (status != RD_OK) {
                    free(*body);
                    *body = NULL;
                    *len = 0;
                }
            }
        } else if (rc == SQLITE_DONE) {
            status = rd_error_set(err, RD_ENOTFOUND, "", "Job %s has no stored result.", id);
        } else {
            status = db_fail(store->db, rc, "read", err);
        }
        done_kept(st);
    }
    pthread_mutex_unlock(&store->mu);
    return status;
}

/* The ids to delete, newest finished first (see rd_store.h); malloc'd array
 * of 17-byte ids in *ids, count in *n. */
static int select_expired(sqlite3 *db, size_t keep_max, size_t keep_bytes, int64_t oldest_ns,
                          char (**ids)[17], size_t *n, rd_error *err)
{
    sqlite3_stmt *st;
    *ids = NULL;
    *n = 0;
    int status = prepare(db,
                         "SELECT id, body_len, finished_ns FROM jobs WHERE status IN "
                         "('succeeded', 'failed', 'cancelled', 'interrupted') "
                         "ORDER BY finished_ns DESC, seq DESC",
                         &st, err);
    if (status != RD_OK)
        return status;
    size_t kept = 0, bytes = 0, cap = 0;
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        size_t len = (size_t)sqlite3_column_int64(st, 1);
        int64_t finished = sqlite3_column_int64(st, 2);
        int expired =
            kept >= 1 && (kept + 1 > keep_max || bytes + len > keep_bytes || finished < oldest_ns);
        if (!expired) {
            kept++;
            bytes += len;
            continue;
        }
        if (*n == cap) {
            cap = cap ? 2 * cap : 16;
            char(*grown)[17] = realloc(*ids, cap * sizeof **ids);
            if (!grown) {
                status = rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
                break;
            }
            *ids = grown;
        }
        copy_text((*ids)[(*n)++], 17, sqlite3_column_text(st, 0));
    }
    if (status == RD_OK && rc != SQLITE_DONE)
        status = db_fail(db, rc, "retention", err);
    sqlite3_finalize(st);
    return status;
}

int rd_store_retain(rd_store *store, size_t keep_max, size_t keep_bytes, int64_t oldest_ns,
                    void (*gone)(void *ctx, const char *id), void *ctx, rd_error *err)
{
    char(*ids)[17] = NULL;
    size_t n = 0;
    pthread_mutex_lock(&store->mu);
    int status = select_expired(store->db, keep_max, keep_bytes, oldest_ns, &ids, &n, err);
    if (status == RD_OK && n > 0 && (status = exec(store->db, "BEGIN IMMEDIATE", err)) == RD_OK) {
        for (size_t i = 0; i < n && status == RD_OK; i++) {
            sqlite3_stmt *st;
            status = prepare_kept(store, delete_sql, &st, err);
            if (status == RD_OK)
                status = run_kept(store->db, st, "delete",
                                  sqlite3_bind_text(st, 1, ids[i], -1, SQLITE_STATIC), err);
        }
        if (status == RD_OK)
            status = exec(store->db, "COMMIT", err);
        /* Hands the freed pages back to the file system (auto_vacuum=INCREMENTAL). */
        if (status == RD_OK)
            status = exec(store->db, "PRAGMA incremental_vacuum", err);
        else
            sqlite3_exec(store->db, "ROLLBACK", NULL, NULL, NULL);
    }
    pthread_mutex_unlock(&store->mu);
    for (size_t i = 0; status == RD_OK && i < n; i++)
        gone(ctx, ids[i]);
    free(ids);
    return status;
}

/* ---- finished sweeps ---- */

/* The CRC of a sweep row: its three texts, each with its NUL. */
static sqlite3_int64 sweep_crc(const char *meta, const char *body, const char *csv)
{
    uLong c = (uLong)body_crc(meta, strlen(meta) + 1);
    c = crc32_combine(c, (uLong)body_crc(body, strlen(body) + 1), (z_off_t)(strlen(body) + 1));
    return (sqlite3_int64)crc32_combine(c, (uLong)body_crc(csv, strlen(csv) + 1),
                                        (z_off_t)(strlen(csv) + 1));
}

/* A sweep row whose CRC does not match, in the report: left out of the
 * list (404), named in the log. */
static void left_out(char *report, size_t n, const char *id)
{
    size_t used = strlen(report);
    if (used == 0)
        snprintf(report, n,
                 "job store: finished sweeps damaged on disk (CRC-32 mismatch), left out: %s", id);
    else if (used + 20 < n)
        snprintf(report + used, n - used, ", %s", id);
}

int rd_store_sweep_put(rd_store *store, const char *id, const char *meta, const char *body,
                       const char *csv, rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare(store->db,
                         "INSERT OR REPLACE INTO sweeps (id, meta, body, csv, crc) "
                         "VALUES (?, ?, ?, ?, ?)",
                         &st, err);
    if (status == RD_OK) {
        int rc = bind_text(st, 1, id);
        rc = rc ? rc : bind_text(st, 2, meta);
        rc = rc ? rc : bind_text(st, 3, body);
        rc = rc ? rc : bind_text(st, 4, csv);
        rc = rc ? rc : sqlite3_bind_int64(st, 5, sweep_crc(meta, body, csv));
        status = run(store->db, st, "sweep insert", rc, err);
    }
    pthread_mutex_unlock(&store->mu);
    return status;
}

int rd_store_sweep_delete(rd_store *store, const char *id, rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status = prepare(store->db, "DELETE FROM sweeps WHERE id = ?", &st, err);
    if (status == RD_OK)
        status = run(store->db, st, "sweep delete", bind_text(st, 1, id), err);
    if (status == RD_OK)
        status = exec(store->db, "PRAGMA incremental_vacuum", err);
    pthread_mutex_unlock(&store->mu);
    return status;
}

int rd_store_sweep_load(rd_store *store,
                        int (*each)(void *ctx, const char *id, const char *meta, const char *body,
                                    const char *csv),
                        void *ctx, rd_error *err)
{
    sqlite3_stmt *st;
    pthread_mutex_lock(&store->mu);
    int status =
        prepare(store->db, "SELECT id, meta, body, csv, crc FROM sweeps ORDER BY seq", &st, err);
    int rc = SQLITE_DONE;
    while (status == RD_OK && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        const char *t[4];
        for (int k = 0; k < 4; k++)
            t[k] = (const char *)sqlite3_column_text(st, k);
        if (!t[0] || !t[1] || !t[2] || !t[3]) {
            status = rd_error_set(err, RD_EINTERNAL, "", "Job store: a sweep row with a NULL.");
            break;
        }
        if (sqlite3_column_type(st, 4) != SQLITE_NULL &&
            sqlite3_column_int64(st, 4) != sweep_crc(t[1], t[2], t[3])) {
            left_out(store->report[2], sizeof store->report[2], t[0]);
            continue;
        }
        status = each(ctx, t[0], t[1], t[2], t[3]);
    }
    if (status == RD_OK && rc != SQLITE_DONE)
        status = db_fail(store->db, rc, "sweep load", err);
    sqlite3_finalize(st);
    pthread_mutex_unlock(&store->mu);
    return status;
}
