/*
 * rd_vec3 — 3-vectors and 3x3 matrices (row-major), inline: the static
 * chain's joints, loads and contact points (core/statics) use them.  Each
 * writes its result through a copy, so out may alias an input.
 */
#ifndef RD_VEC3_H
#define RD_VEC3_H

#include <string.h>

static inline double rd_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void rd_cross3(const double a[3], const double b[3], double out[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(out, c, sizeof c);
}

/* out = A v */
static inline void rd_mv3(const double A[9], const double v[3], double out[3])
{
    double c[3];
    for (int r = 0; r < 3; r++)
        c[r] = A[3 * r] * v[0] + A[3 * r + 1] * v[1] + A[3 * r + 2] * v[2];
    memcpy(out, c, sizeof c);
}

/* out = A B */
static inline void rd_mm3(const double A[9], const double B[9], double out[9])
{
    double c[9];
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            c[3 * r + q] = A[3 * r] * B[q] + A[3 * r + 1] * B[3 + q] + A[3 * r + 2] * B[6 + q];
    memcpy(out, c, sizeof c);
}

#endif
