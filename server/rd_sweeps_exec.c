/*
 * rd_sweeps_exec — sweeps on an executor (rd_sweeps_config.exec, e.g.
 * Slurm): which sweeps go there, their handles (rd_sweep_remote.h), and the
 * executor thread that steps them (rd_sweeps_int.h).
 */
#define _XOPEN_SOURCE 700

#include "rd_sweeps_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rd_sweep.h"

/* How often the executor thread polls the sweeps on the executor. */
#define EXEC_POLL_S 1.0

/* ---- the executor thread ---- */

/* Takes the rows an executor step read and what it shows; ends the sweep
 * when the step did.  Returns 1 when it became final. */
static int exec_apply_locked(rd_sweeps *ss, struct sweep *sw, int phase, const rd_error *why)
{
    size_t i;
    char *row;
    while (rd_sweep_remote_next_row(sw->remote, &i, &row))
        rd_sweeps_store_row_locked(sw, i, row);
    rd_sweep_remote_get_info(sw->remote, &sw->info);
    if (sw->status == SW_QUEUED && sw->info.job_id[0]) {
        sw->status = SW_RUNNING;
        clock_gettime(CLOCK_REALTIME, &sw->started);
    }
    if (phase == RD_REMOTE_RUNNING)
        return 0;
    if (phase == RD_REMOTE_FAILED) {
        sw->error = *why;
        sw->has_error = 1;
    }
    rd_sweep_remote_free(sw->remote);
    sw->remote = NULL;
    sw->running = 0;
    return rd_sweeps_settle_locked(ss, sw);
}

/* Sleeps on `work` for at most `s` seconds (mu held). */
static void wait_work_locked(rd_sweeps *ss, double s)
{
    struct timespec t;
    clock_gettime(CLOCK_REALTIME, &t); /* the condition's clock */
    double at = (double)t.tv_nsec * 1e-9 + s;
    t.tv_sec += (time_t)at;
    t.tv_nsec = (long)((at - floor(at)) * 1e9);
    pthread_cond_timedwait(&ss->work, &ss->mu, &t);
}

/* Steps every unfinished sweep on the executor (rd_sweep_remote_step,
 * unlocked: it runs the scheduler's tools) about every EXEC_POLL_S, and at
 * once on a DELETE.  A sweep being stepped counts as one point running, so
 * it stays in the list.  When the server stops, their tasks are cancelled:
 * the sweeps end interrupted and nobody would collect the chunks. */
void *rd_sweeps_exec_main(void *arg)
{
    rd_sweeps *ss = arg;
    pthread_mutex_lock(&ss->mu);
    while (!ss->stopping) {
        for (struct sweep *sw = ss->head; sw && !ss->stopping; sw = sw->next) {
            if (!sw->remote)
                continue;
            int cancel = sw->cancel;
            rd_error why;
            rd_error_init(&why);
            pthread_mutex_unlock(&ss->mu);
            int phase = rd_sweep_remote_step(sw->remote, cancel, &why);
            pthread_mutex_lock(&ss->mu);
            if (exec_apply_locked(ss, sw, phase, &why))
                rd_sweeps_notify_final_locked(ss);
        }
        if (!ss->stopping)
            wait_work_locked(ss, EXEC_POLL_S);
    }
    for (struct sweep *sw = ss->head; sw; sw = sw->next)
        if (sw->remote) {
            pthread_mutex_unlock(&ss->mu);
            rd_sweep_remote_abandon(sw->remote);
            pthread_mutex_lock(&ss->mu);
            rd_sweep_remote_free(sw->remote);
            sw->remote = NULL;
            sw->running = 0;
        }
    pthread_mutex_unlock(&ss->mu);
    return NULL;
}

/* Whether a parsed sweep runs on the executor: one above the service's
 * limit, or of at least cfg.exec_min_points runs.  A fidelity sweep runs
 * here (its table needs the service): above the limit it is refused. */
int rd_sweeps_exec_choose(rd_sweeps *ss, struct sweep *sw, rd_error *err)
{
    size_t runs = rd_sweep_points(sw->req.sweep) * rd_sweep_runs_per_point(sw->req.sweep);
    int big = runs > ss->cfg.max_points;
    if (!ss->cfg.exec || !(big || runs >= ss->cfg.exec_min_points))
        return RD_OK;
    if (sw->req.fidelity && big)
        return rd_error_set(err, RD_EREQUEST, "",
                            "This fidelity sweep has %zu runs, above the service's limit of %zu "
                            "(--sweep-max-points): fidelity sweeps run on the service's own "
                            "workers; run it as `ringdyn sweep fidelity SCENE --spec` chunks.",
                            runs, ss->cfg.max_points);
    sw->on_exec = !sw->req.fidelity;
    return RD_OK;
}

/* The executor's handle of a sweep that runs there (it holds the spec as
 * posted, `body`); non-zero when out of memory. */
int rd_sweeps_exec_setup(rd_sweeps *ss, struct sweep *sw, const char *body, size_t len)
{
    if (!sw->on_exec)
        return 0;
    sw->remote = rd_sweep_remote_create(ss->cfg.exec, ss->cfg.shared_dir, sw->id, sw->req.sweep,
                                        ss->cfg.exec_chunks, body, len);
    sw->dir = sw->remote ? strdup(rd_sweep_remote_get_dir(sw->remote)) : NULL;
    if (sw->remote)
        rd_sweep_remote_get_info(sw->remote, &sw->info);
    sw->running = 1; /* until the executor thread lets it go (exec_apply_locked) */
    return !sw->dir;
}
