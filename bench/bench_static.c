/*
 * bench_static — accuracy and cost of the pretension and contact analyses.
 *
 *   bench_static            tables: (1) pretension x_a vs n: wall time
 *       (median of repeats), Newton iterations, true error vs the n -> infinity
 *       limit and the solver's own estimate; (2) contact in a round bore:
 *       mean pressure error vs 2 F_t / (d h), wall time; (3) contact points
 *       per segment at n = 40 (round and 4th-order distorted bore): wall time
 *       and the change of the pressure profile vs 20 points; fitted cost
 *       exponents (t ~ n^p over n >= 80).
 *   bench_static --once N   one contact solve at N segments (callgrind).
 *
 * The x_a limit is the Richardson extrapolation from n = 2000 and 1000
 * (order 2, checked in tests/core/test_static.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"

#include "rd_static.h"

static void die(const char *what, const rd_error *err)
{
    fprintf(stderr, "%s: %s\n", what, err->message);
    exit(1);
}

/* Median wall time of repeated pretension solves; the last result kept. */
static double time_pretension(const rd_ring_params *p, int n, int estimate,
                              rd_pretension_result *keep)
{
    double t[64];
    int reps = 0;
    double start = bench_now();
    while (reps < 64 && (reps < 5 || bench_now() - start < 0.3)) {
        rd_pretension_opts o;
        rd_pretension_opts_default(&o);
        rd_static_opts so;
        rd_static_opts_default(&so);
        so.estimate_error = estimate;
        rd_error err;
        rd_error_init(&err);
        rd_pretension_result_cleanup(keep);
        double t0 = bench_now();
        if (rd_pretension_solve(p, n, &o, &so, NULL, keep, &err))
            die("pretension", &err);
        t[reps++] = bench_now() - t0;
    }
    return bench_median(t, reps);
}

static double time_contact(const rd_ring_params *p, int n, const rd_contact_opts *o,
                           rd_contact_result *keep)
{
    double t[64];
    int reps = 0;
    double start = bench_now();
    while (reps < 64 && (reps < 5 || bench_now() - start < 0.3)) {
        rd_static_opts so;
        rd_static_opts_default(&so);
        so.estimate_error = 0;
        rd_error err;
        rd_error_init(&err);
        rd_contact_result_cleanup(keep);
        double t0 = bench_now();
        if (rd_contact_solve(p, n, o, &so, NULL, keep, &err))
            die("contact", &err);
        t[reps++] = bench_now() - t0;
    }
    return bench_median(t, reps);
}

static double profile_change(const rd_contact_result *a, const rd_contact_result *b, double p0)
{
    double worst = 0;
    for (int i = 0; i < a->points; i++)
        worst = fmax(worst, fabs(a->pressure[i] - b->pressure[i]) / p0);
    return worst;
}

int main(int argc, char **argv)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts co;
    rd_contact_opts_default(&co);
    if (argc == 3 && strcmp(argv[1], "--once") == 0) {
        rd_contact_result r;
        rd_static_opts so;
        rd_static_opts_default(&so);
        so.estimate_error = 0;
        rd_error err;
        rd_error_init(&err);
        if (rd_contact_solve(&p, atoi(argv[2]), &co, &so, NULL, &r, &err))
            die("contact", &err);
        rd_contact_result_cleanup(&r);
        return 0;
    }
    double p0 = 2 * p.tangential_force / (p.diameter * p.axial_height);

    rd_pretension_result r1, r2;
    memset(&r1, 0, sizeof r1);
    memset(&r2, 0, sizeof r2);
    time_pretension(&p, 2000, 0, &r1);
    time_pretension(&p, 1000, 0, &r2);
    double limit = r1.gap_opening_inner + (r1.gap_opening_inner - r2.gap_opening_inner) / 3.0;
    printf("## pretension (force method, thesis ring): x_a limit %.6f mm\n\n", limit * 1e3);
    printf("| n | x_a (mm) | true error | estimate | Newton iterations | wall (ms) | wall with "
           "estimate (ms) |\n|---|---|---|---|---|---|---|\n");
    const int ns[] = {10, 20, 40, 80, 160, 320, 640, 1280};
    const int nn = sizeof ns / sizeof ns[0];
    double xs[16], ts[16], tc[16];
    int k = 0;
    for (int i = 0; i < nn; i++) {
        double t = time_pretension(&p, ns[i], 0, &r1);
        int iters = r1.stats.iterations;
        double xa = r1.gap_opening_inner;
        double te = time_pretension(&p, ns[i], 1, &r1);
        printf("| %d | %.4f | %.2e | %.2e | %d | %.2f | %.2f |\n", ns[i], xa * 1e3,
               fabs(xa - limit) / limit, r1.stats.error_estimate, iters, t * 1e3, te * 1e3);
        if (ns[i] >= 80) {
            xs[k] = ns[i];
            ts[k++] = t;
        }
    }
    printf("\ncost exponent (t ~ n^p, n >= 80): p = %.2f\n\n", bench_exponent(xs, ts, k));

    printf("## contact, round bore (%d points per segment, the default)\n\n", co.points_per_segment);
    printf("| n | mean pressure / p0 - 1 | Newton iterations | wall (ms) |\n|---|---|---|---|\n");
    rd_contact_result c, c20;
    memset(&c, 0, sizeof c);
    memset(&c20, 0, sizeof c20);
    k = 0;
    for (int i = 0; i < nn; i++) {
        double t = time_contact(&p, ns[i], &co, &c);
        printf("| %d | %+.2e | %d | %.2f |\n", ns[i], c.mean_pressure / p0 - 1, c.stats.iterations,
               t * 1e3);
        if (ns[i] >= 80) {
            xs[k] = ns[i];
            tc[k++] = t;
        }
    }
    printf("\ncost exponent (t ~ n^p, n >= 80): p = %.2f\n\n", bench_exponent(xs, tc, k));

    printf("## contact points per segment, n = 40\n\n");
    printf("| points | round bore: wall (ms) | change vs 20 points (of p0) | distorted "
           "(k=4, 1.3 x bound): wall (ms) | change vs 20 points |\n|---|---|---|---|---|\n");
    rd_contact_opts cd = co;
    cd.n_distortion = 1;
    cd.distortion[0].order = 4;
    cd.distortion[0].phase_deg = 45;
    cd.distortion[0].amplitude = 1.3 * 4.3246e-6; /* 1.3 x F_t R^3 / (E I 15^2) */
    rd_contact_result d, d20;
    memset(&d, 0, sizeof d);
    memset(&d20, 0, sizeof d20);
    co.points_per_segment = cd.points_per_segment = 20;
    time_contact(&p, 40, &co, &c20);
    time_contact(&p, 40, &cd, &d20);
    const int ms[] = {1, 2, 3, 5, 10, 20};
    for (int i = 0; i < 6; i++) {
        co.points_per_segment = cd.points_per_segment = ms[i];
        double t = time_contact(&p, 40, &co, &c);
        double td = time_contact(&p, 40, &cd, &d);
        printf("| %d | %.2f | %.1e | %.2f | %.1e |\n", ms[i], t * 1e3,
               profile_change(&c, &c20, p0), td * 1e3, profile_change(&d, &d20, p0));
    }
    rd_pretension_result_cleanup(&r1);
    rd_pretension_result_cleanup(&r2);
    rd_contact_result_cleanup(&c);
    rd_contact_result_cleanup(&c20);
    rd_contact_result_cleanup(&d);
    rd_contact_result_cleanup(&d20);
    return 0;
}
