/*
 * rd_scene_facts — what a job service needs to know of a parsed scene
 * before it runs: its name, a canonical text that identifies its result,
 * and the predicted cost of running it.
 *
 * The canonical text is the echoed scene (rd_scene_echo: defaults filled,
 * only the blocks the analysis reads) written with sorted keys, compact, and
 * every real in its shortest round-trip text (rd_dtoa), so two scenes that
 * run the same computation (whatever their key order, spacing, omitted
 * defaults or spelling of numbers: 2e11 or 200000000000.0) give the same
 * bytes, and
 * scenes that differ in any value the run reads give different bytes.  The
 * name and description are part of it (the result echoes them).
 */
#ifndef RD_SCENE_FACTS_H
#define RD_SCENE_FACTS_H

#include "rd_api.h"

/* The scene's "name", or NULL when it has none.  Lives as long as the scene. */
const char *rd_scene_name(const rd_scene *scene);

/* The canonical text above; malloc'd, NULL when out of memory. */
char *rd_scene_canonical_json(const rd_scene *scene);

/* Predicted CPU seconds of rd_scene_run (its analysis' predict hook, core's
 * cost model), or NAN when the analysis has none (every analysis but modal
 * today). */
double rd_scene_cost_predict(const rd_scene *scene);

#endif
