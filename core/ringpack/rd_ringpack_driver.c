/*
 * rd_ringpack_driver.c — the ring pack's CVODE driver (equations and state
 * layout in rd_ringpack.h): set-up, the flank state machine at CVODE's
 * roots, the output of the last cycle, the balance and periodicity of the
 * last two cycles, and the error estimate (rd_accuracy: the run again at
 * rtol/10, atol/10); the public handle (rd_ringpack_create/run/free) that
 * keeps the lift rings' models for its runs.
 *
 * Roots of an axial ring: a seated ring watches its net force F (it leaves
 * when F stops pressing it on the flank), a free ring watches z and a - z
 * (it lands).  At such a root the ring's mode changes, the state is set on
 * the flank (z = 0 or a, z' = 0: an inelastic landing) and CVODE restarts.
 * With a band (flank_band > 0, rd_ringpack.h) a free ring also watches
 * z - e and a - z - e, e = flank_band a, both ways: its band state
 * (band_state) moves at those roots without a restart (the state is not
 * touched there), and the flank changes are dated there: a landing where z
 * moves into a band, a leave where it moves out.  touch_deg: the inelastic
 * landing (z reaching the flank) after a landing, the mode change (F
 * turning away) or an impact against the load (z reaching the flank while
 * F pulls it away: it stays free and leaves at once) before a leave.  A
 * band crossing is handled before a mode change at the same root return.
 * Without a band the events are the mode changes themselves (touch_deg =
 * crank_deg), and an impact against the load is none.  A sample's flank is
 * the band z is in (with flank_band 0: the mode), as a lift ring's is the
 * band of its mean lift.
 * A lift ring's five roots and state machine are the lift driver's
 * (rd_lift_track_roots; its band edge the model's eps), with its root
 * directions (roots 1 and 3 both ways with a band).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "rd_accuracy.h"
#include "rd_cvode.h"
#include "rd_internal.h"
#include "rd_ringpack_model.h"

#define HMAX_DEG     2.0    /* largest step, crank degrees */
#define HMAX_LIFT    1.0    /* with lift rings: the lift driver's bound */
#define ORDER_LIFT   2      /* with lift rings: the lift driver's BDF order bound */
#define NR           5      /* roots per ring (an axial ring uses two, four with a band) */
#define RESTARTS_MAX 200000 /* flank changes allowed in a run */

/* An axial ring's flank band (header comment): the band z is in (enum
 * rd_flank), whether z reached the flank since it entered it, when it last
 * left the flank (s; NAN: not since), and the landing awaiting its touch
 * (index in the result's events; -1: none, or not in the last cycle). */
typedef struct band_state {
    int band, touched, landing;
    double cand;
} band_state;

/* The handle (rd_ringpack.h): the scene, checked once, and each lift
 * ring's model, made by the first run and kept for the next runs and
 * levels. */
struct rd_ringpack {
    rd_ringpack_params p;
    rd_packring *ring[RD_RINGPACK_RINGS_MAX];
};

typedef struct drv {
    rd_ringpack_model m;
    rd_packring **rings; /* the handle's */
    rd_cvode cs;         /* the context and CVODE's memory (cs.cv) */
    N_Vector y, abstol;
    SUNMatrix A;
    SUNLinearSolver LS;
    rd_ringpack_newton *pn; /* with lift rings: the bordered Newton solver */
    double deg_per_s;
    rd_ringpack_rec rec; /* the recorded cycle (rd_ringpack_record.c) */
    int cap[RD_RINGPACK_RINGS_MAX];
    int banded; /* flank_band > 0: events at the bands' edges */
    band_state band[RD_RINGPACK_RINGS_MAX];
} drv;

static int cv_rhs(sunrealtype t, N_Vector y, N_Vector yd, void *user)
{
    drv *d = user;
    double *f = N_VGetArrayPointer(yd);
    if (rd_ringpack_rhs(&d->m, t, N_VGetArrayPointer(y), f))
        return 1;
    for (int k = 0; k < d->m.N; k++)
        if (!isfinite(f[k]))
            return 1;
    return 0;
}

/* A lift ring's roots, the lift driver's (rd_lift_driver.c): L, L - eps,
 * c_a - L, c_a - L - eps and its load without the flanks; an exact zero
 * nudged up. */
static void lift_roots(const rd_ringpack_model *m, int i, double t, const double *y,
                       const double *pv, double *g)
{
    rd_packring *L = m->lr[i];
    double f[3], up, lo, fz, fr, eps = rd_packring_eps(L), a = m->ca[i];
    rd_ringpack_faces(m, i, t, pv, f);
    rd_packring_gas(L, f);
    double lift = rd_packring_areas(L, y + m->off[i], &up, &lo);
    rd_packring_loads(L, t, y + m->off[i], &fz, &fr);
    g[0] = lift;
    g[1] = lift - eps;
    g[2] = a - lift;
    g[3] = a - lift - eps;
    g[4] = fz;
    for (int k = 0; k < NR; k++)
        if (g[k] == 0.0)
            g[k] = 1e-300;
}

static int cv_roots(sunrealtype t, N_Vector yv, sunrealtype *g, void *user)
{
    drv *d = user;
    const rd_ringpack_model *m = &d->m;
    const double *y = N_VGetArrayPointer(yv);
    double pv[RD_RINGPACK_VOLUMES_MAX];
    rd_ringpack_pressures(m, t, y, pv);
    for (int i = 0; i < m->R; i++) {
        double *gi = g + NR * i;
        for (int k = 0; k < NR; k++)
            gi[k] = 1.0;
        if (m->lr[i]) {
            lift_roots(m, i, t, y, pv, gi);
            continue;
        }
        if (m->p->rings[i].pinned != RD_PIN_FREE)
            continue;
        if (m->mode[i] == RD_FLANK_FREE) {
            double z = RP_Z(m, y, i), a = m->ca[i], e = m->p->flank_band * a;
            gi[0] = z;
            gi[1] = a - z;
            if (d->banded) { /* the bands' edges (an exact zero nudged up) */
                gi[2] = z - e != 0.0 ? z - e : 1e-300;
                gi[3] = a - z - e != 0.0 ? a - z - e : 1e-300;
            }
        } else {
            gi[0] = rd_ringpack_ring_force(m, i, t, y, pv);
        }
    }
    return 0;
}

static int cv_linsys(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix A, sunbooleantype jok,
                     sunbooleantype *jcur, sunrealtype gamma, void *user, N_Vector t1, N_Vector t2,
                     N_Vector t3)
{
    (void)A, (void)jok, (void)t1, (void)t2, (void)t3;
    drv *d = user;
    *jcur = SUNTRUE;
    return rd_ringpack_newton_linsys(d->pn, t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy),
                                     gamma);
}

/* A CVODE set-up, query or restart call failed (misuse). */
static int cv_fail(const drv *d, int flag, const char *what, rd_error *err)
{
    return rd_cvode_misuse(&d->cs, flag, what, err);
}

/* The integration failed (flag < 0): dated at the crank angle reached. */
static int cv_failed(const drv *d, int flag, rd_error *err)
{
    double t = 0.0;
    long steps = d->rec.res->steps, now = 0;
    if (CVodeGetCurrentTime(d->cs.cv, &t) || CVodeGetNumSteps(d->cs.cv, &now))
        return cv_fail(d, flag, "query", err);
    rd_cvode_limit lim = {"ring-pack", "ring pack's run", d->m.p->max_steps, 720.0 * d->rec.C,
                          steps + now};
    size_t m = rd_error_enter(err, flag == CV_TOO_MUCH_WORK ? "/numerics" : "");
    int rc = rd_cvode_failure(&d->cs, flag, t, &lim, err);
    rd_error_leave(err, m);
    return rc;
}

static void drv_close(drv *d)
{
    rd_cvode_close(&d->cs);
    if (d->LS)
        SUNLinSolFree(d->LS);
    if (d->A)
        SUNMatDestroy(d->A);
    if (d->y)
        N_VDestroy(d->y);
    if (d->abstol)
        N_VDestroy(d->abstol);
    rd_cvode_close_context(&d->cs);
    free(d->rec.prev);
    rd_ringpack_model_cleanup(&d->m);
}

/* Initial state (every volume at the crankcase pressure, rings at rest on
 * their flank) and tolerances. */
static int initial_state(drv *d, double rtol, double atol, rd_error *err)
{
    const rd_ringpack_model *m = &d->m;
    double *y = N_VGetArrayPointer(d->y), *ab = N_VGetArrayPointer(d->abstol), vsum = 0.0;
    for (int v = 0; v < m->V; v++) {
        y[v] = m->p->crankcase_pa;
        ab[v] = rtol * m->p->crankcase_pa;
        vsum += m->vol[v + 1];
    }
    for (int i = 0; i < m->R; i++) {
        RP_Z(m, y, i) = m->mode[i] == RD_FLANK_UPPER             ? m->ca[i]
                        : m->p->rings[i].pinned == RD_PIN_MIDDLE ? 0.5 * m->ca[i]
                                                                 : 0.0;
        RP_ZD(m, y, i) = 0.0;
        RP_Z(m, ab, i) = atol;
        RP_ZD(m, ab, i) = atol * m->omega;
    }
    for (int k = 0; k < 4; k++) {
        RP_CUM(m, y, k) = 0.0;
        RP_CUM(m, ab, k) = rtol * m->p->crankcase_pa * vsum / (m->law.R * m->p->T_lands);
    }
    for (int i = 0; i < m->R; i++) {
        int rc = m->lr[i] ? rd_packring_initial(m->lr[i], atol, y + m->off[i], ab + m->off[i], err)
                          : RD_OK;
        if (rc)
            return rc;
    }
    return RD_OK;
}

/* The lift rings' models, their states after the network's; their model
 * facts into the result. */
static int open_rings(drv *d, rd_error *err)
{
    rd_ringpack_model *m = &d->m;
    rd_ringpack_result *r = d->rec.res;
    rd_ringpack_choose(m, r->ring_why);
    for (int i = 0; i < m->R; i++) {
        int n = 0, modes = 0, rc;
        double k = 0.0;
        r->ring_model[i] = m->kind[i];
        r->ring_dof[i] = m->p->rings[i].pinned == RD_PIN_FREE ? 1 : 0;
        if (m->kind[i] == RD_RINGPACK_AXIAL)
            continue;
        if (!d->rings[i] && (rc = rd_packring_create(m, i, &d->rings[i], err)))
            return rc;
        if ((rc = rd_packring_open(m, i, d->rings[i], d->cs.ctx, &n, &modes, &k, err)))
            return rc;
        m->off[i] = m->N;
        m->N += n;
        m->lifted++;
        r->ring_dof[i] = n / 2;
        r->ring_stiffness[i] = k;
        r->ring_modes[i] = m->kind[i] == RD_LIFT_MODEL_MODAL ? modes : 0;
    }
    r->states = m->N;
    return RD_OK;
}

/* The Newton solver: with lift rings the bordered one (rd_ringpack_newton.c)
 * under the lift driver's settings (order <= 2, a fresh matrix each step,
 * steps <= 1 deg: rd_lift_driver.c says why); else CVODE's dense one with a
 * difference-quotient Jacobian. */
static int solver(drv *d, rd_error *err)
{
    int flag = 0;
    if (!d->m.lifted) {
        d->A = SUNDenseMatrix(d->m.N, d->m.N, d->cs.ctx);
        d->LS = d->A ? SUNLinSol_Dense(d->y, d->A, d->cs.ctx) : NULL;
    } else {
        d->A = SUNDenseMatrix(d->m.N0, d->m.N0, d->cs.ctx);
        d->LS = d->A ? rd_ringpack_newton_create(&d->m, d->cs.ctx, d->A, &d->pn) : NULL;
    }
    if (!d->A || !d->LS)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory setting up CVODE for the pack.");
    if ((flag = CVodeSetLinearSolver(d->cs.cv, d->LS, d->A)))
        return cv_fail(d, flag, "set-up", err);
    if (!d->m.lifted)
        return RD_OK;
    if ((flag = CVodeSetLinSysFn(d->cs.cv, cv_linsys)) ||
        (flag = CVodeSetMaxOrd(d->cs.cv, ORDER_LIFT)) ||
        (flag = CVodeSetMaxStep(d->cs.cv, HMAX_LIFT / d->deg_per_s)) ||
        (flag = CVodeSetLSetupFrequency(d->cs.cv, 1)) ||
        (flag = CVodeSetJacEvalFrequency(d->cs.cv, 1)))
        return cv_fail(d, flag, "set-up", err);
    return RD_OK;
}

/* Root directions: an axial ring's both ways; a lift ring's as the lift
 * driver's (landing, leave confirmed, landing, leave confirmed, load;
 * with a band: landing, the lower band's edge both ways, and so on). */
static int root_directions(drv *d)
{
    int b = d->banded ? 0 : +1;
    int dir[NR * RD_RINGPACK_RINGS_MAX] = {0}, lift[NR] = {-1, b, -1, b, 0};
    for (int i = 0; i < d->m.R; i++)
        if (d->m.lr[i])
            memcpy(dir + NR * i, lift, sizeof lift);
    return CVodeSetRootDirection(d->cs.cv, dir);
}

static int drv_open(drv *d, const rd_ringpack_params *p, double rtol, double atol, rd_error *err)
{
    int rc = rd_ringpack_model_init(&d->m, p, err), flag;
    if (rc)
        return rc;
    d->deg_per_s = d->m.omega * 180.0 / M_PI;
    d->banded = p->flank_band > 0.0;
    if ((rc = rd_cvode_open(&d->cs, d->deg_per_s, err)))
        return rc;
    if ((rc = open_rings(d, err)) || (rc = rd_ringpack_films_open(&d->m, d->rec.S, err)))
        return rc;
    sunindextype N = d->m.N;
    d->y = N_VNew_Serial(N, d->cs.ctx);
    d->abstol = N_VNew_Serial(N, d->cs.ctx);
    if ((rc = rd_cvode_create(&d->cs, err)))
        return rc;
    if (!d->y || !d->abstol)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory setting up CVODE for the pack.");
    if ((rc = initial_state(d, rtol, atol, err)))
        return rc;
    if ((flag = CVodeInit(d->cs.cv, cv_rhs, 0.0, d->y)) ||
        (flag = CVodeSVtolerances(d->cs.cv, rtol, d->abstol)) ||
        (flag = CVodeSetUserData(d->cs.cv, d)) ||
        (flag = CVodeSetMaxStep(d->cs.cv, HMAX_DEG / d->deg_per_s)) ||
        (flag = CVodeSetMaxNumSteps(d->cs.cv, p->max_steps)) ||
        (flag = CVodeRootInit(d->cs.cv, NR * d->m.R, cv_roots)) || (flag = root_directions(d)) ||
        (flag = CVodeSetNoInactiveRootWarn(d->cs.cv)))
        return cv_fail(d, flag, "set-up", err);
    return solver(d, err);
}

/* ------------------------------------------------------------- events */

/* Ring i's flank change at t (s) of the last cycle, `touch` its touch_deg's
 * time (s; NAN: none), both as crank angles of that cycle; earlier ones are
 * dropped. */
static int push_event(drv *d, int i, double t, int kind, double touch, rd_error *err)
{
    double deg = t * d->deg_per_s - 720.0 * d->rec.cyc;
    rd_ringpack_result *r = d->rec.res;
    if (deg < 0.0) /* only the recorded cycle's are kept */
        return RD_OK;
    if (r->n_events[i] == d->cap[i]) {
        int cap = d->cap[i] ? 2 * d->cap[i] : 16;
        rd_lift_event *e = realloc(r->events[i], (size_t)cap * sizeof *e);
        if (!e)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory recording flank changes.");
        r->events[i] = e;
        d->cap[i] = cap;
    }
    r->events[i][r->n_events[i]++] =
        (rd_lift_event){deg, kind, touch * d->deg_per_s - 720.0 * d->rec.cyc};
    return RD_OK;
}

/* The flank change reaching (leave 0) or leaving (1) `flank`. */
static int flank_event(int flank, int leave)
{
    if (flank == RD_FLANK_UPPER)
        return leave ? RD_EVENT_LEAVE_UPPER : RD_EVENT_REACH_UPPER;
    return leave ? RD_EVENT_LEAVE_LOWER : RD_EVENT_REACH_LOWER;
}

/* Axial ring i moves into the band at `flank` at t: a landing, awaiting
 * its touch. */
static int band_enter(drv *d, int i, double t, int flank, rd_error *err)
{
    int n = d->rec.res->n_events[i], rc = push_event(d, i, t, flank_event(flank, 0), NAN, err);
    d->band[i] = (band_state){flank, 0, d->rec.res->n_events[i] > n ? n : -1, NAN};
    return rc;
}

/* Axial ring i's band crossing at t (rf: its root flags): into a band (z -
 * e or a - z - e falling) a landing; out of the band it is in a leave,
 * touch_deg when z last left the flank (NAN if it never touched it). */
static int band_cross(drv *d, int i, double t, const int *rf, rd_error *err)
{
    band_state *b = &d->band[i];
    int upper = rf[3] != 0, flank = upper ? RD_FLANK_UPPER : RD_FLANK_LOWER;
    if ((upper ? rf[3] : rf[2]) < 0)
        return b->band == RD_FLANK_FREE ? band_enter(d, i, t, flank, err) : RD_OK;
    if (b->band != flank)
        return RD_OK;
    double touch = b->touched ? (isnan(b->cand) ? t : b->cand) : NAN;
    *b = (band_state){RD_FLANK_FREE, 0, -1, NAN};
    return push_event(d, i, t, flank_event(flank, 1), touch, err);
}

/* Axial ring i reached `flank` at t (an inelastic landing) and sits on it
 * (seated) or leaves it again at once (against its load): the landing's
 * touch, and where a leave left the flank.  Reaching the flank outside its
 * band (not expected: the band's root comes first) enters the band there. */
static int band_touch(drv *d, int i, double t, int flank, int seated, rd_error *err)
{
    band_state *b = &d->band[i];
    int rc = b->band != flank ? band_enter(d, i, t, flank, err) : RD_OK;
    if (!b->touched && b->landing >= 0)
        d->rec.res->events[i][b->landing].touch_deg = t * d->deg_per_s - 720.0 * d->rec.cyc;
    b->touched = 1;
    b->landing = -1;
    b->cand = seated ? NAN : t;
    return rc;
}

/* The new mode of ring i at (t, y): `fired` says its root was found (or,
 * at the start, that the check is due).  With a band its events come at
 * the band's edges (band_cross); here where a leave left the flank and a
 * landing touched it. */
static int ring_switch(drv *d, int i, double t, double *y, const double *pv, int fired,
                       rd_error *err)
{
    rd_ringpack_model *m = &d->m;
    double F = rd_ringpack_ring_force(m, i, t, y, pv), z = RP_Z(m, y, i), a = m->ca[i];
    int mode = m->mode[i];
    if (!fired || m->p->rings[i].pinned != RD_PIN_FREE)
        return RD_OK;
    if ((mode == RD_FLANK_LOWER && F >= 0.0) || (mode == RD_FLANK_UPPER && F <= 0.0)) {
        m->mode[i] = RD_FLANK_FREE;
        d->band[i].cand = t;
        return d->banded ? RD_OK : push_event(d, i, t, flank_event(mode, 1), t, err);
    }
    if (mode != RD_FLANK_FREE)
        return RD_OK;
    /* landed: on the flank, not moving into it; seated if F presses it there */
    int upper = z > 0.5 * a, flank = upper ? RD_FLANK_UPPER : RD_FLANK_LOWER;
    int seated = upper ? F >= 0.0 : F <= 0.0;
    RP_Z(m, y, i) = upper ? a : 0.0;
    RP_ZD(m, y, i) = upper ? fmin(RP_ZD(m, y, i), 0.0) : fmax(RP_ZD(m, y, i), 0.0);
    if (seated) {
        m->mode[i] = flank;
        RP_ZD(m, y, i) = 0.0;
    }
    if (d->banded)
        return band_touch(d, i, t, flank, seated, err);
    return seated ? push_event(d, i, t, flank_event(flank, 0), t, err) : RD_OK;
}

/* Adds CVODE's counters since its last (re)start to the result's (a restart
 * zeroes them). */
static void counters(drv *d, rd_ringpack_result *r)
{
    long v;
    if (!CVodeGetNumSteps(d->cs.cv, &v))
        r->steps += v;
    if (!CVodeGetNumRhsEvals(d->cs.cv, &v))
        r->rhs_evals += v;
    if (!CVodeGetNumJacEvals(d->cs.cv, &v))
        r->jac_evals += v;
    if (!CVodeGetNumGEvals(d->cs.cv, &v))
        r->root_evals += v;
    if (!CVodeGetNumErrTestFails(d->cs.cv, &v))
        r->err_test_fails += v;
    if (!CVodeGetNumNonlinSolvConvFails(d->cs.cv, &v))
        r->nonlin_fails += v;
}

/* A lift ring at a root (or at the start: all == 1): the lift driver's
 * flank state machine (rd_lift_track_roots); no restart (its flanks are
 * penalty contacts). */
static int lift_switch(drv *d, int i, double t, const double *y, const double *pv, const int *rf,
                       int all, rd_error *err)
{
    rd_ringpack_model *m = &d->m;
    rd_packring *L = m->lr[i];
    double f[3], fz, fr;
    int any = 0;
    for (int k = 0; k < NR; k++)
        any |= rf[k] != 0;
    if (!all && !any)
        return RD_OK;
    rd_ringpack_faces(m, i, t, pv, f);
    rd_packring_gas(L, f);
    rd_packring_loads(L, t, y + m->off[i], &fz, &fr);
    if (all) { /* seated at rest: a load already pulling it away dates a leave at 0 */
        *rd_packring_track(L) = rd_lift_track_seated(rd_packring_track(L)->banded, fz, t);
        return RD_OK;
    }
    return rd_lift_track_roots(rd_packring_track(L), rf, t, d->deg_per_s, fz, rd_packring_events(L),
                               err);
}

/* Mode changes at a root (or at the start: all == 1), then the restart
 * when an axial ring changed. */
static int at_root(drv *d, double t, int all, rd_error *err)
{
    int found[NR * RD_RINGPACK_RINGS_MAX] = {0}, flag, rc = RD_OK, axial = all;
    double pv[RD_RINGPACK_VOLUMES_MAX], *y = N_VGetArrayPointer(d->y);
    if (!all && (flag = CVodeGetRootInfo(d->cs.cv, found)))
        return cv_fail(d, flag, "root info", err);
    rd_ringpack_pressures(&d->m, t, y, pv);
    for (int i = 0; !rc && i < d->m.R; i++) {
        const int *rf = found + NR * i;
        if (d->m.lr[i]) {
            rc = lift_switch(d, i, t, y, pv, rf, all, err);
            continue;
        }
        if (all) /* at rest on its flank (or pinned there) */
            d->band[i] = (band_state){d->m.mode[i], 1, -1, NAN};
        if (d->banded && !all && (rf[2] || rf[3])) /* first: the band (header comment) */
            rc = band_cross(d, i, t, rf, err);
        axial |= rf[0] || rf[1]; /* a mode change: the restart; a band crossing: none */
        rc = rc ? rc : ring_switch(d, i, t, y, pv, all || rf[0] || rf[1], err);
    }
    if (rc || !axial)
        return rc;
    if (!all && ++d->rec.res->restarts > RESTARTS_MAX)
        return rd_error_set(err, RD_ELIMIT, "",
                            "More than %d flank changes near crank angle %.2f deg: a ring "
                            "chatters on its flank; pin it or change the clearances.",
                            RESTARTS_MAX, t * d->deg_per_s);
    counters(d, d->rec.res);
    if ((flag = CVodeReInit(d->cs.cv, t, d->y)))
        return cv_fail(d, flag, "restart", err);
    return RD_OK;
}

/* Sample k of the recorded cycle at t (rd_ringpack_record). */
static void record(drv *d, int k, double t)
{
    int flank[RD_RINGPACK_RINGS_MAX];
    double pv[RD_RINGPACK_VOLUMES_MAX], *y = N_VGetArrayPointer(d->y);
    for (int i = 0; i < d->m.R; i++)
        flank[i] = d->banded ? d->band[i].band : d->m.mode[i];
    rd_ringpack_record(&d->rec, &d->m, flank, k, t, y);
    rd_ringpack_pressures(&d->m, t, y, pv);
    rd_ringpack_films_sample(&d->m, k, t, pv);
}

/* The work bound over the whole run (the restarts zero CVODE's counter). */
static int work_bound(drv *d, double t, rd_error *err)
{
    long now = 0;
    if (CVodeGetNumSteps(d->cs.cv, &now) || d->rec.res->steps + now <= d->m.p->max_steps)
        return RD_OK;
    size_t m = rd_error_enter(err, "/numerics");
    int rc = rd_error_set(err, RD_ELIMIT, "/max_steps",
                          "The run needed more than @/max_steps = %ld CVODE steps by crank angle "
                          "%.2f deg (of %d cycles); raise it, or loosen @/rtol.",
                          d->m.p->max_steps, t * d->deg_per_s, d->rec.C);
    rd_error_leave(err, m);
    return rc;
}

/* Steps per CVode call with lift rings, so the monitor is asked often: as
 * the lift driver's (rd_lift_driver.c), 2000 segment-steps (~45 ms); 0:
 * none (axial rings: a sample costs microseconds). */
static long step_chunk(const rd_ringpack_model *m)
{
    int n = 0;
    for (int i = 0; i < m->R; i++)
        if (m->lr[i])
            n = m->kind[i] == RD_LIFT_MODEL_RIGID
                    ? (n > 1 ? n : 1)
                    : (m->p->rings[i].segments > n ? m->p->rings[i].segments : n);
    return n ? (2000 / n > 1 ? 2000 / n : 1) : 0;
}

/* The whole run: C cycles, sampled at every output angle. */
static int integrate(drv *d, const rd_monitor *mon, rd_error *err)
{
    double t = 0.0, dt = 720.0 / d->rec.S / d->deg_per_s;
    int total = d->rec.C * d->rec.S, rc = at_root(d, 0.0, 1, err), flag;
    long chunk = step_chunk(&d->m);
    if (rc || (chunk && (flag = CVodeSetMaxNumSteps(d->cs.cv, chunk))))
        return rc ? rc : cv_fail(d, flag, "set-up", err);
    record(d, 0, 0.0);
    for (int j = 1; j <= total && !d->rec.done; j++) {
        double tout = j * dt;
        while (t < tout) {
            flag = CVode(d->cs.cv, tout, d->y, &t, CV_NORMAL);
            if (flag == CV_ROOT_RETURN) {
                if ((rc = at_root(d, t, 0, err)))
                    return rc;
            } else if (flag == CV_TOO_MUCH_WORK && chunk) { /* a chunk ended */
                if ((rc = work_bound(d, t, err)) ||
                    (rc = rd_monitor_report(mon, (j - 1.0) / total, err)))
                    return rc;
            } else if (flag < 0) {
                return cv_failed(d, flag, err);
            } else {
                t = tout;
            }
        }
        int k = j - d->rec.cyc * d->rec.S;
        record(d, k, t);
        if (k == d->rec.S) {
            rd_ringpack_cycle_end(&d->rec, &d->m);
            for (int i = 0; !d->rec.done && i < d->m.R; i++)
                d->band[i].landing = -1; /* a landing of the cycle before awaits no touch */
            if (!d->rec.done && (rc = rd_ringpack_films_cycle(&d->m, d->rec.cyc, err)))
                return rc;
        }
        if ((rc = work_bound(d, t, err)) || (rc = rd_monitor_report(mon, (double)j / total, err)))
            return rc;
    }
    return RD_OK;
}

/* The lift rings' flank changes of the last cycle into the result. */
static int lift_events(drv *d, rd_error *err)
{
    for (int i = 0; i < d->m.R; i++) {
        if (!d->m.lr[i])
            continue;
        const rd_lift_pass *o = rd_packring_events(d->m.lr[i]);
        for (int e = 0; e < o->n_events; e++) { /* its absolute angles; NAN stays NAN */
            const rd_lift_event *ev = &o->events[e];
            int rc = push_event(d, i, ev->crank_deg / d->deg_per_s, ev->kind,
                                ev->touch_deg / d->deg_per_s, err);
            if (rc)
                return rc;
        }
    }
    return RD_OK;
}

/* One run of p at (rtol, atol) into r, on the handle's lift rings. */
static int run_once(rd_ringpack *h, const rd_ringpack_params *p, double rtol, double atol,
                    const rd_monitor *mon, rd_ringpack_result *r, rd_error *err)
{
    drv d;
    memset(&d, 0, sizeof d);
    d.rings = h->ring;
    d.rec.res = r;
    d.rec.C = (int)p->engine.cycles;
    d.rec.S = (int)lround(720.0 / p->step_deg);
    int rc = drv_open(&d, p, rtol, atol, err);
    rc = rc ? rc : rd_ringpack_record_open(&d.rec, &d.m, r, err);
    rc = rc ? rc : integrate(&d, mon, err);
    if (!rc) {
        counters(&d, r);
        rc = lift_events(&d, err);
    }
    rc = rc ? rc : rd_ringpack_films_result(&d.m, r, err);
    drv_close(&d);
    return rc;
}

/* ------------------------------------------------------- accuracy driver */

typedef struct acc {
    rd_ringpack *h;
    const rd_ringpack_params *p;
    rd_ringpack_result *out, ref;
} acc;

/* Level 1 differs from level 0 in the cycles, the periodic rule and the
 * tolerances only: the lift rings' models (which read none of them) are
 * the same. */
static int acc_solve(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    acc *a = ctx;
    if (!level)
        return run_once(a->h, a->p, a->p->rtol, a->p->atol, mon, a->out, err);
    rd_ringpack_params q = *a->p; /* as many cycles as the run it checks */
    q.periodic = 0;
    q.engine.cycles = a->out->cycles;
    q.estimate_error = 0; /* the films' own estimate is the main run's */
    return run_once(a->h, &q, q.rtol * 0.1, q.atol * 0.1, mon, &a->ref, err);
}

/* The estimate: the larger of the blow-by's relative change and the
 * largest pressure change relative to the cylinder peak; the events'
 * largest angle change when both runs have the same flank changes. */
static int acc_compare(void *ctx, rd_error *err)
{
    (void)err;
    acc *a = ctx;
    rd_ringpack_result *r = a->out, *q = &a->ref;
    size_t n = (size_t)r->samples * r->n_volumes;
    double peak = 0.0, dp = 0.0, de = 0.0;
    for (size_t k = 0; k < n; k++) {
        peak = fmax(peak, r->pressure[k]);
        dp = fmax(dp, fabs(r->pressure[k] - q->pressure[k]));
    }
    r->error_estimate =
        fmax(dp / peak, fabs(r->blowby_kg - q->blowby_kg) / fmax(fabs(q->blowby_kg), 1e-300));
    for (int i = 0; i < r->n_rings; i++) {
        if (r->n_events[i] != q->n_events[i]) {
            de = NAN;
            break;
        }
        for (int e = 0; e < r->n_events[i]; e++)
            de = fmax(de, fabs(r->events[i][e].crank_deg - q->events[i][e].crank_deg));
    }
    r->event_error_deg = de;
    return RD_OK;
}

static void result_init(rd_ringpack_result *out)
{
    memset(out, 0, sizeof *out);
    out->error_estimate = out->event_error_deg = NAN;
}

int rd_ringpack_create(const rd_ringpack_params *p, rd_ringpack **out, rd_error *err)
{
    *out = NULL;
    int rc = rd_ringpack_validate(p, err);
    if (rc)
        return rc;
    if (!(*out = calloc(1, sizeof **out)))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the ring pack.");
    (*out)->p = *p;
    return RD_OK;
}

int rd_ringpack_run(rd_ringpack *h, const rd_monitor *mon, rd_ringpack_result *out, rd_error *err)
{
    result_init(out);
    acc a = {h, &h->p, out, {0}};
    rd_accuracy_plan plan = {.solve = acc_solve,
                             .compare = acc_compare,
                             .ctx = &a,
                             .estimate = h->p.estimate_error,
                             .main_share = 0.5,
                             .reference = "rtol/10, atol/10"};
    int rc = rd_accuracy_run(&plan, mon, NULL, err);
    rd_ringpack_result_cleanup(&a.ref);
    return rc;
}

void rd_ringpack_free(rd_ringpack *h)
{
    if (!h)
        return;
    for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++)
        rd_packring_free(h->ring[i]);
    free(h);
}

int rd_ringpack_solve(const rd_ringpack_params *p, const rd_monitor *mon, rd_ringpack_result *out,
                      rd_error *err)
{
    rd_ringpack *h = NULL;
    result_init(out);
    int rc = rd_ringpack_create(p, &h, err);
    if (rc == RD_OK)
        rc = rd_ringpack_run(h, mon, out, err);
    rd_ringpack_free(h);
    return rc;
}

void rd_ringpack_result_cleanup(rd_ringpack_result *r)
{
    if (!r)
        return;
    free(r->crank_deg);
    free(r->pressure);
    free(r->lift);
    free(r->flank);
    free(r->friction);
    free(r->flow);
    for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++) {
        free(r->events[i]);
        rd_lift_lube_cleanup(&r->lube[i]);
    }
    memset(r, 0, sizeof *r);
}
