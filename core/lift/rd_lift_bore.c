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
 * Validation (rd_lift_bore_validate): the ranges of the bore block, with the
 * contact analysis' convex-bore rule (rd_bore_convex_validate, rd_liner.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

int rd_lift_bore_distorted(const rd_lift_bore *b, double ring_diameter)
{
    return (b->diameter > 0.0 && b->diameter != ring_diameter) || b->n_distortion > 0;
}

int rd_lift_bore_validate(const rd_lift_bore *b, const rd_ring_params *ring, rd_error *err)
{
    double d = ring->diameter, sum = 0.0, bend = 0.0;
    if (!isfinite(b->diameter) ||
        (b->diameter != 0.0 && (b->diameter < 0.98 * d || b->diameter > 1.02 * d)))
        return rd_error_set(err, RD_EINVAL, "/bore/diameter",
                            "/bore/diameter = %g m is out of range: 0 (the ring's diameter) or "
                            "%g to %g m (within 2 %% of it).",
                            b->diameter, 0.98 * d, 1.02 * d);
    if (b->n_distortion < 0 || b->n_distortion > RD_LIFT_DISTORTION_MAX)
        return rd_error_set(err, RD_ELIMIT, "/bore/distortion",
                            "/bore/distortion has %d terms; at most %d are allowed.",
                            b->n_distortion, RD_LIFT_DISTORTION_MAX);
    for (int k = 0; k < b->n_distortion; k++) {
        char path[64];
        int rc;
        snprintf(path, sizeof path, "/bore/distortion/%d/order", k);
        if (b->distortion[k].order < 1 || b->distortion[k].order > 64)
            return rd_error_set(err, RD_EINVAL, path, "%s = %d is out of range: allowed 1 to 64.",
                                path, b->distortion[k].order);
        snprintf(path, sizeof path, "/bore/distortion/%d/phase_deg", k);
        if ((rc = rd_error_range(b->distortion[k].phase_deg, -360.0, 360.0, path, "deg", err)))
            return rc;
        snprintf(path, sizeof path, "/bore/distortion/%d/amplitude", k);
        if ((rc = rd_error_range(b->distortion[k].amplitude, -0.01 * d, 0.01 * d, path, "m", err)))
            return rc;
        sum += fabs(b->distortion[k].amplitude);
        bend += rd_bore_bend_term(b->distortion[k].order, b->distortion[k].amplitude);
    }
    if (sum > 0.01 * d)
        return rd_error_set(err, RD_EINVAL, "/bore/distortion",
                            "/bore/distortion: the amplitudes sum to %g m; at most 1 %% of the "
                            "ring diameter (%g m) is allowed.",
                            sum, 0.01 * d);
    return rd_bore_convex_validate(bend, d, err); /* the contact analysis' rule */
}

int rd_lift_bore_init(rd_lift_model *c, rd_error *err)
{
    const rd_lift_bore *b = &c->p->bore;
    double d = rd_ring_get_params(c->ring)->diameter;
    c->bo_gap = NULL;
    if (!rd_lift_bore_distorted(b, d))
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
