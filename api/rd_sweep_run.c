/*
 * rd_sweep_run — one point of a sweep run into a table row (rd_sweep.h):
 * its scene goes through rd_scene_parse_value and rd_scene_run exactly like
 * a posted scene, and the outputs are read from its result (a pointer, or
 * an aggregate over "*" tokens).
 *
 * With "over" (issue 42) the point runs once per over value v_k (k = 0..m-1,
 * written at the over path after the point's parameters), and each output O
 * becomes five cells
 *   min:O = min_k O_k,  max:O = max_k O_k,  mean:O = (1/m) sum_k O_k,
 *   argmin:O = v_k at the first k reaching the min,  argmax:O likewise.
 * A point is ok only when all m runs are: the first run that fails (in over
 * order) gives the point its status and a message naming its over value,
 * with null aggregates; leaving that value out would answer another
 * question than the one asked ("over these values").
 */
#include <jansson.h>
#include <stdio.h>
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

/* The cell of output o for a result (new reference; NULL out of memory). */
static json_t *output_value(const output *o, json_t *result)
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
        rc = json_array_append_new(row, output_value(&s->o[k], result));
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

/* Parses and runs one scene (borrowed) as a posted scene runs; on RD_OK
 * *result is the result text (caller frees), else e says why. */
static int run_scene(json_t *scene, const rd_monitor *mon, char **result, rd_error *e)
{
    rd_scene *sc = NULL;
    *result = NULL;
    int status = rd_scene_parse_value(scene, &sc, e);
    if (status == RD_OK)
        status = rd_scene_run(sc, mon, result, e);
    rd_scene_free(sc);
    return status;
}

/* ---- over ---- */

/* "over P = v: " before e's message (v as compact JSON). */
static void name_value(const rd_sweep *s, size_t k, rd_error *e)
{
    json_t *v = rd_sweep_entry(&s->over, k);
    char *text = v ? json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT |
                                       JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS))
                   : NULL;
    rd_error named = {e->code, "", "", ""};
    memcpy(named.path, e->path, sizeof named.path);
    snprintf(named.message, sizeof named.message, "over %.80s = %.40s: %.380s", s->over.path,
             text ? text : "?", e->message[0] ? e->message : rd_error_summary(e->code));
    *e = named;
    free(text);
    json_decref(v);
}

/* The outputs of run k's result as one array appended to `runs`; a value
 * that is neither a number nor null fails the point (e). */
static int collect(const rd_sweep *s, size_t k, const char *result_text, json_t *runs, rd_error *e)
{
    json_t *result = json_loads(result_text, 0, NULL), *cells = json_array();
    int rc = result && cells ? RD_OK : RD_ENOMEM;
    for (int j = 0; rc == RD_OK && j < s->no; j++) {
        json_t *c = output_value(&s->o[j], result);
        if (c && !json_is_number(c) && !json_is_null(c)) {
            char at[64];
            snprintf(at, sizeof at, "/outputs/%d", j);
            rc = rd_error_set(e, RD_EREQUEST, at,
                              "output %s is %s, not a number: an over sweep tabulates min, max, "
                              "mean, argmin and argmax of numbers only",
                              s->o[j].text,
                              json_is_string(c)   ? "a string"
                              : json_is_array(c)  ? "an array"
                              : json_is_object(c) ? "an object"
                                                  : "true or false");
            name_value(s, k, e);
        }
        if (rc != RD_OK)
            json_decref(c);
        else if (json_array_append_new(cells, c) != 0)
            rc = RD_ENOMEM;
    }
    if (rc == RD_OK && json_array_append(runs, cells) != 0)
        rc = RD_ENOMEM;
    json_decref(cells);
    json_decref(result);
    return rc;
}

/* Run k of point i (scene borrowed): its outputs appended to `runs`.
 * RD_OK, RD_ECANCELED, RD_ENOMEM, or the run's failure in e. */
static int run_one(const rd_sweep *s, size_t k, json_t *scene, const rd_monitor *mon, json_t *runs,
                   rd_error *e)
{
    double m = (double)s->over.n;
    if (rd_monitor_report(mon, (double)k / m, e) != RD_OK)
        return RD_ECANCELED;
    json_t *copy = json_deep_copy(scene);
    int set = copy ? rd_jsonptr_set(copy, s->over.path, rd_sweep_entry(&s->over, k)) : -2;
    int status = set == -2   ? RD_ENOMEM
                 : set == -1 ? rd_error_set(e, RD_EINVAL, "",
                                            "the point's parameters leave no place for it: a "
                                            "part of the path is not an object or array element")
                             : RD_OK;
    char *result = NULL;
    if (status == RD_OK) {
        rd_monitor_span span;
        const rd_monitor *sub =
            rd_monitor_span_init(&span, mon, (double)k / m, (double)(k + 1) / m);
        status = run_scene(copy, sub, &result, e);
    }
    if (status == RD_OK)
        status = collect(s, k, result, runs, e);
    else if (status != RD_ECANCELED && status != RD_ENOMEM)
        name_value(s, k, e);
    free(result);
    json_decref(copy);
    return status;
}

/* The five cells of output j over the runs (all numbers or nulls). */
static int append_aggregates(const rd_sweep *s, json_t *runs, int j, json_t *row)
{
    size_t m = json_array_size(runs), lo = 0, hi = 0;
    double sum = 0;
    int null = 0;
    for (size_t k = 0; k < m; k++) {
        json_t *c = json_array_get(json_array_get(runs, k), (size_t)j);
        null |= !json_is_number(c);
        double x = json_number_value(c);
        sum += x;
        lo = x < json_number_value(json_array_get(json_array_get(runs, lo), (size_t)j)) ? k : lo;
        hi = x > json_number_value(json_array_get(json_array_get(runs, hi), (size_t)j)) ? k : hi;
    }
    json_t *cells[RD_SWEEP_OVER_COLUMNS] = {NULL};
    if (!null) {
        cells[0] = json_deep_copy(json_array_get(json_array_get(runs, lo), (size_t)j));
        cells[1] = json_deep_copy(json_array_get(json_array_get(runs, hi), (size_t)j));
        cells[2] = json_real(sum / (double)m);
        cells[3] = rd_sweep_entry(&s->over, lo);
        cells[4] = rd_sweep_entry(&s->over, hi);
    }
    int rc = 0;
    for (int c = 0; c < RD_SWEEP_OVER_COLUMNS; c++)
        if (json_array_append_new(row, null ? json_null() : cells[c]) != 0)
            rc = -1;
    return rc;
}

static int over_run(const rd_sweep *s, size_t i, json_t *scene, const rd_monitor *mon, json_t *row,
                    rd_error *err)
{
    json_t *runs = json_array();
    rd_error e;
    rd_error_init(&e);
    int status = runs ? RD_OK : RD_ENOMEM, rc = 0;
    for (size_t k = 0; status == RD_OK && k < s->over.n; k++)
        status = run_one(s, k, scene, mon, runs, &e);
    if (status == RD_ECANCELED || status == RD_ENOMEM) {
        json_decref(runs);
        return status == RD_ECANCELED
                   ? rd_error_set(err, status, "", "the sweep was cancelled at point %zu", i)
                   : rd_error_set(err, status, "", "out of memory at point %zu", i);
    }
    for (int j = 0; rc == 0 && j < s->no; j++) {
        if (status == RD_OK)
            rc = append_aggregates(s, runs, j, row);
        for (int c = 0; status != RD_OK && rc == 0 && c < RD_SWEEP_OVER_COLUMNS; c++)
            rc = json_array_append_new(row, json_null());
    }
    if (rc == 0)
        rc = json_array_append_new(row, json_string(rd_error_code_name(status)));
    if (rc == 0)
        rc = json_array_append_new(row, status == RD_OK ? json_null() : json_string(e.message));
    json_decref(runs);
    return rc == 0 ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory at point %zu", i);
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
        status = over_run(s, i, scene, mon, r, err);
        if (status != RD_OK)
            goto out;
    } else if (rc == 0) {
        status = run_scene(scene, mon, &result, &e);
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
