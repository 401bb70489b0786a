/*
 * rd_lift_scales.c — the scene's scales that the lift models and the
 * validation size things by: the largest flank pressure, the default
 * contact stiffness, the acceleration scale (declared in rd_lift_model.h
 * and rd_lift.h).
 *
 * Default stiffness k (Pa/m, contact_stiffness = 0), the larger of
 *   k_load = P_max / (1e-3 c_a): the largest pressure the scene can put on a
 *     flank (inertia rho h r w^2 (1 + lambda), gravity, friction, gas)
 *     pushes it in by at most 1e-3 of the clearance;
 *   k_dyn = rho h (3e4 w)^2: the flank contact frequency w_c = sqrt(k / (rho h))
 *     is 3e4 times the crank's, so the damped contact follows the load with
 *     a lag 2 zeta / w_c = 3.3e-4 rad = 0.02 deg of crank.
 */
#include <math.h>

#include "rd_lift_model.h"

#define LOAD_PENETRATION   1e-3 /* largest load penetration / c_a for the default k */
#define CONTACT_FREQ_RATIO 3e4  /* flank contact frequency / crank frequency */
#define GRAVITY            RD_LIFT_GRAVITY

static double table_max_abs(const rd_gas_params *g, const double *v)
{
    double m = 0.0;
    for (int i = 0; i < g->points; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

double rd_lift_flank_pressure_scale(const rd_ring_params *ring, const rd_lift_params *p)
{
    const rd_engine_params *e = &p->engine;
    rd_section s;
    rd_section_init(&s, ring);
    double w = rd_engine_omega(e), lam = e->crank_radius / e->rod_length;
    double rho_h = ring->density * s.h; /* mass per unit flank area */
    double P = rho_h * e->crank_radius * w * w * (1.0 + lam);
    if (p->gravity)
        P = fmax(P, rho_h * GRAVITY);
    if (p->friction.model != RD_FRICTION_NONE) {
        /* mu p0 h / b: the friction force per unit flank area */
        double p0 = 2.0 * ring->tangential_force / (ring->diameter * s.run.height);
        double pf = p->friction.coefficient * p0 * s.run.height / s.lower.width;
        if (p->friction.model == RD_FRICTION_STRIBECK) {
            /* + the hydrodynamic K eta u h per unit length at the peak speed */
            double umax = e->crank_radius * w * (1.0 + lam);
            pf += p->friction.hydrodynamic_slope * p->friction.viscosity * umax * s.run.height /
                  (M_PI * ring->diameter * s.lower.width);
        }
        P = fmax(P, pf);
    }
    if (p->gas.points > 0) {
        P = fmax(P, table_max_abs(&p->gas, p->gas.above));
        P = fmax(P, table_max_abs(&p->gas, p->gas.behind));
        P = fmax(P, table_max_abs(&p->gas, p->gas.below));
    }
    return P;
}

double rd_lift_contact_stiffness_default(const rd_ring_params *ring, const rd_lift_params *p)
{
    double w = rd_engine_omega(&p->engine);
    double k_load =
        rd_lift_flank_pressure_scale(ring, p) / (LOAD_PENETRATION * p->groove.axial_clearance);
    double wc = CONTACT_FREQ_RATIO * w;
    rd_section s;
    rd_section_init(&s, ring);
    double k_dyn = ring->density * s.h * wc * wc;
    return fmax(k_load, k_dyn);
}

double rd_lift_accel_scale(const rd_ring_params *rp, const rd_lift_params *p)
{
    const rd_engine_params *e = &p->engine;
    double w = rd_engine_omega(e);
    double a = e->crank_radius * w * w * (1.0 + e->crank_radius / e->rod_length);
    rd_section s;
    rd_section_init(&s, rp);
    return fmax(a, rd_lift_flank_pressure_scale(rp, p) / (rp->density * s.h));
}
