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

#endif
