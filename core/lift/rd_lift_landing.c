/*
 * rd_lift_landing.c — the landing law of the lift model: the oil squeeze
 * film between a ring face and the groove flank it approaches (issue 10
 * item 4; scene: /physics/squeeze_film, off by default; file map:
 * rd_lift_model.h).
 *
 * Reynolds' equation for two parallel plates of width b (the ring's radial
 * width, across which the oil escapes) and length L >> b, approaching at
 * V = -dh/dt, with ambient pressure at both edges, gives the parabolic
 * pressure p(x) = 6 mu V (b^2/4 - x^2) / h^3 and the load
 *     W = mu b^3 L V / h^3,  i.e. a mean pressure  p = mu b^2 V / h^3
 * (the infinitely long parallel-surface squeeze film: B. J. Hamrock,
 * S. R. Schmid, B. O. Jacobson, Fundamentals of Fluid Film Lubrication,
 * 2nd ed., Marcel Dekker 2004, ch. "Squeeze film bearings", parallel
 * surfaces of infinite length).  Applied here at each flank point with the
 * local gap h and closing speed V (a local parallel-plate approximation: the
 * twist's gap variation across b is ignored), on the point's tributary area
 * like the penalty's pressure:
 *     p = mu b^2 r(V) / h_e^3,   h_e = h_min + max(h, 0),
 * h_min the film left at contact (surface roughness: the film does not
 * thin to zero; below it the dry penalty carries the load).  The film
 * cavitates rather than pull (half-Sommerfeld: no pressure while the gap
 * opens), with the ramp r(V) = 0 (V <= 0), V^2 (2 v_r - V) / v_r^2
 * (0 < V < v_r), V (V >= v_r) keeping p C1 in V and exact above v_r;
 * v_r = 1e-2 c_a omega, a hundredth of the speed of a flight across the
 * clearance in one radian (landings come at ~c_a omega).
 *
 * Closed form (tests/core/test_lift.c): a face pressed by a constant force
 * F with negligible inertia approaches as dh_e/dt = -F h_e^3 / (mu b^2 A),
 * so 1 / h_e^2 = 1 / h_e0^2 + 2 F t / (mu b^2 A).
 */
#include "rd_lift_model.h"

#define V_REG_FRACTION 1e-2 /* v_r / (c_a omega) */

void rd_lift_landing_init(rd_lift_model *m, const rd_section *s, const rd_lift_params *p)
{
    m->sq_on = p->squeeze.on;
    /* b: the flank's width (the lower's; the upper is alike) */
    m->sq_coef = p->squeeze.viscosity * s->lower.width * s->lower.width;
    m->sq_hmin = p->squeeze.min_film;
    m->sq_vreg = V_REG_FRACTION * m->ca * m->omega;
    if (!(m->sq_vreg > 0.0))
        m->sq_vreg = V_REG_FRACTION * m->ca; /* a piston at rest: 1e-2 c_a per second */
}

double rd_lift_squeeze(const rd_lift_model *m, double gap, double closing, double *p_gap,
                       double *p_closing)
{
    *p_gap = *p_closing = 0.0;
    if (closing <= 0.0)
        return 0.0;
    double r = closing, r_v = 1.0;
    if (closing < m->sq_vreg) { /* the C1 ramp V^2 (2 v_r - V) / v_r^2 */
        double x = closing / m->sq_vreg;
        r = closing * x * (2.0 - x);
        r_v = x * (4.0 - 3.0 * x);
    }
    double he = m->sq_hmin + (gap > 0.0 ? gap : 0.0);
    double c = m->sq_coef / (he * he * he), p = c * r;
    if (gap > 0.0)
        *p_gap = -3.0 * p / he;
    *p_closing = c * r_v;
    return p;
}
