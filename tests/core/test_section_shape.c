/*
 * test_section_shape — general cross-sections (core/ring/rd_section_shape.c,
 * rd_torsion.c):
 *   - polygon moments against closed forms: the rectangle (b h, h b^3/12,
 *     b h^3/12), and the inner bevel as the rectangle less a triangle whose
 *     moments come from the triangle's vertex formulas (an independent way);
 *   - the principal angle: tan 2a = 2 I_rz / (I_rr - I_zz), the principal
 *     moments' product moment 0, and 0 for symmetric shapes;
 *   - the Saint-Venant constant by finite elements converging: on the
 *     rectangle (the series J = a c^3 [1/3 - ...]) monotone from below with
 *     the error falling ~4x a level, on the equilateral triangle (J = sqrt(3)
 *     s^4 / 80, exact for the polygon), on a 64-gon against the circle (pi
 *     a^4 / 2, the polygon's own deficit ~0.2 %); the extrapolated J within
 *     its estimate of the closed form;
 *   - a polygon section equal to the rectangle gives the rectangle's
 *     properties, and its beam the rectangle's pretension answer;
 *   - the energy method's shear form factors: the rectangle's 6/5 both
 *     ways, and a rhombus' 31/30 both ways (its integral A / I^2 int S^2 / t
 *     in closed form: t = 2a (1 - |y| / c), I = a c^3 / 3);
 *   - bad input: a self-intersecting polygon, a bevel larger than the
 *     section, a keystone angle that leaves no section, a polygon whose box
 *     is not b x h: refused at the field, naming the value and the range.
 */
#include <math.h>
#include <string.h>

#include <lapacke.h>

#include "check.h"
#include "rd_internal.h"
#include "rd_section.h"
#include "rd_static.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define B 0.0029
#define H 0.0012

static rd_ring_params ring_with(int shape)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    p.section = shape;
    memset(&p.spec, 0, sizeof p.spec);
    return p;
}

/* int x^a y^b over a triangle, a + b = 2, by its vertex formulas. */
static void triangle_moments(const double v[3][2], double *A, double m1[2], double m2[3])
{
    double area = 0.5 * ((v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) -
                         (v[2][0] - v[0][0]) * (v[1][1] - v[0][1]));
    *A = fabs(area);
    for (int k = 0; k < 2; k++)
        m1[k] = *A * (v[0][k] + v[1][k] + v[2][k]) / 3.0;
    double xx = 0, yy = 0, xy = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double w = i == j ? 2.0 : 1.0;
            xx += w * v[i][0] * v[j][0];
            yy += w * v[i][1] * v[j][1];
            xy += w * v[i][0] * v[j][1];
        }
    m2[0] = *A * xx / 12.0, m2[1] = *A * yy / 12.0, m2[2] = *A * xy / 12.0;
}

static void test_moments(void)
{
    double rect[4][2] = {{0, 0}, {B, 0}, {B, H}, {0, H}};
    const double(*R)[2] = (const double(*)[2])rect;
    CHECK_REL(rd_section_polygon_moment(R, 4, 0, 0), B * H, 1e-14, "area");
    CHECK_REL(rd_section_polygon_moment(R, 4, 2, 0), H * B * B * B / 3.0, 1e-14, "int u^2");
    CHECK_REL(rd_section_polygon_moment(R, 4, 1, 1), B * B * H * H / 4.0, 1e-14, "int u v");

    /* inner bevel, top, legs w x t: rectangle less the corner triangle */
    double w = 0.6e-3, t = 0.4e-3;
    rd_ring_params p = ring_with(RD_SECTION_INNER_BEVEL);
    p.spec.width = w, p.spec.height = t;
    p.spec.solved = 1, p.spec.J = 1.0; /* J is not under test here */
    rd_section s;
    rd_section_init(&s, &p);
    double tri[3][2] = {{0, H - t}, {w, H}, {0, H}}, At, m1[2], m2[3];
    triangle_moments((const double(*)[2])tri, &At, m1, m2);
    double A = B * H - At, Su = B * B * H / 2 - m1[0], Sv = B * H * H / 2 - m1[1];
    double uc = Su / A, vc = Sv / A;
    double Irr = H * B * B * B / 3 - m2[0] - A * uc * uc,
           Izz = B * H * H * H / 3 - m2[1] - A * vc * vc;
    double Irz = B * B * H * H / 4 - m2[2] - A * uc * vc;
    CHECK_REL(s.area, A, 1e-13, "bevel area");
    CHECK_REL(s.R, 0.5 * p.diameter - B + uc, 1e-14, "bevel centroid radius");
    CHECK_REL(s.z_c, vc - 0.5 * H, 1e-11, "bevel centroid height");
    CHECK_REL(s.I_rr, Irr, 1e-11, "I_rr");
    CHECK_REL(s.I_zz, Izz, 1e-11, "I_zz");
    CHECK_REL(s.I_rz, Irz, 1e-10, "I_rz");
    CHECK(s.I_rz > 0 && s.angle > 0, "the top inner bevel turns the axes toward +z: %g rad",
          s.angle);
    CHECK_REL(tan(2 * s.angle), 2 * Irz / (Irr - Izz), 1e-10, "principal angle");
    double c = cos(s.angle), sn = sin(s.angle);
    double prod = (s.I_zz - s.I_rr) * sn * c + s.I_rz * (c * c - sn * sn);
    CHECK(fabs(prod) < 1e-12 * s.I_inplane, "principal product %.3g", prod);
    CHECK_REL(s.I_inplane + s.I_outplane, Irr + Izz, 1e-12, "trace kept");
    /* the bottom bevel mirrors it: the same moments, the angle turned back */
    rd_section sb;
    p.spec.side = 1;
    rd_section_init(&sb, &p);
    CHECK_REL(sb.I_rz, -s.I_rz, 1e-10, "bottom bevel I_rz");
    CHECK_REL(sb.z_c, -s.z_c, 1e-10, "bottom bevel centroid");
    /* the double keystone is symmetric about mid-height */
    p = ring_with(RD_SECTION_KEYSTONE);
    p.spec.angle_deg = 7.0, p.spec.double_sided = 1, p.spec.solved = 1, p.spec.J = 1.0;
    rd_section_init(&s, &p);
    CHECK(fabs(s.angle) < 1e-12 && fabs(s.z_c) < 1e-15, "double keystone: angle %g", s.angle);
    CHECK_REL(s.area, B * H - B * B * tan(7 * M_PI / 180), 1e-12, "keystone area");
}

static void test_torsion(void)
{
    double rect[4][2] = {{0, 0}, {B, 0}, {B, H}, {0, H}}, prev = 0, err_prev = 0;
    const double(*R)[2] = (const double(*)[2])rect;
    double want = rd_section_torsion_constant(B, H);
    rd_error e;
    rd_error_init(&e);
    for (int level = 3; level <= 7; level++) {
        double J;
        CHECK(rd_section_torsion_polygon(R, 4, level, &J, &e) == RD_OK, "%s", e.message);
        double err = want - J;
        CHECK(err > 0 && J > prev, "level %d: J %.6g below the series %.6g, rising", level, J,
              want);
        if (level > 3)
            CHECK(err_prev / err > 3.5 && err_prev / err < 4.5, "level %d: error ratio %.3f", level,
                  err_prev / err);
        printf("rectangle level %d: J = %.8g (series %.8g), error %.3g\n", level, J, want,
               err / want);
        prev = J, err_prev = err;
    }
    double J, Je;
    CHECK(rd_section_torsion_solve(R, 4, &J, &Je, &e) == RD_OK, "%s", e.message);
    CHECK(fabs(J - want) <= Je && Je < 1e-4 * want, "rectangle: J %.8g +- %.2g, series %.8g", J, Je,
          want);
    /* equilateral triangle of side a: J = sqrt(3) a^4 / 80 */
    double a = 2e-3, tri[3][2] = {{0, 0}, {a, 0}, {0.5 * a, 0.5 * sqrt(3.0) * a}};
    CHECK(rd_section_torsion_solve((const double(*)[2])tri, 3, &J, &Je, &e) == RD_OK, "%s",
          e.message);
    double wt = sqrt(3.0) * pow(a, 4) / 80.0;
    CHECK(fabs(J - wt) <= Je + 1e-12 * wt && Je < 1e-3 * wt,
          "triangle: J %.8g +- %.2g, closed form %.8g", J, Je, wt);
    printf("triangle: J = %.8g +- %.2g, closed form %.8g\n", J, Je, wt);
    /* a 64-gon in a circle of radius r: pi r^4 / 2 less the polygon's deficit */
    double poly[64][2], r = 1e-3;
    for (int i = 0; i < 64; i++)
        poly[i][0] = r * cos(2 * M_PI * i / 64), poly[i][1] = r * sin(2 * M_PI * i / 64);
    CHECK(rd_section_torsion_solve((const double(*)[2])poly, 64, &J, &Je, &e) == RD_OK, "%s",
          e.message);
    double wc = M_PI * pow(r, 4) / 2;
    CHECK(J < wc && J > 0.994 * wc, "64-gon: J %.8g, circle %.8g", J, wc);
    printf("64-gon: J = %.8g +- %.2g, circle %.8g (%.4f)\n", J, Je, wc, J / wc);
}

/* A polygon equal to the rectangle: the rectangle's section and beam. */
static void test_shear_factors(void)
{
    rd_ring_params p = ring_with(RD_SECTION_POLYGON);
    double rect[4][2] = {{0, 0}, {B, 0}, {B, H}, {0, H}};
    memcpy(p.spec.points, rect, sizeof rect);
    p.spec.n_points = 4;
    rd_section s;
    rd_section_init(&s, &p);
    printf("shear form factors: rectangle %.9f, %.9f (6/5)", s.shear_factor, s.shear_factor_axial);
    CHECK_REL(s.shear_factor, 1.2, 1e-6, "the rectangle's in-plane shear factor");
    CHECK_REL(s.shear_factor_axial, 1.2, 1e-6, "the rectangle's axial shear factor");
    double rhomb[4][2] = {{0.5 * B, 0}, {B, 0.5 * H}, {0.5 * B, H}, {0, 0.5 * H}};
    memcpy(p.spec.points, rhomb, sizeof rhomb);
    rd_section_init(&s, &p);
    printf("; rhombus %.9f, %.9f (31/30)\n", s.shear_factor, s.shear_factor_axial);
    CHECK_REL(s.shear_factor, 31.0 / 30.0, 1e-6, "the rhombus' in-plane shear factor");
    CHECK_REL(s.shear_factor_axial, 31.0 / 30.0, 1e-6, "the rhombus' axial shear factor");
}

static void test_polygon_rectangle(void)
{
    rd_ring_params pr = ring_with(RD_SECTION_RECTANGLE), pp = ring_with(RD_SECTION_POLYGON);
    double pts[5][2] = {{5e-3, 1e-3},
                        {5e-3 - B, 1e-3},
                        {5e-3 - B, 1e-3 + H},
                        {5e-3, 1e-3 + H},
                        {5e-3, 1e-3 + 0.5 * H}}; /* clockwise, a point mid-edge, any origin */
    memcpy(pp.spec.points, pts, sizeof pts);
    pp.spec.n_points = 5;
    rd_error e;
    rd_error_init(&e);
    CHECK(rd_section_spec_solve(pp.section, &pp.spec, B, H, &e) == RD_OK, "%s", e.message);
    rd_section sr, sp;
    rd_section_init(&sr, &pr);
    rd_section_init(&sp, &pp);
    CHECK_REL(sp.area, sr.area, 1e-12, "area");
    CHECK_REL(sp.R, sr.R, 1e-14, "R");
    CHECK_REL(sp.I_inplane, sr.I_inplane, 1e-11, "I_inplane");
    CHECK_REL(sp.I_outplane, sr.I_outplane, 1e-11, "I_outplane");
    CHECK(fabs(sp.angle) < 1e-12, "angle %g", sp.angle);
    CHECK_REL(sp.J, sr.J, 1e-4, "J");
    rd_pretension_opts o;
    rd_static_opts so;
    rd_pretension_opts_default(&o);
    rd_static_opts_default(&so);
    so.estimate_error = 0;
    rd_pretension_result a, b;
    memset(&a, 0, sizeof a), memset(&b, 0, sizeof b);
    int ok = rd_pretension_solve(&pr, 20, &o, &so, NULL, &a, &e) == RD_OK &&
             rd_pretension_solve(&pp, 20, &o, &so, NULL, &b, &e) == RD_OK;
    CHECK(ok, "pretension: %s", e.message);
    if (ok)
        CHECK_REL(b.gap_opening_inner, a.gap_opening_inner, 1e-8, "x_a of the polygon");
    /* unsolved: the section's J is NAN, and the ring solves its own copy */
    rd_ring_params pu = pp;
    pu.spec.solved = 0;
    rd_section su;
    rd_section_init(&su, &pu);
    CHECK(isnan(su.J), "unsolved J %g", su.J);
    rd_ring *ring = rd_ring_create(&pu, 20, 0, &e);
    CHECK(ring && rd_ring_get_section(ring)->J == sp.J, "the ring's J: %s", e.message);
    rd_ring_free(ring);
    rd_pretension_result_cleanup(&a);
    rd_pretension_result_cleanup(&b);
}

/* The beam of a turned section: under pure tip moments a cantilever's
 * rotations are C M, C = (L / E) [[I_rr, -I_rz], [-I_rz, I_zz]]^-1 =
 * (L / (E det)) [[I_zz, I_rz], [I_rz, I_rr]], in the local (axial y, radial
 * outward z: e3 = e1 x e2) frame: a rotation (theta_y, theta_z) moves the
 * section point (r', z') along the chord by theta_y r' - theta_z z', so the
 * bending energy is E / (2 L) (theta_y^2 I_rr - 2 theta_y theta_z I_rz +
 * theta_z^2 I_zz), whatever the shear: the rotation block of Kc^-1.  (Until
 * 0.3.16 this test took the radial axis inward, as Kc's turn did: every
 * turned section was solved mirrored; test_free_shape checks the twist's
 * sign against the ring makers' rule.) */
static void test_turned_beam(void)
{
    rd_ring_params p = ring_with(RD_SECTION_INNER_STEP);
    p.spec.width = 0.0008, p.spec.height = 0.0005;
    rd_error e;
    rd_error_init(&e);
    rd_ring *ring = rd_ring_create(&p, 24, 0, &e);
    CHECK(ring != NULL, "%s", e.message);
    if (!ring)
        return;
    const rd_section *s = rd_ring_get_cross_section(ring);
    const double *K = rd_ring_joint_stiffness(ring, 0), *P0 = rd_ring_reference_point(ring, 0),
                 *P1 = rd_ring_reference_point(ring, 1);
    double C[36], L = hypot(P1[0] - P0[0], P1[1] - P0[1]);
    lapack_int piv[6];
    memcpy(C, K, sizeof C);
    CHECK(LAPACKE_dgetrf(LAPACK_ROW_MAJOR, 6, 6, C, 6, piv) == 0 &&
              LAPACKE_dgetri(LAPACK_ROW_MAJOR, 6, C, 6, piv) == 0,
          "Kc inverts");
    double det = s->I_rr * s->I_zz - s->I_rz * s->I_rz, f = L / p.youngs_modulus / det;
    double want[2][2] = {{f * s->I_zz, f * s->I_rz}, {f * s->I_rz, f * s->I_rr}};
    CHECK(fabs(s->angle) > 0.02, "a turned section: %g rad", s->angle);
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < 2; c++)
            CHECK_ABS(C[6 * (4 + r) + 4 + c], want[r][c], 1e-9 * fabs(want[0][0]),
                      "rotation compliance %d %d", r, c);
    rd_ring_free(ring);
}

static void expect(int shape, const rd_section_spec *sp, const char *path, const char *words)
{
    double pts[RD_SECTION_POINTS_MAX][2];
    int n;
    rd_error e;
    rd_error_init(&e);
    rd_error_enter(&e, "/ring"); /* the outline's paths are relative to the ring's block */
    int rc = rd_section_outline(shape, sp, B, H, pts, &n, &e);
    CHECK(rc == RD_EINVAL && strcmp(e.path, path) == 0, "refused at %s (got %d at %s)", path, rc,
          e.path);
    CHECK(strstr(e.message, words) != NULL, "\"%s\" says \"%s\"", e.message, words);
}

static void test_errors(void)
{
    rd_section_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.n_points = 4; /* a bow tie */
    double bow[4][2] = {{0, 0}, {B, H}, {B, 0}, {0, H}};
    memcpy(sp.points, bow, sizeof bow);
    expect(RD_SECTION_POLYGON, &sp, "/ring/section/points_m",
           "crosses itself: the edge from point 0 to 1 meets the edge from point 2 to 3");
    double small[4][2] = {{0, 0}, {0.002, 0}, {0.002, H}, {0, H}};
    memcpy(sp.points, small, sizeof small);
    expect(RD_SECTION_POLYGON, &sp, "/ring/section/points_m", "spans 0.002 m radially");
    memset(&sp, 0, sizeof sp);
    sp.width = 0.003, sp.height = 0.0004;
    expect(RD_SECTION_INNER_BEVEL, &sp, "/ring/section/width_m",
           "width_m = 0.003 m is out of range: allowed above 0 and below 0.0029 m");
    sp.width = 0.001, sp.height = 0.0012;
    expect(RD_SECTION_INNER_STEP, &sp, "/ring/section/height_m",
           "height_m = 0.0012 m is out of range: allowed above 0 and below 0.0012 m");
    memset(&sp, 0, sizeof sp);
    sp.angle_deg = 15, sp.double_sided = 1; /* 2.9 tan 15 = 0.78 mm > 0.6 */
    expect(RD_SECTION_KEYSTONE, &sp, "/ring/section/angle_deg",
           "angle_deg = 15 deg is out of range: allowed above 0 and below 11.");
}

int main(void)
{
    test_moments();
    test_torsion();
    test_shear_factors();
    test_polygon_rectangle();
    test_turned_beam();
    test_errors();
    return check_done();
}
