/*
 * rd_film_track.h — the film of a rigid face over a run (private to core):
 * the radial balance of the face, integrated in time with the squeeze film
 * (MODEL.md "Ring-liner lubrication", radial balance).
 *
 * At each instant the caller's loads give the liner speed U, the viscosity,
 * the radial load on the face W_ext (N per metre of circumference: the
 * ring's elastic pressure times its height plus the gas behind it) and the
 * gas pressures at the face's edges; the film thickness h0 follows from
 *     W_film(h0, dh0/dt) + W_asperity(h0) = W_ext,
 * integrated by variable-step BDF2 (the first step backward Euler), each
 * step's h0 a secant root kept in a bracket (W_film + W_a falls as h0
 * grows).  The step follows the local error (the corrector against a
 * quadratic predictor, Milne's device) to rtol * h0 + 1e-3 sigma, at most
 * dt_max, and lands on every multiple of `period` (the cycles' ends).
 * A warm-up (a cycle before t = 0, its first three quarters at a looser
 * error and longer steps: RD_FILM_WARM_RTOL, RD_FILM_WARM_STEPS) starts it
 * on its periodic orbit; `periodic_change` says how far h0 at the run's end still differs
 * from one cycle earlier.
 *
 * Usage:
 *     rd_film_track tr;
 *     rc = rd_film_track_run(&film, &loads, t_end, dt_max, t_cycle, t_cycle, NAN, &tr, err);
 *     rd_film_point pt; rd_film_track_at(&tr, t, &pt);   linear in t
 *     rd_film_track_free(&tr);
 */
#ifndef RD_FILM_TRACK_H
#define RD_FILM_TRACK_H

#include "rd_film.h"

#define RD_FILM_H_MAX 1e-4 /* m: a face pushed further off the liner is held there */

typedef struct rd_film_loads {
    /* at time t (s): liner speed past the ring U (m/s, + up), eta (Pa s),
     * W_ext (N/m), the gas at the lower and upper edges (Pa) */
    void (*at)(void *ctx, double t, double *U, double *eta, double *W_ext, double *p_lo,
               double *p_hi);
    void *ctx;
} rd_film_loads;

/* The film's state and loads at one instant, per metre of circumference. */
typedef struct rd_film_point {
    double t, h0, W, Wa, Cc, Fp, U, cavitated;
} rd_film_point;

#define RD_FILM_WARM_RTOL  1e-2 /* the same in the warm-up but its last quarter period */
#define RD_FILM_WARM_STEPS 5.0  /* the warm-up's largest step, in dt_max */

typedef struct rd_film_track {
    int steps; /* points 0 .. steps: pt[0].t = 0, pt[steps].t = t_end */
    int cap;   /* allocated points */
    rd_film_point *pt;
    double periodic_change; /* |h0(end) - h0(end - period)| / max(|h0(end)|, sigma); 0 for a run
                             * shorter than a period */
    long solves;            /* film solves, warm-up included */
    int held;               /* steps where h0 was held at RD_FILM_H_MAX */
} rd_film_track;

/* From t = -t_warm (s) to t_end, recording from t = 0, steps at most
 * dt_max landing on the multiples of `period` (s, > 0); h_start: the film
 * at -t_warm (m; below 0 where the asperities carry the face), NAN: the
 * steady balance there. */
int rd_film_track_run(rd_film *f, const rd_film_loads *ld, double t_end, double dt_max,
                      double period, double t_warm, double h_start, rd_film_track *tr,
                      rd_error *err);
void rd_film_track_at(const rd_film_track *tr, double t, rd_film_point *out);
void rd_film_track_free(rd_film_track *tr);

#endif
