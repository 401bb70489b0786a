/*
 * rd_calibration — a calibration's rules, its fit and its result
 * (rd_calibration.h; the spec is described in rd_an_calibration.c).
 *
 * Residual layout: measurement j's values i at offset off_j + i, off_j the
 * values of the measurements before it; r = (model - value) / sigma.
 */
#include "rd_calibration.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_json.h"
#include "rd_jsonptr.h"
#include "rd_scene.h"

#define ERR(path, ...) rd_error_set(err, RD_EREQUEST, path, __VA_ARGS__)

/* Only the keys of `allowed` (NULL-ended) in the object at `path`. */
static int only_keys(json_t *obj, const char *const *allowed, const char *path, rd_error *err)
{
    const char *key;
    json_t *v;
    json_object_foreach(obj, key, v)
    {
        int ok = 0;
        for (const char *const *a = allowed; *a && !ok; a++)
            ok = strcmp(*a, key) == 0;
        if (!ok)
            return ERR(path, "%s/%s is not a field of %s (its fields: %s)", path, key, path,
                       allowed[3] ? "set, observe, value, sigma" : "path, min, max, start");
    }
    return RD_OK;
}

static int number_field(json_t *item, const char *key, const char *at, int required, double *out,
                        rd_error *err)
{
    char path[RD_ERROR_PATH_MAX];
    json_t *v = json_object_get(item, key);
    snprintf(path, sizeof path, "%s/%s", at, key);
    if (!v && !required)
        return 1; /* absent */
    if (!json_is_number(v) || !isfinite(json_number_value(v)))
        return ERR(path, "%s must be a finite number", path);
    *out = json_number_value(v);
    return RD_OK;
}

static int check_parameter(struct rd_calibration *c, size_t i, rd_error *err)
{
    static const char *const keys[] = {"path", "min", "max", "start", NULL};
    struct rd_calibration_param *p = &c->p[i];
    json_t *item = json_array_get(c->params_json, i);
    char at[64], path[RD_ERROR_PATH_MAX];
    snprintf(at, sizeof at, "/parameters/%zu", i);
    if (!json_is_object(item))
        return ERR(at, "%s must be an object {path, min, max, start}", at);
    int rc = only_keys(item, keys, at, err);
    snprintf(path, sizeof path, "%s/path", at);
    p->path = json_string_value(json_object_get(item, "path"));
    double base = 0;
    if (rc == RD_OK)
        rc = rd_study_number_at(&c->base, p->path, path, &base, err);
    for (size_t k = 0; rc == RD_OK && k < i; k++)
        if (strcmp(c->p[k].path, p->path) == 0)
            rc = ERR(path, "%s repeats /parameters/%zu/path (%s)", path, k, p->path);
    if (rc == RD_OK)
        rc = number_field(item, "min", at, 1, &p->min, err);
    if (rc == RD_OK)
        rc = number_field(item, "max", at, 1, &p->max, err);
    if (rc == RD_OK && !(p->min < p->max))
        rc = ERR(at, "%s: min %g must be below max %g (bounds reversed or equal)", at, p->min,
                 p->max);
    p->start = base;
    int absent = rc == RD_OK ? number_field(item, "start", at, 0, &p->start, err) : rc;
    if (absent < 0)
        return absent;
    if (!(p->start >= p->min && p->start <= p->max)) {
        snprintf(path, sizeof path, "%s/start", at);
        return ERR(absent == 1 ? at : path, "%s: the start %g (%s) is outside min %g to max %g", at,
                   p->start, absent == 1 ? "the base scene's value; give a start" : "as given",
                   p->min, p->max);
    }
    const char *ptrs[1] = {p->path};
    snprintf(path, sizeof path, "%s/min", at);
    rc = rd_study_try(&c->base, NULL, ptrs, &p->min, 1, path, path, err);
    snprintf(path, sizeof path, "%s/max", at);
    return rc == RD_OK ? rd_study_try(&c->base, NULL, ptrs, &p->max, 1, path, path, err) : rc;
}

/* value/sigma: a number, or an array of numbers (sigma: one, or as many as value). */
static int numbers(json_t *v, const char *path, size_t want, double **out, size_t *n, int positive,
                   rd_error *err)
{
    size_t len = json_is_array(v) ? json_array_size(v) : 1;
    if (!json_is_number(v) && !(json_is_array(v) && len >= 1 && len <= RD_STUDY_VALUES_MAX))
        return ERR(path, "%s must be a number or an array of 1 to %d numbers", path,
                   RD_STUDY_VALUES_MAX);
    if (want && len != 1 && len != want)
        return ERR(path, "%s has %zu entries: give one sigma for all values or %zu", path, len,
                   want);
    size_t count = want ? want : len;
    *out = calloc(count, sizeof **out);
    if (!*out)
        return rd_error_set(err, RD_ENOMEM, path, "out of memory for %s", path);
    for (size_t k = 0; k < count; k++) {
        json_t *x = json_is_array(v) ? json_array_get(v, len == 1 ? 0 : k) : v;
        double d = json_number_value(x);
        if (!json_is_number(x) || !isfinite(d) || (positive && !(d > 0)))
            return ERR(path, "%s%s must be a finite number%s", path, json_is_array(v) ? "/k" : "",
                       positive ? " above 0" : "");
        (*out)[k] = d;
    }
    *n = count;
    return RD_OK;
}

static int check_set(struct rd_calibration *c, json_t *set, const char *at, rd_error *err)
{
    char path[RD_ERROR_PATH_MAX];
    snprintf(path, sizeof path, "%s/set", at);
    if (!json_is_object(set) || json_object_size(set) > RD_STUDY_SET_MAX)
        return ERR(path, "%s must be an object of at most %d JSON Pointer -> value pairs", path,
                   RD_STUDY_SET_MAX);
    const char *key;
    json_t *v;
    json_object_foreach(set, key, v)
    {
        if (key[0] != '/' || !rd_jsonptr_valid(key) || strcmp(key, "/analysis") == 0)
            return ERR(path,
                       "%s: \"%s\" must be a JSON Pointer into the base scene, not "
                       "/analysis",
                       path, key);
        for (size_t k = 0; k < c->np; k++)
            if (strcmp(key, c->p[k].path) == 0)
                return ERR(path, "%s sets %s, which /parameters/%zu fits", path, key, k);
    }
    return rd_study_try(&c->base, set, NULL, NULL, 0, path, path, err);
}

static int check_measurement(struct rd_calibration *c, size_t j, rd_error *err)
{
    static const char *const keys[] = {"set", "observe", "value", "sigma", NULL};
    struct rd_calibration_meas *m = &c->m[j];
    json_t *item = json_array_get(c->meas_json, j);
    char at[64], path[RD_ERROR_PATH_MAX];
    snprintf(at, sizeof at, "/measurements/%zu", j);
    if (!json_is_object(item))
        return ERR(at, "%s must be an object {set, observe, value, sigma}", at);
    int rc = only_keys(item, keys, at, err);
    m->set = json_object_get(item, "set");
    if (rc == RD_OK && m->set)
        rc = check_set(c, m->set, at, err);
    snprintf(path, sizeof path, "%s/observe", at);
    m->observe = json_string_value(json_object_get(item, "observe"));
    if (rc == RD_OK)
        rc = rd_study_check_observe(&c->base, m->observe, path, err);
    snprintf(path, sizeof path, "%s/value", at);
    if (rc == RD_OK)
        rc = numbers(json_object_get(item, "value"), path, 0, &m->value, &m->n, 0, err);
    snprintf(path, sizeof path, "%s/sigma", at);
    size_t ns = 0;
    if (rc == RD_OK)
        rc = numbers(json_object_get(item, "sigma"), path, m->n, &m->sigma, &ns, 1, err);
    return rc;
}

int rd_calibration_check(struct rd_calibration *c, const struct rd_scene_ops *ops, rd_error *err)
{
    if (!c->base_given || !c->params_given || !c->meas_given)
        return ERR(!c->base_given     ? "/base"
                   : !c->params_given ? "/parameters"
                                      : "/measurements",
                   "a calibration needs /base (a scene), /parameters (what to fit) and "
                   "/measurements (what was measured)");
    int rc = rd_error_range(c->max_runs, 3, 100000, "/numerics/max_runs", "runs", err);
    if (rc == RD_OK)
        rc = rd_error_range(c->threads, 0, RD_STUDY_THREADS_MAX, "/numerics/threads", "threads",
                            err);
    if (rc == RD_OK)
        rc = rd_study_base_parse(c->base_json, ops, &c->base, err);
    if (rc != RD_OK)
        return rc;
    size_t np = json_array_size(c->params_json), nm = json_array_size(c->meas_json);
    if (!json_is_array(c->params_json) || np < 1 || np > RD_FIT_PARAMS_MAX)
        return ERR("/parameters", "/parameters must be an array of 1 to %d parameters",
                   RD_FIT_PARAMS_MAX);
    if (!json_is_array(c->meas_json) || nm < 1 || nm > RD_CALIBRATION_MEASUREMENTS_MAX)
        return ERR("/measurements", "/measurements must be an array of 1 to %d measurements",
                   RD_CALIBRATION_MEASUREMENTS_MAX);
    for (c->np = 0; c->np < np; c->np++)
        if ((rc = check_parameter(c, c->np, err)) != RD_OK)
            return rc;
    c->m = calloc(nm, sizeof *c->m);
    if (!c->m)
        return rd_error_set(err, RD_ENOMEM, "/measurements", "out of memory");
    for (c->nm = 0; c->nm < nm; c->nm++) {
        if ((rc = check_measurement(c, c->nm, err)) != RD_OK) {
            c->nm++; /* its arrays are freed with the others */
            return rc;
        }
        c->n_values += c->m[c->nm].n;
        struct rd_calibration_meas *m = &c->m[c->nm];
        for (m->group = 0; m->group < c->ng; m->group++) {
            json_t *other = c->m[c->group_meas[m->group]].set;
            if (other == m->set || (other && m->set && json_equal(other, m->set)))
                break;
        }
        if (m->group == c->ng)
            c->group_meas[c->ng++] = c->nm;
    }
    if (c->n_values < c->np)
        return ERR("/measurements",
                   "/measurements hold %zu measured values for %zu parameters: a fit needs at "
                   "least as many values as parameters",
                   c->n_values, c->np);
    if ((size_t)c->max_runs < (c->np + 2) * c->ng)
        return rd_error_set(err, RD_EINVAL, "/numerics/max_runs",
                            "/numerics/max_runs = %d is too few: one start and one Jacobian of "
                            "%zu parameters over %zu distinct measurement sets take %zu runs",
                            c->max_runs, c->np, c->ng, (c->np + 2) * c->ng);
    return RD_OK;
}

void rd_calibration_cleanup(struct rd_calibration *c)
{
    for (size_t j = 0; c->m && j < c->nm; j++) {
        free(c->m[j].value);
        free(c->m[j].sigma);
    }
    free(c->m);
    rd_study_base_cleanup(&c->base);
    json_decref(c->base_json);
    json_decref(c->params_json);
    json_decref(c->meas_json);
}

json_t *rd_calibration_echo_parameters(const struct rd_calibration *c)
{
    if (!c->params_json)
        return json_null();
    json_t *out = json_deep_copy(c->params_json);
    for (size_t i = 0; out && i < c->np; i++)
        json_object_set_new(json_array_get(out, i), "start", json_real(c->p[i].start));
    return out;
}
