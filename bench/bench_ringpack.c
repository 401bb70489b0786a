/*
 * bench_ringpack — what the ring pack costs per engine cycle (issue 15: one
 * cycle of a 3-ring pack with rigid rings <= 50 ms).
 *
 *   bench_ringpack [--reps R]
 *     The thesis pack of examples/thesis_ringpack_*.json (three rigid rings,
 *     synthetic cylinder pressure), motored 2400 rpm, full load 2400 and
 *     6000 rpm, at rtol 1e-6 without the error estimate (the API's default
 *     doubles it with an rtol/10 run, about 1.3x to 2x): wall time of six
 *     cycles from rest (median of R >= 3) divided by six, CVODE steps,
 *     right-hand sides and restarts per cycle, the blow-by and the
 *     periodicity reached.
 *   bench_ringpack --once    one six-cycle run, for instruction counts.
 *
 * Wall times on a shared 2-core machine are noisy: medians of repeats.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rd_ringpack.h"

/* The examples' pack (examples/thesis_ringpack_full_load_2400rpm.json). */
static void thesis_pack(rd_ringpack_params *p, double rpm, int motored, double peak_deg)
{
    static const double h[3] = {0.0012, 0.0015, 0.0025}, g[3] = {3e-4, 4e-4, 3e-4};
    static const double ca[3] = {3e-5, 4e-5, 4e-5}, lh[3] = {0.005, 0.004, 0.0035};
    static const double lc[3] = {4e-4, 3e-4, 2e-4};
    rd_ringpack_params_default(p);
    p->n_rings = 3;
    for (int i = 0; i < 3; i++) {
        p->rings[i].ring.axial_height = h[i];
        p->rings[i].ring.closed_gap = g[i];
        p->rings[i].groove.axial_clearance = ca[i];
        p->rings[i].land_height = lh[i];
        p->rings[i].land_clearance = lc[i];
    }
    p->engine.speed_rpm = rpm;
    p->engine.cycles = 6;
    p->estimate_error = 0;
    p->synthetic.peak_crank_deg = peak_deg;
    if (motored)
        p->cylinder_kind = p->synthetic.kind = RD_CYLINDER_MOTORED;
}

int main(int argc, char **argv)
{
    int reps = 3, once = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--once") == 0)
            once = 1;
    }
    reps = reps < 3 ? 3 : reps > 50 ? 50 : reps;
    struct {
        const char *what;
        double rpm;
        int motored;
        double peak_deg;
    } cases[] = {{"motored 2400 rpm", 2400, 1, 15},
                 {"full load 2400 rpm", 2400, 0, 15},
                 {"full load 6000 rpm", 6000, 0, 18}};
    printf("| case | ms per cycle (median of %d) | steps/cycle | rhs/cycle | restarts/cycle "
           "| blow-by L/min | periodicity |\n|---|---|---|---|---|---|---|\n",
           reps);
    for (int c = 0; c < (once ? 1 : 3); c++) {
        rd_ringpack_params p;
        thesis_pack(&p, cases[c].rpm, cases[c].motored, cases[c].peak_deg);
        double t[50];
        rd_ringpack_result r;
        memset(&r, 0, sizeof r);
        for (int k = 0; k < (once ? 1 : reps); k++) {
            rd_error err;
            rd_error_init(&err);
            rd_ringpack_result_cleanup(&r);
            double t0 = bench_now();
            if (rd_ringpack_solve(&p, NULL, &r, &err) != RD_OK) {
                fprintf(stderr, "%s: %s\n", cases[c].what, err.message);
                return 1;
            }
            t[k] = bench_now() - t0;
        }
        double C = p.engine.cycles;
        printf("| %s | %.2f | %.0f | %.0f | %.1f | %.3f | %.2g |\n", cases[c].what,
               1e3 * bench_median(t, once ? 1 : reps) / C, r.steps / C, r.rhs_evals / C,
               r.restarts / C, r.blowby_l_per_min, r.periodicity);
        rd_ringpack_result_cleanup(&r);
    }
    return 0;
}
