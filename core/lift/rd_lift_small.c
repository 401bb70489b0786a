/*
 * rd_lift_small.c — a one-step implicit integrator for the small lift forms
 * (the rigid model: 3 + 3 states), in place of CVODE whose bookkeeping for
 * vectors, matrices and history costs more than the model's forces there.
 *
 * Method: TR-BDF2 (R. E. Bank et al., IEEE Trans. CAD 4, 1985; in the form
 * of M. E. Hosea and L. F. Shampine, Appl. Numer. Math. 20, 1996), L-stable,
 * second order.  For y' = f(t, y), a step of size h from (t, y_n):
 *     trapezoid to t + g h:  z   - d h f(z)   = y_n + d h f_n
 *     BDF2 to t + h:         y_1 - d h f(y_1) = y_n + w h (f_n + f_z)
 * with g = 2 - sqrt 2, d = g / 2, w = sqrt 2 / 4.  Both stages share the
 * Newton matrix I - d h J.  f_z and f_1 come from the stage equations,
 * f = (x - rhs) / (d h), so a stage costs its Newton iterations only (the
 * forces at the end state would carry the stiff contacts' transients into
 * the error estimate: the error test then failed in the seated phases).
 *
 * Newton.  Predictors: the last step's interpolant (extended by at most one
 * step) for the trapezoid stage, the quadratic through y_n, h f_n and z for
 * the BDF2 stage.  Converged when the correction's norm times rate / (1 -
 * rate) is <= 0.01 of the error tolerance; a first correction counts only
 * when it is <= 0.001: with the stiff, kinked contact laws the Jacobian at
 * y_n can be far from the one at the stage, the first correction then
 * proves nothing, and the stage derivatives taken from the formula carry
 * the unconverged part (measured on thesis_lift_1000rpm: a test at 0.1 of
 * the tolerance moved landings by 0.4 deg, one that trusted a rate kept
 * from earlier steps by 4 deg; at 0.01 they agree with 0.001 within 2e-4
 * deg).  J = df/dy is evaluated at the start of a step and kept for at
 * most 2 further steps while Newton converges at a rate <= 0.3 with it; it
 * is re-evaluated after any failed attempt, and a kept one that fails to
 * converge is replaced at the same step size (a matrix kept from a closed
 * contact carries its stiffness after it opened: the CVODE path evaluates
 * it every step for that reason).
 * Error: the difference to the embedded third-order solution
 *     y_n + h ((1 - w) f_n + (3 w + 1) f_z + d f_1) / 3
 * is e = h ((1 - 4 w) f_n + f_z - 2 d f_1) / 3, filtered by (I - d h J)^-1
 * (Hosea-Shampine: bounded for stiff components), measured in CVODE's
 * weighted RMS norm (weights 1 / (rtol |y_n| + atol)), accepted at <= 1;
 * the next step is h (0.9 / err)^(1/3), within 0.2 h .. 5 h and hmax.
 *
 * Second-order form: y = (q, v) with q' = v (the form's one block of `nb`
 * positions), so J = [0 I; A B] and (I - c J) x = r is solved as
 * (I - c B - c^2 A) x_v = r_v + c A r_q, x_q = r_q + c x_v: one nb x nb LU.
 *
 * Output and events: cubic Hermite interpolation over the last step (y, f
 * at both ends).  Root functions are checked at every step end; a sign
 * change in an allowed direction is located on the interpolant (Illinois,
 * to CVODE's time tolerance 100 eps (|t| + |h|)), as CVODE does.  The
 * step that crosses a leave is checked by the error test like any other, so
 * the seated phases need no step bound (rd_lift_driver.c); redoing steps to
 * end at every root was tried and changed flank changes by < 3e-4 deg for
 * 8 % more steps.
 */
#include "rd_lift_small.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>

#define NMAX        (2 * RD_LIFT_SMALL_BLOCK_MAX)
#define BMAX        RD_LIFT_SMALL_BLOCK_MAX
#define RMAX        RD_LIFT_SMALL_ROOTS_MAX
#define NEWTON_MAX  4    /* iterations per stage */
#define NEWTON_TOL  0.01 /* converged correction, in units of the error tolerance */
#define FAIL_MAX    12   /* failed attempts in a row before giving up */
#define ROOT_ITER   60   /* Illinois iterations (superlinear: ~10 reach the tolerance) */
#define JAC_AGE_MAX 2    /* steps a Jacobian is kept while Newton converges fast */
#define RATE_STALE  0.3  /* the convergence rate a kept Jacobian must show */

static const double GAM = 0.58578643762690495; /* 2 - sqrt 2 */
static const double DCO = 0.29289321881345248; /* g / 2 */
static const double WCO = 0.35355339059327376; /* sqrt 2 / 4 */

struct rd_lift_small {
    const rd_lift_form *form;
    int N, nb, ng;
    double rtol, atol[NMAX], hmax;
    CVRootFn g;
    void *gu;
    int rootdir[RMAX], rf[RMAX];
    double t, h;                      /* time reached, next step size */
    double y[NMAX], f[NMAX];          /* state and derivative at t */
    double wt[NMAX];                  /* 1 / (rtol |y| + atol): the weights at t */
    double tp, yp[NMAX], fp[NMAX];    /* the last step's start */
    double tlo, glo[RMAX], ghi[RMAX]; /* roots searched up to tlo; g at tlo and t */
    double A[3 * BMAX * BMAX], B[BMAX * BMAX], S[BMAX * BMAX];
    int piv[BMAX];
    double c_lu; /* the d h of the factorization in S, 0: none */
    int jac_age; /* steps since A, B were evaluated (at the start of a step); -1: none */
    double ybuf[NMAX], fbuf[NMAX];
    N_Vector vy, vf; /* wrappers of ybuf, fbuf for the form's and the root callbacks */
    long mxstep;
    long c[8]; /* counters (rd_lift_small_counters) */
};

enum { C_STEPS, C_RHS, C_JAC, C_SETUPS, C_NITER, C_NFAIL, C_ETFAIL, C_GEVALS };

int rd_lift_small_usable(const rd_lift_form *form)
{
    return form->blocks && form->block >= 1 && form->block <= BMAX &&
           form->N == 2 * (sunindextype)form->block;
}

/* ----------------------------------------------------------- callbacks */

static int rhs(rd_lift_small *s, double t, const double *x, double *fx)
{
    memcpy(s->ybuf, x, (size_t)s->N * sizeof *x);
    s->c[C_RHS]++;
    if (s->form->rhs(t, s->vy, s->vf, s->form->user))
        return 1;
    memcpy(fx, s->fbuf, (size_t)s->N * sizeof *fx);
    return 0;
}

static int groots(rd_lift_small *s, double t, const double *x, double *gx)
{
    memcpy(s->ybuf, x, (size_t)s->N * sizeof *x);
    s->c[C_GEVALS]++;
    return s->g(t, s->vy, gx, s->gu);
}

/* ------------------------------------------------------- linear algebra */

/* The rigid model's block size: factor() and lsolve() are compiled for it
 * separately (constant n: the loops unrolled, ~2x fewer instructions for
 * its 3 x 3 system). */
#define NB_RIGID 3

/* S = I - c B - c^2 A_diag, LU with partial pivoting; 1 if singular. */
static inline int factor_n(rd_lift_small *s, int n, double c)
{
    const double *Ad = s->A + n * n;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            s->S[n * i + j] = (i == j) - c * s->B[n * i + j] - c * c * Ad[n * i + j];
    s->c[C_SETUPS]++;
    s->c_lu = 0.0;
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(s->S[n * i + k]) > fabs(s->S[n * p + k]))
                p = i;
        s->piv[k] = p;
        if (s->S[n * p + k] == 0.0)
            return 1;
        if (p != k)
            for (int j = 0; j < n; j++) {
                double tmp = s->S[n * k + j];
                s->S[n * k + j] = s->S[n * p + j];
                s->S[n * p + j] = tmp;
            }
        for (int i = k + 1; i < n; i++) {
            double l = s->S[n * i + k] /= s->S[n * k + k];
            for (int j = k + 1; j < n; j++)
                s->S[n * i + j] -= l * s->S[n * k + j];
        }
    }
    s->c_lu = c;
    return 0;
}

static int factor(rd_lift_small *s, double c)
{
    return s->nb == NB_RIGID ? factor_n(s, NB_RIGID, c) : factor_n(s, s->nb, c);
}

/* x = (I - c J)^-1 r in second-order form (file comment); x may be r. */
static inline void lsolve_n(const rd_lift_small *s, int n, const double *r, double *x)
{
    double c = s->c_lu, v[BMAX];
    const double *Ad = s->A + n * n;
    for (int i = 0; i < n; i++) {
        v[i] = r[n + i];
        for (int j = 0; j < n; j++)
            v[i] += c * Ad[n * i + j] * r[j];
    }
    for (int k = 0; k < n; k++) {
        int p = s->piv[k];
        double tmp = v[k];
        v[k] = v[p];
        v[p] = tmp;
        for (int i = k + 1; i < n; i++)
            v[i] -= s->S[n * i + k] * v[k];
    }
    for (int i = n - 1; i >= 0; i--) {
        for (int j = i + 1; j < n; j++)
            v[i] -= s->S[n * i + j] * v[j];
        v[i] /= s->S[n * i + i];
    }
    for (int i = 0; i < n; i++) {
        x[i] = r[i] + c * v[i];
        x[n + i] = v[i];
    }
}

static void lsolve(const rd_lift_small *s, const double *r, double *x)
{
    if (s->nb == NB_RIGID)
        lsolve_n(s, NB_RIGID, r, x);
    else
        lsolve_n(s, s->nb, r, x);
}

/* Weighted RMS norm of e with the weights of state y (and y2 if not NULL:
 * the larger magnitude). */
static double wrms(const rd_lift_small *s, const double *e, const double *y, const double *y2)
{
    double sum = 0.0;
    for (int i = 0; i < s->N; i++) {
        double a = fabs(y[i]);
        if (y2)
            a = fmax(a, fabs(y2[i]));
        double w = e[i] / (s->rtol * a + s->atol[i]);
        sum += w * w;
    }
    return sqrt(sum / s->N);
}

/* The weights of the state at t, for the Newton corrections' norm: one set
 * per step instead of N divisions per Newton iteration (a correction's
 * norm may differ from wrms's in the last bit). */
static void set_weights(rd_lift_small *s)
{
    for (int i = 0; i < s->N; i++)
        s->wt[i] = 1.0 / (s->rtol * fabs(s->y[i]) + s->atol[i]);
}

/* wrms(s, e, s->y, NULL) with the step's weights. */
static double wnorm(const rd_lift_small *s, const double *e)
{
    double sum = 0.0;
    for (int i = 0; i < s->N; i++) {
        double w = e[i] * s->wt[i];
        sum += w * w;
    }
    return sqrt(sum / s->N);
}

/* A step's ends, for its interpolant. */
typedef struct span {
    double t0, t1;
    const double *y0, *f0, *y1, *f1;
} span;

static span last_step(const rd_lift_small *s)
{
    return (span){s->tp, s->t, s->yp, s->fp, s->y, s->f};
}

/* Cubic Hermite interpolation over a step at tt. */
static void interp(const rd_lift_small *s, const span *sp, double tt, double *out)
{
    double H = sp->t1 - sp->t0;
    if (H <= 0.0) {
        memcpy(out, sp->y1, (size_t)s->N * sizeof *out);
        return;
    }
    double u = (tt - sp->t0) / H, u2 = u * u, u3 = u2 * u;
    double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int i = 0; i < s->N; i++)
        out[i] = h00 * sp->y0[i] + h10 * H * sp->f0[i] + h01 * sp->y1[i] + h11 * H * sp->f1[i];
}

/* ----------------------------------------------------------------- step */

/* Solves x - c f(ts, x) = b by Newton from the predictor in x; 0 when
 * converged, 1 when not (or the forces were not finite). */
static int newton(rd_lift_small *s, double ts, const double *b, double *x)
{
    double fx[NMAX], r[NMAX], prev = 0.0;
    for (int k = 0; k < NEWTON_MAX; k++) {
        if (rhs(s, ts, x, fx))
            return 1;
        for (int i = 0; i < s->N; i++)
            r[i] = b[i] + s->c_lu * fx[i] - x[i];
        lsolve(s, r, r);
        for (int i = 0; i < s->N; i++)
            x[i] += r[i];
        s->c[C_NITER]++;
        double nd = wnorm(s, r);
        if (!isfinite(nd))
            return 1;
        if (k > 0) {
            double rate = nd / prev;
            if (rate > (s->jac_age > 0 ? RATE_STALE : 0.9))
                return 1;
            if (nd * rate / (1.0 - rate) <= NEWTON_TOL)
                return 0;
        } else if (nd <= 0.1 * NEWTON_TOL) { /* a first correction proves little (file comment) */
            return 0;
        }
        prev = nd;
    }
    return 1;
}

/* One attempt of size h from (t, y): the new state and its derivative into
 * y1, f1, the error norm into *err.  0, or 1 when a stage's Newton failed. */
static int attempt(rd_lift_small *s, double h, double *y1, double *f1, double *err)
{
    int N = s->N;
    double c = DCO * h, z[NMAX], fz[NMAX], b[NMAX], e[NMAX];
    if (s->jac_age < 0) {
        s->form->blocks(s->form->user, s->t, s->y, s->A, s->B);
        s->c[C_JAC]++;
        s->jac_age = 0;
        s->c_lu = 0.0;
    }
    if (s->c_lu != c && factor(s, c))
        return 1;
    for (int i = 0; i < N; i++) {
        b[i] = s->y[i] + c * s->f[i];
        z[i] = s->y[i] + GAM * h * s->f[i];
    }
    if (s->tp < s->t && GAM * h <= s->t - s->tp) { /* the last step's interpolant, extended */
        span sp = last_step(s);
        interp(s, &sp, s->t + GAM * h, z);
    }
    if (newton(s, s->t + GAM * h, b, z))
        return s->jac_age > 0 ? 2 : 1;
    for (int i = 0; i < N; i++) {
        fz[i] = (z[i] - b[i]) / c;
        /* quadratic through y_n, h f_n and z, at the step end */
        y1[i] = s->y[i] + h * s->f[i] + (z[i] - s->y[i] - GAM * h * s->f[i]) / (GAM * GAM);
        b[i] = s->y[i] + WCO * h * (s->f[i] + fz[i]);
    }
    if (newton(s, s->t + h, b, y1))
        return s->jac_age > 0 ? 2 : 1;
    for (int i = 0; i < N; i++)
        f1[i] = (y1[i] - b[i]) / c;
    for (int i = 0; i < N; i++)
        e[i] = h * ((1.0 - 4.0 * WCO) * s->f[i] + fz[i] - 2.0 * DCO * f1[i]) / 3.0;
    lsolve(s, e, e);
    *err = wrms(s, e, s->y, y1);
    return 0;
}

/* ----------------------------------------------------------------- roots */

static int crossing(const rd_lift_small *s, int i, double a, double b)
{
    if (a < 0.0 && b >= 0.0)
        return s->rootdir[i] >= 0 ? +1 : 0;
    if (a > 0.0 && b <= 0.0)
        return s->rootdir[i] <= 0 ? -1 : 0;
    return 0;
}

/* CVODE's time tolerance of root location over a step. */
static double root_ttol(const span *sp)
{
    return 100.0 * DBL_EPSILON * (fabs(sp->t1) + fabs(sp->t1 - sp->t0));
}

/* The root of g_i in (ta, tb] on the step's interpolant (Illinois),
 * returned as the right end of the final bracket. */
static double locate(rd_lift_small *s, const span *sp, int i, double ta, double ga, double tb,
                     double gb)
{
    double ttol = root_ttol(sp), x[NMAX], g[RMAX];
    int side = 0;
    for (int it = 0; it < ROOT_ITER && tb - ta > ttol; it++) {
        double tm = tb - gb * (tb - ta) / (gb - ga);
        tm = fmin(fmax(tm, ta + 0.5 * ttol), tb - 0.5 * ttol);
        interp(s, sp, tm, x);
        if (groots(s, tm, x, g))
            break;
        if ((g[i] > 0.0) == (ga > 0.0)) {
            ta = tm;
            ga = g[i];
            if (side == -1)
                gb *= 0.5;
            side = -1;
        } else {
            tb = tm;
            gb = g[i];
            if (side == +1)
                ga *= 0.5;
            side = +1;
        }
    }
    return tb;
}

/* The earliest root in (tlo, sp->t1] given g at both ends, or INFINITY if
 * none; sets rf for every function whose root is within the time tolerance
 * of the earliest. */
static double earliest_root(rd_lift_small *s, const span *sp, double tlo, const double *glo,
                            const double *ghi)
{
    double best = INFINITY, at[RMAX], ttol = root_ttol(sp);
    for (int i = 0; i < s->ng; i++) {
        at[i] = INFINITY;
        if (crossing(s, i, glo[i], ghi[i])) {
            at[i] = locate(s, sp, i, tlo, glo[i], sp->t1, ghi[i]);
            best = fmin(best, at[i]);
        }
    }
    for (int i = 0; i < s->ng; i++)
        s->rf[i] = at[i] <= best + ttol ? crossing(s, i, glo[i], ghi[i]) : 0;
    return best;
}

/* ------------------------------------------------------------ public */

rd_lift_small *rd_lift_small_create(const rd_lift_form *form, SUNContext ctx, double t0,
                                    const double *y0, double rtol, const double *abstol,
                                    double hmax, int ng, CVRootFn g, const int *rootdir, void *user)
{
    if (!rd_lift_small_usable(form) || ng > RMAX)
        return NULL;
    rd_lift_small *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->form = form;
    s->N = (int)form->N;
    s->nb = form->block;
    s->ng = ng;
    s->rtol = rtol;
    memcpy(s->atol, abstol, (size_t)s->N * sizeof *abstol);
    s->hmax = hmax;
    s->g = g;
    s->gu = user;
    memcpy(s->rootdir, rootdir, (size_t)ng * sizeof *rootdir);
    s->mxstep = 500;
    s->vy = N_VMake_Serial(s->N, s->ybuf, ctx);
    s->vf = N_VMake_Serial(s->N, s->fbuf, ctx);
    if (!s->vy || !s->vf || rd_lift_small_reinit(s, t0, y0)) {
        rd_lift_small_free(s);
        return NULL;
    }
    return s;
}

void rd_lift_small_free(rd_lift_small *s)
{
    if (!s)
        return;
    if (s->vy)
        N_VDestroy(s->vy);
    if (s->vf)
        N_VDestroy(s->vf);
    free(s);
}

int rd_lift_small_reinit(rd_lift_small *s, double t, const double *y)
{
    s->t = s->tp = s->tlo = t;
    memcpy(s->y, y, (size_t)s->N * sizeof *y);
    memcpy(s->yp, y, (size_t)s->N * sizeof *y);
    set_weights(s);
    s->jac_age = -1;
    s->c_lu = 0.0;
    if (rhs(s, t, s->y, s->f) || groots(s, t, s->y, s->glo))
        return CV_RHSFUNC_FAIL;
    memcpy(s->fp, s->f, (size_t)s->N * sizeof *s->f);
    memcpy(s->ghi, s->glo, (size_t)s->ng * sizeof *s->glo);
    /* first step: the rates move by 1 % of their tolerance */
    double nf = wrms(s, s->f, s->y, NULL);
    s->h = nf > 0.0 ? fmin(s->hmax, 0.01 / nf) : s->hmax;
    return CV_SUCCESS;
}

void rd_lift_small_set_max_steps(rd_lift_small *s, long max_steps)
{
    s->mxstep = max_steps;
}

/* Accepts the attempted step to t + h (state y1, f1, roots g1). */
static void accept(rd_lift_small *s, double h, const double *y1, const double *f1, const double *g1)
{
    size_t nb = (size_t)s->N * sizeof *y1;
    s->tp = s->t;
    memcpy(s->yp, s->y, nb);
    memcpy(s->fp, s->f, nb);
    s->t += h;
    s->tlo = s->tp;
    memcpy(s->y, y1, nb);
    memcpy(s->f, f1, nb);
    set_weights(s);
    memcpy(s->ghi, g1, (size_t)s->ng * sizeof *g1);
    s->jac_age = s->jac_age >= 0 && s->jac_age < JAC_AGE_MAX ? s->jac_age + 1 : -1;
    s->c[C_STEPS]++;
}

/* One step from (t, y), ending at a root found well inside it (file
 * comment); CV_SUCCESS or a failure flag. */
static int step(rd_lift_small *s)
{
    double y1[NMAX], f1[NMAX], g1[RMAX], err = 0.0;
    int fails = 0, rejected = 0;
    for (;;) {
        double h = fmin(s->h, s->hmax);
        if (h < 10.0 * DBL_EPSILON * fmax(fabs(s->t), 1e-3))
            return CV_ERR_FAILURE;
        int a = attempt(s, h, y1, f1, &err);
        if (a == 2) { /* a kept Jacobian did not converge: a fresh one, same h */
            s->jac_age = -1;
            continue;
        }
        if (a || !isfinite(err)) {
            s->c[C_NFAIL]++;
            s->h = 0.25 * h;
            if (++fails > FAIL_MAX)
                return CV_CONV_FAILURE;
            rejected = 1;
            continue;
        }
        if (err > 1.0) {
            s->c[C_ETFAIL]++;
            if (s->jac_age > 0)
                s->jac_age = -1;
            s->h = h * fmax(0.2, 0.9 * pow(err, -1.0 / 3.0));
            if (++fails > FAIL_MAX)
                return CV_ERR_FAILURE;
            rejected = 1;
            continue;
        }
        if (groots(s, s->t + h, y1, g1))
            return CV_RHSFUNC_FAIL;
        double fac = err > 0.0 ? fmin(5.0, 0.9 * pow(err, -1.0 / 3.0)) : 5.0;
        if (rejected)
            fac = fmin(fac, 1.0);
        accept(s, h, y1, f1, g1);
        if (rejected)
            s->jac_age = -1;
        s->h = h * fac;
        return CV_SUCCESS;
    }
}

int rd_lift_small_solve(rd_lift_small *s, double tout, double *y, double *t)
{
    long taken = 0;
    for (;;) {
        /* roots in what is left of the last step; one after tout waits (CVODE's order) */
        if (s->tlo < s->t) {
            span sp = last_step(s);
            double tr = earliest_root(s, &sp, s->tlo, s->glo, s->ghi);
            if (tr <= s->t && tr <= tout) {
                interp(s, &sp, tr, y);
                if (groots(s, tr, y, s->glo))
                    return CV_RHSFUNC_FAIL;
                s->tlo = tr;
                *t = tr;
                return CV_ROOT_RETURN;
            }
            if (tr > s->t) {
                s->tlo = s->t;
                memcpy(s->glo, s->ghi, (size_t)s->ng * sizeof *s->ghi);
            }
        }
        if (s->t >= tout) {
            span sp = last_step(s);
            interp(s, &sp, tout, y);
            *t = tout;
            return CV_SUCCESS;
        }
        if (taken >= s->mxstep) {
            memcpy(y, s->y, (size_t)s->N * sizeof *y);
            *t = s->t;
            return CV_TOO_MUCH_WORK;
        }
        int flag = step(s);
        if (flag != CV_SUCCESS) {
            memcpy(y, s->y, (size_t)s->N * sizeof *y);
            *t = s->t;
            return flag;
        }
        taken++;
    }
}

void rd_lift_small_root_info(const rd_lift_small *s, int *rf)
{
    memcpy(rf, s->rf, (size_t)s->ng * sizeof *rf);
}

double rd_lift_small_time(const rd_lift_small *s)
{
    return s->t;
}

void rd_lift_small_counters(const rd_lift_small *s, long *c)
{
    memcpy(c, s->c, sizeof s->c);
}
