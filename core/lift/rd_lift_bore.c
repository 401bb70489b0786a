/*
 * rd_lift_bore.c — the bore of a lift scene (bore.diameter, bore.distortion,
 * as in the contact analysis): r_b(theta) = D/2 + sum_k A_k cos(k (theta -
 * phi_k)), theta from the gap middle (rd_lift.h).
 *
 * The bore contact of the full model (rd_lift_forces.c) is measured from
 * the round bore of the ring's diameter d: a bore point at angle psi has
 * penetration delta_pre + u_r - g(psi), g(psi) = r_b(psi) - d/2 the bore's
 * outward offset there (precomputed per point, rd_lift_bore_init).  So the
 * radial contact pressure, and with it the friction, varies around the ring.
 * The ring starts from its static equilibrium in such a bore
 * (rd_lift_start.c).
 *
 * Validation: rd_bore_validate (rd_liner.h), the contact analysis' rules.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

int rd_lift_bore_init(rd_lift_model *c, rd_error *err)
{
    const rd_bore *b = &c->p->bore;
    double d = rd_ring_get_params(c->ring)->diameter;
    c->bo_gap = NULL;
    if (!rd_bore_distorted(b, d))
        return RD_OK;
    size_t np = (size_t)c->n * RD_LIFT_ARC_POINTS;
    c->bo_gap = malloc(np * sizeof *c->bo_gap);
    if (!c->bo_gap)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift bore.");
    double g0 = b->diameter > 0.0 ? 0.5 * (b->diameter - d) : 0.0;
    for (size_t j = 0; j < np; j++) {
        double psi = atan2(c->bo_e[2 * j + 1], c->bo_e[2 * j]), g = g0;
        for (int k = 0; k < b->n_distortion; k++)
            g += b->distortion[k].amplitude *
                 cos(b->distortion[k].order * (psi - b->distortion[k].phase_deg * M_PI / 180.0));
        c->bo_gap[j] = g;
    }
    return RD_OK;
}
