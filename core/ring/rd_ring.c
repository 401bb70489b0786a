/*
 * rd_ring — the beam's section constants (a view of rd_section.c's), segment
 * mass properties and the global stiffness and mass matrices of the
 * segmented ring (thesis 3.1-3.2).
 *
 * Joint stiffness.  Neighbouring segments i, i+1 with reference points P_i,
 * P_{i+1} on the centroid circle are joined by a straight Timoshenko beam of
 * length L = |P_{i+1} - P_i| (the chord).  Local frame: e1 along the chord,
 * e2 = global z (axial), e3 = e1 x e2 (radial, outward).  With end A clamped,
 * the tip B obeys the cantilever relation (thesis 3.15, our axes)
 *
 *   [F1]   [EA/L                                              ] [d1]
 *   [F2]   [     12EIo/(L^3(1+Po))                -6EIo/(L^2(1+Po))] [d2]
 *   [F3] = [          12EIi/(L^3(1+Pi))  6EIi/(L^2(1+Pi))     ] [d3]
 *   [M1]   [                 GJ/L                              ] [t1]
 *   [M2]   [         sym.       (4+Pi)EIi/(L(1+Pi))           ] [t2]
 *   [M3]   [                                 (4+Po)EIo/(L(1+Po))] [t3]
 *
 * where Io = b h^3/12 (out-of-plane bending, deflection d2 along the axis),
 * Ii = h b^3/12 (in-plane bending, deflection d3 radial), P = 12 E I f_s /
 * (G A L^2) the shear parameter (3.3, 3.11), f_s the shear form factor
 * (Tab. 3.1) and J the Saint-Venant torsion constant (3.31, not the polar
 * moment).  The relative motion of B seen from A's frame is
 *
 *   d = u_B - u_A - theta_A x (P_B - P_A),   t = theta_B - theta_A,
 *
 * so the joint's strain energy is 1/2 [d;t]^T Kc [d;t] (local components) and
 * its 12x12 stiffness is T^T Kc T: for small motions exactly a straight
 * Timoshenko beam element between the two reference points.  A rigid motion
 * gives d = t = 0, so K has the six rigid-body modes in its null space.
 *
 * Mass.  Each segment is the section swept through phi = span/n (graded:
 * its own phi_i) about the ring axis; its mass, centre of mass and inertia tensor are integrated
 * exactly.  With DOFs (u, theta) at the reference point P and the centre of
 * mass at P + c:  v_com = u' - [c]x theta', hence
 *   M_i = [[ m I,  -m [c]x ], [ m [c]x,  I_com - m [c]x [c]x ]].
 */
#include "rd_ring.h"
#include "rd_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct rd_ring {
    rd_ring_params p;
    rd_section sec;    /* the cross-section */
    rd_ring_section s; /* its view for the beam */
    int n, closed, joints, graded;
    double phi;            /* mean segment angle span / n, rad (every segment's unless graded) */
    double *phis;          /* n segment angles, rad */
    double *alpha;         /* n mid-angles from the gap middle, rad */
    double *P;             /* 3n reference points */
    rd_segment_mass *mass; /* n */
    double *Mseg;          /* n x 36, row-major per segment */
    double *Kc;            /* joints x 36: each joint's local cantilever stiffness, row-major */
    double *T;             /* joints x (6 x 12) transfer matrices, local components */
    int *pos;              /* band position of each segment */
};

#define M6(A, r, c) ((A)[6 * (r) + (c)])

void rd_ring_params_default(rd_ring_params *p)
{
    p->diameter = 0.0765;
    p->radial_width = 0.0029;
    p->axial_height = 0.0012;
    p->closed_gap = 0.0003;
    p->tangential_force = 10.0;
    p->youngs_modulus = 2.1e11;
    p->poisson_ratio = 0.3;
    p->density = 7850.0;
    p->section = RD_SECTION_RECTANGLE;
}

int rd_ring_validate(const rd_ring_params *p, int closed, rd_error *err)
{
    int rc = RD_OK;
    if ((rc = rd_error_range(p->diameter, 1e-3, 5.0, "/diameter", "m", err)))
        return rc;
    if ((rc = rd_error_range(p->radial_width, 1e-5, 0.25 * p->diameter, "/radial_width",
                             "m (at most a quarter of the diameter)", err)))
        return rc;
    if ((rc = rd_error_range(p->axial_height, 1e-5, 0.5 * p->diameter, "/axial_height",
                             "m (at most half the diameter)", err)))
        return rc;
    double ratio = p->radial_width / p->axial_height;
    if (ratio < 0.05 || ratio > 20.0)
        return rd_error_set(err, RD_EINVAL, "/axial_height",
                            "@/axial_height = %g m gives a width/height ratio b/h = %g; "
                            "allowed 0.05 to 20.",
                            p->axial_height, ratio);
    if (p->section < 0 || p->section >= RD_SECTION_SHAPES)
        return rd_error_set(err, RD_EINVAL, "/section", "unknown section shape %d.", p->section);
    if (p->section == RD_SECTION_CIRCLE && p->radial_width != p->axial_height)
        return rd_error_set(err, RD_EINVAL, "/axial_height",
                            "a circular section needs axial_height = radial_width (the wire "
                            "diameter); got %g m and %g m.",
                            p->axial_height, p->radial_width);
    if (p->section >= RD_SECTION_TAPER_FACE) {
        double pts[RD_SECTION_POINTS_MAX][2];
        int n;
        if ((rc = rd_section_outline(p->section, &p->spec, p->radial_width, p->axial_height, pts,
                                     &n, err)))
            return rc;
    }
    if (!closed && (rc = rd_error_range(p->closed_gap, 0.0, 0.1 * M_PI * p->diameter, "/closed_gap",
                                        "m (at most 10 % of the circumference)", err)))
        return rc;
    if ((rc = rd_error_range(p->tangential_force, 0.0, 1e5, "/tangential_force", "N", err)))
        return rc;
    if ((rc = rd_error_range(p->youngs_modulus, 1e6, 1e15, "/material/youngs_modulus", "Pa", err)))
        return rc;
    if (!isfinite(p->poisson_ratio) || p->poisson_ratio <= -1.0 || p->poisson_ratio >= 0.5)
        return rd_error_set(err, RD_EINVAL, "/material/poisson_ratio",
                            "@/material/poisson_ratio = %g is out of range: allowed "
                            "-1 < nu < 0.5.",
                            p->poisson_ratio);
    if ((rc = rd_error_range(p->density, 0.1, 1e7, "/material/density", "kg/m^3", err)))
        return rc;
    return RD_OK;
}

int rd_segments_validate(int segments, rd_error *err)
{
    if (segments < RD_SEGMENTS_MIN || segments > RD_SEGMENTS_MAX)
        return rd_error_set(err, segments > RD_SEGMENTS_MAX ? RD_ELIMIT : RD_EINVAL, "/segments",
                            "@/segments = %d is out of range: allowed %d to %d.", segments,
                            RD_SEGMENTS_MIN, RD_SEGMENTS_MAX);
    return RD_OK;
}

int rd_ring_scene_validate(const rd_ring_params *p, int segments, int closed, rd_error *err)
{
    size_t m = rd_error_enter(err, "/ring");
    int rc = rd_ring_validate(p, closed, err);
    rd_error_leave(err, m);
    if (rc)
        return rc;
    m = rd_error_enter(err, "/discretization");
    rc = rd_segments_validate(segments, err);
    rd_error_leave(err, m);
    return rc;
}

/* The beam's constants: the section's area and moments, G, the span. */
static void section_view(const rd_section *sec, const rd_ring_params *p, int closed,
                         rd_ring_section *s)
{
    s->R = sec->R;
    s->G = p->youngs_modulus / (2.0 * (1.0 + p->poisson_ratio));
    s->area = sec->area;
    s->I_inplane = sec->I_inplane;
    s->I_outplane = sec->I_outplane;
    s->J = sec->J;
    s->shear_factor = sec->shear_factor;
    s->shear_factor_axial = sec->shear_factor_axial;
    s->angle = sec->angle;
    s->span = closed ? 2.0 * M_PI : 2.0 * M_PI - p->closed_gap / s->R;
}

void rd_ring_section_get(const rd_ring_params *p, int closed, rd_ring_section *s)
{
    rd_section sec;
    rd_section_init(&sec, p);
    section_view(&sec, p, closed, s);
}

double rd_ring_conformability(const rd_ring_params *p)
{
    rd_section s;
    rd_section_init(&s, p);
    double db = s.D;
    return p->tangential_force * db * db / (4.0 * p->youngs_modulus * s.I_inplane);
}

double rd_ring_free_gap_formula(const rd_ring_params *p)
{
    /* (1.5): k = 2/(3 pi) m/(d - b), m the opening beyond the closed gap */
    rd_section s;
    rd_section_init(&s, p);
    double m = 1.5 * M_PI * rd_ring_conformability(p) * s.D;
    return p->closed_gap + m;
}

/* (phi - sin phi) / 2 without cancellation for small phi. */
static double half_phi_minus_sin(double phi)
{
    if (phi < 1e-2) {
        double p2 = phi * phi;
        return 0.5 * phi * p2 / 6.0 * (1.0 - p2 / 20.0 * (1.0 - p2 / 42.0));
    }
    return 0.5 * (phi - sin(phi));
}

/* The section swept about the ring axis through phi (density rho). */
static void sweep_mass(const rd_section *sec, double rho, double phi, rd_segment_mass *out)
{
    /* Section moments about the ring axis (r radial coordinate, z axial):
     * S1 = int r dA, S2 = int r^2 dA, S3 = int r^3 dA, Z = int r z^2 dA.
     * Sweeping through psi in [-phi/2, phi/2] (x radial at the mid-angle):
     * m = rho phi S1, int x dm = 2 rho S2 sin(phi/2),
     * int x^2 dm = rho S3 (phi + sin phi)/2, int y^2 dm = rho S3 (phi - sin phi)/2,
     * int z^2 dm = rho phi Z. */
    double S1 = sec->S1, S2 = sec->S2, S3 = sec->S3, Z = sec->Z;
    double m = rho * phi * S1;
    double xx = rho * S3 * (phi - half_phi_minus_sin(phi)); /* (phi + sin phi)/2 */
    double yy = rho * S3 * half_phi_minus_sin(phi);
    double zz = rho * phi * Z;
    double rc = 2.0 * rho * S2 * sin(0.5 * phi) / m;
    out->mass = m;
    out->com_radius = rc;
    out->I_rr = yy + zz;               /* about the radial axis through the COM */
    out->I_tt = xx + zz - m * rc * rc; /* parallel-axis shift by rc */
    out->I_zz = xx + yy - m * rc * rc;
}

void rd_ring_segment_mass_get(const rd_ring_params *p, double phi, rd_segment_mass *out)
{
    rd_section sec;
    rd_section_init(&sec, p);
    sweep_mass(&sec, p->density, phi, out);
}

/* out = [v]x, the cross-product matrix (row-major 3x3). */
static void skew(const double v[3], double out[9])
{
    out[0] = 0;
    out[1] = -v[2];
    out[2] = v[1];
    out[3] = v[2];
    out[4] = 0;
    out[5] = -v[0];
    out[6] = -v[1];
    out[7] = v[0];
    out[8] = 0;
}

/* Kc of a section whose principal axes are turned by `a` from the radial
 * one toward +z (rd_section.h): the in-plane principal axis p1 = cos a e_r
 * + sin a e_z, the other p2 = -sin a e_r + cos a e_z.  With T the turn about
 * the chord x taking the local (y axial, z radial outward: e3 = e1 x e2)
 * components to the principal ones (y' = v.p2 = cos a y - sin a z,
 * z' = v.p1 = sin a y + cos a z), Kc := T6^T Kc T6, T6 = diag(T, T).  The
 * bending block about (axial, radial) is then E/L [[I_rr, -I_rz], [-I_rz,
 * I_zz]] up to the cantilever's factors: a rotation theta moves the section
 * point (r', z') along the chord by theta_z r' - theta_r z'.  (Before
 * 0.3.16 T turned by -a, as if z were radial inward: every turned section
 * was solved mirrored about its mid-height; tests/core/test_free_shape.c
 * checks the sign now.)  The rectangle and the circle (a = 0) skip it. */
static void turn_principal(double Kc[36], double a)
{
    double T[36] = {0}, W[36] = {0}, c = cos(a), s = -sin(a);
    for (int b = 0; b < 2; b++) {
        int o = 3 * b;
        M6(T, o, o) = 1.0;
        M6(T, o + 1, o + 1) = c, M6(T, o + 1, o + 2) = s;
        M6(T, o + 2, o + 1) = -s, M6(T, o + 2, o + 2) = c;
    }
    for (int r = 0; r < 6; r++) /* W = Kc T */
        for (int q = 0; q < 6; q++)
            for (int k = 0; k < 6; k++)
                M6(W, r, q) += M6(Kc, r, k) * M6(T, k, q);
    for (int r = 0; r < 6; r++) /* Kc = T^T W */
        for (int q = 0; q < 6; q++) {
            double v = 0.0;
            for (int k = 0; k < 6; k++)
                v += M6(T, k, r) * M6(W, k, q);
            M6(Kc, r, q) = v;
        }
}

static void cantilever_stiffness(const rd_ring_params *p, const rd_ring_section *s, double L,
                                 double Kc[36])
{
    double E = p->youngs_modulus, G = s->G, A = s->area;
    double Io = s->I_outplane, Ii = s->I_inplane;
    double Po = 12.0 * E * Io * s->shear_factor_axial / (G * A * L * L);
    double Pi = 12.0 * E * Ii * s->shear_factor / (G * A * L * L);
    memset(Kc, 0, 36 * sizeof *Kc);
    M6(Kc, 0, 0) = E * A / L;
    M6(Kc, 1, 1) = 12.0 * E * Io / (L * L * L * (1.0 + Po));
    M6(Kc, 1, 5) = M6(Kc, 5, 1) = -6.0 * E * Io / (L * L * (1.0 + Po));
    M6(Kc, 5, 5) = (4.0 + Po) * E * Io / (L * (1.0 + Po));
    M6(Kc, 2, 2) = 12.0 * E * Ii / (L * L * L * (1.0 + Pi));
    M6(Kc, 2, 4) = M6(Kc, 4, 2) = 6.0 * E * Ii / (L * L * (1.0 + Pi));
    M6(Kc, 4, 4) = (4.0 + Pi) * E * Ii / (L * (1.0 + Pi));
    M6(Kc, 3, 3) = G * s->J / L;
    if (s->angle != 0.0)
        turn_principal(Kc, s->angle);
}

void rd_ring_segment_frame(const rd_ring *ring, int i, double e_r[3], double e_t[3])
{
    double a = ring->alpha[i];
    e_r[0] = cos(a);
    e_r[1] = sin(a);
    e_r[2] = 0.0;
    e_t[0] = -sin(a);
    e_t[1] = cos(a);
    e_t[2] = 0.0;
}

/* Segment mass matrix (global components, DOFs at P_i). */
static void segment_mass_matrix(const rd_ring *ring, int i, double Ms[36])
{
    const rd_segment_mass *sm = &ring->mass[i];
    double e_r[3], e_t[3], e_z[3] = {0, 0, 1};
    rd_ring_segment_frame(ring, i, e_r, e_t);
    double c[3], S[9], Ic[9];
    for (int k = 0; k < 3; k++)
        c[k] = (sm->com_radius - ring->s.R) * e_r[k];
    skew(c, S);
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            Ic[3 * r + q] = sm->I_rr * e_r[r] * e_r[q] + sm->I_tt * e_t[r] * e_t[q] +
                            sm->I_zz * e_z[r] * e_z[q];
    memset(Ms, 0, 36 * sizeof *Ms);
    for (int r = 0; r < 3; r++) {
        M6(Ms, r, r) = sm->mass;
        for (int q = 0; q < 3; q++) {
            M6(Ms, r, 3 + q) = -sm->mass * S[3 * r + q];
            M6(Ms, 3 + r, q) = sm->mass * S[3 * r + q];
            double SS = 0.0;
            for (int k = 0; k < 3; k++)
                SS += S[3 * r + k] * S[3 * k + q];
            M6(Ms, 3 + r, 3 + q) = Ic[3 * r + q] - sm->mass * SS;
        }
    }
}

/* Transfer matrix T (6x12, row-major, local components) of joint j:
 * [d; t] = T [q_A; q_B]. */
static void joint_transfer(const rd_ring *ring, int a, int b, double T[72])
{
    const double *PA = ring->P + 3 * a, *PB = ring->P + 3 * b;
    double dP[3] = {PB[0] - PA[0], PB[1] - PA[1], PB[2] - PA[2]};
    double L = sqrt(dP[0] * dP[0] + dP[1] * dP[1] + dP[2] * dP[2]);
    double e1[3] = {dP[0] / L, dP[1] / L, dP[2] / L}, e2[3] = {0, 0, 1};
    double e3[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0]};
    const double *E[3] = {e1, e2, e3};
    double S[9];
    skew(dP, S);
    /* global: d = -u_A + [dP]x th_A + u_B, t = -th_A + th_B; local rows = e_k . (...) */
    memset(T, 0, 72 * sizeof *T);
    for (int k = 0; k < 3; k++) {
        for (int q = 0; q < 3; q++) {
            double SE = 0.0;
            for (int r = 0; r < 3; r++)
                SE += E[k][r] * S[3 * r + q];
            T[12 * k + q] = -E[k][q];
            T[12 * k + 3 + q] = SE;
            T[12 * k + 6 + q] = E[k][q];
            T[12 * (3 + k) + 3 + q] = -E[k][q];
            T[12 * (3 + k) + 9 + q] = E[k][q];
        }
    }
}

static void joint_ends(const rd_ring *ring, int j, int *a, int *b)
{
    *a = j;
    *b = (j + 1) % ring->n;
}

rd_ring *rd_ring_create(const rd_ring_params *p, int segments, int closed, rd_error *err)
{
    return rd_ring_create_graded(p, segments, closed, NULL, err);
}

/* The ring's copy of p, with a general section's J computed here unless
 * the caller did (rd_section_spec_solve). */
static int own_params(rd_ring *ring, const rd_ring_params *p, rd_error *err)
{
    ring->p = *p;
    if (p->section < RD_SECTION_TAPER_FACE || p->spec.solved)
        return RD_OK;
    rd_section box; /* its b and h (J not yet) */
    rd_section_init(&box, p);
    size_t m = rd_error_enter(err, "/ring");
    int rc = rd_section_spec_solve(p->section, &ring->p.spec, box.b, box.h, err);
    rd_error_leave(err, m);
    return rc;
}

rd_ring *rd_ring_create_graded(const rd_ring_params *p, int segments, int closed,
                               const double *weights, rd_error *err)
{
    rd_ring *ring = NULL;
    if (rd_ring_scene_validate(p, segments, closed, err) != RD_OK)
        return NULL;
    int n = segments;
    ring = calloc(1, sizeof *ring);
    if (!ring)
        goto nomem;
    if (own_params(ring, p, err) != RD_OK) {
        free(ring);
        return NULL;
    }
    p = &ring->p;
    ring->n = n;
    ring->closed = closed ? 1 : 0;
    ring->joints = closed ? n : n - 1;
    rd_section_init(&ring->sec, p);
    section_view(&ring->sec, p, ring->closed, &ring->s);
    ring->phi = ring->s.span / n;
    ring->phis = malloc((size_t)n * sizeof *ring->phis);
    ring->alpha = malloc((size_t)n * sizeof *ring->alpha);
    ring->P = malloc((size_t)n * 3 * sizeof *ring->P);
    ring->mass = malloc((size_t)n * sizeof *ring->mass);
    ring->Mseg = malloc((size_t)n * 36 * sizeof *ring->Mseg);
    ring->Kc = malloc((size_t)(ring->joints > 0 ? ring->joints : 1) * 36 * sizeof *ring->Kc);
    ring->T = malloc((size_t)ring->joints * 72 * sizeof *ring->T);
    ring->pos = malloc((size_t)n * sizeof *ring->pos);
    if (!ring->phis || !ring->alpha || !ring->P || !ring->mass || !ring->Mseg || !ring->Kc ||
        !ring->T || !ring->pos)
        goto nomem;

    /* the segments' angles: equal, or span-scaled weights (their sum) */
    double start = closed ? 0.0 : 0.5 * p->closed_gap / ring->s.R, wsum = 0.0, at = 0.0;
    for (int i = 0; weights && i < n; i++)
        wsum += weights[i];
    ring->graded = weights != NULL;
    for (int i = 0; i < n; i++) {
        if (weights) {
            ring->phis[i] = ring->s.span * weights[i] / wsum;
            ring->alpha[i] = start + at + 0.5 * ring->phis[i];
            at += ring->phis[i];
        } else {
            ring->phis[i] = ring->phi;
            ring->alpha[i] = start + (i + 0.5) * ring->phi;
        }
        ring->P[3 * i + 0] = ring->s.R * cos(ring->alpha[i]);
        ring->P[3 * i + 1] = ring->s.R * sin(ring->alpha[i]);
        ring->P[3 * i + 2] = 0.0;
    }
    for (int i = 0; i < n; i++) {
        if (i == 0 || ring->phis[i] != ring->phis[i - 1])
            sweep_mass(&ring->sec, p->density, ring->phis[i], &ring->mass[i]);
        else
            ring->mass[i] = ring->mass[i - 1];
        segment_mass_matrix(ring, i, ring->Mseg + 36 * i);
    }
    for (int j = 0; j < ring->joints; j++) {
        int a, b;
        joint_ends(ring, j, &a, &b);
        joint_transfer(ring, a, b, ring->T + 72 * j);
        /* the chord between the two segments' reference points */
        double d = 0.5 * (ring->phis[a] + ring->phis[b]);
        if (j > 0 && ring->phis[a] == ring->phis[a - 1] && ring->phis[b] == ring->phis[a])
            memcpy(ring->Kc + 36 * j, ring->Kc + 36 * (j - 1), 36 * sizeof *ring->Kc);
        else
            cantilever_stiffness(p, &ring->s, 2.0 * ring->s.R * sin(0.5 * d), ring->Kc + 36 * j);
    }
    for (int k = 0; k < n; k++) {
        int seg = closed ? (k % 2 == 0 ? k / 2 : n - 1 - (k - 1) / 2) : k;
        ring->pos[seg] = k;
    }
    return ring;
nomem:
    rd_ring_free(ring);
    rd_error_set(err, RD_ENOMEM, "", "Out of memory building a %d-segment ring.", segments);
    return NULL;
}

void rd_ring_free(rd_ring *ring)
{
    if (!ring)
        return;
    free(ring->phis);
    free(ring->alpha);
    free(ring->P);
    free(ring->mass);
    free(ring->Mseg);
    free(ring->Kc);
    free(ring->T);
    free(ring->pos);
    free(ring);
}

int rd_ring_get_segments(const rd_ring *ring)
{
    return ring->n;
}
int rd_ring_get_dof(const rd_ring *ring)
{
    return 6 * ring->n;
}
int rd_ring_is_closed(const rd_ring *ring)
{
    return ring->closed;
}
int rd_ring_get_joints(const rd_ring *ring)
{
    return ring->joints;
}
const rd_ring_params *rd_ring_get_params(const rd_ring *ring)
{
    return &ring->p;
}
const rd_ring_section *rd_ring_get_section(const rd_ring *ring)
{
    return &ring->s;
}
const rd_section *rd_ring_get_cross_section(const rd_ring *ring)
{
    return &ring->sec;
}
double rd_ring_get_segment_angle(const rd_ring *ring, int i)
{
    return ring->alpha[i];
}
const rd_segment_mass *rd_ring_get_segment_mass(const rd_ring *ring, int i)
{
    return &ring->mass[i];
}
const double *rd_ring_segment_mass_matrix(const rd_ring *ring, int i)
{
    return ring->Mseg + 36 * i;
}

const double *rd_ring_reference_point(const rd_ring *ring, int i)
{
    return ring->P + 3 * i;
}
const double *rd_ring_joint_stiffness(const rd_ring *ring, int j)
{
    return ring->Kc + 36 * j;
}
double rd_ring_segment_phi(const rd_ring *ring)
{
    return ring->phi;
}
int rd_ring_is_graded(const rd_ring *ring)
{
    return ring->graded;
}
double rd_ring_segment_phi_at(const rd_ring *ring, int i)
{
    return ring->phis[i];
}

int rd_ring_band_index(const rd_ring *ring, int i, int k)
{
    return 6 * ring->pos[i] + k;
}
int rd_ring_band_kd(const rd_ring *ring)
{
    return ring->closed ? 17 : 11;
}

/* Ke = T^T Kc T (12x12, row-major) for joint j. */
static void joint_stiffness(const rd_ring *ring, int j, double Ke[144])
{
    const double *T = ring->T + 72 * j;
    double KT[72];
    for (int r = 0; r < 6; r++)
        for (int c = 0; c < 12; c++) {
            double s = 0.0;
            for (int k = 0; k < 6; k++)
                s += ring->Kc[36 * j + 6 * r + k] * T[12 * k + c];
            KT[12 * r + c] = s;
        }
    for (int r = 0; r < 12; r++)
        for (int c = 0; c < 12; c++) {
            double s = 0.0;
            for (int k = 0; k < 6; k++)
                s += T[12 * k + r] * KT[12 * k + c];
            Ke[12 * r + c] = s;
        }
}

/* Calls add(ctx, row, col, value) for every K and M entry, global segment
 * DOF numbering (6i + k); `which` 0 = K, 1 = M. */
typedef void (*entry_fn)(void *ctx, int which, int gi, int gj, double v);

static void for_each_entry(const rd_ring *ring, entry_fn add, void *ctx)
{
    double Ke[144];
    for (int j = 0; j < ring->joints; j++) {
        int a, b;
        joint_ends(ring, j, &a, &b);
        joint_stiffness(ring, j, Ke);
        for (int r = 0; r < 12; r++)
            for (int c = 0; c < 12; c++) {
                int gr = 6 * (r < 6 ? a : b) + r % 6, gc = 6 * (c < 6 ? a : b) + c % 6;
                add(ctx, 0, gr, gc, Ke[12 * r + c]);
            }
    }
    for (int i = 0; i < ring->n; i++)
        for (int r = 0; r < 6; r++)
            for (int c = 0; c < 6; c++)
                add(ctx, 1, 6 * i + r, 6 * i + c, ring->Mseg[36 * i + 6 * r + c]);
}

struct band_ctx {
    const rd_ring *ring;
    rd_band *K, *M;
};

static void band_add(void *vctx, int which, int gi, int gj, double v)
{
    struct band_ctx *ctx = vctx;
    int bi = rd_ring_band_index(ctx->ring, gi / 6, gi % 6);
    int bj = rd_ring_band_index(ctx->ring, gj / 6, gj % 6);
    if (bi <= bj)
        rd_band_add(which ? ctx->M : ctx->K, bi, bj, v);
}

int rd_ring_assemble_band(const rd_ring *ring, rd_band *K, rd_band *M, rd_error *err)
{
    int N = 6 * ring->n, kd = rd_ring_band_kd(ring);
    K->ab = M->ab = NULL;
    if (rd_band_init(K, N, kd, err) || rd_band_init(M, N, kd, err)) {
        rd_band_cleanup(K);
        rd_band_cleanup(M);
        return err ? err->code : RD_ENOMEM;
    }
    struct band_ctx ctx = {ring, K, M};
    for_each_entry(ring, band_add, &ctx);
    return RD_OK;
}

struct dense_ctx {
    int N;
    double *K, *M;
};

static void dense_add(void *vctx, int which, int gi, int gj, double v)
{
    struct dense_ctx *ctx = vctx;
    (which ? ctx->M : ctx->K)[gi + (size_t)gj * ctx->N] += v;
}

int rd_ring_assemble_dense(const rd_ring *ring, double *K, double *M, rd_error *err)
{
    if (ring->n > 500) {
        size_t m = rd_error_enter(err, "/discretization");
        int rc = rd_error_set(err, RD_ELIMIT, "/segments",
                              "Dense matrices are limited to 500 segments (got %d).", ring->n);
        rd_error_leave(err, m);
        return rc;
    }
    int N = 6 * ring->n;
    memset(K, 0, (size_t)N * N * sizeof *K);
    memset(M, 0, (size_t)N * N * sizeof *M);
    struct dense_ctx ctx = {N, K, M};
    for_each_entry(ring, dense_add, &ctx);
    return RD_OK;
}

double rd_ring_strain_energy(const rd_ring *ring, const double *q)
{
    double e = 0.0;
    for (int j = 0; j < ring->joints; j++) {
        int a, b;
        joint_ends(ring, j, &a, &b);
        const double *T = ring->T + 72 * j;
        double qe[12], d[6];
        for (int k = 0; k < 6; k++) {
            qe[k] = q[6 * a + k];
            qe[6 + k] = q[6 * b + k];
        }
        for (int r = 0; r < 6; r++) {
            d[r] = 0.0;
            for (int c = 0; c < 12; c++)
                d[r] += T[12 * r + c] * qe[c];
        }
        for (int r = 0; r < 6; r++)
            for (int c = 0; c < 6; c++)
                e += 0.5 * d[r] * ring->Kc[36 * j + 6 * r + c] * d[c];
    }
    return e;
}

double rd_ring_kinetic_energy(const rd_ring *ring, const double *v)
{
    double e = 0.0;
    for (int i = 0; i < ring->n; i++) {
        const double *Ms = ring->Mseg + 36 * i, *vi = v + 6 * i;
        for (int r = 0; r < 6; r++)
            for (int c = 0; c < 6; c++)
                e += 0.5 * vi[r] * Ms[6 * r + c] * vi[c];
    }
    return e;
}

void rd_ring_rigid_motion(const rd_ring *ring, const double t[3], const double w[3], double *q)
{
    for (int i = 0; i < ring->n; i++) {
        const double *P = ring->P + 3 * i;
        double wxP[3] = {w[1] * P[2] - w[2] * P[1], w[2] * P[0] - w[0] * P[2],
                         w[0] * P[1] - w[1] * P[0]};
        for (int k = 0; k < 3; k++) {
            q[6 * i + k] = t[k] + wxP[k];
            q[6 * i + 3 + k] = w[k];
        }
    }
}

double rd_ring_lambda_max_estimate(const rd_ring *ring)
{
    /* K_jj / M_jj over one interior segment's DOFs (all segments are alike). */
    double Ke[144], best = 0.0;
    joint_stiffness(ring, 0, Ke);
    const double *Ms = ring->Mseg;
    for (int k = 0; k < 6; k++) {
        double kjj = Ke[12 * (6 + k) + (6 + k)] + Ke[12 * k + k]; /* two joints meet */
        double r = kjj / Ms[6 * k + k];
        if (r > best)
            best = r;
    }
    return best;
}
