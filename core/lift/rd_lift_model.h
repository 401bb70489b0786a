/*
 * rd_lift_model.h — the full lift model's pieces, shared by its files (not
 * part of the public API: core/lift/ is private to core; tests and benches
 * reach it through ringdyn_core_internal).
 *
 * The lift folder, split by concern (MODEL.md "lift" and rd_lift.h for the
 * physics; each file's comment for its part; docs/architecture.md):
 *   rd_lift.c         parameters and their validation
 *   rd_lift_scales.c  the scene's scales: largest flank pressure, default
 *                     contact stiffness, acceleration scale
 *   rd_lift_model.c   the model: state layout, geometry of the contact
 *                     points, mass (M_i^-1) and stiffness (K, -M_i^-1 K_ij),
 *                     the right-hand side and the Jacobian assembled from
 *                     the force elements
 *   rd_lift_forces.c  the force elements, each a small unit that adds its
 *                     generalized force on segment i and its local Jacobian
 *                     contribution df_i/dq_i, df_i/dv_i: inertia and
 *                     gravity, flank contacts, bore contact and friction
 *                     (the liner's law, core/liner), groove back, gas faces
 *   rd_lift_landing.c the landing law: the oil squeeze film on the flanks
 *   rd_lift_bore.c    a distorted bore's offsets per contact point
 *   rd_lift_start.c   the static start in a distorted bore
 *   rd_lift_rigid.c, rd_lift_modal.c   the reduced formulations
 *   rd_lift_newton.c  the Newton systems in second-order form (half the
 *                     unknowns, block-tridiagonal LU of I - gamma B -
 *                     gamma^2 A by rd_blocktri.c)
 *   rd_lift_small.c   the small forms' TR-BDF2 integrator; rd_lift_stick.c
 *                     the seated ring's sticking phase
 *   rd_lift_driver.c  the CVODE driver (core/numerics/rd_cvode.h): set-up,
 *                     events (root finding and the flank state machine),
 *                     output sampling, counters, the work bound and
 *                     cancellation
 *   rd_lift_partial.c what a stopped run keeps
 *   rd_lift_check.c   auto's run-time check of a rigid run on a friction
 *                     scene: the full ring over the rigid run's flights
 *   rd_lift_solve.c   the public handle and solve (what a scene's runs
 *                     share, the model's choice and its check, the accuracy
 *                     driver's solves: rtol/10 and n/2, and their
 *                     comparison), on top
 *   rd_lift_hooks.c   the test hooks (Jacobian check, twist stiffness)
 * The piston's kinematics and tilt are core/engine's (rd_engine.h).
 *
 * State layout (interleaved per segment so that the Jacobian is banded):
 *     y[12 i + k] = q_i[k],  y[12 i + 6 + k] = v_i[k],  k = 0..5   (Q(), V())
 *
 * Jacobian structure, and the plan for elements that couple all segments.
 * Today every force element is local: f_i depends on q_i, v_i only, so its
 * contribution is a 6x6 block on the diagonal, and the only coupling is the
 * ring's K (segment i to i +- 1; the ring is open, so 0 and n - 1 are not
 * coupled): block tridiagonal, a band with MU = 11, ML = 23; its Newton
 * system is solved in second-order form by block-tridiagonal LU in O(n)
 * (rd_lift_newton.c; "band LU" below stands for that factorization, whose
 * rd_blocktri_solve gives the extra solves).  Two planned elements break
 * locality:
 *  - a gas volume shared by the whole ring (a groove-back or inter-ring
 *    land pressure p_g that is a state, dp_g/dt = g(p_g, all flank gaps)):
 *    p_g becomes one extra unknown appended after the 12 n segment states.
 *    Its row depends on every segment (the gaps) and its column acts on
 *    every segment (the face loads), so the Newton matrix is banded with a
 *    border: [B  U; V^T  D] with B the band, U, V of width m = number of
 *    shared volumes.  Solve by block elimination: factor B (band LU, as
 *    today), solve B X = U (m extra band solves), then the dense m x m
 *    Schur complement D - V^T X, then back-substitute; O(n m + m^3) per
 *    step, keeping the band cost.  This needs a custom SUNLinearSolver
 *    (setup: band LU of B, X, the Schur factorization; solve: two band
 *    solves and one m x m solve) over a SUNMatrix that stores the band and
 *    the border; a force element then adds, besides its 6x6 local block,
 *    entries of U (d f_i / d p_g) and V (d g / d q_i).
 *  - several rings in a pack: each ring keeps its own band block (its own
 *    K, its own segments), the rings couple only through the shared gas
 *    volumes between them, so the pack's matrix is block-diagonal in the
 *    rings plus the same border (one column per inter-ring volume), solved
 *    by the same bordered elimination with one band factorization per ring.
 * Force elements stay "add f and the local blocks"; the border entries are
 * a second, optional output of the few elements that touch a shared volume.
 */
#ifndef RD_LIFT_MODEL_H
#define RD_LIFT_MODEL_H

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "rd_internal.h"
#include "rd_lift.h"
#include "rd_lift_internal.h"
#include "rd_liner_law.h"

#define RD_LIFT_GRAVITY      9.80665
#define RD_LIFT_ARC_POINTS   3 /* contact positions along a segment's arc */
#define RD_LIFT_FLANK_POINTS (2 * RD_LIFT_ARC_POINTS)
#define RD_LIFT_MU           11 /* upper half bandwidth of the Jacobian */
#define RD_LIFT_ML           23 /* lower half bandwidth */

/* State access, cvRoberts style. */
#define RD_LIFT_Q(y, i) ((y) + 12 * (size_t)(i))
#define RD_LIFT_V(y, i) ((y) + 12 * (size_t)(i) + 6)

/* The full model of one ring: constants of the scene and the geometry of its
 * contact points, plus scratch and the force elements' last outputs. */
typedef struct rd_lift_model {
    const rd_ring *ring;
    const rd_lift_params *p;
    int n, piston_fixed;
    double omega;  /* crank speed, rad/s */
    double ca, cr; /* axial and radial clearances */
    double k, d0, c_flank, c_rad;
    double eps;           /* the band's edge on the mean lift, m (flank_band c_a; without
                           * a band the 1 % that confirms a leave) */
    int banded;           /* 1: flank changes dated at the band's edge (flank_band > 0) */
    double g_on;          /* gravity, m/s^2, or 0 */
    double p0, delta_pre; /* pretension pressure and bore preload penetration */
    rd_liner liner;       /* the running face on the liner: friction (rd_liner_law.h) */
    double h, L_run;
    int sq_on;                        /* the squeeze-film landing law (rd_lift_landing.c) */
    double sq_coef, sq_hmin, sq_vreg; /* mu b^2 (Pa s m^2), h_min (m), v_r (m/s) */
    rd_band K;
    double *Minv; /* n x 36 row-major */
    double *Mez;  /* n x 6: M_i e_z */
    double *fl_d; /* n x FLANK_POINTS x 2: in-plane offsets of flank points */
    double fl_area[RD_LIFT_FLANK_POINTS];
    double *bo_d, *bo_e;     /* n x ARC_POINTS x 2: bore point offsets, radial unit */
    double *ba_d;            /* n x ARC_POINTS x 2: back point offsets */
    double bo_area, ba_area; /* per point */
    double *cen_d;           /* n x 2: face centroid offsets */
    double *bo_gap;          /* n x ARC_POINTS: the bore's outward offset at each bore
                            * point (rd_lift_bore.c), NULL for the round bore; with a bore
                            * map, at the ring's depth of the last force call's t */
    double *bo_layers;       /* a bore map: n_layers x (n x ARC_POINTS), each layer's offsets */
    double *e_r;             /* n x 2: segment radial unit */
    double *e_t;             /* n x 2: segment tangential unit */
    double face_area, back_chord_area;
    double face_width;      /* the flank face's radial width b, m */
    double *qbuf, *fbuf;    /* 12 n and 6 n scratch */
    double *MK;             /* n x 3 x 36: -M_i^-1 K_ij, j = i-1, i, i+1 */
    double *Dq, *Dv;        /* n x 36: local force derivatives (Jacobian) */
    double friction;        /* total axial friction of the last force call, N */
    double fz_ext;          /* total axial force on the ring except the flanks, N */
    rd_lift_energy *energy; /* non-NULL: the forces accumulate the bookkeeping */
    /* Non-NULL: the gauge gas pressures (above, behind, below; Pa) of every
     * force call, instead of p->gas's tables: a caller that computes them
     * (the ring pack, rd_ringpack_lift.c) sets them before each call. */
    const double *gas_now;
    /* The piston's kinematics of the last force call, at time kin_t (NAN:
     * none): a call at the same time reuses them (a step's Newton
     * iterations, Jacobian and roots share its time).  Set by the force
     * calls only. */
    double kin_t, kin[6]; /* sd, acc, cb, sb, bd, bdd (force_env) */
    /* p->films (a distorted bore's films): scratch of each force call, the
     * films (count) and each segment's (n) at t (rd_lift_films_at). */
    rd_film_point *film_grp, *film_seg;
} rd_lift_model;

/* The scratch of p->films' points (film_grp, film_seg) for the films now
 * set (none: freed); the model's init calls it, and whoever sets p->films
 * on a model already made (the ring pack's rings). */
int rd_lift_model_films(rd_lift_model *m, rd_error *err);
/* Builds the model of a valid scene on `ring` (borrowed, as p).  On failure
 * the model is still safe to clean up. */
int rd_lift_model_init(rd_lift_model *m, const rd_ring *ring, const rd_lift_params *p,
                       const rd_lift_setup *setup, rd_error *err);
void rd_lift_model_cleanup(rd_lift_model *m);

static inline double rd_lift_dot6(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

/* Inverse of the contacts' elastic part: the penetration where k sp(delta)
 * = p (rd_lift_forces.c). */
double rd_lift_contact_inverse(const rd_lift_model *m, double p);

/* The squeeze-film landing law (rd_lift_landing.c): its constants from the
 * scene (after ca and omega are set), and its pressure (Pa) at a flank
 * point with gap `gap` (m) closing at `closing` (m/s), with the partial
 * derivatives dp/dgap, dp/dclosing. */
void rd_lift_landing_init(rd_lift_model *m, const rd_section *s, const rd_lift_params *p);
double rd_lift_squeeze(const rd_lift_model *m, double gap, double closing, double *p_gap,
                       double *p_closing);

/* Generalized forces on all segments (without -K q) into m->fbuf; with Dq,
 * Dv (n x 36 each) also their local derivatives df_i/dq_i, df_i/dv_i.  Sets
 * m->friction and m->fz_ext (rd_lift_forces.c). */
void rd_lift_forces(rd_lift_model *m, double t, const double *y, double *Dq, double *Dv);
/* A gas table's value at crank angle deg (linear, periodic over 720 deg). */
double rd_lift_gas_at(const rd_gas_params *g, const double *val, double deg);

/* Only m->friction and m->fz_ext of rd_lift_forces, the same numbers (the
 * same elements in the same order), without the flank and groove-back
 * contacts, which do not enter them (the flanks still run with dynamic gas
 * areas: their sealing weights; the bore contact only with friction), and
 * without the Jacobian; m->fbuf is left partial.  For the root function and the samples (rd_lift_model.c). */
void rd_lift_loads(rd_lift_model *m, double t, const double *y);

/* The radial contact pressure on the running face at state y (the full
 * state, 12 n) and time t (the bore at the ring's depth then): each
 * segment's mean over its bore points into seg (n values), Pa.  The
 * segment's, not a point's: a rigid segment on a curved bore bears on some
 * of its points only. */
void rd_lift_bore_pressure(rd_lift_model *m, double t, const double *y, double *seg);

/* rd_lift_loads for one segment i at state (q, v) (6 values each; f: 6
 * scratch), the ring's loads being n times its (the rigid model). */
void rd_lift_loads_segment(rd_lift_model *m, double t, int i, const double *q, const double *v,
                           double *f);

/* rd_lift_forces for one segment i at state (q, v) (6 values each): its force
 * into f (6), its local derivatives into dq, dv (36 each, or NULL), and its
 * friction and axial load without the flanks into m->friction, m->fz_ext. */
void rd_lift_forces_segment(rd_lift_model *m, double t, int i, const double *q, const double *v,
                            double *f, double *dq, double *dv);

/* The CVODE callbacks of the model (user data: the rd_lift_model).
 * rhs: ydot = (v, M^-1 (f - K q)) per segment; 1 (recoverable) if not
 * finite.  jac: d(ydot)/dy into the band matrix J (RD_LIFT_MU, RD_LIFT_ML). */
int rd_lift_cv_rhs(sunrealtype t, N_Vector y, N_Vector yd, void *user);
int rd_lift_cv_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user, N_Vector t1,
                   N_Vector t2, N_Vector t3);

/* Mean lift L (mean over segments of the bottom face's axial position);
 * per-segment values into seg (n values) when not NULL. */
double rd_lift_model_mean_lift(const rd_lift_model *m, const double *y, double *seg);

/* The scene's largest acceleration (m/s^2, for the velocity tolerance) and
 * the largest pressure it can put on a flank (Pa) (rd_lift_scales.c). */
double rd_lift_accel_scale(const rd_ring_params *rp, const rd_lift_params *p);
double rd_lift_flank_pressure_scale(const rd_ring_params *ring, const rd_lift_params *p);

/* Output samples of a valid scene: cycles x 720 / step_deg + 1 (rd_lift.c). */
int rd_lift_samples(const rd_lift_params *p);

/* A formulation of the equations the driver integrates: the full model's
 * 12 n states, or a reduced one (rd_lift_rigid.c) built on the same model's
 * geometry and force elements.  `user` is passed to every function. */
typedef struct rd_lift_form {
    const char *name; /* "full", "rigid" */
    sunindextype N;   /* number of states */
    int dense;        /* 1: dense Newton matrix; 0: band (RD_LIFT_MU, RD_LIFT_ML) */
    void *user;
    rd_lift_model *m; /* the model whose constants (ca, eps, omega, p) apply */
    CVRhsFn rhs;
    CVLsJacFn jac; /* the Jacobian as a matrix (the Jacobian check only) */
    /* The Newton system in second-order form (rd_lift_newton.c): the state
     * is N / (2 block) blocks of [q (block values), v (block values)] with
     * q' = v; `blocks` puts at (t, y) d(v')/dq, row block i's blocks i-1, i,
     * i+1 (block x block row-major each, zero outside the ring) into A
     * (N / (2 block) x 3 x block^2) and d(v')/dv (block diagonal) into B.
     * blocks NULL: CVODE's dense or band Newton matrix from `jac` instead. */
    int block;
    void (*blocks)(void *user, double t, const double *y, double *A, double *B);
    /* mean lift L; the per-segment lifts into seg (n values) when not NULL */
    double (*lift)(void *user, const double *y, double *seg);
    int uniform; /* 1: every segment's lift is the mean (the rigid form) */
    /* the loads at (t, y): sets m->fz_ext and m->friction */
    void (*loads)(void *user, double t, const double *y);
    /* the 12 n full state of y into full; NULL: y is the full state */
    void (*expand)(void *user, const double *y, double *full);
    /* A plastic landing (rd_lift.h enum rd_lift_landing): arrests in y the
     * ring's axial velocity towards the flank (upper: 1 the upper flank). */
    void (*impact)(void *user, double *y, int upper);
    /* the initial state and absolute tolerances (atol on translations, m) */
    int (*initial)(void *user, const rd_lift_setup *setup, double atol, double *y, double *abstol,
                   rd_error *err);
    /* the central-difference step of state j for the Jacobian check; NULL:
     * the driver's rule for the full and rigid layouts */
    double (*fd_step)(void *user, sunindextype j);
    /* frees `user`; NULL: nothing to free (the full model) */
    void (*close)(struct rd_lift_form *form);
} rd_lift_form;

/* The Newton solver of a form (rd_lift_newton.c): a DIRECT SUNLinearSolver
 * over the second-order system matrix *S (owned by the solver, to be given
 * to CVodeSetLinearSolver with it), and its handle for the linear-system
 * function: rd_lift_newton_linsys evaluates the form's blocks at (t, y)
 * unless jok (CVODE allows reuse), sets *jcur, and assembles S for gamma.
 * NULL when out of memory.  `form` must outlive the solver. */
typedef struct rd_lift_newton rd_lift_newton;
SUNLinearSolver rd_lift_newton_create(const rd_lift_form *form, SUNContext ctx, SUNMatrix *S,
                                      rd_lift_newton **nw);
int rd_lift_newton_linsys(rd_lift_newton *nw, double t, N_Vector y, int jok, int *jcur,
                          double gamma);

/* The full model as a formulation (rd_lift_model.c). */
void rd_lift_full_form(rd_lift_model *m, rd_lift_form *form);

/* The rigid model (rd_lift_rigid.c): uniform axial lift, twist and radial
 * motion of the whole ring.  rd_lift_rigid_open allocates its state; the
 * form's user is freed by rd_lift_rigid_close. */
int rd_lift_rigid_open(rd_lift_model *m, rd_lift_form *form, rd_error *err);
void rd_lift_rigid_close(rd_lift_form *form);
/* The rigid ring's twist stiffnesses on m (N m / rad): free, seated on the
 * inner edge, on the outer edge (rd_lift_rigid.c). */
int rd_lift_rigid_twist(rd_lift_model *m, double k[3], rd_error *err);

/* The bore (rd_lift_bore.c): the per-point offsets of a distorted bore into
 * m->bo_gap (NULL for a round one), and the static equilibrium of the
 * installed ring in it (y0: 12 n values, the rates 0). */
int rd_lift_bore_init(rd_lift_model *m, rd_error *err);
/* A bore map: m->bo_gap at the ring's depth when the piston has travelled
 * s (m) from TDC (linear in depth between the map's layers, as the map). */
void rd_lift_bore_at_travel(rd_lift_model *m, double s);
int rd_lift_bore_static(const rd_ring *ring, const rd_lift_params *p, double *y0, rd_error *err);

/* The modal model (rd_lift_modal.c): the 6 rigid-body and `modes` lowest
 * elastic modes of the ring (1 <= modes <= 6 n - 6; n at most
 * RD_LIFT_MODAL_SEGMENTS_MAX, its modes are solved densely).  The form's
 * close frees it (also after a failed open). */
#define RD_LIFT_MODAL_SEGMENTS_MAX 200
int rd_lift_modal_open(rd_lift_model *m, int modes, rd_lift_form *form, rd_error *err);
void rd_lift_modal_close(rd_lift_form *form);

/* The formulation of `model` (enum rd_lift_model_kind, not auto) on m
 * (rd_lift_driver.c); on failure the form is safe to close. */
int rd_lift_form_open(rd_lift_model *m, int model, int modes, rd_lift_form *form, rd_error *err);

/* One integration of `model` (enum rd_lift_model_kind, not auto; modal with
 * run->modes) at tolerances (rtol, atol): `res`
 * (optional) receives the per-sample results and the counters, `lift`
 * (samples values) the mean lift, *events / *n_events the flank changes
 * (owned by the caller after the call, also on failure) (rd_lift_driver.c). */
typedef struct rd_lift_pass {
    double rtol, atol;
    int modes; /* elastic modes of the modal model */
    int dof;   /* out: degrees of freedom integrated (states / 2) */
    /* out, when /numerics/max_steps ran out (RD_ELIMIT) or the monitor
     * stopped the run: the samples stored (0 .. done - 1) and the crank
     * angle the integrator reached, deg */
    int done;
    double reached_deg;
    rd_lift_result *res; /* may be NULL */
    double *lift;        /* samples values */
    int samples;
    rd_lift_event *events;
    int n_events, cap_events;
} rd_lift_pass;
int rd_lift_integrate(const rd_ring *ring, const rd_lift_params *p, const rd_lift_setup *setup,
                      int model, const rd_monitor *mon, rd_lift_pass *run, rd_error *err);

/* The run-time check of a rigid run's flank changes against the full ring
 * over its flights (rd_lift_check.c): worst_deg the largest move of a
 * flank change, NAN when the full ring's differ in number or kind (the
 * check stops at that window); the windows and events checked and the full
 * ring's steps there. */
typedef struct rd_lift_check {
    double worst_deg;
    int windows, events;
    long steps;
} rd_lift_check;
typedef struct rd_lift_check_in {
    const rd_lift_event *events; /* the rigid run's */
    int n_events;
    const double *states;       /* its form's state at every output sample, N each */
    int N;                      /* 6 */
    const rd_lift_form *expand; /* a rigid form of the scene: expands a state to 12 n */
    double *flex_deg; /* out, n_events (may be NULL): the full ring's angle of each checked
                         flank change, NAN where not matched */
} rd_lift_check_in;
/* mon: progress over the windows and the cancel (RD_ECANCELED, RD_ETIMEOUT
 * returned as such). */
int rd_lift_check_rigid(const rd_ring *ring, const rd_lift_params *p, const rd_lift_check_in *in,
                        const rd_monitor *mon, rd_lift_check *out, rd_error *err);

/* A level-0 run `r` that stopped with `why` (RD_ELIMIT, RD_ECANCELED or
 * RD_ETIMEOUT) keeps its whole cycles in `out` (partial = 1, samples cut to
 * the last whole cycle, warning); returns RD_OK for RD_ELIMIT with at least
 * one whole cycle (err cleared), else `why` (rd_lift_partial.c). */
int rd_lift_keep_partial(rd_lift_result *out, const rd_lift_params *p, const rd_lift_pass *r,
                         int why, rd_error *err);
/* A run stopped in its error-estimate run (`why`: a stop, or RD_ELIMIT at
 * `reached_deg`): every cycle, no estimate; returns RD_OK for RD_ELIMIT (err
 * cleared), else `why` (rd_lift_partial.c). */
int rd_lift_estimate_stopped(rd_lift_result *out, const rd_lift_params *p, int why,
                             double reached_deg, rd_error *err);

/* The flank-change state machine of the events (rd_lift_driver.c header):
 * the committed flank (enum rd_flank) and the time a pending leave started
 * (its load's sign change), NAN if none.  rd_lift_track_roots advances it at
 * a root return: rf the root flags of the five roots L, L - eps, c_a - L,
 * c_a - L - eps, the load fz (N) at time t (s); events go to run. */
typedef struct rd_lift_flank_track {
    int state;   /* enum rd_flank: the band the mean lift is in (without a band:
                  * the flank it sits on) */
    double cand; /* when the load turned away from the flank it touches, s; NAN */
    int banded;  /* 1: events at the band's edge (rd_lift_model.banded) */
    int touched; /* 1: the mean lift has reached the flank since it entered the band */
    int landing; /* index in run->events of the landing awaiting its touch, or -1 */
} rd_lift_flank_track;
/* A ring seated at rest on its lower flank; fz its load at time t. */
rd_lift_flank_track rd_lift_track_seated(int banded, double fz, double t);
int rd_lift_track_roots(rd_lift_flank_track *tr, const int *rf, double t, double deg_per_s,
                        double fz, rd_lift_pass *run, rd_error *err);

#endif
