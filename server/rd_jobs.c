/*
 * rd_jobs — job pool over the job store (rd_jobs.h).
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
#include "rd_jobs.h"
#include "rd_clock.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <jansson.h>

#include "rd_gzip.h"
#include "rd_json.h"
#include "rd_scene_facts.h"

/* How long DELETE waits for a running job to acknowledge the cancellation. */
#define CANCEL_WAIT_S 5.0
/* How long rd_jobs_shutdown waits for the callbacks of runs that just ended. */
#define NOTIFY_WAIT_S 2.0
/* How long rd_jobs_free waits for idle workers to leave. */
#define IDLE_WAIT_S 1.0
/* Run time assumed for Retry-After before any job has finished. */
#define RUN_ESTIMATE_INITIAL_S 1.0

struct body {
    rd_jobs_body pub; /* first: the public view is a pointer to it */
    rd_jobs *jobs;
    struct job *owner; /* the job whose `body` this is, NULL once it is gone */
    int refs;
    char *data;
    char *gz; /* its gzip, made once by rd_jobs_body_gzip, or NULL */
    size_t gz_len;
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
    struct body
        *recent;       /* the body read last, held one reference longer (see keep_recent_locked) */
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

struct run_ctx {
    rd_jobs *jobs;
    struct job *job;
};

static const char *const status_names[RD_JOB_NSTATUS] = {"queued", "running",   "succeeded",
                                                         "failed", "cancelled", "interrupted"};

const char *rd_jobs_status_name(int status)
{
    if (status < 0 || status >= RD_JOB_NSTATUS)
        return "unknown";
    return status_names[status];
}

static int status_from_name(const char *name)
{
    for (int i = 0; i < RD_JOB_NSTATUS; i++)
        if (strcmp(name, status_names[i]) == 0)
            return i;
    return -1;
}

static int is_final(int status)
{
    return status >= RD_JOB_SUCCEEDED;
}

/* A job whose JSON (with `result`) is stored: every succeeded job, and a
 * stopped one whose run returned a partial result. */
static int has_body(const struct job *job)
{
    return job->status == RD_JOB_SUCCEEDED || (is_final(job->status) && job->body_len > 0);
}

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

void rd_jobs_hash(const char *data, size_t len, uint64_t out[2])
{
    uint64_t a = 0xcbf29ce484222325u; /* FNV-1a 64 offset basis and prime */
    uint64_t b = 0x9e3779b97f4a7c15u;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)data[i];
        a = (a ^ c) * 0x100000001b3u;
        b = (b ^ c) * 0xff51afd7ed558ccdu;
        b ^= b >> 29;
    }
    out[0] = a;
    out[1] = b ^ (uint64_t)len;
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

static int id_is_wellformed(const char *id)
{
    size_t n = 0;
    for (; id[n]; n++)
        if (n >= RD_JOBS_ID_LEN ||
            !((id[n] >= '0' && id[n] <= '9') || (id[n] >= 'a' && id[n] <= 'f')))
            return 0;
    return n == RD_JOBS_ID_LEN;
}

static int not_found(rd_error *err, const char *id)
{
    if (!id_is_wellformed(id))
        return rd_error_set(err, RD_ENOTFOUND, "", "There is no job with this id.");
    return rd_error_set(err, RD_ENOTFOUND, "",
                        "There is no job %s (the server keeps only the most recent finished jobs).",
                        id);
}

/* An error body from rd_api_error_json, or NULL when out of memory. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static char *
error_json(int code, const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    return rd_api_error_json(&err);
}

/* The error of an interrupted job: code "interrupted", which the status
 * table of core/ (errors of a request or a run) has no entry for. */
static char *interrupted_json(const char *when)
{
    char message[256];
    snprintf(message, sizeof message,
             "The server stopped while the job was %s; it did not finish and is not run again. "
             "Submit the scene again.",
             when);
    json_t *o = json_pack("{s:{s:s, s:s}}", "error", "code", "interrupted", "message", message);
    char *text = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    return text;
}

static void store_row(const struct job *job, rd_store_row *row)
{
    memset(row, 0, sizeof *row);
    memcpy(row->id, job->id, sizeof row->id);
    memcpy(row->analysis, job->analysis, sizeof row->analysis);
    row->status = status_names[job->status];
    row->progress = job->progress;
    row->created_ns = to_ns(&job->created);
    row->started_ns = to_ns(&job->started);
    row->finished_ns = to_ns(&job->finished);
    row->error = job->error;
    row->body_len = job->body_len;
}

/* A store failure after the job has been accepted is the server's problem,
 * not the client's: it is logged and the job goes on in memory. */
static void log_store_error(const char *what, const rd_error *err)
{
    fprintf(stderr, "ringdyn-server: job store, %s: %s\n", what, err->message);
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
    if (job->body)
        job->body->owner = NULL;
    rd_scene_free(job->scene);
    free(job->error);
    free(job->name);
    free(job->idem_key);
    free(job->unstored_echo);
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

static void push_locked(rd_jobs *jobs, struct job *job)
{
    job->seq = ++jobs->next_seq;
    job->next = jobs->head;
    if (jobs->head)
        jobs->head->prev = job;
    else
        jobs->tail = job;
    jobs->head = job;
    jobs->counts[job->status]++;
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
}

/* rd_store_retain's callback: the row is gone, so is the job. */
static void forget_locked(void *ctx, const char *id)
{
    rd_jobs *jobs = ctx;
    struct job *job = find_locked(jobs, id);
    if (job) {
        unlink_locked(jobs, job);
        release_locked(job);
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

static void retain_locked(rd_jobs *jobs)
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
        log_store_error("retention", &err);
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
static void update_store(rd_jobs *jobs, struct job *job, const char *body)
{
    rd_store_row row;
    char key[33], idem[33];
    rd_error err;
    rd_error_init(&err);
    store_row(job, &row);
    if (job->unstored_echo) {
        row_identity(job, &row, key, idem);
        if (rd_store_insert(jobs->cfg.store, &row, job->unstored_echo, body, &err) != RD_OK)
            log_store_error("insert", &err);
        free(job->unstored_echo);
        job->unstored_echo = NULL;
    } else if (rd_store_update(jobs->cfg.store, &row, body, &err) != RD_OK) {
        log_store_error("update", &err);
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
    set_status_locked(jobs, job, status);
    update_store(jobs, job, NULL);
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

static int snapshot_locked(const rd_jobs *jobs, const struct job *job, struct snap *s)
{
    memcpy(s->id, job->id, sizeof s->id);
    memcpy(s->analysis, job->analysis, sizeof s->analysis);
    s->status = job->status;
    s->progress = job->progress;
    s->created = job->created;
    s->started = job->started;
    s->finished = job->finished;
    s->error = NULL;
    s->name = NULL;
    s->predicted_s = job->predicted_s * (jobs->cost_scale > 0 ? jobs->cost_scale : 1);
    if (is_final(job->status) && job->error && !(s->error = strdup(job->error)))
        return -1;
    if (job->name && !(s->name = strdup(job->name))) {
        free(s->error);
        s->error = NULL;
        return -1;
    }
    return 0;
}

/* ---- rendering (no lock needed: works on a snapshot) ---- */

/* ISO-8601 UTC with milliseconds, or null for a time not reached yet. */
static json_t *iso_time(const struct timespec *ts)
{
    char buf[64];
    return rd_clock_iso8601(ts, buf, sizeof buf) == 0 ? json_string(buf) : json_null();
}

/* Seconds a running job still needs: from the predicted cost while the run
 * is within it, else from its progress and elapsed time; null when neither
 * says anything. */
static json_t *eta(const struct snap *s)
{
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    double elapsed = (double)(now.tv_sec - s->started.tv_sec) +
                     1e-9 * (double)(now.tv_nsec - s->started.tv_nsec);
    if (!(elapsed >= 0))
        elapsed = 0;
    /* The cost model (scaled to this machine by the runs so far) first: the
     * progress of a modal run moves in uneven steps, so the rate it implies
     * is rough.  Once the run outlasts the model, the progress rate. */
    if (s->predicted_s > elapsed)
        return json_real(s->predicted_s - elapsed);
    /* Below 1 % the rate is mostly start-up cost: it would overstate. */
    if (s->progress >= 0.01 && s->progress < 1)
        return json_real(elapsed * (1 - s->progress) / s->progress);
    return json_null();
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
    bad |= json_object_set_new(o, "name", s->name ? json_string(s->name) : json_null());
    bad |= json_object_set_new(o, "created", iso_time(&s->created));
    bad |= json_object_set_new(o, "started", iso_time(&s->started));
    bad |= json_object_set_new(o, "finished", iso_time(&s->finished));
    if (s->status == RD_JOB_RUNNING)
        bad |= json_object_set_new(o, "eta_s", eta(s));
    if (s->error) {
        /* The error body is {"error": {...}}; the job carries the inner object. */
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

static char *render_head(const struct snap *s)
{
    json_t *o = job_object(s);
    char *head = o ? rd_json_dumps(o, 6, 0) : NULL; /* json_dumps's bytes, faster */
    json_decref(o);
    return head;
}

/* The whole succeeded job: the envelope built by jansson, then the api's
 * result text spliced in verbatim as the last member (it is already JSON,
 * and may be megabytes, so it is not parsed again).  NULL when out of memory. */
static char *render_with_result(const struct snap *s, const char *result, size_t *len)
{
    static const char key[] = ",\"result\":";
    char *head = render_head(s);
    if (!head)
        return NULL;
    size_t hl = strlen(head), rl = strlen(result);
    /* head is "{...}": drop its '}', append the member and close again. */
    char *out = malloc(hl - 1 + (sizeof key - 1) + rl + 2);
    if (out) {
        memcpy(out, head, hl - 1);
        memcpy(out + hl - 1, key, sizeof key - 1);
        memcpy(out + hl - 1 + sizeof key - 1, result, rl);
        memcpy(out + hl - 1 + sizeof key - 1 + rl, "}", 2);
        *len = hl - 1 + (sizeof key - 1) + rl + 1;
    }
    free(head);
    return out;
}

/* Called with `mu` held and a reference on `job`: snapshots, unlocks,
 * renders (without result), drops the reference.  Returns with `mu` released. */
static int view_and_release(rd_jobs *jobs, struct job *job, char **json, int *finished,
                            rd_error *err)
{
    struct snap s;
    int bad = snapshot_locked(jobs, job, &s);
    pthread_mutex_unlock(&jobs->mu);
    if (finished)
        *finished = is_final(s.status);
    *json = bad ? NULL : render_head(&s);
    free(s.error);
    free(s.name);
    pthread_mutex_lock(&jobs->mu);
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    if (!*json)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory while rendering job %s.", s.id);
    return RD_OK;
}

/* ---- the shared JSON of a succeeded job ---- */

static void body_free(struct body *b)
{
    if (b) {
        free(b->data);
        free(b->gz);
        free(b);
    }
}

void rd_jobs_body_release(void *pub)
{
    struct body *b = pub;
    if (!b)
        return;
    rd_jobs *jobs = b->jobs;
    pthread_mutex_lock(&jobs->mu);
    int last = --b->refs == 0;
    if (last && b->owner)
        b->owner->body = NULL;
    pthread_mutex_unlock(&jobs->mu);
    if (last)
        body_free(b);
}

/* Holds `b` as the most recently read body, dropping the one held before;
 * returns that one when this was its last reference (the caller frees it
 * after unlocking).  So a job read again and again (a page polling it,
 * clients whose socket buffers swallow the whole answer) is read from the
 * store once, at the cost of one result held while nobody reads it. */
static struct body *keep_recent_locked(rd_jobs *jobs, struct body *b)
{
    struct body *old = jobs->recent;
    if (old == b)
        return NULL;
    b->refs++;
    jobs->recent = b;
    if (!old || --old->refs > 0)
        return NULL;
    if (old->owner)
        old->owner->body = NULL;
    return old;
}

/* Called with `mu` held and a reference on a `job` with a body: its shared
 * body, read from the store unless some request holds it already.  Returns
 * with `mu` released and the job's reference dropped. */
static int body_and_release(rd_jobs *jobs, struct job *job, rd_jobs_body **out, rd_error *err)
{
    struct body *b = job->body;
    if (b) {
        b->refs++;
        struct body *dropped = keep_recent_locked(jobs, b);
        release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        body_free(dropped);
        *out = &b->pub;
        return RD_OK;
    }
    char id[RD_JOBS_ID_LEN + 1];
    memcpy(id, job->id, sizeof id);
    pthread_mutex_unlock(&jobs->mu);

    char *data = NULL;
    size_t len = 0;
    rd_error read_err;
    rd_error_init(&read_err);
    int rc = rd_store_read_body(jobs->cfg.store, id, &data, &len, &read_err);
    struct body *fresh = rc == RD_OK ? calloc(1, sizeof *fresh) : NULL;
    if (rc == RD_OK && !fresh)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory reading job %s.", id);

    pthread_mutex_lock(&jobs->mu);
    if (rc == RD_ENOTFOUND && !find_locked(jobs, id)) /* retention took it meanwhile */
        rc = not_found(err, id);
    else if (rc == RD_ENOTFOUND) /* a succeeded job's row has a body: ours to explain */
        rc = rd_error_set(err, RD_EINTERNAL, "", "The result of job %s is missing from the store.",
                          id);
    else if (rc != RD_OK && read_err.code != RD_OK)
        rc = rd_error_set(err, read_err.code, "", "%s", read_err.message);
    if (rc == RD_OK) {
        if (job->body) { /* another request read it meanwhile: share that one */
            free(data);
            free(fresh);
        } else {
            fresh->jobs = jobs;
            fresh->owner = job;
            fresh->data = data;
            fresh->pub.data = data;
            fresh->pub.len = len;
            job->body = fresh;
        }
        job->body->refs++;
        *out = &job->body->pub;
    } else {
        free(data);
    }
    struct body *dropped = rc == RD_OK ? keep_recent_locked(jobs, job->body) : NULL;
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    body_free(dropped);
    return rc;
}

/* ---- workers ---- */

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
     * cycles): the job keeps it beside its error (run_job). */
    const char *kept =
        rc != RD_OK && result ? "  Its complete part is in `result` (\"partial\": true)." : "";
    if (cancel) {
        *error = error_json(RD_ECANCELED, "The job was cancelled by a DELETE request.%s", kept);
        return RD_JOB_CANCELLED;
    }
    if (rc == RD_OK && result)
        return RD_JOB_SUCCEEDED;
    /* A run that honoured the shutdown's stop request in time ends as one the
     * shutdown had to leave behind: interrupted, not failed. */
    if (rc == RD_ECANCELED && stopping && !timed_out) {
        *error = interrupted_json("running");
        return RD_JOB_INTERRUPTED;
    }
    if (rc == RD_ECANCELED && timed_out) {
        *error = error_json(RD_ETIMEOUT,
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

/* Writes the end of a run (snapshot `s` with status, error and body) to the
 * store: an update, or with `echo` (an inline run's; `job` is read for its
 * fixed fields only) the job's one insert. */
static int store_end(rd_jobs *jobs, const struct job *job, const char *echo, const struct snap *s,
                     int status, const char *error, const char *body, size_t body_len)
{
    rd_store_row row;
    char key[33], idem[33];
    memset(&row, 0, sizeof row);
    memcpy(row.id, s->id, sizeof row.id);
    memcpy(row.analysis, s->analysis, sizeof row.analysis);
    row.status = status_names[status];
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
        log_store_error("writing a finished job", &err);
    return rc;
}

/* Runs one job (taken by the caller, who holds a reference) to its end:
 * the store row first (with the rendered JSON of a success), then the
 * status in memory.  A job that shutdown already ended `interrupted` keeps
 * that end; what its run produced is dropped. */
static void run_job(rd_jobs *jobs, struct job *job, rd_scene *scene, int pooled)
{
    struct run_ctx ctx = {jobs, job};
    rd_monitor mon = {report_progress, &ctx};
    rd_error err;
    rd_error_init(&err);
    char *result = NULL, *error = NULL, *body = NULL;
    size_t body_len = 0;
    char job_analysis[sizeof job->analysis];
    memcpy(job_analysis, job->analysis, sizeof job_analysis); /* job may be freed below */

    double t0 = rd_clock_mono_s();
    int rc = rd_scene_run(scene, &mon, &result, &err);
    double t1 = rd_clock_mono_s();
    rd_scene_free(scene);
    int status = final_status(jobs, job, rc, result, &err, &error);

    pthread_mutex_lock(&jobs->mu);
    if (pooled) {
        jobs->in_solver--;
        pthread_cond_broadcast(&jobs->idle);
    }
    note_stop_latency_locked(jobs, job, t1);
    int detached = is_final(job->status);
    struct snap s;
    memset(&s, 0, sizeof s);
    int bad = detached ? 0 : snapshot_locked(jobs, job, &s);
    char *echo = NULL; /* an inline run's row, ours to write (end_locked wrote a detached one's) */
    if (!detached) {
        echo = job->unstored_echo;
        job->unstored_echo = NULL;
    }
    pthread_mutex_unlock(&jobs->mu);

    if (!detached && !bad) {
        clock_gettime(CLOCK_REALTIME, &s.finished);
        s.status = status;
        if (status == RD_JOB_SUCCEEDED)
            s.progress = 1;
        /* a success's result, or the partial result of a run that stopped */
        if (result && (status == RD_JOB_SUCCEEDED || rc != RD_OK)) {
            free(s.error); /* the body carries the job's final error beside the result */
            s.error = error ? strdup(error) : NULL;
            body = error && !s.error ? NULL : render_with_result(&s, result, &body_len);
            if (!body && status == RD_JOB_SUCCEEDED) { /* the result exists but cannot be sent */
                status = RD_JOB_FAILED;
                error = error_json(RD_ENOMEM, "Out of memory while storing the result.");
            }
        }
        if (store_end(jobs, job, echo, &s, status, error, body, body_len) != RD_OK && body) {
            free(body);
            body = NULL;
            free(error);
            status = RD_JOB_FAILED;
            error = error_json(RD_EINTERNAL, "The result could not be written to the job store "
                                             "(the server's log says why).");
            store_end(jobs, job, echo, &s, status, error, NULL, 0);
        }
    }
    free(echo);
    free(result);
    free(s.error);
    free(s.name);
    /* The JSON just stored is what the client waiting for the job reads
     * next: it becomes the job's shared body (held as the recent one), so
     * that read costs no trip to the store. */
    struct body *kept = body ? calloc(1, sizeof *kept) : NULL;
    struct body *dropped = NULL;
    if (kept) {
        kept->jobs = jobs;
        kept->data = body;
        kept->pub.data = body;
        kept->pub.len = body_len;
    } else {
        free(body);
    }

    pthread_mutex_lock(&jobs->mu);
    if (kept && !detached && !job->body) {
        kept->owner = job;
        job->body = kept;
        dropped = keep_recent_locked(jobs, kept);
        kept = NULL;
    }
    if (!detached) {
        free(job->error);
        job->error = error;
        error = NULL;
        job->body_len = body ? body_len : 0;
        if (status == RD_JOB_SUCCEEDED)
            job->progress = 1;
        job->finished = s.finished;
        set_status_locked(jobs, job, status);
        jobs->mean_run_s = 0.7 * jobs->mean_run_s + 0.3 * (t1 - t0);
        if (status == RD_JOB_SUCCEEDED && job->predicted_s > 0) {
            double ratio = (t1 - t0) / job->predicted_s;
            jobs->cost_scale = jobs->cost_scale > 0 ? 0.8 * jobs->cost_scale + 0.2 * ratio : ratio;
        }
        retain_locked(jobs);
        jobs->notifying++;
        pthread_cond_broadcast(&jobs->done);
    }
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    body_free(kept); /* not taken (detached) */
    body_free(dropped);
    free(error);

    if (!detached) {
        if (jobs->cfg.on_final)
            jobs->cfg.on_final(jobs->cfg.on_final_ctx);
        if (jobs->cfg.on_finish)
            jobs->cfg.on_finish(jobs->cfg.on_finish_ctx, job_analysis, status, t1 - t0);
        pthread_mutex_lock(&jobs->mu);
        jobs->notifying--;
        pthread_cond_broadcast(&jobs->done);
        pthread_mutex_unlock(&jobs->mu);
    }
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
            jobs->active--;
            pthread_cond_broadcast(&jobs->idle);
            pthread_mutex_unlock(&jobs->mu);
            return NULL;
        }
        job->refs++;
        set_status_locked(jobs, job, RD_JOB_RUNNING);
        clock_gettime(CLOCK_REALTIME, &job->started);
        job->deadline = rd_clock_mono_s() + job->timeout_s;
        rd_scene *scene = job->scene;
        job->scene = NULL;
        update_store(jobs, job, NULL); /* small: status and start time */
        jobs->in_solver++;
        pthread_mutex_unlock(&jobs->mu);

        run_job(jobs, job, scene, 1);
    }
}

/* ---- start: the jobs of the store ---- */

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
        job_free(job);
        return RD_ENOMEM;
    }
    push_locked(jobs, job);
    return RD_OK;
}

/* What the last process left queued or running ends `interrupted`, then
 * every row is loaded and retention applied. */
static int load_store(rd_jobs *jobs, rd_error *err)
{
    char *queued = interrupted_json("queued"), *running = interrupted_json("running");
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
        retain_locked(jobs);
    pthread_mutex_unlock(&jobs->mu);
    return rc;
}

/* ---- public functions ---- */

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
                 : load_store(jobs, err);
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
            end_locked(jobs, j, RD_JOB_INTERRUPTED, interrupted_json("queued"));
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
            end_locked(jobs, j, RD_JOB_INTERRUPTED, interrupted_json("running"));
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
        job_free(j); /* only the list's reference is left: no caller may be active */
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
            job_free(job);
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

/* Writes a new job's row (mu held). */
static int insert_row_locked(rd_jobs *jobs, const struct job *job, const char *echo, rd_error *err)
{
    char key[33], idem[33];
    rd_store_row row;
    store_row(job, &row);
    row_identity(job, &row, key, idem);
    rd_error store_err;
    rd_error_init(&store_err);
    if (rd_store_insert(jobs->cfg.store, &row, echo, NULL, &store_err) == RD_OK)
        return RD_OK;
    log_store_error("insert", &store_err);
    return rd_error_set(err, store_err.code == RD_ENOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                        "The job could not be written to the job store.");
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
    } else if ((rc = new_id_locked(jobs, job->id, err)) == RD_OK) {
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
            rc = insert_row_locked(jobs, job, echo, err);
        }
        if (rc == RD_OK) {
            push_locked(jobs, job);
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
        job_free(job);
        return rc;
    }
    if (run_inline) {
        run_job(jobs, job, taken, 0); /* drops the run's reference */
        out->ran_inline = 1;
    }
    return RD_OK;
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
        return body_and_release(jobs, job, body, err);
    return view_and_release(jobs, job, json, NULL, err);
}

int rd_jobs_get(rd_jobs *jobs, const char *id, double wait_s, rd_jobs_body **body, char **json,
                int *finished, rd_error *err)
{
    *body = NULL;
    *json = NULL;
    if (finished)
        *finished = 0;
    struct job *job;
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (wait_s > 0)
        wait_final_locked(jobs, job, wait_s);
    return answer_and_release(jobs, job, body, json, finished, err);
}

int rd_jobs_is_final(rd_jobs *jobs, const char *id)
{
    pthread_mutex_lock(&jobs->mu);
    struct job *job = find_locked(jobs, id);
    int final = !job || is_final(job->status);
    pthread_mutex_unlock(&jobs->mu);
    return final;
}

int rd_jobs_request_cancel(rd_jobs *jobs, const char *id, rd_error *err)
{
    struct job *job;
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    int ended = 0;
    if (job->status == RD_JOB_QUEUED) {
        end_locked(jobs, job, RD_JOB_CANCELLED,
                   error_json(RD_ECANCELED, "The job was cancelled by a DELETE request."));
        retain_locked(jobs);
        pthread_cond_broadcast(&jobs->done);
        ended = 1;
    } else if (job->status == RD_JOB_RUNNING && !job->cancel) {
        job->cancel = 1;
        job->stop_asked = rd_clock_mono_s();
    }
    release_locked(job);
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
    retain_locked(jobs);
    pthread_mutex_unlock(&jobs->mu);
}

/* The result member of a succeeded job's JSON, which render_with_result
 * wrote as the last member: a NUL-terminated copy, or NULL. */
static char *result_of(const rd_jobs_body *b)
{
    static const char key[] = ",\"result\":";
    const char *p = strstr(b->data, key);
    if (!p || b->len < 1)
        return NULL;
    p += sizeof key - 1;
    size_t n = (size_t)(b->data + b->len - 1 - p); /* up to the closing '}' */
    char *copy = malloc(n + 1);
    if (copy) {
        memcpy(copy, p, n);
        copy[n] = '\0';
    }
    return copy;
}

int rd_jobs_result_csv(rd_jobs *jobs, const char *id, char **csv, rd_error *err)
{
    *csv = NULL;
    struct job *job;
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (!has_body(job)) {
        int rc = rd_error_set(err, RD_ENOTFOUND, "", "Job %s has no result (status %s).", job->id,
                              rd_jobs_status_name(job->status));
        release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        return rc;
    }
    rd_jobs_body *body = NULL;
    int rc = body_and_release(jobs, job, &body, err);
    if (rc != RD_OK)
        return rc;
    char *result = result_of(body);
    rd_jobs_body_release(body);
    if (!result)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory reading job %s.", id);

    /* The input is the api's own output, so a failure here is ours, not the
     * client's: report it as internal (or out of memory) whatever the api said. */
    rd_error e;
    rd_error_init(&e);
    *csv = rd_api_result_csv(result, &e);
    free(result);
    if (!*csv)
        return rd_error_set(err, e.code == RD_ENOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                            "Cannot write the result of job %s as CSV: %s", id,
                            e.message[0] ? e.message : "unknown error.");
    return RD_OK;
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
        bad |= snapshot_locked(jobs, j, &s);
        if (!bad)
            bad |= json_array_append_new(list, job_object(&s));
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
    int acquired = acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (!is_final(job->status)) {
        release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        return rd_jobs_request_cancel(jobs, id, err);
    }
    rd_error store_err;
    rd_error_init(&store_err);
    int rc = rd_store_delete(jobs->cfg.store, id, &store_err);
    if (rc == RD_OK) { /* the row is gone first: a restart cannot bring the job back */
        unlink_locked(jobs, job);
        release_locked(job); /* the list's reference */
        *deleted = 1;
    } else {
        log_store_error("delete", &store_err);
        rc = rd_error_set(err, RD_EINTERNAL, "", "Job %s could not be deleted from the job store.",
                          id);
    }
    release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    return rc;
}

int rd_jobs_body_gzip(rd_jobs_body *pub, const char **data, size_t *len)
{
    struct body *b = (struct body *)pub;
    rd_jobs *jobs = b->jobs;
    pthread_mutex_lock(&jobs->mu);
    int have = b->gz != NULL;
    pthread_mutex_unlock(&jobs->mu);
    if (!have) { /* compressed without the lock; a racing reader's copy is dropped */
        char *gz;
        size_t n;
        if (rd_gzip(b->data, pub->len, &gz, &n) != 0)
            return RD_ENOMEM;
        pthread_mutex_lock(&jobs->mu);
        if (!b->gz) {
            b->gz = gz;
            b->gz_len = n;
            gz = NULL;
        }
        pthread_mutex_unlock(&jobs->mu);
        free(gz);
    }
    *data = b->gz; /* never changes once set, and lives as long as the body */
    *len = b->gz_len;
    return RD_OK;
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
