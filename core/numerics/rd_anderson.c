/*
 * rd_anderson — see rd_anderson.h.  The least-squares problem has at most
 * RD_ANDERSON_DEPTH_MAX columns: its normal equations are solved by
 * Cholesky, with a relative 1e-12 on the diagonal so that nearly dependent
 * differences (a converged component) give a small gamma, not a blow-up.
 */
#include "rd_anderson.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rd_anderson_init(rd_anderson *a, int n, int depth)
{
    memset(a, 0, sizeof *a);
    if (n < 1 || depth < 1 || depth > RD_ANDERSON_DEPTH_MAX)
        return -1;
    a->n = n;
    a->depth = depth;
    a->dF = malloc((size_t)depth * n * sizeof *a->dF);
    a->dG = malloc((size_t)depth * n * sizeof *a->dG);
    a->f_prev = malloc((size_t)n * sizeof *a->f_prev);
    a->g_prev = malloc((size_t)n * sizeof *a->g_prev);
    return a->dF && a->dG && a->f_prev && a->g_prev ? 0 : -1;
}

void rd_anderson_free(rd_anderson *a)
{
    free(a->dF);
    free(a->dG);
    free(a->f_prev);
    free(a->g_prev);
    memset(a, 0, sizeof *a);
}

void rd_anderson_reset(rd_anderson *a)
{
    a->m = a->head = a->have_prev = 0;
}

/* Solves the m x m symmetric positive definite A y = b in place (y in b);
 * returns 0, or -1 when a pivot is not positive. */
static int cholesky_solve(double *A, double *b, int m)
{
    for (int j = 0; j < m; j++) {
        double d = A[j * m + j];
        for (int k = 0; k < j; k++)
            d -= A[j * m + k] * A[j * m + k];
        if (!(d > 0.0))
            return -1;
        A[j * m + j] = sqrt(d);
        for (int i = j + 1; i < m; i++) {
            double s = A[i * m + j];
            for (int k = 0; k < j; k++)
                s -= A[i * m + k] * A[j * m + k];
            A[i * m + j] = s / A[j * m + j];
        }
    }
    for (int i = 0; i < m; i++) { /* L z = b */
        for (int k = 0; k < i; k++)
            b[i] -= A[i * m + k] * b[k];
        b[i] /= A[i * m + i];
    }
    for (int i = m - 1; i >= 0; i--) { /* L^T y = z */
        for (int k = i + 1; k < m; k++)
            b[i] -= A[k * m + i] * b[k];
        b[i] /= A[i * m + i];
    }
    return 0;
}

void rd_anderson_mix(rd_anderson *a, const double *x, double *g)
{
    int n = a->n;
    if (a->have_prev) {
        double *df = a->dF + (size_t)a->head * n, *dg = a->dG + (size_t)a->head * n;
        for (int i = 0; i < n; i++) {
            double f = g[i] - x[i];
            df[i] = f - a->f_prev[i];
            dg[i] = g[i] - a->g_prev[i];
        }
        a->head = (a->head + 1) % a->depth;
        if (a->m < a->depth)
            a->m++;
    }
    for (int i = 0; i < n; i++) {
        a->f_prev[i] = g[i] - x[i];
        a->g_prev[i] = g[i];
    }
    a->have_prev = 1;
    int m = a->m;
    if (m == 0)
        return;
    double A[RD_ANDERSON_DEPTH_MAX * RD_ANDERSON_DEPTH_MAX], y[RD_ANDERSON_DEPTH_MAX], big = 0.0;
    for (int p = 0; p < m; p++) {
        const double *cp = a->dF + (size_t)p * n;
        double s = 0.0;
        for (int i = 0; i < n; i++)
            s += cp[i] * a->f_prev[i];
        y[p] = s;
        for (int q = 0; q <= p; q++) {
            const double *cq = a->dF + (size_t)q * n;
            double t = 0.0;
            for (int i = 0; i < n; i++)
                t += cp[i] * cq[i];
            A[p * m + q] = A[q * m + p] = t;
        }
        big = fmax(big, A[p * m + p]);
    }
    if (!(big > 0.0))
        return;
    for (int p = 0; p < m; p++)
        A[p * m + p] += 1e-12 * big;
    if (cholesky_solve(A, y, m) != 0)
        return;
    for (int p = 0; p < m; p++) {
        const double *cg = a->dG + (size_t)p * n;
        for (int i = 0; i < n; i++)
            g[i] -= cg[i] * y[p];
    }
}
