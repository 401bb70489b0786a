/*
 * rd_sweep_over — a sweep's "over" member (rd_sweep.h, issue 42): every
 * point runs once per over value v_k (k = 0..m-1, the values of a
 * values/range parameter, written at the over path after the point's
 * parameters), and each output O becomes five cells
 *   min:O = min_k O_k,  max:O = max_k O_k,  mean:O = (1/m) sum_k O_k,
 *   argmin:O = v_k at the first k reaching the min,  argmax:O likewise,
 * over every k: a point is ok only when all m runs are.  The first run that
 * fails (in over order) gives the point its status and a message naming its
 * over value, with null aggregates: leaving that value out would answer
 * another question than the one asked ("over these values").
 */
#include <jansson.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_jsonptr.h"
#include "rd_sweep_int.h"

static const char *const prefixes[RD_SWEEP_OVER_COLUMNS] = {
    "min:", "max:", "mean:", "argmin:", "argmax:"};

static int over_error(rd_error *err, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int over_error(rd_error *err, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = rd_error_setv(err, RD_EREQUEST, path, fmt, ap);
    va_end(ap);
    return rc;
}

/* The over path against the parameters': not one of them, not above one
 * (each over value would replace that parameter's value). */
static int check_paths(const rd_sweep *s, rd_error *err)
{
    const char *o = s->over.path;
    size_t n = strlen(o);
    for (int p = 0; p < s->np; p++) {
        const char *q = s->p[p].path;
        if (strcmp(q, o) == 0)
            return over_error(err, "/over/path",
                              "/over/path %s is also the path of /parameters/%d: a point cannot "
                              "both set it and run over it",
                              o, p);
        if (strncmp(q, o, n) == 0 && q[n] == '/')
            return over_error(err, "/over/path",
                              "/over/path %s holds %s, the path of /parameters/%d: each over "
                              "value would replace that parameter's value",
                              o, q, p);
    }
    return RD_OK;
}

int rd_sweep_over_parse(rd_sweep *s, json_t *spec, rd_error *err)
{
    json_t *v = json_object_get(spec, "over");
    if (!v)
        return RD_OK;
    if (rd_sweep_parse_param(v, "/over", 0, &s->over, err) || check_paths(s, err))
        return err->code;
    if (s->np == 0 && json_object_get(spec, "combine"))
        return over_error(err, "/combine",
                          "/combine combines parameters: a sweep without /parameters has one "
                          "point, run once per over value");
    for (int k = 0; k < s->no; k++) {
        char at[64];
        snprintf(at, sizeof at, "/outputs/%d", k);
        if (s->o[k].kind == O_ALL)
            return over_error(err, at,
                              "%s = %s is a list, not a number: an over sweep tabulates min, max, "
                              "mean, argmin and argmax of each output; use max(P), min(P) or "
                              "mean(P), or a sweep without \"over\"",
                              at, s->o[k].text);
    }
    return RD_OK;
}

void rd_sweep_over_columns(const rd_sweep *s, const output *o, json_t *cols)
{
    if (!s->over.n) {
        json_array_append_new(cols, json_string(o->text));
        return;
    }
    for (int c = 0; c < RD_SWEEP_OVER_COLUMNS; c++) {
        size_t n = strlen(prefixes[c]) + strlen(o->text) + 1;
        char *name = malloc(n);
        if (name)
            snprintf(name, n, "%s%s", prefixes[c], o->text);
        json_array_append_new(cols, name ? json_string(name) : NULL);
        free(name);
    }
}

/* "over P = v: " before e's message (v as compact JSON). */
static void name_value(const rd_sweep *s, size_t k, rd_error *e)
{
    json_t *v = rd_sweep_entry(&s->over, k);
    char *text = v ? json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT |
                                       JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS))
                   : NULL;
    rd_error named = {e->code, "", ""};
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
        json_t *c = rd_sweep_output_value(&s->o[j], result);
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
        rc = rc == RD_OK && json_array_append_new(cells, c) != 0 ? RD_ENOMEM : rc;
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
        status = rd_sweep_run_scene(copy, sub, &result, e);
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

int rd_sweep_over_run(const rd_sweep *s, size_t i, json_t *scene, const rd_monitor *mon,
                      json_t *row, rd_error *err)
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
