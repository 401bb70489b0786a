/*
 * rd_jobs_persist — a job and its rd_store row (rd_jobs_int.h): the row of a
 * job, the writes as it changes and ends, retention, and the jobs of the
 * store at start (what the last process left queued or running ends
 * `interrupted`).
 */
#include "rd_jobs_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int64_t to_ns(const struct timespec *ts)
{
    return (int64_t)ts->tv_sec * 1000000000 + ts->tv_nsec;
}

static struct timespec from_ns(int64_t ns)
{
    struct timespec ts = {(time_t)(ns / 1000000000), (long)(ns % 1000000000)};
    return ts;
}

static int64_t real_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return to_ns(&ts);
}

static int status_from_name(const char *name)
{
    for (int i = 0; i < RD_JOB_NSTATUS; i++)
        if (strcmp(name, rd_jobs_status_name(i)) == 0)
            return i;
    return -1;
}

/* A 128-bit key as 32 hex digits (buf: 33 bytes). */
static void format_key(const uint64_t key[2], char *buf)
{
    snprintf(buf, 33, "%016llx%016llx", (unsigned long long)key[0], (unsigned long long)key[1]);
}

static int parse_key(const char *text, uint64_t key[2])
{
    char half[17];
    if (strlen(text) != 32 || strspn(text, "0123456789abcdef") != 32)
        return 0;
    memcpy(half, text, 16);
    half[16] = '\0';
    key[0] = strtoull(half, NULL, 16);
    key[1] = strtoull(text + 16, NULL, 16);
    return 1;
}

static void store_row(const struct job *job, rd_store_row *row)
{
    memset(row, 0, sizeof *row);
    memcpy(row->id, job->id, sizeof row->id);
    memcpy(row->analysis, job->analysis, sizeof row->analysis);
    row->status = rd_jobs_status_name(job->status);
    row->progress = job->progress;
    row->created_ns = to_ns(&job->created);
    row->started_ns = to_ns(&job->started);
    row->finished_ns = to_ns(&job->finished);
    row->error = job->error;
    row->body_len = job->body_len;
}

/* A store failure after the job has been accepted is the server's problem,
 * not the client's: it is logged and the job goes on in memory. */
void rd_jobs_log_store_error(const char *what, const rd_error *err)
{
    fprintf(stderr, "ringdyn-server: job store, %s: %s\n", what, err->message);
}

/* rd_store_retain's callback: the row is gone, so is the job. */
static void forget_locked(void *ctx, const char *id)
{
    rd_jobs *jobs = ctx;
    struct job *job = rd_jobs_find_locked(jobs, id);
    if (job) {
        rd_jobs_unlink_locked(jobs, job);
        rd_jobs_release_locked(job);
    }
}

/* Would rd_store_retain delete anything?  The list mirrors the store's
 * rows, so the answer comes from memory, and the store (a query over every
 * finished row) is asked only when some limit is passed: a job ending is
 * then no store read at all. */
static int over_limits_locked(const rd_jobs *jobs, int64_t oldest)
{
    size_t n = 0, bytes = 0;
    for (const struct job *j = jobs->head; j; j = j->next)
        if (is_final(j->status)) {
            n++;
            bytes += j->body_len;
            if (n > (size_t)jobs->cfg.keep_max || bytes > jobs->cfg.keep_bytes ||
                to_ns(&j->finished) < oldest)
                return 1;
        }
    return 0;
}

void rd_jobs_retain_locked(rd_jobs *jobs)
{
    rd_error err;
    rd_error_init(&err);
    int64_t oldest = jobs->cfg.keep_age_s > 0
                         ? real_now_ns() - (int64_t)(jobs->cfg.keep_age_s * 1e9)
                         : INT64_MIN;
    if (!over_limits_locked(jobs, oldest))
        return;
    /* Once a limit is passed, trim an eighth below it: the store's pass (a
     * transaction, page frees, a WAL commit) then runs once every
     * keep_max / 8 jobs, not after every job, when the server is full. */
    size_t keep_max = (size_t)jobs->cfg.keep_max, keep_bytes = jobs->cfg.keep_bytes;
    if (rd_store_retain(jobs->cfg.store, keep_max - keep_max / 8, keep_bytes - keep_bytes / 8,
                        oldest, forget_locked, jobs, &err) != RD_OK)
        rd_jobs_log_store_error("retention", &err);
}

/* What only an insert writes: name, cache key, idempotency key (key and
 * idem are the caller's buffers for the hex texts). */
static void row_identity(const struct job *job, rd_store_row *row, char key[33], char idem[33])
{
    format_key(job->key, key);
    format_key(job->idem_hash, idem);
    row->name = job->name;
    row->cache_key = key;
    row->idem_key = job->idem_key;
    row->idem_hash = job->idem_key ? idem : NULL;
}

/* The job's state into its row (mu held): an update, or the insert of an
 * inline job that has no row yet. */
void rd_jobs_update_store(rd_jobs *jobs, struct job *job, const char *body)
{
    rd_store_row row;
    char key[33], idem[33];
    rd_error err;
    rd_error_init(&err);
    store_row(job, &row);
    if (job->unstored_echo) {
        row_identity(job, &row, key, idem);
        if (rd_store_insert(jobs->cfg.store, &row, job->unstored_echo, body, &err) != RD_OK)
            rd_jobs_log_store_error("insert", &err);
        free(job->unstored_echo);
        job->unstored_echo = NULL;
    } else if (rd_store_update(jobs->cfg.store, &row, body, &err) != RD_OK) {
        rd_jobs_log_store_error("update", &err);
    }
}

/* Writes the end of a run (snapshot `s` with status, error and body) to the
 * store: an update, or with `echo` (an inline run's; `job` is read for its
 * fixed fields only) the job's one insert. */
int rd_jobs_store_end(rd_jobs *jobs, const struct job *job, const char *echo, const struct snap *s,
                      int status, const char *error, const char *body, size_t body_len)
{
    rd_store_row row;
    char key[33], idem[33];
    memset(&row, 0, sizeof row);
    memcpy(row.id, s->id, sizeof row.id);
    memcpy(row.analysis, s->analysis, sizeof row.analysis);
    row.status = rd_jobs_status_name(status);
    row.progress = s->progress;
    row.created_ns = to_ns(&s->created);
    row.started_ns = to_ns(&s->started);
    row.finished_ns = to_ns(&s->finished);
    row.error = error;
    row.body_len = body ? body_len : 0;
    rd_error err;
    rd_error_init(&err);
    if (echo)
        row_identity(job, &row, key, idem);
    int rc = echo ? rd_store_insert(jobs->cfg.store, &row, echo, body, &err)
                  : rd_store_update(jobs->cfg.store, &row, body, &err);
    if (rc != RD_OK)
        rd_jobs_log_store_error("writing a finished job", &err);
    return rc;
}

/* Writes a new job's row (mu held). */
int rd_jobs_insert_row_locked(rd_jobs *jobs, const struct job *job, const char *echo, rd_error *err)
{
    char key[33], idem[33];
    rd_store_row row;
    store_row(job, &row);
    row_identity(job, &row, key, idem);
    rd_error store_err;
    rd_error_init(&store_err);
    if (rd_store_insert(jobs->cfg.store, &row, echo, NULL, &store_err) == RD_OK)
        return RD_OK;
    rd_jobs_log_store_error("insert", &store_err);
    return rd_error_set(err, store_err.code == RD_ENOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                        "The job could not be written to the job store.");
}

/* rd_store_load's callback: one row becomes one job in the list. */
static int load_row(void *ctx, const rd_store_row *row)
{
    rd_jobs *jobs = ctx;
    int status = status_from_name(row->status);
    if (status < 0 || !is_final(status))
        return RD_OK; /* marked interrupted before loading; anything else is not ours */
    struct job *job = calloc(1, sizeof *job);
    if (!job)
        return RD_ENOMEM;
    memcpy(job->id, row->id, sizeof job->id);
    memcpy(job->analysis, row->analysis, sizeof job->analysis);
    job->status = status;
    job->progress = row->progress;
    job->created = from_ns(row->created_ns);
    job->started = from_ns(row->started_ns);
    job->finished = from_ns(row->finished_ns);
    job->body_len = row->body_len;
    job->refs = 1;
    job->timeout_s = jobs->cfg.timeout_s;
    job->predicted_s = NAN;
    job->has_key = row->cache_key && parse_key(row->cache_key, job->key);
    if (row->idem_hash) /* a malformed one stays zero and matches no body: a conflict */
        (void)parse_key(row->idem_hash, job->idem_hash);
    if ((row->error && !(job->error = strdup(row->error))) ||
        (row->name && !(job->name = strdup(row->name))) ||
        (row->idem_key && !(job->idem_key = strdup(row->idem_key)))) {
        rd_jobs_job_free(job);
        return RD_ENOMEM;
    }
    rd_jobs_push_locked(jobs, job);
    return RD_OK;
}

/* What the last process left queued or running ends `interrupted`, then
 * every row is loaded and retention applied. */
int rd_jobs_load_store(rd_jobs *jobs, rd_error *err)
{
    char *queued = rd_jobs_interrupted_json("queued"),
         *running = rd_jobs_interrupted_json("running");
    int rc = !queued || !running ? rd_error_set(err, RD_ENOMEM, "", "Out of memory.") : RD_OK;
    int64_t now = real_now_ns();
    int n_queued = 0, n_running = 0;
    if (rc == RD_OK)
        rc = rd_store_mark(jobs->cfg.store, "queued", "queued", "interrupted", now, queued,
                           &n_queued, err);
    if (rc == RD_OK)
        rc = rd_store_mark(jobs->cfg.store, "running", "running", "interrupted", now, running,
                           &n_running, err);
    free(queued);
    free(running);
    if (rc == RD_OK && n_queued + n_running > 0)
        fprintf(stderr,
                "ringdyn-server: %d queued and %d running jobs of the last run are marked "
                "interrupted\n",
                n_queued, n_running);
    pthread_mutex_lock(&jobs->mu);
    if (rc == RD_OK && (rc = rd_store_load(jobs->cfg.store, load_row, jobs, err)) == RD_ENOMEM)
        rd_error_set(err, RD_ENOMEM, "", "Out of memory loading the job store.");
    if (rc == RD_OK)
        rd_jobs_retain_locked(jobs);
    pthread_mutex_unlock(&jobs->mu);
    return rc;
}
