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

#endif
