/*
 * rd_an_sensitivity — d(output)/d(parameter) of a scene by central
 * differences (issue 42 item 2): the sensitivity analysis in the api
 * (rd_registry.h).  The base runs first; each parameter x_j is then moved
 * by +-h_j and +-2 h_j (4 runs each, all at once on threads):
 *     D(h)  = (f(x + h) - f(x - h)) / (2 h),
 *     error = |D(h) - D(2h)| / 3          (the O(h^2) truncation, Richardson)
 *           + 2 e / (2 h)                 (the outputs' own error e at +-h)
 * h_j = the given step, else max(eps^(1/3), 1e-4) |x_j|, eps the outputs'
 * relative run-to-run noise (noise_of), the step that balances the two
 * error terms.  A derivative not above its error is flagged (significant
 * false).
 */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_study.h"

#define SO(member)  offsetof(struct sens, member)
#define PARAMS_MAX  16
#define OUTPUTS_MAX 32

struct sens {
    int base_given, params_given, outputs_given;
    json_t *base_json, *params_json, *outputs_json; /* as given (owned) */
    int threads;
    rd_study_base base;
    size_t np, no;
    const char *path[PARAMS_MAX], *output[OUTPUTS_MAX];
    double x[PARAMS_MAX]; /* the parameters' values in the base */
    double h[PARAMS_MAX]; /* their steps, given or chosen (finish) */
    double eps;           /* the outputs' relative run-to-run noise (noise_of) */
    const char *eps_from; /* how eps was taken, for the note */
};

#define ERR(path, ...) rd_error_set(err, RD_EREQUEST, path, __VA_ARGS__)

static int parse_base(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    struct sens *o = s->opts;
    (void)f;
    return rd_study_keep(&o->base_json, &o->base_given, v, path, err);
}
static int parse_params(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    struct sens *o = s->opts;
    (void)f;
    return rd_study_keep(&o->params_json, &o->params_given, v, path, err);
}
static int parse_outputs(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    struct sens *o = s->opts;
    (void)f;
    return rd_study_keep(&o->outputs_json, &o->outputs_given, v, path, err);
}
static json_t *echo_base(const rd_scene *s)
{
    return rd_study_echo(((struct sens *)s->opts)->base_json);
}
static json_t *echo_params(const rd_scene *s)
{
    return rd_study_echo(((struct sens *)s->opts)->params_json);
}
static json_t *echo_outputs(const rd_scene *s)
{
    return rd_study_echo(((struct sens *)s->opts)->outputs_json);
}

static const rd_field numerics_fields[] = {
    {"threads", RD_F_INTEGER, SO(threads), RD_MIN(0), RD_MAX(RD_STUDY_THREADS_MAX),
     .desc = "Runs at once; 0 (default) = the machine's processors."},
    {.key = NULL},
};
static const rd_block numerics_block = {
    "SensitivityNumerics", "/numerics (sensitivity): parallel runs.", 1, 0, numerics_fields};

static const rd_field scene_fields[] = {
    RD_SCENE_HEAD,
    {"base", RD_F_CUSTOM, SO(base_given), .required = 1, .parse = parse_base, .echo = echo_base,
     .extra = "{\"type\": \"object\"}",
     .desc = "The scene whose outputs are differentiated (any analysis but a study)."},
    {"parameters", RD_F_CUSTOM, SO(params_given), .required = 1, .parse = parse_params,
     .echo = echo_params,
     .extra = "{\"type\": \"array\", \"minItems\": 1, \"maxItems\": 16, \"items\": {\"type\": "
              "\"object\", \"required\": [\"path\"], \"additionalProperties\": false, "
              "\"properties\": {\"path\": {\"type\": \"string\"}, \"step\": {\"type\": "
              "\"number\", \"exclusiveMinimum\": true, \"minimum\": 0}}}}",
     .desc = "1 to 16 {path (a JSON Pointer to a number of the base, defaults included), step "
             "(> 0, in the parameter's unit; default: chosen from its value and the outputs' "
             "error estimate, and needed where the value is 0)}."},
    {"outputs", RD_F_CUSTOM, SO(outputs_given), .required = 1, .parse = parse_outputs,
     .echo = echo_outputs,
     .extra = "{\"type\": \"array\", \"minItems\": 1, \"maxItems\": 32, \"items\": {\"type\": "
              "\"string\"}}",
     .desc = "1 to 32 JSON Pointers into the base's result, each naming one number."},
    {"numerics", RD_F_BLOCK, 0, .block = &numerics_block},
    {.key = NULL},
};
static const rd_block scene_block = {
    "SensitivityScene",
    "A sensitivity: d(output)/d(parameter) of the base scene by central differences, with the "
    "error of each derivative.",
    0, 0, scene_fields};

/* eps: the relative noise of the base's outputs from run to run — 10 times
 * its solver tolerance (numerics rtol, else tolerance), else 1e-12 (a direct
 * solver).  Not its error estimate: a discretisation error is smooth in the
 * parameters and cancels in a difference. */
static double noise_of(const rd_study_base *b, const char **from)
{
    json_t *num = json_object_get(b->echo, "numerics");
    json_t *t = json_object_get(num, "rtol");
    *from = "10 numerics.rtol";
    if (!json_is_number(t)) {
        t = json_object_get(num, "tolerance");
        *from = "10 numerics.tolerance";
    }
    if (json_is_number(t) && json_number_value(t) > 0)
        return 10 * json_number_value(t);
    *from = "1e-12 (a direct solver)";
    return 1e-12;
}

static int check_param(struct sens *o, size_t j, rd_error *err)
{
    json_t *item = json_array_get(o->params_json, j);
    char at[64], path[96];
    snprintf(at, sizeof at, "/parameters/%zu", j);
    snprintf(path, sizeof path, "%s/path", at);
    const char *key;
    json_t *v;
    if (!json_is_object(item))
        return ERR(at, "%s must be an object {path, step}", at);
    json_object_foreach(item, key, v)
    {
        if (strcmp(key, "path") != 0 && strcmp(key, "step") != 0)
            return ERR(at, "%s/%s is not a field of %s (its fields: path, step)", at, key, at);
    }
    o->path[j] = json_string_value(json_object_get(item, "path"));
    int rc = rd_study_number_at(&o->base, o->path[j], path, &o->x[j], err);
    for (size_t k = 0; rc == RD_OK && k < j; k++)
        if (strcmp(o->path[k], o->path[j]) == 0)
            rc = ERR(path, "%s repeats /parameters/%zu/path", path, k);
    if (rc != RD_OK)
        return rc;
    json_t *st = json_object_get(item, "step");
    snprintf(path, sizeof path, "%s/step", at);
    if (st && !(json_is_number(st) && json_number_value(st) > 0 && isfinite(json_number_value(st))))
        return ERR(path, "%s must be a number above 0", path);
    if (!st && o->x[j] == 0)
        return ERR(path, "%s is needed: %s is 0 in the base, so no step follows from its value",
                   path, o->path[j]);
    /* the step that balances truncation (~h^2) and noise (~eps/h) */
    o->h[j] = st ? json_number_value(st) : fmax(cbrt(o->eps), 1e-4) * fabs(o->x[j]);
    /* the farthest points must be scenes the analysis takes */
    double h = o->h[j], far[2] = {o->x[j] - 2 * h, o->x[j] + 2 * h};
    for (int s = 0; s < 2 && rc == RD_OK; s++) {
        char what[160];
        snprintf(what, sizeof what, "%s = %g (the base's value %s twice the step)", o->path[j],
                 far[s], s ? "plus" : "minus");
        rc = rd_study_try(&o->base, NULL, &o->path[j], &far[s], 1, at, what, err);
    }
    return rc;
}

static int finish(rd_scene *s, rd_error *err)
{
    struct sens *o = s->opts;
    if (!o->base_given || !o->params_given || !o->outputs_given)
        return ERR(!o->base_given     ? "/base"
                   : !o->params_given ? "/parameters"
                                      : "/outputs",
                   "a sensitivity needs /base (a scene), /parameters and /outputs");
    int rc =
        rd_error_range(o->threads, 0, RD_STUDY_THREADS_MAX, "/numerics/threads", "threads", err);
    if (rc == RD_OK)
        rc = rd_study_base_parse(o->base_json, s->ops, &o->base, err);
    if (rc != RD_OK)
        return rc;
    o->eps = noise_of(&o->base, &o->eps_from);
    size_t np = json_array_size(o->params_json), no = json_array_size(o->outputs_json);
    if (!json_is_array(o->params_json) || np < 1 || np > PARAMS_MAX)
        return ERR("/parameters", "/parameters must be an array of 1 to %d parameters", PARAMS_MAX);
    if (!json_is_array(o->outputs_json) || no < 1 || no > OUTPUTS_MAX)
        return ERR("/outputs", "/outputs must be an array of 1 to %d JSON Pointers", OUTPUTS_MAX);
    for (o->np = 0; o->np < np && rc == RD_OK; o->np++)
        rc = check_param(o, o->np, err);
    for (o->no = 0; o->no < no && rc == RD_OK; o->no++) {
        char path[64];
        snprintf(path, sizeof path, "/outputs/%zu", o->no);
        o->output[o->no] = json_string_value(json_array_get(o->outputs_json, o->no));
        rc = rd_study_check_observe(&o->base, o->output[o->no], path, err);
    }
    return rc;
}

static void cleanup(void *opts)
{
    struct sens *o = opts;
    rd_study_base_cleanup(&o->base);
    json_decref(o->base_json);
    json_decref(o->params_json);
    json_decref(o->outputs_json);
}

/* Output k of a finished run, or an error naming it. */
static int value_of(const struct sens *o, const rd_study_run *r, size_t k, const char *where,
                    double *v, rd_error *err)
{
    char at[64];
    size_t n = 0;
    snprintf(at, sizeof at, "/outputs/%zu", k);
    if (r->rc != RD_OK)
        return rd_error_set(err, r->rc == RD_ECANCELED ? RD_ECANCELED : r->rc, at,
                            "the run %s failed: %s%s%s", where, r->err.path,
                            r->err.path[0] ? ": " : "", r->err.message);
    if (rd_study_values(r->result, o->output[k], v, 1, &n) != 0 || n != 1)
        return rd_error_set(err, RD_EINVAL, at,
                            "%s = \"%s\" names %s in the result of the run %s, not one number", at,
                            o->output[k], n ? "several numbers" : "no number", where);
    return RD_OK;
}

static json_t *derivative_json(const struct sens *o, size_t j, const double *f, double v,
                               double e_abs, double h)
{
    double d1 = (f[1] - f[0]) / (2 * h), d2 = (f[3] - f[2]) / (4 * h);
    double err = fabs(d1 - d2) / 3 + e_abs / h;
    return json_pack(
        "{s:s, s:f, s:f, s:o, s:o, s:o, s:b}", "path", o->path[j], "at", o->x[j], "step", h,
        "derivative", rd_result_real(d1), "error_estimate", rd_result_real(err), "elasticity",
        rd_result_real(v != 0 ? d1 * o->x[j] / v : NAN), "significant", fabs(d1) > err);
}

static int run(const rd_scene *s, const rd_monitor *mon, json_t **result, rd_error *err)
{
    const struct sens *o = s->opts;
    double t0 = rd_clock_s(), at[4], base_v[OUTPUTS_MAX];
    size_t nr = 1 + 4 * o->np;
    rd_study_run *runs = calloc(nr, sizeof *runs);
    int rc = runs ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory");
    *result = NULL;
    if (rc == RD_OK) {
        rc = rd_study_scene(&o->base, NULL, NULL, NULL, 0, &runs[0].scene, err);
    }
    if (rc == RD_OK)
        rc = rd_study_run_batch(&o->base, runs, 1, o->threads, mon, 0.0, err);
    for (size_t k = 0; k < o->no && rc == RD_OK; k++)
        rc = value_of(o, &runs[0], k, "of the base", &base_v[k], err);
    for (size_t j = 0; j < o->np && rc == RD_OK; j++) {
        const double mult[4] = {-1, 1, -2, 2};
        for (int q = 0; q < 4 && rc == RD_OK; q++) {
            rd_study_run *r = &runs[1 + 4 * j + (size_t)q];
            at[q] = o->x[j] + mult[q] * o->h[j];
            rc = rd_study_scene(&o->base, NULL, &o->path[j], &at[q], 1, &r->scene, err);
        }
    }
    if (rc == RD_OK)
        rc = rd_study_run_batch(&o->base, runs + 1, nr - 1, o->threads, mon, 1.0 / (double)nr, err);
    json_t *outs = rc == RD_OK ? json_array() : NULL;
    for (size_t k = 0; outs && k < o->no && rc == RD_OK; k++) {
        json_t *ds = json_array();
        for (size_t j = 0; j < o->np && rc == RD_OK; j++) {
            double f[4];
            for (int q = 0; q < 4 && rc == RD_OK; q++) {
                char where[200];
                snprintf(where, sizeof where, "at %s %s %d step", o->path[j],
                         q % 2 ? "plus" : "minus", q < 2 ? 1 : 2);
                rc = value_of(o, &runs[1 + 4 * j + (size_t)q], k, where, &f[q], err);
            }
            if (rc == RD_OK)
                json_array_append_new(
                    ds, derivative_json(o, j, f, base_v[k], o->eps * fabs(base_v[k]), o->h[j]));
        }
        json_array_append_new(outs, json_pack("{s:s, s:f, s:o}", "observe", o->output[k], "value",
                                              base_v[k], "derivatives", ds));
    }
    char note[640];
    snprintf(note, sizeof note,
             "Derivatives of the discretised model by central differences at +-h; each "
             "error_estimate is the truncation |D(h) - D(2h)|/3 (Richardson) plus the outputs' "
             "run-to-run noise over the step, taken as %s = %.3g of each output: a bound, "
             "far above the true error where the runs are more accurate than their tolerance "
             "(a steady state). It does not cover the model's own error (its error estimate) "
             "nor an output that jumps between the steps (a flank change, a regime switch).",
             o->eps_from, o->eps);
    if (rc == RD_OK) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        int threads = o->threads > 0 ? o->threads : cpus > 0 ? (int)cpus : 1;
        *result =
            json_pack("{s:s, s:o, s:o, s:I, s:[s], s:{s:f, s:i}}", "analysis", "sensitivity",
                      "scene", rd_scene_echo(s), "outputs", outs, "runs", (json_int_t)nr, "notes",
                      note, "numerics", "wall_s", rd_clock_s() - t0, "threads", threads);
        outs = NULL;
        if (!*result)
            rc = rd_error_set(err, RD_ENOMEM, "", "out of memory for the result");
    }
    json_decref(outs);
    for (size_t k = 0; runs && k < nr; k++) {
        json_decref(runs[k].scene);
        json_decref(runs[k].result);
    }
    free(runs);
    return rc;
}

static const char *const result_keys[] = {"analysis", "scene",    "outputs",  "runs",
                                          "notes",    "numerics", "warnings", NULL};

const rd_analysis_def rd_an_sensitivity = {
    .name = "sensitivity",
    .scene = &scene_block,
    .opts_size = sizeof(struct sens),
    .finish = finish,
    .cleanup = cleanup,
    .run = run,
    .csv_none = "a sensitivity's result is a few derivatives per output, not a table",
    .page = "none",
    .result_keys = result_keys,
};
