/*
 * rd_lift_solve.c — the lift analysis' public handle and solve (rd_lift.h):
 * the scene checked once and what its runs share (the ring and its n/2
 * ring, the lubricated film, a distorted bore's static starts), the model a
 * scene gets, the accuracy plan (rd_accuracy.h: the scene at rtol and again
 * at rtol/10 for the error estimate), the result's arrays.  The top of the
 * lift folder: it calls the driver, the static start and the
 * partial-result keeping, nothing calls it back.
 *
 * Error estimate (estimate_error): the accuracy driver (rd_accuracy.h) runs
 * the scene again at rtol/10 and atol/10; the estimate is the largest lift
 * difference over the clearance, and the largest change of the flank-change
 * angles when both runs see the same changes (else NAN).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_accuracy.h"
#include "rd_lift_model.h"

/* The model a scene gets (numerics.model; auto: the cheapest the scene
 * allows at the accuracy target) and why, into out->model and out->why.
 *
 * A distorted bore (rd_lift_bore.c) or a tilted piston (rd_engine_tilt.c)
 * makes the contact pressure or the flank gap vary around the ring: the rigid
 * ring cannot represent it (asked for, it is refused in validation) and auto
 * runs the full ring.  Otherwise the scene is axisymmetric: a round bore, a
 * groove aligned with the ring, loads uniform around it.  On such a scene the rigid model (rd_lift_rigid.c) is exact except for what
 * the split ring's free ends do.  Without friction that is nothing
 * measurable: its flank changes agree with the full model's within 0.035
 * deg (thesis_lift_1000rpm, and the gas example without friction: 0.007
 * deg; test_lift_rigid).  Friction on the running face puts a couple on the
 * ring that the split ring, with its free ends, does not take uniformly.
 * Seated, the ends twist more: the rigid ring takes that with the seated
 * split ring's twist stiffness (rd_lift_rigid.c), which brings a leave
 * decided by the twist's edge lift (1000 rpm Coulomb) from 0.95 to 0.27 deg
 * of full n = 40.  In flight, the ends answer a leave with a wave the middle
 * does not, and the full ring's landings wait for the part that lags: 0.8-0.9
 * deg after the rigid ring's on the 6000 rpm gas example, 3.1 deg at 8000
 * rpm (test_lift_auto), up to 5.9 deg and a different number of flank
 * changes over a 48-scene battery (README "Models").  No uniform stiffness
 * holds that, and the Ritz bases tried (static and Krylov shapes of the
 * split ring, 10-14 dof) land later still; so no accuracy target admits the
 * rigid ring with friction and auto gives friction scenes the full model.
 *
 * The modal model (rd_lift_modal.c) is not picked by auto: measured against
 * the full model on friction scenes (tests/core/test_lift_modal.c, README
 * "Lift models") it converges in m, but slowly where the flank contacts
 * matter: at n = 20, 1000 rpm Coulomb, m = 1..16 modes miss a twist-driven
 * leave by ~1.0 deg and m = 32 by 0.07 deg; on a 6000 rpm gas + Coulomb
 * scene its landings come 1-3 deg late even at m = 32.  At the m that meets
 * 0.1 deg its dense Newton matrix (2 (10 + m)) costs more per step than the
 * full model's band one, so it is never the cheapest model meeting the
 * target; it is there by request (numerics.model = modal). */
#define MODAL_DEFAULT_MODES 12
#define SEGMENT_ORDER       1.5 /* p of the segment-count estimate (compare_levels) */
#define HALF_SEGMENTS_MIN   6   /* the n/2 run of the segment-count estimate: at least this */
static int modal_default_modes(int n)
{
    return MODAL_DEFAULT_MODES < 6 * n - 6 ? MODAL_DEFAULT_MODES : 6 * n - 6;
}
static void choose_model(const rd_lift_params *p, int n, double ring_d, rd_lift_result *out)
{
    int fric = p->friction.model != RD_FRICTION_NONE;
    out->model = p->model == RD_LIFT_MODEL_RIGID ? RD_LIFT_MODEL_RIGID : RD_LIFT_MODEL_FULL;
    if (p->model == RD_LIFT_MODEL_RIGID)
        snprintf(out->why, sizeof out->why, "asked for (numerics.model = rigid)%s",
                 fric ? "; with friction its flank changes can miss the full model's by "
                        "several degrees"
                      : "");
    else if (p->model == RD_LIFT_MODEL_FULL)
        snprintf(out->why, sizeof out->why, "asked for (numerics.model = full)");
    else if (p->model == RD_LIFT_MODEL_MODAL) {
        out->model = RD_LIFT_MODEL_MODAL;
        out->modes = p->modes ? p->modes : modal_default_modes(n);
        snprintf(out->why, sizeof out->why,
                 "asked for (numerics.model = modal, %d elastic modes%s)%s", out->modes,
                 p->modes ? "" : " by default",
                 rd_lift_bore_distorted(p, ring_d) && out->modes < 6 * n - 6
                     ? "; with a distorted bore its truncated basis cannot hold the stiff bore "
                       "contact's equilibrium: flank changes measured up to 100 deg off the "
                       "full model's, use full"
                     : "");
    } else if (rd_lift_bore_distorted(p, ring_d)) {
        snprintf(out->why, sizeof out->why,
                 "auto: the bore is distorted, so the contact pressure and the friction vary "
                 "around the ring, which the rigid ring cannot represent, and the modal model is "
                 "not cheaper than the full ring at the accuracy target");
    } else if (rd_engine_tilted(&p->engine)) {
        snprintf(out->why, sizeof out->why,
                 "auto: the piston tilt makes the flank gap vary around the ring, which the "
                 "rigid ring cannot represent, and the modal model is not cheaper than the full "
                 "ring at the accuracy target");
    } else if (!fric) {
        out->model = RD_LIFT_MODEL_RIGID;
        snprintf(out->why, sizeof out->why,
                 "auto: the scene is axisymmetric (round bore, aligned groove, loads uniform "
                 "around the ring) and without friction the rigid ring is exact for it");
    } else {
        out->model = RD_LIFT_MODEL_RIGID; /* checked at run time (check_rigid) */
        snprintf(out->why, sizeof out->why, "auto: the rigid ring, checked");
    }
}

/* The handle (rd_lift.h): the scene, checked once, and what its runs share,
 * each made by the first run that needs it. */
struct rd_lift {
    rd_ring_params rp;
    rd_lift_params p; /* p.film: the film below once it is solved */
    int segments;
    rd_ring *ring;        /* n segments (rd_lift_create) */
    rd_ring *half;        /* n/2 segments: the segment-count estimate, auto's check */
    rd_film film;         /* the lubricated model's film over the run */
    rd_film_track track;  /* (track.pt: solved) */
    rd_lift_films films;  /* a distorted bore's films instead (films.count > 0: solved) */
    double *y0, *y0_half; /* a distorted bore's static starts of n and n/2 segments */
};

/* The solves of the accuracy driver and what they keep.  Level 1, the
 * reference, is the scene at rtol/10 and atol/10 (the time integration's
 * error) and, for the flexible models, the scene at n/2 segments at the
 * scene's tolerances (the segment count's error, below). */
typedef struct lift_solve {
    rd_lift *h;
    const rd_ring *ring;
    const rd_ring *half; /* n/2 segments; NULL: no segment-count estimate */
    const rd_lift_params *p;
    const rd_lift_setup *setup, *setup_half;
    rd_lift_result *out;
    rd_lift_pass run[3]; /* the scene; rtol/10, atol/10; n/2 segments */
    int main_done;       /* level 0 ran every cycle */
    int check;           /* auto with friction: the rigid run is checked (check_rigid) */
    const rd_ring_params *rp;
    double *states;        /* the checked rigid run's state at every sample (6 each) */
    int states_next;       /* the sample keep_state stores next */
    rd_lift_setup su, suh; /* the set-ups with the bore starts */
} lift_solve;

/* The handle's ring of n/2 segments, made at the first need. */
static rd_ring *half_of(rd_lift *h, rd_error *err)
{
    if (!h->half)
        h->half = rd_ring_create(&h->rp, h->segments / 2, 0, err);
    return h->half;
}

/* The rigid run's states for the check's window starts (rd_lift_setup.state:
 * called once per output sample, in order; counted, not taken from t, whose
 * last sample may be a shortened step). */
static void keep_state(void *ctx, double t, const double *y, int N)
{
    (void)t;
    lift_solve *s = ctx;
    int k = s->states_next++;
    if (N == 6 && k < s->run[0].samples)
        memcpy(s->states + 6 * (size_t)k, y, 6 * sizeof *y);
}

/* auto on a friction scene: the rigid run's flank changes checked against
 * the full ring over its flights (rd_lift_check.c); kept when they agree
 * within numerics.accuracy_deg, else the full ring runs.  Returns 1 when
 * the rigid run stands, 0 when the full ring must run (out->why says why),
 * a negative status when the check was stopped (cancel, time limit) or ran
 * out of memory. */
/* The check of the rigid run on `ring` (the scene's, or n/2 segments): the
 * full ring's angles of the checked flank changes into flex (n_events). */
static int run_check(lift_solve *s, const rd_ring *ring, const rd_monitor *mon, double *flex,
                     rd_lift_check *ck, rd_error *err)
{
    const rd_lift_pass *r = &s->run[0];
    rd_lift_model m;
    rd_lift_form form = {0};
    int rc = rd_lift_model_init(&m, ring, s->p, NULL, err);
    if (rc == RD_OK && (rc = rd_lift_rigid_open(&m, &form, err)) == RD_OK) {
        rd_lift_check_in in = {r->events, r->n_events, s->states, 6, &form, flex};
        rc = rd_lift_check_rigid(ring, s->p, &in, mon, ck, err);
    }
    if (form.close)
        form.close(&form);
    rd_lift_model_cleanup(&m);
    return rc;
}

/* A kept rigid run's segment-count share: the check again at n/2 segments
 * (estimate on, n >= 2 HALF_SEGMENTS_MIN), the full ring's angles at n and
 * n/2 compared as compare_levels does for a full run; a warning where they
 * differ in number or by more than RD_LIFT_SEGMENT_WARN_DEG. */
static int check_half(lift_solve *s, const rd_monitor *mon, const double *fn, rd_error *err)
{
    rd_lift_result *out = s->out;
    int n = out->segments, nh = n / 2, ne = s->run[0].n_events, rc;
    if (!s->p->estimate_error || nh < HALF_SEGMENTS_MIN)
        return RD_OK;
    rd_ring *half = half_of(s->h, err);
    double *fh = malloc((size_t)(ne > 0 ? ne : 1) * sizeof *fh);
    rd_lift_check ck = {NAN, 0, 0, 0};
    rc = !half || !fh ? rd_error_set(err, RD_ENOMEM, "", "Out of memory for the auto check.")
                      : run_check(s, half, mon, fh, &ck, err);
    double dn = rc == RD_OK && isfinite(ck.worst_deg) ? 0.0 : NAN;
    for (int j = 0; isfinite(dn) && j < ne; j++)
        dn = fmax(dn, fabs(fn[j] - fh[j]));
    free(fh);
    if (rc == RD_ECANCELED || rc == RD_ETIMEOUT || rc == RD_ENOMEM)
        return rc;
    rd_error_init(err);
    out->segments_half = nh;
    out->event_error_segments_deg = dn / (pow(2.0, SEGMENT_ORDER) - 1.0);
    if (!(out->event_error_segments_deg <= RD_LIFT_SEGMENT_WARN_DEG))
        snprintf(out->accuracy_warning, sizeof out->accuracy_warning,
                 "The flank changes are not converged in the segment count: the run-time check's "
                 "full ring at n/2 = %d segments %s; the rigid ring matches the full ring at n = "
                 "%d, which is not converged; run the full ring at more segments "
                 "(/discretization/segments, /numerics/model) and compare before trusting the "
                 "angles.",
                 nh, isnan(dn) ? "has other flank changes than at n" : "moves them by over 1 deg",
                 n);
    return RD_OK;
}

static int check_rigid(lift_solve *s, const rd_monitor *mon, rd_error *err)
{
    rd_lift_result *out = s->out;
    rd_lift_check ck = {NAN, 0, 0, 0};
    rd_error e2;
    rd_error_init_local(&e2, err);
    double tol = s->p->accuracy_deg;
    int ne = s->run[0].n_events;
    double *fn = malloc((size_t)(ne > 0 ? ne : 1) * sizeof *fn);
    rd_monitor_span sp;
    int rc = fn ? run_check(s, s->ring, rd_monitor_span_init(&sp, mon, 0.0, 0.67), fn, &ck, &e2)
                : rd_error_set(&e2, RD_ENOMEM, "", "Out of memory for the auto check.");
    if (rc == RD_OK && isfinite(ck.worst_deg) && ck.worst_deg <= tol)
        rc = check_half(s, rd_monitor_span_init(&sp, mon, 0.67, 1.0), fn, &e2);
    free(fn);
    if (rc == RD_ECANCELED || rc == RD_ETIMEOUT || rc == RD_ENOMEM) { /* stopped, not refused */
        rd_error_forward(err, &e2);
        return rc;
    }
    if (rc == RD_OK && isfinite(ck.worst_deg) && ck.worst_deg <= tol) {
        out->event_error_model_deg = ck.worst_deg;
        if (ck.events == 0)
            snprintf(out->why, sizeof out->why,
                     "auto: the scene is axisymmetric; with friction the rigid ring was checked "
                     "at run time against the full ring (%d segments, the scene's tolerances): "
                     "the rigid ring stays on its flank, and so does the full ring over the "
                     "whole run (%ld steps)",
                     out->segments, ck.steps);
        else
            snprintf(out->why, sizeof out->why,
                     "auto: the scene is axisymmetric; with friction the rigid ring was checked "
                     "at run time against the full ring (%d segments, the scene's tolerances) "
                     "over each of its %d flights (%d flank changes, %ld steps): they move by at "
                     "most %.3g deg, within numerics.accuracy_deg = %g",
                     out->segments, ck.windows, ck.events, ck.steps, ck.worst_deg, tol);
        return 1;
    }
    if (rc != RD_OK)
        snprintf(out->why, sizeof out->why,
                 "auto: with friction the rigid ring's flank changes are checked against the "
                 "full ring over its flights, and the check failed (%.150s): the full ring ran",
                 e2.message);
    else if (isnan(ck.worst_deg))
        snprintf(out->why, sizeof out->why,
                 "auto: with friction the rigid ring's flank changes were checked against the "
                 "full ring over its flights, and the full ring has other flank changes there "
                 "(window %d): the full ring ran",
                 ck.windows + 1);
    else
        snprintf(out->why, sizeof out->why,
                 "auto: with friction the rigid ring's flank changes were checked against the "
                 "full ring over its flights: they move by up to %.3g deg, more than "
                 "numerics.accuracy_deg = %g, so the full ring ran",
                 ck.worst_deg, tol);
    return 0;
}

static int solve_run(lift_solve *s, int k, const rd_monitor *mon, rd_error *err)
{
    rd_lift_pass *r = &s->run[k];
    double scale = k == 1 ? 0.1 : 1.0;
    r->rtol = scale * s->p->rtol;
    r->atol = scale * s->p->atol;
    r->res = k ? NULL : s->out;
    r->modes = s->out->modes;
    if (k == 2 && r->modes > 6 * rd_ring_get_segments(s->half) - 6)
        r->modes = 6 * rd_ring_get_segments(s->half) - 6;
    rd_lift_setup su = {.state = keep_state, .ctx = s};
    const rd_lift_setup *setup = k == 2 ? s->setup_half : s->setup;
    s->states_next = 0;
    if (k == 0 && s->check && s->out->model == RD_LIFT_MODEL_RIGID)
        setup = &su;
    int rc = rd_lift_integrate(k == 2 ? s->half : s->ring, s->p, setup, s->out->model, mon, r, err);
    if (rc != RD_ENOCONV || s->out->model != RD_LIFT_MODEL_RIGID || s->p->cvode)
        return rc;
    /* the rigid ring's own integrator (rd_lift_small.c) gave up, its step
     * collapsed (seen on Coulomb scenes without gas at rtol 1e-7): the run
     * again with CVODE, whose BDF error control gets through */
    rd_lift_params q = *s->p;
    q.cvode = 1;
    free(r->events);
    r->events = NULL;
    r->n_events = r->cap_events = r->done = 0;
    rd_error_init(err);
    s->states_next = 0;
    return rd_lift_integrate(s->ring, &q, setup, s->out->model, mon, r, err);
}

/* The n/2 ring of the segment-count estimate of a flexible model, from the
 * scene's own start (a test's start y0 has none); made before the bore
 * start (bore_start) or, for the full ring that auto ran after its check,
 * after it (the scene is then axisymmetric: no bore start). */
static int half_ring(lift_solve *s, rd_error *err)
{
    int nh = s->out->segments / 2;
    if (!s->p->estimate_error || nh < HALF_SEGMENTS_MIN || s->half || (s->setup && s->setup->y0))
        return RD_OK;
    if (!(s->half = half_of(s->h, err)))
        return err && err->code ? err->code : RD_ENOMEM;
    s->run[2].samples = s->run[0].samples;
    s->run[2].lift = malloc((size_t)s->run[2].samples * sizeof(double));
    if (!s->run[2].lift)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples.",
                            s->run[2].samples);
    return RD_OK;
}

static int solve_level(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    lift_solve *s = ctx;
    if (level == 1 && s->out->partial)
        return RD_OK; /* no estimate for a partial result: its reference would stop too */
    if (level == 1) {
        rd_monitor_span sp;
        double split = s->half ? 0.8 : 1.0; /* n/2 at rtol costs ~1/4 of n at rtol/10 */
        int rc = solve_run(s, 1, rd_monitor_span_init(&sp, mon, 0.0, split), err);
        if (rc == RD_OK && s->half)
            rc = solve_run(s, 2, rd_monitor_span_init(&sp, mon, split, 1.0), err);
        return rc;
    }
    /* auto with friction: the rigid run (progress 0-5 %), its check (5-50 %),
     * and if refused the full ring (50-100 %) */
    rd_monitor_span sp;
    int rc = solve_run(s, 0, s->check ? rd_monitor_span_init(&sp, mon, 0.0, 0.05) : mon, err);
    int kept = s->check && rc == RD_OK
                   ? check_rigid(s, rd_monitor_span_init(&sp, mon, 0.05, 0.5), err)
                   : 1;
    if (kept < 0)
        return kept;
    if (s->check && (rc != RD_OK || !kept)) {
        if (rc == RD_ECANCELED || rc == RD_ETIMEOUT)
            return rc;
        if (rc != RD_OK)
            snprintf(s->out->why, sizeof s->out->why,
                     "auto: with friction the rigid ring runs first and is checked against the "
                     "full ring, but it failed (%.150s): the full ring ran",
                     err->message);
        rd_error_init(err);
        rd_lift_pass *r = &s->run[0];
        free(r->events);
        r->events = NULL;
        r->n_events = r->cap_events = r->done = 0;
        s->out->model = RD_LIFT_MODEL_FULL;
        s->out->dof = 6 * s->out->segments;
        s->out->event_error_model_deg = NAN;
        if ((rc = half_ring(s, err)))
            return rc;
        rc = solve_run(s, 0, rd_monitor_span_init(&sp, mon, 0.5, 1.0), err);
    }
    if ((rc == RD_ELIMIT || rc == RD_ECANCELED || rc == RD_ETIMEOUT) && s->run[0].done > 0 &&
        s->run[0].reached_deg > 0.0)
        rc = rd_lift_keep_partial(s->out, s->p, &s->run[0], rc, err);
    if (rc == RD_OK && !s->out->partial)
        s->main_done = 1;
    return rc;
}

/* Largest lift difference of two runs, m, and the largest angle change of
 * their matched flank changes, deg (NAN when they differ in number or kind:
 * the estimate cannot pair them). */
static void run_diff(const rd_lift_pass *a, const rd_lift_pass *b, double *lift, double *deg)
{
    double e = 0.0, de = a->n_events == b->n_events ? 0.0 : NAN;
    for (int k = 0; k < a->samples; k++)
        e = fmax(e, fabs(a->lift[k] - b->lift[k]));
    for (int j = 0; isfinite(de) && j < a->n_events; j++)
        de = b->events[j].kind != a->events[j].kind
                 ? NAN
                 : fmax(de, fabs(b->events[j].crank_deg - a->events[j].crank_deg));
    *lift = e;
    *deg = de;
}

/* The warning of flank changes not converged in the segment count. */
static void segment_warning(rd_lift_result *out, int n_events)
{
    int n = out->segments, nh = out->segments_half;
    if (isnan(out->event_error_segments_deg))
        snprintf(out->accuracy_warning, sizeof out->accuracy_warning,
                 "The flank changes are not converged in the segment count: the check run at "
                 "n/2 = %d segments has %d flank changes where n = %d has %d, so the angles "
                 "cannot be given an error; run at more segments (/discretization/segments) and "
                 "compare before trusting them.",
                 nh, out->segments_half_events, n, n_events);
    else if (out->event_error_segments_deg > RD_LIFT_SEGMENT_WARN_DEG)
        snprintf(out->accuracy_warning, sizeof out->accuracy_warning,
                 "The flank changes are not converged in the segment count: against the check "
                 "run at n/2 = %d segments they move by up to %.3g deg (estimated error %.3g "
                 "deg at n = %d); run at more segments (/discretization/segments) and compare "
                 "before trusting the angles.",
                 nh, out->event_error_segments_deg * (pow(2.0, SEGMENT_ORDER) - 1.0),
                 out->event_error_segments_deg, n);
}

/* error_estimate: the lift error over the clearance; event_error_deg: the
 * flank changes' (NAN when a reference run sees other flank changes).  The
 * time integration's share is the difference from the rtol/10 run.  The
 * segment count's share is the difference from the n/2 run divided by
 * 2^p - 1: the error against the limit n -> infinity if the answer
 * converges as n^-p; p = 1.5, the order observed on the friction battery
 * (docs/lift.md, Segment count).  The two shares add. */
static int compare_levels(void *ctx, rd_error *err)
{
    (void)err;
    lift_solve *s = ctx;
    rd_lift_result *out = s->out;
    double ca = s->p->groove.axial_clearance, lt, dt, ln = 0.0, dn = 0.0;
    if (out->partial)
        return RD_OK;
    run_diff(&s->run[0], &s->run[1], &lt, &dt);
    out->event_error_time_deg = dt;
    if (s->half) {
        run_diff(&s->run[0], &s->run[2], &ln, &dn);
        double f = 1.0 / (pow(2.0, SEGMENT_ORDER) - 1.0);
        ln *= f;
        dn *= f;
        out->event_error_segments_deg = dn;
        out->segments_half = rd_ring_get_segments(s->half);
        out->segments_half_events = s->run[2].n_events;
        segment_warning(out, s->run[0].n_events);
    }
    if (!s->half && out->segments_half > 0) /* a kept rigid run's, from its check (check_half) */
        dn = out->event_error_segments_deg;
    out->error_estimate = (lt + ln) / ca;
    out->event_error_deg =
        dt + dn + (isfinite(out->event_error_model_deg) ? out->event_error_model_deg : 0.0);
    return RD_OK;
}

/* The result's arrays for S samples of n segments. */
static int result_alloc(rd_lift_result *out, const rd_lift_params *p, int S, int n, rd_error *err)
{
    out->segments = n;
    out->dof = 6 * n;
    out->samples = S;
    out->crank_deg = malloc((size_t)S * sizeof(double));
    out->lift = malloc((size_t)S * sizeof(double));
    out->lift_min = malloc((size_t)S * sizeof(double));
    out->lift_max = malloc((size_t)S * sizeof(double));
    out->lift_segments = malloc((size_t)S * n * sizeof(double));
    out->twist = malloc((size_t)S * sizeof(double));
    out->friction_force = malloc((size_t)S * sizeof(double));
    out->bore_pressure = malloc((size_t)S * n * sizeof(double));
    out->bore_pressure_min = malloc((size_t)S * sizeof(double));
    out->bore_pressure_max = malloc((size_t)S * sizeof(double));
    out->ring_depth = p->bore_map ? malloc((size_t)S * sizeof(double)) : NULL;
    out->flank = malloc((size_t)S * sizeof(int));
    if (!out->crank_deg || !out->lift || !out->lift_min || !out->lift_max || !out->lift_segments ||
        !out->twist || !out->friction_force || !out->flank || !out->bore_pressure ||
        !out->bore_pressure_min || !out->bore_pressure_max || (p->bore_map && !out->ring_depth))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples x %d segments.",
                            S, n);
    return RD_OK;
}

/* The model's run-time check, the n/2 ring and the runs' buffers. */
static int prepare(lift_solve *s, int S, rd_error *err)
{
    const rd_lift_params *p = s->p;
    const rd_lift_setup *setup = s->setup;
    rd_lift_result *out = s->out;
    /* (a test's set-up with its own start or hooks runs the full ring) */
    s->check = p->model == RD_LIFT_MODEL_AUTO && out->model == RD_LIFT_MODEL_RIGID &&
               p->friction.model != RD_FRICTION_NONE;
    if (s->check && setup && (setup->y0 || setup->sample || setup->energy || setup->state)) {
        s->check = 0;
        out->model = RD_LIFT_MODEL_FULL;
        snprintf(out->why, sizeof out->why, "auto: a test's set-up (its own start or hooks)");
    }
    if (s->check && !(s->states = calloc(6 * (size_t)S, sizeof *s->states)))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the auto check.");
    if (out->model == RD_LIFT_MODEL_RIGID)
        out->dof = 3; /* axial lift, twist, radial */
    else if (out->model == RD_LIFT_MODEL_MODAL)
        out->dof = 6 + out->modes; /* rigid-body and elastic modes */
    for (int l = 0; l < 2; l++) {
        int need = l == 0 || p->estimate_error;
        s->run[l].samples = S;
        s->run[l].lift = need ? malloc((size_t)S * sizeof(double)) : NULL;
        if (need && !s->run[l].lift)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples.", S);
    }
    s->run[2].samples = S;
    /* the segment-count estimate: the flexible models, from the scene's own start */
    return out->model != RD_LIFT_MODEL_RIGID ? half_ring(s, err) : RD_OK;
}

/* A distorted bore's static start of `ring` into *y0 (12 n values), solved
 * at the first need and kept by the handle. */
static int bore_y0(lift_solve *s, const rd_ring *ring, double **y0, rd_error *err)
{
    if (*y0)
        return RD_OK;
    double *y = malloc(12 * (size_t)rd_ring_get_segments(ring) * sizeof *y);
    if (!y)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the bore start.");
    int rc = rd_lift_bore_static(ring, s->p, y, err);
    if (rc) {
        free(y);
        return rc;
    }
    *y0 = y;
    return RD_OK;
}

/* A distorted bore: every run starts from its ring's static equilibrium in it. */
static int bore_start(lift_solve *s, rd_error *err)
{
    int rc;
    s->su = s->setup ? *s->setup : (rd_lift_setup){0};
    s->suh = s->su;
    s->setup_half = s->setup;
    if (!rd_lift_bore_distorted(s->p, s->rp->diameter) || s->su.y0)
        return RD_OK;
    if ((rc = bore_y0(s, s->ring, &s->h->y0, err)) ||
        (s->half && (rc = bore_y0(s, s->half, &s->h->y0_half, err))))
        return rc;
    s->su.y0 = s->h->y0;
    s->suh.y0 = s->h->y0_half;
    s->setup = &s->su;
    s->setup_half = &s->suh;
    return RD_OK;
}

/* The lubricated model's film over the run (rd_lift_film.c), solved by the
 * handle's first run and given to every run through p.film; in a distorted
 * bore the films of the segments' static loads (p.films, or p.film where
 * they are all one). */
static int film_once(lift_solve *s, const rd_monitor *mon, rd_error *err)
{
    rd_lift *h = s->h;
    if (h->p.friction.model != RD_FRICTION_LUBRICATED || h->p.film || h->p.films)
        return RD_OK;
    int rc;
    if (rd_lift_films_needed(&h->p, h->rp.diameter)) {
        if ((rc = rd_lift_films_bore(h->ring, &h->p, mon, &h->films, err))) {
            rd_lift_films_free(&h->films);
            return rc;
        }
        if (h->films.count == 1)
            h->p.film = &h->films.tr[0];
        else
            h->p.films = &h->films;
        return RD_OK;
    }
    rc = rd_lift_film_run(&h->rp, &h->p, &h->film, &h->track, err);
    if (rc) {
        rd_film_track_free(&h->track);
        rd_film_free(&h->film);
        return rc;
    }
    h->p.film = &h->track;
    return RD_OK;
}

static void result_init(rd_lift_result *out)
{
    memset(out, 0, sizeof *out);
    out->error_estimate = NAN;
    out->event_error_deg = NAN;
    out->event_error_time_deg = NAN;
    out->event_error_segments_deg = NAN;
    out->event_error_model_deg = NAN;
}

/* The accuracy plan's runs (solve_level, compare_levels) and the result's
 * events and film. */
static int run_plan(lift_solve *s, const rd_monitor *mon, rd_error *err)
{
    rd_lift *h = s->h;
    const rd_lift_params *p = s->p;
    rd_lift_result *out = s->out;
    /* the reference run at rtol/10 typically costs 1.5-2x the main run, the n/2 one ~0.5x */
    rd_accuracy_plan plan = {.solve = solve_level,
                             .compare = compare_levels,
                             .ctx = s,
                             .estimate = p->estimate_error,
                             .main_share = s->half ? 0.3 : 0.4,
                             .reference = s->half ? "rtol/10 and atol/10, and at n/2 segments"
                                                  : "rtol/10 and atol/10"};
    int rc = rd_accuracy_run(&plan, mon, NULL, err);
    if ((rc == RD_ECANCELED || rc == RD_ETIMEOUT || rc == RD_ELIMIT) && s->main_done)
        rc = rd_lift_estimate_stopped(out, p, rc,
                                      fmax(s->run[1].reached_deg, s->run[2].reached_deg), err);
    if (out->model == RD_LIFT_MODEL_MODAL && s->run[0].dof > 0)
        out->dof = s->run[0].dof; /* with the correction shapes kept */
    out->n_events = s->run[0].n_events;
    out->events = s->run[0].events;
    s->run[0].events = NULL;
    if (rc == RD_OK && !out->partial)
        out->crank_deg_reached = 720.0 * p->engine.cycles;
    while (out->partial && out->n_events > 0 &&
           out->events[out->n_events - 1].crank_deg > out->crank_deg[out->samples - 1])
        out->n_events--; /* events after the last whole cycle */
    if (h->track.pt && (rc == RD_OK || out->partial)) {
        int frc = rd_lift_film_result(&h->rp, p, &h->film, &h->track, out, err);
        if (frc == RD_OK && p->estimate_error)
            frc = rd_lift_film_estimate(&h->rp, p, out, err);
        rc = rc == RD_OK ? frc : rc;
    } else if (h->films.count > 0 && (rc == RD_OK || out->partial)) {
        int frc = rd_lift_films_result(&h->rp, p, &h->films, out, err);
        if (frc == RD_OK && p->estimate_error)
            frc = rd_lift_films_estimate(&h->rp, p, &h->films, mon, out, err);
        rc = rc == RD_OK ? frc : rc;
    }
    return rc;
}

/* One run of the handle's scene with a test's set-up (NULL: the scene's). */
static int run_setup(rd_lift *h, const rd_lift_setup *setup, const rd_monitor *mon,
                     rd_lift_result *out, rd_error *err)
{
    lift_solve s = {.h = h, .ring = h->ring, .rp = &h->rp, .setup = setup, .out = out};
    result_init(out);
    s.p = &h->p;
    int rc, S = rd_lift_samples(s.p);
    if ((rc = result_alloc(out, s.p, S, h->segments, err)))
        goto out;
    choose_model(s.p, h->segments, h->rp.diameter, out);
    if ((rc = prepare(&s, S, err)) || (rc = bore_start(&s, err)) || (rc = film_once(&s, mon, err)))
        goto out;
    rc = run_plan(&s, mon, err);
out:
    for (int l = 0; l < 3; l++) {
        free(s.run[l].lift);
        free(s.run[l].events);
    }
    free(s.states);
    return rc;
}

int rd_lift_create(const rd_ring_params *ring, int segments, const rd_lift_params *p, rd_lift **out,
                   rd_error *err)
{
    *out = NULL;
    int rc = rd_lift_validate(p, ring, segments, err);
    if (rc)
        return rc;
    rd_lift *h = calloc(1, sizeof *h);
    if (!h)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift analysis.");
    h->rp = *ring;
    h->p = *p;
    h->segments = segments;
    if (!(h->ring = rd_ring_create(&h->rp, segments, 0, err))) {
        rd_lift_free(h);
        return err && err->code ? err->code : RD_ENOMEM;
    }
    *out = h;
    return RD_OK;
}

int rd_lift_run(rd_lift *h, const rd_monitor *mon, rd_lift_result *out, rd_error *err)
{
    return run_setup(h, NULL, mon, out, err);
}

void rd_lift_free(rd_lift *h)
{
    if (!h)
        return;
    rd_ring_free(h->ring);
    rd_ring_free(h->half);
    rd_film_track_free(&h->track);
    rd_film_free(&h->film);
    rd_lift_films_free(&h->films);
    free(h->y0);
    free(h->y0_half);
    free(h);
}

int rd_lift_solve_setup(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                        const rd_lift_setup *setup, const rd_monitor *mon, rd_lift_result *out,
                        rd_error *err)
{
    rd_lift *h = NULL;
    result_init(out);
    int rc = rd_lift_create(rp, segments, p, &h, err);
    if (rc == RD_OK)
        rc = run_setup(h, setup, mon, out, err);
    rd_lift_free(h);
    return rc;
}

int rd_lift_solve(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                  const rd_monitor *mon, rd_lift_result *out, rd_error *err)
{
    return rd_lift_solve_setup(ring, segments, p, NULL, mon, out, err);
}
