/* rd_internal.h — functions shared between core modules, not part of the
 * public API (no caller outside core/ may include this). */
#ifndef RD_INTERNAL_H
#define RD_INTERNAL_H

#include "rd_band.h"
#include "rd_ring.h"

/* M_PI is POSIX/XSI, not C11. */
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Global DOF index of segment i's local DOF k (0..5) in the band ordering:
 * identity for a split ring, folded (0, n-1, 1, n-2, ...) for a closed ring
 * so that the joint n-1 -> 0 stays inside the band. */
int rd_ring_band_index(const rd_ring *ring, int i, int k);
/* Half bandwidth of K and M in that ordering. */
int rd_ring_band_kd(const rd_ring *ring);
/* Initializes and fills banded K and M (6n x 6n) in the band ordering. */
int rd_ring_assemble_band(const rd_ring *ring, rd_band *K, rd_band *M, rd_error *err);
/* Unit vectors of segment i's local cylindrical frame in global components. */
void rd_ring_segment_frame(const rd_ring *ring, int i, double e_r[3], double e_t[3]);
/* 6x6 mass matrix of segment i (global components, DOFs at its reference point),
 * row-major. */
const double *rd_ring_segment_mass_matrix(const rd_ring *ring, int i);
/* Largest ratio K_jj / M_jj: a cheap proxy for the largest eigenvalue of
 * (K, M), used to size numerical-noise thresholds. */
double rd_ring_lambda_max_estimate(const rd_ring *ring);
/* Reference point P_i (3 values, on the centroid circle). */
const double *rd_ring_reference_point(const rd_ring *ring, int i);
/* Joint j's local cantilever stiffness Kc (6x6 row-major, local axes
 * chord, axial, radial); all joints are alike unless the ring is graded. */
const double *rd_ring_joint_stiffness(const rd_ring *ring, int j);
/* The mean segment angle phi = span / n, rad: every segment's unless the
 * ring is graded. */
double rd_ring_segment_phi(const rd_ring *ring);
/* Was it built with weights (rd_ring_create_graded)? */
int rd_ring_is_graded(const rd_ring *ring);
/* Segment i's angle, rad. */
double rd_ring_segment_phi_at(const rd_ring *ring, int i);
/* A graded ring (the contact analysis' local refinement): segment i spans
 * span * weights[i] / sum(weights), in order from the gap (weights NULL:
 * equal segments, as rd_ring_create).  Each joint is the Timoshenko beam
 * along the chord between its two segments' reference points, each
 * segment's mass that of its own sector. */
rd_ring *rd_ring_create_graded(const rd_ring_params *p, int segments, int closed,
                               const double *weights, rd_error *err);

/* Conformability k (1.4) and the free gap m from (1.5) (rd_ring.c; the
 * public declarations are rd_static.h's, where pretension and contact
 * report them). */
double rd_ring_conformability(const rd_ring_params *p);
double rd_ring_free_gap_formula(const rd_ring_params *p);

#endif
