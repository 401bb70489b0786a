/*
 * rd_lift_driver.c — the CVODE driver of the full lift model (file map:
 * rd_lift_model.h): integrator set-up, events (root finding and the flank
 * state machine), output sampling, solver counters, the work bound, progress
 * and cancellation.  The rigid form is stepped by rd_lift_small.c instead
 * (CVODE's calls, small_open), unless the sticking phase or rd_lift_params
 * .cvode asks for CVODE.
 *
 * Integration: SUNDIALS CVODE, BDF of order <= 2, Newton with the analytic
 * Jacobian's blocks, the system solved in second-order form by block-
 * tridiagonal LU of half the size (rd_lift_newton.c, rd_blocktri.c), so
 * each step costs O(n).  Order <= 2: the undamped elastic modes of a finely
 * cut ring are fast and on the imaginary axis, where BDF3-5 are unstable
 * (n = 200 took 70x more steps); BDF2 is A-stable.  The Jacobian is re-evaluated and
 * factored at every step: a Newton matrix kept from a closed contact carries
 * that penalty's stiffness after the contact opened, and the modified Newton
 * iteration then converges falsely and holds the ring on the flank (landings
 * came 5-40 deg late with CVODE's default reuse; with any reuse the tests'
 * 1-DOF and stiffness checks fail at rtol 1e-6).  Tolerances: rtol; atol on
 * the translations (m), atol / R on the rotations, and atol w_v on their
 * rates with w_v = sqrt(a_ref / c_a), the rate of a flight across the
 * clearance under the scene's largest acceleration a_ref.  Steps <= 1 crank
 * degree, so no gas-table feature or short contact is stepped over.
 *
 * Work bound and cancellation: CVODE is called with at most STEP_CHUNK / n
 * steps per call (about 45 ms: a step costs ~22 us per segment, issue 10's
 * measurement), so the monitor is asked between chunks and a cancel takes
 * effect within ~0.1 s even when one output interval takes thousands of
 * steps; an interrupted call is resumed where it stopped (the chunking does
 * not change the steps taken).  When /numerics/max_steps runs out the error
 * names the crank angle the integrator really reached (CVODE's current time).
 *
 * Events: the ring's mean lift L (mean over segments of the bottom face's
 * axial position above the lower flank) and F, the total axial force on the
 * ring without the flank contacts (inertia, gravity, gas, friction; the
 * elastic forces sum to zero).  CVODE locates the roots of L (landing on the
 * lower flank), L - eps, c_a - L (landing on the upper flank), c_a - L - eps
 * (eps = 1e-2 c_a) and F.  A landing is dated where L reaches the flank.  A
 * leave is dated where F turns away from the flank (the 1-DOF definition:
 * a seated ring separates with zero velocity and acceleration, so the
 * geometric separation time is ill-conditioned, ~(6 atol / jerk)^(1/3) =
 * 0.3 deg at 1000 rpm), and confirmed only when L has moved eps off the
 * flank; if F turns back first, nothing is reported.  So hops lower than 1 %
 * of the clearance (micro-bounces, the penalty's settling, an edge lifting
 * under a twist) are not flank changes.  A sample's flank: lower if L < eps,
 * upper if L > c_a - eps, else free.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "rd_cvode.h"
#include "rd_lift_model.h"
#include "rd_lift_small.h"
#include "rd_lift_stick.h"

#define Q          RD_LIFT_Q
#define V          RD_LIFT_V
#define HMAX_DEG   1.0  /* largest step, crank degrees */
#define HMAX_SMALL 10.0 /* largest step of rd_lift_small without a gas table, deg */
#define MAX_ORDER  2    /* BDF order bound (header comment) */
#define STEP_CHUNK 2000 /* segment-steps between monitor calls (header comment) */
#define N_ROOTS    5
#define N_COUNTERS 8 /* the solver counters of rd_lift_result */

/* One integration's solver objects and bookkeeping. */
typedef struct driver {
    rd_lift_model m;
    rd_lift_form form; /* what is integrated: the full model or a reduced one */
    double *full;      /* 12 n: the full state of a sample (reduced forms) */
    rd_cvode cs;       /* the context, CVODE's memory (cs.cv; NULL with sm) */
    N_Vector y, abstol;
    SUNMatrix S; /* the Newton matrix, owned by LS (second-order forms) */
    SUNMatrix A; /* owned: the Newton matrix of a form without blocks */
    SUNLinearSolver LS;
    rd_lift_newton *nw;
    rd_lift_small *sm;     /* the small forms' integrator (rd_lift_small.c), instead of cv */
    double *seg;           /* n: per-segment lift of the current sample */
    double deg_per_s;      /* crank degrees per second */
    long chunk;            /* steps per CVode call between monitor calls */
    long base[N_COUNTERS]; /* counters before the last CVODE restart (plastic landings) */
    N_Vector yd, yk;       /* the sticking phase's scratch (rd_lift_stick.c); NULL: none */
    int stick;             /* 1 while the seated ring is advanced quasi-statically */
    double t_stick;        /* the time the sticking phase has reached, s */
    double t0;             /* the start, s (a window's, rd_lift_setup) */
    int stop_events;       /* > 0: stop at the root that records that many events */
    int stopped;           /* 1: stopped there */
} driver;

/* Flank tracking between root returns: the committed flank and the time a
 * pending leave started (the load's sign change), NAN if none. */
typedef rd_lift_flank_track flank_track;

/* Root functions (directions in rootdir of cv_configure): landing on the
 * lower flank, leave confirmed, landing on the upper flank, leave confirmed,
 * and the ring's total axial load without the flanks (its sign change dates
 * a leave).  An exact zero is nudged up: CVODE stops with an error when a
 * root function stays exactly zero just after a root. */
static int roots(sunrealtype t, N_Vector yv, sunrealtype *g, void *user)
{
    driver *d = user;
    rd_lift_model *c = &d->m;
    const double *y = N_VGetArrayPointer(yv);
    double L = d->form.lift(d->form.user, y, NULL);
    d->form.loads(d->form.user, t, y);
    g[0] = L;
    g[1] = L - c->eps;
    g[2] = c->ca - L;
    g[3] = c->ca - L - c->eps;
    g[4] = c->fz_ext;
    for (int i = 0; i < N_ROOTS; i++)
        if (g[i] == 0.0)
            g[i] = 1e-300;
    return 0;
}

static int drv_rhs(sunrealtype t, N_Vector y, N_Vector yd, void *user)
{
    driver *d = user;
    return d->form.rhs(t, y, yd, d->form.user);
}

static int drv_linsys(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix S, sunbooleantype jok,
                      sunbooleantype *jcur, sunrealtype gamma, void *user, N_Vector t1, N_Vector t2,
                      N_Vector t3)
{
    (void)fy;
    (void)S;
    (void)t1;
    (void)t2;
    (void)t3;
    driver *d = user;
    int cur = 0, rc = rd_lift_newton_linsys(d->nw, t, y, jok, &cur, gamma);
    *jcur = cur ? SUNTRUE : SUNFALSE;
    return rc;
}

/* A form without second-order blocks: CVODE forms I - gamma J from the
 * form's matrix Jacobian (dense or band). */
static int drv_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user, N_Vector t1,
                   N_Vector t2, N_Vector t3)
{
    driver *d = user;
    return d->form.jac(t, y, fy, J, d->form.user, t1, t2, t3);
}

/* An error from a CVODE query or set-up call (these fail only on misuse). */
static int cv_fail(const driver *d, int flag, const char *what, rd_error *err)
{
    return rd_cvode_misuse(&d->cs, flag, what, err);
}

static void driver_free(driver *d)
{
    rd_cvode_close(&d->cs);
    rd_lift_small_free(d->sm);
    if (d->LS)
        SUNLinSolFree(d->LS);
    if (d->A)
        SUNMatDestroy(d->A);
    if (d->y)
        N_VDestroy(d->y);
    if (d->yd)
        N_VDestroy(d->yd);
    if (d->yk)
        N_VDestroy(d->yk);
    if (d->abstol)
        N_VDestroy(d->abstol);
    rd_cvode_close_context(&d->cs);
    free(d->seg);
    free(d->full);
    if (d->form.close)
        d->form.close(&d->form);
    rd_lift_model_cleanup(&d->m);
}

static int cv_configure(driver *d, double rtol, rd_error *err)
{
    int flag, b = d->m.banded ? 0 : +1, rootdir[N_ROOTS] = {-1, b, -1, b, 0};
    if ((flag = CVodeInit(d->cs.cv, drv_rhs, d->t0, d->y)) ||
        (flag = CVodeSVtolerances(d->cs.cv, rtol, d->abstol)) ||
        (flag = CVodeSetUserData(d->cs.cv, d)) ||
        (flag = CVodeSetLinearSolver(d->cs.cv, d->LS, d->A ? d->A : d->S)) ||
        (flag = d->A ? CVodeSetJacFn(d->cs.cv, drv_jac) : CVodeSetLinSysFn(d->cs.cv, drv_linsys)) ||
        (flag = CVodeSetMaxOrd(d->cs.cv, MAX_ORDER)) ||
        (flag = CVodeSetMaxStep(d->cs.cv, HMAX_DEG / d->deg_per_s)) ||
        (flag = CVodeSetLSetupFrequency(d->cs.cv, 1)) || /* fresh Newton matrix each step */
        (flag = CVodeSetJacEvalFrequency(d->cs.cv, 1)) ||
        (flag = CVodeRootInit(d->cs.cv, N_ROOTS, roots)) ||
        (flag = CVodeSetRootDirection(d->cs.cv, rootdir)) ||
        (flag = CVodeSetNoInactiveRootWarn(d->cs.cv)))
        return cv_fail(d, flag, "set-up", err);
    return RD_OK;
}

int rd_lift_form_open(rd_lift_model *m, int model, int modes, rd_lift_form *form, rd_error *err)
{
    if (model == RD_LIFT_MODEL_RIGID)
        return rd_lift_rigid_open(m, form, err);
    if (model == RD_LIFT_MODEL_MODAL)
        return rd_lift_modal_open(m, modes, form, err);
    rd_lift_full_form(m, form);
    return RD_OK;
}

/* The small forms' integrator (rd_lift_small.c) with the driver's roots.
 * Its steps are bounded by 1 crank degree when a gas table may hold a
 * feature a step could pass over, else by 10 (the roots are looked at
 * least that often; the seated phases then take ~1 step per 10 deg). */
static int small_open(driver *d, const rd_lift_setup *setup, const rd_lift_pass *o, rd_error *err)
{
    int rc, b = d->m.banded ? 0 : +1, rootdir[N_ROOTS] = {-1, b, -1, b, 0};
    if (!d->y || !d->abstol)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory setting up the lift integrator.");
    if ((rc = d->form.initial(d->form.user, setup, o->atol, N_VGetArrayPointer(d->y),
                              N_VGetArrayPointer(d->abstol), err)))
        return rc;
    double hmax = (d->m.p->gas.points > 0 ? HMAX_DEG : HMAX_SMALL) / d->deg_per_s;
    d->sm = rd_lift_small_create(&d->form, d->cs.ctx, d->t0, N_VGetArrayPointer(d->y), o->rtol,
                                 N_VGetArrayPointer(d->abstol), hmax, N_ROOTS, roots, rootdir, d);
    if (!d->sm)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory setting up the lift integrator.");
    return RD_OK;
}

static int driver_open(driver *d, const rd_ring *ring, const rd_lift_params *p,
                       const rd_lift_setup *setup, int model, const rd_lift_pass *o, rd_error *err)
{
    memset(d, 0, sizeof *d);
    int rc = rd_lift_model_init(&d->m, ring, p, setup, err);
    if (rc || (rc = rd_lift_form_open(&d->m, model, o->modes, &d->form, err)))
        return rc;
    int n = d->m.n;
    int rigid = model == RD_LIFT_MODEL_RIGID;
    sunindextype N = d->form.N;
    d->deg_per_s = d->m.omega * 180.0 / M_PI;
    d->t0 = setup && setup->t1_deg > 0.0 ? setup->t0_deg / d->deg_per_s : 0.0;
    d->stop_events = setup ? setup->stop_events : 0;
    d->chunk = STEP_CHUNK / n > 1 ? STEP_CHUNK / n : 1;
    if (rigid) /* a step costs about as much as one segment's forces */
        d->chunk = STEP_CHUNK;
    d->seg = malloc((size_t)n * sizeof *d->seg);
    d->full = d->form.expand ? malloc(12 * (size_t)n * sizeof *d->full) : NULL;
    if (!d->seg || (d->form.expand && !d->full))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift output.");
    if ((rc = rd_cvode_open(&d->cs, d->deg_per_s, err)))
        return rc;
    d->y = N_VNew_Serial(N, d->cs.ctx);
    d->abstol = N_VNew_Serial(N, d->cs.ctx);
    if (!(p->stick && rd_lift_stick_usable(&d->form)) && !p->cvode &&
        rd_lift_small_usable(&d->form))
        return small_open(d, setup, o, err);
    if (d->form.blocks) {
        d->LS = rd_lift_newton_create(&d->form, d->cs.ctx, &d->S, &d->nw);
    } else if (d->y) {
        d->A = d->form.dense ? SUNDenseMatrix(N, N, d->cs.ctx)
                             : SUNBandMatrix(N, RD_LIFT_MU, RD_LIFT_ML, d->cs.ctx);
        if (d->A)
            d->LS = d->form.dense ? SUNLinSol_Dense(d->y, d->A, d->cs.ctx)
                                  : SUNLinSol_Band(d->y, d->A, d->cs.ctx);
    }
    int stick = p->stick && rd_lift_stick_usable(&d->form);
    if ((rc = rd_cvode_create(&d->cs, err)))
        return rc;
    if (stick && d->y) {
        d->yd = N_VNew_Serial(N, d->cs.ctx);
        d->yk = N_VNew_Serial(N, d->cs.ctx);
    }
    if (!d->y || !d->abstol || !d->LS || (stick && (!d->yd || !d->yk)))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory setting up CVODE for %d segments.",
                            n);
    if ((rc = d->form.initial(d->form.user, setup, o->atol, N_VGetArrayPointer(d->y),
                              N_VGetArrayPointer(d->abstol), err)))
        return rc;
    return cv_configure(d, o->rtol, err);
}

/* ---------------------------------------------------------------- events */

static int push_event(rd_lift_pass *o, double deg, int kind, double touch_deg, rd_error *err)
{
    if (o->n_events == o->cap_events) {
        int cap = o->cap_events ? 2 * o->cap_events : 16;
        rd_lift_event *e = realloc(o->events, (size_t)cap * sizeof *e);
        if (!e)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory recording flank changes.");
        o->events = e;
        o->cap_events = cap;
    }
    o->events[o->n_events] = (rd_lift_event){deg, kind, touch_deg};
    o->n_events++;
    return RD_OK;
}

/* Without a band: a seated ring leaves when the load turns away (rf[4]
 * with sign `away`) and the lift then confirms it (rf[confirm] > 0). */
static int track_seated(flank_track *tr, const int *rf, int away, int confirm, int kind, double t,
                        double deg_per_s, rd_lift_pass *o, rd_error *err)
{
    if (rf[4] == away)
        tr->cand = t;
    else if (rf[4] == -away)
        tr->cand = NAN; /* the load turned back before the ring got away */
    if (rf[confirm] > 0) {
        double deg = (isnan(tr->cand) ? t : tr->cand) * deg_per_s;
        tr->state = RD_FLANK_FREE;
        tr->touched = 0;
        return push_event(o, deg, kind, deg, err);
    }
    return RD_OK;
}

/* The mean lift reached the flank it is in the band of (state): the
 * landing's touch, and the leave watch from there (a ring landing against
 * its load leaves again). */
static void touch_flank(flank_track *tr, double t, double deg_per_s, double fz, rd_lift_pass *o)
{
    int away = tr->state == RD_FLANK_UPPER ? -1 : +1;
    tr->touched = 1;
    tr->cand = fz * away > 0.0 ? t : NAN;
    if (tr->landing >= 0)
        o->events[tr->landing].touch_deg = t * deg_per_s;
    tr->landing = -1;
}

/* With a band: a landing where the mean lift enters it, a leave where it
 * moves out; touch_deg where it reached the flank, or left it (the load
 * turning away while it touched, else the band's edge). */
static int track_band(flank_track *tr, const int *rf, double t, double deg_per_s, double fz,
                      rd_lift_pass *o, rd_error *err)
{
    if (tr->state == RD_FLANK_FREE) {
        int upper = rf[3] < 0;
        if (!upper && rf[1] >= 0)
            return RD_OK;
        tr->state = upper ? RD_FLANK_UPPER : RD_FLANK_LOWER;
        tr->touched = 0;
        tr->cand = NAN;
        tr->landing = o->n_events;
        int rc = push_event(o, t * deg_per_s, upper ? RD_EVENT_REACH_UPPER : RD_EVENT_REACH_LOWER,
                            NAN, err);
        if (rc == RD_OK && rf[upper ? 2 : 0] < 0)
            touch_flank(tr, t, deg_per_s, fz, o);
        return rc;
    }
    int upper = tr->state == RD_FLANK_UPPER, away = upper ? -1 : +1;
    if (!tr->touched && rf[upper ? 2 : 0] < 0)
        touch_flank(tr, t, deg_per_s, fz, o);
    else if (tr->touched && rf[4] == away)
        tr->cand = t;
    else if (tr->touched && rf[4] == -away)
        tr->cand = NAN;
    if (rf[upper ? 3 : 1] <= 0)
        return RD_OK;
    double touch = tr->touched ? (isnan(tr->cand) ? t : tr->cand) * deg_per_s : NAN;
    tr->state = RD_FLANK_FREE;
    tr->touched = 0;
    tr->landing = -1;
    return push_event(o, t * deg_per_s, upper ? RD_EVENT_LEAVE_UPPER : RD_EVENT_LEAVE_LOWER, touch,
                      err);
}

int rd_lift_track_roots(flank_track *tr, const int *rf, double t, double deg_per_s, double fz,
                        rd_lift_pass *o, rd_error *err)
{
    if (tr->banded)
        return track_band(tr, rf, t, deg_per_s, fz, o, err);
    if (tr->state == RD_FLANK_LOWER)
        return track_seated(tr, rf, +1, 1, RD_EVENT_LEAVE_LOWER, t, deg_per_s, o, err);
    if (tr->state == RD_FLANK_UPPER)
        return track_seated(tr, rf, -1, 3, RD_EVENT_LEAVE_UPPER, t, deg_per_s, o, err);
    if (rf[0] < 0) {
        tr->state = RD_FLANK_LOWER;
        tr->touched = 1;
        tr->cand = fz > 0.0 ? t : NAN; /* landed against its load: leaves again */
        return push_event(o, t * deg_per_s, RD_EVENT_REACH_LOWER, t * deg_per_s, err);
    }
    if (rf[2] < 0) {
        tr->state = RD_FLANK_UPPER;
        tr->touched = 1;
        tr->cand = fz < 0.0 ? t : NAN;
        return push_event(o, t * deg_per_s, RD_EVENT_REACH_UPPER, t * deg_per_s, err);
    }
    return RD_OK;
}

rd_lift_flank_track rd_lift_track_seated(int banded, double fz, double t)
{
    return (flank_track){RD_FLANK_LOWER, fz > 0.0 ? t : NAN, banded, 1, -1};
}

/* The event state machine starts where the initial state is (the seated
 * ring on the lower flank; a load already pulling it away dates a leave at 0). */
static flank_track initial_flank(driver *d)
{
    const double *yy = N_VGetArrayPointer(d->y);
    double L0 = d->form.lift(d->form.user, yy, NULL);
    d->form.loads(d->form.user, d->t0, yy);
    flank_track tr = rd_lift_track_seated(d->m.banded, d->m.fz_ext, d->t0);
    if (L0 > d->m.ca - d->m.eps) { /* a window's start on the upper flank */
        tr.state = RD_FLANK_UPPER;
        tr.touched = d->m.banded && L0 >= d->m.ca - d->m.d0;
        tr.cand = NAN;
        return tr;
    }
    if (L0 > d->m.eps)
        tr.state = RD_FLANK_FREE;
    if (tr.state != RD_FLANK_LOWER || (d->m.banded && L0 > d->m.d0)) {
        tr.cand = NAN; /* not on the lower flank: no leave pending */
        tr.touched = 0;
    }
    return tr;
}

/* CVODE's counters (rd_lift_result order: steps, rhs, Jacobians, set-ups,
 * Newton iterations and failures, error-test failures, root evaluations)
 * plus those before its last restart. */
static int read_counters(const driver *d, long *c)
{
    int flag;
    if (d->sm) {
        rd_lift_small_counters(d->sm, c);
        for (int k = 0; k < N_COUNTERS; k++)
            c[k] += d->base[k];
        return 0;
    }
    if ((flag = rd_cvode_counters(&d->cs, c)))
        return flag;
    for (int k = 0; k < N_COUNTERS; k++)
        c[k] += d->base[k];
    return 0;
}

/* The counters so far into d->base before a CVODE restart (read through a
 * copy: read_counters adds d->base to its output). */
static int keep_counters(driver *d)
{
    long c[N_COUNTERS];
    int flag = read_counters(d, c);
    if (!flag)
        memcpy(d->base, c, sizeof c);
    return flag;
}

static int step_error(driver *d, int flag, rd_error *err);

/* The integrator's own time (CVODE's or rd_lift_small's), s. */
static int current_time(const driver *d, double *tc)
{
    if (d->sm) {
        *tc = rd_lift_small_time(d->sm);
        return CV_SUCCESS;
    }
    return CVodeGetCurrentTime(d->cs.cv, tc);
}

/* One call of the integrator towards tout with at most max_steps steps
 * (CVODE's CV_NORMAL conventions, rd_lift_small.h), and its root info. */
static int integrator_solve(driver *d, double tout, long max_steps, double *t)
{
    int flag;
    if (d->sm) {
        rd_lift_small_set_max_steps(d->sm, max_steps);
        return rd_lift_small_solve(d->sm, tout, N_VGetArrayPointer(d->y), t);
    }
    if ((flag = CVodeSetMaxNumSteps(d->cs.cv, max_steps)))
        return flag;
    return CVode(d->cs.cv, tout, d->y, t, CV_NORMAL);
}

static int root_info(const driver *d, int *rf)
{
    if (d->sm) {
        rd_lift_small_root_info(d->sm, rf);
        return CV_SUCCESS;
    }
    return CVodeGetRootInfo(d->cs.cv, rf);
}

/* A plastic landing (rd_lift.h): the form arrests the ring's velocity
 * towards the flank, and CVODE restarts from that state at the root (its
 * counters carry over in d->base). */
static int land_plastic(driver *d, double t, int upper, rd_error *err)
{
    int flag;
    if (d->sm) { /* its counters run on over a restart */
        d->form.impact(d->form.user, N_VGetArrayPointer(d->y), upper);
        if ((flag = rd_lift_small_reinit(d->sm, t, N_VGetArrayPointer(d->y))))
            return step_error(d, flag, err);
        return RD_OK;
    }
    if ((flag = keep_counters(d)))
        return cv_fail(d, flag, "counter query", err);
    d->form.impact(d->form.user, N_VGetArrayPointer(d->y), upper);
    if ((flag = CVodeReInit(d->cs.cv, t, d->y)))
        return cv_fail(d, flag, "restart", err);
    return RD_OK;
}

/* The error of a failed or exhausted integration, dated at the crank angle
 * the integrator really reached. */
static int step_error(driver *d, int flag, rd_error *err)
{
    double tc = 0.0, total = d->m.p->engine.cycles * 720.0;
    long c[N_COUNTERS], nst;
    int f2;
    if ((f2 = current_time(d, &tc)) || (f2 = read_counters(d, c)))
        return cv_fail(d, f2, "query", err);
    nst = c[0];
    rd_cvode_limit lim = {"lift", "ring's motion", d->m.p->max_steps, total, nst};
    size_t m = rd_error_enter(err, flag == CV_TOO_MUCH_WORK ? "/numerics" : "");
    int rc = rd_cvode_failure(&d->cs, flag, tc, &lim, err);
    rd_error_leave(err, m);
    return rc;
}

/* Integrates to tout in chunks of d->chunk steps, handling the roots on the
 * way and asking the monitor between chunks (at progress `frac`). */
static int advance(driver *d, double tout, flank_track *tr, rd_lift_pass *o, const rd_monitor *mon,
                   double frac, rd_error *err)
{
    double *yy = N_VGetArrayPointer(d->y), t = 0.0;
    for (;;) {
        long c[N_COUNTERS];
        int flag, rc;
        if ((flag = read_counters(d, c)))
            return cv_fail(d, flag, "query", err);
        long left = d->m.p->max_steps - c[0];
        if (left <= 0)
            return step_error(d, CV_TOO_MUCH_WORK, err);
        flag = integrator_solve(d, tout, left < d->chunk ? left : d->chunk, &t);
        if (flag == CV_ILL_INPUT)
            return cv_fail(d, flag, "set-up", err);
        if (flag == CV_ROOT_RETURN) {
            int rf[N_ROOTS];
            if ((flag = root_info(d, rf)))
                return cv_fail(d, flag, "query", err);
            d->form.loads(d->form.user, t, yy);
            int was = tr->touched;
            if ((rc = rd_lift_track_roots(tr, rf, t, d->deg_per_s, d->m.fz_ext, o, err)))
                return rc;
            if (!was && tr->touched && d->m.p->landing == RD_LANDING_PLASTIC &&
                (rc = land_plastic(d, t, tr->state == RD_FLANK_UPPER, err)))
                return rc;
            if (d->stop_events > 0 &&
                (o->n_events > d->stop_events || (o->n_events == d->stop_events && tr->touched))) {
                d->stopped = 1;
                return RD_OK;
            }
            continue;
        }
        if (flag == CV_TOO_MUCH_WORK) { /* a chunk ended, or max_steps did */
            if ((rc = rd_monitor_report(mon, frac, err)))
                return rc;
            continue;
        }
        if (flag < 0)
            return step_error(d, flag, err);
        return RD_OK;
    }
}

/* A seated ring pressed onto its flank and at rest (rates within atol)
 * enters the sticking phase (rd_lift_stick.c) when its form allows it. */
static int may_stick(driver *d, const flank_track *tr, double t)
{
    const double *yy = N_VGetArrayPointer(d->y), *at = N_VGetArrayPointer(d->abstol);
    int away = tr->state == RD_FLANK_LOWER ? +1 : -1;
    if (!d->yd || tr->state == RD_FLANK_FREE || !tr->touched || !isnan(tr->cand))
        return 0;
    for (sunindextype k = d->form.N / 2; k < d->form.N; k++)
        if (fabs(yy[k]) > at[k])
            return 0;
    d->form.loads(d->form.user, t, yy);
    return d->m.fz_ext * away < 0.0;
}

/* advance(), or the sticking phase to tout while the ring sticks: at its
 * end (the load turned away) the leave candidate is dated and CVODE
 * restarts from the quasi-static state, its counters carried over. */
static int advance_or_stick(driver *d, double tout, flank_track *tr, rd_lift_pass *o,
                            const rd_monitor *mon, double frac, rd_error *err)
{
    double tl = 0.0;
    int flag, rc;
    if (!d->stick) {
        if ((rc = advance(d, tout, tr, o, mon, frac, err)) || !may_stick(d, tr, tout))
            return rc;
        d->stick = 1;
        d->t_stick = tout;
        return RD_OK;
    }
    N_VScale(1.0, d->y, d->yk);
    int away = tr->state == RD_FLANK_LOWER ? +1 : -1;
    int got = rd_lift_stick_advance(&d->form, d->t_stick, tout, away, d->y, d->yd,
                                    N_VGetArrayPointer(d->abstol), &tl);
    if (got == 0) {
        d->t_stick = tout;
        return RD_OK;
    }
    d->stick = 0;
    if (got < 0) { /* Newton failed: integrate from where the phase stood */
        N_VScale(1.0, d->yk, d->y);
        tl = d->t_stick;
    } else {
        tr->cand = tl;
    }
    if ((flag = keep_counters(d)) || (flag = CVodeReInit(d->cs.cv, tl, d->y)))
        return cv_fail(d, flag, "restart", err);
    return advance(d, tout, tr, o, mon, frac, err);
}

/* Sample k's bore pressure per segment, its extremes and the ring's depth on a
 * bore map (state yf, the full one). */
static void store_bore(rd_lift_model *c, rd_lift_result *res, int k, double tout, const double *yf)
{
    if (!res->bore_pressure)
        return;
    double *seg = res->bore_pressure + (size_t)k * c->n;
    double lo = INFINITY, hi = -INFINITY;
    rd_lift_bore_pressure(c, tout, yf, seg);
    for (int i = 0; i < c->n; i++) {
        lo = fmin(lo, seg[i]);
        hi = fmax(hi, seg[i]);
    }
    res->bore_pressure_min[k] = lo;
    res->bore_pressure_max[k] = hi;
    if (res->ring_depth) {
        double s = 0.0, v, a;
        rd_engine_piston(&c->p->engine, c->omega * tout, &s, &v, &a);
        res->ring_depth[k] = c->p->ring_z_tdc + s;
    }
}

/* The outputs of sample k at time tout (state in d->y). */
static void store_sample(driver *d, int k, double deg, double tout, rd_lift_pass *o,
                         const rd_lift_setup *setup)
{
    rd_lift_model *c = &d->m;
    const double *yy = N_VGetArrayPointer(d->y), *yf = yy;
    /* the full state only for what reads it (the reference run stores the lift only) */
    if (d->form.expand && (o->res || (setup && (setup->sample || setup->energy)))) {
        d->form.expand(d->form.user, yy, d->full);
        yf = d->full;
    }
    int n = c->n;
    double L = d->form.lift(d->form.user, yy, d->seg);
    o->lift[k] = L;
    rd_lift_result *res = o->res;
    if (res) {
        res->crank_deg[k] = deg;
        res->lift[k] = L;
        double lo = d->seg[0], hi = d->seg[0], tw = 0.0;
        for (int i = 0; i < n; i++) {
            lo = fmin(lo, d->seg[i]);
            hi = fmax(hi, d->seg[i]);
            const double *q = Q(yf, i);
            tw += q[3] * c->e_t[2 * i] + q[4] * c->e_t[2 * i + 1];
        }
        memcpy(res->lift_segments + (size_t)k * n, d->seg, (size_t)n * sizeof *d->seg);
        res->lift_min[k] = lo;
        res->lift_max[k] = hi;
        res->twist[k] = tw / n;
        c->friction = 0.0; /* the loads only for a scene with friction */
        if (c->p->friction.model != RD_FRICTION_NONE)
            d->form.loads(d->form.user, tout, yy);
        res->friction_force[k] = c->friction;
        store_bore(c, res, k, tout, yf);
        res->flank[k] =
            L < c->eps ? RD_FLANK_LOWER : (L > c->ca - c->eps ? RD_FLANK_UPPER : RD_FLANK_FREE);
    }
    if (setup && setup->sample)
        setup->sample(setup->ctx, tout, yf);
    if (setup && setup->state)
        setup->state(setup->ctx, tout, yy, (int)d->form.N);
    if (setup && setup->energy) {
        rd_lift_energy en = {0.0, 0.0, 0.0};
        c->energy = &en;
        rd_lift_forces(c, tout, yf, NULL, NULL);
        c->energy = NULL;
        setup->energy(setup->ctx, tout, &en);
    }
}

static int store_counters(driver *d, rd_lift_result *r, rd_error *err)
{
    long c[N_COUNTERS];
    int flag = read_counters(d, c);
    if (flag)
        return cv_fail(d, flag, "counter query", err);
    r->steps = c[0];
    r->rhs_evals = c[1];
    r->jac_evals = c[2];
    r->lin_setups = c[3];
    r->nonlin_iters = c[4];
    r->nonlin_fails = c[5];
    r->err_test_fails = c[6];
    r->root_evals = c[7];
    return RD_OK;
}

int rd_lift_integrate(const rd_ring *ring, const rd_lift_params *p, const rd_lift_setup *setup,
                      int model, const rd_monitor *mon, rd_lift_pass *o, rd_error *err)
{
    driver d;
    int rc = driver_open(&d, ring, p, setup, model, o, err);
    if (rc)
        goto out;
    o->dof = (int)(d.form.N / 2);
    flank_track tr = initial_flank(&d);
    int S = o->samples;
    double t0 = d.t0 * d.deg_per_s, total = p->engine.cycles * 720.0;
    if (setup && setup->t1_deg > 0.0)
        total = setup->t1_deg;
    for (int k = 0; k < S && !d.stopped; k++) {
        double deg = fmin(t0 + k * p->step_deg, total), tout = deg / d.deg_per_s;
        if (k > 0 && (rc = advance_or_stick(&d, tout, &tr, o, mon, (double)k / S, err))) {
            double tc = 0.0;
            o->done = k; /* a stopped run's partial result may keep the samples */
            if (current_time(&d, &tc) == CV_SUCCESS)
                o->reached_deg = tc * d.deg_per_s;
            break;
        }
        if (d.stopped) {
            o->done = k;
            break;
        }
        store_sample(&d, k, deg, tout, o, setup);
        if ((rc = rd_monitor_report(mon, (k + 1.0) / S, err))) {
            o->done = k + 1;
            o->reached_deg = deg;
            break;
        }
    }
    /* the work done, also by a run stopped early (for its partial result) */
    if (o->res && (rc == RD_OK || rc == RD_ELIMIT || rc == RD_ECANCELED || rc == RD_ETIMEOUT)) {
        rd_error ignored = {0};
        int c = store_counters(&d, o->res, rc ? &ignored : err);
        rc = rc ? rc : c;
    }
out:
    driver_free(&d);
    return rc;
}
