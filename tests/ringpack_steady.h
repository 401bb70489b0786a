/* ringpack_steady.h — the ring pack's gas laws written again and a steady
 * network solved with them, for tests (a second method beside core's
 * rd_gasflow.c and the pack's time integration to its steady state):
 *   nozzle: the orifice (Heywood App. C) with the band of 1e-4 below equal
 *     pressures continued linearly (rd_gasflow.h);
 *   slot: the laminar isothermal slot; limited: the 4-norm blend;
 *   steady: one ring held at half its clearance (both flank passages open)
 *     under a constant cylinder pressure pc: top entry -> land; land ->
 *     groove (upper flank) -> crankcase (lower flank); land -> crankcase
 *     (end gap), solved by nested bisection to round-off.
 * Static functions: include it in one test file. */
#ifndef RINGPACK_STEADY_H
#define RINGPACK_STEADY_H

#include <math.h>

#include "rd_gasflow.h"
#include "rd_ringpack.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Orifice, Heywood App. C, for gas (k, R): from pu to pd (pd <= pu), the
 * band of 1e-4 below equal pressures continued linearly (rd_gasflow.h). */
static double nozzle(double k, double R, double cd, double A, double pu, double T, double pd)
{
    double r = pd / pu, rc = pow(2.0 / (k + 1.0), k / (k - 1.0));
    if (r > 1.0 - 1e-4)
        return nozzle(k, R, cd, A, pu, T, pu * (1.0 - 1e-4)) * (1.0 - r) / 1e-4;
    double base = cd * A * pu / sqrt(R * T);
    if (r < rc)
        return base * sqrt(k) * pow(2.0 / (k + 1.0), (k + 1.0) / (2.0 * (k - 1.0)));
    return base * pow(r, 1.0 / k) * sqrt(2.0 * k / (k - 1.0) * (1.0 - pow(r, (k - 1.0) / k)));
}

/* Laminar isothermal slot of width w, height h, length L. */
static double slot(double w, double h, double L, double mu, double R, double T, double pa,
                   double pb)
{
    return w * h * h * h * (pa * pa - pb * pb) / (24.0 * mu * R * T * L);
}

/* The blend: the 4-norm of the resistances, (a^-4 + b^-4)^(-1/4). */
static double limited(double a, double b)
{
    return a > 0.0 && b > 0.0 ? 1.0 / pow(pow(a, -4.0) + pow(b, -4.0), 0.25) : 0.0;
}

/* The flank passage's flow from pa to pb (pa >= pb) in the test's laws. */
static double flank(const rd_ringpack_params *p, double pa, double pb, double T, int visc)
{
    const rd_ringpack_ring *r = &p->rings[0];
    double b = r->ring.radial_width, w = M_PI * (r->ring.diameter - b);
    double h = 0.5 * r->groove.axial_clearance, A = M_PI * r->ring.diameter * h;
    double mu = p->gas_viscosity > 0.0 ? p->gas_viscosity : rd_gas_viscosity(T);
    double o = nozzle(p->kappa, p->gas_constant, r->discharge_coefficient, A, pa, p->T_lands, pb);
    if (!visc)
        return o;
    /* the slot's h from the orifice's area pi d h over its width w */
    return limited(o, slot(w, A / w, b, mu, p->gas_constant, T, pa, pb));
}

/* The groove pressure balancing the two flank passages, land pressure pl. */
static double groove_of(const rd_ringpack_params *p, double pl, int visc)
{
    double lo = p->crankcase_pa, hi = pl, Tl = p->T_lands, Tm = 0.5 * (Tl + p->T_crankcase);
    for (int it = 0; it < 200; it++) {
        double g = 0.5 * (lo + hi);
        if (flank(p, pl, g, Tl, visc) > flank(p, g, p->crankcase_pa, Tm, visc))
            lo = g;
        else
            hi = g;
    }
    return 0.5 * (lo + hi);
}

/* Land and groove pressures and the flow: the land balances the entry
 * against the end gap and the upper flank. */
static double steady(const rd_ringpack_params *p, double pc, double *pl, double *pg, int visc)
{
    const rd_ringpack_ring *r = &p->rings[0];
    double k = p->kappa, R = p->gas_constant, T = p->T_lands, cd = r->discharge_coefficient;
    double A_in = M_PI * r->ring.diameter * r->land_clearance,
           A_gap = r->ring.closed_gap * r->land_clearance;
    double lo = p->crankcase_pa, hi = pc;
    for (int it = 0; it < 200; it++) {
        double l = 0.5 * (lo + hi), g = groove_of(p, l, visc);
        double in = nozzle(k, R, cd, A_in, pc, T, l);
        double out = nozzle(k, R, cd, A_gap, l, T, p->crankcase_pa) + flank(p, l, g, T, visc);
        if (in > out)
            lo = l;
        else
            hi = l;
    }
    *pl = 0.5 * (lo + hi);
    *pg = groove_of(p, *pl, visc);
    return nozzle(k, R, cd, A_in, pc, T, *pl);
}

#endif
