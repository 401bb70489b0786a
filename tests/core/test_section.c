/* test_section — the cross-section object (rd_section) against closed forms:
 * the rectangle's and the circle's area, second moments and centroid, the
 * moments about the ring axis (Pappus and the annulus' integrals), the faces'
 * radii and areas against the segment arcs of a built ring, and the ring's
 * beam constants as its view. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "check.h"
#include "rd_internal.h"
#include "rd_ring.h"
#include "rd_section.h"

#define PI 3.14159265358979323846

/* Every member after `shape` is a double: compared bit for bit, no padding. */
static int same_section(const rd_section *a, const rd_section *b)
{
    size_t at = offsetof(rd_section, b);
    return a->shape == b->shape &&
           memcmp((const char *)a + at, (const char *)b + at, sizeof *a - at) == 0;
}

static void test_rectangle(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_section s;
    rd_section_init(&s, &p);
    double b = 2.9e-3, h = 1.2e-3, d = 0.0765, R = (d - b) / 2;
    CHECK(s.shape == RD_SECTION_RECTANGLE, "shape %d", s.shape);
    CHECK(s.b == b && s.h == h, "b %g h %g", s.b, s.h);
    CHECK_REL(s.R, R, 1e-15, "centroid radius (d - b)/2");
    CHECK(s.D == d - b && s.R == 0.5 * s.D, "reference diameter d - b = 2 R");
    CHECK(s.z_c == 0.0, "centroid at mid-height: z_c %g", s.z_c);
    CHECK_REL(s.area, b * h, 1e-15, "A = b h");
    CHECK_REL(s.I_rr, h * b * b * b / 12, 1e-14, "I_rr = h b^3/12");
    CHECK_REL(s.I_zz, b * h * h * h / 12, 1e-14, "I_zz = b h^3/12");
    CHECK(s.I_rz == 0.0 && s.angle == 0.0, "symmetric: I_rz %g, angle %g", s.I_rz, s.angle);
    CHECK(s.I_inplane == s.I_rr && s.I_outplane == s.I_zz, "principal moments at angle 0");
    CHECK_REL(s.J, rd_section_torsion_constant(b, h), 1e-15, "J: the Saint-Venant series");
    CHECK(s.J < s.I_rr + s.I_zz, "J %g below the polar moment %g", s.J, s.I_rr + s.I_zz);
    CHECK_REL(s.shear_factor, 1.2, 1e-15, "shear factor 6/5");
    /* about the ring axis, the annulus ri..ro of height h */
    double ri = R - b / 2, ro = R + b / 2;
    CHECK_REL(s.S1, b * h * R, 1e-14, "S1 = A R (Pappus)");
    CHECK_REL(s.S2, h * (pow(ro, 3) - pow(ri, 3)) / 3, 1e-13, "S2 = int r^2 dA");
    CHECK_REL(s.S3, h * (pow(ro, 4) - pow(ri, 4)) / 4, 1e-13, "S3 = int r^3 dA");
    CHECK_REL(s.Z, b * h * R * h * h / 12, 1e-13, "Z = int r z^2 dA = S1 h^2/12");
}

static void test_circle(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    p.diameter = 2.1;
    p.radial_width = p.axial_height = 0.1; /* NAFEMS: R = 1 m, wire 0.1 m */
    p.section = RD_SECTION_CIRCLE;
    rd_section s;
    rd_section_init(&s, &p);
    double a = 0.05, R = 1.0;
    CHECK_REL(s.R, R, 1e-15, "centroid radius");
    CHECK(s.z_c == 0.0 && s.I_rz == 0.0 && s.angle == 0.0, "symmetric circle");
    CHECK_REL(s.area, PI * a * a, 1e-15, "A = pi a^2");
    CHECK_REL(s.I_rr, PI * pow(a, 4) / 4, 1e-15, "I_rr = pi a^4/4");
    CHECK_REL(s.I_zz, PI * pow(a, 4) / 4, 1e-15, "I_zz = pi a^4/4");
    CHECK_REL(s.J, PI * pow(a, 4) / 2, 1e-15, "J = pi a^4/2 (polar, exact for a circle)");
    CHECK_REL(s.shear_factor, 10.0 / 9.0, 1e-15, "shear factor 10/9");
    /* torus: int r dA = A R, int r^2 dA = A (R^2 + a^2/4), int r z^2 dA = R I_zz */
    CHECK_REL(s.S1, PI * a * a * R, 1e-15, "S1 = A R");
    CHECK_REL(s.S2, PI * a * a * (R * R + a * a / 4), 1e-15, "S2");
    CHECK_REL(s.Z, R * PI * pow(a, 4) / 4, 1e-15, "Z = R I_zz");
}

/* The faces against the bore, the box and the segment arcs of a built ring. */
static void test_faces(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_section s;
    rd_section_init(&s, &p);
    double b = p.radial_width, h = p.axial_height, d = p.diameter, g = p.closed_gap;
    CHECK_REL(s.run.r, d / 2, 1e-15, "running face on the bore");
    CHECK_REL(s.run.r - s.back.r, b, 1e-12, "running to back face: b");
    CHECK(s.run.d == 0.5 * b && s.back.d == -0.5 * b, "offsets from R");
    CHECK(s.run.height == h && s.back.height == h, "face heights h");
    CHECK(s.run.z_touch == 0.0 && s.back.z_touch == 0.0, "touch at mid-height");
    for (int k = -2; k <= 2; k++)
        CHECK(rd_section_face_profile(&s, 0.25 * k * h) == 0.0, "flat face at z = %g h", 0.25 * k);
    CHECK_REL(s.run.area_rad * 2 * PI, PI * d * h, 1e-15, "running face: pi d h per turn");
    const rd_section_flank *fl[2] = {&s.lower, &s.upper};
    for (int k = 0; k < 2; k++) {
        CHECK(fl[k]->r_in == s.back.r && fl[k]->r_out == s.run.r, "flank %d edges", k);
        CHECK(fl[k]->d_in == -0.5 * b && fl[k]->d_out == 0.5 * b, "flank %d offsets", k);
        CHECK_REL(fl[k]->width, fl[k]->r_out - fl[k]->r_in, 1e-12, "flank %d width", k);
        /* the annulus less the gap's share */
        double ann = PI * (fl[k]->r_out * fl[k]->r_out - fl[k]->r_in * fl[k]->r_in);
        CHECK_REL(fl[k]->area_ring, ann - g * b, 1e-13, "flank %d area over the ring", k);
    }
    /* the faces swept over the ring's segments: per-radian areas times the arcs */
    rd_error err;
    rd_error_init(&err);
    rd_ring *ring = rd_ring_create(&p, 24, 0, &err);
    CHECK(ring != NULL, "create: %s", err.message);
    if (!ring)
        return;
    const rd_section *rs = rd_ring_get_cross_section(ring);
    CHECK(same_section(rs, &s), "the ring's section is rd_section_init's");
    double flank = 0.0, run = 0.0, mass = 0.0;
    for (int i = 0; i < rd_ring_get_segments(ring); i++) {
        double phi = rd_ring_segment_phi_at(ring, i);
        flank += phi * 0.5 * (rs->lower.r_out * rs->lower.r_out - rs->lower.r_in * rs->lower.r_in);
        run += phi * rs->run.area_rad;
        mass += rd_ring_get_segment_mass(ring, i)->mass;
    }
    CHECK_REL(flank, rs->lower.area_ring, 1e-13, "segments' flank areas = the split ring's");
    CHECK_REL(run, h * (PI * d - g * d / (d - b)), 1e-13, "running face over the span");
    CHECK_REL(mass, p.density * h * rs->lower.area_ring, 1e-13, "mass = rho h (flank area)");
    rd_ring_free(ring);
}

/* rd_ring_section is the section's view: the same numbers, bit for bit. */
static void test_view(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    for (int closed = 0; closed < 2; closed++) {
        rd_error err;
        rd_error_init(&err);
        rd_ring *ring = rd_ring_create(&p, 12, closed, &err);
        CHECK(ring != NULL, "create: %s", err.message);
        if (!ring)
            return;
        rd_ring_section v;
        rd_ring_section_get(&p, closed, &v);
        const rd_ring_section *w = rd_ring_get_section(ring);
        const rd_section *s = rd_ring_get_cross_section(ring);
        CHECK(memcmp(&v, w, sizeof v) == 0, "rd_ring_section_get = rd_ring_get_section");
        CHECK(w->R == s->R && w->area == s->area && w->I_inplane == s->I_inplane &&
                  w->I_outplane == s->I_outplane && w->J == s->J &&
                  w->shear_factor == s->shear_factor,
              "view of the section (closed %d)", closed);
        CHECK_REL(w->span, closed ? 2 * PI : 2 * PI - p.closed_gap / s->R, 1e-15, "span");
        rd_ring_free(ring);
    }
}

int main(void)
{
    test_rectangle();
    test_circle();
    test_faces();
    test_view();
    return check_done();
}
