/*
 * rd_blocks — the blocks several analyses read, declared once
 * (rd_registry.h): the ring with its material, the three discretization
 * blocks (the analyses differ in the segment range and whether the ring
 * may be closed) and the Newton numerics of pretension and contact, with
 * the result pieces those two share; what lift and the ring pack share of
 * the engine, the bore and friction (their rows are rd_registry.h's
 * macros: the two describe some fields in their own words); and the wall
 * clock every runner times its solve with.
 */
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_schema.h"

#define AT(member) offsetof(struct rd_scene, member)

static const rd_field material_fields[] = {
    {"youngs_modulus", RD_F_NUMBER, AT(ring.youngs_modulus), RD_MIN(1e6), RD_MAX(1e15),
     .desc = "Young's modulus E, Pa."},
    {"poisson_ratio", RD_F_NUMBER, AT(ring.poisson_ratio), RD_XMIN(-1), RD_XMAX(0.5),
     .desc = "Poisson's ratio nu, -1 < nu < 0.5."},
    {"density", RD_F_NUMBER, AT(ring.density), RD_MIN(0.1), RD_MAX(1e7),
     .desc = "Density rho, kg/m^3."},
    {.key = NULL},
};
static const rd_block material = {NULL, "Material.", 0, 0, material_fields};

/* /ring/section's JSON schema: a name or a general shape's object. */
#define SECTION_SCHEMA                                                                           \
    "{\"default\": \"rectangle\", \"oneOf\": [{\"type\": \"string\", \"enum\": [\"rectangle\", " \
    "\"circle\"]}, {\"type\": \"object\", \"additionalProperties\": false, \"required\": "       \
    "[\"shape\"], "                                                                              \
    "\"properties\": {\"shape\": {\"type\": \"string\", \"enum\": [\"taper_face\", "             \
    "\"inner_bevel\", "                                                                          \
    "\"inner_step\", \"keystone\", \"polygon\"]}, \"side\": {\"type\": \"string\", \"enum\": "   \
    "[\"top\", \"bottom\"], \"default\": \"top\"}, \"width_m\": {\"type\": \"number\"}, "        \
    "\"height_m\": {\"type\": \"number\"}, \"angle_deg\": {\"type\": \"number\"}, \"double\": "  \
    "{\"type\": \"boolean\", \"default\": false}, \"points_m\": {\"type\": \"array\", "          \
    "\"minItems\": 3, \"maxItems\": 64, \"items\": {\"type\": \"array\", \"minItems\": 2, "      \
    "\"maxItems\": 2, \"items\": {\"type\": \"number\"}}}}}]}"

/* /ring/pressure_distribution's JSON schema. */
#define PRESSURE_SCHEMA                                                                           \
    "{\"oneOf\": [{\"type\": \"string\", \"enum\": [\"uniform\"]}, {\"type\": \"object\", "       \
    "\"additionalProperties\": false, \"required\": [\"orders\"], \"properties\": {\"orders\": "  \
    "{\"type\": \"array\", \"maxItems\": 16, \"items\": {\"type\": \"object\", "                  \
    "\"additionalProperties\": false, \"required\": [\"order\", \"amplitude\"], \"properties\": " \
    "{\"order\": {\"type\": \"integer\", \"minimum\": 2, \"maximum\": 64}, \"amplitude\": "       \
    "{\"type\": \"number\", \"minimum\": -1, \"maximum\": 1}}}}}}, {\"type\": \"object\", "       \
    "\"additionalProperties\": false, \"required\": [\"theta_deg\", \"ratio\"], \"properties\": " \
    "{\"theta_deg\": {\"type\": \"array\", \"minItems\": 2, \"maxItems\": 721, \"items\": "       \
    "{\"type\": \"number\"}}, \"ratio\": {\"type\": \"array\", \"minItems\": 2, \"maxItems\": "   \
    "721, \"items\": {\"type\": \"number\", \"minimum\": 0, \"maximum\": 20}}}}]}"

#define FREE_TABLE_SCHEMA                                                                          \
    "{\"type\": \"object\", \"additionalProperties\": false, \"required\": [\"theta_deg\", "       \
    "\"radius_m\"], \"properties\": {\"theta_deg\": {\"type\": \"array\", \"minItems\": 8, "       \
    "\"maxItems\": 721, \"items\": {\"type\": \"number\", \"minimum\": -180, \"maximum\": 180}}, " \
    "\"radius_m\": {\"type\": \"array\", \"minItems\": 8, \"maxItems\": 721, \"items\": "          \
    "{\"type\": \"number\"}}, \"fit_order\": {\"type\": \"integer\", \"minimum\": 2, "             \
    "\"maximum\": 12, \"default\": 6}}}"

/* The ring's rows, shared by the plain ring block and the one with a face. */
#define RING_ROWS                                                                                  \
    {"diameter",    RD_F_NUMBER, AT(ring.diameter),                                                \
     RD_MIN(0.001), RD_MAX(5.0), .desc = "Nominal (= bore) diameter d, m."},                       \
        {"radial_width", RD_F_NUMBER, AT(ring.radial_width), RD_MIN(1e-05),                        \
         .desc = "Radial width b, m; at most d/4."},                                               \
        {"axial_height", RD_F_NUMBER, AT(ring.axial_height), RD_MIN(1e-05),                        \
         .desc =                                                                                   \
             "Axial height h, m; at most d/2, with b/h from 0.05 to 20; equal to radial_width "    \
             "for a circular section."},                                                           \
        {"closed_gap", RD_F_NUMBER, AT(ring.closed_gap), RD_MIN(0.0),                              \
         .desc = "Gap in the installed (closed) state, m; at most 10 % of the circumference "      \
                 "(pi d / 10); not checked for a closed ring."},                                   \
        {"tangential_force",                                                                       \
         RD_F_NUMBER,                                                                              \
         AT(ring.tangential_force),                                                                \
         RD_MIN(0.0),                                                                              \
         RD_MAX(100000.0),                                                                         \
         .desc = "Tangential (pretension) force F_t, N; the contact analysis needs it > 0."},      \
        {"section",                                                                                \
         RD_F_CUSTOM,                                                                              \
         AT(ring.section),                                                                         \
         .parse = rd_section_parse,                                                                \
         .echo = rd_section_echo,                                                                  \
         .extra = SECTION_SCHEMA,                                                                  \
         .desc = "Cross-section: rectangle b x h, circle (a wire of diameter b = h), or a "        \
                 "general shape in the b x h box (docs/geometry.md): taper_face (angle_deg), "     \
                 "inner_bevel / inner_step (side, width_m, height_m), keystone (angle_deg, "       \
                 "double, side), polygon (points_m). The lift analysis needs rectangle; general "  \
                 "shapes are read by the pretension analysis only."},                              \
        {"pressure_distribution",                                                                  \
         RD_F_CUSTOM,                                                                              \
         AT(free_shape),                                                                           \
         .parse = rd_free_shape_parse,                                                             \
         .echo = rd_free_shape_echo,                                                               \
         .nullable = 1,                                                                            \
         .extra = PRESSURE_SCHEMA,                                                                 \
         .desc = "The ring made with the free shape that a round bore of its diameter closes "     \
                 "to its closed gap with this radial pressure (p0 = 2 F_t / (d h) its mean; "      \
                 "theta from the point opposite the gap): \"uniform\", {\"orders\": [{\"order\": " \
                 "k, \"amplitude\": a_k}]} for p / p0 = 1 + sum a_k cos k theta (k 2..64), or "    \
                 "{\"theta_deg\": [...], \"ratio\": [...]} (p / p0, from 0 mirrored or -180, to "  \
                 "180). Absent: the stress-free closed ring opened by F_t on its gap faces. Read " \
                 "by the pretension and contact analyses (a turned section twists when closed: "   \
                 "pretension gives shape.static_twist_deg)."},                                     \
        {"free_shape",                                                                             \
         RD_F_CUSTOM,                                                                              \
         AT(free_table),                                                                           \
         .parse = rd_free_table_parse,                                                             \
         .echo = rd_free_table_echo,                                                               \
         .nullable = 1,                                                                            \
         .extra = FREE_TABLE_SCHEMA,                                                               \
         .desc = "A measured free shape: the running face's radius radius_m (m) at theta_deg "     \
                 "from the point opposite the gap, about any centre; one side (from 0-20 to 150 "  \
                 "deg or more) or the whole ring (-150 to 150 or more), no point in the gap. "     \
                 "ringdyn fits F_t and the pressure orders 2..fit_order (default 6) whose exact "  \
                 "free shape is closest to it (the centre and, whole, the angle's origin free) "   \
                 "and solves that ring; result free_shape_fit. Instead of "                        \
                 "pressure_distribution; tangential_force then follows from it. Read by the "      \
                 "pretension and contact analyses."},                                              \
    {                                                                                              \
        "material", RD_F_BLOCK, 0, .block = &material                                              \
    }

static const rd_field ring_fields[] = {
    RING_ROWS,
    {.key = NULL},
};
const rd_block rd_block_ring = {
    "Ring",
    "The ring (every analysis). Defaults: the thesis ring. Ranges are checked by the server; "
    "those that depend on other fields are given in the descriptions.",
    0, 0, ring_fields};

/* /ring/face: the running face of the lubricated friction model. */
static const char *const profile_names[] = {"barrel", "taper", "flat", "table", NULL};
static const rd_field face_table_fields[] = {
    {"x_m", RD_F_TABLE, AT(face_table[0]), RD_MIN(2), RD_MAX(RD_FACE_TABLE_MAX), .required = 1,
     .desc = "Axial positions from the face's lower edge, m, strictly increasing from 0 to the "
             "running face's height."},
    {"drop_m", RD_F_TABLE, AT(face_table[1]), RD_MIN(2), RD_MAX(RD_FACE_TABLE_MAX), .required = 1,
     .desc = "The face's recess from the liner side at each x_m, m, each 0 to 1e-4 (the "
             "smallest is where the film is thinnest)."},
    {.key = NULL},
};
static const rd_block face_table_block = {
    "FaceTable", "/ring/face/table: the profile as points, linear between them.", 0, 0,
    face_table_fields};
static const rd_field face_fields[] = {
    {"profile", RD_F_CHOICE, AT(face.profile), .choices = profile_names,
     .desc = "barrel: drop = crown ((x - x_c) / (L/2))^2, x_c = L/2 + offset. taper: drop = "
             "tan(taper) x, the lower edge on the liner. flat: flat with rounded edges. table: "
             "points (table)."},
    {"crown_m", RD_F_NUMBER, AT(face.crown), RD_MIN(0), RD_MAX(1e-4),
     .desc = "Barrel: the drop at the edges of a centred crown, m."},
    {"offset_m", RD_F_NUMBER, AT(face.offset),
     .desc = "Barrel: the crown's position above "
             "mid-height, m; |offset| below half the "
             "face's height."},
    {"taper_deg", RD_F_NUMBER, AT(face.taper_deg), RD_MIN(0), RD_MAX(5),
     .desc = "Taper: the face's angle to the liner, deg; above 0 with profile taper."},
    {"edge_radius_m", RD_F_NUMBER, AT(face.edge_radius), RD_MIN(0), RD_MAX(0.01),
     .desc = "Flat: the radius of each rounded edge, m, at most half the face's height."},
    {"table", RD_F_OPTBLOCK, AT(face_table_given), .block = &face_table_block},
    {"roughness_rq_m", RD_F_NUMBER, AT(face.roughness_rq), RD_MIN(1e-9), RD_MAX(5e-6),
     .desc = "The face's Rq, m (the composite sigma = sqrt(Rq_face^2 + Rq_liner^2))."},
    {.key = NULL},
};
static const rd_block face_block = {
    "RingFace",
    "/ring/face: the running face across its axial height and its roughness, read by the "
    "lubricated friction model only (refused with other friction models). Default: a barrel, "
    "crown 5 um, Rq 0.2 um.",
    0, 0, face_fields};

static const rd_field ring_face_fields[] = {
    RING_ROWS,
    {"face", RD_F_OPTBLOCK, AT(face_given), .block = &face_block},
    {.key = NULL},
};
const rd_block rd_block_ring_face = {
    "RingWithFace", "The ring (lift), with its running face for the lubricated friction model.", 0,
    0, ring_face_fields};

/* The lubricated model's oil and asperities (moved from the lift analysis:
 * the ring pack offers the model too). */
static const rd_field vogel_fields[] = {
    {"a_pa_s", RD_F_NUMBER, AT(lube.lube.vogel_a), RD_MIN(1e-9), RD_MAX(1),
     .desc = "a of eta = a exp(b / (T - c)), Pa s."},
    {"b_k", RD_F_NUMBER, AT(lube.lube.vogel_b), RD_MIN(0), RD_MAX(1e4), .desc = "b, K."},
    {"c_k", RD_F_NUMBER, AT(lube.lube.vogel_c), RD_MIN(0), RD_MAX(250),
     .desc = "c, K (T in kelvin)."},
    {.key = NULL},
};
static const rd_block vogel_block = {
    "Vogel",
    "/physics/friction/oil/vogel: eta = a exp(b / (T - c)), T the liner temperature in kelvin. "
    "Default: an SAE 5W-30-like oil (a 4.88e-5 Pa s, b 1197 K, c 141.15 K: 51 mPa s at 40 C, "
    "8.5 at 100 C, 3.4 at 150 C).",
    0, 0, vogel_fields};
static const rd_field temp_table_fields[] = {
    {"crank_deg", RD_F_TABLE, AT(lube.temp_table[0]), RD_MIN(2), RD_MAX(RD_LIFT_TABLE_MAX),
     .required = 1, .desc = "Crank angles, deg, strictly increasing within 0..720."},
    {"value_c", RD_F_TABLE, AT(lube.temp_table[1]), RD_MIN(2), RD_MAX(RD_LIFT_TABLE_MAX),
     .required = 1, .desc = "Liner temperature at each angle, deg C, each -40 to 250."},
    {.key = NULL},
};
static const rd_block temp_table_block = {
    "OilTemperatureTable",
    "/physics/friction/oil/temperature_table: the liner temperature vs crank angle (linear, "
    "periodic over 720 deg) in place of temperature_c.",
    0, 0, temp_table_fields};
static const rd_field oil_fields[] = {
    {"viscosity_pa_s", RD_F_NUMBER, AT(lube.lube.viscosity), RD_MIN(0), RD_MAX(10),
     .desc = "A constant dynamic viscosity, Pa s (1e-4 to 10); 0 = the Vogel law at the liner "
             "temperature (default)."},
    {"vogel", RD_F_OPTBLOCK, AT(lube.vogel_given), .block = &vogel_block},
    {"temperature_c", RD_F_NUMBER, AT(lube.lube.temperature_c), RD_MIN(-40), RD_MAX(250),
     .desc = "The liner temperature, deg C (default 100)."},
    {"temperature_table", RD_F_OPTBLOCK, AT(lube.temp_table_given), .block = &temp_table_block},
    {.key = NULL},
};
const rd_block rd_block_oil = {"Oil", "/physics/friction/oil: the lubricated model's oil.", 0, 0,
                               oil_fields};
static const rd_field asperity_fields[] = {
    {"density_per_m2", RD_F_NUMBER, AT(lube.lube.asperity_density), RD_MIN(1e6), RD_MAX(1e14),
     .desc = "Asperity density n, per m^2 (default 5e8)."},
    {"radius_m", RD_F_NUMBER, AT(lube.lube.asperity_radius), RD_MIN(1e-7), RD_MAX(1e-2),
     .desc = "Asperity tip radius beta, m (default 3e-4: n beta sigma = 0.04 with the default "
             "roughness)."},
    {"boundary_coefficient", RD_F_NUMBER, AT(lube.lube.boundary_coefficient), RD_MIN(0), RD_MAX(1),
     .desc = "Friction coefficient of the asperity load (default 0.1)."},
    {"composite_modulus_pa", RD_F_NUMBER, AT(lube.lube.composite_modulus), RD_MIN(0), RD_MAX(1e12),
     .desc = "E' with 1/E' = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2, Pa (1e9 to 1e12); 0 = the "
             "ring's material on a grey cast-iron liner (E 120 GPa, nu 0.26)."},
    {.key = NULL},
};
const rd_block rd_block_asperity = {
    "Asperity",
    "/physics/friction/asperity: Greenwood-Tripp asperity contact, W_a = (16 sqrt 2 / 15) pi (n "
    "beta sigma)^2 sqrt(sigma / beta) E' A F_5/2(h / sigma).",
    0, 0, asperity_fields};

/* The face's table into the face (scene-owned arrays, borrowed). */
int rd_scene_face_finish(struct rd_scene *s, int lubricated, rd_error *err)
{
    if (s->face_given && !lubricated)
        return rd_error_set(err, RD_EINVAL, "/ring/face",
                            "/ring/face is read by the lubricated friction model only: set "
                            "/physics/friction/model to lubricated, or remove /ring/face.");
    if (s->face_table_given != (s->face.profile == RD_FACE_TABLE))
        return rd_error_set(err, RD_EINVAL, "/ring/face/table",
                            s->face_table_given ? "/ring/face/table is read with profile table "
                                                  "only."
                                                : "profile table needs /ring/face/table.");
    if (s->face_table_given) {
        if (s->face_table[0].n != s->face_table[1].n)
            return rd_error_set(err, RD_EINVAL, "/ring/face/table/drop_m",
                                "x_m has %d values but drop_m has %d: the same length, please.",
                                s->face_table[0].n, s->face_table[1].n);
        s->face.points = s->face_table[0].n;
        s->face.x = s->face_table[0].v;
        s->face.drop = s->face_table[1].v;
    }
    return RD_OK;
}

const char *const rd_cavitation_names[] = {"reynolds", "jfo", NULL};

int rd_scene_lube_finish(struct rd_scene *s, int lub, rd_lube_params *l, double *liner_rq,
                         rd_error *err)
{
    struct rd_lube_scene *o = &s->lube;
    if (o->bore_rq != RD_LINER_RQ_DEFAULT && !lub)
        return rd_error_set(err, RD_EINVAL, "/bore/roughness_rq_m",
                            "/bore/roughness_rq_m is read by the lubricated friction model only.");
    if (!lub && o->lube.supply_film > 0.0)
        return rd_error_set(err, RD_EINVAL, "/physics/friction/supply",
                            "/physics/friction/supply is read by the lubricated friction model "
                            "only (model is not lubricated).");
    if (!lub && o->lube.cavitation != RD_CAVITATION_REYNOLDS)
        return rd_error_set(err, RD_EINVAL, "/physics/friction/cavitation",
                            "/physics/friction/cavitation \"%s\" is read by the lubricated "
                            "friction model only (model is not lubricated).",
                            rd_cavitation_names[o->lube.cavitation]);
    if (!lub && (o->oil_given || o->asperity_given))
        return rd_error_set(err, RD_EINVAL,
                            o->oil_given ? "/physics/friction/oil" : "/physics/friction/asperity",
                            "%s is read by the lubricated friction model only (model is not "
                            "lubricated).",
                            o->oil_given ? "/physics/friction/oil" : "/physics/friction/asperity");
    *l = o->lube;
    *liner_rq = o->bore_rq;
    if (o->vogel_given && l->viscosity > 0.0)
        return rd_error_set(err, RD_EINVAL, "/physics/friction/oil/vogel",
                            "give either viscosity_pa_s (a constant) or vogel, not both.");
    if (l->viscosity > 0.0 && (l->temperature_c != 100.0 || o->temp_table_given))
        return rd_error_set(err, RD_EINVAL,
                            o->temp_table_given ? "/physics/friction/oil/temperature_table"
                                                : "/physics/friction/oil/temperature_c",
                            "a constant viscosity_pa_s does not read the temperature: give "
                            "either viscosity_pa_s or the temperature (Vogel law), not both.");
    if (o->temp_table_given) {
        if (o->temp_table[0].n != o->temp_table[1].n)
            return rd_error_set(err, RD_EINVAL, "/physics/friction/oil/temperature_table/value_c",
                                "crank_deg has %d values but value_c has %d.", o->temp_table[0].n,
                                o->temp_table[1].n);
        l->temp_points = o->temp_table[0].n;
        l->temp_crank_deg = o->temp_table[0].v;
        l->temp_c = o->temp_table[1].v;
    }
    return RD_OK;
}

int rd_supply_parse(const rd_field *f, json_t *v, const char *path, struct rd_scene *s,
                    rd_error *err)
{
    (void)f;
    if (json_is_string(v) && strcmp(json_string_value(v), "flooded") == 0) {
        s->lube.lube.supply_film = 0.0;
        return RD_OK;
    }
    json_t *h = json_object_get(v, "film_m");
    if (!json_is_object(v) || json_object_size(v) != 1 || !json_is_number(h))
        return rd_schema_type_error(err, path, "\"flooded\" or {\"film_m\": a number}", v);
    double x = json_number_value(h);
    char at[RD_ERROR_PATH_MAX];
    rd_schema_path_join(at, sizeof at, path, "film_m");
    if (!(x >= 1e-8 && x <= 1e-3))
        return rd_error_set(err, RD_EINVAL, at,
                            "%s = %g m is out of range: allowed 1e-8 to 1e-3 m (the oil film on "
                            "the liner; \"flooded\" for as much as the face takes in).",
                            at, x);
    s->lube.lube.supply_film = x;
    return RD_OK;
}

json_t *rd_supply_echo(const struct rd_scene *s)
{
    double x = s->lube.lube.supply_film;
    return x > 0.0 ? json_pack("{s:f}", "film_m", x) : json_string("flooded");
}

int rd_face_unread(const rd_face_params *fp, const char *prefix, rd_error *err)
{
    const char *unread = fp->profile != RD_FACE_BARREL && fp->crown != 5e-6      ? "crown_m"
                         : fp->profile != RD_FACE_BARREL && fp->offset != 0.0    ? "offset_m"
                         : fp->profile != RD_FACE_TAPER && fp->taper_deg != 0.0  ? "taper_deg"
                         : fp->profile != RD_FACE_FLAT && fp->edge_radius != 0.0 ? "edge_radius_m"
                                                                                 : NULL;
    if (!unread)
        return RD_OK;
    char path[RD_ERROR_PATH_MAX];
    snprintf(path, sizeof path, "%s/face/%s", prefix, unread);
    return rd_error_set(err, RD_EINVAL, path, "%s is not read by this face profile.", path);
}

static const rd_field modal_discretization[] = {
    {"segments", RD_F_INTEGER, AT(segments), RD_MIN(3), RD_MAX(2000),
     .desc = "Number of rigid segments n; at most 3e5 min(b, h) / (R sqrt(max(1, G / E))) "
             "with the error estimate, 3e6 min(b, h) / (...) without (the modal slenderness "
             "limit)."},
    {"closed", RD_F_BOOL, AT(closed), .desc = "Join the gap (a closed ring)."},
    {.key = NULL},
};
const rd_block rd_block_discretization_modal = {
    "ModalDiscretization", "Discretization of a modal scene.", 0, 0, modal_discretization};

#define SPLIT_ONLY                                                                            \
    {                                                                                         \
        "closed", RD_F_BOOL, AT(closed), .only_false = 1,                                     \
                                         .desc = "Must be false (true is 422 invalid_scene)." \
    }

static const rd_field static_discretization[] = {
    {"segments", RD_F_INTEGER, AT(segments), RD_MIN(4), RD_MAX(2000),
     .desc = "Number of rigid segments n."},
    SPLIT_ONLY,
    {.key = NULL},
};
const rd_block rd_block_discretization_static = {
    "StaticDiscretization",
    "Discretization of a pretension or contact scene: the forces act on the gap faces, so the "
    "ring must be split.",
    0, 0, static_discretization};

static const rd_field lift_discretization[] = {
    {"segments", RD_F_INTEGER, AT(segments), RD_MIN(4), RD_MAX(1000),
     .desc = "Number of rigid segments n."},
    SPLIT_ONLY,
    {.key = NULL},
};
const rd_block rd_block_discretization_lift = {
    "LiftDiscretization", "Discretization of a lift scene: the split ring in its groove.", 0, 0,
    lift_discretization};

/* lift's /bore/distortion items, also the ring pack's (rd_an_lift.c). */
static const rd_field distortion_fields[] = {
    {"order", RD_F_INTEGER, offsetof(rd_distortion, order), RD_MIN(1), RD_MAX(64), .required = 1,
     .desc = "Fourier order k; a JSON integer."},
    {"amplitude", RD_F_NUMBER, offsetof(rd_distortion, amplitude), .required = 1,
     .desc = "Radius change A_k, m; the sum of |A_k| at most 1 % of the ring diameter, and "
             "sum |A_k| (k^2 + 2) at most the bore radius (a convex bore, as in contact)."},
    {"phase_deg", RD_F_NUMBER, offsetof(rd_distortion, phase_deg), RD_MIN(-360), RD_MAX(360),
     .desc = "Phase phi_k, deg: in lift from the ring's gap middle; in ringpack from the bore's "
             "angle 0 (each ring's gap sits at its gap_angle_deg)."},
    {.key = NULL},
};
const rd_block rd_block_lift_distortion = {"LiftBoreDistortion",
                                           "One Fourier term of the bore distortion (lift).", 0, 1,
                                           distortion_fields};

#define ST(member) offsetof(struct rd_static_scene, member)

/* The Newton fields pretension and contact share; contact adds its accuracy target. */
#define STATIC_NUMERICS_FIELDS                                                                    \
    {"tolerance",                                                                                 \
     RD_F_NUMBER,                                                                                 \
     ST(statics.tol),                                                                             \
     RD_MIN(1e-13),                                                                               \
     RD_MAX(0.001),                                                                               \
     .desc = "Relative residual tolerance: largest force residual <= tolerance * F_ref, moment "  \
             "residual <= tolerance * F_ref * R. Raised to the ring's rounding floor when that "  \
             "is larger (result numerics.tolerance gives the one used)."},                        \
        {"max_iterations",                                                                        \
         RD_F_INTEGER,                                                                            \
         ST(statics.max_iterations),                                                              \
         RD_MIN(1),                                                                               \
         RD_MAX(100000),                                                                          \
         .desc = "Newton iterations allowed over all load steps."},                               \
        {"error_estimate", RD_F_BOOL, ST(statics.estimate_error),                                 \
         .desc = "Estimate the discretization error by a second solve at 2n segments (n/2 above " \
                 "1000)."},

static const rd_field static_numerics[] = {
    STATIC_NUMERICS_FIELDS{.key = NULL},
};
const rd_block rd_block_static_numerics = {
    "StaticNumerics", "/numerics of a pretension scene: Newton's method with load stepping.", 1, 0,
    static_numerics};

static const rd_field contact_numerics[] = {
    STATIC_NUMERICS_FIELDS{
        "accuracy", RD_F_NUMBER, ST(contact.accuracy), RD_MIN(1e-4), RD_MAX(0.5),
        .desc = "Target relative accuracy of the pressure (relative to 2 F_t / (d h)), held to the "
                "same standard for the light-gap quantities: the solve refines n, 2n, 4n ... up to "
                "contact.max_segments until its error estimates meet it, or says why not "
                "(numerics.accuracy_met, accuracy_note)."},
    {.key = NULL},
};
const rd_block rd_block_contact_numerics = {
    "ContactNumerics",
    "/numerics of a contact scene: Newton's method with load stepping, and the accuracy target.", 1,
    0, contact_numerics};

void rd_static_scene_defaults(struct rd_scene *s)
{
    struct rd_static_scene *o = s->opts;
    rd_static_opts_default(&o->statics);
    o->statics.estimate_error = 1; /* API default, whatever core's is */
    rd_pretension_opts_default(&o->pretension);
    rd_contact_opts_default(&o->contact);
}

/* ---- engine, bore and friction: what lift and the ring pack share ---- */

const char *const rd_kinematics_names[] = {"exact", "approximate", NULL};
const char *const rd_friction_names[] = {"coulomb", "stribeck", "lubricated", NULL};

int rd_friction_unread(const rd_friction_params *f, const rd_friction_params *z, rd_error *err)
{
    if (f->model == RD_FRICTION_LUBRICATED && f->coefficient != z->coefficient)
        return rd_error_set(err, RD_EINVAL, "/physics/friction/coefficient",
                            "/physics/friction/coefficient = %g is read by the coulomb and "
                            "stribeck models only (model lubricated: its boundary friction is "
                            "/physics/friction/asperity/boundary_coefficient).",
                            f->coefficient);
    if (f->model == RD_FRICTION_STRIBECK)
        return RD_OK;
    const struct {
        const char *key;
        double v, v0;
    } st[] = {{"viscosity", f->viscosity, z->viscosity},
              {"sommerfeld_transition", f->sommerfeld_transition, z->sommerfeld_transition},
              {"hydrodynamic_slope", f->hydrodynamic_slope, z->hydrodynamic_slope}};
    for (size_t k = 0; k < sizeof st / sizeof st[0]; k++) {
        if (st[k].v == st[k].v0)
            continue;
        char at[64];
        snprintf(at, sizeof at, "/physics/friction/%s", st[k].key);
        return rd_error_set(
            err, RD_EINVAL, at, "%s = %g is read by the stribeck model only (model is %s).", at,
            st[k].v, f->model == RD_FRICTION_NONE ? "none" : rd_friction_names[f->model - 1]);
    }
    return RD_OK;
}

int rd_engine_scene_finish(const struct rd_engine_scene *es, rd_engine_params *e, rd_bore *b,
                           rd_friction_params *f, rd_error *err)
{
    f->model = es->friction_given ? es->friction_model + 1 : RD_FRICTION_NONE;
    e->tilt_points = 0;
    if (es->tilt_given && (!es->tilt_table[0].v || !es->tilt_table[1].v ||
                           es->tilt_table[1].n != es->tilt_table[0].n))
        return rd_error_set(err, RD_EINVAL, "/engine/piston_tilt/tilt_deg",
                            "/engine/piston_tilt needs crank_deg and tilt_deg of the same length "
                            "(got %d and %d values).",
                            es->tilt_table[0].n, es->tilt_table[1].n);
    if (es->tilt_given) {
        e->tilt_points = es->tilt_table[0].n;
        e->tilt_crank_deg = es->tilt_table[0].v;
        e->tilt_deg = es->tilt_table[1].v;
    }
    *b = es->bore;
    return RD_OK;
}

void rd_engine_scene_cleanup(struct rd_engine_scene *es)
{
    for (int k = 0; k < 2; k++)
        free(es->tilt_table[k].v);
}

/* ---- what the runners share ---- */

double rd_clock_s(void)
{
    struct timespec t;
    if (clock_gettime(CLOCK_MONOTONIC, &t) != 0)
        return NAN; /* reported as null: no time rather than a wrong one */
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- the result pieces pretension and contact share ---- */

static const char static_solver[] =
    "Newton's method with load stepping on the 6n equilibrium equations, large rotations, "
    "closed-form tangent factored as block tridiagonal";

json_t *rd_static_result_numerics(const rd_static_stats *st, double wall_s, const char *what)
{
    char method[192];
    int estimated = st->reference_segments > 0;
    snprintf(method, sizeof method, "%s from a second solve at %d segments", what,
             st->reference_segments);
    return json_pack("{s:i, s:i, s:o, s:s, s:i, s:i, s:i, s:i, s:o, s:o, s:o, s:o, s:o, s:o}",
                     "segments", st->segments, "dof", st->dof, "wall_s", rd_result_real(wall_s),
                     "solver", static_solver, "load_steps", st->load_steps, "iterations",
                     st->iterations, "factorizations", st->factorizations, "multiplier_updates",
                     st->outer_iterations, "residual", rd_result_real(st->residual), "tolerance",
                     rd_result_real(st->tolerance), "strain_energy",
                     rd_result_real(st->strain_energy), "reference_segments",
                     estimated ? json_integer(st->reference_segments) : json_null(),
                     "error_estimate", rd_result_real(st->error_estimate), "error_method",
                     estimated ? json_string(method) : json_null());
}

json_t *rd_static_result_support(const rd_static_stats *st)
{
    return json_pack("{s:o, s:o}", "force_n", rd_result_real(st->support_force), "moment_nm",
                     rd_result_real(st->support_moment));
}
