/*
 * rd_lift — the flexible split ring in its piston groove over engine cycles
 * (thesis 3.5, 2.4; MODEL.md "lift").  SI units; crank angles in the API in
 * degrees, alpha = omega t inside (rad), alpha = 0 at TDC.
 *
 * Unknowns.  Per segment i (n segments of rd_ring, split ring, band order =
 * segment order) the small displacement of its reference point P_i and its
 * small rotation, global components, q_i = (ux, uy, uz, rx, ry, rz), from
 * the installed reference (closed shape centred in the bore, bottom face on
 * the groove's lower flank, z = 0 at the ring's mid-plane), and their rates
 * v_i.  The state is interleaved per segment so that the Jacobian is banded:
 *     y[12 i + k] = q_i[k],  y[12 i + 6 + k] = v_i[k],  k = 0..5   (Q(), V())
 * Equations (linear kinematics: a point X of segment i moves by
 * u_i + r_i x (X - P_i)):
 *     dq_i/dt = v_i,   M_i dv_i/dt = -(K q)_i + f_i(t, q_i, v_i)
 * K: the ring's banded stiffness (rd_ring_assemble_band, kd = 11), M_i: the
 * segment's exact 6x6 mass matrix (inverted once by Cholesky, dpotrf/dpotri).
 * Segment i couples only to i +- 1, so d(ydot)/dy has upper bandwidth 11
 * (dv_i/dq_{i+1}) and lower bandwidth 23 (dv_{i+1}/dq_i).
 *
 * Piston (thesis 1.6-1.8).  s(alpha) = distance of the piston below TDC.
 *   approximate: s = r (1 - cos a + lambda/4 (1 - cos 2a))              (1.6)
 *                v = r w (sin a + lambda/2 sin 2a)                        (1.7)
 *                a = r w^2 (cos a + lambda cos 2a),  lambda = r / l       (1.8)
 *   exact:       s = r (1 - cos a) + l (1 - Q),  Q = sqrt(1 - lambda^2 sin^2 a)
 *                ds/da = r sin a (1 + lambda cos a / Q)
 *                d2s/da2 = r (cos a + lambda (cos 2a + lambda^2 sin^4 a) / Q^3)
 * The piston height is z_p = -s, so in the piston frame each segment feels
 * the pseudo-force -m z_p'' = +m s'' along z; for a rigid segment whose
 * centre of mass is off P_i the exact generalized force is M_i e_z s'' with
 * e_z = (0, 0, 1, 0, 0, 0) the unit axial translation.  Gravity: -g M_i e_z.
 *
 *
 * Files (rd_lift_model.h has the map and the Jacobian plan): this file holds
 * the parameters, their validation, the piston kinematics, the default
 * contact stiffness and the public solve; the forces (contacts, friction,
 * gas) are in rd_lift_forces.c, the model (mass, stiffness, right-hand side,
 * Jacobian) in rd_lift_model.c, the integration and events in
 * rd_lift_driver.c.
 *
 * Default stiffness k (Pa/m, contact_stiffness = 0), the larger of
 *   k_load = P_max / (1e-3 c_a): the largest pressure the scene can put on a
 *     flank (inertia rho h r w^2 (1 + lambda), gravity, friction, gas)
 *     pushes it in by at most 1e-3 of the clearance;
 *   k_dyn = rho h (3e4 w)^2: the flank contact frequency w_c = sqrt(k / (rho h))
 *     is 3e4 times the crank's, so the damped contact follows the load with
 *     a lag 2 zeta / w_c = 3.3e-4 rad = 0.02 deg of crank.
 * Both effects shift the flank-change angles by far less than the flight
 * times (degrees); test_lift checks the angles over 2 decades of k.
 *
 * Error estimate (estimate_error): the accuracy driver (rd_accuracy.h) runs
 * the scene again at rtol/10 and atol/10; the estimate is the largest lift
 * difference over the clearance, and the largest change of the flank-change
 * angles when both runs see the same changes (else NAN).
 */
#include "rd_lift.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_accuracy.h"
#include "rd_lift_model.h"

#define LOAD_PENETRATION 1e-3 /* largest load penetration / c_a for the default k */
/* the range of a given k (validate_stiffness) */
#define STIFFNESS_PENETRATION_MAX 0.1  /* largest load penetration / c_a */
#define STIFFNESS_DEFAULT_MAX     1e3  /* k / the default k */
#define CONTACT_FREQ_RATIO        3e4  /* flank contact frequency / crank frequency */
#define UREG_FRACTION             1e-3 /* u_reg / mean piston speed */
#define MEMORY_BOUND              2e6  /* samples x segments: 16 MB here, ~40 MB as JSON text */
#define GRAVITY                   RD_LIFT_GRAVITY

/* ---------------------------------------------------------------- params */

void rd_lift_params_default(rd_lift_params *p)
{
    memset(p, 0, sizeof *p);
    p->engine.speed_rpm = 1000.0;
    p->engine.crank_radius = 0.04345;
    p->engine.rod_length = 0.130;
    p->engine.kinematics = RD_KINEMATICS_EXACT;
    p->engine.cycles = 2.0;
    p->groove.axial_clearance = 3e-5;
    p->groove.radial_clearance = 5e-4;
    p->gravity = 0;
    p->friction.model = RD_FRICTION_NONE;
    p->friction.coefficient = 0.1;
    /* Stribeck defaults for the thesis ring: SAE 30-40 oil near 100 C (eta =
     * 0.01 Pa s); So_lim = 1e7 puts the mixed-to-hydrodynamic transition near
     * 0.5 m/s sliding speed (So = 63 N / (eta u h)); K = 2e4 gives about 1.2 N
     * (an effective coefficient 0.02) at 5 m/s.  Calibrate for real use. */
    p->friction.viscosity = 0.01;
    p->friction.sommerfeld_transition = 1e7;
    p->friction.hydrodynamic_slope = 2e4;
    p->squeeze.on = 0;
    p->squeeze.viscosity = 0.01; /* the Stribeck default's oil */
    p->squeeze.min_film = 1e-6;  /* ~3 x the combined flank roughness (Ra 0.2-0.4 um) */
    p->gas.points = 0;
    p->gas.active_area = RD_GAS_AREA_FIXED;
    p->contact_stiffness = 0.0;
    p->step_deg = 1.0;
    p->rtol = 1e-6;
    p->atol = 1e-9;
    p->max_steps = 500000;
    p->estimate_error = 1;
    p->model = RD_LIFT_MODEL_AUTO;
    p->modes = 0;
    p->accuracy_deg = 0.1;
}

const char *rd_lift_model_name(int model)
{
    switch (model) {
    case RD_LIFT_MODEL_FULL:
        return "full";
    case RD_LIFT_MODEL_RIGID:
        return "rigid";
    case RD_LIFT_MODEL_MODAL:
        return "modal";
    case RD_LIFT_MODEL_AUTO:
        return "auto";
    default:
        return NULL;
    }
}

static int lift_samples(const rd_lift_params *p)
{
    double total = p->engine.cycles * 720.0;
    return (int)ceil(total / p->step_deg - 1e-9) + 1;
}

static int check_table(const double *v, int n, const char *path, rd_error *err)
{
    if (!v)
        return rd_error_set(err, RD_EINVAL, path, "%s is missing (the gas table has %d points).",
                            path, n);
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]) || v[i] < -1e6 || v[i] > 1e9)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s[%d] = %g Pa is out of range: allowed -1e6 to 1e9 Pa (gauge).",
                                path, i, v[i]);
    return RD_OK;
}

/* engine.piston_tilt_deg and the engine.piston_tilt table. */
static int validate_tilt(const rd_engine_params *e, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range(e->piston_tilt_deg, -RD_LIFT_TILT_MAX_DEG, RD_LIFT_TILT_MAX_DEG,
                             "/engine/piston_tilt_deg", "deg", err)))
        return rc;
    if (e->tilt_points < 0 || e->tilt_points > RD_LIFT_TABLE_MAX)
        return rd_error_set(err, RD_EINVAL, "/engine/piston_tilt/crank_deg",
                            "/engine/piston_tilt has %d points: allowed 1 to %d.", e->tilt_points,
                            RD_LIFT_TABLE_MAX);
    double big = 0.0;
    for (int i = 0; i < e->tilt_points; i++) {
        double a = e->tilt_crank_deg[i], b = e->tilt_deg[i];
        if (!isfinite(a) || a < 0.0 || a > 720.0 || (i > 0 && !(a > e->tilt_crank_deg[i - 1])))
            return rd_error_set(err, RD_EINVAL, "/engine/piston_tilt/crank_deg",
                                "/engine/piston_tilt/crank_deg[%d] = %g deg: the crank angles "
                                "must be strictly increasing within 0 to 720 deg.",
                                i, a);
        if (!isfinite(b))
            return rd_error_set(err, RD_EINVAL, "/engine/piston_tilt/tilt_deg",
                                "/engine/piston_tilt/tilt_deg[%d] is not a finite number.", i);
        big = fmax(big, fabs(b));
    }
    if (fabs(e->piston_tilt_deg) + big > RD_LIFT_TILT_MAX_DEG)
        return rd_error_set(err, RD_EINVAL, "/engine/piston_tilt/tilt_deg",
                            "/engine/piston_tilt_deg + the largest /engine/piston_tilt/tilt_deg "
                            "= %g deg: the tilt is allowed up to %g deg (small-angle model).",
                            fabs(e->piston_tilt_deg) + big, RD_LIFT_TILT_MAX_DEG);
    return RD_OK;
}

static int validate_engine(const rd_engine_params *e, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range(e->speed_rpm, 1.0, 30000.0, "/engine/speed_rpm", "rpm", err)) ||
        (rc = rd_error_range(e->crank_radius, 1e-3, 1.0, "/engine/crank_radius", "m", err)))
        return rc;
    /* lambda = r / l <= 0.9: the exact slider-crank needs lambda < 1; real
     * engines have 0.2..0.4. */
    if (!isfinite(e->rod_length) || e->rod_length < e->crank_radius / 0.9 || e->rod_length > 10.0)
        return rd_error_set(err, RD_EINVAL, "/engine/rod_length",
                            "/engine/rod_length = %g m is out of range: allowed %g m (crank "
                            "radius / 0.9) to 10 m.",
                            e->rod_length, e->crank_radius / 0.9);
    if (e->kinematics != RD_KINEMATICS_EXACT && e->kinematics != RD_KINEMATICS_APPROXIMATE)
        return rd_error_set(err, RD_EINVAL, "/engine/kinematics",
                            "/engine/kinematics = %d is unknown: use exact or approximate.",
                            e->kinematics);
    if (!isfinite(e->cycles) || e->cycles <= 0.0 || e->cycles > RD_LIFT_CYCLES_MAX)
        return rd_error_set(err, e->cycles > RD_LIFT_CYCLES_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/engine/cycles",
                            "/engine/cycles = %g is out of range: allowed above 0 up to %g.",
                            e->cycles, RD_LIFT_CYCLES_MAX);
    return RD_OK;
}

/* Groove, gravity and friction. */
static int validate_physics(const rd_lift_params *p, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range(p->groove.axial_clearance, 1e-7, 5e-3, "/groove/axial_clearance", "m",
                             err)) ||
        (rc = rd_error_range(p->groove.radial_clearance, 1e-6, 1e-2, "/groove/radial_clearance",
                             "m", err)))
        return rc;
    if (p->gravity != 0 && p->gravity != 1)
        return rd_error_set(err, RD_EINVAL, "/physics/gravity",
                            "/physics/gravity = %d: use true or false.", p->gravity);
    const rd_friction_params *f = &p->friction;
    if (f->model != RD_FRICTION_NONE && f->model != RD_FRICTION_COULOMB &&
        f->model != RD_FRICTION_STRIBECK)
        return rd_error_set(err, RD_EINVAL, "/physics/friction/model",
                            "/physics/friction/model = %d is unknown: use coulomb or stribeck.",
                            f->model);
    if (f->model != RD_FRICTION_NONE &&
        (rc = rd_error_range(f->coefficient, 0.0, 10.0, "/physics/friction/coefficient", "", err)))
        return rc;
    if (f->model == RD_FRICTION_STRIBECK &&
        ((rc = rd_error_range(f->viscosity, 1e-5, 10.0, "/physics/friction/viscosity", "Pa s",
                              err)) ||
         (rc = rd_error_range(f->sommerfeld_transition, 0.0, 1e15,
                              "/physics/friction/sommerfeld_transition", "", err)) ||
         (rc = rd_error_range(f->hydrodynamic_slope, 0.0, 1e12,
                              "/physics/friction/hydrodynamic_slope", "", err))))
        return rc;
    if (p->landing != RD_LANDING_PENALTY && p->landing != RD_LANDING_PLASTIC)
        return rd_error_set(err, RD_EINVAL, "/contact/landing",
                            "/contact/landing = %d is unknown: use penalty or plastic.",
                            p->landing);
    const rd_squeeze_params *q = &p->squeeze;
    if (q->on != 0 && q->on != 1)
        return rd_error_set(err, RD_EINVAL, "/physics/squeeze_film",
                            "/physics/squeeze_film on = %d: use 0 or 1.", q->on);
    if (q->on && ((rc = rd_error_range(q->viscosity, 1e-8, 10.0, "/physics/squeeze_film/viscosity",
                                       "Pa s", err)) ||
                  (rc = rd_error_range(q->min_film, 1e-9, 1e-4, "/physics/squeeze_film/min_film",
                                       "m", err))))
        return rc;
    return RD_OK;
}

static int validate_gas(const rd_gas_params *g, rd_error *err)
{
    int rc;
    if (g->points == 0)
        return RD_OK;
    if (g->points < 2 || g->points > RD_LIFT_TABLE_MAX)
        return rd_error_set(
            err, g->points > RD_LIFT_TABLE_MAX ? RD_ELIMIT : RD_EINVAL, "/physics/gas/crank_deg",
            "/physics/gas/crank_deg has %d points: allowed 2 to %d.", g->points, RD_LIFT_TABLE_MAX);
    if (!g->crank_deg)
        return rd_error_set(err, RD_EINVAL, "/physics/gas/crank_deg",
                            "/physics/gas/crank_deg is missing.");
    for (int i = 0; i < g->points; i++) {
        double a = g->crank_deg[i];
        if (!isfinite(a) || a < 0.0 || a > 720.0)
            return rd_error_set(err, RD_EINVAL, "/physics/gas/crank_deg",
                                "/physics/gas/crank_deg[%d] = %g deg is out of range: "
                                "allowed 0 to 720 deg.",
                                i, a);
        if (i > 0 && !(a > g->crank_deg[i - 1]))
            return rd_error_set(err, RD_EINVAL, "/physics/gas/crank_deg",
                                "/physics/gas/crank_deg must be strictly increasing: "
                                "[%d] = %g deg follows %g deg.",
                                i, a, g->crank_deg[i - 1]);
    }
    if ((rc = check_table(g->above, g->points, "/physics/gas/above", err)) ||
        (rc = check_table(g->behind, g->points, "/physics/gas/behind", err)) ||
        (rc = check_table(g->below, g->points, "/physics/gas/below", err)))
        return rc;
    if (g->active_area != RD_GAS_AREA_FIXED && g->active_area != RD_GAS_AREA_DYNAMIC)
        return rd_error_set(err, RD_EINVAL, "/physics/gas/active_area",
                            "/physics/gas/active_area = %d is unknown: use fixed or dynamic.",
                            g->active_area);
    return RD_OK;
}

static double flank_pressure_scale(const rd_ring_params *ring, const rd_lift_params *p);

/* A given contact stiffness, against the scene: the largest flank pressure
 * P may push the ring in by at most 10 % of the axial clearance (a softer
 * flank lets it sink through: 2000 clearances at k = 1e3 on the thesis
 * scene), and k may be at most 1e3 times the default (stiffer, the error
 * estimate's two runs stop agreeing on the flank changes: 1e4 times). */
static int validate_stiffness(const rd_lift_params *p, const rd_ring_params *ring, rd_error *err)
{
    double k = p->contact_stiffness;
    int rc = rd_error_range(k, 1e3, 1e20, "/contact/stiffness", "Pa/m (or 0 for the default)", err);
    if (rc != RD_OK)
        return rc;
    double lo =
        flank_pressure_scale(ring, p) / (STIFFNESS_PENETRATION_MAX * p->groove.axial_clearance);
    double hi = STIFFNESS_DEFAULT_MAX * rd_lift_contact_stiffness_default(ring, p);
    if (!(k >= lo && k <= hi))
        return rd_error_set(err, RD_EINVAL, "/contact", /* a rule of the scene, not the field */
                            "/contact/stiffness = %g Pa/m is out of range for this scene: allowed "
                            "%.4g to %.4g Pa/m (or 0 for the default %.4g).  Below, the largest "
                            "flank pressure (%.4g Pa) pushes the ring into the flank by more than "
                            "%g of the axial clearance; above %g times the default the error "
                            "estimate's runs no longer agree on the flank changes.",
                            k, lo, hi, rd_lift_contact_stiffness_default(ring, p),
                            flank_pressure_scale(ring, p), STIFFNESS_PENETRATION_MAX,
                            STIFFNESS_DEFAULT_MAX);
    return RD_OK;
}

/* Contact stiffness, output sampling, tolerances and the work bounds. */
static int validate_numerics(const rd_lift_params *p, const rd_ring_params *ring, int segments,
                             rd_error *err)
{
    int rc;
    const rd_engine_params *e = &p->engine;
    double ring_d = ring->diameter;
    if (p->contact_stiffness != 0.0 && (rc = validate_stiffness(p, ring, err)))
        return rc;
    if ((rc = rd_error_range(p->step_deg, 1e-3, 90.0, "/output/step_deg", "deg", err)) ||
        (rc = rd_error_range(p->rtol, 1e-12, 1e-2, "/numerics/rtol", "", err)) ||
        (rc = rd_error_range(p->atol, 1e-16, 1e-5, "/numerics/atol", "m", err)))
        return rc;
    if (p->max_steps < 100 || p->max_steps > 1000000000L)
        return rd_error_set(err, RD_EINVAL, "/numerics/max_steps",
                            "/numerics/max_steps = %ld is out of range: allowed 100 to 1e9.",
                            p->max_steps);
    if (!rd_lift_model_name(p->model))
        return rd_error_set(err, RD_EINVAL, "/numerics/model",
                            "/numerics/model = %d is unknown: use auto, rigid, modal or full.",
                            p->model);
    if (p->model == RD_LIFT_MODEL_RIGID && rd_lift_bore_distorted(&p->bore, ring_d))
        return rd_error_set(err, RD_EINVAL, "/numerics/model",
                            "/numerics/model = rigid cannot represent a distorted bore "
                            "(/bore/distortion, /bore/diameter): the contact pressure varies "
                            "around the ring; use auto, modal or full.");
    if (p->model == RD_LIFT_MODEL_RIGID && rd_lift_tilted(&p->engine))
        return rd_error_set(err, RD_EINVAL, "/numerics/model",
                            "/numerics/model = rigid cannot represent a tilted piston "
                            "(/engine/piston_tilt_deg, /engine/piston_tilt): the flank gap varies "
                            "around the ring; use auto, modal or full.");
    if (p->model == RD_LIFT_MODEL_MODAL && segments > RD_LIFT_MODAL_SEGMENTS_MAX)
        return rd_error_set(err, RD_ELIMIT, "/numerics/model",
                            "/numerics/model = modal solves the ring's modes densely and allows "
                            "at most %d segments (/discretization/segments = %d): use fewer "
                            "segments or the full model.",
                            RD_LIFT_MODAL_SEGMENTS_MAX, segments);
    if (p->modes > 6 * segments - 6)
        return rd_error_set(err, RD_EINVAL, "/numerics/modes",
                            "/numerics/modes = %d is out of range: a ring of %d segments has "
                            "%d elastic modes.",
                            p->modes, segments, 6 * segments - 6);
    if ((rc = rd_error_range(p->accuracy_deg, 1e-4, 10.0, "/numerics/accuracy_deg", "deg", err)))
        return rc;
    if (p->modes < 0 || p->modes > RD_LIFT_MODES_MAX)
        return rd_error_set(err, RD_EINVAL, "/numerics/modes",
                            "/numerics/modes = %d is out of range: allowed 0 (auto) to %d.",
                            p->modes, RD_LIFT_MODES_MAX);
    if (p->estimate_error != 0 && p->estimate_error != 1)
        return rd_error_set(err, RD_EINVAL, "/numerics/error_estimate",
                            "/numerics/error_estimate = %d: use true or false.", p->estimate_error);
    double samples = ceil(e->cycles * 720.0 / p->step_deg - 1e-9) + 1.0;
    if (samples > RD_LIFT_SAMPLES_MAX)
        return rd_error_set(err, RD_ELIMIT, "/output/step_deg",
                            "/output/step_deg = %g deg over %g cycles gives %.0f output samples; "
                            "at most %d are allowed: use a larger step or fewer cycles.",
                            p->step_deg, e->cycles, samples, RD_LIFT_SAMPLES_MAX);
    if (samples * segments > MEMORY_BOUND)
        return rd_error_set(err, RD_ELIMIT, "/output/step_deg",
                            "%.0f output samples x %d segments = %.3g per-segment values; at "
                            "most %g are allowed: use a larger /output/step_deg, fewer cycles or "
                            "fewer segments.",
                            samples, segments, samples * segments, MEMORY_BOUND);
    return RD_OK;
}

int rd_lift_validate(const rd_lift_params *p, const rd_ring_params *ring, int segments,
                     rd_error *err)
{
    int rc;
    if ((rc = rd_ring_validate(ring, segments, 0, err)))
        return rc;
    if (ring->section != RD_SECTION_RECTANGLE)
        return rd_error_set(err, RD_EINVAL, "/ring/section",
                            "the lift analysis needs a rectangular ring section (its faces "
                            "seal on the groove flanks).");
    if (segments < 4 || segments > RD_LIFT_SEGMENTS_MAX)
        return rd_error_set(err, segments > RD_LIFT_SEGMENTS_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/discretization/segments",
                            "/discretization/segments = %d is out of range for a lift analysis: "
                            "allowed 4 to %d.",
                            segments, RD_LIFT_SEGMENTS_MAX);
    if ((rc = validate_engine(&p->engine, err)) || (rc = validate_tilt(&p->engine, err)) ||
        (rc = rd_lift_bore_validate(&p->bore, ring, err)) || (rc = validate_physics(p, err)) ||
        (rc = validate_gas(&p->gas, err)) || (rc = validate_numerics(p, ring, segments, err)))
        return rc;
    return RD_OK;
}

/* ------------------------------------------------------------- kinematics */

void rd_lift_piston(const rd_engine_params *e, double alpha, double *s, double *v, double *a)
{
    double r = e->crank_radius, lam = r / e->rod_length;
    double w = e->speed_rpm * 2.0 * M_PI / 60.0;
    double sa = sin(alpha), ca = cos(alpha);
    double s_, ds, dds; /* s and its derivatives with respect to alpha */
    if (e->kinematics == RD_KINEMATICS_APPROXIMATE) {
        s_ = r * (1.0 - ca + 0.25 * lam * (1.0 - cos(2.0 * alpha))); /* (1.6) */
        ds = r * (sa + 0.5 * lam * sin(2.0 * alpha));                /* (1.7) / w */
        dds = r * (ca + lam * cos(2.0 * alpha));                     /* (1.8) / w^2 */
    } else {
        double Q = sqrt(1.0 - lam * lam * sa * sa);
        /* l (1 - Q) = l lam^2 sin^2 / (1 + Q): no cancellation */
        s_ = r * (1.0 - ca) + e->rod_length * lam * lam * sa * sa / (1.0 + Q);
        ds = r * sa * (1.0 + lam * ca / Q);
        dds = r * (ca + lam * (cos(2.0 * alpha) + lam * lam * pow(sa, 4)) / (Q * Q * Q));
    }
    if (s)
        *s = s_;
    if (v)
        *v = w * ds;
    if (a)
        *a = w * w * dds;
}

/* ------------------------------------------------------- default stiffness */

double rd_lift_omega(const rd_engine_params *e)
{
    return e->speed_rpm * 2.0 * M_PI / 60.0;
}

static double table_max_abs(const rd_gas_params *g, const double *v)
{
    double m = 0.0;
    for (int i = 0; i < g->points; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* Largest pressure the scene can put on a flank, Pa. */
static double flank_pressure_scale(const rd_ring_params *ring, const rd_lift_params *p)
{
    const rd_engine_params *e = &p->engine;
    double w = rd_lift_omega(e), lam = e->crank_radius / e->rod_length;
    double rho_h = ring->density * ring->axial_height;
    double P = rho_h * e->crank_radius * w * w * (1.0 + lam);
    if (p->gravity)
        P = fmax(P, rho_h * GRAVITY);
    if (p->friction.model != RD_FRICTION_NONE) {
        /* mu p0 h / b: the friction force per unit flank area */
        double p0 = 2.0 * ring->tangential_force / (ring->diameter * ring->axial_height);
        double pf = p->friction.coefficient * p0 * ring->axial_height / ring->radial_width;
        if (p->friction.model == RD_FRICTION_STRIBECK) {
            /* + the hydrodynamic K eta u h per unit length at the peak speed */
            double umax = e->crank_radius * w * (1.0 + lam);
            pf += p->friction.hydrodynamic_slope * p->friction.viscosity * umax *
                  ring->axial_height / (M_PI * ring->diameter * ring->radial_width);
        }
        P = fmax(P, pf);
    }
    if (p->gas.points > 0) {
        P = fmax(P, table_max_abs(&p->gas, p->gas.above));
        P = fmax(P, table_max_abs(&p->gas, p->gas.behind));
        P = fmax(P, table_max_abs(&p->gas, p->gas.below));
    }
    return P;
}

double rd_lift_contact_stiffness_default(const rd_ring_params *ring, const rd_lift_params *p)
{
    double w = rd_lift_omega(&p->engine);
    double k_load = flank_pressure_scale(ring, p) / (LOAD_PENETRATION * p->groove.axial_clearance);
    double wc = CONTACT_FREQ_RATIO * w;
    double k_dyn = ring->density * ring->axial_height * wc * wc;
    return fmax(k_load, k_dyn);
}

double rd_lift_accel_scale(const rd_ring_params *rp, const rd_lift_params *p)
{
    const rd_engine_params *e = &p->engine;
    double w = rd_lift_omega(e);
    double a = e->crank_radius * w * w * (1.0 + e->crank_radius / e->rod_length);
    return fmax(a, flank_pressure_scale(rp, p) / (rp->density * rp->axial_height));
}

double rd_lift_friction_ureg(const rd_lift_params *p)
{
    /* mean piston speed = 2 x stroke x revolutions per second */
    double mean_speed = 4.0 * p->engine.crank_radius * p->engine.speed_rpm / 60.0;
    return UREG_FRACTION * mean_speed;
}

void rd_lift_result_cleanup(rd_lift_result *r)
{
    if (!r)
        return;
    free(r->crank_deg);
    free(r->lift);
    free(r->lift_min);
    free(r->lift_max);
    free(r->lift_segments);
    free(r->twist);
    free(r->friction_force);
    free(r->flank);
    free(r->events);
    memset(r, 0, sizeof *r);
    r->error_estimate = NAN;
    r->event_error_deg = NAN;
}

/* ------------------------------------------------------------------ solve */

/* The model a scene gets (numerics.model; auto: the cheapest the scene
 * allows at the accuracy target) and why, into out->model and out->why.
 *
 * A distorted bore (rd_lift_bore.c) or a tilted piston (rd_lift_tilt.c)
 * makes the contact pressure or the flank gap vary around the ring: the rigid
 * ring cannot represent it (asked for, it is refused in validation) and auto
 * runs the full ring.  Otherwise the scene is axisymmetric: a round bore, a
 * groove aligned with the ring, loads uniform around it.  On such a scene the rigid model (rd_lift_rigid.c) is exact except for what
 * the split ring's free ends do.  Without friction that is nothing
 * measurable: its flank changes agree with the full model's within 0.035
 * deg (thesis_lift_1000rpm, and the gas example without friction: 0.007
 * deg; test_lift_rigid).  Friction on the running face puts a couple on the
 * ring that the split ring, with its free ends, does not take uniformly.
 * Seated, the ends twist more: the rigid ring takes that with the seated
 * split ring's twist stiffness (rd_lift_rigid.c), which brings a leave
 * decided by the twist's edge lift (1000 rpm Coulomb) from 0.95 to 0.27 deg
 * of full n = 40.  In flight, the ends answer a leave with a wave the middle
 * does not, and the full ring's landings wait for the part that lags: 0.8-0.9
 * deg after the rigid ring's on the 6000 rpm gas example, 3.1 deg at 8000
 * rpm (test_lift_auto), up to 5.9 deg and a different number of flank
 * changes over a 48-scene battery (README "Models").  No uniform stiffness
 * holds that, and the Ritz bases tried (static and Krylov shapes of the
 * split ring, 10-14 dof) land later still; so no accuracy target admits the
 * rigid ring with friction and auto gives friction scenes the full model.
 *
 * The modal model (rd_lift_modal.c) is not picked by auto: measured against
 * the full model on friction scenes (tests/core/test_lift_modal.c, README
 * "Lift models") it converges in m, but slowly where the flank contacts
 * matter: at n = 20, 1000 rpm Coulomb, m = 1..16 modes miss a twist-driven
 * leave by ~1.0 deg and m = 32 by 0.07 deg; on a 6000 rpm gas + Coulomb
 * scene its landings come 1-3 deg late even at m = 32.  At the m that meets
 * 0.1 deg its dense Newton matrix (2 (10 + m)) costs more per step than the
 * full model's band one, so it is never the cheapest model meeting the
 * target; it is there by request (numerics.model = modal). */
#define MODAL_DEFAULT_MODES 12
static int modal_default_modes(int n)
{
    return MODAL_DEFAULT_MODES < 6 * n - 6 ? MODAL_DEFAULT_MODES : 6 * n - 6;
}
static void choose_model(const rd_lift_params *p, int n, double ring_d, rd_lift_result *out)
{
    int fric = p->friction.model != RD_FRICTION_NONE;
    out->model = p->model == RD_LIFT_MODEL_RIGID ? RD_LIFT_MODEL_RIGID : RD_LIFT_MODEL_FULL;
    if (p->model == RD_LIFT_MODEL_RIGID)
        snprintf(out->why, sizeof out->why, "asked for (numerics.model = rigid)%s",
                 fric ? "; with friction its flank changes can miss the full model's by "
                        "several degrees"
                      : "");
    else if (p->model == RD_LIFT_MODEL_FULL)
        snprintf(out->why, sizeof out->why, "asked for (numerics.model = full)");
    else if (p->model == RD_LIFT_MODEL_MODAL) {
        out->model = RD_LIFT_MODEL_MODAL;
        out->modes = p->modes ? p->modes : modal_default_modes(n);
        snprintf(out->why, sizeof out->why,
                 "asked for (numerics.model = modal, %d elastic modes%s)%s", out->modes,
                 p->modes ? "" : " by default",
                 rd_lift_bore_distorted(&p->bore, ring_d) && out->modes < 6 * n - 6
                     ? "; with a distorted bore its truncated basis cannot hold the stiff bore "
                       "contact's equilibrium: flank changes measured up to 100 deg off the "
                       "full model's, use full"
                     : "");
    } else if (rd_lift_bore_distorted(&p->bore, ring_d)) {
        snprintf(out->why, sizeof out->why,
                 "auto: the bore is distorted, so the contact pressure and the friction vary "
                 "around the ring, which the rigid ring cannot represent, and the modal model is "
                 "not cheaper than the full ring at the accuracy target");
    } else if (rd_lift_tilted(&p->engine)) {
        snprintf(out->why, sizeof out->why,
                 "auto: the piston tilt makes the flank gap vary around the ring, which the "
                 "rigid ring cannot represent, and the modal model is not cheaper than the full "
                 "ring at the accuracy target");
    } else if (!fric) {
        out->model = RD_LIFT_MODEL_RIGID;
        snprintf(out->why, sizeof out->why,
                 "auto: the scene is axisymmetric (round bore, aligned groove, loads uniform "
                 "around the ring) and without friction the rigid ring is exact for it");
    } else
        snprintf(out->why, sizeof out->why,
                 "auto: with friction the split ring's free ends lift differently from its "
                 "middle in flight, which delays its landings by up to several degrees against "
                 "the rigid ring's, and the modal model needs more modes than make it cheaper "
                 "than the full ring (numerics.model = modal by request)");
}

/* The two solves of the accuracy driver and what they keep. */
typedef struct lift_solve {
    const rd_ring *ring;
    const rd_lift_params *p;
    const rd_lift_setup *setup;
    rd_lift_result *out;
    rd_lift_run run[2]; /* level 0: the scene; level 1: rtol/10, atol/10 */
    int main_done;      /* level 0 ran every cycle */
} lift_solve;

static int solve_level(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    lift_solve *s = ctx;
    rd_lift_run *r = &s->run[level];
    double scale = level ? 0.1 : 1.0;
    if (level == 1 && s->out->partial)
        return RD_OK; /* no estimate for a partial result: its reference would stop too */
    r->rtol = scale * s->p->rtol;
    r->atol = scale * s->p->atol;
    r->res = level ? NULL : s->out;
    r->modes = s->out->modes;
    int rc = rd_lift_integrate(s->ring, s->p, s->setup, s->out->model, mon, r, err);
    if (level == 0 && (rc == RD_ELIMIT || rc == RD_ECANCELED || rc == RD_ETIMEOUT) && r->done > 0 &&
        r->reached_deg > 0.0)
        rc = rd_lift_keep_partial(s->out, s->p, &s->run[0], rc, err);
    if (level == 0 && rc == RD_OK && !s->out->partial)
        s->main_done = 1;
    return rc;
}

/* error_estimate: largest lift difference / clearance; event error: the
 * largest angle change of matched events, NAN when the two runs see a
 * different number or kind of flank changes (the estimate cannot pair them). */
static int compare_levels(void *ctx, rd_error *err)
{
    (void)err;
    lift_solve *s = ctx;
    const rd_lift_run *a = &s->run[0], *b = &s->run[1];
    double e = 0.0;
    if (s->out->partial)
        return RD_OK;
    for (int k = 0; k < a->samples; k++)
        e = fmax(e, fabs(a->lift[k] - b->lift[k]));
    s->out->error_estimate = e / s->p->groove.axial_clearance;
    if (b->n_events == a->n_events) {
        double de = 0.0;
        for (int j = 0; j < a->n_events; j++) {
            if (b->events[j].kind != a->events[j].kind) {
                de = NAN;
                break;
            }
            de = fmax(de, fabs(b->events[j].crank_deg - a->events[j].crank_deg));
        }
        s->out->event_error_deg = de;
    }
    return RD_OK;
}

/* The result's arrays for S samples of n segments. */
static int result_alloc(rd_lift_result *out, int S, int n, rd_error *err)
{
    out->segments = n;
    out->dof = 6 * n;
    out->samples = S;
    out->crank_deg = malloc((size_t)S * sizeof(double));
    out->lift = malloc((size_t)S * sizeof(double));
    out->lift_min = malloc((size_t)S * sizeof(double));
    out->lift_max = malloc((size_t)S * sizeof(double));
    out->lift_segments = malloc((size_t)S * n * sizeof(double));
    out->twist = malloc((size_t)S * sizeof(double));
    out->friction_force = malloc((size_t)S * sizeof(double));
    out->flank = malloc((size_t)S * sizeof(int));
    if (!out->crank_deg || !out->lift || !out->lift_min || !out->lift_max || !out->lift_segments ||
        !out->twist || !out->friction_force || !out->flank)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples x %d segments.",
                            S, n);
    return RD_OK;
}

int rd_lift_solve_setup(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                        const rd_lift_setup *setup, const rd_monitor *mon, rd_lift_result *out,
                        rd_error *err)
{
    lift_solve s = {.p = p, .setup = setup, .out = out};
    double *y0 = NULL;
    int rc;
    memset(out, 0, sizeof *out);
    out->error_estimate = NAN;
    out->event_error_deg = NAN;
    if ((rc = rd_lift_validate(p, rp, segments, err)))
        return rc;
    rd_ring *ring = rd_ring_create(rp, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    s.ring = ring;
    int S = lift_samples(p);
    if ((rc = result_alloc(out, S, segments, err)))
        goto out;
    choose_model(p, segments, rp->diameter, out);
    if (out->model == RD_LIFT_MODEL_RIGID)
        out->dof = 3; /* axial lift, twist, radial */
    else if (out->model == RD_LIFT_MODEL_MODAL)
        out->dof = 6 + out->modes; /* rigid-body and elastic modes */
    for (int l = 0; l < 2; l++) {
        s.run[l].samples = S;
        s.run[l].lift = l == 0 || p->estimate_error ? malloc((size_t)S * sizeof(double)) : NULL;
        if ((l == 0 || p->estimate_error) && !s.run[l].lift) {
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples.", S);
            goto out;
        }
    }
    /* a distorted bore: both runs start from the ring's static equilibrium in it */
    rd_lift_setup su = setup ? *setup : (rd_lift_setup){0};
    if (rd_lift_bore_distorted(&p->bore, rp->diameter) && !su.y0) {
        y0 = malloc(12 * (size_t)segments * sizeof *y0);
        if (!y0) {
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the bore start.");
            goto out;
        }
        if ((rc = rd_lift_bore_static(ring, p, y0, err)))
            goto out;
        su.y0 = y0;
        s.setup = &su;
    }
    /* the reference run at rtol/10 typically costs 1.5-2x the main run */
    rd_accuracy_plan plan = {.solve = solve_level,
                             .compare = compare_levels,
                             .ctx = &s,
                             .estimate = p->estimate_error,
                             .main_share = 0.4,
                             .reference = "rtol/10 and atol/10"};
    rc = rd_accuracy_run(&plan, mon, NULL, err);
    if ((rc == RD_ECANCELED || rc == RD_ETIMEOUT) && s.main_done)
        rd_lift_estimate_stopped(out, p);
    if (out->model == RD_LIFT_MODEL_MODAL && s.run[0].dof > 0)
        out->dof = s.run[0].dof; /* with the correction shapes kept */
    out->n_events = s.run[0].n_events;
    out->events = s.run[0].events;
    s.run[0].events = NULL;
    if (rc == RD_OK && !out->partial)
        out->crank_deg_reached = 720.0 * p->engine.cycles;
    while (out->partial && out->n_events > 0 &&
           out->events[out->n_events - 1].crank_deg > out->crank_deg[out->samples - 1])
        out->n_events--; /* events after the last whole cycle */
out:
    for (int l = 0; l < 2; l++) {
        free(s.run[l].lift);
        free(s.run[l].events);
    }
    rd_ring_free(ring);
    free(y0);
    return rc;
}

int rd_lift_solve(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                  const rd_monitor *mon, rd_lift_result *out, rd_error *err)
{
    return rd_lift_solve_setup(ring, segments, p, NULL, mon, out, err);
}
