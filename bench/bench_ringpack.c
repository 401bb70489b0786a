/*
 * bench_ringpack — what the ring pack costs per engine cycle (issue 15: one
 * cycle of a 3-ring pack with rigid rings <= 50 ms; with a flexible top
 * ring <= 10x the same ring's lift run alone).
 *
 *   bench_ringpack [--reps R]
 *     The thesis pack of examples/thesis_ringpack_*.json (top, second and
 *     oil ring, synthetic cylinder pressure; viscous-limited flank passages
 *     and linear flank pressure, the defaults), motored 2400 rpm, full load 2400 and
 *     6000 rpm, at rtol 1e-6 without the error estimate (the API's default
 *     doubles it with an rtol/10 run, about 1.3x to 2x): wall time of six
 *     cycles from rest (median of R >= 3) divided by six, CVODE steps,
 *     right-hand sides and restarts per cycle, the blow-by and the
 *     periodicity reached; once with the axial ring asked for (numerics.model
 *     axial) and once with the lift analysis' rigid rings (numerics.model
 *     rigid, auto's choice under the default linear flank pressure).
 *     Then the flexible top ring: the full-load packs with a full top ring
 *     (n = 20, the others axial), two cycles from rest, per cycle; against
 *     the top ring's lift analysis run alone (full, n = 20, one cycle) on
 *     the pack's pressures of its last cycle as gauge tables, at the same
 *     contact stiffness: the ratio of the times per cycle (medians).
 *   bench_ringpack --once    one run of each (the first case), for instruction counts.
 *   --section axial|rigid|flexible   only that table.
 *
 * Wall times on a shared 2-core machine are noisy: medians of repeats.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

/* The examples' pack (examples/thesis_ringpack_full_load_2400rpm.json: the
 * scene's default pack, rd_ringpack_params_thesis, its oil ring held). */
static void thesis_pack(rd_ringpack_params *p, double rpm, int motored, double peak_deg)
{
    rd_ringpack_params_thesis(p);
    p->engine.speed_rpm = rpm;
    p->engine.cycles = 6;
    p->estimate_error = 0;
    p->synthetic.peak_crank_deg = peak_deg;
    if (motored)
        p->cylinder_kind = p->synthetic.kind = RD_CYLINDER_MOTORED;
}

/* Median wall time (s) of `reps` runs of the pack; the last result in r. */
static int time_pack(const rd_ringpack_params *p, int reps, rd_ringpack_result *r, double *med)
{
    double t[50];
    for (int k = 0; k < reps; k++) {
        rd_error err;
        rd_error_init(&err);
        rd_ringpack_result_cleanup(r);
        double t0 = bench_now();
        if (rd_ringpack_solve(p, NULL, r, &err) != RD_OK) {
            fprintf(stderr, "pack: %s\n", err.message);
            return 1;
        }
        t[k] = bench_now() - t0;
    }
    *med = bench_median(t, reps);
    return 0;
}

static const struct {
    const char *what;
    double rpm;
    int motored;
    double peak_deg;
} cases[] = {{"motored 2400 rpm", 2400, 1, 15},
             {"full load 2400 rpm", 2400, 0, 15},
             {"full load 6000 rpm", 6000, 0, 18}};

/* The three scenes with every moving ring on `model` (auto gives the
 * rigid ring under the default linear flank pressure; the axial table asks
 * for the axial ring). */
static int rigid_table(int model, int reps, int once)
{
    printf("\n| case (%s rings) | ms per cycle (median of %d) | steps/cycle | rhs/cycle | "
           "restarts/cycle | blow-by L/min | periodicity |\n|---|---|---|---|---|---|---|\n",
           rd_ringpack_model_name(model), reps);
    for (int c = 0; c < (once ? 1 : 3); c++) {
        rd_ringpack_params p;
        rd_ringpack_result r;
        double med;
        memset(&r, 0, sizeof r);
        thesis_pack(&p, cases[c].rpm, cases[c].motored, cases[c].peak_deg);
        p.model = model;
        if (time_pack(&p, reps, &r, &med))
            return 1;
        double C = p.engine.cycles;
        printf("| %s | %.2f | %.0f | %.0f | %.1f | %.3f | %.2g |\n", cases[c].what, 1e3 * med / C,
               r.steps / C, r.rhs_evals / C, r.restarts / C, r.blowby_l_per_min, r.periodicity);
        rd_ringpack_result_cleanup(&r);
    }
    return 0;
}

/* The top ring's lift run alone on the pack's last-cycle pressures. */
static int time_lift(const rd_ringpack_params *p, const rd_ringpack_result *r, int reps,
                     double *med, long *steps)
{
    int S = r->samples;
    double *tab = malloc(3 * (size_t)S * sizeof *tab), t[50];
    if (!tab)
        return 1;
    for (int k = 0; k < S; k++) /* above: top land, behind: groove 1, below: second land */
        for (int f = 0; f < 3; f++)
            tab[(size_t)f * S + k] = r->pressure[(size_t)(f + 1) * S + k] - p->crankcase_pa;
    rd_lift_params lp;
    rd_lift_params_default(&lp);
    lp.engine = p->engine;
    lp.engine.cycles = 1;
    lp.groove = p->rings[0].groove;
    lp.gravity = p->gravity;
    lp.gas = (rd_gas_params){S, r->crank_deg, tab, tab + S, tab + 2 * S, RD_GAS_AREA_FIXED};
    lp.contact_stiffness = r->ring_stiffness[0];
    lp.estimate_error = 0;
    lp.model = RD_LIFT_MODEL_FULL;
    rd_lift_result l;
    int rc = 0;
    for (int k = 0; !rc && k < reps; k++) {
        rd_error err;
        rd_error_init(&err);
        double t0 = bench_now();
        rc = rd_lift_solve(&p->rings[0].ring, p->rings[0].segments, &lp, NULL, &l, &err);
        t[k] = bench_now() - t0;
        if (rc)
            fprintf(stderr, "lift: %s\n", err.message);
        *steps = l.steps;
        rd_lift_result_cleanup(&l);
    }
    free(tab);
    *med = bench_median(t, reps);
    return rc;
}

static int flexible_table(int reps, int once)
{
    printf(
        "\n| case (full top ring, n = 20) | pack ms per cycle | pack steps/cycle | lift alone ms "
        "per cycle | lift steps/cycle | ratio (target <= 10) |\n|---|---|---|---|---|---|\n");
    for (int c = 1; c < (once ? 2 : 3); c++) {
        rd_ringpack_params p;
        rd_ringpack_result r;
        double tp, tl;
        long ls = 0;
        memset(&r, 0, sizeof r);
        thesis_pack(&p, cases[c].rpm, cases[c].motored, cases[c].peak_deg);
        p.engine.cycles = 2;
        p.step_deg = 0.25; /* the lift run's tables */
        p.rings[0].model = RD_LIFT_MODEL_FULL;
        p.rings[0].segments = 20;
        if (time_pack(&p, reps, &r, &tp) || time_lift(&p, &r, reps, &tl, &ls))
            return 1;
        double C = p.engine.cycles;
        printf("| %s | %.1f | %.0f | %.1f | %ld | %.2f |\n", cases[c].what, 1e3 * tp / C,
               r.steps / C, 1e3 * tl, ls, tp / C / tl);
        rd_ringpack_result_cleanup(&r);
    }
    return 0;
}

int main(int argc, char **argv)
{
    int reps = 3, once = 0;
    const char *only = "";
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--once") == 0)
            once = 1;
        else if (strcmp(argv[i], "--section") == 0 && i + 1 < argc)
            only = argv[++i];
    }
    reps = once ? 1 : reps < 3 ? 3 : reps > 50 ? 50 : reps;
    int all = !*only;
    if ((all || !strcmp(only, "axial")) && rigid_table(RD_RINGPACK_AXIAL, reps, once))
        return 1;
    if ((all || !strcmp(only, "rigid")) && rigid_table(RD_LIFT_MODEL_RIGID, reps, once))
        return 1;
    return all || !strcmp(only, "flexible") ? flexible_table(reps, once) : 0;
}
