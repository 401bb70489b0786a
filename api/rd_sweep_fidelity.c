/*
 * rd_sweep_fidelity — the speed/accuracy trade of one scene as a sweep
 * (rd_sweep.h, "fidelity"): the spec that runs a scene over its fidelity
 * settings, and the table that sets each run's cost against its error
 * estimate and against the finest run.
 *
 * The error against the finest run e_j = max_k |q_jk - Q_k| / s_k, with Q the
 * finest run's quantity and s_k = |Q_k| (modal frequencies, x_a, mean
 * pressure: relative errors, as the estimates are), or the axial clearance
 * for lift (the lift estimate's own measure).  It is an error against a
 * better answer, not against the exact one: for the finest row it is 0 by
 * construction, and for the others it underestimates the true error by the
 * finest run's own error.
 *
 * The basis of each row's error (issue 44: the trade trusts only what it
 * measured).  A row differs from the finest run in some of its
 * discretisations ("changes": segments, time = the rtol, model = the model
 * that ran); its estimate covers some ("estimate_covers": modal, pretension,
 * contact the segment count, from their second solve; lift the time
 * integration, plus the segment count when a flexible ring had its n/2 run,
 * core/lift/rd_lift_solve.c compare_levels — the rigid ring's checks are in
 * its flank-change error, not in the lift estimate).  The row's error is its
 * estimate ("basis": "estimate") when that covers every change and is not
 * below the measured difference; else the measured difference ("measured").
 * So a row's error_on_basis is never below what was measured.
 */
#include "rd_sweep.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_api.h"

#define DUMP_FLAGS (JSON_COMPACT | JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS))

static const double modal_ladder[] = {5, 10, 20, 40, 80, 160, 320};
static const double lift_ladder[] = {4, 8, 16, 32};
static const double lift_rtols[] = {1e-4, 1e-5, 1e-6, 1e-7};

/* What a fidelity sweep compares, per analysis. */
static const struct {
    const char *analysis;
    const char *block; /* the block whose "error_estimate": true turns it on */
    const char *estimate, *quantity;
} kinds[] = {
    {"modal", "modal", "max(/modes/*/error_estimate)", "all(/modes/*/frequency_hz)"},
    {"pretension", "numerics", "/numerics/error_estimate", "all(/gap_opening_inner)"},
    {"contact", "numerics", "/numerics/error_estimate", "all(/mean_pressure_pa)"},
    {"lift", "numerics", "/numerics/error_estimate", "all(/lift)"},
};

static json_t *reals(const double *v, size_t n)
{
    json_t *a = json_array();
    for (size_t k = 0; a && k < n; k++)
        json_array_append_new(a, json_real(v[k]));
    return a;
}

/* {"path": p, "values": values} appended to params (values stolen). */
static void add_param(json_t *params, const char *path, json_t *values)
{
    json_array_append_new(params, json_pack("{s:s, s:o}", "path", path, "values", values));
}

/* The scene as the base of the sweep, with its estimate on, and its kind. */
static json_t *fidelity_base(const char *text, size_t len, int *kind, rd_error *err)
{
    rd_scene *sc = NULL;
    if (rd_scene_parse(text, len, &sc, err) != RD_OK)
        return NULL;
    const char *analysis = rd_scene_analysis(sc);
    *kind = -1;
    for (int k = 0; k < (int)(sizeof kinds / sizeof kinds[0]); k++)
        if (strcmp(kinds[k].analysis, analysis) == 0)
            *kind = k;
    rd_scene_free(sc);
    json_t *base = *kind >= 0 ? json_loadb(text, len, 0, NULL) : NULL;
    if (!base) {
        rd_error_set(err, *kind < 0 ? RD_EINVAL : RD_ENOMEM, "/analysis",
                     *kind < 0 ? "a fidelity sweep needs a modal, pretension, contact or lift "
                                 "scene"
                               : "out of memory");
        return NULL;
    }
    const char *block = kinds[*kind].block;
    json_t *b = json_object_get(base, block);
    if (!json_is_object(b)) {
        b = json_object();
        json_object_set_new(base, block, b);
    }
    json_object_set_new(b, "error_estimate", json_true());
    json_object_del(base, "name");
    json_object_del(base, "description");
    return base;
}

char *rd_sweep_fidelity_spec(const char *scene, size_t len, const rd_sweep_fidelity_opts *opts,
                             rd_error *err)
{
    static const rd_sweep_fidelity_opts none = {0};
    int kind;
    opts = opts ? opts : &none;
    json_t *base = fidelity_base(scene, len, &kind, err);
    if (!base)
        return NULL;
    int lift = strcmp(kinds[kind].analysis, "lift") == 0;
    json_t *params = json_array(), *models = json_array();
    add_param(params, "/discretization/segments",
              opts->segments ? reals(opts->segments, opts->n_segments)
              : lift         ? reals(lift_ladder, sizeof lift_ladder / sizeof lift_ladder[0])
                             : reals(modal_ladder, sizeof modal_ladder / sizeof modal_ladder[0]));
    if (lift)
        add_param(params, "/numerics/rtol",
                  opts->rtol ? reals(opts->rtol, opts->n_rtol)
                             : reals(lift_rtols, sizeof lift_rtols / sizeof lift_rtols[0]));
    for (size_t k = 0; models && k < opts->n_models; k++)
        json_array_append_new(models, json_string(opts->models[k]));
    if (opts->n_models)
        add_param(params, "/numerics/model", json_incref(models));
    json_t *outputs =
        json_pack("[s, s, s]", "/numerics/wall_s", kinds[kind].estimate, kinds[kind].quantity);
    if (lift && outputs) { /* and the model a lift run really integrated (auto's choice) */
        json_array_append_new(outputs, json_string("/scene/groove/axial_clearance"));
        json_array_append_new(outputs, json_string("/numerics/model/name"));
        json_array_append_new(outputs, json_string("/numerics/segments_check"));
    }
    json_t *spec = json_pack("{s:o, s:o, s:s, s:o}", "base", base, "parameters", params, "combine",
                             "product", "outputs", outputs);
    json_decref(models);
    char *text = spec ? json_dumps(spec, DUMP_FLAGS) : NULL;
    json_decref(spec);
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while building the fidelity sweep");
    return text;
}

/* ---- the fidelity table -------------------------------------------------- */

/* Index of the column named `name` (or starting with it when prefix), or -1. */
static int column(json_t *cols, const char *name, int prefix)
{
    for (size_t k = 0; k < json_array_size(cols); k++) {
        const char *c = json_string_value(json_array_get(cols, k));
        if (c && (prefix ? strncmp(c, name, strlen(name)) == 0 : strcmp(c, name) == 0))
            return (int)k;
    }
    return -1;
}

typedef struct {
    int seg, rtol, model, ran, wall, est, q, clearance, check, status;
} fidelity_cols;

/* The discretisations, as named in "changes" and "estimate_covers". */
enum { D_SEGMENTS = 1, D_TIME = 2, D_MODEL = 4 };

static int row_ok(json_t *row, const fidelity_cols *c)
{
    const char *s = json_string_value(json_array_get(row, (size_t)c->status));
    return s && strcmp(s, "ok") == 0 && json_is_array(json_array_get(row, (size_t)c->q));
}

static double cell(json_t *row, int k)
{
    json_t *v = k >= 0 ? json_array_get(row, (size_t)k) : NULL;
    return json_is_number(v) ? json_number_value(v) : NAN;
}

/* The finest ok row: most segments, then the smallest rtol; NULL if none. */
static json_t *finest_row(json_t *rows, const fidelity_cols *c)
{
    json_t *best = NULL;
    for (size_t i = 0; i < json_array_size(rows); i++) {
        json_t *r = json_array_get(rows, i);
        if (!row_ok(r, c))
            continue;
        double n = cell(r, c->seg), bn = best ? cell(best, c->seg) : -1;
        double t = c->rtol >= 0 ? cell(r, c->rtol) : 0,
               bt = best && c->rtol >= 0 ? cell(best, c->rtol) : 0;
        if (!best || n > bn || (n == bn && t < bt))
            best = r;
    }
    return best;
}

/* e = max_k |q_k - Q_k| / s_k (file comment); null when not comparable. */
static json_t *error_vs(json_t *row, json_t *finest, const fidelity_cols *c)
{
    if (!finest || !row_ok(row, c))
        return json_null();
    json_t *q = json_array_get(row, (size_t)c->q), *Q = json_array_get(finest, (size_t)c->q);
    double scale = c->clearance >= 0 ? cell(finest, c->clearance) : NAN, e = 0;
    if (json_array_size(q) != json_array_size(Q) || json_array_size(Q) == 0)
        return json_null();
    for (size_t k = 0; k < json_array_size(Q); k++) {
        double a = json_number_value(json_array_get(q, k)),
               b = json_number_value(json_array_get(Q, k));
        double s = c->clearance >= 0 ? scale : fabs(b);
        double d = s > 0 ? fabs(a - b) / s : (a == b ? 0 : INFINITY);
        e = d > e ? d : e;
    }
    return isfinite(e) ? json_real(e) : json_null();
}

/* What the row's estimate covers (file comment); 0 when it has none. */
static unsigned covers(json_t *row, const fidelity_cols *c)
{
    if (!row_ok(row, c) || !isfinite(cell(row, c->est)))
        return 0;
    if (c->clearance < 0) /* modal, pretension, contact: a second solve at other segments */
        return D_SEGMENTS;
    const char *ran = c->ran >= 0 ? json_string_value(json_array_get(row, (size_t)c->ran)) : NULL;
    int rigid = ran && strcmp(ran, "rigid") == 0;
    return D_TIME | (!rigid && isfinite(cell(row, c->check)) ? D_SEGMENTS : 0u);
}

static int same_value(json_t *row, json_t *finest, int k)
{
    return k < 0 || json_equal(json_array_get(row, (size_t)k), json_array_get(finest, (size_t)k));
}

/* Where the row's setting differs from the finest run's (for the model, the
 * one that ran: auto's choice). */
static unsigned changes(json_t *row, json_t *finest, const fidelity_cols *c)
{
    if (!finest)
        return 0;
    return (same_value(row, finest, c->seg) ? 0u : D_SEGMENTS) |
           (same_value(row, finest, c->rtol) ? 0u : D_TIME) |
           (same_value(row, finest, c->ran >= 0 ? c->ran : c->model) ? 0u : D_MODEL);
}

/* "segments time model" (those in `set`); null when `none_null` and empty. */
static json_t *names(unsigned set, int none_null)
{
    char text[32] = "";
    static const char *const word[] = {"segments", "time", "model"};
    if (!set && none_null)
        return json_null();
    for (int k = 0; k < 3; k++)
        if (set & (1u << k)) {
            if (text[0])
                strcat(text, " ");
            strcat(text, word[k]);
        }
    return json_string(text);
}

/* The basis of the row's error: 1 estimate, 0 measured, -1 none (not
 * comparable with the finest run); *e the error on it. */
static int basis(json_t *row, json_t *finest, const fidelity_cols *c, double *e)
{
    json_t *vs = error_vs(row, finest, c);
    double m = json_is_number(vs) ? json_number_value(vs) : NAN, est = cell(row, c->est);
    unsigned need = changes(row, finest, c), have = covers(row, c);
    json_decref(vs);
    *e = NAN;
    if (!isfinite(m))
        return -1;
    if (have && (need & ~have) == 0 && est >= m) {
        *e = est;
        return 1;
    }
    *e = m;
    return 0;
}

/* Row i is on the front: no other row with a basis (e[j] not NaN) is at most
 * as slow and at most as wrong on its basis, and better in one. */
static int pareto(json_t *rows, size_t i, const double *e, const fidelity_cols *c)
{
    double w = cell(json_array_get(rows, i), c->wall);
    if (isnan(e[i]) || !isfinite(w))
        return 0;
    for (size_t j = 0; j < json_array_size(rows); j++) {
        double ow = cell(json_array_get(rows, j), c->wall);
        if (j != i && !isnan(e[j]) && ow <= w && e[j] <= e[i] && (ow < w || e[j] < e[i]))
            return 0;
    }
    return 1;
}

/* Row i of the fidelity table (new reference); b[i], e[i] its basis. */
static json_t *fidelity_row(json_t *rows, size_t i, json_t *finest, const int *b, const double *e,
                            const fidelity_cols *c)
{
    json_t *r = json_array_get(rows, i), *out = json_array();
    for (size_t k = 0; out && k < json_array_size(r); k++) {
        if ((int)k == c->q || (int)k == c->clearance || (int)k == c->check)
            continue;
        if ((int)k == c->status) {
            json_array_append_new(out, error_vs(r, finest, c));
            json_array_append_new(out, names(covers(r, c), 1));
            json_array_append_new(out, row_ok(r, c) && finest ? names(changes(r, finest, c), 0)
                                                              : json_null());
            json_array_append_new(out, b[i] < 0 ? json_null()
                                                : json_string(b[i] ? "estimate" : "measured"));
            json_array_append_new(out, b[i] < 0 ? json_null() : json_real(e[i]));
            json_array_append_new(out, json_boolean(pareto(rows, i, e, c)));
        }
        json_array_append(out, json_array_get(r, k));
    }
    return out;
}

char *rd_sweep_fidelity_table(const char *table_json, rd_error *err)
{
    json_t *t = json_loads(table_json, 0, NULL), *cols = json_object_get(t, "columns");
    json_t *rows = json_object_get(t, "rows");
    fidelity_cols c = {column(cols, "/discretization/segments", 0),
                       column(cols, "/numerics/rtol", 0),
                       column(cols, "/numerics/model", 0),
                       column(cols, "/numerics/model/name", 0),
                       column(cols, "/numerics/wall_s", 0),
                       -1,
                       column(cols, "all(", 1),
                       column(cols, "/scene/groove/axial_clearance", 0),
                       column(cols, "/numerics/segments_check", 0),
                       column(cols, "status", 0)};
    c.est = c.wall + 1;
    if (!json_is_array(rows) || c.seg < 0 || c.wall < 0 || c.q < 0 || c.status < 0 ||
        c.est >= (int)json_array_size(cols)) {
        json_decref(t);
        rd_error_set(err, RD_EINTERNAL, "", "not the table of a fidelity sweep");
        return NULL;
    }
    size_t n = json_array_size(rows);
    json_t *finest = finest_row(rows, &c), *ncols = json_array(), *nrows = json_array();
    int *b = malloc((n ? n : 1) * sizeof *b);
    double *e = malloc((n ? n : 1) * sizeof *e);
    for (size_t i = 0; b && e && i < n; i++) {
        json_t *r = json_array_get(rows, i);
        e[i] = NAN;
        b[i] = row_ok(r, &c) ? basis(r, finest, &c, &e[i]) : -1;
    }
    for (size_t k = 0; k < json_array_size(cols); k++) {
        if ((int)k == c.q || (int)k == c.clearance || (int)k == c.check)
            continue;
        if ((int)k == c.status) {
            static const char *const added[] = {"error_vs_finest", "estimate_covers", "changes",
                                                "basis",           "error_on_basis",  "pareto"};
            for (size_t a = 0; a < sizeof added / sizeof added[0]; a++)
                json_array_append_new(ncols, json_string(added[a]));
        }
        json_array_append(ncols, json_array_get(cols, k));
    }
    for (size_t i = 0; b && e && i < n; i++)
        json_array_append_new(nrows, fidelity_row(rows, i, finest, b, e, &c));
    json_t *out = NULL;
    if (b && e)
        out = json_pack("{s:o, s:o}", "columns", ncols, "rows", nrows); /* steals both */
    else {
        json_decref(ncols);
        json_decref(nrows);
    }
    free(b);
    free(e);
    char *text = out ? json_dumps(out, DUMP_FLAGS | JSON_PRESERVE_ORDER) : NULL;
    json_decref(out);
    json_decref(t);
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the fidelity table");
    return text;
}
