/*
 * rd_jobs — the job store, the bounded queue and the worker pool.
 *
 * A job is created `queued` by rd_jobs_submit, taken by one of the workers in
 * submission order (`running`), and ends `succeeded`, `failed` or
 * `cancelled`.  The store keeps at most `keep_max` finished jobs (the oldest
 * finished job is evicted first) and at most `queue_max` queued ones; running
 * jobs are bounded by the worker count.  Jobs are rendered as the JSON of
 * API.md (the job object with `result` or `error`).
 *
 * Knows nothing of HTTP: errors are rd_error statuses (RD_ENOTFOUND for an
 * unknown id, RD_EBUSY for a full queue) that the caller maps.  Every
 * function is thread-safe.  Every returned char* is malloc'd, caller frees.
 */
#ifndef RD_JOBS_H
#define RD_JOBS_H

#include <stddef.h>

#include "rd_api.h"
#include "rd_error.h"

/* Job ids are RD_JOBS_ID_LEN lowercase hex digits (64 random bits). */
#define RD_JOBS_ID_LEN 16

enum rd_job_status {
    RD_JOB_QUEUED,
    RD_JOB_RUNNING,
    RD_JOB_SUCCEEDED,
    RD_JOB_FAILED,
    RD_JOB_CANCELLED,
    RD_JOB_NSTATUS
};

/* "queued", "running", ... as in API.md. */
const char *rd_jobs_status_name(int status);

typedef struct rd_jobs_config {
    int threads;      /* workers, >= 1 */
    int queue_max;    /* queued (not yet running) jobs accepted at once, >= 1 */
    int keep_max;     /* finished jobs kept for GET, >= 1 */
    size_t keep_bytes; /* and at most this much result text (the newest is always kept) */
    double timeout_s; /* run time limit per job, > 0 */
    /* Called by a worker after each job that ran, with its final status and
     * run time; no lock is held.  May be NULL. */
    void (*on_finish)(void *ctx, int status, double run_seconds);
    void *on_finish_ctx;
} rd_jobs_config;

typedef struct rd_jobs rd_jobs;

/* Starts the workers.  On success *out owns the pool; free with rd_jobs_free. */
int rd_jobs_create(const rd_jobs_config *cfg, rd_jobs **out, rd_error *err);

/* Stops taking jobs, cancels queued and running ones and wakes every waiter,
 * so callers blocked in rd_jobs_view return at once.  Idempotent. */
void rd_jobs_shutdown(rd_jobs *jobs);

/* Shuts down, joins the workers (a running job stops at its next progress
 * report) and frees everything.  No other call may be in progress or follow.
 * NULL is a no-op. */
void rd_jobs_free(rd_jobs *jobs);

/* Queues a parsed scene.  Takes ownership of `scene` in every case.  On
 * success writes the new id (RD_JOBS_ID_LEN + 1 bytes with the NUL).
 * RD_EBUSY when the queue is full or the pool is shutting down. */
int rd_jobs_submit(rd_jobs *jobs, rd_scene *scene, char *id, rd_error *err);

/* The job as JSON: {"id", "status", "progress", "analysis", "created",
 * "started", "finished", "result" | "error"}.  Waits up to `wait_s` seconds
 * (0: not at all) for the job to finish; *finished (may be NULL) tells
 * whether it had.  RD_ENOTFOUND for an unknown id. */
int rd_jobs_view(rd_jobs *jobs, const char *id, double wait_s, char **json, int *finished,
                 rd_error *err);

/* Cancels a queued job at once, or asks a running one to stop and waits a
 * few seconds for it; a finished job is left as it is.  Then renders the job
 * as rd_jobs_view does.  RD_ENOTFOUND for an unknown id. */
int rd_jobs_cancel(rd_jobs *jobs, const char *id, char **json, rd_error *err);

/* The result of a succeeded job as CSV (rd_api_result_csv).  RD_ENOTFOUND for
 * an unknown id or a job without a result (the message gives its status). */
int rd_jobs_result_csv(rd_jobs *jobs, const char *id, char **csv, rd_error *err);

/* {"jobs": [...]}: at most `limit` jobs, newest first, without results. */
int rd_jobs_list(rd_jobs *jobs, size_t limit, char **json, rd_error *err);

/* Current number of jobs in each state (RD_JOB_NSTATUS entries). */
void rd_jobs_get_counts(rd_jobs *jobs, size_t *counts);

/* Seconds a client turned away by a full queue should wait before retrying:
 * the queue ahead of it times the recent mean run time, 1..300. */
int rd_jobs_get_retry_after(rd_jobs *jobs);

#endif
