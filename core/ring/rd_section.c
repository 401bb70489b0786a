/*
 * rd_section — the cross-section's area properties and faces (rd_section.h),
 * the one place that turns rd_ring_params' b and h into geometry.
 *
 * Every expression below is the one its models used before they asked the
 * section (the same operations in the same order), so their answers are
 * unchanged bit for bit: R = 0.5 (d - b), the edges R -/+ 0.5 b, the areas
 * per radian height x radius.
 */
#include "rd_section.h"
#include "rd_ring.h"

#include <math.h>
#include <string.h>

/* M_PI is POSIX/XSI, not C11. */
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double rd_section_torsion_constant(double a, double c)
{
    /* J = a c^3 [1/3 - (64/pi^5)(c/a) sum_{k odd} tanh(k pi a / 2c) / k^5], a >= c. */
    if (a < c) {
        double t = a;
        a = c;
        c = t;
    }
    double sum = 0.0;
    for (int k = 1; k < 200; k += 2) {
        double term = tanh(k * M_PI * a / (2.0 * c)) / pow(k, 5);
        sum += term;
        if (term < 1e-17 * sum)
            break;
    }
    return a * c * c * c * (1.0 / 3.0 - 64.0 / pow(M_PI, 5) * (c / a) * sum);
}

/* Round wire of diameter b (radius a): a2 = int (r - R)^2 dA / A = a^2 / 4. */
static void circle(rd_section *s)
{
    double a = 0.5 * s->b, R = s->R;
    s->area = M_PI * a * a;
    s->I_rr = s->I_zz = M_PI * pow(a, 4) / 4.0;
    s->J = M_PI * pow(a, 4) / 2.0;
    s->shear_factor = s->shear_factor_axial = 10.0 / 9.0;
    double A = M_PI * a * a, a2 = a * a / 4.0;
    s->S1 = A * R;
    s->S2 = A * (R * R + a2);
    s->S3 = A * (R * R * R + 3.0 * R * a2);
    s->Z = R * A * a2;
}

/* The b x h rectangle from ri = R - b/2 to ro = R + b/2. */
static void rectangle(rd_section *s)
{
    double b = s->b, h = s->h, R = s->R;
    s->area = b * h;
    s->I_rr = h * b * b * b / 12.0;
    s->I_zz = b * h * h * h / 12.0;
    s->J = rd_section_torsion_constant(b, h);
    s->shear_factor = s->shear_factor_axial = 6.0 / 5.0;
    double ri = R - 0.5 * b, ro = R + 0.5 * b;
    s->S1 = h * (ro * ro - ri * ri) / 2.0;
    s->S2 = h * (ro * ro * ro - ri * ri * ri) / 3.0;
    s->S3 = h * (pow(ro, 4) - pow(ri, 4)) / 4.0;
    s->Z = (ro * ro - ri * ri) / 2.0 * h * h * h / 12.0;
}

/* int u^a v^b dA of the outline P (n points). */
#define MOM(a, b) rd_section_polygon_moment(P, n, (a), (b))

/* A general shape (rd_section_shape.c): its outline's moments in the box
 * frame (u from the inner edge at r_i = d/2 - b, v from the bottom), the
 * principal axes, and J computed once (p->spec) or now.  An outline the
 * validation refuses leaves the rectangle's numbers. */
static void general(rd_section *s, const rd_ring_params *p)
{
    double pts[RD_SECTION_POINTS_MAX][2];
    int n;
    if (rd_section_outline(p->section, &p->spec, s->b, s->h, pts, &n, NULL) != RD_OK) {
        rectangle(s);
        return;
    }
    const double(*P)[2] = (const double(*)[2])pts;
    double A = MOM(0, 0), Su = MOM(1, 0), Sv = MOM(0, 1), uc = Su / A, vc = Sv / A;
    double ri = 0.5 * p->diameter - s->b;
    s->area = A;
    s->r_c = uc;
    s->R = ri + uc;
    s->D = 2.0 * s->R;
    s->z_c = vc - 0.5 * s->h;
    s->I_rr = MOM(2, 0) - A * uc * uc;
    s->I_zz = MOM(0, 2) - A * vc * vc;
    s->I_rz = MOM(1, 1) - A * uc * vc;
    s->angle = rd_section_principal_angle(s->I_rr, s->I_zz, s->I_rz);
    double c = cos(s->angle), sn = sin(s->angle);
    s->I_inplane = s->I_rr * c * c + 2.0 * s->I_rz * sn * c + s->I_zz * sn * sn;
    s->I_outplane = s->I_rr * sn * sn - 2.0 * s->I_rz * sn * c + s->I_zz * c * c;
    s->J = p->spec.solved ? p->spec.J : NAN; /* rd_section_spec_solve's, once */
    double sf[2] = {p->spec.shear_factor, p->spec.shear_factor_axial};
    if (!p->spec.solved) /* rd_section_spec_solve's, once; else here */
        rd_section_shear_factors(P, n, sf);
    s->shear_factor = sf[0];
    s->shear_factor_axial = sf[1];
    double M20 = MOM(2, 0), M11 = MOM(1, 1);
    s->S1 = ri * A + Su;
    s->S2 = ri * ri * A + 2.0 * ri * Su + M20;
    s->S3 = ri * ri * ri * A + 3.0 * ri * ri * Su + 3.0 * ri * M20 + MOM(3, 0);
    s->Z = ri * s->I_zz + MOM(1, 2) - 2.0 * vc * M11 + vc * vc * Su;
}

/* The faces of the b x h box: running face outside, back face inside, both
 * touching at mid-height; flat flanks over the whole width. */
static void faces(rd_section *s, const rd_ring_params *p)
{
    double b = s->b, h = s->h, R = s->R;
    s->run = (rd_section_side){.height = h, .d = 0.5 * b, .r = R + 0.5 * b, .z_touch = 0.0};
    s->back = (rd_section_side){.height = h, .d = -0.5 * b, .r = R - 0.5 * b, .z_touch = 0.0};
    s->run.area_rad = s->run.height * s->run.r;
    s->back.area_rad = s->back.height * s->back.r;
    s->lower = (rd_section_flank){.d_in = -0.5 * b,
                                  .d_out = 0.5 * b,
                                  .r_in = R - 0.5 * b,
                                  .r_out = R + 0.5 * b,
                                  .width = b,
                                  .area_ring = b * (M_PI * (p->diameter - b) - p->closed_gap)};
    s->upper = s->lower;
}

/* A general shape's faces: those of its box, from the centroid at R. */
static void general_faces(rd_section *s, const rd_ring_params *p)
{
    double b = s->b, h = s->h, ro = 0.5 * p->diameter, ri = ro - b;
    s->run = (rd_section_side){.height = h, .d = ro - s->R, .r = ro, .z_touch = -s->z_c};
    s->back = (rd_section_side){.height = h, .d = ri - s->R, .r = ri, .z_touch = -s->z_c};
    s->run.area_rad = h * ro;
    s->back.area_rad = h * ri;
    s->lower = (rd_section_flank){.d_in = ri - s->R,
                                  .d_out = ro - s->R,
                                  .r_in = ri,
                                  .r_out = ro,
                                  .width = b,
                                  .area_ring = b * (M_PI * (ri + ro) - p->closed_gap)};
    s->upper = s->lower;
}

void rd_section_init(rd_section *s, const rd_ring_params *p)
{
    memset(s, 0, sizeof *s);
    s->shape = p->section;
    s->b = p->radial_width;
    s->h = p->axial_height;
    s->D = p->diameter - s->b;
    s->R = 0.5 * s->D;
    if (p->section >= RD_SECTION_TAPER_FACE) {
        general(s, p);
        general_faces(s, p);
        return;
    }
    if (p->section == RD_SECTION_CIRCLE)
        circle(s);
    else
        rectangle(s);
    /* symmetric shapes: centroid at mid-height, principal axes r and z */
    s->z_c = s->I_rz = s->angle = 0.0;
    s->r_c = 0.5 * s->b;
    s->I_inplane = s->I_rr;
    s->I_outplane = s->I_zz;
    faces(s, p);
}

double rd_section_face_profile(const rd_section *s, double z)
{
    (void)s;
    (void)z;
    return 0.0; /* flat running faces */
}
