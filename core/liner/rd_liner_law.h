/*
 * rd_liner_law.h — the ring-liner interface at one point of the running
 * face (private to core; the scene's inputs are rd_liner.h).  Every model
 * that rubs a ring on the liner evaluates it here, so a law exists once:
 * the lift models per bore point (core/lift/rd_lift_forces.c, add_bore) and
 * the ring pack's axial rings per ring (core/ringpack/rd_ringpack.c).
 *
 * Today the radial load N is the caller's (lift: the bore penalty; the
 * pack: pretension plus back gas) and the liner returns the axial friction
 * F(N, u) with dF/dN and dF/du.  The oil-film law plugs in here: it takes
 * the film thickness, its rate and the pressures either side in
 * rd_liner_point and returns the film's load and its slopes as well; the
 * callers chain the slopes as they chain dF/dN now.
 *
 * Friction (u = sliding speed of the ring on the liner, m/s; T = tanh(u /
 * u_reg), u_reg = 1e-3 x the mean piston speed: rd_liner_ureg):
 *   Coulomb:  F = -mu N T
 *   Stribeck (thesis 2.9) with the Sommerfeld number (1.11):
 *     F = -T (C e^{-3 |So_lim / So|^2.5} + K / So) N,
 *     So = N_ring / (eta |u| h),  so K / So N = K eta |u| h N / N_ring.
 *   N_ring = N / share is the ring-equivalent normal force at the point's
 *   local line load (share = its part s_k / L of the running face), so a
 *   uniform load gives exactly (1.11) with the ring's total force and the
 *   hydrodynamic part sums to K eta u h over the ring, independent of n.
 *   Lubricated: the film of the face at this instant (rd_film_track.h,
 *   per metre of circumference, C the circumference pi D):
 *     F = share C (-Cc u + Fp - mu_b Wa T),
 *   its Couette shear at the point's own speed, the pressure gradient's
 *   shear and the asperity friction; N does not enter (the film's own
 *   radial balance carries the face).
 */
#ifndef RD_LINER_LAW_H
#define RD_LINER_LAW_H

#include "rd_engine.h"
#include "rd_film_track.h"
#include "rd_liner.h"

#define RD_LINER_UREG_FRACTION 1e-3 /* u_reg / mean piston speed */

/* The law's constants for one scene. */
typedef struct rd_liner {
    int model;     /* enum rd_friction_model */
    double mu;     /* Coulomb coefficient (C of 2.9) */
    double ureg;   /* regularization speed u_reg, m/s */
    double eta;    /* Stribeck: oil viscosity, Pa s */
    double so_lim; /* Stribeck: So_lim */
    double kh;     /* Stribeck: K */
    double h;      /* the running face's axial height, m */
    double mu_b;   /* lubricated: the asperities' boundary coefficient */
    double circ;   /* lubricated: the liner's circumference pi D, m */
} rd_liner;

/* One point of the running face. */
typedef struct rd_liner_point {
    double N;                  /* radial load the point puts on the liner, N */
    double u;                  /* sliding speed of the ring on the liner, m/s */
    double share;              /* the point's part s_k / L of the running face */
    const rd_film_point *film; /* lubricated: the face's film now */
} rd_liner_point;

/* What the liner does to the point. */
typedef struct rd_liner_force {
    double F;   /* axial friction force on the ring, N */
    double F_N; /* dF/dN */
    double F_u; /* dF/du, N s/m */
} rd_liner_force;

/* The default regularization speed of an engine, m/s. */
double rd_liner_ureg(const rd_engine_params *e);

/* The constants of friction f on a running face of height h (m), with
 * regularization speed ureg (m/s), in a liner of circumference circ (m). */
void rd_liner_init(rd_liner *l, const rd_friction_params *f, double ureg, double h, double circ);

/* The friction at one point (f->model != NONE). */
void rd_liner_eval(const rd_liner *l, const rd_liner_point *in, rd_liner_force *out);

#endif
