/*
 * rd_jobs — job store, bounded queue and worker pool (rd_jobs.h).
 *
 * Data layout: every job lives in one doubly linked list, newest first.  The
 * queue is not a separate structure: a worker takes the oldest `queued` job,
 * found by walking the list from its tail (the store holds a few hundred
 * jobs at most, so the walk costs less than one HTTP request).
 *
 * Locking: one mutex `mu` guards the list, the per-state counts, the stop
 * flag and every field of a job that changes (status, progress, times,
 * cancel and timeout flags, reference count).  `result` and `error` are
 * written once, under `mu`, before the status becomes final; after that
 * they never change, so a thread holding a reference may read them without
 * the lock.  Condition variables: `work` (a job was queued, or stop) wakes
 * workers; `done` (a job finished, or stop) wakes waiters.  Both wait on
 * CLOCK_MONOTONIC so wall-clock jumps do not stretch a wait.
 *
 * Lifetime: a job is freed when its reference count drops to zero.  The
 * list holds one reference; a worker running it and each request reading it
 * hold one more, so eviction never frees a job somebody is still reading.
 *
 * Cancellation and the time limit act through the rd_monitor that the
 * worker passes to rd_scene_run: its report() returns non-zero once the job
 * is cancelled, the pool is stopping or the deadline has passed, and the
 * run then returns RD_ECANCELED at its next progress report.
 */
#include "rd_jobs.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <jansson.h>

/* How long DELETE waits for a running job to acknowledge the cancellation. */
#define CANCEL_WAIT_S 5.0
/* Run time assumed for Retry-After before any job has finished. */
#define RUN_ESTIMATE_INITIAL_S 1.0

struct job {
    struct job *prev, *next; /* store list, newest first */
    int refs;
    char id[RD_JOBS_ID_LEN + 1];
    char analysis[32];
    int status;       /* enum rd_job_status */
    double progress;  /* 0..1 */
    int cancel;       /* DELETE asked a running job to stop */
    int timed_out;    /* the monitor saw the deadline pass */
    double deadline;  /* CLOCK_MONOTONIC seconds, set when the run starts */
    struct timespec created, started, finished; /* CLOCK_REALTIME; zero = not yet */
    rd_scene *scene;  /* owned until a worker takes it */
    char *result;     /* rd_scene_run's JSON, once succeeded */
    size_t result_len; /* strlen(result), counted in rd_jobs.result_bytes while listed */
    char *error;      /* rd_api_error_json body, once failed or cancelled */
};

struct rd_jobs {
    rd_jobs_config cfg;
    pthread_mutex_t mu;
    pthread_cond_t work;
    pthread_cond_t done;
    struct job *head, *tail;
    size_t counts[RD_JOB_NSTATUS]; /* jobs in the list, by status */
    size_t result_bytes;           /* result text held by listed jobs */
    int stopping;
    double mean_run_s; /* moving average of run times, for Retry-After */
    int random_fd;     /* /dev/urandom, for ids */
    pthread_t *workers;
    int nworkers; /* started successfully */
};

/* What a request reads of a job: the mutable fields copied under `mu`, the
 * immutable strings borrowed while a reference is held. */
struct snap {
    char id[RD_JOBS_ID_LEN + 1];
    char analysis[32];
    int status;
    double progress;
    struct timespec created, started, finished;
    const char *result;
    const char *error;
};

struct run_ctx {
    rd_jobs *jobs;
    struct job *job;
};

static const char *const status_names[RD_JOB_NSTATUS] = {"queued", "running", "succeeded",
                                                          "failed", "cancelled"};

const char *rd_jobs_status_name(int status)
{
    if (status < 0 || status >= RD_JOB_NSTATUS)
        return "unknown";
    return status_names[status];
}

static int is_final(int status)
{
    return status == RD_JOB_SUCCEEDED || status == RD_JOB_FAILED || status == RD_JOB_CANCELLED;
}

static double mono_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Absolute CLOCK_MONOTONIC time `seconds` from now, for pthread_cond_timedwait. */
static struct timespec mono_deadline(double seconds)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    double whole = floor(seconds);
    ts.tv_sec += (time_t)whole;
    ts.tv_nsec += (long)((seconds - whole) * 1e9);
    if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
    }
    return ts;
}

static int id_is_wellformed(const char *id)
{
    size_t n = 0;
    for (; id[n]; n++)
        if (n >= RD_JOBS_ID_LEN || !((id[n] >= '0' && id[n] <= '9') || (id[n] >= 'a' && id[n] <= 'f')))
            return 0;
    return n == RD_JOBS_ID_LEN;
}

static int not_found(rd_error *err, const char *id)
{
    if (!id_is_wellformed(id))
        return rd_error_set(err, RD_ENOTFOUND, "", "There is no job with this id.");
    return rd_error_set(err, RD_ENOTFOUND, "",
                        "There is no job %s (the server keeps only the most recent finished jobs).", id);
}

/* An error body from rd_api_error_json, or NULL when out of memory. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static char *error_json(int code, const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    return rd_api_error_json(&err);
}

/* ---- list and reference handling, all with `mu` held ---- */

static struct job *find_locked(rd_jobs *jobs, const char *id)
{
    for (struct job *j = jobs->head; j; j = j->next)
        if (strcmp(j->id, id) == 0)
            return j;
    return NULL;
}

static void job_free(struct job *job)
{
    rd_scene_free(job->scene);
    free(job->result);
    free(job->error);
    free(job);
}

static void release_locked(struct job *job)
{
    if (--job->refs == 0)
        job_free(job);
}

static void set_status_locked(rd_jobs *jobs, struct job *job, int status)
{
    jobs->counts[job->status]--;
    jobs->counts[status]++;
    job->status = status;
}

static void unlink_locked(rd_jobs *jobs, struct job *job)
{
    if (job->prev)
        job->prev->next = job->next;
    else
        jobs->head = job->next;
    if (job->next)
        job->next->prev = job->prev;
    else
        jobs->tail = job->prev;
    job->prev = job->next = NULL;
    jobs->counts[job->status]--;
    jobs->result_bytes -= job->result_len;
}

/* Drops the oldest finished jobs beyond keep_max, or while their results
 * hold more than keep_bytes (a lift result can be tens of MB); the newest
 * finished job always stays. */
static void evict_locked(rd_jobs *jobs)
{
    size_t finished = jobs->counts[RD_JOB_SUCCEEDED] + jobs->counts[RD_JOB_FAILED] +
                      jobs->counts[RD_JOB_CANCELLED];
    struct job *j = jobs->tail;
    while (j && (finished > (size_t)jobs->cfg.keep_max ||
                 (jobs->result_bytes > jobs->cfg.keep_bytes && finished > 1))) {
        struct job *prev = j->prev;
        if (is_final(j->status)) {
            unlink_locked(jobs, j);
            release_locked(j);
            finished--;
        }
        j = prev;
    }
}

/* Ends a job that never ran. */
static void cancel_queued_locked(rd_jobs *jobs, struct job *job, const char *why)
{
    rd_scene_free(job->scene);
    job->scene = NULL;
    job->error = error_json(RD_ECANCELED, "%s", why);
    clock_gettime(CLOCK_REALTIME, &job->finished);
    set_status_locked(jobs, job, RD_JOB_CANCELLED);
}

static struct job *oldest_queued_locked(rd_jobs *jobs)
{
    for (struct job *j = jobs->tail; j; j = j->prev)
        if (j->status == RD_JOB_QUEUED)
            return j;
    return NULL;
}

/* 64 random bits as hex, unique in the store. */
static int new_id_locked(rd_jobs *jobs, char *id, rd_error *err)
{
    static const char hex[] = "0123456789abcdef";
    for (int attempt = 0; attempt < 8; attempt++) {
        unsigned char bytes[RD_JOBS_ID_LEN / 2];
        ssize_t n = read(jobs->random_fd, bytes, sizeof bytes);
        if (n != (ssize_t)sizeof bytes)
            return rd_error_set(err, RD_EINTERNAL, "", "Could not read random bytes for a job id.");
        for (size_t i = 0; i < sizeof bytes; i++) {
            id[2 * i] = hex[bytes[i] >> 4];
            id[2 * i + 1] = hex[bytes[i] & 15];
        }
        id[RD_JOBS_ID_LEN] = '\0';
        if (!find_locked(jobs, id))
            return RD_OK;
    }
    return rd_error_set(err, RD_EINTERNAL, "", "Could not find a free job id.");
}

static void snapshot_locked(const struct job *job, struct snap *s)
{
    memcpy(s->id, job->id, sizeof s->id);
    memcpy(s->analysis, job->analysis, sizeof s->analysis);
    s->status = job->status;
    s->progress = job->progress;
    s->created = job->created;
    s->started = job->started;
    s->finished = job->finished;
    s->result = is_final(job->status) ? job->result : NULL;
    s->error = is_final(job->status) ? job->error : NULL;
}

/* ---- rendering (no lock needed: works on a snapshot) ---- */

/* ISO-8601 UTC with milliseconds, or null for a time not reached yet. */
static json_t *iso_time(const struct timespec *ts)
{
    if (ts->tv_sec == 0 && ts->tv_nsec == 0)
        return json_null();
    struct tm tm;
    time_t t = ts->tv_sec;
    if (!gmtime_r(&t, &tm))
        return json_null();
    char buf[64];
    snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03ldZ", tm.tm_year + 1900,
             tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, ts->tv_nsec / 1000000L);
    return json_string(buf);
}

/* The job object without `result`; NULL when out of memory. */
static json_t *job_object(const struct snap *s)
{
    json_t *o = json_object();
    if (!o)
        return NULL;
    int bad = 0;
    bad |= json_object_set_new(o, "id", json_string(s->id));
    bad |= json_object_set_new(o, "status", json_string(rd_jobs_status_name(s->status)));
    bad |= json_object_set_new(o, "progress", json_real(s->progress));
    bad |= json_object_set_new(o, "analysis", json_string(s->analysis));
    bad |= json_object_set_new(o, "created", iso_time(&s->created));
    bad |= json_object_set_new(o, "started", iso_time(&s->started));
    bad |= json_object_set_new(o, "finished", iso_time(&s->finished));
    if (s->error) {
        /* The api's body is {"error": {...}}; the job carries the inner object. */
        json_t *body = json_loads(s->error, 0, NULL);
        json_t *inner = body ? json_object_get(body, "error") : NULL;
        if (inner)
            bad |= json_object_set(o, "error", inner);
        json_decref(body);
    }
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

/* The whole job: the envelope built by jansson, then the api's result text
 * spliced in verbatim as the last member (it is already JSON, and may be
 * megabytes, so it is not parsed again). */
static int render_job(const struct snap *s, char **json, rd_error *err)
{
    static const char key[] = ",\"result\":";
    char *out = NULL;
    json_t *o = job_object(s);
    char *head = o ? json_dumps(o, JSON_COMPACT | JSON_REAL_PRECISION(6)) : NULL;
    json_decref(o);
    if (!head)
        goto out;
    if (!s->result || s->status != RD_JOB_SUCCEEDED) {
        out = head;
        head = NULL;
        goto out;
    }
    size_t hl = strlen(head), rl = strlen(s->result);
    /* head is "{...}": drop its '}', append the member and close again. */
    out = malloc(hl - 1 + (sizeof key - 1) + rl + 2);
    if (!out)
        goto out;
    memcpy(out, head, hl - 1);
    memcpy(out + hl - 1, key, sizeof key - 1);
    memcpy(out + hl - 1 + sizeof key - 1, s->result, rl);
    memcpy(out + hl - 1 + sizeof key - 1 + rl, "}", 2);
out:
    free(head);
    *json = out;
    if (!out)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory while rendering job %s.", s->id);
    return RD_OK;
}

/* Called with `mu` held and a reference on `job`: snapshots, unlocks,
 * renders, drops the reference.  Returns with `mu` released. */
static int view_and_release(rd_jobs *jobs, struct job *job, char **json, int *finished,
                            rd_error *err)
{
    struct snap s;
    snapshot_locked(job, &s);
    pthread_mutex_unlock(&jobs->mu);
    if (finished)
        *finished = is_final(s.status);
    int rc = render_job(&s, json, err);
    pthread_mutex_lock(&jobs->mu);
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    return rc;
}

/* ---- workers ---- */

/* rd_monitor.report: records progress; non-zero asks the run to stop. */
static int report_progress(void *arg, double fraction)
{
    struct run_ctx *ctx = arg;
    double now = mono_now();
    pthread_mutex_lock(&ctx->jobs->mu);
    struct job *job = ctx->job;
    if (fraction >= 0 && fraction <= 1) /* NaN fails both */
        job->progress = fraction;
    else if (fraction > 1)
        job->progress = 1;
    int stop = job->cancel || ctx->jobs->stopping;
    if (!stop && now >= job->deadline) {
        job->timed_out = 1;
        stop = 1;
    }
    pthread_mutex_unlock(&ctx->jobs->mu);
    return stop;
}

/* Runs one job (taken by the caller, who holds a reference) to its end. */
static void run_job(rd_jobs *jobs, struct job *job, rd_scene *scene)
{
    struct run_ctx ctx = {jobs, job};
    rd_monitor mon = {report_progress, &ctx};
    rd_error err;
    rd_error_init(&err);
    char *result = NULL, *error = NULL;

    double t0 = mono_now();
    int rc = rd_scene_run(scene, &mon, &result, &err);
    double run_s = mono_now() - t0;
    rd_scene_free(scene);

    pthread_mutex_lock(&jobs->mu);
    int cancel = job->cancel, stopping = jobs->stopping, timed_out = job->timed_out;
    double progress = job->progress;
    pthread_mutex_unlock(&jobs->mu);

    /* A DELETE wins even over a run that completed meanwhile: the client was
     * told the job is being cancelled, so it must not turn up succeeded. */
    int status;
    if (cancel) {
        status = RD_JOB_CANCELLED;
        error = error_json(RD_ECANCELED, "The job was cancelled by a DELETE request.");
    } else if (rc == RD_OK && result) {
        status = RD_JOB_SUCCEEDED;
    } else if (stopping) {
        status = RD_JOB_CANCELLED;
        error = error_json(RD_ECANCELED, "The server shut down before the job finished.");
    } else if (rc == RD_ECANCELED && timed_out) {
        status = RD_JOB_FAILED;
        error = error_json(RD_ETIMEOUT,
                           "The job ran longer than the time limit of %g s and was stopped "
                           "(at %.0f %% progress).",
                           jobs->cfg.timeout_s, 100.0 * progress);
    } else {
        status = RD_JOB_FAILED;
        if (err.code == RD_OK)
            rd_error_set(&err, rc != RD_OK ? rc : RD_EINTERNAL, "", "The analysis failed: %s.",
                         rd_error_summary(rc != RD_OK ? rc : RD_EINTERNAL));
        error = rd_api_error_json(&err);
    }
    if (status != RD_JOB_SUCCEEDED) {
        free(result);
        result = NULL;
    }

    pthread_mutex_lock(&jobs->mu);
    job->result = result;
    job->result_len = result ? strlen(result) : 0;
    jobs->result_bytes += job->result_len;
    job->error = error;
    if (status == RD_JOB_SUCCEEDED)
        job->progress = 1;
    clock_gettime(CLOCK_REALTIME, &job->finished);
    set_status_locked(jobs, job, status);
    jobs->mean_run_s = 0.7 * jobs->mean_run_s + 0.3 * run_s;
    evict_locked(jobs);
    pthread_cond_broadcast(&jobs->done);
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);

    if (jobs->cfg.on_finish)
        jobs->cfg.on_finish(jobs->cfg.on_finish_ctx, status, run_s);
}

static void *worker_main(void *arg)
{
    rd_jobs *jobs = arg;
    for (;;) {
        struct job *job = NULL;
        pthread_mutex_lock(&jobs->mu);
        while (!jobs->stopping && !(job = oldest_queued_locked(jobs)))
            pthread_cond_wait(&jobs->work, &jobs->mu);
        if (jobs->stopping) {
            pthread_mutex_unlock(&jobs->mu);
            return NULL;
        }
        job->refs++;
        set_status_locked(jobs, job, RD_JOB_RUNNING);
        clock_gettime(CLOCK_REALTIME, &job->started);
        job->deadline = mono_now() + jobs->cfg.timeout_s;
        rd_scene *scene = job->scene;
        job->scene = NULL;
        pthread_mutex_unlock(&jobs->mu);

        run_job(jobs, job, scene);
    }
}

/* ---- public functions ---- */

int rd_jobs_create(const rd_jobs_config *cfg, rd_jobs **out, rd_error *err)
{
    *out = NULL;
    if (cfg->threads < 1 || cfg->queue_max < 1 || cfg->keep_max < 1 || cfg->keep_bytes < 1 ||
        !(cfg->timeout_s > 0))
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
    pthread_mutex_init(&jobs->mu, NULL);
    pthread_cond_init(&jobs->work, &attr);
    pthread_cond_init(&jobs->done, &attr);
    pthread_condattr_destroy(&attr);

    jobs->workers = calloc((size_t)cfg->threads, sizeof *jobs->workers);
    if (!jobs->workers) {
        rd_jobs_free(jobs);
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    }
    for (int i = 0; i < cfg->threads; i++) {
        int e = pthread_create(&jobs->workers[i], NULL, worker_main, jobs);
        if (e != 0) {
            rd_jobs_free(jobs);
            return rd_error_set(err, RD_EINTERNAL, "", "Cannot start worker thread: %s.", strerror(e));
        }
        jobs->nworkers++;
    }
    *out = jobs;
    return RD_OK;
}

void rd_jobs_shutdown(rd_jobs *jobs)
{
    if (!jobs)
        return;
    pthread_mutex_lock(&jobs->mu);
    if (!jobs->stopping) {
        jobs->stopping = 1;
        /* Running jobs see `stopping` at their next progress report. */
        for (struct job *j = jobs->head; j; j = j->next)
            if (j->status == RD_JOB_QUEUED)
                cancel_queued_locked(jobs, j, "The server shut down before the job started.");
        pthread_cond_broadcast(&jobs->work);
        pthread_cond_broadcast(&jobs->done);
    }
    pthread_mutex_unlock(&jobs->mu);
}

void rd_jobs_free(rd_jobs *jobs)
{
    if (!jobs)
        return;
    rd_jobs_shutdown(jobs);
    for (int i = 0; i < jobs->nworkers; i++)
        pthread_join(jobs->workers[i], NULL);
    free(jobs->workers);
    struct job *j = jobs->head;
    while (j) {
        struct job *next = j->next;
        job_free(j); /* only the list's reference is left: no caller may be active */
        j = next;
    }
    pthread_cond_destroy(&jobs->work);
    pthread_cond_destroy(&jobs->done);
    pthread_mutex_destroy(&jobs->mu);
    close(jobs->random_fd);
    free(jobs);
}

int rd_jobs_submit(rd_jobs *jobs, rd_scene *scene, char *id, rd_error *err)
{
    int rc = RD_OK;
    struct job *job = calloc(1, sizeof *job);
    if (!job) {
        rd_scene_free(scene);
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    }
    const char *analysis = rd_scene_analysis(scene);
    snprintf(job->analysis, sizeof job->analysis, "%s", analysis ? analysis : "");
    job->scene = scene;
    job->refs = 1;
    job->status = RD_JOB_QUEUED;
    clock_gettime(CLOCK_REALTIME, &job->created);

    pthread_mutex_lock(&jobs->mu);
    if (jobs->stopping) {
        rc = rd_error_set(err, RD_EBUSY, "", "The server is shutting down and takes no new jobs.");
        goto out;
    }
    if (jobs->counts[RD_JOB_QUEUED] >= (size_t)jobs->cfg.queue_max) {
        rc = rd_error_set(err, RD_EBUSY, "",
                          "The job queue is full (%d jobs waiting for %d workers); retry later.",
                          jobs->cfg.queue_max, jobs->cfg.threads);
        goto out;
    }
    rc = new_id_locked(jobs, job->id, err);
    if (rc != RD_OK)
        goto out;
    job->next = jobs->head;
    if (jobs->head)
        jobs->head->prev = job;
    else
        jobs->tail = job;
    jobs->head = job;
    jobs->counts[RD_JOB_QUEUED]++;
    memcpy(id, job->id, RD_JOBS_ID_LEN + 1);
    pthread_cond_signal(&jobs->work);
    job = NULL;
out:
    pthread_mutex_unlock(&jobs->mu);
    if (job)
        job_free(job);
    return rc;
}

/* Locks the store and finds job `id`, taking a reference: on RD_OK *out is the
 * job and the mutex is held (drop the job with release_locked); otherwise the
 * mutex is released and the status is RD_ENOTFOUND. */
static int acquire_locked(rd_jobs *jobs, const char *id, struct job **out, rd_error *err)
{
    pthread_mutex_lock(&jobs->mu);
    *out = find_locked(jobs, id);
    if (!*out) {
        pthread_mutex_unlock(&jobs->mu);
        return not_found(err, id);
    }
    (*out)->refs++;
    return RD_OK;
}

/* Waits (mutex held) until the job is final, the server stops, or `seconds` pass. */
static void wait_final_locked(rd_jobs *jobs, struct job *job, double seconds)
{
    struct timespec deadline = mono_deadline(seconds);
    while (!is_final(job->status) && !jobs->stopping)
        if (pthread_cond_timedwait(&jobs->done, &jobs->mu, &deadline) == ETIMEDOUT)
            break;
}

int rd_jobs_view(rd_jobs *jobs, const char *id, double wait_s, char **json, int *finished,
                 rd_error *err)
{
    *json = NULL;
    if (finished)
        *finished = 0;
    struct job *job;
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (wait_s > 0)
        wait_final_locked(jobs, job, wait_s);
    return view_and_release(jobs, job, json, finished, err);
}

int rd_jobs_cancel(rd_jobs *jobs, const char *id, char **json, rd_error *err)
{
    *json = NULL;
    struct job *job;
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (job->status == RD_JOB_QUEUED) {
        cancel_queued_locked(jobs, job, "The job was cancelled by a DELETE request.");
        evict_locked(jobs);
        pthread_cond_broadcast(&jobs->done);
    } else if (job->status == RD_JOB_RUNNING) {
        job->cancel = 1;
        wait_final_locked(jobs, job, CANCEL_WAIT_S);
    }
    return view_and_release(jobs, job, json, NULL, err);
}

int rd_jobs_result_csv(rd_jobs *jobs, const char *id, char **csv, rd_error *err)
{
    *csv = NULL;
    struct job *job;
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (job->status != RD_JOB_SUCCEEDED) {
        int rc = rd_error_set(err, RD_ENOTFOUND, "", "Job %s has no result (status %s).", job->id,
                              rd_jobs_status_name(job->status));
        release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        return rc;
    }
    pthread_mutex_unlock(&jobs->mu);

    /* The input is the api's own output, so a failure here is ours, not the
     * client's: report it as internal (or out of memory) whatever the api said. */
    rd_error e;
    rd_error_init(&e);
    *csv = rd_api_result_csv(job->result, &e);
    int rc = RD_OK;
    if (!*csv)
        rc = rd_error_set(err, e.code == RD_ENOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                          "Cannot write the result of job %s as CSV: %s", id,
                          e.message[0] ? e.message : "unknown error.");

    pthread_mutex_lock(&jobs->mu);
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    return rc;
}

int rd_jobs_list(rd_jobs *jobs, size_t limit, char **json, rd_error *err)
{
    *json = NULL;
    json_t *list = json_array();
    json_t *root = json_object();
    int bad = !list || !root;
    pthread_mutex_lock(&jobs->mu);
    size_t n = 0;
    for (struct job *j = jobs->head; j && n < limit && !bad; j = j->next, n++) {
        struct snap s;
        snapshot_locked(j, &s);
        bad |= json_array_append_new(list, job_object(&s));
    }
    pthread_mutex_unlock(&jobs->mu);
    if (!bad) {
        bad |= json_object_set(root, "jobs", list);
        *json = bad ? NULL : json_dumps(root, JSON_COMPACT | JSON_REAL_PRECISION(6));
    }
    json_decref(list);
    json_decref(root);
    if (!*json)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory while listing jobs.");
    return RD_OK;
}

void rd_jobs_get_counts(rd_jobs *jobs, size_t *counts)
{
    pthread_mutex_lock(&jobs->mu);
    memcpy(counts, jobs->counts, sizeof jobs->counts);
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
