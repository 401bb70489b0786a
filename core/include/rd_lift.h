/*
 * rd_lift — the flexible ring in its piston groove over engine cycles
 * (thesis 3.5, 2.4; MODEL.md "lift").
 *
 * Frame: the piston frame, z along the cylinder axis towards the head.  The
 * ring's 6n DOFs are the small displacements of its segments from the
 * installed reference (the closed shape, centred in the bore, bottom face on
 * the groove's lower flank): ring lift = axial position of the bottom face
 * above the lower flank (0 = seated, axial_clearance = on the upper flank).
 *
 * The piston moves along z with the crank (thesis 1.6-1.8, or the exact
 * slider-crank); in its frame every segment feels the inertia force -m a_p.
 * Each other force is modelled only when the scene asks: gravity, bore
 * friction (Coulomb, regularized, or Stribeck 2.9), gas pressure on the top,
 * back and bottom faces from pressure-vs-crank tables with fixed or dynamic
 * active areas.  Contacts: the groove's lower and upper flanks and back, and
 * the bore (radially, preloaded by the pretension), as smooth penalties.
 *
 * Three formulations (numerics.model): the full ring, integrated with
 * SUNDIALS CVODE (BDF) and a block-tridiagonal Newton solve in second-order
 * form, so the cost grows linearly with n; the rigid ring, with its own
 * TR-BDF2 integrator; the modal reduction, CVODE with a dense Newton solve.
 * Flank changes are located by root finding, not on the output grid.
 */
#ifndef RD_LIFT_H
#define RD_LIFT_H

#include "rd_bore_map.h"
#include "rd_engine.h"
#include "rd_error.h"
#include "rd_liner.h"
#include "rd_ring.h"

/* The gas on the flank faces (rd_lift_forces.c): fixed full faces, each its
 * own side's pressure; dynamic, a sealing face the mean of its own and the
 * groove's, weighted by its flank contact; linear, every face the mean of
 * its own and the groove's (the linear fall across the flank) with the
 * couple of that slope. */
enum rd_gas_area { RD_GAS_AREA_FIXED = 0, RD_GAS_AREA_DYNAMIC = 1, RD_GAS_AREA_LINEAR = 2 };
/* How a landing on a flank is integrated: through the damped penalty alone,
 * or as a plastic impact (the ring's axial velocity towards the flank
 * arrested at the instant it reaches it, then the penalty carries the load). */
enum rd_lift_landing { RD_LANDING_PENALTY = 0, RD_LANDING_PLASTIC = 1 };
enum rd_flank { RD_FLANK_LOWER = 0, RD_FLANK_UPPER = 1, RD_FLANK_FREE = 2 };
/* Which equations are integrated (numerics.model): the full flexible ring
 * (6 n DOFs), the rigid ring (axial lift, twist, radial: exact for
 * axisymmetric scenes, rd_lift_rigid.c), the modal reduction
 * (rd_lift_modal.c, by request), or auto: the cheapest the scene allows. */
enum rd_lift_model_kind {
    RD_LIFT_MODEL_FULL = 0,
    RD_LIFT_MODEL_RIGID = 1,
    RD_LIFT_MODEL_MODAL = 2,
    RD_LIFT_MODEL_AUTO = 3
};
enum rd_lift_event_kind {
    RD_EVENT_LEAVE_LOWER = 0,
    RD_EVENT_REACH_UPPER = 1,
    RD_EVENT_LEAVE_UPPER = 2,
    RD_EVENT_REACH_LOWER = 3
};

/* Limits shared by validation and documentation. */
#define RD_LIFT_CYCLES_MAX     50.0   /* 4-stroke cycles (720 deg each) */
#define RD_LIFT_SAMPLES_MAX    200000 /* output samples (cycles * 720 / step_deg + 1) */
#define RD_LIFT_TABLE_MAX      100000 /* points of a gas pressure table */
#define RD_LIFT_SEGMENTS_MAX   1000
#define RD_LIFT_MODES_MAX      60
#define RD_LIFT_FLANK_BAND     0.01 /* output.flank_band default, of the axial clearance */
#define RD_LIFT_FLANK_BAND_MAX 0.2
/* The segment-count share of the event error that warns: 10x the default
 * accuracy_deg (a choice: an estimate that large is no longer a small
 * correction to the angle but a sign the answer changes with n). */
#define RD_LIFT_SEGMENT_WARN_DEG 1.0

typedef struct rd_groove_params {
    double axial_clearance;  /* groove height minus ring height, m */
    double radial_clearance; /* ring inner face to groove back, m */
} rd_groove_params;

/* The landing law (rd_lift_landing.c): the oil squeeze film between a ring
 * face and the groove flank it approaches.  Off by default (the flanks are
 * then the dry penalty contact alone). */
typedef struct rd_squeeze_params {
    int on;           /* 1: modelled */
    double viscosity; /* oil dynamic viscosity mu, Pa s */
    double min_film;  /* h_min, m: the film left at contact (roughness) */
} rd_squeeze_params;

/* Gas pressures vs crank angle, Pa, linear interpolation, periodic over 720
 * deg.  Borrowed arrays of `points` values each; points == 0: no gas. */
typedef struct rd_gas_params {
    int points;
    const double *crank_deg; /* strictly increasing, within [0, 720] */
    const double *above;     /* on the top face */
    const double *behind;    /* on the back (inner) face */
    const double *below;     /* on the bottom face */
    int active_area;         /* enum rd_gas_area */
} rd_gas_params;

struct rd_film_track; /* core/liner/rd_film_track.h */
struct rd_lift_films; /* core/lift/rd_lift_internal.h */

/* The lubricated model's numerics and defaults. */
#define RD_LIFT_FILM_STEP_DEG     2.0 /* numerics.film_step_deg default: the film's largest step */
#define RD_LIFT_FILM_STEP_MAX_DEG 10.0

typedef struct rd_lift_params {
    rd_engine_params engine;
    rd_bore bore; /* a round bore of the ring's diameter (the default) is the installed
                     reference; otherwise the ring starts from its static equilibrium in
                     it (rd_lift_start.c) */
    /* A bore that changes along its height (borrowed; NULL: `bore` everywhere,
     * and then `bore` must be the default round one): the ring meets the bore
     * of the map at its current depth, ring_z_tdc + the piston's travel from
     * TDC (rd_lift_bore.c); the map must cover the whole stroke. */
    const rd_bore_map *bore_map;
    double ring_z_tdc; /* with bore_map: the ring's depth below the top of the bore at TDC, m */
    rd_groove_params groove;
    int gravity; /* 1: g = 9.80665 m/s^2 along -z */
    rd_friction_params friction;
    rd_gas_params gas;
    rd_squeeze_params squeeze; /* landing law on the flanks */
    double contact_stiffness;  /* flank/bore penalty, Pa/m; 0 = default */
    int landing;               /* enum rd_lift_landing */
    double step_deg;           /* output sampling, crank degrees */
    double rtol, atol;         /* CVODE tolerances (atol on lift, m) */
    long max_steps;            /* bound on CVODE steps for the whole run */
    int estimate_error;        /* 1: second run at rtol/10 for the error estimate */
    int model;                 /* enum rd_lift_model_kind */
    int modes;           /* elastic modes of the modal model, 0 = auto, <= RD_LIFT_MODES_MAX */
    double accuracy_deg; /* target on the flank-change angles, deg (auto) */
    /* Flank changes are dated where the mean lift crosses the edge of a band of
     * flank_band * axial_clearance at each flank (a leave where it moves out,
     * a landing where it moves in; default 0.01, within [0, 0.2]).  0: dated
     * where the mean lift touches the flank (a landing) or where the load turns
     * away from it (a leave, confirmed 1 % of the clearance off the flank). */
    double flank_band;
    int stick; /* 1: the rigid model's sticking phase (rd_lift_stick.c); C only, default 0:
                  it saves steps but not instructions (README) */
    int cvode; /* 1: CVODE for every model; C only, default 0: the rigid model is integrated
                  by rd_lift_small.c (the tests compare the two) */
    /* The lubricated friction model (friction.model RD_FRICTION_LUBRICATED):
     * the running face, and the film's time step (crank degrees).  The film
     * is solved once per run before the ring's motion (rd_lift_film.c);
     * `film` (one film for the whole face) and `films` (a distorted bore:
     * a film per segment load) are core's own (NULL from callers). */
    rd_face_params face;
    double film_step_deg;
    const struct rd_film_track *film;
    const struct rd_lift_films *films;
} rd_lift_params;

typedef struct rd_lift_event {
    double crank_deg; /* where the mean lift crossed the band's edge (flank_band) */
    int kind;         /* enum rd_lift_event_kind */
    /* Where the mean lift itself first touched the flank after a landing, or
     * left it before a leave (the load's turning away, as with flank_band 0);
     * NAN if it never touched the flank in between. */
    double touch_deg;
} rd_lift_event;

/* The oil film of a lubricated run (rd_lift_film.c), per output sample:
 * the film at the face's thinnest point, the friction on the ring split
 * into the film's shear and the asperities' (N, + upwards, at the liner's
 * speed past the piston), the power they take from the piston (W) and the
 * regime; per whole cycle the friction work (J) and its mean effective
 * pressure (work over the displaced volume pi D^2 / 4 x stroke, Pa). */
enum rd_lube_regime { RD_REGIME_HYDRODYNAMIC = 0, RD_REGIME_MIXED = 1, RD_REGIME_BOUNDARY = 2 };
#define RD_LUBE_MIXED_SHARE    0.01 /* asperity share of the radial load: mixed above */
#define RD_LUBE_BOUNDARY_SHARE 0.9  /* boundary above */

typedef struct rd_lift_lube {
    int on;
    double *min_film;                                  /* m */
    double *hydrodynamic_friction, *asperity_friction; /* N */
    double *power;                                     /* W */
    double *asperity_share;                            /* of the radial load */
    int *regime;                                       /* enum rd_lube_regime */
    int cycles;                                        /* whole cycles */
    double *friction_work;                             /* J, per cycle */
    double *fmep;                                      /* Pa, per cycle */
    double min_film_x;      /* where on the face the film is thinnest, m above its lower edge */
    double composite_sigma; /* m */
    double viscosity_min, viscosity_max; /* Pa s over the run */
    double periodic_change;              /* the film's change over its last cycle, relative */
    double film_step_deg;
    long film_solves;
    int held; /* film steps held at the largest film (the face pushed off) */
    /* A distorted bore (films > 1): the segments' static contact loads
     * around the ring (rd_lift_films.c); up to 5 distinct loads a film
     * each, more interpolated between films at 3 to 17 loads.  min_film is
     * the thinnest segment's film, min_film_angle_deg where it is (the
     * segment's mid-angle from the gap middle), the friction their sum.
     * films = 1: one film for the face, min_film_angle_deg NULL. */
    int films;
    double load_min, load_max; /* the segments' elastic radial line load, N/m */
    int load_depths; /* > 1: the bore map's depths the loads were solved at, linear between */
    int tilt_films;  /* 1: each film at its segments' sliding speed on a tilting piston */
    double
        load_depth_error; /* their largest miss at an interval's middle over 2 F_t / D (NAN: one) */
    double *min_film_angle_deg;
    double interp_check; /* the interpolation's bound (NAN: none, rd_lift_films.c) */
    /* The film's error estimate (NAN: not estimated): against the same film
     * on a grid twice as fine (points, steps, local error / 4), the largest
     * relative film difference max |h - h'| / max(|h'|, sigma) over the
     * samples, and the largest relative friction-work difference. */
    double film_error, work_error;
} rd_lift_lube;

typedef struct rd_lift_result {
    int segments, dof, samples;
    double *crank_deg;      /* samples */
    double *lift;           /* mean lift over segments, m, per sample */
    double *lift_min;       /* smallest segment lift, m, per sample */
    double *lift_max;       /* largest segment lift, m, per sample */
    double *lift_segments;  /* samples x segments, row-major (sample-major) */
    double *twist;          /* mean twist (rotation about the tangent), rad, per sample */
    double *friction_force; /* axial bore friction on the ring, N, per sample */
    /* the radial contact pressure on the running face, Pa, per sample: each
     * segment's mean (samples x segments, as lift_segments), and the smallest
     * and the largest of them (uniform in a round bore) */
    double *bore_pressure, *bore_pressure_min, *bore_pressure_max;
    double *ring_depth; /* with a bore map: the ring's depth on it, m, per sample; else NULL */
    int *flank;         /* enum rd_flank per sample */
    int n_events;
    rd_lift_event *events;
    /* Solver work (CVODE counters) */
    long steps, rhs_evals, jac_evals, lin_setups, nonlin_iters, nonlin_fails, err_test_fails,
        root_evals;
    int model;     /* enum rd_lift_model_kind actually integrated */
    int modes;     /* elastic modes of a modal model; 0 otherwise */
    char why[320]; /* why that model (the scene content that decided it) */
    /* A run stopped by /numerics/max_steps after at least one whole cycle
     * returns those cycles (samples and events up to their end) with
     * partial = 1, the crank angle the integrator reached, and the reason
     * and what would make the run cheaper in `warning`; no error estimate.
     * A run stopped by its monitor (cancel, time limit) does the same but
     * still returns RD_ECANCELED (or RD_ETIMEOUT); stopped in the estimate
     * run, it keeps every cycle, partial = 1 and no estimate.  The caller
     * frees the result in every case (rd_lift_result_cleanup). */
    int partial;
    int partial_stop;         /* what stopped it: RD_ELIMIT, RD_ECANCELED or RD_ETIMEOUT */
    double crank_deg_reached; /* deg; the end of the run when not partial */
    char warning[400];        /* empty when not partial */
    /* The error estimate (estimate_error; NAN if none, or if a reference run
     * has other flank changes than the scene's): the lift error over the
     * clearance and the flank changes' error, deg, each the sum of the time
     * integration's share (the run at rtol/10, atol/10) and, for the full and
     * modal models, the segment count's (the run at n/2 segments, its
     * difference / (2^1.5 - 1)); the rigid model's covers the time only. */
    double error_estimate;
    double event_error_deg;
    double event_error_time_deg;     /* the time integration's share, deg */
    double event_error_segments_deg; /* the segment count's share, deg; NAN if not estimated */
    /* the rigid ring's share where auto chose it on a friction scene: its
     * largest difference from the full ring in the run-time check, deg
     * (part of event_error_deg); NAN otherwise */
    double event_error_model_deg;
    int segments_half;        /* n of that run (0: none) */
    int segments_half_events; /* its number of flank changes */
    /* Not empty when the flank changes are not converged in the segment
     * count: the n/2 run has other flank changes, or their segment-count
     * share exceeds RD_LIFT_SEGMENT_WARN_DEG (a warning of the result, path
     * /discretization/segments). */
    char accuracy_warning[400];
    rd_lift_lube lube; /* lubricated runs */
} rd_lift_result;

void rd_lift_params_default(rd_lift_params *p);
/* "full", "rigid", "modal", "auto" (NULL for an unknown kind). */
const char *rd_lift_model_name(int model);
/* Checks every value, naming the scene field ("/engine/speed_rpm", ...). */
int rd_lift_validate(const rd_lift_params *p, const rd_ring_params *ring, int segments,
                     rd_error *err);

/*
 * The lift analysis as a handle: validate and build once, run as often as
 * needed.
 *
 * rd_lift_create checks the scene once (rd_lift_validate's messages) and
 * builds the ring of `segments` segments (rd_ring).  What every run of the
 * scene shares is made by the first run that needs it and kept: the
 * lubricated model's film over the run, the ring of n/2 segments of the
 * error estimate and of auto's check, the static start in a distorted bore.
 * Each rd_lift_run then gives, bit for bit, what a fresh rd_lift_solve of
 * the same scene gives.
 *
 * Use:
 *     rd_lift *lift = NULL;
 *     rd_lift_result res;
 *     int rc = rd_lift_create(&ring, segments, &params, &lift, err);
 *     if (rc == RD_OK)
 *         rc = rd_lift_run(lift, mon, &res, err);  (as often as wanted)
 *     ... res ...
 *     rd_lift_result_cleanup(&res);                (also after a failed run)
 *     rd_lift_free(lift);
 *
 * Ownership: the handle copies *ring and *p; the arrays they point to (gas
 * tables, the tilt table, a bore map, a section's spec) are borrowed and
 * must outlive the handle.  A handle runs one run at a time (it is not
 * thread-safe); different handles are independent.  rd_lift_free(NULL) is a
 * no-op.
 */
typedef struct rd_lift rd_lift;

/* Validates (RD_EINVAL & co. with the field's path, nothing allocated) and
 * builds; *out is NULL on failure. */
int rd_lift_create(const rd_ring_params *ring, int segments, const rd_lift_params *p, rd_lift **out,
                   rd_error *err);
/* One run of the scene: `out` is overwritten and owns its arrays
 * (rd_lift_result_cleanup, also after a failure).  The monitor reports
 * progress and may cancel (the result then keeps its whole cycles, see
 * rd_lift_result.partial). */
int rd_lift_run(rd_lift *h, const rd_monitor *mon, rd_lift_result *out, rd_error *err);
void rd_lift_free(rd_lift *h);

/* rd_lift_create, rd_lift_run, rd_lift_free: one run; `out` is overwritten
 * and owns its arrays (rd_lift_result_cleanup, also after a failure, a
 * refused scene included). */
int rd_lift_solve(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                  const rd_monitor *mon, rd_lift_result *out, rd_error *err);
void rd_lift_result_cleanup(rd_lift_result *r);

/* The flank/bore penalty stiffness (Pa/m) used when p->contact_stiffness is 0
 * (rd_lift.c explains the rule); p and ring must be valid. */
double rd_lift_contact_stiffness_default(const rd_ring_params *ring, const rd_lift_params *p);

/* 1 if the ring meets anything but the round bore of its diameter d (a
 * distortion, another diameter, or a bore map). */
int rd_lift_bore_distorted(const rd_lift_params *p, double d);

#endif
