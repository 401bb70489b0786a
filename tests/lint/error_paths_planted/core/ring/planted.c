/* error_paths.py's self-test: four planted absolute paths, and the forms
 * the lint lets through.  Never compiled. */
#include "rd_error.h"

int planted(double d, int i, rd_error *err)
{
    char at[16];
    snprintf(at, sizeof at, "/rings/%d", i); /* a block's pointer: allowed */
    size_t m = rd_error_enter(err, "/ring"); /* a block: allowed */
    rd_error_leave(err, m);
    if (d < 0) /* 1: an absolute path */
        return rd_error_set(err, RD_EINVAL, "/ring/diameter", "@/diameter = %g m.", d);
    if (d > 1) /* 2: an absolute message, split over two literals */
        return rd_error_set(err, RD_EINVAL, "/diameter",
                            "/ring/"
                            "diameter = %g m is too large.",
                            d);
    if (d == 0) /* 3: a path built from a literal */
        snprintf(at, sizeof at, "/rings/%d/kind", i);
    const char *k = "/physics/gas/heat_capacity_ratio"; /* 4 */
    /* "/ring/diameter" in a comment: allowed; an absolute path mid-message: allowed */
    return rd_error_set(err, RD_EINVAL, k, "the bore (/bore/diameter) %s", 'x' == 'y' ? "" : "");
}
