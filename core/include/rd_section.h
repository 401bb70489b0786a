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

struct rd_ring_params;

/* Cross-section shape.  The thesis ring is rectangular (b x h).  A circular
 * section (wire diameter b = h) serves round-wire rings and the NAFEMS
 * free-ring benchmark. */
enum rd_section_shape {
    RD_SECTION_RECTANGLE = 0,
    RD_SECTION_CIRCLE = 1,
    RD_SECTION_SHAPES /* their count: a new shape goes above it */
};

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
    double shear_factor;          /* shear form factor: 6/5 rectangle, 10/9 circle (Tab. 3.1) */
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

#endif
