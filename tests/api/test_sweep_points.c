/*
 * test_sweep_points — the property of issue 45: every point of a sweep spec
 * is refused up front or is a row of the table (rows = points), and a range
 * or random parameter with a non-finite value (finite endpoints whose
 * difference or ratio overflows a double) is refused up front with
 * RD_EINVAL (422) and its path, never run, never out_of_memory.
 *
 * A few hundred random specs from a seeded splitmix64 (argv[1] overrides the
 * seed): 1 to 3 parameters over cheap modal scenes, each a range (linear or
 * log), a random (latin_hypercube) or a list, with endpoints that are
 * ordinary, outside the scene's range, huge (1e300..1.7e308, either sign) or
 * tiny (1e-300..).  The test predicts non-finite values with the formulas of
 * rd_sweep.h, then parses, runs every point of an accepted spec and counts
 * the rows of its table.
 */
#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_sweep.h"

#define SPECS      400
#define POINTS_CAP 12

static uint64_t rng;

static uint64_t next(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

static double unit(void)
{
    return (double)(next() >> 11) * 0x1.0p-53;
}

static int below(int n)
{
    return (int)(unit() * n);
}

/* Scene fields with a range a modal scene accepts ([lo, hi]). */
static const struct {
    const char *path;
    double lo, hi;
} fields[] = {
    {"/ring/tangential_force", 5, 20},
    {"/ring/closed_gap", 1e-4, 5e-4},
    {"/ring/material/density", 7000, 8000},
    {"/ring/material/youngs_modulus", 1e11, 3e11},
};

enum { ORDINARY, OUTSIDE, BIG, TINY };

/* One endpoint of field f in class cls (-1: a random class); *clean = 0
 * when it is not ordinary. */
static double endpoint(int f, int cls, int *clean)
{
    if (cls < 0) {
        cls = below(10);
        cls = cls < 6 ? ORDINARY : cls < 8 ? BIG : cls < 9 ? TINY : OUTSIDE;
    }
    *clean &= cls == ORDINARY;
    if (cls == ORDINARY)
        return fields[f].lo + (fields[f].hi - fields[f].lo) * unit();
    if (cls == OUTSIDE)
        return -1.0 - unit();
    if (cls == TINY)
        return pow(10.0, -300.0 - 7.0 * unit());
    double mag = fmin(pow(10.0, 300.0 + 8.25 * unit()), 1.7e308);
    return below(2) ? mag : -mag;
}

typedef struct {
    int field, kind, log, count; /* kind: 0 range, 1 random, 2 values */
    double a, b;
    int clean;      /* every value ordinary: the scene accepts each one */
    int wellformed; /* the spec's own rules hold (log > 0, random min <= max) */
    int nonfinite;  /* a value of it is +-inf or NaN (or <= 0 on a log scale) */
} gparam;

/* What rd_sweep.h's formulas give: does parameter q hold a non-finite value? */
static int predict_nonfinite(const gparam *q)
{
    if (q->kind == 2 || !q->wellformed)
        return 0;
    if (q->kind == 1)
        return q->log ? !isfinite(q->b / q->a) : !isfinite(q->b - q->a);
    for (int k = 1; k + 1 < q->count; k++) {
        double t = (double)k / (q->count - 1);
        double v = q->log ? q->a * pow(q->b / q->a, t) : q->a + (q->b - q->a) * t;
        if (!isfinite(v) || (q->log && !(v > 0)))
            return 1;
    }
    return 0;
}

/* Appends parameter q to `params` and fills it in; style 0 ordinary
 * endpoints, 1 endpoints that overflow inside, 2 random classes. */
static void gen_param(json_t *params, gparam *q, int f, int lhs, int count, int style)
{
    json_t *p = json_pack("{s:s}", "path", fields[f].path);
    q->field = f;
    q->clean = 1;
    q->kind = lhs && below(2) ? 1 : below(4) == 0 ? 2 : 0;
    q->log = below(2);
    q->count = count;
    if (style == 0) { /* ordinary: every value is one the scene accepts */
        q->a = endpoint(f, ORDINARY, &q->clean);
        q->b = endpoint(f, ORDINARY, &q->clean);
    } else if (style == 1) { /* overflowing: +-big (linear) or tiny and big (log) */
        q->a = endpoint(f, q->log ? TINY : BIG, &q->clean);
        q->b = fabs(endpoint(f, BIG, &q->clean));
        q->a = q->log ? q->a : -fabs(q->a);
        if (below(2)) {
            double t = q->a;
            q->a = q->b;
            q->b = t;
        }
    } else {
        q->a = endpoint(f, -1, &q->clean);
        q->b = endpoint(f, -1, &q->clean);
    }
    if (q->kind == 1 && q->a > q->b && below(4)) { /* mostly ordered, sometimes not */
        double t = q->a;
        q->a = q->b;
        q->b = t;
    }
    q->wellformed =
        !(q->log && q->kind != 2 && (q->a <= 0 || q->b <= 0)) && !(q->kind == 1 && q->a > q->b);
    const char *scale = q->log ? "log" : "linear";
    if (q->kind == 0)
        json_object_set_new(p, "range",
                            json_pack("{s:f,s:f,s:i,s:s}", "start", q->a, "stop", q->b, "count",
                                      count, "scale", scale));
    else if (q->kind == 1)
        json_object_set_new(p, "random",
                            json_pack("{s:f,s:f,s:s}", "min", q->a, "max", q->b, "scale", scale));
    else {
        json_t *values = json_array();
        json_array_append_new(values, json_real(q->a));
        for (int k = 1; k < count; k++)
            json_array_append_new(values, json_real(fields[f].lo));
        json_object_set_new(p, "values", values);
        q->log = 0;
    }
    q->nonfinite = predict_nonfinite(q);
    json_array_append_new(params, p);
}

/* A random spec (caller frees) and its parameters. */
static char *gen_spec(gparam *q, int *np, int *lhs)
{
    *np = 1 + below(3);
    int combine = below(3); /* 0 product, 1 zip, 2 latin_hypercube */
    *lhs = combine == 2;
    int fs[4] = {0, 1, 2, 3};
    for (int k = 3; k > 0; k--) { /* distinct fields */
        int j = below(k + 1), t = fs[k];
        fs[k] = fs[j];
        fs[j] = t;
    }
    json_t *params = json_array();
    int zip_count = 1 + below(4), total = 1;
    int mode = below(3), bad = below(*np); /* mode 1: parameter `bad` overflows */
    for (int p = 0; p < *np; p++) {
        int count = combine == 1 ? zip_count : 1 + below(4);
        if (combine == 0 && total * count > POINTS_CAP)
            count = 1;
        total *= count;
        gen_param(params, &q[p], fs[p], *lhs, count, mode == 2 ? 2 : mode == 1 && p == bad);
    }
    json_t *spec = json_pack("{s:{s:s,s:{s:i},s:{s:i}},s:o,s:[s]}", "base", "analysis", "modal",
                             "discretization", "segments", 8, "modal", "modes", 1, "parameters",
                             params, "outputs", "/modes/0/frequency_hz");
    json_object_set_new(spec, "combine",
                        json_string(combine == 0   ? "product"
                                    : combine == 1 ? "zip"
                                                   : "latin_hypercube"));
    if (*lhs) {
        json_object_set_new(spec, "samples", json_integer(1 + below(6)));
        json_object_set_new(spec, "seed", json_integer((json_int_t)(next() >> 40)));
    }
    char *text = json_dumps(spec, JSON_COMPACT | JSON_REAL_PRECISION(17));
    json_decref(spec);
    return text;
}

/* Runs every point of s; the number of rows its table holds. */
static size_t table_rows(const rd_sweep *s, int columns, const char *spec)
{
    size_t n = rd_sweep_points(s), made = 0;
    char **rows = calloc(n, sizeof *rows);
    for (size_t i = 0; i < n; i++) {
        rd_error err;
        rd_error_init(&err);
        int rc = rd_sweep_run_point(s, i, NULL, &rows[i], &err);
        json_t *row = rows[i] ? json_loads(rows[i], 0, NULL) : NULL;
        CHECK(rc == RD_OK && (int)json_array_size(row) == columns,
              "point %zu gives a row of %d cells (rc %d: %s) in %s", i, columns, rc, err.message,
              spec);
        made += rc == RD_OK && rows[i];
        json_decref(row);
    }
    rd_error err;
    rd_error_init(&err);
    char *table = rd_sweep_table_json(s, rows, n, &err);
    json_t *doc = table ? json_loads(table, 0, NULL) : NULL;
    size_t in_table = json_array_size(json_object_get(doc, "rows"));
    CHECK(in_table == made, "the table holds the %zu rows made, not %zu", made, in_table);
    json_decref(doc);
    free(table);
    for (size_t i = 0; i < n; i++)
        free(rows[i]);
    free(rows);
    return in_table;
}

static int refused[2], accepted, nonfinite_specs;

/* One spec: the property. */
static void one_spec(void)
{
    gparam q[3];
    int np, lhs;
    char *spec = gen_spec(q, &np, &lhs);
    int any = 0, first = -1, clean_before = 1, wellformed = 1;
    for (int p = 0; p < np; p++) {
        wellformed &= q[p].wellformed;
        any |= q[p].nonfinite;
        if (q[p].nonfinite && first < 0)
            first = p;
        if (first < 0)
            clean_before &= q[p].clean;
    }
    nonfinite_specs += any;
    rd_sweep *s = NULL;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_sweep_parse(spec, strlen(spec), 1000, &s, &err);
    CHECK(rc == RD_OK || rc == RD_EREQUEST || rc == RD_EINVAL,
          "a spec is run or refused as the client's (400/422), not %d (%s): %s", rc, err.message,
          spec);
    CHECK(!any || rc != RD_OK, "a spec with a non-finite value is refused up front: %s", spec);
    if (rc == RD_EINVAL) {
        int p = -1;
        sscanf(err.path, "/parameters/%d/", &p);
        CHECK(p >= 0 && p < np && q[p].nonfinite && strstr(err.message, fields[q[p].field].path),
              "422 names a parameter with a non-finite value and its scene path: %s (%s) in %s",
              err.path, err.message, spec);
    }
    if (any && wellformed && clean_before) {
        char want[64];
        snprintf(want, sizeof want, "/parameters/%d/%s", first,
                 q[first].kind == 1 ? "random" : "range");
        CHECK(rc == RD_EINVAL && strcmp(err.path, want) == 0,
              "the first non-finite parameter is refused with 422 at %s, got %d at %s (%s): %s",
              want, rc, err.path, err.message, spec);
    }
    if (rc == RD_OK) {
        size_t rows = table_rows(s, np + 1 + 2, spec);
        CHECK(rows == rd_sweep_points(s), "rows %zu = points %zu: %s", rows, rd_sweep_points(s),
              spec);
        accepted++;
    } else {
        refused[rc == RD_EINVAL]++;
    }
    rd_sweep_free(s);
    free(spec);
}

int main(int argc, char **argv)
{
    rng = argc > 1 ? strtoull(argv[1], NULL, 0) : 45;
    for (int k = 0; k < SPECS; k++)
        one_spec();
    printf("%d specs (%d with a non-finite value): %d run, %d refused 422, %d refused 400\n", SPECS,
           nonfinite_specs, accepted, refused[1], refused[0]);
    CHECK(accepted >= SPECS / 5 && refused[1] >= SPECS / 20 && refused[0] >= SPECS / 20,
          "the generator covers run, 422 and 400 specs");
    return check_done();
}
