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
 * A bore map (rd_lift_params.bore_map): each layer's offsets at the bore
 * points once, and at each force call's t the offsets at the ring's depth
 * ring_z_tdc + s(t), linear in depth between the two layers around it (as
 * the map's bore is: rd_bore_map.h), a[j] + w (b[j] - a[j]) so that equal
 * layers give the plain bore's offsets bit for bit.  The bore moves past the
 * ring with the piston: the offsets depend on t only, not on the state (the
 * Jacobian is unchanged).
 *
 * Validation: rd_bore_validate (rd_liner.h), the contact analysis' rules;
 * a map's: rd_lift_validate.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

/* The offsets of bore b at every bore point into g (np values). */
static void offsets(const rd_lift_model *c, const rd_bore *b, double d, size_t np, double *g)
{
    double g0 = b->diameter > 0.0 ? 0.5 * (b->diameter - d) : 0.0;
    for (size_t j = 0; j < np; j++) {
        double psi = atan2(c->bo_e[2 * j + 1], c->bo_e[2 * j]), x = g0;
        for (int k = 0; k < b->n_distortion; k++)
            x += b->distortion[k].amplitude *
                 cos(b->distortion[k].order * (psi - b->distortion[k].phase_deg * M_PI / 180.0));
        g[j] = x;
    }
}

int rd_lift_bore_distorted(const rd_lift_params *p, double d)
{
    if (!p->bore_map)
        return rd_bore_distorted(&p->bore, d);
    for (int i = 0; i < p->bore_map->n_layers; i++)
        if (rd_bore_distorted(&p->bore_map->layer[i].bore, d))
            return 1;
    return 0;
}

int rd_lift_bore_init(rd_lift_model *c, rd_error *err)
{
    const rd_lift_params *p = c->p;
    double d = rd_ring_get_params(c->ring)->diameter;
    c->bo_gap = c->bo_layers = NULL;
    if (!rd_lift_bore_distorted(p, d))
        return RD_OK;
    size_t np = (size_t)c->n * RD_LIFT_ARC_POINTS;
    int nl = p->bore_map ? p->bore_map->n_layers : 0;
    c->bo_gap = malloc(np * sizeof *c->bo_gap);
    c->bo_layers = nl ? malloc((size_t)nl * np * sizeof *c->bo_layers) : NULL;
    if (!c->bo_gap || (nl && !c->bo_layers))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift bore.");
    if (!nl) {
        offsets(c, &p->bore, d, np, c->bo_gap);
        return RD_OK;
    }
    for (int i = 0; i < nl; i++)
        offsets(c, &p->bore_map->layer[i].bore, d, np, c->bo_layers + (size_t)i * np);
    double s0 = 0.0, v, a; /* the start's travel */
    if (!c->piston_fixed)
        rd_engine_piston(&p->engine, 0.0, &s0, &v, &a);
    rd_lift_bore_at_travel(c, s0);
    return RD_OK;
}

void rd_lift_bore_at_travel(rd_lift_model *c, double s)
{
    const rd_bore_map *m = c->p->bore_map;
    if (!m || !c->bo_layers)
        return;
    size_t np = (size_t)c->n * RD_LIFT_ARC_POINTS;
    double z = c->p->ring_z_tdc + s;
    int i = 0, nl = m->n_layers;
    while (i + 2 < nl && z > m->layer[i + 1].z)
        i++;
    const double *a = c->bo_layers + (size_t)i * np;
    if (nl == 1) {
        memcpy(c->bo_gap, a, np * sizeof *a);
        return;
    }
    const double *b = a + np;
    double w = (z - m->layer[i].z) / (m->layer[i + 1].z - m->layer[i].z);
    w = fmin(fmax(w, 0.0), 1.0); /* the map covers the stroke (rd_lift_validate) */
    for (size_t j = 0; j < np; j++)
        c->bo_gap[j] = a[j] + w * (b[j] - a[j]);
}
