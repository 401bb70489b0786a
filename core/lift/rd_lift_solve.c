/*
 * rd_lift_solve.c — the lift analysis' public solve (rd_lift.h): the model a
 * scene gets, the accuracy plan (rd_accuracy.h: the scene at rtol and again
 * at rtol/10 for the error estimate), the static start in a distorted bore,
 * the result's arrays.  The top of the lift folder: it calls the driver,
 * the static start and the partial-result keeping, nothing calls it back.
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
                 rd_bore_distorted(&p->bore, ring_d) && out->modes < 6 * n - 6
                     ? "; with a distorted bore its truncated basis cannot hold the stiff bore "
                       "contact's equilibrium: flank changes measured up to 100 deg off the "
                       "full model's, use full"
                     : "");
    } else if (rd_bore_distorted(&p->bore, ring_d)) {
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
    } else
        snprintf(out->why, sizeof out->why,
                 "auto: with friction the split ring's free ends lift differently from its "
                 "middle in flight, which delays its landings by up to several degrees against "
                 "the rigid ring's, and the modal model needs more modes than make it cheaper "
                 "than the full ring (numerics.model = modal by request)");
}

/* The two solves of the accuracy driver and what they keep. */
typedef struct lift_solve {
    const rd_ring *ring;
    const rd_lift_params *p;
    const rd_lift_setup *setup;
    rd_lift_result *out;
    rd_lift_run run[2]; /* level 0: the scene; level 1: rtol/10, atol/10 */
    int main_done;      /* level 0 ran every cycle */
} lift_solve;

static int solve_level(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    lift_solve *s = ctx;
    rd_lift_run *r = &s->run[level];
    double scale = level ? 0.1 : 1.0;
    if (level == 1 && s->out->partial)
        return RD_OK; /* no estimate for a partial result: its reference would stop too */
    r->rtol = scale * s->p->rtol;
    r->atol = scale * s->p->atol;
    r->res = level ? NULL : s->out;
    r->modes = s->out->modes;
    int rc = rd_lift_integrate(s->ring, s->p, s->setup, s->out->model, mon, r, err);
    if (level == 0 && (rc == RD_ELIMIT || rc == RD_ECANCELED || rc == RD_ETIMEOUT) && r->done > 0 &&
        r->reached_deg > 0.0)
        rc = rd_lift_keep_partial(s->out, s->p, &s->run[0], rc, err);
    if (level == 0 && rc == RD_OK && !s->out->partial)
        s->main_done = 1;
    return rc;
}

/* error_estimate: largest lift difference / clearance; event error: the
 * largest angle change of matched events, NAN when the two runs see a
 * different number or kind of flank changes (the estimate cannot pair them). */
static int compare_levels(void *ctx, rd_error *err)
{
    (void)err;
    lift_solve *s = ctx;
    const rd_lift_run *a = &s->run[0], *b = &s->run[1];
    double e = 0.0;
    if (s->out->partial)
        return RD_OK;
    for (int k = 0; k < a->samples; k++)
        e = fmax(e, fabs(a->lift[k] - b->lift[k]));
    s->out->error_estimate = e / s->p->groove.axial_clearance;
    if (b->n_events == a->n_events) {
        double de = 0.0;
        for (int j = 0; j < a->n_events; j++) {
            if (b->events[j].kind != a->events[j].kind) {
                de = NAN;
                break;
            }
            de = fmax(de, fabs(b->events[j].crank_deg - a->events[j].crank_deg));
        }
        s->out->event_error_deg = de;
    }
    return RD_OK;
}

/* The result's arrays for S samples of n segments. */
static int result_alloc(rd_lift_result *out, int S, int n, rd_error *err)
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
    out->flank = malloc((size_t)S * sizeof(int));
    if (!out->crank_deg || !out->lift || !out->lift_min || !out->lift_max || !out->lift_segments ||
        !out->twist || !out->friction_force || !out->flank)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples x %d segments.",
                            S, n);
    return RD_OK;
}

int rd_lift_solve_setup(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                        const rd_lift_setup *setup, const rd_monitor *mon, rd_lift_result *out,
                        rd_error *err)
{
    lift_solve s = {.p = p, .setup = setup, .out = out};
    double *y0 = NULL;
    int rc;
    memset(out, 0, sizeof *out);
    out->error_estimate = NAN;
    out->event_error_deg = NAN;
    if ((rc = rd_lift_validate(p, rp, segments, err)))
        return rc;
    rd_ring *ring = rd_ring_create(rp, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    s.ring = ring;
    int S = rd_lift_samples(p);
    if ((rc = result_alloc(out, S, segments, err)))
        goto out;
    choose_model(p, segments, rp->diameter, out);
    if (out->model == RD_LIFT_MODEL_RIGID)
        out->dof = 3; /* axial lift, twist, radial */
    else if (out->model == RD_LIFT_MODEL_MODAL)
        out->dof = 6 + out->modes; /* rigid-body and elastic modes */
    for (int l = 0; l < 2; l++) {
        s.run[l].samples = S;
        s.run[l].lift = l == 0 || p->estimate_error ? malloc((size_t)S * sizeof(double)) : NULL;
        if ((l == 0 || p->estimate_error) && !s.run[l].lift) {
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples.", S);
            goto out;
        }
    }
    /* a distorted bore: both runs start from the ring's static equilibrium in it */
    rd_lift_setup su = setup ? *setup : (rd_lift_setup){0};
    if (rd_bore_distorted(&p->bore, rp->diameter) && !su.y0) {
        y0 = malloc(12 * (size_t)segments * sizeof *y0);
        if (!y0) {
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the bore start.");
            goto out;
        }
        if ((rc = rd_lift_bore_static(ring, p, y0, err)))
            goto out;
        su.y0 = y0;
        s.setup = &su;
    }
    /* the reference run at rtol/10 typically costs 1.5-2x the main run */
    rd_accuracy_plan plan = {.solve = solve_level,
                             .compare = compare_levels,
                             .ctx = &s,
                             .estimate = p->estimate_error,
                             .main_share = 0.4,
                             .reference = "rtol/10 and atol/10"};
    rc = rd_accuracy_run(&plan, mon, NULL, err);
    if ((rc == RD_ECANCELED || rc == RD_ETIMEOUT) && s.main_done)
        rd_lift_estimate_stopped(out, p);
    if (out->model == RD_LIFT_MODEL_MODAL && s.run[0].dof > 0)
        out->dof = s.run[0].dof; /* with the correction shapes kept */
    out->n_events = s.run[0].n_events;
    out->events = s.run[0].events;
    s.run[0].events = NULL;
    if (rc == RD_OK && !out->partial)
        out->crank_deg_reached = 720.0 * p->engine.cycles;
    while (out->partial && out->n_events > 0 &&
           out->events[out->n_events - 1].crank_deg > out->crank_deg[out->samples - 1])
        out->n_events--; /* events after the last whole cycle */
out:
    for (int l = 0; l < 2; l++) {
        free(s.run[l].lift);
        free(s.run[l].events);
    }
    rd_ring_free(ring);
    free(y0);
    return rc;
}

int rd_lift_solve(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                  const rd_monitor *mon, rd_lift_result *out, rd_error *err)
{
    return rd_lift_solve_setup(ring, segments, p, NULL, mon, out, err);
}
