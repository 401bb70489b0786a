/*
 * bench_modal — what accuracy each segment count buys and what it costs.
 *
 *   bench_modal [--modes K] [--max-n N]   table: n, wall time (median of
 *       repeats), true error of the first K frequencies vs the n -> infinity
 *       limit, the solver's own estimate, cost with the estimate, and the
 *       fitted cost exponent (t ~ n^p over n >= 100).
 *   bench_modal --once N [--modes K]      one solve with the error estimate,
 *       for `valgrind --tool=callgrind` instruction counts (bench/run.sh).
 *
 * The limit is the Richardson extrapolation from n = 2000 and 1000 (the
 * model converges as n^-2; tests/core/test_modal.c checks that order).
 * Wall times on a shared 2-core machine are noisy: each is the median of at
 * least 5 repeats and 0.3 s; instruction counts (run.sh) are exact.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"

#include "rd_modal.h"

static double timed_solve(const rd_ring_params *p, int n, int modes, int estimate, int *iters)
{
    double t[64];
    int reps = 0;
    double start = bench_now();
    while (reps < 64 && (reps < 5 || bench_now() - start < 0.3)) {
        rd_modal_opts o;
        rd_modal_opts_default(&o);
        o.modes = modes;
        o.estimate_error = estimate;
        rd_modal_result r;
        rd_error err;
        rd_error_init(&err);
        double t0 = bench_now();
        if (rd_modal_solve(p, n, 0, &o, NULL, &r, &err)) {
            fprintf(stderr, "n=%d: %s\n", n, err.message);
            exit(1);
        }
        t[reps++] = bench_now() - t0;
        *iters = r.iterations;
        rd_modal_result_cleanup(&r);
    }
    return bench_median(t, reps);
}

int main(int argc, char **argv)
{
    int modes = 6, max_n = 2000, once = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--modes") && i + 1 < argc)
            modes = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--max-n") && i + 1 < argc)
            max_n = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--once") && i + 1 < argc)
            once = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_modal [--modes K] [--max-n N] | --once N [--modes K]\n");
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
    if (once) {
        rd_modal_result r;
        int rc = rd_modal_solve(&p, once, 0, &o, NULL, &r, &err);
        printf("n=%d rc=%d iterations=%d f1=%.6f Hz\n", once, rc, r.iterations,
               rc ? 0.0 : r.modes[0].frequency_hz);
        rd_modal_result_cleanup(&r);
        return rc ? 1 : 0;
    }

    /* spare modes in the limit, so coarse rings with a spurious mode still
     * find their k-th mode of each kind */
    rd_modal_opts lo = o;
    lo.modes = modes + 6 <= RD_MODAL_MODES_MAX ? modes + 6 : RD_MODAL_MODES_MAX;
    rd_modal_result lim;
    if (rd_modal_solve(&p, RD_SEGMENTS_MAX, 0, &lo, NULL, &lim, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    printf("Thesis ring, first %d elastic modes; limit = Richardson(n=2000, 1000).\n\n", modes);
    printf("| n | DOF | solve [ms] | iterations | max true error | max estimated error | "
           "with estimate [ms] |\n|---|---|---|---|---|---|---|\n");
    static const int ns[] = {4, 6, 8, 10, 12, 16, 20, 30, 40, 60, 100, 150, 200, 300, 500, 1000, 2000};
    double lx[32], ly[32];
    int nfit = 0;
    for (size_t k = 0; k < sizeof ns / sizeof ns[0] && ns[k] <= max_n; k++) {
        int n = ns[k], iters = 0, it2 = 0;
        double t = timed_solve(&p, n, modes, 0, &iters);
        double te = timed_solve(&p, n, modes, 1, &it2);
        rd_modal_result r;
        rd_error_init(&err);
        rd_modal_solve(&p, n, 0, &o, NULL, &r, &err);
        double true_err = 0.0;
        /* compare like with like: k-th mode of each kind */
        int seen[2] = {0, 0};
        for (int i = 0; i < r.n_modes; i++) {
            int kind = r.modes[i].kind, want = seen[kind]++, j, c = 0;
            for (j = 0; j < lim.n_modes; j++)
                if (lim.modes[j].kind == kind && c++ == want)
                    break;
            double f = j < lim.n_modes ? lim.modes[j].frequency_extrapolated_hz : NAN;
            double e = fabs(r.modes[i].frequency_hz - f) / f;
            if (!(e <= true_err))
                true_err = e;
        }
        printf("| %d | %d | %.3f | %d | %.2e | %.2e | %.3f |\n", n, 6 * n, 1e3 * t, iters,
               true_err, r.error_estimate, 1e3 * te);
        if (n >= 100) {
            lx[nfit] = n;
            ly[nfit++] = t;
        }
        rd_modal_result_cleanup(&r);
    }
    if (nfit >= 2)
        printf("\nFitted cost exponent (wall time ~ n^p, n >= 100): p = %.2f\n",
               bench_exponent(lx, ly, nfit));
    rd_modal_result_cleanup(&lim);
    return 0;
}
