/*
 * contact_reference — an independent solution of the split ring in a
 * distorted bore, for tests and benches (not part of ringdyn): a linear
 * curved Timoshenko beam (extension, shear, bending) on its centroid circle,
 * N two-node cells with one-point integration, and frictionless unilateral
 * contact at every node against a rigid bore, solved exactly (gap >= 0,
 * force >= 0, gap * force = 0) by a primal-dual active-set iteration.
 * Written apart from core's segment-chain model: it shares only the input.
 */
#ifndef CONTACT_REFERENCE_H
#define CONTACT_REFERENCE_H

#include "rd_static.h"

#define REF_BINS_MAX 72

typedef struct ref_gap {
    double start_deg, end_deg;    /* edges, deg from the gap middle */
    double max_clearance, at_deg; /* largest clearance (m) and where */
} ref_gap;

/* A contact patch: the nodes between the deepest points of the light gaps
 * either side (or a free end), their forces' sum and mean angle. */
typedef struct ref_patch {
    double start_deg, end_deg; /* the gaps' edges either side, or the free end */
    double force_n, centroid_deg;
} ref_patch;

typedef struct ref_result {
    int cells, iterations;
    double contact_fraction; /* contact length / ring span */
    double end_deg[2];       /* the free ends' polar angles: where on the bore they are */
    int n_gaps;
    ref_gap gaps[64];
    double max_clearance, max_clearance_deg;
    double tip_force[2]; /* concentrated force at the two free ends, N */
    int n_patches;
    ref_patch patches[65];
    int bins; /* angular bins of bin_deg from 0 deg on the bore, the first and last reaching past */
    double bin_pressure[REF_BINS_MAX]; /* mean contact pressure per bin, Pa (0 where no ring) */
    double p0;
} ref_result;

/* The battery's bore (bench_static --battery, test_contact): order k at fac
 * times the thin-ring conformability bound F_t R^3 / (E I (k^2 - 1)^2),
 * capped at 0.4 % of the diameter, phase deg; the other contact options at
 * their defaults. */
rd_contact_opts ref_battery_bore(const rd_ring_params *p, int k, double fac, double phase);

/* Solves on `cells` cells (even); bins of bin_deg; light gaps no deeper
 * than gap_floor (m) count as contact.  Returns 0, or -1 (no convergence,
 * out of memory, singular). */
int ref_contact_solve(const rd_ring_params *p, const rd_contact_opts *o, int cells, double bin_deg,
                      double gap_floor, ref_result *out);

/* The linear reference's converged contact states on `cells` cells: act[j]
 * (cells + 1 of them) is 1 where node j touches the bore.  Same returns. */
int ref_contact_active_set(const rd_ring_params *p, const rd_contact_opts *o, int cells, char *act);

/* The same ring, cells, loads and contact as a geometrically exact beam
 * (contact_reference_nl.c): F_t follows the end sections (follower = 1, as
 * ringdyn's force method) or keeps its direction (0, as the linear
 * reference).  Same returns. */
int ref_contact_solve_nl(const rd_ring_params *p, const rd_contact_opts *o, int cells, int follower,
                         double bin_deg, double gap_floor, ref_result *out);

/* The nodes' mesh: `cells` cells of D rad from theta = s (the half closed
 * gap), axial height h and running-face radius ro (m). */
typedef struct ref_mesh {
    int cells;
    double s, D, h, ro;
    const double *shift; /* per node, rad: its polar angle's departure from s + j D, or NULL */
} ref_mesh;

/* Fills out's gaps, contact fraction, tip forces and bins from the nodes'
 * contact states act, gaps (m) and inward contact forces lam (N), shared by
 * both references so that they are compared through the same binning. */
void ref_post(const ref_mesh *m, const char *act, const double *gap, const double *lam,
              double bin_deg, double gap_floor, ref_result *out);

/* The largest move of an edge of r's light gaps deeper than 0.1 um against
 * c's overlapping gap (none: the reference gap's width), deg; NAN when r
 * has no such gap.  The edges' error of bench_static --battery and
 * test_contact. */
double ref_edge_error(const rd_contact_result *c, const ref_result *r);

/* The largest error of c's contact patches' forces against r's, N: each
 * of r's patches against c's that overlap it within a segment, a patch
 * only one of them has by its whole force; *rel the largest relative to
 * its patch's force (at least 0.5 N). */
double ref_patch_error(const rd_contact_result *c, const ref_result *r, double *rel);

/* The patch forces' tracking floor, N: 0.01 N (as the tip forces') plus
 * 1e-3 of r's largest patch force, the two models' settled difference (the
 * 130 mm ring, order 2 at 2.27 x, 126.5 deg: 0.032 N of ~80 N at n = 1280,
 * the reference within 0.0006 N of it from 1440 to 4000 cells). */
double ref_patch_floor(const ref_result *r);

/* Does the estimate est track the true error err: within x3 either way,
 * or both at most `floor` (the tracking criterion; bench_static
 * --battery and test_contact count with it)? */
int ref_tracks(double est, double err, double floor);

#endif
