/*
 * rd_jobs_int.h — the job pool's insides, shared by its files (not a public
 * header: only server/rd_jobs*.c include it).
 *
 * Floors, lowest first; a file calls only the ones below it:
 *   rd_jobs_list.c     status names, the hash, the list, references, lookup,
 *                      snapshots
 *   rd_jobs_render.c   the job as JSON, error bodies
 *   rd_jobs_persist.c  the job's store row, retention, the load at start
 *   rd_jobs_body.c     the shared JSON of a job with a result, its gzip, CSV
 *   rd_jobs_run.c      one run, from the solver to the job's final state
 *   rd_jobs.c          workers, start and shutdown, submission, the other
 *                      public calls
 *
 * Data layout: every job the store holds is also in one doubly linked list
 * in memory, newest first, with its metadata (no scene once it runs, no
 * result: results live in the store).  The queue is not a separate
 * structure: a worker takes the oldest `queued` job, found by walking the
 * list from its tail.
 *
 * Locking: one mutex `mu` guards the list, the per-state counts, the stop
 * flag and every field of a job that changes (status, progress, times,
 * cancel and timeout flags, reference count, the shared body).  `error` is
 * written once, under `mu`, when the status becomes final, and never
 * changes after.  The store has its own mutex, always taken after `mu`
 * (never the other way round); big writes (a result) are made without `mu`.
 * Condition variables: `work` (a job was queued, or stop) wakes workers;
 * `done` (a job finished, or stop) wakes waiters; `idle` (a worker left).
 * They wait on CLOCK_MONOTONIC so wall-clock jumps do not stretch a wait.
 *
 * Lifetime: a job is freed when its reference count drops to zero.  The
 * list holds one reference; a worker running it and each request reading it
 * hold one more, so retention never frees a job somebody is still reading.
 * A succeeded job's rendered JSON (and that of a stopped job whose run
 * returned a partial result: a lift run's whole cycles beside its error)
 * is written to the store when it ends and
 * read back on demand into one `struct body`, which every request sending
 * it shares (reference counted under `mu`); the last release frees it, so
 * a finished job costs no memory while nobody reads it.
 *
 * Functions named *_locked are called with `mu` held.
 */
#ifndef RD_JOBS_INT_H
#define RD_JOBS_INT_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <time.h>

#include <jansson.h>

#include "rd_jobs.h"

/* One derived form of a body (rd_jobs_form): NULL until made. */
struct form {
    char *data;
    size_t len;
    uint64_t hash[2]; /* of the bytes before compression */
};

struct body {
    rd_jobs_body pub; /* first: the public view is a pointer to it */
    rd_jobs *jobs;
    struct job *owner; /* the job whose `body` this is, NULL once it is gone */
    int refs;
    char *data;
    /* Guards `forms`: held while one is made, so it is made once; a form
     * never changes once set and lives as long as the body. */
    pthread_mutex_t make;
    struct form forms[4]; /* by rd_jobs_form */
};

struct job {
    struct job *prev, *next; /* list, newest first */
    int refs;
    char id[RD_JOBS_ID_LEN + 1];
    char analysis[32];
    int status;        /* enum rd_job_status */
    double progress;   /* 0..1 */
    int cancel;        /* DELETE asked a running job to stop */
    int timed_out;     /* the monitor saw the deadline pass */
    double stop_asked; /* CLOCK_MONOTONIC of the DELETE, the deadline, or the shutdown; 0 = none */
    double deadline;   /* CLOCK_MONOTONIC seconds, set when the run starts */
    struct timespec created, started, finished; /* CLOCK_REALTIME; zero = not yet */
    rd_scene *scene;                            /* owned until a worker takes it */
    size_t body_len;       /* bytes of the stored JSON of a job with a result (has_body) */
    struct body *body;     /* that JSON while some request sends it, else NULL */
    char *error;           /* error body, once failed, cancelled or interrupted */
    uint64_t seq;          /* submission order in this process (list cursors), from 1 */
    char *name;            /* the scene's name, or NULL */
    int has_key;           /* `key` is set: a succeeded job is a result cache entry */
    uint64_t key[2];       /* rd_jobs_hash of the canonical scene */
    char *idem_key;        /* the client's Idempotency-Key, or NULL */
    uint64_t idem_hash[2]; /* rd_jobs_hash of the body it came with */
    double timeout_s;      /* this job's run time limit */
    double predicted_s;    /* rd_scene_cost_predict, NAN when unknown */
    /* An inline run's echoed scene until its row is written, once, when it
     * ends (one store write per small job, not two); NULL: the row exists. */
    char *unstored_echo;
};

struct rd_jobs {
    rd_jobs_config cfg;
    pthread_mutex_t mu;
    pthread_cond_t work;
    pthread_cond_t done;
    pthread_cond_t idle;
    struct job *head, *tail;
    size_t counts[RD_JOB_NSTATUS]; /* jobs in the list, by status */
    int stopping;
    double mean_run_s; /* moving average of run times, for Retry-After */
    double stop_last_s, stop_max_s;
    int random_fd; /* /dev/urandom, for ids */
    pthread_t *workers;
    int nworkers;  /* started successfully */
    int active;    /* workers not yet returned */
    int in_solver; /* workers inside rd_scene_run */
    /* The body read last, held one reference longer (rd_jobs_keep_recent_locked). */
    struct body *recent;
    uint64_t next_seq; /* the seq of the next job pushed */
    /* Moving average of (run time / predicted cost) over the succeeded runs
     * that had a prediction: the cost model is fitted to a reference
     * machine, this scales it to the one we run on (and its load). */
    double cost_scale;
    /* Runs that have ended but not yet returned from on_final/on_finish:
     * rd_jobs_shutdown waits for them, so that no callback reaches a caller
     * (the HTTP server) after shutdown has returned and it is being freed. */
    int notifying;
};

/* What a request reads of a job, copied under `mu`. */
struct snap {
    char id[RD_JOBS_ID_LEN + 1];
    char analysis[32];
    int status;
    double progress;
    struct timespec created, started, finished;
    char *error;        /* a copy, or NULL */
    char *name;         /* a copy, or NULL */
    double predicted_s; /* scaled by cost_scale */
};

static inline int is_final(int status)
{
    return status >= RD_JOB_SUCCEEDED;
}

/* A job whose JSON (with `result`) is stored: every succeeded job, and a
 * stopped one whose run returned a partial result. */
static inline int has_body(const struct job *job)
{
    return job->status == RD_JOB_SUCCEEDED || (is_final(job->status) && job->body_len > 0);
}

/* ---- rd_jobs_list.c ---- */

/* The job `id` in the list, or NULL. */
struct job *rd_jobs_find_locked(rd_jobs *jobs, const char *id);
/* Frees a job (its scene, error, names) whatever its references. */
void rd_jobs_job_free(struct job *job);
/* Drops one reference; the last frees the job. */
void rd_jobs_release_locked(struct job *job);
/* Moves a listed job to `status`, keeping the per-state counts. */
void rd_jobs_set_status_locked(rd_jobs *jobs, struct job *job, int status);
/* Lists a job as the newest, giving it the next seq (the list's reference
 * is the one the caller made it with). */
void rd_jobs_push_locked(rd_jobs *jobs, struct job *job);
/* Takes a job off the list (its list reference is the caller's to drop). */
void rd_jobs_unlink_locked(rd_jobs *jobs, struct job *job);
/* The queued job submitted first, or NULL. */
struct job *rd_jobs_oldest_queued_locked(rd_jobs *jobs);
/* A fresh id (RD_JOBS_ID_LEN + 1 bytes) no listed job has. */
int rd_jobs_new_id_locked(rd_jobs *jobs, char *id, rd_error *err);
/* Copies what a request reads of a job into *s (error and name malloc'd:
 * free both); -1 when out of memory (nothing to free then). */
int rd_jobs_snapshot_locked(const rd_jobs *jobs, const struct job *job, struct snap *s);
/* RD_ENOTFOUND with the message for an unknown `id`. */
int rd_jobs_not_found(rd_error *err, const char *id);
/* Locks `mu` and finds job `id`, taking a reference: on RD_OK *out is the
 * job and `mu` is held (drop the job with rd_jobs_release_locked); otherwise
 * `mu` is released and the status is RD_ENOTFOUND. */
int rd_jobs_acquire_locked(rd_jobs *jobs, const char *id, struct job **out, rd_error *err);

/* ---- rd_jobs_render.c ---- */

/* An error body from rd_api_error_json, or NULL when out of memory. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
char *
rd_jobs_error_json(int code, const char *fmt, ...);
/* The error body of a job interrupted while `when` ("queued", "running"). */
char *rd_jobs_interrupted_json(const char *when);
/* The job object without `result`; NULL when out of memory. */
json_t *rd_jobs_job_object(const struct snap *s);
/* The whole JSON of a job with `result` spliced in (*len bytes); NULL when
 * out of memory. */
char *rd_jobs_render_with_result(const struct snap *s, const char *result, size_t *len);
/* With `mu` held and a reference on `job`: renders it (without result) into
 * *json, drops the reference; returns with `mu` released. */
int rd_jobs_view_and_release(rd_jobs *jobs, struct job *job, char **json, int *finished,
                             rd_error *err);

/* ---- rd_jobs_persist.c ---- */

/* Logs a store failure (the job goes on in memory). */
void rd_jobs_log_store_error(const char *what, const rd_error *err);
/* Applies the retention limits (store and list) when one is passed. */
void rd_jobs_retain_locked(rd_jobs *jobs);
/* The job's state into its row: an update, or the insert of an inline job
 * that has no row yet. */
void rd_jobs_update_store(rd_jobs *jobs, struct job *job, const char *body);
/* The end of a run (snapshot `s` with status, error and body) into the
 * store: an update, or with `echo` (an inline run's) the job's one insert. */
int rd_jobs_store_end(rd_jobs *jobs, const struct job *job, const char *echo, const struct snap *s,
                      int status, const char *error, const char *body, size_t body_len);
/* A new queued job's row. */
int rd_jobs_insert_row_locked(rd_jobs *jobs, const struct job *job, const char *echo,
                              rd_error *err);
/* Marks what the last process left queued or running `interrupted`, loads
 * every row into the list and applies retention. */
int rd_jobs_load_store(rd_jobs *jobs, rd_error *err);

/* ---- rd_jobs_body.c ---- */

/* A body owning the malloc'd `data` (freed on failure), no reference yet;
 * NULL when out of memory. */
struct body *rd_jobs_body_new(rd_jobs *jobs, char *data, size_t len);
/* Frees a body that no request holds (NULL is a no-op). */
void rd_jobs_body_free(struct body *b);
/* Holds `b` as the most recently read body; returns the one it replaces
 * when that lost its last reference (free it after unlocking). */
struct body *rd_jobs_keep_recent_locked(rd_jobs *jobs, struct body *b);
/* With `mu` held and a reference on a job with a body: its shared body
 * into *out; returns with `mu` released and the reference dropped. */
int rd_jobs_body_and_release(rd_jobs *jobs, struct job *job, rd_jobs_body **out, rd_error *err);

/* ---- rd_jobs_run.c ---- */

/* Runs a job taken by the caller (running, its scene taken off it, one
 * reference held for the run) to its end, and drops that reference.
 * `pooled`: on a worker (counted in `in_solver`), not inline. */
void rd_jobs_run(rd_jobs *jobs, struct job *job, rd_scene *scene, int pooled);

#endif
