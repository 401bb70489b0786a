/*
 * rd_sweep_run — one point of a sweep run into a table row (rd_sweep.h):
 * its scene goes through rd_scene_parse_value and rd_scene_run exactly like
 * a posted scene, and the outputs are read from its result (a pointer, or
 * an aggregate over "*" tokens).
 */
#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#include "rd_jsonptr.h"
#include "rd_scene.h"
#include "rd_sweep_int.h"

/* 1 if `ptr` has a "*" token. */
static int has_star(const char *ptr)
{
    for (const char *c = strstr(ptr, "/*"); c; c = strstr(c + 1, "/*"))
        if (c[2] == '/' || c[2] == '\0')
            return 1;
    return 0;
}

/* Folds every number in `v` (arrays flattened) into min/max/sum/n, and
 * appends it to `list` when that is not NULL. */
static void fold(json_t *v, double *lo, double *hi, double *sum, size_t *n, json_t *list)
{
    if (json_is_array(v)) {
        for (size_t k = 0; k < json_array_size(v); k++)
            fold(json_array_get(v, k), lo, hi, sum, n, list);
    } else if (json_is_number(v)) {
        if (list)
            json_array_append(list, v);
        double x = json_number_value(v);
        *lo = *n == 0 || x < *lo ? x : *lo;
        *hi = *n == 0 || x > *hi ? x : *hi;
        *sum += x;
        (*n)++;
    }
}

json_t *rd_sweep_output_value(const output *o, json_t *result)
{
    if (o->kind == O_POINTER) {
        json_t *v;
        if (rd_jsonptr_lookup(result, o->ptr, &v) == -2)
            return NULL;
        return v ? json_incref(v) : json_null();
    }
    json_t *all = json_array();
    if (!all || rd_jsonptr_collect(result, o->ptr, all) != 0) {
        json_decref(all);
        return NULL;
    }
    json_t *cell;
    if (o->kind == O_COUNT) {
        json_t *one = json_array_get(all, 0);
        size_t n = json_array_size(all);
        if (!has_star(o->ptr) && json_is_array(one))
            n = json_array_size(one);
        else if (!has_star(o->ptr) && json_is_object(one))
            n = json_object_size(one);
        cell = json_integer((json_int_t)n);
    } else {
        double lo = 0, hi = 0, sum = 0;
        size_t n = 0;
        json_t *list = o->kind == O_ALL ? json_array() : NULL;
        fold(all, &lo, &hi, &sum, &n, list);
        if (o->kind == O_ALL) {
            json_decref(all);
            if (json_array_size(list) != n) { /* an append ran out of memory */
                json_decref(list);
                list = NULL;
            }
            return list;
        }
        double x = o->kind == O_MAX ? hi : o->kind == O_MIN ? lo : sum / (double)n;
        cell = n > 0 ? json_real(x) : json_null();
    }
    json_decref(all);
    return cell;
}

/* Appends the outputs of a finished run (result text) and status "ok". */
static int append_outputs(const rd_sweep *s, json_t *row, const char *result_text)
{
    json_t *result = json_loads(result_text, 0, NULL);
    int rc = result ? 0 : -1;
    for (int k = 0; rc == 0 && k < s->no; k++)
        rc = json_array_append_new(row, rd_sweep_output_value(&s->o[k], result));
    json_decref(result);
    if (rc == 0)
        rc = json_array_append_new(row, json_string("ok"));
    if (rc == 0)
        rc = json_array_append_new(row, json_null());
    return rc;
}

/* Appends null outputs and the point's error. */
static int append_failure(const rd_sweep *s, json_t *row, const rd_error *e)
{
    int rc = 0;
    for (int k = 0; rc == 0 && k < s->no; k++)
        rc = json_array_append_new(row, json_null());
    if (rc == 0)
        rc = json_array_append_new(row, json_string(rd_error_code_name(e->code)));
    if (rc == 0)
        rc = json_array_append_new(
            row, json_string(e->message[0] ? e->message : rd_error_summary(e->code)));
    return rc;
}

int rd_sweep_run_scene(json_t *scene, const rd_monitor *mon, char **result, rd_error *e)
{
    rd_scene *sc = NULL;
    *result = NULL;
    int status = rd_scene_parse_value(scene, &sc, e);
    if (status == RD_OK)
        status = rd_scene_run(sc, mon, result, e);
    rd_scene_free(sc);
    return status;
}

int rd_sweep_run_point(const rd_sweep *s, size_t i, const rd_monitor *mon, char **row,
                       rd_error *err)
{
    *row = NULL;
    if (i >= s->points)
        return rd_error_set(err, RD_EINVAL, "",
                            "point %zu does not exist: the sweep has %zu "
                            "points",
                            i, s->points);
    json_t *r = json_array(), *scene = rd_sweep_point_json(s, i);
    int rc = r && scene ? 0 : -1;
    for (int p = 0; rc == 0 && p < s->np; p++)
        rc = json_array_append_new(r, rd_sweep_param_value(s, p, i));
    rd_error e;
    rd_error_init(&e);
    char *result = NULL;
    int status = RD_ENOMEM;
    if (rc == 0 && s->over.n) {
        status = rd_sweep_over_run(s, i, scene, mon, r, err);
        if (status != RD_OK)
            goto out;
    } else if (rc == 0) {
        status = rd_sweep_run_scene(scene, mon, &result, &e);
        if (status == RD_ECANCELED) {
            rd_error_set(err, RD_ECANCELED, "", "the sweep was cancelled at point %zu", i);
            goto out;
        }
        rc = status == RD_OK ? append_outputs(s, r, result) : append_failure(s, r, &e);
    }
    if (rc == 0)
        *row = json_dumps(r, JSON_COMPACT | JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS));
    status = *row ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory at point %zu", i);
out:
    free(result);
    json_decref(scene);
    json_decref(r);
    return status;
}
