/*
 * rd_jobs — the job store, the bounded queue and the worker pool.
 *
 * A job is created `queued` by rd_jobs_submit, taken by one of the workers in
 * submission order (`running`), and ends `succeeded`, `failed`,
 * `cancelled` or `interrupted` (the server stopped, or died, while the job
 * was queued or running; it is not run again).  Every job is written to the
 * rd_store as it changes, so finished jobs outlive the process; at start
 * the jobs the last process left queued or running become `interrupted`.
 * Retention (applied in the store): at most `keep_max` finished jobs,
 * `keep_bytes` of results and `keep_age_s` of age (the newest finished job
 * always stays; once a limit is passed, an eighth below it is kept); at
 * most `queue_max` queued jobs; running jobs are bounded
 * by the worker count.  Jobs are rendered as the JSON of API.md.
 *
 * A succeeded job's JSON (with its `result`) is rendered once when it ends,
 * stored once, and served from one shared copy (rd_jobs_body) while any
 * request is sending it, however many requests that are.
 *
 * Knows nothing of HTTP: errors are rd_error statuses (RD_ENOTFOUND for an
 * unknown id, RD_EBUSY for a full queue) that the caller maps.  Every
 * function is thread-safe.  Every returned char* is malloc'd, caller frees.
 */
#ifndef RD_JOBS_H
#define RD_JOBS_H

#include <stddef.h>
#include <stdint.h>

#include "rd_api.h"
#include "rd_error.h"
#include "rd_store.h"

/* Job ids are RD_JOBS_ID_LEN lowercase hex digits (64 random bits). */
#define RD_JOBS_ID_LEN 16

enum rd_job_status {
    RD_JOB_QUEUED,
    RD_JOB_RUNNING,
    RD_JOB_SUCCEEDED,
    RD_JOB_FAILED,
    RD_JOB_CANCELLED,
    RD_JOB_INTERRUPTED,
    RD_JOB_NSTATUS
};

/* "queued", "running", ... as in API.md. */
const char *rd_jobs_status_name(int status);

typedef struct rd_jobs_config {
    int threads;       /* workers, >= 1 */
    int queue_max;     /* queued (not yet running) jobs accepted at once, >= 1 */
    int keep_max;      /* finished jobs kept for GET, >= 1 */
    size_t keep_bytes; /* and at most this much result text (the newest is always kept) */
    double keep_age_s; /* and none older than this (0: no age limit) */
    double timeout_s;  /* run time limit per job, > 0 */
    rd_store *store;   /* borrowed; must outlive the pool */
    /* Called after each job that ran (by its worker, or by the thread that
     * ran it inline), with its analysis, final status and run time; no lock
     * is held.  May be NULL. */
    void (*on_finish)(void *ctx, const char *analysis, int status, double run_seconds);
    void *on_finish_ctx;
    /* Called (no lock held) whenever a job reaches a final state, so that
     * requests waiting for it can be woken.  May be NULL. */
    void (*on_final)(void *ctx);
    void *on_final_ctx;
} rd_jobs_config;

/* The JSON of a finished, succeeded job, shared by the requests sending it:
 * `data` (`len` bytes) stays valid until the holder calls
 * rd_jobs_body_release. */
typedef struct rd_jobs_body {
    const char *data;
    size_t len;
} rd_jobs_body;
void rd_jobs_body_release(void *body);

typedef struct rd_jobs rd_jobs;

/* Loads the store (marking what the last process left queued or running
 * `interrupted`) and starts the workers.  On success *out owns the pool;
 * free with rd_jobs_free. */
int rd_jobs_create(const rd_jobs_config *cfg, rd_jobs **out, rd_error *err);

/* Stops taking jobs and ends queued ones `interrupted`; running ones are
 * asked to stop and given `wait_s` seconds: a run that ends in that time
 * ends as it would (a success is kept), the others are then ended
 * `interrupted` (in memory and in the store) and their workers left behind.
 * Wakes every waiter, so callers blocked in rd_jobs_get return with a final
 * job.  Idempotent. */
void rd_jobs_shutdown(rd_jobs *jobs, double wait_s);

/* Shuts down (without waiting), joins the workers and frees everything.  A
 * worker still inside a solver that does not report cannot be joined: then
 * the pool is left to the process exit.  No other call may be in progress or
 * follow.  NULL is a no-op. */
void rd_jobs_free(rd_jobs *jobs);

/* How a scene is submitted (zero: as before these existed). */
typedef struct rd_jobs_submit_opts {
    /* The client's Idempotency-Key (NULL: none) and a hash of the request
     * body it came with (rd_jobs_hash).  A key already held by a kept job
     * answers with that job (same body hash) or a conflict (another). */
    const char *idem_key;
    uint64_t idem_hash[2];
    /* Look the canonical scene up among the succeeded jobs kept (the result
     * cache) and answer with the one that computed it. */
    int use_cache;
    /* The job's run time limit, s: 0 for the pool's timeout_s; larger values
     * are capped at it. */
    double time_limit_s;
    /* > 0: when the scene's predicted cost (rd_scene_cost_predict) is below
     * this many seconds, run it at once on the calling thread (no queue, no
     * worker) before returning. */
    double inline_below_s;
} rd_jobs_submit_opts;

typedef struct rd_jobs_submitted {
    char id[RD_JOBS_ID_LEN + 1]; /* the job that answers the submission */
    int cached;                  /* an earlier job with the same canonical scene answers it */
    int replayed;                /* the Idempotency-Key named this earlier job (same body) */
    int conflict;                /* the Idempotency-Key names job `id`, sent with another body:
                        nothing was submitted */
    int ran_inline;              /* it ran on the calling thread and is final */
} rd_jobs_submitted;

/* Two independent 64-bit hashes of `len` bytes (FNV-1a and a
 * multiply-xorshift): the 128-bit keys of the result cache and of
 * Idempotency-Key bodies. */
void rd_jobs_hash(const char *data, size_t len, uint64_t out[2]);

/* Queues a parsed scene (or answers it from an earlier job, or runs it
 * inline: see the options).  Takes ownership of `scene` in every case.
 * RD_EBUSY when the queue is full or the pool is shutting down. */
int rd_jobs_submit(rd_jobs *jobs, rd_scene *scene, const rd_jobs_submit_opts *opts,
                   rd_jobs_submitted *out, rd_error *err);

/* The job: {"id", "status", "progress", "analysis", "created", "started",
 * "finished", "result" | "error"}.  Waits up to `wait_s` seconds (0: not at
 * all) for the job to finish; *finished (may be NULL) tells whether it had.
 * A succeeded job comes as its shared JSON in *body (release with
 * rd_jobs_body_release) and *json stays NULL; any other job is rendered into
 * *json (malloc'd).  RD_ENOTFOUND for an unknown id. */
int rd_jobs_get(rd_jobs *jobs, const char *id, double wait_s, rd_jobs_body **body, char **json,
                int *finished, rd_error *err);

/* Is job `id` final (or gone)?  For waiters polled after on_final. */
int rd_jobs_is_final(rd_jobs *jobs, const char *id);

/* Asks a running job to stop (DELETE) without waiting; a queued job ends
 * cancelled at once.  RD_ENOTFOUND for an unknown id. */
int rd_jobs_request_cancel(rd_jobs *jobs, const char *id, rd_error *err);

/* Applies the age limit now (the count and size limits apply whenever a job
 * ends); for a periodic timer. */
void rd_jobs_expire(rd_jobs *jobs);

/* Cancels a queued job at once, or asks a running one to stop and waits a
 * few seconds for it; a finished job is left as it is.  Then answers as
 * rd_jobs_get does.  RD_ENOTFOUND for an unknown id. */
int rd_jobs_cancel(rd_jobs *jobs, const char *id, rd_jobs_body **body, char **json, rd_error *err);

/* The shared body of a job with a result (as rd_jobs_get gives it; release
 * with rd_jobs_body_release), for its CSV; the job's analysis into
 * `analysis` (may be NULL; at least 32 bytes).  Only final jobs have one.
 * RD_ENOTFOUND for an unknown id or a job without a result (the message
 * gives its status). */
int rd_jobs_result_body(rd_jobs *jobs, const char *id, rd_jobs_body **body, char *analysis,
                        rd_error *err);

/* Which jobs a list shows. */
typedef struct rd_jobs_filter {
    size_t limit;         /* at most this many, >= 1 */
    int status;           /* enum rd_job_status, or -1 for any */
    const char *analysis; /* exact, or NULL for any */
    const char *name;     /* the scene's name, exact, or NULL for any */
    uint64_t before;      /* a cursor: only jobs submitted before the one it names; 0 = none */
} rd_jobs_filter;

/* {"jobs": [...], "next_cursor": "N" | null}: the jobs `f` selects, newest
 * first, without results; next_cursor, when more match, is the `before` of
 * the next page (decimal; valid while this process runs). */
int rd_jobs_list(rd_jobs *jobs, const rd_jobs_filter *f, char **json, rd_error *err);

/* DELETE: a final job is deleted (memory and store; *deleted = 1); a queued
 * or running one is asked to stop as rd_jobs_request_cancel (*deleted = 0).
 * RD_ENOTFOUND for an unknown id. */
int rd_jobs_delete(rd_jobs *jobs, const char *id, int *deleted, rd_error *err);

/* What a shared body is sent as besides its JSON, each made once per body
 * (the first request pays; those that ask meanwhile wait for it and share
 * the same bytes) and kept with it while it is held, so N connections
 * sending a result's CSV or gzip hold one copy, not N. */
typedef enum rd_jobs_form {
    RD_JOBS_GZIP,     /* the JSON, gzipped */
    RD_JOBS_CACHED,   /* the JSON with "cached":true first (a result cache hit), gzipped */
    RD_JOBS_CSV,      /* the result as CSV (rd_api_result_csv) */
    RD_JOBS_CSV_GZIP, /* that CSV, gzipped */
} rd_jobs_form;

/* `form` of a shared body: *data and *len are valid while the body is held;
 * `hash` (may be NULL) receives rd_jobs_hash of the form's bytes before
 * compression (the ETag of the CSV), computed once.  RD_ENOMEM, or for the
 * CSV RD_EINTERNAL (the stored result is the api's own output: a failure to
 * write it is ours). */
int rd_jobs_body_form(rd_jobs_body *body, rd_jobs_form form, const char **data, size_t *len,
                      uint64_t hash[2], rd_error *err);

/* Current number of jobs in each state (RD_JOB_NSTATUS entries). */
void rd_jobs_get_counts(rd_jobs *jobs, size_t *counts);

/* Stop latency of the last cancelled or timed-out run: seconds from the
 * DELETE (or the deadline) to the solver's return; the largest so far in
 * *max_s.  Both 0 before the first. */
void rd_jobs_get_stop_latency(rd_jobs *jobs, double *last_s, double *max_s);

/* Seconds a client turned away by a full queue should wait before retrying:
 * the queue ahead of it times the recent mean run time, 1..300. */
int rd_jobs_get_retry_after(rd_jobs *jobs);

#endif
