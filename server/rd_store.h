/*
 * rd_store — the job store on disk: one SQLite database (Debian libsqlite3)
 * in WAL mode, so that finished jobs outlive the process.
 *
 * One table of jobs, one row per job (and one of finished sweeps, below): id, analysis, status (the names of
 * rd_jobs_status_name), progress, the three times (nanoseconds since the
 * epoch, 0 = not yet), the echoed scene, the error body (rd_api_error_json)
 * and, for a succeeded job, the job's whole JSON as served (`body`, written
 * once when the job ends, never changed).  Rows keep their submission order
 * (`seq`).
 *
 * Durability: journal_mode=WAL, synchronous=NORMAL.  A commit survives a
 * crash of the process (kill -9: the next open replays the WAL); a power
 * loss may lose the last commits but never corrupts the file.
 *
 * Knows nothing of the job pool: rd_jobs calls it.  Every function is
 * thread-safe (one connection behind one mutex).
 */
#ifndef RD_STORE_H
#define RD_STORE_H

#include <stddef.h>
#include <stdint.h>

#include "rd_error.h"

/* The metadata of one job (everything but scene and body). */
typedef struct rd_store_row {
    char id[17];
    char analysis[32];
    const char *status; /* "queued", ... */
    double progress;
    int64_t created_ns, started_ns, finished_ns; /* CLOCK_REALTIME, 0 = not yet */
    const char *error;                           /* error body, or NULL */
    size_t body_len;                             /* bytes of `body`, 0 without one */
    /* Written by insert only (NULL = none): the scene's name, the result
     * cache key (32 hex digits of the canonical scene's hash), the client's
     * Idempotency-Key and the hash of the body it came with. */
    const char *name, *cache_key, *idem_key, *idem_hash;
} rd_store_row;

typedef struct rd_store rd_store;

/* Opens (creating if needed) DIR/jobs.sqlite3, creating DIR (mode 0700) and
 * its missing parents, and locks DIR/jobs.lock: a second server on the same
 * DIR is refused.  ":memory:" keeps everything in memory (tests). */
int rd_store_create(const char *dir, rd_store **out, rd_error *err);
void rd_store_free(rd_store *store); /* NULL is a no-op */

/* Integrity (issue 45), for a store file:
 * - a 0-byte jobs.sqlite3, or one SQLite finds damaged (PRAGMA quick_check,
 *   or SQLITE_CORRUPT / SQLITE_NOTADB while opening), is moved aside to
 *   jobs.sqlite3.damaged-<UTC time> (with its -wal) and the store starts
 *   empty; the report says so, and how to recover what it held;
 * - a WAL whose replay would drop committed writes (a bad checksum or salt
 *   before later commits, or a bad header) is copied aside and the report
 *   says how many commits are lost (rd_store_check.h);
 * - each stored result (jobs.body) and finished sweep carries a CRC-32
 *   written with it: a result that does not match is RD_EINTERNAL on read,
 *   a sweep row that does not match is left out at load (and named in the
 *   report).  Rows an older server wrote have no CRC and are not verified.
 * The report: lines for the log ("" when nothing was found), valid until
 * the next call or rd_store_free. */
const char *rd_store_get_report(rd_store *store);

/* A new row, every field of `row` written: a queued job's, or a finished
 * job's in one write (an inline run's) with, when `body` is not NULL, its
 * body (`row->body_len` bytes). */
int rd_store_insert(rd_store *store, const rd_store_row *row, const char *scene, const char *body,
                    rd_error *err);

/* Rewrites status, progress, times and error of an existing row and, when
 * `body` is not NULL, stores it (`row->body_len` bytes). */
int rd_store_update(rd_store *store, const rd_store_row *row, const char *body, rd_error *err);

/* Every row whose status is `from_a` or `from_b` becomes `to` with the given
 * finish time and error body; *changed (may be NULL) counts them. */
int rd_store_mark(rd_store *store, const char *from_a, const char *from_b, const char *to,
                  int64_t finished_ns, const char *error, int *changed, rd_error *err);

/* Calls `each` for every row, oldest first (the row's strings live only
 * during the call).  A non-zero return from `each` stops with that status. */
int rd_store_load(rd_store *store, int (*each)(void *ctx, const rd_store_row *row), void *ctx,
                  rd_error *err);

/* Deletes the row of job `id` (an unknown id is no error). */
int rd_store_delete(rd_store *store, const char *id, rd_error *err);

/* The stored body of job `id`: malloc'd, *len bytes (+ a NUL), or
 * RD_ENOTFOUND, or RD_EINTERNAL when it does not match its CRC-32. */
int rd_store_read_body(rd_store *store, const char *id, char **body, size_t *len, rd_error *err);

/* Retention of finished rows (succeeded, failed, cancelled, interrupted):
 * walking from the newest, a row is deleted once more than `keep_max` rows,
 * or more than `keep_bytes` of bodies, come before it or with it, or when it
 * finished before `oldest_ns`; the newest finished row always stays.
 * `gone(ctx, id)` is called for each deleted row. */
int rd_store_retain(rd_store *store, size_t keep_max, size_t keep_bytes, int64_t oldest_ns,
                    void (*gone)(void *ctx, const char *id), void *ctx, rd_error *err);

/* Finished sweeps (rd_sweeps), one row each in table `sweeps`: id, `meta`
 * (the sweep's JSON without its table, for lists), `body` (its whole JSON
 * as served) and `csv` (its table as CSV), written once when it is final.
 * put replaces a row of the same id; delete of an unknown id is no error;
 * load calls `each` oldest first (strings live only during the call). */
int rd_store_sweep_put(rd_store *store, const char *id, const char *meta, const char *body,
                       const char *csv, rd_error *err);
int rd_store_sweep_delete(rd_store *store, const char *id, rd_error *err);
int rd_store_sweep_load(rd_store *store,
                        int (*each)(void *ctx, const char *id, const char *meta, const char *body,
                                    const char *csv),
                        void *ctx, rd_error *err);

#endif
