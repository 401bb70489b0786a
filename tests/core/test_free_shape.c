/* test_free_shape — a ring made with a free shape (rd_static.h's
 * rd_free_shape) against independent references:
 *  - the uniform-pressure free shape's gap against the planar elastica of
 *    the ring's centre line, integrated here in closed form for the angle
 *    and by Simpson's rule for the position (curvature 1/R - M / (E I),
 *    M = q r_o R (1 - cos phi) from the free end), and against the linear
 *    thin-ring formula m = 3 pi F_t R^3 / (E I), which it must exceed by
 *    about 2 % (geometric nonlinearity, the number);
 *  - the force that closes it against F_t (for a uniform pressure, the band
 *    force of (1.3): p0 = 2 F_t / (d h));
 *  - round trips: the ring made with the free shape of a pressure, closed
 *    into a round bore by the contact analysis (Newton on the whole chain
 *    with the contact law, not the statics that made the shape), gives
 *    back the pressure within 1 % of p0 in the 10 deg bins and on every
 *    segment but the two at each free end: uniform, orders 2 and 3 ("positive
 *    ovality" with an odd order), and a table;
 *  - the stress-free closed ring is untouched (a NULL free shape and
 *    RD_FREE_CLOSED give the same numbers bit for bit);
 *  - the installed twist of a section whose principal axes are turned:
 *    against the thin curved beam's closed form at a small load (written
 *    out here, derived in docs/pretension.md), against the same ring closed
 *    by the bore (the contact solve: a second method), its sign (a top
 *    inner bevel twists positive, a bottom one by as much negative), and
 *    the geometric nonlinearity that raises it at larger loads;
 *  - bad input: order 1, a pressure that reaches 0, a table that does not
 *    increase or stops short of the gap. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_section.h"
#include "rd_static.h"

#define PI 3.14159265358979323846

static rd_static_opts opts(void)
{
    rd_static_opts o;
    rd_static_opts_default(&o);
    o.estimate_error = 0;
    return o;
}

static int free_solve(const rd_ring_params *p, int n, const rd_free_shape *fs,
                      rd_pretension_result *r, rd_error *err)
{
    rd_pretension_opts o;
    rd_pretension_opts_default(&o);
    o.free_shape = fs;
    rd_static_opts so = opts();
    rd_error_init(err);
    return rd_pretension_solve(p, n, &o, &so, NULL, r, err);
}

static int contact_solve(const rd_ring_params *p, int n, const rd_free_shape *fs,
                         rd_contact_result *r, rd_error *err)
{
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    o.free_shape = fs;
    rd_static_opts so = opts();
    rd_error_init(err);
    return rd_contact_solve(p, n, &o, &so, NULL, r, err);
}

/* The elastica's free gap between the centre line's ends (the gap faces'
 * centroids), the back held at (-R, 0) with its tangent along -y. */
static double elastica_gap(const rd_ring_params *p)
{
    double b = p->radial_width, h = p->axial_height, R = 0.5 * (p->diameter - b), r_o = R + 0.5 * b,
           EI = p->youngs_modulus * h * b * b * b / 12.0,
           q = 2.0 * p->tangential_force / p->diameter, s = 0.5 * p->closed_gap / R,
           L = R * (PI - s), c = q * r_o * R / EI;
    int N = 20000; /* Simpson, even */
    double x = 0.0, y = 0.0;
    for (int k = 0; k <= N; k++) {
        double sg = L * k / N,
               a = -0.5 * PI + sg / R - c * (sg + R * sin(PI - s - sg / R) - R * sin(PI - s));
        double w = (k == 0 || k == N) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        x += w * cos(a);
        y += w * sin(a);
    }
    (void)x;
    return 2.0 * fabs(y * L / (3.0 * N));
}

static void uniform_gap(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_free_shape fs = {.kind = RD_FREE_PRESSURE};
    rd_pretension_result r;
    rd_error err;
    int n = 160;
    int rc = free_solve(&p, n, &fs, &r, &err);
    CHECK(rc == RD_OK, "uniform free shape: %s", err.message);
    if (rc == RD_OK) {
        double el = elastica_gap(&p), lin = rd_ring_free_gap_formula(&p);
        double b = p.radial_width, R = 0.5 * (p.diameter - b), s = 0.5 * p.closed_gap / R;
        double closed = 2.0 * R * sin(s);
        printf("uniform: neutral gap %.6g m, elastica %.6g m, running-face gap %.6g m; "
               "linear m + g %.6g m; (neutral - closed) / m = %.4f; F close %.6g N (F_t %g)\n",
               r.gap_opening_neutral, el, r.free_gap, lin,
               (r.gap_opening_neutral - closed) / (lin - p.closed_gap), r.tangential_force,
               p.tangential_force);
        CHECK_REL(r.gap_opening_neutral, el, 3e-3, "the elastica's free gap");
        double ratio = (r.gap_opening_neutral - closed) / (lin - p.closed_gap);
        CHECK(ratio > 1.005 && ratio < 1.05,
              "the exact free gap %.4f x the linear one: about 2 %% larger", ratio);
        CHECK_REL(r.tangential_force, p.tangential_force, 0.02, "closing force against F_t");
    }
    rd_pretension_result_cleanup(&r);
}

/* The pressure the contact analysis finds against the wanted one, worst
 * |difference| / p0: in its 10 deg bins (the mean over the ring's arc in
 * each), and on each segment but the two at each free end, whose share of
 * their joint load the flexible faces split differently (their sum is
 * checked as the end bins'). */
static double worst_pressure(const rd_contact_result *c, const rd_free_shape *want,
                             const rd_ring_params *p, double *worst_segment)
{
    double worst = 0.0, R = 0.5 * (p->diameter - p->radial_width), s = 0.5 * p->closed_gap / R;
    *worst_segment = 0.0;
    for (int i = 2; i < c->points - 2; i++) {
        double th = c->angle_deg[i] * PI / 180.0 - PI;
        double d = fabs(c->pressure[i] / c->uniform_pressure - rd_free_shape_pressure(want, th));
        *worst_segment = fmax(*worst_segment, d);
    }
    for (int b = 0; b < RD_CONTACT_BINS; b++) {
        double lo = fmax(b * 10.0 * PI / 180.0, s),
               hi = fmin((b + 1) * 10.0 * PI / 180.0, 2 * PI - s);
        double m = 0.0;
        int N = 400;
        for (int k = 0; k < N; k++)
            m += rd_free_shape_pressure(want, lo + (hi - lo) * (k + 0.5) / N - PI) / N;
        worst = fmax(worst, fabs(c->bin_pressure[b] / c->uniform_pressure - m));
    }
    return worst;
}

/* pressure -> the free shape's rest -> contact in the round bore -> the
 * pressure again; and the free shape from pretension at the same n, whose
 * closing force must match the F_t the pressure's mean stands for */
static void round_trip(const char *what, const rd_free_shape *fs, int n)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_result c;
    rd_error err;
    memset(&c, 0, sizeof c);
    int rc = contact_solve(&p, n, fs, &c, &err);
    CHECK(rc == RD_OK, "%s contact from the pressure: %s", what, err.message);
    if (rc == RD_OK) {
        double ws, w = worst_pressure(&c, fs, &p, &ws);
        printf("%s, n = %d: worst |p - p_want| = %.4g p0 in the bins, %.4g p0 on the segments; "
               "largest light gap %.3g m\n",
               what, n, w, ws, c.max_clearance);
        CHECK(w < 0.01 && ws < 0.01, "%s: given back within 1 %% of p0 (%.4g, %.4g)", what, w, ws);
        CHECK(c.max_clearance < 1e-9, "%s: the ring touches all round (%.3g m)", what,
              c.max_clearance);
    }
    rd_contact_result_cleanup(&c);
}

/* The stress-free closed ring is untouched by the free shape's code. */
static void closed_unchanged(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_free_shape closed = {.kind = RD_FREE_CLOSED};
    rd_pretension_result a, b;
    rd_contact_result ca, cb;
    rd_error err;
    CHECK(free_solve(&p, 40, NULL, &a, &err) == RD_OK, "%s", err.message);
    rd_pretension_opts o;
    rd_pretension_opts_default(&o);
    rd_static_opts so = opts();
    CHECK(rd_pretension_solve(&p, 40, &o, &so, NULL, &b, &err) == RD_OK, "%s", err.message);
    CHECK(a.gap_opening_inner == b.gap_opening_inner && isnan(a.tangential_force),
          "NULL free shape: today's pretension bit for bit, no closing force");
    CHECK(contact_solve(&p, 40, NULL, &ca, &err) == RD_OK, "%s", err.message);
    CHECK(contact_solve(&p, 40, &closed, &cb, &err) == RD_OK, "%s", err.message);
    CHECK(memcmp(ca.pressure, cb.pressure, 40 * sizeof *ca.pressure) == 0,
          "RD_FREE_CLOSED: today's contact bit for bit");
    rd_pretension_result_cleanup(&a);
    rd_pretension_result_cleanup(&b);
    rd_contact_result_cleanup(&ca);
    rd_contact_result_cleanup(&cb);
}

static void refused(const char *what, const rd_free_shape *fs, const rd_ring_params *p,
                    const char *path)
{
    rd_error err;
    rd_error_init(&err);
    rd_error_enter(&err, "/ring"); /* the validator's paths are relative to the ring's block */
    int rc = rd_free_shape_validate(fs, p, &err);
    CHECK(rc == RD_EINVAL && strcmp(err.path, path) == 0, "%s: refused at %s (rc %d, %s: %s)", what,
          path, rc, err.path, err.message);
}

static void bad_input(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_free_shape one = {.kind = RD_FREE_PRESSURE, .n_orders = 1, .order = {1}, .amplitude = {0.1}};
    refused("order 1", &one, &p, "/ring/pressure_distribution/orders");
    rd_free_shape neg = {.kind = RD_FREE_PRESSURE, .n_orders = 1, .order = {2}, .amplitude = {-1}};
    refused("a pressure that reaches 0", &neg, &p, "/ring/pressure_distribution");
    static rd_free_shape t;
    t.kind = RD_FREE_PRESSURE;
    t.n_points = 3;
    double th[3] = {0, 90, 80}, v[3] = {1, 1, 1};
    memcpy(t.theta_deg, th, sizeof th);
    memcpy(t.value, v, sizeof v);
    refused("angles not increasing", &t, &p, "/ring/pressure_distribution/theta_deg");
    t.theta_deg[2] = 170;
    refused("a table short of the gap", &t, &p, "/ring/pressure_distribution/theta_deg");
}

/* ---- the installed twist -------------------------------------------------- */

/* The thesis ring with a slanted section: a parallelogram whose vertical
 * inner and outer faces are offset axially by 0.3 h.  Its centroid is at
 * mid-height (the running face's pressure has no couple about the
 * centroid) and its principal axes are turned by 7.7 deg. */
static rd_ring_params slanted(double Ft)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    double b = p.radial_width, h = p.axial_height, d = 0.3 * h;
    double pts[4][2] = {{0, 0}, {b, d}, {b, h}, {0, h - d}};
    memset(&p.spec, 0, sizeof p.spec);
    p.section = RD_SECTION_POLYGON;
    p.spec.n_points = 4;
    memcpy(p.spec.points, pts, sizeof pts);
    p.tangential_force = Ft;
    rd_error err;
    CHECK(rd_section_spec_solve(p.section, &p.spec, b, h, &err) == RD_OK, "%s", err.message);
    return p;
}

/* The thin curved beam's twist (docs/pretension.md): with free ends and no
 * out-of-plane loads the out-of-plane moment and torque vanish, so
 * kappa_2 = -(I_rz / I_zz) kappa_1, kappa_1 = M / (E I_eff), and Love's
 * kinematics give w'' + w = R^2 (I_rz / I_zz) M / (E I_eff), beta = -w / R up
 * to the tilts; for M = q r_o R (1 + cos theta) (theta from the point
 * opposite the gap, q = 2 F_t / d) and that section held:
 *   twist = (K / R) (1 + theta sin theta / 2 - cos theta),
 *   K = (I_rz / I_zz) q r_o R^3 / (E I_eff),  I_eff = I_rr - I_rz^2 / I_zz,
 * deg, positive the inner edge down: the twist grows toward the gap with
 * theta sin theta, not with the local moment. */
static double closed_twist_deg(const rd_ring_params *p, double theta)
{
    rd_section s;
    rd_section_init(&s, p);
    double q = 2.0 * p->tangential_force / p->diameter, R = s.R,
           Ieff = s.I_rr - s.I_rz * s.I_rz / s.I_zz,
           K = (s.I_rz / s.I_zz) * q * s.run.r * R * R * R / (p->youngs_modulus * Ieff);
    return (K / R) * (1.0 + 0.5 * theta * sin(theta) - cos(theta)) * 180.0 / PI;
}

/* The installed twist's worst difference from the closed form, of its
 * largest value; and that largest value. */
static double twist_vs_closed(const rd_ring_params *p, int n, double *largest)
{
    rd_free_shape uni = {.kind = RD_FREE_PRESSURE};
    rd_pretension_result r;
    rd_error err;
    int rc = free_solve(p, n, &uni, &r, &err);
    CHECK(rc == RD_OK && r.static_twist_deg, "installed twist: %s", err.message);
    double worst = 0.0, big = 0.0, model_big = 0.0;
    for (int k = 1; rc == RD_OK && k <= n; k++) {
        double want = closed_twist_deg(p, r.angle_deg[k] * PI / 180.0 - PI);
        worst = fmax(worst, fabs(r.static_twist_deg[k] - want));
        big = fmax(big, fabs(want));
        model_big = fmax(model_big, fabs(r.static_twist_deg[k]));
    }
    *largest = model_big;
    rd_pretension_result_cleanup(&r);
    return worst / big;
}

static void twist(void)
{
    double big, big1;
    rd_ring_params p = slanted(0.1);
    double e = twist_vs_closed(&p, 80, &big);
    printf("slanted section, F_t = 0.1 N: largest twist %.5f deg, worst |twist - closed form| "
           "%.3g of it\n",
           big, e);
    CHECK(e < 0.02, "the linear twist against the thin curved beam's closed form (%.3g)", e);

    /* a second method: the same ring closed by the bore (contact) */
    rd_free_shape uni = {.kind = RD_FREE_PRESSURE};
    rd_contact_result c;
    rd_pretension_result r;
    rd_error err;
    CHECK(contact_solve(&p, 80, &uni, &c, &err) == RD_OK, "%s", err.message);
    CHECK(free_solve(&p, 80, &uni, &r, &err) == RD_OK, "%s", err.message);
    double worst = 0.0;
    for (int i = 0; i < 80; i++)
        worst = fmax(worst, fabs(c.twist_deg[i] - r.static_twist_deg[i + 1]));
    printf("the same ring closed by the bore: worst twist difference %.3g of %.5f deg\n", worst,
           big);
    CHECK(worst < 0.02 * big, "closed by the bore or by its pressure: the same twist (%.3g deg)",
          worst);
    rd_contact_result_cleanup(&c);
    rd_pretension_result_cleanup(&r);

    /* geometric nonlinearity: the twist turns the principal axes further */
    rd_ring_params p1 = slanted(1.0);
    double e1 = twist_vs_closed(&p1, 80, &big1);
    printf("slanted section, F_t = 1 N: largest twist %.4f deg, %.1f %% above ten times the "
           "0.1 N one (linear)\n",
           big1, 100.0 * (big1 / (10.0 * big) - 1.0));
    CHECK(big1 > 10.0 * big * 1.05 && e1 > 0.05,
          "the nonlinear twist exceeds ten times the linear one (%.4f vs %.4f deg)", big1,
          10.0 * big);

    /* the sign: a relief on the top inner edge twists positive (the inner edge
     * down), on the bottom inner edge negative, by the same amount */
    rd_ring_params top, bottom;
    rd_ring_params_default(&top);
    memset(&top.spec, 0, sizeof top.spec);
    top.section = RD_SECTION_INNER_BEVEL;
    top.spec.width = 0.3 * top.radial_width;
    top.spec.height = 0.3 * top.axial_height;
    bottom = top;
    bottom.spec.side = 1;
    CHECK(rd_section_spec_solve(top.section, &top.spec, top.radial_width, top.axial_height, &err) ==
                  RD_OK &&
              rd_section_spec_solve(bottom.section, &bottom.spec, bottom.radial_width,
                                    bottom.axial_height, &err) == RD_OK,
          "%s", err.message);
    rd_pretension_result rt, rb;
    CHECK(free_solve(&top, 40, &uni, &rt, &err) == RD_OK, "%s", err.message);
    CHECK(free_solve(&bottom, 40, &uni, &rb, &err) == RD_OK, "%s", err.message);
    double at_gap = rt.static_twist_deg[1], mirror = 0.0;
    for (int k = 0; k < rt.points; k++)
        mirror = fmax(mirror, fabs(rt.static_twist_deg[k] + rb.static_twist_deg[k]));
    printf("inner bevel 0.3 b x 0.3 h, F_t = 10 N: twist at the gap %+.4f deg (top), %+.4f deg "
           "(bottom)\n",
           at_gap, rb.static_twist_deg[1]);
    CHECK(at_gap > 0.0, "a top inner bevel twists positive (%.4f deg)", at_gap);
    CHECK(mirror < 1e-6 * fabs(at_gap), "the bottom bevel is its mirror (%.3g deg)", mirror);
    rd_pretension_result_cleanup(&rt);
    rd_pretension_result_cleanup(&rb);
}

/* A table of p / p0 (mirrored) against the same pressure as orders. */
static void table_round_trip(void)
{
    static rd_free_shape t;
    t.kind = RD_FREE_PRESSURE;
    t.n_points = 181;
    for (int k = 0; k <= 180; k++) {
        t.theta_deg[k] = k;
        t.value[k] = 1.0 + 0.1 * cos(2.0 * k * PI / 180.0) + 0.05 * cos(4.0 * k * PI / 180.0);
    }
    round_trip("a table of 1 + 0.1 cos 2 theta + 0.05 cos 4 theta", &t, 80);
}

int main(void)
{
    uniform_gap();
    rd_free_shape uni = {.kind = RD_FREE_PRESSURE};
    round_trip("uniform", &uni, 40);
    round_trip("uniform", &uni, 160);
    rd_free_shape oval = {
        .kind = RD_FREE_PRESSURE, .n_orders = 2, .order = {2, 3}, .amplitude = {0.15, -0.2}};
    round_trip("orders 2 and 3", &oval, 40);
    round_trip("orders 2 and 3", &oval, 160);
    table_round_trip();
    closed_unchanged();
    bad_input();
    twist();
    return check_done();
}
