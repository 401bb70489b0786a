/*
 * rd_bore.c — the bore: whether it is distorted, its range checks and its
 * convexity rule (rd_liner.h).  One set of checks for the contact, lift and
 * ring-pack analyses.
 */
#include <math.h>
#include <stdio.h>

#include "rd_liner.h"

double rd_bore_bend_term(int order, double amplitude)
{
    return fabs(amplitude) * ((double)order * order + 2.0);
}

/* The convex rule (path "/distortion" in the bore's block). */
int rd_bore_convex_validate(double bend, double d, rd_error *err)
{
    if (!(bend > 0.5 * d))
        return RD_OK;
    return rd_error_set(err, RD_EINVAL, "/distortion",
                        "@/distortion: sum of |amplitude| (order^2 + 2) is %.7g m; allowed "
                        "at most the bore radius %.7g m, so that the bore stays convex (a "
                        "non-convex bore makes the contact solve fail to converge and is outside "
                        "the lift model's contact geometry).",
                        bend, 0.5 * d);
}

int rd_bore_distorted(const rd_bore *b, double ring_diameter)
{
    return (b->diameter > 0.0 && b->diameter != ring_diameter) || b->n_distortion > 0;
}

/* Term k's order, amplitude and phase. */
static int validate_term(const rd_distortion *ds, int k, double d, rd_error *err)
{
    char path[64];
    snprintf(path, sizeof path, "/distortion/%d/order", k);
    if (ds->order < 1 || ds->order > 64)
        return rd_error_set(err, RD_EINVAL, path, "@%s = %d is out of range: allowed 1 to 64.",
                            path, ds->order);
    snprintf(path, sizeof path, "/distortion/%d/amplitude", k);
    if (!isfinite(ds->amplitude) || fabs(ds->amplitude) > 0.01 * d)
        return rd_error_set(err, RD_EINVAL, path,
                            "@%s = %g m is out of range: allowed -%g to %g m (1 %% of the "
                            "diameter).",
                            path, ds->amplitude, 0.01 * d, 0.01 * d);
    snprintf(path, sizeof path, "/distortion/%d/phase_deg", k);
    if (!isfinite(ds->phase_deg) || fabs(ds->phase_deg) > 360.0)
        return rd_error_set(err, RD_EINVAL, path,
                            "@%s = %g deg is out of range: allowed -360 to 360 deg.", path,
                            ds->phase_deg);
    return RD_OK;
}

int rd_bore_validate(const rd_bore *b, double d, rd_error *err)
{
    if (b->diameter != 0.0 &&
        (!isfinite(b->diameter) || b->diameter < 0.98 * d || b->diameter > 1.02 * d))
        return rd_error_set(err, RD_EINVAL, "/diameter",
                            "@/diameter = %g m is out of range: allowed 0 (the ring's "
                            "diameter) or %g to %g m (within 2 %% of the ring diameter %g m).",
                            b->diameter, 0.98 * d, 1.02 * d, d);
    if (b->n_distortion < 0 || b->n_distortion > RD_BORE_ORDERS_MAX)
        return rd_error_set(err, RD_ELIMIT, "/distortion",
                            "@/distortion has %d entries; at most %d are allowed.", b->n_distortion,
                            RD_BORE_ORDERS_MAX);
    double total = 0.0, bend = 0.0;
    for (int k = 0; k < b->n_distortion; k++) {
        int rc = validate_term(&b->distortion[k], k, d, err);
        if (rc)
            return rc;
        total += fabs(b->distortion[k].amplitude);
        bend += rd_bore_bend_term(b->distortion[k].order, b->distortion[k].amplitude);
    }
    if (total > 0.01 * d)
        return rd_error_set(err, RD_EINVAL, "/distortion",
                            "@/distortion: the amplitudes add up to %g m; allowed at most "
                            "%g m (1 %% of the diameter).",
                            total, 0.01 * d);
    /* A petal-shaped bore (order 30 or 64 at the 1 % amplitude) ends Newton's
     * continuation unconverged; at the convex edge orders 4..64 converge. */
    return rd_bore_convex_validate(bend, d, err);
}
