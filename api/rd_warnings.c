/*
 * rd_warnings — result "warnings": values that core accepts but that are
 * most likely slips (a unit typed wrong, a field copied from the wrong
 * line), and results whose own error estimate says not to trust them.
 *
 * Every rule reads the finished result object only: its "scene" (the echo,
 * every default filled in, SI units) and its "numerics".  So the rules are
 * generic over the analyses: a rule whose fields an analysis lacks is
 * silent.  A warning never refuses a scene; it is {code, path, message},
 * `path` a JSON Pointer into the scene (or to /numerics/... in the result).
 *
 * The thresholds, and why (solid engineering materials span about
 * 500..23000 kg/m^3 and 1..1200 GPa; gauge gas pressures in an engine
 * are 1e3..2e7 Pa):
 *   density < 1000 kg/m^3        a value in g/cm^3 (steel 7.85) typed as kg/m^3
 *   density > 25000 kg/m^3       above every solid (osmium 22590): g/m^3 or a digit too many
 *   E < 1 GPa                    MPa or GPa typed as Pa (steel 210 GPa = 2.1e11)
 *   E > 1500 GPa                 stiffer than diamond (about 1200 GPa)
 *   poisson_ratio < 0            auxetic: possible, but no ring material is
 *   gas table peak < 1000 Pa     bar (or kPa) typed as Pa, when every non-zero table is so
 *   gas table peak < 200 Pa      ... or when another table peaks above 1e4 Pa
 *   bore vs ring diameter > 1 %  the ring's nominal diameter is its bore's (core allows 2 %)
 *   numerics error > 5 %         the result's own error estimate (relative)
 *   lift event error > 5 deg     flank changes located to worse than 5 deg
 *   oil viscosity > 1 Pa s       thicker than an engine oil at 0 C: mPa s typed as Pa s
 *                                (hot engine oils are 0.003..0.05 Pa s)
 *   a ring pack's bore not round while every ring is held: not read (bore_unread)
 *   a measured free shape's fitted pressure below 0 somewhere: the ring
 *   leaves a round bore there (free_shape_leaves_bore)
 */
#include "rd_warnings.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "rd_json.h"

#define ERROR_LIMIT     0.05   /* relative error above which a result is flagged */
#define EVENT_LIMIT_DEG 5.0    /* flank-change timing uncertainty, deg */
#define BORE_MISMATCH   0.01   /* |bore - ring diameter| / ring diameter */
#define BAR_LIKE_PA     1000.0 /* every gas table below this: typed in bar */
#define BAR_LIKE_ONE_PA 200.0  /* one table below this while another is real */
#define REAL_GAS_PA     1.0e4  /* a table above this was typed in Pa */
#define OIL_THICK_PA_S  1.0    /* an engine oil near 0 C; above: mPa s typed as Pa s */

/* Appends {code, path, message}; nonzero on out of memory. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static int
warn(json_t *out, const char *code, const char *path, const char *fmt, ...)
{
    char message[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    return json_array_append_new(
        out, json_pack("{s:s, s:s, s:s}", "code", code, "path", path, "message", message));
}

/* The number at `ptr` (a JSON Pointer without escapes) under `root`; NAN when absent. */
static double number_at(json_t *root, const char *ptr)
{
    char key[64];
    json_t *v = root;
    while (v && *ptr == '/') {
        ptr++;
        size_t n = 0;
        while (ptr[n] && ptr[n] != '/' && n + 1 < sizeof key) {
            key[n] = ptr[n];
            n++;
        }
        key[n] = '\0';
        ptr += n;
        v = json_object_get(v, key);
    }
    return json_is_number(v) ? json_number_value(v) : NAN;
}

/* Material values outside what any ring material has: a unit slip.  Each
 * message takes the value (%g); NULL means no bound on that side. */
static const struct material_rule {
    const char *code, *path;
    double lo, hi;
    const char *below, *above;
} material_rules[] = {
    {"density_unit", "/ring/material/density", 1000.0, 25000.0,
     "density %g kg/m^3 is below 1000 kg/m^3 (lighter than water): typed in g/cm^3? Steel is "
     "7850 kg/m^3.",
     "density %g kg/m^3 is above 25000 kg/m^3, denser than any solid: a unit or a digit too "
     "many? Steel is 7850 kg/m^3."},
    {"youngs_modulus_unit", "/ring/material/youngs_modulus", 1.0e9, 1.5e12,
     "Young's modulus %g Pa is below 1 GPa, softer than any ring material: a unit slip (kPa, "
     "MPa, GPa typed as Pa)? Steel is 2.1e11 Pa (210 GPa).",
     "Young's modulus %g Pa is above 1500 GPa, stiffer than diamond: a unit or a digit too many? "
     "Steel is 2.1e11 Pa."},
    {"poisson_ratio_negative", "/ring/material/poisson_ratio", 0.0, INFINITY,
     "Poisson's ratio %g is negative (an auxetic material); metals are near 0.3: a lost digit or "
     "sign?",
     NULL},
};

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
static int material(json_t *scene, json_t *result, json_t *out)
{
    (void)result;
    for (size_t k = 0; k < sizeof material_rules / sizeof material_rules[0]; k++) {
        const struct material_rule *r = &material_rules[k];
        double v = number_at(scene, r->path);
        const char *fmt = v < r->lo ? r->below : v > r->hi ? r->above : NULL;
        if (fmt && warn(out, r->code, r->path, fmt, v) != 0)
            return 1;
    }
    return 0;
}
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* Largest |p| of a gas table; NAN when there is none. */
static double table_peak(json_t *gas, const char *key)
{
    json_t *t = json_object_get(gas, key), *x;
    size_t i;
    double peak = json_is_array(t) ? 0.0 : NAN;
    json_array_foreach(t, i, x)
    {
        if (json_is_number(x) && fabs(json_number_value(x)) > peak)
            peak = fabs(json_number_value(x));
    }
    return peak;
}

static int gas_in_bar(json_t *scene, json_t *result, json_t *out)
{
    (void)result;
    static const char *const keys[] = {"above", "behind", "below"};
    json_t *gas = json_object_get(json_object_get(scene, "physics"), "gas");
    double peak[3], largest = 0.0;
    int small = 0, nonzero = 0, bad = 0;
    if (!gas)
        return 0;
    for (int k = 0; k < 3; k++) {
        peak[k] = table_peak(gas, keys[k]);
        if (!(peak[k] > 0.0))
            continue;
        nonzero++;
        small += peak[k] < BAR_LIKE_PA;
        largest = fmax(largest, peak[k]);
    }
    for (int k = 0; k < 3 && !bad; k++) {
        if (!(peak[k] > 0.0))
            continue;
        int all_small = small == nonzero && peak[k] < BAR_LIKE_PA;
        int one_small = peak[k] < BAR_LIKE_ONE_PA && largest > REAL_GAS_PA;
        if (!all_small && !one_small)
            continue;
        char path[40];
        snprintf(path, sizeof path, "/physics/gas/%s", keys[k]);
        bad = warn(out, "gas_pressure_unit", path,
                   "the gas pressure %s peaks at %g Pa%s: typed in bar? Pressures are gauge "
                   "pressures in Pa (1 bar = 1e5 Pa).",
                   keys[k], peak[k],
                   one_small && !all_small ? " while another side reaches 1e4 Pa and more" : "");
    }
    return bad;
}

static int bore_diameter(json_t *scene, json_t *result, json_t *out)
{
    (void)result;
    double bore = number_at(scene, "/bore/diameter"), d = number_at(scene, "/ring/diameter");
    if (bore > 0.0 && d > 0.0 && fabs(bore - d) > BORE_MISMATCH * d)
        return warn(out, "bore_diameter_mismatch", "/bore/diameter",
                    "the bore diameter %g m differs from the ring's nominal diameter %g m by "
                    "%.1f %% (more than 1 %%): a ring is made for its bore, so a ring 1 %% off "
                    "is another ring; a typo?",
                    bore, d, 100.0 * fabs(bore - d) / d);
    return 0;
}

static int error_estimate(json_t *scene, json_t *result, json_t *out)
{
    (void)scene;
    double e = number_at(result, "/numerics/error_estimate");
    json_t *numerics = json_object_get(result, "numerics");
    int by_segments = json_object_get(numerics, "reference_segments") != NULL;
    if (e > ERROR_LIMIT)
        return warn(out, "error_estimate_high", "/numerics/error_estimate",
                    "the estimated relative error of this result is %.1f %% (above 5 %%): %s "
                    "before trusting it.",
                    100.0 * e,
                    by_segments ? "refine (more segments, /discretization/segments)"
                                : "tighten the tolerances (/numerics/rtol and atol)");
    return 0;
}

static int event_error(json_t *scene, json_t *result, json_t *out)
{
    (void)scene;
    double e = number_at(result, "/numerics/event_error_deg");
    if (e > EVENT_LIMIT_DEG)
        return warn(out, "event_error_high", "/numerics/event_error_deg",
                    "the flank changes are located to within %.1f deg only (above 5 deg): tighten "
                    "the tolerances (/numerics/rtol and atol).",
                    e);
    return 0;
}

/* An analysis with an accuracy target (contact's numerics.accuracy) that it
 * could not meet says so in numerics.accuracy_met / accuracy_note. */
static int accuracy_not_met(json_t *scene, json_t *result, json_t *out)
{
    (void)scene;
    json_t *numerics = json_object_get(result, "numerics");
    json_t *met = json_object_get(numerics, "accuracy_met");
    if (!json_is_false(met))
        return 0;
    const char *note = json_string_value(json_object_get(numerics, "accuracy_note"));
    return warn(out, "accuracy_not_met", "/numerics/accuracy",
                "the accuracy target %g was not met: %s", number_at(result, "/numerics/accuracy"),
                note ? note : "the solver stopped refining before its estimates met it.");
}

/* A note of the solver's (contact's accuracy_note) on a result that met its
 * target or had none to meet (accuracy_met true or null): e.g. the contact
 * multipliers stopped at their update limit, within twice their tolerance.
 * A target missed is accuracy_not_met's, which quotes the note already. */
static int solver_note(json_t *scene, json_t *result, json_t *out)
{
    (void)scene;
    json_t *numerics = json_object_get(result, "numerics");
    const char *note = json_string_value(json_object_get(numerics, "accuracy_note"));
    if (!note || json_is_false(json_object_get(numerics, "accuracy_met")))
        return 0;
    return warn(out, "solver_note", "", "the solver noted: %s", note);
}

static int oil_viscosity(json_t *scene, json_t *result, json_t *out)
{
    (void)result;
    double eta = number_at(scene, "/physics/friction/oil/viscosity_pa_s");
    if (eta > OIL_THICK_PA_S)
        return warn(out, "oil_viscosity_unit", "/physics/friction/oil/viscosity_pa_s",
                    "the oil's viscosity %g Pa s is thicker than an engine oil near 0 C (about "
                    "1 Pa s; hot engine oils are 0.003-0.05 Pa s): a value in mPa s typed as "
                    "Pa s? (1 mPa s = 0.001 Pa s)",
                    eta);
    return 0;
}

/* A ring pack whose bore is not round (distortion, layers or points) but
 * whose rings all stand still (held on a flank: no model with degrees of
 * freedom in numerics.model): only moving rings meet the bore (the gas
 * network keeps the rings' diameter), so the bore was not read. */
static int bore_unread(json_t *scene, json_t *result, json_t *out)
{
    const char *an = json_string_value(json_object_get(scene, "analysis"));
    json_t *bore = json_object_get(scene, "bore");
    if (!an || strcmp(an, "ringpack") != 0 || !json_is_object(bore))
        return 0;
    int given = json_array_size(json_object_get(bore, "distortion")) > 0 ||
                json_is_array(json_object_get(bore, "layers")) ||
                json_is_object(json_object_get(bore, "points"));
    json_t *models = json_object_get(json_object_get(result, "numerics"), "model");
    for (size_t i = 0; given && i < json_array_size(models); i++)
        if (json_number_value(json_object_get(json_array_get(models, i), "dof")) > 0)
            return 0;
    if (!given || !json_is_array(models))
        return 0;
    return warn(out, "bore_unread", "/bore",
                "every ring is held on its flank, and only moving rings meet the bore: its "
                "distortion or map changed nothing here (the gas network keeps the rings' "
                "diameter).");
}

/* A measured free shape whose fitted pressure falls below 0 somewhere: a
 * round bore does not hold the ring there (a light gap), and the orders are
 * likely a truncation of a pressure the table's shape puts at the tips. */
static int free_shape_leaves_bore(json_t *scene, json_t *result, json_t *out)
{
    (void)scene;
    json_t *fit = json_object_get(result, "free_shape_fit");
    double lo = number_at(fit, "/pressure_min_ratio"),
           at = number_at(fit, "/pressure_min_theta_deg");
    if (!json_is_object(fit) || !(lo < 0.0))
        return 0;
    return warn(out, "free_shape_leaves_bore", "/ring/free_shape",
                "the pressure fitted to the measured free shape falls to %.3g p0 at %.1f deg from "
                "the point opposite the gap: closed in a round bore the ring leaves it there. "
                "Check the table (its centre, its tips), or fit fewer orders.",
                lo, at);
}

/* The rules, in the order their warnings are listed. */
static int (*const rules[])(json_t *scene, json_t *result, json_t *out) = {
    material,         gas_in_bar,  bore_diameter, error_estimate, event_error,
    accuracy_not_met, solver_note, oil_viscosity, bore_unread,    free_shape_leaves_bore,
};

int rd_warnings_add(json_t *result)
{
    /* the analysis' own warnings first (a lift run's partial result) */
    json_t *own = json_object_get(result, "warnings");
    json_t *list = json_is_array(own) ? rd_json_copy(own) : json_array();
    json_t *scene = json_object_get(result, "scene");
    int bad = !list;
    for (size_t k = 0; !bad && k < sizeof rules / sizeof rules[0]; k++)
        bad = rules[k](scene, result, list) != 0;
    if (!bad)
        bad = json_object_set(result, "warnings", list) != 0;
    json_decref(list);
    return bad ? -1 : 0;
}
