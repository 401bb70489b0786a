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
 * Piston: s(alpha), the distance of the piston below TDC, and its
 * derivatives (rd_engine.h; thesis 1.6-1.8 or the exact slider-crank).
 * The piston height is z_p = -s, so in the piston frame each segment feels
 * the pseudo-force -m z_p'' = +m s'' along z; for a rigid segment whose
 * centre of mass is off P_i the exact generalized force is M_i e_z s'' with
 * e_z = (0, 0, 1, 0, 0, 0) the unit axial translation.  Gravity: -g M_i e_z.
 *
 *
 * Files (rd_lift_model.h has the map and the Jacobian plan): this file holds
 * the parameters and their validation; the scales and the default contact
 * stiffness are rd_lift_scales.c, the public solve rd_lift_solve.c, the
 * forces (contacts, friction, gas) rd_lift_forces.c, the model (mass,
 * stiffness, right-hand side, Jacobian) rd_lift_model.c, the integration and
 * events rd_lift_driver.c.
 *
 */
#include "rd_lift.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

/* the range of a given k (validate_stiffness) */
#define STIFFNESS_PENETRATION_MAX 0.1 /* largest load penetration / c_a */
#define STIFFNESS_DEFAULT_MAX     1e3 /* k / the default k */
#define MEMORY_BOUND              2e6 /* samples x segments: 16 MB here, ~40 MB as JSON text */

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
    p->flank_band = RD_LIFT_FLANK_BAND;
    rd_lube_params_default(&p->friction.lube, &p->face);
    p->bore.roughness_rq = RD_LINER_RQ_DEFAULT;
    p->film_step_deg = RD_LIFT_FILM_STEP_DEG;
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

int rd_lift_samples(const rd_lift_params *p)
{
    double total = p->engine.cycles * 720.0;
    return (int)ceil(total / p->step_deg - 1e-9) + 1;
}

/* A gas table's pressures, path relative to the gas block ("/above"). */
static int check_table(const double *v, int n, const char *path, rd_error *err)
{
    if (!v)
        return rd_error_set(err, RD_EINVAL, path, "@%s is missing (the gas table has %d points).",
                            path, n);
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]) || v[i] < -1e6 || v[i] > 1e9)
            return rd_error_set(err, RD_EINVAL, path,
                                "@%s[%d] = %g Pa is out of range: allowed -1e6 to 1e9 Pa (gauge).",
                                path, i, v[i]);
    return RD_OK;
}

/* engine.cycles (the rest of the engine block: rd_engine_validate), in the
 * engine's block. */
static int validate_cycles(const rd_engine_params *e, rd_error *err)
{
    if (!isfinite(e->cycles) || e->cycles <= 0.0 || e->cycles > RD_LIFT_CYCLES_MAX)
        return rd_error_set(err, e->cycles > RD_LIFT_CYCLES_MAX ? RD_ELIMIT : RD_EINVAL, "/cycles",
                            "@/cycles = %g is out of range: allowed above 0 up to %g.", e->cycles,
                            RD_LIFT_CYCLES_MAX);
    return RD_OK;
}

/* A bore map, in the bore's block: the plain bore's distortion not given
 * besides, the map's rules, and the ring's depth over the whole stroke
 * within the map. */
static int bore_map_checks(const rd_lift_params *p, double d, rd_error *err)
{
    const rd_bore_map *m = p->bore_map;
    if (p->bore.n_distortion > 0)
        return rd_error_set(err, RD_EINVAL, "/distortion",
                            "@/distortion is not read with a bore map: give the distortion "
                            "per layer (@/layers/<i>/distortion).");
    int rc = rd_bore_map_validate(m, d, err);
    if (rc)
        return rc;
    if ((rc = rd_error_range(p->ring_z_tdc, 0.0, RD_BORE_Z_MAX, "/ring_z_tdc_m", "m", err)))
        return rc;
    double lo = p->ring_z_tdc, hi = lo + 2.0 * p->engine.crank_radius;
    double top = m->layer[0].z, bottom = m->layer[m->n_layers - 1].z;
    if (lo < top || hi > bottom)
        return rd_error_set(err, RD_EINVAL, "/layers",
                            "the ring runs from %g m (TDC, @/ring_z_tdc_m) to %g m (BDC, "
                            "two crank radii lower) down the bore, but @/layers covers %g to "
                            "%g m: the map must cover the ring's whole travel (a bore the same at "
                            "every height: @/distortion).",
                            lo, hi, top, bottom);
    return RD_OK;
}

/* The bore block: the bore, then a bore map. */
static int validate_bore(const rd_lift_params *p, double d, rd_error *err)
{
    size_t m = rd_error_enter(err, "/bore");
    int rc = rd_bore_validate(&p->bore, d, err);
    if (!rc && p->bore_map)
        rc = bore_map_checks(p, d, err);
    rd_error_leave(err, m);
    return rc;
}

/* The lubricated model: its inputs (the face at /ring/face), the film's
 * step (any bore and tilt: a distorted bore, a map or a moving tilt gets a
 * film per segment, rd_lift_films.c). */
static int validate_lubricated(const rd_lift_params *p, rd_error *err)
{
    size_t m = rd_error_enter(err, "/ring");
    rd_error_enter(err, "/face");
    int rc = rd_face_validate(&p->face, err);
    rd_error_leave(err, m);
    rc = rc ? rc : rd_lube_validate(&p->friction.lube, p->bore.roughness_rq, err);
    return rc ? rc
              : rd_error_range_in("/numerics", p->film_step_deg, 0.01, RD_LIFT_FILM_STEP_MAX_DEG,
                                  "/film_step_deg", "deg", err);
}

/* Gravity and the friction model's name, in the physics block. */
static int physics_switches(const rd_lift_params *p, rd_error *err)
{
    if (p->gravity != 0 && p->gravity != 1)
        return rd_error_set(err, RD_EINVAL, "/gravity", "@/gravity = %d: use true or false.",
                            p->gravity);
    const rd_friction_params *f = &p->friction;
    if (f->model != RD_FRICTION_NONE && f->model != RD_FRICTION_COULOMB &&
        f->model != RD_FRICTION_STRIBECK && f->model != RD_FRICTION_LUBRICATED)
        return rd_error_set(err, RD_EINVAL, "/friction/model",
                            "@/friction/model = %d is unknown: use coulomb, stribeck or "
                            "lubricated.",
                            f->model);
    return RD_OK;
}

/* The friction laws' constants, in the physics block. */
static int friction_laws(const rd_friction_params *f, rd_error *err)
{
    int rc;
    if (f->model != RD_FRICTION_NONE &&
        (rc = rd_error_range(f->coefficient, 0.0, 10.0, "/friction/coefficient", "", err)))
        return rc;
    if (f->model == RD_FRICTION_STRIBECK &&
        ((rc = rd_error_range(f->viscosity, 1e-5, 10.0, "/friction/viscosity", "Pa s", err)) ||
         (rc = rd_error_range(f->sommerfeld_transition, 0.0, 1e15,
                              "/friction/sommerfeld_transition", "", err)) ||
         (rc = rd_error_range(f->hydrodynamic_slope, 0.0, 1e12, "/friction/hydrodynamic_slope", "",
                              err))))
        return rc;
    return RD_OK;
}

/* The squeeze film, in the physics block. */
static int squeeze_checks(const rd_squeeze_params *q, rd_error *err)
{
    int rc;
    if (q->on != 0 && q->on != 1)
        return rd_error_set(err, RD_EINVAL, "/squeeze_film", "@/squeeze_film on = %d: use 0 or 1.",
                            q->on);
    if (q->on &&
        ((rc = rd_error_range(q->viscosity, 1e-8, 10.0, "/squeeze_film/viscosity", "Pa s", err)) ||
         (rc = rd_error_range(q->min_film, 1e-9, 1e-4, "/squeeze_film/min_film", "m", err))))
        return rc;
    return RD_OK;
}

/* Groove, gravity, friction, landing and the squeeze film. */
static int validate_physics(const rd_lift_params *p, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range_in("/groove", p->groove.axial_clearance, 1e-7, 5e-3,
                                "/axial_clearance", "m", err)) ||
        (rc = rd_error_range_in("/groove", p->groove.radial_clearance, 1e-6, 1e-2,
                                "/radial_clearance", "m", err)))
        return rc;
    size_t m = rd_error_enter(err, "/physics");
    rc = physics_switches(p, err);
    rd_error_leave(err, m);
    if (!rc && p->friction.model == RD_FRICTION_LUBRICATED)
        rc = validate_lubricated(p, err);
    m = rd_error_enter(err, "/physics");
    rc = rc ? rc : friction_laws(&p->friction, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/contact");
    if (!rc && p->landing != RD_LANDING_PENALTY && p->landing != RD_LANDING_PLASTIC)
        rc = rd_error_set(err, RD_EINVAL, "/landing",
                          "@/landing = %d is unknown: use penalty or plastic.", p->landing);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/physics");
    rc = rc ? rc : squeeze_checks(&p->squeeze, err);
    rd_error_leave(err, m);
    return rc;
}

/* The gas tables, in the gas block. */
static int gas_checks(const rd_gas_params *g, rd_error *err)
{
    int rc;
    if (g->points < 2 || g->points > RD_LIFT_TABLE_MAX)
        return rd_error_set(err, g->points > RD_LIFT_TABLE_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/crank_deg", "@/crank_deg has %d points: allowed 2 to %d.", g->points,
                            RD_LIFT_TABLE_MAX);
    if (!g->crank_deg)
        return rd_error_set(err, RD_EINVAL, "/crank_deg", "@/crank_deg is missing.");
    for (int i = 0; i < g->points; i++) {
        double a = g->crank_deg[i];
        if (!isfinite(a) || a < 0.0 || a > 720.0)
            return rd_error_set(err, RD_EINVAL, "/crank_deg",
                                "@/crank_deg[%d] = %g deg is out of range: "
                                "allowed 0 to 720 deg.",
                                i, a);
        if (i > 0 && !(a > g->crank_deg[i - 1]))
            return rd_error_set(err, RD_EINVAL, "/crank_deg",
                                "@/crank_deg must be strictly increasing: "
                                "[%d] = %g deg follows %g deg.",
                                i, a, g->crank_deg[i - 1]);
    }
    if ((rc = check_table(g->above, g->points, "/above", err)) ||
        (rc = check_table(g->behind, g->points, "/behind", err)) ||
        (rc = check_table(g->below, g->points, "/below", err)))
        return rc;
    if (g->active_area != RD_GAS_AREA_FIXED && g->active_area != RD_GAS_AREA_DYNAMIC &&
        g->active_area != RD_GAS_AREA_LINEAR)
        return rd_error_set(err, RD_EINVAL, "/active_area",
                            "@/active_area = %d is unknown: use fixed, dynamic or "
                            "linear.",
                            g->active_area);
    return RD_OK;
}

static int validate_gas(const rd_gas_params *g, rd_error *err)
{
    if (g->points == 0)
        return RD_OK;
    size_t m = rd_error_enter(err, "/physics");
    rd_error_enter(err, "/gas");
    int rc = gas_checks(g, err);
    rd_error_leave(err, m);
    return rc;
}

/* A given contact stiffness, against the scene (in the contact block): the
 * largest flank pressure P may push the ring in by at most 10 % of the
 * axial clearance (a softer flank lets it sink through: 2000 clearances at
 * k = 1e3 on the thesis scene), and k may be at most 1e3 times the default
 * (stiffer, the error estimate's two runs stop agreeing on the flank
 * changes: 1e4 times). */
static int stiffness_checks(const rd_lift_params *p, const rd_ring_params *ring, rd_error *err)
{
    double k = p->contact_stiffness;
    int rc = rd_error_range(k, 1e3, 1e20, "/stiffness", "Pa/m (or 0 for the default)", err);
    if (rc != RD_OK)
        return rc;
    double lo = rd_lift_flank_pressure_scale(ring, p) /
                (STIFFNESS_PENETRATION_MAX * p->groove.axial_clearance);
    double hi = STIFFNESS_DEFAULT_MAX * rd_lift_contact_stiffness_default(ring, p);
    if (!(k >= lo && k <= hi))
        return rd_error_set(err, RD_EINVAL, "", /* a rule of the scene, not the field */
                            "@/stiffness = %g Pa/m is out of range for this scene: allowed "
                            "%.4g to %.4g Pa/m (or 0 for the default %.4g).  Below, the largest "
                            "flank pressure (%.4g Pa) pushes the ring into the flank by more than "
                            "%g of the axial clearance; above %g times the default the error "
                            "estimate's runs no longer agree on the flank changes.",
                            k, lo, hi, rd_lift_contact_stiffness_default(ring, p),
                            rd_lift_flank_pressure_scale(ring, p), STIFFNESS_PENETRATION_MAX,
                            STIFFNESS_DEFAULT_MAX);
    return RD_OK;
}

/* Tolerances, the step bound and the model, in the numerics block. */
static int numerics_checks(const rd_lift_params *p, double ring_d, int segments, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range(p->rtol, 1e-12, 1e-2, "/rtol", "", err)) ||
        (rc = rd_error_range(p->atol, 1e-16, 1e-5, "/atol", "m", err)))
        return rc;
    if (p->max_steps < 100 || p->max_steps > 1000000000L)
        return rd_error_set(err, RD_EINVAL, "/max_steps",
                            "@/max_steps = %ld is out of range: allowed 100 to 1e9.", p->max_steps);
    if (!rd_lift_model_name(p->model))
        return rd_error_set(err, RD_EINVAL, "/model",
                            "@/model = %d is unknown: use auto, rigid, modal or full.", p->model);
    if (p->model == RD_LIFT_MODEL_RIGID && rd_lift_bore_distorted(p, ring_d))
        return rd_error_set(
            err, RD_EINVAL, "/model",
            "@/model = rigid cannot represent a distorted bore "
            "(/bore/distortion, /bore/diameter, /bore/layers): the contact pressure varies "
            "around the ring; use auto, modal or full.");
    if (p->model == RD_LIFT_MODEL_RIGID && rd_engine_tilted(&p->engine))
        return rd_error_set(err, RD_EINVAL, "/model",
                            "@/model = rigid cannot represent a tilted piston "
                            "(/engine/piston_tilt_deg, /engine/piston_tilt): the flank gap varies "
                            "around the ring; use auto, modal or full.");
    if (p->model == RD_LIFT_MODEL_MODAL && segments > RD_LIFT_MODAL_SEGMENTS_MAX)
        return rd_error_set(err, RD_ELIMIT, "/model",
                            "@/model = modal solves the ring's modes densely and allows "
                            "at most %d segments (/discretization/segments = %d): use fewer "
                            "segments or the full model.",
                            RD_LIFT_MODAL_SEGMENTS_MAX, segments);
    if (p->modes > 6 * segments - 6)
        return rd_error_set(err, RD_EINVAL, "/modes",
                            "@/modes = %d is out of range: a ring of %d segments has "
                            "%d elastic modes.",
                            p->modes, segments, 6 * segments - 6);
    return rd_error_range(p->accuracy_deg, 1e-4, 10.0, "/accuracy_deg", "deg", err);
}

/* The modes' bound and the error estimate's switch, in the numerics block. */
static int numerics_switches(const rd_lift_params *p, rd_error *err)
{
    if (p->modes < 0 || p->modes > RD_LIFT_MODES_MAX)
        return rd_error_set(err, RD_EINVAL, "/modes",
                            "@/modes = %d is out of range: allowed 0 (auto) to %d.", p->modes,
                            RD_LIFT_MODES_MAX);
    if (p->estimate_error != 0 && p->estimate_error != 1)
        return rd_error_set(err, RD_EINVAL, "/error_estimate",
                            "@/error_estimate = %d: use true or false.", p->estimate_error);
    return RD_OK;
}

/* The work bounds of the output's step, in the output block. */
static int output_bounds(const rd_lift_params *p, int segments, rd_error *err)
{
    double samples = ceil(p->engine.cycles * 720.0 / p->step_deg - 1e-9) + 1.0;
    if (samples > RD_LIFT_SAMPLES_MAX)
        return rd_error_set(err, RD_ELIMIT, "/step_deg",
                            "@/step_deg = %g deg over %g cycles gives %.0f output samples; "
                            "at most %d are allowed: use a larger step or fewer cycles.",
                            p->step_deg, p->engine.cycles, samples, RD_LIFT_SAMPLES_MAX);
    if (samples * segments > MEMORY_BOUND)
        return rd_error_set(err, RD_ELIMIT, "/step_deg",
                            "%.0f output samples x %d segments = %.3g per-segment values; at "
                            "most %g are allowed: use a larger @/step_deg, fewer cycles or "
                            "fewer segments.",
                            samples, segments, samples * segments, MEMORY_BOUND);
    return RD_OK;
}

/* Contact stiffness, output sampling, tolerances and the work bounds. */
static int validate_numerics(const rd_lift_params *p, const rd_ring_params *ring, int segments,
                             rd_error *err)
{
    size_t m = rd_error_enter(err, "/contact");
    int rc = p->contact_stiffness != 0.0 ? stiffness_checks(p, ring, err) : RD_OK;
    rd_error_leave(err, m);
    rc = rc ? rc : rd_error_range_in("/output", p->step_deg, 1e-3, 90.0, "/step_deg", "deg", err);
    m = rd_error_enter(err, "/numerics");
    rc = rc ? rc : numerics_checks(p, ring->diameter, segments, err);
    rd_error_leave(err, m);
    rc = rc ? rc
            : rd_error_range_in("/output", p->flank_band, 0.0, RD_LIFT_FLANK_BAND_MAX,
                                "/flank_band", "of the axial clearance", err);
    m = rd_error_enter(err, "/numerics");
    rc = rc ? rc : numerics_switches(p, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/output");
    rc = rc ? rc : output_bounds(p, segments, err);
    rd_error_leave(err, m);
    return rc;
}

/* The ring block's and the discretization's rules of the lift analysis. */
static int validate_ring(const rd_ring_params *ring, int segments, rd_error *err)
{
    size_t m = rd_error_enter(err, "/ring");
    int rc = ring->section != RD_SECTION_RECTANGLE
                 ? rd_error_set(err, RD_EINVAL, "/section",
                                "the lift analysis needs a rectangular ring section (its faces "
                                "seal on the groove flanks).")
                 : RD_OK;
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/discretization");
    if (!rc && (segments < 4 || segments > RD_LIFT_SEGMENTS_MAX))
        rc = rd_error_set(err, segments > RD_LIFT_SEGMENTS_MAX ? RD_ELIMIT : RD_EINVAL, "/segments",
                          "@/segments = %d is out of range for a lift analysis: allowed 4 to %d.",
                          segments, RD_LIFT_SEGMENTS_MAX);
    rd_error_leave(err, m);
    return rc;
}

int rd_lift_validate(const rd_lift_params *p, const rd_ring_params *ring, int segments,
                     rd_error *err)
{
    int rc;
    if ((rc = rd_ring_scene_validate(ring, segments, 0, err)) ||
        (rc = validate_ring(ring, segments, err)))
        return rc;
    size_t m = rd_error_enter(err, "/engine");
    if (!(rc = rd_engine_validate(&p->engine, err)))
        rc = validate_cycles(&p->engine, err);
    rd_error_leave(err, m);
    if (rc || (rc = validate_bore(p, ring->diameter, err)) || (rc = validate_physics(p, err)) ||
        (rc = validate_gas(&p->gas, err)) || (rc = validate_numerics(p, ring, segments, err)))
        return rc;
    return RD_OK;
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
    free(r->bore_pressure);
    free(r->bore_pressure_min);
    free(r->bore_pressure_max);
    free(r->ring_depth);
    free(r->flank);
    free(r->events);
    rd_lift_lube_cleanup(&r->lube);
    memset(r, 0, sizeof *r);
    r->error_estimate = NAN;
    r->event_error_deg = NAN;
}
