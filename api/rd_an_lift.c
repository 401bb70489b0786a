/*
 * rd_an_lift — the lift analysis in the api (the ring's axial motion in its
 * groove over engine cycles, thesis 3.5): scene schema, runner, result
 * object and CSV table (rd_registry.h).
 *
 * Options (struct lift_opts): core's rd_lift_params, plus what only the
 * scene knows: which optional physics it named (gas, squeeze film), the
 * four gas tables, which rd_lift_params.gas borrows once the scene is
 * parsed, and what it shares with the ring pack (struct rd_engine_scene:
 * the tilt tables, the bore, the friction model; rd_registry.h).
 */
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "rd_contact_map.h"
#include "rd_json.h"
#include "rd_lift.h"
#include "rd_lube_json.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_static.h"

struct lift_opts {
    rd_lift_params lift;
    struct rd_engine_scene eng; /* the tilt tables, /bore, the friction model */
    int gas_given, squeeze_given;
    int max_steps;                   /* /numerics/max_steps */
    struct rd_table gas_table[4];    /* crank_deg, above, behind, below */
    struct rd_contact_map_scene map; /* /bore/layers or /bore/points, and the map */
    struct rd_ring_depth ring_z;     /* /bore/ring_z_tdc_m */
    /* core's handle, made by finish (which checks the scene through it) and
     * run by run: the scene is checked once per job */
    rd_lift *handle;
};

#define LO(member) offsetof(struct lift_opts, member)

/* ---- scene ---------------------------------------------------------------- */

static const char *const area_names[] = {"fixed", "dynamic", "linear", NULL}; /* enum rd_gas_area */
static const char *const landing_names[] = {"penalty", "plastic", NULL}; /* enum rd_lift_landing */

static const rd_field tilt_fields[] = {
    RD_TILT_FIELDS(LO),
    {.key = NULL},
};
static const rd_block tilt_block = {
    "PistonTilt",
    "/engine/piston_tilt: the piston's tilt about its pin axis vs crank angle; present = "
    "modelled. Two tables of the same length, a periodic (720 deg) C1 cubic spline through them; "
    "|piston_tilt_deg| + the largest |tilt_deg| at most 2 deg.",
    1, 0, tilt_fields};

static json_t *ring_z_echo(const rd_scene *s)
{
    const struct lift_opts *o = s->opts;
    return o->ring_z.given ? rd_result_real(o->ring_z.z) : json_null();
}

static json_t *layers_echo(const rd_scene *s)
{
    const struct lift_opts *o = s->opts;
    return o->map.layers_given ? rd_bore_layers_json(s, o->map.map) : json_null();
}

static const rd_field points_fields[] = {
    RD_BORE_POINTS_FIELDS(LO),
    {.key = NULL},
};
static const rd_block points_block = {
    "LiftBorePoints",
    "/bore/points (lift): a measured bore (theta, z, dr), fitted per layer of equal z by least "
    "squares up to fit_order, as the contact analysis' /bore/points; the same length for the "
    "three tables.",
    1, 0, points_fields};

static const rd_field bore_fields[] = {
    RD_BORE_FIELDS(LO, "Bore diameter D, m; 0 = the ring's diameter; otherwise within 2 % of it.",
                   "Fourier terms of the bore's out-of-roundness, at most 16. The radial contact "
                   "pressure, hence the friction, then varies around the ring; the ring starts "
                   "from its static equilibrium in this bore, and the scene never runs the rigid "
                   "model."),
    {"layers", RD_F_CUSTOM, LO(map.layers_given), .block = &rd_block_bore_layer, RD_MIN(1),
     RD_MAX(RD_BORE_LAYERS_MAX), .parse = rd_contact_map_parse_layers, .echo = layers_echo,
     .desc = "A bore that changes down its height (a bore card, as the contact analysis'): 1 to "
             "50 {z, diameter, distortion}, z strictly increasing, linear in z between them. The "
             "ring meets the bore at its current depth, ring_z_tdc_m plus the piston's travel "
             "from TDC: the layers must cover the whole stroke. With layers, /bore/distortion is "
             "refused and /bore/diameter is the diameter of layers that give none; the full or "
             "modal ring runs (as on any distorted bore)."},
    {"points", RD_F_OPTBLOCK, LO(map.points_given), .block = &points_block,
     .desc = RD_BORE_POINTS_DESC},
    {"ring_z_tdc_m", RD_F_CUSTOM, LO(ring_z.given), .parse = rd_ring_depth_parse,
     .echo = ring_z_echo, .extra = "{\"type\": \"number\", \"minimum\": 0, \"maximum\": 10}",
     .desc = "With /bore/layers or /bore/points (and only then): the ring's depth below the "
             "top of the bore at TDC, m, on the map's z axis."},
    RD_BORE_ROUGHNESS_FIELD,
    {.key = NULL},
};
static const rd_block bore_block = {
    "LiftBore",
    "/bore (lift): r_b(theta) = D/2 + sum A_k cos(k (theta - phi_k)), as in the contact "
    "analysis. Default: the round bore of the ring's diameter.",
    1, 0, bore_fields};

static const rd_field engine_fields[] = {
    RD_ENGINE_CRANK_FIELDS(LO, lift.engine, "Crank speed, rpm."),
    {"cycles", RD_F_NUMBER, LO(lift.engine.cycles), RD_XMIN(0), RD_MAX(50),
     .desc = "4-stroke cycles (720 deg each) simulated; any real > 0."},
    RD_ENGINE_TILT_FIELDS(
        LO, lift.engine,
        "Constant piston tilt about the pin axis (the axis in the ring plane at 90 deg from the "
        "gap middle), deg, positive raising the groove on the gap's side. A tilted scene never "
        "runs the rigid model (the flank gap varies around the ring).",
        tilt_block),
    {.key = NULL},
};
static const rd_block engine_block = {"Engine", "/engine (lift): piston kinematics.", 1, 0,
                                      engine_fields};

static const rd_field groove_fields[] = {
    {"axial_clearance", RD_F_NUMBER, LO(lift.groove.axial_clearance), RD_MIN(1e-07), RD_MAX(0.005),
     .desc = "Groove height minus ring height, m."},
    {"radial_clearance", RD_F_NUMBER, LO(lift.groove.radial_clearance), RD_MIN(1e-06), RD_MAX(0.01),
     .desc = "Ring inner face to groove back, m."},
    {.key = NULL},
};
static const rd_block groove_block = {"Groove", "/groove (lift).", 1, 0, groove_fields};

static const rd_field friction_fields[] = {
    RD_FRICTION_FIELDS(LO, lift.friction,
                       "coulomb: F = -mu N tanh(u / u_reg). stribeck: thesis (2.9) with the "
                       "Sommerfeld number (1.11). lubricated: the oil film on the running face "
                       "(average Reynolds with Patir-Cheng flow factors, the Reynolds or the "
                       "mass-conserving JFO cavitation condition, flooded or starved) and "
                       "Greenwood-Tripp asperity "
                       "contact; reads oil, asperity, /ring/face and /bore/roughness_rq_m.",
                       "Coulomb coefficient mu (also C_Coulomb of 2.9), -."),
    {"viscosity", RD_F_NUMBER, LO(lift.friction.viscosity), RD_MIN(1e-05), RD_MAX(10),
     .desc = "Stribeck only: oil dynamic viscosity eta, Pa s."},
    {"sommerfeld_transition", RD_F_NUMBER, LO(lift.friction.sommerfeld_transition), RD_MIN(0),
     RD_MAX(1e15), .desc = "Stribeck only: So_lim of (2.9), -."},
    {"hydrodynamic_slope", RD_F_NUMBER, LO(lift.friction.hydrodynamic_slope), RD_MIN(0),
     RD_MAX(1e12), .desc = "Stribeck only: K of (2.9), -."},
    RD_LUBE_FRICTION_FIELDS,
    {.key = NULL},
};
static const rd_block friction_block = {
    "Friction",
    "/physics/friction: axial bore friction on the running face; present = modelled. The echo "
    "gives all five fields.",
    1, 0, friction_fields};

#define GAS_TABLE(key, k, text)                                                                 \
    {                                                                                           \
        key, RD_F_TABLE, LO(gas_table[k]), RD_MIN(2), RD_MAX(RD_LIFT_TABLE_MAX), .required = 1, \
                                                                                 .desc = text   \
    }
static const rd_field gas_fields[] = {
    GAS_TABLE("crank_deg", 0, "Crank angles, deg, strictly increasing within 0..720."),
    GAS_TABLE("above", 1, "Gauge pressure on the top face, Pa, each -1e6 to 1e9."),
    GAS_TABLE("behind", 2, "Gauge pressure on the back (inner) face, Pa, each -1e6 to 1e9."),
    GAS_TABLE("below", 3, "Gauge pressure on the bottom face, Pa, each -1e6 to 1e9."),
    {"active_area", RD_F_CHOICE, LO(lift.gas.active_area), .choices = area_names,
     .desc = "fixed: full faces (thesis). dynamic: a face sealing on a flank sees the mean of "
             "the groove-back pressure and its own side's, weighted by its flank contact. "
             "linear: every face carries the linear fall from the groove-back pressure to its "
             "own side's (the classic ring-pack models'): their mean, and the slope's couple "
             "A b (p_below - p_above) / 12 twisting the ring."},
    {.key = NULL},
};
static const rd_block gas_block = {
    "Gas",
    "/physics/gas: gas pressures vs crank angle; present = modelled. Four tables of the same "
    "length (2 to 100000 points), interpolated linearly and periodic over 720 deg.",
    1, 0, gas_fields};

static const rd_field squeeze_fields[] = {
    {"viscosity", RD_F_NUMBER, LO(lift.squeeze.viscosity), RD_MIN(1e-08), RD_MAX(10),
     .desc = "Dynamic viscosity mu of the oil in the flank gaps, Pa s (from 1e-8: a vanishing film "
             "for comparisons)."},
    {"min_film", RD_F_NUMBER, LO(lift.squeeze.min_film), RD_MIN(1e-09), RD_MAX(1e-04),
     .desc = "Film h_min left at contact (roughness), m: the gap in the law is h_min + h."},
    {.key = NULL},
};
static const rd_block squeeze_block = {
    "SqueezeFilm",
    "/physics/squeeze_film: the landing law, the oil squeeze film between a ring face and the "
    "flank it approaches, p = mu b^2 V / (h_min + h)^3 (Reynolds, parallel plates of width b "
    "closing at V; no pressure while the gap opens); present = modelled.",
    1, 0, squeeze_fields};

static const rd_field physics_fields[] = {
    {"gravity", RD_F_BOOL, LO(lift.gravity), .desc = "Gravity, g = 9.80665 m/s^2 along -z."},
    {"friction", RD_F_OPTBLOCK, LO(eng.friction_given), .block = &friction_block},
    {"gas", RD_F_OPTBLOCK, LO(gas_given), .block = &gas_block},
    {"squeeze_film", RD_F_OPTBLOCK, LO(squeeze_given), .block = &squeeze_block},
    {.key = NULL},
};
static const rd_block physics_block = {
    "Physics",
    "/physics (lift): the forces besides piston inertia. An absent entry means that effect is "
    "not modelled (friction, gas and squeeze_film are switched on by naming their block).",
    1, 0, physics_fields};

/* The echo gives the stiffness used, where the scene's 0 means "default". */
static json_t *echo_stiffness(const rd_scene *s)
{
    const struct lift_opts *o = s->opts;
    double k = o->lift.contact_stiffness;
    return rd_result_real(k > 0 ? k : rd_lift_contact_stiffness_default(&s->ring, &o->lift));
}

static const rd_field contact_fields[] = {
    {"stiffness", RD_F_NUMBER, LO(lift.contact_stiffness), RD_MIN(0.0), RD_MAX(1e20),
     .echo = echo_stiffness,
     .desc = "Penalty stiffness k, Pa/m. 0 = a default from the scene's largest flank load and "
             "the crank speed (echoed as the value used); otherwise 1e3 to 1e20, and for the "
             "scene at least 10 P / c_a (P the largest flank pressure: the ring sinks into the "
             "flank by at most 10 % of the axial clearance) and at most 1e3 times the "
             "default."},
    {"landing", RD_F_CHOICE, LO(lift.landing), .choices = landing_names,
     .desc = "penalty: a landing is integrated through the damped penalty (default). plastic: "
             "the ring's axial (rigid: and tilt) rate towards the flank is arrested when it "
             "reaches it, then the penalty carries the load; fewer steps, flank changes moved "
             "by up to ~0.05 deg on the examples."},
    {.key = NULL},
};
static const rd_block contact_block = {
    "LiftContact", "/contact of a lift scene: the flank, bore and groove-back contacts.", 1, 0,
    contact_fields};

static const rd_field output_fields[] = {
    {"step_deg", RD_F_NUMBER, LO(lift.step_deg), RD_MIN(0.001), RD_MAX(90),
     .desc = "Crank-angle step of the output samples, deg."},
    {"flank_band", RD_F_NUMBER, LO(lift.flank_band), RD_MIN(0), RD_MAX(RD_LIFT_FLANK_BAND_MAX),
     .desc = "Width of the band at each flank, as a fraction of the axial clearance, where flank "
             "changes are dated: a leave where the mean lift moves out of the band, a landing "
             "where it moves in (a bounce that leaves the band is two events). Each event also "
             "keeps touch_deg, where the mean lift itself touched or left the flank. 0: dated at "
             "the touch (a landing) and where the load turns away (a leave, confirmed 1 % of the "
             "clearance off the flank). Default 0.01."},
    {.key = NULL},
};
static const rd_block output_block = {"Output", "/output (lift).", 1, 0, output_fields};

/* enum rd_lift_model_kind */
static const char *const model_names[] = {"full", "rigid", "modal", "auto", NULL};

static const rd_field numerics_fields[] = {
    {"model", RD_F_CHOICE, LO(lift.model), .choices = model_names,
     .desc = "Which equations are integrated: auto (the cheapest model the scene allows and the "
             "accuracy target admits), rigid (the ring as one body: axial lift, twist, radial; "
             "exact for axisymmetric scenes without friction), modal (rigid-body motion, the m "
             "lowest elastic modes and 4 static correction shapes of the segmented ring) or "
             "full (the flexible ring, 6n DOFs)."},
    {"modes", RD_F_INTEGER, LO(lift.modes), RD_MIN(0), RD_MAX(RD_LIFT_MODES_MAX),
     .desc = "Elastic modes of the modal model; 0 = chosen automatically."},
    {"accuracy_deg", RD_F_NUMBER, LO(lift.accuracy_deg), RD_MIN(1e-4), RD_MAX(10.0),
     .desc = "Target accuracy of the flank-change angles, deg (used by auto)."},
    {"rtol", RD_F_NUMBER, LO(lift.rtol), RD_MIN(1e-12), RD_MAX(0.01),
     .desc = "Relative tolerance."},
    {"atol", RD_F_NUMBER, LO(lift.atol), RD_MIN(1e-16), RD_MAX(1e-05),
     .desc = "Absolute tolerance on the translations, m (atol / R on the rotations)."},
    {"max_steps", RD_F_INTEGER, LO(max_steps), RD_MIN(100), RD_MAX(1000000000),
     .desc = "CVODE steps allowed for the whole run (a run that needs more fails with "
             "limit_exceeded)."},
    {"error_estimate", RD_F_BOOL, LO(lift.estimate_error),
     .desc = "Estimate the error by a second run at rtol/10 and atol/10."},
    {"film_step_deg", RD_F_NUMBER, LO(lift.film_step_deg), RD_MIN(0.01),
     RD_MAX(RD_LIFT_FILM_STEP_MAX_DEG),
     .desc = "The lubricated model's oil film: its largest time step, crank deg (default 2; "
             "the steps follow the film's local error, 1e-4 of its thickness)."},
    {.key = NULL},
};
static const rd_block numerics_block = {
    "LiftNumerics", "/numerics of a lift scene: the CVODE integration.", 1, 0, numerics_fields};

static const rd_field scene_fields[] = {
    RD_SCENE_HEAD,
    {"ring", RD_F_BLOCK, 0, .block = &rd_block_ring_face,
     .desc = "The ring; the lift analysis needs a rectangular section (its faces seal on the "
             "groove flanks).",
     .extra = "{\"properties\": {\"section\": {\"enum\": [\"rectangle\"]}}}"},
    {"discretization", RD_F_BLOCK, 0, .block = &rd_block_discretization_lift},
    {"engine", RD_F_BLOCK, 0, .block = &engine_block},
    {"groove", RD_F_BLOCK, 0, .block = &groove_block},
    {"bore", RD_F_BLOCK, 0, .block = &bore_block},
    {"physics", RD_F_BLOCK, 0, .block = &physics_block},
    {"contact", RD_F_BLOCK, 0, .block = &contact_block},
    {"output", RD_F_BLOCK, 0, .block = &output_block},
    {"numerics", RD_F_BLOCK, 0, .block = &numerics_block},
    {.key = NULL},
};
static const rd_block scene_block = {
    "LiftScene",
    "Axial motion (lift) of the flexible ring in its piston groove over engine cycles (thesis "
    "3.5): piston inertia always, plus gravity, bore friction and gas pressures when physics "
    "names them. Reads ring (section must be rectangle), discretization (4..1000 segments, "
    "split ring only), engine, groove, bore (LiftBore), physics, contact (LiftContact), output and "
    "numerics (LiftNumerics). Output size: cycles * 720 / step_deg + 1 samples, at most 200000, "
    "and "
    "samples x segments at most 2e7 (limit_exceeded at /output/step_deg otherwise).",
    0, 0, scene_fields};

static void defaults(struct rd_scene *s)
{
    struct lift_opts *o = s->opts;
    rd_lift_params_default(&o->lift);
    o->max_steps = (int)o->lift.max_steps;
    s->lube.bore_rq = o->lift.bore.roughness_rq;
    s->lube.lube = o->lift.friction.lube;
    s->face = o->lift.face;
}

static void cleanup(void *opts)
{
    struct lift_opts *o = opts;
    for (int k = 0; k < 4; k++)
        free(o->gas_table[k].v);
    rd_engine_scene_cleanup(&o->eng);
    rd_contact_map_cleanup(&o->map);
    rd_lift_free(o->handle);
}

/* The gas tables: all four, of the same length; rd_lift_params borrows them. */
static int gas_finish(struct lift_opts *o, rd_error *err)
{
    for (int k = 0; k < 4; k++) {
        char path[64];
        snprintf(path, sizeof path, "/physics/gas/%s", gas_fields[k].key);
        if (!o->gas_table[k].v)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s is missing: a gas block needs crank_deg, above, behind "
                                "and below, all of the same length (use zeros for a face "
                                "without pressure).",
                                path);
        if (o->gas_table[k].n != o->gas_table[0].n)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s has %d values but /physics/gas/crank_deg has %d; all "
                                "four tables must have the same length.",
                                path, o->gas_table[k].n, o->gas_table[0].n);
    }
    o->lift.gas.points = o->gas_table[0].n;
    o->lift.gas.crank_deg = o->gas_table[0].v;
    o->lift.gas.above = o->gas_table[1].v;
    o->lift.gas.behind = o->gas_table[2].v;
    o->lift.gas.below = o->gas_table[3].v;
    return RD_OK;
}

/* The lubricated model's inputs: the face, the liner's roughness and the
 * temperature table (borrowed by rd_lift_params); each refused by name
 * with another friction model. */
static int lube_finish(struct rd_scene *s, struct lift_opts *o, rd_error *err)
{
    rd_lift_params *l = &o->lift;
    int lub = l->friction.model == RD_FRICTION_LUBRICATED;
    if (s->face_given && !lub) { /* its ranges first, then that it is not read */
        size_t m = rd_error_enter(err, "/ring/face");
        int rc = rd_face_validate(&s->face, err);
        rd_error_leave(err, m);
        rc = rc ? rc : rd_lube_validate(&l->friction.lube, RD_LINER_RQ_DEFAULT, err);
        if (rc)
            return rc;
    }
    int rc = rd_scene_face_finish(s, lub, err);
    if (rc)
        return rc;
    l->face = s->face;
    if (!lub && l->film_step_deg != RD_LIFT_FILM_STEP_DEG)
        return rd_error_set(err, RD_EINVAL, "/numerics/film_step_deg",
                            "/numerics/film_step_deg is read by the lubricated friction model "
                            "only.");
    rc = rd_scene_lube_finish(s, lub, &l->friction.lube, &l->bore.roughness_rq, err);
    return rc ? rc : rd_face_unread(&l->face, "/ring", err);
}

/* /bore/layers or /bore/points and /bore/ring_z_tdc_m (rd_ring_depth_finish); core checks
 * the map against the stroke. */
static int map_finish(const rd_scene *s, struct lift_opts *o, rd_error *err)
{
    rd_lift_params *l = &o->lift;
    double D = l->bore.diameter > 0.0 ? l->bore.diameter : s->ring.diameter;
    l->ring_z_tdc = o->ring_z.z;
    return rd_ring_depth_finish(&o->map, &o->ring_z, s->ring.diameter, D, "the ring's",
                                &l->bore_map, err);
}

/* The optional physics the scene named, the gas tables, the engine's tilt,
 * the bore and the friction model, then core's checks. */
static int finish(struct rd_scene *s, rd_error *err)
{
    struct lift_opts *o = s->opts;
    rd_lift_params *l = &o->lift;
    if (s->closed)
        return rd_error_set(err, RD_EINVAL, "/discretization/closed",
                            "/discretization/closed = true joins the gap, but the lift analysis "
                            "models the split ring in its groove: use closed = false.");
    l->squeeze.on = o->squeeze_given;
    l->max_steps = o->max_steps;
    l->gas.points = 0;
    if (o->gas_given) {
        int rc = gas_finish(o, err);
        if (rc != RD_OK)
            return rc;
    }
    rd_lift_params d;
    rd_lift_params_default(&d);
    int rc = rd_engine_scene_finish(&o->eng, &l->engine, &l->bore, &l->friction, err);
    if (rc == RD_OK)
        rc = rd_friction_unread(&l->friction, &d.friction, err);
    if (rc == RD_OK)
        rc = map_finish(s, o, err);
    if (rc == RD_OK)
        rc = lube_finish(s, o, err);
    /* core's checks, and the handle run will run (it borrows the tables above) */
    return rc != RD_OK ? rc : rd_lift_create(&s->ring, s->segments, l, &o->handle, err);
}

/* ---- result --------------------------------------------------------------- */

static const char *const flank_names[] = {"lower", "upper", "free"};
static const char *const event_names[] = {"leave_lower", "reach_upper", "leave_upper",
                                          "reach_lower"};

/* lift_segments (samples x n), flank (per sample), events. */
static int lift_series(const rd_lift_result *res, json_t **segs, json_t **flank, json_t **events)
{
    int N = res->samples, n = res->segments, bad = 0;
    *segs = json_array();
    *flank = json_array();
    *events = json_array();
    bad |= !*segs || !*flank || !*events;
    for (int k = 0; !bad && k < N; k++) {
        int f = res->flank[k];
        bad |= json_array_append_new(
            *segs, rd_result_reals(res->lift_segments + (size_t)k * n, n, 1, 1.0));
        bad |=
            json_array_append_new(*flank, json_string(f >= 0 && f < 3 ? flank_names[f] : "free"));
    }
    for (int k = 0; !bad && k < res->n_events; k++) {
        int e = res->events[k].kind;
        bad |= json_array_append_new(
            *events,
            json_pack("{s:o, s:s, s:o}", "crank_deg", rd_result_real(res->events[k].crank_deg),
                      "event", e >= 0 && e < 4 ? event_names[e] : "unknown", "touch_deg",
                      rd_result_real(res->events[k].touch_deg)));
    }
    return bad ? -1 : 0;
}

/* numerics.error_method: what the estimate measures, and what it does not
 * (docs/lift.md, **Segment count**: on friction scenes the segment count's
 * error was 5-330x the rtol/10 estimate; the rigid ring is picked by auto
 * only where it matches the flexible ring, 0.027 deg at most measured). */
#define METHOD_TIME                                                                             \
    "second run at rtol/10 and atol/10: largest lift difference over the axial clearance, and " \
    "the largest shift of a matched flank change (event_error_time_deg)"
#define METHOD_RIGID                                                                          \
    "; the time integration's error only (the rigid ring's own difference from the flexible " \
    "ring is not in it: numerics.model.why says what the run-time check found)"
#define METHOD_RIGID_CHECKED                                                                   \
    "; plus the rigid ring's largest difference from the full ring in auto's run-time check "  \
    "(event_error_model_deg) and, from the check repeated at n/2 segments, the full ring's "   \
    "segment-count share (event_error_segments_deg; 12 segments or more); the three add. Not " \
    "covered: a flank change of the full ring outside the check's windows"
#define METHOD_FLEX                                                                            \
    "; plus a run at n/2 segments at the scene's tolerances, its difference / (2^1.5 - 1): "   \
    "the segment count's error if the answer converges as n^-1.5 (event_error_segments_deg); " \
    "the two add. Not covered: the model's own assumptions (MODEL.md)"
#define METHOD_FLEX_NO_HALF                                                                     \
    "; the time integration's error only: the segment count's is not in it (below 12 segments " \
    "there is no n/2 check run; compare a run at twice the segments)"

static json_t *lift_numerics(const rd_scene *scene, const rd_lift_result *res, double wall_s)
{
    const struct lift_opts *o = scene->opts;
    int estimated = isfinite(res->error_estimate);
    return json_pack(
        "{s:i, s:i, s:o, s:o, s:s, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:o, s:o, s:o, s:o, "
        "s:o, s:o, s:o, s:o, s:o, s:o}",
        "segments", res->segments, "dof", res->dof, "model",
        json_pack("{s:s, s:i, s:i, s:s}", "name", rd_lift_model_name(res->model), "dof", res->dof,
                  "modes", res->modes, "why", res->why),
        "wall_s", rd_result_real(wall_s), "solver",
        res->model == RD_LIFT_MODEL_RIGID
            ? "TR-BDF2 (L-stable, second order, embedded error estimate; core/lift/"
              "rd_lift_small.c) with a 3 x 3 second-order Newton solve (the rigid ring's 6 "
              "states), root finding for the flank changes"
        : res->model == RD_LIFT_MODEL_MODAL
            ? "SUNDIALS CVODE, BDF with a dense Newton linear solver (2 x dof modal "
              "states), root finding for the flank changes"
            : "SUNDIALS CVODE, BDF with a block-tridiagonal Newton linear solver (second-order "
              "form, 6 n unknowns), root finding for the flank changes",
        "steps", (json_int_t)res->steps, "rhs_evals", (json_int_t)res->rhs_evals, "jac_evals",
        (json_int_t)res->jac_evals, "linear_setups", (json_int_t)res->lin_setups,
        "nonlinear_iterations", (json_int_t)res->nonlin_iters, "nonlinear_failures",
        (json_int_t)res->nonlin_fails, "error_test_fails", (json_int_t)res->err_test_fails,
        "root_evals", (json_int_t)res->root_evals, "rtol", rd_result_real(o->lift.rtol), "atol",
        rd_result_real(o->lift.atol), "error_estimate", rd_result_real(res->error_estimate),
        "event_error_deg", rd_result_real(res->event_error_deg), "error_method",
        estimated
            ? json_string(res->model == RD_LIFT_MODEL_RIGID && isfinite(res->event_error_model_deg)
                              ? METHOD_TIME METHOD_RIGID_CHECKED
                          : res->model == RD_LIFT_MODEL_RIGID ? METHOD_TIME METHOD_RIGID
                          : res->segments_half                ? METHOD_TIME METHOD_FLEX
                                                              : METHOD_TIME METHOD_FLEX_NO_HALF)
            : json_null(),
        "flank_band", rd_result_real(o->lift.flank_band), "event_error_time_deg",
        rd_result_real(res->event_error_time_deg), "event_error_segments_deg",
        rd_result_real(res->event_error_segments_deg), "event_error_model_deg",
        rd_result_real(res->event_error_model_deg), "segments_check",
        res->segments_half ? json_integer(res->segments_half) : json_null());
}

/* The warnings of the run: a partial result ({code: "partial", path, message})
 * and flank changes not converged in the segment count; in the
 * form of rd_warnings' (which appends its own after it); [] otherwise. */
static json_t *lift_warnings(const rd_lift_result *res)
{
    json_t *w = json_array();
    if (res->partial) {
        const char *path = res->partial_stop == RD_ELIMIT ? "/numerics/max_steps" : "";
        json_array_append_new(w, json_pack("{s:s, s:s, s:s}", "code", "partial", "path", path,
                                           "message", res->warning));
    }
    if (res->accuracy_warning[0])
        json_array_append_new(w, json_pack("{s:s, s:s, s:s}", "code", "segments_not_converged",
                                           "path", "/discretization/segments", "message",
                                           res->accuracy_warning));
    return w;
}

/* {"analysis", "scene", "crank_deg", "lift", "lift_min", "lift_max",
 *  "lift_segments", "twist_rad", "friction_force", "bore_pressure_min_pa",
 *  "bore_pressure_max_pa", "bore_pressure_angle_deg", "bore_pressure_pa", ("ring_depth_m"
 *  with a bore map), "flank", "events",
 *  "numerics", "partial", "crank_deg_reached", "warnings"}: a run stopped by
 *  /numerics/max_steps after whole cycles succeeds with those cycles,
 *  partial = true, the angle reached and a warning (docs/lift.md, partial
 *  results; the page lists result.warnings); a run stopped by a cancel or
 *  the time limit returns the same beside its error (rd_api.h). */
static json_t *lift_result(const rd_scene *scene, const rd_lift_result *res, double wall_s)
{
    int N = res->samples;
    json_t *segs, *flank, *events;
    if (lift_series(res, &segs, &flank, &events) != 0) {
        json_decref(segs);
        json_decref(flank);
        json_decref(events);
        return NULL;
    }
    json_t *out = json_pack(
        "{s:s, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:b, s:o, "
        "s:o}",
        "analysis", rd_scene_analysis(scene), "scene", rd_scene_echo(scene), "crank_deg",
        rd_result_reals(res->crank_deg, N, 1, 1.0), "lift", rd_result_reals(res->lift, N, 1, 1.0),
        "lift_min", rd_result_reals(res->lift_min, N, 1, 1.0), "lift_max",
        rd_result_reals(res->lift_max, N, 1, 1.0), "lift_segments", segs, "twist_rad",
        rd_result_reals(res->twist, N, 1, 1.0), "friction_force",
        rd_result_reals(res->friction_force, N, 1, 1.0), "bore_pressure_min_pa",
        rd_result_reals(res->bore_pressure_min, N, 1, 1.0), "bore_pressure_max_pa",
        rd_result_reals(res->bore_pressure_max, N, 1, 1.0), "flank", flank, "events", events,
        "numerics", lift_numerics(scene, res, wall_s), "partial", res->partial, "crank_deg_reached",
        rd_result_real(res->crank_deg_reached), "warnings", lift_warnings(res));
    int n = res->segments;
    double R = 0.5 * (scene->ring.diameter - scene->ring.radial_width);
    double gap = scene->ring.closed_gap / R * 57.29577951308232, centre[RD_LIFT_SEGMENTS_MAX];
    for (int i = 0; i < n && i < RD_LIFT_SEGMENTS_MAX; i++)
        centre[i] = 0.5 * gap + (i + 0.5) * (360.0 - gap) / n;
    json_t *bins = json_array();
    for (int k = 0; bins && k < N; k++)
        if (json_array_append_new(bins,
                                  rd_result_reals(res->bore_pressure + (size_t)k * n, n, 1, 1.0))) {
            json_decref(bins);
            bins = NULL;
        }
    int bad =
        !out || !bins || n > RD_LIFT_SEGMENTS_MAX ||
        json_object_set_new(out, "bore_pressure_angle_deg", rd_result_reals(centre, n, 1, 1.0)) ||
        json_object_set_new(out, "bore_pressure_pa", bins);
    if (!out)
        json_decref(bins);
    if (!bad && res->ring_depth)
        bad = json_object_set_new(out, "ring_depth_m", rd_result_reals(res->ring_depth, N, 1, 1.0));
    const struct lift_opts *o = scene->opts;
    if (!bad && o->map.points_given)
        bad = json_object_set_new(out, "bore_fit", rd_bore_fit_json(scene, &o->map));
    if (bad) {
        json_decref(out);
        return NULL;
    }
    return out;
}

/* The lubrication block's method (rd_result_lube): one film in a round
 * bore, a film per segment load in a distorted one. */
#define LUBE_FILM_ONE                                                                       \
    "one film for the whole running face (a rigid profile on a round bore), solved before " \
    "the ring's motion over the run plus one cycle of warm-up: "
#define LUBE_FILM_SEGMENTS                                                                      \
    "a film per segment (a rigid profile): each segment presses on the liner with its static "  \
    "contact load in the distorted bore, the contact analysis' exact contact of the same ring " \
    "(film_load_n_per_m), plus the gas behind it; up to 5 distinct loads a film each, more "    \
    "interpolated in log load between films at 3 to 17 loads (film_interpolation_error); "      \
    "the films are solved before the ring's motion over the run plus one cycle of warm-up: "
#define LUBE_FILM_MAP                                                                            \
    "a film per segment (a rigid profile) along the bore map: each segment presses on the "      \
    "liner with its static contact load, the contact analysis' exact contact of the same ring "  \
    "in each layer the ring passes (film_load_n_per_m over them all), linear in depth between "  \
    "them as the bore is, at the ring's depth at each instant, plus the gas behind it; up to 5 " \
    "distinct load histories a film each under its own, more interpolated in log load between "  \
    "films at 3 to 17 constant loads at each instant (quasi-static in the load: the two "        \
    "segments whose loads swing most are solved under their own histories, and "                 \
    "film_interpolation_error is the larger of their miss and the nodes'); the films are "       \
    "solved before the ring's motion over the run plus one cycle of warm-up: "
#define LUBE_METHOD_REST                                                                       \
    "the average Reynolds equation "                                                           \
    "across the face (Patir-Cheng flow factors, gamma = 1; the cavitation condition and the "  \
    "oil supply of physics.friction; 41 points) with the squeeze term, Greenwood-Tripp "       \
    "asperity contact, and the radial balance elastic line load + gas behind = film + "        \
    "asperity load, by variable-step BDF2 (local error 1e-4 of the film, steps at most "       \
    "film_step_deg). Friction at the liner's speed past the "                                  \
    "piston. film_error and friction_work_error (with numerics.error_estimate): the film "     \
    "against the same film on a grid twice as fine (81 points, half the steps, a quarter of "  \
    "the local error): within x0.45-1.24 (film) and x0.35-0.90 (work) of the error against a " \
    "grid 8 times finer on an 18-scene battery. Not covered: the model (Patir-Cheng "          \
    "shear-stress factors, oil passed on from other rings (supply is one film for the run), "  \
    "the ring's radial motion in the lift model (its bore contact is the penalty's; in a "     \
    "distorted bore the films' loads are the ring's static ones)."

#define LUBE_FILM_TILT                                                                           \
    "On a tilting piston (a tilt table) the groove slides each segment past the liner at "       \
    "beta' x besides the piston's speed, x its arm about the pin axis (R cos theta, theta from " \
    "the gap middle): each distinct arm and load its own film at that speed. "

#define LUBE_FILM_TILT_ROUND                                                                    \
    "In the round bore every segment presses with 2 F_t / D plus the gas behind it; the films " \
    "are solved before the ring's motion over the run plus one cycle of warm-up: "

static const char *lube_method(const rd_lift_lube *lb)
{
    if (lb->tilt_films && lb->load_depths <= 1 && lb->load_min == lb->load_max)
        return LUBE_FILM_TILT LUBE_FILM_TILT_ROUND LUBE_METHOD_REST;
    if (lb->tilt_films)
        return lb->load_depths > 1 ? LUBE_FILM_TILT LUBE_FILM_MAP LUBE_METHOD_REST
                                   : LUBE_FILM_TILT LUBE_FILM_SEGMENTS LUBE_METHOD_REST;
    if (lb->load_depths > 1)
        return LUBE_FILM_MAP LUBE_METHOD_REST;
    return lb->films > 1 ? LUBE_FILM_SEGMENTS LUBE_METHOD_REST : LUBE_FILM_ONE LUBE_METHOD_REST;
}

static int run(const rd_scene *s, const rd_monitor *mon, json_t **out, rd_error *err)
{
    const struct lift_opts *o = s->opts;
    rd_lift_result res;
    double t0 = rd_clock_s();
    int rc = rd_lift_run(o->handle, mon, &res, err);
    if (rc == RD_OK || res.partial) { /* a stopped run's whole cycles come with its error */
        *out = lift_result(s, &res, rd_clock_s() - t0);
        if (*out && res.lube.on &&
            json_object_set_new(*out, "lubrication",
                                rd_result_lube(&res.lube, res.samples, lube_method(&res.lube))) !=
                0) {
            json_decref(*out);
            *out = NULL;
        }
    }
    rd_lift_result_cleanup(&res);
    return rc;
}

/* The samples, then the band that dates the flank changes and the clearance
 * it is a fraction of, the same in every row: flank is lower where lift_m is
 * below flank_band * axial_clearance_m (1 % with flank_band 0), upper within
 * that of the clearance. */
static const rd_csv_column csv_columns[] = {
    {"crank_deg", "crank_deg", 0},
    {"lift_m", "lift", 0},
    {"lift_min_m", "lift_min", 0},
    {"lift_max_m", "lift_max", 0},
    {"twist_rad", "twist_rad", 0},
    {"friction_force_n", "friction_force", 0},
    {"bore_pressure_min_pa", "bore_pressure_min_pa", RD_CSV_OPTIONAL},
    {"bore_pressure_max_pa", "bore_pressure_max_pa", RD_CSV_OPTIONAL},
    {"ring_depth_m", "ring_depth_m", RD_CSV_OPTIONAL},
    {"flank", "flank", 1},
    {"flank_band", "/numerics/flank_band", 0},
    {"axial_clearance_m", "/scene/groove/axial_clearance", 0},
    {"min_film_m", "lubrication.min_film_m", 0},
    {"hydrodynamic_friction_n", "lubrication.hydrodynamic_friction_n", 0},
    {"asperity_friction_n", "lubrication.asperity_friction_n", 0},
    {"friction_power_w", "lubrication.friction_power_w", 0},
    {"regime", "lubrication.regime", 1},
    {NULL, NULL, 0},
};
static const rd_csv_table csv = {NULL, NULL, csv_columns};

static const char *const result_keys[] = {"analysis",
                                          "scene",
                                          "crank_deg",
                                          "lift",
                                          "lift_min",
                                          "lift_max",
                                          "lift_segments",
                                          "twist_rad",
                                          "friction_force",
                                          "bore_pressure_min_pa",
                                          "bore_pressure_max_pa",
                                          "bore_pressure_angle_deg",
                                          "bore_pressure_pa",
                                          "ring_depth_m",
                                          "bore_fit",
                                          "flank",
                                          "events",
                                          "numerics",
                                          "warnings",
                                          "lubrication",
                                          "partial",
                                          "crank_deg_reached",
                                          NULL};

const rd_analysis_def rd_an_lift = {
    .name = "lift",
    .scene = &scene_block,
    .opts_size = sizeof(struct lift_opts),
    .defaults = defaults,
    .finish = finish,
    .cleanup = cleanup,
    .run = run,
    .csv = &csv,
    .page = "lift.js",
    .result_keys = result_keys,
};
