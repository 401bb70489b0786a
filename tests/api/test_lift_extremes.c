/*
 * test_lift_extremes — the lift analysis at the ends of its documented
 * ranges (issue 45, item 4): every scene inside them converges, every one
 * just past them is refused up front (a 4xx status at the field's path, with
 * the range in the message).  Ranges: segments 4...1000, speed 1...30000 rpm,
 * axial clearance 1e-7...5e-3 m, radial clearance 1e-6...1e-2 m.
 *
 * The default scene (auto: the rigid ring for it) at all 16 corners of
 * segments x speed x both clearances; up to 0.3.15 every corner with 1000
 * segments failed with numerical_failure (the rigid model's banded Cholesky,
 * rd_lift_rigid.c "Effective twist stiffness").  The full and modal models
 * at the corners they reach within a CI budget (below).  Each run is short
 * (cycles 0.05 = 36 deg of crank, output every 6 deg); the time of each case
 * is printed.  Release build, one core: the 16 auto corners 0.01-0.4 s each
 * (1.4 s in all), full n = 4 0.01-0.1 s, modal n = 4 0.05-0.9 s, full
 * n = 1000 at 30000 rpm 2.1 s.
 *
 * The full model at n = 4, 1 rpm, c_a = 5 mm: the ring flies freely for
 * seconds of physical time (36 deg at 1 rpm is 6 s; no gravity in the
 * default scene, the piston's 6e-4 m/s^2 lifts it across the clearance) and
 * its undamped elastic vibration sets the step: the main run takes ~242 000
 * CVODE steps (3.3 s), its error-estimate run at rtol/10 ~3x that and passes
 * numerics.max_steps (500 000) at 26.5 deg.  Up to 0.3.x that failed the
 * whole run with limit_exceeded; now the main run's result is returned
 * without an estimate (partial, with a warning at /numerics/max_steps), as
 * a run whose estimate is cancelled is (full_free_flight, 6.7 s).
 *
 * Left out, for their cost: the modal model at 1 rpm with a large axial
 * clearance (converges in 95 s), the full model at n = 1000 with a 5 mm
 * clearance (65 s at 30000 rpm).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "rd_api.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Parses and runs a scene; the status, err set on failure. */
static int run(const char *body, int *parsed, rd_error *err)
{
    rd_scene *scene = NULL;
    rd_error_init(err);
    *parsed = 0;
    int rc = rd_scene_parse(body, strlen(body), &scene, err);
    if (rc != RD_OK)
        return rc;
    *parsed = 1;
    char *result = NULL;
    rc = rd_scene_run(scene, NULL, &result, err);
    free(result);
    rd_scene_free(scene);
    return rc;
}

static void scene(char *buf, size_t n, const char *model, int segments, double rpm, double ca,
                  double cr)
{
    snprintf(buf, n,
             "{\"analysis\":\"lift\",\"discretization\":{\"segments\":%d},"
             "\"engine\":{\"speed_rpm\":%.17g,\"cycles\":0.05},"
             "\"groove\":{\"axial_clearance\":%.17g,\"radial_clearance\":%.17g},"
             "\"output\":{\"step_deg\":6},\"numerics\":{\"model\":\"%s\"}}",
             segments, rpm, ca, cr, model);
}

/* The scene converges. */
static void converges(const char *model, int segments, double rpm, double ca, double cr)
{
    char body[512];
    rd_error err;
    int parsed;
    scene(body, sizeof body, model, segments, rpm, ca, cr);
    double t0 = now_s();
    int rc = run(body, &parsed, &err);
    double dt = now_s() - t0;
    CHECK(rc == RD_OK, "%s n = %d, %g rpm, c_a %g, c_r %g: %s (%s)", model, segments, rpm, ca, cr,
          err.message, err.path);
    fprintf(stderr, "    %-5s n = %4d  %5g rpm  c_a %-5g c_r %-5g  %s  %.3f s\n", model, segments,
            rpm, ca, cr, rc == RD_OK ? "converged" : "FAILED", dt);
}

/* The full ring at n = 4, 1 rpm, c_a = 5 mm (header comment): succeeds with
 * the main run whole, both flank changes, and no error estimate, said by a
 * warning at /numerics/max_steps. */
static void full_free_flight(void)
{
    char body[512];
    rd_scene *sc = NULL;
    rd_error err;
    rd_error_init(&err);
    scene(body, sizeof body, "full", 4, 1.0, 5e-3, 1e-6);
    double t0 = now_s();
    int rc = rd_scene_parse(body, strlen(body), &sc, &err);
    char *result = NULL;
    if (rc == RD_OK)
        rc = rd_scene_run(sc, NULL, &result, &err);
    CHECK(rc == RD_OK && result, "full n = 4, 1 rpm, c_a 5e-3: %s (%s)", err.message, err.path);
    if (result) {
        CHECK(strstr(result, "\"partial\":true") && strstr(result, "\"crank_deg_reached\":36") &&
                  strstr(result, "\"path\":\"/numerics/max_steps\"") &&
                  strstr(result, "error-estimate run") && strstr(result, "\"reach_upper\"") &&
                  strstr(result, "\"error_estimate\":null"),
              "full n = 4, 1 rpm, c_a 5e-3: the main run without its estimate, warned");
    }
    fprintf(stderr, "    full  n =    4      1 rpm  c_a 0.005 c_r 1e-06  %s  %.3f s\n",
            rc == RD_OK ? "converged, no estimate (max_steps)" : "FAILED", now_s() - t0);
    free(result);
    rd_scene_free(sc);
}

/* The scene is refused when parsed (before any work), at `path`, with a
 * status the contract answers with a 4xx. */
static void refused(const char *what, int segments, double rpm, double ca, double cr,
                    const char *path)
{
    char body[512];
    rd_error err;
    int parsed;
    scene(body, sizeof body, "auto", segments, rpm, ca, cr);
    int rc = run(body, &parsed, &err);
    int status = rd_api_http_status(rc);
    CHECK(!parsed && rc != RD_OK && status >= 400 && status < 500 && strcmp(err.path, path) == 0 &&
              strstr(err.message, "allowed") != NULL,
          "%s: parsed %d, status %d at '%s': %s (want a refusal at %s)", what, parsed, status,
          err.path, err.message, path);
}

int main(void)
{
    const int ns[] = {4, 1000};
    const double rpms[] = {1.0, 30000.0}, cas[] = {1e-7, 5e-3}, crs[] = {1e-6, 1e-2};
    /* the default scene (auto: the rigid ring) at every corner */
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int c = 0; c < 2; c++)
                for (int d = 0; d < 2; d++)
                    converges("auto", ns[a], rpms[b], cas[c], crs[d]);
    /* the rigid ring between the ends as well (the failures were at 700, 800
     * and 1000 segments, while 600 and 900 passed) */
    for (int n = 650; n < 1000; n += 50)
        converges("rigid", n, 1000.0, 3e-5, 5e-4);
    /* the full model: n = 4 at every corner but 1 rpm with c_a = 5 mm (its
     * own check below), and n = 1000 at 30000 rpm, the smallest clearances
     * (header comment) */
    for (int b = 0; b < 2; b++)
        for (int c = 0; c < 2; c++)
            for (int d = 0; d < 2; d++)
                if (b == 1 || c == 0)
                    converges("full", 4, rpms[b], cas[c], crs[d]);
    converges("full", 1000, 30000.0, 1e-7, 1e-6);
    full_free_flight();
    /* the modal model (n <= 200) at n = 4, 30000 rpm */
    for (int c = 0; c < 2; c++)
        converges("modal", 4, 30000.0, cas[c], 1e-2);
    /* one step past each end: refused up front */
    refused("3 segments", 3, 1000.0, 3e-5, 5e-4, "/discretization/segments");
    refused("1001 segments", 1001, 1000.0, 3e-5, 5e-4, "/discretization/segments");
    refused("0.5 rpm", 4, 0.5, 3e-5, 5e-4, "/engine/speed_rpm");
    refused("30001 rpm", 4, 30001.0, 3e-5, 5e-4, "/engine/speed_rpm");
    refused("axial clearance 9e-8", 4, 1000.0, 9e-8, 5e-4, "/groove/axial_clearance");
    refused("axial clearance 5.1e-3", 4, 1000.0, 5.1e-3, 5e-4, "/groove/axial_clearance");
    refused("radial clearance 9e-7", 4, 1000.0, 3e-5, 9e-7, "/groove/radial_clearance");
    refused("radial clearance 1.1e-2", 4, 1000.0, 3e-5, 1.1e-2, "/groove/radial_clearance");
    return check_done();
}
