/*
 * fired_cycle.h — a crude fired cycle for film tests and benches (the
 * thesis crank train, 9:1 polytropic compression and expansion with k 1.35
 * from 1 bar, a 30 bar Gaussian pulse near 370 deg), absolute Pa: 1 bar
 * outside compression and expansion (180..540 deg).  Not a model: a load
 * with the shape of one.
 */
#ifndef FIRED_CYCLE_H
#define FIRED_CYCLE_H

#include <math.h>

#include "rd_lift.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static inline double fired_cycle_pa(double deg)
{
    double a = (deg - 360.0) * M_PI / 180.0, r = 0.04345, l = 0.13, d = 0.0765;
    double s = r * (1.0 - cos(a)) + l - sqrt(l * l - pow(r * sin(a), 2.0));
    double area = 0.25 * M_PI * d * d, vc = area * 2.0 * r / 8.0;
    double p = 1e5 * pow((vc + area * 2.0 * r) / (vc + area * s), 1.35) +
               3.0e6 * exp(-pow((deg - 370.0) / 25.0, 2.0));
    return deg > 180.0 && deg < 540.0 ? p : 1e5;
}

/* The lift's gas tables from it, every 10 deg (0..720): above and behind
 * the cycle less `base` (Pa, not below 0), below a fifth of that, fixed
 * active areas; the arrays are t's. */
#define FIRED_CYCLE_POINTS 73
typedef struct fired_tables {
    double crank[FIRED_CYCLE_POINTS], above[FIRED_CYCLE_POINTS], behind[FIRED_CYCLE_POINTS],
        below[FIRED_CYCLE_POINTS];
} fired_tables;

static inline rd_gas_params fired_cycle_gas(fired_tables *t, double base)
{
    for (int k = 0; k < FIRED_CYCLE_POINTS; k++) {
        t->crank[k] = 10.0 * k;
        t->above[k] = t->behind[k] = fmax(fired_cycle_pa(t->crank[k]) - base, 0.0);
        t->below[k] = 0.2 * t->above[k];
    }
    return (rd_gas_params){FIRED_CYCLE_POINTS, t->crank, t->above,
                           t->behind,          t->below, RD_GAS_AREA_FIXED};
}

#endif
