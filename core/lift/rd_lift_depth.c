/*
 * rd_lift_depth.c — where the ring is in a bore map at time t, and a table
 * over the map's depths read there (rd_lift_internal.h): the films' loads
 * along the stroke (rd_lift_film.c, rd_lift_segfilm.c).  Its own file:
 * both of those read it and neither may read the other.
 *
 * The depth is ring_z_tdc + s(omega t), s the piston's travel below TDC
 * (rd_engine_piston), as the bore's offsets take it (rd_lift_bore.c); a
 * table is linear between the two depths around z, clamped at its ends,
 * a + w (b - a), so that equal values give that value bit for bit.
 */
#include <math.h>

#include "rd_lift_internal.h"

double rd_lift_depth_at(const rd_lift_params *p, double t)
{
    double s = 0.0, v, a;
    rd_engine_piston(&p->engine, rd_engine_omega(&p->engine) * t, &s, &v, &a);
    return p->ring_z_tdc + s;
}

double rd_lift_depth_interp(const double *zs, const double *v, int nz, double z)
{
    if (nz <= 1)
        return v[0];
    int i = 0;
    while (i + 2 < nz && z > zs[i + 1])
        i++;
    double w = fmin(fmax((z - zs[i]) / (zs[i + 1] - zs[i]), 0.0), 1.0);
    return v[i] + w * (v[i + 1] - v[i]);
}
