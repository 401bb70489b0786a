/*
 * test_lift_films_map — the lubricated lift on a bore map: each segment's
 * film under its load at the ring's depth (core/lift/rd_lift_films.c,
 * rd_lift_map_loads, rd_lift_segfilm.c).
 *
 * References:
 *  - equal layers: the plain distorted bore's run bit for bit (the lift
 *    with its films, the lubrication block);
 *  - the loads between two layers: linear in depth against the contact
 *    analysis solved at the bore between them (rd_bore_map_at): exact
 *    where the ring touches all round (the contact pressure is linear in
 *    the distortion there), the contact's nonlinearity where it does not;
 *  - the films: each segment's film under its own load history (solved in
 *    the test for every segment, rd_lift_film_run_table) against the
 *    quasi-static interpolation the lift reads; the reported
 *    interp_check (two segments so solved, and the nodes') against that
 *    true miss over all segments, within x3;
 *  - a film under a load history carries it at every step (its radial
 *    balance);
 *  - a ring running down a bore whose distortion grows toward the bottom:
 *    near TDC it has the top layer's films (the same run on the top layer
 *    alone), near BDC thinner ones (its loads spread more).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fired_cycle.h"
#include "lift_distort.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

#define PI   M_PI
#define WMAX 64 /* films a segment may weigh (the lift's exact films: one per segment, n = 20) */

static void scene(rd_ring_params *rp, rd_lift_params *p, double A)
{
    lubricated_scene(rp, p, A);
}

/* distort_map's two layers, the ring 5 mm down at TDC. */
static void map_of(rd_lift_params *p, rd_bore_map *m, double A_top, double A_bot)
{
    distort_map(m, A_top, A_bot);
    p->bore.n_distortion = 0;
    p->bore_map = m;
    p->ring_z_tdc = 0.005;
}

static int same(const double *a, const double *b, int n)
{
    return !memcmp(a, b, (size_t)n * sizeof *a);
}

/* Equal layers give the plain distorted bore's run bit for bit. */
static void equal_layers(void)
{
    rd_ring_params rp;
    rd_lift_params p, q;
    rd_bore_map m;
    scene(&rp, &p, 5e-6);
    q = p;
    map_of(&q, &m, 5e-6, 5e-6);
    rd_lift_result a, b;
    rd_error err = {0};
    int rc = rd_lift_solve(&rp, 12, &p, NULL, &a, &err);
    rc = rc ? rc : rd_lift_solve(&rp, 12, &q, NULL, &b, &err);
    CHECK(rc == RD_OK, "equal layers: %s", err.message);
    if (rc != RD_OK)
        return;
    int S = a.samples;
    CHECK(S == b.samples && a.lube.films == b.lube.films && a.lube.films > 1,
          "samples %d/%d films %d/%d", S, b.samples, a.lube.films, b.lube.films);
    CHECK(same(a.lube.min_film, b.lube.min_film, S) &&
              same(a.lube.hydrodynamic_friction, b.lube.hydrodynamic_friction, S) &&
              same(a.lube.asperity_friction, b.lube.asperity_friction, S) &&
              same(a.lube.friction_work, b.lube.friction_work, 1) &&
              same(a.lift_segments, b.lift_segments, S * a.segments) &&
              same(a.friction_force, b.friction_force, S),
          "equal layers differ from the plain bore");
    CHECK(b.lube.load_depths == 2 && a.lube.load_depths == 1, "depths %d, %d", b.lube.load_depths,
          a.lube.load_depths);
    printf("equal layers: the plain bore's run bit for bit (%d films, %d samples)\n", a.lube.films,
           S);
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

/* The loads between the layers: linear between the depths they were
 * solved at, against the contact at the bore at depths off them; the
 * reported depth_check against the largest such miss. */
static void between_layers(double A_top, double A_bot)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_bore_map m;
    scene(&rp, &p, 0.0);
    map_of(&p, &m, A_top, A_bot);
    int n = 20, D = 0;
    rd_error err = {0};
    rd_ring *ring = rd_ring_create(&rp, n, 0, &err);
    double load[20 * RD_BORE_LAYERS_MAX], ang[20], z[RD_BORE_LAYERS_MAX], at[20], miss = NAN;
    int rc =
        ring ? rd_lift_map_loads(ring, &p, 320, NULL, load, ang, z, &D, &miss, &err) : RD_ENOMEM;
    CHECK(rc == RD_OK && D >= 2, "loads along the map: %s (%d depths)", err.message, D);
    double w_el = 2.0 * rp.tangential_force / rp.diameter, worst = 0.0;
    for (int q = 0; rc == RD_OK && q < 7; q++) {
        double zq = 0.005 + 0.087 * (q + 0.37) / 7.0; /* within the travel, off the halvings */
        rd_bore b;
        rc = rd_bore_map_at(&m, zq, rp.diameter, &b, &err);
        rc = rc ? rc : rd_lift_bore_loads_at(ring, &b, 320, NULL, at, ang, &err);
        for (int j = 0; rc == RD_OK && j < n; j++)
            worst = fmax(worst, fabs(rd_lift_depth_interp(z, load + D * j, D, zq) - at[j]) / w_el);
    }
    CHECK(rc == RD_OK, "contact between the layers: %s", err.message);
    if (rc == RD_OK) {
        /* the plain straight line between the two layers, for scale */
        double line = 0.0, zq = 0.05;
        rd_bore b;
        rd_bore_map_at(&m, zq, rp.diameter, &b, &err);
        rd_lift_bore_loads_at(ring, &b, 320, NULL, at, ang, &err);
        for (int j = 0; j < n; j++)
            line = fmax(line, fabs(0.5 * (load[D * j] + load[D * j + D - 1]) - at[j]) / w_el);
        printf("loads between layers (%.0f to %.0f um): %d depths; off them within %.3g of "
               "2 F_t / D (reported %.3g; the straight line between the layers: %.3g)\n",
               A_top * 1e6, A_bot * 1e6, D, worst, miss, line);
        CHECK(worst < 2.0 * RD_LIFT_FILMS_DEPTH_TOL, "the loads miss by %g", worst);
        CHECK(worst < 3.0 * miss + 1e-4 && miss < 3.0 * worst + 1e-4, "reported %g against %g",
              miss, worst);
    }
    rd_ring_free(ring);
}

/* Segment j's true miss: its own film (tr) against the interpolation the
 * lift reads; the film relative to max(|h|, sigma), the work relative. */
static double true_miss(const rd_lift_params *p, const rd_ring_params *rp, const rd_lift_films *fs,
                        int j, const rd_film_track *tr, double sigma, double *film_miss)
{
    double fe = 0.0, w[WMAX];
    for (int k = 0; k <= tr->steps; k++) {
        double t = tr->pt[k].t, h = 0.0;
        rd_lift_films_weights(fs, t, j, w);
        for (int g = 0; g < fs->count; g++) {
            rd_film_point pt;
            rd_film_track_at(&fs->tr[g], t, &pt);
            h += w[g] * pt.h0;
        }
        fe = fmax(fe, fabs(h - tr->pt[k].h0) / fmax(fabs(tr->pt[k].h0), sigma));
    }
    /* the work over the last cycle, each on its own steps (midpoint in t) */
    double omega = 2.0 * PI * p->engine.speed_rpm / 60.0, cycle = 4.0 * PI / omega;
    double circ = PI * rp->diameter, ureg = rd_liner_ureg(&p->engine);
    double mu = p->friction.lube.boundary_coefficient, want = 0.0, got = 0.0;
    for (int k = 0; k < tr->steps; k++) {
        const rd_film_point *a = &tr->pt[k], *b = &tr->pt[k + 1];
        double tm = 0.5 * (a->t + b->t);
        if (tm > cycle)
            continue;
        want += 0.5 * (b->t - a->t) *
                (rd_lift_film_power(a, circ, mu, ureg) + rd_lift_film_power(b, circ, mu, ureg));
    }
    for (int g = 0; g < fs->count; g++)
        for (int k = 0; k < fs->tr[g].steps; k++) {
            const rd_film_point *a = &fs->tr[g].pt[k], *b = &fs->tr[g].pt[k + 1];
            if (0.5 * (a->t + b->t) > cycle)
                continue;
            double wa[WMAX], wb[WMAX];
            rd_lift_films_weights(fs, a->t, j, wa);
            rd_lift_films_weights(fs, b->t, j, wb);
            got += 0.5 * (b->t - a->t) *
                   (wa[g] * rd_lift_film_power(a, circ, mu, ureg) +
                    wb[g] * rd_lift_film_power(b, circ, mu, ureg));
        }
    *film_miss = fe;
    return fmax(fe, fabs(got - want) / fabs(want));
}

/* Along a map: the quasi-static interpolation (kept, exact = -1) against
 * every segment's own film, its reported miss against that true miss;
 * and the films the lift takes (exact = 0): interpolated within
 * RD_LIFT_FILMS_TOL as checked, or each history its own film where the
 * check missed it.  Returns whether the lift's films were exact. */
static int histories(double A_top, double A_bot, int gas, int rpm)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_bore_map m;
    scene(&rp, &p, 0.0);
    map_of(&p, &m, A_top, A_bot);
    p.engine.speed_rpm = rpm;
    static fired_tables tables;
    if (gas)
        p.gas = fired_cycle_gas(&tables, 0.0);
    int n = 20, D = 0;
    rd_error err = {0};
    rd_ring *ring = rd_ring_create(&rp, n, 0, &err);
    double load[20 * RD_BORE_LAYERS_MAX], ang[20], z[RD_BORE_LAYERS_MAX], dm;
    rd_lift_films fs = {0}, lift = {0};
    int rc = ring ? rd_lift_map_loads(ring, &p, 320, NULL, load, ang, z, &D, &dm, &err) : RD_ENOMEM;
    rc = rc ? rc
            : rd_lift_films_run(&rp, &p, &(rd_lift_film_loads){n, D, z, load, ang, -1, NULL}, 1,
                                NULL, &fs, &err);
    CHECK(rc == RD_OK && fs.varying && !fs.exact, "films along the map: %s", err.message);
    rc = rc ? rc
            : rd_lift_films_run(&rp, &p, &(rd_lift_film_loads){n, D, z, load, ang, 0, NULL}, 1,
                                NULL, &lift, &err);
    double worst = 0.0, worst_film = 0.0, balance = 0.0, own = 0.0;
    for (int j = 0; rc == RD_OK && j < n; j++) {
        rd_film f = {0};
        rd_film_track tr = {0};
        rc = rd_lift_film_run_table(&rp, &p, fs.z, fs.seg_load + (size_t)fs.depths * j, fs.depths,
                                    1, &f, &tr, &err);
        if (rc == RD_OK) {
            double fm, miss = true_miss(&p, &rp, &fs, j, &tr, f.sigma, &fm);
            worst = fmax(worst, miss);
            worst_film = fmax(worst_film, fm);
            own = fmax(own, true_miss(&p, &rp, &lift, j, &tr, f.sigma, &fm));
            for (int k = 0; k <= tr.steps && !gas; k++) { /* its radial balance */
                double zk = rd_lift_depth_at(&p, tr.pt[k].t);
                double want =
                    rd_lift_depth_interp(fs.z, fs.seg_load + fs.depths * j, fs.depths, zk);
                balance = fmax(balance, fabs(tr.pt[k].W + tr.pt[k].Wa - want) / want);
            }
        }
        rd_film_track_free(&tr);
        rd_film_free(&f);
    }
    CHECK(rc == RD_OK, "each segment's film: %s", err.message);
    int exact = lift.exact;
    if (rc == RD_OK) {
        double r = fs.interp_check / worst;
        printf("map %.0f to %.0f um, %d rpm%s: %d depths, loads %.1f to %.1f N/m; %d films "
               "interpolated quasi-statically miss each segment's own film by %.3g (film %.3g), "
               "reported %.3g (x%.2f); the lift's: %s, %d films, %.3g off\n",
               A_top * 1e6, A_bot * 1e6, rpm, gas ? ", gas" : "", D, fs.load[0],
               fs.load[fs.count - 1], fs.count, worst, worst_film, fs.interp_check, r,
               exact ? "each history its own" : "interpolated", lift.count, own);
        if (!gas)
            printf("  the histories' films carry their load within %.3g\n", balance);
        CHECK(r > 1.0 / 3.0 && r < 3.0, "reported %g against a true miss %g", fs.interp_check,
              worst);
        /* the balance is solved to 1e-6 of the film; where asperities carry
           the load W changes fast with it */
        CHECK(gas || balance < 5e-4, "a history film's balance: %g", balance);
        if (exact)
            CHECK(own == 0.0 && isnan(lift.interp_check) && fs.interp_check > RD_LIFT_FILMS_TOL,
                  "each history its own film: %g off", own);
        else
            CHECK(own < 3.0 * RD_LIFT_FILMS_TOL && lift.interp_check <= RD_LIFT_FILMS_TOL,
                  "interpolated: %g off, reported %g", own, lift.interp_check);
    }
    rd_lift_films_free(&fs);
    rd_lift_films_free(&lift);
    rd_ring_free(ring);
    return exact;
}

/* Down a bore whose distortion grows toward the bottom: the top layer's
 * films near TDC, thinner ones near BDC. */
static void growing(void)
{
    rd_ring_params rp;
    rd_lift_params p, q;
    rd_bore_map m, mt;
    scene(&rp, &p, 0.0);
    q = p;
    map_of(&p, &m, 1e-6, 8e-6);
    map_of(&q, &mt, 1e-6, 1e-6);
    rd_lift_result a, b;
    rd_error err = {0};
    int rc = rd_lift_solve(&rp, 12, &p, NULL, &a, &err);
    rc = rc ? rc : rd_lift_solve(&rp, 12, &q, NULL, &b, &err);
    CHECK(rc == RD_OK, "growing map: %s", err.message);
    if (rc != RD_OK)
        return;
    double top = 0.0, bdc = INFINITY;
    int kb = 0;
    for (int k = 0; k < a.samples; k++) {
        double d = fmod(a.crank_deg[k], 360.0);
        if (d < 20.0 || d > 340.0) /* near TDC: the ring near the top layer */
            top = fmax(top, fabs(a.lube.min_film[k] - b.lube.min_film[k]) / b.lube.min_film[k]);
        if (fabs(d - 180.0) < 20.0) {
            bdc = fmin(bdc, (b.lube.min_film[k] - a.lube.min_film[k]) / b.lube.min_film[k]);
            kb++;
        }
    }
    printf("a map growing from 1 to 8 um: near TDC the film within %.3g of the top layer's, near "
           "BDC at least %.3g thinner (%d samples); loads %.1f to %.1f N/m against %.1f to %.1f\n",
           top, bdc, kb, a.lube.load_min, a.lube.load_max, b.lube.load_min, b.lube.load_max);
    CHECK(kb > 4 && bdc > 0.02, "near BDC the film should be thinner: %g", bdc);
    CHECK(top < 0.5 * bdc, "near TDC the film should be the top layer's: %g", top);
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

int main(void)
{
    equal_layers();
    between_layers(2e-6, 10e-6);
    between_layers(1e-6, 4e-6);
    int exact = histories(2e-6, 10e-6, 0, 2400);
    exact += histories(10e-6, 0.0, 1, 2400);
    exact += histories(1e-6, 8e-6, 0, 600);
    int interpolated = !histories(1e-6, 3e-6, 0, 2400);
    interpolated += !histories(3e-6, 1e-6, 1, 1200);
    CHECK(exact > 0 && interpolated > 0, "the battery takes both ways: %d exact, %d interpolated",
          exact, interpolated);
    growing();
    return check_done();
}
