/*
 * rd_section — the ring's cross-section: its area properties and the faces
 * the models put their contacts, loads and areas on, built once from the
 * ring's parameters.  Every core file but this one and the ring's validation
 * (rd_ring.c) asks the section, never rd_ring_params' radial_width b and
 * axial_height h (tests/lint/section_reads.py).
 *
 * Section frame: r radial (outward), z axial (up), origin at the centroid.
 * The reference radius R is the centroid's; the ring's reference points lie
 * on the circle of radius R in the plane z = 0 (rd_ring.h).
 *
 * Shapes today (enum rd_section_shape): the thesis' rectangle b x h and the
 * round wire of diameter b = h.  Both are symmetric about r and z through
 * the centroid, so the centroid sits at mid-height (z_c = 0), I_rz = 0 and
 * the principal axes are r and z (angle 0).  A circle's faces are those of
 * its bounding box (the lift and ring-pack analyses take rectangles only).
 *
 * Faces.  The running face (at the bore) and the back face (at the groove
 * back) are cylinders of radius r = R + d; each touches at axial position
 * z_touch (mid-height today), and the running face's profile is
 * rd_section_face_profile (flat today).  The lower and upper flanks are
 * annuli from r_in = R + d_in to r_out = R + d_out.  Areas "per radian" are
 * per radian of the ring's arc: a face over the angle phi has phi times it.
 *
 * Usage:
 *     rd_section s;
 *     rd_section_init(&s, &params);       // or rd_ring_get_cross_section(ring)
 *     double p0 = 2.0 * params.tangential_force / (params.diameter * s.run.height);
 *     double bore_area = s.run.area_rad * phi; // running face of a segment of angle phi
 *
 * rd_ring_section (rd_ring.h) is a view of it for the beam: the section's
 * area and moments with the material's G and the ring's span.
 */
#ifndef RD_SECTION_H
#define RD_SECTION_H

#include "rd_error.h"

struct rd_ring_params;

/* Cross-section shape.  The thesis ring is rectangular (b x h).  A circular
 * section (wire diameter b = h) serves round-wire rings and the NAFEMS
 * free-ring benchmark. */
enum rd_section_shape {
    RD_SECTION_RECTANGLE = 0,
    RD_SECTION_CIRCLE = 1,
    /* General shapes (ring.section objects), each a polygon inside the b x h
     * box (rd_section_outline); their properties are computed from it. */
    RD_SECTION_TAPER_FACE = 2,  /* the running face turned by angle_deg, its lower edge at b */
    RD_SECTION_INNER_BEVEL = 3, /* the inner top (bottom) corner cut: legs width x height */
    RD_SECTION_INNER_STEP = 4,  /* a width x height notch at the inner top (bottom) corner */
    RD_SECTION_KEYSTONE = 5,    /* the top (bottom; both if double_sided) flank turned by
                                   angle_deg, the section thinner inside */
    RD_SECTION_POLYGON = 6,     /* points: its bounding box is b x h */
    RD_SECTION_SHAPES           /* their count: a new shape goes above it */
};
#define RD_SECTION_POINTS_MAX 64

/* The fields of a general shape (rd_ring_params.spec); unused ones stay 0.
 * The Saint-Venant constant of a general shape is a numerical solution
 * (rd_section_torsion_polygon, 0.1-1 s): rd_section_spec_solve computes it
 * once into J and J_error, and rd_section_init reads it; unsolved, the
 * section's J is NAN (rd_ring_create solves its own copy of the params
 * then, so a beam always has it). */
typedef struct rd_section_spec {
    int side;                                /* 0 top, 1 bottom */
    double width, height;                    /* bevel's legs, step's depth and height, m */
    double angle_deg;                        /* taper, keystone */
    int double_sided;                        /* keystone on both flanks */
    int n_points;                            /* polygon: 3..RD_SECTION_POINTS_MAX */
    double points[RD_SECTION_POINTS_MAX][2]; /* polygon: (radial out, axial up), m */
    int solved;                              /* J, J_error and the shear factors below hold
                                                the shape's */
    double J, J_error;                       /* m^4: extrapolated, and its estimate */
    double shear_factor, shear_factor_axial; /* rd_section_shear_factors' */
} rd_section_spec;

/* A cylindrical face: the running face or the back face. */
typedef struct rd_section_side {
    double height;   /* axial height of the face, m (rectangle: h) */
    double d;        /* radial offset from R, m (running +b/2, back -b/2) */
    double r;        /* its radius R + d, m */
    double z_touch;  /* axial position where it touches (the bore, the groove
                      * back), from the centroid, m: 0 (mid-height) */
    double area_rad; /* area per radian of arc, height r, m^2/rad */
} rd_section_side;

/* A flank: the annulus between two radii. */
typedef struct rd_section_flank {
    double d_in, d_out; /* inner and outer edges' offsets from R, m (-b/2, +b/2) */
    double r_in, r_out; /* their radii R + d_in, R + d_out, m */
    double width;       /* radial width of the face, m (b) */
    double area_ring;   /* the face over the split ring of closed gap g, m^2: the annulus
                         * pi (r_out^2 - r_in^2) less the gap's share width g */
} rd_section_flank;

typedef struct rd_section {
    int shape;    /* enum rd_section_shape */
    double r_c;   /* general shapes: centroid's radial position from the inner edge, m */
    double b, h;  /* radial width and axial height of its bounding box, m */
    double D;     /* reference diameter d - b, m */
    double R;     /* reference radius: the centroid's, D / 2, m */
    double z_c;   /* axial offset of the centroid from mid-height, m: 0 */
    double area;  /* A, m^2 */
    double I_rr;  /* int (r - R)^2 dA, m^4: in-plane bending (rectangle h b^3 / 12) */
    double I_zz;  /* int (z - z_c)^2 dA, m^4: out-of-plane bending (rectangle b h^3 / 12) */
    double I_rz;  /* int (r - R)(z - z_c) dA, m^4: 0 for a symmetric section */
    double angle; /* principal angle from r to the in-plane principal axis, rad: 0 */
    double I_inplane, I_outplane; /* principal moments, m^4 (I_rr and I_zz at angle 0) */
    double J;                     /* Saint-Venant torsion constant, m^4 (rectangle: series; circle
                          * pi a^4 / 2), not the polar moment */
    double shear_factor;          /* shear form factor for the in-plane shear (along the in-plane
                                     principal axis, radial for symmetric shapes): 6/5 rectangle,
                                     10/9 circle (Tab. 3.1); a general shape's by the energy
                                     method on its outline (Jourawski's shear flow) */
    double shear_factor_axial;    /* the same for the out-of-plane (axial) shear */
    /* Moments about the ring axis, for the swept segment's mass (rd_ring.c):
     * S1 = int r dA (= A R), S2 = int r^2 dA, S3 = int r^3 dA, Z = int r z^2 dA. */
    double S1, S2, S3, Z;
    rd_section_side run, back;     /* running face (bore), back face (groove back) */
    rd_section_flank lower, upper; /* the flanks (alike for both shapes today) */
} rd_section;

/* Fills s from p's diameter, radial_width, axial_height, closed_gap and
 * section.  p should be valid (rd_ring_validate): any numbers give numbers,
 * but meaningful ones only then. */
void rd_section_init(rd_section *s, const struct rd_ring_params *p);

/* The running face's radial recess at axial position z (from the centroid),
 * m, inward positive, relative to where it touches: the face profile's
 * hook (a barrel or a taper face).  Flat faces: 0 for every z. */
double rd_section_face_profile(const rd_section *s, double z);

/* Saint-Venant torsion constant of a solid a x c rectangle (series solution). */
double rd_section_torsion_constant(double a, double c);

/* The outline of a general shape (shape = enum rd_section_shape >=
 * RD_SECTION_TAPER_FACE) with fields `spec` in the b x h box: its n points
 * (u radial from the inner edge, v axial from the bottom, m) written to
 * pts, counter-clockwise.  Checks the fields (paths relative to the ring's
 * block: "/section/..."):
 * side 0 or 1, a bevel's and a step's legs inside the box, angles that
 * leave a section, a polygon of 3..RD_SECTION_POINTS_MAX points that does
 * not cross itself, has an area, and whose bounding box is b x h (relative
 * 1e-9; any origin). */
int rd_section_outline(int shape, const rd_section_spec *spec, double b, double h, double (*pts)[2],
                       int *n, rd_error *err);

/* int_A u^a v^b dA of the polygon (counter-clockwise), exact (Green's
 * theorem, Gauss-Legendre on each edge), a + b <= 4. */
double rd_section_polygon_moment(const double (*pts)[2], int n, int a, int b);

/* Saint-Venant torsion constant of the polygon by finite elements: the
 * Prandtl stress function, -laplace phi = 2 in the section, phi = 0 on its
 * boundary, J = 2 int phi dA, on linear triangles (the polygon cut into
 * triangles, then each split in four `level` times), solved by conjugate
 * gradients.  The discrete J is below the exact one and rises with level,
 * its error ~ 4^-level (smooth solutions; slower at re-entrant corners).
 * RD_ENOMEM, RD_ENOCONV (the iteration), RD_EINVAL (not a simple polygon). */
int rd_section_torsion_polygon(const double (*pts)[2], int n, int level, double *J, rd_error *err);

/* J of a general shape from its three finest levels: the finest level
 * holding at most ~40000 triangles, Richardson-extrapolated as h^2 (J_L +
 * (J_L - J_{L-1}) / 3); J_error the change of that extrapolation from the
 * pair of levels below (measured: 15x the true error on the rectangle,
 * 6.3e-6 against 4e-7 of J, tests/core/test_section_shape.c). */
int rd_section_torsion_solve(const double (*pts)[2], int n, double *J, double *J_error,
                             rd_error *err);

/* Computes spec->J and J_error for shape `shape` in the b x h box once
 * (rd_section_spec's contract); the outline's errors otherwise. */
int rd_section_spec_solve(int shape, rd_section_spec *spec, double b, double h, rd_error *err);

/* The principal angle from the moments (rd_section.angle's rule). */
double rd_section_principal_angle(double I_rr, double I_zz, double I_rz);
/* The energy method's shear form factors of the polygon P (n points) for
 * shear along its in-plane and its out-of-plane principal axis, into out
 * (rd_section.shear_factor, shear_factor_axial): kappa = A / I^2 int
 * S(w)^2 / t(w) dw over the lines w = const across it (Jourawski's shear
 * flow), by the midpoint rule on 4000 lines; 0.1-0.4 ms, so computed once
 * (rd_section_spec_solve). */
void rd_section_shear_factors(const double (*P)[2], int n, double out[2]);

#endif
