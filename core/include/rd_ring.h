/*
 * rd_ring — the discretized piston ring (thesis ch. 3.1-3.2).
 *
 * Geometry (SI units).  Section (rd_section.h): radial width b, axial height h;
 * nominal diameter d (= bore), closed gap g.  Centroid radius R = (d - b)/2.
 * The split ring spans the arc 2*pi - g/R of the centroid circle, centred on
 * the angle opposite the gap: angle 0 is the middle of the gap, segments run
 * from g/(2R) to 2*pi - g/(2R).  A `closed` ring joins the gap (g is ignored,
 * the ring spans 2*pi and the last segment is joined to the first).
 *
 * Global frame: z is the ring axis (cylinder axis, up), the ring lies in the
 * z = 0 plane with its centre at the origin, angle theta measured from +x.
 *
 * The ring is cut into n rigid segments (annular sectors), equal unless
 * graded (rd_ring_create_graded, rd_internal.h: the contact analysis'
 * local refinement gives each its own angle, each joint its own beam
 * along its chord and each segment its own sector's mass).  Segment i
 * has a reference point P_i on the centroid circle at its mid-angle; its six
 * degrees of freedom are the small translation of P_i and the small rotation
 * vector of the segment, global components:
 *     q[6i + 0..2] = (ux, uy, uz),  q[6i + 3..5] = (rx, ry, rz).
 * Neighbouring segments are joined by a Timoshenko beam spring (thesis 3.15)
 * spanning the chord P_i -> P_{i+1}.
 */
#ifndef RD_RING_H
#define RD_RING_H

#include "rd_error.h"
#include "rd_section.h"

/* Ring definition as the user gives it.  Plain struct, caller-owned. */
typedef struct rd_ring_params {
    double diameter;         /* d, m: nominal (= bore) diameter */
    double radial_width;     /* b, m */
    double axial_height;     /* h, m */
    double closed_gap;       /* g, m: gap in the closed (installed) state */
    double tangential_force; /* F_t, N: pretension force */
    double youngs_modulus;   /* E, Pa */
    double poisson_ratio;    /* nu, - */
    double density;          /* rho, kg/m^3 */
    int section;             /* enum rd_section_shape; default rectangle */
    rd_section_spec spec;    /* a general shape's fields (rd_section.h) */
} rd_ring_params;

/* Allowed ranges, shared by validation and documentation. */
#define RD_SEGMENTS_MIN 3
#define RD_SEGMENTS_MAX 2000

/* The beam's constants: a view of the ring's rd_section (its area and
 * moments) with the material's G and the ring's span.  Geometry (faces,
 * radii, areas) is the rd_section's: rd_ring_get_cross_section. */
typedef struct rd_ring_section {
    double R;            /* centroid radius, m */
    double area;         /* A = b h */
    double I_inplane;    /* I about the axial direction: h b^3 / 12 (in-plane bending) */
    double I_outplane;   /* I about the radial direction: b h^3 / 12 (out-of-plane bending) */
    double J;            /* Saint-Venant torsion constant (rectangle: series; circle: pi a^4/2) */
    double G;            /* shear modulus E / (2 (1 + nu)) */
    double shear_factor; /* form factor for shear: 6/5 rectangle, 10/9 circle (Tab. 3.1) */
    double shear_factor_axial; /* the same for the out-of-plane shear (rd_section.h) */
    double span;               /* angle covered by the ring, rad */
    double angle;              /* principal axes turned from r toward z, rad (rd_section.h); 0 for
                            the rectangle and the circle */
} rd_ring_section;

/* Mass properties of one rigid segment, in the segment's local cylindrical
 * frame at its mid-angle (e_r radial outward, e_t tangential, e_z axial). */
typedef struct rd_segment_mass {
    double mass;             /* kg */
    double com_radius;       /* radius of the centre of mass, m */
    double I_rr, I_tt, I_zz; /* principal moments about the centre of mass, kg m^2 */
} rd_segment_mass;

/* Fills `p` with the thesis ring: d 76.5 mm, b 2.9 mm, h 1.2 mm, g 0.3 mm,
 * F_t 10 N, steel E 210 GPa, nu 0.3, rho 7850 kg/m^3. */
void rd_ring_params_default(rd_ring_params *p);

/* Checks every parameter (finite, in range); paths relative to the ring's
 * block ("/diameter", "/material/density": rd_error.h).  Returns RD_OK or
 * RD_EINVAL. */
int rd_ring_validate(const rd_ring_params *p, int closed, rd_error *err);
/* The segment count, RD_SEGMENTS_MIN..RD_SEGMENTS_MAX (RD_ELIMIT above);
 * path relative to the discretization block ("/segments"). */
int rd_segments_validate(int segments, rd_error *err);
/* Both, for a scene whose ring is at /ring and whose segments are at
 * /discretization/segments, relative to the scene's root. */
int rd_ring_scene_validate(const rd_ring_params *p, int segments, int closed, rd_error *err);

/* The beam's constants of p's section, without a ring (the ring's own copy:
 * rd_ring_get_section); p must be valid. */
void rd_ring_section_get(const rd_ring_params *p, int closed, rd_ring_section *out);

/* Exact mass properties of one segment: the section of `p` swept about the
 * ring axis through the angle phi (an annular sector for a rectangle, a torus
 * sector for a circle). */
void rd_ring_segment_mass_get(const rd_ring_params *p, double phi, rd_segment_mass *out);

/* The assembled model: opaque. */
typedef struct rd_ring rd_ring;

/* Builds the n-segment model.  Validates first (rd_ring_scene_validate: its
 * paths relative to a scene with the ring at /ring).  Returns NULL and fills
 * err on failure.  Free with rd_ring_free (NULL is a no-op). */
rd_ring *rd_ring_create(const rd_ring_params *p, int segments, int closed, rd_error *err);
void rd_ring_free(rd_ring *ring);

int rd_ring_get_segments(const rd_ring *ring);
int rd_ring_get_dof(const rd_ring *ring); /* 6 n */
int rd_ring_is_closed(const rd_ring *ring);
const rd_ring_params *rd_ring_get_params(const rd_ring *ring);
const rd_ring_section *rd_ring_get_section(const rd_ring *ring);
/* The ring's cross-section (rd_section.h), built once with the ring. */
const rd_section *rd_ring_get_cross_section(const rd_ring *ring);
/* Mid-angle of segment i, rad, measured from the middle of the gap. */
double rd_ring_get_segment_angle(const rd_ring *ring, int i);
/* Mass properties of segment i (all equal, kept per segment for clarity). */
const rd_segment_mass *rd_ring_get_segment_mass(const rd_ring *ring, int i);

/* Number of joints: n - 1 for a split ring, n for a closed one. */
int rd_ring_get_joints(const rd_ring *ring);

/* Dense global matrices (6n x 6n, column-major, caller-allocated, n <= 500).
 * For tests and small problems; the solvers use banded storage internally. */
int rd_ring_assemble_dense(const rd_ring *ring, double *K, double *M, rd_error *err);

/* Strain energy 1/2 q^T K q and kinetic energy 1/2 v^T M v, evaluated element
 * by element (no assembled matrix). */
double rd_ring_strain_energy(const rd_ring *ring, const double *q);
double rd_ring_kinetic_energy(const rd_ring *ring, const double *v);

/* Rigid-body motion: fills q (6n) with the translation t and small rotation w
 * about the origin: u_i = t + w x P_i, r_i = w. */
void rd_ring_rigid_motion(const rd_ring *ring, const double t[3], const double w[3], double *q);

#endif
