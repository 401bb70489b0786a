/* rd_band — symmetric banded matrices on top of LAPACK (rd_band.h). */
#include "rd_band.h"

#include <assert.h>
#include <lapacke.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int rd_band_init(rd_band *b, int n, int kd, rd_error *err)
{
    b->n = n;
    b->kd = kd;
    b->ab = NULL;
    if (n <= 0 || kd < 0 || (size_t)(kd + 1) > SIZE_MAX / sizeof(double) / (size_t)n)
        return rd_error_set(err, RD_ELIMIT, "", "A %d x %d band matrix is too large.", n, kd);
    b->ab = calloc((size_t)(kd + 1) * (size_t)n, sizeof(double));
    if (!b->ab)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for a %d x %d band matrix.", n, kd);
    return RD_OK;
}

void rd_band_cleanup(rd_band *b)
{
    if (!b)
        return;
    free(b->ab);
    b->ab = NULL;
}

void rd_band_add(rd_band *b, int i, int j, double v)
{
    assert(i <= j && j - i <= b->kd && j < b->n && i >= 0);
    RD_BAND_AT(b, i, j) += v;
}

void rd_band_symv(const rd_band *b, const double *x, double *y)
{
    const int n = b->n, kd = b->kd;
    memset(y, 0, (size_t)n * sizeof *y);
    for (int j = 0; j < n; j++) {
        const double *col = b->ab + (size_t)j * (kd + 1);
        int i0 = j - kd < 0 ? 0 : j - kd;
        double yj = 0.0;
        for (int i = i0; i < j; i++) {
            double a = col[kd + i - j];
            y[i] += a * x[j];
            yj += a * x[i];
        }
        y[j] += yj + col[kd] * x[j];
    }
}

void rd_band_axpby(rd_band *c, const rd_band *a, double s, const rd_band *b)
{
    size_t len = (size_t)(a->kd + 1) * (size_t)a->n;
    assert(a->n == b->n && a->kd == b->kd && c->n == a->n && c->kd == a->kd);
    for (size_t k = 0; k < len; k++)
        c->ab[k] = a->ab[k] + s * b->ab[k];
}

int rd_band_cholesky(rd_band *b, rd_error *err)
{
    lapack_int info = LAPACKE_dpbtrf_work(LAPACK_COL_MAJOR, 'U', b->n, b->kd, b->ab, b->kd + 1);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "Banded Cholesky factorization failed (LAPACK dpbtrf info %d): the "
                            "shifted stiffness matrix is not positive definite.",
                            (int)info);
    return RD_OK;
}

int rd_band_solve(const rd_band *factor, int nrhs, double *x, rd_error *err)
{
    lapack_int info = LAPACKE_dpbtrs_work(LAPACK_COL_MAJOR, 'U', factor->n, factor->kd, nrhs,
                                          factor->ab, factor->kd + 1, x, factor->n);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "", "Banded solve failed (LAPACK dpbtrs info %d).",
                            (int)info);
    return RD_OK;
}
