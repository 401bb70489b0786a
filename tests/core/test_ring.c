/* test_ring — section constants, segment mass properties and the assembled
 * K and M of rd_ring, each against an independent value: published torsion
 * coefficients, closed-form integrals over the whole ring, numerical
 * quadrature, and the rigid-body null space. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_internal.h"
#include "rd_ring.h"

#define PI  3.14159265358979323846
#define EPS 2.220446049250313e-16

static void test_torsion_constant(void)
{
    /* beta = J / (a c^3): square 0.1406 (Roark), Tab. 3.2 of the thesis:
     * 0.229 (2), 0.281 (4), 0.299 ~ 0.3 (6), 0.307 (8), 1/3 as a/c -> inf.
     * Tolerance 1e-3 = the tables' last digit. */
    double c = 1.0;
    CHECK_ABS(rd_section_torsion_constant(1.0, c), 0.1406, 1e-3, "square");
    CHECK_ABS(rd_section_torsion_constant(2.0, c) / 2.0, 0.229, 1e-3, "b/h = 2");
    CHECK_ABS(rd_section_torsion_constant(4.0, c) / 4.0, 0.281, 1e-3, "b/h = 4");
    CHECK_ABS(rd_section_torsion_constant(6.0, c) / 6.0, 0.299, 1e-3, "b/h = 6");
    CHECK_ABS(rd_section_torsion_constant(8.0, c) / 8.0, 0.307, 1e-3, "b/h = 8");
    /* thin strip: beta = 1/3 (1 - 0.630 c/a) to O((c/a)^5) */
    CHECK_REL(rd_section_torsion_constant(1000.0, c) / 1000.0, (1.0 - 0.630 / 1000.0) / 3.0, 1e-5,
              "thin strip");
    /* symmetric in its arguments (b < h rings) */
    CHECK_REL(rd_section_torsion_constant(0.3, 1.0), rd_section_torsion_constant(1.0, 0.3), 1e-15,
              "J(b,h) = J(h,b)");
}

static void test_section(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_ring_section s;
    rd_ring_section_get(&p, 0, &s);
    CHECK_REL(s.R, (0.0765 - 0.0029) / 2, 1e-15, "centroid radius");
    CHECK_REL(s.I_inplane, 1.2e-3 * pow(2.9e-3, 3) / 12, 1e-14, "I in-plane = h b^3/12");
    CHECK_REL(s.I_outplane, 2.9e-3 * pow(1.2e-3, 3) / 12, 1e-14, "I out-of-plane = b h^3/12");
    CHECK(s.J < s.I_inplane + s.I_outplane, "Saint-Venant J %g must be below the polar moment %g",
          s.J, s.I_inplane + s.I_outplane);
    CHECK_REL(s.span, 2 * PI - 0.0003 / s.R, 1e-15, "split ring span");
    CHECK_REL(s.shear_factor, 1.2, 1e-15, "rectangle form factor 6/5");
}

/* Mass properties of a segment by brute-force midpoint quadrature over the
 * sector (r, psi; z analytically): an independent second method. */
static void quadrature_mass(const rd_ring_params *p, double phi, rd_segment_mass *q)
{
    double b = p->radial_width, h = p->axial_height, rho = p->density;
    double R = 0.5 * (p->diameter - b), ri = R - b / 2;
    int nr = 400, np = 400;
    double m = 0, mx = 0, xx = 0, yy = 0;
    for (int i = 0; i < nr; i++) {
        double r = ri + (i + 0.5) * b / nr;
        for (int j = 0; j < np; j++) {
            double psi = -phi / 2 + (j + 0.5) * phi / np;
            double dm = rho * h * r * (b / nr) * (phi / np);
            double x = r * cos(psi), y = r * sin(psi);
            m += dm;
            mx += dm * x;
            xx += dm * x * x;
            yy += dm * y * y;
        }
    }
    double zz = m * h * h / 12;
    q->mass = m;
    q->com_radius = mx / m;
    q->I_rr = yy + zz;
    q->I_tt = xx + zz - m * q->com_radius * q->com_radius;
    q->I_zz = xx + yy - m * q->com_radius * q->com_radius;
}

static void test_segment_mass(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    double phis[] = {2 * PI / 3, 0.3, 2 * PI / 2000};
    for (int k = 0; k < 3; k++) {
        rd_segment_mass a, q;
        rd_ring_segment_mass_get(&p, phis[k], &a);
        quadrature_mass(&p, phis[k], &q);
        /* midpoint rule, 400 x 400 cells: error ~ (1/400)^2 relative */
        CHECK_REL(a.mass, q.mass, 1e-5, "mass phi=%g", phis[k]);
        CHECK_REL(a.com_radius, q.com_radius, 1e-5, "COM radius phi=%g", phis[k]);
        CHECK_REL(a.I_rr, q.I_rr, 1e-4, "I_rr phi=%g", phis[k]);
        CHECK_REL(a.I_zz, q.I_zz, 1e-4, "I_zz phi=%g", phis[k]);
        if (phis[k] > 0.1) /* I_tt is a difference of large numbers for thin sectors */
            CHECK_REL(a.I_tt, q.I_tt, 1e-4, "I_tt phi=%g", phis[k]);
    }
    /* small-angle limit: centroid of the revolved rectangle R + b^2/(12 R) */
    rd_segment_mass a;
    rd_ring_segment_mass_get(&p, 1e-6, &a);
    double R = 0.5 * (p.diameter - p.radial_width);
    CHECK_REL(a.com_radius, R + p.radial_width * p.radial_width / (12 * R), 1e-11,
              "revolved-rectangle centroid");
}

/* Weights of a graded ring of n segments (rd_ring_create_graded): the
 * contact refinement's pattern, segments of 1, 1/2, 1/4 and 1/8 of a base
 * segment and back, and a lone short one, so that no two neighbours but
 * the base ones are alike; NULL for equal segments. */
static double *graded(int n, int on)
{
    if (!on)
        return NULL;
    double *w = malloc((size_t)n * sizeof *w);
    for (int i = 0; i < n; i++)
        w[i] = 1.0 / (1 << (i % 4)) + (i == n / 3 ? 0.37 : 0.0);
    return w;
}

/* The assembled M against whole-ring integrals (Pappus and the ring's inertia
 * tensor): kinetic energy of rigid motions; on a graded ring too (each
 * segment's mass is its own sector's, exactly). */
static void test_mass_matrix_rigid(int closed, int n, int grade)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    double *wts = graded(n, grade);
    rd_ring *ring = rd_ring_create_graded(&p, n, closed, wts, &err);
    free(wts);
    CHECK(ring != NULL, "create: %s", err.message);
    if (!ring)
        return;
    const rd_ring_section *s = rd_ring_get_section(ring);
    double b = p.radial_width, h = p.axial_height, rho = p.density;
    double ri = s->R - b / 2, ro = s->R + b / 2, span = s->span;
    double th0 = closed ? 0.0 : 0.5 * p.closed_gap / s->R, th1 = th0 + span;
    double mtot = rho * h * span * (ro * ro - ri * ri) / 2;
    double S3 = rho * h * (pow(ro, 4) - pow(ri, 4)) / 4;
    double Izz = S3 * span;
    double sin2 = 0.5 * (span - 0.5 * (sin(2 * th1) - sin(2 * th0))); /* int sin^2 */
    double Zz = rho * (ro * ro - ri * ri) / 2 * h * h * h / 12 * span;
    double Ixx = S3 * sin2 + Zz;

    int N = 6 * n;
    double *q = calloc((size_t)N, sizeof *q);
    double t[3] = {0.3, -0.4, 1.2}, w0[3] = {0, 0, 0};
    rd_ring_rigid_motion(ring, t, w0, q);
    CHECK_REL(rd_ring_kinetic_energy(ring, q), 0.5 * mtot * (0.09 + 0.16 + 1.44), 1e-12,
              "translation KE, n=%d closed=%d", n, closed);
    double tz[3] = {0, 0, 0}, wz[3] = {0, 0, 2.0}, wx[3] = {1.5, 0, 0};
    rd_ring_rigid_motion(ring, tz, wz, q);
    CHECK_REL(rd_ring_kinetic_energy(ring, q), 0.5 * Izz * 4.0, 1e-12,
              "spin about the axis KE, n=%d closed=%d", n, closed);
    rd_ring_rigid_motion(ring, tz, wx, q);
    CHECK_REL(rd_ring_kinetic_energy(ring, q), 0.5 * Ixx * 2.25, 1e-12,
              "rotation about x KE, n=%d closed=%d", n, closed);
    free(q);
    rd_ring_free(ring);
}

/* K: symmetric, rigid motions in its null space, and 1/2 q^T K q equal to the
 * element-by-element strain energy; graded: each joint its own beam. */
static void test_stiffness(int closed, int n, int grade)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    double *wts = graded(n, grade);
    rd_ring *ring = rd_ring_create_graded(&p, n, closed, wts, &err);
    free(wts);
    int N = 6 * n;
    double *K = malloc((size_t)N * N * sizeof *K), *M = malloc((size_t)N * N * sizeof *M);
    double *q = malloc((size_t)N * sizeof *q);
    CHECK(rd_ring_assemble_dense(ring, K, M, &err) == RD_OK, "%s", err.message);
    double kmax = 0, asym = 0;
    for (int i = 0; i < N * N; i++)
        kmax = fmax(kmax, fabs(K[i]));
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            asym = fmax(asym, fabs(K[i + j * N] - K[j + i * N]));
    CHECK(asym <= 10 * EPS * kmax, "K asymmetry %g vs |K| %g", asym, kmax);

    /* rigid motions: strain energy at rounding level relative to a deformation
     * of the same amplitude (a single segment moved) */
    double t[3] = {1e-4, -2e-4, 3e-4}, w[3] = {2e-3, -1e-3, 5e-3};
    rd_ring_rigid_motion(ring, t, w, q);
    double e_rigid = rd_ring_strain_energy(ring, q);
    memset(q, 0, (size_t)N * sizeof *q);
    q[6 * (n / 2) + 0] = 1e-4;
    double e_def = rd_ring_strain_energy(ring, q);
    /* d = u_B - u_A - th_A x dP rounds to ~eps |u|, so the energy ratio is
     * ~eps^2 = 5e-32; 1e-20 leaves room yet any wrong term in T gives ~1e-2. */
    CHECK(e_rigid <= 1e-20 * e_def && e_def > 0, "rigid-motion energy %g vs deformation energy %g",
          e_rigid, e_def);

    /* 1/2 q^T K q == element-wise energy for a pseudo-random q */
    for (int i = 0; i < N; i++)
        q[i] = 1e-4 * sin(1.7 * i + 0.3);
    double quad = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            quad += 0.5 * q[i] * K[i + j * N] * q[j];
    CHECK_REL(quad, rd_ring_strain_energy(ring, q), 1e-10, "assembly vs element energy");
    double kin = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            kin += 0.5 * q[i] * M[i + j * N] * q[j];
    CHECK_REL(kin, rd_ring_kinetic_energy(ring, q), 1e-12, "assembly vs segment KE");
    free(K);
    free(M);
    free(q);
    rd_ring_free(ring);
}

/* A graded ring's segments: their angles in proportion to the weights and
 * summing to the span, each midway between its ends; a joint's axial
 * stiffness E A / L with L its chord (thesis 3.1); equal weights the equal
 * ring's segments (to rounding). */
static void test_graded_segments(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    int n = 20;
    double *w = graded(n, 1), sum = 0.0, span = 0.0;
    for (int i = 0; i < n; i++)
        sum += w[i];
    rd_ring *ring = rd_ring_create_graded(&p, n, 0, w, &err);
    const rd_ring_section *s = rd_ring_get_section(ring);
    double start = 0.5 * p.closed_gap / s->R;
    for (int i = 0; i < n; i++) {
        double phi = rd_ring_segment_phi_at(ring, i);
        CHECK_REL(phi, s->span * w[i] / sum, 1e-14, "segment %d's angle", i);
        CHECK_REL(rd_ring_get_segment_angle(ring, i), start + span + 0.5 * phi, 1e-14,
                  "segment %d's middle", i);
        span += phi;
        CHECK_REL(rd_ring_get_segment_mass(ring, i)->mass,
                  p.density * p.axial_height * phi * s->R * p.radial_width, 1e-13,
                  "segment %d's mass (Pappus)", i);
    }
    CHECK_REL(span, s->span, 1e-14, "the segments fill the span");
    for (int j = 0; j < n - 1; j++) {
        double L =
            2.0 * s->R *
            sin(0.25 * (rd_ring_segment_phi_at(ring, j) + rd_ring_segment_phi_at(ring, j + 1)));
        CHECK_REL(rd_ring_joint_stiffness(ring, j)[0], p.youngs_modulus * s->area / L, 1e-13,
                  "joint %d's E A / L", j);
    }
    rd_ring_free(ring);
    for (int i = 0; i < n; i++)
        w[i] = 2.5;
    ring = rd_ring_create_graded(&p, n, 0, w, &err);
    rd_ring *eq = rd_ring_create(&p, n, 0, &err);
    for (int i = 0; i < n; i++)
        CHECK_REL(rd_ring_get_segment_angle(ring, i), rd_ring_get_segment_angle(eq, i), 1e-14,
                  "equal weights: segment %d", i);
    CHECK_REL(rd_ring_joint_stiffness(ring, 3)[6 * 5 + 5],
              rd_ring_joint_stiffness(eq, 3)[6 * 5 + 5], 1e-13,
              "equal weights: a joint's bending stiffness");
    rd_ring_free(ring);
    rd_ring_free(eq);
    free(w);
}

/* A closed ring under a single joint's axial stretch has the energy of the
 * chord's axial spring: EA/L * d^2 / 2 (thesis 3.1). */
static void test_axial_spring(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    int n = 12;
    rd_ring *ring = rd_ring_create(&p, n, 0, &err);
    const rd_ring_section *s = rd_ring_get_section(ring);
    double phi = s->span / n, L = 2 * s->R * sin(phi / 2);
    /* move segments 6..11 rigidly along the chord direction of joint 5 -> 6 */
    double a5 = rd_ring_get_segment_angle(ring, 5), a6 = rd_ring_get_segment_angle(ring, 6);
    double e1[3] = {cos(a6) - cos(a5), sin(a6) - sin(a5), 0};
    double len = hypot(e1[0], e1[1]);
    double d = 1e-6, w0[3] = {0, 0, 0}, t[3] = {d * e1[0] / len, d * e1[1] / len, 0};
    double q[6 * 12];
    memset(q, 0, sizeof q);
    double part[6 * 12];
    rd_ring_rigid_motion(ring, t, w0, part);
    for (int i = 6; i < n; i++)
        for (int k = 0; k < 6; k++)
            q[6 * i + k] = part[6 * i + k];
    CHECK_REL(rd_ring_strain_energy(ring, q), 0.5 * p.youngs_modulus * s->area / L * d * d, 1e-12,
              "axial spring energy");
    rd_ring_free(ring);
}

static void test_validation(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_ring_scene_validate(&p, 20, 0, &err) == RD_OK, "defaults valid: %s", err.message);

    struct {
        const char *path;
        double *field, value;
    } bad[] = {
        {"/ring/diameter", &p.diameter, -1},
        {"/ring/diameter", &p.diameter, NAN},
        {"/ring/radial_width", &p.radial_width, 0.03},
        {"/ring/radial_width", &p.radial_width, 0},
        {"/ring/axial_height", &p.axial_height, 1e-9},
        {"/ring/closed_gap", &p.closed_gap, -1e-3},
        {"/ring/tangential_force", &p.tangential_force, INFINITY},
        {"/ring/material/youngs_modulus", &p.youngs_modulus, 0},
        {"/ring/material/poisson_ratio", &p.poisson_ratio, 0.5},
        {"/ring/material/density", &p.density, -7850},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        rd_ring_params_default(&p);
        *bad[i].field = bad[i].value;
        rd_error_init(&err);
        int rc = rd_ring_scene_validate(&p, 20, 0, &err);
        CHECK(rc == RD_EINVAL && strcmp(err.path, bad[i].path) == 0,
              "value %g: rc %d path '%s' want '%s'", bad[i].value, rc, err.path, bad[i].path);
        CHECK(strstr(err.message, "allowed") != NULL, "message names the range: %s", err.message);
    }
    rd_ring_params_default(&p);
    rd_error_init(&err);
    CHECK(rd_ring_scene_validate(&p, 2, 0, &err) == RD_EINVAL &&
              strcmp(err.path, "/discretization/segments") == 0,
          "2 segments: %s", err.message);
    rd_error_init(&err);
    CHECK(rd_ring_scene_validate(&p, RD_SEGMENTS_MAX + 1, 0, &err) == RD_ELIMIT,
          "over the segment limit: %s", err.message);
    rd_error_init(&err);
    CHECK(rd_ring_create(&p, 1, 0, &err) == NULL && err.code == RD_EINVAL,
          "create validates first");
}

int main(void)
{
    test_torsion_constant();
    test_section();
    test_segment_mass();
    int ns[] = {3, 7, 20, 64};
    for (int i = 0; i < 4; i++)
        for (int closed = 0; closed < 2; closed++)
            for (int grade = 0; grade < 2; grade++) {
                test_mass_matrix_rigid(closed, ns[i], grade);
                test_stiffness(closed, ns[i], grade);
            }
    test_graded_segments();
    test_axial_spring();
    test_validation();
    return check_done();
}
