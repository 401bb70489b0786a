/*
 * rd_jobs — the job pool (rd_jobs.h): the workers, the pool's start and
 * shutdown, submission (idempotency, the result cache, inline runs) and the
 * other public calls.
 *
 * The data layout, the locking and the lifetime of jobs are described in
 * rd_jobs_int.h.  One run, from the solver to the job's final state, is
 * rd_jobs_run.c; the list, the JSON, the store rows and the shared bodies
 * lie below that.
 */
#include "rd_jobs_int.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rd_clock.h"
#include "rd_scene_facts.h"

/* How long DELETE waits for a running job to acknowledge the cancellation. */
#define CANCEL_WAIT_S 5.0
/* How long rd_jobs_shutdown waits for the callbacks of runs that just ended. */
#define NOTIFY_WAIT_S 2.0
/* How long rd_jobs_free waits for idle workers to leave. */
#define IDLE_WAIT_S 1.0
/* Run time assumed for Retry-After before any job has finished. */
#define RUN_ESTIMATE_INITIAL_S 1.0

/* A worker: takes the oldest queued job, marks it running (memory and
 * store) and runs it, until the pool stops. */
static void *worker_main(void *arg)
{
    rd_jobs *jobs = arg;
    for (;;) {
        struct job *job = NULL;
        pthread_mutex_lock(&jobs->mu);
        while (!jobs->stopping && !(job = rd_jobs_oldest_queued_locked(jobs)))
            pthread_cond_wait(&jobs->work, &jobs->mu);
        if (jobs->stopping) {
            jobs->active--;
            pthread_cond_broadcast(&jobs->idle);
            pthread_mutex_unlock(&jobs->mu);
            return NULL;
        }
        job->refs++;
        rd_jobs_set_status_locked(jobs, job, RD_JOB_RUNNING);
        clock_gettime(CLOCK_REALTIME, &job->started);
        job->deadline = rd_clock_mono_s() + job->timeout_s;
        rd_scene *scene = job->scene;
        job->scene = NULL;
        rd_jobs_update_store(jobs, job, NULL); /* small: status and start time */
        jobs->in_solver++;
        pthread_mutex_unlock(&jobs->mu);

        rd_jobs_run(jobs, job, scene, 1);
    }
}

/* Ends a job that is not running (queued), or detaches a running one from
 * its worker (shutdown): final at once, in the store too. */
static void end_locked(rd_jobs *jobs, struct job *job, int status, char *error)
{
    rd_scene_free(job->scene);
    job->scene = NULL;
    free(job->error);
    job->error = error;
    clock_gettime(CLOCK_REALTIME, &job->finished);
    rd_jobs_set_status_locked(jobs, job, status);
    rd_jobs_update_store(jobs, job, NULL);
}

int rd_jobs_create(const rd_jobs_config *cfg, rd_jobs **out, rd_error *err)
{
    *out = NULL;
    if (cfg->threads < 1 || cfg->queue_max < 1 || cfg->keep_max < 1 || cfg->keep_bytes < 1 ||
        !(cfg->timeout_s > 0) || !(cfg->keep_age_s >= 0) || !cfg->store)
        return rd_error_set(err, RD_EINVAL, "", "Job pool settings out of range.");
    rd_jobs *jobs = calloc(1, sizeof *jobs);
    if (!jobs)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    jobs->cfg = *cfg;
    jobs->mean_run_s = RUN_ESTIMATE_INITIAL_S;
    jobs->random_fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    if (jobs->random_fd < 0) {
        int e = errno;
        free(jobs);
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot open /dev/urandom: %s.", strerror(e));
    }
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    int sync_failed =
        pthread_mutex_init(&jobs->mu, NULL) != 0 || pthread_cond_init(&jobs->work, &attr) != 0 ||
        pthread_cond_init(&jobs->done, &attr) != 0 || pthread_cond_init(&jobs->idle, &attr) != 0;
    pthread_condattr_destroy(&attr);

    int rc = sync_failed
                 ? rd_error_set(err, RD_EINTERNAL, "", "Cannot initialise the job queue's locks.")
                 : rd_jobs_load_store(jobs, err);
    jobs->workers = rc == RD_OK ? calloc((size_t)cfg->threads, sizeof *jobs->workers) : NULL;
    if (rc == RD_OK && !jobs->workers)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    for (int i = 0; rc == RD_OK && i < cfg->threads; i++) {
        pthread_mutex_lock(&jobs->mu);
        jobs->active++;
        pthread_mutex_unlock(&jobs->mu);
        int e = pthread_create(&jobs->workers[i], NULL, worker_main, jobs);
        if (e != 0) {
            pthread_mutex_lock(&jobs->mu);
            jobs->active--;
            pthread_mutex_unlock(&jobs->mu);
            rc =
                rd_error_set(err, RD_EINTERNAL, "", "Cannot start worker thread: %s.", strerror(e));
        } else {
            jobs->nworkers++;
        }
    }
    if (rc != RD_OK) {
        rd_jobs_shutdown(jobs, 0);
        rd_jobs_free(jobs);
        return rc;
    }
    *out = jobs;
    return RD_OK;
}

void rd_jobs_shutdown(rd_jobs *jobs, double wait_s)
{
    if (!jobs)
        return;
    pthread_mutex_lock(&jobs->mu);
    if (jobs->stopping) {
        pthread_mutex_unlock(&jobs->mu);
        return;
    }
    jobs->stopping = 1;
    double now = rd_clock_mono_s();
    for (struct job *j = jobs->head; j; j = j->next) {
        if (j->status == RD_JOB_QUEUED)
            end_locked(jobs, j, RD_JOB_INTERRUPTED, rd_jobs_interrupted_json("queued"));
        else if (j->status == RD_JOB_RUNNING && !(j->stop_asked > 0))
            j->stop_asked = now; /* runs see `stopping` at their next report */
    }
    pthread_cond_broadcast(&jobs->work);
    pthread_cond_broadcast(&jobs->done);
    /* Runs that end within wait_s end as they would (a success is kept);
     * the rest are ended interrupted now and their workers left behind. */
    struct timespec deadline = rd_clock_mono_deadline(wait_s);
    while (jobs->counts[RD_JOB_RUNNING] > 0)
        if (pthread_cond_timedwait(&jobs->done, &jobs->mu, &deadline) == ETIMEDOUT)
            break;
    for (struct job *j = jobs->head; j; j = j->next)
        if (j->status == RD_JOB_RUNNING)
            end_locked(jobs, j, RD_JOB_INTERRUPTED, rd_jobs_interrupted_json("running"));
    pthread_cond_broadcast(&jobs->done);
    /* Callbacks of runs that ended meanwhile take microseconds; the bound
     * only guards against a callback that blocks. */
    struct timespec notified = rd_clock_mono_deadline(NOTIFY_WAIT_S);
    while (jobs->notifying > 0)
        if (pthread_cond_timedwait(&jobs->done, &jobs->mu, &notified) == ETIMEDOUT)
            break;
    pthread_mutex_unlock(&jobs->mu);
    if (jobs->cfg.on_final)
        jobs->cfg.on_final(jobs->cfg.on_final_ctx);
}

void rd_jobs_free(rd_jobs *jobs)
{
    if (!jobs)
        return;
    rd_jobs_shutdown(jobs, 0);
    /* Idle workers leave at once; wait (briefly) for them, not for solvers. */
    pthread_mutex_lock(&jobs->mu);
    struct timespec deadline = rd_clock_mono_deadline(IDLE_WAIT_S);
    while (jobs->active > jobs->in_solver)
        if (pthread_cond_timedwait(&jobs->idle, &jobs->mu, &deadline) == ETIMEDOUT)
            break;
    int active = jobs->active;
    pthread_mutex_unlock(&jobs->mu);
    if (active > 0) {
        /* A solver that does not report cannot be stopped: the process exit
         * ends it.  Freeing the pool under it would be a use after free. */
        fprintf(stderr,
                "ringdyn-server: %d worker(s) still in a solver; leaving them to the exit\n",
                active);
        return;
    }
    for (int i = 0; i < jobs->nworkers; i++)
        pthread_join(jobs->workers[i], NULL);
    free(jobs->workers);
    if (jobs->recent) /* no request is left: this is its last reference */
        rd_jobs_body_release(&jobs->recent->pub);
    struct job *j = jobs->head;
    while (j) {
        struct job *next = j->next;
        rd_jobs_job_free(j); /* only the list's reference is left: no caller may be active */
        j = next;
    }
    pthread_cond_destroy(&jobs->work);
    pthread_cond_destroy(&jobs->done);
    pthread_cond_destroy(&jobs->idle);
    pthread_mutex_destroy(&jobs->mu);
    close(jobs->random_fd);
    free(jobs);
}

/* An earlier job that answers a submission (mu held): the one holding its
 * Idempotency-Key (a replay, or a conflict when the body differs), else,
 * with the cache on, a succeeded job of the same canonical scene. */
static struct job *earlier_answer_locked(rd_jobs *jobs, const rd_jobs_submit_opts *o,
                                         const uint64_t key[2], rd_jobs_submitted *out)
{
    if (o->idem_key)
        for (struct job *j = jobs->head; j; j = j->next)
            if (j->idem_key && strcmp(j->idem_key, o->idem_key) == 0) {
                int same = j->idem_hash[0] == o->idem_hash[0] && j->idem_hash[1] == o->idem_hash[1];
                out->replayed = same;
                out->conflict = !same;
                return j;
            }
    if (o->use_cache)
        for (struct job *j = jobs->head; j; j = j->next)
            if (j->status == RD_JOB_SUCCEEDED && j->has_key && j->key[0] == key[0] &&
                j->key[1] == key[1]) {
                out->cached = 1;
                return j;
            }
    return NULL;
}

/* A new job for `scene` (not yet listed; takes the scene), or NULL when out
 * of memory (the scene is then freed). */
static struct job *new_job(rd_jobs *jobs, rd_scene *scene, const rd_jobs_submit_opts *o)
{
    struct job *job = calloc(1, sizeof *job);
    char *canon = job ? rd_scene_canonical_json(scene) : NULL;
    const char *name = rd_scene_name(scene);
    if (job)
        job->scene = scene;
    if (!canon || (name && !(job->name = strdup(name))) ||
        (o->idem_key && !(job->idem_key = strdup(o->idem_key)))) {
        free(canon);
        if (job)
            rd_jobs_job_free(job);
        else
            rd_scene_free(scene);
        return NULL;
    }
    rd_jobs_hash(canon, strlen(canon), job->key);
    job->has_key = 1;
    free(canon);
    memcpy(job->idem_hash, o->idem_hash, sizeof job->idem_hash);
    const char *analysis = rd_scene_analysis(scene);
    snprintf(job->analysis, sizeof job->analysis, "%s", analysis ? analysis : "");
    job->timeout_s = o->time_limit_s > 0 && o->time_limit_s < jobs->cfg.timeout_s
                         ? o->time_limit_s
                         : jobs->cfg.timeout_s;
    job->predicted_s = rd_scene_cost_predict(scene);
    job->refs = 1;
    job->status = RD_JOB_QUEUED;
    clock_gettime(CLOCK_REALTIME, &job->created);
    return job;
}

int rd_jobs_submit(rd_jobs *jobs, rd_scene *scene, const rd_jobs_submit_opts *o,
                   rd_jobs_submitted *out, rd_error *err)
{
    int rc = RD_OK;
    memset(out, 0, sizeof *out);
    char *echo = rd_scene_to_json(scene);
    struct job *job = echo ? new_job(jobs, scene, o) : NULL;
    if (!job) {
        if (!echo)
            rd_scene_free(scene);
        free(echo);
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    }
    /* NaN (no cost model) is never below the threshold: such jobs queue. */
    int run_inline = o->inline_below_s > 0 && job->predicted_s < o->inline_below_s;

    pthread_mutex_lock(&jobs->mu);
    struct job *earlier;
    if (jobs->stopping) {
        rc = rd_error_set(err, RD_EBUSY, "", "The server is shutting down and takes no new jobs.");
    } else if ((earlier = earlier_answer_locked(jobs, o, job->key, out))) {
        memcpy(out->id, earlier->id, sizeof out->id);
    } else if (!run_inline && jobs->counts[RD_JOB_QUEUED] >= (size_t)jobs->cfg.queue_max) {
        rc = rd_error_set(err, RD_EBUSY, "",
                          "The job queue is full (%d jobs waiting for %d workers); retry later.",
                          jobs->cfg.queue_max, jobs->cfg.threads);
    } else if ((rc = rd_jobs_new_id_locked(jobs, job->id, err)) == RD_OK) {
        if (run_inline) { /* running from the start, with the run's own reference */
            job->status = RD_JOB_RUNNING;
            job->started = job->created;
            job->deadline = rd_clock_mono_s() + job->timeout_s;
            job->refs++;
        }
        if (run_inline) { /* the row is written once, when the run ends */
            job->unstored_echo = echo;
            echo = NULL;
        } else {
            rc = rd_jobs_insert_row_locked(jobs, job, echo, err);
        }
        if (rc == RD_OK) {
            rd_jobs_push_locked(jobs, job);
            memcpy(out->id, job->id, sizeof out->id);
            if (!run_inline)
                pthread_cond_signal(&jobs->work);
        }
    }
    int listed = rc == RD_OK && !out->cached && !out->replayed && !out->conflict;
    rd_scene *taken = NULL;
    if (listed && run_inline) {
        taken = job->scene;
        job->scene = NULL;
    }
    pthread_mutex_unlock(&jobs->mu);
    free(echo);
    if (!listed) {
        rd_jobs_job_free(job);
        return rc;
    }
    if (run_inline) {
        rd_jobs_run(jobs, job, taken, 0); /* drops the run's reference */
        out->ran_inline = 1;
    }
    return RD_OK;
}

/* Waits (mutex held) until the job is final or `seconds` pass.  Shutdown
 * makes every job final within its wait, so a waiter always gets a final job. */
static void wait_final_locked(rd_jobs *jobs, struct job *job, double seconds)
{
    struct timespec deadline = rd_clock_mono_deadline(seconds);
    while (!is_final(job->status))
        if (pthread_cond_timedwait(&jobs->done, &jobs->mu, &deadline) == ETIMEDOUT)
            break;
}

/* With `mu` held and a reference on `job`: the shared body of a job with
 * a result (has_body), else its rendering.  Returns with `mu` released. */
static int answer_and_release(rd_jobs *jobs, struct job *job, rd_jobs_body **body, char **json,
                              int *finished, rd_error *err)
{
    if (finished)
        *finished = is_final(job->status);
    if (has_body(job))
        return rd_jobs_body_and_release(jobs, job, body, err);
    return rd_jobs_view_and_release(jobs, job, json, NULL, err);
}

int rd_jobs_get(rd_jobs *jobs, const char *id, double wait_s, rd_jobs_body **body, char **json,
                int *finished, rd_error *err)
{
    *body = NULL;
    *json = NULL;
    if (finished)
        *finished = 0;
    struct job *job;
    int acquired = rd_jobs_acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (wait_s > 0)
        wait_final_locked(jobs, job, wait_s);
    return answer_and_release(jobs, job, body, json, finished, err);
}

int rd_jobs_is_final(rd_jobs *jobs, const char *id)
{
    pthread_mutex_lock(&jobs->mu);
    struct job *job = rd_jobs_find_locked(jobs, id);
    int final = !job || is_final(job->status);
    pthread_mutex_unlock(&jobs->mu);
    return final;
}

int rd_jobs_request_cancel(rd_jobs *jobs, const char *id, rd_error *err)
{
    struct job *job;
    int acquired = rd_jobs_acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    int ended = 0;
    if (job->status == RD_JOB_QUEUED) {
        end_locked(jobs, job, RD_JOB_CANCELLED,
                   rd_jobs_error_json(RD_ECANCELED, "The job was cancelled by a DELETE request."));
        rd_jobs_retain_locked(jobs);
        pthread_cond_broadcast(&jobs->done);
        ended = 1;
    } else if (job->status == RD_JOB_RUNNING && !job->cancel) {
        job->cancel = 1;
        job->stop_asked = rd_clock_mono_s();
    }
    rd_jobs_release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    if (ended && jobs->cfg.on_final)
        jobs->cfg.on_final(jobs->cfg.on_final_ctx);
    return RD_OK;
}

int rd_jobs_cancel(rd_jobs *jobs, const char *id, rd_jobs_body **body, char **json, rd_error *err)
{
    *body = NULL;
    *json = NULL;
    int rc = rd_jobs_request_cancel(jobs, id, err);
    if (rc != RD_OK)
        return rc;
    return rd_jobs_get(jobs, id, CANCEL_WAIT_S, body, json, NULL, err);
}

void rd_jobs_expire(rd_jobs *jobs)
{
    pthread_mutex_lock(&jobs->mu);
    rd_jobs_retain_locked(jobs);
    pthread_mutex_unlock(&jobs->mu);
}

static int matches(const struct job *j, const rd_jobs_filter *f)
{
    return (f->before == 0 || j->seq < f->before) && (f->status < 0 || j->status == f->status) &&
           (!f->analysis || strcmp(j->analysis, f->analysis) == 0) &&
           (!f->name || (j->name && strcmp(j->name, f->name) == 0));
}

int rd_jobs_list(rd_jobs *jobs, const rd_jobs_filter *f, char **json, rd_error *err)
{
    *json = NULL;
    json_t *list = json_array();
    json_t *root = json_object();
    int bad = !list || !root;
    uint64_t last = 0;
    int more = 0;
    pthread_mutex_lock(&jobs->mu);
    size_t n = 0;
    for (struct job *j = jobs->head; j && !bad; j = j->next) {
        if (!matches(j, f))
            continue;
        if (n == f->limit) { /* one more matches: there is a next page */
            more = 1;
            break;
        }
        struct snap s;
        bad |= rd_jobs_snapshot_locked(jobs, j, &s);
        if (!bad)
            bad |= json_array_append_new(list, rd_jobs_job_object(&s));
        free(s.error);
        free(s.name);
        last = j->seq;
        n++;
    }
    pthread_mutex_unlock(&jobs->mu);
    char cursor[24];
    snprintf(cursor, sizeof cursor, "%llu", (unsigned long long)last);
    if (!bad) {
        bad |= json_object_set(root, "jobs", list);
        bad |= json_object_set_new(root, "next_cursor", more ? json_string(cursor) : json_null());
        *json = bad ? NULL : json_dumps(root, JSON_COMPACT | JSON_REAL_PRECISION(6));
    }
    json_decref(list);
    json_decref(root);
    if (!*json)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory while listing jobs.");
    return RD_OK;
}

int rd_jobs_delete(rd_jobs *jobs, const char *id, int *deleted, rd_error *err)
{
    *deleted = 0;
    struct job *job;
    int acquired = rd_jobs_acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (!is_final(job->status)) {
        rd_jobs_release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        return rd_jobs_request_cancel(jobs, id, err);
    }
    rd_error store_err;
    rd_error_init(&store_err);
    int rc = rd_store_delete(jobs->cfg.store, id, &store_err);
    if (rc == RD_OK) { /* the row is gone first: a restart cannot bring the job back */
        rd_jobs_unlink_locked(jobs, job);
        rd_jobs_release_locked(job); /* the list's reference */
        *deleted = 1;
    } else {
        rd_jobs_log_store_error("delete", &store_err);
        rc = rd_error_set(err, RD_EINTERNAL, "", "Job %s could not be deleted from the job store.",
                          id);
    }
    rd_jobs_release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    return rc;
}

void rd_jobs_get_counts(rd_jobs *jobs, size_t *counts)
{
    pthread_mutex_lock(&jobs->mu);
    memcpy(counts, jobs->counts, sizeof jobs->counts);
    pthread_mutex_unlock(&jobs->mu);
}

void rd_jobs_get_stop_latency(rd_jobs *jobs, double *last_s, double *max_s)
{
    pthread_mutex_lock(&jobs->mu);
    *last_s = jobs->stop_last_s;
    *max_s = jobs->stop_max_s;
    pthread_mutex_unlock(&jobs->mu);
}

int rd_jobs_get_retry_after(rd_jobs *jobs)
{
    pthread_mutex_lock(&jobs->mu);
    double ahead = (double)(jobs->counts[RD_JOB_QUEUED] + jobs->counts[RD_JOB_RUNNING]);
    double s = jobs->mean_run_s * ahead / jobs->cfg.threads;
    pthread_mutex_unlock(&jobs->mu);
    if (!(s >= 1))
        return 1;
    if (s > 300)
        return 300;
    return (int)ceil(s);
}
