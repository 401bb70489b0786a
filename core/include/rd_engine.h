/*
 * rd_engine — the engine the ring rides in: the crank train's speed and
 * piston kinematics (thesis 1.6-1.8, or the exact slider-crank) and the
 * piston's tilt about its pin axis.  Shared by the lift analysis and the
 * ring pack; the pressure traces the pack synthesizes use the same
 * kinematics (rd_gasflow.h).  SI units; crank angle alpha in rad inside,
 * deg in the scene, alpha = 0 at (firing) TDC.
 *
 * Usage:
 *     rd_engine_params e = scene's engine block;
 *     if ((rc = rd_engine_validate(&e, err))) return rc;   (cycles: the caller's)
 *     double w = rd_engine_omega(&e), s, v, a;
 *     rd_engine_piston(&e, w * t, &s, &v, &a);
 */
#ifndef RD_ENGINE_H
#define RD_ENGINE_H

#include "rd_error.h"

enum rd_kinematics { RD_KINEMATICS_EXACT = 0, RD_KINEMATICS_APPROXIMATE = 1 };

#define RD_ENGINE_TILT_MAX_DEG 2.0    /* |piston tilt|, deg: the small-angle model */
#define RD_ENGINE_TABLE_MAX    100000 /* points of a tilt table */

typedef struct rd_engine_params {
    double speed_rpm;    /* 1 .. 30000 */
    double crank_radius; /* r, m (half the stroke) */
    double rod_length;   /* l, m, > crank_radius */
    int kinematics;      /* enum rd_kinematics */
    double cycles;       /* 4-stroke cycles simulated, > 0 (its range is the analysis') */
    /* Piston tilt about its pin axis (the axis in the ring plane at 90 deg
     * from the gap middle), deg, positive raising the groove on the gap's
     * side: the constant piston_tilt_deg plus a table vs crank angle
     * (tilt_points values at tilt_crank_deg, strictly increasing within
     * [0, 720], periodic, a C1 cubic spline: rd_engine_tilt_at); |tilt| <=
     * RD_ENGINE_TILT_MAX_DEG.  Borrowed arrays; tilt_points == 0: no table. */
    double piston_tilt_deg;
    int tilt_points;
    const double *tilt_crank_deg, *tilt_deg;
} rd_engine_params;

/* Range checks of everything but `cycles` (paths relative to the engine
 * block: "/speed_rpm", ...). */
int rd_engine_validate(const rd_engine_params *e, rd_error *err);

/* The crank's angular speed, rad/s: the one place rpm becomes omega. */
double rd_engine_omega(const rd_engine_params *e);

/* The mean piston speed 2 x stroke x revolutions per second, m/s. */
double rd_engine_mean_speed(const rd_engine_params *e);

/* Piston kinematics: position below TDC s (m), velocity ds/dt (m/s) and
 * acceleration d2s/dt2 (m/s^2) at crank angle alpha (rad); any output may
 * be NULL. */
void rd_engine_piston(const rd_engine_params *e, double alpha, double *s, double *v, double *a);

/* The same per radian of crank: s (m), ds/dalpha (m), d2s/dalpha2 (m). */
void rd_engine_piston_alpha(const rd_engine_params *e, double alpha, double *s, double *ds,
                            double *dds);

/* The piston tilt (deg) at crank angle `deg` and its first and second
 * derivatives with respect to the crank angle (deg/deg, deg/deg^2)
 * (rd_engine_tilt.c). */
void rd_engine_tilt_at(const rd_engine_params *e, double deg, double *beta, double *d1, double *d2);

/* 1 if the scene tilts the piston (a constant or a table). */
int rd_engine_tilted(const rd_engine_params *e);

#endif
