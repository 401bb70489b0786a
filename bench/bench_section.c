/* bench_section — what a general cross-section costs a pretension solve
 * once its properties are computed (issue 46: "a general section adds no
 * more than 10 % to an analysis after its properties are computed once").
 * The thesis ring as the rectangle, as the same rectangle given as a
 * polygon (a general shape: its outline, moments, shear factors and J from
 * rd_section_spec_solve, once), and with an inner bevel 0.3 b x 0.3 h
 * (principal axes turned 2.8 deg: the in-plane and out-of-plane halves of
 * the beam couple, so the solver's planar split does not apply).  The
 * least of 31 solves each (the shared machine's load only adds), with the
 * Newton iterations, n = 20, 80, 320, no error estimate; the one-off
 * property cost beside.
 *
 * usage: bench_section */
#include <stdio.h>
#include <string.h>

#include "bench_util.h"
#include "rd_section.h"
#include "rd_static.h"

#define REPS 31

static double solve_ms(const rd_ring_params *p, int n, int *iterations)
{
    rd_pretension_opts o;
    rd_static_opts so;
    rd_pretension_opts_default(&o);
    rd_static_opts_default(&so);
    so.estimate_error = 0;
    double t[REPS];
    for (int r = 0; r < REPS; r++) {
        rd_pretension_result res;
        rd_error e;
        rd_error_init(&e);
        double t0 = bench_now();
        if (rd_pretension_solve(p, n, &o, &so, NULL, &res, &e) != RD_OK)
            fprintf(stderr, "pretension: %s\n", e.message);
        t[r] = bench_now() - t0;
        *iterations = res.stats.iterations;
        rd_pretension_result_cleanup(&res);
    }
    bench_median(t, REPS); /* sorts */
    return 1e3 * t[0];
}

/* p's general shape's properties, once; their cost in ms. */
static double properties_ms(rd_ring_params *p)
{
    rd_error e;
    rd_error_init(&e);
    double t0 = bench_now();
    if (rd_section_spec_solve(p->section, &p->spec, p->radial_width, p->axial_height, &e) != RD_OK)
        fprintf(stderr, "section: %s\n", e.message);
    return 1e3 * (bench_now() - t0);
}

int main(void)
{
    rd_ring_params rect, poly, bevel;
    rd_ring_params_default(&rect);
    poly = bevel = rect;
    double b = rect.radial_width, h = rect.axial_height;
    double pts[4][2] = {{0, 0}, {b, 0}, {b, h}, {0, h}};
    memset(&poly.spec, 0, sizeof poly.spec);
    poly.section = RD_SECTION_POLYGON;
    poly.spec.n_points = 4;
    memcpy(poly.spec.points, pts, sizeof pts);
    memset(&bevel.spec, 0, sizeof bevel.spec);
    bevel.section = RD_SECTION_INNER_BEVEL;
    bevel.spec.width = 0.3 * b;
    bevel.spec.height = 0.3 * h;
    double tp = properties_ms(&poly), tb = properties_ms(&bevel);
    printf("properties once: polygon rectangle %.0f ms, inner bevel %.0f ms (J by finite "
           "elements, shear factors)\n",
           tp, tb);
    printf("| n | rectangle [ms] | polygon rectangle | inner bevel (turned axes) "
           "|\n|---|---|---|---|\n");
    for (int n = 20; n <= 320; n *= 4) {
        int ir, iq, iv;
        double r = solve_ms(&rect, n, &ir), q = solve_ms(&poly, n, &iq),
               v = solve_ms(&bevel, n, &iv);
        printf("| %d | %.3f (%d it) | %.3f (%.2fx, %d it) | %.3f (%.2fx, %d it) |\n", n, r, ir, q,
               q / r, iq, v, v / r, iv);
    }
    return 0;
}
