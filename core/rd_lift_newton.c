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
 * S has nb bs unknowns (half of the state) and, being block tridiagonal,
 * half bandwidths 2 bs - 1; its band LU (SUNDIALS band, partial pivoting)
 * costs (6n) 11 (22) against (12n) 23 (34) multiply-adds for the full model's
 * 12n band with MU = 11, ML = 23: 6.5x fewer.  The elimination of the
 * identity block is exact algebra, so the Newton iteration is the same; only
 * rounding differs (pivoting acts on S instead of the whole matrix).
 *
 * Plumbing: CVodeSetLinSysFn hands us gamma and the state, and S is
 * assembled straight from the form's blocks (no band copy of J kept by
 * CVODE, no I - gamma J pass over a 12n band); the matrix CVODE holds is S
 * itself, and the SUNLinearSolver here is DIRECT, so CVODE's own handling
 * (its Jacobian-reuse flag jok, the 2 / (1 + gamma ratio) scaling of a
 * solution with an older gamma, its counters) is unchanged.  With jok the
 * saved blocks are reused and only S is rebuilt for the new gamma, as CVODE
 * does with its saved J.
 */
#include <stdlib.h>
#include <string.h>

#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include "rd_lift_model.h"

struct rd_lift_newton {
    const rd_lift_form *form;
    int nb, bs;         /* blocks and block size */
    sunindextype N2;    /* nb bs: unknowns of S */
    double *A, *B;      /* nb x 3 x bs^2 and nb x bs^2, the form's blocks */
    double gamma;       /* of the last set-up */
    SUNMatrix S;        /* band (2 bs - 1, 2 bs - 1), owned */
    SUNLinearSolver lu; /* SUNDIALS band LU of S, owned */
    N_Vector r, xv;     /* N2 scratch */
};

/* S = I - gamma B - gamma^2 A into its band storage (all of it written). */
static void assemble(rd_lift_newton *nw)
{
    int bs = nw->bs, bb = bs * bs;
    double g = nw->gamma, g2 = g * g;
    /* the band storage is one contiguous array: memset, not SUNMatZero_Band's
     * element loop (5 % of a full-model step) */
    memset(SM_DATA_B(nw->S), 0, (size_t)SM_LDATA_B(nw->S) * sizeof(double));
    for (int i = 0; i < nw->nb; i++) {
        sunindextype r0 = (sunindextype)i * bs;
        const double *Bi = nw->B + (size_t)bb * i;
        for (int j = i - 1; j <= i + 1; j++) {
            if (j < 0 || j >= nw->nb)
                continue;
            const double *Aij = nw->A + (size_t)bb * (3 * (size_t)i + (j - i + 1));
            sunindextype c0 = (sunindextype)j * bs;
            for (int c = 0; c < bs; c++) {
                double *col = SM_COLUMN_B(nw->S, c0 + c);
                for (int r = 0; r < bs; r++) {
                    double v = -g2 * Aij[bs * r + c];
                    if (j == i)
                        v += (r == c ? 1.0 : 0.0) - g * Bi[bs * r + c];
                    SM_COLUMN_ELEMENT_B(col, r0 + r, c0 + c) = v;
                }
            }
        }
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
    rd_lift_newton *nw = LS->content;
    return SUNLinSolInitialize(nw->lu);
}

/* The band LU of S (assembled by rd_lift_newton_linsys); a singular S is
 * the band solver's recoverable LUFACT failure: CVODE cuts the step. */
static int nw_setup(SUNLinearSolver LS, SUNMatrix S)
{
    rd_lift_newton *nw = LS->content;
    return SUNLinSolSetup(nw->lu, S);
}

/* x = (I - gamma J)^-1 b by the elimination of the header comment. */
static int nw_solve(SUNLinearSolver LS, SUNMatrix S, N_Vector xv, N_Vector bv, sunrealtype tol)
{
    (void)tol;
    rd_lift_newton *nw = LS->content;
    int bs = nw->bs, bb = bs * bs;
    const double *b = N_VGetArrayPointer(bv);
    double *x = N_VGetArrayPointer(xv), *r = N_VGetArrayPointer(nw->r), g = nw->gamma;
    for (int i = 0; i < nw->nb; i++) {
        const double *bvi = b + 2 * (size_t)bs * i + bs;
        for (int k = 0; k < bs; k++) {
            double s = 0.0;
            for (int j = i - 1; j <= i + 1; j++) {
                if (j < 0 || j >= nw->nb)
                    continue;
                const double *Aij = nw->A + (size_t)bb * (3 * (size_t)i + (j - i + 1));
                const double *bqj = b + 2 * (size_t)bs * j;
                for (int c = 0; c < bs; c++)
                    s += Aij[bs * k + c] * bqj[c];
            }
            r[(size_t)bs * i + k] = bvi[k] + g * s;
        }
    }
    int flag = SUNLinSolSolve(nw->lu, S, nw->xv, nw->r, 0.0);
    if (flag)
        return flag;
    const double *sv = N_VGetArrayPointer(nw->xv);
    for (int i = 0; i < nw->nb; i++) {
        const double *bqi = b + 2 * (size_t)bs * i;
        double *xq = x + 2 * (size_t)bs * i, *xvi = xq + bs;
        for (int k = 0; k < bs; k++) {
            xvi[k] = sv[(size_t)bs * i + k];
            xq[k] = bqi[k] + g * xvi[k];
        }
    }
    return 0;
}

static int nw_free(SUNLinearSolver LS)
{
    if (!LS)
        return 0;
    rd_lift_newton *nw = LS->content;
    if (nw) {
        if (nw->lu)
            SUNLinSolFree(nw->lu);
        if (nw->S)
            SUNMatDestroy(nw->S);
        if (nw->r)
            N_VDestroy(nw->r);
        if (nw->xv)
            N_VDestroy(nw->xv);
        free(nw->A);
        free(nw->B);
        free(nw);
        LS->content = NULL;
    }
    SUNLinSolFreeEmpty(LS);
    return 0;
}

SUNLinearSolver rd_lift_newton_create(const rd_lift_form *form, SUNContext ctx, SUNMatrix *S,
                                      rd_lift_newton **out)
{
    SUNLinearSolver LS = SUNLinSolNewEmpty(ctx);
    rd_lift_newton *nw = calloc(1, sizeof *nw);
    if (!LS || !nw) {
        free(nw);
        if (LS)
            SUNLinSolFreeEmpty(LS);
        return NULL;
    }
    LS->content = nw;
    LS->ops->gettype = nw_type;
    LS->ops->getid = nw_id;
    LS->ops->initialize = nw_initialize;
    LS->ops->setup = nw_setup;
    LS->ops->solve = nw_solve;
    LS->ops->free = nw_free;
    nw->form = form;
    nw->bs = form->block;
    nw->nb = (int)(form->N / (2 * form->block));
    nw->N2 = (sunindextype)nw->nb * nw->bs;
    size_t bb = (size_t)nw->bs * nw->bs;
    nw->A = calloc(3 * bb * nw->nb, sizeof *nw->A);
    nw->B = calloc(bb * nw->nb, sizeof *nw->B);
    sunindextype w = nw->N2 > 1 ? (2 * nw->bs - 1 < nw->N2 - 1 ? 2 * nw->bs - 1 : nw->N2 - 1) : 0;
    nw->S = SUNBandMatrix(nw->N2, w, w, ctx);
    nw->r = N_VNew_Serial(nw->N2, ctx);
    nw->xv = N_VNew_Serial(nw->N2, ctx);
    if (nw->S && nw->r)
        nw->lu = SUNLinSol_Band(nw->r, nw->S, ctx);
    if (!nw->A || !nw->B || !nw->S || !nw->r || !nw->xv || !nw->lu) {
        nw_free(LS);
        return NULL;
    }
    *S = nw->S;
    *out = nw;
    return LS;
}
