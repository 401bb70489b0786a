/*
 * rd_an_modal — the modal analysis in the api: scene schema, runner,
 * result object and CSV table (rd_registry.h).
 *
 * Mode shapes: core gives per segment i six components in the segment's
 * local cylindrical frame, shape[6i + 0..2] = radial, tangential, axial
 * translation and shape[6i + 3..5] = rotation about the radial, tangential,
 * axial axes (1/m, the translations being normalized to a largest value of
 * 1).  The result reports the three translations and the twist of the
 * section, rotation about the tangential axis times the centroid radius R,
 * which makes it dimensionless and comparable with the translations.
 */
#include <jansson.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "rd_json.h"
#include "rd_modal.h"
#include "rd_registry.h"
#include "rd_ring.h"
#include "rd_scene.h"

#define PI         3.14159265358979323846
#define AT(member) offsetof(struct rd_scene, member)

/* ---- scene ---------------------------------------------------------------- */

static const rd_field modal_fields[] = {
    {"modes", RD_F_INTEGER, AT(modal.modes), RD_MIN(1), RD_MAX(RD_MODAL_MODES_MAX),
     .desc = "Elastic modes wanted (the six rigid-body modes are not counted); at most 6 n - 6 "
             "for n segments."},
    {"error_estimate", RD_F_BOOL, AT(modal.estimate_error),
     .desc = "Estimate the discretization error by a second solve at 2n segments (n/2 when "
             "2n > 2000) and Richardson extrapolation."},
    {.key = NULL},
};
static const rd_block modal_block = {"ModalOptions", "/modal: what the modal analysis computes.", 0,
                                     0, modal_fields};

static const rd_field scene_fields[] = {
    RD_SCENE_COMMON(rd_block_discretization_modal),
    {"modal", RD_F_BLOCK, 0, .block = &modal_block},
    {.key = NULL},
};
static const rd_block scene_block = {
    "ModalScene",
    "Free-free natural frequencies and mode shapes of the segmented ring (thesis 3.3). Reads "
    "ring, discretization (3..2000 segments; closed allowed) and modal.  The slenderness "
    "n R / min(b, h) x sqrt(max(1, G / E)) (R = (d - b) / 2, G = E / (2 (1 + nu))) may be at "
    "most 3e5 with the error estimate, 3e6 without: beyond it rounding swamps the low modes.",
    0, 0, scene_fields};

static void defaults(struct rd_scene *s)
{
    rd_modal_opts_default(&s->modal);
    s->modal.estimate_error = 1; /* API default, whatever core's is */
}

static int finish(struct rd_scene *s, rd_error *err)
{
    size_t m = rd_error_enter(err, "/modal");
    int rc = rd_modal_validate(&s->modal, s->segments, err);
    rd_error_leave(err, m);
    return rc != RD_OK
               ? rc
               : rd_modal_validate_ring(&s->ring, s->segments, s->modal.estimate_error, err);
}

/* ---- result --------------------------------------------------------------- */

#define SHAPE(m, i, k) ((m)->shape[6 * (i) + (k)])
enum { S_RADIAL = 0, S_TANGENTIAL = 1, S_AXIAL = 2, S_ROT_TANGENTIAL = 4 };

static const char modal_solver[] =
    "shift-invert block Lanczos with explicit rigid-body deflation on banded K, M, in-plane and "
    "out-of-plane parts solved separately where they decouple (LAPACK dpbtrf/dpbtrs, dsbev, dsygv)";

static json_t *mode_shape(const rd_mode *m, int n, double R)
{
    if (!m->shape)
        return json_null();
    return json_pack("{s:o, s:o, s:o, s:o}", "radial",
                     rd_result_reals(&SHAPE(m, 0, S_RADIAL), n, 6, 1.0), "tangential",
                     rd_result_reals(&SHAPE(m, 0, S_TANGENTIAL), n, 6, 1.0), "axial",
                     rd_result_reals(&SHAPE(m, 0, S_AXIAL), n, 6, 1.0), "twist",
                     rd_result_reals(&SHAPE(m, 0, S_ROT_TANGENTIAL), n, 6, R));
}

static json_t *modal_modes(const rd_modal_result *res, int n, double R)
{
    json_t *modes = json_array();
    for (int k = 0; modes && k < res->n_modes; k++) {
        const rd_mode *m = &res->modes[k];
        /* json_pack steals every "o" value, also when it fails. */
        json_t *mode =
            json_pack("{s:i, s:o, s:s, s:o, s:o, s:o, s:o, s:o}", "mode", k + 1, "frequency_hz",
                      rd_result_real(m->frequency_hz), "kind",
                      m->kind == RD_MODE_IN_PLANE ? "in_plane" : "out_of_plane",
                      "in_plane_energy_fraction", rd_result_real(m->in_plane_fraction),
                      "error_estimate", rd_result_real(m->error_estimate),
                      "frequency_extrapolated_hz", rd_result_real(m->frequency_extrapolated_hz),
                      "residual", rd_result_real(m->residual), "shape", mode_shape(m, n, R));
        if (json_array_append_new(modes, mode) != 0) {
            json_decref(modes);
            modes = NULL;
        }
    }
    return modes;
}

static json_t *modal_numerics(const rd_modal_result *res, double wall_s)
{
    char method[128];
    int estimated = res->reference_segments > 0;
    snprintf(method, sizeof method,
             "Richardson extrapolation from a second solve at %d segments, convergence order 2",
             res->reference_segments);
    return json_pack("{s:i, s:i, s:o, s:s, s:i, s:i, s:o, s:o, s:o, s:o}", "segments",
                     res->segments, "dof", res->dof, "wall_s", rd_result_real(wall_s), "solver",
                     modal_solver, "iterations", res->iterations, "block_size", res->block_size,
                     "max_residual", rd_result_real(res->max_residual), "reference_segments",
                     estimated ? json_integer(res->reference_segments) : json_null(),
                     "error_estimate", rd_result_real(res->error_estimate), "error_method",
                     estimated ? json_string(method) : json_null());
}

/* The result object (API.md "Results", rd_api.h); `ring` is the model that
 * was solved (segment angles, centroid radius). */
static json_t *modal_result(const rd_scene *scene, const rd_ring *ring, const rd_modal_result *res,
                            double wall_s)
{
    int n = rd_ring_get_segments(ring);
    double R = rd_ring_get_section(ring)->R;

    json_t *angles = json_array();
    for (int i = 0; angles && i < n; i++) {
        double deg = rd_ring_get_segment_angle(ring, i) * 180.0 / PI;
        if (json_array_append_new(angles, json_real(deg)) != 0) {
            json_decref(angles);
            angles = NULL;
        }
    }
    return json_pack("{s:s, s:o, s:i, s:o, s:o, s:o}", "analysis", rd_scene_analysis(scene),
                     "scene", rd_scene_echo(scene), "rigid_body_modes", res->rigid_body_modes,
                     "segment_angle_deg", angles, "modes", modal_modes(res, n, R), "numerics",
                     modal_numerics(res, wall_s));
}

/* The ring model (for the segment angles and R) and the eigen-solve with
 * its error estimate; wall_s times the solve alone. */
static int run(const rd_scene *s, const rd_monitor *mon, json_t **out, rd_error *err)
{
    rd_ring *ring = NULL;
    rd_modal_result res;
    rd_error ring_err;
    int rc;

    memset(&res, 0, sizeof res);
    rd_error_init(&ring_err);
    ring = rd_ring_create(&s->ring, s->segments, s->closed, &ring_err);
    if (!ring) {
        rc = rd_error_set(err, ring_err.code != RD_OK ? ring_err.code : RD_EINTERNAL, ring_err.path,
                          "%s", ring_err.message);
        goto out;
    }
    double t0 = rd_clock_s();
    rc = rd_modal_solve(&s->ring, s->segments, s->closed, &s->modal, mon, &res, err);
    if (rc == RD_OK)
        *out = modal_result(s, ring, &res, rd_clock_s() - t0);
out:
    rd_modal_result_cleanup(&res);
    rd_ring_free(ring);
    return rc;
}

static double predict(const rd_scene *s)
{
    return rd_modal_cost_predict(&s->modal, s->segments, s->closed);
}

/* mode,kind,frequency_hz,error_estimate,frequency_extrapolated_hz,
 * in_plane_energy_fraction: one row per mode. */
static const rd_csv_column csv_columns[] = {
    {"mode", "mode", 0},
    {"kind", "kind", 1},
    {"frequency_hz", "frequency_hz", 0},
    {"error_estimate", "error_estimate", 0},
    {"frequency_extrapolated_hz", "frequency_extrapolated_hz", 0},
    {"in_plane_energy_fraction", "in_plane_energy_fraction", 0},
    {NULL, NULL, 0},
};
static const rd_csv_table csv = {NULL, "modes", csv_columns};

static const char *const result_keys[] = {"analysis",          "scene", "rigid_body_modes",
                                          "segment_angle_deg", "modes", "numerics",
                                          "warnings",          NULL};

const rd_analysis_def rd_an_modal = {
    .name = "modal",
    .scene = &scene_block,
    .opts_size = 0,
    .defaults = defaults,
    .finish = finish,
    .run = run,
    .predict = predict,
    .csv = &csv,
    .page = "modal.js",
    .result_keys = result_keys,
};
