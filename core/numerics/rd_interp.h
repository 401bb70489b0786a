/*
 * rd_interp — linear interpolation in a table, shared by the files that read
 * tables (the ring pack's gas traces, rd_gasflow.c; a free shape's pressure,
 * rd_free_shape.c).
 *
 * Usage:
 *     double p = rd_interp_linear(crank_deg, pressure, n, 123.0);
 */
#ifndef RD_INTERP_H
#define RD_INTERP_H

/* y at t, linear between the points of x (n >= 1, strictly increasing), the
 * end values held outside them; bisection, O(log n). */
static inline double rd_interp_linear(const double *x, const double *y, int n, double t)
{
    if (t <= x[0])
        return y[0];
    if (t >= x[n - 1])
        return y[n - 1];
    int lo = 0, hi = n - 1; /* x[lo] <= t < x[hi] */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (x[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    double w = (t - x[lo]) / (x[hi] - x[lo]);
    return y[lo] + w * (y[hi] - y[lo]);
}

#endif
