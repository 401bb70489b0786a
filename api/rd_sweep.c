/*
 * rd_sweep — sweep specs: parsing, validation against the scene schema,
 * and deterministic expansion (product, zip, Latin hypercube over
 * splitmix64).  The spec format, the expansion formulas and the output
 * syntax are in rd_sweep.h; running one point into a table row is in
 * rd_sweep_run.c, the table, CSV and chunk files in rd_sweep_table.c.
 *
 * A point's scene is the base with each parameter's value written at its
 * pointer; it goes through rd_scene_parse_value and rd_scene_run exactly like
 * a posted scene, so a sweep can only ask what a single job could.
 */
#include "rd_sweep.h"

#include <float.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rd_jsonptr.h"
#include "rd_result_schema.h"
#include "rd_scene.h"
#include "rd_sweep_int.h"

/* Values of a range tried at validation: all of them up to this count,
 * the two endpoints above it (each try parses a whole scene). */
#define RANGE_CHECK_ALL 1000

/* ---- splitmix64 (Steele, Lea, Flood, OOPSLA 2014) ------------------------ */

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* A uniform double in [0, 1) from the top 53 bits: exact on every machine. */
static double uniform(uint64_t *x)
{
    return (double)(splitmix64(x) >> 11) * 0x1.0p-53;
}

/* The design of rd_sweep.h: per parameter a Fisher-Yates permutation of the
 * S strata, then S jitters; u = (stratum + jitter) / S. */
static int lhs_design(rd_sweep *s, uint64_t seed)
{
    size_t S = s->points;
    s->u = malloc((size_t)s->np * S * sizeof *s->u);
    size_t *perm = malloc(S * sizeof *perm);
    if (!s->u || !perm) {
        free(perm);
        return RD_ENOMEM;
    }
    uint64_t x = seed;
    for (int p = 0; p < s->np; p++) {
        for (size_t k = 0; k < S; k++)
            perm[k] = k;
        for (size_t k = S - 1; k >= 1; k--) {
            size_t j = (size_t)(uniform(&x) * (double)(k + 1));
            size_t t = perm[k];
            perm[k] = perm[j];
            perm[j] = t;
        }
        for (size_t i = 0; i < S; i++)
            s->u[(size_t)p * S + i] = ((double)perm[i] + uniform(&x)) / (double)S;
    }
    free(perm);
    return RD_OK;
}

/* ---- values of a point --------------------------------------------------- */

/* The number at t in [0, 1] of a range or random parameter (rd_sweep.h). */
static double at(const param *q, double t)
{
    return q->log ? q->a * pow(q->b / q->a, t) : q->a + (q->b - q->a) * t;
}

/* The number of entry k of a range, endpoints exact. */
static double range_number(const param *q, size_t k)
{
    if (k == 0)
        return q->a;
    if (k == q->n - 1)
        return q->b;
    return at(q, (double)k / (double)(q->n - 1));
}

/* A number as a JSON value.  Validation (check_finite) refuses every spec
 * with a non-finite value, so NULL means out of memory; were one to slip
 * through, it is written as null, which the point's scene then refuses
 * (a row with its error, never a lost point). */
static json_t *number_value(const param *q, double v)
{
    if (!isfinite(v))
        return json_null();
    return q->integer ? json_integer((json_int_t)llround(v)) : json_real(v);
}

/* Entry k of a values/range parameter (new reference).  A listed value is
 * copied, not shared: a later parameter may write inside it (/ring, then
 * /ring/diameter), and the spec must stay unmodified for other threads. */
json_t *rd_sweep_entry(const param *q, size_t k)
{
    if (q->kind == P_VALUES)
        return json_deep_copy(json_array_get(q->values, k));
    return number_value(q, range_number(q, k));
}

json_t *rd_sweep_param_value(const rd_sweep *s, int p, size_t i)
{
    const param *q = &s->p[p];
    if (s->combine == C_ZIP)
        return rd_sweep_entry(q, i);
    if (s->combine == C_PRODUCT)
        return rd_sweep_entry(q, (i / q->stride) % q->n);
    double u = s->u[(size_t)p * s->points + i];
    if (q->kind == P_RANDOM)
        return number_value(q, at(q, u));
    size_t k = (size_t)(u * (double)q->n);
    return rd_sweep_entry(q, k < q->n ? k : q->n - 1);
}

/* `scene` (or, when NULL, a deep copy of the base) with `value` written at
 * `path`; value and scene are stolen.  NULL when the path cannot be written
 * (it crosses a scalar or indexes past an array) or memory runs out (then
 * *oom is 1). */
static json_t *with_value(const json_t *base, json_t *scene, const char *path, json_t *value,
                          int *oom)
{
    if (!scene)
        scene = json_deep_copy(base);
    int rc = !scene || !value ? -2 : rd_jsonptr_set(scene, path, value);
    if (rc != 0) {
        if (!scene || !value)
            json_decref(value);
        json_decref(scene);
        *oom = rc == -2;
        return NULL;
    }
    return scene;
}

json_t *rd_sweep_point_json(const rd_sweep *s, size_t i)
{
    json_t *scene = json_deep_copy(s->base);
    int oom = 0;
    for (int p = 0; scene && p < s->np; p++)
        scene = with_value(s->base, scene, s->p[p].path, rd_sweep_param_value(s, p, i), &oom);
    return scene;
}

/* ---- spec parsing -------------------------------------------------------- */

static int spec_error(rd_error *err, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int spec_error(rd_error *err, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = rd_error_setv(err, RD_EREQUEST, path, fmt, ap);
    va_end(ap);
    return rc;
}

/* Every key of `obj` is one of `allowed` (NULL-terminated). */
static int known_keys(json_t *obj, const char *const *allowed, const char *path, rd_error *err)
{
    const char *key;
    json_t *v;
    json_object_foreach(obj, key, v)
    {
        int ok = 0;
        for (int k = 0; allowed[k] && !ok; k++)
            ok = strcmp(key, allowed[k]) == 0;
        if (!ok)
            return spec_error(err, path, "unknown field \"%s\" in %s", key,
                              path[0] ? path : "the sweep spec");
    }
    return RD_OK;
}

/* A finite number member `key` of obj (required). */
static int number(json_t *obj, const char *key, const char *path, double *out, rd_error *err)
{
    json_t *v = json_object_get(obj, key);
    if (!json_is_number(v) || !isfinite(json_number_value(v)))
        return spec_error(err, path, "%s/%s must be a finite number", path, key);
    *out = json_number_value(v);
    return RD_OK;
}

/* "scale": "linear" (default) or "log"; *log = 1 for log. */
static int scale(json_t *obj, const char *path, int *log, rd_error *err)
{
    json_t *v = json_object_get(obj, "scale");
    *log = 0;
    if (!v || (json_is_string(v) && strcmp(json_string_value(v), "linear") == 0))
        return RD_OK;
    if (json_is_string(v) && strcmp(json_string_value(v), "log") == 0) {
        *log = 1;
        return RD_OK;
    }
    return spec_error(err, path, "%s/scale must be \"linear\" or \"log\"", path);
}

static int parse_range(json_t *r, const char *path, param *q, rd_error *err)
{
    static const char *const keys[] = {"start", "stop", "count", "scale", "integer", NULL};
    if (!json_is_object(r))
        return spec_error(err, path, "%s must be an object {start, stop, count, scale}", path);
    json_t *count = json_object_get(r, "count"), *integer = json_object_get(r, "integer");
    if (known_keys(r, keys, path, err) || number(r, "start", path, &q->a, err) ||
        number(r, "stop", path, &q->b, err) || scale(r, path, &q->log, err))
        return err->code;
    if (!json_is_integer(count) || json_integer_value(count) < 1 ||
        json_integer_value(count) > RD_SWEEP_POINTS_MAX)
        return spec_error(err, path, "%s/count must be an integer from 1 to %d", path,
                          RD_SWEEP_POINTS_MAX);
    if (integer && !json_is_boolean(integer))
        return spec_error(err, path, "%s/integer must be true or false", path);
    /* llround is defined only for values a long long holds; beyond 2^53 a
     * double has no fractional part to round anyway. */
    if (json_is_true(integer) && (fabs(q->a) > 0x1p53 || fabs(q->b) > 0x1p53))
        return spec_error(err, path, "%s: an integer range must lie within +-2^53", path);
    if (q->log && (q->a <= 0 || q->b <= 0))
        return spec_error(err, path, "%s: a log range needs start > 0 and stop > 0, got %g and %g",
                          path, q->a, q->b);
    q->n = (size_t)json_integer_value(count);
    q->integer = json_is_true(integer);
    q->kind = P_RANGE;
    return RD_OK;
}

static int parse_random(json_t *r, const char *path, param *q, rd_error *err)
{
    static const char *const keys[] = {"min", "max", "scale", NULL};
    if (!json_is_object(r))
        return spec_error(err, path, "%s must be an object {min, max, scale}", path);
    if (known_keys(r, keys, path, err) || number(r, "min", path, &q->a, err) ||
        number(r, "max", path, &q->b, err) || scale(r, path, &q->log, err))
        return err->code;
    if (q->a > q->b)
        return spec_error(err, path, "%s: min %g is above max %g", path, q->a, q->b);
    if (q->log && q->a <= 0)
        return spec_error(err, path, "%s: a log scale needs min > 0, got %g", path, q->a);
    q->kind = P_RANDOM;
    return RD_OK;
}

/* A parameter at `path` in the spec (/parameters/k, or /over without
 * random): {"path", one of values/range/random}. */
static int parse_param(json_t *v, const char *path, int random_ok, param *q, rd_error *err)
{
    static const char *const keys[] = {"path", "values", "range", "random", NULL};
    static const char *const over_keys[] = {"path", "values", "range", NULL};
    const char *forms = random_ok ? "values|range|random" : "values|range";
    char sub[80];
    if (!json_is_object(v))
        return spec_error(err, path, "%s must be an object {path, %s}", path, forms);
    if (!random_ok && json_object_get(v, "random"))
        return spec_error(err, path,
                          "%s takes \"values\" or \"range\", not \"random\": every value of "
                          "an over is run (use a random parameter with \"combine\": "
                          "\"latin_hypercube\" to sample)",
                          path);
    if (known_keys(v, random_ok ? keys : over_keys, path, err))
        return err->code;
    json_t *p = json_object_get(v, "path");
    if (!json_is_string(p) || !rd_jsonptr_valid(json_string_value(p)) ||
        json_string_value(p)[0] != '/')
        return spec_error(err, path,
                          "%s/path must be a JSON Pointer into the scene, such as "
                          "\"/ring/tangential_force\"",
                          path);
    q->path = json_string_value(p);
    json_t *values = json_object_get(v, "values"), *range = json_object_get(v, "range"),
           *random = json_object_get(v, "random");
    if ((values != NULL) + (range != NULL) + (random != NULL) != 1)
        return spec_error(err, path, "%s needs exactly one of %s", path,
                          random_ok ? "\"values\", \"range\", \"random\""
                                    : "\"values\", \"range\"");
    if (range) {
        snprintf(sub, sizeof sub, "%s/range", path);
        return parse_range(range, sub, q, err);
    }
    if (random) {
        snprintf(sub, sizeof sub, "%s/random", path);
        return parse_random(random, sub, q, err);
    }
    snprintf(sub, sizeof sub, "%s/values", path);
    if (!json_is_array(values) || json_array_size(values) == 0)
        return spec_error(err, sub, "%s must be a non-empty array of values", sub);
    q->kind = P_VALUES;
    q->values = values;
    q->n = json_array_size(values);
    return RD_OK;
}

/* outputs[k]: a pointer, or name(pointer) for an aggregate. */
static int parse_output(json_t *v, int k, output *o, rd_error *err)
{
    static const char *const names[] = {"max", "min", "mean", "count", "all"};
    static const int kinds[] = {O_MAX, O_MIN, O_MEAN, O_COUNT, O_ALL};
    char path[64];
    snprintf(path, sizeof path, "/outputs/%d", k);
    const char *t = json_string_value(v);
    o->text = t;
    o->kind = -1;
    if (t && t[0] == '/' && rd_jsonptr_valid(t)) {
        o->kind = O_POINTER;
        o->ptr = strdup(t);
    }
    for (int a = 0; t && o->kind < 0 && a < 5; a++) {
        size_t n = strlen(names[a]), len = strlen(t);
        if (strncmp(t, names[a], n) != 0 || t[n] != '(' || t[len - 1] != ')' || t[n + 1] != '/')
            continue;
        o->ptr = strndup(t + n + 1, len - n - 2);
        if (o->ptr && !rd_jsonptr_valid(o->ptr))
            break;
        o->kind = kinds[a];
    }
    if (o->kind < 0)
        return spec_error(err, path,
                          "%s must be a JSON Pointer into the result (\"/...\") or "
                          "max(P), min(P), mean(P), count(P), all(P) of one",
                          path);
    return o->ptr ? RD_OK : RD_ENOMEM;
}

/* Number of points, or an error when above `max` (a saturating product). */
static int count_points(rd_sweep *s, json_t *spec, size_t max, rd_error *err)
{
    double total = 1;
    if (s->combine == C_LHS) {
        json_t *n = json_object_get(spec, "samples");
        if (!json_is_integer(n) || json_integer_value(n) < 1)
            return spec_error(err, "/samples",
                              "/samples must be a positive integer (the "
                              "number of points of the latin_hypercube)");
        total = (double)json_integer_value(n);
    } else {
        for (int p = 0; p < s->np; p++)
            total = s->combine == C_ZIP ? (double)s->p[0].n : total * (double)s->p[p].n;
    }
    double runs = total * (double)rd_sweep_runs_per_point(s);
    if (runs > (double)max && s->over.n)
        return spec_error(err, "/over",
                          "the sweep has %.0f points x %zu over values = %.0f runs, more than the "
                          "limit of %zu runs%s",
                          total, s->over.n, runs, max,
                          max < RD_SWEEP_POINTS_MAX
                              ? "; run larger sweeps with the same binary on a cluster: "
                                "ringdyn sweep run SPEC --index I --chunks K --out DIR"
                              : "; split it into several specs");
    if (total > (double)max)
        return spec_error(err, s->combine == C_LHS ? "/samples" : "/parameters",
                          "the sweep has %.0f points, more than the limit of %zu%s", total, max,
                          max < RD_SWEEP_POINTS_MAX
                              ? "; run larger sweeps with the same binary on a cluster: "
                                "ringdyn sweep run SPEC --index I --chunks K --out DIR"
                              : "; split it into several specs");
    s->points = (size_t)total;
    size_t stride = 1;
    for (int p = s->np - 1; p >= 0; p--) {
        s->p[p].stride = stride;
        stride *= s->p[p].n ? s->p[p].n : 1;
    }
    return RD_OK;
}

/* "combine", and what each combination asks of the parameters. */
static int parse_combine(rd_sweep *s, json_t *spec, rd_error *err)
{
    json_t *c = json_object_get(spec, "combine");
    const char *name = c ? json_string_value(c) : "product";
    if (name && strcmp(name, "product") == 0)
        s->combine = C_PRODUCT;
    else if (name && strcmp(name, "zip") == 0)
        s->combine = C_ZIP;
    else if (name && strcmp(name, "latin_hypercube") == 0)
        s->combine = C_LHS;
    else
        return spec_error(err, "/combine",
                          "/combine must be \"product\", \"zip\" or \"latin_hypercube\"");
    if (s->combine != C_LHS) {
        if (json_object_get(spec, "samples") || json_object_get(spec, "seed"))
            return spec_error(err, json_object_get(spec, "samples") ? "/samples" : "/seed",
                              "samples and seed are for \"combine\": \"latin_hypercube\" only");
    }
    for (int p = 0; p < s->np; p++) {
        char path[64];
        snprintf(path, sizeof path, "/parameters/%d", p);
        if (s->combine != C_LHS && s->p[p].kind == P_RANDOM)
            return spec_error(err, path,
                              "%s is random: random parameters need \"combine\": "
                              "\"latin_hypercube\"",
                              path);
        if (s->combine == C_ZIP && s->p[p].n != s->p[0].n)
            return spec_error(err, path,
                              "zip needs parameters of one length: %s has %zu values, "
                              "/parameters/0 has %zu",
                              path, s->p[p].n, s->p[0].n);
    }
    return RD_OK;
}

/* The seed of a latin_hypercube: an integer >= 0, default 0. */
static int parse_seed(json_t *spec, uint64_t *seed, rd_error *err)
{
    json_t *v = json_object_get(spec, "seed");
    *seed = 0;
    if (!v)
        return RD_OK;
    if (!json_is_integer(v) || json_integer_value(v) < 0)
        return spec_error(err, "/seed", "/seed must be an integer >= 0");
    *seed = (uint64_t)json_integer_value(v);
    return RD_OK;
}

/* "parameters" and "outputs": non-empty arrays, no path or output twice. */
static int parse_lists(rd_sweep *s, json_t *spec, rd_error *err)
{
    json_t *params = json_object_get(spec, "parameters"), *outs = json_object_get(spec, "outputs");
    if (json_object_get(spec, "over") ? params && !json_is_array(params)
                                      : !json_is_array(params) || json_array_size(params) == 0)
        return spec_error(err, "/parameters",
                          "/parameters must be a non-empty array (with \"over\": an array, "
                          "possibly empty, or left out for one point)");
    if (json_array_size(params) > RD_SWEEP_PARAMS_MAX)
        return spec_error(err, "/parameters", "/parameters has %zu entries, more than %d",
                          json_array_size(params), RD_SWEEP_PARAMS_MAX);
    if (!json_is_array(outs) || json_array_size(outs) == 0)
        return spec_error(err, "/outputs",
                          "/outputs must be a non-empty array of JSON Pointers "
                          "into the result");
    if (json_array_size(outs) > RD_SWEEP_OUTPUTS_MAX)
        return spec_error(err, "/outputs", "/outputs has %zu entries, more than %d",
                          json_array_size(outs), RD_SWEEP_OUTPUTS_MAX);
    for (s->np = 0; s->np < (int)json_array_size(params); s->np++) {
        int p = s->np;
        char path[64];
        snprintf(path, sizeof path, "/parameters/%d", p);
        if (parse_param(json_array_get(params, (size_t)p), path, 1, &s->p[p], err))
            return err->code;
        for (int q = 0; q < p; q++)
            if (strcmp(s->p[q].path, s->p[p].path) == 0)
                return spec_error(err, "/parameters",
                                  "/parameters/%d and /parameters/%d both "
                                  "set %s",
                                  q, p, s->p[p].path);
    }
    for (s->no = 0; s->no < (int)json_array_size(outs); s->no++) {
        int k = s->no;
        int rc = parse_output(json_array_get(outs, (size_t)k), k, &s->o[k], err);
        if (rc == RD_ENOMEM)
            return rd_error_set(err, rc, "", "out of memory while reading the sweep spec");
        if (rc)
            return rc;
        for (int q = 0; q < k; q++)
            if (strcmp(s->o[q].text, s->o[k].text) == 0)
                return spec_error(err, "/outputs", "/outputs/%d repeats /outputs/%d", k, q);
    }
    return RD_OK;
}

/* A short text of a JSON value for messages. */
static void value_text(const json_t *v, char *buf, size_t size)
{
    char *t =
        json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT | JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS));
    snprintf(buf, size, "%s", t ? t : "?");
    if (t && strlen(t) >= size && size > 4)
        strcpy(buf + size - 4, "...");
    free(t);
}

/* Applies `value` (stolen) alone to the base and checks that the scene is
 * valid and reads q's path; errors point at `where` in the spec and call q
 * `what` ("parameter", "over"). */
static int try_value(const rd_sweep *s, const param *q, const char *what, json_t *value,
                     const char *where, rd_error *err)
{
    const char *path = q->path;
    char text[64];
    value_text(value, text, sizeof text);
    int oom = 0;
    json_t *scene = with_value(s->base, NULL, path, value, &oom);
    if (!scene && oom)
        return rd_error_set(err, RD_ENOMEM, "", "out of memory while checking the sweep spec");
    if (!scene)
        return spec_error(err, where,
                          "%s %s cannot be set in the base scene: a part of "
                          "the path is not an object or array element",
                          what, path);
    rd_error e;
    rd_error_init(&e);
    rd_scene *sc = NULL;
    int rc = rd_scene_parse_value(scene, &sc, &e);
    json_decref(scene);
    if (rc == RD_ENOMEM)
        return rd_error_set(err, rc, "", "out of memory while checking the sweep spec");
    if (rc != RD_OK)
        return spec_error(err, where, "%s %s = %s gives an invalid scene: %s", what, path, text,
                          e.message);
    char *echo = rd_scene_to_json(sc);
    json_t *doc = echo ? json_loads(echo, 0, NULL) : NULL, *at;
    int found = rd_jsonptr_lookup(doc, path, &at);
    const char *analysis = rd_scene_analysis(sc);
    rc = !doc || found == -2
             ? rd_error_set(err, RD_ENOMEM, "", "out of memory while checking the sweep spec")
         : found == 0 ? RD_OK
                      : spec_error(err, where, "%s %s is not a field that a %s scene reads", what,
                                   path, analysis);
    json_decref(doc);
    free(echo);
    rd_scene_free(sc);
    return rc;
}

/* Every number of a range or random parameter p is finite (and above 0 on
 * a log scale): finite endpoints can still overflow inside, when stop - start
 * (linear) or stop / start (log) is beyond a double, and those points would
 * hold +-inf or NaN, which JSON cannot carry.  RD_EINVAL (422): the spec is
 * the client's mistake.  Random parameters are checked at every sample of
 * the design, so this runs after lhs_design. */
static int check_finite(const rd_sweep *s, const param *q, int p, const char *prefix, rd_error *err)
{
    if (q->kind == P_VALUES)
        return RD_OK;
    int rnd = q->kind == P_RANDOM;
    const char *lo = rnd ? "min" : "start", *hi = rnd ? "max" : "stop";
    size_t m = rnd ? s->points : q->n, k = 0;
    double v = 0;
    for (; k < m; k++) {
        v = rnd ? at(q, s->u[(size_t)p * s->points + k]) : range_number(q, k);
        if (!isfinite(v) || (q->log && !(v > 0)))
            break;
    }
    if (k == m)
        return RD_OK;
    char where[64], head[256];
    snprintf(where, sizeof where, "%s/%s", prefix, rnd ? "random" : "range");
    snprintf(head, sizeof head, "%s (%s %s): %s %zu of %zu is %g, not a finite number%s", where,
             p < 0 ? "over" : "parameter", q->path, rnd ? "sample" : "value", k + 1, m, v,
             q->log ? " above 0" : "");
    if (q->log)
        return rd_error_set(err, RD_EINVAL, where,
                            "%s: %s / %s = %.15g / %.15g is beyond a double; a log scale needs "
                            "%s / %s from %g to %g",
                            head, hi, lo, q->b, q->a, hi, lo, DBL_MIN, DBL_MAX);
    return rd_error_set(err, RD_EINVAL, where,
                        "%s: %s - %s = %.15g - (%.15g) overflows a double; a linear scale needs "
                        "|%s - %s| <= %g",
                        head, hi, lo, q->b, q->a, hi, lo, DBL_MAX);
}

/* Every value of q that validation tries (rd_sweep.h); p its index, or -1
 * for the over; errors at `prefix` (/parameters/p or /over). */
static int check_param(const rd_sweep *s, const param *q, int p, const char *prefix, rd_error *err)
{
    const char *what = p < 0 ? "over" : "parameter";
    char where[96];
    if (check_finite(s, q, p, prefix, err))
        return err->code;
    if (q->kind == P_RANDOM) {
        snprintf(where, sizeof where, "%s/random/min", prefix);
        if (try_value(s, q, what, json_real(q->a), where, err))
            return err->code;
        snprintf(where, sizeof where, "%s/random/max", prefix);
        return try_value(s, q, what, json_real(q->b), where, err);
    }
    for (size_t k = 0; k < q->n; k++) {
        if (q->kind == P_RANGE && q->n > RANGE_CHECK_ALL && k > 0 && k < q->n - 1)
            k = q->n - 1;
        if (q->kind == P_VALUES)
            snprintf(where, sizeof where, "%s/values/%zu", prefix, k);
        else
            snprintf(where, sizeof where, "%s/range", prefix);
        if (try_value(s, q, what, rd_sweep_entry(q, k), where, err))
            return err->code;
    }
    return RD_OK;
}

/* FNV-1a 64 of the canonical spec, as 16 hex digits. */
static int spec_hash(rd_sweep *s)
{
    char *text = json_dumps(s->spec, JSON_COMPACT | JSON_SORT_KEYS | JSON_REAL_PRECISION(17));
    if (!text)
        return RD_ENOMEM;
    uint64_t h = 0xcbf29ce484222325u;
    for (const unsigned char *c = (const unsigned char *)text; *c; c++)
        h = (h ^ *c) * 0x100000001b3u;
    free(text);
    snprintf(s->hash, sizeof s->hash, "%016llx", (unsigned long long)h);
    return RD_OK;
}

/* Each output's pointer against the analysis' result schema. */
static int check_outputs(const rd_sweep *s, const char *analysis, rd_error *err)
{
    for (int k = 0; k < s->no; k++) {
        char path[32];
        snprintf(path, sizeof path, "/outputs/%d", k);
        if (rd_result_pointer_check(analysis, s->o[k].ptr, path, err))
            return err->code;
    }
    return RD_OK;
}

/* Steps after the JSON is decoded: shape, base, parameters, size, design. */
static int parse_spec(rd_sweep *s, size_t max, rd_error *err)
{
    static const char *const keys[] = {"base", "parameters", "over", "combine",     "samples",
                                       "seed", "outputs",    "name", "description", NULL};
    json_t *spec = s->spec;
    uint64_t seed;
    if (!json_is_object(spec))
        return rd_error_set(err, RD_EJSON, "", "the sweep spec must be a JSON object");
    if (known_keys(spec, keys, "", err))
        return err->code;
    s->base = json_object_get(spec, "base");
    if (!json_is_object(s->base))
        return spec_error(err, "/base",
                          "/base must be a scene object, such as "
                          "{\"analysis\": \"modal\"}");
    rd_error e;
    rd_error_init(&e);
    rd_scene *sc = NULL;
    int rc = rd_scene_parse_value(s->base, &sc, &e);
    char analysis[32] = "";
    if (rc == RD_OK)
        snprintf(analysis, sizeof analysis, "%s", rd_scene_analysis(sc));
    rd_scene_free(sc);
    if (rc != RD_OK) {
        char path[RD_ERROR_PATH_MAX + 8]; /* rd_error_set truncates to RD_ERROR_PATH_MAX */
        snprintf(path, sizeof path, "/base%s", e.path);
        return rc == RD_ENOMEM ? rd_error_set(err, rc, "", "%s", e.message)
                               : spec_error(err, path, "the base scene is invalid: %s", e.message);
    }
    json_t *over = json_object_get(spec, "over");
    if (parse_lists(s, spec, err) || check_outputs(s, analysis, err) ||
        (over && parse_param(over, "/over", 0, &s->over, err)) ||
        rd_sweep_over_check(s, spec, err) || parse_combine(s, spec, err) ||
        parse_seed(spec, &seed, err) || count_points(s, spec, max, err))
        return err->code;
    if (s->combine == C_LHS && (double)s->points * s->np > RD_SWEEP_LHS_ENTRIES_MAX)
        return spec_error(err, "/samples",
                          "a latin_hypercube of %zu samples over %d parameters "
                          "holds more than %d entries",
                          s->points, s->np, RD_SWEEP_LHS_ENTRIES_MAX);
    if ((s->combine == C_LHS && lhs_design(s, seed) != RD_OK) || spec_hash(s) != RD_OK)
        return rd_error_set(err, RD_ENOMEM, "", "out of memory while expanding the sweep");
    for (int p = 0; p < s->np; p++) {
        char at[64];
        snprintf(at, sizeof at, "/parameters/%d", p);
        if (check_param(s, &s->p[p], p, at, err))
            return err->code;
    }
    return s->over.n ? check_param(s, &s->over, -1, "/over", err) : RD_OK;
}

int rd_sweep_parse(const char *body, size_t len, size_t max_points, rd_sweep **out, rd_error *err)
{
    *out = NULL;
    if (len > RD_API_BODY_MAX)
        return rd_error_set(err, RD_ETOOLARGE, "", "the sweep spec is larger than %d bytes",
                            RD_API_BODY_MAX);
    json_error_t jerr;
    json_t *spec = json_loadb(body, len, JSON_REJECT_DUPLICATES, &jerr);
    if (!spec)
        return rd_error_set(err, RD_EJSON, "",
                            "the sweep spec is not valid JSON: %s (line %d, "
                            "column %d)",
                            jerr.text, jerr.line, jerr.column);
    rd_sweep *s = calloc(1, sizeof *s);
    if (!s) {
        json_decref(spec);
        return rd_error_set(err, RD_ENOMEM, "", "out of memory while reading the sweep spec");
    }
    s->spec = spec;
    if (parse_spec(s, max_points < RD_SWEEP_POINTS_MAX ? max_points : RD_SWEEP_POINTS_MAX, err) !=
        RD_OK) {
        rd_sweep_free(s);
        return err->code;
    }
    *out = s;
    return RD_OK;
}

void rd_sweep_free(rd_sweep *s)
{
    if (!s)
        return;
    for (int k = 0; k < RD_SWEEP_OUTPUTS_MAX; k++)
        free(s->o[k].ptr);
    free(s->u);
    json_decref(s->spec);
    free(s);
}

size_t rd_sweep_points(const rd_sweep *s)
{
    return s->points;
}

size_t rd_sweep_runs_per_point(const rd_sweep *s)
{
    return s->over.n ? s->over.n : 1;
}

const char *rd_sweep_hash(const rd_sweep *s)
{
    return s->hash;
}

char *rd_sweep_columns_json(const rd_sweep *s)
{
    json_t *cols = json_array();
    for (int p = 0; cols && p < s->np; p++)
        json_array_append_new(cols, json_string(s->p[p].path));
    for (int k = 0; cols && k < s->no; k++)
        rd_sweep_over_columns(s, &s->o[k], cols);
    json_array_append_new(cols, json_string("status"));
    json_array_append_new(cols, json_string("error"));
    size_t want = (size_t)(s->np + s->no * (s->over.n ? RD_SWEEP_OVER_COLUMNS : 1) + 2);
    char *text = json_array_size(cols) == want ? json_dumps(cols, JSON_COMPACT) : NULL;
    json_decref(cols);
    return text;
}

char *rd_sweep_point_scene(const rd_sweep *s, size_t i, rd_error *err)
{
    if (i >= s->points) {
        rd_error_set(err, RD_EINVAL, "", "point %zu does not exist: the sweep has %zu points", i,
                     s->points);
        return NULL;
    }
    json_t *scene = rd_sweep_point_json(s, i);
    char *text =
        scene ? json_dumps(scene, JSON_COMPACT | JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS)) : NULL;
    json_decref(scene);
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while expanding point %zu", i);
    return text;
}
