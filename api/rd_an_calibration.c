/*
 * rd_an_calibration — fitting a scene's uncertain inputs to measurements
 * (issue 42): the calibration analysis in the api (rd_registry.h).
 *
 * A calibration names a base scene, the parameters to fit (JSON Pointers
 * into it with bounds), and measurements: each a variation of the base
 * ("set": pointer -> JSON value), a pointer into its result ("observe": a
 * number or an array of numbers) and the measured value(s) with their
 * standard deviation(s).  The fit minimises
 *     chi^2 = sum over measurements j and their values i of
 *             ((model_ji(x) - value_ji) / sigma_ji)^2
 * with rd_fit (GSL's Levenberg-Marquardt within bounds, core/include/rd_fit.h);
 * each evaluation runs the M variations at once (rd_study.h: threads).
 */
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_calibration.h"
#include "rd_fit.h"
#include "rd_json.h"
#include "rd_jsonptr.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_study.h"

#define CO(member) offsetof(struct rd_calibration, member)

static const rd_field numerics_fields[] = {
    {"max_runs", RD_F_INTEGER, CO(max_runs), RD_MIN(3), RD_MAX(100000),
     .desc = "Scene runs the fit may use (every measurement of every evaluation is one run; a "
             "Jacobian of p parameters costs p evaluations); default 2000. A fit that needs more "
             "stops with converged false and says so."},
    {"threads", RD_F_INTEGER, CO(threads), RD_MIN(0), RD_MAX(RD_STUDY_THREADS_MAX),
     .desc = "Runs at once; 0 (default) = the machine's processors."},
    {.key = NULL},
};
static const rd_block numerics_block = {
    "CalibrationNumerics", "/numerics (calibration): the fit's budget and parallel runs.", 1, 0,
    numerics_fields};

/* Stores a deep copy of the given value (checked in finish). */

static int parse_base(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    struct rd_calibration *c = s->opts;
    (void)f;
    return rd_study_keep(&c->base_json, &c->base_given, v, path, err);
}

static int parse_parameters(const rd_field *f, json_t *v, const char *path, rd_scene *s,
                            rd_error *err)
{
    struct rd_calibration *c = s->opts;
    (void)f;
    return rd_study_keep(&c->params_json, &c->params_given, v, path, err);
}

static int parse_measurements(const rd_field *f, json_t *v, const char *path, rd_scene *s,
                              rd_error *err)
{
    struct rd_calibration *c = s->opts;
    (void)f;
    return rd_study_keep(&c->meas_json, &c->meas_given, v, path, err);
}

static json_t *echo_base(const rd_scene *s)
{
    return rd_study_echo(((struct rd_calibration *)s->opts)->base_json);
}
static json_t *echo_parameters(const rd_scene *s)
{
    return rd_calibration_echo_parameters(s->opts);
}
static json_t *echo_measurements(const rd_scene *s)
{
    return rd_study_echo(((struct rd_calibration *)s->opts)->meas_json);
}

static const rd_field scene_fields[] = {
    RD_SCENE_HEAD,
    {"base", RD_F_CUSTOM, CO(base_given), .required = 1, .parse = parse_base, .echo = echo_base,
     .extra = "{\"type\": \"object\"}",
     .desc = "The scene the measurements vary (any analysis but a study); its own schema is "
             "the Scene's."},
    {"parameters", RD_F_CUSTOM, CO(params_given), .required = 1, .parse = parse_parameters,
     .echo = echo_parameters,
     .extra = "{\"type\": \"array\", \"minItems\": 1, \"maxItems\": 16, \"items\": {\"type\": "
              "\"object\", \"required\": [\"path\", \"min\", \"max\"], \"additionalProperties\": "
              "false, \"properties\": {\"path\": {\"type\": \"string\"}, \"min\": {\"type\": "
              "\"number\"}, \"max\": {\"type\": \"number\"}, \"start\": {\"type\": \"number\"}}}}",
     .desc = "What to fit, 1 to 16: {path (a JSON Pointer to a number of the base scene, "
             "defaults included), min < max, start (default: the base's value)}."},
    {"measurements", RD_F_CUSTOM, CO(meas_given), .required = 1, .parse = parse_measurements,
     .echo = echo_measurements,
     .extra = "{\"type\": \"array\", \"minItems\": 1, \"maxItems\": 200, \"items\": {\"type\": "
              "\"object\", \"required\": [\"observe\", \"value\", \"sigma\"], "
              "\"additionalProperties\": false, \"properties\": {\"set\": {\"type\": \"object\"}, "
              "\"observe\": {\"type\": \"string\"}, \"value\": {\"oneOf\": [{\"type\": "
              "\"number\"}, {\"type\": \"array\", \"items\": {\"type\": \"number\"}}]}, "
              "\"sigma\": {\"oneOf\": [{\"type\": \"number\"}, {\"type\": \"array\", \"items\": "
              "{\"type\": \"number\"}}]}}}}",
     .desc = "What was measured, 1 to 200: {set (pointer -> value written into the base for this "
             "measurement: speed, load, a pressure table; default none), observe (a pointer into "
             "the result naming a number or an array of numbers), value (the same shape), sigma "
             "(> 0: one for all values or one each)}. The fit needs at least as many values as "
             "parameters."},
    {"numerics", RD_F_BLOCK, 0, .block = &numerics_block},
    {.key = NULL},
};
static const rd_block scene_block = {
    "CalibrationScene",
    "A calibration: the base scene's parameters fitted to measurements by weighted least squares "
    "(POST /api/v1/calibrations).",
    0, 0, scene_fields};

static void defaults(rd_scene *s)
{
    struct rd_calibration *c = s->opts;
    c->max_runs = 2000;
}

static int finish(rd_scene *s, rd_error *err)
{
    return rd_calibration_check(s->opts, s->ops, err);
}

static void cleanup(void *opts)
{
    rd_calibration_cleanup(opts);
}

static int run(const rd_scene *s, const rd_monitor *mon, json_t **result, rd_error *err)
{
    double t0 = rd_clock_s();
    int rc = rd_calibration_run(s->opts, mon, result, err);
    if (rc == RD_OK && *result) {
        json_t *echo = rd_scene_echo(s);
        json_t *num = json_object_get(*result, "numerics");
        if (!echo || json_object_set_new(*result, "scene", echo) != 0 ||
            json_object_set_new(num, "wall_s", rd_result_real(rd_clock_s() - t0)) != 0) {
            json_decref(*result);
            *result = NULL;
        }
    }
    return rc;
}

static const char *const result_keys[] = {
    "analysis", "scene",    "parameters", "correlation", "residuals",    "measurements",
    "chi2",     "dof",      "converged",  "stop",        "identifiable", "runs",
    "notes",    "numerics", "warnings",   NULL};

const rd_analysis_def rd_an_calibration = {
    .name = "calibration",
    .scene = &scene_block,
    .opts_size = sizeof(struct rd_calibration),
    .defaults = defaults,
    .finish = finish,
    .cleanup = cleanup,
    .run = run,
    .csv_none = "a calibration's result is a few fitted values with their uncertainty, not a "
                "table; its measurements' fitted values are in result.measurements",
    .page = "none",
    .result_keys = result_keys,
};
