/*
 * rd_ringpack_newton.c — the Newton systems of a pack with rings on the lift
 * models: the bordered elimination planned in rd_lift_model.h ("several
 * rings in a pack").
 *
 * CVODE's BDF Newton iteration solves M x = b, M = I - gamma J.  Order the
 * state as y = [y_b, y_1, ..., y_R]: y_b the N0 network and axial-ring
 * states (rd_ringpack_model.h), y_i ring i's lift-model states.  Then
 *     M = [M_bb  M_b1 ... M_bR]     M_bb  = I - gamma J_bb     (dense, N0 x N0)
 *         [M_1b  M_11         ]     M_ii  = I - gamma J_ii     (the ring's own,
 *         [ ...        ...    ]             rd_lift_newton: band LU in O(n))
 *         [M_Rb           M_RR]     M_ib  = -gamma d f_i / d y_b
 *                                   M_bi  = -gamma d f_b / d y_i
 * with the structure the couplings have:
 *  - a ring's rates depend on y_b only through its three face pressures
 *    (land above, groove, volume below; the crankcase is no state), so M_ib
 *    has at most 3 non-zero columns c_ik = -gamma d f_i / d p_k (the forces
 *    are linear in the pressures: a difference quotient is exact up to
 *    rounding);
 *  - the network depends on y_i only through the ring's two flank areas A_a
 *    (rd_packring_areas), so M_bi w = -gamma sum_a G_ia (dA_ia . w), with
 *    G_ia = d f_b / d A_ia (the orifice flow is linear in its area: exact
 *    quotient) and dA_ia . w the areas' derivative along w: the lifts are
 *    linear in the state, dL_j = L_j(w) - L_j(0), and the clamp's slope is
 *    1 inside (0, a), 0 outside.
 * Block elimination (Schur complement on the network):
 *   setup: X_ik = M_ii^-1 c_ik (3 band solves per ring),
 *          S = M_bb - sum_i sum_k (M_bi X_ik) e_k^T, dense LU (N0 <= 16);
 *   solve: z_i = M_ii^-1 b_i,
 *          S x_b = b_b - sum_i M_bi z_i,
 *          x_i = z_i - sum_k X_ik x_b[k].
 * Exact algebra (to the quotients' rounding), so CVODE's Newton iteration is
 * the coupled system's; O(n) per ring and step.  J_bb and G_ia are the
 * network's exact partial derivatives (rd_ringpack_base_jacobian: one sweep
 * of the orifice flows with their derivatives; difference quotients took
 * one sweep per pressure and per flank area, half the pack's work).
 * S is block lower triangular: the cumulative masses and a lift ring's
 * unused axial slots feed nothing back (zero columns; their rows in S are
 * those of I, plus the masses' dependence on the pressures), so only the
 * "active" part S_aa (pressures and the axial rings' z, z': 6 x 6 for three
 * lift rings) is LU-factored, the rest follows by substitution:
 *   S_aa x_a = b_a,   x_r = b_r - S_ra x_a.
 *
 * Plumbing as rd_lift_newton.c: CVodeSetLinSysFn hands gamma and the state
 * to rd_ringpack_newton_linsys, which builds everything; the solver is
 * DIRECT over a dense N0 x N0 matrix that holds S (CVODE's jok reuse and
 * gamma-ratio scaling unchanged; the driver asks for a fresh set-up at
 * every step, as the lift driver does).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sundials/sundials_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "rd_cvode.h"
#include "rd_ringpack_model.h"

typedef struct pring {
    rd_packring *L;
    int N, off;
    double *X[3];    /* M_ii^-1 c_ik, N each */
    int pcol[3], np; /* the face pressures' state indices (above, behind, below) */
    double *D[3];    /* d f_i / d p_k, N each, once (below) */
    int have_D;
    double *r1, *w; /* N scratch */
} pring;

#define NA_MAX (4 * RD_RINGPACK_RINGS_MAX) /* active unknowns: pressures, axial z, z' */

struct rd_ringpack_newton {
    rd_ringpack_model *m;
    int N0;
    double gamma, t;
    SUNMatrix A;                               /* dense N0 x N0: S (column-major) */
    int na, act[NA_MAX], rest[NA_MAX + 4], nr; /* active and remaining indices */
    double Sa[NA_MAX * NA_MAX], *col[NA_MAX];  /* S_aa, LU-factored (SUNDIALS dense LU) */
    double xa[NA_MAX];
    sunindextype piv[NA_MAX];
    int info;
    double *J, *G;        /* J: N0 x N0; G: R x 2 x N0 */
    const double *y, *fy; /* the set-up state and f(t, y) */
    pring ring[RD_RINGPACK_RINGS_MAX];
};

/* ------------------------------------------------------------ set-up */

/* G and the active columns of S = I - gamma J_bb (rd_ringpack_base_jacobian);
 * the other columns are I's and never read. */
static void network_block(rd_ringpack_newton *nw, const double *area)
{
    size_t N0 = (size_t)nw->N0;
    double *S = SM_DATA_D(nw->A);
    rd_ringpack_base_jacobian(nw->m, nw->t, nw->y, area, nw->J, nw->G);
    for (int c = 0; c < nw->na; c++) {
        size_t j = (size_t)nw->act[c];
        for (size_t r = 0; r < N0; r++)
            S[j * N0 + r] = -nw->gamma * nw->J[j * N0 + r];
        S[j * N0 + j] += 1.0;
    }
}

/* LU of S_aa (the header comment); nonzero: singular. */
static int factor_active(rd_ringpack_newton *nw)
{
    const double *S = SM_DATA_D(nw->A);
    int na = nw->na;
    for (int c = 0; c < na; c++)
        for (int r = 0; r < na; r++)
            nw->Sa[c * na + r] = S[(size_t)nw->act[c] * nw->N0 + nw->act[r]];
    return SUNDlsMat_denseGETRF(nw->col, na, na, nw->piv) != 0;
}

/* x = S^-1 x in place (the header comment). */
static void solve_s(rd_ringpack_newton *nw, double *x)
{
    const double *S = SM_DATA_D(nw->A);
    int na = nw->na;
    size_t N0 = (size_t)nw->N0;
    for (int k = 0; k < na; k++)
        nw->xa[k] = x[nw->act[k]];
    SUNDlsMat_denseGETRS(nw->col, na, nw->piv, nw->xa);
    for (int k = 0; k < na; k++)
        x[nw->act[k]] = nw->xa[k];
    for (int q = 0; q < nw->nr; q++) {
        int r = nw->rest[q];
        for (int k = 0; k < na; k++)
            x[r] -= S[nw->act[k] * N0 + r] * nw->xa[k];
    }
}

/* out (N0) += gamma sum_a G_ia dA_ia . w: gamma times the network's rates
 * along ring state w (-M_bi w). */
static void network_along(rd_ringpack_newton *nw, int i, const double *w, double *out)
{
    pring *pr = &nw->ring[i];
    double du, dl;
    rd_packring_area_slope(pr->L, nw->y + pr->off, w, &du, &dl);
    const double *Gu = nw->G + (size_t)nw->N0 * (2 * i), *Gl = Gu + nw->N0;
    for (int r = 0; r < nw->N0; r++)
        out[r] += nw->gamma * (Gu[r] * du + Gl[r] * dl);
}

/* d f_i / d p_k of ring i, p_k the state pressures its faces read (pv:
 * the network's pressures, g: its faces' gauge pressures from them).  The
 * forces are affine in the face pressures, and the faces in the state's
 * (rd_ringpack_faces: each its volume's, or with flank_pressure linear
 * averaged with the groove's); with fixed active areas their coefficients
 * are of the geometry alone, so the quotients are computed once, at the
 * first set-up, against CVODE's f(t, y); dynamic areas weight them by the
 * faces' sealing, a function of the state: then at every set-up. */
static int pressure_columns(rd_ringpack_newton *nw, int i, const double *pv, const double *g)
{
    pring *pr = &nw->ring[i];
    rd_ringpack_model *m = nw->m;
    const double *f0 = nw->fy + pr->off;
    double g1[3], pv1[RD_RINGPACK_VOLUMES_MAX];
    memcpy(pv1, pv, (size_t)(m->V + 2) * sizeof *pv1);
    for (int c = 0; c < pr->np; c++) {
        int v = pr->pcol[c] + 1, rc; /* the network index of the state pressure */
        double dp = 1e-3 * fmax(fabs(pv[v] - m->p->crankcase_pa), m->p->crankcase_pa);
        pv1[v] = pv[v] + dp;
        rd_ringpack_faces(m, i, nw->t, pv1, g1);
        pv1[v] = pv[v];
        rd_packring_gas(pr->L, g1);
        rc = rd_packring_rhs(pr->L, nw->t, (double *)nw->y + pr->off, pr->r1);
        rd_packring_gas(pr->L, g);
        if (rc)
            return rc;
        for (int k = 0; k < pr->N; k++)
            pr->D[c][k] = (pr->r1[k] - f0[k]) / dp;
    }
    pr->have_D = 1;
    return 0;
}

/* Ring i's own Newton matrix, its pressure columns X_ik, and their share
 * of the Schur complement. */
static int ring_block(rd_ringpack_newton *nw, int i, const double *pv)
{
    rd_ringpack_model *m = nw->m;
    pring *pr = &nw->ring[i];
    double g[3], *S = SM_DATA_D(nw->A);
    int rc;
    rd_ringpack_faces(m, i, nw->t, pv, g);
    rd_packring_gas(pr->L, g);
    if ((rc = rd_packring_solver_setup(pr->L, nw->t, (double *)nw->y + pr->off, nw->gamma)))
        return rc;
    if ((!pr->have_D || nw->m->p->active_area == RD_GAS_AREA_DYNAMIC) &&
        (rc = pressure_columns(nw, i, pv, g)))
        return rc;
    for (int c = 0; c < pr->np; c++) {
        for (int k = 0; k < pr->N; k++)
            pr->w[k] = -nw->gamma * pr->D[c][k];
        if ((rc = rd_packring_solver_solve(pr->L, pr->X[c], pr->w)))
            break;
        network_along(nw, i, pr->X[c], S + (size_t)pr->pcol[c] * nw->N0); /* -M_bi X_ik */
    }
    return rc;
}

int rd_ringpack_newton_linsys(rd_ringpack_newton *nw, double t, const double *y, const double *fy,
                              double gamma)
{
    rd_ringpack_model *m = nw->m;
    double area[2 * RD_RINGPACK_RINGS_MAX], pv[RD_RINGPACK_VOLUMES_MAX];
    nw->t = t;
    nw->y = y;
    nw->fy = fy;
    nw->gamma = gamma;
    rd_ringpack_areas(m, y, area);
    rd_ringpack_pressures(m, t, y, pv);
    network_block(nw, area);
    for (int i = 0; i < m->R; i++) {
        if (!m->lr[i])
            continue;
        int rc = ring_block(nw, i, pv);
        if (rc)
            return rc;
    }
    nw->info = factor_active(nw);
    return nw->info ? 1 : 0; /* singular: recoverable, CVODE cuts the step */
}

/* ------------------------------------------------------------ solver */

static SUNLinearSolver_Type pn_type(SUNLinearSolver LS)
{
    (void)LS;
    return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID pn_id(SUNLinearSolver LS)
{
    (void)LS;
    return SUNLINEARSOLVER_CUSTOM;
}

static int pn_initialize(SUNLinearSolver LS)
{
    (void)LS;
    return 0;
}

static int pn_setup(SUNLinearSolver LS, SUNMatrix A)
{
    (void)A;
    rd_ringpack_newton *nw = LS->content;
    return nw->info ? SUNLS_LUFACT_FAIL : 0;
}

/* x = M^-1 b by the elimination of the header comment. */
static int pn_solve(SUNLinearSolver LS, SUNMatrix A, N_Vector xv, N_Vector bv, sunrealtype tol)
{
    (void)A;
    (void)tol;
    rd_ringpack_newton *nw = LS->content;
    const double *b = N_VGetArrayPointer(bv);
    double *x = N_VGetArrayPointer(xv), *xb = x;
    int N0 = nw->N0, rc;
    memcpy(xb, b, (size_t)N0 * sizeof *xb);
    for (int i = 0; i < nw->m->R; i++) {
        pring *pr = &nw->ring[i];
        if (!pr->L)
            continue;
        if ((rc = rd_packring_solver_solve(pr->L, x + pr->off, (double *)b + pr->off)))
            return rc;
        network_along(nw, i, x + pr->off, xb);
    }
    solve_s(nw, xb);
    for (int i = 0; i < nw->m->R; i++) {
        pring *pr = &nw->ring[i];
        for (int c = 0; pr->L && c < pr->np; c++)
            for (int k = 0; k < pr->N; k++)
                x[pr->off + k] -= pr->X[c][k] * xb[pr->pcol[c]];
    }
    return 0;
}

static void ring_free(pring *pr)
{
    for (int c = 0; c < 3; c++)
        free(pr->X[c]);
    for (int c = 0; c < 3; c++)
        free(pr->D[c]);
    free(pr->r1);
    free(pr->w);
}

static int pn_free(SUNLinearSolver LS)
{
    if (!LS)
        return 0;
    rd_ringpack_newton *nw = LS->content;
    if (nw) {
        for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++)
            ring_free(&nw->ring[i]);
        free(nw->J);
        free(nw->G);
        free(nw);
        LS->content = NULL;
    }
    SUNLinSolFreeEmpty(LS);
    return 0;
}

/* Ring i's part: its own solver, views, scratch, pressure columns. */
static int ring_open(rd_ringpack_newton *nw, int i, SUNContext ctx)
{
    rd_ringpack_model *m = nw->m;
    pring *pr = &nw->ring[i];
    pr->L = m->lr[i];
    pr->N = (int)rd_packring_form(pr->L)->N;
    pr->off = m->off[i];

    pr->r1 = malloc((size_t)pr->N * sizeof(double));
    pr->w = malloc((size_t)pr->N * sizeof(double));
    if (rd_packring_solver_open(pr->L, ctx) || !pr->r1 || !pr->w)
        return -1;
    int cols[3] = {2 * i, 2 * i + 1, i + 1 < m->R ? 2 * i + 2 : -1};
    pr->np = 0;
    for (int f = 0; f < 3 && !m->p->face_tables; f++) {
        if (cols[f] < 0)
            continue;
        pr->pcol[pr->np] = cols[f];
        pr->X[pr->np] = malloc((size_t)pr->N * sizeof(double));
        pr->D[pr->np] = malloc((size_t)pr->N * sizeof(double));
        if (!pr->X[pr->np] || !pr->D[pr->np])
            return -1;
        pr->np++;
    }
    return 0;
}

/* The active unknowns (the header comment): the pressures and the axial
 * rings' z, z'; the rest: the cumulative masses, the lift rings' slots. */
static void active_set(rd_ringpack_newton *nw)
{
    const rd_ringpack_model *m = nw->m;
    nw->na = nw->nr = 0;
    for (int j = 0; j < nw->N0; j++) {
        int slot = j >= 2 * m->R && j < 4 * m->R, lifted = slot && m->lr[(j - 2 * m->R) / 2];
        if (j < 2 * m->R || (slot && !lifted))
            nw->act[nw->na++] = j;
        else
            nw->rest[nw->nr++] = j;
    }
    for (int c = 0; c < nw->na; c++)
        nw->col[c] = nw->Sa + (size_t)c * nw->na;
}

SUNLinearSolver rd_ringpack_newton_create(rd_ringpack_model *m, SUNContext ctx, SUNMatrix A,
                                          rd_ringpack_newton **out)
{
    static const struct _generic_SUNLinearSolver_Ops ops = {.gettype = pn_type,
                                                            .getid = pn_id,
                                                            .initialize = pn_initialize,
                                                            .setup = pn_setup,
                                                            .solve = pn_solve,
                                                            .free = pn_free};
    rd_ringpack_newton *nw = calloc(1, sizeof *nw);
    SUNLinearSolver LS = rd_linsol_wrap(ctx, nw, &ops);
    if (!LS) {
        free(nw);
        return NULL;
    }
    nw->m = m;
    nw->N0 = m->N0;
    nw->A = A;
    size_t N0 = (size_t)m->N0;
    nw->J = malloc(N0 * N0 * sizeof(double));
    nw->G = malloc(2 * RD_RINGPACK_RINGS_MAX * N0 * sizeof(double));
    int bad = !nw->J || !nw->G;
    for (int i = 0; !bad && i < m->R; i++)
        bad = m->lr[i] && ring_open(nw, i, ctx);
    if (bad) {
        pn_free(LS);
        return NULL;
    }
    active_set(nw);
    *out = nw;
    return LS;
}
