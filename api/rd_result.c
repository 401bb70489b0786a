/*
 * rd_result — result objects and CSV tables (rd_result.h).
 *
 * Mode shapes: core gives per segment i six components in the segment's
 * local cylindrical frame, shape[6i + 0..2] = radial, tangential, axial
 * translation and shape[6i + 3..5] = rotation about the radial, tangential,
 * axial axes (1/m, the translations being normalized to a largest value of
 * 1).  The result reports the three translations and the twist of the
 * section, rotation about the tangential axis times the centroid radius R,
 * which makes it dimensionless and comparable with the translations.
 */
#include "rd_result.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

#define SHAPE(m, i, k) ((m)->shape[6 * (i) + (k)])
enum { S_RADIAL = 0, S_TANGENTIAL = 1, S_AXIAL = 2, S_ROT_TANGENTIAL = 4 };

static const char modal_solver[] =
    "shift-invert subspace iteration on banded K, M (LAPACK dpbtrf/dpbtrs, dsygv)";

/* A real, or null when there is none (NaN): jansson refuses non-finite reals. */
static json_t *real_or_null(double x)
{
    return isfinite(x) ? json_real(x) : json_null();
}

/* [scale * x[0], scale * x[stride], ...], n values. */
static json_t *real_array(const double *x, int n, int stride, double scale)
{
    json_t *a = json_array();
    for (int i = 0; a && i < n; i++) {
        if (json_array_append_new(a, real_or_null(scale * x[(size_t)i * (size_t)stride])) != 0) {
            json_decref(a);
            a = NULL;
        }
    }
    return a;
}

static json_t *mode_shape(const rd_mode *m, int n, double R)
{
    if (!m->shape)
        return json_null();
    return json_pack("{s:o, s:o, s:o, s:o}",
                     "radial", real_array(&SHAPE(m, 0, S_RADIAL), n, 6, 1.0),
                     "tangential", real_array(&SHAPE(m, 0, S_TANGENTIAL), n, 6, 1.0),
                     "axial", real_array(&SHAPE(m, 0, S_AXIAL), n, 6, 1.0),
                     "twist", real_array(&SHAPE(m, 0, S_ROT_TANGENTIAL), n, 6, R));
}

static json_t *modal_modes(const rd_modal_result *res, int n, double R)
{
    json_t *modes = json_array();
    for (int k = 0; modes && k < res->n_modes; k++) {
        const rd_mode *m = &res->modes[k];
        /* json_pack steals every "o" value, also when it fails. */
        json_t *mode = json_pack(
            "{s:i, s:o, s:s, s:o, s:o, s:o, s:o, s:o}",
            "mode", k + 1,
            "frequency_hz", real_or_null(m->frequency_hz),
            "kind", m->kind == RD_MODE_IN_PLANE ? "in_plane" : "out_of_plane",
            "in_plane_energy_fraction", real_or_null(m->in_plane_fraction),
            "error_estimate", real_or_null(m->error_estimate),
            "frequency_extrapolated_hz", real_or_null(m->frequency_extrapolated_hz),
            "residual", real_or_null(m->residual),
            "shape", mode_shape(m, n, R));
        if (json_array_append_new(modes, mode) != 0) {
            json_decref(modes);
            modes = NULL;
        }
    }
    return modes;
}

static json_t *modal_numerics(const rd_modal_result *res, double wall_s)
{
    char method[128];
    int estimated = res->reference_segments > 0;
    snprintf(method, sizeof method,
             "Richardson extrapolation from a second solve at %d segments, convergence order 2",
             res->reference_segments);
    return json_pack("{s:i, s:i, s:o, s:s, s:i, s:i, s:o, s:o, s:o, s:o}",
                     "segments", res->segments,
                     "dof", res->dof,
                     "wall_s", real_or_null(wall_s),
                     "solver", modal_solver,
                     "iterations", res->iterations,
                     "block_size", res->block_size,
                     "max_residual", real_or_null(res->max_residual),
                     "reference_segments",
                         estimated ? json_integer(res->reference_segments) : json_null(),
                     "error_estimate", real_or_null(res->error_estimate),
                     "error_method", estimated ? json_string(method) : json_null());
}

json_t *rd_result_modal(const rd_scene *scene, const rd_ring *ring, const rd_modal_result *res,
                        double wall_s)
{
    int n = rd_ring_get_segments(ring);
    double R = rd_ring_get_section(ring)->R;

    json_t *angles = json_array();
    for (int i = 0; angles && i < n; i++) {
        double deg = rd_ring_get_segment_angle(ring, i) * 180.0 / PI;
        if (json_array_append_new(angles, json_real(deg)) != 0) {
            json_decref(angles);
            angles = NULL;
        }
    }
    return json_pack("{s:s, s:o, s:i, s:o, s:o, s:o}",
                     "analysis", rd_scene_analysis(scene),
                     "scene", rd_scene_echo(scene),
                     "rigid_body_modes", res->rigid_body_modes,
                     "segment_angle_deg", angles,
                     "modes", modal_modes(res, n, R),
                     "numerics", modal_numerics(res, wall_s));
}

/* ---- pretension and contact ------------------------------------------------ */

static const char static_solver[] =
    "Newton's method with load stepping on the 6n equilibrium equations, large rotations, "
    "central-difference tangent in LAPACK band storage (dgbsv)";

static json_t *static_numerics(const rd_static_stats *st, double wall_s, const char *what)
{
    char method[192];
    int estimated = st->reference_segments > 0;
    snprintf(method, sizeof method,
             "%s from a second solve at %d segments", what, st->reference_segments);
    return json_pack("{s:i, s:i, s:o, s:s, s:i, s:i, s:o, s:o, s:o, s:o, s:o, s:o}",
                     "segments", st->segments,
                     "dof", st->dof,
                     "wall_s", real_or_null(wall_s),
                     "solver", static_solver,
                     "load_steps", st->load_steps,
                     "iterations", st->iterations,
                     "residual", real_or_null(st->residual),
                     "tolerance", real_or_null(st->tolerance),
                     "strain_energy", real_or_null(st->strain_energy),
                     "reference_segments",
                         estimated ? json_integer(st->reference_segments) : json_null(),
                     "error_estimate", real_or_null(st->error_estimate),
                     "error_method", estimated ? json_string(method) : json_null());
}

static json_t *support_object(const rd_static_stats *st)
{
    return json_pack("{s:o, s:o}", "force_n", real_or_null(st->support_force), "moment_nm",
                     real_or_null(st->support_moment));
}

json_t *rd_result_pretension(const rd_scene *scene, const rd_pretension_result *res,
                             double wall_s)
{
    int np = res->points;
    double *rx = malloc((size_t)np * sizeof *rx), *ry = malloc((size_t)np * sizeof *ry);
    json_t *out = NULL;
    if (!rx || !ry)
        goto out;
    double R = 0.5 * (scene->ring.diameter - scene->ring.radial_width);
    for (int k = 0; k < np; k++) {
        rx[k] = R * cos(res->angle_deg[k] * PI / 180.0);
        ry[k] = R * sin(res->angle_deg[k] * PI / 180.0);
    }
    out = json_pack(
        "{s:s, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:{s:o, s:o, s:o, s:o, s:o, s:o}, s:o}",
        "analysis", rd_scene_analysis(scene),
        "scene", rd_scene_echo(scene),
        "gap_opening_inner", real_or_null(res->gap_opening_inner),
        "lateral_opening", real_or_null(res->lateral_opening),
        "gap_opening_neutral", real_or_null(res->gap_opening_neutral),
        "free_gap_formula", real_or_null(res->free_gap_formula),
        "conformability", real_or_null(res->conformability),
        "support", support_object(&res->stats),
        "shape",
            "angle_deg", real_array(res->angle_deg, np, 1, 1.0),
            "x", real_array(res->x, np, 1, 1.0),
            "y", real_array(res->y, np, 1, 1.0),
            "z", real_array(res->z, np, 1, 1.0),
            "reference_x", real_array(rx, np, 1, 1.0),
            "reference_y", real_array(ry, np, 1, 1.0),
        "numerics", static_numerics(&res->stats, wall_s,
                                    "Richardson extrapolation (order 2) of x_a and x_c"));
out:
    free(rx);
    free(ry);
    return out;
}

/* Light gaps, tip forces, bins and the accuracy record (issue 11) added to
 * a contact result; non-zero on out of memory. */
static int contact_accuracy(json_t *out, const rd_contact_result *res)
{
    json_t *gaps = json_array(), *num = json_object_get(out, "numerics");
    int bad = !gaps || !num;
    for (int g = 0; !bad && g < res->n_gaps; g++) {
        const rd_contact_gap *p = &res->gaps[g];
        bad |= json_array_append_new(
            gaps, json_pack("{s:o, s:o, s:o, s:o}", "start_deg", real_or_null(p->start_deg),
                            "end_deg", real_or_null(p->end_deg), "max_clearance",
                            real_or_null(p->max_clearance), "max_clearance_angle_deg",
                            real_or_null(p->max_clearance_deg)));
    }
    bad |= json_object_set_new(out, "light_gaps", gaps);
    bad |= json_object_set_new(out, "tip_forces_n", real_array(res->tip_force, 2, 1, 1.0));
    bad |= json_object_set_new(
        out, "pressure_bins",
        json_pack("{s:f, s:o}", "bin_deg", RD_CONTACT_BIN_DEG, "pressure_pa",
                  real_array(res->bin_pressure, RD_CONTACT_BINS, 1, 1.0)));
    if (bad)
        return 1;
    const rd_contact_estimates *e = &res->estimates;
    bad |= json_object_set_new(
        num, "error_estimates",
        json_pack("{s:o, s:o, s:o, s:o}", "pressure", real_or_null(e->pressure),
                  "contact_fraction", real_or_null(e->contact_fraction), "max_clearance",
                  real_or_null(e->max_clearance), "gap_edges_deg", real_or_null(e->gap_edges_deg)));
    bad |= json_object_set_new(num, "accuracy", real_or_null(res->accuracy_met < 0 ? NAN
                                                                                  : res->accuracy));
    bad |= json_object_set_new(num, "accuracy_met", res->accuracy_met < 0
                                                        ? json_null()
                                                        : json_boolean(res->accuracy_met));
    bad |= json_object_set_new(num, "accuracy_note", res->accuracy_note[0]
                                                         ? json_string(res->accuracy_note)
                                                         : json_null());
    return bad;
}

json_t *rd_result_contact(const rd_scene *scene, const rd_contact_result *res, double wall_s)
{
    int n = res->points;
    json_t *dist = json_array();
    for (int k = 0; dist && k < scene->contact.n_distortion; k++) {
        const rd_distortion *d = &scene->contact.distortion[k];
        if (json_array_append_new(dist, json_pack("{s:i, s:o, s:o, s:o}", "order", d->order,
                                                  "amplitude", real_or_null(d->amplitude),
                                                  "phase_deg", real_or_null(d->phase_deg),
                                                  "conformability_bound",
                                                  real_or_null(res->bound[k]))) != 0) {
            json_decref(dist);
            dist = NULL;
        }
    }
    json_t *out = json_pack(
        "{s:s, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o,"
        " s:o}",
        "analysis", rd_scene_analysis(scene),
        "scene", rd_scene_echo(scene),
        "angle_deg", real_array(res->angle_deg, n, 1, 1.0),
        "pressure_pa", real_array(res->pressure, n, 1, 1.0),
        "clearance", real_array(res->clearance, n, 1, 1.0),
        "bore_radius", real_array(res->bore_radius, n, 1, 1.0),
        "mean_pressure_pa", real_or_null(res->mean_pressure),
        "uniform_pressure_pa", real_or_null(res->uniform_pressure),
        "contact_fraction", real_or_null(res->contact_fraction),
        "max_clearance", real_or_null(res->max_clearance),
        "max_clearance_angle_deg", real_or_null(res->max_clearance_angle_deg),
        "max_penetration", real_or_null(res->max_penetration),
        "contact_stiffness", real_or_null(res->stiffness),
        "conformability", real_or_null(res->conformability),
        "distortion", dist,
        "support", support_object(&res->stats),
        "numerics", static_numerics(&res->stats, wall_s,
                                    "Largest difference of the binned pressure, relative to "
                                    "the uniform pressure, at the last two refinement levels,"));
    if (out && contact_accuracy(out, res) != 0) {
        json_decref(out);
        out = NULL;
    }
    return out;
}

/* ---- lift ------------------------------------------------------------------ */

static const char *const flank_names[] = {"lower", "upper", "free"};
static const char *const event_names[] = {"leave_lower", "reach_upper", "leave_upper",
                                          "reach_lower"};

json_t *rd_result_lift(const rd_scene *scene, const rd_lift_result *res, double wall_s)
{
    int N = res->samples, n = res->segments;
    json_t *segs = json_array(), *flank = json_array(), *events = json_array();
    for (int k = 0; segs && k < N; k++)
        if (json_array_append_new(segs, real_array(res->lift_segments + (size_t)k * n, n, 1,
                                                   1.0)) != 0) {
            json_decref(segs);
            segs = NULL;
        }
    for (int k = 0; flank && k < N; k++) {
        int f = res->flank[k];
        if (json_array_append_new(flank, json_string(f >= 0 && f < 3 ? flank_names[f] : "free")) != 0) {
            json_decref(flank);
            flank = NULL;
        }
    }
    for (int k = 0; events && k < res->n_events; k++) {
        int e = res->events[k].kind;
        if (json_array_append_new(events, json_pack("{s:o, s:s}", "crank_deg",
                                                    real_or_null(res->events[k].crank_deg),
                                                    "event",
                                                    e >= 0 && e < 4 ? event_names[e] : "unknown")) != 0) {
            json_decref(events);
            events = NULL;
        }
    }
    int estimated = isfinite(res->error_estimate);
    json_t *numerics = json_pack(
        "{s:i, s:i, s:o, s:s, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:o, s:o, s:o, s:o, s:o}",
        "segments", n,
        "dof", res->dof,
        "wall_s", real_or_null(wall_s),
        "solver", "SUNDIALS CVODE, BDF with a banded Newton linear solver, root finding for the "
                  "flank changes",
        "steps", (json_int_t)res->steps,
        "rhs_evals", (json_int_t)res->rhs_evals,
        "jac_evals", (json_int_t)res->jac_evals,
        "linear_setups", (json_int_t)res->lin_setups,
        "nonlinear_iterations", (json_int_t)res->nonlin_iters,
        "nonlinear_failures", (json_int_t)res->nonlin_fails,
        "error_test_fails", (json_int_t)res->err_test_fails,
        "root_evals", (json_int_t)res->root_evals,
        "rtol", real_or_null(scene->lift.rtol),
        "atol", real_or_null(scene->lift.atol),
        "error_estimate", real_or_null(res->error_estimate),
        "event_error_deg", real_or_null(res->event_error_deg),
        "error_method", estimated ? json_string("second run at rtol/10 and atol/10: largest lift "
                                                "difference over the axial clearance, and the "
                                                "largest shift of a matched flank change")
                                  : json_null());
    return json_pack("{s:s, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o}",
                     "analysis", rd_scene_analysis(scene),
                     "scene", rd_scene_echo(scene),
                     "crank_deg", real_array(res->crank_deg, N, 1, 1.0),
                     "lift", real_array(res->lift, N, 1, 1.0),
                     "lift_min", real_array(res->lift_min, N, 1, 1.0),
                     "lift_max", real_array(res->lift_max, N, 1, 1.0),
                     "lift_segments", segs,
                     "twist_rad", real_array(res->twist, N, 1, 1.0),
                     "friction_force", real_array(res->friction_force, N, 1, 1.0),
                     "flank", flank,
                     "events", events,
                     "numerics", numerics);
}

/* ---- CSV ----------------------------------------------------------------- */

/* A growing string; `failed` sticks after the first allocation failure. */
typedef struct strbuf {
    char *p;
    size_t len, cap;
    int failed;
} strbuf;

static void sb_printf(strbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void sb_printf(strbuf *b, const char *fmt, ...)
{
    va_list ap;
    if (b->failed)
        return;
    va_start(ap, fmt);
    int need = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (need < 0) {
        b->failed = 1;
        return;
    }
    if (b->len + (size_t)need + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1024;
        while (cap < b->len + (size_t)need + 1)
            cap *= 2;
        char *p = realloc(b->p, cap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(b->p + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    b->len += (size_t)need;
}

/* A cell from a number or null (empty); anything else is malformed. */
static int csv_real(strbuf *b, json_t *v, const char *sep)
{
    if (json_is_null(v)) {
        sb_printf(b, "%s", sep);
        return 0;
    }
    if (!json_is_number(v))
        return -1;
    sb_printf(b, "%.10g%s", json_number_value(v), sep);
    return 0;
}

/* A text cell, quoted (RFC 4180) when it holds a separator, quote or newline. */
static void csv_text(strbuf *b, const char *s, const char *sep)
{
    if (!strpbrk(s, ",\"\r\n")) {
        sb_printf(b, "%s%s", s, sep);
        return;
    }
    sb_printf(b, "\"");
    for (; *s; s++) {
        if (*s == '"')
            sb_printf(b, "\"\"");
        else
            sb_printf(b, "%c", *s);
    }
    sb_printf(b, "\"%s", sep);
}

static int csv_modal(json_t *result, strbuf *b, rd_error *err)
{
    static const char *const reals[] = {"frequency_hz", "error_estimate",
                                        "frequency_extrapolated_hz", "in_plane_energy_fraction"};
    const size_t n_reals = sizeof reals / sizeof reals[0];
    json_t *modes = json_object_get(result, "modes");
    size_t i;
    json_t *mode;

    if (!json_is_array(modes))
        return rd_error_set(err, RD_EINTERNAL, "",
                            "malformed modal result: /modes is not an array");
    sb_printf(b, "mode,kind");
    for (size_t k = 0; k < n_reals; k++)
        sb_printf(b, ",%s", reals[k]);
    sb_printf(b, "\n");

    json_array_foreach(modes, i, mode) {
        json_t *number = json_object_get(mode, "mode");
        json_t *kind = json_object_get(mode, "kind");
        if (!json_is_integer(number) || !json_is_string(kind))
            return rd_error_set(err, RD_EINTERNAL, "",
                                "malformed modal result: /modes/%zu needs an integer \"mode\" and "
                                "a string \"kind\"",
                                i);
        sb_printf(b, "%" JSON_INTEGER_FORMAT ",", json_integer_value(number));
        csv_text(b, json_string_value(kind), ",");
        for (size_t k = 0; k < n_reals; k++) {
            if (csv_real(b, json_object_get(mode, reals[k]), k + 1 < n_reals ? "," : "\n") != 0)
                return rd_error_set(err, RD_EINTERNAL, "",
                                    "malformed modal result: /modes/%zu/%s is not a number or null",
                                    i, reals[k]);
        }
    }
    return RD_OK;
}

/* Columns of equal-length arrays: header names (with units) and the result
 * keys they come from; `text` columns hold strings. */
typedef struct column {
    const char *header, *key;
    int text;
} column;

static int csv_columns(json_t *result, strbuf *b, const column *cols, int ncols,
                       const char *analysis, rd_error *err)
{
    size_t rows = 0;
    for (int c = 0; c < ncols; c++) {
        json_t *a = json_object_get(result, cols[c].key);
        if (!json_is_array(a))
            return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s is not an array",
                                analysis, cols[c].key);
        if (c == 0)
            rows = json_array_size(a);
        else if (json_array_size(a) != rows)
            return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s has %zu rows, "
                                "not %zu", analysis, cols[c].key, json_array_size(a), rows);
        sb_printf(b, "%s%s", cols[c].header, c + 1 < ncols ? "," : "\n");
    }
    for (size_t i = 0; i < rows; i++)
        for (int c = 0; c < ncols; c++) {
            json_t *v = json_array_get(json_object_get(result, cols[c].key), i);
            const char *sep = c + 1 < ncols ? "," : "\n";
            if (cols[c].text && json_is_string(v))
                csv_text(b, json_string_value(v), sep);
            else if (cols[c].text || csv_real(b, v, sep) != 0)
                return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s/%zu",
                                    analysis, cols[c].key, i);
        }
    return RD_OK;
}

static int csv_pretension(json_t *result, strbuf *b, rd_error *err)
{
    static const column cols[] = {{"angle_deg", "angle_deg", 0}, {"x_m", "x", 0},
                                  {"y_m", "y", 0}, {"z_m", "z", 0},
                                  {"reference_x_m", "reference_x", 0},
                                  {"reference_y_m", "reference_y", 0}};
    return csv_columns(json_object_get(result, "shape"), b, cols, 6, "pretension", err);
}

static int csv_contact(json_t *result, strbuf *b, rd_error *err)
{
    static const column cols[] = {{"angle_deg", "angle_deg", 0},
                                  {"pressure_pa", "pressure_pa", 0},
                                  {"clearance_m", "clearance", 0},
                                  {"bore_radius_m", "bore_radius", 0}};
    return csv_columns(result, b, cols, 4, "contact", err);
}

static int csv_lift(json_t *result, strbuf *b, rd_error *err)
{
    static const column cols[] = {{"crank_deg", "crank_deg", 0}, {"lift_m", "lift", 0},
                                  {"lift_min_m", "lift_min", 0}, {"lift_max_m", "lift_max", 0},
                                  {"twist_rad", "twist_rad", 0},
                                  {"friction_force_n", "friction_force", 0},
                                  {"flank", "flank", 1}};
    return csv_columns(result, b, cols, 7, "lift", err);
}

/* One table per analysis; a later analysis adds its writer here. */
static const struct csv_table {
    const char *analysis;
    int (*write)(json_t *result, strbuf *b, rd_error *err);
} csv_tables[] = {
    {"modal", csv_modal},
    {"pretension", csv_pretension},
    {"contact", csv_contact},
    {"lift", csv_lift},
};

char *rd_result_csv(json_t *result, rd_error *err)
{
    strbuf b = {NULL, 0, 0, 0};
    const char *analysis = json_string_value(json_object_get(result, "analysis"));
    const struct csv_table *table = NULL;
    int rc;

    if (!analysis) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "malformed result: no \"analysis\" string");
        goto out;
    }
    for (size_t k = 0; k < sizeof csv_tables / sizeof csv_tables[0]; k++)
        if (strcmp(csv_tables[k].analysis, analysis) == 0)
            table = &csv_tables[k];
    if (!table) {
        rc = rd_error_set(err, RD_ENOTFOUND, "", "a %.40s result has no CSV table", analysis);
        goto out;
    }
    rc = table->write(result, &b, err);
    if (rc == RD_OK && b.failed)
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the CSV table");
out:
    if (rc != RD_OK) {
        free(b.p);
        return NULL;
    }
    return b.p;
}
