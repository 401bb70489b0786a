/*
 * rd_blocktri.c — block-tridiagonal LU (block Thomas algorithm); the
 * equations, storage and stability argument are in rd_blocktri.h.
 *
 * The kernels take the block size as an argument and are inlined into
 * factor/solve bodies called with a literal size for the sizes in use (6:
 * a segment of the full lift model or of the static chain; 3: the rigid
 * ring; 12: two segments, the static tangent with flexible contact faces,
 * 2.6 M instructions a factorization at n = 320 where the run-time size
 * took 3.8 M), so the compiler unrolls and vectorizes their fixed-length
 * loops; any other size runs the same code with a run-time size.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_blocktri.h"
#include "rd_error.h"

#if defined(__GNUC__)
#define BT_INLINE static inline __attribute__((always_inline))
#else
#define BT_INLINE static inline
#endif

int rd_blocktri_init(rd_blocktri *m, int nb, int bs)
{
    memset(m, 0, sizeof *m);
    if (nb < 1 || bs < 1)
        return RD_EINVAL;
    if ((size_t)nb > ((size_t)-1 / sizeof(double)) / ((size_t)bs * bs * 3))
        return RD_ENOMEM;
    size_t n = (size_t)nb * bs * bs;
    m->nb = nb;
    m->bs = bs;
    m->L = calloc(3 * n, sizeof *m->L);
    m->piv = calloc((size_t)nb * bs, sizeof *m->piv);
    if (!m->L || !m->piv) {
        rd_blocktri_cleanup(m);
        return RD_ENOMEM;
    }
    m->D = m->L + n;
    m->U = m->D + n;
    return RD_OK;
}

void rd_blocktri_cleanup(rd_blocktri *m)
{
    free(m->L);
    free(m->piv);
    memset(m, 0, sizeof *m);
}

/* a = P L U in place (row-major, unit L below the diagonal), partial
 * pivoting by rows; piv[k] = the row swapped with row k at step k.
 * Returns 0, or 1 + k at an exactly zero pivot. */
BT_INLINE int lu_block(double *restrict a, int *restrict piv, int bs)
{
    for (int k = 0; k < bs; k++) {
        int p = k;
        double big = fabs(a[bs * k + k]);
        for (int r = k + 1; r < bs; r++)
            if (fabs(a[bs * r + k]) > big) {
                big = fabs(a[bs * r + k]);
                p = r;
            }
        piv[k] = p;
        if (big == 0.0)
            return 1 + k;
        if (p != k)
            for (int c = 0; c < bs; c++) {
                double t = a[bs * k + c];
                a[bs * k + c] = a[bs * p + c];
                a[bs * p + c] = t;
            }
        double inv = 1.0 / a[bs * k + k];
        for (int r = k + 1; r < bs; r++) {
            double l = a[bs * r + k] * inv;
            a[bs * r + k] = l;
            for (int c = k + 1; c < bs; c++)
                a[bs * r + c] -= l * a[bs * k + c];
        }
    }
    return 0;
}

/* X = (P L U)^-1 X for nc right-hand sides stored as the columns of the
 * bs x nc row-major X (nc = 1: a vector). */
BT_INLINE void lu_solve(const double *restrict a, const int *restrict piv, double *restrict X,
                        int nc, int bs)
{
    for (int k = 0; k < bs; k++)
        if (piv[k] != k)
            for (int c = 0; c < nc; c++) {
                double t = X[nc * k + c];
                X[nc * k + c] = X[nc * piv[k] + c];
                X[nc * piv[k] + c] = t;
            }
    for (int r = 1; r < bs; r++)
        for (int k = 0; k < r; k++) {
            double l = a[bs * r + k];
            for (int c = 0; c < nc; c++)
                X[nc * r + c] -= l * X[nc * k + c];
        }
    for (int r = bs - 1; r >= 0; r--) {
        for (int k = r + 1; k < bs; k++) {
            double u = a[bs * r + k];
            for (int c = 0; c < nc; c++)
                X[nc * r + c] -= u * X[nc * k + c];
        }
        double inv = 1.0 / a[bs * r + r];
        for (int c = 0; c < nc; c++)
            X[nc * r + c] *= inv;
    }
}

/* Y -= A X: A bs x bs, X and Y bs x nc, all row-major. */
BT_INLINE void sub_mul(double *restrict Y, const double *restrict A, const double *restrict X,
                       int nc, int bs)
{
    for (int r = 0; r < bs; r++)
        for (int k = 0; k < bs; k++) {
            double a = A[bs * r + k];
            for (int c = 0; c < nc; c++)
                Y[nc * r + c] -= a * X[nc * k + c];
        }
}

BT_INLINE int factor(rd_blocktri *m, int bs)
{
    size_t bb = (size_t)bs * bs;
    for (int i = 0; i < m->nb; i++) {
        double *D = m->D + bb * i;
        if (i > 0)
            sub_mul(D, m->L + bb * i, m->U + bb * (i - 1), bs, bs);
        int bad = lu_block(D, m->piv + (size_t)bs * i, bs);
        if (bad)
            return bs * i + bad;
        if (i + 1 < m->nb)
            lu_solve(D, m->piv + (size_t)bs * i, m->U + bb * i, bs, bs);
    }
    return 0;
}

BT_INLINE void solve(const rd_blocktri *m, double *x, int bs)
{
    size_t bb = (size_t)bs * bs;
    for (int i = 0; i < m->nb; i++) {
        double *xi = x + (size_t)bs * i;
        if (i > 0)
            sub_mul(xi, m->L + bb * i, xi - bs, 1, bs);
        lu_solve(m->D + bb * i, m->piv + (size_t)bs * i, xi, 1, bs);
    }
    for (int i = m->nb - 2; i >= 0; i--)
        sub_mul(x + (size_t)bs * i, m->U + bb * i, x + (size_t)bs * (i + 1), 1, bs);
}

int rd_blocktri_factor(rd_blocktri *m)
{
    if (m->bs == 6)
        return factor(m, 6);
    if (m->bs == 3)
        return factor(m, 3);
    if (m->bs == 12)
        return factor(m, 12);
    return factor(m, m->bs);
}

void rd_blocktri_solve(const rd_blocktri *m, double *x)
{
    if (m->bs == 6)
        solve(m, x, 6);
    else if (m->bs == 3)
        solve(m, x, 3);
    else if (m->bs == 12)
        solve(m, x, 12);
    else
        solve(m, x, m->bs);
}
