/*
 * bench_ringpack_lube — the cost of the lubricated friction model on the
 * ring pack's rings (issue 40's target: a 3-ring lubricated pack cycle
 * <= 150 ms).
 *
 *   bench_ringpack_lube [reps [cycles]]   (default 3 reps, 6 cycles)
 *
 * The thesis pack at full load, 2400 rpm (rd_ringpack_params_thesis: two
 * moving rings, the oil ring pinned), no error estimate: without friction
 * (auto: axial rings), with Coulomb friction (auto: rigid rings) and
 * lubricated (auto: rigid rings, each ring's film).  Per case: ms per cycle
 * (median of reps), CVODE steps per cycle, film solves per cycle (all
 * rings).  The machine is shared: compare the ratios, not one timing.
 */
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "rd_ringpack.h"

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 3, C = argc > 2 ? atoi(argv[2]) : 6;
    if (reps < 1 || reps > 100 || C < 2 || C > 50) {
        fprintf(stderr, "usage: bench_ringpack_lube [reps 1..100 [cycles 2..50]]\n");
        return 2;
    }
    static const char *const name[] = {"no friction", "coulomb mu 0.1", "lubricated"};
    static const int model[] = {RD_FRICTION_NONE, RD_FRICTION_COULOMB, RD_FRICTION_LUBRICATED};
    double base = 0.0;
    printf("thesis pack, full load 2400 rpm, %d cycles, no error estimate; median of %d\n", C,
           reps);
    printf("%-16s %12s %10s %14s %10s\n", "friction", "ms/cycle", "x none", "steps/cycle",
           "solves/cyc");
    for (int c = 0; c < 3; c++) {
        double t[100];
        long steps = 0, solves = 0;
        for (int k = 0; k < reps; k++) {
            rd_ringpack_params p;
            rd_ringpack_params_thesis(&p);
            p.engine.cycles = C;
            p.estimate_error = 0;
            p.friction.model = model[c];
            rd_ringpack_result r;
            rd_error err;
            rd_error_init(&err);
            double t0 = bench_now();
            if (rd_ringpack_solve(&p, NULL, &r, &err)) {
                fprintf(stderr, "%s: %s\n", name[c], err.message);
                return 1;
            }
            t[k] = (bench_now() - t0) / C * 1e3;
            steps = r.steps;
            solves = 0;
            for (int i = 0; i < r.n_rings; i++)
                solves += r.lube[i].on ? r.lube[i].film_solves : 0;
            rd_ringpack_result_cleanup(&r);
        }
        double ms = bench_median(t, reps);
        if (c == 0)
            base = ms;
        printf("%-16s %12.1f %10.2f %14.0f %10.0f\n", name[c], ms, ms / base, (double)steps / C,
               (double)solves);
    }
    return 0;
}
