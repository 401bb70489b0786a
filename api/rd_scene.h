/*
 * rd_scene — the scene model of the api layer: what a parsed, type-checked,
 * defaults-filled scene holds, and its echo as JSON.
 *
 * Implements the rd_scene_parse / rd_scene_free / rd_scene_run entry
 * points declared in rd_api.h (rd_scene.c), and rd_scene_analysis /
 * rd_scene_to_json with the echo (rd_scene_echo.c, below the registry: the
 * runners call it); this header adds what the other api modules need to
 * see.  Not for the server: it should only include rd_api.h.
 *
 * Parsing order (the first error wins and is `error`; rd_scene_parse_issues
 * also lists every problem the tables find, the "errors" of the answer):
 *   1. the body is a JSON object (RD_EJSON otherwise, with jansson's
 *      line/column/text);
 *   2. "analysis" names an analysis of the registry (rd_registry.h);
 *   3. a top-level block the analysis does not read (one other analyses
 *      read, or one its registry entry says it reads elsewhere) is refused,
 *      naming the block and the analysis; every other key is known (typos
 *      are errors, not ignored) and has the right JSON type (rd_schema.h);
 *   4. the analysis' finish hook runs core's validators (rd_ring_validate,
 *      rd_modal_validate, ...); their errors pass through unchanged.
 */
#ifndef RD_SCENE_H
#define RD_SCENE_H

#include "rd_api.h"
#include "rd_liner.h"
#include "rd_modal.h"
#include "rd_ring.h"
#include "rd_static.h"

struct json_t; /* jansson; api-internal headers use it without including jansson.h */
struct rd_analysis_def;

/* Segment count when the scene gives none: the thesis' compromise (3.3). */
#define RD_SCENE_DEFAULT_SEGMENTS 20

/* Significant digits of the reals in a scene's JSON text: every decimal a
 * person types (up to 15 digits) is written back unchanged, where 17 would
 * turn 0.0765 into 0.076499999999999999.  A scene with a real that 15
 * digits do not give back exactly is echoed with 17 (rd_scene_to_json). */
#define RD_SCENE_REAL_DIGITS 15

/* The analyses of the built-in registry, by index (rd_registry.c keeps
 * this order). */
enum rd_analysis {
    RD_ANALYSIS_MODAL = 0,
    RD_ANALYSIS_PRETENSION,
    RD_ANALYSIS_CONTACT,
    RD_ANALYSIS_LIFT,
    RD_ANALYSIS_RINGPACK,
    RD_ANALYSIS_CALIBRATION,
    RD_ANALYSIS_SENSITIVITY
};

/* An array of numbers read from the scene (malloc'd). */
struct rd_table {
    double *v;
    int n;
};

/* What a study (an analysis that runs other scenes, rd_study.h) needs of
 * this module, handed down in every scene: the analyses stay below
 * rd_scene.c, which lists them, with no circle of calls through the
 * registry (tests/lint/layers.py). */
struct rd_scene_ops {
    int (*parse_value)(struct json_t *value, rd_scene **out, rd_error *err);
    void (*free)(rd_scene *scene);
};

struct rd_scene {
    int analysis;                     /* index into the registry it was parsed with */
    const struct rd_scene_ops *ops;   /* rd_scene_parse_value and rd_scene_free */
    const struct rd_analysis_def *an; /* that registry entry */
    char *name;                       /* optional metadata, NULL when absent; owned */
    char *description;                /* optional metadata, NULL when absent; owned */
    rd_ring_params ring;              /* /ring */
    rd_free_shape free_shape;         /* /ring/pressure_distribution (RD_FREE_CLOSED: absent) */
    rd_free_table free_table;         /* /ring/free_shape (n_points 0: absent) */
    /* /ring/face (the analyses whose ring block is rd_block_ring_face): the
     * running face's profile and roughness; face_given 1 when named */
    rd_face_params face;
    int face_given, face_table_given;
    struct rd_table face_table[2]; /* x_m, drop_m */
    /* /physics/friction/oil and /asperity, /bore/roughness_rq_m: the
     * lubricated model's oil, rough contact and liner (the analyses that
     * offer it: rd_block_oil, rd_block_asperity, rd_scene_lube_finish) */
    struct rd_lube_scene {
        rd_lube_params lube;
        int vogel_given, temp_table_given, oil_given, asperity_given;
        struct rd_table temp_table[2]; /* crank_deg, value_c */
        double bore_rq;                /* the liner's Rq, m */
    } lube;
    int segments;             /* /discretization/segments */
    int closed;               /* /discretization/closed: 1 joins the gap */
    rd_modal_opts modal;      /* /modal: the modal analysis' options (a member, not
                            in opts, because callers and tests read it here) */
    void *opts;               /* the analysis' own options (an->opts_size bytes,
                            owned; an->cleanup frees what it holds) */
    struct rd_issues *issues; /* while parsing: where every problem is listed
                                 (rd_schema_parse), or NULL; NULL afterwards */
};

/* Name of an analysis of the built-in registry ("modal", ...); "unknown"
 * outside it. */
const char *rd_scene_analysis_name(int analysis);

/* The scene's analysis name as a JSON string (new reference, NULL on out
 * of memory): the echo of the "analysis" field (RD_SCENE_HEAD). */
struct json_t *rd_scene_echo_analysis(const rd_scene *scene);

/* The echoed scene as a new jansson object (caller owns the reference):
 * analysis, name/description when given, and the blocks the analysis reads
 * with every default filled in.  NULL on out of memory. */
struct json_t *rd_scene_echo(const rd_scene *scene);

/* The digits a scene's reals are written with: RD_SCENE_REAL_DIGITS, or
 * 17 when one of the reals of `v` would not read back from 15. */
int rd_scene_real_digits(struct json_t *v);

/* Parses an already decoded JSON value as a scene (steps 2-4 above; a
 * non-object is RD_EJSON).  `value` is borrowed and not modified (it is not
 * const only because jansson's object iteration takes a mutable json_t).
 * Same contract as rd_scene_parse otherwise. */
int rd_scene_parse_value(struct json_t *value, rd_scene **out, rd_error *err);

/* rd_scene_parse_value against another registry (NULL-ended array of
 * analyses): how tests try an analysis that is not built in. */
int rd_scene_parse_with(const struct rd_analysis_def *const *registry, struct json_t *value,
                        rd_scene **out, rd_error *err);

/* rd_scene_parse_with that also lists every problem in `issues` (may be
 * NULL; rd_schema.h): the table's findings (types, unknown keys, values
 * outside the static ranges) and core's first validator error, which
 * replaces the table's note on the same field.  Emptied on success. */
struct rd_issues;
int rd_scene_parse_issues(const struct rd_analysis_def *const *registry, struct json_t *value,
                          rd_scene **out, rd_error *err, struct rd_issues *issues);

/* rd_scene_parse with `issues` as above; *root_out (may be NULL) gets the
 * decoded body (a new reference, NULL when it was not JSON). */
int rd_scene_parse_keep(const char *body, size_t len, rd_scene **out, rd_error *err,
                        struct rd_issues *issues, struct json_t **root_out);

/* A scene of analysis `an` holding only defaults (what a scene that names
 * nothing else parses to, before core's checks): the source of the
 * OpenAPI defaults.  NULL when out of memory. */
rd_scene *rd_scene_defaults(const struct rd_analysis_def *an);

#endif
