/*
 * rd_lift_newton.c — the Newton systems of the lift formulations, solved in
 * second-order form (issue 10 item 4; file map: rd_lift_model.h).
 *
 * CVODE's BDF Newton iteration solves (I - gamma J) x = b, J = d(ydot)/dy.
 * Every lift formulation is second order: its state is nb blocks of
 * [q (bs values), v (bs values)] with q' = v, v' = a(t, q, v), so
 *     J = [0  I]      A = da/dq: block tridiagonal (block i couples to i +- 1),
 *         [A  B],     B = da/dv: block diagonal.
 * The rows of (I - gamma J) x = b read x_q - gamma x_v = b_q and
 * -gamma A x_q + (I - gamma B) x_v = b_v; substituting x_q = b_q + gamma x_v:
 *     S x_v = b_v + gamma A b_q,    S = I - gamma B - gamma^2 A,
 *     x_q = b_q + gamma x_v.
 * S has nb bs unknowns (half of the state) and is block tridiagonal with
 * bs x bs blocks (the ring is open: segment 0 and n - 1 are not coupled; every
 * force element is local, rd_lift_model.h), so it is factored by the block
 * Thomas algorithm of rd_blocktri.c: nb (bs^3 / 3 + 2 bs^3) multiply-adds,
 * about 1/3 of a band LU of the same matrix (half bandwidths 2 bs - 1 with
 * partial-pivoting fill), in fixed-size loops.  Pivoting is within the
 * diagonal blocks only.  That is stable when, scaled by the segments' mass
 * matrices, M S = M - gamma C + gamma^2 K_t (damping C = M B, tangent
 * stiffness K_t = -M A) has a positive definite symmetric part, as the
 * ring's elastic stiffness and the contacts' penalty stiffness and damping
 * give it; the unsymmetric parts (friction's dependence on the contact
 * pressure, dynamic gas areas) are not covered by that argument, but an
 * inexact solve there only slows the Newton iteration, whose convergence
 * test (not the linear solve) decides a step, and an exactly zero pivot is
 * the recoverable LUFACT failure: CVODE retries with a smaller step, where
 * S tends to I.  Checked against a dense LAPACK solve on the lift's own
 * matrices (tests/core/test_blocktri.c).  The elimination of the identity
 * block is exact algebra, so the Newton iteration is the same as with
 * I - gamma J; only rounding differs.
 *
 * Plumbing: CVodeSetLinSysFn hands us gamma and the state, and S is
 * assembled straight from the form's blocks into the block storage (no copy
 * of J kept by CVODE, no zeroing of a band).  The SUNMatrix CVODE holds is
 * an empty placeholder (a user linear-system function never touches it); the
 * SUNLinearSolver here is DIRECT, so CVODE's own handling (its
 * Jacobian-reuse flag jok, the 2 / (1 + gamma ratio) scaling of a solution
 * with an older gamma, its counters) is unchanged.  With jok the saved
 * blocks are reused and only S is rebuilt and factored for the new gamma, as
 * CVODE does with its saved J.  The factorization is made once per set-up and
 * serves every Newton iteration of the step.
 */
#include <stdlib.h>
#include <string.h>

#include "rd_blocktri.h"
#include "rd_cvode.h"
#include "rd_lift_model.h"

#if defined(__GNUC__)
#define NW_INLINE static inline __attribute__((always_inline))
#else
#define NW_INLINE static inline
#endif

struct rd_lift_newton {
    const rd_lift_form *form;
    int nb, bs;     /* blocks and block size */
    double *A, *B;  /* nb x 3 x bs^2 and nb x bs^2, the form's blocks */
    double gamma;   /* of the last set-up */
    rd_blocktri S;  /* S's blocks, then their factors */
    double *r;      /* nb bs scratch: the reduced right-hand side */
    SUNMatrix hold; /* the empty SUNMatrix CVODE is given, owned */
};

/* S = I - gamma B - gamma^2 A into the block storage: D_i = I - gamma B_i -
 * gamma^2 A_ii, L_i = -gamma^2 A_i,i-1, U_i = -gamma^2 A_i,i+1. */
static void assemble(rd_lift_newton *nw)
{
    int bs = nw->bs;
    size_t bb = (size_t)bs * bs;
    double g = nw->gamma, g2 = g * g;
    for (int i = 0; i < nw->nb; i++) {
        const double *Ai = nw->A + 3 * bb * i, *Bi = nw->B + bb * i;
        double *L = nw->S.L + bb * i, *D = nw->S.D + bb * i, *U = nw->S.U + bb * i;
        for (size_t k = 0; k < bb; k++) {
            L[k] = -g2 * Ai[k];
            D[k] = -g * Bi[k] - g2 * Ai[bb + k];
            U[k] = -g2 * Ai[2 * bb + k];
        }
        for (int k = 0; k < bs; k++)
            D[(bs + 1) * k] += 1.0;
    }
}

int rd_lift_newton_linsys(rd_lift_newton *nw, double t, N_Vector y, int jok, int *jcur,
                          double gamma)
{
    if (!jok)
        nw->form->blocks(nw->form->user, t, N_VGetArrayPointer(y), nw->A, nw->B);
    *jcur = !jok;
    nw->gamma = gamma;
    assemble(nw);
    return 0;
}

static SUNLinearSolver_Type nw_type(SUNLinearSolver LS)
{
    (void)LS;
    return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID nw_id(SUNLinearSolver LS)
{
    (void)LS;
    return SUNLINEARSOLVER_CUSTOM;
}

static int nw_initialize(SUNLinearSolver LS)
{
    (void)LS;
    return SUNLS_SUCCESS;
}

/* The block LU of S (assembled by rd_lift_newton_linsys); a zero pivot is
 * the recoverable LUFACT failure: CVODE cuts the step. */
static int nw_setup(SUNLinearSolver LS, SUNMatrix S)
{
    (void)S;
    rd_lift_newton *nw = LS->content;
    return rd_blocktri_factor(&nw->S) ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
}

/* r = b_v + gamma A b_q for the state-layout right-hand side b (blocks
 * [q, v] of bs values each); inlined with a literal bs where it matters (as
 * rd_blocktri.c's kernels) so the fixed-length loops unroll. */
NW_INLINE void reduce_rhs(const double *restrict A, const double *restrict b, double *restrict r,
                          double g, int nb, int bs)
{
    size_t bb = (size_t)bs * bs;
    for (int i = 0; i < nb; i++) {
        double *ri = r + (size_t)bs * i;
        for (int k = 0; k < bs; k++)
            ri[k] = 0.0;
        for (int j = i > 0 ? i - 1 : 0; j <= i + 1 && j < nb; j++) {
            const double *Aij = A + bb * (3 * (size_t)i + (j - i + 1));
            const double *bqj = b + 2 * (size_t)bs * j;
            for (int k = 0; k < bs; k++)
                for (int c = 0; c < bs; c++)
                    ri[k] += Aij[bs * k + c] * bqj[c];
        }
        const double *bvi = b + 2 * (size_t)bs * i + bs;
        for (int k = 0; k < bs; k++)
            ri[k] = bvi[k] + g * ri[k];
    }
}

/* x = (I - gamma J)^-1 b by the elimination of the header comment: r =
 * b_v + gamma A b_q, S x_v = r, x_q = b_q + gamma x_v. */
static int nw_solve(SUNLinearSolver LS, SUNMatrix S, N_Vector xv, N_Vector bv, sunrealtype tol)
{
    (void)S;
    (void)tol;
    rd_lift_newton *nw = LS->content;
    int bs = nw->bs, nb = nw->nb;
    const double *b = N_VGetArrayPointer(bv);
    double *x = N_VGetArrayPointer(xv), *r = nw->r, g = nw->gamma;
    if (bs == 6)
        reduce_rhs(nw->A, b, r, g, nb, 6);
    else
        reduce_rhs(nw->A, b, r, g, nb, bs);
    rd_blocktri_solve(&nw->S, r);
    for (int i = 0; i < nb; i++) {
        const double *bqi = b + 2 * (size_t)bs * i;
        double *xq = x + 2 * (size_t)bs * i, *xvi = xq + bs;
        for (int k = 0; k < bs; k++) {
            xvi[k] = r[(size_t)bs * i + k];
            xq[k] = bqi[k] + g * xvi[k];
        }
    }
    return SUNLS_SUCCESS;
}

static int nw_free(SUNLinearSolver LS)
{
    if (!LS)
        return 0;
    rd_lift_newton *nw = LS->content;
    if (nw) {
        if (nw->hold)
            SUNMatFreeEmpty(nw->hold);
        rd_blocktri_cleanup(&nw->S);
        free(nw->A);
        free(nw->B);
        free(nw->r);
        free(nw);
        LS->content = NULL;
    }
    SUNLinSolFreeEmpty(LS);
    return 0;
}

static SUNMatrix_ID hold_id(SUNMatrix M)
{
    (void)M;
    return SUNMATRIX_CUSTOM;
}

SUNLinearSolver rd_lift_newton_create(const rd_lift_form *form, SUNContext ctx, SUNMatrix *S,
                                      rd_lift_newton **out)
{
    static const struct _generic_SUNLinearSolver_Ops ops = {.gettype = nw_type,
                                                            .getid = nw_id,
                                                            .initialize = nw_initialize,
                                                            .setup = nw_setup,
                                                            .solve = nw_solve,
                                                            .free = nw_free};
    rd_lift_newton *nw = calloc(1, sizeof *nw);
    SUNLinearSolver LS = rd_linsol_wrap(ctx, nw, &ops);
    if (!LS) {
        free(nw);
        return NULL;
    }
    nw->form = form;
    nw->bs = form->block;
    nw->nb = (int)(form->N / (2 * form->block));
    size_t bb = (size_t)nw->bs * nw->bs;
    nw->A = calloc(3 * bb * nw->nb, sizeof *nw->A);
    nw->B = calloc(bb * nw->nb, sizeof *nw->B);
    nw->r = calloc((size_t)nw->nb * nw->bs, sizeof *nw->r);
    nw->hold = SUNMatNewEmpty(ctx);
    if (nw->hold)
        nw->hold->ops->getid = hold_id;
    if (rd_blocktri_init(&nw->S, nw->nb, nw->bs) || !nw->A || !nw->B || !nw->r || !nw->hold) {
        nw_free(LS);
        return NULL;
    }
    *S = nw->hold;
    *out = nw;
    return LS;
}
