/*
 * rd_static — geometrically nonlinear statics of the segment chain: the
 * pretensioned free shape (thesis 3.4.1-3.4.2) and the ring in a round or
 * distorted bore (thesis 3.4.3).
 *
 * Kinematics.  Segment i has a position x_i of its reference point (on the
 * centroid circle in the reference, the closed shape) and a rotation matrix
 * Q_i (body to global, I in the reference).  Joint j between A = j and
 * B = j + 1 acts on the relative position and rotation of B's end frame seen
 * from A's (MODEL.md: "as in the thesis' multibody software"):
 *   d = E (Q_A^T (x_B - x_A) - (P_B - P_A)),   t = E log(Q_A^T Q_B),
 * with E the joint's local frame (rows: chord, axial, radial) and
 * U_j = 1/2 [d;t]^T Kc [d;t], Kc the Timoshenko cantilever matrix (3.15).
 * Rigid motions of the whole ring leave d = t = 0 exactly, for any size of
 * rotation; for small motions this is the linear element of rd_ring.
 *
 * Pretension (thesis: "free shape = closed shape + pretension in the opposite
 * direction"): the stress-free closed ring is opened by F_t on the two gap
 * faces, applied at the neutral axis and pushing the faces apart.  Force
 * method: each force stays normal to its face as the face turns (follower).
 * Field method: the force follows the last segment's face (Adams' J marker)
 * and the first face gets the equal and opposite vector plus the balancing
 * couple (thesis Fig. 3.18).  Optional lateral (axial) dead forces F_l: +z on
 * the first face, -z on the last.  The cross-section opposite the gap is
 * held (all six components), so the rigid motions are fixed without
 * affecting the deformation; the force that holds it is reported.
 *
 * Contact: the same closed ring, pressed outwards by F_t on the gap faces
 * (force method), inside the bore r_b(theta) = D/2 + sum A_k cos(k (theta -
 * phi_k)).  Each segment carries m contact points on its running face
 * (mid-height), each against the exact bore surface with the smooth law
 *   p(delta) = k eps ln(1 + exp(delta / eps)),  eps = 0.05 p0 / k,
 * (penetration delta, pressure p, nominal pressure p0 = 2 F_t / (d h)):
 * linear with stiffness k once in contact, smooth through delta = 0, so
 * Newton's method sees no kink; k only sets the penetration p / k.
 * Out-of-plane rigid motions and the rotation about the axis are held at the
 * section opposite the gap (an anti-rotation pin, zero force for a symmetric
 * bore; reported).
 *
 * Solution: Newton's method on all 6n equations with load stepping
 * (pretension: lambda scales F_t and F_l; contact: F_t first, then the
 * bore's departure from the ring's closed shape, each segment moved with
 * the bore as a predictor, the law smoothed 1000 times wider until the bore
 * is in place and then narrowed to eps), backtracking line search,
 * Levenberg-Marquardt damping when a plain step fails, the exact tangent
 * (each joint's and the contact law's in closed form, the gap faces' by
 * central differences) assembled in 6x6 blocks (12x12, two segments, with
 * flexible contact faces, which couple a segment's two neighbours), block
 * tridiagonal, factored by the block Thomas algorithm (rd_blocktri.h; the
 * field method's one off-diagonal block by the Woodbury identity).
 * Convergence: largest force residual <= tol * F_ref and largest moment
 * residual <= tol * F_ref * R, tol raised to the rounding floor of the
 * stiffest spring when that is larger (reported as numerics.tolerance).
 */
#ifndef RD_STATIC_H
#define RD_STATIC_H

#include "rd_error.h"
#include "rd_liner.h"
#include "rd_ring.h"

enum rd_pretension_method { RD_PRETENSION_FORCE = 0, RD_PRETENSION_FIELD = 1 };

#define RD_CONTACT_POINTS_MAX  64
#define RD_STATIC_SEGMENTS_MAX 2000

typedef struct rd_static_opts {
    double tol;         /* relative residual tolerance, default 1e-9 */
    int max_iterations; /* Newton iterations over all load steps, default 2000 */
    int estimate_error; /* 1: second solve at 2n (n/2 above 1000) for the error estimate */
    int max_updates;    /* contact: the multipliers' updates at most (Uzawa), default 60 */
    double update_eta;  /* contact: each update's Newton solve stops at eta times its
                           change's force on a segment while the updates are far from
                           converged (rd_static.c's uzawa); 0: every one to tol;
                           default 0.03, 0..1 */
} rd_static_opts;

/* The ring's free shape (since 0.3.16; rd_free_shape.c).  RD_FREE_CLOSED,
 * the default and every analysis' model before: the closed shape is
 * stress-free and F_t on the gap faces stands for the ring's pretension.
 * RD_FREE_PRESSURE: the ring is made with the free shape that a round bore
 * of its diameter closes to its closed gap with the radial pressure
 * p(theta) = p0 (1 + sum a_k cos k theta), or a table of p / p0, p0 =
 * 2 F_t / (d h), theta from the point opposite the gap (uniform: no orders,
 * no table); that shape is stress-free, closing it stresses the ring, and
 * its gap faces are free.  Tables: theta_deg strictly increasing from 0
 * (the pressure mirrored about the point opposite the gap) or from -180,
 * to 180; linear between the points. */
enum rd_free_kind { RD_FREE_CLOSED = 0, RD_FREE_PRESSURE = 1 };
#define RD_FREE_ORDERS_MAX 16
#define RD_FREE_POINTS_MAX 721
typedef struct rd_free_shape {
    int kind; /* enum rd_free_kind */
    int n_orders;
    int order[RD_FREE_ORDERS_MAX];        /* k, 2..64 (1 would push the ring off centre) */
    double amplitude[RD_FREE_ORDERS_MAX]; /* a_k, -1..1; p stays > 0 everywhere */
    int n_points;                         /* table: 0 or 2..RD_FREE_POINTS_MAX */
    double theta_deg[RD_FREE_POINTS_MAX];
    double value[RD_FREE_POINTS_MAX]; /* p / p0, 0..20 */
    int measured; /* 1: the orders fitted to a measured free shape (rd_free_fit): the pressure
                     may fall to 0 or below somewhere (the ring leaves the bore there), and
                     |a_k| up to 5 */
} rd_free_shape;

/* A measured free shape (since 0.3.17; rd_free_fit.c): the running face's
 * radius about a centre, at angles from the point opposite the gap; either
 * one side (theta_deg from <= 20 to >= 150, mirrored) or the whole ring
 * (from <= -150 to >= 150), strictly increasing, no point in the gap.
 * Ring makers describe a free shape by its pressure; the pressure is the
 * shape's fourth derivative (1 % of p0 is ~7 nm of radius over a 7 mm
 * segment of the thesis ring), so the shape is not differentiated:
 * rd_free_shape_fit finds F_t and the orders 2..fit_order of the pressure
 * whose exact free shape (rd_pretension's, the same chain) is closest to
 * the points in least squares, the table's centre (and, whole, its
 * rotation) free. */
#define RD_FREE_FIT_ORDER_MAX 12
typedef struct rd_free_table {
    int n_points; /* 0: none; else 8..RD_FREE_POINTS_MAX (and 4 more than the parameters) */
    double theta_deg[RD_FREE_POINTS_MAX];
    double radius[RD_FREE_POINTS_MAX]; /* m, within 30 % of d / 2 */
    int fit_order;                     /* K: the pressure's orders 2..K; default 6, 2..12 */
} rd_free_table;

/* The fit (rd_free_shape_fit). */
typedef struct rd_free_fit {
    rd_free_shape shape;        /* the fitted pressure (kind RD_FREE_PRESSURE, measured 1) */
    double tangential_force;    /* F_t it implies, N (p0 = 2 F_t / (d h)) */
    double tangential_force_se; /* its standard error from the residual, N */
    double amplitude_se[RD_FREE_ORDERS_MAX]; /* each a_k's standard error */
    double tangential_force_error;           /* the chain's error: |fit(n) - fit(n / 2)| / 3, N */
    double amplitude_error[RD_FREE_ORDERS_MAX]; /* the same for each a_k */
    double pressure_se_max; /* the largest standard error of p / p0 around the ring */
    double pressure_min, pressure_min_deg; /* the fitted p / p0's least value, and where */
    double centre[2];    /* the table's centre in the fitted shape's frame (x toward the
                                  point opposite the gap, from the closed ring's centre), m */
    double rotation_deg; /* the table's turn (whole tables; 0 mirrored) */
    double residual_rms, residual_max; /* measured - fitted radius, m */
    int segments;                      /* the chain the fit solved */
    int parameters, iterations;
} rd_free_fit;

/* 0 or the table's error (its field under "/free_shape" of the ring's
 * block). */
int rd_free_table_validate(const rd_free_table *t, const rd_ring_params *p, rd_error *err);
/* Fits t (rd_free_table) with the exact free shapes of p's ring at
 * `segments` (the fit's chain: 80..320 of them is ample, rd_free_fit.c):
 * Gauss-Newton on (F_t, F_t a_k, centre, turn), the pressure's columns of
 * the Jacobian by whole solves, once.  The standard errors are those of a
 * least-squares fit whose residual is the measurement's scatter: they do
 * not cover the model itself (the chain gives a pressure back within
 * 0.3-0.8 % of p0, test_free_shape).  RD_ENOCONV when it does not settle in
 * 30 iterations; RD_EINVAL when the table does not fix the orders (a
 * singular fit) or a point falls in the fitted shape's gap.  It fits again
 * at segments / 2 for the chain's error (order 2 in n, *_error).  mon is
 * asked before each free solve (fraction 0): a stop ends it, RD_ECANCELED. */
int rd_free_shape_fit(const rd_ring_params *p, int segments, const rd_free_table *t,
                      const rd_static_opts *so, const rd_monitor *mon, rd_free_fit *out,
                      rd_error *err);

typedef struct rd_pretension_opts {
    int method;                      /* enum rd_pretension_method */
    double lateral_force;            /* F_l, N, >= 0 */
    const rd_free_shape *free_shape; /* NULL or RD_FREE_CLOSED: the stress-free closed ring
                                        opened by F_t; otherwise the free shape itself (F_l
                                        on it), its gap and the force that closes it */
} rd_pretension_opts;

typedef struct rd_contact_opts {
    rd_bore bore;                    /* the bore (rd_liner.h) */
    int points_per_segment;          /* m, 1..RD_CONTACT_POINTS_MAX, default 10 (bench_static:
                               5 moves a distorted bore's pressures by ~0.2 p0, 10 by ~0.05,
                               at n = 40); above 640 segments no more than keep the points
                               360/6400 deg apart, and at least 5 (rd_contact_points) */
    double stiffness;                /* k, Pa/m; 0 = default (see rd_contact_default_stiffness) */
    double accuracy;                 /* a: refine n until the error estimates meet a (pressure, of
                               p0), 2a (contact fraction), 5a (largest light gap, relative;
                               or the gap is certainly under 0.1 um) and 100a deg (gap
                               edges); default 0.01, 1e-4..0.5 */
    int max_segments;                /* refinement stops here (the first pair n, 2n always runs);
                               default 1280 (640 in 0.3.0, 320 before),
                               4..RD_STATIC_SEGMENTS_MAX */
    const rd_free_shape *free_shape; /* NULL or RD_FREE_CLOSED: the stress-free closed ring
                                        pressed out by F_t on its gap faces; otherwise the
                                        ring made with this free shape, its gap faces free */
    int flexible_face;               /* 1 (default): each segment's running face bent and sheared
                               with the ring between its joints (rd_contact_face.c), from 80
                               segments on; 0: rigid arcs (binned pressure within 0.02 p0 of
                               the exact reference on 15 of the 32 battery bores, against 22
                               flexible; bench_static --battery [--rigid]) */
} rd_contact_opts;

#define RD_CONTACT_BIN_DEG  10.0 /* width of the pressure bins, from the gap middle */
#define RD_CONTACT_BINS     36
#define RD_CONTACT_ARCS_MAX 16 /* graded arcs a result reports (rd_contact_result) */
#define RD_CONTACT_GAPS_MAX 64

/* A light gap: a run of the running face off the bore. */
typedef struct rd_contact_gap {
    double start_deg, end_deg; /* edges, deg from the gap middle (start < end) */
    double max_clearance;      /* largest clearance, m */
    double max_clearance_deg;  /* where */
} rd_contact_gap;

/* A contact patch (since 0.3.15): a run of the running face on the bore
 * between two light gaps, or between a free end and a gap (the whole ring
 * where there is no gap). */
typedef struct rd_contact_patch {
    double start_deg, end_deg; /* where it touches: the gaps' edges either side, or the free
                                  end, deg where on the bore */
    double force_n;            /* the bore's radial force on it, N: the segments' resultants
                                  between the deepest points of the gaps either side (a free
                                  end's concentrated force included) */
    double centroid_deg;       /* where that force acts: its mean angle, deg */
} rd_contact_patch;

/* Error estimates of a contact result (NAN when not estimated). */
/* What the largest part of the binned pressure's estimate is (since 0.3.4):
 * the bins' change between the levels (in one bin), a gap edge's segment
 * spreading its force past a bin boundary, a gap edge within its
 * uncertainty of a boundary, a patch too narrow to split across a boundary,
 * or the contact law's compliance (the bins' move at twice the stiffness). */
enum { RD_EST_NONE, RD_EST_LEVELS, RD_EST_EDGE_SEGMENT, RD_EST_EDGE, RD_EST_PATCH, RD_EST_LAW };
/* Its name in results and notes ("levels", "edge_segment", "edge",
 * "patch", "law"), NULL for RD_EST_NONE. */
const char *rd_contact_est_source_name(int source);

typedef struct rd_contact_estimates {
    double pressure;         /* largest binned-pressure error / p0 */
    double contact_fraction; /* absolute */
    double max_clearance;    /* m */
    double gap_edges_deg;    /* deg */
    double tip_forces_n;     /* N, the larger of the two free ends' (since 0.3.1) */
    double patch_forces_n;   /* N, the largest patch's (since 0.3.15) */
    /* where the pressure's estimate's largest part is: a bin's middle
     * (RD_EST_LEVELS, RD_EST_LAW) or a bin boundary, deg on the bore (NAN:
     * none), and which part (RD_EST_*) */
    double pressure_at_deg;
    int pressure_source;
    double pressure_levels; /* of the pressure's: half the bins' largest change between the
                               levels, / p0 (the part the bin-boundary shares do not hold), or
                               (pressure_shifted) that change less what shifting the coarser
                               level's segments moves */
    int pressure_shifted;   /* 1: pressure_levels from the pair solved again on meshes shifted
                               by half a segment (since 0.3.10, rd_contact_refine.c) */
} rd_contact_estimates;

/* Counters and accuracy common to both analyses. */
typedef struct rd_static_stats {
    int segments, dof;
    int load_steps;     /* accepted load steps */
    int iterations;     /* Newton iterations, all steps, the main solve */
    int factorizations; /* tangents assembled and factored (contact: the chord step after
                           each multipliers' update reuses one) */
    /* contact: the multipliers' updates (Uzawa; 0 otherwise), the last one's
     * largest change / p0 and its tolerance: stopped at the updates' limit if
     * the change is above the tolerance */
    int outer_iterations;
    double outer_change, outer_tolerance;
    double residual;        /* final relative residual */
    double tolerance;       /* residual tolerance used: the requested one, or the
                              rounding floor of this ring if that is larger */
    double support_force;   /* |force| the support/pin carries, N */
    double support_moment;  /* |moment| it carries, N m */
    int reference_segments; /* segments of the error-estimate solve; 0 if none */
    double error_estimate;  /* relative, of the headline quantity; NAN if none */
    double strain_energy;   /* J */
} rd_static_stats;

typedef struct rd_pretension_result {
    rd_static_stats stats;
    double gap_opening_inner;   /* x_a: distance between the inner gap corners (mid-height), m */
    double lateral_opening;     /* x_c: axial separation of the inner top corners, m */
    double gap_opening_neutral; /* distance between the face centroids, m */
    double free_gap_formula;    /* closed gap + m of (1.4)-(1.5), m */
    double conformability;      /* k of (1.4) */
    /* The gap between the running face's tips at the centroid's height, m;
     * and with a free shape (rd_free_shape; NAN otherwise) the tangential
     * force that closes it to the closed gap by forces normal to the gap
     * faces at their centroids (the force method's), N. */
    double free_gap, tangential_force;
    /* Deformed centroid line, n + 2 points: first face, the n reference
     * points, last face; x, y, z each; and each point's reference angle. */
    int points;
    double *x, *y, *z, *angle_deg;
    /* The running face at the centroid's height over the same n + 2 points
     * (the free ends' outer corners, the segments' middles): polar angle
     * from the point opposite the gap about the closed ring's centre, deg,
     * increasing, and radius, m: the free shape as a gauge measures it. */
    double *face_theta_deg, *face_radius;
    /* With a free shape (NULL otherwise): the twist of the ring closed by the
     * pressure it was made for (rd_free_shape.c's rd_free_shape_installed),
     * each section's turn about the ring's tangent relative to the section
     * opposite the gap, deg, positive the ring makers' positive twist (the
     * inner edge down, away from the combustion side), at the same n + 2
     * points (the free ends take their segments'); geometrically exact, 0
     * for a section symmetric about its mid-height. */
    double *static_twist_deg;
} rd_pretension_result;

typedef struct rd_contact_result {
    rd_static_stats stats;
    /* Per segment (the contact points of one rigid segment share its misfit
     * against a curved bore, so only their resultant is meaningful): */
    int points;              /* = segments */
    double *angle_deg;       /* position angle of the segment's running-face middle, deg */
    double *pressure;        /* resultant contact force / (h * segment's running-face arc), Pa */
    double *clearance;       /* closest approach of its points to the bore, m (<= 0: touching) */
    double *bore_radius;     /* bore radius at the segment's middle, m */
    double *width_deg;       /* the segment's arc on the ring, deg: all alike unless the
                                refinement graded them (grade_* below) */
    double *twist_deg;       /* the section's turn about the ring's tangent, deg, positive the
                                ring makers' positive twist (the inner edge down, away from
                                the combustion side +z), relative to the section opposite the
                                gap (held in its tilts): 0 unless the section's principal axes
                                are turned and the ring is made with a free shape */
    double mean_pressure;    /* mean of the segment pressures over their arcs, Pa */
    double uniform_pressure; /* 2 F_t / (d h) (1.3), Pa */
    double contact_fraction; /* contact length / running-face length (point clearances,
                                   edges located between points) */
    double max_clearance;    /* largest segment clearance (light gap), m, >= 0 */
    double max_clearance_angle_deg; /* where; NAN when the ring touches everywhere */
    double max_penetration;         /* m: what the contact stiffness allows */
    double stiffness;               /* k used, Pa/m */
    double conformability;          /* k of (1.4) */
    /* Thin-ring conformability bound of each distortion order:
     * F_t R^3 / (E I (k^2 - 1)^2), m (NAN for k = 1). */
    double bound[RD_BORE_ORDERS_MAX];
    /* Light gaps deeper than gap_floor (rd_contact_gap_floor, or a rigid
     * face's misfit), in angle order; edges where the clearance crosses
     * zero, angles where on the bore. */
    int n_gaps;
    rd_contact_gap gaps[RD_CONTACT_GAPS_MAX];
    double gap_floor;         /* m */
    double marginal_gap_deg;  /* width of the runs off the bore whose depth is within x2 of
                                gap_floor, counted or not: the contact fraction's threshold
                                uncertainty, deg */
    double marginal_depth;    /* of those runs, the depth nearest gap_floor (by ratio), m; 0
                                 if none */
    double point_spacing_deg; /* contact points' spacing (graded: the finest), deg: the edge
                                 locator's resolution */
    int points_per_segment;   /* m */
    int graded;               /* the segments are not all alike */
    double tip_force[2];      /* concentrated force at the first / last free end, N */
    double edge_bin_share;    /* the most a segment holding a gap edge put past a bin boundary
                                 from the edge, as a bin pressure, Pa (rd_contact_bins) */
    double edge_bin_at_deg;   /* that boundary, deg (NAN: none) */

    /* The contact patches (since 0.3.15), in angle order; the deepest points
     * of the runs off the bore within x2 of gap_floor (marginal_gap_deg's, at
     * most RD_CONTACT_GAPS_MAX), deg; and the most force such a run would move
     * from a patch were it counted the other way (a patch split in two, or
     * two merged), N. */
    int n_patches;
    rd_contact_patch patches[RD_CONTACT_GAPS_MAX + 1];
    int n_marginal;
    double marginal_at_deg[RD_CONTACT_GAPS_MAX];
    double patch_marginal_n;

    double bin_pressure[RD_CONTACT_BINS]; /* mean pressure over the ring's arc in each
                                   RD_CONTACT_BIN_DEG bin, Pa */
    /* Accuracy: estimates of the reported values' errors from the last two
     * refinement levels (the reported level is the finer), the target, and
     * whether it was met (if not, why, in accuracy_note). */
    rd_contact_estimates estimates;
    double accuracy;
    int accuracy_met; /* 1 met, 0 not (see accuracy_note), -1 not estimated */
    double law_share; /* the contact law's share in estimates.pressure, of p0: twice the
                         binned pressure's move at twice the stiffness (NAN if not solved) */
    int levels;       /* solves made */
    /* The local refinement of the reported level (0.3.7): its segments
     * over each arc grade_factor times finer than the rest's grade_base
     * (equal) segments, halving outwards; grade_factor 1 (and no arcs):
     * equal segments. */
    int grade_base, grade_factor, grade_arcs;
    double grade_lo_deg[RD_CONTACT_ARCS_MAX], grade_hi_deg[RD_CONTACT_ARCS_MAX];
    char accuracy_note[512];
} rd_contact_result;

void rd_static_opts_default(rd_static_opts *o);
void rd_pretension_opts_default(rd_pretension_opts *o);
void rd_contact_opts_default(rd_contact_opts *o);

/* Range checks of a scene's blocks, paths relative to its root (each block
 * entered: "/pretension/...", "/bore/...", "/contact/...", "/numerics/..."). */
int rd_static_validate(const rd_static_opts *o, int segments, int closed, rd_error *err);
int rd_pretension_validate(const rd_pretension_opts *o, const rd_ring_params *p, int segments,
                           rd_error *err);
int rd_contact_validate(const rd_contact_opts *o, const rd_ring_params *p, rd_error *err);

/* Default contact stiffness: 2e6 E I / (h R^4), so the penetration under the
 * nominal pressure is 5e-7 of the radial deflection scale of the ring (1e6
 * until 0.3.1: twice as stiff, the multipliers' updates converge in fewer
 * steps and the answers of bench_static's battery move less with the law;
 * its estimates track the error on more bores). */
double rd_contact_default_stiffness(const rd_ring_params *p);

/* The light gaps' floor: runs off the bore no deeper than this are contact,
 * ten times the penetration under p0 of a law of 1e6 E I / (h R^4) (9.4 nm
 * for the thesis ring): a property of the ring, not of the chosen
 * stiffness (with the multipliers the ring does not sink into the bore at
 * any stiffness). */
double rd_contact_gap_floor(const rd_ring_params *p);

/* The contact points a segment carries at n segments when m are asked for:
 * m up to 640 segments, then no closer than 360/6400 deg, and at least 5
 * (or m if fewer).  Measured on bench_static's battery at n = 1280: the
 * binned pressure within 0.02 p0 of the reference on the same 31 of 32
 * bores with 5 points as with 10, the hardest bore's CPU time 0.20 -> 0.16 s
 * (half the points' evaluations, about half the Newton iteration's cost). */
int rd_contact_points(int m, int n);

/* Checks a free shape (paths relative to the ring's block,
 * "/pressure_distribution/..."): the
 * orders, amplitudes and tables' ranges, and p > 0 around the ring.  Any
 * section: a turned one twists when closed (rd_pretension_result's
 * static_twist_deg). */
int rd_free_shape_validate(const rd_free_shape *fs, const rd_ring_params *p, rd_error *err);
/* p(theta) / p0 of a RD_FREE_PRESSURE shape at theta (rad, from the point
 * opposite the gap); 1 for a uniform one. */
double rd_free_shape_pressure(const rd_free_shape *fs, double theta);

/* Conformability k (1.4) and the free gap m from (1.5). */
double rd_ring_conformability(const rd_ring_params *p);
double rd_ring_free_gap_formula(const rd_ring_params *p);

/* Solve; results own their arrays (cleanup also after a failure). */
int rd_pretension_solve(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                        const rd_static_opts *so, const rd_monitor *mon, rd_pretension_result *out,
                        rd_error *err);
int rd_contact_solve(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                     const rd_static_opts *so, const rd_monitor *mon, rd_contact_result *out,
                     rd_error *err);
/* The contact solve in every layer of a bore map (rd_bore_map.h): res[i]
 * (the caller's array of map->n_layers results, each cleaned up by the
 * caller, also after a failure) is rd_contact_solve with o's bore replaced
 * by layer i's.  A layer's failure names the layer in its message. */
struct rd_bore_map;
int rd_contact_solve_layers(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                            const struct rd_bore_map *map, const rd_static_opts *so,
                            const rd_monitor *mon, rd_contact_result *res, rd_error *err);
void rd_pretension_result_cleanup(rd_pretension_result *r);
void rd_contact_result_cleanup(rd_contact_result *r);

#endif
