/*
 * rd_lift_check.c — the run-time check that lets auto give a friction scene
 * the rigid ring (rd_lift_solve.c, choose_model): does the rigid ring's run
 * date the flank changes as the flexible ring would, within the scene's
 * numerics.accuracy_deg?
 *
 * What differs between the two rings happens where the flanks act: a leave
 * (the split ring peels off its flank, its ends first, or lifts its edge
 * under the friction's twist before its load turns) and a landing (its
 * parts arrive one after another).  A seated ring follows its loads
 * quasi-statically and a flying one moves with its total load, which is the
 * same for both rings.  So the check runs the full ring (the scene's n and
 * tolerances: the flexible ring's answer the scene would get; at rtol/10 and
 * atol/10 the windows cost ~2x the steps, 46720 instead of 22615 at 8000 rpm,
 * Coulomb, no gas, for the same verdicts on 6 battery scenes) only over each
 * flight of the rigid run:
 * from LEAD_DEG before the crank angle where the rigid ring's mean lift left
 * its flank (touch_deg of the leave) to the flight's landing, i.e. to the
 * root that records the window's last band crossing — not through the
 * landing's settling, where the full ring spends most of its steps (the
 * gas example: ~3400 of ~3960 steps per half cycle in the degree after its
 * band entry), but to where its mean lift touches the flank (a full ring
 * whose mean lift dips into the band and out again before it lands has
 * another flank-change list).  The window starts from the rigid ring's own
 * state at the last output sample LEAD_DEG before the leave (seated: its
 * quasi-static twist and preload, the same on every segment); LEAD_DEG lets
 * the full ring settle from there under its loads (an undeformed start set
 * off a twist transient that left the band 9 deg early at 1000 rpm,
 * Coulomb, 100 um).  Flights closer than LEAD_DEG after
 * the previous landing share one window (a bounce: the check then runs
 * through that landing).  The check passes when every window has the rigid
 * ring's flank changes (number and kind) and none moves by more than the
 * target; its largest move is reported (rd_lift_result.event_error_model_deg).
 *
 * A rigid run without flank changes is checked over the whole run (the full
 * ring must stay seated too; seated phases are cheap).  What it does not
 * see: a flank change the rigid run does not have, outside its windows (a
 * twist-driven leave more than LEAD_DEG before the rigid ring's own; the
 * full ring leaving earlier then shows as a moved or extra event at the
 * window's start, which fails the check).  The segment count is the
 * caller's: rd_lift_solve.c repeats the check at n/2 for the estimate.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

#define LEAD_DEG   10.0 /* the window's start before the rigid ring's leave (header comment) */
#define TAIL_DEG   2.0  /* a window runs at most this far past the rigid ring's last landing */
#define CHECK_RTOL 1.0  /* the windows at the scene's rtol and atol x this (header comment) */

static int is_leave(int kind)
{
    return kind == RD_EVENT_LEAVE_LOWER || kind == RD_EVENT_LEAVE_UPPER;
}

/* Where the rigid ring's mean lift left its flank before event e (a leave). */
static double left_at(const rd_lift_event *e)
{
    return isfinite(e->touch_deg) ? e->touch_deg : e->crank_deg;
}

/* One window: the full ring from t0 (the rigid ring's state LEAD_DEG
 * before the leave `first`, or the scene's own start at 0) over the events
 * first..last of the rigid run (none: the whole run, from its start).
 * *worst takes the largest angle move, NAN when the full ring's flank
 * changes there differ in number or kind; *steps its steps. */
static int run_window(const rd_ring *ring, const rd_lift_params *p, const rd_lift_check_in *in,
                      int first, int last, const rd_monitor *mon, double *worst, long *steps,
                      rd_error *err)
{
    const rd_lift_event *ev = in->events;
    int n = rd_ring_get_segments(ring), cnt = last - first + 1;
    int k0 = cnt ? (int)floor(fmax(0.0, left_at(&ev[first]) - LEAD_DEG) / p->step_deg) : 0;
    double t0 = k0 * p->step_deg, end_deg = 720.0 * p->engine.cycles;
    double t1 = cnt ? fmin(end_deg, ev[last].crank_deg + TAIL_DEG) : end_deg;
    double *y0 = NULL, lift[2];
    if (k0 > 0) { /* the rigid ring's state there, on every segment */
        y0 = malloc(12 * (size_t)n * sizeof *y0);
        if (!y0)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the auto check.");
        in->expand->expand(in->expand->user, in->states + (size_t)in->N * k0, y0);
    }
    rd_lift_params q = *p;
    q.step_deg = t1 - t0;
    rd_lift_setup su = {.y0 = y0, .t0_deg = t0, .t1_deg = t1, .stop_events = cnt ? cnt : 1};
    rd_lift_result res;
    memset(&res, 0, sizeof res);
    rd_lift_pass run = {.rtol = CHECK_RTOL * p->rtol,
                        .atol = CHECK_RTOL * p->atol,
                        .res = &res,
                        .lift = lift,
                        .samples = 2};
    double *buf[8] = {NULL};
    int rc = RD_OK;
    /* store_sample writes the result's per-sample arrays: two samples */
    res.crank_deg = buf[0] = malloc(2 * sizeof(double));
    res.lift = buf[1] = malloc(2 * sizeof(double));
    res.lift_min = buf[2] = malloc(2 * sizeof(double));
    res.lift_max = buf[3] = malloc(2 * sizeof(double));
    res.lift_segments = buf[4] = malloc(2 * (size_t)n * sizeof(double));
    res.twist = buf[5] = malloc(2 * sizeof(double));
    res.friction_force = buf[6] = malloc(2 * sizeof(double));
    res.flank = malloc(2 * sizeof(int));
    for (int k = 0; k < 7; k++)
        if (!buf[k])
            rc = RD_ENOMEM;
    if (rc || !res.flank)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the auto check.");
    else
        rc = rd_lift_integrate(ring, &q, &su, RD_LIFT_MODEL_FULL, mon, &run, err);
    if (rc == RD_OK) {
        double w = run.n_events == cnt ? 0.0 : NAN;
        for (int j = 0; isfinite(w) && j < cnt; j++)
            w = run.events[j].kind != ev[first + j].kind
                    ? NAN
                    : fmax(w, fabs(run.events[j].crank_deg - ev[first + j].crank_deg));
        for (int j = 0; in->flex_deg && isfinite(w) && j < cnt; j++)
            in->flex_deg[first + j] = run.events[j].crank_deg;
        *worst = isnan(w) || isnan(*worst) ? NAN : fmax(*worst, w);
        *steps += res.steps;
    }
    for (int k = 0; k < 7; k++)
        free(buf[k]);
    free(res.flank);
    free(run.events);
    free(y0);
    return rc;
}

int rd_lift_check_rigid(const rd_ring *ring, const rd_lift_params *p, const rd_lift_check_in *in,
                        const rd_monitor *mon, rd_lift_check *out, rd_error *err)
{
    const rd_lift_event *ev = in->events;
    int n_ev = in->n_events;
    memset(out, 0, sizeof *out);
    for (int j = 0; in->flex_deg && j < n_ev; j++)
        in->flex_deg[j] = NAN;
    if (n_ev == 0) { /* seated all along: the full ring must be too, over the whole run */
        int rc = run_window(ring, p, in, 0, -1, mon, &out->worst_deg, &out->steps, err);
        out->windows = rc == RD_OK;
        return rc;
    }
    for (int a = 0; a < n_ev;) {
        if (!is_leave(ev[a].kind)) { /* a landing without its leave: the run's start */
            out->worst_deg = NAN;
            return RD_OK;
        }
        /* the cluster: the leave, its landing, and the flights that leave
         * again within LEAD_DEG of a landing */
        int b = a + 1 < n_ev ? a + 1 : a;
        while (b + 2 < n_ev && is_leave(ev[b + 1].kind) &&
               left_at(&ev[b + 1]) - LEAD_DEG < ev[b].crank_deg)
            b += 2;
        rd_monitor_span sp; /* progress: the share of the run's events checked */
        const rd_monitor *wm =
            rd_monitor_span_init(&sp, mon, (double)a / n_ev, (double)(b + 1) / n_ev);
        int rc = run_window(ring, p, in, a, b, wm, &out->worst_deg, &out->steps, err);
        if (rc)
            return rc;
        out->windows++;
        out->events += b - a + 1;
        if (isnan(out->worst_deg))
            return RD_OK;
        a = b + 1;
    }
    return RD_OK;
}
