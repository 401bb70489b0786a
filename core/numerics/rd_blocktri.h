/*
 * rd_blocktri.h — LU factorization and solve of a block-tridiagonal matrix
 * with dense square blocks (the block Thomas algorithm).
 *
 * The matrix has nb block rows of size bs:
 *     row i:  L_i x_{i-1} + D_i x_i + U_i x_{i+1} = b_i     (L_0, U_{nb-1} absent)
 * Factorization (block LU without pivoting between blocks, partial pivoting
 * inside each diagonal block):
 *     D'_0 = D_0,   W_{i-1} = D'_{i-1}^-1 U_{i-1},   D'_i = D_i - L_i W_{i-1},
 * each D'_i factored P L U in place; solve:
 *     z_0 = D'_0^-1 b_0,  z_i = D'_i^-1 (b_i - L_i z_{i-1}),
 *     x_{nb-1} = z_{nb-1},  x_i = z_i - W_i x_{i+1}.
 * Cost (nb bs^3 (1/3 + 2)) multiply-adds to factor, 3 nb bs^2 to solve.
 * Without pivoting between blocks it is stable when the Schur complements
 * D'_i stay well conditioned, e.g. for a matrix whose block-row scaling by
 * SPD blocks (here the segments' mass matrices M_i) has a positive definite
 * symmetric part; that is the lift Newton matrix M (I - gamma B - gamma^2 A)
 * = M - gamma C + gamma^2 K_t with damping C and tangent stiffness K_t
 * (rd_lift_newton.c).  A zero pivot is reported, never divided by.
 *
 * Storage (caller fills L, D, U; all blocks bs x bs row-major): L, D, U hold
 * nb blocks each, block i at offset i bs^2; L's block 0 and U's block nb - 1
 * are not read.  rd_blocktri_factor overwrites D with the LU factors of the
 * D'_i and U with the W_i; L is kept (the solve reads it).
 */
#ifndef RD_BLOCKTRI_H
#define RD_BLOCKTRI_H

typedef struct rd_blocktri {
    int nb, bs;
    double *L, *D, *U; /* nb bs^2 each, owned */
    int *piv;          /* nb bs: the row swaps of each D'_i (LAPACK dgetrf's ipiv, 0-based) */
} rd_blocktri;

/* Allocates the storage for nb >= 1 blocks of size bs >= 1 (contents
 * zero).  Returns RD_OK, RD_EINVAL (a size < 1) or RD_ENOMEM; the struct is
 * safe to clean up either way. */
int rd_blocktri_init(rd_blocktri *m, int nb, int bs);
void rd_blocktri_cleanup(rd_blocktri *m);

/* Factors in place (see the header comment).  Returns 0, or 1 + the global
 * row index of the first exactly zero pivot (the matrix is singular or its
 * block elimination breaks down; the factors are then unusable). */
int rd_blocktri_factor(rd_blocktri *m);

/* x = A^-1 x (nb bs values) with the factors of rd_blocktri_factor. */
void rd_blocktri_solve(const rd_blocktri *m, double *x);

/* Two sets of unknowns no entry couples (e.g. a planar structure's
 * in-plane and out-of-plane ones) can be factored and solved apart, with
 * exactly the numbers of the whole's factorization: the partial pivoting
 * never picks an exact zero over a nonzero, so it makes the same choices,
 * and every operation it does across the sets adds or subtracts an exact
 * zero (rd_static.c's plane_solve; test_blocktri checks it bit for bit). */

#endif
