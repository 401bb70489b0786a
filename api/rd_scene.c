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
    F_OPTBLOCK, /* F_BLOCK whose presence sets the int at `offset` to 1 */
    F_TABLE,    /* struct rd_table: an array of numbers, malloc'd */
    F_DISTORTION, /* /bore/distortion: an array of {order, amplitude, phase_deg} */
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

/* ---- pretension and contact ---- */
static const char *const method_names[] = {"force", "field", NULL}; /* enum rd_pretension_method */

static const field pretension_fields[] = {
    {"method", F_CHOICE, AT(pretension.method), NULL, method_names, 0, 0},
    {"lateral_force", F_NUMBER, AT(pretension.lateral_force), NULL, NULL, 0, 0},
    END,
};

static const field bore_fields[] = {
    {"diameter", F_NUMBER, AT(contact.bore_diameter), NULL, NULL, 0, 0},
    {"distortion", F_DISTORTION, AT(contact), NULL, NULL, 0, 0},
    END,
};

static const field contact_fields[] = {
    {"points_per_segment", F_INTEGER, AT(contact.points_per_segment), NULL, NULL, 1,
     RD_CONTACT_POINTS_MAX},
    {"stiffness", F_NUMBER, AT(contact.stiffness), NULL, NULL, 0, 0},
    {"max_segments", F_INTEGER, AT(contact.max_segments), NULL, NULL, 4, RD_STATIC_SEGMENTS_MAX},
    END,
};

static const field static_numerics_fields[] = {
    {"tolerance", F_NUMBER, AT(statics.tol), NULL, NULL, 0, 0},
    {"max_iterations", F_INTEGER, AT(statics.max_iterations), NULL, NULL, 1, 100000},
    {"error_estimate", F_BOOL, AT(statics.estimate_error), NULL, NULL, 0, 0},
    END,
};

/* ---- lift ---- */
static const char *const kinematics_names[] = {"exact", "approximate", NULL}; /* enum rd_kinematics */
static const char *const friction_names[] = {"coulomb", "stribeck", NULL};   /* model - 1 */
static const char *const area_names[] = {"fixed", "dynamic", NULL};          /* enum rd_gas_area */

static const field engine_fields[] = {
    {"speed_rpm", F_NUMBER, AT(lift.engine.speed_rpm), NULL, NULL, 0, 0},
    {"crank_radius", F_NUMBER, AT(lift.engine.crank_radius), NULL, NULL, 0, 0},
    {"rod_length", F_NUMBER, AT(lift.engine.rod_length), NULL, NULL, 0, 0},
    {"kinematics", F_CHOICE, AT(lift.engine.kinematics), NULL, kinematics_names, 0, 0},
    {"cycles", F_NUMBER, AT(lift.engine.cycles), NULL, NULL, 0, 0},
    END,
};

static const field groove_fields[] = {
    {"axial_clearance", F_NUMBER, AT(lift.groove.axial_clearance), NULL, NULL, 0, 0},
    {"radial_clearance", F_NUMBER, AT(lift.groove.radial_clearance), NULL, NULL, 0, 0},
    END,
};

static const field friction_fields[] = {
    {"model", F_CHOICE, AT(friction_model), NULL, friction_names, 0, 0},
    {"coefficient", F_NUMBER, AT(lift.friction.coefficient), NULL, NULL, 0, 0},
    {"viscosity", F_NUMBER, AT(lift.friction.viscosity), NULL, NULL, 0, 0},
    {"sommerfeld_transition", F_NUMBER, AT(lift.friction.sommerfeld_transition), NULL, NULL, 0, 0},
    {"hydrodynamic_slope", F_NUMBER, AT(lift.friction.hydrodynamic_slope), NULL, NULL, 0, 0},
    END,
};

static const field gas_fields[] = {
    {"crank_deg", F_TABLE, AT(gas_table[0]), NULL, NULL, 0, 0},
    {"above", F_TABLE, AT(gas_table[1]), NULL, NULL, 0, 0},
    {"behind", F_TABLE, AT(gas_table[2]), NULL, NULL, 0, 0},
    {"below", F_TABLE, AT(gas_table[3]), NULL, NULL, 0, 0},
    {"active_area", F_CHOICE, AT(lift.gas.active_area), NULL, area_names, 0, 0},
    END,
};

static const field physics_fields[] = {
    {"gravity", F_BOOL, AT(lift.gravity), NULL, NULL, 0, 0},
    {"friction", F_OPTBLOCK, AT(friction_given), friction_fields, NULL, 0, 0},
    {"gas", F_OPTBLOCK, AT(gas_given), gas_fields, NULL, 0, 0},
    END,
};

static const field lift_contact_fields[] = {
    {"stiffness", F_NUMBER, AT(lift.contact_stiffness), NULL, NULL, 0, 0},
    END,
};

static const field output_fields[] = {
    {"step_deg", F_NUMBER, AT(lift.step_deg), NULL, NULL, 0, 0},
    END,
};

static const field lift_numerics_fields[] = {
    {"rtol", F_NUMBER, AT(lift.rtol), NULL, NULL, 0, 0},
    {"atol", F_NUMBER, AT(lift.atol), NULL, NULL, 0, 0},
    {"max_steps", F_INTEGER, AT(max_steps), NULL, NULL, 100, 1000000000},
    {"error_estimate", F_BOOL, AT(lift.estimate_error), NULL, NULL, 0, 0},
    END,
};

#define COMMON_FIELDS                                                                             \
    {"analysis", F_ANALYSIS, 0, NULL, NULL, 0, 0},                                                \
        {"name", F_STRING, AT(name), NULL, NULL, 0, 0},                                           \
        {"description", F_STRING, AT(description), NULL, NULL, 0, 0},                             \
        {"ring", F_BLOCK, 0, ring_fields, NULL, 0, 0},                                            \
        {"discretization", F_BLOCK, 0, discretization_fields, NULL, 0, 0}
#define IGNORED(key) {key, F_IGNORED, 0, NULL, NULL, 0, 0}

static const field pretension_scene_fields[] = {
    COMMON_FIELDS,
    {"pretension", F_BLOCK, 0, pretension_fields, NULL, 0, 0},
    {"numerics", F_BLOCK, 0, static_numerics_fields, NULL, 0, 0},
    IGNORED("modal"), IGNORED("bore"), IGNORED("contact"), IGNORED("engine"), IGNORED("groove"),
    IGNORED("physics"), IGNORED("output"),
    END,
};

static const field contact_numerics_fields[] = {
    {"tolerance", F_NUMBER, AT(statics.tol), NULL, NULL, 0, 0},
    {"max_iterations", F_INTEGER, AT(statics.max_iterations), NULL, NULL, 1, 100000},
    {"error_estimate", F_BOOL, AT(statics.estimate_error), NULL, NULL, 0, 0},
    {"accuracy", F_NUMBER, AT(contact.accuracy), NULL, NULL, 0, 0},
    END,
};

static const field contact_scene_fields[] = {
    COMMON_FIELDS,
    {"bore", F_BLOCK, 0, bore_fields, NULL, 0, 0},
    {"contact", F_BLOCK, 0, contact_fields, NULL, 0, 0},
    {"numerics", F_BLOCK, 0, contact_numerics_fields, NULL, 0, 0},
    IGNORED("modal"), IGNORED("pretension"), IGNORED("engine"), IGNORED("groove"),
    IGNORED("physics"), IGNORED("output"),
    END,
};

static const field lift_scene_fields[] = {
    COMMON_FIELDS,
    {"engine", F_BLOCK, 0, engine_fields, NULL, 0, 0},
    {"groove", F_BLOCK, 0, groove_fields, NULL, 0, 0},
    {"physics", F_BLOCK, 0, physics_fields, NULL, 0, 0},
    {"contact", F_BLOCK, 0, lift_contact_fields, NULL, 0, 0},
    {"output", F_BLOCK, 0, output_fields, NULL, 0, 0},
    {"numerics", F_BLOCK, 0, lift_numerics_fields, NULL, 0, 0},
    IGNORED("modal"), IGNORED("pretension"), IGNORED("bore"),
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
    {"contact", F_IGNORED, 0, NULL, NULL, 0, 0},
    END,
};

/* Every analysis of the contract; `fields` NULL = not available in this
 * version.  Indexed by enum rd_analysis. */
static const struct analysis_def {
    const char *name;
    const field *fields;
} analyses[] = {
    [RD_ANALYSIS_MODAL] = {"modal", modal_scene_fields},
    [RD_ANALYSIS_PRETENSION] = {"pretension", pretension_scene_fields},
    [RD_ANALYSIS_CONTACT] = {"contact", contact_scene_fields},
    [RD_ANALYSIS_LIFT] = {"lift", lift_scene_fields},
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

/* F_TABLE: a non-empty array of numbers, at most RD_LIFT_TABLE_MAX long. */
static int parse_table(json_t *v, const char *path, struct rd_table *t, rd_error *err)
{
    size_t i;
    json_t *x;
    if (!json_is_array(v))
        return type_error(err, path, "an array of numbers", v);
    size_t n = json_array_size(v);
    if (n == 0 || n > RD_LIFT_TABLE_MAX)
        return rd_error_set(err, n ? RD_ELIMIT : RD_EINVAL, path,
                            "%s has %zu values; allowed 2 to %d.", path, n, RD_LIFT_TABLE_MAX);
    free(t->v);
    t->n = 0;
    t->v = malloc(n * sizeof *t->v);
    if (!t->v)
        return rd_error_set(err, RD_ENOMEM, path, "out of memory while reading %s", path);
    json_array_foreach(v, i, x) {
        if (!json_is_number(x)) {
            char item[RD_ERROR_PATH_MAX + 24];
            snprintf(item, sizeof item, "%s/%zu", path, i);
            return type_error(err, item, "a number", x);
        }
        t->v[i] = json_number_value(x);
    }
    t->n = (int)n;
    return RD_OK;
}

/* F_DISTORTION: [{"order": k, "amplitude": A, "phase_deg": phi}, ...]. */
static int parse_distortion(json_t *v, const char *path, rd_contact_opts *c, rd_error *err)
{
    static const char *const keys[] = {"order", "amplitude", "phase_deg"};
    size_t i;
    json_t *item;
    if (!json_is_array(v))
        return type_error(err, path, "an array of {order, amplitude, phase_deg}", v);
    if (json_array_size(v) > RD_DISTORTION_MAX)
        return rd_error_set(err, RD_ELIMIT, path, "%s has %zu entries; at most %d are allowed.",
                            path, json_array_size(v), RD_DISTORTION_MAX);
    c->n_distortion = 0;
    json_array_foreach(v, i, item) {
        char at[RD_ERROR_PATH_MAX + 24], child[RD_ERROR_PATH_MAX + 48];
        snprintf(at, sizeof at, "%s/%zu", path, i);
        if (!json_is_object(item))
            return type_error(err, at, "an object {order, amplitude, phase_deg}", item);
        const char *key;
        json_t *x;
        json_object_foreach(item, key, x) {
            int known = 0;
            for (int k = 0; k < 3; k++)
                known |= strcmp(key, keys[k]) == 0;
            if (!known) {
                char q[QUOTE_MAX + 8];
                quote(q, sizeof q, key);
                path_join(child, sizeof child, at, key);
                return rd_error_set(err, RD_EINVAL, child,
                                    "unknown field %s in %s (known: order, amplitude, phase_deg)",
                                    q, at);
            }
        }
        rd_distortion *d = &c->distortion[i];
        d->order = 0;
        d->amplitude = 0.0;
        d->phase_deg = 0.0;
        json_t *order = json_object_get(item, "order"), *amp = json_object_get(item, "amplitude"),
               *phase = json_object_get(item, "phase_deg");
        path_join(child, sizeof child, at, "order");
        if (!order)
            return rd_error_set(err, RD_EINVAL, child, "%s is missing: each distortion needs its "
                                "Fourier order (1 to 64)", child);
        if (!json_is_integer(order))
            return type_error(err, child, "an integer", order);
        json_int_t k = json_integer_value(order);
        d->order = k < -1000 ? -1000 : k > 1000 ? 1000 : (int)k;
        path_join(child, sizeof child, at, "amplitude");
        if (!amp)
            return rd_error_set(err, RD_EINVAL, child, "%s is missing: each distortion needs its "
                                "amplitude (m)", child);
        if (!json_is_number(amp))
            return type_error(err, child, "a number", amp);
        d->amplitude = json_number_value(amp);
        if (phase) {
            path_join(child, sizeof child, at, "phase_deg");
            if (!json_is_number(phase))
                return type_error(err, child, "a number", phase);
            d->phase_deg = json_number_value(phase);
        }
        c->n_distortion = (int)i + 1;
    }
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
    case F_OPTBLOCK:
        *(int *)at = 1;
        /* fall through */
    case F_BLOCK:
        if (!json_is_object(v))
            return type_error(err, path, "an object", v);
        return parse_block(v, f->block, path, s, err);
    case F_TABLE:
        return parse_table(v, path, (struct rd_table *)at, err);
    case F_DISTORTION:
        return parse_distortion(v, path, (rd_contact_opts *)at, err);
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

/* Lift: the optional physics the scene named, the gas tables (four of the
 * same length), then core's checks. */
static int lift_finish(struct rd_scene *s, rd_error *err)
{
    static const char *const names[] = {"crank_deg", "above", "behind", "below"};
    rd_lift_params *l = &s->lift;
    if (s->closed)
        return rd_error_set(err, RD_EINVAL, "/discretization/closed",
                            "/discretization/closed = true joins the gap, but the lift analysis "
                            "models the split ring in its groove: use closed = false.");
    l->friction.model = s->friction_given ? s->friction_model + 1 : RD_FRICTION_NONE;
    l->max_steps = s->max_steps;
    l->gas.points = 0;
    if (s->gas_given) {
        for (int k = 0; k < 4; k++) {
            char path[64];
            snprintf(path, sizeof path, "/physics/gas/%s", names[k]);
            if (!s->gas_table[k].v)
                return rd_error_set(err, RD_EINVAL, path,
                                    "%s is missing: a gas block needs crank_deg, above, behind "
                                    "and below, all of the same length (use zeros for a face "
                                    "without pressure).",
                                    path);
            if (s->gas_table[k].n != s->gas_table[0].n)
                return rd_error_set(err, RD_EINVAL, path,
                                    "%s has %d values but /physics/gas/crank_deg has %d; all "
                                    "four tables must have the same length.",
                                    path, s->gas_table[k].n, s->gas_table[0].n);
        }
        l->gas.points = s->gas_table[0].n;
        l->gas.crank_deg = s->gas_table[0].v;
        l->gas.above = s->gas_table[1].v;
        l->gas.behind = s->gas_table[2].v;
        l->gas.below = s->gas_table[3].v;
    }
    return rd_lift_validate(l, &s->ring, s->segments, err);
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
    rd_static_opts_default(&s->statics);
    s->statics.estimate_error = 1;
    rd_pretension_opts_default(&s->pretension);
    rd_contact_opts_default(&s->contact);
    rd_lift_params_default(&s->lift);
    s->max_steps = (int)s->lift.max_steps;

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
    switch (s->analysis) {
    case RD_ANALYSIS_MODAL:
        rc = rd_modal_validate(&s->modal, s->segments, err);
        break;
    case RD_ANALYSIS_PRETENSION:
        if ((rc = rd_static_validate(&s->statics, s->segments, s->closed, err)) == RD_OK)
            rc = rd_pretension_validate(&s->pretension, &s->ring, err);
        break;
    case RD_ANALYSIS_CONTACT:
        if ((rc = rd_static_validate(&s->statics, s->segments, s->closed, err)) == RD_OK)
            rc = rd_contact_validate(&s->contact, &s->ring, err);
        break;
    case RD_ANALYSIS_LIFT:
        rc = lift_finish(s, err);
        break;
    }
    if (rc != RD_OK)
        goto out;
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
    for (int k = 0; k < 4; k++)
        free(scene->gas_table[k].v);
    free(scene);
}

/* ---- echo ---------------------------------------------------------------- */

/* A real or null (non-finite values never reach here after validation, but
 * jansson refuses them, so be safe). */
static json_t *real(double x)
{
    return isfinite(x) ? json_real(x) : json_null();
}

static json_t *table_echo(const struct rd_table *t)
{
    json_t *a = json_array();
    for (int i = 0; a && i < t->n; i++)
        if (json_array_append_new(a, real(t->v[i])) != 0) {
            json_decref(a);
            return NULL;
        }
    return a;
}

static json_t *distortion_echo(const rd_contact_opts *c)
{
    json_t *a = json_array();
    for (int i = 0; a && i < c->n_distortion; i++) {
        const rd_distortion *d = &c->distortion[i];
        if (json_array_append_new(a, json_pack("{s:i, s:o, s:o}", "order", d->order, "amplitude",
                                               real(d->amplitude), "phase_deg",
                                               real(d->phase_deg))) != 0) {
            json_decref(a);
            return NULL;
        }
    }
    return a;
}

static json_t *static_numerics_echo(const rd_scene *s)
{
    return json_pack("{s:o, s:i, s:b}", "tolerance", real(s->statics.tol), "max_iterations",
                     s->statics.max_iterations, "error_estimate", s->statics.estimate_error);
}

/* The blocks only one analysis reads; NULL on out of memory. */
static int echo_analysis_blocks(const rd_scene *s, json_t *o)
{
    int bad = 0;
    const rd_lift_params *l = &s->lift;
    switch (s->analysis) {
    case RD_ANALYSIS_MODAL:
        bad |= json_object_set_new(o, "modal", json_pack("{s:i, s:b}", "modes", s->modal.modes,
                                                         "error_estimate",
                                                         s->modal.estimate_error));
        break;
    case RD_ANALYSIS_PRETENSION:
        bad |= json_object_set_new(o, "pretension",
                                   json_pack("{s:s, s:o}", "method",
                                             method_names[s->pretension.method], "lateral_force",
                                             real(s->pretension.lateral_force)));
        bad |= json_object_set_new(o, "numerics", static_numerics_echo(s));
        break;
    case RD_ANALYSIS_CONTACT:
        bad |= json_object_set_new(
            o, "bore",
            json_pack("{s:o, s:o}", "diameter",
                      real(s->contact.bore_diameter > 0 ? s->contact.bore_diameter
                                                        : s->ring.diameter),
                      "distortion", distortion_echo(&s->contact)));
        bad |= json_object_set_new(
            o, "contact",
            json_pack("{s:i, s:o, s:i}", "points_per_segment", s->contact.points_per_segment,
                      "stiffness",
                      real(s->contact.stiffness > 0 ? s->contact.stiffness
                                                    : rd_contact_default_stiffness(&s->ring)),
                      "max_segments", s->contact.max_segments));
        json_t *num = static_numerics_echo(s);
        bad |= !num || json_object_set_new(num, "accuracy", real(s->contact.accuracy));
        bad |= json_object_set_new(o, "numerics", num);
        break;
    case RD_ANALYSIS_LIFT: {
        json_t *physics = json_pack("{s:b}", "gravity", l->gravity);
        if (physics && s->friction_given)
            bad |= json_object_set_new(
                physics, "friction",
                json_pack("{s:s, s:o, s:o, s:o, s:o}", "model", friction_names[s->friction_model],
                          "coefficient", real(l->friction.coefficient), "viscosity",
                          real(l->friction.viscosity), "sommerfeld_transition",
                          real(l->friction.sommerfeld_transition), "hydrodynamic_slope",
                          real(l->friction.hydrodynamic_slope)));
        if (physics && s->gas_given)
            bad |= json_object_set_new(
                physics, "gas",
                json_pack("{s:o, s:o, s:o, s:o, s:s}", "crank_deg", table_echo(&s->gas_table[0]),
                          "above", table_echo(&s->gas_table[1]), "behind",
                          table_echo(&s->gas_table[2]), "below", table_echo(&s->gas_table[3]),
                          "active_area", area_names[l->gas.active_area]));
        bad |= json_object_set_new(
            o, "engine",
            json_pack("{s:o, s:o, s:o, s:s, s:o}", "speed_rpm", real(l->engine.speed_rpm),
                      "crank_radius", real(l->engine.crank_radius), "rod_length",
                      real(l->engine.rod_length), "kinematics",
                      kinematics_names[l->engine.kinematics], "cycles", real(l->engine.cycles)));
        bad |= json_object_set_new(o, "groove",
                                   json_pack("{s:o, s:o}", "axial_clearance",
                                             real(l->groove.axial_clearance), "radial_clearance",
                                             real(l->groove.radial_clearance)));
        bad |= json_object_set_new(o, "physics", physics);
        bad |= json_object_set_new(
            o, "contact",
            json_pack("{s:o}", "stiffness",
                      real(l->contact_stiffness > 0
                               ? l->contact_stiffness
                               : rd_lift_contact_stiffness_default(&s->ring, l))));
        bad |= json_object_set_new(o, "output", json_pack("{s:o}", "step_deg", real(l->step_deg)));
        bad |= json_object_set_new(o, "numerics",
                                   json_pack("{s:o, s:o, s:I, s:b}", "rtol", real(l->rtol), "atol",
                                             real(l->atol), "max_steps", (json_int_t)l->max_steps,
                                             "error_estimate", l->estimate_error));
        break;
    }
    }
    return bad ? -1 : 0;
}

json_t *rd_scene_echo(const rd_scene *s)
{
    const rd_ring_params *r = &s->ring;
    const int n_sections = (int)(sizeof section_names / sizeof section_names[0]) - 1;
    const char *section = r->section >= 0 && r->section < n_sections ? section_names[r->section]
                                                                    : "unknown";
    /* Key order is the order of the schema. */
    json_t *o = json_pack("{s:s, s:s*, s:s*,"
                          " s:{s:f, s:f, s:f, s:f, s:f, s:s, s:{s:f, s:f, s:f}},"
                          " s:{s:i, s:b}}",
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
                              "closed", s->closed);
    if (o && echo_analysis_blocks(s, o) != 0) {
        json_decref(o);
        o = NULL;
    }
    return o;
}

char *rd_scene_to_json(const rd_scene *scene)
{
    json_t *echo = rd_scene_echo(scene);
    size_t flags = JSON_COMPACT | JSON_REAL_PRECISION(RD_SCENE_REAL_DIGITS);
    char *text = echo ? json_dumps(echo, flags) : NULL;
    json_decref(echo);
    return text;
}
