/*
 * test_film_starved — the starved inlet of the oil film (rd_film.h:
 * rd_lube_params.supply_film, the oil on the liner ahead of the face).
 *
 *   (1) a supply above what the face takes in gives the flooded film
 *       exactly (the same solve);
 *   (2) a second method written here: the steady film of a smooth
 *       parabolic face, L 2 mm, crown 10 um, h0 1 um, U 10 m/s, eta 10 mPa
 *       s, fed h_s: the flow is U h_s throughout, so the Reynolds outlet
 *       (p = p' = 0) sits where h = 2 h_s, and from there p' = 6 eta U (h -
 *       2 h_s) / h^3 integrated back to p = 0 gives the meniscus x_in and
 *       the load (trapezoid on 4e5 steps, a bisection for x_in).  The
 *       solver's load within 2 % at 41 points and 0.3 % at 401 (measured
 *       below and printed), its dry nodes where the meniscus is;
 *   (3) less oil than half the thinnest gap: the whole face dry (no film
 *       load, no shear);
 *   (4) the load falls as the supply does (monotone, 8 supplies from
 *       0.51 to 0.5975 um, each below the flooded load), and 0.7 um floods
 *       the face; reversed sliding is the mirror image (case 2);
 *   (5) a taper face starved both ways (its thinnest point the inlet
 *       edge, then the outlet edge): finite loads, no read past the faces
 *       (ASan);
 *   (6) in time: a lift's film (2400 rpm, no gas) is thinner mid-stroke
 *       with 1 um of oil on the liner than flooded.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "rd_film.h"
#include "rd_lift_internal.h"

#define L_FACE 2e-3
#define CROWN  10e-6
#define H0     1e-6
#define U_S    10.0
#define ETA    0.01

static rd_lube_params lube_with(double supply)
{
    rd_lube_params l = {.viscosity = ETA,
                        .asperity_density = 5e8,
                        .asperity_radius = 3e-4,
                        .boundary_coefficient = 0.1,
                        .composite_modulus = 1e11,
                        .supply_film = supply};
    return l;
}

static double gap(double x)
{
    double u = (x - 0.5 * L_FACE) / (0.5 * L_FACE);
    return H0 + CROWN * u * u;
}

/* p at x integrated back from the outlet x_out (h = 2 hs), N steps. */
static double p_back(double x, double x_out, double hs, int N)
{
    double s = 0.0, d = (x_out - x) / N;
    for (int k = 0; k <= N; k++) {
        double t = x + k * d, h = gap(t), w = (k == 0 || k == N) ? 0.5 : 1.0;
        s += w * 6.0 * ETA * U_S * (2.0 * hs - h) / (h * h * h);
    }
    return s * d;
}

/* The second method: the meniscus and the load of the steady starved film. */
static double starved_load(double hs, double *x_in)
{
    double x_out = 0.5 * L_FACE + 0.5 * L_FACE * sqrt((2.0 * hs - H0) / CROWN);
    double lo = 0.0, hi = 0.5 * L_FACE; /* p(lo) < 0 when starved, p(hi) > 0 */
    for (int it = 0; it < 60; it++) {
        double m = 0.5 * (lo + hi);
        if (p_back(m, x_out, hs, 20000) < 0.0)
            lo = m;
        else
            hi = m;
    }
    *x_in = 0.5 * (lo + hi);
    int N = 400000;
    double d = (x_out - *x_in) / N, W = 0.0, p = 0.0;
    for (int k = N - 1; k >= 0; k--) { /* p from the outlet back, trapezoid in p and W */
        double a = *x_in + k * d, b = a + d, ha = gap(a), hb = gap(b);
        double pa = p + 0.5 * d * 6.0 * ETA * U_S *
                            ((2.0 * hs - ha) / (ha * ha * ha) + (2.0 * hs - hb) / (hb * hb * hb));
        W += 0.5 * d * (pa + p);
        p = pa;
    }
    return W;
}

static int film(rd_film *f, int nodes, double supply)
{
    rd_face_params face = {.profile = RD_FACE_BARREL, .crown = CROWN, .roughness_rq = 1e-12};
    rd_lube_params l = lube_with(supply);
    rd_error err = {0};
    int rc = rd_film_init(f, &face, L_FACE, nodes, 1e-12, &l, 2e11, 0.3, &err);
    CHECK(rc == RD_OK, "film: %s", err.message);
    return rc;
}

static void flooded_limit(void)
{
    rd_film a, b;
    if (film(&a, RD_FILM_NODES, 0.0) || film(&b, RD_FILM_NODES, 1.0))
        return;
    for (double h = 0.5e-6; h < 5e-6; h *= 1.7) {
        rd_film_out x, y;
        rd_film_solve(&a, h, 0.0, U_S, ETA, 0.0, 0.0, &x);
        rd_film_solve(&b, h, 0.0, U_S, ETA, 0.0, 0.0, &y);
        CHECK(x.W == y.W && x.Cc == y.Cc && x.Fp == y.Fp && b.dry == 0,
              "a 1 m supply is flooded at h0 %g: W %g vs %g", h, y.W, x.W);
    }
    rd_film_free(&a);
    rd_film_free(&b);
}

static void second_method(void)
{
    double hs[3] = {0.52e-6, 0.56e-6, 0.6e-6}; /* flooded above ~0.625 um, dry below 0.5 */
    int nodes[2] = {RD_FILM_NODES, 401};
    double tol[2] = {0.03, 0.003};
    for (int s = 0; s < 3; s++) {
        double x_in, W = starved_load(hs[s], &x_in);
        for (int k = 0; k < 2; k++) {
            rd_film f;
            if (film(&f, nodes[k], hs[s]))
                continue;
            rd_film_out o;
            rd_film_solve(&f, H0, 0.0, U_S, ETA, 0.0, 0.0, &o);
            double x_dry = (f.dry - 1) * f.dx; /* the last dry node */
            printf("h_s %.2f um, %d points: load %.6g N/m (second method %.6g, %+.2e), meniscus "
                   "%.4f mm (last dry node %.4f mm)\n",
                   hs[s] * 1e6, nodes[k], o.W, W, o.W / W - 1.0, x_in * 1e3, x_dry * 1e3);
            CHECK_REL(o.W, W, tol[k], "starved load, h_s %g, %d points", hs[s], nodes[k]);
            CHECK(x_dry <= x_in + 1e-12 && x_in < x_dry + f.dx + 1e-12,
                  "the meniscus %g m lies past the last dry node %g m, within a spacing", x_in,
                  x_dry);
            rd_film_out r;
            rd_film_solve(&f, H0, 0.0, -U_S, ETA, 0.0, 0.0, &r);
            CHECK_REL(r.W, o.W, 1e-9, "reversed sliding, the mirror image");
            rd_film_free(&f);
        }
    }
}

static void dry_and_monotone(void)
{
    rd_film f;
    if (film(&f, RD_FILM_NODES, 0.45e-6))
        return;
    rd_film_out o;
    rd_film_solve(&f, H0, 0.0, U_S, ETA, 0.0, 0.0, &o);
    CHECK(o.W == 0.0 && o.Cc == 0.0 && o.Fp == 0.0 && f.dry == f.n,
          "0.45 um of oil under a 1 um gap: the face dry (W %g, Cc %g, dry %d of %d)", o.W, o.Cc,
          f.dry, f.n);
    rd_film_free(&f);
    double last = 0.0, flooded = 0.0;
    if (film(&f, RD_FILM_NODES, 0.0))
        return;
    rd_film_solve(&f, H0, 0.0, U_S, ETA, 0.0, 0.0, &o);
    flooded = o.W;
    rd_film_free(&f);
    for (int s = 0; s < 8; s++) {
        double hs = 0.51e-6 + s * 0.0125e-6;
        if (film(&f, RD_FILM_NODES, hs))
            return;
        rd_film_solve(&f, H0, 0.0, U_S, ETA, 0.0, 0.0, &o);
        CHECK(o.W > last && o.W < flooded,
              "more oil, more load: %g at h_s %g after %g (flooded %g)", o.W, hs, last, flooded);
        last = o.W;
        rd_film_free(&f);
    }
    if (!film(&f, RD_FILM_NODES, 0.7e-6)) {
        rd_film_solve(&f, H0, 0.0, U_S, ETA, 0.0, 0.0, &o);
        CHECK(o.W == flooded, "0.7 um of oil floods the face: %g vs %g", o.W, flooded);
        rd_film_free(&f);
    }
}

/* A taper face starved in both sliding directions: one way its thinnest
 * point is the inlet edge, the other way the outlet edge (where the
 * meniscus search once read past the faces: a ring pack under ASan). */
static void taper_both_ways(void)
{
    rd_face_params face = {.profile = RD_FACE_TAPER, .taper_deg = 0.5, .roughness_rq = 2e-7};
    rd_lube_params l = lube_with(0.6e-6);
    rd_film f;
    rd_error err = {0};
    if (rd_film_init(&f, &face, 1.5e-3, RD_FILM_NODES, 2e-7, &l, 2e11, 0.3, &err)) {
        CHECK(0, "taper film: %s", err.message);
        return;
    }
    for (int s = -1; s <= 1; s += 2)
        for (double h = -0.5e-6; h < 3e-6; h += 0.5e-6) {
            rd_film_out o;
            rd_film_solve(&f, h, 0.0, s * U_S, ETA, 1e5, 0.0, &o);
            CHECK(isfinite(o.W) && isfinite(o.Cc) && isfinite(o.Fp) && o.W >= 0.0,
                  "taper, U %+g, h0 %g: W %g, Cc %g, Fp %g", s * U_S, h, o.W, o.Cc, o.Fp);
        }
    rd_film_free(&f);
}

static double film90(double supply)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_ring_params_default(&rp);
    rd_lift_params_default(&p);
    p.engine.speed_rpm = 2400.0;
    p.engine.cycles = 1.0;
    p.friction.model = RD_FRICTION_LUBRICATED;
    p.friction.lube.supply_film = supply;
    rd_film f;
    rd_film_track tr;
    rd_error err = {0};
    double h = NAN;
    if (rd_lift_film_run(&rp, &p, &f, &tr, &err) == RD_OK) {
        rd_film_point pt;
        rd_film_track_at(&tr, 90.0 * M_PI / 180.0 / (2400.0 * M_PI / 30.0), &pt);
        h = pt.h0;
    }
    CHECK(isfinite(h), "film run: %s", err.message);
    rd_film_track_free(&tr);
    rd_film_free(&f);
    return h;
}

int main(void)
{
    flooded_limit();
    second_method();
    dry_and_monotone();
    taper_both_ways();
    double flooded = film90(0.0), starved = film90(1e-6);
    printf("film at 90 deg, 2400 rpm: flooded %.4g m, 1 um of oil on the liner %.4g m\n", flooded,
           starved);
    CHECK(starved < 0.9 * flooded, "a starved face runs thinner: %g vs %g", starved, flooded);
    return check_done();
}
