/*
 * rd_engine_tilt.c — the piston's tilt about its pin axis vs crank angle
 * (engine.piston_tilt_deg and the engine.piston_tilt table; the forces it
 * causes: core/lift/rd_lift_forces.c, add_inertia_gravity and add_bore).
 *
 * beta(alpha) = piston_tilt_deg + table(alpha), deg, with the table a
 * periodic (720 deg) cubic Hermite spline through its points, the tangent at
 * point k the central difference (y_{k+1} - y_{k-1}) / (x_{k+1} - x_{k-1})
 * (wrapping around 720 deg): C1, so the tilt rate is continuous and the
 * angular acceleration (the frame's Euler force) is bounded, piecewise
 * linear.  A table of one point is a constant.  Returns the tilt, its first
 * and second derivatives with respect to the crank angle, in deg, deg/deg
 * and deg/deg^2.
 */
#include <math.h>

#include "rd_engine.h"

/* x_k and y_k of the periodic extension (k any integer). */
static double px(const rd_engine_params *e, int k)
{
    int n = e->tilt_points, q = (int)floor((double)k / n);
    return e->tilt_crank_deg[k - q * n] + 720.0 * q;
}

static double py(const rd_engine_params *e, int k)
{
    int n = e->tilt_points, q = (int)floor((double)k / n);
    return e->tilt_deg[k - q * n];
}

static double tangent(const rd_engine_params *e, int k)
{
    return (py(e, k + 1) - py(e, k - 1)) / (px(e, k + 1) - px(e, k - 1));
}

void rd_engine_tilt_at(const rd_engine_params *e, double deg, double *beta, double *d1, double *d2)
{
    *beta = e->piston_tilt_deg;
    *d1 = *d2 = 0.0;
    int n = e->tilt_points;
    if (n < 1)
        return;
    if (n == 1) {
        *beta += e->tilt_deg[0];
        return;
    }
    double x0 = e->tilt_crank_deg[0];
    double d = x0 + fmod(fmod(deg - x0, 720.0) + 720.0, 720.0); /* in [x0, x0 + 720) */
    int a = n - 1;
    for (int k = 0; k < n; k++)
        if (px(e, k + 1) > d) {
            a = k;
            break;
        }
    double xa = px(e, a), h = px(e, a + 1) - xa, s = (d - xa) / h;
    double ya = py(e, a), yb = py(e, a + 1), ma = h * tangent(e, a), mb = h * tangent(e, a + 1);
    double s2 = s * s, s3 = s2 * s;
    *beta += (2 * s3 - 3 * s2 + 1) * ya + (s3 - 2 * s2 + s) * ma + (-2 * s3 + 3 * s2) * yb +
             (s3 - s2) * mb;
    *d1 = ((6 * s2 - 6 * s) * ya + (3 * s2 - 4 * s + 1) * ma + (-6 * s2 + 6 * s) * yb +
           (3 * s2 - 2 * s) * mb) /
          h;
    *d2 = ((12 * s - 6) * ya + (6 * s - 4) * ma + (-12 * s + 6) * yb + (6 * s - 2) * mb) / (h * h);
}

int rd_engine_tilted(const rd_engine_params *e)
{
    return e->piston_tilt_deg != 0.0 || e->tilt_points > 0;
}
