/*
 * test_sensitivity — sensitivities against closed forms:
 *   - modal: the ring's stiffness is linear in E (the shear modulus
 *     E / (2 (1 + nu)) with it) and its mass in rho, so every frequency is
 *     c sqrt(E / rho): df/dE = f / (2 E), df/drho = -f / (2 rho) exactly at
 *     any n; and no frequency reads the tangential force (0, flagged);
 *   - the steady ring pack of the shipped example: its top-land entry and
 *     end gap are orifices with the same C_d, so the mass flow is
 *     proportional to C_d and the land pressure independent of it;
 *   - the same ring held at half its clearance (both flank passages open,
 *     viscous-limited: the slot's share does not scale with C_d), whose
 *     land and groove pressures do depend on C_d: the derivatives against
 *     those of the steady network solved in the test (ringpack_steady.h:
 *     the laws written again, nested bisection to round-off) by a central
 *     difference of 1e-3 C_d (truncation ~1e-7), within 1e-4;
 *   - the error estimate against the true error (the closed form's) on a
 *     battery of given steps where truncation dominates: within x3;
 *   - bad specs: 400 with the field named.
 * Usage: test_sensitivity EXAMPLES_DIR
 */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_api.h"
#include "ringpack_steady.h"

static json_t *run_text(const char *text, rd_error *err)
{
    rd_scene *s = NULL;
    char *out = NULL;
    json_t *r = NULL;
    rd_error_init(err);
    if (rd_scene_parse(text, strlen(text), &s, err) == RD_OK &&
        rd_scene_run(s, NULL, &out, err) == RD_OK)
        r = json_loads(out, 0, NULL);
    free(out);
    rd_scene_free(s);
    return r;
}

static json_t *deriv(json_t *r, int out, int param)
{
    return json_array_get(
        json_object_get(json_array_get(json_object_get(r, "outputs"), (size_t)out), "derivatives"),
        (size_t)param);
}
static double num(json_t *o, const char *key)
{
    return json_number_value(json_object_get(o, key));
}
static double out_value(json_t *r, int out)
{
    return num(json_array_get(json_object_get(r, "outputs"), (size_t)out), "value");
}

static void test_modal(void)
{
    const char *spec =
        "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"modal\", \"modal\": "
        "{\"modes\": 3}}, \"parameters\": [{\"path\": \"/ring/material/youngs_modulus\"}, "
        "{\"path\": \"/ring/material/density\"}, {\"path\": \"/ring/tangential_force\"}], "
        "\"outputs\": [\"/modes/0/frequency_hz\", \"/modes/2/frequency_hz\"]}";
    rd_error err;
    json_t *r = run_text(spec, &err);
    CHECK(r != NULL, "modal sensitivity: %s %s", err.path, err.message);
    for (int k = 0; r && k < 2; k++) {
        double f = out_value(r, k);
        json_t *dE = deriv(r, k, 0), *drho = deriv(r, k, 1), *dF = deriv(r, k, 2);
        double wantE = f / (2 * num(dE, "at")), wantr = -f / (2 * num(drho, "at"));
        /* default step h = cbrt(1e-12) |x| = 1e-4 |x|: truncation ~ h^2/8 ~ 1e-9, noise
         * 1e-12/1e-4 = 1e-8 of f'; 1e-7 leaves a margin of 10 */
        CHECK_REL(num(dE, "derivative"), wantE, 1e-7, "mode %d: df/dE = f / 2E", k);
        CHECK_REL(num(drho, "derivative"), wantr, 1e-7, "mode %d: df/drho = -f / 2 rho", k);
        CHECK(fabs(num(dE, "derivative") - wantE) <= num(dE, "error_estimate") &&
                  fabs(num(drho, "derivative") - wantr) <= num(drho, "error_estimate"),
              "mode %d: the default step's estimates bound the true errors", k);
        CHECK_REL(num(dE, "elasticity"), 0.5, 1e-7, "mode %d: elasticity 1/2 in E", k);
        CHECK(json_is_true(json_object_get(dE, "significant")), "df/dE significant");
        CHECK(num(dF, "derivative") == 0 && json_is_false(json_object_get(dF, "significant")),
              "mode %d: the tangential force moves no frequency (%g, flagged)", k,
              num(dF, "derivative"));
    }
    CHECK(r && json_integer_value(json_object_get(r, "runs")) == 13, "1 + 4 x 3 runs");
    json_decref(r);
}

/* Given steps of 2 to 20 % of E and rho: the estimate |D(h) - D(2h)|/3
 * against the true error of D(h) (the closed form's), within x3. */
static void test_estimate_battery(void)
{
    const double rel[4] = {0.02, 0.05, 0.1, 0.2};
    const double E = 2.1e11, rho = 7850;
    int n = 0;
    double worst = 1;
    for (int i = 0; i < 4; i++) {
        char spec[1024];
        snprintf(spec, sizeof spec,
                 "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"modal\", \"modal\": "
                 "{\"modes\": 2}}, \"parameters\": [{\"path\": \"/ring/material/youngs_modulus\", "
                 "\"step\": %.17g}, {\"path\": \"/ring/material/density\", \"step\": %.17g}], "
                 "\"outputs\": [\"/modes/0/frequency_hz\", \"/modes/1/frequency_hz\"]}",
                 rel[i] * E, rel[i] * rho);
        rd_error err;
        json_t *r = run_text(spec, &err);
        CHECK(r != NULL, "battery %g: %s", rel[i], err.message);
        for (int k = 0; r && k < 2; k++)
            for (int j = 0; j < 2; j++) {
                double f = out_value(r, k), x = j ? rho : E;
                double want = j ? -f / (2 * x) : f / (2 * x);
                json_t *d = deriv(r, k, j);
                double truth = fabs(num(d, "derivative") - want), est = num(d, "error_estimate");
                double ratio = est / truth;
                CHECK(ratio >= 1.0 / 3 && ratio <= 3,
                      "step %g, mode %d, param %d: estimate %.3g, "
                      "true error %.3g",
                      rel[i], k, j, est, truth);
                worst = fmax(worst, fmax(ratio, 1 / ratio));
                n++;
            }
        json_decref(r);
    }
    printf("error estimate over %d derivatives: within x%.2f of the true error\n", n, worst);
}

static void test_ringpack(const char *examples)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/sensitivity_ringpack_steady.json", examples);
    json_t *spec = json_load_file(path, 0, NULL);
    char *text = json_dumps(spec, JSON_COMPACT);
    rd_error err;
    json_t *r = run_text(text, &err);
    CHECK(r != NULL, "ring-pack sensitivity: %s %s", err.path, err.message);
    json_t *dm = deriv(r, 0, 0), *dp = deriv(r, 1, 0);
    double cd = num(dm, "at");
    CHECK_REL(num(dm, "derivative"), out_value(r, 0) / cd, 1e-4,
              "d(blow-by)/dC_d = blow-by / C_d (orifices in series, one C_d)");
    CHECK(fabs(num(dp, "elasticity")) <= 1e-4, "d(p_land)/dC_d C_d / p_land = %g, 0 within 1e-4",
          num(dp, "elasticity"));
    CHECK(fabs(num(dp, "derivative")) <= num(dp, "error_estimate") &&
              json_is_false(json_object_get(dp, "significant")),
          "d(p_land)/dC_d = 0 within its estimate (%g +- %g), flagged", num(dp, "derivative"),
          num(dp, "error_estimate"));
    json_decref(r);
    free(text);
    json_decref(spec);
}

/* A number at a JSON Pointer of the scene echo. */
static double at(json_t *scene, const char *ptr)
{
    char buf[128];
    snprintf(buf, sizeof buf, "%s", ptr);
    json_t *o = scene;
    for (char *k = strtok(buf, "/"); k && o; k = strtok(NULL, "/"))
        o = json_is_array(o) ? json_array_get(o, (size_t)atoi(k)) : json_object_get(o, k);
    CHECK(json_is_number(o), "the base scene's echo has %s", ptr);
    return json_number_value(o);
}

/* The steady network's parameters from the base run's scene echo (what the
 * run used, defaults filled in), C_d set to cd. */
static void held_params(json_t *sc, double cd, rd_ringpack_params *p)
{
    rd_ringpack_params_default(p);
    rd_ringpack_ring *r = &p->rings[0];
    r->pinned = RD_PIN_MIDDLE;
    r->discharge_coefficient = cd;
    r->ring.diameter = at(sc, "/rings/0/ring/diameter");
    r->ring.radial_width = at(sc, "/rings/0/ring/radial_width");
    r->ring.closed_gap = at(sc, "/rings/0/ring/closed_gap");
    r->groove.axial_clearance = at(sc, "/rings/0/groove/axial_clearance");
    r->land_clearance = at(sc, "/rings/0/land/radial_clearance");
    p->T_lands = at(sc, "/gas_temperature_k/lands");
    p->T_crankcase = at(sc, "/gas_temperature_k/crankcase");
    p->crankcase_pa = at(sc, "/crankcase_pressure_pa");
    p->kappa = at(sc, "/physics/gas/heat_capacity_ratio");
    p->gas_constant = at(sc, "/physics/gas/gas_constant");
    p->gas_viscosity = at(sc, "/physics/gas/viscosity_pa_s");
    p->engine.speed_rpm = at(sc, "/engine/speed_rpm");
}

static void test_ringpack_held(void)
{
    const char *spec =
        "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"ringpack\", \"rings\": "
        "[{\"pinned\": \"middle\"}], \"cylinder_pressure\": {\"crank_deg\": [0, 720], "
        "\"pressure_pa\": [500000, 500000]}, \"engine\": {\"cycles\": 12}, \"numerics\": "
        "{\"rtol\": 1e-10, \"error_estimate\": false}}, \"parameters\": [{\"path\": "
        "\"/rings/0/discharge_coefficient\"}], \"outputs\": [\"/volumes/1/pressure_pa/719\", "
        "\"/volumes/2/pressure_pa/719\", \"/blowby/kg_per_cycle\"]}";
    rd_error err;
    json_t *r = run_text(spec, &err), *spec_json = json_loads(spec, 0, NULL);
    char *base = json_dumps(json_object_get(spec_json, "base"), JSON_COMPACT);
    json_t *b = run_text(base, &err), *sc = json_object_get(b, "scene");
    free(base);
    json_decref(spec_json);
    CHECK(r != NULL && sc != NULL, "held ring sensitivity: %s %s", err.path, err.message);
    if (!r || !sc) {
        json_decref(r);
        json_decref(b);
        return;
    }
    double cd = num(deriv(r, 0, 0), "at"), h = 1e-3 * cd, pl[3], pg[3], m[3];
    for (int k = 0; k < 3; k++) {
        rd_ringpack_params p;
        held_params(sc, cd + (k - 1) * h, &p);
        m[k] = steady(&p, 5e5, &pl[k], &pg[k], 1) * 120.0 / p.engine.speed_rpm;
    }
    double want[3] = {(pl[2] - pl[0]) / (2 * h), (pg[2] - pg[0]) / (2 * h),
                      (m[2] - m[0]) / (2 * h)};
    double value[3] = {pl[1], pg[1], m[1]};
    const char *name[3] = {"land", "groove", "blow-by"};
    for (int o = 0; o < 3; o++) {
        json_t *d = deriv(r, o, 0);
        CHECK_REL(out_value(r, o), value[o], 1e-6, "held ring: the %s at C_d %.2f, steady %.9g",
                  name[o], cd, value[o]);
        CHECK_REL(num(d, "derivative"), want[o], 1e-4,
                  "held ring: d(%s)/dC_d %.9g, the steady network's %.9g", name[o],
                  num(d, "derivative"), want[o]);
        CHECK(json_is_true(json_object_get(d, "significant")), "held ring: d(%s)/dC_d significant",
              name[o]);
        printf("held ring: d(%s)/dC_d = %.9g (steady network %.9g, estimate %.2g)\n", name[o],
               num(d, "derivative"), want[o], num(d, "error_estimate"));
    }
    json_decref(r);
    json_decref(b);
}

static void refused(const char *what, const char *spec, const char *path)
{
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_scene_parse(spec, strlen(spec), &s, &err);
    CHECK(rc == RD_EREQUEST && strcmp(err.path, path) == 0, "%s: %d at %s (%s), want 400 at %s",
          what, rc, err.path, err.message, path);
    rd_scene_free(s);
}

static void test_bad_input(void)
{
    refused("a pointer to nothing",
            "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"modal\"}, \"parameters\": "
            "[{\"path\": \"/ring/width\"}], \"outputs\": [\"/modes/0/frequency_hz\"]}",
            "/parameters/0/path");
    refused("a zero base value without a step",
            "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"lift\"}, \"parameters\": "
            "[{\"path\": \"/engine/piston_tilt_deg\"}], \"outputs\": [\"/lift_max\"]}",
            "/parameters/0/step");
    refused("a step that leaves the scene's range",
            "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"modal\"}, \"parameters\": "
            "[{\"path\": \"/ring/tangential_force\", \"step\": 100}], \"outputs\": "
            "[\"/modes/0/frequency_hz\"]}",
            "/parameters/0");
    refused("an output of another analysis",
            "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"modal\"}, \"parameters\": "
            "[{\"path\": \"/ring/tangential_force\"}], \"outputs\": [\"/blowby/l_per_min\"]}",
            "/outputs/0");
    refused("no outputs",
            "{\"analysis\": \"sensitivity\", \"base\": {\"analysis\": \"modal\"}, \"parameters\": "
            "[{\"path\": \"/ring/tangential_force\"}]}",
            "/outputs");
}

int main(int argc, char **argv)
{
    test_bad_input();
    test_modal();
    test_estimate_battery();
    test_ringpack(argc > 1 ? argv[1] : "examples");
    test_ringpack_held();
    return check_done();
}
