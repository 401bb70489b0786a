/*
 * bench_modal — what accuracy each segment count buys and what it costs.
 *
 *   bench_modal [--modes K] [--max-n N]   table: n, wall and CPU time
 *       (medians of repeats) without and with the error estimate, Lanczos
 *       steps, the true error of the first K frequencies vs the n -> infinity
 *       limit, the solver's own estimate, the true error of its Richardson-
 *       extrapolated frequencies, and the fitted cost exponents (t ~ n^p over
 *       n >= 100, and locally 500 -> 1000 -> 2000).
 *   bench_modal --once N [--modes K]      one solve with the error estimate,
 *       for `valgrind --tool=callgrind` instruction counts (bench/run.sh).
 *   bench_modal --predict                 rd_modal_cost_predict against the
 *       measured CPU time over n, modes, split/closed, with/without the
 *       estimate, and the worst ratio.
 *
 * The limit is the Richardson extrapolation from n = 2000 and 1000 (the
 * model converges as n^-2; tests/core/test_modal.c checks that order).
 * Times on a shared 2-core machine are noisy: each is the median of at least
 * 11 repeats and 0.5 s; instruction counts (run.sh) are exact.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"

#include "rd_modal.h"

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* Median wall and CPU time of one rd_modal_solve, s. */
static void timed_solve(const rd_ring_params *p, int n, int modes, int estimate, int *iters,
                        double *wall, double *cpu)
{
    double tw[256], tc[256];
    int reps = 0;
    double start = bench_now();
    while (reps < 256 && (reps < 11 || bench_now() - start < 0.5)) {
        rd_modal_opts o;
        rd_modal_opts_default(&o);
        o.modes = modes;
        o.estimate_error = estimate;
        rd_modal_result r;
        rd_error err;
        rd_error_init(&err);
        double t0 = bench_now(), c0 = cpu_now();
        if (rd_modal_solve(p, n, 0, &o, NULL, &r, &err)) {
            fprintf(stderr, "n=%d: %s\n", n, err.message);
            exit(1);
        }
        tc[reps] = cpu_now() - c0;
        tw[reps++] = bench_now() - t0;
        *iters = r.iterations;
        rd_modal_result_cleanup(&r);
    }
    *wall = bench_median(tw, reps);
    *cpu = bench_median(tc, reps);
}

/* The limit frequency of mode i of r: the same-kind mode of lim, extrapolated. */
static double limit_of(const rd_modal_result *lim, const rd_modal_result *r, int i)
{
    int kind = r->modes[i].kind, want = 0, c = 0;
    for (int k = 0; k < i; k++)
        want += r->modes[k].kind == kind;
    for (int j = 0; j < lim->n_modes; j++)
        if (lim->modes[j].kind == kind && c++ == want)
            return lim->modes[j].frequency_extrapolated_hz;
    return NAN;
}

/* rd_modal_cost_predict against measured CPU-time medians. */
static int predict_table(const rd_ring_params *p)
{
    static const int ns[] = {5, 10, 20, 50, 100, 300, 1000}, ms[] = {1, 6, 20, 60};
    double worst = 1.0;
    printf("| closed | n | modes | estimate | predicted CPU [ms] | measured CPU [ms] | ratio |\n"
           "|---|---|---|---|---|---|---|\n");
    for (int closed = 0; closed < 2; closed++)
        for (size_t a = 0; a < sizeof ns / sizeof ns[0]; a++)
            for (size_t b = 0; b < sizeof ms / sizeof ms[0]; b++)
                for (int e = 0; e < 2; e++) {
                    rd_modal_opts o;
                    rd_modal_opts_default(&o);
                    o.modes = ms[b];
                    o.estimate_error = e;
                    if (o.modes > 6 * ns[a] - 6)
                        continue;
                    double t[9];
                    for (int r = 0; r < 9; r++) {
                        rd_modal_result res;
                        double c0 = cpu_now();
                        if (rd_modal_solve(p, ns[a], closed, &o, NULL, &res, NULL))
                            return 1;
                        t[r] = cpu_now() - c0;
                        rd_modal_result_cleanup(&res);
                    }
                    double meas = bench_median(t, 9);
                    double pred = rd_modal_cost_predict(&o, ns[a], closed);
                    worst = fmax(worst, fmax(pred / meas, meas / pred));
                    printf("| %d | %d | %d | %d | %.3f | %.3f | %.2f |\n", closed, ns[a], ms[b], e,
                           1e3 * pred, 1e3 * meas, pred / meas);
                }
    printf("\nWorst factor between predicted and measured: %.2f\n", worst);
    return 0;
}

/* The accuracy/cost table against the limit from n = 2000 and 1000. */
static int accuracy_table(const rd_ring_params *pp, const rd_modal_opts *o, int max_n)
{
    const rd_ring_params p = *pp;
    int modes = o->modes;
    rd_error err;
    rd_error_init(&err);
    /* spare modes in the limit, so coarse rings with a spurious mode still
     * find their k-th mode of each kind */
    rd_modal_opts lo = *o;
    lo.modes = modes + 6 <= RD_MODAL_MODES_MAX ? modes + 6 : RD_MODAL_MODES_MAX;
    rd_modal_result lim;
    if (rd_modal_solve(&p, RD_SEGMENTS_MAX, 0, &lo, NULL, &lim, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    printf("Thesis ring, first %d elastic modes; limit = Richardson(n=2000, 1000); times are "
           "medians (wall / CPU of the calling thread).\n\n",
           modes);
    printf("| n | DOF | solve wall / CPU [ms] | Lanczos steps | with estimate wall / CPU [ms] | "
           "max true error | max estimated error | max error of extrapolated f |\n"
           "|---|---|---|---|---|---|---|---|\n");
    static const int ns[] = {4,  6,   8,   10,  12,  16,  20,   30,  40,
                             60, 100, 150, 200, 300, 500, 1000, 2000};
    double lx[32], ly[32], t_at[3] = {0, 0, 0};
    int nfit = 0;
    for (size_t k = 0; k < sizeof ns / sizeof ns[0] && ns[k] <= max_n; k++) {
        int n = ns[k], iters = 0, it2 = 0;
        double tw, tc, tew, tec;
        timed_solve(&p, n, modes, 0, &iters, &tw, &tc);
        timed_solve(&p, n, modes, 1, &it2, &tew, &tec);
        rd_modal_result r;
        rd_error_init(&err);
        rd_modal_solve(&p, n, 0, o, NULL, &r, &err);
        double true_err = 0.0, extra_err = 0.0;
        for (int i = 0; i < r.n_modes; i++) {
            double f = limit_of(&lim, &r, i);
            double e = fabs(r.modes[i].frequency_hz - f) / f;
            double x = fabs(r.modes[i].frequency_extrapolated_hz - f) / f;
            if (!(e <= true_err))
                true_err = e;
            if (!(x <= extra_err))
                extra_err = x;
        }
        printf("| %d | %d | %.3f / %.3f | %d | %.3f / %.3f | %.2e | %.2e | %.1e |\n", n, 6 * n,
               1e3 * tw, 1e3 * tc, iters, 1e3 * tew, 1e3 * tec, true_err, r.error_estimate,
               extra_err);
        if (n >= 100) {
            lx[nfit] = n;
            ly[nfit++] = tc;
        }
        for (int a = 0; a < 3; a++)
            if (n == 500 << a)
                t_at[a] = tc;
        rd_modal_result_cleanup(&r);
    }
    if (nfit >= 2)
        printf("\nFitted cost exponent (CPU time of one solve ~ n^p, n >= 100): p = %.2f\n",
               bench_exponent(lx, ly, nfit));
    if (t_at[0] > 0 && t_at[1] > 0)
        printf("Local exponent 500 -> 1000: %.2f\n", log(t_at[1] / t_at[0]) / log(2.0));
    if (t_at[1] > 0 && t_at[2] > 0)
        printf("Local exponent 1000 -> 2000: %.2f\n", log(t_at[2] / t_at[1]) / log(2.0));
    rd_modal_result_cleanup(&lim);
    return 0;
}

int main(int argc, char **argv)
{
    int modes = 6, max_n = 2000, once = 0, predict = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--modes") && i + 1 < argc)
            modes = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--max-n") && i + 1 < argc)
            max_n = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--once") && i + 1 < argc)
            once = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--predict"))
            predict = 1;
        else {
            fprintf(stderr, "usage: bench_modal [--modes K] [--max-n N] | --once N [--modes K] | "
                            "--predict\n");
            return 2;
        }
    }
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_modal_opts o;
    rd_modal_opts_default(&o);
    o.modes = modes;
    rd_error err;
    rd_error_init(&err);
    if (predict)
        return predict_table(&p);
    if (once) {
        rd_modal_result r;
        int rc = rd_modal_solve(&p, once, 0, &o, NULL, &r, &err);
        printf("n=%d rc=%d iterations=%d f1=%.6f Hz\n", once, rc, r.iterations,
               rc ? 0.0 : r.modes[0].frequency_hz);
        rd_modal_result_cleanup(&r);
        return rc ? 1 : 0;
    }

    return accuracy_table(&p, &o, max_n);
}
