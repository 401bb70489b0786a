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
    o->free_shape = NULL;
}

double rd_contact_default_stiffness(const rd_ring_params *p)
{
    rd_ring_section s;
    rd_section sec;
    rd_ring_section_get(p, 0, &s);
    rd_section_init(&sec, p);
    return 2e6 * p->youngs_modulus * s.I_inplane / (sec.h * pow(s.R, 4));
}

double rd_contact_gap_floor(const rd_ring_params *p)
{
    rd_section sec;
    rd_section_init(&sec, p);
    double p0 = 2.0 * p->tangential_force / (p->diameter * sec.run.height);
    return 20.0 * p0 / rd_contact_default_stiffness(p);
}

int rd_contact_points(int m, int n)
{
    int dense = n > 0 ? (6400 + n - 1) / n : m;
    return m < 5 ? m : (dense < 5 ? 5 : (dense < m ? dense : m));
}

/* A pretension, in the ring's block. */
static int pretension_check(const rd_ring_params *p, rd_error *err)
{
    if (p->tangential_force <= 0.0)
        return rd_error_set(err, RD_EINVAL, "/tangential_force",
                            "@/tangential_force = %g N: the contact analysis needs a pretension "
                            "> 0 (without it the ring presses on nothing and its place in the "
                            "bore is undetermined).",
                            p->tangential_force);
    return RD_OK;
}

/* The contact block's points and segments. */
static int contact_counts(const rd_contact_opts *o, rd_error *err)
{
    if (o->points_per_segment < 1 || o->points_per_segment > RD_CONTACT_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/points_per_segment",
                            "@/points_per_segment = %d is out of range: allowed 1 to %d.",
                            o->points_per_segment, RD_CONTACT_POINTS_MAX);
    return RD_OK;
}

/* The contact block's segment bound and stiffness. */
static int contact_limits(const rd_contact_opts *o, const rd_ring_params *p, rd_error *err)
{
    if (o->max_segments < 4 || o->max_segments > RD_STATIC_SEGMENTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/max_segments",
                            "@/max_segments = %d is out of range: allowed 4 to %d.",
                            o->max_segments, RD_STATIC_SEGMENTS_MAX);
    double k0 = rd_contact_default_stiffness(p);
    if (o->stiffness != 0.0 &&
        (!isfinite(o->stiffness) || o->stiffness < 1e-3 * k0 || o->stiffness > 1e2 * k0))
        return rd_error_set(err, RD_EINVAL, "/stiffness",
                            "@/stiffness = %g Pa/m is out of range for this ring: allowed %g to "
                            "%g Pa/m (1e-3 to 1e2 times the default %g).",
                            o->stiffness, 1e-3 * k0, 1e2 * k0, k0);
    return RD_OK;
}

int rd_contact_validate(const rd_contact_opts *o, const rd_ring_params *p, rd_error *err)
{
    size_t m = rd_error_enter(err, "/ring");
    int rc = pretension_check(p, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/bore");
    rc = rc ? rc : rd_bore_validate(&o->bore, p->diameter, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/ring");
    rc = rc ? rc : rd_free_shape_validate(o->free_shape, p, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/contact");
    rc = rc ? rc : contact_counts(o, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/numerics");
    if (!rc && (!isfinite(o->accuracy) || o->accuracy < 1e-4 || o->accuracy > 0.5))
        rc = rd_error_set(err, RD_EINVAL, "/accuracy",
                          "@/accuracy = %g is out of range: allowed 1e-4 to 0.5.", o->accuracy);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/contact");
    rc = rc ? rc : contact_limits(o, p, err);
    rd_error_leave(err, m);
    return rc;
}
