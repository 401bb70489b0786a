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
 *
 * The list, rendering and a sweep's end are in rd_sweeps_state.c; sweeps on
 * an executor (Slurm) and the thread that steps them in rd_sweeps_exec.c
 * (rd_sweeps_int.h).  The workers skip those sweeps.
 */
#define _XOPEN_SOURCE 700

#include "rd_sweeps_int.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rd_api.h"
#include "rd_clock.h"
#include "rd_store.h"
#include "rd_sweep.h"
#include "rd_sweeps_reply.h"

/* How long a DELETE waits for the running points of a sweep to stop. */
#define CANCEL_WAIT_S 5.0

/* What a point's monitor reads. */
struct point_ctx {
    rd_sweeps *ss;
    struct sweep *sw;
    double deadline; /* CLOCK_MONOTONIC */
    int timed_out;
    size_t runs; /* done, as its monitor last said (< m); sw->partial sums them */
};

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
        if (!rd_sweeps_final_status(sw->status) && !sw->cancel && !sw->on_exec &&
            sw->next_point < sw->n)
            return sw;
    return NULL;
}

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
        if (rd_sweeps_final_status(
                sw->status)) { /* ended under it (shutdown): the row comes too late */
            free(row);
        } else if (row) {
            rd_sweeps_store_row_locked(sw, i, row);
        } else if (!sw->cancel && !ss->stopping) { /* out of memory: the spare row */
            sw->rows[i] = sw->spare_row;
            sw->failed++;
            sw->done++;
        }
        sw->running--;
        ss->busy--;
        if (sw->running == 0 && sw->body)
            rd_sweeps_release_rows(sw);
        pthread_cond_broadcast(&ss->idle);
        if (rd_sweeps_settle_locked(ss, sw))
            rd_sweeps_notify_final_locked(ss);
    }
    pthread_mutex_unlock(&ss->mu);
    return NULL;
}

/* ---- life cycle ---- */

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
        if (rd_store_sweep_load(cfg->store, rd_sweeps_load_one, ss, err) != RD_OK) {
            rd_sweeps_free(ss);
            return err->code;
        }
        pthread_mutex_lock(&ss->mu);
        rd_sweeps_retain_locked(ss);
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
    if (cfg->exec) {
        int e = pthread_create(&ss->exec_thread, NULL, rd_sweeps_exec_main, ss);
        if (e != 0) {
            rd_sweeps_free(ss);
            return rd_error_set(err, RD_EINTERNAL, "", "Cannot start the executor thread: %s.",
                                strerror(e));
        }
        ss->exec_started = 1;
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
    if (ss->exec_started) { /* it cancels the executor's tasks, then ends */
        ss->exec_started = 0;
        pthread_mutex_unlock(&ss->mu);
        pthread_join(ss->exec_thread, NULL);
        pthread_mutex_lock(&ss->mu);
    }
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
        if (!rd_sweeps_final_status(sw->status)) { /* what still runs is abandoned: interrupted */
            sw->status = SW_INTERRUPTED;
            clock_gettime(CLOCK_REALTIME, &sw->finished);
            rd_sweeps_freeze_locked(ss, sw);
            ended = 1;
        }
    pthread_mutex_unlock(&ss->mu);
    if (ended)
        rd_sweeps_notify_final(ss);
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
        rd_sweeps_unlink_locked(ss, sw);
        rd_sweeps_sweep_free(sw);
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
    struct sweep *sw = rd_sweeps_find_locked(ss, id);
    char *body = sw ? rd_sweeps_json(sw, &err) : NULL;
    int final = sw && rd_sweeps_final_status(sw->status);
    pthread_mutex_unlock(&ss->mu);
    if (!sw) {
        rd_sweeps_reply_not_found(r, id);
        return;
    }
    if (!body) {
        rd_sweeps_reply_error(r, &err);
        return;
    }
    rd_sweeps_reply_json(r, submit && !(waited && final) ? 202 : 200, body);
    if (submit)
        snprintf(r->location, sizeof r->location, "/api/v1/sweeps/%s", id);
}

void rd_sweeps_post(rd_sweeps *ss, const char *body, size_t len, double wait_s, rd_sweeps_reply *r)
{
    rd_error err;
    rd_error_init(&err);
    struct sweep *sw = calloc(1, sizeof *sw);
    if (!sw) {
        rd_sweeps_reply_fail(r, RD_ENOMEM, "The server is out of memory.");
        return;
    }
    size_t limit = ss->cfg.exec ? RD_SWEEP_POINTS_MAX : ss->cfg.max_points;
    if (rd_sweep_request_parse(body, len, limit, &sw->req, &err) != RD_OK ||
        rd_sweeps_exec_choose(ss, sw, &err) != RD_OK) {
        rd_sweeps_sweep_free(sw);
        rd_sweeps_reply_error(r, &err);
        return;
    }
    sw->n = rd_sweep_points(sw->req.sweep);
    sw->m = rd_sweep_runs_per_point(sw->req.sweep);
    sw->fidelity = sw->req.fidelity;
    memcpy(sw->hash, rd_sweep_hash(sw->req.sweep), sizeof sw->hash);
    sw->rows = calloc(sw->n ? sw->n : 1, sizeof *sw->rows);
    sw->spare_row = rd_sweep_request_spare_row(&sw->req);
    if (!sw->rows || !sw->spare_row || new_id(ss, sw->id) != 0 ||
        rd_sweeps_exec_setup(ss, sw, body, len)) {
        rd_sweeps_sweep_free(sw);
        rd_sweeps_reply_fail(r, RD_ENOMEM, "The server is out of memory.");
        return;
    }
    clock_gettime(CLOCK_REALTIME, &sw->created);
    pthread_mutex_lock(&ss->mu);
    int unfinished = 0;
    for (struct sweep *s = ss->head; s; s = s->next)
        unfinished += !rd_sweeps_final_status(s->status);
    if (ss->stopping || unfinished >= ss->cfg.queue_max) {
        pthread_mutex_unlock(&ss->mu);
        rd_sweeps_sweep_free(sw);
        rd_sweeps_reply_fail(
            r, RD_EBUSY,
            "The server has %d sweeps queued or running, its limit; retry when one has "
            "finished, or run this one with `ringdyn sweep run`.",
            ss->cfg.queue_max);
        return;
    }
    rd_sweeps_link_locked(ss, sw);
    char id[RD_SWEEPS_ID_LEN + 1];
    memcpy(id, sw->id, sizeof id);
    int final = rd_sweeps_settle_locked(
        ss, sw); /* a sweep of 0 points (cannot happen today) ends at once */
    pthread_cond_broadcast(&ss->work);
    pthread_mutex_unlock(&ss->mu);
    if (final)
        rd_sweeps_notify_final(ss);
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
                                                   : rd_sweeps_object(sw)) != 0;
    pthread_mutex_unlock(&ss->mu);
    json_t *o = bad ? NULL : json_pack("{s:O}", "sweeps", list);
    rd_sweeps_reply_json(r, 200, o ? json_dumps(o, JSON_COMPACT) : NULL);
    json_decref(o);
    json_decref(list);
}

static void item_csv(rd_sweeps *ss, const char *id, rd_sweeps_reply *r)
{
    rd_error err;
    rd_error_init(&err);
    pthread_mutex_lock(&ss->mu);
    struct sweep *sw = rd_sweeps_find_locked(ss, id);
    char *csv = !sw       ? NULL
                : sw->csv ? strdup(sw->csv)
                          : rd_sweep_table_csv(sw->req.sweep, sw->rows, sw->n, &err);
    if (sw && !csv && err.code == RD_OK)
        rd_error_set(&err, RD_ENOMEM, "", "The server is out of memory.");
    pthread_mutex_unlock(&ss->mu);
    if (!sw) {
        rd_sweeps_reply_not_found(r, id);
    } else if (!csv) {
        rd_sweeps_reply_error(r, &err);
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
    struct sweep *sw = rd_sweeps_find_locked(ss, id);
    if (!sw) {
        pthread_mutex_unlock(&ss->mu);
        rd_sweeps_reply_not_found(r, id);
        return;
    }
    if (rd_sweeps_final_status(sw->status) && sw->running == 0) {
        rd_sweeps_drop_locked(ss, sw);
        pthread_mutex_unlock(&ss->mu);
        r->status = 204;
        return;
    }
    sw->cancel = 1;
    int final = rd_sweeps_settle_locked(ss, sw);
    pthread_cond_broadcast(&ss->work); /* the executor thread cancels at once */
    pthread_mutex_unlock(&ss->mu);
    if (final) {
        rd_sweeps_notify_final(ss);
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
    struct sweep *sw = rd_sweeps_find_locked(ss, id);
    int final = !sw || rd_sweeps_final_status(sw->status);
    pthread_mutex_unlock(&ss->mu);
    return final;
}
