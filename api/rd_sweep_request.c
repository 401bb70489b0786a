/*
 * rd_sweep_request — a POST /api/v1/sweeps body (spec or fidelity request)
 * to a validated sweep, and the row of a point the service stopped
 * (rd_sweep_request.h).
 */
#include "rd_sweep_request.h"

#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#include "rd_jsonptr.h"

#define DUMP_FLAGS (JSON_COMPACT | JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS))

/* Where a generated fidelity spec's parameter came from in the request. */
static const struct {
    const char *param, *field;
} fidelity_fields[] = {{"/discretization/segments", "/segments"},
                       {"/numerics/rtol", "/rtol"},
                       {"/numerics/model", "/models"}};

/* A list of the request (`key`): 1..RD_SWEEP_REQUEST_LIST_MAX numbers (or
 * strings when `strings`), copied into nums / strs.  Returns the count, 0
 * when absent, -1 after setting err. */
static int fidelity_list(json_t *req, const char *key, int strings, double *nums, const char **strs,
                         rd_error *err)
{
    json_t *a = json_object_get(req, key);
    if (!a)
        return 0;
    size_t n = json_is_array(a) ? json_array_size(a) : 0;
    if (n == 0 || n > RD_SWEEP_REQUEST_LIST_MAX) {
        rd_error_set(err, RD_EREQUEST, "", "/%s must be a list of 1 to %d %s.", key,
                     RD_SWEEP_REQUEST_LIST_MAX, strings ? "names" : "numbers");
        snprintf(err->path, sizeof err->path, "/%s", key);
        return -1;
    }
    for (size_t k = 0; k < n; k++) {
        json_t *v = json_array_get(a, k);
        if (strings ? !json_is_string(v) : !json_is_number(v)) {
            rd_error_set(err, RD_EREQUEST, "", "/%s/%zu must be a %s.", key, k,
                         strings ? "string" : "number");
            snprintf(err->path, sizeof err->path, "/%s/%zu", key, k);
            return -1;
        }
        if (strings)
            strs[k] = json_string_value(v);
        else
            nums[k] = json_number_value(v);
    }
    return (int)n;
}

/* Rewrites a path into the generated spec as a path into the request:
 * /base/X -> /fidelity/X, /parameters/k/values/j -> /segments/j etc. */
static void fidelity_error_path(const char *spec_text, rd_error *err)
{
    char path[RD_ERROR_PATH_MAX];
    unsigned k;
    int used = 0;
    if (strncmp(err->path, "/base", 5) == 0 && (err->path[5] == '/' || err->path[5] == '\0')) {
        snprintf(path, sizeof path, "/fidelity%.*s", (int)sizeof path - 10, err->path + 5);
        memcpy(err->path, path, sizeof path);
        return;
    }
    if (sscanf(err->path, "/parameters/%u%n", &k, &used) != 1)
        return;
    json_t *spec = json_loads(spec_text, 0, NULL);
    const char *param = json_string_value(
        json_object_get(json_array_get(json_object_get(spec, "parameters"), k), "path"));
    const char *rest = err->path + used;
    if (strncmp(rest, "/values", 7) == 0)
        rest += 7;
    for (size_t f = 0; param && f < sizeof fidelity_fields / sizeof fidelity_fields[0]; f++)
        if (strcmp(param, fidelity_fields[f].param) == 0) {
            snprintf(path, sizeof path, "%s%.*s", fidelity_fields[f].field, (int)sizeof path - 10,
                     rest);
            memcpy(err->path, path, sizeof path);
        }
    json_decref(spec);
}

/* The fidelity request `req` (an object with "fidelity") to a sweep. */
static int parse_fidelity(json_t *req, size_t max_points, rd_sweep_request *out, rd_error *err)
{
    double segs[RD_SWEEP_REQUEST_LIST_MAX], rtol[RD_SWEEP_REQUEST_LIST_MAX];
    const char *models[RD_SWEEP_REQUEST_LIST_MAX];
    const char *key;
    json_t *v;
    json_object_foreach(req, key, v)
    {
        if (strcmp(key, "fidelity") && strcmp(key, "segments") && strcmp(key, "rtol") &&
            strcmp(key, "models")) {
            rd_error_set(
                err, RD_EREQUEST, "",
                "A fidelity request has no field \"%.60s\"; it takes fidelity (the scene), "
                "segments, rtol and models.",
                key);
            snprintf(err->path, sizeof err->path, "/%.100s", key);
            return RD_EREQUEST;
        }
    }
    json_t *scene = json_object_get(req, "fidelity");
    if (!json_is_object(scene))
        return rd_error_set(err, RD_EREQUEST, "/fidelity",
                            "/fidelity must be the scene (an object) whose speed and accuracy "
                            "are measured.");
    rd_sweep_fidelity_opts o = {0};
    int n;
    if ((n = fidelity_list(req, "segments", 0, segs, NULL, err)) < 0)
        return err->code;
    o.segments = n ? segs : NULL;
    o.n_segments = (size_t)n;
    if ((n = fidelity_list(req, "rtol", 0, rtol, NULL, err)) < 0)
        return err->code;
    o.rtol = n ? rtol : NULL;
    o.n_rtol = (size_t)n;
    if ((n = fidelity_list(req, "models", 1, NULL, models, err)) < 0)
        return err->code;
    o.models = n ? models : NULL;
    o.n_models = (size_t)n;

    char *text = json_dumps(scene, DUMP_FLAGS);
    if (!text)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    rd_error e;
    rd_error_init(&e);
    char *spec = rd_sweep_fidelity_spec(text, strlen(text), &o, &e);
    free(text);
    int rc = spec ? rd_sweep_parse(spec, strlen(spec), max_points, &out->sweep, &e) : e.code;
    if (rc != RD_OK) {
        if (spec)
            fidelity_error_path(spec, &e);
        else if (e.code != RD_ENOMEM) { /* the scene's own error: a path into it */
            char path[RD_ERROR_PATH_MAX];
            snprintf(path, sizeof path, "/fidelity%.*s", (int)sizeof path - 10, e.path);
            memcpy(e.path, path, sizeof path);
            e.code = RD_EREQUEST;
        }
        rc = e.code;
        rd_error_set(err, rc, e.path, "%s", e.message);
    } else {
        out->fidelity = 1;
        json_t *parsed = json_loads(spec, 0, NULL);
        out->n_params = json_array_size(json_object_get(parsed, "parameters"));
        json_decref(parsed);
    }
    free(spec);
    return rc;
}

int rd_sweep_request_parse(const char *body, size_t len, size_t max_points, rd_sweep_request *out,
                           rd_error *err)
{
    memset(out, 0, sizeof *out);
    json_t *req = json_loadb(body, len, JSON_REJECT_DUPLICATES, NULL);
    if (json_is_object(req) && json_object_get(req, "fidelity")) {
        int rc = parse_fidelity(req, max_points, out, err);
        json_decref(req);
        return rc;
    }
    /* A spec (or not JSON at all): rd_sweep_parse judges it and names the problem. */
    int rc = rd_sweep_parse(body, len, max_points, &out->sweep, err);
    if (rc == RD_OK)
        out->n_params = json_array_size(json_object_get(req, "parameters"));
    json_decref(req);
    return rc;
}

void rd_sweep_request_cleanup(rd_sweep_request *req)
{
    rd_sweep_free(req->sweep);
    memset(req, 0, sizeof *req);
}

char *rd_sweep_request_failed_row(const rd_sweep_request *req, size_t i, const rd_error *why,
                                  rd_error *err)
{
    char *scene_text = rd_sweep_point_scene(req->sweep, i, err);
    char *columns_text = scene_text ? rd_sweep_columns_json(req->sweep) : NULL;
    json_t *scene = scene_text ? json_loads(scene_text, 0, NULL) : NULL;
    json_t *columns = columns_text ? json_loads(columns_text, 0, NULL) : NULL;
    json_t *row = json_array();
    size_t ncols = json_array_size(columns);
    char *text = NULL;
    int bad = !scene || !columns || !row || ncols < req->n_params + 2;
    for (size_t k = 0; !bad && k < ncols - 2; k++) {
        json_t *v = NULL;
        if (k < req->n_params)
            bad = rd_jsonptr_lookup(scene, json_string_value(json_array_get(columns, k)), &v) == -2;
        bad = bad || json_array_append_new(row, v ? json_deep_copy(v) : json_null()) != 0;
    }
    if (!bad && json_array_append_new(row, json_string(rd_error_code_name(why->code))) == 0 &&
        json_array_append_new(
            row, json_string(why->message[0] ? why->message : rd_error_summary(why->code))) == 0)
        text = json_dumps(row, DUMP_FLAGS);
    if (!text && scene_text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory at point %zu", i);
    json_decref(row);
    json_decref(columns);
    json_decref(scene);
    free(columns_text);
    free(scene_text);
    return text;
}

char *rd_sweep_request_spare_row(const rd_sweep_request *req)
{
    char *columns_text = rd_sweep_columns_json(req->sweep);
    json_t *columns = columns_text ? json_loads(columns_text, 0, NULL) : NULL;
    json_t *row = json_array();
    size_t ncols = json_array_size(columns);
    int bad = !row || ncols < 2;
    for (size_t k = 0; !bad && k < ncols - 2; k++)
        bad = json_array_append_new(row, json_null()) != 0;
    char *text = NULL;
    if (!bad && json_array_append_new(row, json_string(rd_error_code_name(RD_ENOMEM))) == 0 &&
        json_array_append_new(row, json_string("the server ran out of memory while it ran this "
                                               "point; run it again")) == 0)
        text = json_dumps(row, DUMP_FLAGS);
    json_decref(row);
    json_decref(columns);
    free(columns_text);
    return text;
}
