/*
 * rd_registry — the analyses this build knows, each one api file
 * (rd_an_<name>.c) that declares everything the api needs of it:
 *
 *   scene    its schema: the top-level block of fields (rd_schema.h), which
 *            references the shared blocks declared below (ring, material,
 *            discretization, static numerics) and its own;
 *   opts     the size of its own options (struct rd_scene.opts) and the
 *            hooks that fill their defaults, check them with core's
 *            validators once parsed, and free what they hold;
 *   run      the runner: calls the core solver and builds the result
 *            object (API.md "Results") once, as data;
 *   predict  its cost model, when core has one (the server's inline runs);
 *   csv      its main table (columns of that result object), or NULL with
 *            `csv_none` saying why there is none;
 *   page     its tab on the web page (a module in static/), or "none".
 *
 * rd_registry.c lists them; everything else (parsing, echo, OpenAPI,
 * running, CSV) walks the list.  Adding an analysis is one new
 * rd_an_<name>.c, one line in rd_registry.c, its core module and an
 * example scene (README "The registry").
 */
#ifndef RD_REGISTRY_H
#define RD_REGISTRY_H

#include <stddef.h>

#include "rd_error.h"
#include "rd_lift.h"
#include "rd_result.h"
#include "rd_scene.h"
#include "rd_schema.h"

struct json_t;
struct rd_scene;

typedef struct rd_analysis_def {
    const char *name;      /* the scene's "analysis" */
    const rd_block *scene; /* top level; its name is the OpenAPI component */
    size_t opts_size;      /* bytes of struct rd_scene.opts (0: none) */
    /* Fills the analysis' defaults (s->opts is zeroed, the common fields
     * hold theirs); may be NULL. */
    void (*defaults)(struct rd_scene *s);
    /* After parsing: the analysis' cross-field rules and core's validators
     * (rd_ring_validate has already passed). */
    int (*finish)(struct rd_scene *s, rd_error *err);
    void (*cleanup)(void *opts); /* frees what opts holds (not opts); may be NULL */
    /* Solves and builds the result object; a NULL *result on success means
     * out of memory, which the caller reports. */
    int (*run)(const struct rd_scene *s, const rd_monitor *mon, struct json_t **result,
               rd_error *err);
    /* Predicted CPU seconds of `run` (core's cost model); NULL when the
     * analysis has none. */
    double (*predict)(const struct rd_scene *s);
    const rd_csv_table *csv; /* the main table, or NULL */
    const char *csv_none;    /* why there is no table (csv NULL) */
    const char *page;        /* "modal.js": its tab in static/, or "none" */
    /* Top-level keys a user may send to this analysis that it reads
     * somewhere else: NULL-ended pairs {key, where it is read}, named in
     * their refusal (rd_scene.c).  May be NULL. */
    const char *const *elsewhere;
    /* 1: reads general /ring/section shapes (objects: their properties and
     * turned principal axes); 0: refuses them, naming the analysis
     * (rd_section_scene.c). */
    int general_sections;
    /* 1: reads /ring/pressure_distribution (the ring made with that
     * pressure's free shape); 0: refuses it, naming the analysis
     * (rd_free_shape_scene.c). */
    int free_shapes;
    /* The top-level members of its result (NULL-ended; the OpenAPI result
     * schema's properties, tests/api/test_schema.c): what a study's result
     * pointer may start with (rd_study.h). */
    const char *const *result_keys;
} rd_analysis_def;

/* The built-in registry, NULL-ended, in enum rd_analysis order. */
extern const rd_analysis_def *const rd_registry[];

/* The entry named `name` in `registry`, its index in *index; NULL if none. */
const rd_analysis_def *rd_registry_find(const rd_analysis_def *const *registry, const char *name,
                                        int *index);

/* The top-level keys that analyses of `registry` other than `an` read and
 * `an` does not: refused in `an`'s scenes, naming `an`.  Written to keys[]
 * (at most max - 1, NULL-ended, in the contract's order); returns their
 * count. */
int rd_registry_ignored(const rd_analysis_def *const *registry, const rd_analysis_def *an,
                        const char **keys, int max);

/* (rd_openapi.c) The OpenAPI document `template_json` with its scene
 * schemas filled in from `registry`: components.schemas gets "Scene" (oneOf the analyses,
 * discriminated by "analysis"), one "<Name>Scene" per analysis and every
 * named block they reference.  New reference; NULL + err when the
 * template is not a JSON object with components.schemas, or on out of
 * memory. */
struct json_t *rd_registry_openapi(const rd_analysis_def *const *registry,
                                   const char *template_json, rd_error *err);

/* (rd_section_scene.c) /ring/section: "rectangle", "circle" or a general
 * shape's object, into s->ring.section and s->ring.spec; and its echo. */
int rd_section_parse(const rd_field *f, struct json_t *v, const char *path, struct rd_scene *s,
                     rd_error *err);
struct json_t *rd_section_echo(const struct rd_scene *s);
/* (rd_free_shape_scene.c) /ring/pressure_distribution: "uniform", orders or
 * a table, into s->free_shape; and its echo (JSON null when absent). */
int rd_free_shape_parse(const rd_field *f, struct json_t *v, const char *path, struct rd_scene *s,
                        rd_error *err);
struct json_t *rd_free_shape_echo(const struct rd_scene *s);
/* The result's "free_shape_model": which ring the statics solved, as a
 * string: "stress_free_closed" (the closed ring stress-free, F_t on its gap
 * faces), "pressure_distribution" (made with that pressure's free shape,
 * its gap faces free) or "measured_free_shape" (the pressure fitted to
 * /ring/free_shape).  NULL on out of memory. */
struct json_t *rd_free_shape_model(const struct rd_scene *s);
/* (rd_free_shape_scene.c) /ring/free_shape: a measured table into
 * s->free_table, and its echo (JSON null when absent). */
int rd_free_table_parse(const rd_field *f, struct json_t *v, const char *path, struct rd_scene *s,
                        rd_error *err);
struct json_t *rd_free_table_echo(const struct rd_scene *s);
/* The free-shape fields' checks across the ring block, from the
 * pretension and contact finish hooks: pressure_distribution or free_shape,
 * not both; with a measured shape, tangential_force left at its default
 * (the fit gives it); the table's values (rd_free_table_validate). */
int rd_free_shape_finish(const struct rd_scene *s, rd_error *err);
/* The ring a free-shape analysis solves: `ring` (the scene's, a general
 * section's torsion solved) and the scene's pressure, or
 * with a measured free shape the fitted F_t and pressure (rd_free_shape_fit
 * with RD_FREE_FIT_SEGMENTS segments, and half as many for its error). */
#define RD_FREE_FIT_SEGMENTS 160
typedef struct rd_free_run {
    rd_ring_params ring;
    const rd_free_shape *free_shape; /* NULL: the stress-free closed ring */
    int fitted, points;              /* points: the table's */
    rd_free_fit fit;
} rd_free_run;
int rd_free_run_prepare(const struct rd_scene *s, const rd_ring_params *ring,
                        const rd_static_opts *so, const rd_monitor *mon, rd_free_run *r,
                        rd_error *err);
/* The result's "free_shape_fit" (null without a measured shape) added to
 * out; nonzero on out of memory. */
int rd_free_run_result(struct json_t *out, const rd_free_run *r);

/* ---- shared blocks (rd_blocks.c), referenced by the analyses ---- */
/* Monotonic wall clock, s: what a runner reports as numerics.wall_s. */
double rd_clock_s(void);
extern const rd_block rd_block_ring;      /* /ring, with /ring/material */
extern const rd_block rd_block_ring_face; /* the same with /ring/face (lift) */
/* /ring/face into the scene's face (its table borrowed), refused unless the
 * friction model is lubricated. */
int rd_scene_face_finish(struct rd_scene *s, int lubricated, rd_error *err);
/* The lubricated model's oil and asperity blocks (their offsets into the
 * scene's `lube`, struct rd_lube_scene); an analysis that offers the model
 * puts RD_LUBE_FRICTION_FIELDS in its friction block, RD_BORE_ROUGHNESS_FIELD
 * in its bore block, fills s->lube's defaults (rd_lube_params_default) and
 * finishes with rd_scene_lube_finish. */
extern const rd_block rd_block_oil, rd_block_asperity;
int rd_supply_parse(const rd_field *f, struct json_t *v, const char *path, struct rd_scene *s,
                    rd_error *err);
struct json_t *rd_supply_echo(const struct rd_scene *s);
#define RD_SUPPLY_SCHEMA                                                                         \
    "{\"oneOf\": [{\"type\": \"string\", \"enum\": [\"flooded\"]}, {\"type\": \"object\", "      \
    "\"required\": [\"film_m\"], \"additionalProperties\": false, \"properties\": {\"film_m\": " \
    "{\"type\": \"number\", \"minimum\": 1e-8, \"maximum\": 1e-3, \"description\": \"The oil "   \
    "film "                                                                                      \
    "on the liner ahead of the ring, m.\"}}}], \"default\": \"flooded\"}"
extern const char *const rd_cavitation_names[]; /* enum rd_cavitation */
#define RD_LUBE_FRICTION_FIELDS                                                                  \
    {"oil", RD_F_OPTBLOCK, offsetof(struct rd_scene, lube.oil_given), .in_scene = 1,             \
     .block = &rd_block_oil},                                                                    \
        {"cavitation",                                                                           \
         RD_F_CHOICE,                                                                            \
         offsetof(struct rd_scene, lube.lube.cavitation),                                        \
         .in_scene = 1,                                                                          \
         .choices = rd_cavitation_names,                                                         \
         .desc = "Where the film ruptures: \"reynolds\" (default; Swift-Stieber: p >= 0, the "   \
                 "flow lost downstream of a rupture) or \"jfo\" (mass-conserving, "              \
                 "Jakobsson-Floberg-Olsson in Elrod-Adams' form: a cavity's oil carried by the " \
                 "liner and kept from one instant to the next, the film reforming where its "    \
                 "flow meets it, e.g. before an outlet edge under gas pressure). Read by the "   \
                 "lubricated model only."},                                                      \
        {"supply",                                                                               \
         RD_F_CUSTOM,                                                                            \
         offsetof(struct rd_scene, lube.lube.supply_film),                                       \
         .in_scene = 1,                                                                          \
         .parse = rd_supply_parse,                                                               \
         .echo = rd_supply_echo,                                                                 \
         .extra = RD_SUPPLY_SCHEMA,                                                              \
         .desc = "The oil the face is fed: \"flooded\" (default: as much as it takes in) or "    \
                 "{\"film_m\": h_s}, the oil film on the liner ahead of the ring (1e-8 to 1e-3 " \
                 "m): where the face would take in more than U h_s, its inlet is starved (a "    \
                 "meniscus inside the face, dry ahead of it; less than half the thinnest gap: "  \
                 "the face runs dry, on its asperities). Read by the lubricated model only."},   \
    {                                                                                            \
        "asperity", RD_F_OPTBLOCK, offsetof(struct rd_scene, lube.asperity_given),               \
            .in_scene = 1, .block = &rd_block_asperity                                           \
    }
#define RD_BORE_ROUGHNESS_FIELD                                                               \
    {                                                                                         \
        "roughness_rq_m", RD_F_NUMBER, offsetof(struct rd_scene, lube.bore_rq),               \
            .in_scene = 1, RD_MIN(1e-9), RD_MAX(5e-6),                                        \
            .desc = "The liner's Rq, m; read by the lubricated friction model only. Default " \
                    "0.2 um."                                                                 \
    }
/* The scene's oil, asperities and liner roughness into core's (the
 * temperature table borrowed), each refused by name unless `lubricated`. */
int rd_scene_lube_finish(struct rd_scene *s, int lubricated, rd_lube_params *lube, double *liner_rq,
                         rd_error *err);
/* A face field its profile does not read, refused (at prefix/face/...). */
int rd_face_unread(const rd_face_params *fp, const char *prefix, rd_error *err);
extern const rd_block rd_block_discretization_modal;  /* 3..2000 segments, closed allowed */
extern const rd_block rd_block_discretization_static; /* 4..2000, split ring */
extern const rd_block rd_block_discretization_lift;   /* 4..1000, split ring */
extern const rd_block rd_block_static_numerics;       /* Newton, in struct rd_static_scene */
extern const rd_block rd_block_contact_numerics;      /* the same + the accuracy target */
/* One Fourier term of a lift-model bore's distortion (an item of an
 * RD_F_DISTORTION field): lift's /bore/distortion and the ring pack's. */
extern const rd_block rd_block_lift_distortion;

/* The options of pretension and contact (their opts): the static numerics
 * block is shared, so both keep it at the same place. */
#include "rd_bore_map.h"
#include "rd_static.h"
/* The contact analysis' bore map (rd_contact_map.c): /bore/layers,
 * /bore/points and /contact/height as given, and the map they make. */
struct rd_contact_map_scene {
    int layers_given, points_given, height_given; /* present in the scene */
    struct rd_table points[3];                    /* theta_deg, z, dr */
    int fit_order;                                /* /bore/points/fit_order */
    int height_all;                               /* /contact/height "all" */
    double height;                                /* /contact/height, m */
    rd_bore_map *map;                             /* the layers or the points' fit; owned */
    rd_bore at;                                   /* the bore at `height` (finish) */
};
struct rd_static_scene {
    rd_static_opts statics;          /* /numerics */
    rd_pretension_opts pretension;   /* /pretension */
    rd_contact_opts contact;         /* /bore, /contact */
    struct rd_contact_map_scene map; /* /bore/layers, /bore/points, /contact/height */
};
/* Their common defaults (the error estimate on, as the API promises). */
void rd_static_scene_defaults(struct rd_scene *s);
/* Their result's "numerics" ({"segments", ..., "error_method"}; `what` the
 * estimate's method) and "support" objects; NULL on out of memory. */
struct json_t *rd_static_result_numerics(const rd_static_stats *st, double wall_s,
                                         const char *what);
struct json_t *rd_static_result_support(const rd_static_stats *st);

/* ---- engine, bore and friction: what lift and the ring pack share ----
 * Both read /engine (with /engine/piston_tilt), /bore and /physics/friction
 * alike: each field's key, type, storage, range and choices are written
 * once below, and so is its description where the two say the same.  Each
 * analysis writes the rest in its own words (block names and descriptions,
 * the descriptions that differ, the cycles row, friction's further rows).
 * Their opts hold a struct rd_engine_scene named `eng`; in the row macros
 * AT(member) is the analysis' offsetof into its opts, E the path of its
 * rd_engine_params there and F that of its rd_friction_params. */

/* What the scene gives beside core's params (rd_blocks.c turns it into
 * theirs). */
struct rd_engine_scene {
    int tilt_given;                /* /engine/piston_tilt present */
    struct rd_table tilt_table[2]; /* crank_deg, tilt_deg */
    rd_bore bore;                  /* /bore */
    int friction_given;            /* /physics/friction present */
    int friction_model;            /* index into rd_friction_names */
};
extern const char *const rd_kinematics_names[]; /* enum rd_kinematics */
extern const char *const rd_friction_names[];   /* enum rd_friction_model - 1 */

/* A friction field the chosen model (f->model) does not read, given other
 * than the analysis' default (z): RD_EINVAL naming it -- the Coulomb
 * coefficient with the lubricated model (its boundary friction is the
 * asperity block's), Stribeck's three with another model. */
int rd_friction_unread(const rd_friction_params *f, const rd_friction_params *z, rd_error *err);

/* Core's friction model, tilt table (borrowed: both tables, of the same
 * length, else RD_EINVAL at /engine/piston_tilt/tilt_deg) and bore from
 * what the scene gave. */
int rd_engine_scene_finish(const struct rd_engine_scene *es, rd_engine_params *engine,
                           rd_bore *bore, rd_friction_params *friction, rd_error *err);
/* Frees the tilt tables. */
void rd_engine_scene_cleanup(struct rd_engine_scene *es);

/* /engine: speed (its description given), crank radius, rod length,
 * kinematics; then, after the analysis' cycles row, the constant tilt (its
 * description given) and the /engine/piston_tilt block. */
#define RD_ENGINE_CRANK_FIELDS(AT, E, speed_desc)                                                \
    {"speed_rpm", RD_F_NUMBER, AT(E.speed_rpm), RD_MIN(1), RD_MAX(30000), .desc = (speed_desc)}, \
        {"crank_radius", RD_F_NUMBER, AT(E.crank_radius),                                        \
         RD_MIN(0.001),  RD_MAX(1.0), .desc = "Crank radius r (half the stroke), m."},           \
        {"rod_length", RD_F_NUMBER, AT(E.rod_length), RD_MAX(10.0),                              \
         .desc = "Connecting rod length l, m; from r / 0.9 to 10 m."},                           \
    {                                                                                            \
        "kinematics", RD_F_CHOICE, AT(E.kinematics),                                             \
            .choices = rd_kinematics_names,                                                      \
            .desc = "exact slider-crank, or the approximate series (thesis 1.6-1.8)."            \
    }
#define RD_ENGINE_TILT_FIELDS(AT, E, tilt_desc, tilt_block)                      \
    {"piston_tilt_deg", RD_F_NUMBER, AT(E.piston_tilt_deg),                      \
     RD_MIN(-2),        RD_MAX(2),   .desc = (tilt_desc)},                       \
    {                                                                            \
        "piston_tilt", RD_F_OPTBLOCK, AT(eng.tilt_given), .block = &(tilt_block) \
    }
/* /engine/piston_tilt: the two tables. */
#define RD_TILT_FIELDS(AT)                                                                        \
    {"crank_deg",                                                                                 \
     RD_F_TABLE,                                                                                  \
     AT(eng.tilt_table[0]),                                                                       \
     RD_MIN(1),                                                                                   \
     RD_MAX(RD_LIFT_TABLE_MAX),                                                                   \
     .required = 1,                                                                               \
     .desc = "Crank angles, deg, strictly increasing within 0..720."},                            \
    {                                                                                             \
        "tilt_deg", RD_F_TABLE, AT(eng.tilt_table[1]), RD_MIN(1), RD_MAX(RD_LIFT_TABLE_MAX),      \
            .required = 1, .desc = "Piston tilt at those angles, deg (added to piston_tilt_deg)." \
    }
/* /bore: diameter and distortion, their descriptions given. */
#define RD_BORE_FIELDS(AT, diameter_desc, distortion_desc)                                  \
    {"diameter", RD_F_NUMBER, AT(eng.bore.diameter), RD_MIN(0.0), .desc = (diameter_desc)}, \
    {                                                                                       \
        "distortion", RD_F_DISTORTION, AT(eng.bore), .block = &rd_block_lift_distortion,    \
                                                     RD_MAX(RD_BORE_ORDERS_MAX),            \
                                                     .desc = (distortion_desc)              \
    }
/* /physics/friction: model and Coulomb coefficient, descriptions given. */
#define RD_FRICTION_FIELDS(AT, F, model_desc, coefficient_desc)                  \
    {"model", RD_F_CHOICE, AT(eng.friction_model), .choices = rd_friction_names, \
     .desc = (model_desc)},                                                      \
    {                                                                            \
        "coefficient", RD_F_NUMBER, AT(F.coefficient), RD_MIN(0), RD_MAX(10),    \
            .desc = (coefficient_desc)                                           \
    }

/* The fields every scene opens with: analysis (echoed, and its OpenAPI
 * enum written, by rd_scene_echo_analysis), name and description. */
#define RD_SCENE_HEAD                                                         \
    {"analysis", RD_F_ANALYSIS, 0, .echo = rd_scene_echo_analysis,            \
     .desc = "Which analysis to run; decides which blocks are "               \
             "read."},                                                        \
        {"name", RD_F_STRING, offsetof(struct rd_scene, name),                \
         .desc = "Free text, echoed in the result; absent when not given."},  \
    {                                                                         \
        "description", RD_F_STRING, offsetof(struct rd_scene, description),   \
            .desc = "Free text, echoed in the result; absent when not given." \
    }

/* The fields every analysis with a top-level ring reads first: the head,
 * ring and its discretization block.  _WITH adds to the shared ring what
 * this analysis requires of it (a description and a JSON schema, allOf). */
#define RD_SCENE_COMMON_WITH(ring_desc, ring_extra, discretization) \
    RD_SCENE_HEAD, {"ring",                                         \
                    RD_F_BLOCK,                                     \
                    0,                                              \
                    .block = &rd_block_ring,                        \
                    .desc = (ring_desc),                            \
                    .extra = (ring_extra)},                         \
    {                                                               \
        "discretization", RD_F_BLOCK, 0, .block = &(discretization) \
    }
#define RD_SCENE_COMMON(discretization) RD_SCENE_COMMON_WITH(NULL, NULL, discretization)

#endif
