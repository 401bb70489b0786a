/*
 * rd_result — results as the contract writes them: the `result` JSON object
 * of each analysis (API.md "Results"), and its main table as CSV.
 *
 * api-internal (rd_api.c uses it); jansson values are passed as
 * struct json_t so this header does not pull in jansson.h.
 */
#ifndef RD_RESULT_H
#define RD_RESULT_H

#include "rd_lift.h"
#include "rd_modal.h"
#include "rd_ring.h"
#include "rd_scene.h"
#include "rd_static.h"

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

/* The static results (rd_static.h):
 *   pretension: {"analysis", "scene", "gap_opening_inner", "lateral_opening",
 *     "gap_opening_neutral", "free_gap_formula", "conformability",
 *     "support":{"force_n","moment_nm"}, "shape":{"angle_deg","x","y","z",
 *     "reference_x","reference_y"} (n + 2 points), "numerics"}
 *   contact: {"analysis", "scene", "angle_deg", "pressure_pa", "clearance",
 *     "bore_radius" (n each, per segment), "mean_pressure_pa",
 *     "uniform_pressure_pa", "contact_fraction", "max_clearance",
 *     "max_clearance_angle_deg", "max_penetration", "contact_stiffness",
 *     "conformability", "distortion":[{"order","amplitude","phase_deg",
 *     "conformability_bound"}], "support":{...}, "numerics"}
 * with numerics {"segments","dof","wall_s","solver","load_steps",
 * "iterations","residual","tolerance","strain_energy","reference_segments",
 * "error_estimate","error_method"}. */
struct json_t *rd_result_pretension(const rd_scene *scene, const rd_pretension_result *res,
                                     double wall_s);
struct json_t *rd_result_contact(const rd_scene *scene, const rd_contact_result *res,
                                 double wall_s);

/* The lift result (rd_lift.h): {"analysis", "scene", "crank_deg", "lift",
 * "lift_min", "lift_max", "lift_segments" (samples x n), "twist_rad",
 * "friction_force", "flank", "events":[{"crank_deg","event"}], "numerics":
 * {"segments","dof","wall_s","solver","steps","rhs_evals","jac_evals",
 * "linear_setups","nonlinear_iterations","nonlinear_failures",
 * "error_test_fails","root_evals","rtol","atol","error_estimate",
 * "event_error_deg","error_method"}}. */
struct json_t *rd_result_lift(const rd_scene *scene, const rd_lift_result *res, double wall_s);

/* The main table of a result object as CSV text (malloc'd, caller frees):
 * a header row whose column names carry their units, one row per entry,
 * reals as %.10g, an empty cell for null.  Dispatches on "analysis"; an
 * analysis without a table is RD_ENOTFOUND, a malformed result RD_EINTERNAL.
 * `result` is borrowed. */
char *rd_result_csv(struct json_t *result, rd_error *err);

#endif
