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
 * 2 F_t / D), plus the gas behind it.  Up to RD_LIFT_FILMS_EXACT distinct loads (within
 * RD_LIFT_FILMS_SAME of 2 F_t / D) get a film each.  More are
 * interpolated: films at Chebyshev-Lobatto nodes of log(load + 0.1 x
 * 2 F_t / D) over the segments' range, 3, then 5, 9, 17 (nested), until the
 * coarser level misses the new nodes' films (film over max(|h0|, sigma),
 * friction work, relative) by at most RD_LIFT_FILMS_TOL; the finer level
 * is used and that miss kept (interp_check: it tracked the used level's
 * miss against each segment's own film within x0.45-1.1 on
 * test_lift_films' battery, where that miss is the films' own time-step
 * noise, 3e-3 to 9e-3, and more nodes do not lower it).  Each segment's
 * film is the interpolation at its load (the film's quantities are linear
 * in the films' points).  The films are
 * solved before the ring's motion; its radial motion during the run does
 * not feed back into the loads.  Usage:
 *     rd_lift_films fs;
 *     rc = rd_lift_films_bore(ring, p, &fs, err);   (or rd_lift_films_run)
 *     q.films = &fs;   each force call: rd_lift_films_at(&fs, t, n, grp, seg)
 *     rd_lift_films_free(&fs);   also after a failure */
#define RD_LIFT_FILMS_NODES            17
#define RD_LIFT_FILMS_EXACT            5
#define RD_LIFT_FILMS_TOL              1e-2
#define RD_LIFT_FILMS_SAME             1e-6
#define RD_LIFT_FILMS_CONTACT_SEGMENTS 320 /* the contact solve's segments: 16 n, 64 to this */
typedef struct rd_lift_films {
    int m;                             /* segments the loads were taken on */
    int count;                         /* films (1 .. RD_LIFT_FILMS_NODES) */
    int exact;                         /* 1: every segment's load is a film's; 0: interpolated */
    double load[RD_LIFT_FILMS_NODES];  /* each film's elastic radial line load, N/m */
    double share[RD_LIFT_FILMS_NODES]; /* its share of the ring: the sum of wt over m */
    double *wt;          /* m x RD_LIFT_FILMS_NODES: segment j's film = sum_g wt film g */
    double *seg_load;    /* m: each segment's load, N/m */
    double *angle_deg;   /* m: each segment's mid-angle from the gap middle, deg */
    double interp_check; /* the coarser level's miss (NAN: exact) */
    int solved[RD_LIFT_FILMS_NODES];   /* film g is solved (to free) */
    rd_film film[RD_LIFT_FILMS_NODES]; /* each keeps its own cavitation state */
    rd_film_track tr[RD_LIFT_FILMS_NODES];
} rd_lift_films;
/* mon: asked before each film (NULL: none). */
int rd_lift_films_run(const rd_ring_params *rp, const rd_lift_params *p, const double *load,
                      const double *angle_deg, int m, int fine, const rd_monitor *mon,
                      rd_lift_films *fs, rd_error *err);
void rd_lift_films_free(rd_lift_films *fs);
/* The n segments' elastic radial line loads (N/m) on the liner of `ring` in
 * p's bore (the contact analysis', above) and their mid-angles from the gap
 * middle, deg in [0, 360); rd_lift_films_run on them. */
int rd_lift_bore_loads(const struct rd_ring *ring, const rd_lift_params *p, double *load,
                       double *angle_deg, rd_error *err);
/* The same with the contact solved once at `segments` (rd_lift_bore_loads:
 * 16 n within 64 .. RD_LIFT_FILMS_CONTACT_SEGMENTS), asking mon (NULL: none). */
int rd_lift_bore_loads_at(const struct rd_ring *ring, const rd_lift_params *p, int segments,
                          const rd_monitor *mon, double *load, double *angle_deg, rd_error *err);
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

/* A lubrication block's films (rd_lift_lube_fill_films): count tracks on one
 * face, each with its share of the ring (NULL: one film, the whole ring);
 * m > 0: the thinnest film is taken over m segments, segment j's film
 * sum_g wt[j NODES + g] film g, at angle_deg[j]. */
typedef struct rd_lube_films {
    const rd_film *film; /* the face (its x_min, sigma) */
    const rd_film_track *tr;
    int count;
    const double *share;
    int m;
    const double *wt, *angle_deg;
} rd_lube_films;
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
