/*
 * rd_ringpack — the ring pack and blow-by (issue 15; thesis 2.4.4, eqs.
 * 2.22-2.25; MODEL.md "Ring pack and blow-by"): the gas pressures between 1
 * to 3 rings computed from one cylinder pressure, coupled both ways with the
 * rings' axial motion in their grooves.
 *
 * Network (absolute pressures throughout; the lift analysis' tables are
 * gauge).  For rings i = 1..R (top first) the gas volumes are
 *   land_i    the crevice between piston land and liner above ring i
 *             (land_1 = top land), V = pi h c (d - c), h its height, c its
 *             piston-to-liner clearance, d the bore;
 *   groove_i  the groove space the ring does not fill: behind it
 *             pi (r_in^2 - r_b^2)(h_r + a) plus the axial clearance over the
 *             faces pi (d^2/4 - r_in^2) a, with r_in = d/2 - b the ring's inner
 *             radius, r_b = r_in - radial clearance, h_r the ring height, a
 *             the axial clearance (constant: the ring moving up fills the
 *             space above it and frees the same below);
 * bounded by the cylinder (the input trace) above and the crankcase (a
 * constant pressure) below ring R.  Each volume holds ideal gas at its
 * given temperature (lands and grooves T_l, crankcase T_c):
 *   p V = m R_g T   and   dp/dt = R_g T / V * sum of the mass flows in.
 * Passages (rd_gasflow.h; discharge coefficient C_d of the ring):
 *   cylinder -> land_1         orifice, area pi d c_1 (the top land's
 *                              clearance);
 *   ring i upper flank, land_i -> groove_i,  area pi d max(a - z_i, 0);
 *   ring i lower flank, groove_i -> below_i, area pi d max(z_i, 0);
 *     each the orifice limited by the viscous slot flow (rd_gasflow_limited:
 *     width pi (d - b), the flank's mean circumference, length b, the
 *     ring's radial width, height area / width), or the orifice alone
 *     (flank_passage);
 *   ring i end gap,     land_i -> below_i,   orifice, area end_gap_area or
 *                                            g_i min(c_i, c_{i+1}) (closed
 *                                            gap times the narrower land
 *                                            clearance; the last ring: c_i);
 *                                            an oil ring: leak_area, C_d 1;
 * below_i = land_{i+1}, or the crankcase under the last ring.  Gas entering
 * the crevices takes the crevice temperature (Namazian & Heywood 1982), so
 * the cylinder -> land flow uses T_l whichever way it goes.
 *
 * Rings, per ring (numerics.model pack-wide, rings[i].model per ring):
 *  - axial (RD_RINGPACK_AXIAL; auto without friction): the pack's own ring,
 *    below;
 *  - rigid, full, modal: the lift analysis' models (rd_lift_model.h), with
 *    the network's pressures as their gauge face loads and their
 *    per-segment lifts sizing the flank passages (rd_ringpack_lift.c);
 *    auto with friction gives rigid (friction's couple twists the ring and
 *    decides its leaves, which the axial ring cannot represent);
 *  - a pinned ring is held on its flank whatever the model.
 * The axial ring: axial only (what the lift analysis' rigid model reduces
 * to for axisymmetric scenes without friction): lift z_i (0 = seated on the
 * lower flank, a = on the upper),
 *   m_i z_i'' = m_i s''(t) - m_i g + A_i (p_below - p_above),
 * s the piston's distance below TDC (rd_engine_piston; m s'' is the inertia
 * pseudo-force in the piston frame), A_i = b (pi (d - b) - g) the face area
 * and m_i = rho h A_i the mass; p_above = p(land_i), p_below = p(below_i)
 * (the lift analysis' "fixed" active areas; with flank_pressure linear
 * each is averaged with the groove's, so A_i (p_below - p_above) / 2).
 * With gravity 0 the m_i g term is left out.  The flanks are hard stops:
 * a ring stays seated while the net force presses it on the flank, leaves
 * when it changes sign, and lands inelastically (the oil film absorbs the
 * impact; MODEL.md "lift models").  Changes are located by CVODE's root
 * finding and the integration restarts there.  A pinned ring stays on its
 * flank.
 * Flank changes (every ring's events; issue 39): dated where the ring's
 * (mean) lift crosses the edge of a band of flank_band x its axial
 * clearance at each flank, a landing where it moves into the band, a leave
 * where it moves out (a bounce that leaves the band is two events), as the
 * lift analysis dates them (rd_lift.h).  Each event also keeps touch_deg:
 * after a landing where the lift first reached the flank (the axial ring's
 * inelastic impact), before a leave where it last left it (the axial ring's
 * net force turning away, or its impact against its load); NAN if it never
 * touched in between.  flank_band 0: dated at the touch and the leave
 * themselves (touch_deg = crank_deg).
 * Friction (physics.friction, Coulomb only): the liner's axial friction on
 * the ring, as the lift analysis' (rd_lift_forces.c) on the uniform ring,
 *   F_f = -mu N tanh(u / u_reg),  u = z_i' - s'(t)  (sliding speed on the liner),
 *   N = p0 h L + (p_groove - p_cc) h 2 pi r_in,   p0 = 2 F_t / (d h),
 * N the ring's bore normal force in radial equilibrium: the pretension over
 * the running face (L = pi d - g) plus the groove's gas (gauge against the
 * crankcase) on the back face; u_reg = 1e-3 x the mean piston speed
 * (rd_liner_ureg).  Added to the axial force above.
 *
 * State (N0 = 2R + 2R + 4): y = [p(land_1), p(groove_1), ..., p(groove_R),
 * z_1, z_1', ..., z_R, z_R', M_in, M_back, M_cc, M_cc_back], the last four
 * the cumulative masses in from the cylinder, back into it, into the
 * crankcase and out of it (kg); then each lift-model ring's own states (its
 * z_i slots unused).  CVODE BDF; dense Newton (DQ Jacobian) with axial rings
 * only, else the bordered block elimination of rd_ringpack_newton.c.
 * Since every flow leaves one state volume and enters another, BDF keeps
 * the linear invariant sum m_v + M_back - M_in + M_cc - M_cc_back exactly
 * (to round-off): the mass balance the tests check.
 */
#ifndef RD_RINGPACK_H
#define RD_RINGPACK_H

#include "rd_error.h"
#include "rd_gasflow.h"
#include "rd_lift.h"
#include "rd_ring.h"

#define RD_RINGPACK_RINGS_MAX    3
#define RD_RINGPACK_VOLUMES_MAX  (2 * RD_RINGPACK_RINGS_MAX + 2) /* with cylinder, crankcase */
#define RD_RINGPACK_FLOWS_MAX    (3 * RD_RINGPACK_RINGS_MAX + 1)
#define RD_RINGPACK_CYCLES_MAX   50
#define RD_RINGPACK_PERIODIC_TOL 1e-3 /* numerics.periodic_tolerance's default */
/* An oil ring's default leakage area C_d A, m^2: the 0.3 x 0.2 mm gap at
 * C_d 0.7 of the rectangular stand-in the thesis pack used before. */
#define RD_RINGPACK_OIL_LEAK 4.2e-8

/* A pinned ring is held: on a flank, or at half its axial clearance
 * (middle: both flank passages open a/2, the limit of a fluttering ring). */
enum rd_ringpack_pin { RD_PIN_FREE = 0, RD_PIN_LOWER = 1, RD_PIN_UPPER = 2, RD_PIN_MIDDLE = 3 };
/* A ring's kind: a compression ring (end gap, flanks), or the oil-control
 * ring (last only: its leakage through gap, rails and drain as one
 * effective area leak_area, C_d included, from the land above it to the
 * crankcase; held on its lower flank unless asked otherwise). */
enum rd_ringpack_kind { RD_RING_COMPRESSION = 0, RD_RING_OIL = 1 };
/* Flank passages: the smaller of the orifice and the viscous slot flow
 * (rd_gasflow_limited), or the orifice alone. */
enum rd_flank_passage { RD_PASSAGE_VISCOUS_LIMITED = 0, RD_PASSAGE_ORIFICE = 1 };
/* The gas on a ring's flanks (faces): full (each face carries its own
 * land's pressure, the thesis'), or linear (each face carries the mean of
 * the groove's and its land's pressures: the linear fall from groove to
 * land across the flank, sealed or open; the axial net gas force is then
 * half the full one). */
enum rd_flank_pressure { RD_FLANK_PRESSURE_FULL = 0, RD_FLANK_PRESSURE_LINEAR = 1 };
/* The pack's own ring model beside the lift analysis' (enum
 * rd_lift_model_kind): axial lift only, hard flank stops (above). */
#define RD_RINGPACK_AXIAL        4
#define RD_RINGPACK_SEGMENTS_MAX 200

typedef struct rd_ringpack_ring {
    rd_ring_params ring; /* section, closed gap, density */
    rd_groove_params groove;
    double land_height;           /* the land above the ring, m */
    double land_clearance;        /* its piston-to-liner radial clearance, m */
    double gap_angle_deg;         /* where the gap sits around the bore, deg: turns the bore's
                                   * distortion into the ring's frame; with a tilt, 0 or 180 */
    double discharge_coefficient; /* C_d of its passages, 0..1 */
    int pinned;                   /* enum rd_ringpack_pin */
    /* The ring's model (rd_ringpack_lift.c): enum rd_lift_model_kind or
     * RD_RINGPACK_AXIAL; RD_LIFT_MODEL_AUTO: the pack's p->model. */
    int model;
    int segments; /* n of the full and modal models, 4..RD_RINGPACK_SEGMENTS_MAX */
    int modes;    /* elastic modes of the modal model, 0 = 12 */
    /* The end gap's flow area, m^2 (C_d applies); 0: the rule, closed gap x
     * the smaller of the radial clearances of the land above and the land
     * below (the last ring: the land above) */
    double end_gap_area;
    int kind;         /* enum rd_ringpack_kind */
    double leak_area; /* RD_RING_OIL: effective leakage area C_d A, m^2 */
    /* The running face of the lubricated friction model (rd_liner.h; the
     * lift analysis' ring.face), each ring its own. */
    rd_face_params face;
} rd_ringpack_ring;

typedef struct rd_ringpack_params {
    rd_engine_params engine; /* cycles: whole cycles, 2..50 (periodic: the most run) */
    /* 1: run until a cycle's change against the one before (the result's
     * periodicity) is below periodic_tolerance, at least 2 cycles and at
     * most engine.cycles; 0: engine.cycles cycles */
    int periodic;
    double periodic_tolerance; /* 1e-6 .. 0.1, default 1e-3 */
    int n_rings;               /* 1..3 */
    rd_ringpack_ring rings[RD_RINGPACK_RINGS_MAX];
    int cylinder_kind;       /* enum rd_cylinder_kind */
    int table_points;        /* RD_CYLINDER_TABLE: the trace, borrowed */
    const double *table_deg; /* strictly increasing, 0 .. 720 covered */
    const double *table_pa;  /* absolute, Pa, > 0 */
    rd_cylinder_synthetic synthetic;
    double crankcase_pa; /* absolute, Pa */
    /* physics.gas: heat capacity ratio k (1 < k < 1.67), gas constant R
     * (J/(kg K)), viscosity (Pa s; 0: Sutherland's law, rd_gas_viscosity,
     * at each flank passage's temperature: the mean of its two volumes') */
    double kappa, gas_constant, gas_viscosity;
    int flank_passage;           /* enum rd_flank_passage */
    int flank_pressure;          /* enum rd_flank_pressure */
    double T_lands, T_crankcase; /* K */
    int gravity;                 /* 1: g along -z */
    double step_deg;             /* output sampling (rounded so 720 / step is whole) */
    /* output.flank_band: the band at each flank, a fraction of each ring's
     * axial clearance, where flank changes are dated (above); 0 to
     * RD_LIFT_FLANK_BAND_MAX, default RD_LIFT_FLANK_BAND */
    double flank_band;
    double rtol, atol;  /* atol on the lifts, m */
    long max_steps;     /* CVODE steps for the whole run */
    int estimate_error; /* 1: second run at rtol/10, atol/10 */
    /* model NONE (default), COULOMB or LUBRICATED: each ring's own oil film
     * (its face, friction.lube, bore.roughness_rq; rd_ringpack_film.c): the
     * film of a cycle is integrated, at its end, over the pressures and
     * speeds the ring's faces saw in it, and carries the ring's friction in
     * the next cycle (the first cycle's film: no gas); film_step_deg its
     * largest time step, crank deg */
    rd_friction_params friction;
    double film_step_deg;
    int model; /* every ring's model unless its own says (rd_ringpack_ring) */
    /* Carried to the lift-model rings (rd_ringpack_lift.c): the bore every
     * ring runs in (rd_bore, rd_liner.h; distortion phases from
     * the bore's angle 0, each ring's taken from its gap at gap_angle_deg),
     * the piston tilt (engine.piston_tilt_deg and the table, about the pin
     * axis at 90 deg from the bore's angle 0, positive raising the groove at
     * angle 0) and the active areas (enum rd_gas_area).  A distorted bore or a
     * tilt needs a flexible ring (auto: full), dynamic areas a lift model
     * (auto: rigid); the axial ring takes none of them. */
    rd_bore bore;
    int active_area;
    /* A bore that changes down its height (rd_bore_map.h; borrowed, NULL:
     * none), its layers' phases from the bore's angle 0 as bore's: each
     * moving ring meets it at its own depth, ring_z_tdc (the top ring's
     * depth below the top of the bore at TDC, m) plus the rings and lands
     * above it (rd_ringpack_ring_depth) plus the piston's travel, as the
     * lift analysis' ring does (rd_lift_params.bore_map); every layer the
     * same bore gives /bore/distortion's run bit for bit.  Like a distorted
     * bore it needs a flexible ring (auto: full). */
    const rd_bore_map *bore_map;
    double ring_z_tdc;
    /* Test hook: the ring faces' pressures from these gauge tables (above,
     * below; behind for friction) instead of the network's.  NULL normally. */
    const rd_gas_params *face_tables;
} rd_ringpack_params;

/* Ring i's depth at TDC on a bore map: ring_z_tdc plus, for every ring
 * above it, its axial height and the land below it (rings[j].land_height
 * of the ring under it), m. */
double rd_ringpack_ring_depth(const rd_ringpack_params *p, int i);

typedef struct rd_ringpack_result {
    int samples, n_rings, n_volumes, n_flows, cycles;
    double *crank_deg; /* samples: the last cycle, 0..720 */
    double *pressure;  /* n_volumes x samples: cylinder, land_1, groove_1, ..., crankcase */
    double *lift;      /* n_rings x samples, m */
    /* n_rings x samples, enum rd_flank: the band the lift is in (a lift
     * ring's mean lift, an axial ring's z, against flank_band x c_a; with
     * flank_band 0 a lift ring's against 1 % of c_a, an axial ring's mode:
     * seated lower or upper, or free) */
    int *flank;
    double *friction; /* n_rings x samples, N, +z up (0 without friction) */
    double *flow;     /* n_flows x samples, kg/s, positive from `flow_from` to `flow_to` */
    /* the last cycle's, crank_deg in 0..720; touch_deg shifted alike (a
     * leave's may fall before 0: it left the flank in the cycle before) */
    rd_lift_event *events[RD_RINGPACK_RINGS_MAX];
    int n_events[RD_RINGPACK_RINGS_MAX];
    const char *volume_name[RD_RINGPACK_VOLUMES_MAX]; /* static strings */
    double volume_m3[RD_RINGPACK_VOLUMES_MAX];        /* 0 for cylinder and crankcase */
    char flow_name[RD_RINGPACK_FLOWS_MAX][32];
    int flow_from[RD_RINGPACK_FLOWS_MAX], flow_to[RD_RINGPACK_FLOWS_MAX]; /* volume indices */
    /* Last cycle's balance, kg per cycle */
    double inflow_kg;        /* from the cylinder into the top land */
    double reverse_kg;       /* from the top land back into the cylinder */
    double blowby_kg;        /* net into the crankcase */
    double blowby_l_per_min; /* at 1.01325 bar and 20 C */
    double stored_change_kg; /* gas held in the volumes, end minus start of the cycle */
    double mass_residual;    /* |in - back - blowby - stored change| / throughput */
    double periodicity;      /* relative change of the last cycle against the one before */
    int settled;             /* periodic: the change fell below the tolerance (else the
                              * most cycles ran first); 0 otherwise */
    /* CVODE's work over the whole run (summed over the restarts) */
    long steps, rhs_evals, jac_evals, root_evals, restarts, err_test_fails, nonlin_fails;
    /* Per ring: the model integrated (RD_RINGPACK_AXIAL or enum
     * rd_lift_model_kind), its degrees of freedom, elastic modes, why it was
     * chosen, and a lift model's flank contact stiffness (Pa/m; 0 axial). */
    int ring_model[RD_RINGPACK_RINGS_MAX], ring_dof[RD_RINGPACK_RINGS_MAX];
    int ring_modes[RD_RINGPACK_RINGS_MAX];
    char ring_why[RD_RINGPACK_RINGS_MAX][240];
    double ring_stiffness[RD_RINGPACK_RINGS_MAX];
    int states; /* CVODE's unknowns: 2R pressures, 2R axial slots, 4 masses, the lift rings' */
    /* Lubricated friction: each ring's oil film over the last cycle (the
     * lift analysis' block, one cycle), and film_lag: how far that film (from
     * the cycle before's pressures) is from the film the last cycle's own
     * pressures give, max |h0 - h0'| / max(h0', sigma) over the cycle. */
    rd_lift_lube lube[RD_RINGPACK_RINGS_MAX];
    double film_lag[RD_RINGPACK_RINGS_MAX];
    double error_estimate;  /* from the rtol/10 run; NAN if none */
    double event_error_deg; /* largest flank-change angle change in that run; NAN if none */
} rd_ringpack_result;

/* The defaults: one thesis ring in the thesis engine at 2400 rpm, 6 cycles,
 * a fired synthetic trace (60 bar at 15 deg), 1 bar crankcase, 450/380 K;
 * air (k 1.35, R 287, Sutherland's viscosity), viscous-limited flank
 * passages, linear flank pressures, gravity on. */
void rd_ringpack_params_default(rd_ringpack_params *p);
/* The thesis engine's pack (the scene's default): the defaults with three
 * rings, the thesis ring on top (h 1.2 mm, gap 0.3 mm, top land 5 x 0.4
 * mm, axial clearance 30 um), a second ring (h 1.5 mm, gap 0.4 mm, land 4 x
 * 0.3 mm, 40 um, gap at 180 deg) and an oil-control ring (h 2.5 mm, F_t 20
 * N, land 3.5 x 0.2 mm, 40 um, gap at 90 deg, held on its lower flank,
 * leak area RD_RINGPACK_OIL_LEAK). */
void rd_ringpack_params_thesis(rd_ringpack_params *p);
/* Every value, naming the scene field ("/rings/1/groove/axial_clearance"). */
int rd_ringpack_validate(const rd_ringpack_params *p, rd_error *err);

/*
 * The ring pack as a handle: validate once, keep each ring's model.
 *
 * rd_ringpack_create checks the scene once (rd_ringpack_validate's
 * messages).  The first run makes each ring that runs on a lift model
 * (rigid, full, modal) once: its lift parameters, checked
 * (rd_lift_validate), its rd_ring, its lift model (K, M^-1, the contact
 * geometry) and its form (the rigid ring's twist stiffnesses, the modal
 * basis), and in a distorted bore its static start; every later run and
 * accuracy level (the run again at rtol/10, rd_accuracy.h) reuses them.
 * Each rd_ringpack_run gives, bit for bit, what a fresh rd_ringpack_solve
 * of the same scene gives.
 *
 * Use:
 *     rd_ringpack *pack = NULL;
 *     rd_ringpack_result res;
 *     int rc = rd_ringpack_create(&params, &pack, err);
 *     if (rc == RD_OK)
 *         rc = rd_ringpack_run(pack, mon, &res, err);  (as often as wanted)
 *     ... res ...
 *     rd_ringpack_result_cleanup(&res);                (also after a failed run)
 *     rd_ringpack_free(pack);
 *
 * Ownership: the handle copies *p; the arrays it points to (the cylinder
 * table, the tilt table, a bore map, the test hook's tables) are borrowed
 * and must outlive the handle.  A handle runs one run at a time (it is not
 * thread-safe).  rd_ringpack_free(NULL) is a no-op.
 */
typedef struct rd_ringpack rd_ringpack;

/* Validates (nothing allocated on failure) and makes the handle; *out is
 * NULL on failure. */
int rd_ringpack_create(const rd_ringpack_params *p, rd_ringpack **out, rd_error *err);
/* One run: `out` is overwritten and owns its arrays
 * (rd_ringpack_result_cleanup, also after a failure).  The monitor
 * reports progress and may cancel. */
int rd_ringpack_run(rd_ringpack *h, const rd_monitor *mon, rd_ringpack_result *out, rd_error *err);
void rd_ringpack_free(rd_ringpack *h);

/* rd_ringpack_create, rd_ringpack_run, rd_ringpack_free: one run; `out` is
 * overwritten and owns its arrays (rd_ringpack_result_cleanup, also after
 * a failure, a refused scene included). */
int rd_ringpack_solve(const rd_ringpack_params *p, const rd_monitor *mon, rd_ringpack_result *out,
                      rd_error *err);
void rd_ringpack_result_cleanup(rd_ringpack_result *r);

/* "axial", or the lift model's name (rd_lift_model_name); NULL if unknown. */
const char *rd_ringpack_model_name(int model);

/* Standard density of the blow-by gas of gas constant R, kg/m^3:
 * 101325 / (R 293.15). */
double rd_ringpack_standard_density(double R);

#endif
