/*
 * test_sweep — sweep specs (api/rd_sweep.h) and JSON Pointers
 * (api/rd_jsonptr.h): expansion (product order, zip, Latin hypercube strata,
 * exact range endpoints), determinism against the published splitmix64
 * sequence, validation errors with their spec paths, rows of failed points,
 * aggregates against the result read directly, CSV quoting, chunk ranges.
 */
#include <jansson.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "rd_api.h"
#include "rd_jsonptr.h"
#include "rd_sweep.h"

/* Parses a spec with a point limit; NULL (and err filled) on error. */
static rd_sweep *parse(const char *spec, size_t max, rd_error *err)
{
    rd_sweep *s = NULL;
    rd_error_init(err);
    rd_sweep_parse(spec, strlen(spec), max, &s, err);
    return s;
}

/* The value at `ptr` in the scene of point i, as a number (NAN if absent). */
static double point_number(const rd_sweep *s, size_t i, const char *ptr)
{
    rd_error err;
    rd_error_init(&err);
    char *text = rd_sweep_point_scene(s, i, &err);
    json_t *scene = text ? json_loads(text, 0, NULL) : NULL;
    json_t *v = rd_jsonptr_get(scene, ptr);
    double x = json_is_number(v) ? json_number_value(v) : NAN;
    json_decref(scene);
    free(text);
    return x;
}

static void test_jsonptr(void)
{
    json_t *doc = json_loads("{\"a/b\": {\"m~n\": [10, 20]}, \"\": 1, \"c\": {\"d\": 2}}", 0, NULL);
    CHECK(json_integer_value(rd_jsonptr_get(doc, "/a~1b/m~0n/1")) == 20, "RFC 6901 escapes");
    CHECK(json_integer_value(rd_jsonptr_get(doc, "/")) == 1, "empty key");
    CHECK(rd_jsonptr_get(doc, "") == doc, "\"\" is the whole document");
    CHECK(rd_jsonptr_get(doc, "/a~1b/m~0n/01") == NULL, "leading zero is not an index");
    CHECK(rd_jsonptr_get(doc, "/a~1b/m~0n/2") == NULL, "index past the end");
    CHECK(!rd_jsonptr_valid("/a~2") && !rd_jsonptr_valid("a") && rd_jsonptr_valid(""),
          "malformed pointers");
    CHECK(rd_jsonptr_set(doc, "/x/y/z", json_integer(3)) == 0 &&
              json_integer_value(rd_jsonptr_get(doc, "/x/y/z")) == 3,
          "set creates missing objects");
    CHECK(rd_jsonptr_set(doc, "/a~1b/m~0n/2", json_integer(30)) == 0 &&
              json_array_size(rd_jsonptr_get(doc, "/a~1b/m~0n")) == 3,
          "set at the array length appends");
    CHECK(rd_jsonptr_set(doc, "/a~1b/m~0n/5", json_integer(1)) != 0, "no holes in arrays");
    CHECK(rd_jsonptr_set(doc, "/c/d/e", json_integer(1)) != 0, "cannot cross a scalar");
    json_t *all = json_array();
    rd_jsonptr_collect(doc, "/a~1b/m~0n/*", all);
    CHECK(json_array_size(all) == 3 && json_integer_value(json_array_get(all, 2)) == 30,
          "collect with a star");
    json_decref(all);
    json_decref(doc);
}

/* product: the last parameter varies fastest; log range endpoints exact. */
static void test_product_and_ranges(void)
{
    rd_error err;
    rd_sweep *s = parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
                        "{\"path\": \"/ring/tangential_force\", \"values\": [8, 10, 12]},"
                        "{\"path\": \"/ring/closed_gap\", \"range\": {\"start\": 1e-7, "
                        "\"stop\": 1e-3, \"count\": 5, \"scale\": \"log\"}}],"
                        "\"outputs\": [\"/modes/0/frequency_hz\"]}",
                        1000, &err);
    CHECK(s != NULL, "product spec parses: %s", err.message);
    if (!s)
        return;
    CHECK(rd_sweep_points(s) == 15, "3 x 5 points, got %zu", rd_sweep_points(s));
    for (size_t i = 0; i < 15; i++) {
        CHECK(point_number(s, i, "/ring/tangential_force") == 8 + 2 * (double)(i / 5),
              "point %zu: force from the outer loop", i);
        double want = 1e-7 * pow(10, (double)(i % 5));
        CHECK_REL(point_number(s, i, "/ring/closed_gap"), want, 1e-14,
                  "point %zu: log range (pow rounding only)", i);
    }
    /* The endpoints are the values written, bit for bit (not pow's). */
    CHECK(point_number(s, 0, "/ring/closed_gap") == 1e-7, "log range start exact");
    CHECK(point_number(s, 4, "/ring/closed_gap") == 1e-3, "log range stop exact");
    rd_error_init(&err);
    CHECK(rd_sweep_point_scene(s, 15, &err) == NULL && err.code == RD_EINVAL, "point N refused");
    rd_sweep_free(s);

    s = parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
              "{\"path\": \"/ring/closed_gap\", \"range\": {\"start\": 0.0001, \"stop\": 0.0007, "
              "\"count\": 7}},"
              "{\"path\": \"/discretization/segments\", \"range\": {\"start\": 10, \"stop\": 80, "
              "\"count\": 7, \"scale\": \"log\", \"integer\": true}}],"
              "\"combine\": \"zip\", \"outputs\": [\"/numerics/dof\"]}",
              1000, &err);
    CHECK(s != NULL && rd_sweep_points(s) == 7, "zip: 7 points (%s)", err.message);
    for (size_t i = 0; s && i < 7; i++) {
        CHECK_REL(point_number(s, i, "/ring/closed_gap"), 1e-4 * (double)(i + 1), 1e-15,
                  "zip point %zu: linear range", i);
        double n = 10 * pow(2, (double)i / 2);
        CHECK(point_number(s, i, "/discretization/segments") == round(n),
              "zip point %zu: integer log range %g", i, n);
    }
    rd_sweep_free(s);
}

/* A parameter that writes inside another's value leaves the spec as it was. */
static void test_nested_parameters(void)
{
    rd_error err;
    rd_sweep *s = parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
                        "{\"path\": \"/ring\", \"values\": [{\"diameter\": 0.07}]},"
                        "{\"path\": \"/ring/tangential_force\", \"values\": [8, 12]}],"
                        "\"outputs\": [\"/numerics/dof\"]}",
                        1000, &err);
    CHECK(s != NULL, "nested parameters: %s", err.message);
    for (int pass = 0; s && pass < 2; pass++)
        for (size_t i = 0; i < 2; i++) {
            CHECK(point_number(s, i, "/ring/tangential_force") == (i ? 12 : 8) &&
                      point_number(s, i, "/ring/diameter") == 0.07,
                  "pass %d, point %zu: the listed object plus the force", pass, i);
        }
    /* The row shows the value as listed, not the scene's /ring after the
     * force was written into it. */
    char *row = NULL;
    CHECK(s && rd_sweep_run_point(s, 1, NULL, &row, &err) == RD_OK && row &&
              strncmp(row, "[{\"diameter\":0.07},12,", 22) == 0,
          "row: %s", row ? row : "(null)");
    free(row);
    char *cols = s ? rd_sweep_columns_json(s) : NULL;
    CHECK(cols && strcmp(cols, "[\"/ring\",\"/ring/tangential_force\",\"/numerics/dof\","
                               "\"status\",\"error\"]") == 0,
          "columns: %s", cols ? cols : "(null)");
    free(cols);
    rd_sweep_free(s);
}

/* Latin hypercube: every stratum of every parameter once; the design is the
 * published splitmix64 sequence. */
static void test_latin_hypercube(void)
{
    rd_error err;
    const size_t S = 37;
    char spec[1024];
    snprintf(spec, sizeof spec,
             "{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
             "{\"path\": \"/ring/tangential_force\", \"random\": {\"min\": 5, \"max\": 15}},"
             "{\"path\": \"/ring/closed_gap\", \"random\": {\"min\": 1e-5, \"max\": 1e-3, "
             "\"scale\": \"log\"}},"
             "{\"path\": \"/discretization/segments\", \"values\": [10, 20, 40, 80]}],"
             "\"combine\": \"latin_hypercube\", \"samples\": %zu, \"seed\": 42, "
             "\"outputs\": [\"/numerics/dof\"]}",
             S);
    rd_sweep *s = parse(spec, 1000, &err), *again = parse(spec, 1000, &err);
    CHECK(s && again && rd_sweep_points(s) == S, "LHS parses: %s", err.message);
    if (!s || !again) {
        rd_sweep_free(s);
        rd_sweep_free(again);
        return;
    }
    int hit_f[37] = {0}, hit_g[37] = {0}, per_n[4] = {0}, same = 1;
    for (size_t i = 0; i < S; i++) {
        double f = point_number(s, i, "/ring/tangential_force");
        double g = point_number(s, i, "/ring/closed_gap");
        double n = point_number(s, i, "/discretization/segments");
        int sf = (int)floor((f - 5) / 10 * (double)S);
        int sg = (int)floor(log(g / 1e-5) / log(100.0) * (double)S);
        if (sf >= 0 && sf < (int)S)
            hit_f[sf]++;
        if (sg >= 0 && sg < (int)S)
            hit_g[sg]++;
        for (int k = 0; k < 4; k++)
            per_n[k] += n == 10 * pow(2, k);
        same &= f == point_number(again, i, "/ring/tangential_force") &&
                g == point_number(again, i, "/ring/closed_gap");
    }
    int once = 1;
    for (size_t k = 0; k < S; k++)
        once &= hit_f[k] == 1 && hit_g[k] == 1;
    CHECK(once, "each of the %zu strata of each random parameter hit exactly once", S);
    /* 37 strata over 4 values: floor(u m) gives each value 9 or 10 points. */
    for (int k = 0; k < 4; k++)
        CHECK(per_n[k] == 9 || per_n[k] == 10, "segments value %d used %d times", k, per_n[k]);
    CHECK(same, "the same spec expands to the same points");
    CHECK(strcmp(rd_sweep_hash(s), rd_sweep_hash(again)) == 0, "same spec, same hash");
    rd_sweep_free(s);
    rd_sweep_free(again);

    /* Seed 0, S = 2: the shuffle draws 0xe220a8397b1dcdaf (u = 0.88: no swap),
     * the jitters are the next two outputs of splitmix64 from state 0 (the
     * published test vector of Vigna's splitmix64.c). */
    s = parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
              "{\"path\": \"/ring/tangential_force\", \"random\": {\"min\": 0, \"max\": 1}}],"
              "\"combine\": \"latin_hypercube\", \"samples\": 2, \"seed\": 0,"
              "\"outputs\": [\"/numerics/dof\"]}",
              1000, &err);
    double u1 = (double)(0x6e789e6aa1b965f4u >> 11) * 0x1.0p-53;
    double u2 = (double)(0x06c45d188009454fu >> 11) * 0x1.0p-53;
    /* The scene text carries 15 digits (RD_SWEEP_REAL_DIGITS). */
    CHECK_REL(point_number(s, 0, "/ring/tangential_force"), u1 / 2, 1e-14, "LHS point 0, seed 0");
    CHECK_REL(point_number(s, 1, "/ring/tangential_force"), (1 + u2) / 2, 1e-14,
              "LHS point 1, seed 0");
    rd_sweep_free(s);
}

/* Outputs checked against the analysis' result schema before anything
 * runs: a misspelt member is refused at its /outputs/k with what exists
 * there (a table of empty cells marked ok, before); good nested pointers,
 * aggregates of them and the echoed scene pass. */
static void test_bad_outputs(void)
{
    static const struct {
        const char *outputs, *path, *words;
    } cases[] = {
        {"\"/modes/0/frequency_hzz\"", "/outputs/0", "did you mean \"frequency_hz\""},
        {"\"/numerics/dof\", \"max(/modes/x/frequency_hz)\"", "/outputs/1",
         "no \"x\" in /modes (an array: an index"},
        {"\"/numerics/dof/1\"", "/outputs/0", "a value, no members"},
        {"\"/mode/0\"", "/outputs/0", "at its top level (there: analysis, scene,"},
        {"\"/modes/0/frequency_hz\", \"mean(/modes/3/frequency_hz)\", "
         "\"/scene/ring/diameter\", \"/warnings/0/code\"",
         NULL, NULL},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char spec[1024];
        snprintf(spec, sizeof spec,
                 "{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [{\"path\": "
                 "\"/ring/diameter\", \"values\": [0.07]}], \"outputs\": [%s]}",
                 cases[c].outputs);
        rd_error err;
        rd_sweep *s = parse(spec, 1000, &err);
        if (!cases[c].path) {
            CHECK(s != NULL, "outputs case %zu accepted: %s", c, err.message);
        } else {
            CHECK(!s && err.code == RD_EREQUEST, "outputs case %zu refused (%s)", c,
                  rd_error_code_name(err.code));
            CHECK(strcmp(err.path, cases[c].path) == 0, "outputs case %zu: path %s, want %s", c,
                  err.path, cases[c].path);
            CHECK(strstr(err.message, cases[c].words) != NULL,
                  "outputs case %zu: message \"%s\" lacks \"%s\"", c, err.message, cases[c].words);
        }
        rd_sweep_free(s);
    }
}

/* Bad specs: 400 (invalid_request) with the spec path and the problem named. */
static void test_bad_specs(void)
{
    static const struct {
        const char *params, *extra, *path, *words;
        size_t max;
    } cases[] = {
        {"{\"path\": \"/ring/tangetial_force\", \"values\": [8]}", "", "/parameters/0/values/0",
         "unknown field \"tangetial_force\"", 1000},
        {"{\"path\": \"/discretization/segments\", \"values\": [20, 2001]}", "",
         "/parameters/0/values/1", "2001 is out of range: allowed 3 to 2000", 1000},
        {"{\"path\": \"/discretization/segments\", \"range\": {\"start\": 10, \"stop\": 3000, "
         "\"count\": 3}}",
         "", "/parameters/0/range", "allowed 3 to 2000", 1000},
        {"{\"path\": \"/engine/speed_rpm\", \"values\": [1000]}", "", "/parameters/0/values/0",
         "the modal analysis does not read a top-level \"engine\"", 1000},
        {"{\"path\": \"/ring/diameter\", \"values\": []}", "", "/parameters/0/values", "non-empty",
         1000},
        {"{\"path\": \"/ring/diameter\", \"range\": {\"start\": 0.05, \"stop\": 0.1, \"count\": "
         "1000}}, {\"path\": \"/ring/closed_gap\", \"range\": {\"start\": 1e-4, \"stop\": 1e-3, "
         "\"count\": 1000}}, {\"path\": \"/ring/tangential_force\", \"range\": {\"start\": 5, "
         "\"stop\": 15, \"count\": 1000}}",
         "", "/parameters", "1000000000 points", 1000000000},
        {"{\"path\": \"/ring/diameter\", \"range\": {\"start\": 0.05, \"stop\": 0.1, \"count\": "
         "200}}",
         "", "/parameters", "ringdyn sweep run", 100},
        {"{\"path\": \"/ring/diameter\", \"random\": {\"min\": 0.05, \"max\": 0.1}}", "",
         "/parameters/0", "latin_hypercube", 1000},
        {"{\"path\": \"/ring/diameter\", \"values\": [0.07]}, {\"path\": \"/ring/diameter\", "
         "\"values\": [0.08]}",
         "", "/parameters", "both set /ring/diameter", 1000},
        {"{\"path\": \"/ring/diameter\", \"values\": [0.07], \"rnage\": 1}", "", "/parameters/0",
         "unknown field \"rnage\"", 1000},
        {"{\"path\": \"/ring/diameter\", \"values\": [0.07, 0.08]}, {\"path\": "
         "\"/ring/closed_gap\","
         " \"values\": [1e-4]}",
         ", \"combine\": \"zip\"", "/parameters/1", "one length", 1000},
        {"{\"path\": \"/ring/diameter\", \"range\": {\"start\": 0, \"stop\": 0.1, \"count\": 3, "
         "\"scale\": \"log\"}}",
         "", "/parameters/0/range", "start > 0", 1000},
        {"{\"path\": \"ring/diameter\", \"values\": [0.07]}", "", "/parameters/0", "JSON Pointer",
         1000},
        {"{\"path\": \"/ring/diameter\", \"values\": [0.07]}", ", \"seed\": 3", "/seed",
         "samples and seed are for", 1000},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char spec[2048];
        snprintf(spec, sizeof spec,
                 "{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [%s]%s, "
                 "\"outputs\": [\"/numerics/dof\"]}",
                 cases[c].params, cases[c].extra);
        rd_error err;
        rd_sweep *s = parse(spec, cases[c].max, &err);
        CHECK(!s && err.code == RD_EREQUEST && rd_api_http_status(err.code) == 400,
              "case %zu refused with a 400, got %s", c, rd_error_code_name(err.code));
        CHECK(strcmp(err.path, cases[c].path) == 0, "case %zu: path %s, want %s", c, err.path,
              cases[c].path);
        CHECK(strstr(err.message, cases[c].words) != NULL, "case %zu: message \"%s\" lacks \"%s\"",
              c, err.message, cases[c].words);
        rd_sweep_free(s);
    }
    rd_error err;
    CHECK(!parse("{\"base\": {\"analysis\": \"modal\", \"ring\": {\"diameter\": -1}}, "
                 "\"parameters\": [{\"path\": \"/ring/closed_gap\", \"values\": [1e-4]}], "
                 "\"outputs\": [\"/x\"]}",
                 1000, &err) &&
              strcmp(err.path, "/base/ring/diameter") == 0,
          "an invalid base names its field under /base: %s", err.path);
    CHECK(!parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [{\"path\": "
                 "\"/ring/closed_gap\", \"values\": [1e-4]}], \"outputs\": [\"max/x\"]}",
                 1000, &err) &&
              strcmp(err.path, "/outputs/0") == 0,
          "a malformed output is named: %s", err.path);
    CHECK(!parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [], \"outputs\": "
                 "[\"/x\"]}",
                 1000, &err) &&
              strcmp(err.path, "/parameters") == 0,
          "no parameters: %s", err.path);
    CHECK(!parse("[1, 2", 1000, &err) && err.code == RD_EJSON, "not JSON");
}

/* One point run through the sweep against the same scene run directly. */
static void test_outputs(void)
{
    rd_error err;
    rd_sweep *s = parse("{\"base\": {\"analysis\": \"modal\", \"modal\": {\"modes\": 4}}, "
                        "\"parameters\": [{\"path\": \"/discretization/segments\", \"values\": "
                        "[12]}], \"outputs\": [\"/modes/1/frequency_hz\", "
                        "\"max(/modes/*/frequency_hz)\", \"min(/modes/*/error_estimate)\", "
                        "\"mean(/modes/*/frequency_hz)\", \"count(/modes)\"]}",
                        1000, &err);
    const char *scene = "{\"analysis\": \"modal\", \"modal\": {\"modes\": 4}, "
                        "\"discretization\": {\"segments\": 12}}";
    rd_scene *sc = NULL;
    char *result = NULL, *row = NULL;
    CHECK(s && rd_scene_parse(scene, strlen(scene), &sc, &err) == RD_OK &&
              rd_scene_run(sc, NULL, &result, &err) == RD_OK,
          "direct run: %s", err.message);
    CHECK(s && rd_sweep_run_point(s, 0, NULL, &row, &err) == RD_OK, "point 0: %s", err.message);
    json_t *res = result ? json_loads(result, 0, NULL) : NULL,
           *r = row ? json_loads(row, 0, NULL) : NULL;
    double f[4], e[4], fmax = 0, emin = INFINITY, fsum = 0;
    for (int k = 0; k < 4; k++) {
        f[k] = json_number_value(json_object_get(
            json_array_get(json_object_get(res, "modes"), (size_t)k), "frequency_hz"));
        e[k] = json_number_value(json_object_get(
            json_array_get(json_object_get(res, "modes"), (size_t)k), "error_estimate"));
        fmax = fmax > f[k] ? fmax : f[k];
        emin = emin < e[k] ? emin : e[k];
        fsum += f[k];
    }
    /* Results carry 10 digits; a row re-writes them with 15, exactly. */
    CHECK(json_number_value(json_array_get(r, 0)) == 12, "parameter cell");
    CHECK(json_number_value(json_array_get(r, 1)) == f[1], "pointer output");
    CHECK(json_number_value(json_array_get(r, 2)) == fmax, "max over a star");
    CHECK(json_number_value(json_array_get(r, 3)) == emin, "min over a star");
    CHECK_REL(json_number_value(json_array_get(r, 4)), fsum / 4, 1e-14, "mean over a star");
    CHECK(json_integer_value(json_array_get(r, 5)) == 4, "count of an array");
    CHECK(json_is_string(json_array_get(r, 6)) &&
              strcmp(json_string_value(json_array_get(r, 6)), "ok") == 0 &&
              json_is_null(json_array_get(r, 7)),
          "status ok, no error");
    json_decref(res);
    json_decref(r);
    free(result);
    free(row);
    rd_scene_free(sc);
    rd_sweep_free(s);
}

static int stop_now(void *ctx, double fraction)
{
    (void)ctx;
    (void)fraction;
    return 1;
}

/* A combination the scene refuses, and a run that fails, are rows. */
static void test_failed_points(void)
{
    rd_error err;
    /* A 10 mm wide section fits the thesis ring (at most d/4 = 19 mm) and
     * the 20 mm ring fits the thesis width, but not each other (d/4 = 5 mm). */
    rd_sweep *s = parse("{\"base\": {\"analysis\": \"modal\", \"modal\": {\"modes\": 2, "
                        "\"error_estimate\": false}}, \"parameters\": ["
                        "{\"path\": \"/ring/diameter\", \"values\": [0.0765, 0.02]},"
                        "{\"path\": \"/ring/radial_width\", \"values\": [0.0029, 0.01]}],"
                        "\"outputs\": [\"/modes/0/frequency_hz\"]}",
                        1000, &err);
    CHECK(s != NULL, "each value alone is valid: %s", err.message);
    char *rows[4] = {NULL};
    for (size_t i = 0; s && i < 4; i++)
        CHECK(rd_sweep_run_point(s, i, NULL, &rows[i], &err) == RD_OK, "point %zu is a row", i);
    json_t *bad = rows[3] ? json_loads(rows[3], 0, NULL) : NULL;
    CHECK(json_is_null(json_array_get(bad, 2)) &&
              strcmp(json_string_value(json_array_get(bad, 3)), "invalid_scene") == 0 &&
              strstr(json_string_value(json_array_get(bad, 4)), "radial_width") != NULL,
          "the invalid combination: null output, status invalid_scene, the message: %s",
          rows[3] ? rows[3] : "(none)");
    json_t *good = rows[0] ? json_loads(rows[0], 0, NULL) : NULL;
    CHECK(json_number_value(json_array_get(good, 2)) > 0, "the others ran: %s",
          rows[0] ? rows[0] : "(none)");
    char *table = s ? rd_sweep_table_json(s, rows, 4, &err) : NULL;
    json_t *t = table ? json_loads(table, 0, NULL) : NULL;
    CHECK(json_array_size(json_object_get(t, "rows")) == 4 &&
              json_array_size(json_object_get(t, "columns")) == 5,
          "table of 4 rows x 5 columns");
    rd_monitor mon = {stop_now, NULL};
    char *row = NULL;
    rd_error_init(&err);
    CHECK(s && rd_sweep_run_point(s, 0, &mon, &row, &err) == RD_ECANCELED && !row,
          "a cancelled point cancels the sweep, no row");
    json_decref(t);
    free(table);
    json_decref(bad);
    json_decref(good);
    for (int i = 0; i < 4; i++)
        free(rows[i]);
    rd_sweep_free(s);

    /* A lift run stopped by its work bound: status not_converged (or what
     * the analysis reports), its message, a null output. */
    s = parse("{\"base\": {\"analysis\": \"lift\", \"discretization\": {\"segments\": 4}, "
              "\"engine\": {\"cycles\": 0.05}, \"numerics\": {\"error_estimate\": false}},"
              "\"parameters\": [{\"path\": \"/numerics/max_steps\", \"values\": [100]}],"
              "\"outputs\": [\"count(/events)\"]}",
              1000, &err);
    CHECK(s && rd_sweep_run_point(s, 0, NULL, &row, &err) == RD_OK, "failed run is a row");
    json_t *r = row ? json_loads(row, 0, NULL) : NULL;
    const char *status = json_string_value(json_array_get(r, 2));
    CHECK(status && strcmp(status, "ok") != 0 && json_is_string(json_array_get(r, 3)),
          "the run's error in the row: %s", row ? row : "(none)");
    json_decref(r);
    free(row);
    rd_sweep_free(s);
}

static void test_csv_and_chunks(void)
{
    rd_error err;
    rd_error_init(&err);
    char *rec =
        rd_sweep_csv_record("[1.5, \"a,b\", \"say \\\"hi\\\"\", null, true, 7, [1,2]]", &err);
    CHECK(rec && strcmp(rec, "1.5,\"a,b\",\"say \"\"hi\"\"\",,true,7,\"[1,2]\"\r\n") == 0,
          "RFC 4180 record: %s", rec ? rec : "(null)");
    free(rec);
    CHECK(rd_sweep_csv_record("{}", &err) == NULL, "not an array");

    rd_sweep *s = parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
                        "{\"path\": \"/ring/closed_gap\", \"range\": {\"start\": 1e-4, \"stop\": "
                        "1e-3, \"count\": 10}}, {\"path\": \"/ring/tangential_force\", "
                        "\"values\": [5, 10, 15]}], \"outputs\": [\"/numerics/dof\"]}",
                        1000, &err);
    size_t n = s ? rd_sweep_points(s) : 0;
    for (size_t k = 1; s && k <= n; k++) {
        size_t next = 0, first, end;
        int ok = 1;
        for (size_t c = 0; c < k; c++) {
            ok &= rd_sweep_chunk_range(s, c, k, &first, &end, &err) == RD_OK && first == next &&
                  end > first;
            next = end;
        }
        CHECK(ok && next == n, "%zu chunks partition the %zu points", k, n);
    }
    rd_error_init(&err);
    size_t first, end;
    CHECK(s && rd_sweep_chunk_range(s, 0, n + 1, &first, &end, &err) == RD_EREQUEST,
          "more chunks than points refused");
    rd_sweep_free(s);
}

/* Runs every point of a sweep; the table JSON (caller frees). */
static char *run_table(const rd_sweep *s)
{
    rd_error err;
    size_t n = rd_sweep_points(s);
    char **rows = calloc(n, sizeof *rows), *table = NULL;
    int ok = rows != NULL;
    for (size_t i = 0; ok && i < n; i++)
        ok = rd_sweep_run_point(s, i, NULL, &rows[i], &err) == RD_OK;
    if (ok)
        table = rd_sweep_table_json(s, rows, n, &err);
    for (size_t i = 0; rows && i < n; i++)
        free(rows[i]);
    free(rows);
    return table;
}

/* The fidelity table of the thesis ring (modal): the estimate and the error
 * against the finest run agree where the finest run's own error is small. */
static void test_fidelity(void)
{
    rd_error err;
    rd_error_init(&err);
    const char *scene = "{\"analysis\": \"modal\", \"modal\": {\"modes\": 4, "
                        "\"error_estimate\": false}}";
    const double seg[] = {10, 20, 40, 320};
    rd_sweep_fidelity_opts o = {seg, 4, NULL, 0, NULL, 0};
    char *spec = rd_sweep_fidelity_spec(scene, strlen(scene), &o, &err);
    rd_sweep *s = spec ? parse(spec, 1000, &err) : NULL;
    CHECK(s && rd_sweep_points(s) == 4, "fidelity spec: %s", err.message);
    char *table = s ? run_table(s) : NULL;
    char *fid = table ? rd_sweep_fidelity_table(table, &err) : NULL;
    json_t *t = fid ? json_loads(fid, 0, NULL) : NULL, *rows = json_object_get(t, "rows");
    json_t *cols = json_object_get(t, "columns");
    static const char *const want[] = {"/discretization/segments",
                                       "/numerics/wall_s",
                                       "max(/modes/*/error_estimate)",
                                       "error_vs_finest",
                                       "estimate_covers",
                                       "changes",
                                       "basis",
                                       "error_on_basis",
                                       "pareto",
                                       "status",
                                       "error"};
    CHECK(json_array_size(cols) == 11, "11 columns, not %zu", json_array_size(cols));
    for (size_t k = 0; k < 11 && k < json_array_size(cols); k++)
        CHECK(strcmp(json_string_value(json_array_get(cols, k)), want[k]) == 0, "column %zu: %s", k,
              want[k]);
    for (size_t i = 0; i < json_array_size(rows); i++) {
        json_t *r = json_array_get(rows, i);
        double est = json_number_value(json_array_get(r, 2));
        double vs = json_number_value(json_array_get(r, 3));
        const char *basis = json_string_value(json_array_get(r, 6));
        double on = json_number_value(json_array_get(r, 7));
        /* The modal estimate covers the segment count, all a setting changes
         * here: its basis unless the measured difference is larger. */
        CHECK(strcmp(json_string_value(json_array_get(r, 4)), "segments") == 0, "covers segments");
        CHECK(strcmp(json_string_value(json_array_get(r, 5)), i == 3 ? "" : "segments") == 0,
              "changes: the segment count but for the finest run");
        CHECK(basis && strcmp(basis, est >= vs ? "estimate" : "measured") == 0,
              "n = %g: basis %s (estimate %g, measured %g)", seg[i], basis, est, vs);
        CHECK(on == (est >= vs ? est : vs), "error on its basis, never below the measured one");
        if (i == 3) {
            CHECK(vs == 0, "the finest run against itself");
            continue;
        }
        /* The estimate (switched on by the fidelity sweep although the scene
         * had it off) claims the true error to a factor 3; the error against
         * n = 320 is the true error minus n = 320's own (< 1e-4 of these). */
        CHECK(est > 0 && vs > est / 3 && vs < est * 3, "n = %g: estimate %g vs finest %g", seg[i],
              est, vs);
        CHECK(json_is_boolean(json_array_get(r, 8)), "pareto flag");
    }
    json_decref(t);
    free(fid);
    free(table);
    free(spec);
    rd_sweep_free(s);

    /* A model parameter is only accepted where the scene schema has one. */
    const char *const models[] = {"no_such_model"};
    rd_sweep_fidelity_opts m = {seg, 2, NULL, 0, models, 1};
    rd_error_init(&err);
    spec = rd_sweep_fidelity_spec(scene, strlen(scene), &m, &err);
    s = spec ? parse(spec, 1000, &err) : NULL;
    CHECK(!s && err.code == RD_EREQUEST && strncmp(err.path, "/parameters/1/values/0", 22) == 0,
          "a model the schema does not have is refused: %s %s", err.path, err.message);
    free(spec);
    rd_sweep_free(s);

    const char *lift = "{\"analysis\": \"lift\", \"engine\": {\"cycles\": 0.05}}";
    rd_error_init(&err);
    spec = rd_sweep_fidelity_spec(lift, strlen(lift), NULL, &err);
    s = spec ? parse(spec, 1000, &err) : NULL;
    CHECK(s && rd_sweep_points(s) == 16, "lift: 4 segment counts x 4 rtol: %s", err.message);
    rd_sweep_free(s);
    free(spec);
    rd_error_init(&err);
    const char *bad = "{\"analysis\": \"modal\", \"ring\": 1}";
    spec = rd_sweep_fidelity_spec(bad, strlen(bad), NULL, &err);
    CHECK(!spec && strcmp(err.path, "/ring") == 0, "an invalid scene gives its own error: %s",
          err.path);
    free(spec);
}

/* The basis of a lift row's error (rd_sweep_fidelity_table): the lift
 * estimate covers the time integration, and the segment count only where a
 * flexible ring had its n/2 run.  A table like the tilted piston's (issue
 * 44): 4 segments estimate 0.3 % but sit 14 % from the finest run. */
static void test_fidelity_basis(void)
{
    const char *table =
        "{\"columns\": [\"/discretization/segments\", \"/numerics/rtol\", \"/numerics/wall_s\", "
        "\"/numerics/error_estimate\", \"all(/lift)\", \"/scene/groove/axial_clearance\", "
        "\"/numerics/model/name\", \"/numerics/segments_check\", \"status\", \"error\"], "
        "\"rows\": ["
        /* 0: time only, segments differ: measured */
        "[4, 1e-4, 0.3, 0.003, [0, 1.4e-5], 1e-4, \"full\", null, \"ok\", null],"
        /* 1: same segments as the finest, rtol differs, time covered: estimate */
        "[32, 1e-4, 10, 0.0028, [0, 1e-9], 1e-4, \"full\", 16, \"ok\", null],"
        /* 2: segments and time covered: estimate */
        "[16, 1e-4, 3, 0.011, [0, 4.9e-7], 1e-4, \"full\", 8, \"ok\", null],"
        /* 3: covered, but the estimate is below what was measured: measured */
        "[16, 1e-5, 3.1, 0.001, [0, 4.9e-7], 1e-4, \"full\", 8, \"ok\", null],"
        /* 4: a rigid ring's n/2 check is not in its lift estimate: measured */
        "[16, 1e-6, 0.1, 0.002, [0, 5e-7], 1e-4, \"rigid\", 8, \"ok\", null],"
        /* 5: the finest run */
        "[32, 1e-7, 11, 0.0028, [0, 0], 1e-4, \"full\", 16, \"ok\", null],"
        /* 6: failed */
        "[8, 1e-4, 1, null, null, null, null, null, \"time_limit\", \"too slow\"]]}";
    static const struct {
        const char *covers, *changes, *basis;
        double error;
    } want[] = {{"time", "segments time", "measured", 0.14},
                {"segments time", "time", "estimate", 0.0028},
                {"segments time", "segments time", "estimate", 0.011},
                {"segments time", "segments time", "measured", 0.0049},
                {"time", "segments time model", "measured", 0.005},
                {"segments time", "", "estimate", 0.0028}};
    rd_error err;
    rd_error_init(&err);
    char *fid = rd_sweep_fidelity_table(table, &err);
    json_t *t = fid ? json_loads(fid, 0, NULL) : NULL, *rows = json_object_get(t, "rows");
    json_t *cols = json_object_get(t, "columns");
    CHECK(json_array_size(cols) == 13, "lift fidelity columns: %zu (%s)", json_array_size(cols),
          err.message);
    CHECK(json_array_size(rows) == 7, "one row per point");
    for (size_t i = 0; i < 6 && i < json_array_size(rows); i++) {
        json_t *r = json_array_get(rows, i);
        const char *cov = json_string_value(json_array_get(r, 6)),
                   *chg = json_string_value(json_array_get(r, 7)),
                   *b = json_string_value(json_array_get(r, 8));
        CHECK(cov && strcmp(cov, want[i].covers) == 0, "row %zu covers '%s'", i, cov);
        CHECK(chg && strcmp(chg, want[i].changes) == 0, "row %zu changes '%s'", i, chg);
        CHECK(b && strcmp(b, want[i].basis) == 0, "row %zu basis %s", i, b);
        CHECK_REL(json_number_value(json_array_get(r, 9)), want[i].error, 1e-9,
                  "row %zu: error on its basis", i);
    }
    json_t *failed = json_array_get(rows, 6);
    CHECK(json_is_null(json_array_get(failed, 6)) && json_is_null(json_array_get(failed, 8)) &&
              json_is_null(json_array_get(failed, 9)) && json_is_false(json_array_get(failed, 10)),
          "a failed row has no basis and is off the front");
    /* The front on the error on its basis: the rigid row (cheapest, 0.5 %),
     * 16/1e-5 (0.49 %) and 32/1e-4 (0.28 %); 4 segments (0.3 s, 14 %) is
     * dominated by the rigid row, which its estimate alone (0.3 %) is not. */
    static const int front[] = {0, 1, 0, 1, 1, 0};
    for (size_t i = 0; i < 6 && i < json_array_size(rows); i++)
        CHECK(json_is_true(json_array_get(json_array_get(rows, i), 10)) == front[i],
              "row %zu pareto %d", i, front[i]);
    json_decref(t);
    free(fid);
}

/* rd_sweep_chunk_read (the service's Slurm executor): every chunk of `dir`
 * gives back exactly the rows written; a chunk not there is RD_ENOTFOUND, a
 * chunk of another spec or a truncated one RD_EINVAL with no row left. */
static void check_chunk_read(const rd_sweep *s, const char *dir, size_t k, char *const *rows)
{
    rd_error err;
    rd_error_init(&err);
    size_t n = rd_sweep_points(s), same = 0;
    char **back = calloc(n, sizeof *back);
    for (size_t c = 0; back && c < k; c++)
        CHECK(rd_sweep_chunk_read(s, dir, c, k, back, &err) == RD_OK, "chunk %zu read (%s)", c,
              err.message);
    for (size_t i = 0; back && i < n; i++)
        same += back[i] && strcmp(back[i], rows[i]) == 0;
    CHECK(same == n, "the rows read back are the rows written, byte for byte (%zu of %zu)", same,
          n);
    rd_error_init(&err);
    CHECK(rd_sweep_chunk_read(s, dir, 0, k + 1, back, &err) == RD_ENOTFOUND,
          "a chunk of another split is not there (%s)", err.message);
    rd_sweep *other = parse("{\"base\": {\"analysis\": \"modal\"}, \"parameters\": ["
                            "{\"path\": \"/ring/diameter\", \"values\": [0.07, 0.08, 0.09, "
                            "0.1, 0.11, 0.12]}], \"outputs\": [\"/modes/0/frequency_hz\"]}",
                            1000, &err);
    char **none = calloc(n, sizeof *none);
    size_t left = 0;
    rd_error_init(&err);
    CHECK(other && none && rd_sweep_chunk_read(other, dir, 1, k, none, &err) == RD_EINVAL &&
              strstr(err.message, "head differs"),
          "a chunk of another spec is refused (%s)", err.message);
    char path[160], *name = rd_sweep_chunk_name(2, k);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    struct stat st;
    int cut = stat(path, &st) == 0 && truncate(path, st.st_size - 4) == 0;
    rd_error_init(&err);
    CHECK(cut && none && rd_sweep_chunk_read(s, dir, 2, k, none, &err) == RD_EINVAL,
          "a truncated chunk is refused (%s)", err.message);
    for (size_t i = 0; none && i < n; i++)
        left += none[i] != NULL;
    CHECK(left == 0, "no row is left from a refused chunk");
    if (cut) { /* as it was, for the reduce below */
        FILE *f = fopen(path, "a");
        fputs("\n]}\n", f);
        fclose(f);
    }
    free(name);
    free(none);
    rd_sweep_free(other);
    for (size_t i = 0; back && i < n; i++)
        free(back[i]);
    free(back);
}

/* The in-memory table (what a service builds) and the reduced chunk files
 * (what a cluster writes) are the same bytes, JSON and CSV. */
static void test_table_matches_reduce(void)
{
    rd_error err;
    rd_sweep *s = parse("{\"base\": {\"analysis\": \"modal\", \"modal\": {\"modes\": 2, "
                        "\"error_estimate\": false}}, \"parameters\": ["
                        "{\"path\": \"/ring/diameter\", \"values\": [0.0765, 0.02]},"
                        "{\"path\": \"/ring/radial_width\", \"values\": [0.0029, 0.01, 0.004]}],"
                        "\"outputs\": [\"/modes/0/frequency_hz\", \"/numerics/wall_s\"]}",
                        1000, &err);
    size_t n = s ? rd_sweep_points(s) : 0, k = 4;
    char **rows = calloc(n, sizeof *rows);
    for (size_t i = 0; rows && i < n; i++)
        rd_sweep_run_point(s, i, NULL, &rows[i], &err);
    char dir[] = "/tmp/test_sweep_XXXXXX";
    int ok = s && rows && mkdtemp(dir) != NULL;
    for (size_t c = 0; ok && c < k; c++) {
        size_t first, end;
        char *name = rd_sweep_chunk_name(c, k), *head = rd_sweep_chunk_head(s, c, k), path[128];
        rd_sweep_chunk_range(s, c, k, &first, &end, &err);
        snprintf(path, sizeof path, "%s/%s", dir, name);
        FILE *f = fopen(path, "w");
        ok = f && fputs(head, f) != EOF;
        for (size_t i = first; ok && i < end; i++)
            ok = fputs(rows[i], f) != EOF && fputs(i + 1 < end ? ",\n" : "\n", f) != EOF;
        ok = f && fputs("]}\n", f) != EOF && fclose(f) == 0 && ok;
        free(name);
        free(head);
    }
    check_chunk_read(s, dir, k, rows);
    for (int csv = 0; ok && csv < 2; csv++) {
        char *mem = NULL, *table = csv ? rd_sweep_table_csv(s, rows, n, &err)
                                       : rd_sweep_table_json(s, rows, n, &err);
        size_t size = 0;
        FILE *out = open_memstream(&mem, &size);
        int rc = rd_sweep_reduce(dir, csv, out, &err);
        fclose(out);
        CHECK(rc == RD_OK && table && strncmp(mem, table, strlen(table)) == 0 &&
                  strcmp(mem + strlen(table), csv ? "" : "\n") == 0,
              "%s: reduce of %zu chunks = the in-memory table (%s)", csv ? "CSV" : "JSON", k,
              err.message);
        free(mem);
        free(table);
    }
    CHECK(ok, "chunk files written");
    for (size_t c = 0; c < k; c++) {
        char *name = rd_sweep_chunk_name(c, k), path[128];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        remove(path);
        free(name);
    }
    rmdir(dir);
    for (size_t i = 0; rows && i < n; i++)
        free(rows[i]);
    free(rows);
    rd_sweep_free(s);
}

typedef struct {
    const rd_sweep *s;
    size_t from, step;
    char **rows;
    int failed;
} worker;

/* Runs points from, from + step, ... of a shared sweep. */
static void *work(void *arg)
{
    worker *w = arg;
    rd_error err;
    rd_error_init(&err);
    for (size_t i = w->from; i < rd_sweep_points(w->s); i += w->step)
        w->failed |= rd_sweep_run_point(w->s, i, NULL, &w->rows[i], &err) != RD_OK;
    return NULL;
}

/* One parsed sweep run by two threads at once (as a server's workers would)
 * gives the rows one thread gives. */
static void test_threads(void)
{
    rd_error err;
    rd_sweep *s = parse("{\"base\": {\"analysis\": \"pretension\"}, \"parameters\": ["
                        "{\"path\": \"/ring/tangential_force\", \"values\": [6, 8, 10, 12, 14]},"
                        "{\"path\": \"/discretization/segments\", \"values\": [8, 12]}],"
                        "\"outputs\": [\"/gap_opening_inner\", \"/numerics/error_estimate\"]}",
                        1000, &err);
    size_t n = s ? rd_sweep_points(s) : 0;
    char **one = calloc(n, sizeof *one), **two = calloc(n, sizeof *two);
    worker w1 = {s, 0, 1, one, 0}, a = {s, 0, 2, two, 0}, b = {s, 1, 2, two, 0};
    pthread_t ta, tb;
    if (!s || !one || !two || pthread_create(&ta, NULL, work, &a) != 0) {
        CHECK(0, "set-up: %s", err.message);
    } else {
        int second = pthread_create(&tb, NULL, work, &b) == 0;
        if (!second)
            work(&b);
        pthread_join(ta, NULL);
        if (second)
            pthread_join(tb, NULL);
        work(&w1);
        int same = !a.failed && !b.failed && !w1.failed;
        for (size_t i = 0; same && i < n; i++)
            same = one[i] && two[i] && strcmp(one[i], two[i]) == 0;
        CHECK(same, "2 threads on one sweep give the rows of 1 thread");
    }
    for (size_t i = 0; i < n; i++) {
        free(one[i]);
        free(two[i]);
    }
    free(one);
    free(two);
    rd_sweep_free(s);
}

int main(void)
{
    test_jsonptr();
    test_product_and_ranges();
    test_nested_parameters();
    test_latin_hypercube();
    test_bad_specs();
    test_bad_outputs();
    test_outputs();
    test_failed_points();
    test_csv_and_chunks();
    test_fidelity();
    test_fidelity_basis();
    test_table_matches_reduce();
    test_threads();
    return check_done();
}
