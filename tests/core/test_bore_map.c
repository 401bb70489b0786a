/*
 * test_bore_map — bore maps (core/include/rd_bore_map.h):
 *   - points generated from known layered orders (and a mean radius per
 *     layer) are fitted back exactly: the orders, phases and diameters, and
 *     the radius at 720 angles, to rounding; the residual ~0;
 *   - with more content than the fit order, on equally spaced angles the
 *     least-squares fit equals the discrete Fourier coefficients (an
 *     independent formula), and its residual is the rms of what is left;
 *   - between two layers the bore is (1 - t) r_i + t r_{i+1} at every angle;
 *     at a layer, or between equal layers, it is that layer bit for bit;
 *   - the contact down a map whose layers are all one bore gives that
 *     bore's contact answer bit for bit, in every layer;
 *   - bad input: z not increasing, too few points for the order, a height
 *     outside the layers, too many orders between two layers: refused at
 *     the field, naming the value and the allowed range.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_bore_map.h"
#include "rd_static.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define D 0.0765 /* the thesis ring's diameter */
/* rounding of a radius: 4 ulps of D/2 */
#define ROUND (4.0 * DBL_EPSILON * 0.5 * D)

static double radius(const rd_bore *b, double theta_deg)
{
    double r = 0.5 * (b->diameter > 0 ? b->diameter : D);
    for (int k = 0; k < b->n_distortion; k++) {
        const rd_distortion *q = &b->distortion[k];
        r += q->amplitude * cos(q->order * (theta_deg - q->phase_deg) * M_PI / 180.0);
    }
    return r;
}

/* Three layers of known orders and mean radii (the generator). */
static void known_map(rd_bore_map *m)
{
    memset(m, 0, sizeof *m);
    m->n_layers = 3;
    double z[3] = {0.0, 0.02, 0.05}, grow[3] = {0.0, 4e-6, 10e-6};
    for (int l = 0; l < 3; l++) {
        rd_bore *b = &m->layer[l].bore;
        m->layer[l].z = z[l];
        b->diameter = D + 2.0 * grow[l];
        b->n_distortion = 3;
        b->distortion[0] = (rd_distortion){2, 5e-6 * (1 + l), 17.0 + 3 * l};
        b->distortion[1] = (rd_distortion){3, 2e-6, -25.0 + 10 * l};
        b->distortion[2] = (rd_distortion){4, 1e-6 * (3 - l), 8.0};
    }
}

static void test_fit_exact(void)
{
    rd_bore_map gen, fit;
    known_map(&gen);
    enum { PER = 23, N = 3 * PER };
    double th[N], z[N], dr[N];
    for (int l = 0, j = 0; l < 3; l++)
        for (int i = 0; i < PER; i++, j++) { /* uneven angles, some past 360 */
            th[j] = -40.0 + i * 17.3 + l * 1.1;
            z[j] = gen.layer[l].z;
            dr[j] = radius(&gen.layer[l].bore, th[j]) - 0.5 * D;
        }
    rd_bore_points p = {N, th, z, dr, 5};
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_bore_points_validate(&p, D, &err) == RD_OK, "points: %s", err.message);
    CHECK(rd_bore_map_fit(&p, D, &fit, &err) == RD_OK, "fit: %s", err.message);
    CHECK(fit.n_layers == 3, "%d layers", fit.n_layers);
    CHECK(fit.residual_rms < 1e-17, "residual %.3g m", fit.residual_rms);
    double worst = 0.0, worst_amp = 0.0;
    for (int l = 0; l < 3; l++) {
        CHECK_REL(fit.layer[l].bore.diameter, gen.layer[l].bore.diameter, 1e-14, "layer %d", l);
        for (int i = 0; i < 720; i++)
            worst = fmax(worst, fabs(radius(&fit.layer[l].bore, 0.5 * i) -
                                     radius(&gen.layer[l].bore, 0.5 * i)));
        for (int k = 0; k < fit.layer[l].bore.n_distortion; k++) {
            const rd_distortion *q = &fit.layer[l].bore.distortion[k];
            const rd_distortion *w = NULL;
            for (int j = 0; j < gen.layer[l].bore.n_distortion; j++)
                if (gen.layer[l].bore.distortion[j].order == q->order)
                    w = &gen.layer[l].bore.distortion[j];
            if (!w) { /* orders 1 and 5: absent */
                worst_amp = fmax(worst_amp, fabs(q->amplitude));
                continue;
            }
            CHECK_REL(q->amplitude, w->amplitude, 1e-12, "layer %d order %d", l, q->order);
            CHECK_ABS(q->phase_deg, w->phase_deg, 1e-8, "layer %d order %d", l, q->order);
        }
    }
    CHECK(worst < ROUND, "radius off by %.3g m", worst);
    CHECK(worst_amp < ROUND, "absent orders fitted to %.3g m", worst_amp);
}

/* Equally spaced angles: least squares = discrete Fourier coefficients. */
static void test_fit_fourier(void)
{
    enum { N = 36 };
    double th[N], z[N], dr[N], a2 = 0, b2 = 0, c0 = 0;
    for (int j = 0; j < N; j++) {
        th[j] = 10.0 * j;
        z[j] = 0.01;
        double t = th[j] * M_PI / 180.0;
        dr[j] = 1e-6 + 3e-6 * cos(2 * t - 0.4) + 1e-6 * sin(5 * t) + 2e-7 * cos(9 * t);
    }
    for (int j = 0; j < N; j++) {
        double t = th[j] * M_PI / 180.0;
        c0 += dr[j] / N;
        a2 += 2.0 / N * dr[j] * cos(2 * t);
        b2 += 2.0 / N * dr[j] * sin(2 * t);
    }
    rd_bore_points p = {N, th, z, dr, 3};
    rd_bore_map m;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_bore_map_fit(&p, D, &m, &err) == RD_OK, "fit: %s", err.message);
    const rd_distortion *q = &m.layer[0].bore.distortion[1];
    CHECK(q->order == 2, "order %d", q->order);
    CHECK_REL(q->amplitude, hypot(a2, b2), 1e-12, "order 2 amplitude");
    CHECK_ABS(q->phase_deg, atan2(b2, a2) / 2 * 180 / M_PI, 1e-9, "order 2 phase");
    CHECK_REL(m.layer[0].bore.diameter, D + 2 * c0, 1e-14, "mean radius");
    /* what orders 5 and 9 leave: rms of 1e-6 sin 5t + 2e-7 cos 9t */
    CHECK_REL(m.residual_rms, sqrt((1e-12 + 4e-14) / 2), 1e-9, "residual");
}

static void test_interpolation(void)
{
    rd_bore_map m;
    known_map(&m);
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_bore_map_validate(&m, D, &err) == RD_OK, "map: %s", err.message);
    rd_bore b;
    double z = 0.029, t = (z - 0.02) / 0.03, worst = 0;
    CHECK(rd_bore_map_at(&m, z, D, &b, &err) == RD_OK, "at: %s", err.message);
    for (int i = 0; i < 720; i++) {
        double want =
            (1 - t) * radius(&m.layer[1].bore, 0.5 * i) + t * radius(&m.layer[2].bore, 0.5 * i);
        worst = fmax(worst, fabs(radius(&b, 0.5 * i) - want));
    }
    CHECK(worst < ROUND, "interpolated radius off by %.3g m", worst);
    CHECK(rd_bore_map_at(&m, 0.02, D, &b, &err) == RD_OK &&
              memcmp(&b, &m.layer[1].bore, sizeof b) == 0,
          "at a layer: that layer bit for bit");
    /* a layer with other orders: the union, linear at every angle */
    m.layer[2].bore.distortion[2].order = 7;
    CHECK(rd_bore_map_at(&m, z, D, &b, &err) == RD_OK && b.n_distortion == 4, "%d orders",
          b.n_distortion);
    worst = 0;
    for (int i = 0; i < 720; i++) {
        double want =
            (1 - t) * radius(&m.layer[1].bore, 0.5 * i) + t * radius(&m.layer[2].bore, 0.5 * i);
        worst = fmax(worst, fabs(radius(&b, 0.5 * i) - want));
    }
    CHECK(worst < ROUND, "union of orders off by %.3g m", worst);
}

static rd_ring_params thesis_ring(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    return p;
}

/* The same orders at every layer: every layer's contact is the plain one. */
static void test_contact_same_layers(void)
{
    rd_ring_params p = thesis_ring();
    rd_contact_opts o;
    rd_static_opts so;
    rd_contact_opts_default(&o);
    rd_static_opts_default(&so);
    so.estimate_error = 0;
    o.bore.n_distortion = 1;
    o.bore.distortion[0] = (rd_distortion){3, 4e-6, 20.0};
    rd_bore_map m;
    memset(&m, 0, sizeof m);
    m.n_layers = 2;
    m.layer[0] = (rd_bore_layer){0.0, o.bore};
    m.layer[1] = (rd_bore_layer){0.04, o.bore};
    rd_error err;
    rd_error_init(&err);
    rd_contact_result plain, at, layers[2];
    memset(&plain, 0, sizeof plain);
    memset(&at, 0, sizeof at);
    memset(layers, 0, sizeof layers);
    int ok = rd_contact_solve(&p, 40, &o, &so, NULL, &plain, &err) == RD_OK;
    rd_contact_opts oz = o;
    ok = ok && rd_bore_map_at(&m, 0.013, p.diameter, &oz.bore, &err) == RD_OK;
    ok = ok && rd_contact_solve(&p, 40, &oz, &so, NULL, &at, &err) == RD_OK;
    ok = ok && rd_contact_solve_layers(&p, 40, &o, &m, &so, NULL, layers, &err) == RD_OK;
    CHECK(ok, "solves: %s", err.message);
    if (ok) {
        size_t bytes = (size_t)plain.points * sizeof(double);
        CHECK(at.points == plain.points && memcmp(at.pressure, plain.pressure, bytes) == 0 &&
                  memcmp(at.clearance, plain.clearance, bytes) == 0,
              "height 13 mm: the plain bore's answer bit for bit");
        for (int l = 0; l < 2; l++)
            CHECK(layers[l].points == plain.points &&
                      memcmp(layers[l].pressure, plain.pressure, bytes) == 0 &&
                      layers[l].max_clearance == plain.max_clearance &&
                      layers[l].contact_fraction == plain.contact_fraction,
                  "layer %d: the plain bore's answer bit for bit", l);
    }
    rd_contact_result_cleanup(&plain);
    rd_contact_result_cleanup(&at);
    rd_contact_result_cleanup(&layers[0]);
    rd_contact_result_cleanup(&layers[1]);
}

static void expect_error(int rc, const rd_error *err, const char *path, const char *words)
{
    CHECK(rc == RD_EINVAL || rc == RD_ELIMIT, "refused (%d)", rc);
    CHECK(strcmp(err->path, path) == 0, "path %s, want %s", err->path, path);
    CHECK(strstr(err->message, words) != NULL, "message \"%s\" says \"%s\"", err->message, words);
}

static void test_errors(void)
{
    rd_bore_map m;
    rd_error err;
    known_map(&m);
    m.layer[2].z = 0.02; /* equal to the one before */
    rd_error_init(&err);
    rd_error_enter(&err, "/bore"); /* core writes paths relative to the block */
    expect_error(rd_bore_map_validate(&m, D, &err), &err, "/bore/layers/2/z",
                 "= 0.02 m is not below the layer before it");
    known_map(&m);
    m.layer[1].bore.distortion[0].amplitude = 1e-3; /* 1.3 % of d */
    rd_error_init(&err);
    rd_error_enter(&err, "/bore"); /* core writes paths relative to the block */
    expect_error(rd_bore_map_validate(&m, D, &err), &err, "/bore/layers/1/distortion/0/amplitude",
                 "allowed -0.000765 to 0.000765 m");
    known_map(&m);
    for (int k = 0; k < 10; k++) { /* 3 + 10 orders, then 10 others below */
        m.layer[1].bore.distortion[3 + k] = (rd_distortion){10 + k, 1e-9, 0};
        m.layer[2].bore.distortion[3 + k] = (rd_distortion){30 + k, 1e-9, 0};
    }
    m.layer[1].bore.n_distortion = m.layer[2].bore.n_distortion = 13;
    rd_error_init(&err);
    rd_error_enter(&err, "/bore"); /* core writes paths relative to the block */
    expect_error(rd_bore_map_validate(&m, D, &err), &err, "/bore/layers/2/distortion",
                 "23 distinct orders together; allowed at most 16");
    known_map(&m);
    rd_bore b;
    rd_error_init(&err);
    rd_error_enter(&err, "/contact"); /* core writes paths relative to the block */
    expect_error(rd_bore_map_at(&m, 0.06, D, &b, &err), &err, "/contact/height",
                 "= 0.06 m is outside the bore map: allowed 0 to 0.05 m");
    /* 8 angles in the second layer, order 4 needs 9 */
    double th[17], z[17], dr[17];
    for (int j = 0; j < 17; j++) /* 9 angles at z = 0 (one past 360), 8 at 10 mm */
        th[j] = j < 9 ? 40.0 * j + (j == 3 ? 360.0 : 0.0) : 45.0 * (j - 9),
        z[j] = j < 9 ? 0.0 : 0.01, dr[j] = 0.0;
    rd_bore_points p = {17, th, z, dr, 4};
    rd_error_init(&err);
    rd_error_enter(&err, "/bore"); /* core writes paths relative to the block */
    expect_error(rd_bore_points_validate(&p, D, &err), &err, "/bore/points/fit_order",
                 "fit_order = 4 needs at least 9 points at distinct angles in every layer, but "
                 "the layer at z = 0.01 m has 8: allowed fit_order 0 to 3");
    dr[5] = 1e-3;
    rd_error_init(&err);
    rd_error_enter(&err, "/bore"); /* core writes paths relative to the block */
    expect_error(rd_bore_points_validate(&p, D, &err), &err, "/bore/points/dr/5", "out of range");
}

int main(void)
{
    test_fit_exact();
    test_fit_fourier();
    test_interpolation();
    test_errors();
    test_contact_same_layers();
    return check_done();
}
