/* rd_ringpack_model.h — the ring pack's network and ring equations, shared by
 * rd_ringpack.c (model) and rd_ringpack_driver.c (CVODE); not part of the
 * public API (no caller outside core/ may include this).  Equations and the
 * state layout: rd_ringpack.h. */
#ifndef RD_RINGPACK_MODEL_H
#define RD_RINGPACK_MODEL_H

#include "rd_lift_model.h"
#include "rd_ringpack.h"

/* State access. */
#define RP_P(m, y, v)   ((y)[(v)])                  /* pressure of state volume v (0..2R-1) */
#define RP_Z(m, y, i)   ((y)[2 * (m)->R + 2 * (i)]) /* lift of ring i */
#define RP_ZD(m, y, i)  ((y)[2 * (m)->R + 2 * (i) + 1])
#define RP_CUM(m, y, k) ((y)[4 * (m)->R + (k)]) /* k: 0 in, 1 back, 2 cc in, 3 cc out */

/* A ring on one of the lift analysis' models (rd_ringpack_lift.c). */
typedef struct rd_packring rd_packring;

typedef struct rd_ringpack_model {
    const rd_ringpack_params *p;
    int R, V, N, F;           /* rings, state volumes, states, flows */
    double omega;             /* rad/s */
    double *cyl_deg, *cyl_pa; /* the cylinder trace (owned when synthetic) */
    double *cyl_slope;        /* its slopes at its points (rd_gasflow_trace_slopes), owned */
    int cyl_n, cyl_owned;
    rd_gasflow_law law;                  /* the orifice law's constants (k, R) */
    double vol[RD_RINGPACK_VOLUMES_MAX]; /* by network index: 0 cylinder .. V+1 crankcase */
    double temp[RD_RINGPACK_VOLUMES_MAX];
    double ca[RD_RINGPACK_RINGS_MAX]; /* axial clearances */
    double mass[RD_RINGPACK_RINGS_MAX], area[RD_RINGPACK_RINGS_MAX];
    double circ[RD_RINGPACK_RINGS_MAX]; /* pi d: the flank passages' width */
    double gap_area[RD_RINGPACK_RINGS_MAX], top_area, cd[RD_RINGPACK_RINGS_MAX];
    double gap_cd[RD_RINGPACK_RINGS_MAX]; /* the end gap's C_d (an oil ring's: 1) */
    rd_gasflow_slot
        slot[2 * RD_RINGPACK_RINGS_MAX]; /* the flank passages' viscous limits, as areas */
    int limited;                         /* flank_passage viscous_limited */
    int from[RD_RINGPACK_FLOWS_MAX], to[RD_RINGPACK_FLOWS_MAX]; /* network indices */
    int mode[RD_RINGPACK_RINGS_MAX]; /* enum rd_flank: lower, upper, free */
    /* friction (rd_ringpack.h): N = n_pre + n_back (p_groove - p_cc), N */
    double n_pre[RD_RINGPACK_RINGS_MAX], n_back[RD_RINGPACK_RINGS_MAX];
    rd_liner liner[RD_RINGPACK_RINGS_MAX]; /* each axial ring on the liner (rd_liner_law.h) */
    /* Rings on a lift model: lr[i] (NULL: the axial ring), whose states
     * follow the N0 = 4R + 4 above at y + off[i]; N counts them all. */
    int N0, lifted;
    rd_packring *lr[RD_RINGPACK_RINGS_MAX];
    int off[RD_RINGPACK_RINGS_MAX];
    int kind[RD_RINGPACK_RINGS_MAX]; /* RD_RINGPACK_AXIAL or enum rd_lift_model_kind */
    /* the lubricated model: each ring's oil film (rd_ringpack_film.c), else NULL */
    struct rd_packfilm *film[RD_RINGPACK_RINGS_MAX];
} rd_ringpack_model;

/* Network index of the volume below ring i (land_{i+1} or the crankcase). */
static inline int rp_below(const rd_ringpack_model *m, int i)
{
    return i + 1 < m->R ? 2 * (i + 1) + 1 : m->V + 1;
}

/* Builds the network of a valid scene (the synthetic trace included); the
 * lift rings are attached by the driver (rd_packring_open), and the
 * cleanup closes their run (rd_packring_close), not the rings. */
int rd_ringpack_model_init(rd_ringpack_model *m, const rd_ringpack_params *p, rd_error *err);
void rd_ringpack_model_cleanup(rd_ringpack_model *m);
/* The model each ring gets (numerics.model per ring and pack-wide; auto:
 * the cheapest exact for the scene) into kind[], and the reason into why
 * (RD_RINGPACK_RINGS_MAX x 240, or NULL). */
void rd_ringpack_choose(rd_ringpack_model *m, char (*why)[240]);
/* Pressures of every network volume at (t, y) into pv (V + 2 values). */
void rd_ringpack_pressures(const rd_ringpack_model *m, double t, const double *y, double *pv);
/* The flank passages' areas (m^2) of every ring at y: area[2 i] upper,
 * area[2 i + 1] lower. */
void rd_ringpack_areas(const rd_ringpack_model *m, const double *y, double *area);
/* Mass flows (kg/s, F values, signed from -> to) at pressures pv and flank
 * areas `area` (rd_ringpack_areas). */
void rd_ringpack_flows(const rd_ringpack_model *m, const double *pv, const double *area,
                       double *mdot);
/* The gas around ring i at t, gauge against the crankcase: the land
 * above, the groove behind, the volume below (the test hook's tables when
 * set). */
void rd_ringpack_around(const rd_ringpack_model *m, int i, double t, const double *pv,
                        double out[3]);
/* Ring i's gauge pressures above, behind, below (against the crankcase;
 * the network's, or the test hook's tables), Pa. */
void rd_ringpack_faces(const rd_ringpack_model *m, int i, double t, const double *pv,
                       double out[3]);
/* Net axial force on ring i (N, +z up) at (t, y, pv). */
double rd_ringpack_ring_force(const rd_ringpack_model *m, int i, double t, const double *y,
                              const double *pv);
/* The liner's axial friction on ring i (N, +z up; 0 without friction). */
double rd_ringpack_friction(const rd_ringpack_model *m, int i, double t, const double *y,
                            const double *pv);
/* dy/dt of the N0 network and axial-ring states, the flank areas given
 * (the lift rings' lifts enter only through them). */
void rd_ringpack_base_rhs(const rd_ringpack_model *m, double t, const double *y, const double *area,
                          double *yd);
/* The exact partial derivatives of rd_ringpack_base_rhs at (t, y, area):
 * J = d f_b / d y_b (N0 x N0, column-major, J[N0 c + r] = d f_r / d y_c)
 * and G = d f_b / d area (2R columns of N0: ring i's upper flank area in
 * column 2 i, lower in 2 i + 1), from the orifice flows' derivatives
 * (rd_gasflow_flow) and the axial rings' forces (affine in the pressures;
 * the friction's tanh).  An axial ring's lift acts on the flows through
 * its flank areas (max(a - z, 0), max(z, 0): slope 0 where clamped); that
 * is in its z column.  Columns of the cumulative masses and of a lift
 * ring's unused slots are zero, as are their rows' f where constant.  Each
 * column's entries weighted by V/(R T) (volumes) and +-1 (masses) sum to
 * zero, as the mass balance needs of a Newton matrix. */
void rd_ringpack_base_jacobian(const rd_ringpack_model *m, double t, const double *y,
                               const double *area, double *J, double *G);
/* dy/dt, all N states; nonzero if a lift model's right-hand side failed. */
int rd_ringpack_rhs(const rd_ringpack_model *m, double t, const double *y, double *yd);

/* Names and volumes into the result. */
void rd_ringpack_describe(const rd_ringpack_model *m, rd_ringpack_result *r);

/* ---- the oil films (rd_ringpack_film.c; the lubricated model) ---- */

typedef struct rd_packfilm rd_packfilm;
/* The lubricated model's inputs (each ring's face named under /rings/i),
 * and the round bore and untilted piston its one film per ring needs. */
int rd_ringpack_lube_validate(const rd_ringpack_params *p, rd_error *err);
/* Each ring's film for the first cycle (no gas), S samples a cycle; the
 * lift rings rub on it.  Nothing without the lubricated model. */
int rd_ringpack_films_open(rd_ringpack_model *m, int S, rd_error *err);
/* The pressures around each ring at sample k of the cycle (pv: the
 * network's, rd_ringpack_pressures). */
void rd_ringpack_films_sample(rd_ringpack_model *m, int k, double t, const double *pv);
/* At a cycle's end: each film of cycle `next` from the cycle's samples. */
int rd_ringpack_films_cycle(rd_ringpack_model *m, int next, rd_error *err);
/* Ring i's film at time t (s; m->film[i] set). */
void rd_ringpack_film_at(const rd_ringpack_model *m, int i, double t, rd_film_point *pt);
/* The lubrication blocks and film_lag of the last cycle into r. */
int rd_ringpack_films_result(rd_ringpack_model *m, rd_ringpack_result *r, rd_error *err);
void rd_ringpack_films_close(rd_ringpack_model *m);

/* ---- the output (rd_ringpack_record.c) ---- */

/* The cycle being recorded: its samples in `res` (k = 0 .. S), the cycle
 * before's pressures, the cumulative masses and stored gas at the two
 * cycles' starts and this one's end; cyc counts from 0; done once the
 * run's last cycle has ended (the C-th, or with p->periodic the first
 * whose change is below the tolerance). */
typedef struct rd_ringpack_rec {
    rd_ringpack_result *res;
    double *prev;     /* n_volumes x (S + 1) */
    double cum[3][4]; /* RP_CUM at the cycle before's start, this one's, its end */
    double stored[3]; /* gas in the volumes then, kg */
    int S, C;         /* samples per cycle (intervals), cycles (periodic: at most) */
    int cyc, done;
} rd_ringpack_rec;

/* Allocates the result's arrays for S + 1 samples (d->S set) and names
 * its volumes and flows. */
int rd_ringpack_record_open(rd_ringpack_rec *d, const rd_ringpack_model *m, rd_ringpack_result *r,
                            rd_error *err);
/* Sample k of the recorded cycle at (t, y); flank[i]: an axial ring's
 * flank (its band, or its mode), a lift ring's is its mean lift's. */
void rd_ringpack_record(rd_ringpack_rec *d, const rd_ringpack_model *m, const int *flank, int k,
                        double t, const double *y);
/* After sample S: the cycle's balance and change (from the second on);
 * done, or the next cycle starts from this one's end (its pressures
 * become the cycle before's, the events recorded so far are dropped). */
void rd_ringpack_cycle_end(rd_ringpack_rec *d, const rd_ringpack_model *m);

/* ---- rings on the lift models (rd_ringpack_lift.c) ---- */

/* What the scene needs of auto's choice: the full ring for a distorted
 * bore or a tilt, the rigid ring for dynamic areas without friction (with
 * the reason in *why, a static string); -1 when it needs nothing. */
int rd_packring_auto(const rd_ringpack_params *p, const char **why);
/* The bore, tilt and active areas against every free ring's model (a
 * distorted bore or a tilt refuse axial and rigid, dynamic areas axial; a
 * tilt needs gaps at 0 or 180 deg), with the lift analysis' checks of the
 * tilt and bore fields. */
int rd_packring_validate(const rd_ringpack_params *p, rd_error *err);

/* Ring i's lift model of kind m->kind[i], made once per job (the pack's
 * handle keeps it across its runs and accuracy levels): its lift
 * parameters from the pack's, checked (rd_lift_validate), its ring of
 * `segments`, its model and form.  *out is NULL on failure. */
int rd_packring_create(const rd_ringpack_model *m, int i, rd_packring **out, rd_error *err);
/* Ring i's part in one run of m (m->lr[i] = L): state vectors in ctx, the
 * flank tracker seated, no events; its state count into *N, a modal
 * model's elastic modes into *modes, its contact stiffness (Pa/m) into *k.
 * rd_packring_close ends the run's part (also after a failed open);
 * rd_packring_free frees the rest (NULL: no-op). */
int rd_packring_open(rd_ringpack_model *m, int i, rd_packring *L, SUNContext ctx, int *N,
                     int *modes, double *k, rd_error *err);
void rd_packring_close(rd_packring *L);
void rd_packring_free(rd_packring *L);
/* Its form (rd_lift_model.h) and model. */
rd_lift_form *rd_packring_form(rd_packring *L);
/* Its initial state (seated at rest; in a distorted bore its static
 * equilibrium there, solved by the first run and kept) and tolerances at
 * y + off, ab + off. */
int rd_packring_initial(rd_packring *L, double atol, double *y, double *ab, rd_error *err);
/* Sets its gauge face pressures (above, behind, below), Pa. */
void rd_packring_gas(rd_packring *L, const double g[3]);
/* Its states' rates at (t, y) (y, yd: the ring's own states). */
int rd_packring_rhs(rd_packring *L, double t, double *y, double *yd);
/* Its mean lift and its flank passages' areas from the per-segment lifts:
 * upper pi d / n sum clamp(a - L_j, 0, a), lower pi d / n sum clamp(L_j, 0, a). */
double rd_packring_areas(rd_packring *L, const double *y, double *up, double *lo);
/* The areas' derivatives along the state direction w at y (the lifts are
 * linear in the state; the clamps' slopes 1 inside (0, a), else 0). */
void rd_packring_area_slope(rd_packring *L, const double *y, const double *w, double *du,
                            double *dl);
/* Its axial load without the flanks (N, +z up) and friction (N) at (t, y). */
/* Its lift parameters' film (the lubricated model: rd_ringpack_film.c). */
void rd_packring_film(rd_packring *L, const rd_film_track *tr);
/* Or a distorted bore's films, a film per segment load (rd_lift_films_at). */
int rd_packring_films(rd_packring *L, const struct rd_lift_films *fs, rd_error *err);
void rd_packring_loads(rd_packring *L, double t, const double *y, double *fz, double *friction);
/* Its event threshold eps and clearance. */
double rd_packring_eps(const rd_packring *L);
/* The flank-change tracker (rd_lift_track_roots) and its events (absolute
 * crank angles). */
rd_lift_flank_track *rd_packring_track(rd_packring *L);
rd_lift_pass *rd_packring_events(rd_packring *L);
/* Its own Newton solver (M = I - gamma J of its states at fixed
 * pressures): opened once (nonzero: out of memory), set up at (t, y,
 * gamma) (y: its states; nonzero: failed, positive recoverable), and
 * x = M^-1 b. */
int rd_packring_solver_open(rd_packring *L, SUNContext ctx);
int rd_packring_solver_setup(rd_packring *L, double t, double *y, double gamma);
int rd_packring_solver_solve(rd_packring *L, double *x, double *b);

/* ---- the pack's Newton systems with lift rings (rd_ringpack_newton.c) ---- */

typedef struct rd_ringpack_newton rd_ringpack_newton;
/* A DIRECT SUNLinearSolver over A (dense N0 x N0, the caller's, given to
 * CVodeSetLinearSolver with it); NULL when out of memory.  m must have its
 * lift rings open. */
SUNLinearSolver rd_ringpack_newton_create(rd_ringpack_model *m, SUNContext ctx, SUNMatrix A,
                                          rd_ringpack_newton **nw);
/* The linear-system function's work at (t, y, gamma), fy = f(t, y) (N
 * values, CVODE's): every block, the Schur complement and its LU; 0, or
 * nonzero (recoverable: positive). */
int rd_ringpack_newton_linsys(rd_ringpack_newton *nw, double t, const double *y, const double *fy,
                              double gamma);

#endif
