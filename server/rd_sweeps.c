/*
 * rd_sweeps — sweeps in the service: the list of sweeps, the worker pool
 * that runs their points, and the answers of the /api/v1/sweeps routes
 * (rd_sweeps.h).
 *
 * State (all under `mu`): sweeps in submission order, each with its rows
 * (rows[i] NULL until point i has run), the next point to hand out, the
 * points running now, and the flags.  A worker takes the next point of the
 * oldest unfinished sweep, runs it unlocked, and stores the row.  A sweep
 * is freed only when final and no worker holds one of its points (running
 * == 0), so a worker's pointer stays valid while it runs.
 *
 * A point's monitor (report) reads the sweep's cancel flag, the stop flag
 * and the point's deadline: the run returns RD_ECANCELED at its next report
 * (the solvers report often enough for a stop within ~100 ms).
 */
#define _XOPEN_SOURCE 700

#include "rd_sweeps.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <jansson.h>
#include <math.h>

#include "rd_api.h"
#include "rd_clock.h"
#include "rd_store.h"
#include "rd_sweep.h"
#include "rd_sweep_request.h"

/* Retry-After for a full sweep queue: a sweep takes minutes, not seconds. */
#define BUSY_RETRY_S 30
/* How long a DELETE waits for the running points of a sweep to stop. */
#define CANCEL_WAIT_S 5.0

enum { SW_QUEUED, SW_RUNNING, SW_SUCCEEDED, SW_CANCELLED, SW_INTERRUPTED };
static const char *const status_names[] = {"queued", "running", "succeeded", "cancelled",
                                           "interrupted"};

struct sweep {
    struct sweep *prev, *next;
    char id[RD_SWEEPS_ID_LEN + 1];
    char hash[RD_SWEEPS_ID_LEN + 1]; /* rd_sweep_hash */
    int fidelity;
    rd_sweep_request req; /* NULL sweep once frozen and released */
    size_t n, next_point, running, done, failed, m, partial; /* m: runs per point */
    char **rows;
    char *spare_row; /* rows[i] of a point whose row could not be made (shared) */
    int status, cancel;
    struct timespec created, started, finished; /* CLOCK_REALTIME; zero = not yet */
    /* A final sweep, rendered once (freeze_locked): its list entry, JSON and
     * CSV.  NULL until then (or when rendering ran out of memory). */
    char *meta, *body, *csv;
};

struct rd_sweeps {
    rd_sweeps_config cfg;
    pthread_mutex_t mu;
    pthread_cond_t work; /* a point to run, or stop */
    pthread_cond_t idle; /* a point finished */
    struct sweep *head, *tail;
    size_t busy;   /* points running in all */
    int notifying; /* workers inside on_final (shutdown waits for them) */
    int stopping;
    int random_fd;
    pthread_t *workers;
    int nworkers;
};

/* What a point's monitor reads. */
struct point_ctx {
    rd_sweeps *ss;
    struct sweep *sw;
    double deadline; /* CLOCK_MONOTONIC */
    int timed_out;
    size_t runs; /* done, as its monitor last said (< m); sw->partial sums them */
};

static int is_final(int status)
{
    return status >= SW_SUCCEEDED;
}

/* ---- replies ---- */

static void reply_error(rd_sweeps_reply *r, const rd_error *err)
{
    r->status = rd_api_http_status(err->code);
    r->body = rd_api_error_json(err);
    r->content_type = "application/json";
    if (err->code == RD_EBUSY)
        r->retry_after = BUSY_RETRY_S;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void
reply_fail(rd_sweeps_reply *r, int code, const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    reply_error(r, &err);
}

static void reply_json(rd_sweeps_reply *r, int status, char *body)
{
    if (!body) {
        reply_fail(r, RD_ENOMEM, "The server is out of memory.");
        return;
    }
    r->status = status;
    r->body = body;
    r->content_type = "application/json";
}

void rd_sweeps_reply_cleanup(rd_sweeps_reply *reply)
{
    free(reply->body);
    reply->body = NULL;
}

/* ---- rendering (mu held) ---- */

static json_t *iso_time(const struct timespec *ts)
{
    char buf[64];
    return rd_clock_iso8601(ts, buf, sizeof buf) == 0 ? json_string(buf) : json_null();
}

/* The sweep without its table. */
static json_t *sweep_object(const struct sweep *sw)
{
    json_t *o = json_object();
    if (!o)
        return NULL;
    int bad = json_object_set_new(o, "id", json_string(sw->id));
    bad |= json_object_set_new(o, "kind", json_string(sw->fidelity ? "fidelity" : "sweep"));
    bad |= json_object_set_new(o, "status", json_string(status_names[sw->status]));
    size_t m = sw->m ? sw->m : 1, runs = sw->n * m; /* progress counts runs */
    bad |= json_object_set_new(
        o, "progress", json_real(runs ? (double)(sw->done * m + sw->partial) / (double)runs : 1));
    bad |= json_object_set_new(o, "points", json_integer((json_int_t)sw->n));
    bad |= json_object_set_new(o, "runs", json_integer((json_int_t)runs));
    bad |= json_object_set_new(o, "done", json_integer((json_int_t)sw->done));
    bad |= json_object_set_new(o, "failed", json_integer((json_int_t)sw->failed));
    bad |= json_object_set_new(o, "spec_hash", json_string(sw->hash));
    bad |= json_object_set_new(o, "created", iso_time(&sw->created));
    bad |= json_object_set_new(o, "started", iso_time(&sw->started));
    bad |= json_object_set_new(o, "finished", iso_time(&sw->finished));
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

/* `head` (a JSON object's text) with `,"key":value` inserted before its
 * closing brace; frees head.  NULL when either is NULL or out of memory. */
static char *splice(char *head, const char *key, const char *value)
{
    size_t hn = head ? strlen(head) : 0, kn = strlen(key), vn = value ? strlen(value) : 0;
    char *out = head && value && hn >= 2 ? malloc(hn + kn + vn + 6) : NULL;
    if (out) {
        memcpy(out, head, hn - 1);
        int w = sprintf(out + hn - 1, "%s\"%s\":", hn > 2 ? "," : "", key);
        memcpy(out + hn - 1 + (size_t)w, value, vn);
        strcpy(out + hn - 1 + (size_t)w + vn, "}");
    }
    free(head);
    return out;
}

/* The whole sweep: object, `table` with the rows done so far, and for a
 * succeeded fidelity sweep `fidelity` (rd_sweep_fidelity_table). */
static char *sweep_json(const struct sweep *sw, rd_error *err)
{
    if (sw->body) {
        char *copy = strdup(sw->body);
        if (!copy)
            rd_error_set(err, RD_ENOMEM, "", "The server is out of memory.");
        return copy;
    }
    json_t *o = sweep_object(sw);
    char *text = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    char *table = rd_sweep_table_json(sw->req.sweep, sw->rows, sw->n, err);
    char *fid = NULL;
    if (table && sw->req.fidelity && sw->status == SW_SUCCEEDED)
        fid = rd_sweep_fidelity_table(table, err);
    text = splice(text, "table", table);
    if (sw->req.fidelity && sw->status == SW_SUCCEEDED)
        text = splice(text, "fidelity", fid);
    free(fid);
    free(table);
    if (!text && err->code == RD_OK)
        rd_error_set(err, RD_ENOMEM, "", "The server is out of memory.");
    return text;
}

static struct sweep *find_locked(rd_sweeps *ss, const char *id)
{
    for (struct sweep *sw = ss->head; sw; sw = sw->next)
        if (strcmp(sw->id, id) == 0)
            return sw;
    return NULL;
}

static void reply_not_found(rd_sweeps_reply *r, const char *id)
{
    reply_fail(r, RD_ENOTFOUND,
               "There is no sweep %.16s%s (finished sweeps are kept in memory until the server "
               "stops or newer ones push them out; GET /api/v1/sweeps lists them).",
               id, strlen(id) > 16 ? "..." : "");
}

/* ---- the list and the pool (mu held unless said) ---- */

static void unlink_locked(rd_sweeps *ss, struct sweep *sw)
{
    if (sw->prev)
        sw->prev->next = sw->next;
    else
        ss->head = sw->next;
    if (sw->next)
        sw->next->prev = sw->prev;
    else
        ss->tail = sw->prev;
}

/* The rows and the spec of a sweep (not what freeze_locked rendered). */
static void release_rows(struct sweep *sw)
{
    for (size_t i = 0; sw->rows && i < sw->n; i++)
        if (sw->rows[i] != sw->spare_row)
            free(sw->rows[i]);
    free(sw->rows);
    free(sw->spare_row);
    sw->rows = NULL;
    sw->spare_row = NULL;
    rd_sweep_request_cleanup(&sw->req);
}

static void sweep_free(struct sweep *sw)
{
    if (!sw)
        return;
    release_rows(sw);
    free(sw->meta);
    free(sw->body);
    free(sw->csv);
    free(sw);
}

/* Removes a final sweep from memory and from the store. */
static void drop_locked(rd_sweeps *ss, struct sweep *sw)
{
    rd_error err;
    rd_error_init(&err);
    unlink_locked(ss, sw);
    if (ss->cfg.store && rd_store_sweep_delete(ss->cfg.store, sw->id, &err) != RD_OK)
        fprintf(stderr, "ringdyn-server: sweep %s: %s\n", sw->id, err.message);
    sweep_free(sw);
}

/* Drops the oldest finished sweeps beyond keep_max. */
static void retain_locked(rd_sweeps *ss)
{
    int finished = 0;
    for (struct sweep *sw = ss->tail; sw;) {
        struct sweep *prev = sw->prev;
        if (is_final(sw->status) && sw->running == 0 && ++finished > ss->cfg.keep_max)
            drop_locked(ss, sw);
        sw = prev;
    }
}

/* Renders a sweep that just became final once (its list entry, JSON and
 * CSV), stores it, and frees its rows and spec once no point of it runs.
 * Out of memory: it stays unrendered and is rendered at each request. */
static void freeze_locked(rd_sweeps *ss, struct sweep *sw)
{
    rd_error err;
    rd_error_init(&err);
    json_t *o = sweep_object(sw);
    char *meta = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    char *body = sweep_json(sw, &err);
    char *csv = rd_sweep_table_csv(sw->req.sweep, sw->rows, sw->n, &err);
    if (!meta || !body || !csv) {
        free(meta);
        free(body);
        free(csv);
        return;
    }
    sw->meta = meta;
    sw->body = body;
    sw->csv = csv;
    if (ss->cfg.store && rd_store_sweep_put(ss->cfg.store, sw->id, meta, body, csv, &err) != RD_OK)
        fprintf(stderr, "ringdyn-server: sweep %s is kept in memory only: %s\n", sw->id,
                err.message);
    if (sw->running == 0)
        release_rows(sw);
}

/* Ends `sw` if nothing of it runs and it is complete, cancelled or the
 * server stops.  Returns 1 when it became final. */
static int settle_locked(rd_sweeps *ss, struct sweep *sw)
{
    if (is_final(sw->status) || sw->running > 0)
        return 0;
    if (sw->done == sw->n && !sw->cancel)
        sw->status = SW_SUCCEEDED;
    else if (ss->stopping)
        sw->status = SW_INTERRUPTED;
    else if (sw->cancel)
        sw->status = SW_CANCELLED;
    else
        return 0;
    clock_gettime(CLOCK_REALTIME, &sw->finished);
    freeze_locked(ss, sw);
    retain_locked(ss);
    return 1;
}

static void notify_final(rd_sweeps *ss)
{
    if (ss->cfg.on_final)
        ss->cfg.on_final(ss->cfg.on_final_ctx);
}

/* rd_monitor.report: counts runs done (the last with the row); non-zero asks to stop. */
static int report(void *arg, double fraction)
{
    struct point_ctx *p = arg;
    size_t k = (size_t)fmin(fraction * (double)p->sw->m + 1e-9, (double)(p->sw->m - 1));
    pthread_mutex_lock(&p->ss->mu);
    p->sw->partial = p->sw->partial - p->runs + k;
    p->runs = k;
    int stop = p->sw->cancel || p->ss->stopping;
    pthread_mutex_unlock(&p->ss->mu);
    if (!stop && rd_clock_mono_s() >= p->deadline) {
        p->timed_out = 1;
        stop = 1;
    }
    return stop;
}

/* Runs point i of sw (no lock held) under ctx; the row, or NULL when the
 * sweep is being stopped. */
static char *run_point(struct point_ctx *ctx, size_t i)
{
    rd_sweeps *ss = ctx->ss;
    struct sweep *sw = ctx->sw;
    rd_monitor mon = {report, ctx};
    rd_error err;
    rd_error_init(&err);
    char *row = NULL;
    int rc = rd_sweep_run_point(sw->req.sweep, i, &mon, &row, &err);
    if (rc == RD_OK || (rc == RD_ECANCELED && !ctx->timed_out))
        return row;
    rd_error why;
    rd_error_init(&why);
    if (rc == RD_ECANCELED)
        rd_error_set(&why, RD_ETIMEOUT, "",
                     "Point %zu passed the service's time limit of %g s per run (--job-timeout; "
                     "%zu runs); run it with `ringdyn sweep run`, which has none.",
                     i, ss->cfg.timeout_s, sw->m);
    else
        why = err;
    rd_error_init(&err);
    return rd_sweep_request_failed_row(&sw->req, i, &why, &err);
}

/* The oldest unfinished sweep with a point to hand out. */
static struct sweep *next_work_locked(rd_sweeps *ss)
{
    for (struct sweep *sw = ss->head; sw; sw = sw->next)
        if (!is_final(sw->status) && !sw->cancel && sw->next_point < sw->n)
            return sw;
    return NULL;
}

static const char ok_tail[] = ",\"ok\",null]";

static void *worker_main(void *arg)
{
    rd_sweeps *ss = arg;
    pthread_mutex_lock(&ss->mu);
    while (!ss->stopping) {
        struct sweep *sw = next_work_locked(ss);
        if (!sw) {
            pthread_cond_wait(&ss->work, &ss->mu);
            continue;
        }
        size_t i = sw->next_point++;
        sw->running++;
        ss->busy++;
        if (sw->status == SW_QUEUED) {
            sw->status = SW_RUNNING;
            clock_gettime(CLOCK_REALTIME, &sw->started);
        }
        struct point_ctx ctx = {
            .ss = ss, .sw = sw, .deadline = rd_clock_mono_s() + ss->cfg.timeout_s * (double)sw->m};
        pthread_mutex_unlock(&ss->mu);
        char *row = run_point(&ctx, i);
        pthread_mutex_lock(&ss->mu);
        sw->partial -= ctx.runs;
        if (is_final(sw->status)) { /* ended under it (shutdown): the row comes too late */
            free(row);
        } else if (row) {
            size_t len = strlen(row), tail = sizeof ok_tail - 1;
            /* An ok row ends with status "ok" and error null (rd_sweep.h). */
            sw->failed += len < tail || strcmp(row + len - tail, ok_tail) != 0;
            sw->rows[i] = row;
            sw->done++;
        } else if (!sw->cancel && !ss->stopping) { /* out of memory: the spare row */
            sw->rows[i] = sw->spare_row;
            sw->failed++;
            sw->done++;
        }
        sw->running--;
        ss->busy--;
        if (sw->running == 0 && sw->body)
            release_rows(sw);
        pthread_cond_broadcast(&ss->idle);
        if (settle_locked(ss, sw)) {
            ss->notifying++;
            pthread_mutex_unlock(&ss->mu);
            notify_final(ss);
            pthread_mutex_lock(&ss->mu);
            ss->notifying--;
            pthread_cond_broadcast(&ss->idle);
        }
    }
    pthread_mutex_unlock(&ss->mu);
    return NULL;
}

/* ---- life cycle ---- */

/* rd_store_sweep_load: a stored sweep back in memory, rendered and final. */
static int load_one(void *ctx, const char *id, const char *meta, const char *body, const char *csv)
{
    rd_sweeps *ss = ctx;
    json_t *m = json_loads(meta, 0, NULL);
    const char *status = json_string_value(json_object_get(m, "status"));
    struct sweep *sw = calloc(1, sizeof *sw);
    int known = 0;
    for (int k = SW_SUCCEEDED; sw && status && k <= SW_INTERRUPTED; k++)
        if (strcmp(status, status_names[k]) == 0) {
            sw->status = k;
            known = 1;
        }
    if (sw && known && strlen(id) == RD_SWEEPS_ID_LEN) {
        memcpy(sw->id, id, sizeof sw->id);
        const char *kind = json_string_value(json_object_get(m, "kind"));
        sw->fidelity = kind && strcmp(kind, "fidelity") == 0;
        sw->meta = strdup(meta);
        sw->body = strdup(body);
        sw->csv = strdup(csv);
    }
    json_decref(m);
    if (!sw || !sw->meta || !sw->body || !sw->csv) { /* unreadable row: left out */
        sweep_free(sw);
        return RD_OK;
    }
    sw->prev = ss->tail;
    if (ss->tail)
        ss->tail->next = sw;
    else
        ss->head = sw;
    ss->tail = sw;
    return RD_OK;
}

int rd_sweeps_create(const rd_sweeps_config *cfg, rd_sweeps **out, rd_error *err)
{
    *out = NULL;
    if (cfg->threads < 1 || cfg->max_points < 1 || cfg->max_points > RD_SWEEP_POINTS_MAX ||
        !(cfg->timeout_s > 0) || cfg->queue_max < 1 || cfg->keep_max < 1)
        return rd_error_set(err, RD_EINVAL, "", "Sweep limits out of range.");
    rd_sweeps *ss = calloc(1, sizeof *ss);
    if (!ss)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    ss->cfg = *cfg;
    ss->random_fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    if (ss->random_fd < 0) {
        int e = errno;
        free(ss);
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot open /dev/urandom: %s.", strerror(e));
    }
    if (pthread_mutex_init(&ss->mu, NULL) != 0 || pthread_cond_init(&ss->work, NULL) != 0 ||
        pthread_cond_init(&ss->idle, NULL) != 0) {
        close(ss->random_fd);
        free(ss);
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot initialise the sweeps' locks.");
    }
    if (cfg->store) {
        if (rd_store_sweep_load(cfg->store, load_one, ss, err) != RD_OK) {
            rd_sweeps_free(ss);
            return err->code;
        }
        pthread_mutex_lock(&ss->mu);
        retain_locked(ss);
        pthread_mutex_unlock(&ss->mu);
    }
    ss->workers = calloc((size_t)cfg->threads, sizeof *ss->workers);
    if (!ss->workers) {
        rd_sweeps_free(ss);
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    }
    for (int t = 0; t < cfg->threads; t++) {
        int e = pthread_create(&ss->workers[t], NULL, worker_main, ss);
        if (e != 0) {
            rd_sweeps_free(ss);
            return rd_error_set(err, RD_EINTERNAL, "", "Cannot start a sweep worker: %s.",
                                strerror(e));
        }
        ss->nworkers++;
    }
    *out = ss;
    return RD_OK;
}

void rd_sweeps_stop(rd_sweeps *ss)
{
    if (!ss)
        return;
    pthread_mutex_lock(&ss->mu);
    ss->stopping = 1;
    pthread_cond_broadcast(&ss->work);
    pthread_mutex_unlock(&ss->mu);
}

void rd_sweeps_shutdown(rd_sweeps *ss, double wait_s)
{
    if (!ss)
        return;
    pthread_mutex_lock(&ss->mu);
    ss->stopping = 1;
    pthread_cond_broadcast(&ss->work);
    double until = rd_clock_mono_s() + wait_s;
    while (ss->busy > 0 && rd_clock_mono_s() < until) {
        struct timespec t;
        clock_gettime(CLOCK_REALTIME, &t);
        t.tv_nsec += 20000000L; /* the idle condition uses the realtime clock: poll in 20 ms */
        if (t.tv_nsec >= 1000000000L) {
            t.tv_sec++;
            t.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&ss->idle, &ss->mu, &t);
    }
    /* A worker that ended a sweep just before may still be telling on_final;
     * after this returns nobody calls it (every sweep is final). */
    while (ss->notifying > 0)
        pthread_cond_wait(&ss->idle, &ss->mu);
    int ended = 0;
    for (struct sweep *sw = ss->head; sw; sw = sw->next)
        if (!is_final(sw->status)) { /* what still runs is abandoned: interrupted */
            sw->status = SW_INTERRUPTED;
            clock_gettime(CLOCK_REALTIME, &sw->finished);
            freeze_locked(ss, sw);
            ended = 1;
        }
    pthread_mutex_unlock(&ss->mu);
    if (ended)
        notify_final(ss);
}

void rd_sweeps_free(rd_sweeps *ss)
{
    if (!ss)
        return;
    rd_sweeps_shutdown(ss, 0);
    pthread_mutex_lock(&ss->mu);
    size_t busy = ss->busy;
    pthread_mutex_unlock(&ss->mu);
    if (busy > 0) /* a point inside a solver that does not report: left to the exit */
        return;
    for (int t = 0; t < ss->nworkers; t++)
        pthread_join(ss->workers[t], NULL);
    while (ss->head) {
        struct sweep *sw = ss->head;
        unlink_locked(ss, sw);
        sweep_free(sw);
    }
    free(ss->workers);
    close(ss->random_fd);
    pthread_cond_destroy(&ss->work);
    pthread_cond_destroy(&ss->idle);
    pthread_mutex_destroy(&ss->mu);
    free(ss);
}

/* ---- requests ---- */

static int new_id(rd_sweeps *ss, char *id)
{
    uint64_t r;
    if (read(ss->random_fd, &r, sizeof r) != (ssize_t)sizeof r)
        return -1;
    snprintf(id, RD_SWEEPS_ID_LEN + 1, "%016llx", (unsigned long long)r);
    return 0;
}

/* The answer about sweep `id` (mu not held): the sweep, or for a submission
 * with Location and 200 when final after a wait, else 202. */
static void answer(rd_sweeps *ss, const char *id, int submit, int waited, rd_sweeps_reply *r)
{
    rd_error err;
    rd_error_init(&err);
    pthread_mutex_lock(&ss->mu);
    struct sweep *sw = find_locked(ss, id);
    char *body = sw ? sweep_json(sw, &err) : NULL;
    int final = sw && is_final(sw->status);
    pthread_mutex_unlock(&ss->mu);
    if (!sw) {
        reply_not_found(r, id);
        return;
    }
    if (!body) {
        reply_error(r, &err);
        return;
    }
    reply_json(r, submit && !(waited && final) ? 202 : 200, body);
    if (submit)
        snprintf(r->location, sizeof r->location, "/api/v1/sweeps/%s", id);
}

void rd_sweeps_post(rd_sweeps *ss, const char *body, size_t len, double wait_s, rd_sweeps_reply *r)
{
    rd_error err;
    rd_error_init(&err);
    struct sweep *sw = calloc(1, sizeof *sw);
    if (!sw) {
        reply_fail(r, RD_ENOMEM, "The server is out of memory.");
        return;
    }
    if (rd_sweep_request_parse(body, len, ss->cfg.max_points, &sw->req, &err) != RD_OK) {
        sweep_free(sw);
        reply_error(r, &err);
        return;
    }
    sw->n = rd_sweep_points(sw->req.sweep);
    sw->m = rd_sweep_runs_per_point(sw->req.sweep);
    sw->fidelity = sw->req.fidelity;
    memcpy(sw->hash, rd_sweep_hash(sw->req.sweep), sizeof sw->hash);
    sw->rows = calloc(sw->n ? sw->n : 1, sizeof *sw->rows);
    sw->spare_row = rd_sweep_request_spare_row(&sw->req);
    if (!sw->rows || !sw->spare_row || new_id(ss, sw->id) != 0) {
        sweep_free(sw);
        reply_fail(r, RD_ENOMEM, "The server is out of memory.");
        return;
    }
    clock_gettime(CLOCK_REALTIME, &sw->created);
    pthread_mutex_lock(&ss->mu);
    int unfinished = 0;
    for (struct sweep *s = ss->head; s; s = s->next)
        unfinished += !is_final(s->status);
    if (ss->stopping || unfinished >= ss->cfg.queue_max) {
        pthread_mutex_unlock(&ss->mu);
        sweep_free(sw);
        reply_fail(r, RD_EBUSY,
                   "The server has %d sweeps queued or running, its limit; retry when one has "
                   "finished, or run this one with `ringdyn sweep run`.",
                   ss->cfg.queue_max);
        return;
    }
    sw->prev = ss->tail;
    if (ss->tail)
        ss->tail->next = sw;
    else
        ss->head = sw;
    ss->tail = sw;
    char id[RD_SWEEPS_ID_LEN + 1];
    memcpy(id, sw->id, sizeof id);
    int final = settle_locked(ss, sw); /* a sweep of 0 points (cannot happen today) ends at once */
    pthread_cond_broadcast(&ss->work);
    pthread_mutex_unlock(&ss->mu);
    if (final)
        notify_final(ss);
    if (wait_s > 0 && !rd_sweeps_is_final(ss, id)) {
        r->status = 0;
        memcpy(r->wait_id, id, sizeof id);
        r->wait_s = wait_s;
        r->wait_submit = 1;
        return;
    }
    answer(ss, id, 1, wait_s >= 0, r);
}

void rd_sweeps_answer_wait(rd_sweeps *ss, const char *id, int submit, rd_sweeps_reply *reply)
{
    answer(ss, id, submit, 1, reply);
}

void rd_sweeps_list(rd_sweeps *ss, size_t limit, rd_sweeps_reply *r)
{
    json_t *list = json_array();
    int bad = !list;
    pthread_mutex_lock(&ss->mu);
    size_t k = 0;
    for (struct sweep *sw = ss->tail; sw && !bad && k < limit; sw = sw->prev, k++)
        bad = json_array_append_new(list, sw->meta ? json_loads(sw->meta, 0, NULL)
                                                   : sweep_object(sw)) != 0;
    pthread_mutex_unlock(&ss->mu);
    json_t *o = bad ? NULL : json_pack("{s:O}", "sweeps", list);
    reply_json(r, 200, o ? json_dumps(o, JSON_COMPACT) : NULL);
    json_decref(o);
    json_decref(list);
}

static void item_csv(rd_sweeps *ss, const char *id, rd_sweeps_reply *r)
{
    rd_error err;
    rd_error_init(&err);
    pthread_mutex_lock(&ss->mu);
    struct sweep *sw = find_locked(ss, id);
    char *csv = !sw       ? NULL
                : sw->csv ? strdup(sw->csv)
                          : rd_sweep_table_csv(sw->req.sweep, sw->rows, sw->n, &err);
    if (sw && !csv && err.code == RD_OK)
        rd_error_set(&err, RD_ENOMEM, "", "The server is out of memory.");
    pthread_mutex_unlock(&ss->mu);
    if (!sw) {
        reply_not_found(r, id);
    } else if (!csv) {
        reply_error(r, &err);
    } else {
        r->status = 200;
        r->body = csv;
        r->content_type = "text/csv; charset=utf-8";
        snprintf(r->disposition, sizeof r->disposition, "attachment; filename=\"sweep-%.16s.csv\"",
                 id);
    }
}

/* DELETE: cancels an unfinished sweep (waiting for its running points to
 * stop), deletes a finished one (204). */
static void item_delete(rd_sweeps *ss, const char *id, rd_sweeps_reply *r)
{
    pthread_mutex_lock(&ss->mu);
    struct sweep *sw = find_locked(ss, id);
    if (!sw) {
        pthread_mutex_unlock(&ss->mu);
        reply_not_found(r, id);
        return;
    }
    if (is_final(sw->status) && sw->running == 0) {
        drop_locked(ss, sw);
        pthread_mutex_unlock(&ss->mu);
        r->status = 204;
        return;
    }
    sw->cancel = 1;
    int final = settle_locked(ss, sw);
    pthread_mutex_unlock(&ss->mu);
    if (final) {
        notify_final(ss);
        answer(ss, id, 0, 0, r);
        return;
    }
    r->status = 0;
    memcpy(r->wait_id, id, sizeof r->wait_id);
    r->wait_s = CANCEL_WAIT_S;
}

void rd_sweeps_item(rd_sweeps *ss, const char *method, const char *id, int csv, rd_sweeps_reply *r)
{
    if (csv)
        item_csv(ss, id, r);
    else if (strcmp(method, "DELETE") == 0)
        item_delete(ss, id, r);
    else
        answer(ss, id, 0, 0, r);
}

int rd_sweeps_is_final(rd_sweeps *ss, const char *id)
{
    pthread_mutex_lock(&ss->mu);
    struct sweep *sw = find_locked(ss, id);
    int final = !sw || is_final(sw->status);
    pthread_mutex_unlock(&ss->mu);
    return final;
}
