/*
 * rd_contact_opts — the contact analysis' options: defaults, range checks
 * (paths "/bore/...", "/contact/...", "/numerics/..."), the default contact
 * stiffness, and the convex-bore rule shared with the lift analysis
 * (declarations in rd_static.h; the analysis itself in rd_contact.c).
 */
#include "rd_static_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void rd_contact_opts_default(rd_contact_opts *o)
{
    memset(o, 0, sizeof *o);
    o->points_per_segment = 10;
    o->accuracy = 0.01;
    o->max_segments = 1280;
    o->flexible_face = 1;
}

double rd_contact_default_stiffness(const rd_ring_params *p)
{
    rd_ring_section s;
    rd_ring_section_get(p, 0, &s);
    return 2e6 * p->youngs_modulus * s.I_inplane / (p->axial_height * pow(s.R, 4));
}

double rd_contact_gap_floor(const rd_ring_params *p)
{
    double p0 = 2.0 * p->tangential_force / (p->diameter * p->axial_height);
    return 20.0 * p0 / rd_contact_default_stiffness(p);
}

int rd_contact_points(int m, int n)
{
    int dense = n > 0 ? (6400 + n - 1) / n : m;
    return m < 5 ? m : (dense < 5 ? 5 : (dense < m ? dense : m));
}

int rd_contact_validate(const rd_contact_opts *o, const rd_ring_params *p, rd_error *err)
{
    double d = p->diameter;
    if (p->tangential_force <= 0.0)
        return rd_error_set(err, RD_EINVAL, "/ring/tangential_force",
                            "/ring/tangential_force = %g N: the contact analysis needs a "
                            "pretension > 0 (without it the ring presses on nothing and its "
                            "place in the bore is undetermined).",
                            p->tangential_force);
    if (o->bore_diameter != 0.0 &&
        (!isfinite(o->bore_diameter) || o->bore_diameter < 0.98 * d || o->bore_diameter > 1.02 * d))
        return rd_error_set(err, RD_EINVAL, "/bore/diameter",
                            "/bore/diameter = %g m is out of range: allowed %g to %g m (within "
                            "2 %% of the ring diameter %g m).",
                            o->bore_diameter, 0.98 * d, 1.02 * d, d);
    if (o->n_distortion < 0 || o->n_distortion > RD_DISTORTION_MAX)
        return rd_error_set(err, RD_ELIMIT, "/bore/distortion",
                            "/bore/distortion has %d entries; at most %d are allowed.",
                            o->n_distortion, RD_DISTORTION_MAX);
    double total = 0.0, bend = 0.0;
    for (int k = 0; k < o->n_distortion; k++) {
        const rd_distortion *ds = &o->distortion[k];
        char path[64];
        snprintf(path, sizeof path, "/bore/distortion/%d/order", k);
        if (ds->order < 1 || ds->order > 64)
            return rd_error_set(err, RD_EINVAL, path, "%s = %d is out of range: allowed 1 to 64.",
                                path, ds->order);
        snprintf(path, sizeof path, "/bore/distortion/%d/amplitude", k);
        if (!isfinite(ds->amplitude) || fabs(ds->amplitude) > 0.01 * d)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s = %g m is out of range: allowed -%g to %g m (1 %% of the "
                                "diameter).",
                                path, ds->amplitude, 0.01 * d, 0.01 * d);
        snprintf(path, sizeof path, "/bore/distortion/%d/phase_deg", k);
        if (!isfinite(ds->phase_deg) || fabs(ds->phase_deg) > 360.0)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s = %g deg is out of range: allowed -360 to 360 deg.", path,
                                ds->phase_deg);
        total += fabs(ds->amplitude);
        bend += rd_bore_bend_term(ds->order, ds->amplitude);
    }
    if (total > 0.01 * d)
        return rd_error_set(err, RD_EINVAL, "/bore/distortion",
                            "/bore/distortion: the amplitudes add up to %g m; allowed at most "
                            "%g m (1 %% of the diameter).",
                            total, 0.01 * d);
    /* A petal-shaped bore (order 30 or 64 at the 1 % amplitude) ends Newton's
     * continuation unconverged; at the convex edge orders 4..64 converge. */
    int rc = rd_bore_convex_validate(bend, d, err);
    if (rc != RD_OK)
        return rc;
    if (o->points_per_segment < 1 || o->points_per_segment > RD_CONTACT_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/contact/points_per_segment",
                            "/contact/points_per_segment = %d is out of range: allowed 1 to %d.",
                            o->points_per_segment, RD_CONTACT_POINTS_MAX);
    if (!isfinite(o->accuracy) || o->accuracy < 1e-4 || o->accuracy > 0.5)
        return rd_error_set(err, RD_EINVAL, "/numerics/accuracy",
                            "/numerics/accuracy = %g is out of range: allowed 1e-4 to 0.5.",
                            o->accuracy);
    if (o->max_segments < 4 || o->max_segments > RD_STATIC_SEGMENTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/contact/max_segments",
                            "/contact/max_segments = %d is out of range: allowed 4 to %d.",
                            o->max_segments, RD_STATIC_SEGMENTS_MAX);
    double k0 = rd_contact_default_stiffness(p);
    if (o->stiffness != 0.0 &&
        (!isfinite(o->stiffness) || o->stiffness < 1e-3 * k0 || o->stiffness > 1e2 * k0))
        return rd_error_set(err, RD_EINVAL, "/contact/stiffness",
                            "/contact/stiffness = %g Pa/m is out of range for this ring: "
                            "allowed %g to %g Pa/m (1e-3 to 1e2 times the default %g).",
                            o->stiffness, 1e-3 * k0, 1e2 * k0, k0);
    return RD_OK;
}
