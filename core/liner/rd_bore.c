/*
 * rd_bore.c — the bore's convexity rule (rd_liner.h).
 */
#include <math.h>

#include "rd_liner.h"

double rd_bore_bend_term(int order, double amplitude)
{
    return fabs(amplitude) * ((double)order * order + 2.0);
}

int rd_bore_convex_validate(double bend, double d, rd_error *err)
{
    if (!(bend > 0.5 * d))
        return RD_OK;
    return rd_error_set(err, RD_EINVAL, "/bore/distortion",
                        "/bore/distortion: sum of |amplitude| (order^2 + 2) is %.7g m; allowed "
                        "at most the bore radius %.7g m, so that the bore stays convex (a "
                        "non-convex bore makes the contact solve fail to converge and is outside "
                        "the lift model's contact geometry).",
                        bend, 0.5 * d);
}
