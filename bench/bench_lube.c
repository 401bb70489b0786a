/*
 * bench_lube — the cost of the lubricated friction model (issue target: a
 * lubricated rigid-ring lift cycle <= 10 ms).
 *
 *   bench_lube [reps [scene]]   (default 5 reps, median wall times; scene 0-3 alone)
 *
 * Scenes (one 720 deg cycle, thesis ring, rigid model, no error estimate):
 * 2400 rpm without gas, and 1000 / 2400 / 6000 rpm with the thesis gas
 * example's tables (examples/ scenes are not read: a firing pulse written
 * here).  Per scene: the whole lift with lubricated friction, the film
 * alone (rd_lift_film_run), the same lift with Coulomb friction, the film's
 * steps and solves, the film with the JFO cavitation.  Instruction counts: bench/run.sh runs this under
 * callgrind (`valgrind --tool=callgrind bench_lube 1`).
 *
 * Then the flexible ring in a distorted bore (issue target: its per-segment
 * films <= 2x its Coulomb cost): the full ring, n = 20, orders 2 (5 um) and
 * 4 (2 um at 30 deg), 2400 rpm without and with gas, one cycle, no error
 * estimate: the lubricated lift (a film per segment load), the same with
 * Coulomb 0.1, their ratio, the films and their solves (scene 4 alone:
 * `bench_lube reps 4`).
 *
 * Then the same ring on a bore map (scene 5 alone: `bench_lube reps 5`):
 * orders 2 + 4 as above at the top layer (z = 0) growing to 2x or 5x at
 * z = 0.1 m, the ring 5 mm down at TDC, 2400 rpm with gas: the lubricated
 * lift (the loads at the layers and the depths they need, films
 * interpolated at each instant or each load history its own), the same
 * with Coulomb 0.1, their ratio, the depths and the films.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "fired_cycle.h"
#include "rd_lift_internal.h"

static fired_tables tables;

static void scene(rd_lift_params *p, double rpm, int gas, int model)
{
    rd_lift_params_default(p);
    p->engine.speed_rpm = rpm;
    p->engine.cycles = 1.0;
    p->friction.model = model;
    p->model = RD_LIFT_MODEL_RIGID;
    p->estimate_error = 0;
    if (gas) /* absolute used as gauge, as measured */
        p->gas = fired_cycle_gas(&tables, 0.0);
}

/* The median wall time of reps lifts (ms); the last run's films and film
 * solves into films, solves (NULL: not wanted). */
static double lift_ms_films(const rd_ring_params *rp, const rd_lift_params *p, int reps, int *films,
                            long *solves)
{
    double t[16];
    for (int k = 0; k < reps; k++) {
        rd_lift_result r;
        rd_error err;
        rd_error_init(&err);
        double t0 = bench_now();
        int rc = rd_lift_solve(rp, 20, p, NULL, &r, &err);
        t[k] = 1e3 * (bench_now() - t0);
        if (rc)
            fprintf(stderr, "lift: %s\n", err.message);
        if (films) {
            *films = r.lube.films;
            *solves = r.lube.film_solves;
        }
        rd_lift_result_cleanup(&r);
    }
    return bench_median(t, reps);
}

static double lift_ms(const rd_ring_params *rp, const rd_lift_params *p, int reps)
{
    return lift_ms_films(rp, p, reps, NULL, NULL);
}

/* The films' two parts alone (median ms): the segments' loads (the
 * contact analysis) and the films on them. */
static void parts_ms(const rd_ring_params *rp, const rd_lift_params *p, int reps, double *out)
{
    double t[2][16], load[20], ang[20];
    rd_error err;
    rd_error_init(&err);
    rd_ring *ring = rd_ring_create(rp, 20, 0, &err);
    for (int k = 0; ring && k < reps; k++) {
        rd_lift_films fs;
        double t0 = bench_now();
        if (rd_lift_bore_loads(ring, p, load, ang, &err))
            fprintf(stderr, "loads: %s\n", err.message);
        double t1 = bench_now();
        if (rd_lift_films_run(rp, p, &(rd_lift_film_loads){20, 1, NULL, load, ang, 0, NULL}, 1,
                              NULL, &fs, &err))
            fprintf(stderr, "films: %s\n", err.message);
        t[0][k] = 1e3 * (t1 - t0);
        t[1][k] = 1e3 * (bench_now() - t1);
        rd_lift_films_free(&fs);
    }
    out[0] = bench_median(t[0], reps);
    out[1] = bench_median(t[1], reps);
    rd_ring_free(ring);
}

/* The distorted bore's table (file comment). */
static void distorted(const rd_ring_params *rp, int reps)
{
    printf("\n| full ring n = 20, distorted bore | lubricated (per-segment films), ms | "
           "Coulomb, ms | ratio | films | film solves | of it: the loads (contact analysis), ms | "
           "the films, ms |\n|---|---|---|---|---|---|---|---|\n");
    for (int gas = 0; gas < 2; gas++) {
        rd_lift_params p;
        double ms[2], ms_parts[2];
        int films = 0;
        long solves = 0;
        for (int m = 0; m < 2; m++) {
            scene(&p, 2400.0, gas, m ? RD_FRICTION_COULOMB : RD_FRICTION_LUBRICATED);
            p.model = RD_LIFT_MODEL_FULL;
            p.bore.n_distortion = 2;
            p.bore.distortion[0] = (rd_distortion){.order = 2, .amplitude = 5e-6};
            p.bore.distortion[1] = (rd_distortion){.order = 4, .amplitude = 2e-6, .phase_deg = 30};
            ms[m] = lift_ms_films(rp, &p, reps, m ? NULL : &films, &solves);
            if (m == 0)
                parts_ms(rp, &p, reps, ms_parts);
        }
        printf("| 2400 rpm%s | %.0f | %.0f | %.2f | %d | %ld | %.0f | %.0f |\n", gas ? ", gas" : "",
               ms[0], ms[1], ms[0] / ms[1], films, solves, ms_parts[0], ms_parts[1]);
    }
}

/* The bore map's table (file comment). */
static void mapped(const rd_ring_params *rp, int reps)
{
    printf("\n| full ring n = 20, bore map, 2400 rpm, gas | lubricated, ms | Coulomb, ms | ratio | "
           "depths | films | film_interpolation_error |\n|---|---|---|---|---|---|---|\n");
    double grow[2] = {2.0, 5.0};
    for (int c = 0; c < 2; c++) {
        rd_lift_params p;
        rd_bore_map map;
        double ms[2];
        rd_lift_result r = {0};
        for (int m = 0; m < 2; m++) {
            scene(&p, 2400.0, 1, m ? RD_FRICTION_COULOMB : RD_FRICTION_LUBRICATED);
            p.model = RD_LIFT_MODEL_FULL;
            map = (rd_bore_map){.n_layers = 2, .residual_rms = NAN};
            for (int i = 0; i < 2; i++) {
                double a = i ? grow[c] * 2e-6 : 2e-6;
                map.layer[i].z = 0.1 * i;
                map.layer[i].bore.n_distortion = 2;
                map.layer[i].bore.distortion[0] = (rd_distortion){.order = 2, .amplitude = 2.5 * a};
                map.layer[i].bore.distortion[1] =
                    (rd_distortion){.order = 4, .amplitude = a, .phase_deg = 30};
            }
            p.bore_map = &map;
            p.ring_z_tdc = 0.005;
            ms[m] = lift_ms(rp, &p, reps);
            rd_error err;
            rd_error_init(&err);
            if (m == 0 && rd_lift_solve(rp, 20, &p, NULL, &r, &err))
                fprintf(stderr, "lift: %s\n", err.message);
        }
        printf("| 5/2 um growing %.0fx | %.0f | %.0f | %.2f | %d | %d | %.3g |\n", grow[c], ms[0],
               ms[1], ms[0] / ms[1], r.lube.load_depths, r.lube.films, r.lube.interp_check);
        rd_lift_result_cleanup(&r);
    }
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 5;
    reps = reps < 1 ? 1 : (reps > 15 ? 15 : reps);
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    double rpms[4] = {2400.0, 1000.0, 2400.0, 6000.0};
    int gases[4] = {0, 1, 1, 1};
    int only = argc > 2 ? atoi(argv[2]) : -1;
    if (only < 4)
        printf("| scene | lubricated lift, ms | film alone, ms | film steps | film solves | "
               "Coulomb lift, ms | the estimate's film, ms | film alone with JFO cavitation, ms "
               "(solves) "
               "|\n|---|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < 4 && only != 4 && only != 5; s++) {
        if (only >= 0 && s != only)
            continue;
        rd_lift_params p;
        scene(&p, rpms[s], gases[s], RD_FRICTION_LUBRICATED);
        double lub = lift_ms(&rp, &p, reps), t[16];
        rd_film_track tr = {0};
        for (int k = 0; k < reps; k++) {
            rd_film f;
            rd_error err;
            rd_error_init(&err);
            rd_film_track_free(&tr);
            double t0 = bench_now();
            if (rd_lift_film_run(&rp, &p, &f, &tr, &err))
                fprintf(stderr, "film: %s\n", err.message);
            t[k] = 1e3 * (bench_now() - t0);
            rd_film_free(&f);
        }
        double film = bench_median(t, reps);
        for (int k = 0; k < reps; k++) { /* the error estimate's film (grid twice as fine) */
            rd_film f;
            rd_film_track tf = {0};
            rd_error err;
            rd_error_init(&err);
            double t0 = bench_now();
            if (rd_lift_film_run_at(&rp, &p, 2, &f, &tf, &err))
                fprintf(stderr, "film: %s\n", err.message);
            t[k] = 1e3 * (bench_now() - t0);
            rd_film_track_free(&tf);
            rd_film_free(&f);
        }
        double fine = bench_median(t, reps);
        p.friction.lube.cavitation = RD_CAVITATION_JFO;
        long jfo_solves = 0;
        for (int k = 0; k < reps; k++) { /* the film with mass-conserving cavitation */
            rd_film f;
            rd_film_track tj = {0};
            rd_error err;
            rd_error_init(&err);
            double t0 = bench_now();
            if (rd_lift_film_run(&rp, &p, &f, &tj, &err))
                fprintf(stderr, "film: %s\n", err.message);
            t[k] = 1e3 * (bench_now() - t0);
            jfo_solves = tj.solves;
            rd_film_track_free(&tj);
            rd_film_free(&f);
        }
        double jfo = bench_median(t, reps);
        scene(&p, rpms[s], gases[s], RD_FRICTION_COULOMB);
        double cou = lift_ms(&rp, &p, reps);
        printf("| %.0f rpm%s | %.1f | %.1f | %d | %ld | %.1f | %.1f | %.1f (%ld) |\n", rpms[s],
               gases[s] ? ", gas" : "", lub, film, tr.steps, tr.solves, cou, fine, jfo, jfo_solves);
        rd_film_track_free(&tr);
    }
    if (only < 0 || only == 4)
        distorted(&rp, reps < 3 ? reps : 3);
    if (only < 0 || only == 5)
        mapped(&rp, reps < 3 ? reps : 3);
    return 0;
}
