/*
 * rd_static_problem.h — the static chain and its solver, as the problems
 * built on it (rd_pretension.c, rd_contact.c) and tests/ see them (no
 * caller outside core/ may include this):
 *   rd_static_problem.c  the problem's state, geometry and support, and
 *                    the chain's own loads (the gap faces');
 *   rd_static.c      the residual, Newton's method and the load stepping;
 *   rd_static_tangent.c  the residual's tangent;
 *   rd_static_joint.c  one joint's forces and their exact derivative, and the
 *                    SO(3) maps.
 * A problem's further loads reach the solver through its rd_static_loads
 * (pb->loads), so the solver names no problem.  The model and its
 * equations are in rd_static.h; the state layout in rd_static.c.
 */
#ifndef RD_STATIC_PROBLEM_H
#define RD_STATIC_PROBLEM_H

#include <string.h>

#include "rd_blocktri.h"
#include "rd_internal.h"
#include "rd_static.h"
#include "rd_vec3.h"

struct rd_contact_eval; /* rd_static_internal.h */
struct rd_static_loads; /* below */
struct rd_static_work;  /* rd_static.c's scratch */
typedef struct rd_static_session rd_static_session;

typedef struct rd_static_problem {
    const rd_ring *ring;
    const struct rd_static_loads *loads; /* the problem's own loads (never NULL) */
    int n;
    double R, b, h;
    const double *Kc;
    double *E;    /* 9 per joint: rows chord, axial, radial */
    double *dP0;  /* 3 per joint: P_B - P_A */
    double *e0;   /* 6 per joint or NULL: the free shape's [d; t] (rd_free_shape.c), the
                    joints' rest, taken on with F_t's load factor; NULL: the reference */
    double *dead; /* rd_free_shape.c's installed ring: 8 points a segment of (body offset,
                     global force), dead loads taken on with the rest; else NULL */
    double *x;    /* 3n */
    double *Q;    /* 9n */
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
    /* contact (rd_contact.c; its loads read these) */
    int m;           /* points per segment */
    double *cp;      /* 3 per point: body offsets (the flexible face's, rd_contact.c) */
    double *cp0;     /* 3 per point: the rigid face's offsets, in cp's block (NULL: cp rigid) */
    double *face;    /* 14 per joint: rd_contact_face.c's cache, in cp's block */
    double *face_rz; /* per segment: its turn about the axis (the same cache) */
    double *mult;    /* per point: the augmented Lagrangian's multiplier, Pa (NULL: none) */
    struct rd_contact_eval *pe; /* m n: each point at the last rd_contact_loads */
    int tip_mult;               /* mult[n], mult[n + 1]: the free ends' very tips their own */
    double *area;    /* n: tributary area of one point of each segment, m^2 (in cp's block) */
    double area_max; /* the largest of them (0 without contact) */
    double r_o;      /* running-face radius of the closed ring */
    double bore_dr;  /* D/2 - r_o */
    const rd_contact_opts *co;
    double bore_phase[2 * RD_BORE_ORDERS_MAX]; /* cos, sin of each distortion's k phi_k */
    double k, eps, p0;
    /* scales */
    double F_ref;
} rd_static_problem;

/* The DOFs a segment's loads may take from its neighbours (a contact
 * segment's flexible face), in the order of rd_static_loads.face_jacobian's
 * K: segment o - 1's planar three (dx, dy, dpsi_z), o's six, o + 1's planar
 * three; rd_face_dof_seg[q] is q's segment less o - 1, rd_face_dof[q] its
 * DOF (rd_static_tangent.c). */
enum { RD_FACE_DOFS = 12 };
extern const int rd_face_dof_seg[RD_FACE_DOFS], rd_face_dof[RD_FACE_DOFS];

/* A problem's loads beyond the chain's own (its joints, the gap faces'
 * loads, the support), and what the solver asks of them: one table per
 * problem, pb->loads (contact's is rd_contact_static_loads; pretension's
 * loads are the chain's own, so it has none).  rd_lift_form's pattern: the
 * solver calls these and names no problem.  A NULL hook adds nothing. */
typedef struct rd_static_loads {
    /* F_t's share of its full value at pb->lambda (rd_static_force_factor;
     * NULL: lambda) */
    double (*force_factor)(const rd_static_problem *pb);
    /* subtracts the loads at pb's state from r (6n), keeping what the
     * derivatives below and residual_again read */
    void (*residual)(const rd_static_problem *pb, double *r);
    /* the same where only what `outer` changes between its solves changed
     * since the last residual (the state and the load factor as then), bit
     * for bit residual's; NULL: never asked */
    void (*residual_again)(const rd_static_problem *pb, double *r);
    /* the loads' derivative by segment i's own DOFs at the last residual's
     * state: J[r + 6 d] = d f_r / d DOF d, DOFs (dx, dpsi) as in rd_static.c */
    void (*segment_jacobian)(const rd_static_problem *pb, int i, double J[36]);
    /* Do a segment's loads depend on its neighbours' planar DOFs?  Then the
     * tangent pairs the segments (rd_static_per_block) and adds
     * face_jacobian's blocks. */
    int (*coupled)(const rd_static_problem *pb);
    /* that dependence at the last residual's state: K[q][t] the load on DOF
     * q by DOF t (rd_face_dof's order) of segment o's points, less the part
     * segment_jacobian gives; returns 0 where it adds nothing (K not
     * written) */
    int (*face_jacobian)(const rd_static_problem *pb, int o, double K[RD_FACE_DOFS][RD_FACE_DOFS]);
    /* the predictor of a load step: pb's state moved from load factor l0 to
     * l1 (pb->lambda is set to l1 after it) */
    void (*predict)(rd_static_problem *pb, double l0, double l1);
    /* the stiffest spring of the loads (N/m), for the rounding floor of the
     * residual's tolerance (rd_static_solve_path) */
    double (*stiffest)(const rd_static_problem *pb);
    /* iterations at the full load after the load path, each solving again
     * with rd_static_resolve (contact's multipliers, rd_contact_uzawa.c):
     * RD_OK or an error (set in s->err) */
    int (*outer)(rd_static_problem *pb, rd_static_session *s);
    /* 1: the line search takes every full step within 1e3 x the solve's
     * best residual (rd_static.c's line_search has why) */
    int full_steps;
    /* 1: the problem stays in its plane, so its tangent is tried in two
     * halves (rd_static_tangent_planar) */
    int planar;
} rd_static_loads;

/* Allocates the state and fills the reference geometry, the gap faces and
 * the support; `loads` the problem's own (NULL: none beyond the chain's);
 * the caller sets the loads' values.  RD_ENOMEM on failure; cleanup is safe
 * either way. */
int rd_static_problem_init(rd_static_problem *pb, const rd_ring *ring,
                           const rd_static_loads *loads);
void rd_static_problem_cleanup(rd_static_problem *pb);

/* Load stepping from lambda = 0 to 1 with Newton's method, then the loads'
 * outer iterations; `mon` sees 0..1 of this solve (and is called inside
 * the iterations, so a cancel takes effect within one iteration).  Fills
 * the counters of st. */
int rd_static_solve_path(rd_static_problem *pb, const rd_static_opts *so, const rd_monitor *mon,
                         rd_static_stats *st, rd_error *err);

/* A solve in progress, as the loads' outer iterations see it: its
 * tolerance (residual_norm's scale), the Newton iterations left, the
 * options, counters and error, and rd_static.c's scratch, which keeps the
 * last tangent's factors for a chord step. */
struct rd_static_session {
    double tol;
    int budget;
    const rd_static_opts *so;
    rd_static_stats *st;
    rd_error *err;
    struct rd_static_work *work;
};
/* Newton's iterations at pb's load factor from its state, within s: the
 * first `chord` may reuse the last factorization; `again`: only what
 * loads->residual_again reads changed since the last residual; loose > 0
 * stops at max(tol, min(loose, a tenth of the first residual)), 0 at tol.
 * Returns 1 converged (its residual norm in *res), 0 not, < 0 an error or
 * a cancel (s->err set). */
int rd_static_resolve(rd_static_problem *pb, rd_static_session *s, int chord, int again,
                      double loose, double *res);

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
/* Joint j's [d; t] (rd_static.h) at those states, its rest e0 not subtracted. */
void rd_static_joint_strain(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                            const double *xB, const double *QB, double dt[6]);
/* Their exact derivative: K[12 r + c] = d g_r / d DOF c, DOFs (dx_A, dpsi_A,
 * dx_B, dpsi_B) as in rd_static.c. */
void rd_static_joint_tangent(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                             const double *xB, const double *QB, double K[144]);

/* rd_static_tangent.c: the residual's tangent into t (6x6 blocks, or 12x12
 * where the loads couple neighbours: rd_static_per_block segments a
 * block), at the state of the last residual evaluation; Marquardt's
 * damping of its diagonal by mu; a copy (xo, Qo) of a segment's state
 * moved by h along DOF k (0..2 translate, 3..5 turn). */
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

/* (rd_free_shape.c) pb->e0 for the free shape fs of the ring with params
 * p (pb set up by rd_static_problem_init): RD_FREE_PRESSURE from the
 * pressure's loads on the closed ring, the joints' forces found by statics
 * from each free end to the section opposite the gap.  Nothing for NULL or
 * RD_FREE_CLOSED.  RD_ENOMEM, or RD_EINVAL (a singular joint). */
int rd_free_shape_prestrain(rd_static_problem *pb, const rd_ring_params *p, const rd_free_shape *fs,
                            rd_error *err);

/* (rd_free_shape.c) The ring made with the free shape fs closed by the
 * pressure it was made for, as dead loads, the section opposite the gap
 * held: each segment's turn about the ring's tangent, deg, ring makers'
 * sign (rd_contact_result.twist_deg), into twist_deg (segments).  In its
 * plane the ring closes to round exactly (the out-of-plane forces of an
 * open ring without out-of-plane loads are zero), so this is the static
 * twist under that pressure; the bore's contact across the running face's
 * height, which a twisted ring moves to an edge, is not in it. */
int rd_free_shape_installed(const rd_ring_params *p, int segments, const rd_free_shape *fs,
                            const rd_static_opts *so, double *twist_deg, rd_error *err);

/* (rd_pretension.c) The free shape of the ring made with fs at `segments`,
 * no load on it: out's face_theta_deg and face_radius (n + 2 points, the
 * tips first and last) and openings, as rd_pretension_solve's level run,
 * without the closing force, the twist or an estimate.  For the measured
 * free shape's fit (rd_free_fit.c). */
int rd_pretension_free_face(const rd_ring_params *p, int segments, const rd_free_shape *fs,
                            const rd_static_opts *so, rd_pretension_result *out, rd_error *err);

/* Strain energy, support force and moment, sizes, after a solve. */
void rd_static_stats_fill(rd_static_problem *pb, rd_static_stats *st);

/* rd_static_problem.c.  Current global position of the body offset c of
 * segment i. */
void rd_static_point_at(const rd_static_problem *pb, int i, const double c[3], double y[3]);

/* Adds (F, (y - x) x F) for a force F at body offset c of a segment at (x, Q). */
void rd_static_add_force(const double *Q, const double c[3], const double F[3], double f[6]);

/* The load factor of F_t: the loads' force_factor, or lambda (pretension's
 * F_t and F_l grow with it). */
double rd_static_force_factor(const rd_static_problem *pb);

/* Adds the gap-face loads on segment i (0 or n - 1) at (x, Q) to f: F_t by
 * the force or the field method, and F_l (both problems' residual and
 * tangent apply them). */
void rd_static_gap_face_load(const rd_static_problem *pb, int i, const double *x, const double *Q,
                             double f[6]);

#endif
