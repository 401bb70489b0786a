/*
 * test_lift_films_tilt — the lubricated lift on a tilting piston: the
 * groove turns with the tilt beta(t) about the pin axis, so a segment at
 * arm x = R cos(theta) (theta from the gap middle, the pin axis at 90 deg)
 * slides past the liner at the piston's speed plus beta' x, and its film
 * is solved at that speed (core/lift/rd_lift_film.c lever, rd_lift_films.c).
 *
 * References:
 *  - a constant tilt does not slide the groove: one film, the untilted
 *    round bore's bit for bit;
 *  - every film's sliding speed at every step against the piston's speed
 *    plus beta' x from the slider-crank and the tilt's spline derivative
 *    (rd_engine_tilt_at) written out here;
 *  - mid-stroke, where the film is hydrodynamic, h0 ~ U^alpha between the
 *    fastest and the slowest segment: alpha near 1 on a 100 um crown (a
 *    rigid cylinder at steady sliding: W = C eta U R / h0, Martin), near
 *    1/2 on the default nearly flat barrel (a flat slider: W ~ eta U B^2 /
 *    h0^2);
 *  - a vanishing tilt rate gives the round bore's friction work;
 *  - the whole lift (full ring) runs on those films, one per distinct arm.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lift_distort.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

static const double tilt_crank[4] = {0.0, 180.0, 360.0, 540.0};
static double tilt_deg[4];

static void scene(rd_ring_params *rp, rd_lift_params *p, double amplitude_deg, int moving)
{
    lubricated_scene(rp, p, 0.0);
    if (!moving) {
        p->engine.piston_tilt_deg = amplitude_deg;
        return;
    }
    for (int k = 0; k < 4; k++)
        tilt_deg[k] = k % 2 ? -amplitude_deg : amplitude_deg;
    p->engine.tilt_points = 4;
    p->engine.tilt_crank_deg = tilt_crank;
    p->engine.tilt_deg = tilt_deg;
}

static int same(const double *a, const double *b, int n)
{
    return !memcmp(a, b, (size_t)n * sizeof *a);
}

/* A constant tilt: the round bore's one film. */
static void constant(void)
{
    rd_ring_params rp;
    rd_lift_params p, q;
    scene(&rp, &p, 0.0, 0);
    scene(&rp, &q, 0.5, 0);
    rd_lift_result a, b;
    rd_error err = {0};
    int rc = rd_lift_solve(&rp, 12, &p, NULL, &a, &err);
    rc = rc ? rc : rd_lift_solve(&rp, 12, &q, NULL, &b, &err);
    CHECK(rc == RD_OK, "constant tilt: %s", err.message);
    if (rc != RD_OK)
        return;
    CHECK(b.lube.films == 1 && same(a.lube.min_film, b.lube.min_film, a.samples) &&
              same(a.lube.friction_work, b.lube.friction_work, 1),
          "a constant tilt: %d films, not the round bore's", b.lube.films);
    printf("constant tilt 0.5 deg: one film, the untilted one's bit for bit\n");
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

/* The films of a moving tilt: their speeds, and h0 against U (a crown of
 * `crown` m: 100 um a cylinder's, alpha near 1; the default 5 um a nearly
 * flat slider's, whose load W ~ eta U B^2 / h0^2 gives alpha near 1/2). */
static void speeds(double crown, double alo, double ahi, int n)
{
    rd_ring_params rp;
    rd_lift_params p;
    scene(&rp, &p, 1.5, 1);
    if (crown > 0.0)
        p.face.crown = crown;
    rd_error err = {0};
    rd_ring *ring = rd_ring_create(&rp, n, 0, &err);
    rd_lift_films fs = {0};
    int rc = ring ? rd_lift_films_bore(ring, &p, NULL, &fs, &err) : RD_ENOMEM;
    CHECK(rc == RD_OK && fs.exact && fs.lever, "films of a moving tilt: %s", err.message);
    if (rc != RD_OK || !fs.lever) {
        rd_lift_films_free(&fs);
        rd_ring_free(ring);
        return;
    }
    double omega = 2.0 * M_PI * p.engine.speed_rpm / 60.0, r = p.engine.crank_radius,
           l = p.engine.rod_length, worst = 0.0, top = 0.0;
    int lo = 0, hi = 0;
    for (int g = 0; g < fs.count; g++) {
        double x = fs.lever[fs.follows[g]];
        lo = x < fs.lever[fs.follows[lo]] ? g : lo;
        hi = x > fs.lever[fs.follows[hi]] ? g : hi;
        for (int k = 0; k <= fs.tr[g].steps; k++) {
            const rd_film_point *pt = &fs.tr[g].pt[k];
            double a = omega * pt->t, s = sin(a), b, b1, b2;
            double v = r * omega * (s + r * s * cos(a) / sqrt(l * l - r * r * s * s));
            rd_engine_tilt_at(&p.engine, a * 180.0 / M_PI, &b, &b1, &b2);
            double want = v + b1 * omega * x;
            worst = fmax(worst, fabs(pt->U - want));
            top = fmax(top, fabs(want));
        }
    }
    printf("moving tilt 1.5 deg, n = %d: %d films over arms %.4f to %.4f m; their speeds within "
           "%.3g of "
           "the slider-crank's plus beta' x (largest %.3g m/s)\n",
           n, fs.count, fs.lever[fs.follows[lo]], fs.lever[fs.follows[hi]], worst / top, top);
    CHECK(fs.count == n / 2, "distinct arms (mirrored about the pin axis): %d films", fs.count);
    CHECK(worst < 1e-9 * top, "the films' speeds: %g off", worst / top);
    /* mid-stroke: h0 ~ U^alpha between the fastest and the slowest film */
    double amin = INFINITY, amax = -INFINITY;
    int used = 0;
    for (double deg = 60.0; deg <= 120.0; deg += 5.0) {
        double t = deg * M_PI / 180.0 / omega + 4.0 * M_PI / omega; /* the run's cycle */
        rd_film_point a, b;
        rd_film_track_at(&fs.tr[lo], t - 4.0 * M_PI / omega, &a);
        rd_film_track_at(&fs.tr[hi], t - 4.0 * M_PI / omega, &b);
        if (fabs(b.U - a.U) < 0.01 * fabs(a.U) || a.Wa > 0.05 * a.W)
            continue;
        double alpha = log(b.h0 / a.h0) / log(b.U / a.U);
        amin = fmin(amin, alpha);
        amax = fmax(amax, alpha);
        used++;
    }
    printf("  crown %.0f um, mid-stroke (60-120 deg, %d samples): h0 ~ U^alpha, alpha %.3f to "
           "%.3f\n",
           p.face.crown * 1e6, used, amin, amax);
    CHECK(used >= 5 && amin > alo && amax < ahi, "h0 against U: alpha %g to %g", amin, amax);
    rd_lift_films_free(&fs);
    rd_ring_free(ring);
}

/* A vanishing tilt rate: the round bore's work; the whole lift runs. */
static void vanishing_and_lift(void)
{
    rd_ring_params rp;
    rd_lift_params p, q;
    scene(&rp, &p, 0.0, 0);
    scene(&rp, &q, 1e-7, 1);
    rd_lift_result a, b;
    rd_error err = {0};
    int rc = rd_lift_solve(&rp, 12, &p, NULL, &a, &err);
    rc = rc ? rc : rd_lift_solve(&rp, 12, &q, NULL, &b, &err);
    CHECK(rc == RD_OK, "vanishing tilt rate: %s", err.message);
    if (rc == RD_OK) {
        double dw =
            fabs(b.lube.friction_work[0] - a.lube.friction_work[0]) / a.lube.friction_work[0];
        printf("tilt 1e-7 deg: %d films, friction work within %.3g of the untilted %.6g J\n",
               b.lube.films, dw, a.lube.friction_work[0]);
        CHECK(b.lube.films == 6 && dw < 1e-6, "vanishing tilt: %d films, work %g", b.lube.films,
              dw);
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
    scene(&rp, &q, 1.5, 1);
    rc = rd_lift_solve(&rp, 12, &q, NULL, &b, &err);
    CHECK(rc == RD_OK && b.lube.films == 6 && b.lube.min_film_angle_deg,
          "the lift on a tilting piston: %s", err.message);
    if (rc == RD_OK) {
        printf("the lift, tilt 1.5 deg: %d films, work %.6g J, thinnest film %.3g m\n",
               b.lube.films, b.lube.friction_work[0], b.lube.min_film[0]);
        rd_lift_result_cleanup(&b);
    }
}

int main(void)
{
    constant();
    speeds(100e-6, 0.8, 1.1, 12);
    speeds(0.0, 0.4, 0.6, 40); /* 20 films: more than the interpolation's 17 */
    vanishing_and_lift();
    return check_done();
}
