/*
 * rd_result — results as the contract writes them: the `result` JSON object
 * of each analysis (API.md "Results"), and its main table as CSV.
 *
 * api-internal (rd_api.c uses it); jansson values are passed as
 * struct json_t so this header does not pull in jansson.h.
 */
#ifndef RD_RESULT_H
#define RD_RESULT_H

#include "rd_modal.h"
#include "rd_ring.h"
#include "rd_scene.h"

struct json_t;

/* Significant digits of the reals in a result: well below the model's
 * discretization error (~1e-3) and the solver tolerance, and it keeps the
 * mode shapes of a large ring (60 modes x 4 x 2000 numbers) compact. */
#define RD_RESULT_REAL_DIGITS 10

/* The modal result object:
 *   {"analysis":"modal", "scene":{echo}, "rigid_body_modes",
 *    "segment_angle_deg":[n], "modes":[{"mode", "frequency_hz", "kind",
 *    "in_plane_energy_fraction", "error_estimate", "frequency_extrapolated_hz",
 *    "residual", "shape":{"radial","tangential","axial","twist"}}...],
 *    "numerics":{"segments", "dof", "wall_s", "solver", "iterations",
 *    "block_size", "max_residual", "reference_segments", "error_estimate",
 *    "error_method"}}
 * NaN values (nothing estimated) become null.  `ring` is the model that was
 * solved (segment angles, centroid radius); everything is borrowed.
 * Returns a new reference, or NULL when out of memory. */
struct json_t *rd_result_modal(const rd_scene *scene, const rd_ring *ring,
                               const rd_modal_result *res, double wall_s);

/* The main table of a result object as CSV text (malloc'd, caller frees):
 * a header row whose column names carry their units, one row per entry,
 * reals as %.10g, an empty cell for null.  Dispatches on "analysis"; an
 * analysis without a table is RD_ENOTFOUND, a malformed result RD_EINTERNAL.
 * `result` is borrowed. */
char *rd_result_csv(struct json_t *result, rd_error *err);

#endif
