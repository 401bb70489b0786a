/*
 * test_sweep_over — a sweep's "over" member (api/rd_sweep.h, issue 42):
 * its aggregates against the same values run as a plain parameter (min,
 * max, mean, argmin, argmax recomputed here from the plain table), a point
 * whose over value fails, refused specs with their codes and paths, the
 * limit on runs, the spec hash, progress over the runs, and chunks +
 * reduce against the in-memory table.
 */
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "rd_api.h"
#include "rd_sweep.h"

#define BASE                                                            \
    "\"base\": {\"analysis\": \"contact\", \"bore\": {\"distortion\": " \
    "[{\"order\": 2, \"amplitude\": 5e-6, \"phase_deg\": 0}]}}"
#define FORCES "{\"path\": \"/ring/tangential_force\", \"values\": [8, 12]}"
#define PHASES                                                               \
    "\"path\": \"/bore/distortion/0/phase_deg\", \"range\": {\"start\": 0, " \
    "\"stop\": 90, \"count\": 4}"
#define OUTPUTS                                                    \
    "\"outputs\": [\"/mean_pressure_pa\", \"max(/pressure_pa)\", " \
    "\"/contact_fraction\", \"count(/pressure_pa)\"]"

static const char over_spec[] =
    "{" BASE ", \"parameters\": [" FORCES "], \"over\": {" PHASES "}, " OUTPUTS "}";
static const char plain_spec[] =
    "{" BASE ", \"parameters\": [" FORCES ", {" PHASES "}], " OUTPUTS "}";

static rd_sweep *parse(const char *spec, size_t max, rd_error *err)
{
    rd_sweep *s = NULL;
    rd_error_init(err);
    rd_sweep_parse(spec, strlen(spec), max, &s, err);
    return s;
}

/* The rows of every point (caller frees each and the array); NULL on failure. */
static char **run_rows(const rd_sweep *s)
{
    rd_error err;
    rd_error_init(&err);
    size_t n = rd_sweep_points(s);
    char **rows = calloc(n, sizeof *rows);
    int ok = rows != NULL;
    for (size_t i = 0; ok && i < n; i++)
        ok = rd_sweep_run_point(s, i, NULL, &rows[i], &err) == RD_OK;
    CHECK(ok, "every point runs: %s", err.message);
    return rows;
}

static void free_rows(char **rows, size_t n)
{
    for (size_t i = 0; rows && i < n; i++)
        free(rows[i]);
    free(rows);
}

/* The table of a sweep as JSON (new reference). */
static json_t *table_of(const rd_sweep *s, char **rows)
{
    rd_error err;
    rd_error_init(&err);
    char *text = rows ? rd_sweep_table_json(s, rows, rd_sweep_points(s), &err) : NULL;
    json_t *t = text ? json_loads(text, 0, NULL) : NULL;
    free(text);
    return t;
}

/* The over table against the plain one: point p of the over sweep is the
 * plain points 4p .. 4p + 3 (the phase varies fastest). */
static void test_equals_plain(void)
{
    rd_error err;
    rd_sweep *o = parse(over_spec, 1000, &err), *p = parse(plain_spec, 1000, &err);
    CHECK(o && p, "both specs parse: %s", err.message);
    if (!o || !p)
        goto out;
    CHECK(rd_sweep_points(o) == 2 && rd_sweep_runs_per_point(o) == 4 && rd_sweep_points(p) == 8 &&
              rd_sweep_runs_per_point(p) == 1,
          "2 points x 4 runs against 8 points");
    char **ro = run_rows(o), **rp = run_rows(p);
    json_t *to = table_of(o, ro), *tp = table_of(p, rp);
    json_t *cols = json_object_get(to, "columns");
    const char *names[] = {"min:", "max:", "mean:", "argmin:", "argmax:"};
    const char *outs[] = {"/mean_pressure_pa", "max(/pressure_pa)", "/contact_fraction",
                          "count(/pressure_pa)"};
    int named = json_array_size(cols) == 1 + 4 * 5 + 2 &&
                strcmp(json_string_value(json_array_get(cols, 0)), "/ring/tangential_force") == 0;
    for (int j = 0; named && j < 4; j++)
        for (int c = 0; named && c < 5; c++) {
            char want[64];
            snprintf(want, sizeof want, "%s%s", names[c], outs[j]);
            named =
                strcmp(json_string_value(json_array_get(cols, (size_t)(1 + 5 * j + c))), want) == 0;
        }
    CHECK(named, "columns: the parameter, then min:O max:O mean:O argmin:O argmax:O per output");
    for (size_t pt = 0; pt < 2; pt++) {
        json_t *row = json_array_get(json_object_get(to, "rows"), pt);
        CHECK(strcmp(json_string_value(json_array_get(row, 21)), "ok") == 0, "point %zu ok", pt);
        for (int j = 0; j < 4; j++) {
            size_t lo = 0, hi = 0;
            double sum = 0, x[4];
            json_t *plain[4];
            for (size_t k = 0; k < 4; k++) {
                plain[k] = json_array_get(json_object_get(tp, "rows"), 4 * pt + k);
                x[k] = json_number_value(json_array_get(plain[k], (size_t)(2 + j)));
                sum += x[k];
                lo = x[k] < x[lo] ? k : lo; /* the first one on ties */
                hi = x[k] > x[hi] ? k : hi;
            }
            json_t *cell = json_array_get(row, (size_t)(1 + 5 * j));
            CHECK(json_equal(cell, json_array_get(plain[lo], (size_t)(2 + j))) &&
                      json_equal(json_array_get(row, (size_t)(2 + 5 * j)),
                                 json_array_get(plain[hi], (size_t)(2 + j))),
                  "point %zu %s: min and max are the plain table's", pt, outs[j]);
            CHECK_REL(json_number_value(json_array_get(row, (size_t)(3 + 5 * j))), sum / 4, 1e-14,
                      "point %zu %s: mean", pt, outs[j]);
            CHECK(json_equal(json_array_get(row, (size_t)(4 + 5 * j)),
                             json_array_get(plain[lo], 1)) &&
                      json_equal(json_array_get(row, (size_t)(5 + 5 * j)),
                                 json_array_get(plain[hi], 1)),
                  "point %zu %s: argmin and argmax are the plain rows' phases", pt, outs[j]);
        }
    }
    CHECK(json_is_integer(json_array_get(json_array_get(json_object_get(to, "rows"), 0), 16)),
          "an integer output (count) keeps integer min");
    json_decref(to);
    json_decref(tp);
    free_rows(ro, 2);
    free_rows(rp, 8);
out:
    rd_sweep_free(o);
    rd_sweep_free(p);
}

/* A point with a failing over value fails whole, naming the value; the
 * other point is ok. */
static void test_failing_value(void)
{
    rd_error err;
    rd_sweep *s = parse(
        "{\"base\": {\"analysis\": \"contact\"}, \"parameters\": [{\"path\": "
        "\"/ring/diameter\", \"values\": [0.0765, 0.0779]}], \"over\": {\"path\": "
        "\"/bore/diameter\", \"values\": [0.0775, 0.0762]}, \"outputs\": [\"/mean_pressure_pa\"]}",
        1000, &err);
    CHECK(s != NULL, "each over value is valid alone on the base: %s", err.message);
    if (!s)
        return;
    char **rows = run_rows(s);
    json_t *t = table_of(s, rows), *r0 = json_array_get(json_object_get(t, "rows"), 0),
           *r1 = json_array_get(json_object_get(t, "rows"), 1);
    static const char want[] =
        "over /bore/diameter = 0.0762: /bore/diameter = 0.0762 m is out of range";
    CHECK(strcmp(json_string_value(json_array_get(r0, 6)), "ok") == 0, "the 76.5 mm ring is ok");
    const char *msg = json_string_value(json_array_get(r1, 7));
    CHECK(strcmp(json_string_value(json_array_get(r1, 6)), "invalid_scene") == 0 && msg &&
              strncmp(msg, want, strlen(want)) == 0,
          "the 77.9 mm ring fails at its second over value, the 76.2 mm bore, named: %s",
          msg ? msg : "(none)");
    int nulls = json_real_value(json_array_get(r1, 0)) == 0.0779;
    for (size_t k = 1; k < 6; k++)
        nulls = nulls && json_is_null(json_array_get(r1, k));
    CHECK(nulls, "its aggregates are null (not those of its first over value alone)");
    json_decref(t);
    free_rows(rows, 2);
    rd_sweep_free(s);
}

/* Refused up front with the code and the path of the problem. */
static void test_bad_specs(void)
{
    static const struct {
        const char *spec, *path, *words;
        int code;
    } cases[] = {
        {"{" BASE ", \"over\": {\"path\": \"/ring/tangential_force\", \"random\": {\"min\": 1, "
         "\"max\": 2}}, " OUTPUTS "}",
         "/over", "not \"random\"", RD_EREQUEST},
        {"{" BASE ", \"parameters\": [" FORCES "], \"over\": {\"path\": "
         "\"/ring/tangential_force\", \"values\": [9]}, " OUTPUTS "}",
         "/over/path", "also the path of /parameters/0", RD_EREQUEST},
        {"{" BASE ", \"parameters\": [" FORCES "], \"over\": {\"path\": \"/ring\", \"values\": "
         "[{}]}, " OUTPUTS "}",
         "/over/path", "would replace that parameter's value", RD_EREQUEST},
        {"{" BASE ", \"over\": {\"path\": \"/engine/speed_rpm\", \"values\": [1000]}, " OUTPUTS "}",
         "/over/values/0", "over /engine/speed_rpm = 1000 gives an invalid scene", RD_EREQUEST},
        {"{" BASE
         ", \"over\": {\"path\": \"/ring/tangential_force\", \"values\": [8, -1]}, " OUTPUTS "}",
         "/over/values/1", "out of range", RD_EREQUEST},
        {"{" BASE ", \"over\": {\"path\": \"/ring/tangential_force\", \"range\": {\"start\": "
         "-1e308, \"stop\": 1e308, \"count\": 3}}, " OUTPUTS "}",
         "/over/range", "overflows a double", RD_EINVAL},
        {"{" BASE ", \"over\": {" PHASES "}, \"outputs\": [\"/mean_pressure_pa\", "
         "\"all(/pressure_pa)\"]}",
         "/outputs/1", "a list, not a number", RD_EREQUEST},
        {"{" BASE ", \"over\": {" PHASES "}, \"combine\": \"zip\", " OUTPUTS "}", "/combine",
         "without /parameters has one point", RD_EREQUEST},
        {"{" BASE ", \"parameters\": [{\"path\": \"/ring/tangential_force\", \"range\": "
         "{\"start\": 5, \"stop\": 15, \"count\": 3}}], \"over\": {" PHASES "}, " OUTPUTS "}",
         "/over", "3 points x 4 over values = 12 runs, more than the limit of 10 runs",
         RD_EREQUEST},
        {"{" BASE ", \"over\": {\"path\": \"/ring/tangential_force\"}, " OUTPUTS "}", "/over",
         "exactly one of \"values\", \"range\"", RD_EREQUEST},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rd_error err;
        rd_sweep *s = parse(cases[c].spec, 10, &err);
        CHECK(!s && err.code == cases[c].code && strcmp(err.path, cases[c].path) == 0 &&
                  strstr(err.message, cases[c].words),
              "case %zu: want %s at %s (\"%s\"), got %s at %s: %s", c,
              rd_error_code_name(cases[c].code), cases[c].path, cases[c].words,
              rd_error_code_name(err.code), err.path, err.message);
        rd_sweep_free(s);
    }
}

/* No parameters: one point; the hash changes with the over; a string
 * output fails the point naming it. */
static void test_one_point_hash_and_strings(void)
{
    rd_error err;
    rd_sweep *a = parse("{" BASE ", \"over\": {" PHASES "}, " OUTPUTS "}", 10, &err);
    rd_sweep *b = parse("{" BASE ", \"over\": {\"path\": \"/bore/distortion/0/phase_deg\", "
                        "\"values\": [0, 30]}, " OUTPUTS "}",
                        10, &err);
    rd_sweep *c = parse("{" BASE ", \"parameters\": [{\"path\": "
                        "\"/bore/distortion/0/phase_deg\", \"values\": [0, 30]}], " OUTPUTS "}",
                        10, &err);
    CHECK(a && b && c && rd_sweep_points(a) == 1 && rd_sweep_runs_per_point(a) == 4,
          "without parameters: 1 point of 4 runs (%s)", err.message);
    CHECK(a && b && c && strcmp(rd_sweep_hash(a), rd_sweep_hash(b)) != 0 &&
              strcmp(rd_sweep_hash(b), rd_sweep_hash(c)) != 0,
          "the spec hash changes with the over");
    rd_sweep *d =
        parse("{" BASE ", \"over\": {" PHASES "}, \"outputs\": [\"/scene/analysis\"]}", 10, &err);
    char *row = NULL;
    if (d)
        rd_sweep_run_point(d, 0, NULL, &row, &err);
    CHECK(row && strstr(row, "\"invalid_request\",\"over /bore/distortion/0/phase_deg = 0.0: "
                             "output /scene/analysis is a string, not a number"),
          "a string output fails the point, naming it: %s", row ? row : err.message);
    free(row);
    rd_sweep_free(a);
    rd_sweep_free(b);
    rd_sweep_free(c);
    rd_sweep_free(d);
}

typedef struct {
    double last;
    int steps, backwards, stop_at;
} progress;

static int watch(void *ctx, double fraction)
{
    progress *p = ctx;
    p->backwards |= fraction < p->last - 1e-12;
    for (int k = 1; k < 4; k++)
        p->steps |= fabs(fraction - k / 4.0) < 1e-12 ? 1 << k : 0;
    p->last = fraction;
    return p->stop_at && fraction >= p->stop_at / 4.0;
}

/* The monitor sees the runs: k/4 at the start of run k, never backwards;
 * a stop asked for during run 2 cancels the point (no row). */
static void test_progress(void)
{
    rd_error err;
    rd_sweep *s = parse("{" BASE ", \"over\": {" PHASES "}, " OUTPUTS "}", 10, &err);
    progress p = {0, 0, 0, 0}, q = {0, 0, 0, 2};
    rd_monitor mon = {watch, &p}, stop = {watch, &q};
    char *row = NULL, *none = NULL;
    int rc = s ? rd_sweep_run_point(s, 0, &mon, &row, &err) : -1;
    CHECK(rc == RD_OK && p.steps == (2 | 4 | 8) && !p.backwards,
          "fractions 1/4, 2/4, 3/4 at the runs' starts, never backwards (steps %x)", p.steps);
    rd_error_init(&err);
    rc = s ? rd_sweep_run_point(s, 0, &stop, &none, &err) : -1;
    CHECK(rc == RD_ECANCELED && none == NULL, "a stop cancels the point: %s", err.message);
    free(row);
    rd_sweep_free(s);
}

/* The in-memory table and 2 chunk files reduced are the same bytes. */
static void test_chunks(void)
{
    rd_error err;
    rd_sweep *s = parse(over_spec, 1000, &err);
    char **rows = s ? run_rows(s) : NULL;
    char dir[] = "/tmp/test_sweep_over_XXXXXX";
    int ok = rows && mkdtemp(dir) != NULL;
    for (size_t c = 0; ok && c < 2; c++) {
        char *name = rd_sweep_chunk_name(c, 2), *head = rd_sweep_chunk_head(s, c, 2), path[128];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        FILE *f = fopen(path, "w");
        ok = f && head && fprintf(f, "%s%s\n]}\n", head, rows[c]) > 0;
        ok = f && fclose(f) == 0 && ok;
        free(name);
        free(head);
    }
    char *mem = NULL, *table = ok ? rd_sweep_table_json(s, rows, 2, &err) : NULL;
    size_t size = 0;
    FILE *out = open_memstream(&mem, &size);
    int rc = ok ? rd_sweep_reduce(dir, 0, out, &err) : -1;
    fclose(out);
    CHECK(rc == RD_OK && table && strncmp(mem, table, strlen(table)) == 0 &&
              strcmp(mem + strlen(table), "\n") == 0,
          "reduce of 2 chunks = the in-memory table (%s)", err.message);
    for (size_t c = 0; c < 2; c++) {
        char *name = rd_sweep_chunk_name(c, 2), path[128];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        remove(path);
        free(name);
    }
    rmdir(dir);
    free(mem);
    free(table);
    free_rows(rows, 2);
    rd_sweep_free(s);
}

int main(void)
{
    test_equals_plain();
    test_failing_value();
    test_bad_specs();
    test_one_point_hash_and_strings();
    test_progress();
    test_chunks();
    return check_done();
}
