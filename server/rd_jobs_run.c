/*
 * rd_jobs_run — one run, from the solver to the job's final state
 * (rd_jobs_int.h): the monitor that reports progress and asks the run to
 * stop, the final status and error of what the run returned, the store row
 * with the rendered JSON, then the state in memory and the callbacks.
 *
 * Order of a job's end: the store row is written first, then the status in
 * memory becomes final, so whoever sees a final status finds the row.
 *
 * Cancellation and the time limit act through the rd_monitor that the
 * worker passes to rd_scene_run: its report() reads the job's cancel flag,
 * the stop flag and the deadline, and returns non-zero once any is set; the
 * run then returns RD_ECANCELED at that report.  How soon that is depends on
 * how often the solver reports (core/); the time from the request to the
 * solver's return is measured here (rd_jobs_get_stop_latency).
 */
#include "rd_jobs_int.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "rd_clock.h"

struct run_ctx {
    rd_jobs *jobs;
    struct job *job;
};

/* rd_monitor.report: records progress; non-zero asks the run to stop. */
static int report_progress(void *arg, double fraction)
{
    struct run_ctx *ctx = arg;
    double now = rd_clock_mono_s();
    pthread_mutex_lock(&ctx->jobs->mu);
    struct job *job = ctx->job;
    if (fraction >= 0 && fraction <= 1) /* NaN fails both */
        job->progress = fraction;
    else if (fraction > 1)
        job->progress = 1;
    int stop = job->cancel || ctx->jobs->stopping || is_final(job->status);
    if (!stop && now >= job->deadline) {
        job->timed_out = 1;
        job->stop_asked = job->deadline;
        stop = 1;
    }
    pthread_mutex_unlock(&ctx->jobs->mu);
    return stop;
}

/* The final status and error of a run that returned `rc`. */
static int final_status(rd_jobs *jobs, struct job *job, int rc, const char *result, rd_error *err,
                        char **error)
{
    pthread_mutex_lock(&jobs->mu);
    int cancel = job->cancel, timed_out = job->timed_out, stopping = jobs->stopping;
    double progress = job->progress;
    pthread_mutex_unlock(&jobs->mu);
    /* A DELETE wins even over a run that completed meanwhile: the client was
     * told the job is being cancelled, so it must not turn up succeeded. */
    /* A stopped run may still return a partial result (a lift run's whole
     * cycles): the job keeps it beside its error (store_run). */
    const char *kept =
        rc != RD_OK && result ? "  Its complete part is in `result` (\"partial\": true)." : "";
    if (cancel) {
        *error =
            rd_jobs_error_json(RD_ECANCELED, "The job was cancelled by a DELETE request.%s", kept);
        return RD_JOB_CANCELLED;
    }
    if (rc == RD_OK && result)
        return RD_JOB_SUCCEEDED;
    /* A run that honoured the shutdown's stop request in time ends as one the
     * shutdown had to leave behind: interrupted, not failed. */
    if (rc == RD_ECANCELED && stopping && !timed_out) {
        *error = rd_jobs_interrupted_json("running");
        return RD_JOB_INTERRUPTED;
    }
    if (rc == RD_ECANCELED && timed_out) {
        *error =
            rd_jobs_error_json(RD_ETIMEOUT,
                               "The job ran longer than the time limit of %g s and was stopped "
                               "(at %.0f %% progress).%s",
                               job->timeout_s, 100.0 * progress, kept);
        return RD_JOB_FAILED;
    }
    if (err->code == RD_OK)
        rd_error_set(err, rc != RD_OK ? rc : RD_EINTERNAL, "", "The analysis failed: %s.",
                     rd_error_summary(rc != RD_OK ? rc : RD_EINTERNAL));
    *error = rd_api_error_json(err);
    return RD_JOB_FAILED;
}

/* Records how long the solver took to honour a stop request. */
static void note_stop_latency_locked(rd_jobs *jobs, const struct job *job, double now)
{
    if (!(job->stop_asked > 0))
        return;
    double latency = now - job->stop_asked;
    jobs->stop_last_s = latency;
    if (latency > jobs->stop_max_s)
        jobs->stop_max_s = latency;
}

/* A run's end, carried from the solver's return to the job's final state. */
struct run_end {
    int rc;          /* rd_scene_run's status */
    int status;      /* the job's final status (enum rd_job_status) */
    char *result;    /* the run's result text (also a stopped run's partial one), or NULL */
    char *error;     /* the final error body, or NULL */
    char *body;      /* the job's JSON with its result, as stored, or NULL */
    size_t body_len; /* bytes of `body` in the store: 0 when none was stored */
    double seconds;  /* the run's time */
    struct timespec finished;
    int detached; /* shutdown ended the job meanwhile: that end stands */
};

/* The end of an attached run into the store (snapshot `s`, ours): the JSON
 * with the result (a success's, or the partial result of a run that
 * stopped), and `failed` instead when that cannot be made or stored. */
static void store_run(rd_jobs *jobs, const struct job *job, const char *echo, struct snap *s,
                      struct run_end *e)
{
    clock_gettime(CLOCK_REALTIME, &s->finished);
    s->status = e->status;
    if (e->status == RD_JOB_SUCCEEDED)
        s->progress = 1;
    if (e->result && (e->status == RD_JOB_SUCCEEDED || e->rc != RD_OK)) {
        free(s->error); /* the body carries the job's final error beside the result */
        s->error = e->error ? strdup(e->error) : NULL;
        e->body =
            e->error && !s->error ? NULL : rd_jobs_render_with_result(s, e->result, &e->body_len);
        if (!e->body && e->status == RD_JOB_SUCCEEDED) { /* the result exists but cannot be sent */
            e->status = RD_JOB_FAILED;
            e->error = rd_jobs_error_json(RD_ENOMEM, "Out of memory while storing the result.");
        }
    }
    if (rd_jobs_store_end(jobs, job, echo, s, e->status, e->error, e->body, e->body_len) != RD_OK &&
        e->body) {
        free(e->body);
        e->body = NULL;
        free(e->error);
        e->status = RD_JOB_FAILED;
        e->error = rd_jobs_error_json(RD_EINTERNAL, "The result could not be written to the job "
                                                    "store (the server's log says why).");
        rd_jobs_store_end(jobs, job, echo, s, e->status, e->error, NULL, 0);
    }
    if (!e->body)
        e->body_len = 0;
}

/* The solver has returned (at `t1`): the worker leaves it, and the end goes
 * to the store, not yet into memory.  A job that shutdown already ended
 * `interrupted` keeps that end (its row is written); what its run produced
 * is dropped. */
static void settle(rd_jobs *jobs, struct job *job, int pooled, double t1, struct run_end *e)
{
    pthread_mutex_lock(&jobs->mu);
    if (pooled) {
        jobs->in_solver--;
        pthread_cond_broadcast(&jobs->idle);
    }
    note_stop_latency_locked(jobs, job, t1);
    e->detached = is_final(job->status);
    struct snap s;
    memset(&s, 0, sizeof s);
    int bad = e->detached ? 0 : rd_jobs_snapshot_locked(jobs, job, &s);
    char *echo =
        NULL; /* an inline run's row, ours to write (rd_jobs.c's end_locked wrote a detached one's) */
    if (!e->detached) {
        echo = job->unstored_echo;
        job->unstored_echo = NULL;
    }
    pthread_mutex_unlock(&jobs->mu);

    if (!e->detached && !bad)
        store_run(jobs, job, echo, &s, e);
    e->finished = s.finished;
    free(echo);
    free(s.error);
    free(s.name);
}

/* The job's final state in memory (mu held), after the store has it, and
 * the pool's run statistics; waiters are woken. */
static void finish_locked(rd_jobs *jobs, struct job *job, struct run_end *e)
{
    free(job->error);
    job->error = e->error;
    e->error = NULL;
    job->body_len = e->body_len;
    if (e->status == RD_JOB_SUCCEEDED)
        job->progress = 1;
    job->finished = e->finished;
    rd_jobs_set_status_locked(jobs, job, e->status);
    jobs->mean_run_s = 0.7 * jobs->mean_run_s + 0.3 * e->seconds;
    if (e->status == RD_JOB_SUCCEEDED && job->predicted_s > 0) {
        double ratio = e->seconds / job->predicted_s;
        jobs->cost_scale = jobs->cost_scale > 0 ? 0.8 * jobs->cost_scale + 0.2 * ratio : ratio;
    }
    rd_jobs_retain_locked(jobs);
    jobs->notifying++;
    pthread_cond_broadcast(&jobs->done);
}

/* The callbacks of a job that reached its final state (no lock held);
 * rd_jobs_shutdown waits for them (`notifying`). */
static void notify(rd_jobs *jobs, const char *analysis, int status, double seconds)
{
    if (jobs->cfg.on_final)
        jobs->cfg.on_final(jobs->cfg.on_final_ctx);
    if (jobs->cfg.on_finish)
        jobs->cfg.on_finish(jobs->cfg.on_finish_ctx, analysis, status, seconds);
    pthread_mutex_lock(&jobs->mu);
    jobs->notifying--;
    pthread_cond_broadcast(&jobs->done);
    pthread_mutex_unlock(&jobs->mu);
}

/* The end of a run into memory: the JSON just stored is what the client
 * waiting for the job reads next, so it becomes the job's shared body (held
 * as the recent one) and that read costs no trip to the store.  Drops the
 * run's reference on `job`. */
static void publish(rd_jobs *jobs, struct job *job, struct run_end *e, const char *analysis)
{
    struct body *kept = e->body ? rd_jobs_body_new(jobs, e->body, e->body_len) : NULL;
    struct body *dropped = NULL;
    e->body = NULL;

    pthread_mutex_lock(&jobs->mu);
    if (kept && !e->detached && !job->body) {
        kept->owner = job;
        job->body = kept;
        dropped = rd_jobs_keep_recent_locked(jobs, kept);
        kept = NULL;
    }
    if (!e->detached)
        finish_locked(jobs, job, e);
    rd_jobs_release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    rd_jobs_body_free(kept); /* not taken (detached) */
    rd_jobs_body_free(dropped);
    free(e->error);

    if (!e->detached)
        notify(jobs, analysis, e->status, e->seconds);
}

/* Runs one job (taken by the caller, who holds a reference) to its end:
 * the store row first (with the rendered JSON of a success), then the
 * status in memory. */
void rd_jobs_run(rd_jobs *jobs, struct job *job, rd_scene *scene, int pooled)
{
    struct run_ctx ctx = {jobs, job};
    rd_monitor mon = {report_progress, &ctx};
    rd_error err;
    rd_error_init(&err);
    struct run_end e;
    memset(&e, 0, sizeof e);
    char analysis[sizeof job->analysis];
    memcpy(analysis, job->analysis, sizeof analysis); /* job may be freed below */

    double t0 = rd_clock_mono_s();
    e.rc = rd_scene_run(scene, &mon, &e.result, &err);
    double t1 = rd_clock_mono_s();
    e.seconds = t1 - t0;
    rd_scene_free(scene);
    e.status = final_status(jobs, job, e.rc, e.result, &err, &e.error);
    settle(jobs, job, pooled, t1, &e);
    free(e.result);
    publish(jobs, job, &e, analysis);
}
