/*
 * bench_contact_cost — what one contact solve costs, and a fingerprint of
 * everything it answers, so a change meant to make the solve cheaper can
 * be shown to leave its answers bit for bit (or to say which moved).
 *
 *   bench_contact_cost [--rigid] [--cap N] K A PHASE [N]
 *       one bore of bench_static's battery (order K, A x the thin-ring
 *       bound capped at 0.4 % of the diameter, PHASE deg), at N segments
 *       without refinement, or (no N) refined as by default: segments,
 *       Newton iterations (one tangent and factorization each), load
 *       steps, final residual, CPU s, and the fingerprint.
 *   bench_contact_cost [--rigid] [--cap N] --battery
 *       the same, one line a bore, for the 32 battery bores (CPU the
 *       median of 3 solves), and the sums.
 *   --rigid: rigid running faces (rd_contact_opts.flexible_face = 0)
 *       instead of the default flexible ones (--face, the flexible ones, is
 *       accepted and changes nothing, as in bench_static);
 *   --cap N: rd_contact_opts.max_segments.
 *
 * The fingerprint is FNV-1a over the bytes of every double of the result
 * (per-segment profiles, summaries, gaps, bins, tip forces, estimates):
 * two builds agree on it only if every reported number is identical.
 * Callgrind instruction counts: valgrind --tool=callgrind
 * --toggle-collect=rd_contact_solve bench_contact_cost ...
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "contact_reference.h"

#include "rd_static.h"

static int flexible_face = 1, cap = 0;

static uint64_t fnv(uint64_t h, const void *data, size_t len)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < len; i++)
        h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

static uint64_t fingerprint(const rd_contact_result *c)
{
    uint64_t h = 1469598103934665603ull;
    size_t n = (size_t)c->points * sizeof(double);
    h = fnv(h, c->angle_deg, n);
    h = fnv(h, c->pressure, n);
    h = fnv(h, c->clearance, n);
    h = fnv(h, c->bore_radius, n);
    double s[] = {c->mean_pressure,
                  c->contact_fraction,
                  c->max_clearance,
                  c->max_clearance_angle_deg,
                  c->max_penetration,
                  c->gap_floor,
                  c->marginal_gap_deg,
                  c->tip_force[0],
                  c->tip_force[1],
                  c->estimates.pressure,
                  c->estimates.contact_fraction,
                  c->estimates.max_clearance,
                  c->estimates.gap_edges_deg,
                  c->stats.strain_energy,
                  c->stats.support_force};
    h = fnv(h, s, sizeof s);
    h = fnv(h, c->bin_pressure, sizeof c->bin_pressure);
    h = fnv(h, &c->n_gaps, sizeof c->n_gaps);
    for (int g = 0; g < c->n_gaps; g++)
        h = fnv(h, &c->gaps[g], sizeof c->gaps[g]);
    return h;
}

/* bench_static's battery bore (contact_reference.c), with the options
 * given on the command line. */
static rd_contact_opts bore(const rd_ring_params *p, int k, double fac, double phase)
{
    rd_contact_opts o = ref_battery_bore(p, k, fac, phase);
    o.flexible_face = flexible_face;
    if (cap)
        o.max_segments = cap;
    return o;
}

/* reps solves (CPU time the median); the last result in c.  0 or the error. */
static int solve(const rd_ring_params *p, const rd_contact_opts *o, int n, int reps,
                 rd_contact_result *c, double *cpu)
{
    double t[3];
    int rc = 0;
    for (int r = 0; r < reps && rc == 0; r++) {
        rd_static_opts so;
        rd_static_opts_default(&so);
        so.estimate_error = n == 0;
        rd_error err;
        rd_error_init(&err);
        if (r > 0)
            rd_contact_result_cleanup(c);
        clock_t c0 = clock();
        rc = rd_contact_solve(p, n > 0 ? n : 20, o, &so, NULL, c, &err);
        t[r] = (double)(clock() - c0) / CLOCKS_PER_SEC;
        if (rc)
            fprintf(stderr, "contact: %s\n", err.message);
    }
    *cpu = bench_median(t, reps);
    return rc;
}

static void line(int k, double fac, double phase, const rd_contact_result *c, double cpu)
{
    printf("| %d | %g | %g | %d | %d | %d | %d | %.2e | %.3f | %016llx |\n", k, fac, phase,
           c->stats.segments, c->stats.iterations, c->stats.factorizations, c->stats.load_steps,
           c->stats.residual, cpu, (unsigned long long)fingerprint(c));
}

static const char *header = "| k | A / bound | phase | n | Newton iterations | factorizations | "
                            "load steps | residual | cpu (s) | fingerprint |\n"
                            "|---|---|---|---|---|---|---|---|---|---|\n";

int main(int argc, char **argv)
{
    int a = 1;
    for (; a < argc && strncmp(argv[a], "--", 2) == 0 && strcmp(argv[a], "--battery"); a++) {
        if (strcmp(argv[a], "--face") == 0)
            flexible_face = 1;
        else if (strcmp(argv[a], "--rigid") == 0)
            flexible_face = 0;
        else if (strcmp(argv[a], "--cap") == 0 && a + 1 < argc)
            cap = atoi(argv[++a]);
        else
            break;
    }
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_result c;
    memset(&c, 0, sizeof c);
    double cpu;
    if (a == argc - 1 && strcmp(argv[a], "--battery") == 0) {
        const int orders[] = {2, 3, 4, 6};
        const double facs[] = {0.1, 1, 3, 10}, phases[] = {0, 17};
        int its = 0, facts = 0, fast = 0;
        double total = 0.0;
        printf("%s", header);
        for (int ki = 0; ki < 4; ki++)
            for (int fi = 0; fi < 4; fi++)
                for (int pi = 0; pi < 2; pi++) {
                    rd_contact_opts o = bore(&p, orders[ki], facs[fi], phases[pi]);
                    if (solve(&p, &o, 0, 3, &c, &cpu))
                        return 1;
                    line(orders[ki], facs[fi], phases[pi], &c, cpu);
                    its += c.stats.iterations, facts += c.stats.factorizations;
                    total += cpu, fast += cpu <= 0.2;
                    rd_contact_result_cleanup(&c);
                }
        printf("\nNewton iterations (finest level) %d in all, %d factorizations; cpu %.3f s in "
               "all, <= 0.2 s: %d of 32\n",
               its, facts, total, fast);
        return 0;
    }
    if (argc - a < 3 || argc - a > 4) {
        fprintf(stderr, "usage: bench_contact_cost [--rigid] [--cap N] (K A PHASE [N] | "
                        "--battery)\n");
        return 2;
    }
    rd_contact_opts o = bore(&p, atoi(argv[a]), atof(argv[a + 1]), atof(argv[a + 2]));
    if (solve(&p, &o, argc - a == 4 ? atoi(argv[a + 3]) : 0, 1, &c, &cpu))
        return 1;
    printf("%s", header);
    line(atoi(argv[a]), atof(argv[a + 1]), atof(argv[a + 2]), &c, cpu);
    rd_contact_result_cleanup(&c);
    return 0;
}
