/*
 * rd_band — symmetric banded matrices in LAPACK upper band storage (internal
 * to core).  Element (i, j), 0 <= j - i <= kd, lives at
 *     ab[(kd + i - j) + j * (kd + 1)]        (column-major, ldab = kd + 1).
 * The ring's chain of segments couples only neighbours, so K and M are banded
 * with kd = 11 (split ring) or 17 (closed ring in folded order, see rd_ring.c).
 */
#ifndef RD_BAND_H
#define RD_BAND_H

#include "rd_error.h"

typedef struct rd_band {
    int n, kd;
    double *ab; /* (kd + 1) * n, owned */
} rd_band;

#define RD_BAND_AT(B, i, j) ((B)->ab[((B)->kd + (i) - (j)) + (size_t)(j) * ((B)->kd + 1)])

/* Allocates a zero n x n band matrix.  RD_ENOMEM on failure. */
int rd_band_init(rd_band *b, int n, int kd, rd_error *err);
void rd_band_cleanup(rd_band *b);

/* A(i,j) += v for the upper triangle (i <= j, j - i <= kd; asserts). Callers
 * adding a symmetric block add only its upper entries. */
void rd_band_add(rd_band *b, int i, int j, double v);

/* y = A x (A symmetric, full product from the upper band). */
void rd_band_symv(const rd_band *b, const double *x, double *y);

/* c = A + s B for matrices of equal size and bandwidth. */
void rd_band_axpby(rd_band *c, const rd_band *a, double s, const rd_band *b);

/* In-place Cholesky factorization (LAPACK dpbtrf).  RD_ENUMERIC if the matrix
 * is not positive definite. */
int rd_band_cholesky(rd_band *b, rd_error *err);

/* Solves A X = B for nrhs columns (leading dimension n) with the factor from
 * rd_band_cholesky (LAPACK dpbtrs). */
int rd_band_solve(const rd_band *factor, int nrhs, double *x, rd_error *err);

#endif
