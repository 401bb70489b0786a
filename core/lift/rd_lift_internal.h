/* rd_lift_internal.h — test and benchmark hooks of rd_lift (not part of the
 * public API; no caller outside core/, tests/ and bench/ may include this).
 *
 * rd_lift_solve runs the scene as the user gives it: the ring starts seated
 * at rest on the lower flank and the piston moves.  Some checks need other
 * set-ups (a free vibration in the middle of the groove with the piston at
 * rest, the friction regularization halved, the state at every sample); they
 * go through rd_lift_solve_setup with the same code path. */
#ifndef RD_LIFT_INTERNAL_H
#define RD_LIFT_INTERNAL_H

#include "rd_film_track.h"
#include "rd_lift.h"

/* Energy bookkeeping of one state (rd_lift_setup.energy).  Along a solution
 *   d/dt (kinetic + strain + contact) = friction_power + damping_power
 *                                       + the power of the piston's pseudo-
 *                                         force, gravity and gas
 * (kinetic and strain: rd_ring_kinetic_energy, rd_ring_strain_energy). */
typedef struct rd_lift_energy {
    double contact;        /* J: potential of the contacts' elastic parts, A k int_0^delta sp
                            * over flanks, bore and groove back, minus the work of the
                            * constant pretension, sum p0 A u_r over the bore points */
    double friction_power; /* W: sum over the bore points of F u, u the sliding velocity
                            * (with the piston fixed, the friction's power on the ring) */
    double damping_power;  /* W: power on the ring of the contacts' damping parts,
                            * sum -(p - k sp) A delta' (<= 0) */
} rd_lift_energy;

typedef struct rd_lift_setup {
    /* Initial state, 12 n values, per segment [q_i (6), v_i (6)] (the state
     * layout of rd_lift.c); borrowed.  NULL: seated at rest (q = v = 0). */
    const double *y0;
    int piston_fixed;  /* 1: the piston does not move (no inertia pseudo-force) */
    double ureg_scale; /* multiplies the friction regularization velocity; 0 = 1 */
    /* Called at every output sample with the time (s) and the state (12 n);
     * NULL: not called. */
    void (*sample)(void *ctx, double t, const double *y);
    void *ctx;
    /* Called at every output sample, after `sample`, with the same ctx, the
     * time (s) and the energy bookkeeping of the state; NULL: not called. */
    void (*energy)(void *ctx, double t, const rd_lift_energy *e);
    /* A window of the run (the auto check, rd_lift_check.c): from t0_deg
     * (state y0, seated at rest when NULL) to t1_deg, sampled every step_deg
     * from t0_deg (the run's `samples` must match); t1_deg = 0: the whole
     * run.  stop_events > 0: the run ends at the root where it has recorded
     * that many flank changes and its mean lift touches the flank of the
     * last, or where it records more (its samples stop there: `done`). */
    double t0_deg, t1_deg;
    int stop_events;
    /* Called at every output sample with the time (s) and the integrated
     * form's own state (N values: 6 for the rigid ring, 12 n for the full
     * one); NULL: not called.  Same ctx. */
    void (*state)(void *ctx, double t, const double *y, int N);
} rd_lift_setup;

/* rd_lift_solve with a set-up; setup == NULL is rd_lift_solve. */
int rd_lift_solve_setup(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                        const rd_lift_setup *setup, const rd_monitor *mon, rd_lift_result *out,
                        rd_error *err);

/* Largest relative difference between the analytic Jacobian of the lift
 * equations at (t, y) and central differences of the right-hand side: the
 * full model's (y: 12 n values), or the rigid model's when p->model is
 * RD_LIFT_MODEL_RIGID (y: z, theta, r and their rates, 6 values) (entries smaller than 1e-6 of the largest are compared
 * absolutely at that level). */
int rd_lift_jacobian_check(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                           double t, const double *y, double *max_err, rd_error *err);

/* The rigid model's twist stiffnesses of a valid scene (rd_lift_rigid.c),
 * N m / rad: k[0] of the uniform twist shape, k[1], k[2] of the split ring
 * seated on its inner, outer edge under a uniform couple. */
int rd_lift_twist_stiffness(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                            double k[3], rd_error *err);

/* The lubricated model (rd_lift_film.c): the film of the running face over
 * the run, solved before the ring's motion (`film` and `tr` the caller's,
 * freed with rd_film_free and rd_film_track_free also after a failure),
 * and the result's lubrication block from it (out's samples set). */
int rd_lift_film_run(const rd_ring_params *rp, const rd_lift_params *p, rd_film *film,
                     rd_film_track *tr, rd_error *err);
/* The same on a grid `fine` times finer: (RD_FILM_NODES - 1) fine + 1
 * points, steps at most film_step_deg / fine, local error RD_FILM_RTOL /
 * fine^2 (the error estimate's second film: 2; the tests' reference: 8). */
int rd_lift_film_run_at(const rd_ring_params *rp, const rd_lift_params *p, int fine, rd_film *film,
                        rd_film_track *tr, rd_error *err);
int rd_lift_film_result(const rd_ring_params *rp, const rd_lift_params *p, const rd_film *film,
                        const rd_film_track *tr, rd_lift_result *out, rd_error *err);
/* The lubrication block lb from a film track over S samples at crank
 * angles crank_deg (deg from t_first, s), the friction work and FMEP of C
 * whole cycles from t_first (the ring pack's rings too, rd_ringpack_film.c);
 * lb->film_step_deg is the caller's. */
int rd_lift_lube_fill(rd_lift_lube *lb, const rd_film *film, const rd_film_track *tr,
                      const rd_lube_params *l, const rd_engine_params *e, double diameter,
                      const double *crank_deg, int S, double t_first, int C, rd_error *err);
/* lb's film_error and work_error against `fine`, the same block (S
 * samples) of a film on a grid twice as fine. */
void rd_lift_lube_compare(rd_lift_lube *lb, const rd_lift_lube *fine, int S);
/* The lift's film estimate: its film again on a grid twice as fine
 * (rd_lift_film_run_at, 2), compared with out's lubrication block. */
int rd_lift_film_estimate(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_result *out,
                          rd_error *err);
void rd_lift_lube_cleanup(rd_lift_lube *lb);
/* The oil's viscosity at crank angle deg, Pa s (rd_lube_params). */
double rd_lift_lube_viscosity(const rd_lube_params *l, double deg);

/* The film under elastic line load w_el (N/m) on a grid `fine` times finer
 * (rd_lift_film_run_at's, which takes 2 F_t / D). */
int rd_lift_film_run_load(const rd_ring_params *rp, const rd_lift_params *p, double w_el, int fine,
                          rd_film *film, rd_film_track *tr, rd_error *err);
/* The same under an elastic line load that follows the ring's depth: w_el
 * over nz depths z (rd_lift_depth_interp at rd_lift_depth_at; nz 1: the
 * constant w_el[0], z unread). */
int rd_lift_film_run_table(const rd_ring_params *rp, const rd_lift_params *p, const double *z,
                           const double *w_el, int nz, int fine, rd_film *film, rd_film_track *tr,
                           rd_error *err);
/* The same with the face at arm `lever` (m, along the ring frame's x: R
 * cos of its angle from the gap middle) about the piston pin: a tilting
 * piston's groove slides it past the liner at beta' lever besides the
 * piston's speed (0: none). */
int rd_lift_film_run_history(const rd_ring_params *rp, const rd_lift_params *p, const double *z,
                             const double *w_el, int nz, double lever, int fine, rd_film *film,
                             rd_film_track *tr, rd_error *err);
/* The friction power of film point pt on the ring (W, per the whole liner
 * circumference circ): its shear and its asperities' friction times U. */
double rd_lift_film_power(const rd_film_point *pt, double circ, double mu_b, double ureg);
/* The friction work of one film track over [t0, t0 + cycle] (J, per the
 * whole liner circumference circ): the power over its own steps. */
double rd_lift_film_work(const rd_film_track *tr, double circ, double mu_b, double ureg, double t0,
                         double cycle);

/* A distorted bore's films (rd_lift_films.c).  The ring of m segments
 * presses on the liner with each segment's static contact load: the
 * contact analysis' exact contact of the same ring in the same bore
 * (rd_contact_solve once at 16 n segments, 64 to 320, no estimate:
 * test_lift_films measures it against the contact at 2000 segments; its
 * pressure over its uniform p0, averaged over the segment's arc, times
 * 2 F_t / D), plus the gas behind it.  On a bore map the loads are solved
 * so at each layer the ring passes (depths) and are linear in depth
 * between them, as the map's bore is; the ring's depth at t is
 * rd_lift_depth_at.  Up to RD_LIFT_FILMS_EXACT distinct load histories
 * (within RD_LIFT_FILMS_SAME of 2 F_t / D at every depth) get a film each,
 * under that history.  More are interpolated: films under constant loads
 * at Chebyshev-Lobatto nodes of log(load + 0.1 x 2 F_t / D) over the
 * segments' range, 3, then 5, 9, 17 (nested), until the coarser level
 * misses the new nodes' films (film over max(|h0|, sigma), friction work,
 * relative) by at most RD_LIFT_FILMS_TOL; the finer level is used and that
 * miss kept (interp_check: it tracked the used level's miss against each
 * segment's own film within x0.45-1.1 on test_lift_films' battery, where
 * that miss is the films' own time-step noise, 3e-3 to 9e-3, and more
 * nodes do not lower it).  Each segment's film is the interpolation at
 * its load; along a map at its load at the ring's depth now (varying),
 * quasi-static in the load, and the two segments whose loads swing most
 * are solved under their own histories to measure that (interp_check
 * the larger miss); where that misses by more than RD_LIFT_FILMS_TOL
 * every distinct history gets its own film instead (exact, up to m
 * films).  The film's quantities are linear in the films'
 * points.  The films are solved before the ring's motion; its radial
 * motion during the run does not feed back into the loads.  Usage:
 *     rd_lift_films fs;
 *     rc = rd_lift_films_bore(ring, p, &fs, err);   (or rd_lift_films_run)
 *     q.films = &fs;   each force call: rd_lift_films_at(&fs, t, n, grp, seg)
 *     rd_lift_films_free(&fs);   also after a failure */
#define RD_LIFT_FILMS_NODES            17
#define RD_LIFT_FILMS_EXACT            5
#define RD_LIFT_FILMS_TOL              1e-2
#define RD_LIFT_FILMS_SAME             1e-6
#define RD_LIFT_FILMS_CONTACT_SEGMENTS 320 /* the contact solve's segments: 16 n, 64 to this */
#define RD_LIFT_FILMS_CHECKS           2   /* along a map: segments solved under their history */
/* The segments' loads: m x depths, over the depths z (depths 1: the same
 * all along the stroke, z unread); arrays borrowed. */
typedef struct rd_lift_film_loads {
    int m, depths;
    const double *z;    /* m down the bore, increasing */
    const double *load; /* segment j's elastic radial line load at depth d: [j depths + d], N/m */
    const double *angle_deg; /* m: each segment's mid-angle from the gap middle, deg */
    int exact; /* 1: each distinct history its own film, whatever their number; -1: interpolated
                  where the histories' check misses too (the tests measure it); 0: as above */
    const double *lever; /* m: each segment's arm about the piston pin, m (a tilting piston's
                            own sliding: rd_lift_film_run_history; any nonzero: each history its
                            own film); NULL: none */
} rd_lift_film_loads;
typedef struct rd_lift_films {
    const rd_lift_params *p;        /* the scene the films are of (borrowed) */
    int m;                          /* segments the loads were taken on */
    int depths;                     /* 1, or the map's depths the loads were solved at */
    int count;                      /* films (1 .. cap) */
    int cap;                        /* RD_LIFT_FILMS_NODES, or m if larger along a map */
    int exact;                      /* 1: every segment's loads are a film's; 0: interpolated */
    int varying;                    /* interpolated and the loads change with the depth */
    double scale;                   /* 2 F_t / D, N/m */
    double z[RD_BORE_LAYERS_MAX];   /* the depths, m */
    double xs[RD_LIFT_FILMS_NODES]; /* interpolated: the nodes' coordinates */
    double *load;        /* cap: each film's elastic radial line load (exact: at z[0]), N/m */
    double *share;       /* cap: its share of the ring, the sum of wt over m / m */
    double *acc;         /* cap: scratch of rd_lift_films_at */
    int *follows;        /* cap: exact, the segment whose loads film g is under */
    int *solved;         /* cap: film g is solved (to free) */
    double *wt;          /* m x cap: segment j's film = sum_g wt[j cap + g] film g */
    double *seg_load;    /* m x depths: each segment's loads, N/m */
    double *angle_deg;   /* m: each segment's mid-angle from the gap middle, deg */
    double *lever;       /* m: each segment's arm about the piston pin (NULL: none), m */
    double *lever_buf;   /* its storage */
    double interp_check; /* the interpolation's miss (NAN: exact) */
    double depth_check;  /* a map: the loads' miss between depths over 2 F_t / D (NAN: none) */
    rd_film *film;       /* cap, each keeps its own cavitation state */
    rd_film_track *tr;   /* cap */
} rd_lift_films;
/* mon: asked before each film (NULL: none); p is kept (fs->p).  fine > 1
 * (the estimate's films) does not repeat the histories' check. */
int rd_lift_films_run(const rd_ring_params *rp, const rd_lift_params *p,
                      const rd_lift_film_loads *ld, int fine, const rd_monitor *mon,
                      rd_lift_films *fs, rd_error *err);
void rd_lift_films_free(rd_lift_films *fs);
/* The n segments' elastic radial line loads (N/m) on the liner of `ring` in
 * p's bore (the contact analysis', above) and their mid-angles from the gap
 * middle, deg in [0, 360); rd_lift_films_run on them. */
int rd_lift_bore_loads(const struct rd_ring *ring, const rd_lift_params *p, double *load,
                       double *angle_deg, rd_error *err);
/* The same with the contact solved once at `segments` (rd_lift_bore_loads:
 * 16 n within 64 .. RD_LIFT_FILMS_CONTACT_SEGMENTS), asking mon (NULL: none),
 * in bore b (p's bore, or a map's layer). */
int rd_lift_bore_loads_at(const struct rd_ring *ring, const rd_bore *b, int segments,
                          const rd_monitor *mon, double *load, double *angle_deg, rd_error *err);
/* A bore map's loads: the layers the ring passes (from the one at or
 * above its depth at TDC to the one at or below it at BDC), and between
 * two depths their middle where the loads there miss the straight line
 * between them by more than RD_LIFT_FILMS_DEPTH_TOL x 2 F_t / D (the
 * contact is not linear in the distortion where the ring lifts off),
 * halving RD_LIFT_FILMS_DEPTH_LEVELS times at most: the depths into z
 * (their count in *depths, at most RD_BORE_LAYERS_MAX), each of the n
 * segments' loads there into load (n x RD_BORE_LAYERS_MAX, [j depths + d]),
 * and the largest miss of a kept interval's middle over 2 F_t / D into
 * *miss. */
#define RD_LIFT_FILMS_DEPTH_TOL    2e-3
#define RD_LIFT_FILMS_DEPTH_LEVELS 4
int rd_lift_map_loads(const struct rd_ring *ring, const rd_lift_params *p, int segments,
                      const rd_monitor *mon, double *load, double *angle_deg, double *z,
                      int *depths, double *miss, rd_error *err);
/* The scene needs films per segment: a distorted bore or a map, or a
 * piston tilt that moves (its groove slides each segment at its own
 * speed). */
int rd_lift_films_needed(const rd_lift_params *p, double d);
/* mon: the job's, asked by the contact solve and before the films (a stop
 * or the time limit ends them). */
int rd_lift_films_bore(const struct rd_ring *ring, const rd_lift_params *p, const rd_monitor *mon,
                       rd_lift_films *fs, rd_error *err);
/* The films at t into grp (count points), and each of n segments' film into
 * seg (rd_lift_segfilm.c): the films of the m segments its arc covers,
 * weighted by the overlap (n = m: its own; n = m / 2: the mean of two), so
 * the friction of a coarser ring is the sum of the finer one's over the
 * same arc. */
void rd_lift_films_at(const rd_lift_films *fs, double t, int n, rd_film_point *grp,
                      rd_film_point *seg);
/* Segment j's weights over the films at t into w (count; constant unless
 * fs->varying), and film g's share of the ring at t (rd_lift_segfilm.c).
 * rd_lift_films_at writes fs->acc: one caller at a time. */
void rd_lift_films_weights(const rd_lift_films *fs, double t, int j, double *w);
double rd_lift_films_share(const rd_lift_films *fs, double t, int g);
/* The interpolation's coordinate of a load (log, floored at a tenth of
 * scale) and the barycentric weights at x over the K Chebyshev-Lobatto
 * nodes xs (a node itself one-hot). */
double rd_lift_films_coord(double load, double scale);
void rd_lift_films_cheb(const double *xs, int K, double x, double *w);
/* The ring's depth in the bore at t (m down: ring_z_tdc + the piston's
 * travel) and a table v over nz depths zs read at z, linear between the
 * two around it and clamped (rd_lift_depth.c). */
double rd_lift_depth_at(const rd_lift_params *p, double t);
double rd_lift_depth_interp(const double *zs, const double *v, int nz, double z);

/* A lubrication block's films (rd_lift_lube_fill_films): count tracks on one
 * face, each with its share of the ring (NULL: one film, the whole ring);
 * m > 0: the thinnest film is taken over m segments, segment j's film
 * sum_g wt[j stride + g] film g, at angle_deg[j]. */
typedef struct rd_lube_films {
    const rd_film *film; /* the face (its x_min, sigma) */
    const rd_film_track *tr;
    int count;
    const double *share;
    int m;
    const double *wt, *angle_deg;
    int stride;
    const rd_lift_films *src; /* src->varying: the shares and wt at each time from it */
} rd_lube_films;
/* The lubrication block's view of a distorted bore's films. */
rd_lube_films rd_lift_films_view(const rd_lift_films *fs);
int rd_lift_lube_fill_films(rd_lift_lube *lb, const rd_lube_films *fs, const rd_lube_params *l,
                            const rd_engine_params *e, double diameter, const double *crank_deg,
                            int S, double t_first, int C, rd_error *err);
/* The lubrication block of the films and its estimate against the same
 * films on a grid twice as fine (the interpolation's error from the check
 * film, fs's). */
int rd_lift_films_result(const rd_ring_params *rp, const rd_lift_params *p, const rd_lift_films *fs,
                         rd_lift_result *out, rd_error *err);
int rd_lift_films_estimate(const rd_ring_params *rp, const rd_lift_params *p,
                           const rd_lift_films *fs, const rd_monitor *mon, rd_lift_result *out,
                           rd_error *err);

#endif
