/*
 * bench_bore_map — what a contact table down a bore map costs
 * (contact.height "all", rd_contact_solve_layers) against one contact.
 *
 *   bench_bore_map [LAYERS [N]]
 *       the thesis ring in a bore of LAYERS layers (default 10) over 0 to
 *       90 mm whose distortion grows toward the bottom (order 2 from 0 to
 *       1.5 x its thin-ring bound, order 4 from 0 to 1 x, order 3 at 0.5 x
 *       throughout, phases fixed), refined as by default (error estimate
 *       on), or at N segments without refinement; prints per layer the CPU
 *       s of its own contact solve, then the table's CPU s, its ratio to
 *       the sum of the single solves (the overhead) and to the mean, the
 *       median and the largest single solve.  CPU times are medians of 3.
 *   bench_bore_map LAYERS N single|table
 *       only the single solves, or only the table, once each (N = 0:
 *       refined): for instruction counts, which a loaded machine does not
 *       move (valgrind --tool=callgrind --toggle-collect=rd_contact_solve
 *       ... single, and --toggle-collect=rd_contact_solve_layers ... table).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rd_bore_map.h"
#include "rd_static.h"

static double cpu_now(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median3(double a, double b, double c)
{
    double v[3] = {a, b, c};
    qsort(v, 3, sizeof *v, cmp);
    return v[1];
}

static void make_map(const rd_ring_params *p, int layers, rd_bore_map *m)
{
    rd_ring_section s;
    rd_ring_section_get(p, 0, &s);
    double R = s.R, EI = p->youngs_modulus * s.I_inplane;
    memset(m, 0, sizeof *m);
    m->n_layers = layers;
    for (int l = 0; l < layers; l++) {
        double t = layers > 1 ? (double)l / (layers - 1) : 1.0;
        rd_bore *b = &m->layer[l].bore;
        m->layer[l].z = 0.09 * t;
        b->n_distortion = 3;
        for (int q = 0; q < 3; q++) {
            int k = q + 2;
            double bound = p->tangential_force * pow(R, 3) / (EI * pow(k * k - 1.0, 2));
            double f = k == 2 ? 1.5 * t : k == 3 ? 0.5 : t;
            b->distortion[q] = (rd_distortion){k, f * bound, 15.0 * q};
        }
    }
    m->residual_rms = NAN;
}

int main(int argc, char **argv)
{
    int layers = argc > 1 ? atoi(argv[1]) : 10, n = argc > 2 ? atoi(argv[2]) : 0;
    const char *only = argc > 3 ? argv[3] : NULL;
    int reps = only ? 1 : 3;
    if (layers < 1 || layers > RD_BORE_LAYERS_MAX) {
        fprintf(stderr, "usage: bench_bore_map [LAYERS (1..%d) [N]]\n", RD_BORE_LAYERS_MAX);
        return 2;
    }
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o;
    rd_static_opts so;
    rd_contact_opts_default(&o);
    rd_static_opts_default(&so);
    so.estimate_error = n == 0;
    int segments = n > 0 ? n : 20;
    rd_bore_map m;
    make_map(&p, layers, &m);
    rd_error err;
    rd_error_init(&err);
    if (rd_bore_map_validate(&m, p.diameter, &err) != RD_OK) {
        fprintf(stderr, "map: %s\n", err.message);
        return 1;
    }
    double single[RD_BORE_LAYERS_MAX], sum = 0, worst = 0;
    printf("layer z_m segments contact_fraction max_clearance_m cpu_s\n");
    for (int l = 0; l < layers && !(only && strcmp(only, "table") == 0); l++) {
        double t[3] = {0, 0, 0};
        rd_contact_result r;
        for (int rep = 0; rep < reps; rep++) {
            rd_contact_opts ol = o;
            ol.bore = m.layer[l].bore;
            memset(&r, 0, sizeof r);
            double t0 = cpu_now();
            if (rd_contact_solve(&p, segments, &ol, &so, NULL, &r, &err) != RD_OK) {
                fprintf(stderr, "layer %d: %s\n", l, err.message);
                return 1;
            }
            t[rep] = cpu_now() - t0;
            if (rep < reps - 1)
                rd_contact_result_cleanup(&r);
        }
        single[l] = reps == 1 ? t[0] : median3(t[0], t[1], t[2]);
        sum += single[l];
        worst = fmax(worst, single[l]);
        printf("%d %.4f %d %.6f %.4g %.3f\n", l, m.layer[l].z, r.stats.segments, r.contact_fraction,
               r.max_clearance, single[l]);
        rd_contact_result_cleanup(&r);
    }
    if (only && strcmp(only, "single") == 0)
        return 0;
    double t[3] = {0, 0, 0};
    for (int rep = 0; rep < reps; rep++) {
        rd_contact_result *res = calloc((size_t)layers, sizeof *res);
        double t0 = cpu_now();
        int rc = rd_contact_solve_layers(&p, segments, &o, &m, &so, NULL, res, &err);
        t[rep] = cpu_now() - t0;
        for (int l = 0; l < layers; l++)
            rd_contact_result_cleanup(&res[l]);
        free(res);
        if (rc != RD_OK) {
            fprintf(stderr, "table: %s\n", err.message);
            return 1;
        }
    }
    double all = median3(t[0], t[1], t[2]);
    if (only) {
        printf("table of %d layers: %.3f s CPU\n", layers, t[0]);
        return 0;
    }
    qsort(single, (size_t)layers, sizeof *single, cmp);
    double med = single[layers / 2];
    printf("table of %d layers: %.3f s CPU; / sum of single solves %.3f; / mean single %.2f, "
           "/ median single %.2f, / largest single %.2f (the target: <= %d)\n",
           layers, all, all / sum, all / (sum / layers), all / med, all / worst, layers);
    return 0;
}
