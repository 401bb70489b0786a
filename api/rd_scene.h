/*
 * rd_scene — the scene model of the api layer: what a parsed, type-checked,
 * defaults-filled scene holds, and its echo as JSON.
 *
 * Implements the rd_scene_parse / rd_scene_free / rd_scene_analysis /
 * rd_scene_to_json entry points declared in rd_api.h; this header adds what
 * the other api modules (rd_api.c, rd_result.c, rd_examples.c) need to see.
 * Not for the server: it should only include rd_api.h.
 *
 * Parsing order (the first error wins and is the only one reported):
 *   1. the body is a JSON object (RD_EJSON otherwise, with jansson's
 *      line/column/text);
 *   2. "analysis" names an available analysis;
 *   3. every key the analysis reads is known (typos are errors, not ignored)
 *      and has the right JSON type; blocks the analysis does not read are
 *      ignored entirely;
 *   4. core's validators (rd_ring_validate, rd_modal_validate) check values
 *      and ranges; their errors pass through unchanged.
 */
#ifndef RD_SCENE_H
#define RD_SCENE_H

#include "rd_api.h"
#include "rd_lift.h"
#include "rd_modal.h"
#include "rd_ring.h"
#include "rd_static.h"

struct json_t; /* jansson; api-internal headers use it without including jansson.h */

/* Segment count when the scene gives none: the thesis' compromise (3.3). */
#define RD_SCENE_DEFAULT_SEGMENTS 20

/* Significant digits of the reals in a scene's JSON text: every decimal a
 * person types (up to 15 digits) is written back unchanged, where 17 would
 * turn 0.0765 into 0.076499999999999999. */
#define RD_SCENE_REAL_DIGITS 15

/* Analyses the contract names, available or not (API.md). */
enum rd_analysis {
    RD_ANALYSIS_MODAL = 0,
    RD_ANALYSIS_PRETENSION,
    RD_ANALYSIS_CONTACT,
    RD_ANALYSIS_LIFT
};

struct rd_scene {
    int analysis;        /* enum rd_analysis */
    char *name;          /* optional metadata, NULL when absent; owned */
    char *description;   /* optional metadata, NULL when absent; owned */
    rd_ring_params ring; /* /ring */
    int segments;        /* /discretization/segments */
    int closed;          /* /discretization/closed: 1 joins the gap */
    rd_modal_opts modal; /* /modal: modes, estimate_error */
    rd_static_opts statics;        /* /numerics of pretension and contact */
    rd_pretension_opts pretension; /* /pretension */
    rd_contact_opts contact;       /* /bore, /contact */
    rd_lift_params lift;           /* /engine, /groove, /physics, /contact, /output, /numerics */
    /* lift: which optional physics the scene names, and the gas tables it
     * owns (rd_lift_params.gas borrows them) */
    int friction_given, gas_given;
    int friction_model;            /* index into the "model" choices */
    int max_steps;                 /* /numerics/max_steps (lift) */
    struct rd_table {
        double *v;
        int n;
    } gas_table[4];                /* crank_deg, above, behind, below */
};

/* Name of an analysis ("modal", ...); "unknown" outside the enum. */
const char *rd_scene_analysis_name(int analysis);

/* The echoed scene as a new jansson object (caller owns the reference):
 * analysis, name/description when given, and the blocks the analysis reads
 * with every default filled in.  NULL on out of memory. */
struct json_t *rd_scene_echo(const rd_scene *scene);

/* Parses an already decoded JSON value as a scene (steps 2-4 above; a
 * non-object is RD_EJSON).  `value` is borrowed and not modified (it is not
 * const only because jansson's object iteration takes a mutable json_t).
 * Same contract as rd_scene_parse otherwise. */
int rd_scene_parse_value(struct json_t *value, rd_scene **out, rd_error *err);

#endif
