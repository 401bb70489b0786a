/*
 * test_calibration — calibrations through the public scene functions, on the
 * thesis ring pack with pinned rings (tens of ms a run):
 *   - synthetic recovery: measurements made by ringdyn itself at known
 *     values of two discharge coefficients and the oil ring's leak area
 *     (its effective gap) are fitted back to 1e-4 without noise, and with
 *     seeded noise within two reported standard errors in >= 90 % of 50
 *     trials (a coverage check of the standard errors);
 *   - a parameter the data cannot fix (the top ring's tangential force: a
 *     pinned ring's gas flows do not read it) is reported not identifiable,
 *     with no standard error, beside one they fix (tests/core/test_fit.c has
 *     the exact product);
 *   - the shipped example (blow-by at 4 operating points) in <= 60 runs;
 *   - bad specs: 400 with the field named.
 * Usage: test_calibration EXAMPLES_DIR
 */
#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_api.h"
#include "seeded_normal.h"

static const char *examples;

static const char *const params[3] = {"/rings/0/discharge_coefficient",
                                      "/rings/1/discharge_coefficient", "/rings/2/leak_area_m2"};
static const double truth[3] = {0.62, 0.78, 5.5e-8};
static const double lo[3] = {0.3, 0.3, 1e-8}, hi[3] = {1.0, 1.0, 2e-7};

/* The thesis ring pack at full load, its rings pinned, 2 cycles. */
static json_t *base_scene(double rtol)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/thesis_ringpack_full_load_2400rpm.json", examples);
    json_t *s = json_load_file(path, 0, NULL);
    json_object_del(s, "name");
    json_object_del(s, "description");
    size_t i;
    json_t *r;
    json_array_foreach(json_object_get(s, "rings"), i, r)
        json_object_set_new(r, "pinned", json_string("lower"));
    json_object_set_new(json_object_get(s, "engine"), "cycles", json_integer(2));
    json_object_set_new(s, "numerics", json_pack("{s:b, s:f}", "error_estimate", 0, "rtol", rtol));
    json_object_set_new(s, "output", json_pack("{s:f}", "step_deg", 10.0));
    return s;
}

/* Runs `scene` (borrowed) and returns its result (new reference) or NULL. */
static json_t *run(json_t *scene)
{
    char *text = json_dumps(scene, JSON_COMPACT | JSON_REAL_PRECISION(17)), *out = NULL;
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    json_t *r = NULL;
    if (rd_scene_parse(text, strlen(text), &s, &err) == RD_OK &&
        rd_scene_run(s, NULL, &out, &err) == RD_OK)
        r = json_loads(out, 0, NULL);
    CHECK(r != NULL, "run: %s %s", err.path, err.message);
    free(out);
    free(text);
    rd_scene_free(s);
    return r;
}

/* The measurements at two operating points: blow-by and the second land's
 * pressure trace at each (the model's values at `truth`, noise added by the
 * caller). */
static json_t *measurements(json_t *base)
{
    static const double rpm[2] = {1500, 4800};
    json_t *ms = json_array();
    for (int k = 0; k < 2; k++) {
        json_t *scene = json_deep_copy(base), *rings = json_object_get(scene, "rings");
        json_object_set_new(json_object_get(scene, "engine"), "speed_rpm", json_real(rpm[k]));
        json_object_set_new(json_array_get(rings, 0), "discharge_coefficient", json_real(truth[0]));
        json_object_set_new(json_array_get(rings, 1), "discharge_coefficient", json_real(truth[1]));
        json_object_set_new(json_array_get(rings, 2), "leak_area_m2", json_real(truth[2]));
        json_t *r = run(scene);
        json_t *set = json_pack("{s:f}", "/engine/speed_rpm", rpm[k]);
        double bb = json_real_value(json_object_get(json_object_get(r, "blowby"), "l_per_min"));
        json_array_append_new(ms, json_pack("{s:O, s:s, s:f, s:f}", "set", set, "observe",
                                            "/blowby/l_per_min", "value", bb, "sigma", 0.01 * bb));
        json_t *trace =
            json_object_get(json_array_get(json_object_get(r, "volumes"), 2), "pressure_pa");
        json_array_append_new(ms,
                              json_pack("{s:o, s:s, s:O, s:f}", "set", set, "observe",
                                        "/volumes/2/pressure_pa", "value", trace, "sigma", 2000.0));
        json_decref(r);
        json_decref(scene);
    }
    return ms;
}

static json_t *spec_of(json_t *base, json_t *ms, const double *start)
{
    json_t *ps = json_array();
    for (int j = 0; j < 3; j++) {
        json_t *p = json_pack("{s:s, s:f, s:f}", "path", params[j], "min", lo[j], "max", hi[j]);
        if (start)
            json_object_set_new(p, "start", json_real(start[j]));
        json_array_append_new(ps, p);
    }
    return json_pack("{s:s, s:O, s:o, s:O}", "analysis", "calibration", "base", base, "parameters",
                     ps, "measurements", ms);
}

/* Each value of each measurement + sigma * N(0, 1). */
static json_t *noisy(json_t *ms, uint64_t *seed)
{
    json_t *out = json_deep_copy(ms);
    size_t j;
    json_t *m;
    json_array_foreach(out, j, m)
    {
        double sd = json_number_value(json_object_get(m, "sigma"));
        json_t *v = json_object_get(m, "value");
        if (json_is_number(v)) {
            json_object_set_new(m, "value",
                                json_real(json_number_value(v) + sd * seeded_normal(seed)));
            continue;
        }
        for (size_t i = 0; i < json_array_size(v); i++)
            json_array_set_new(
                v, i,
                json_real(json_number_value(json_array_get(v, i)) + sd * seeded_normal(seed)));
    }
    return out;
}

/* Runs a spec; the result (new reference) or NULL with err filled. */
static json_t *calibrate(json_t *spec, rd_error *err)
{
    char *text = json_dumps(spec, JSON_COMPACT | JSON_REAL_PRECISION(17)), *out = NULL;
    rd_scene *s = NULL;
    rd_error_init(err);
    json_t *r = NULL;
    if (rd_scene_parse(text, strlen(text), &s, err) == RD_OK &&
        rd_scene_run(s, NULL, &out, err) == RD_OK)
        r = json_loads(out, 0, NULL);
    free(out);
    free(text);
    rd_scene_free(s);
    return r;
}

static double param(json_t *r, int j, const char *key)
{
    return json_number_value(
        json_object_get(json_array_get(json_object_get(r, "parameters"), (size_t)j), key));
}

static void test_recovery(void)
{
    json_t *base = base_scene(1e-8), *ms = measurements(base);
    json_t *spec = spec_of(base, ms, NULL);
    rd_error err;
    json_t *r = calibrate(spec, &err);
    CHECK(r != NULL, "noise-free fit: %s %s", err.path, err.message);
    for (int j = 0; r && j < 3; j++)
        CHECK_REL(param(r, j, "value"), truth[j], 1e-4, "%s recovered without noise", params[j]);
    CHECK(r && json_is_true(json_object_get(r, "identifiable")) &&
              json_is_true(json_object_get(r, "converged")),
          "identifiable and converged");
    printf("noise-free: %lld runs, values %.9g %.9g %.9g\n",
           (long long)json_integer_value(json_object_get(r, "runs")), param(r, 0, "value"),
           param(r, 1, "value"), param(r, 2, "value"));
    json_decref(r);
    json_decref(spec);
    json_decref(ms);
    json_decref(base);
}

/* 50 noisy trials started at the truth: each estimate within two of its
 * standard errors ~95 % of the time (>= 90 % asked; 150 estimates, the
 * binomial's 3 sigma at 95 % is 5 %). */
static void test_coverage(void)
{
    json_t *base = base_scene(1e-6), *ms = measurements(base);
    uint64_t seed = 2026;
    int in1 = 0, in2 = 0, n = 0;
    for (int trial = 0; trial < 50; trial++) {
        json_t *m = noisy(ms, &seed), *spec = spec_of(base, m, truth);
        rd_error err;
        json_t *r = calibrate(spec, &err);
        CHECK(r != NULL, "trial %d: %s %s", trial, err.path, err.message);
        for (int j = 0; r && j < 3; j++) {
            double z = fabs(param(r, j, "value") - truth[j]) / param(r, j, "std_error");
            in1 += z <= 1;
            in2 += z <= 2;
            n++;
        }
        json_decref(r);
        json_decref(spec);
        json_decref(m);
    }
    printf("coverage over %d estimates: %.3f within 1 standard error, %.3f within 2\n", n,
           (double)in1 / n, (double)in2 / n);
    CHECK(n == 150 && in2 >= 0.9 * n, "within 2 standard errors %d of %d", in2, n);
    /* 68.3 % expected; the binomial's 3 sigma over 150 draws is 11 % */
    CHECK(in1 >= 0.55 * n && in1 <= 0.8 * n, "within 1 standard error %d of %d (~68 %%)", in1, n);
    json_decref(ms);
    json_decref(base);
}

static const char *note_with(json_t *r, const char *needle)
{
    size_t i;
    json_t *v;
    json_array_foreach(json_object_get(r, "notes"), i,
                       v) if (strstr(json_string_value(v), needle)) return json_string_value(v);
    return NULL;
}

static void test_unfixed(void)
{
    json_t *base = base_scene(1e-6), *ms = measurements(base);
    json_t *rings = json_object_get(base, "rings"); /* the other two at their true values */
    json_object_set_new(json_array_get(rings, 1), "discharge_coefficient", json_real(truth[1]));
    json_object_set_new(json_array_get(rings, 2), "leak_area_m2", json_real(truth[2]));
    json_t *ps =
        json_pack("[{s:s, s:f, s:f}, {s:s, s:f, s:f}]", "path", params[0], "min", 0.3, "max", 1.0,
                  "path", "/rings/0/ring/tangential_force", "min", 5.0, "max", 20.0);
    json_t *spec = json_pack("{s:s, s:O, s:o, s:O}", "analysis", "calibration", "base", base,
                             "parameters", ps, "measurements", ms);
    rd_error err;
    json_t *r = calibrate(spec, &err);
    CHECK(r != NULL, "product fit: %s %s", err.path, err.message);
    json_t *ps_out = json_object_get(r, "parameters");
    CHECK(r && json_is_false(json_object_get(r, "identifiable")),
          "the tangential force: not identifiable");
    CHECK(r && json_is_null(json_object_get(json_array_get(ps_out, 1), "std_error")) &&
              json_is_false(json_object_get(json_array_get(ps_out, 1), "identifiable")),
          "no standard error for what the data cannot fix");
    CHECK(r && json_is_true(json_object_get(json_array_get(ps_out, 0), "identifiable")) &&
              json_is_number(json_object_get(json_array_get(ps_out, 0), "std_error")),
          "the top ring's C_d stays identifiable beside it");
    CHECK(r && note_with(r, "/rings/0/ring/tangential_force is not identifiable") &&
              !note_with(r, "/rings/0/discharge_coefficient is not identifiable"),
          "the notes name the one the data cannot fix");
    json_decref(r);
    json_decref(spec);
    json_decref(ms);
    json_decref(base);
}

static void test_example(void)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/calibration_ringpack_blowby.json", examples);
    json_t *spec = json_load_file(path, 0, NULL);
    rd_error err;
    json_t *r = calibrate(spec, &err);
    CHECK(r != NULL, "the example: %s %s", err.path, err.message);
    json_int_t runs = json_integer_value(json_object_get(r, "runs"));
    double v = param(r, 0, "value"), sd = param(r, 0, "std_error");
    CHECK(runs <= 60, "blow-by at 4 operating points fitted in %lld runs (<= 60)", (long long)runs);
    CHECK(fabs(v - 5.5e-8) <= 3 * sd,
          "the leak area %.4g within 3 standard errors (%.3g) of the "
          "5.5e-8 its synthetic data came from",
          v, sd);
    CHECK(json_array_size(json_object_get(r, "residuals")) == 4, "one residual per measurement");
    json_decref(r);
    json_decref(spec);
}

/* A bad spec: refused with `code` at `path`. */
static void refused(const char *what, json_t *spec, int code, const char *path)
{
    char *text = json_dumps(spec, JSON_COMPACT);
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_scene_parse(text, strlen(text), &s, &err);
    CHECK(rc == code && strcmp(err.path, path) == 0, "%s: %d at \"%s\" (%s), want %d at %s", what,
          rc, err.path, err.message, code, path);
    rd_scene_free(s);
    free(text);
    json_decref(spec);
}

static void test_bad_input(void)
{
    json_t *base = json_pack("{s:s}", "analysis", "ringpack");
    json_t *m1 =
        json_pack("[{s:s, s:f, s:f}]", "observe", "/blowby/l_per_min", "value", 1.2, "sigma", 0.02);
#define SPEC(ps, ms)                                                                             \
    json_pack("{s:s, s:O, s:o, s:o}", "analysis", "calibration", "base", base, "parameters", ps, \
              "measurements", ms)
#define P1(p, a, b) \
    json_pack("[{s:s, s:f, s:f}]", "path", p, "min", (double)(a), "max", (double)(b))
    refused("a pointer to a string", SPEC(P1("/rings/2/kind", 0, 1), json_deep_copy(m1)),
            RD_EREQUEST, "/parameters/0/path");
    refused("a pointer to nothing", SPEC(P1("/rings/0/gap", 0, 1), json_deep_copy(m1)), RD_EREQUEST,
            "/parameters/0/path");
    refused("bounds reversed", SPEC(P1(params[0], 0.9, 0.3), json_deep_copy(m1)), RD_EREQUEST,
            "/parameters/0");
    refused("a bound the scene refuses", SPEC(P1(params[0], 0.5, 1.5), json_deep_copy(m1)),
            RD_EREQUEST, "/parameters/0/max");
    refused(
        "a measurement of another analysis",
        SPEC(P1(params[0], 0.3, 1), json_pack("[{s:s, s:f, s:f}]", "observe",
                                              "/modes/0/frequency_hz", "value", 1.0, "sigma", 1.0)),
        RD_EREQUEST, "/measurements/0/observe");
    refused("more parameters than values",
            SPEC(json_pack("[{s:s, s:f, s:f}, {s:s, s:f, s:f}]", "path", params[0], "min", 0.3,
                           "max", 1.0, "path", params[1], "min", 0.3, "max", 1.0),
                 json_deep_copy(m1)),
            RD_EREQUEST, "/measurements");
    refused("a set that changes the analysis",
            SPEC(P1(params[0], 0.3, 1),
                 json_pack("[{s:{s:s}, s:s, s:f, s:f}]", "set", "/analysis", "lift", "observe",
                           "/blowby/l_per_min", "value", 1.0, "sigma", 1.0)),
            RD_EREQUEST, "/measurements/0/set");
    refused("a set the scene refuses",
            SPEC(P1(params[0], 0.3, 1),
                 json_pack("[{s:{s:f}, s:s, s:f, s:f}]", "set", "/engine/speed_rpm", -5.0,
                           "observe", "/blowby/l_per_min", "value", 1.0, "sigma", 1.0)),
            RD_EREQUEST, "/measurements/0/set");
    refused("a zero sigma",
            SPEC(P1(params[0], 0.3, 1), json_pack("[{s:s, s:f, s:f}]", "observe",
                                                  "/blowby/l_per_min", "value", 1.0, "sigma", 0.0)),
            RD_EREQUEST, "/measurements/0/sigma");
    refused("a start outside the bounds",
            SPEC(json_pack("[{s:s, s:f, s:f, s:f}]", "path", params[0], "min", 0.3, "max", 1.0,
                           "start", 1.2),
                 json_deep_copy(m1)),
            RD_EREQUEST, "/parameters/0/start");
    refused("a study as the base",
            json_pack("{s:s, s:{s:s}, s:o, s:O}", "analysis", "calibration", "base", "analysis",
                      "calibration", "parameters", P1(params[0], 0.3, 1), "measurements", m1),
            RD_EREQUEST, "/base/analysis");
    refused("no measurements",
            json_pack("{s:s, s:O, s:o}", "analysis", "calibration", "base", base, "parameters",
                      P1(params[0], 0.3, 1)),
            RD_EREQUEST, "/measurements");
    refused("an unknown key in a parameter",
            SPEC(json_pack("[{s:s, s:f, s:f, s:f}]", "path", params[0], "min", 0.3, "max", 1.0,
                           "step", 0.1),
                 json_deep_copy(m1)),
            RD_EREQUEST, "/parameters/0");
#undef SPEC
#undef P1
    json_decref(m1);
    json_decref(base);
    /* the study's own path: no "analysis" is a calibration, another is refused */
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    char *errors = NULL;
    const char *body = "{\"analysis\": \"modal\"}";
    CHECK(rd_scene_parse_report_as(body, strlen(body), "calibration", &s, &err, &errors) ==
                  RD_EREQUEST &&
              strcmp(err.path, "/analysis") == 0 && errors && strstr(errors, "/api/v1/jobs"),
          "another analysis on the calibrations path: %s", err.message);
    free(errors);
}

int main(int argc, char **argv)
{
    examples = argc > 1 ? argv[1] : "examples";
    test_bad_input();
    test_unfixed();
    test_example();
    test_recovery();
    test_coverage();
    return check_done();
}
