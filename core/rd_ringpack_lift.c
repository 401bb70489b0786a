/*
 * rd_ringpack_lift.c — a ring of the pack on one of the lift analysis'
 * models (numerics.model rigid, full or modal; rd_lift_model.h), coupled
 * both ways with the pack's gas network (rd_ringpack.h).
 *
 * The ring is the lift analysis' own: its rd_ring of n segments, its
 * rd_lift_model (geometry, mass, stiffness, force elements) and its form
 * (rd_lift_rigid_open, rd_lift_modal_open or the full model), built from a
 * rd_lift_params that carries the pack's engine, groove, gravity and
 * friction.  Its states are appended to the pack's (rd_ringpack_model.h)
 * and its right-hand side is the form's, called on them.
 *
 * Gas: the lift model's gas tables are replaced by the pack's pressures of
 * the moment (rd_lift_model.gas_now), gauge against the crankcase like the
 * lift analysis' tables: above = land_i, behind = groove_i, below = the
 * volume under the ring, each minus p_cc.  The axial load depends only on
 * differences, so the reference matters only for the back face's radial
 * push (and through it the friction's normal force), which the pack's axial
 * ring also takes as p_groove - p_cc.  The lift model's default contact
 * stiffness and velocity tolerances read the largest table pressure; the
 * lift parameters carry a two-point table holding the cylinder's peak
 * (gauge) on the top face for that rule only (gas_now overrides it in the
 * forces).
 *
 * Flank passages: from the per-segment lifts L_j (rd_lift_form.lift),
 *   A_upper = pi d / n sum_j clamp(a - L_j, 0, a),
 *   A_lower = pi d / n sum_j clamp(L_j, 0, a),
 * each segment's share of the circumference open by its own gap, so a ring
 * lifted on one side leaks there (the rigid model's L_j are all equal: the
 * axial ring's pi d (a - z), pi d z).  The clamp drops the contact
 * penalty's penetration (1e-3 a) from the seated ring's passage.
 *
 * Events: the lift analysis' definitions and state machine
 * (rd_lift_track_roots, its five roots on the mean lift and the load).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "rd_ringpack_model.h"

struct rd_packring {
    rd_ring *ring;
    rd_lift_params lp;
    double tab_deg[2], tab_top[2], tab_zero[2]; /* the stiffness rule's table */
    rd_lift_model m;
    rd_lift_form form;
    double gas[3];
    double *seg, *seg_w, *seg_0; /* n per-segment lifts (at y, along w, at 0: once) */
    double *zero;                /* the zero state */
    N_Vector ys, yd;             /* views on the ring's part of the pack's vectors */
    double circ;                 /* pi d */
    rd_lift_flank_track track;
    rd_lift_run events;
    /* its Newton solver: the second-order one (rd_lift_newton.c) for a form
     * with blocks, else CVODE's dense or band LU of I - gamma J from the
     * form's Jacobian, as the lift driver picks (rd_lift_driver.c) */
    SUNLinearSolver LS;
    SUNMatrix S, J; /* S: the second-order solver's (owned by LS); J: owned */
    rd_lift_newton *nw;
    N_Vector x, b, t1, t2, t3; /* views (x, b) and the Jacobian's scratch */
};

/* The lift parameters of pack ring i. */
static void lift_params(const rd_ringpack_model *m, int i, rd_packring *L)
{
    const rd_ringpack_params *p = m->p;
    rd_lift_params *lp = &L->lp;
    rd_lift_params_default(lp);
    lp->engine = p->engine;
    lp->groove = p->rings[i].groove;
    lp->gravity = p->gravity;
    lp->friction = p->friction;
    lp->rtol = p->rtol;
    lp->atol = p->atol;
    lp->max_steps = p->max_steps;
    lp->estimate_error = 0;
    lp->model = m->kind[i];
    lp->modes = p->rings[i].modes;
    double peak = 0.0;
    for (int k = 0; k < m->cyl_n; k++)
        peak = fmax(peak, m->cyl_pa[k] - p->crankcase_pa);
    L->tab_deg[0] = 0.0;
    L->tab_deg[1] = 720.0;
    L->tab_top[0] = L->tab_top[1] = peak;
    L->tab_zero[0] = L->tab_zero[1] = 0.0;
    lp->gas =
        (rd_gas_params){2, L->tab_deg, L->tab_top, L->tab_zero, L->tab_zero, RD_GAS_AREA_FIXED};
}

int rd_packring_open(rd_ringpack_model *m, int i, SUNContext ctx, int *N, int *modes_out, double *k,
                     rd_error *err)
{
    const rd_ringpack_ring *pr = &m->p->rings[i];
    rd_packring *L = calloc(1, sizeof *L);
    if (!L)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's lift model.", i + 1);
    m->lr[i] = L;
    lift_params(m, i, L);
    int n = pr->segments;
    int modes = pr->modes ? pr->modes : (12 < 6 * n - 6 ? 12 : 6 * n - 6);
    int rc = rd_lift_validate(&L->lp, &pr->ring, n, err);
    if (rc)
        return rc;
    L->ring = rd_ring_create(&pr->ring, n, 0, err);
    if (!L->ring)
        return err ? err->code : RD_ENOMEM;
    if ((rc = rd_lift_model_init(&L->m, L->ring, &L->lp, NULL, err)) ||
        (rc = rd_lift_form_open(&L->m, m->kind[i], modes, &L->form, err)))
        return rc;
    L->m.gas_now = L->gas;
    L->circ = M_PI * pr->ring.diameter;
    L->seg = malloc(3 * (size_t)n * sizeof *L->seg);
    L->zero = calloc((size_t)L->form.N, sizeof *L->zero);
    L->seg_w = L->seg ? L->seg + n : NULL;
    L->seg_0 = L->seg ? L->seg + 2 * n : NULL;
    L->ys = N_VMake_Serial(L->form.N, NULL, ctx);
    L->yd = N_VMake_Serial(L->form.N, NULL, ctx);
    if (!L->seg || !L->zero || !L->ys || !L->yd)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's lift model.", i + 1);
    L->form.lift(L->form.user, L->zero, L->seg_0);
    L->track = (rd_lift_flank_track){RD_FLANK_LOWER, NAN};
    *N = (int)L->form.N;
    *modes_out = modes;
    *k = L->m.k;
    return RD_OK;
}

void rd_packring_close(rd_packring *L)
{
    if (!L)
        return;
    if (L->form.close)
        L->form.close(&L->form);
    rd_lift_model_cleanup(&L->m);
    rd_ring_free(L->ring);
    if (L->LS)
        SUNLinSolFree(L->LS);
    if (L->J)
        SUNMatDestroy(L->J);
    N_Vector v[] = {L->ys, L->yd, L->x, L->b, L->t1, L->t2, L->t3};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (v[k])
            N_VDestroy(v[k]);
    free(L->seg);
    free(L->zero);
    free(L->events.events);
    free(L);
}

rd_lift_form *rd_packring_form(rd_packring *L)
{
    return &L->form;
}

int rd_packring_initial(rd_packring *L, double atol, double *y, double *ab, rd_error *err)
{
    return L->form.initial(L->form.user, NULL, atol, y, ab, err);
}

void rd_packring_gas(rd_packring *L, const double g[3])
{
    memcpy(L->gas, g, sizeof L->gas);
}

int rd_packring_rhs(rd_packring *L, double t, double *y, double *yd)
{
    N_VSetArrayPointer(y, L->ys);
    N_VSetArrayPointer(yd, L->yd);
    return L->form.rhs(t, L->ys, L->yd, L->form.user);
}

/* fmin(fmax(x, 0), a) without the library calls (a step of every
 * right-hand side and root function; NaN gives 0 as there). */
static double clamp(double x, double a)
{
    return x > 0.0 ? (x < a ? x : a) : 0.0;
}

/* The form's per-segment lifts at y into seg and their mean; a form whose
 * segments all lift alike (form.uniform: the rigid ring) gives the mean
 * only, and the loops below add that one value n times: the same sums as
 * over n equal entries, so the same areas to the last bit, without n
 * entries to fill and read at every right-hand side. */
static double lifts(rd_packring *L, const double *y, double *seg)
{
    return L->form.lift(L->form.user, y, L->form.uniform ? NULL : seg);
}

double rd_packring_areas(rd_packring *L, const double *y, double *up, double *lo)
{
    double mean = lifts(L, y, L->seg), a = L->m.ca, su = 0.0, sl = 0.0;
    int n = L->m.n;
    if (L->form.uniform) {
        double cu = clamp(a - mean, a), cl = clamp(mean, a);
        for (int j = 0; j < n; j++) {
            su += cu;
            sl += cl;
        }
    } else {
        for (int j = 0; j < n; j++) {
            su += clamp(a - L->seg[j], a);
            sl += clamp(L->seg[j], a);
        }
    }
    *up = L->circ * su / n;
    *lo = L->circ * sl / n;
    return mean;
}

void rd_packring_area_slope(rd_packring *L, const double *y, const double *w, double *du,
                            double *dl)
{
    double a = L->m.ca, su = 0.0, sl = 0.0;
    int n = L->m.n, u = L->form.uniform;
    double L_y = lifts(L, y, L->seg), L_w = lifts(L, w, L->seg_w); /* seg_0: at open */
    for (int j = 0; j < n; j++) {
        double s = u ? L_y : L->seg[j], open = s > 0.0 && s < a ? 1.0 : 0.0;
        double dL = (u ? L_w : L->seg_w[j]) - L->seg_0[j];
        su -= open * dL;
        sl += open * dL;
    }
    *du = L->circ * su / n;
    *dl = L->circ * sl / n;
}

void rd_packring_loads(rd_packring *L, double t, const double *y, double *fz, double *friction)
{
    L->form.loads(L->form.user, t, y);
    *fz = L->m.fz_ext;
    *friction = L->m.friction;
}

double rd_packring_eps(const rd_packring *L)
{
    return L->m.eps;
}

rd_lift_flank_track *rd_packring_track(rd_packring *L)
{
    return &L->track;
}

rd_lift_run *rd_packring_events(rd_packring *L)
{
    return &L->events;
}

int rd_packring_solver_open(rd_packring *L, SUNContext ctx)
{
    sunindextype N = L->form.N;
    L->x = N_VMake_Serial(N, NULL, ctx);
    L->b = N_VMake_Serial(N, NULL, ctx);
    if (!L->x || !L->b)
        return -1;
    if (L->form.blocks) {
        L->LS = rd_lift_newton_create(&L->form, ctx, &L->S, &L->nw);
        return L->LS ? SUNLinSolInitialize(L->LS) : -1;
    }
    L->t1 = N_VNew_Serial(N, ctx);
    L->t2 = N_VNew_Serial(N, ctx);
    L->t3 = N_VNew_Serial(N, ctx);
    L->J =
        L->form.dense ? SUNDenseMatrix(N, N, ctx) : SUNBandMatrix(N, RD_LIFT_MU, RD_LIFT_ML, ctx);
    if (!L->t1 || !L->t2 || !L->t3 || !L->J)
        return -1;
    L->LS = L->form.dense ? SUNLinSol_Dense(L->t1, L->J, ctx) : SUNLinSol_Band(L->t1, L->J, ctx);
    L->S = L->J;
    return L->LS ? SUNLinSolInitialize(L->LS) : -1;
}

int rd_packring_solver_setup(rd_packring *L, double t, double *y, double gamma)
{
    int cur = 0, rc;
    N_VSetArrayPointer(y, L->b);
    if (L->nw)
        rc = rd_lift_newton_linsys(L->nw, t, L->b, 0, &cur, gamma);
    else if (!(rc = L->form.rhs(t, L->b, L->t1, L->form.user)) &&
             !(rc = L->form.jac(t, L->b, L->t1, L->J, L->form.user, L->x, L->t2, L->t3)))
        rc = SUNMatScaleAddI(-gamma, L->J);
    return rc ? rc : SUNLinSolSetup(L->LS, L->S);
}

int rd_packring_solver_solve(rd_packring *L, double *x, double *b)
{
    N_VSetArrayPointer(x, L->x);
    N_VSetArrayPointer(b, L->b);
    return SUNLinSolSolve(L->LS, L->S, L->x, L->b, 0.0);
}
