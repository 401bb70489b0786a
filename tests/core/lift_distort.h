/*
 * lift_distort.h — the distorted bore of the lift tests (test_lift_bore,
 * test_lift_films): orders 2 at amplitude A (phase 0) and 4 at 0.4 A (30 deg
 * from the gap middle).
 */
#ifndef LIFT_DISTORT_H
#define LIFT_DISTORT_H

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

#endif
