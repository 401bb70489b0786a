/*
 * test_ringpack_lube — the lubricated friction model on the pack's rings
 * (physics.friction.model lubricated; core/ringpack/rd_ringpack_film.c):
 * each ring's oil film, coupled with the gas network a cycle late.
 *
 * Scenes: the thesis pack (rd_ringpack_params_thesis: three rings, the oil
 * ring pinned on its lower flank), 2400 rpm, fired or motored, no error
 * estimate, fixed cycle counts.  TOLERANCES below gives each bound and
 * where it comes from (the numbers measured are printed by each case).
 *   (1) film_lag, the pack's estimate of its lagged coupling's error,
 *       against the true error: the last cycle's min_film of a C-cycle run
 *       (C = 3, 4, 5) against the same scene run 20 cycles, max over the
 *       samples of |h_C - h_20| / max(h_20, sigma); fired and motored,
 *       rings 0-2.  The ratio film_lag / true must lie within x3.
 *   (2) a second driver: the lift analysis run alone (rd_lift_solve,
 *       lubricated, its own film driver rd_lift_film.c over its own warm-up
 *       cycle) on ring 0 of the settled fired pack (run until its
 *       periodicity < 1e-4), given the pack's last-cycle pressures as its
 *       gauge tables (above: land_1, behind: groove_1, below: land_2, each
 *       minus the crankcase pressure; linear active areas for the pack's
 *       linear flank pressure): its min_film at the same crank angles, its
 *       cycle's friction work and its friction force along the cycle (the
 *       summed difference over the summed size, test_ringpack_lift's
 *       friction_gap).  If the pack fed its film other loads than the
 *       pressures it reports, or ran it at another speed, viscosity or face,
 *       the two films would part.
 *   (3) the friction work the pack reports for each ring against the
 *       trapezoid, over its own output samples, of (hydrodynamic + asperity
 *       friction) x the piston's speed, the speed from the exact
 *       slider-crank written here (not rd_engine_piston).
 *   (4) the pinned oil ring: the friction in its motion (r.friction) is its
 *       lube block's hydrodynamic + asperity friction at every sample (the
 *       ring rubs on the film that is reported).
 *   (5) physics: the top ring's film is thinner fired than motored just
 *       after firing TDC (the groove's gas behind it loads it), and twice
 *       the oil's viscosity thickens every ring's film mid-stroke.
 *   (6) core validation with the lubricated model: a distorted bore, a
 *       piston tilt, Stribeck friction, a face without roughness.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* TOLERANCES (measured on this build; each case prints its numbers)
 *
 * LAG_FACTOR 3 (case 1): film_lag is the film the last cycle used (over
 * cycle c-1's pressures) against the film over cycle c's own: one cycle's
 * lag, from the same start.  The true error of a C-cycle run against the
 * 20-cycle film also carries the film's start (h0 at the cycle's start,
 * itself lagged from the cycles before) and the pressures' own approach to
 * periodicity, so the two agree in size, not in value: measured 0.51-0.96
 * fired, 0.54-0.87 motored (C = 3, 4, 5, rings 0-2; true errors 3e-3 to
 * 9e-2, so the 20-cycle runs' own periodicity, 3.3e-4 fired and 3.7e-4
 * motored, does not blur them; 0.43-1.78 over C = 3..6 before this test).
 * x3 bounds them and fails an estimate off by an order.
 *
 * Case 2 runs the pack to periodicity 1e-4 (periodic: settled after 10
 * cycles, 5.4e-5; at 2 deg film steps after 16, and 20 fixed cycles end at
 * 3.3e-4: the fired pack wanders between 8e-5 and 5e-4 from 12 to 30
 * cycles) with the film's largest step
 * LIFT_FILM_STEP 0.5 deg in both drivers, the lift run LIFT_CYCLES 2.
 * FILM_TOL 1e-3 (relative to max(h, sigma)): the films differ by the
 * pack's remaining coupling lag (its film_lag: 8.5e-6), the lift film's
 * start (one warm-up cycle, then two: periodic_change 1e-5) and, most, the
 * two drivers' own time steps near firing TDC, where the film is thinnest
 * (h ~ 1.1-1.4 sigma) and fastest: measured 1.9e-4 (at 2 deg).  At the
 * default film step of 2 deg the same comparison gives 3.9e-3 (one lift
 * cycle), 5.7e-3 (two, three); at 1 deg 1.2e-3 and 4.5e-3; at 0.5 deg
 * 1.4e-3 (one) and 1.9e-4 (two): step placement, not a coupling error (the
 * films' starts agree within 7e-5).  A lift run 1 % faster parts the films
 * by 1.1e-2, one without the groove's gas by 3e2 (the face pushed off).
 * WORK_TOL 1 % (the brief's): measured 2.2e-6 (a 1 % speed error: 6.8e-3).
 * FRICTION_TOL 1e-4 (summed difference over summed size, as
 * test_ringpack_lift's friction_gap): the pack's rigid ring rubs on its
 * film at its own speed in the groove as the lift's does, on films within
 * FILM_TOL: measured 8.1e-6 (2.7e-4 with 2 deg film steps).
 *
 * WORK3_TOL 2 % (case 3): the pack integrates the power over the film's own
 * steps (<= 2 deg), the test over the 1 deg output samples of the film
 * track interpolated, with the speed written here: two quadratures of the
 * same power, kinks at the dead centres; measured 2e-7 .. 1.1e-4.
 *
 * PIN_TOL 1e-9 of the largest force (case 4): the same film point read
 * twice at the same time, the pinned ring's speed in its groove 0: equal
 * to round-off if the ring rubs on the reported film at the reported
 * speed.  MEASURED 2.3e-4 (fired and motored): the motion's law
 * (rd_liner_eval in rd_ringpack.c liner_force) takes the exact piston speed
 * for the Couette shear and the asperities' tanh, the lube block
 * (rd_lift_lube_fill) the film track's U, linear between film steps; the gap
 * falls with the film step as that interpolation's error does (2.3e-4,
 * 2.2e-5, 4.9e-7 at 2, 1, 0.5 deg).  A reporting mismatch in core, left
 * failing here on purpose.
 */
#define LAG_FACTOR     3.0
#define FILM_TOL       1e-3
#define LIFT_FILM_STEP 0.5
#define LIFT_CYCLES    2
#define WORK_TOL       1e-2
#define FRICTION_TOL   1e-4
#define WORK3_TOL      2e-2
#define PIN_TOL        1e-9
#define TRUTH_CYCLES   20

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void scene(rd_ringpack_params *p, int motored, int cycles)
{
    rd_ringpack_params_thesis(p);
    p->friction.model = RD_FRICTION_LUBRICATED;
    p->estimate_error = 0;
    p->periodic = 0;
    p->engine.cycles = cycles;
    if (motored)
        p->cylinder_kind = p->synthetic.kind = RD_CYLINDER_MOTORED;
}

static int run(const rd_ringpack_params *p, rd_ringpack_result *r, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    double t0 = now();
    int rc = rd_ringpack_solve(p, NULL, r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    printf("%s: %.1f s, %d cycles, periodicity %.2e, film_lag %.2e %.2e %.2e\n", what, now() - t0,
           r->cycles, r->periodicity, r->film_lag[0], r->n_rings > 1 ? r->film_lag[1] : 0.0,
           r->n_rings > 2 ? r->film_lag[2] : 0.0);
    if (rc == RD_OK)
        for (int i = 0; i < r->n_rings; i++)
            CHECK(r->lube[i].on && r->lube[i].min_film, "%s: ring %d has no lube block", what, i);
    return rc;
}

/* max_k |a_k - b_k| / max(|b_k|, floor) */
static double rel_gap(const double *a, const double *b, int n, double floor_)
{
    double g = 0.0;
    for (int k = 0; k < n; k++)
        g = fmax(g, fabs(a[k] - b[k]) / fmax(fabs(b[k]), floor_));
    return g;
}

/* mean of v over the samples with crank angle in [lo, hi] */
static double mean_over(const rd_ringpack_result *r, const double *v, double lo, double hi)
{
    double s = 0.0;
    int n = 0;
    for (int k = 0; k < r->samples; k++)
        if (r->crank_deg[k] >= lo - 1e-9 && r->crank_deg[k] <= hi + 1e-9) {
            s += v[k];
            n++;
        }
    return n ? s / n : NAN;
}

/* The runs every case shares: [scene][C index], C = 3, 4, 5, 20. */
static const int CYCLES[4] = {3, 4, 5, TRUTH_CYCLES};
static rd_ringpack_result runs[2][4];
static int ok[2][4];

/* (1) */
static void test_film_lag(void)
{
    double lo = INFINITY, hi = 0.0;
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "motored" : "fired";
        for (int c = 0; c < 4; c++) {
            rd_ringpack_params p;
            scene(&p, m, CYCLES[c]);
            char what[64];
            snprintf(what, sizeof what, "%s, %d cycles", name, CYCLES[c]);
            ok[m][c] = run(&p, &runs[m][c], what) == RD_OK;
        }
        if (!ok[m][3])
            continue;
        const rd_ringpack_result *T = &runs[m][3];
        for (int c = 0; c < 3; c++) {
            if (!ok[m][c])
                continue;
            const rd_ringpack_result *r = &runs[m][c];
            for (int i = 0; i < r->n_rings; i++) {
                double truth = rel_gap(r->lube[i].min_film, T->lube[i].min_film, r->samples,
                                       T->lube[i].composite_sigma);
                double ratio = r->film_lag[i] / truth;
                printf("film_lag %s C=%d ring %d: film_lag %.3e, true %.3e, ratio %.3f\n", name,
                       CYCLES[c], i, r->film_lag[i], truth, ratio);
                lo = fmin(lo, ratio);
                hi = fmax(hi, ratio);
                CHECK(isfinite(ratio) && ratio >= 1.0 / LAG_FACTOR && ratio <= LAG_FACTOR,
                      "%s C=%d ring %d: film_lag %.3g vs true %.3g (ratio %.3g)", name, CYCLES[c],
                      i, r->film_lag[i], truth, ratio);
            }
        }
    }
    printf("film_lag / true over the battery: %.3f .. %.3f\n", lo, hi);
}

/* (2) */
static void test_lift_driver(void)
{
    rd_ringpack_params p;
    scene(&p, 0, 30);
    p.periodic = 1; /* settled: stops at the first cycle changing less than 1e-4 */
    p.periodic_tolerance = 1e-4;
    p.film_step_deg = LIFT_FILM_STEP;
    rd_ringpack_result pr, *r = &pr;
    char what[80];
    snprintf(what, sizeof what, "fired, settled to 1e-4, film step %g deg", LIFT_FILM_STEP);
    if (run(&p, r, what) != RD_OK) {
        rd_ringpack_result_cleanup(r);
        return;
    }
    CHECK(r->settled && r->periodicity < 1e-4, "the settled pack: periodicity %.3g after %d cycles",
          r->periodicity, r->cycles);
    CHECK(r->ring_model[0] == RD_LIFT_MODEL_RIGID, "ring 0's model %d (%s)", r->ring_model[0],
          r->ring_why[0]);
    int S = r->samples;
    double *tab = malloc(3 * (size_t)S * sizeof *tab);
    CHECK(tab != NULL, "memory");
    if (!tab) {
        rd_ringpack_result_cleanup(r);
        return;
    }
    static const int VOL[3] = {1, 2, 3}; /* land_1, groove_1, land_2 */
    for (int k = 0; k < S; k++)
        for (int f = 0; f < 3; f++)
            tab[(size_t)f * S + k] = r->pressure[(size_t)VOL[f] * S + k] - p.crankcase_pa;
    int lc = LIFT_CYCLES;
    rd_lift_params lp;
    rd_lift_params_default(&lp);
    lp.engine = p.engine;
    lp.engine.cycles = lc;
    lp.bore = p.bore;
    lp.groove = p.rings[0].groove;
    lp.friction = p.friction;
    lp.face = p.rings[0].face;
    lp.bore.roughness_rq = p.bore.roughness_rq;
    lp.film_step_deg = p.film_step_deg;
    lp.gravity = p.gravity;
    lp.gas = (rd_gas_params){S, r->crank_deg, tab, tab + S, tab + 2 * S, RD_GAS_AREA_LINEAR};
    lp.cvode = 1; /* the pack steps its rings with CVODE */
    lp.rtol = p.rtol;
    lp.atol = p.atol;
    lp.contact_stiffness = r->ring_stiffness[0];
    lp.estimate_error = 0;
    lp.model = RD_LIFT_MODEL_RIGID;
    lp.flank_band = p.flank_band;
    lp.step_deg = p.step_deg;
    rd_lift_result l;
    memset(&l, 0, sizeof l);
    rd_error err;
    rd_error_init(&err);
    double t0 = now();
    int rc = rd_lift_solve(&p.rings[0].ring, p.rings[0].segments, &lp, NULL, &l, &err);
    CHECK(rc == RD_OK && l.lube.on, "lift run: %s", err.message);
    if (rc == RD_OK && l.lube.on) {
        int k0 = (int)lround(720.0 * (lc - 1) / p.step_deg), kw = 0;
        CHECK(l.samples - k0 == S, "lift samples %d from %d, pack %d", l.samples, k0, S);
        double sig = r->lube[0].composite_sigma, film = 0.0, size = 0.0, gap = 0.0;
        for (int k = 0; k < S && k0 + k < l.samples; k++) {
            double d = fabs(l.lube.min_film[k0 + k] - r->lube[0].min_film[k]) /
                       fmax(r->lube[0].min_film[k], sig);
            if (d > film) {
                film = d;
                kw = k;
            }
            size += fabs(l.friction_force[k0 + k]);
            gap += fabs(l.friction_force[k0 + k] - r->friction[k]);
        }
        double wl = l.lube.friction_work[lc - 1], wp = r->lube[0].friction_work[0];
        double work = fabs(wl - wp) / fabs(wp), fr = gap / size;
        printf("lift driver, %d cycles (%.1f s): min_film within %.2e (largest at %.0f deg, "
               "h %.3e m, sigma %.3e m; the pack's film_lag %.2e, the lift film's "
               "periodic_change %.2e), work %.6g vs the pack's %.6g J (%.2e), friction force "
               "within %.2e of its size\n",
               lc, now() - t0, film, r->crank_deg[kw], r->lube[0].min_film[kw], sig, r->film_lag[0],
               l.lube.periodic_change, wl, wp, work, fr);
        CHECK(film <= FILM_TOL, "lift driver: min_film %.3g apart", film);
        CHECK(work <= WORK_TOL, "lift driver: work %.3g apart", work);
        CHECK(fr <= FRICTION_TOL, "lift driver: friction %.3g apart", fr);
    }
    rd_lift_result_cleanup(&l);
    free(tab);
    rd_ringpack_result_cleanup(r);
}

/* The piston's speed, m/s, positive moving away from TDC (down), at crank
 * angle a (rad, 0 at TDC): the exact slider-crank's ds/dt. */
static double piston_speed(const rd_engine_params *e, double a)
{
    double r = e->crank_radius, l = e->rod_length, w = e->speed_rpm * 2.0 * M_PI / 60.0;
    double s = sin(a);
    return r * w * (s + r * sin(2.0 * a) / (2.0 * sqrt(l * l - r * r * s * s)));
}

/* (3) */
static void test_work(void)
{
    double worst = 0.0;
    for (int m = 0; m < 2; m++) {
        if (!ok[m][3])
            continue;
        const rd_ringpack_result *r = &runs[m][3];
        rd_ringpack_params p;
        scene(&p, m, TRUTH_CYCLES);
        double w_ = p.engine.speed_rpm * 2.0 * M_PI / 60.0;
        for (int i = 0; i < r->n_rings; i++) {
            const rd_lift_lube *lb = &r->lube[i];
            double W = 0.0;
            for (int k = 0; k + 1 < r->samples; k++) {
                double a0 = r->crank_deg[k] * M_PI / 180.0, a1 = r->crank_deg[k + 1] * M_PI / 180.0;
                double f0 = (lb->hydrodynamic_friction[k] + lb->asperity_friction[k]) *
                            piston_speed(&p.engine, a0);
                double f1 = (lb->hydrodynamic_friction[k + 1] + lb->asperity_friction[k + 1]) *
                            piston_speed(&p.engine, a1);
                W += 0.5 * (a1 - a0) / w_ * (f0 + f1);
            }
            double d = fabs(W - lb->friction_work[0]) / fabs(lb->friction_work[0]);
            worst = fmax(worst, d);
            printf("work %s ring %d: pack %.6g J, trapezoid of the samples %.6g J (%.2e)\n",
                   m ? "motored" : "fired", i, lb->friction_work[0], W, d);
            CHECK(W > 0.0 && d <= WORK3_TOL, "%s ring %d: work %.6g vs %.6g J",
                  m ? "motored" : "fired", i, lb->friction_work[0], W);
        }
    }
    printf("friction work against the samples' trapezoid: within %.2e\n", worst);
}

/* (4) */
static void test_pinned(void)
{
    for (int m = 0; m < 2; m++) {
        if (!ok[m][3])
            continue;
        const rd_ringpack_result *r = &runs[m][3];
        CHECK(r->n_rings == 3, "rings %d", r->n_rings);
        if (r->n_rings != 3)
            return;
        const rd_lift_lube *lb = &r->lube[2];
        int S = r->samples;
        double big = 0.0, gap = 0.0;
        for (int k = 0; k < S; k++) {
            double f = lb->hydrodynamic_friction[k] + lb->asperity_friction[k];
            big = fmax(big, fabs(f));
            gap = fmax(gap, fabs(r->friction[2 * (size_t)S + k] - f));
        }
        printf("pinned oil ring (%s): friction within %.2e of its largest %.4g N\n",
               m ? "motored" : "fired", gap / big, big);
        CHECK(big > 0.0 && gap <= PIN_TOL * big, "pinned ring: friction %.3g of %.3g N apart", gap,
              big);
    }
}

/* (5) */
static void test_trends(void)
{
    if (ok[0][3] && ok[1][3]) {
        double f = mean_over(&runs[0][3], runs[0][3].lube[0].min_film, 5.0, 40.0);
        double mo = mean_over(&runs[1][3], runs[1][3].lube[0].min_film, 5.0, 40.0);
        printf("top ring after firing TDC (5-40 deg): fired %.4g m, motored %.4g m\n", f, mo);
        CHECK(f < mo, "fired film %.4g m not thinner than motored %.4g m", f, mo);
    }
    /* twice the default oil's viscosity at its 100 C (Vogel), constant,
     * against the default; both 5 cycles (film_lag 3e-3..5e-3 then, the
     * change measured x1.37-1.40, ~sqrt 2) */
    if (!ok[0][2])
        return;
    rd_ringpack_params p;
    scene(&p, 0, CYCLES[2]);
    const rd_lube_params *l = &p.friction.lube;
    double eta = l->vogel_a * exp(l->vogel_b / (l->temperature_c + 273.15 - l->vogel_c));
    p.friction.lube.viscosity = 2.0 * eta;
    rd_ringpack_result v;
    char what[64];
    snprintf(what, sizeof what, "fired, %d cycles, viscosity %.4g Pa s", CYCLES[2], 2.0 * eta);
    if (run(&p, &v, what) == RD_OK) {
        const rd_ringpack_result *d = &runs[0][2];
        for (int i = 0; i < v.n_rings; i++) {
            double thick = mean_over(&v, v.lube[i].min_film, 60.0, 120.0);
            double thin = mean_over(d, d->lube[i].min_film, 60.0, 120.0);
            printf("ring %d mid-stroke (60-120 deg): %.4g m at eta %.4g, %.4g m at 2 eta "
                   "(x%.3f)\n",
                   i, thin, eta, thick, thick / thin);
            CHECK(thick > thin, "ring %d: 2x viscosity film %.4g m, default %.4g m", i, thick,
                  thin);
        }
    }
    rd_ringpack_result_cleanup(&v);
}

/* (6) */
static void refused(const rd_ringpack_params *p, const char *path, int prefix, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_validate(p, &err);
    int match = prefix ? strncmp(err.path, path, strlen(path)) == 0 : strcmp(err.path, path) == 0;
    printf("%s: refused %d at %s (%s)\n", what, rc != RD_OK, err.path, err.message);
    CHECK(rc != RD_OK && match, "%s: rc %d, path '%s', want '%s'", what, rc, err.path, path);
}

static void test_validate(void)
{
    rd_ringpack_params p;
    rd_error err;
    scene(&p, 0, 3);
    rd_error_init(&err);
    CHECK(rd_ringpack_validate(&p, &err) == RD_OK, "the lubricated scene: %s", err.message);
    scene(&p, 0, 3);
    p.bore.n_distortion = 1;
    p.bore.distortion[0].order = 2;
    p.bore.distortion[0].amplitude = 5e-6;
    rd_error_init(&err);
    CHECK(rd_ringpack_validate(&p, &err) == RD_OK, "a distorted bore (a film per segment load): %s",
          err.message); /* test_ringpack_films runs it */
    scene(&p, 0, 3);
    p.engine.piston_tilt_deg = 0.05;
    p.rings[2].gap_angle_deg = 0.0; /* a tilt takes gaps on its plane */
    rd_error_init(&err);
    CHECK(rd_ringpack_validate(&p, &err) == RD_OK, "a piston tilt (films per sliding speed): %s",
          err.message); /* test_ringpack_films runs a moving one */
    scene(&p, 0, 3);
    p.friction.model = RD_FRICTION_STRIBECK;
    refused(&p, "/physics/friction/model", 0, "stribeck");
    scene(&p, 0, 3);
    p.rings[1].face.roughness_rq = 0.0;
    refused(&p, "/rings/1/ring/face", 1, "ring 1 face roughness 0");
}

int main(void)
{
    double t0 = now();
    test_validate();
    test_film_lag();
    test_lift_driver();
    test_work();
    test_pinned();
    test_trends();
    for (int m = 0; m < 2; m++)
        for (int c = 0; c < 4; c++)
            rd_ringpack_result_cleanup(&runs[m][c]);
    printf("total %.1f s\n", now() - t0);
    return check_done();
}
