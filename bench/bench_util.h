/* bench_util.h — what every benchmark needs: a monotonic clock, the median
 * of repeated timings (wall times on a shared machine are noisy), and the
 * least-squares exponent p of t ~ n^p. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <math.h>
#include <stdlib.h>
#include <time.h>

static inline double bench_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static inline int bench_cmp_(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of t[0..k-1] (sorts t). */
static inline double bench_median(double *t, int k)
{
    qsort(t, (size_t)k, sizeof t[0], bench_cmp_);
    return t[k / 2];
}

/* Least-squares slope of log t against log n over k points. */
static inline double bench_exponent(const double *n, const double *t, int k)
{
    double mx = 0, my = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < k; i++) {
        mx += log(n[i]) / k;
        my += log(t[i]) / k;
    }
    for (int i = 0; i < k; i++) {
        sxx += (log(n[i]) - mx) * (log(n[i]) - mx);
        sxy += (log(n[i]) - mx) * (log(t[i]) - my);
    }
    return sxy / sxx;
}

#endif
