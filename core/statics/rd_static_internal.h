/*
 * rd_static_internal.h — what the contact files share (no caller outside
 * core/ may include this, but tests/ may, for the derivatives they check),
 * above the chain and its solver (rd_static_problem.h, included):
 *   rd_contact_law.c  the contact law and one point's evaluation;
 *   rd_contact_face.c  the flexible faces and the points' loads;
 *   rd_contact.c     the ring pressed into a round or distorted bore: the
 *                    problem, its loads' table and one solve;
 *   rd_contact_uzawa.c  the multipliers' outer iterations;
 *   rd_contact_gaps.c, rd_contact_patch.c  what one solve reports;
 *   rd_contact_estimate.c  the estimates between two levels;
 *   rd_contact_refine.c  the refinement and the error estimates' solves.
 * (rd_pretension.c, the free shape under F_t and F_l on the gap faces,
 * needs only rd_static_problem.h.)  The model and its equations are in
 * rd_static.h; the state layout in rd_static.c.
 */
#ifndef RD_STATIC_INTERNAL_H
#define RD_STATIC_INTERNAL_H

#include "rd_static_problem.h"

/* One contact point as the last rd_contact_loads found it (what the
 * tangent's contact blocks and the multipliers' update read, so a Newton
 * iteration evaluates each point once): its penetration delta (m, without
 * the multiplier's shift), arm = Q c its offset turned to global, n =
 * grad(delta) the bore's outward normal (|n| = nn, ~1), the law p and its
 * slope dp; with flexible
 * faces dyu, the point's move per unit u, and du[b][d], u's derivative by
 * the planar DOF d of segment i - 1 + b (rd_contact_face.c).  A point off
 * the bore by more than 746 smoothing lengths has p = dp = 0 exactly (the
 * law's exp underflows) and nothing else filled: it adds nothing to the
 * loads or their derivative. */
typedef struct rd_contact_eval {
    double delta, arm[3], n[3], nn, p, dp, dyu[3], du[3][3];
} rd_contact_eval;

/* Does the point press (its law or slope not exactly 0)?  Those that do not
 * add nothing to the loads or their derivatives. */
static inline int rd_contact_presses(const rd_contact_eval *pe)
{
    return pe->p != 0.0 || pe->dp != 0.0;
}

/* ---- rd_contact_law.c: the law and one point's evaluation ----------------- */

/* The contact's load path (rd_contact_law.c has why): F_t over lambda
 * 0..RD_CONTACT_LF with the bore still the ring's closed shape, the bore's
 * departure from it over RD_CONTACT_LF..RD_CONTACT_BORE_DONE, then the
 * law's smoothing brought down to its own by lambda = 1. */
#define RD_CONTACT_LF        0.4
#define RD_CONTACT_BORE_DONE 0.8
/* F_t's share at pb->lambda (rd_static_loads.force_factor): all of it from
 * RD_CONTACT_LF on. */
double rd_contact_force_factor(const rd_static_problem *pb);
/* Bore radius r and its derivative dr by theta at the angle theta, at the
 * current load factor. */
void rd_contact_bore_radius(const rd_static_problem *pb, double theta, double *r, double *dr);
/* Point k of segment i's multiplier: its segment's (i), or with tip_mult
 * the very tip's own (n on the first free end, n + 1 on the last). */
int rd_contact_mult_of(const rd_static_problem *pb, int i, int k);
/* The law's stiffness at multiplier q: k, or a stiffer one at a tip's own
 * point once the load is on. */
double rd_contact_law_stiffness(const rd_static_problem *pb, int q);
/* The law p(delta) at multiplier q (its shift included), Pa. */
double rd_contact_pressure(const rd_static_problem *pb, double delta, int q);
/* What every point's evaluation at the current load factor shares,
 * hoisted out of the points' loop: the law's smoothing length e and the
 * share mu of the bore's departure from round that is in place; at the
 * point y of segment o, pe's delta, the law p and its slope dp (its
 * multiplier's shift included) and, where it presses, n = grad(delta), the
 * bore's outward normal (|n| ~1). */
typedef struct rd_contact_at {
    double e, mu;
} rd_contact_at;
rd_contact_at rd_contact_now(const rd_static_problem *pb);
void rd_contact_point(const rd_static_problem *pb, int o, int k, const double y[3],
                      const rd_contact_at *at, rd_contact_eval *pe);
/* pe's law and slope again at its kept delta (the multiplier changed). */
void rd_contact_law_again(const rd_static_problem *pb, int o, int k, double e, rd_contact_eval *pe);

/* ---- rd_contact_face.c: the faces and the points' loads ------------------- */

/* Each contact point's offset cp set to the rigid face's cp0 moved outward
 * by the ring's bending and shear over its segment, from the current state
 * (nothing when cp0 is NULL). */
void rd_contact_face_update(const rd_static_problem *pb);
/* Point k of segment i's angle from the segment's centre (rad). */
double rd_contact_point_offset(const rd_static_problem *pb, int i, int k);
/* Adds the bore's contact forces on segment i at (x, Q) to f (with
 * flexible faces its neighbours' points' too, at their states in pb,
 * through the faces as pb last computed them). */
void rd_contact_segment_load(const rd_static_problem *pb, int i, const double *x, const double *Q,
                             double f[6]);
/* The same for every segment at pb's state, subtracted from r (6n); each
 * point's evaluation kept in pb->pe for the derivatives. */
void rd_contact_loads(const rd_static_problem *pb, double *r);
/* The same where only the multipliers changed since the last
 * rd_contact_loads (the state and the load factor as then): each point's
 * law again at its kept penetration, bit for bit what rd_contact_loads
 * would give, without the points' geometry (the multipliers' updates,
 * rd_contact_uzawa.c). */
void rd_contact_loads_again(const rd_static_problem *pb, double *r);
/* The face's part of the derivative of the contact loads of segment o's
 * points at the state of the last rd_contact_loads: K[q][t] the load on
 * DOF q by DOF t (rd_face_dof's order), less the rigid part
 * rd_contact_segment_jacobian gives.  Returns how many of o's points press;
 * K is written only when some do (and never without a face). */
int rd_contact_face_jacobian(const rd_static_problem *pb, int o,
                             double K[RD_FACE_DOFS][RD_FACE_DOFS]);

/* ---- rd_contact.c, rd_contact_uzawa.c: the problem ------------------------ */

/* The contact problem's loads (rd_static_loads), for rd_static_problem_init. */
extern const rd_static_loads rd_contact_static_loads;
/* The loads' derivative at the state of the last rd_contact_loads: J[r + 6
 * d] = d f_r / d DOF d of segment i, DOFs (dx, dpsi) as in rd_static.c (the
 * normal's turn, p / (k rho) ~ 1e-7 of the rest, left out). */
void rd_contact_segment_jacobian(const rd_static_problem *pb, int i, double J[36]);
/* The augmented Lagrangian's outer (Uzawa) iterations at the full load
 * (rd_static_loads.outer): each updates the multipliers and solves again
 * in s (rd_static_resolve) until they settle; RD_OK or an error. */
int rd_contact_uzawa(rd_static_problem *pb, rd_static_session *s);

/* Flexible faces (rd_contact_face.c) from this many segments on.  Below,
 * a face bends by up to ~2 um over its long segment (n = 20), twenty times
 * the law's widest smoothing, and Newton needed 100-260 iterations where
 * rigid faces need 16-29 (bench_static --bins 2 1 17); those levels only
 * start the finer ones, which converge as fast from either. */
#define RD_CONTACT_FACE_MIN_SEGMENTS 80

/* A solved level's shape, for the next level's start: per segment its
 * reference angle (rad), radial and tangential displacement (m) and turn
 * about the axis (rad). */
typedef struct rd_contact_warm {
    int n, n_mult;
    double *ang, *ur, *ut, *rz;
    double *mult; /* the multipliers (n_mult), for a start at the same n */
    double step;  /* the first load step the level accepted from its own
                     warm start (0: none, or a cold start) */
    int only;     /* 1: if the start from this shape fails, so does the solve (no
                     whole load path after it: a shifted level, rd_contact_refine.c) */
} rd_contact_warm;
void rd_contact_warm_free(rd_contact_warm *w);

/* One contact solve at `segments`, from the shape `from` if given (a
 * coarser level's, or the same level's with its multipliers: then at the
 * full load), the solved shape left in `to` if given. */
int rd_contact_once(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                    const rd_static_opts *so, const rd_monitor *mon, const rd_contact_warm *from,
                    rd_contact_warm *to, rd_contact_result *out, rd_error *err);
/* The same on a graded ring (rd_ring_create_graded's weights; NULL: equal
 * segments). */
int rd_contact_once_graded(const rd_ring_params *p, int segments, const double *weights,
                           const rd_contact_opts *o, const rd_static_opts *so,
                           const rd_monitor *mon, const rd_contact_warm *from, rd_contact_warm *to,
                           rd_contact_result *out, rd_error *err);

/* How many of the estimates e of r miss the target a (see
 * rd_contact_opts.accuracy; NAN misses), each named with its value and
 * bound in buf (if not NULL), e.g. "gap edges 1.02 deg (at most 1)"
 * (rd_contact_target.c); rd_contact_meets: none. */
int rd_contact_misses(const rd_contact_estimates *e, const rd_contact_result *r, double a,
                      char *buf, size_t size);
int rd_contact_meets(const rd_contact_estimates *e, const rd_contact_result *r, double a);

/* rd_contact_gaps.c: light gaps and contact fraction from the segments'
 * closest points (angles ts, deg, increasing; clearances cs, m) and all m n
 * contact points (t, c), their edges among the points if `points` (faces
 * that follow the bore) else between the segments' closest points, the
 * free ends at tip0 < tip1 deg; binned pressure from the segments' forces
 * (N) acting at at_deg_i within their arcs [seg_deg_i, seg_deg_i+1] on the
 * bore (n + 1 ends, deg), spread over the parts the light gaps of `gaps`
 * leave on the bore. */
void rd_contact_gaps(const double *ts, const double *cs, int n, const double *t, const double *c,
                     int m, int points, double tip0, double tip1, double gap_floor,
                     rd_contact_result *out);
void rd_contact_bins(const double *seg_deg, const double *force, const double *at_deg, int n,
                     double h_ro, const rd_contact_result *gaps, rd_contact_result *out);
/* The arc of the segment nearest the angle a (deg): 360 / n where the
 * segments are alike (as the estimates were measured), its own where
 * graded. */
double rd_contact_width_at(const rd_contact_result *r, double a);
/* rd_contact_patch.c: out's contact patches from its light gaps and the
 * segments' forces (N) acting at at (deg on the bore), their arcs' ends lo
 * (n + 1, deg: lo[0] and lo[n] the free ends). */
void rd_contact_patches(const double *lo, const double *force, const double *at, int n,
                        rd_contact_result *out);
/* The largest change of a patch's force between a and b, N: each patch
 * against those of the other that overlap it within a segment, one none
 * overlaps by its whole force (a patch one of them splits in two moves by
 * the larger part). */
double rd_contact_patch_moves(const rd_contact_result *a, const rd_contact_result *b);
/* rd_contact_estimate.c: arcs (deg) where a graded level should be finer:
 * around each bin boundary that a gap edge or a narrow patch of f may lie
 * across, where the force that could cross it (the binned pressure's
 * estimate's edge_segment, edge and patch shares) exceeds z->threshold (of
 * p0), padded by the edge's uncertainty and a segment of f; merged where
 * they overlap, added to those z has. */
#define RD_CONTACT_ZONES_MAX RD_CONTACT_ARCS_MAX
typedef struct rd_contact_zones {
    double threshold;
    int n;
    double lo[RD_CONTACT_ZONES_MAX], hi[RD_CONTACT_ZONES_MAX];
} rd_contact_zones;
void rd_contact_zones_find(const rd_contact_result *f, const rd_contact_result *c,
                           rd_contact_zones *z);
/* The error estimates of the finer of two levels. */
void rd_contact_estimate(const rd_contact_result *fine, const rd_contact_result *coarse,
                         rd_contact_estimates *e);
/* The same with the binned pressure's levels part from the levels' moves
 * when their meshes are shifted by half a segment (own: the finer's, below:
 * the coarser's; shifted less unshifted, RD_CONTACT_BINS each, Pa): in each
 * bin the larger of the finer level's own move and half the smaller of its
 * changes from the coarser level and from the coarser level shifted, where
 * both are of one sign (else half the first, as rd_contact_estimate). */
void rd_contact_estimate_shifted(const rd_contact_result *fine, const rd_contact_result *coarse,
                                 const double *own, const double *below, rd_contact_estimates *e);
/* Adds to e the contact law's share of r's errors from s, the same level
 * solved at twice the stiffness (the binned pressure, largest gap and tip
 * forces: twice each move, the law's error going as 1/k; the edges: the
 * move once, and the contact fraction's edge term again with it), added to
 * the refinement's (in quadrature, the 10 x k moves of the battery's bins
 * exceeded the estimate on 11 of 29 bores, added on 4); returns the binned
 * pressure's share, of p0. */
double rd_contact_estimate_law(const rd_contact_result *r, const rd_contact_result *s,
                               rd_contact_estimates *e);

#endif
