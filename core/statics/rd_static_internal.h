/*
 * rd_static_internal.h — what the static files share (no caller outside
 * core/ may include this, but tests/ may, for the derivatives they check):
 *   rd_static.c      the residual, Newton's method and the load stepping;
 *   rd_static_tangent.c  the residual's tangent;
 *   rd_static_joint.c  one joint's forces and their exact derivative, and the
 *                    SO(3) maps;
 *   rd_pretension.c  the free shape under F_t (and F_l) on the gap faces;
 *   rd_contact.c     the ring pressed into a round or distorted bore: the
 *                    problem, its law and one solve;
 *   rd_contact_refine.c  the refinement and the error estimates' solves.
 * The model and its equations are in rd_static.h; the state layout in
 * rd_static.c.
 */
#ifndef RD_STATIC_INTERNAL_H
#define RD_STATIC_INTERNAL_H

#include <string.h>

#include "rd_blocktri.h"
#include "rd_internal.h"
#include "rd_static.h"
#include "rd_vec3.h"

enum { RD_STATIC_PRETENSION = 0, RD_STATIC_CONTACT = 1 };

/* ---- the problem ---------------------------------------------------------- */

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

typedef struct rd_static_problem {
    const rd_ring *ring;
    int n, kind;
    double R, b, h;
    const double *Kc;
    double *E;   /* 9 per joint: rows chord, axial, radial */
    double *dP0; /* 3 per joint: P_B - P_A */
    double *x;   /* 3n */
    double *Q;   /* 9n */
    double lambda;
    double lambda_start; /* where the load path starts (a warm start: past 0) */
    double step_start;   /* the load path's first step (0: all of it at once) */
    double step_taken;   /* the first load step accepted (load_steps sets it) */
    /* gap-face loads */
    double Ft, Fl;
    int method;
    int jseg;            /* field method: the segment whose face carries the J marker */
    double cA[3], cB[3]; /* face centroids, body offsets of segments 0, n-1 */
    double tA[3], tB[3]; /* face forces' directions, body components */
    /* support at the section opposite the gap */
    int pa, pb;
    double mask[6];
    double k_t, k_r;
    /* contact */
    int m;               /* points per segment */
    double *cp;          /* 3 per point: body offsets (the flexible face's, rd_contact.c) */
    double *cp0;         /* 3 per point: the rigid face's offsets, in cp's block (NULL: cp rigid) */
    double *face;        /* 14 per joint: rd_contact_face.c's cache, in cp's block */
    double *face_rz;     /* per segment: its turn about the axis (the same cache) */
    double *mult;        /* per point: the augmented Lagrangian's multiplier, Pa (NULL: none) */
    rd_contact_eval *pe; /* m n: each point at the last rd_contact_loads */
    int tip_mult;        /* mult[n], mult[n + 1]: the free ends' very tips their own */
    double *area;        /* n: tributary area of one point of each segment, m^2 (in cp's block) */
    double area_max;     /* the largest of them (0 without contact) */
    double r_o;          /* running-face radius of the closed ring */
    double bore_dr;      /* D/2 - r_o */
    const rd_contact_opts *co;
    double bore_phase[2 * RD_DISTORTION_MAX]; /* cos, sin of each distortion's k phi_k */
    double k, eps, p0;
    /* scales */
    double F_ref;
} rd_static_problem;

/* Allocates the state and fills the reference geometry, the gap faces and
 * the support (kind: RD_STATIC_PRETENSION or RD_STATIC_CONTACT); the caller
 * sets the loads.  RD_ENOMEM on failure; cleanup is safe either way. */
int rd_static_problem_init(rd_static_problem *pb, const rd_ring *ring, int kind);
void rd_static_problem_cleanup(rd_static_problem *pb);

/* Load stepping from lambda = 0 to 1 with Newton's method; `mon` sees 0..1
 * of this solve (and is called inside the iterations, so a cancel takes
 * effect within one iteration).  Fills the counters of st. */
int rd_static_solve_path(rd_static_problem *pb, const rd_static_opts *so, const rd_monitor *mon,
                         rd_static_stats *st, rd_error *err);

/* rd_static_joint.c.  Rodrigues: R = exp([w]x). */
void rd_static_rot_exp(const double w[3], double R[9]);
/* The rotation vector of R (|w| < pi; the chain's relative rotations are far
 * from pi, and the support's are held near zero). */
void rd_static_rot_log(const double R[9], double w[3]);
/* out = Jl^-T(psi) v (rd_static_joint.c's header). */
void rd_static_jl_inv_t(const double psi[3], const double v[3], double out[3]);
/* Joint j's generalized forces g (12: A's force and moment, then B's) at the
 * states (xA, QA) of segment j and (xB, QB) of segment j + 1, and its strain
 * energy (J) when `energy` is not NULL. */
void rd_static_joint_residual(const rd_static_problem *pb, int j, const double *xA,
                              const double *QA, const double *xB, const double *QB, double g[12],
                              double *energy);
/* Their exact derivative: K[12 r + c] = d g_r / d DOF c, DOFs (dx_A, dpsi_A,
 * dx_B, dpsi_B) as in rd_static.c. */
void rd_static_joint_tangent(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                             const double *xB, const double *QB, double K[144]);

/* rd_static_tangent.c: the residual's tangent into t (6x6 blocks, or 12x12
 * with flexible contact faces: rd_static_per_block segments a block), at
 * the state of the last residual evaluation; Marquardt's damping of its
 * diagonal by mu; a copy (xo, Qo) of a segment's state moved by h along
 * DOF k (0..2 translate, 3..5 turn). */
int rd_static_per_block(const rd_static_problem *pb);
void rd_static_tangent(rd_static_problem *pb, rd_blocktri *t, double mu);
void rd_static_perturb(const double *x, const double *Q, int k, double h, double xo[3],
                       double Qo[9]);
/* The tangent straight into its in-plane (part[0]: dx, dy, dpsi_z of each
 * segment of a block) and out-of-plane (part[1]: dz, dpsi_x, dpsi_y) halves,
 * 3 DOFs a segment: returns 1, or 0 if an entry coupling the halves was not
 * exactly 0 (then the halves are void). */
int rd_static_tangent_planar(rd_static_problem *pb, rd_blocktri part[2], double mu);
/* A segment's DOFs in each half, in the halves' order (in-plane dx, dy,
 * dpsi_z; out-of-plane dz, dpsi_x, dpsi_y). */
extern const int rd_plane_dof[2][3];

/* Strain energy, support force and moment, sizes, after a solve. */
void rd_static_stats_fill(rd_static_problem *pb, rd_static_stats *st);

/* Current global position of the body offset c of segment i. */
void rd_static_point_at(const rd_static_problem *pb, int i, const double c[3], double y[3]);

/* Adds (F, (y - x) x F) for a force F at body offset c of a segment at (x, Q). */
void rd_static_add_force(const double *Q, const double c[3], const double F[3], double f[6]);

/* The load factor of F_t: pretension grows with lambda; contact applies it
 * over lambda 0..1/2 (rd_contact.c has the bore's part of the path). */
double rd_static_force_factor(const rd_static_problem *pb);

/* rd_static_problem.c: adds the gap-face loads on segment i (0 or n - 1)
 * at (x, Q) to f: F_t by the force or the field method, and F_l (both
 * problems' residual and tangent apply them). */
void rd_static_gap_face_load(const rd_static_problem *pb, int i, const double *x, const double *Q,
                             double f[6]);

/* rd_contact_face.c: adds the bore's contact forces on segment i at (x, Q)
 * to f (with flexible faces its neighbours' points' too, at their states in
 * pb, through the faces as pb last computed them). */
void rd_contact_segment_load(const rd_static_problem *pb, int i, const double *x, const double *Q,
                             double f[6]);
/* The same for every segment at pb's state, subtracted from r (6n); each
 * point's evaluation kept in pb->pe for the derivatives below. */
void rd_contact_loads(const rd_static_problem *pb, double *r);
/* The same where only the multipliers changed since the last
 * rd_contact_loads (the state and the load factor as then): each point's
 * law again at its kept penetration, bit for bit what rd_contact_loads
 * would give, without the points' geometry (rd_static.c's uzawa). */
void rd_contact_loads_again(const rd_static_problem *pb, double *r);
/* Does the point press (its law or slope not exactly 0)?  Those that do not
 * add nothing to the loads or their derivatives. */
static inline int rd_contact_presses(const rd_contact_eval *pe)
{
    return pe->p != 0.0 || pe->dp != 0.0;
}
/* rd_contact.c: the loads' derivative at the state of the last
 * rd_contact_loads: J[r + 6 d] = d f_r / d DOF d of segment i, DOFs (dx,
 * dpsi) as in rd_static.c (the normal's turn, p / (k rho) ~ 1e-7 of the
 * rest, left out). */
void rd_contact_segment_jacobian(const rd_static_problem *pb, int i, double J[36]);
/* The predictor of a load step: each segment moved with the bore under it
 * from load factor l0 to l1. */
void rd_contact_follow_bore(rd_static_problem *pb, double l0, double l1);
/* rd_contact_law.c.  The contact's load path (rd_contact_law.c has why):
 * F_t over lambda 0..RD_CONTACT_LF with the bore still the ring's closed
 * shape, the bore's departure from it over RD_CONTACT_LF..
 * RD_CONTACT_BORE_DONE, then the law's smoothing brought down to its own
 * by lambda = 1. */
#define RD_CONTACT_LF        0.4
#define RD_CONTACT_BORE_DONE 0.8
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
/* What every point's evaluation at the current load factor
 * shares, hoisted out of the points' loop: the law's smoothing length e and
 * the share mu of the bore's departure from round that is in place; at the
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
/* rd_contact_face.c: each contact point's offset cp set to the rigid face's
 * cp0 moved outward by the ring's bending and shear over its segment, from
 * the current state (nothing when cp0 is NULL). */
void rd_contact_face_update(const rd_static_problem *pb);
/* Point k of segment i's angle from the segment's centre (rad). */
double rd_contact_point_offset(const rd_static_problem *pb, int i, int k);
/* The DOFs a flexible face couples, in the order of rd_contact_face_jacobian's
 * K: segment o - 1's planar three (dx, dy, dpsi_z), o's six, o + 1's planar
 * three; rd_face_dof_seg[q] is q's segment less o - 1, rd_face_dof[q] its DOF. */
enum { RD_FACE_DOFS = 12 };
extern const int rd_face_dof_seg[RD_FACE_DOFS], rd_face_dof[RD_FACE_DOFS];
/* The face's part of the derivative of the contact loads of segment o's
 * points at the state of the last rd_contact_loads: K[q][t] the load on
 * DOF q by DOF t (the order above), less the rigid part
 * rd_contact_segment_jacobian gives.  Returns how many of o's points press;
 * K is written only when some do (and never without a face). */
int rd_contact_face_jacobian(const rd_static_problem *pb, int o,
                             double K[RD_FACE_DOFS][RD_FACE_DOFS]);
/* rd_contact.c: the augmented Lagrangian's update at the state of the last
 * rd_contact_loads, lambda_q <- p_q (each point's current pressure);
 * returns max_q |p_q - lambda_q| / p0 before it. */
double rd_contact_update_multipliers(rd_static_problem *pb);

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
