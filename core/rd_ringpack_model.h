/* rd_ringpack_model.h — the ring pack's network and ring equations, shared by
 * rd_ringpack.c (model) and rd_ringpack_driver.c (CVODE); not part of the
 * public API (no caller outside core/ may include this).  Equations and the
 * state layout: rd_ringpack.h. */
#ifndef RD_RINGPACK_MODEL_H
#define RD_RINGPACK_MODEL_H

#include "rd_ringpack.h"

/* State access. */
#define RP_P(m, y, v)   ((y)[(v)])                  /* pressure of state volume v (0..2R-1) */
#define RP_Z(m, y, i)   ((y)[2 * (m)->R + 2 * (i)]) /* lift of ring i */
#define RP_ZD(m, y, i)  ((y)[2 * (m)->R + 2 * (i) + 1])
#define RP_CUM(m, y, k) ((y)[4 * (m)->R + (k)]) /* k: 0 in, 1 back, 2 cc in, 3 cc out */

typedef struct rd_ringpack_model {
    const rd_ringpack_params *p;
    int R, V, N, F;           /* rings, state volumes, states, flows */
    double omega;             /* rad/s */
    double *cyl_deg, *cyl_pa; /* the cylinder trace (owned when synthetic) */
    int cyl_n, cyl_owned;
    double vol[RD_RINGPACK_VOLUMES_MAX]; /* by network index: 0 cylinder .. V+1 crankcase */
    double temp[RD_RINGPACK_VOLUMES_MAX];
    double ca[RD_RINGPACK_RINGS_MAX]; /* axial clearances */
    double mass[RD_RINGPACK_RINGS_MAX], area[RD_RINGPACK_RINGS_MAX];
    double circ[RD_RINGPACK_RINGS_MAX]; /* pi d: the flank passages' width */
    double gap_area[RD_RINGPACK_RINGS_MAX], top_area, cd[RD_RINGPACK_RINGS_MAX];
    int from[RD_RINGPACK_FLOWS_MAX], to[RD_RINGPACK_FLOWS_MAX]; /* network indices */
    int mode[RD_RINGPACK_RINGS_MAX]; /* enum rd_flank: lower, upper, free */
    /* friction (rd_ringpack.h): N = n_pre + n_back (p_groove - p_cc), N */
    double n_pre[RD_RINGPACK_RINGS_MAX], n_back[RD_RINGPACK_RINGS_MAX], ureg;
} rd_ringpack_model;

/* Network index of the volume below ring i (land_{i+1} or the crankcase). */
static inline int rp_below(const rd_ringpack_model *m, int i)
{
    return i + 1 < m->R ? 2 * (i + 1) + 1 : m->V + 1;
}

/* Builds the network of a valid scene (the synthetic trace included). */
int rd_ringpack_model_init(rd_ringpack_model *m, const rd_ringpack_params *p, rd_error *err);
void rd_ringpack_model_cleanup(rd_ringpack_model *m);
/* Pressures of every network volume at (t, y) into pv (V + 2 values). */
void rd_ringpack_pressures(const rd_ringpack_model *m, double t, const double *y, double *pv);
/* Mass flows (kg/s, F values, signed from -> to) at pressures pv, lifts of y. */
void rd_ringpack_flows(const rd_ringpack_model *m, const double *pv, const double *y, double *mdot);
/* Net axial force on ring i (N, +z up) at (t, y, pv). */
double rd_ringpack_ring_force(const rd_ringpack_model *m, int i, double t, const double *y,
                              const double *pv);
/* The liner's axial friction on ring i (N, +z up; 0 without friction). */
double rd_ringpack_friction(const rd_ringpack_model *m, int i, double t, const double *y,
                            const double *pv);
/* dy/dt. */
void rd_ringpack_rhs(const rd_ringpack_model *m, double t, const double *y, double *yd);
/* Names and volumes into the result. */
void rd_ringpack_describe(const rd_ringpack_model *m, rd_ringpack_result *r);

#endif
