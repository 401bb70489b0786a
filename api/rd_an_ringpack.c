/*
 * rd_an_ringpack — the ring pack analysis in the api (issue 15: gas
 * pressures between the rings, their lifts and the blow-by from one
 * cylinder pressure; core/rd_ringpack.h): scene schema, runner, result
 * object and CSV table (rd_registry.h).  Absolute pressures throughout
 * (the lift analysis' gas tables are gauge).
 *
 * Options (struct pack_opts): core's rd_ringpack_params plus what only the
 * scene knows, and what it shares with lift (struct rd_engine_scene: the
 * tilt tables, the bore, the friction model; rd_registry.h).  `rings` is an array of items whose blocks nest the shared
 * ring block; each item is parsed (and echoed) through a temporary scene
 * whose `ring` is the item's ring and whose opts are a pack_opts holding
 * the item in `proto` — so `proto` must stay the first member: the item
 * blocks' offsets point there, and the OpenAPI defaults are read from the
 * defaults-filled scene's proto.
 */
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_contact_map.h"
#include "rd_json.h"
#include "rd_registry.h"
#include "rd_ringpack.h"
#include "rd_ringpack_json.h"
#include "rd_scene.h"
#include "rd_static.h"

struct pack_opts {
    rd_ringpack_ring proto; /* first: one ring item while parsing or echoing it */
    rd_ringpack_params pack;
    struct rd_engine_scene eng;          /* the tilt tables, /bore, the friction model */
    int synthetic_given, synthetic_kind; /* kind: index into synthetic_names */
    int max_steps;
    double cycles;            /* /engine/cycles as given: 0 = "periodic" */
    struct rd_table table[2]; /* crank_deg, pressure_pa */
    /* each ring's /rings/i/ring/face: given, and its table (owned) */
    int face_given[RD_RINGPACK_RINGS_MAX], face_table_given[RD_RINGPACK_RINGS_MAX];
    struct rd_table face_table[RD_RINGPACK_RINGS_MAX][2];
    struct rd_contact_map_scene map; /* /bore/layers or /bore/points, and the map */
    struct rd_ring_depth ring_z;     /* /bore/ring_z_tdc_m: the top ring's */
    /* core's handle, made by finish (which checks the scene through it) and
     * run by run: the scene is checked once per job */
    rd_ringpack *handle;
};

#define PO(member) offsetof(struct pack_opts, member)

/* ---- scene ---------------------------------------------------------------- */

static const char *const pin_names[] = {"none", "lower", "upper", "middle",
                                        NULL};                        /* enum rd_ringpack_pin */
static const char *const kind_names[] = {"compression", "oil", NULL}; /* enum rd_ringpack_kind */
static const char *const synthetic_names[] = {"fired", "motored", NULL};
/* enum rd_lift_model_kind order, then RD_RINGPACK_AXIAL */
static const char *const model_names[] = {"full", "rigid", "modal", "auto", "axial", NULL};
#define MODEL_DESC                                                                                 \
    "axial: lift only, hard flank stops (the pack's own ring); rigid: the lift analysis' rigid "   \
    "ring (lift, twist, radial motion); full: its flexible ring of `segments` segments; modal: "   \
    "its modal reduction (`modes`); auto: full with a distorted bore or a piston tilt, else "      \
    "rigid with friction or dynamic active areas, else axial (README \"Ring pack\"); axial and "   \
    "rigid are refused where the scene needs a flexible ring. A pinned ring is held on its flank " \
    "(no model)."

/* The ranges the pack's solver was found to converge on (README "Limits"):
 * rtol up to 1e-5 (at 3e-5 the 1 rpm scene fails, at 1e-3..1e-2 pressures go
 * negative); with friction, rtol up to 1e-6 and at least 300 rpm (below,
 * its regularization speed, 1e-3 x the mean piston speed, makes the
 * friction force too stiff: the axial ring fails at 30 rpm with mu = 10, at
 * 1 rpm already with mu = 0.05; three of the lift's rigid rings, auto's
 * choice with friction, exceed the default max_steps at 100 rpm with mu = 1
 * and converge at 300 rpm with mu = 10 in 28 s, Release). */
#define RTOL_MAX          1e-5
#define FRICTION_RTOL_MAX 1e-6
#define FRICTION_RPM_MIN  300.0

static const rd_field tilt_fields[] = {
    RD_TILT_FIELDS(PO),
    {.key = NULL},
};
static const rd_block tilt_block = {
    "PackPistonTilt",
    "/engine/piston_tilt (ringpack): the piston's tilt vs crank angle, as in lift (a periodic C1 "
    "cubic spline; |piston_tilt_deg| + the largest |tilt_deg| at most 2 deg); present = "
    "modelled.",
    1, 0, tilt_fields};

static json_t *layers_echo(const rd_scene *s)
{
    const struct pack_opts *o = s->opts;
    return o->map.layers_given ? rd_bore_layers_json(s, o->map.map) : json_null();
}

static json_t *ring_z_echo(const rd_scene *s)
{
    const struct pack_opts *o = s->opts;
    return o->ring_z.given ? rd_result_real(o->ring_z.z) : json_null();
}

static const rd_field points_fields[] = {
    RD_BORE_POINTS_FIELDS(PO),
    {.key = NULL},
};
static const rd_block points_block = {
    "PackBorePoints",
    "/bore/points (ringpack): a measured bore (theta, z, dr; theta from the bore's angle 0), "
    "fitted per layer of equal z by least squares up to fit_order, as the contact analysis' "
    "/bore/points; the same length for the three tables.",
    1, 0, points_fields};

static const rd_field bore_fields[] = {
    RD_BORE_FIELDS(PO,
                   "Bore diameter D, m; 0 = the rings' diameter; otherwise within 2 % of it (the "
                   "lift-model rings run in it; the network's areas and volumes keep the rings' "
                   "diameter).",
                   "Fourier terms of the bore's out-of-roundness, at most 16, phases from the "
                   "bore's angle 0 (ring i sees phi_k - gap_angle_deg). Every free ring then needs "
                   "a flexible model (auto: full; axial and rigid are refused) and starts from its "
                   "static equilibrium in this bore, as in lift."),
    {"layers", RD_F_CUSTOM, PO(map.layers_given), .block = &rd_block_bore_layer, RD_MIN(1),
     RD_MAX(RD_BORE_LAYERS_MAX), .parse = rd_contact_map_parse_layers, .echo = layers_echo,
     .desc = "A bore that changes down its height (a bore card, as lift's): 1 to 50 {z, "
             "diameter, distortion}, z strictly increasing, linear in z between them, phases "
             "from the bore's angle 0 (ring i sees phi_k - gap_angle_deg). Each moving ring "
             "meets the bore at its own depth: ring_z_tdc_m plus the rings and lands above it "
             "plus the piston's travel from TDC; the layers must cover every moving ring's whole "
             "travel. With layers, /bore/distortion is refused and /bore/diameter is the "
             "diameter of layers that give none; as on any distorted bore each moving ring runs "
             "a flexible model (auto: full)."},
    {"points", RD_F_OPTBLOCK, PO(map.points_given), .block = &points_block,
     .desc = RD_BORE_POINTS_DESC},
    {"ring_z_tdc_m", RD_F_CUSTOM, PO(ring_z.given), .parse = rd_ring_depth_parse,
     .echo = ring_z_echo, .extra = "{\"type\": \"number\", \"minimum\": 0, \"maximum\": 10}",
     .desc = "With /bore/layers or /bore/points (and only then): the top ring's depth below "
             "the top of the bore at TDC, m, on the map's z axis (the point of the ring lift's "
             "ring_z_tdc_m names); ring i sits lower by the axial heights of the rings above it "
             "and the heights of the lands between them."},
    RD_BORE_ROUGHNESS_FIELD,
    {.key = NULL},
};
static const rd_block bore_block = {
    "PackBore",
    "/bore (ringpack): the bore all rings run in, r_b(theta) = D/2 + sum A_k cos(k (theta - "
    "phi_k)), as in lift. Default: the round bore of the rings' diameter.",
    1, 0, bore_fields};

static const rd_field engine_fields[] = {
    RD_ENGINE_CRANK_FIELDS(PO, pack.engine,
                           "Crank speed, rpm; at least 300 with physics.friction."),
    {"cycles", RD_F_NUMBER, PO(cycles), RD_MIN(2), RD_MAX(RD_RINGPACK_CYCLES_MAX),
     .word = "periodic",
     .desc = "Whole 4-stroke cycles simulated from rest (all volumes at the crankcase "
             "pressure); the last is reported and compared with the one before "
             "(periodicity). \"periodic\": cycles until the last one's change against the one "
             "before is below /numerics/periodic_tolerance (at least 2, at most 50); the result "
             "says how many ran (numerics.cycles) and whether it settled (periodic_reached)."},
    RD_ENGINE_TILT_FIELDS(
        PO, pack.engine,
        "Constant piston tilt about the pin axis (in the ring plane, 90 deg from the bore's angle "
        "0), deg, positive raising the groove at angle 0. Every free ring then needs a flexible "
        "model (auto: full; axial and rigid are refused) and its gap at gap_angle_deg 0 or 180 "
        "(the lift models tilt about the axis 90 deg from the gap).",
        tilt_block),
    {.key = NULL},
};
static const rd_block engine_block = {"PackEngine", "/engine (ringpack): piston kinematics.", 1, 0,
                                      engine_fields};

static const rd_field groove_fields[] = {
    {"axial_clearance", RD_F_NUMBER, PO(proto.groove.axial_clearance), RD_MIN(1e-07), RD_MAX(0.005),
     .desc = "Groove height minus ring height, m (> 0: a ring as tall as its groove or taller "
             "is refused), smaller than the ring's height."},
    {"radial_clearance", RD_F_NUMBER, PO(proto.groove.radial_clearance), RD_MIN(1e-06),
     RD_MAX(0.01), .desc = "Ring inner face to groove back, m (sizes the groove's gas volume)."},
    {.key = NULL},
};
static const rd_block groove_block = {"PackGroove", "The ring's groove.", 1, 0, groove_fields};

static const rd_field land_fields[] = {
    {"height", RD_F_NUMBER, PO(proto.land_height), RD_MIN(1e-05), RD_MAX(0.1),
     .desc = "Height of the piston land above the ring, m (the top land for the first ring)."},
    {"radial_clearance", RD_F_NUMBER, PO(proto.land_clearance), RD_MIN(1e-07),
     .desc = "Piston-to-liner radial clearance of that land, m, up to a quarter of the bore; "
             "sets its volume pi h c (d - c) and the end gap's flow area (closed gap x c)."},
    {.key = NULL},
};
static const rd_block land_block = {"PackLand", "The land (crevice) above the ring.", 1, 0,
                                    land_fields};

static const rd_field item_fields[] = {
    {"ring", RD_F_BLOCK, 0, .block = &rd_block_ring_face,
     .desc = "The ring block: section (rectangle), closed gap (its end gap in the bore), density, "
             "and its running face (read by the lubricated friction model: each ring its own). "
             "All rings share the bore: every diameter equals the first ring's."},
    {"groove", RD_F_BLOCK, 0, .block = &groove_block},
    {"land", RD_F_BLOCK, 0, .block = &land_block},
    {"gap_angle_deg", RD_F_NUMBER, PO(proto.gap_angle_deg), RD_MIN(-360), RD_MAX(360),
     .desc = "Where the end gap's middle sits around the bore, deg from its angle 0: turns "
             "/bore/distortion into the ring's frame; with a piston tilt 0 or 180 (mod 360). "
             "Otherwise recorded only (a round bore's loads are uniform around it)."},
    {"discharge_coefficient", RD_F_NUMBER, PO(proto.discharge_coefficient), RD_MIN(0), RD_MAX(1),
     .desc = "C_d of the ring's passages (end gap, flanks; the first ring's also for "
             "the top-land entry), -."},
    {"pinned", RD_F_CHOICE, PO(proto.pinned), .choices = pin_names, .nullable = 1,
     .desc = "lower / upper: the ring stays on that flank; middle: held at half its axial "
             "clearance (both flank passages open: the limit of a fluttering ring); none (or "
             "null): it moves (an oil ring's default: lower)."},
    /* this ring's model (rd_ringpack_lift.c) */
    {"model", RD_F_CHOICE, PO(proto.model), .choices = model_names,
     .desc = "This ring's model; auto: /numerics/model's. " MODEL_DESC},
    {"segments", RD_F_INTEGER, PO(proto.segments), RD_MIN(4), RD_MAX(RD_RINGPACK_SEGMENTS_MAX),
     .desc = "Segments n of the ring's full and modal models (and of the rigid model's geometry)."},
    {"modes", RD_F_INTEGER, PO(proto.modes), RD_MIN(0), RD_MAX(RD_LIFT_MODES_MAX),
     .desc = "Elastic modes of the modal model, at most 6 n - 6; 0 = 12 (or 6 n - 6)."},
    {"kind", RD_F_CHOICE, PO(proto.kind), .choices = kind_names,
     .desc = "compression: end gap and flank passages. oil: the oil-control ring, the last ring "
             "only: its gas leak (gap, rails and drain holes together) is one effective area "
             "leak_area_m2 from the land above it to the crankcase; held on its lower flank "
             "unless pinned is given (none, or null: it moves)."},
    {"end_gap_area_m2", RD_F_NUMBER, PO(proto.end_gap_area), RD_MIN(0), RD_MAX(1e-4),
     .desc = "The end gap's flow area, m^2 (the discharge coefficient applies); 0 (the "
             "default): the closed gap times the narrower of the radial clearances of the land "
             "above and the land below the ring (the last ring: the land above). A compression "
             "ring's only."},
    {"leak_area_m2", RD_F_NUMBER, PO(proto.leak_area), RD_MIN(1e-12), RD_MAX(1e-4),
     .desc = "kind oil: the effective leakage area C_d A from the land above to the crankcase, "
             "m^2 (default 4.2e-8: the 0.3 mm x 0.2 mm gap at C_d 0.7 of the thesis pack's "
             "stand-in). An oil ring's only."},
    {.key = NULL},
};
static const rd_block item_block = {"PackRing", "One ring of the pack, top ring first.", 1, 0,
                                    item_fields};

static const rd_field synthetic_fields[] = {
    {"kind", RD_F_CHOICE, PO(synthetic_kind), .choices = synthetic_names,
     .desc = "motored: polytropic compression and expansion (n = 1.32); fired: plus a Wiebe "
             "heat release (a = 5, m = 2, 50 deg) scaled to peak_pa at peak_crank_deg."},
    {"peak_pa", RD_F_NUMBER, PO(pack.synthetic.peak_pa), RD_MAX(1e8),
     .desc = "Fired: peak cylinder pressure, Pa, absolute; above 1.05 x the motored peak "
             "intake_pa x compression_ratio^1.32."},
    {"peak_crank_deg", RD_F_NUMBER, PO(pack.synthetic.peak_crank_deg), RD_MIN(0), RD_MAX(60),
     .desc = "Fired: crank angle of the peak, deg after firing TDC."},
    {"compression_ratio", RD_F_NUMBER, PO(pack.synthetic.compression_ratio), RD_MIN(2), RD_MAX(40),
     .desc = "Geometric compression ratio, -."},
    {"intake_pa", RD_F_NUMBER, PO(pack.synthetic.intake_pa), RD_MIN(1e4), RD_MAX(1e7),
     .desc = "Pressure at inlet closing (BDC) and during exhaust and intake, Pa, absolute."},
    {.key = NULL},
};
static const rd_block synthetic_block = {
    "SyntheticCylinderPressure",
    "A generated cylinder pressure (README \"Ring pack\"): single zone, no wall heat loss, "
    "blowdown blended to intake_pa from 130 to 180 deg.",
    1, 0, synthetic_fields};

static const rd_field cylinder_fields[] = {
    {"crank_deg", RD_F_TABLE, PO(table[0]), RD_MIN(2), RD_MAX(RD_LIFT_TABLE_MAX),
     .desc = "Crank angles, deg, strictly increasing from 0 to 720 (0 = firing TDC)."},
    {"pressure_pa", RD_F_TABLE, PO(table[1]), RD_MIN(2), RD_MAX(RD_LIFT_TABLE_MAX),
     .desc = "Cylinder pressure at those angles, Pa, ABSOLUTE, each 1e3 to 1e9."},
    {"synthetic", RD_F_OPTBLOCK, PO(synthetic_given), .block = &synthetic_block},
    {.key = NULL},
};
static const rd_block cylinder_block = {
    "CylinderPressure",
    "/cylinder_pressure: either a table (crank_deg and pressure_pa, absolute, periodic over 720 "
    "deg, a monotone C1 cubic between the points: it never overshoots them) or synthetic; absent "
    "or {}: synthetic with its defaults (fired).",
    1, 0, cylinder_fields};

static const rd_field temperature_fields[] = {
    {"lands", RD_F_NUMBER, PO(pack.T_lands), RD_MIN(200), RD_MAX(1500),
     .desc = "Gas temperature in the lands and grooves (and of gas entering the top land), K."},
    {"crankcase", RD_F_NUMBER, PO(pack.T_crankcase), RD_MIN(200), RD_MAX(1500),
     .desc = "Crankcase gas temperature, K."},
    {.key = NULL},
};
static const rd_block temperature_block = {"GasTemperature", "/gas_temperature_k.", 1, 0,
                                           temperature_fields};

static const rd_field output_fields[] = {
    {"step_deg", RD_F_NUMBER, PO(pack.step_deg), RD_MIN(0.01), RD_MAX(90),
     .desc = "Crank-angle step of the output samples, deg (rounded so 720 / step is whole)."},
    {"flank_band", RD_F_NUMBER, PO(pack.flank_band), RD_MIN(0), RD_MAX(RD_LIFT_FLANK_BAND_MAX),
     .desc = "Width of the band at each flank, as a fraction of each ring's axial clearance, "
             "where flank changes are dated (as in lift): a leave where the ring's (mean) lift "
             "moves out of the band, a landing where it moves in (a bounce that leaves the band "
             "is two events). Each event also keeps touch_deg, where the lift itself touched or "
             "left the flank (an axial ring: its impact, or its net force turning away), null "
             "if it never touched in between. The samples' flank is the band the lift is in. 0: "
             "dated at the touch and where the ring leaves the flank (touch_deg = crank_deg; an "
             "axial ring's flank is then its contact state). Default 0.01."},
    {.key = NULL},
};
static const rd_block output_block = {"PackOutput", "/output (ringpack).", 1, 0, output_fields};

/* stribeck is named (as in lift) but refused by rd_ringpack_validate */
static const rd_field friction_fields[] = {
    RD_FRICTION_FIELDS(PO, pack.friction,
                       "coulomb: F = -mu N tanh(u / u_reg) on each ring, N its bore normal force "
                       "(the pretension plus its groove's gas on the back face), u its sliding "
                       "speed on the liner (the lift analysis' law). lubricated: each ring's oil "
                       "film on its running face (/rings/i/ring/face), as lift's, loaded by the "
                       "pack's own pressures (its groove behind it, its lands at the face's "
                       "edges), each cycle's film integrated over the cycle before's pressures "
                       "(the result's rings[i].lubrication.film_lag says how far that lags); "
                       "reads oil, asperity and /bore/roughness_rq_m. stribeck: refused, not "
                       "available in the pack.",
                       "Coulomb coefficient mu, -."),
    RD_LUBE_FRICTION_FIELDS,
    {.key = NULL},
};
static const rd_block friction_block = {
    "PackFriction",
    "/physics/friction (ringpack): axial liner friction on every ring; present = modelled.", 1, 0,
    friction_fields};

static const char *const area_names[] = {"fixed", "dynamic", NULL}; /* enum rd_gas_area */

static const char *const passage_names[] = {"viscous_limited", "orifice",
                                            NULL};                    /* enum rd_flank_passage */
static const char *const pressure_names[] = {"full", "linear", NULL}; /* enum rd_flank_pressure */

static const rd_field gas_fields[] = {
    {"active_area", RD_F_CHOICE, PO(pack.active_area), .choices = area_names,
     .desc = "As lift's /physics/gas/active_area. fixed: full faces (thesis). dynamic: a face "
             "sealing on a flank sees the mean of the groove-back pressure and its own side's, "
             "weighted by its flank contact (the lift models' contact, ~5 nm deep); lift-model "
             "rings only (auto: rigid without friction; axial is refused); not with "
             "flank_pressure linear."},
    {"flank_pressure", RD_F_CHOICE, PO(pack.flank_pressure), .choices = pressure_names,
     .desc = "The gas on the rings' flanks. full: each face carries its own land's pressure "
             "(the thesis'). linear: each face carries the mean of the groove's and its land's "
             "pressures, the linear fall across the flank from groove to land (sealed on it or "
             "open), as the classic ring-pack models; a ring's net axial gas force is then half "
             "the full one. Every ring model."},
    {"flank_passage", RD_F_CHOICE, PO(pack.flank_passage), .choices = passage_names,
     .desc = "The flank passages' law. viscous_limited: the smaller of the orifice flow and the "
             "viscous (laminar, isothermal) slot flow pi (d - b) h^3 (p_a^2 - p_b^2) / (24 mu R "
             "T b), h the flank's lift, b the ring's radial width, blended smoothly where they "
             "cross; orifice: the orifice alone (16x the viscous flow at a 2 um lift, 60 -> 30 "
             "bar, on the thesis ring)."},
    {"heat_capacity_ratio", RD_F_NUMBER, PO(pack.kappa), RD_XMIN(1), RD_XMAX(1.67),
     .desc = "The gas's heat capacity ratio k in the orifice law, -: above 1, below 1.67."},
    {"gas_constant", RD_F_NUMBER, PO(pack.gas_constant), RD_MIN(50), RD_MAX(5000),
     .desc = "The gas's specific gas constant R, J/(kg K) (air, and near enough burnt gas: 287); "
             "also the blow-by's standard volume (101325 Pa, 20 C)."},
    {"viscosity_pa_s", RD_F_NUMBER, PO(pack.gas_viscosity), RD_MIN(0), RD_MAX(0.001),
     .desc = "The gas's dynamic viscosity in the flank passages, Pa s, 1e-6 to 1e-3; 0 (the "
             "default): Sutherland's law for air at each passage's temperature (the mean of its "
             "two volumes': 2.48e-5 Pa s at 450 K)."},
    {.key = NULL},
};
static const rd_block gas_block = {
    "PackGas",
    "/physics/gas (ringpack): the gas's properties, the flank passages' law and how the "
    "network's pressures load the rings' faces (the pressures themselves are computed, never "
    "given).",
    1, 0, gas_fields};

static const rd_field physics_fields[] = {
    {"friction", RD_F_OPTBLOCK, PO(eng.friction_given), .block = &friction_block},
    {"gas", RD_F_BLOCK, 0, .block = &gas_block},
    {"gravity", RD_F_BOOL, PO(pack.gravity),
     .desc = "Gravity on the rings, g = 9.80665 m/s^2 along -z (as lift's)."},
    {.key = NULL},
};
static const rd_block physics_block = {
    "PackPhysics",
    "/physics (ringpack): the forces on the rings besides inertia, gravity and the gas on the "
    "faces; an absent entry is not modelled.",
    1, 0, physics_fields};

static const rd_field numerics_fields[] = {
    {"model", RD_F_CHOICE, PO(pack.model), .choices = model_names,
     .desc = "Every ring's model unless its own rings/i/model says. " MODEL_DESC},
    {"rtol", RD_F_NUMBER, PO(pack.rtol), RD_MIN(1e-12), RD_MAX(RTOL_MAX),
     .desc = "Relative tolerance, at most 1e-5 (1e-6 with friction): looser, the rings' flank "
             "stops and the gas network go unstable (negative pressures, CVODE failures at 1 "
             "rpm)."},
    {"atol", RD_F_NUMBER, PO(pack.atol), RD_MIN(1e-16), RD_MAX(1e-05),
     .desc = "Absolute tolerance on the lifts, m (rtol x the crankcase pressure on pressures)."},
    {"max_steps", RD_F_INTEGER, PO(max_steps), RD_MIN(100), RD_MAX(1000000000),
     .desc = "CVODE steps allowed for the whole run."},
    {"error_estimate", RD_F_BOOL, PO(pack.estimate_error),
     .desc = "Estimate the error by a second run at rtol/10 and atol/10 (as many cycles as the "
             "run)."},
    {"film_step_deg", RD_F_NUMBER, PO(pack.film_step_deg), RD_MIN(0.01),
     RD_MAX(RD_LIFT_FILM_STEP_MAX_DEG),
     .desc = "The lubricated model's oil films: their largest time step, crank deg (default 2; "
             "read with physics.friction.model lubricated only)."},
    {"periodic_tolerance", RD_F_NUMBER, PO(pack.periodic_tolerance), RD_MIN(1e-6), RD_MAX(0.1),
     .desc = "With /engine/cycles \"periodic\": the change of a cycle against the one before "
             "(the result's periodicity: the blow-by's relative change and the largest pressure "
             "change over each volume's peak) at which the run stops."},
    {.key = NULL},
};
static const rd_block numerics_block = {"PackNumerics", "/numerics of a ringpack scene.", 1, 0,
                                        numerics_fields};

static int parse_rings(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err);
static json_t *echo_rings(const rd_scene *s);

static const rd_field scene_fields[] = {
    RD_SCENE_HEAD,
    {"engine", RD_F_BLOCK, 0, .block = &engine_block},
    {"rings", RD_F_ITEMS, 0, .block = &item_block, RD_MIN(1), RD_MAX(RD_RINGPACK_RINGS_MAX),
     .parse = parse_rings, .echo = echo_rings,
     .desc = "1 to 3 rings, top ring first; absent: the thesis engine's pack (top ring, second "
             "ring, oil-control ring; README \"Ring pack\"). Each ring's fields default to the "
             "top ring's."},
    {"bore", RD_F_BLOCK, 0, .block = &bore_block},
    {"cylinder_pressure", RD_F_BLOCK, 0, .block = &cylinder_block},
    {"crankcase_pressure_pa", RD_F_NUMBER, PO(pack.crankcase_pa), RD_MIN(1e3), RD_MAX(1e7),
     .in_opts = 1, .desc = "Crankcase pressure, Pa, ABSOLUTE."},
    {"gas_temperature_k", RD_F_BLOCK, 0, .block = &temperature_block},
    {"output", RD_F_BLOCK, 0, .block = &output_block},
    {"physics", RD_F_BLOCK, 0, .block = &physics_block},
    {"numerics", RD_F_BLOCK, 0, .block = &numerics_block},
    {.key = NULL},
};
static const rd_block scene_block = {
    "RingpackScene",
    "The ring pack (thesis 2.4.4): the gas pressures in the lands and grooves "
    "between 1 to 3 rings computed from one cylinder pressure by a compressible orifice "
    "network coupled both ways with the rings' axial motion, and the blow-by into the "
    "crankcase. All pressures are ABSOLUTE (the lift analysis' tables are gauge). Reads "
    "engine (with the piston tilt), rings, bore, cylinder_pressure, crankcase_pressure_pa, "
    "gas_temperature_k, physics (friction, gas), output "
    "and numerics (PackNumerics); not the top-level ring.",
    0, 0, scene_fields};

/* The fields one kind of ring reads: an oil ring's leak area, a
 * compression ring's end-gap area (each refused on the other kind where
 * it differs from its default; the echo writes both). */
static int kind_fields(const rd_ringpack_ring *r, double leak_default, const char *at,
                       rd_error *err)
{
    char f[RD_ERROR_PATH_MAX];
    if (r->kind == RD_RING_OIL && r->end_gap_area != 0.0) {
        snprintf(f, sizeof f, "%s/end_gap_area_m2", at);
        return rd_error_set(err, RD_EINVAL, f,
                            "%s = %g m^2: an oil ring (kind oil) leaks through leak_area_m2 "
                            "only; end_gap_area_m2 is a compression ring's.",
                            f, r->end_gap_area);
    }
    if (r->kind == RD_RING_COMPRESSION && r->leak_area != leak_default) {
        snprintf(f, sizeof f, "%s/leak_area_m2", at);
        return rd_error_set(err, RD_EINVAL, f,
                            "%s = %g m^2 is an oil ring's (kind oil); a compression ring leaks "
                            "through its end gap (end_gap_area_m2, or closed_gap).",
                            f, r->leak_area);
    }
    return RD_OK;
}

/* Ring i's face table into its face (o's arrays, borrowed). */
static int item_face(struct pack_opts *o, int i, const char *at, rd_face_params *face,
                     rd_error *err)
{
    char f[RD_ERROR_PATH_MAX];
    snprintf(f, sizeof f, "%s/ring/face/table", at);
    if (o->face_table_given[i] != (face->profile == RD_FACE_TABLE))
        return rd_error_set(err, RD_EINVAL, f,
                            o->face_table_given[i] ? "%s is read with profile table only."
                                                   : "profile table needs %s.",
                            f);
    if (!o->face_table_given[i])
        return RD_OK;
    if (o->face_table[i][0].n != o->face_table[i][1].n)
        return rd_error_set(err, RD_EINVAL, f, "%s: x_m has %d values but drop_m has %d.", f,
                            o->face_table[i][0].n, o->face_table[i][1].n);
    face->points = o->face_table[i][0].n;
    face->x = o->face_table[i][0].v;
    face->drop = o->face_table[i][1].v;
    return RD_OK;
}

/* One item through a temporary scene (file comment). */
static int parse_ring(json_t *item, const char *at, rd_scene *s, int i, rd_error *err)
{
    struct pack_opts *o = s->opts, slot;
    if (!json_is_object(item))
        return rd_schema_type_error(err, at, "an object {ring, groove, land, ...}", item);
    json_t *copy = rd_json_copy(item);
    if (!copy)
        return rd_error_set(err, RD_ENOMEM, at, "out of memory while reading %s", at);
    int none = json_is_null(json_object_get(copy, "pinned"));
    if (none) /* the contract's null: not pinned */
        json_object_del(copy, "pinned");
    memset(&slot, 0, sizeof slot);
    slot.proto = o->proto; /* the defaults */
    rd_scene tmp = *s;
    tmp.opts = &slot;
    tmp.ring = slot.proto.ring;
    tmp.face = slot.proto.face;
    tmp.face_given = tmp.face_table_given = 0;
    memset(tmp.face_table, 0, sizeof tmp.face_table);
    int rc = rd_schema_parse(copy, &item_block, NULL, at, &tmp, err);
    int pin_given = json_object_get(item, "pinned") != NULL;
    json_decref(copy);
    slot.proto.ring = tmp.ring;
    slot.proto.face = tmp.face;
    memcpy(o->face_table[i], tmp.face_table, sizeof tmp.face_table); /* owned by o */
    o->face_given[i] = tmp.face_given;
    o->face_table_given[i] = tmp.face_table_given;
    rc = rc ? rc : item_face(o, i, at, &slot.proto.face, err);
    if (none)
        slot.proto.pinned = RD_PIN_FREE;
    if (!rc && slot.proto.kind == RD_RING_OIL && !pin_given) /* no dynamics unless asked */
        slot.proto.pinned = RD_PIN_LOWER;
    rc = rc ? rc : kind_fields(&slot.proto, o->proto.leak_area, at, err);
    o->pack.rings[i] = slot.proto;
    return rc;
}

static int parse_rings(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    struct pack_opts *o = s->opts;
    size_t n = json_array_size(v);
    if (n < (size_t)f->min || n > (size_t)f->max)
        return rd_error_set(err, n ? RD_ELIMIT : RD_EINVAL, path,
                            "%s has %zu rings; allowed %d to %d.", path, n, (int)f->min,
                            (int)f->max);
    for (size_t i = 0; i < n; i++) {
        char at[RD_ERROR_PATH_MAX];
        snprintf(at, sizeof at, "%s/%zu", path, i);
        int rc = parse_ring(json_array_get(v, i), at, s, (int)i, err);
        if (rc != RD_OK)
            return rc;
    }
    o->pack.n_rings = (int)n;
    return RD_OK;
}

static json_t *echo_rings(const rd_scene *s)
{
    const struct pack_opts *o = s->opts;
    json_t *a = json_array();
    for (int i = 0; a && i < o->pack.n_rings; i++) {
        struct pack_opts slot;
        memset(&slot, 0, sizeof slot);
        slot.proto = o->pack.rings[i];
        rd_scene tmp = *s;
        tmp.opts = &slot;
        tmp.ring = slot.proto.ring;
        tmp.face = slot.proto.face;
        tmp.face_given = o->face_given[i];
        tmp.face_table_given = o->face_table_given[i];
        memcpy(tmp.face_table, o->face_table[i], sizeof tmp.face_table);
        json_t *item = json_object();
        int bad = !item || rd_schema_echo(&item_block, &tmp, item) != 0;
        if (!bad && slot.proto.pinned == RD_PIN_FREE)
            bad = json_object_set_new(item, "pinned", json_null());
        if (bad || json_array_append_new(a, item) != 0) {
            if (bad)
                json_decref(item);
            json_decref(a);
            a = NULL;
        }
    }
    return a;
}

static void defaults(struct rd_scene *s)
{
    struct pack_opts *o = s->opts;
    rd_ringpack_params_thesis(&o->pack);
    o->proto = o->pack.rings[0];
    s->face = o->proto.face;
    s->lube.lube = o->pack.friction.lube;
    s->lube.bore_rq = o->pack.bore.roughness_rq;
    o->max_steps = (int)o->pack.max_steps;
    o->cycles = o->pack.engine.cycles;
    o->synthetic_kind = 0;
}

static void cleanup(void *opts)
{
    struct pack_opts *o = opts;
    for (int k = 0; k < 2; k++) {
        free(o->table[k].v);
        for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++)
            free(o->face_table[i][k].v);
    }
    rd_engine_scene_cleanup(&o->eng);
    rd_contact_map_cleanup(&o->map);
    rd_ringpack_free(o->handle);
}

/* A table or the synthetic trace, never both; the table's two columns alike. */
static int cylinder_finish(struct pack_opts *o, rd_error *err)
{
    rd_ringpack_params *p = &o->pack;
    int has = (o->table[0].v != NULL) + (o->table[1].v != NULL);
    p->synthetic.kind = o->synthetic_kind ? RD_CYLINDER_MOTORED : RD_CYLINDER_FIRED;
    if (has == 0) { /* synthetic, echoed as such */
        p->cylinder_kind = p->synthetic.kind;
        o->synthetic_given = 1;
        return RD_OK;
    }
    const char *miss =
        o->table[0].v ? "/cylinder_pressure/pressure_pa" : "/cylinder_pressure/crank_deg";
    if (o->synthetic_given)
        return rd_error_set(err, RD_EINVAL, "/cylinder_pressure/synthetic",
                            "/cylinder_pressure gives both a table and synthetic: use one.");
    if (has == 1)
        return rd_error_set(err, RD_EINVAL, miss,
                            "%s is missing: a cylinder pressure table needs crank_deg and "
                            "pressure_pa of the same length.",
                            miss);
    if (o->table[0].n != o->table[1].n)
        return rd_error_set(err, RD_EINVAL, "/cylinder_pressure/pressure_pa",
                            "/cylinder_pressure/pressure_pa has %d values but crank_deg has %d; "
                            "they must have the same length.",
                            o->table[1].n, o->table[0].n);
    p->cylinder_kind = RD_CYLINDER_TABLE;
    p->table_points = o->table[0].n;
    p->table_deg = o->table[0].v;
    p->table_pa = o->table[1].v;
    return RD_OK;
}

/* The ranges above that core's validator (wider) does not know. */
static int solver_ranges(const struct pack_opts *o, rd_error *err)
{
    if (o->pack.rtol > RTOL_MAX)
        return rd_error_set(err, RD_EINVAL, "/numerics/rtol",
                            "/numerics/rtol = %g is out of range: allowed 1e-12 to %g (looser, the "
                            "rings' flank stops and the gas network go unstable: negative "
                            "pressures, CVODE failures).",
                            o->pack.rtol, RTOL_MAX);
    if (!o->eng.friction_given)
        return RD_OK;
    if (o->pack.engine.speed_rpm < FRICTION_RPM_MIN || o->pack.rtol > FRICTION_RTOL_MAX)
        return rd_error_set(err, RD_EINVAL, "/physics/friction",
                            "/physics/friction needs /engine/speed_rpm >= %g (got %g) and "
                            "/numerics/rtol <= %g (got %g): below that speed the friction's "
                            "regularization speed (1e-3 x the mean piston speed) makes it too "
                            "stiff, and looser tolerances let CVODE fail.",
                            FRICTION_RPM_MIN, o->pack.engine.speed_rpm, FRICTION_RTOL_MAX,
                            o->pack.rtol);
    return RD_OK;
}

/* The lubricated model's inputs (each ring's face, the oil, the liner),
 * each refused by name with another friction model. */
static int lube_finish(struct rd_scene *s, struct pack_opts *o, rd_error *err)
{
    rd_ringpack_params *p = &o->pack;
    int lub = p->friction.model == RD_FRICTION_LUBRICATED;
    for (int i = 0; i < p->n_rings; i++) {
        char at[32];
        snprintf(at, sizeof at, "/rings/%d/ring", i % 10);
        if (o->face_given[i] && !lub) {
            char f[RD_ERROR_PATH_MAX];
            snprintf(f, sizeof f, "%s/face", at);
            return rd_error_set(err, RD_EINVAL, f,
                                "%s is read by the lubricated friction model only: set "
                                "/physics/friction/model to lubricated, or remove it.",
                                f);
        }
        int rc = rd_face_unread(&p->rings[i].face, at, err);
        if (rc)
            return rc;
    }
    if (!lub && p->film_step_deg != RD_LIFT_FILM_STEP_DEG)
        return rd_error_set(err, RD_EINVAL, "/numerics/film_step_deg",
                            "/numerics/film_step_deg is read by the lubricated friction model "
                            "only.");
    return rd_scene_lube_finish(s, lub, &p->friction.lube, &p->bore.roughness_rq, err);
}

static int finish(struct rd_scene *s, rd_error *err)
{
    struct pack_opts *o = s->opts;
    rd_ringpack_params *p = &o->pack;
    p->max_steps = o->max_steps;
    p->periodic = o->cycles == 0.0; /* "periodic": at most the most cycles */
    p->engine.cycles = p->periodic ? RD_RINGPACK_CYCLES_MAX : o->cycles;
    if (!p->periodic && p->periodic_tolerance != RD_RINGPACK_PERIODIC_TOL)
        return rd_error_set(err, RD_EINVAL, "/numerics/periodic_tolerance",
                            "/numerics/periodic_tolerance = %g is read only with /engine/cycles "
                            "\"periodic\" (here %g cycles are run).",
                            p->periodic_tolerance, o->cycles);
    int rc = cylinder_finish(o, err);
    rc = rc ? rc : rd_engine_scene_finish(&o->eng, &p->engine, &p->bore, &p->friction, err);
    rd_ringpack_params d;
    rd_ringpack_params_default(&d);
    rc = rc ? rc : rd_friction_unread(&p->friction, &d.friction, err);
    p->ring_z_tdc = o->ring_z.z;
    double D = p->bore.diameter > 0.0 ? p->bore.diameter : p->rings[0].ring.diameter;
    rc = rc ? rc
            : rd_ring_depth_finish(&o->map, &o->ring_z, p->rings[0].ring.diameter, D,
                                   "the top ring's", &p->bore_map, err);
    rc = rc ? rc : lube_finish(s, o, err);
    /* core's checks, and the handle run will run (it borrows the tables above) */
    rc = rc ? rc : rd_ringpack_create(&o->pack, &o->handle, err);
    return rc ? rc : solver_ranges(o, err);
}

static int run(const rd_scene *s, const rd_monitor *mon, json_t **out, rd_error *err)
{
    const struct pack_opts *o = s->opts;
    rd_ringpack_result res;
    double t0 = rd_clock_s();
    int rc = rd_ringpack_run(o->handle, mon, &res, err);
    if (rc == RD_OK)
        *out = rd_ringpack_json(s, &o->pack, &res, rd_clock_s() - t0);
    if (rc == RD_OK && *out && o->map.points_given &&
        json_object_set_new(*out, "bore_fit", rd_bore_fit_json(s, &o->map)) != 0) {
        json_decref(*out);
        *out = NULL;
    }
    rd_ringpack_result_cleanup(&res);
    return rc;
}

static const rd_csv_column csv_columns[] = {
    {"crank_deg", "crank_deg", 0},
    {"cylinder_pa", "cylinder_pa", 0},
    {"top_land_pa", "top_land_pa", 0},
    {"groove_1_pa", "groove_1_pa", 0},
    {"second_land_pa", "second_land_pa", 0},
    {"groove_2_pa", "groove_2_pa", 0},
    {"third_land_pa", "third_land_pa", 0},
    {"groove_3_pa", "groove_3_pa", 0},
    {"lift_1_m", "lift_1_m", 0},
    {"lift_2_m", "lift_2_m", 0},
    {"lift_3_m", "lift_3_m", 0},
    {"blowby_kg_s", "blowby_kg_s", 0},
    {NULL, NULL, 0},
};
static const rd_csv_table csv = {"table", NULL, csv_columns};

/* What a scene of another analysis, or the page's single-ring fields, put at
 * the top level: each ring of a pack has its own. */
static const char *const elsewhere[] = {
    "ring",
    "each ring is /rings/i/ring (the first ring: /rings/0/ring)",
    "material",
    "each ring's material is /rings/i/ring/material",
    "discretization",
    "each ring's segment count is /rings/i/segments",
    "segments",
    "each ring's segment count is /rings/i/segments",
    "groove",
    "each ring's groove is /rings/i/groove",
    NULL};

static const char *const result_keys[] = {
    "analysis", "scene",       "crank_deg",        "volumes", "rings",    "flows",
    "blowby",   "periodicity", "periodic_reached", "table",   "numerics", "warnings",
    "bore_fit", NULL};

const rd_analysis_def rd_an_ringpack = {
    .name = "ringpack",
    .scene = &scene_block,
    .opts_size = sizeof(struct pack_opts),
    .defaults = defaults,
    .finish = finish,
    .cleanup = cleanup,
    .run = run,
    .csv = &csv,
    .page = "ringpack.js",
    .result_keys = result_keys,
    .elsewhere = elsewhere,
};
