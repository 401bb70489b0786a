/*
 * bench_lift — what the lift analysis costs per engine cycle and what its
 * segment count and tolerance buy.
 *
 *   bench_lift [--max-n N] [--reps R]
 *     1. The thesis ring at 1000 rpm, inertia only (examples/thesis_lift_
 *        1000rpm.json), one cycle, n = 4 .. 1000: wall time (median of R >= 3
 *        runs), CVODE steps, rhs and Jacobian evaluations, the flank-change
 *        angles of the cycle and their largest change against the finest n;
 *        fitted cost exponent (least-squares slope of log time vs log n over
 *        n >= 32).
 *     2. n = 20: the flank-change angles' error vs rtol (1e-4 .. 1e-8, atol =
 *        1e-3 m x rtol) against a reference run at rtol 1e-10, and the cost.
 *   bench_lift --once N    one cycle, for instruction counts (callgrind).
 *   bench_lift --example-once FILE [--once-reps R] [--rigid] [--plastic]
 *                          one cycle of a lift example as the scene asks (its
 *                          n, rtol, model, error estimate on), for instruction
 *                          counts (callgrind); prints the median wall time of R
 *                          runs (default 1), its counters and events;
 *                          --rigid / --plastic: that model / landing law.
 *   bench_lift --models EXAMPLES_DIR [--reps R]
 *     3. The two lift examples, one cycle each, as the scene asks (its n,
 *        rtol, and the error estimate on, as the API runs it): numerics.model
 *        auto, rigid and full, each with the default penalty landing and with
 *        contact.landing = plastic; wall time (median of R >= 3, including
 *        the error estimate's second run), CVODE steps, Jacobian evaluations
 *        and factorizations (linear-solver set-ups) of the main run, and the
 *        flank changes' largest difference from the full model at n = 40,
 *        rtol 1e-8 (atol 1e-11 m, penalty landing).
 *   bench_lift --modal EXAMPLES_DIR [--reps R]
 *     4. The modal model against the full model it reduces: the two
 *        examples, one cycle, their n and rtol, no error estimate; the full
 *        model, then modal with m = 4, 8, 16, 32 elastic modes: dof, wall
 *        time, steps, and the flank changes' largest difference from the
 *        full model at the same n and rtol.
 *   bench_lift --distorted EXAMPLES_DIR [--reps R]
 *     5. The distorted-bore examples (lift_distorted, lift_distorted_tilted),
 *        one cycle each, as the API runs them (auto, their n and rtol, error
 *        estimate on): the model auto picks, dof, wall time (median of R,
 *        with the load average), steps, and the per-segment flank changes'
 *        largest difference from the full model at n = 40, rtol 1e-8 (atol
 *        1e-11 m); then the same comparison for full at the example's n and
 *        rtol 1e-8 and for full n = 40 at the example's rtol, which split
 *        the difference into the segment count's and the tolerance's parts.
 *        Per-segment flank changes (the analysis reports the mean lift's
 *        only): tests/core/lift_segments.h; a segment of the coarse ring is
 *        compared with the reference ring's flank changes interpolated to its
 *        mid-angle.
 *   bench_lift --segment-estimate EXAMPLES_DIR [--order P] [--no-4n] [--scene K]
 *     6. Would a run at n/2 segments estimate the full model's segment-count
 *        error?  8 scenes (the three 6000 rpm examples, 1000 rpm with Coulomb
 *        friction at 30 and 10 um, gas at 3000 rpm and at 60 um, 1000 rpm
 *        inertia only), one cycle each, full model at the scene's n and rtol:
 *        the candidate est = |f(n) - f(n/2)| / 2^P (same rtol; P default 1.5,
 *        the error against full at 2n that an order-P convergence predicts),
 *        the current estimate |f(n) - f(n, rtol/10)|, the true error against
 *        full at 2n and 4n (rtol 1e-8, atol 1e-11 m) and their ratios, and the
 *        observed order from n/2, n, 2n, 4n at rtol 1e-8; f = the mean lift's
 *        flank changes (deg), the same with each landing dated where the mean
 *        lift comes within 0.5 % of the clearance of the flank ("ev near": the
 *        runs sampled every 0.05 deg, interpolated), and its largest lift
 *        difference / clearance (every 1 deg).
 *        Each run's steps and flank changes go to stderr.  --no-4n skips the
 *        4n runs (the costliest), --scene K runs scene K (0-7) alone.
 *   bench_lift --landing-dating EXAMPLES_DIR [--no-80] [--scene K]
 *     7. Would the rigid ring date the friction scenes' landings as the full
 *        ring does if a landing were dated where the mean lift comes within a
 *        fraction of the clearance of the flank, not where it touches it?
 *        9 scenes (the gas example at 6000, 3000, 8000 rpm; 1000 rpm with
 *        Coulomb friction at 100, 1000 (30 and 10 um), 3000, 8000 rpm and
 *        with Stribeck friction at 1000 rpm), one cycle each, rtol 1e-8:
 *        rigid, full n = 20, 40, 80 (--no-80 skips the costliest), sampled
 *        every 0.02 deg (--step DEG; n = 80 every 0.04 deg at least: the
 *        result's cap on per-segment values); each landing dated at touch (the run's event) and
 *        where the mean lift comes within 1 %, 0.5 %, 0.2 % of the clearance
 *        of the flank (interpolated; the leaves as the run dates them, after
 *        1 % confirmation): the largest flank-change difference rigid vs
 *        full at each n, and full's between n and 2n.  Each run's steps and
 *        flank changes go to stderr.  --scene K runs scene K (0-8) alone.
 *
 * Wall times on a shared 2-core machine are noisy: medians of repeats.
 */
#define _DEFAULT_SOURCE /* getloadavg (glibc) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"

#include "lift_example.h"
#include "lift_segments.h"
#include "rd_lift.h"

#define MAX_EV 32

typedef struct run {
    double wall;
    long steps, rhs, jac, setups;
    int model, dof;
    int n_events;
    double deg[MAX_EV];
    int kind[MAX_EV];
} run;

static void params(rd_lift_params *p, double rtol)
{
    rd_lift_params_default(p);
    p->model = RD_LIFT_MODEL_FULL;
    p->engine.cycles = 1.0;
    p->estimate_error = 0;
    p->step_deg = 1.0;
    p->rtol = rtol;
    p->atol = 1e-3 * rtol;
}

/* Median wall time of `reps` runs; counters and events of the last. */
static int timed_p(const rd_ring_params *rp, int n, const rd_lift_params *pp, int reps, run *out)
{
    double t[64];
    rd_lift_params p = *pp;
    double rtol = p.rtol;
    for (int k = 0; k < reps && k < 64; k++) {
        rd_lift_result r;
        rd_error err;
        rd_error_init(&err);
        double t0 = bench_now();
        int rc = rd_lift_solve(rp, n, &p, NULL, &r, &err);
        t[k] = bench_now() - t0;
        if (rc) {
            fprintf(stderr, "n=%d rtol=%g: %s\n", n, rtol, err.message);
            rd_lift_result_cleanup(&r);
            return rc;
        }
        out->steps = r.steps;
        out->rhs = r.rhs_evals;
        out->jac = r.jac_evals;
        out->setups = r.lin_setups;
        out->model = r.model;
        out->dof = r.dof;
        out->n_events = r.n_events < MAX_EV ? r.n_events : MAX_EV;
        for (int i = 0; i < out->n_events; i++) {
            out->deg[i] = r.events[i].crank_deg;
            out->kind[i] = r.events[i].kind;
        }
        rd_lift_result_cleanup(&r);
    }
    out->wall = bench_median(t, reps);
    return 0;
}

static int timed(const rd_ring_params *rp, int n, double rtol, int reps, run *out)
{
    rd_lift_params p;
    params(&p, rtol);
    return timed_p(rp, n, &p, reps, out);
}

static double event_change(const run *a, const run *b)
{
    if (a->n_events != b->n_events)
        return NAN;
    double d = 0.0;
    for (int i = 0; i < a->n_events; i++) {
        if (a->kind[i] != b->kind[i])
            return NAN;
        d = fmax(d, fabs(a->deg[i] - b->deg[i]));
    }
    return d;
}

/* Table 3 (file comment). */
static int models(const char *dir, int reps)
{
    static const char *files[] = {"thesis_lift_1000rpm.json", "thesis_lift_gas_6000rpm.json"};
    static const int kinds[] = {RD_LIFT_MODEL_AUTO, RD_LIFT_MODEL_RIGID, RD_LIFT_MODEL_FULL};
    printf(
        "One 720 deg cycle of each lift example, its own n and rtol, error estimate on;\n"
        "wall = median of %d runs (Release); steps, Jacobians, factorizations: the main run;\n"
        "change = largest flank-change difference from full n = 40, rtol 1e-8.\n\n"
        "| example | model | landing | used | dof | wall [ms/cycle] | steps | Jacobians | "
        "factorizations | change vs full n=40 [deg] |\n|---|---|---|---|---|---|---|---|---|---|\n",
        reps);
    for (int f = 0; f < 2; f++) {
        gcase c;
        if (!load_example(&c, dir, files[f])) {
            fprintf(stderr, "cannot read %s/%s\n", dir, files[f]);
            return 1;
        }
        c.p.engine.cycles = 1.0;
        run ref, r;
        rd_lift_params p = c.p;
        p.rtol = 1e-8;
        p.atol = 1e-11;
        if (timed_p(&c.ring, 40, &p, 1, &ref))
            return 1;
        for (int k = 0; k < 6; k++) {
            p = c.p;
            p.estimate_error = 1;
            p.model = kinds[k / 2];
            p.landing = k % 2 ? RD_LANDING_PLASTIC : RD_LANDING_PENALTY;
            if (timed_p(&c.ring, c.n, &p, reps, &r))
                return 1;
            printf("| %s | %s | %s | %s | %d | %.2f | %ld | %ld | %ld | %.4f |\n", files[f],
                   rd_lift_model_name(kinds[k / 2]), k % 2 ? "plastic" : "penalty",
                   rd_lift_model_name(r.model), r.dof, 1e3 * r.wall, r.steps, r.jac, r.setups,
                   event_change(&r, &ref));
            fflush(stdout);
        }
        for (int k = 0; k < 4; k++)
            free(c.gas[k]);
    }
    return 0;
}

/* One cycle of an example as the API runs it (file comment). */
static int example_once(const char *file, int reps, int model, int landing)
{
    gcase c;
    if (!load_example(&c, ".", file)) {
        fprintf(stderr, "cannot read %s\n", file);
        return 1;
    }
    c.p.engine.cycles = 1.0;
    c.p.estimate_error = 1;
    c.p.model = model; /* auto: the API's default (load_example asks for full) */
    c.p.landing = landing;
    run r;
    int rc = timed_p(&c.ring, c.n, &c.p, reps, &r);
    printf("%s: rc=%d model=%s wall=%.3f ms steps=%ld rhs=%ld jac=%ld setups=%ld events:", file, rc,
           rd_lift_model_name(r.model), 1e3 * r.wall, r.steps, r.rhs, r.jac, r.setups);
    for (int i = 0; i < r.n_events; i++)
        printf(" %.4f", r.deg[i]);
    printf("\n");
    for (int k = 0; k < 4; k++)
        free(c.gas[k]);
    return rc ? 1 : 0;
}

/* Table 4 (file comment). */
static int modal_table(const char *dir, int reps)
{
    static const char *files[] = {"thesis_lift_1000rpm.json", "thesis_lift_gas_6000rpm.json"};
    static const int ms[] = {4, 8, 16, 32};
    printf("One 720 deg cycle of each lift example, its own n and rtol, no error estimate;\n"
           "wall = median of %d runs (Release); change = largest flank-change difference from\n"
           "the full model at the same n and rtol (NAN: a different list of flank changes).\n\n"
           "| example | model | modes | dof | wall [ms/cycle] | steps | change vs full [deg] |\n"
           "|---|---|---|---|---|---|---|\n",
           reps);
    for (int f = 0; f < 2; f++) {
        gcase c;
        if (!load_example(&c, dir, files[f])) {
            fprintf(stderr, "cannot read %s/%s\n", dir, files[f]);
            return 1;
        }
        c.p.engine.cycles = 1.0;
        c.p.estimate_error = 0;
        run ref, r;
        rd_lift_params p = c.p;
        p.model = RD_LIFT_MODEL_FULL;
        if (timed_p(&c.ring, c.n, &p, reps, &ref))
            return 1;
        printf("| %s | full | - | %d | %.2f | %ld | 0 |\n", files[f], ref.dof, 1e3 * ref.wall,
               ref.steps);
        for (int k = 0; k < 4; k++) {
            p = c.p;
            p.model = RD_LIFT_MODEL_MODAL;
            p.modes = ms[k];
            if (timed_p(&c.ring, c.n, &p, reps, &r))
                return 1;
            printf("| %s | modal | %d | %d | %.2f | %ld | %.4f |\n", files[f], ms[k], r.dof,
                   1e3 * r.wall, r.steps, event_change(&r, &ref));
            fflush(stdout);
        }
        for (int k = 0; k < 4; k++)
            free(c.gas[k]);
    }
    return 0;
}

/* ---------------------------------------- per-segment flank changes (5.) */

#define FINE_STEP_DEG 0.02 /* output step of the comparison runs (lift_segments.h) */

/* One run sampled every FINE_STEP_DEG, the result kept (free it).  With the
 * error estimate or without, the main run is the same: its lift_segments
 * are what is compared. */
static int fine_run(const rd_ring_params *rp, int n, const rd_lift_params *pp, rd_lift_result *r)
{
    rd_lift_params p = *pp;
    rd_error err;
    rd_error_init(&err);
    p.step_deg = FINE_STEP_DEG;
    if (rd_lift_solve(rp, n, &p, NULL, r, &err)) {
        fprintf(stderr, "n=%d rtol=%g: %s\n", n, p.rtol, err.message);
        return 1;
    }
    return 0;
}

/* Largest change of the mean lift's flank changes (NAN: different lists). */
static double mean_change(const rd_lift_result *a, const rd_lift_result *b)
{
    if (a->n_events != b->n_events)
        return NAN;
    double d = 0.0;
    for (int i = 0; i < a->n_events; i++)
        d = a->events[i].kind != b->events[i].kind
                ? NAN
                : fmax(d, fabs(a->events[i].crank_deg - b->events[i].crank_deg));
    return d;
}

static void print_cmp(const char *file, const char *what, const rd_lift_result *r,
                      const rd_lift_result *ref, double ca)
{
    seg_cmp c;
    if (compare_segments(r, ref, ca, &c))
        return;
    printf("| %s | %s | %d | %ld | %d | %d | %.4f (segment %d, %s) | %.4f |\n", file, what, r->dof,
           r->steps, c.events, c.differ, c.max_deg, c.worst_seg,
           c.worst_seg < 0    ? "-"
           : c.worst_kind % 2 ? "landing"
                              : "leave",
           mean_change(r, ref));
    fflush(stdout);
}

/* The full model's comparison rows at (n, rtol) (file comment). */
static int full_row(const gcase *c, int n, double rtol, const char *what, const rd_lift_result *ref)
{
    rd_lift_params p = c->p;
    rd_lift_result f;
    p.model = RD_LIFT_MODEL_FULL;
    p.estimate_error = 0;
    p.rtol = rtol;
    p.atol = 1e-3 * rtol;
    int rc = fine_run(&c->ring, n, &p, &f);
    if (!rc)
        print_cmp(c->name, what, &f, ref, c->p.groove.axial_clearance);
    rd_lift_result_cleanup(&f);
    return rc;
}

/* Table 5 (file comment): one example. */
static int distorted_one(const char *dir, const char *file, int reps)
{
    gcase c;
    if (!load_example(&c, dir, file)) {
        fprintf(stderr, "cannot read %s/%s\n", dir, file);
        return 1;
    }
    c.p.engine.cycles = 1.0;
    rd_lift_params p = c.p, pf = c.p;
    p.model = RD_LIFT_MODEL_AUTO;
    p.estimate_error = 1;
    double load[3] = {NAN, NAN, NAN};
    run r;
    int rc = timed_p(&c.ring, c.n, &p, reps, &r);
    if (getloadavg(load, 3) < 1)
        load[0] = NAN;
    rd_lift_result ref, a;
    memset(&ref, 0, sizeof ref);
    memset(&a, 0, sizeof a);
    pf.model = RD_LIFT_MODEL_FULL;
    pf.estimate_error = 0;
    pf.rtol = 1e-8;
    pf.atol = 1e-11;
    if (!rc)
        rc = fine_run(&c.ring, 40, &pf, &ref) || fine_run(&c.ring, c.n, &p, &a);
    if (!rc) {
        printf("\n%s: auto -> %s, dof %d, wall %.0f ms (median of %d, error estimate on; load "
               "%.1f), steps %ld (sampled every %g deg: %ld); its estimate: lift %.2g of c_a, "
               "flank changes %.4f deg\n\n",
               file, rd_lift_model_name(r.model), r.dof, 1e3 * r.wall, reps, load[0], r.steps,
               FINE_STEP_DEG, a.steps, a.error_estimate, a.event_error_deg);
        printf("| example | run | dof | steps | per-segment flank changes | segments whose list "
               "differs | largest per-segment change vs full n=40 rtol 1e-8 [deg] | mean lift's "
               "[deg] |\n|---|---|---|---|---|---|---|---|\n");
        print_cmp(file, "auto", &a, &ref, c.p.groove.axial_clearance);
        rc = full_row(&c, c.n, 1e-8, "full, its n, rtol 1e-8", &ref) ||
             full_row(&c, 40, c.p.rtol, "full n=40, its rtol", &ref);
    }
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&ref);
    free_example(&c);
    return rc;
}

static int distorted(const char *dir, int reps)
{
    static const char *files[] = {"lift_distorted.json", "lift_distorted_tilted.json"};
    for (int f = 0; f < 2; f++)
        if (distorted_one(dir, files[f], reps))
            return 1;
    return 0;
}

/* ------------------------------- the full model's segment-count estimate (6.) */

/* A scene of the batteries (6. and 7.): an example, then what is changed
 * in it, for one cycle. */
typedef struct bat_scene {
    const char *label, *file;
    double speed_rpm, clearance; /* 0: the example's */
    int friction;                /* enum rd_friction_model, coefficient 0.1; -1: the example's */
} bat_scene;

/* Reads s's example from dir into c and applies s; 0 (and a message) if
 * the file cannot be read. */
static int bat_load(gcase *c, const char *dir, const bat_scene *s)
{
    if (!load_example(c, dir, s->file)) {
        fprintf(stderr, "cannot read %s/%s\n", dir, s->file);
        return 0;
    }
    c->p.engine.cycles = 1.0;
    if (s->speed_rpm > 0)
        c->p.engine.speed_rpm = s->speed_rpm;
    if (s->clearance > 0)
        c->p.groove.axial_clearance = s->clearance;
    if (s->friction >= 0) {
        c->p.friction.model = s->friction;
        c->p.friction.coefficient = 0.1;
    }
    return 1;
}

#define SEG_STEP_DEG   0.05 /* output step: the threshold landings' resolution (interpolated) */
#define SEG_SAMPLES    14500
#define SEG_LIFT_EVERY 20   /* the lift compared every 1 deg, as the result's estimate */
#define SEG_NEAR       5e-3 /* a threshold landing: the mean lift within this x c_a of the flank */

/* One run's mean lift (every SEG_STEP_DEG), flank changes and the same
 * with each landing dated where the mean lift comes within SEG_NEAR c_a of
 * the flank (the leaves as the run dates them), estimate off. */
typedef struct seg_run {
    int ok, samples, n_events;
    double lift[SEG_SAMPLES], deg[MAX_EV], near[MAX_EV];
    int kind[MAX_EV];
} seg_run;

/* The first crossing of the mean lift into SEG_NEAR c_a of the flank a
 * landing reaches, after angle a0, interpolated between samples (NAN: none). */
static double seg_near_landing(const seg_run *o, int kind, double a0, double ca)
{
    int upper = kind == RD_EVENT_REACH_UPPER;
    double lim = upper ? (1.0 - SEG_NEAR) * ca : SEG_NEAR * ca;
    for (int k = 1; k < o->samples; k++) {
        double l0 = o->lift[k - 1], l1 = o->lift[k];
        if (k * SEG_STEP_DEG <= a0)
            continue;
        if (upper ? (l1 >= lim && l0 < lim) : (l1 <= lim && l0 > lim))
            return SEG_STEP_DEG * (k - 1 + (lim - l0) / (l1 - l0));
    }
    return NAN;
}

static void seg_solve(const gcase *c, int n, double rtol, double atol, seg_run *o)
{
    rd_lift_params p = c->p;
    rd_lift_result r;
    rd_error err;
    rd_error_init(&err);
    p.model = RD_LIFT_MODEL_FULL;
    p.estimate_error = 0;
    p.step_deg = SEG_STEP_DEG;
    p.rtol = rtol;
    p.atol = atol;
    memset(o, 0, sizeof *o);
    if (rd_lift_solve(&c->ring, n, &p, NULL, &r, &err) || r.samples > SEG_SAMPLES) {
        fprintf(stderr, "%s n=%d rtol=%g: %s\n", c->name, n, rtol, err.message);
    } else {
        o->ok = 1;
        o->samples = r.samples;
        memcpy(o->lift, r.lift, (size_t)r.samples * sizeof *o->lift);
        o->n_events = r.n_events < MAX_EV ? r.n_events : MAX_EV;
        fprintf(stderr, "%s n=%d rtol=%g steps %ld:", c->name, n, rtol, r.steps);
        for (int i = 0; i < o->n_events; i++) {
            o->deg[i] = r.events[i].crank_deg;
            o->kind[i] = r.events[i].kind;
            o->near[i] = o->deg[i];
            if (o->kind[i] % 2) /* a landing: from the leave before it */
                o->near[i] = seg_near_landing(o, o->kind[i], i ? o->deg[i - 1] : 0.0,
                                              c->p.groove.axial_clearance);
            fprintf(stderr, " %d:%.3f", o->kind[i], o->deg[i]);
            if (o->kind[i] % 2)
                fprintf(stderr, " (near %.3f)", o->near[i]);
        }
        fprintf(stderr, "\n");
    }
    rd_lift_result_cleanup(&r);
}

/* Largest flank-change difference (NAN: different lists), the same with
 * the threshold landings, and the largest lift difference (every 1 deg)
 * over the clearance ca: v[0], v[1], v[2]. */
static void seg_diff(const seg_run *a, const seg_run *b, double ca, double v[3])
{
    v[0] = v[1] = v[2] = NAN;
    if (!a->ok || !b->ok)
        return;
    double l = 0.0;
    for (int k = 0; k < a->samples && k < b->samples; k += SEG_LIFT_EVERY)
        l = fmax(l, fabs(a->lift[k] - b->lift[k]));
    v[2] = l / ca;
    if (a->n_events != b->n_events)
        return;
    double d = 0.0, dn = 0.0;
    for (int i = 0; i < a->n_events; i++) {
        d = a->kind[i] != b->kind[i] ? NAN : fmax(d, fabs(a->deg[i] - b->deg[i]));
        dn = a->kind[i] != b->kind[i] ? NAN : fmax(dn, fabs(a->near[i] - b->near[i]));
    }
    v[0] = d;
    v[1] = dn;
}

/* Table 6: for each scene, the full model at its n and rtol (the result),
 * the candidate estimate |f(n) - f(n/2)| at the same rtol, the current one
 * |f(n) - f(n, rtol/10)|, the true error against full at 2n and 4n, rtol
 * 1e-8, and the observed order from n/2, n, 2n, 4n at rtol 1e-8. */
static int seg_battery(const char *dir, int with4n, int only, double order)
{
    static const bat_scene sc[] = {
        {"gas 6000 rpm (example)", "thesis_lift_gas_6000rpm.json", 0, 0, -1},
        {"distorted bore (example)", "lift_distorted.json", 0, 0, -1},
        {"tilted piston (example)", "lift_tilted.json", 0, 0, -1},
        {"1000 rpm Coulomb", "thesis_lift_1000rpm.json", 0, 0, RD_FRICTION_COULOMB},
        {"1000 rpm Coulomb, 10 um", "thesis_lift_1000rpm.json", 0, 1e-5, RD_FRICTION_COULOMB},
        {"gas 3000 rpm", "thesis_lift_gas_6000rpm.json", 3000, 0, -1},
        {"gas 6000 rpm, 60 um", "thesis_lift_gas_6000rpm.json", 0, 6e-5, -1},
        {"1000 rpm inertia only", "thesis_lift_1000rpm.json", 0, 0, -1},
    };
    double div = pow(2.0, order);
    printf("One cycle, full model, each scene's n and rtol.  est = |f(n) - f(n/2)| / 2^p (both at "
           "the scene's rtol; p = %.2f), the error against full at 2n it predicts; est_t = |f(n) - "
           "f(n, rtol/10)| (the current estimate); true = |f(n) - f(m, rtol 1e-8)|, m = 2n, 4n; "
           "observed order p = log2(d(n/2, n) / d(n, 2n)) at rtol 1e-8, and the same one n "
           "up.  ev: the mean lift's flank changes [deg] (NAN: different lists); ev near: the "
           "same with each landing dated where the mean lift comes within %g c_a of the flank; "
           "lift: its largest difference / clearance (every 1 deg).\n\n"
           "| scene | n | qty | est | est_t | true 2n | true 4n | est/true 2n | est/true 4n | "
           "est_t/true 2n | p (n/2, n, 2n) | p (n, 2n, 4n) |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
           order, SEG_NEAR);
    for (int s = 0; s < (int)(sizeof sc / sizeof sc[0]); s++) {
        gcase c;
        if (only >= 0 && s != only)
            continue;
        if (!bat_load(&c, dir, &sc[s]))
            return 1;
        int n = c.n;
        double rtol = c.p.rtol, atol = c.p.atol, ca = c.p.groove.axial_clearance;
        static seg_run a, h, t, f[4]; /* f: n/2, n, 2n, 4n at rtol 1e-8 */
        seg_solve(&c, n, rtol, atol, &a);
        seg_solve(&c, n / 2, rtol, atol, &h);
        seg_solve(&c, n, 0.1 * rtol, 0.1 * atol, &t);
        for (int k = 0; k < (with4n ? 4 : 3); k++)
            seg_solve(&c, (n / 2) << k, 1e-8, 1e-11, &f[k]);
        if (!with4n)
            f[3].ok = 0;
        double v[7][3];
        seg_diff(&a, &h, ca, v[0]);
        seg_diff(&a, &t, ca, v[1]);
        seg_diff(&a, &f[2], ca, v[2]);
        seg_diff(&a, &f[3], ca, v[3]);
        seg_diff(&f[0], &f[1], ca, v[4]);
        seg_diff(&f[1], &f[2], ca, v[5]);
        seg_diff(&f[2], &f[3], ca, v[6]);
        for (int q = 0; q < 3; q++) {
            static const char *qty[3] = {"ev", "ev near", "lift"};
            double est = v[0][q] / div;
            printf("| %s | %d | %s | %.3g | %.3g | %.3g | %.3g | %.2f | %.2f | %.3f | %.2f | %.2f "
                   "|\n",
                   sc[s].label, n, qty[q], est, v[1][q], v[2][q], v[3][q], est / v[2][q],
                   est / v[3][q], v[1][q] / v[2][q], log2(v[4][q] / v[5][q]),
                   log2(v[5][q] / v[6][q]));
        }
        fflush(stdout);
        free_example(&c);
    }
    return 0;
}

/* ------------------------- landings dated at a fraction of the clearance (7.) */

#define LD_SAMPLES 36100 /* one cycle at 0.02 deg, the finest output step */
#define LD_NTH     4     /* touch (the run's event), then the fractions below */
#define LD_RUNS    4     /* rigid, full n = 20, 40, 80 */

static const double ld_frac[LD_NTH] = {0.0, 1e-2, 5e-3, 2e-3};

/* One run's mean lift and flank changes, each landing dated at every
 * threshold of ld_frac (the leaves as the run dates them). */
typedef struct ld_run {
    int ok, samples, n_events;
    long steps;
    double step, lift[LD_SAMPLES], deg[LD_NTH][MAX_EV];
    int kind[MAX_EV];
} ld_run;

/* The first crossing of the mean lift into frac c_a of the flank a landing
 * of `kind` reaches, after angle a0, interpolated between samples (NAN: none). */
static double ld_landing(const ld_run *o, int kind, double a0, double ca, double frac)
{
    int upper = kind == RD_EVENT_REACH_UPPER;
    double lim = upper ? (1.0 - frac) * ca : frac * ca;
    for (int k = 1; k < o->samples; k++) {
        double l0 = o->lift[k - 1], l1 = o->lift[k];
        if (k * o->step <= a0)
            continue;
        if (upper ? (l1 >= lim && l0 < lim) : (l1 <= lim && l0 > lim))
            return o->step * (k - 1 + (lim - l0) / (l1 - l0));
    }
    return NAN;
}

/* n = 0: the rigid ring.  rtol 1e-8, atol 1e-11 m x c_a / 30 um; sampled
 * every `step` deg (>= 0.02). */
static void ld_solve(const gcase *c, int n, double step, ld_run *o)
{
    rd_lift_params p = c->p;
    rd_lift_result r;
    rd_error err;
    rd_error_init(&err);
    double ca = c->p.groove.axial_clearance;
    p.model = n ? RD_LIFT_MODEL_FULL : RD_LIFT_MODEL_RIGID;
    p.estimate_error = 0;
    p.step_deg = step;
    p.rtol = 1e-8;
    p.atol = 1e-11 * ca / 3e-5;
    memset(o, 0, sizeof *o);
    o->step = step;
    if (rd_lift_solve(&c->ring, n ? n : c->n, &p, NULL, &r, &err) || r.samples > LD_SAMPLES) {
        fprintf(stderr, "%s n=%d: %s\n", c->name, n, err.message);
        return;
    }
    o->ok = 1;
    o->samples = r.samples;
    o->steps = r.steps;
    memcpy(o->lift, r.lift, (size_t)r.samples * sizeof *o->lift);
    o->n_events = r.n_events < MAX_EV ? r.n_events : MAX_EV;
    fprintf(stderr, "%s %s n=%d steps %ld:", c->name, n ? "full" : "rigid", n, r.steps);
    for (int i = 0; i < o->n_events; i++) {
        o->kind[i] = r.events[i].kind;
        for (int t = 0; t < LD_NTH; t++) {
            o->deg[t][i] = r.events[i].crank_deg;
            if (t && o->kind[i] % 2) /* a landing: from the flank change before it */
                o->deg[t][i] =
                    ld_landing(o, o->kind[i], i ? r.events[i - 1].crank_deg : 0.0, ca, ld_frac[t]);
        }
        fprintf(stderr, " %d:%.3f", o->kind[i], o->deg[0][i]);
        if (o->kind[i] % 2)
            fprintf(stderr, " (%.3f %.3f %.3f)", o->deg[1][i], o->deg[2][i], o->deg[3][i]);
    }
    fprintf(stderr, "\n");
    rd_lift_result_cleanup(&r);
}

/* Largest flank-change difference at threshold t, t = LD_NTH: the leaves
 * alone (NAN: a run failed or the lists differ). */
static double ld_diff(const ld_run *a, const ld_run *b, int t)
{
    if (!a->ok || !b->ok || a->n_events != b->n_events)
        return NAN;
    double d = 0.0;
    for (int i = 0; i < a->n_events; i++)
        if (a->kind[i] != b->kind[i])
            return NAN;
        else if (t < LD_NTH || a->kind[i] % 2 == 0)
            d = fmax(d, fabs(a->deg[t % LD_NTH][i] - b->deg[t % LD_NTH][i]));
    return d;
}

/* Table 7: for each scene, rigid vs full n = 20, 40, 80 (rtol 1e-8) at
 * each landing threshold, and full's convergence in n. */
static int landing_dating(const char *dir, int with80, int only, double step)
{
    static const bat_scene sc[] = {
        {"gas 6000 rpm (example)", "thesis_lift_gas_6000rpm.json", 0, 0, -1},
        {"gas 3000 rpm", "thesis_lift_gas_6000rpm.json", 3000, 0, -1},
        {"gas 8000 rpm", "thesis_lift_gas_6000rpm.json", 8000, 0, -1},
        {"100 rpm Coulomb", "thesis_lift_1000rpm.json", 100, 0, RD_FRICTION_COULOMB},
        {"1000 rpm Coulomb", "thesis_lift_1000rpm.json", 0, 0, RD_FRICTION_COULOMB},
        {"1000 rpm Coulomb, 10 um", "thesis_lift_1000rpm.json", 0, 1e-5, RD_FRICTION_COULOMB},
        {"3000 rpm Coulomb", "thesis_lift_1000rpm.json", 3000, 0, RD_FRICTION_COULOMB},
        {"8000 rpm Coulomb", "thesis_lift_1000rpm.json", 8000, 0, RD_FRICTION_COULOMB},
        {"1000 rpm Stribeck", "thesis_lift_1000rpm.json", 0, 0, RD_FRICTION_STRIBECK},
    };
    static const char *th[LD_NTH + 1] = {"touch", "1 %", "0.5 %", "0.2 %", "(leaves alone)"};
    /* n = 80 at every 0.02 deg exceeds the result's per-segment value cap */
    double step80 = fmax(step, 0.04);
    printf("One cycle, rtol 1e-8 (atol 1e-11 m x c_a / 30 um), sampled every %g "
           "deg (n = 80: every %g deg).  Landings dated where the mean lift touches the flank "
           "(the run's event) or comes within a fraction of the clearance of it; leaves as the "
           "run dates them.  Largest flank-change difference [deg] (NAN: different lists).\n\n"
           "| scene | landing at | rigid - full 20 | rigid - full 40 | rigid - full 80 | full 20 - "
           "40 | full 40 - 80 |\n|---|---|---|---|---|---|---|\n",
           step, step80);
    for (int s = 0; s < (int)(sizeof sc / sizeof sc[0]); s++) {
        gcase c;
        if (only >= 0 && s != only)
            continue;
        if (!bat_load(&c, dir, &sc[s]))
            return 1;
        static ld_run r[LD_RUNS]; /* rigid, full 20, 40, 80 */
        for (int k = 0; k < LD_RUNS; k++) {
            r[k].ok = 0;
            if (k < 3 || with80)
                ld_solve(&c, k ? 10 << k : 0, k == 3 ? step80 : step, &r[k]);
        }
        for (int t = 0; t <= LD_NTH; t++)
            printf("| %s | %s | %.3f | %.3f | %.3f | %.3f | %.3f |\n", t ? "" : sc[s].label, th[t],
                   ld_diff(&r[0], &r[1], t), ld_diff(&r[0], &r[2], t), ld_diff(&r[0], &r[3], t),
                   ld_diff(&r[1], &r[2], t), ld_diff(&r[2], &r[3], t));
        fflush(stdout);
        free_example(&c);
    }
    return 0;
}

int main(int argc, char **argv)
{
    int max_n = 1000, reps = 3, once = 0, once_reps = 1, once_model = RD_LIFT_MODEL_AUTO,
        once_landing = RD_LANDING_PENALTY;
    const char *examples = NULL, *modal_dir = NULL, *example = NULL, *distorted_dir = NULL;
    const char *seg_dir = NULL; /* --segment-estimate (6.) */
    int seg_4n = 1, seg_only = -1;
    double seg_order = 1.5;
    const char *ld_dir = NULL; /* --landing-dating (7.) */
    int ld_80 = 1;
    double ld_step = 0.02;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--max-n") && i + 1 < argc)
            max_n = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--once") && i + 1 < argc)
            once = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--models") && i + 1 < argc)
            examples = argv[++i];
        else if (!strcmp(argv[i], "--example-once") && i + 1 < argc)
            example = argv[++i];
        else if (!strcmp(argv[i], "--once-reps") && i + 1 < argc)
            once_reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--rigid"))
            once_model = RD_LIFT_MODEL_RIGID;
        else if (!strcmp(argv[i], "--plastic"))
            once_landing = RD_LANDING_PLASTIC;
        else if (!strcmp(argv[i], "--modal") && i + 1 < argc)
            modal_dir = argv[++i];
        else if (!strcmp(argv[i], "--distorted") && i + 1 < argc)
            distorted_dir = argv[++i];
        else if (!strcmp(argv[i], "--segment-estimate") && i + 1 < argc)
            seg_dir = argv[++i];
        else if (!strcmp(argv[i], "--scene") && i + 1 < argc)
            seg_only = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--order") && i + 1 < argc)
            seg_order = atof(argv[++i]);
        else if (!strcmp(argv[i], "--no-4n"))
            seg_4n = 0;
        else if (!strcmp(argv[i], "--landing-dating") && i + 1 < argc)
            ld_dir = argv[++i];
        else if (!strcmp(argv[i], "--no-80"))
            ld_80 = 0;
        else if (!strcmp(argv[i], "--step") && i + 1 < argc)
            ld_step = fmax(atof(argv[++i]), 0.02);
        else {
            fprintf(stderr,
                    "usage: bench_lift [--max-n N] [--reps R] | --once N | --example-once FILE "
                    "[--once-reps R] [--rigid] [--plastic] | "
                    "--models EXAMPLES_DIR [--reps R] | --modal EXAMPLES_DIR [--reps R] | "
                    "--distorted EXAMPLES_DIR [--reps R] | --segment-estimate EXAMPLES_DIR "
                    "[--order P] [--no-4n] [--scene K] | --landing-dating EXAMPLES_DIR [--no-80] "
                    "[--step DEG] [--scene K]\n");
            return 2;
        }
    }
    if (reps < 3)
        reps = 3;
    if (example)
        return example_once(example, once_reps, once_model, once_landing);
    if (examples)
        return models(examples, reps);
    if (modal_dir)
        return modal_table(modal_dir, reps);
    if (distorted_dir)
        return distorted(distorted_dir, reps);
    if (seg_dir)
        return seg_battery(seg_dir, seg_4n, seg_only, seg_order);
    if (ld_dir)
        return landing_dating(ld_dir, ld_80, seg_only, ld_step);
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    if (once) {
        run r;
        int rc = timed(&rp, once, 1e-6, 1, &r);
        printf("n=%d rc=%d steps=%ld rhs=%ld jac=%ld events=%d\n", once, rc, r.steps, r.rhs, r.jac,
               r.n_events);
        return rc ? 1 : 0;
    }

    static const int ns[] = {4, 8, 16, 32, 64, 125, 250, 500, 1000};
    int nn = 0;
    while (nn < (int)(sizeof ns / sizeof ns[0]) && ns[nn] <= max_n)
        nn++;
    run *runs = calloc((size_t)nn, sizeof *runs);
    if (!runs)
        return 1;
    for (int k = 0; k < nn; k++)
        if (timed(&rp, ns[k], 1e-6, reps, &runs[k]))
            return 1;
    const run *fine = &runs[nn - 1];
    printf("Thesis ring, 1000 rpm, inertia only, one cycle (720 deg), rtol 1e-6, atol 1e-9 m;\n"
           "wall time = median of %d runs; change = largest flank-change angle difference\n"
           "against n = %d (NAN: a different number of flank changes).\n\n",
           reps, ns[nn - 1]);
    printf("| n | DOF | wall [s/cycle] | steps | rhs evals | jac evals | flank changes [deg] | "
           "change vs n=%d [deg] |\n|---|---|---|---|---|---|---|---|\n",
           ns[nn - 1]);
    double lx[16], ly[16];
    int nfit = 0;
    for (int k = 0; k < nn; k++) {
        const run *r = &runs[k];
        char ev[512] = "";
        size_t len = 0;
        for (int i = 0; i < r->n_events && len + 16 < sizeof ev; i++)
            len += (size_t)snprintf(ev + len, sizeof ev - len, "%s%.3f", i ? " " : "", r->deg[i]);
        printf("| %d | %d | %.3f | %ld | %ld | %ld | %s | %.4f |\n", ns[k], 6 * ns[k], r->wall,
               r->steps, r->rhs, r->jac, ev, event_change(r, fine));
        if (ns[k] >= 32) {
            lx[nfit] = ns[k];
            ly[nfit++] = r->wall;
        }
    }
    if (nfit >= 2)
        printf("\nFitted cost exponent (wall time ~ n^p, n >= 32): p = %.2f\n",
               bench_exponent(lx, ly, nfit));

    run ref;
    if (timed(&rp, 20, 1e-10, 1, &ref))
        return 1;
    printf(
        "\nn = 20: flank-change angle error vs rtol (atol = 1e-3 m x rtol), reference rtol "
        "1e-10\n\n| rtol | wall [s/cycle] | steps | max angle error [deg] |\n|---|---|---|---|\n");
    for (double rtol = 1e-4; rtol > 0.5e-8; rtol /= 10) {
        run r;
        if (timed(&rp, 20, rtol, reps, &r))
            return 1;
        printf("| %.0e | %.3f | %ld | %.4f |\n", rtol, r.wall, r.steps, event_change(&r, &ref));
    }
    free(runs);
    return 0;
}
