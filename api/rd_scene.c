/*
 * rd_scene — scene parsing: JSON body -> type-checked, defaults-filled
 * struct rd_scene, and the echo back to JSON (rd_scene.h).
 *
 * The schema is data: one table of fields per block, so the type checks,
 * the "known:" list of an unknown-field error and the set of keys an
 * analysis reads cannot drift apart.  Values and ranges are core's business
 * (rd_ring_validate, rd_modal_validate); this file checks shape and type.
 */
#include "rd_scene.h"

#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* How much of a user-supplied key or string a message quotes, bytes. */
#define QUOTE_MAX 40

enum field_type {
    F_ANALYSIS, /* "analysis": checked first, on its own (parse_analysis) */
    F_NUMBER,   /* double, any JSON number */
    F_INTEGER,  /* int: a JSON integer, or a real with an integral value */
    F_BOOL,     /* int 0/1 from JSON true/false only */
    F_STRING,   /* char *, strdup'd */
    F_CHOICE,   /* int: index of the JSON string in `choices` */
    F_BLOCK,    /* nested object with its own field table */
    F_IGNORED   /* a block this analysis does not read: not even type-checked */
};

typedef struct field {
    const char *key;
    enum field_type type;
    size_t offset;             /* into struct rd_scene (F_NUMBER..F_CHOICE) */
    const struct field *block; /* F_BLOCK: its fields, ended by a NULL key */
    const char *const *choices; /* F_CHOICE: allowed strings, NULL-ended */
    int lo, hi;                /* F_INTEGER: allowed range, quoted only when the
                                  value does not even fit an int (core checks
                                  the range of everything that does) */
} field;

#define AT(member) offsetof(struct rd_scene, member)
#define END {NULL, F_IGNORED, 0, NULL, NULL, 0, 0}

static const field material_fields[] = {
    {"youngs_modulus", F_NUMBER, AT(ring.youngs_modulus), NULL, NULL, 0, 0},
    {"poisson_ratio", F_NUMBER, AT(ring.poisson_ratio), NULL, NULL, 0, 0},
    {"density", F_NUMBER, AT(ring.density), NULL, NULL, 0, 0},
    END,
};

/* Indexed by enum rd_section_shape. */
static const char *const section_names[] = {"rectangle", "circle", NULL};

static const field ring_fields[] = {
    {"diameter", F_NUMBER, AT(ring.diameter), NULL, NULL, 0, 0},
    {"radial_width", F_NUMBER, AT(ring.radial_width), NULL, NULL, 0, 0},
    {"axial_height", F_NUMBER, AT(ring.axial_height), NULL, NULL, 0, 0},
    {"closed_gap", F_NUMBER, AT(ring.closed_gap), NULL, NULL, 0, 0},
    {"tangential_force", F_NUMBER, AT(ring.tangential_force), NULL, NULL, 0, 0},
    {"section", F_CHOICE, AT(ring.section), NULL, section_names, 0, 0},
    {"material", F_BLOCK, 0, material_fields, NULL, 0, 0},
    END,
};

static const field discretization_fields[] = {
    {"segments", F_INTEGER, AT(segments), NULL, NULL, RD_SEGMENTS_MIN, RD_SEGMENTS_MAX},
    {"closed", F_BOOL, AT(closed), NULL, NULL, 0, 0},
    END,
};

static const field modal_fields[] = {
    {"modes", F_INTEGER, AT(modal.modes), NULL, NULL, 1, RD_MODAL_MODES_MAX},
    {"error_estimate", F_BOOL, AT(modal.estimate_error), NULL, NULL, 0, 0},
    END,
};

/* Top level of a modal scene.  The blocks of the other analyses are known
 * (so they are not typos) but ignored: API.md, "a block the analysis does
 * not use is ignored". */
static const field modal_scene_fields[] = {
    {"analysis", F_ANALYSIS, 0, NULL, NULL, 0, 0},
    {"name", F_STRING, AT(name), NULL, NULL, 0, 0},
    {"description", F_STRING, AT(description), NULL, NULL, 0, 0},
    {"ring", F_BLOCK, 0, ring_fields, NULL, 0, 0},
    {"discretization", F_BLOCK, 0, discretization_fields, NULL, 0, 0},
    {"modal", F_BLOCK, 0, modal_fields, NULL, 0, 0},
    {"pretension", F_IGNORED, 0, NULL, NULL, 0, 0},
    {"bore", F_IGNORED, 0, NULL, NULL, 0, 0},
    {"engine", F_IGNORED, 0, NULL, NULL, 0, 0},
    {"groove", F_IGNORED, 0, NULL, NULL, 0, 0},
    {"physics", F_IGNORED, 0, NULL, NULL, 0, 0},
    {"output", F_IGNORED, 0, NULL, NULL, 0, 0},
    {"numerics", F_IGNORED, 0, NULL, NULL, 0, 0},
    END,
};

/* Every analysis of the contract; `fields` NULL = not available in this
 * version.  Indexed by enum rd_analysis. */
static const struct analysis_def {
    const char *name;
    const field *fields;
} analyses[] = {
    [RD_ANALYSIS_MODAL] = {"modal", modal_scene_fields},
    [RD_ANALYSIS_PRETENSION] = {"pretension", NULL},
    [RD_ANALYSIS_CONTACT] = {"contact", NULL},
    [RD_ANALYSIS_LIFT] = {"lift", NULL},
};
#define N_ANALYSES ((int)(sizeof analyses / sizeof analyses[0]))

const char *rd_scene_analysis_name(int analysis)
{
    if (analysis < 0 || analysis >= N_ANALYSES)
        return "unknown";
    return analyses[analysis].name;
}

const char *rd_scene_analysis(const rd_scene *scene)
{
    return rd_scene_analysis_name(scene->analysis);
}

/* ---- message helpers ------------------------------------------------------ */

/* Length of the longest prefix of s of at most max bytes that does not end
 * inside a UTF-8 sequence, so quoted user text stays valid UTF-8. */
static size_t utf8_prefix(const char *s, size_t max)
{
    size_t n = strlen(s);
    if (n <= max)
        return n;
    while (max > 0 && ((unsigned char)s[max] & 0xC0) == 0x80)
        max--;
    return max;
}

/* Writes `"text"` (cut to QUOTE_MAX bytes, "..." marking the cut). */
static void quote(char *buf, size_t size, const char *s)
{
    size_t n = utf8_prefix(s, QUOTE_MAX);
    snprintf(buf, size, "\"%.*s%s\"", (int)n, s, s[n] ? "..." : "");
}

/* A JSON value as a message shows it: its type and, for scalars, the value
 * ("string \"abc\"", "number 20.5", "true", "null", "an array"). */
static void describe(const json_t *v, char *buf, size_t size)
{
    char q[QUOTE_MAX + 8];
    switch (json_typeof(v)) {
    case JSON_STRING:
        quote(q, sizeof q, json_string_value(v));
        snprintf(buf, size, "string %s", q);
        break;
    case JSON_INTEGER:
        snprintf(buf, size, "number %" JSON_INTEGER_FORMAT, json_integer_value(v));
        break;
    case JSON_REAL:
        snprintf(buf, size, "number %.15g", json_real_value(v));
        break;
    case JSON_TRUE:
        snprintf(buf, size, "true");
        break;
    case JSON_FALSE:
        snprintf(buf, size, "false");
        break;
    case JSON_NULL:
        snprintf(buf, size, "null");
        break;
    case JSON_OBJECT:
        snprintf(buf, size, "an object");
        break;
    case JSON_ARRAY:
        snprintf(buf, size, "an array");
        break;
    }
}

static int type_error(rd_error *err, const char *path, const char *want, const json_t *v)
{
    char got[QUOTE_MAX + 32];
    describe(v, got, sizeof got);
    return rd_error_set(err, RD_EINVAL, path, "%s must be %s, got %s", path, want, got);
}

/* parent + "/" + key as a JSON Pointer (RFC 6901: '~' -> "~0", '/' -> "~1").
 * A path longer than the buffer is cut; it only ever labels an error. */
static void path_join(char *out, size_t size, const char *parent, const char *key)
{
    size_t n = (size_t)snprintf(out, size, "%s/", parent);
    for (; *key && n + 3 < size; key++) {
        if (*key == '~' || *key == '/') {
            out[n++] = '~';
            out[n++] = *key == '~' ? '0' : '1';
        } else {
            out[n++] = *key;
        }
    }
    if (n < size)
        out[n] = '\0';
}

/* "a, b, c": the names of a field table, or of the analyses (all, or only
 * the available ones). */
static void list_fields(char *buf, size_t size, const field *fields)
{
    size_t n = 0;
    buf[0] = '\0';
    for (const field *f = fields; f->key && n < size; f++)
        n += (size_t)snprintf(buf + n, size - n, "%s%s", f == fields ? "" : ", ", f->key);
}

static void list_analyses(char *buf, size_t size, int available_only)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; i < N_ANALYSES && n < size; i++) {
        if (available_only && !analyses[i].fields)
            continue;
        n += (size_t)snprintf(buf + n, size - n, "%s%s", n ? ", " : "", analyses[i].name);
    }
}

/* ---- parsing ------------------------------------------------------------- */

static int parse_block(json_t *obj, const field *fields, const char *path, struct rd_scene *s,
                       rd_error *err);

/* F_INTEGER: JSON integers, and reals with an integral value (20.0), since
 * many JSON writers do not distinguish the two. */
static int parse_integer(const field *f, json_t *v, const char *path, int *out, rd_error *err)
{
    double d;
    if (json_is_integer(v)) {
        d = (double)json_integer_value(v);
    } else if (json_is_real(v)) {
        d = json_real_value(v);
        if (d != floor(d))
            return rd_error_set(err, RD_EINVAL, path, "%s must be an integer, got %.15g", path, d);
    } else {
        return type_error(err, path, "an integer", v);
    }
    if (d < (double)INT_MIN || d > (double)INT_MAX)
        return rd_error_set(err, d > 0 ? RD_ELIMIT : RD_EINVAL, path,
                            "%s = %.15g is out of range (allowed: %d to %d)", path, d, f->lo,
                            f->hi);
    *out = (int)d;
    return RD_OK;
}

static int parse_field(const field *f, json_t *v, const char *path, struct rd_scene *s,
                       rd_error *err)
{
    char *at = (char *)s + f->offset;
    switch (f->type) {
    case F_NUMBER:
        if (!json_is_number(v))
            return type_error(err, path, "a number", v);
        *(double *)at = json_number_value(v);
        return RD_OK;
    case F_INTEGER:
        return parse_integer(f, v, path, (int *)at, err);
    case F_BOOL:
        if (!json_is_boolean(v))
            return type_error(err, path, "true or false", v);
        *(int *)at = json_is_true(v);
        return RD_OK;
    case F_STRING: {
        if (!json_is_string(v))
            return type_error(err, path, "a string", v);
        char **dst = (char **)at;
        free(*dst);
        *dst = strdup(json_string_value(v));
        if (!*dst)
            return rd_error_set(err, RD_ENOMEM, path, "out of memory while reading %s", path);
        return RD_OK;
    }
    case F_CHOICE: {
        char want[128];
        size_t n = (size_t)snprintf(want, sizeof want, "one of");
        for (int k = 0; f->choices[k]; k++) {
            if (json_is_string(v) && strcmp(json_string_value(v), f->choices[k]) == 0) {
                *(int *)at = k;
                return RD_OK;
            }
            if (n < sizeof want)
                n += (size_t)snprintf(want + n, sizeof want - n, "%s \"%s\"", k ? "," : "",
                                      f->choices[k]);
        }
        return type_error(err, path, want, v);
    }
    case F_BLOCK:
        if (!json_is_object(v))
            return type_error(err, path, "an object", v);
        return parse_block(v, f->block, path, s, err);
    case F_ANALYSIS:
    case F_IGNORED:
        return RD_OK;
    }
    return rd_error_set(err, RD_EINTERNAL, path, "unhandled field type for %s", path);
}

static const field *find_field(const field *fields, const char *key)
{
    for (const field *f = fields; f->key; f++)
        if (strcmp(f->key, key) == 0)
            return f;
    return NULL;
}

/* Unknown keys first (a typo is the likeliest cause of anything else that
 * looks wrong), then every known field in table order. */
static int parse_block(json_t *obj, const field *fields, const char *path, struct rd_scene *s,
                       rd_error *err)
{
    char child[RD_ERROR_PATH_MAX];
    const char *key;
    json_t *v;

    json_object_foreach(obj, key, v) {
        if (find_field(fields, key))
            continue;
        char known[256], q[QUOTE_MAX + 8];
        list_fields(known, sizeof known, fields);
        quote(q, sizeof q, key);
        path_join(child, sizeof child, path, key);
        return rd_error_set(err, RD_EINVAL, child, "unknown field %s in %s (known: %s)", q,
                            *path ? path : "the scene", known);
    }
    for (const field *f = fields; f->key; f++) {
        v = json_object_get(obj, f->key);
        if (!v)
            continue; /* absent: the default stays */
        path_join(child, sizeof child, path, f->key);
        int rc = parse_field(f, v, child, s, err);
        if (rc != RD_OK)
            return rc;
    }
    return RD_OK;
}

/* "analysis" decides which keys are known, so it is checked before them. */
static int parse_analysis(json_t *root, int *out, rd_error *err)
{
    char all[128], available[128], q[QUOTE_MAX + 8];
    list_analyses(all, sizeof all, 0);
    list_analyses(available, sizeof available, 1);

    json_t *v = json_object_get(root, "analysis");
    if (!v)
        return rd_error_set(err, RD_EINVAL, "/analysis",
                            "the scene must say which analysis to run: \"analysis\" is missing "
                            "(available: %s)",
                            available);
    if (!json_is_string(v))
        return type_error(err, "/analysis", "a string", v);

    const char *name = json_string_value(v);
    for (int i = 0; i < N_ANALYSES; i++) {
        if (strcmp(name, analyses[i].name) != 0)
            continue;
        if (!analyses[i].fields)
            return rd_error_set(err, RD_EINVAL, "/analysis",
                                "analysis \"%s\" is not available in this version (available: %s)",
                                analyses[i].name, available);
        *out = i;
        return RD_OK;
    }
    quote(q, sizeof q, name);
    return rd_error_set(err, RD_EINVAL, "/analysis",
                        "unknown analysis %s (allowed: %s; available in this version: %s)", q, all,
                        available);
}

int rd_scene_parse_value(struct json_t *root, rd_scene **out, rd_error *err)
{
    rd_scene *s = NULL;
    int rc;

    *out = NULL;
    if (!json_is_object(root)) {
        char got[QUOTE_MAX + 32];
        describe(root, got, sizeof got);
        rc = rd_error_set(err, RD_EJSON, "", "the scene must be a JSON object, got %s", got);
        goto out;
    }
    s = calloc(1, sizeof *s);
    if (!s) {
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while reading the scene");
        goto out;
    }
    /* Defaults: the thesis ring, cut as the thesis recommends (3.3). */
    rd_ring_params_default(&s->ring);
    s->segments = RD_SCENE_DEFAULT_SEGMENTS;
    s->closed = 0;
    rd_modal_opts_default(&s->modal);
    s->modal.estimate_error = 1; /* API default, whatever core's is */

    rc = parse_analysis(root, &s->analysis, err);
    if (rc != RD_OK)
        goto out;
    rc = parse_block(root, analyses[s->analysis].fields, "", s, err);
    if (rc != RD_OK)
        goto out;

    /* Values and ranges: core's validators, messages passed on unchanged. */
    rc = rd_ring_validate(&s->ring, s->segments, s->closed, err);
    if (rc != RD_OK)
        goto out;
    if (s->analysis == RD_ANALYSIS_MODAL) {
        rc = rd_modal_validate(&s->modal, s->segments, err);
        if (rc != RD_OK)
            goto out;
    }
    *out = s;
    s = NULL;
out:
    rd_scene_free(s);
    return rc;
}

int rd_scene_parse(const char *body, size_t len, rd_scene **out, rd_error *err)
{
    json_error_t jerr;
    json_t *root = NULL;
    int rc;

    *out = NULL;
    if (len > RD_API_BODY_MAX) {
        rc = rd_error_set(err, RD_ETOOLARGE, "",
                          "the scene is %zu bytes, more than the limit of %d bytes", len,
                          RD_API_BODY_MAX);
        goto out;
    }
    /* DECODE_ANY so that a scalar body gets the same "must be a JSON object"
     * answer as an array; duplicate keys are rejected because which one
     * would win is not obvious to whoever wrote them. */
    root = json_loadb(body ? body : "", body ? len : 0, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY,
                      &jerr);
    if (!root) {
        rc = rd_error_set(err, RD_EJSON, "", "the body is not valid JSON: %s (line %d, column %d)",
                          jerr.text, jerr.line, jerr.column);
        goto out;
    }
    rc = rd_scene_parse_value(root, out, err);
out:
    json_decref(root);
    return rc;
}

void rd_scene_free(rd_scene *scene)
{
    if (!scene)
        return;
    free(scene->name);
    free(scene->description);
    free(scene);
}

/* ---- echo ---------------------------------------------------------------- */

json_t *rd_scene_echo(const rd_scene *s)
{
    const rd_ring_params *r = &s->ring;
    const int n_sections = (int)(sizeof section_names / sizeof section_names[0]) - 1;
    const char *section = r->section >= 0 && r->section < n_sections ? section_names[r->section]
                                                                    : "unknown";
    /* Key order is the order of the schema.  Only the modal blocks exist so
     * far; another analysis adds its own blocks here. */
    return json_pack("{s:s, s:s*, s:s*,"
                     " s:{s:f, s:f, s:f, s:f, s:f, s:s, s:{s:f, s:f, s:f}},"
                     " s:{s:i, s:b}, s:{s:i, s:b}}",
                     "analysis", rd_scene_analysis(s),
                     "name", s->name,
                     "description", s->description,
                     "ring",
                         "diameter", r->diameter,
                         "radial_width", r->radial_width,
                         "axial_height", r->axial_height,
                         "closed_gap", r->closed_gap,
                         "tangential_force", r->tangential_force,
                         "section", section,
                         "material",
                             "youngs_modulus", r->youngs_modulus,
                             "poisson_ratio", r->poisson_ratio,
                             "density", r->density,
                     "discretization",
                         "segments", s->segments,
                         "closed", s->closed,
                     "modal",
                         "modes", s->modal.modes,
                         "error_estimate", s->modal.estimate_error);
}

char *rd_scene_to_json(const rd_scene *scene)
{
    json_t *echo = rd_scene_echo(scene);
    size_t flags = JSON_COMPACT | JSON_REAL_PRECISION(RD_SCENE_REAL_DIGITS);
    char *text = echo ? json_dumps(echo, flags) : NULL;
    json_decref(echo);
    return text;
}
