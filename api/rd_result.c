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

/* One table per analysis; a later analysis adds its writer here. */
static const struct csv_table {
    const char *analysis;
    int (*write)(json_t *result, strbuf *b, rd_error *err);
} csv_tables[] = {
    {"modal", csv_modal},
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
