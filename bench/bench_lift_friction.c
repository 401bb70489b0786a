/*
 * bench_lift_friction — how far the rigid lift model (rd_lift_rigid.c) is
 * from the full one on axisymmetric scenes WITH bore friction, the scenes
 * auto gives the full ring (README "Lift", "Models").
 *
 *   bench_lift_friction [N]     (N segments, default 6)
 *
 * 48 scenes, one cycle each: friction Coulomb and Stribeck x gas (a 58 bar
 * firing pulse, dynamic areas) off and on x 100, 1000, 3000, 8000 rpm x axial
 * clearances 5, 30, 100 um; thesis ring, gravity.  The rigid ring at rtol
 * 1e-8, the full ring at 1e-7 (atol 1e-3 rtol c_a / 30 um), both at N.  Per
 * scene: the number of flank changes of each, their largest angle
 * difference ("count" when the lists differ in length or kind), and the full
 * ring's largest spread of the segments' lifts (lift_max - lift_min) / c_a.
 * Cost: ~3 min CPU at N = 6, ~25 min at N = 20 (Release).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lift_battery.h"
#include "rd_lift.h"

/* The battery's scene (lift_battery.h), sampled every 1 deg. */
static void scene(rd_lift_params *p, double rpm, double ca, int gas, int fric, double rtol)
{
    lift_battery_scene(p, rpm, ca, gas, fric, rtol, 1.0);
}

static int run(const rd_lift_params *p, int model, int n, rd_lift_result *r)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params q = *p;
    q.model = model;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve(&rp, n, &q, NULL, r, &err);
    if (rc)
        fprintf(stderr, "%s: %s\n", rd_lift_model_name(model), err.message);
    return rc;
}

/* Largest angle difference of matched flank changes; -1 if the lists differ. */
static double event_diff(const rd_lift_result *a, const rd_lift_result *b)
{
    if (a->n_events != b->n_events)
        return -1.0;
    double d = 0.0;
    for (int i = 0; i < a->n_events; i++) {
        if (a->events[i].kind != b->events[i].kind)
            return -1.0;
        d = fmax(d, fabs(a->events[i].crank_deg - b->events[i].crank_deg));
    }
    return d;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 6;
    const double rpms[] = {100.0, 1000.0, 3000.0, 8000.0}, cas[] = {5e-6, 3e-5, 1e-4};
    printf("| friction | gas | rpm | c_a [um] | events rigid / full | rigid - full [deg] | full "
           "spread / c_a |\n");
    printf("|---|---|---|---|---|---|---|\n");
    for (int fr = RD_FRICTION_COULOMB; fr <= RD_FRICTION_STRIBECK; fr++)
        for (int g = 0; g < 2; g++)
            for (int a = 0; a < 4; a++)
                for (int c = 0; c < 3; c++) {
                    rd_lift_params p;
                    rd_lift_result ra = {0}, rf = {0};
                    scene(&p, rpms[a], cas[c], g, fr, 1e-8);
                    int rc = run(&p, RD_LIFT_MODEL_RIGID, n, &ra);
                    scene(&p, rpms[a], cas[c], g, fr, 1e-7);
                    int rc2 = rc ? rc : run(&p, RD_LIFT_MODEL_FULL, n, &rf);
                    if (rc || rc2)
                        return 1;
                    double d = event_diff(&ra, &rf), spread = 0.0;
                    for (int k = 0; k < rf.samples; k++)
                        spread = fmax(spread, (rf.lift_max[k] - rf.lift_min[k]) / cas[c]);
                    char ds[32];
                    if (d < 0.0)
                        snprintf(ds, sizeof ds, "count");
                    else
                        snprintf(ds, sizeof ds, "%.3f", d);
                    printf("| %s | %s | %.0f | %.0f | %d / %d | %s | %.3f |\n",
                           fr == RD_FRICTION_COULOMB ? "Coulomb" : "Stribeck", g ? "on" : "off",
                           rpms[a], cas[c] * 1e6, ra.n_events, rf.n_events, ds, spread);
                    fflush(stdout);
                    rd_lift_result_cleanup(&ra);
                    rd_lift_result_cleanup(&rf);
                }
    return 0;
}
