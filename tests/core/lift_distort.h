/*
 * lift_distort.h — the distorted bore of the lift tests (test_lift_bore,
 * test_lift_films*): orders 2 at amplitude A (phase 0) and 4 at 0.4 A (30 deg
 * from the gap middle); a two-layer map of it; the lubricated full ring's
 * scene of the film tests.
 */
#ifndef LIFT_DISTORT_H
#define LIFT_DISTORT_H

#include <math.h>
#include <string.h>

#include "rd_lift.h"

static inline void distort(rd_lift_params *p, double A)
{
    p->bore.n_distortion = 2;
    p->bore.distortion[0].order = 2;
    p->bore.distortion[0].amplitude = A;
    p->bore.distortion[0].phase_deg = 0.0;
    p->bore.distortion[1].order = 4;
    p->bore.distortion[1].amplitude = 0.4 * A;
    p->bore.distortion[1].phase_deg = 30.0;
}

/* Two layers: distort() at A_top at z = 0 and A_bot at z = 0.1 m (0: a
 * round layer). */
static inline void distort_map(rd_bore_map *m, double A_top, double A_bot)
{
    memset(m, 0, sizeof *m);
    m->n_layers = 2;
    m->residual_rms = NAN;
    double A[2] = {A_top, A_bot};
    for (int i = 0; i < 2; i++) {
        rd_lift_params q;
        rd_lift_params_default(&q);
        if (A[i] > 0.0)
            distort(&q, A[i]);
        m->layer[i].z = 0.1 * i;
        m->layer[i].bore = q.bore;
    }
}

/* The film tests' scene: the thesis ring, 2400 rpm, one cycle, lubricated
 * friction, the full ring, no error estimate; distort() at A (0: round). */
static inline void lubricated_scene(rd_ring_params *rp, rd_lift_params *p, double A)
{
    rd_ring_params_default(rp);
    rd_lift_params_default(p);
    p->engine.speed_rpm = 2400.0;
    p->engine.cycles = 1.0;
    p->friction.model = RD_FRICTION_LUBRICATED;
    p->model = RD_LIFT_MODEL_FULL;
    p->estimate_error = 0;
    if (A > 0.0)
        distort(p, A);
}

#endif
