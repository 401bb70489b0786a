/*
 * test_ringpack_band — the ring pack's flank changes dated at the band
 * (issue 39, item 1; rd_ringpack.h "Flank changes", output.flank_band).
 *
 * The scene with a closed form: one ring driven by the pack's test hook
 * (fixed gauge face pressures: above 0, behind 0, below P), no friction,
 * the approximate piston kinematics (thesis 1.6-1.8,
 * s(t) = r (1 - cos wt + lam/4 (1 - cos 2 wt))).  The axial ring's net force
 * is then m (s''(t) - G) with G = g - P / (rho h) (F = m (s'' - g) + A P and
 * m = rho h A): a function of time only, so a free flight from rest at
 * (t0, z0) is, exactly,
 *   z(t) = z0 + s(t) - s(t0) - s'(t0) (t - t0) - G (t - t0)^2 / 2.
 * The reference below is the axial ring's hard-stop model (rd_ringpack.h)
 * written again on that closed form: seated until s'' - G turns away from
 * the flank, inelastic landings, a landing against the load leaving again
 * from rest; every root found by a scan of 0.002 deg and bisection to
 * round-off, with the band dating of rd_ringpack.h.  The pack integrates z
 * (CVODE) and finds the roots on its interpolant: its events must meet the
 * reference's within the integration's error.
 *
 *   (1) the axial ring, G = g (inertia and gravity only): band-dated events
 *       and their touch_deg against the reference; flank_band 0 against the
 *       reference's touch dating; flank_band 0's events against flank_band
 *       0.01's touch_deg (the same integration but for round-off: only the
 *       dating differs; TOL_SAME);
 *       a landing's touch after it, a leave's before it; the sampled lift
 *       crossing the band's edge within one sample of each event, and the
 *       samples' flank the band the lift is in;
 *   (2) the axial ring landing against its load (P chosen so that s'' - G
 *       is negative only in two narrow windows before and after BDC, and
 *       a clearance the falling ring crosses only after s'' - G has turned
 *       up again): in the band at entry, touched at the impact, a leave
 *       where it moves out, whose touch_deg is the impact; with flank_band
 *       0 no event (today's dating);
 *   (3) the lift rigid ring in the pack on scene (1): its penalty flanks
 *       against the same reference, and (1)'s checks of its own runs;
 *   (4) validation: flank_band -0.1, 0.3 and NaN refused at
 *       /output/flank_band with the value and the range, 0 and 0.2 accepted.
 * About 3 s with the sanitizers.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define GRAVITY 9.80665 /* the pack's */
#define REF_MAX 64
#define SCAN    0.002 /* deg: the reference's root scan */
#define ZARM    1e-14 /* m: a flight counts its return to its flank once this far off */

/* ---- the reference (file comment) ---- */

typedef struct ref_scene {
    double w, r, lam; /* crank speed rad/s, crank radius m, r / l */
    double G, a, e;   /* effective gravity m/s^2, clearance m, band edge m */
} ref_scene;

/* Events in absolute crank degrees, each with the lift's speed (m/s) where
 * it is dated (slope) and touched (tslope): NAN where it is dated by the
 * force turning away instead (a leave from the flank), whose date does not
 * depend on the lift. */
typedef struct ref_out {
    int n, n0; /* band-dated, touch-dated (flank_band 0) */
    rd_lift_event ev[REF_MAX], ev0[REF_MAX];
    double slope[REF_MAX], tslope[REF_MAX], slope0[REF_MAX];
} ref_out;

static double s_at(const ref_scene *q, double t)
{
    double th = q->w * t;
    return q->r * (1.0 - cos(th) + 0.25 * q->lam * (1.0 - cos(2.0 * th)));
}

static double v_at(const ref_scene *q, double t)
{
    double th = q->w * t;
    return q->r * q->w * (sin(th) + 0.5 * q->lam * sin(2.0 * th));
}

/* The ring's acceleration in the groove, free: s'' - G. */
static double acc(const ref_scene *q, double t)
{
    double th = q->w * t;
    return q->r * q->w * q->w * (cos(th) + q->lam * cos(2.0 * th)) - q->G;
}

/* The flight from rest at (t0, z0): its lift and speed at t. */
static double z_at(const ref_scene *q, double t0, double z0, double t)
{
    double tau = t - t0;
    return z0 + s_at(q, t) - s_at(q, t0) - v_at(q, t0) * tau - 0.5 * q->G * tau * tau;
}

static double zd_at(const ref_scene *q, double t0, double t)
{
    return v_at(q, t) - v_at(q, t0) - q->G * (t - t0);
}

/* Where z(t) - c (c = NAN: acc) changes sign in [lo, hi], to round-off. */
static double bisect(const ref_scene *q, double t0, double z0, double c, double lo, double hi)
{
    double flo = isnan(c) ? acc(q, lo) : z_at(q, t0, z0, lo) - c;
    for (;;) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            return hi;
        double fm = isnan(c) ? acc(q, mid) : z_at(q, t0, z0, mid) - c;
        if ((fm > 0.0) == (flo > 0.0)) {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
}

typedef struct ref_state {
    int mode, band, touched, landing; /* enum rd_flank x2, 0/1, index or -1 */
    double cand, cslope;              /* left the flank (s, NAN), the speed there */
    double t0, z0;                    /* the flight's start */
} ref_state;

static int reach(int flank)
{
    return flank == RD_FLANK_UPPER ? RD_EVENT_REACH_UPPER : RD_EVENT_REACH_LOWER;
}

static int leave(int flank)
{
    return flank == RD_FLANK_UPPER ? RD_EVENT_LEAVE_UPPER : RD_EVENT_LEAVE_LOWER;
}

static void push(rd_lift_event *ev, double *slope, int *n, double deg, int kind, double touch,
                 double v)
{
    if (*n < REF_MAX) {
        ev[*n] = (rd_lift_event){deg, kind, touch};
        slope[*n] = fabs(v);
    }
    (*n)++;
}

/* The next root after t of the ring in state st, its time into *tr: 0
 * the lower flank, 1 the upper, 2 the lower band's edge, 3 the upper's
 * (both ways), 4 the force turning away (seated); -1 none before T.  A
 * flight's own flank counts once it got ZARM away. */
static int next_root(const ref_scene *q, const ref_state *st, double t, double T, double h,
                     double *tr)
{
    if (st->mode != RD_FLANK_FREE) {
        int away = st->mode == RD_FLANK_LOWER ? +1 : -1;
        for (double lo = t, hi = t + h; lo < T; lo = hi, hi += h)
            if (acc(q, hi) * away >= 0.0) {
                *tr = bisect(q, 0.0, 0.0, NAN, lo, hi);
                return 4;
            }
        return -1;
    }
    double zp = z_at(q, st->t0, st->z0, t), edge[2] = {q->e, q->a - q->e};
    int armed[2] = {st->z0 > 0.5 * q->a, st->z0 < 0.5 * q->a};
    for (double lo = t, hi = t + h; lo < T; lo = hi, hi += h) {
        double z = z_at(q, st->t0, st->z0, hi), best = INFINITY;
        int k = -1;
        for (int b = 0; b < 2; b++)
            if ((zp > edge[b]) != (z > edge[b])) {
                double r = bisect(q, st->t0, st->z0, edge[b], lo, hi);
                if (r < best)
                    best = r, k = 2 + b;
            }
        if (armed[0] && z <= 0.0) { /* an impact after the edge's crossing, if both */
            double r = bisect(q, st->t0, st->z0, 0.0, lo, hi);
            if (r < best)
                best = r, k = 0;
        }
        if (armed[1] && z >= q->a) {
            double r = bisect(q, st->t0, st->z0, q->a, lo, hi);
            if (r < best)
                best = r, k = 1;
        }
        if (k >= 0) {
            *tr = best;
            return k;
        }
        armed[0] |= z > ZARM;
        armed[1] |= z < q->a - ZARM;
        zp = z;
    }
    return -1;
}

/* The band's edge at t (k = 2 lower, 3 upper): a landing into it, a leave
 * out of it with its touch (where z last left the flank). */
static void ref_edge(const ref_scene *q, ref_state *st, ref_out *o, int k, double t, double dps)
{
    int flank = k == 2 ? RD_FLANK_LOWER : RD_FLANK_UPPER;
    double v = zd_at(q, st->t0, t), deg = t * dps;
    int into = flank == RD_FLANK_LOWER ? v < 0.0 : v > 0.0;
    if (into && st->band == RD_FLANK_FREE) {
        *st = (ref_state){st->mode, flank, 0, o->n, NAN, NAN, st->t0, st->z0};
        push(o->ev, o->slope, &o->n, deg, reach(flank), NAN, v);
    } else if (!into && st->band == flank) {
        double touch = st->touched ? (isnan(st->cand) ? t : st->cand) * dps : NAN;
        if (o->n < REF_MAX)
            o->tslope[o->n] = st->cslope;
        push(o->ev, o->slope, &o->n, deg, leave(flank), touch, v);
        *st = (ref_state){st->mode, RD_FLANK_FREE, 0, -1, NAN, NAN, st->t0, st->z0};
    }
}

/* The reference over `cycles` cycles from rest on the lower flank. */
static void ref_run(const ref_scene *q, double cycles, ref_out *o)
{
    double dps = q->w * 180.0 / M_PI, T = cycles * 720.0 / dps, h = SCAN / dps, t = 0.0;
    ref_state st = {RD_FLANK_LOWER, RD_FLANK_LOWER, 1, -1, NAN, NAN, 0.0, 0.0};
    o->n = o->n0 = 0;
    int k = acc(q, 0.0) >= 0.0 ? 4 : next_root(q, &st, t, T, h, &t); /* pulled away at 0 */
    while (k >= 0) {
        double deg = t * dps;
        if (k == 4) { /* leaves its flank from rest */
            int flank = st.mode;
            push(o->ev0, o->slope0, &o->n0, deg, leave(flank), deg, NAN);
            st.mode = RD_FLANK_FREE;
            st.cand = st.t0 = t;
            st.cslope = NAN; /* the force's root */
            st.z0 = flank == RD_FLANK_UPPER ? q->a : 0.0;
        } else if (k >= 2) {
            ref_edge(q, &st, o, k, t, dps);
        } else { /* an impact: seated, or from rest again against its load */
            int flank = k == 1 ? RD_FLANK_UPPER : RD_FLANK_LOWER;
            int seated = flank == RD_FLANK_UPPER ? acc(q, t) >= 0.0 : acc(q, t) <= 0.0;
            double v = zd_at(q, st.t0, t);
            if (!st.touched && st.landing >= 0 && st.landing < REF_MAX) {
                o->ev[st.landing].touch_deg = deg;
                o->tslope[st.landing] = fabs(v);
            }
            st.touched = 1;
            st.landing = -1;
            st.cand = seated ? NAN : t;
            st.cslope = fabs(v);
            if (seated) {
                st.mode = flank;
                push(o->ev0, o->slope0, &o->n0, deg, reach(flank), deg, v);
            }
            st.t0 = t;
            st.z0 = flank == RD_FLANK_UPPER ? q->a : 0.0;
        }
        k = next_root(q, &st, t, T, h, &t);
    }
}

/* ---- the pack on the same scene ---- */

static double tab_deg[2] = {0.0, 720.0}, tab_zero[2] = {0.0, 0.0}, tab_below[2];
static const rd_gas_params tables = {2, tab_deg, tab_zero, tab_zero, tab_below, RD_GAS_AREA_FIXED};

/* The pack's scene (file comment): below = P gauge, clearance a, two
 * cycles, the approximate kinematics, at rtol, atol. */
static void scene(rd_ringpack_params *p, double P, double a, int model, double rtol, double atol)
{
    rd_ringpack_params_default(p);
    p->engine.kinematics = RD_KINEMATICS_APPROXIMATE;
    p->engine.cycles = 2;
    p->estimate_error = 0;
    p->rings[0].groove.axial_clearance = a;
    p->model = model;
    tab_below[0] = tab_below[1] = P;
    p->face_tables = &tables;
    p->rtol = rtol;
    p->atol = atol;
    p->step_deg = 0.25;
}

static ref_scene reference_of(const rd_ringpack_params *p, double P)
{
    const rd_engine_params *e = &p->engine;
    const rd_ring_params *rp = &p->rings[0].ring;
    double a = p->rings[0].groove.axial_clearance;
    return (ref_scene){e->speed_rpm * M_PI / 30.0,
                       e->crank_radius,
                       e->crank_radius / e->rod_length,
                       GRAVITY - P / (rp->density * rp->axial_height),
                       a,
                       p->flank_band * a};
}

static int run(const rd_ringpack_params *p, rd_ringpack_result *r, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    return rc;
}

/* The largest differences of a comparison: of the dates (deg), of those
 * dated on the lift turned into lift (m: times the reference's speed
 * there, the date's own condition), of those dated by the force's root
 * (deg). */
typedef struct diffs {
    double deg, lift, root;
} diffs;

static void add_diff(diffs *d, double x, double y, double slope, double dps)
{
    if (isnan(x) && isnan(y))
        return;
    double g = isnan(x) || isnan(y) ? INFINITY : fabs(x - y);
    d->deg = fmax(d->deg, g);
    if (isnan(slope))
        d->root = fmax(d->root, g);
    else
        d->lift = fmax(d->lift, g / dps * slope);
}

/* The pack's last-cycle events against the reference's from t0 deg on
 * (kinds, dates, touch_deg), shifted by t0. */
static diffs against(const rd_ringpack_result *r, const rd_lift_event *ev, const double *slope,
                     const double *tslope, int n, double t0, double dps, const char *what)
{
    diffs d = {0.0, 0.0, 0.0};
    int e0 = 0;
    while (e0 < n && ev[e0].crank_deg < t0)
        e0++;
    CHECK(n - e0 == r->n_events[0] && n <= REF_MAX, "%s: %d events, the reference %d", what,
          r->n_events[0], n - e0);
    for (int k = 0; k < r->n_events[0] && e0 + k < n && n <= REF_MAX; k++) {
        const rd_lift_event *p = &r->events[0][k], *q = &ev[e0 + k];
        CHECK(p->kind == q->kind, "%s: event %d kind %d, the reference's %d", what, k, p->kind,
              q->kind);
        add_diff(&d, p->crank_deg, q->crank_deg - t0, slope[e0 + k], dps);
        if (tslope)
            add_diff(&d, p->touch_deg, q->touch_deg - t0, tslope[e0 + k], dps);
    }
    return d;
}

/* A landing's touch after it, a leave's before it (NAN: never touched);
 * the sampled lift crossing the band's edge, the event's way, within one
 * sample of each event; the samples' flank the band the lift is in. */
static void check_band(const rd_ringpack_result *r, double a, double band, const char *what)
{
    double e = band * a, step = 720.0 / (r->samples - 1);
    int order = 1, cross = 1, flank = 1;
    for (int k = 0; k < r->n_events[0]; k++) {
        const rd_lift_event *p = &r->events[0][k];
        int land = p->kind == RD_EVENT_REACH_LOWER || p->kind == RD_EVENT_REACH_UPPER;
        int upper = p->kind == RD_EVENT_REACH_UPPER || p->kind == RD_EVENT_LEAVE_UPPER;
        if (!isnan(p->touch_deg))
            order &= land ? p->touch_deg >= p->crank_deg : p->touch_deg <= p->crank_deg;
        double edge = upper ? a - e : e;
        int found = 0, j0 = (int)floor(p->crank_deg / step);
        for (int j = j0 - 1 < 0 ? 0 : j0 - 1; j <= j0 + 1 && j + 1 < r->samples; j++) {
            int in0 = upper ? r->lift[j] > edge : r->lift[j] < edge;
            int in1 = upper ? r->lift[j + 1] > edge : r->lift[j + 1] < edge;
            found |= land ? !in0 && in1 : in0 && !in1;
        }
        cross &= found;
    }
    for (int j = 0; j < r->samples; j++) {
        double l = r->lift[j];
        flank &= r->flank[j] == (l < e       ? RD_FLANK_LOWER
                                 : l > a - e ? RD_FLANK_UPPER
                                             : RD_FLANK_FREE);
    }
    CHECK(order, "%s: a landing's touch_deg before it or a leave's after it", what);
    CHECK(cross, "%s: an event without the lift crossing the band's edge within a sample", what);
    CHECK(flank, "%s: the samples' flank is not the band the lift is in", what);
}

/* flank_band 0's events against the band's touch_deg: the band's events
 * without a touch (bounces within the band) and its landing-leave pairs
 * touched at one impact (against the load: no event at flank_band 0)
 * dropped, the rest one to one.  The largest difference, deg; the pairs
 * dropped into *impacts. */
static double zero_vs_touch(const rd_ringpack_result *r0, const rd_ringpack_result *rb,
                            int *impacts, const char *what)
{
    double worst = 0.0;
    int j = 0, n = rb->n_events[0], bad = 0;
    const rd_lift_event *b = rb->events[0];
    *impacts = 0;
    for (int k = 0; k < n && !bad; k++) {
        int land = b[k].kind == RD_EVENT_REACH_LOWER || b[k].kind == RD_EVENT_REACH_UPPER;
        if (isnan(b[k].touch_deg))
            continue;
        if (land && k + 1 < n && b[k + 1].touch_deg == b[k].touch_deg) {
            k++;
            (*impacts)++;
            continue;
        }
        bad = j >= r0->n_events[0] || r0->events[0][j].kind != b[k].kind;
        worst = bad ? INFINITY : fmax(worst, fabs(r0->events[0][j++].crank_deg - b[k].touch_deg));
    }
    CHECK(!bad && j == r0->n_events[0],
          "%s: flank_band 0's %d events do not pair with the band's touches (%d paired)", what,
          r0->n_events[0], j);
    return bad ? INFINITY : worst;
}

/* Tolerances, measured with the sanitizers' build (the printout).  The
 * pack integrates z at rtol 1e-10, atol 1e-15 m here: an event dated on
 * the lift is off by the lift's global error over the reference's speed
 * there, so that comparison is made in lift: TOL_Z 1e-12 m, the per-step
 * tolerance on z (rtol a + atol, ~5e-15 m) over a flight's hundreds of
 * steps (measured 3e-14 m and 6e-14 m: 3e-8 deg at the slowest crossing,
 * the band's edge after a leave, at ~7 mm/s).  A leave's touch is the root
 * of a function of time alone (the net force; no state enters it here):
 * TOL_ROOT, measured 1e-11 deg.  flank_band 0 against the band's
 * touch_deg: the same integration, but the band's roots move the
 * landings' roots (and the restarts there) by CVODE's root tolerance, so
 * the runs part by round-off: TOL_SAME, measured 5e-10 deg (at the
 * default rtol 1e-6 and atol 1e-9 the restarts' step sequences then part:
 * 4e-5 deg on scene (1), within the integration's error; a lift ring never
 * restarts: 0). */
#define TOL_Z    1e-12
#define TOL_ROOT 1e-6
#define TOL_SAME 1e-6
#define BAND     0.01

/* (1) and (2): the axial ring on scene (P, a); impact: the reference must
 * land against its load in the last cycle (2). */
static void test_axial(double P, double a, int impact, const char *what)
{
    rd_ringpack_params p;
    rd_ringpack_result rb, r0;
    static ref_out o;
    scene(&p, P, a, RD_RINGPACK_AXIAL, 1e-10, 1e-15);
    p.flank_band = BAND;
    ref_scene q = reference_of(&p, P);
    double dps = q.w * 180.0 / M_PI;
    ref_run(&q, p.engine.cycles, &o);
    int ok = run(&p, &rb, what) == RD_OK;
    p.flank_band = 0.0;
    ok = run(&p, &r0, what) == RD_OK && ok;
    if (ok) {
        int impacts;
        diffs db = against(&rb, o.ev, o.slope, o.tslope, o.n, 720.0, dps, what);
        diffs d0 = against(&r0, o.ev0, o.slope0, NULL, o.n0, 720.0, dps, what);
        double same = zero_vs_touch(&r0, &rb, &impacts, what);
        printf("%s: %d band-dated flank changes (%d landings against the load), dates and "
               "touches within %.3g deg of the closed form (%.3g m as lift, force roots "
               "%.3g deg); flank_band 0: %d within %.3g deg (%.3g m); its dates against the "
               "band's touch_deg within %.3g deg\n",
               what, rb.n_events[0], impacts, db.deg, db.lift, db.root, r0.n_events[0], d0.deg,
               d0.lift, same);
        CHECK(db.lift <= TOL_Z && db.root <= TOL_ROOT && d0.lift <= TOL_Z && d0.root <= TOL_ROOT,
              "%s: band %.3g m, %.3g deg; flank_band 0 %.3g m, %.3g deg", what, db.lift, db.root,
              d0.lift, d0.root);
        CHECK(same <= TOL_SAME, "%s: flank_band 0 against the touches %.3g deg", what, same);
        CHECK(impact ? impacts > 0 : impacts == 0, "%s: %d landings against the load", what,
              impacts);
        check_band(&rb, a, BAND, what);
        /* the dating must matter: the first event, a leave, moves out of
         * the band degrees after it left the flank */
        CHECK(rb.n_events[0] > 0 && rb.events[0][0].crank_deg - rb.events[0][0].touch_deg > 1.0,
              "%s: the first event at %.4f deg, touched %.4f", what,
              rb.n_events[0] ? rb.events[0][0].crank_deg : NAN,
              rb.n_events[0] ? rb.events[0][0].touch_deg : NAN);
    }
    rd_ringpack_result_cleanup(&rb);
    rd_ringpack_result_cleanup(&r0);
}

/* (2) A ring landing against its load.  With P the net acceleration
 * s'' - G is negative only in two windows around BDC: lam = r / l > 1/4
 * puts the minima of cos th + lam cos 2 th at cos th = -1 / (4 lam), where
 * it is -1 / (8 lam) - lam; G 40 m/s^2 above r w^2 times that.  Released
 * from the upper flank in the first window, the ring falls the clearance
 * (5e-5 m) only after the force has turned up again: it reaches the lower
 * flank against its load, and flies back up out of the band (four such
 * impacts in the last cycle, two around each BDC). */
static void test_against_load(void)
{
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    const rd_engine_params *e = &p.engine;
    double w = e->speed_rpm * M_PI / 30.0, lam = e->crank_radius / e->rod_length;
    double G = e->crank_radius * w * w * (-1.0 / (8.0 * lam) - lam) + 40.0;
    double rh = p.rings[0].ring.density * p.rings[0].ring.axial_height;
    test_axial((GRAVITY - G) * rh, 5e-5, 1, "axial ring, landing against its load");
}

/* (3) The lift rigid ring in the pack on scene (1).  Its flanks are
 * penalty contacts with a quadratic start over d0 = 1e-4 c_a
 * (rd_lift_forces.c): seated, it sinks a fraction of d0 into the flank,
 * and unloading that start sends it off with a little speed, so its
 * flights run ahead of the hard stops' by a lift growing along them
 * (measured 4e-10 m at the leaves' band exits, 1.8 deg after the leave,
 * 2.9e-9 m at the landings 8 deg after; the dates 0.0014 deg and 0.0003
 * deg early; 0.0009 and 0.0002 at rtol 1e-9: the models' difference, not
 * the integration's).  So its dates against the closed form within
 * TOL_PENALTY, 7x that; its leaves' touch is the load's root, the same
 * function of time: TOL_ROOT.  Against the lift analysis' own driver on
 * the same ring: test_ringpack_lift.  rtol 1e-8, atol 1e-12: the contact's
 * stiffness takes ~60x the axial ring's steps. */
#define TOL_PENALTY 0.01
static void test_lift_ring(void)
{
    rd_ringpack_params p;
    rd_ringpack_result rb, r0;
    static ref_out o;
    const char *what = "lift rigid ring, inertia and gravity";
    double a = 3e-5;
    scene(&p, 0.0, a, RD_LIFT_MODEL_RIGID, 1e-8, 1e-12);
    p.flank_band = BAND;
    ref_scene q = reference_of(&p, 0.0);
    double dps = q.w * 180.0 / M_PI;
    ref_run(&q, p.engine.cycles, &o);
    int ok = run(&p, &rb, what) == RD_OK;
    p.flank_band = 0.0;
    ok = run(&p, &r0, what) == RD_OK && ok;
    if (ok) {
        int impacts;
        diffs db = against(&rb, o.ev, o.slope, o.tslope, o.n, 720.0, dps, what);
        diffs d0 = against(&r0, o.ev0, o.slope0, NULL, o.n0, 720.0, dps, what);
        double same = zero_vs_touch(&r0, &rb, &impacts, what);
        printf("%s: %d band-dated flank changes within %.3g deg of the hard stops' closed form "
               "(%.3g m as lift, force roots %.3g deg); flank_band 0: within %.3g deg (%.3g m); "
               "its dates against the band's touch_deg within %.3g deg\n",
               what, rb.n_events[0], db.deg, db.lift, db.root, d0.deg, d0.lift, same);
        CHECK(rb.ring_model[0] == RD_LIFT_MODEL_RIGID, "%s: model %d", what, rb.ring_model[0]);
        CHECK(db.deg <= TOL_PENALTY && db.root <= TOL_ROOT && d0.deg <= TOL_PENALTY &&
                  d0.root <= TOL_ROOT,
              "%s: band %.3g deg, roots %.3g deg; flank_band 0 %.3g deg, roots %.3g deg", what,
              db.deg, db.root, d0.deg, d0.root);
        CHECK(same <= TOL_SAME && impacts == 0, "%s: flank_band 0 against the touches %.3g deg",
              what, same);
        check_band(&rb, a, BAND, what);
    }
    rd_ringpack_result_cleanup(&rb);
    rd_ringpack_result_cleanup(&r0);
}

/* (4) output.flank_band's range, named with its value and the range. */
static void test_validation(void)
{
    const double bad[] = {-0.1, 0.3, NAN}, good[] = {0.0, RD_LIFT_FLANK_BAND_MAX};
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    CHECK(p.flank_band == RD_LIFT_FLANK_BAND && RD_LIFT_FLANK_BAND == 0.01, "default flank_band %g",
          p.flank_band);
    for (int k = 0; k < 3; k++) {
        rd_error err;
        rd_error_init(&err);
        p.flank_band = bad[k];
        int rc = rd_ringpack_validate(&p, &err);
        char want[96];
        snprintf(want, sizeof want, "/output/flank_band = %g of the axial clearance", bad[k]);
        CHECK(rc == RD_EINVAL && strcmp(err.path, "/output/flank_band") == 0 &&
                  strstr(err.message, want) && strstr(err.message, "allowed 0 to 0.2"),
              "flank_band %g: %d at %s: %s", bad[k], rc, err.path, err.message);
    }
    for (int k = 0; k < 2; k++) {
        rd_error err;
        rd_error_init(&err);
        p.flank_band = good[k];
        CHECK(rd_ringpack_validate(&p, &err) == RD_OK, "flank_band %g: %s", good[k], err.message);
    }
}

int main(void)
{
    test_validation();
    test_axial(0.0, 3e-5, 0, "axial ring, inertia and gravity");
    test_against_load();
    test_lift_ring();
    return check_done();
}
