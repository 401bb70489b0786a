/*
 * rd_schema_write — what the field tables write (rd_schema.h): the echo of
 * a parsed scene (every field, defaults filled) and the OpenAPI schema of a
 * block (types, defaults read from a defaults-filled scene, ranges, enums,
 * descriptions).  Parsing by the same tables is rd_schema.c's.
 *
 * A field's value lives at base + offset, where base is the scene, the
 * analysis' opts (rd_block.in_opts) or one array item (rd_block.items).
 */
#include <jansson.h>
#include <stdio.h>

#include "rd_json.h"
#include "rd_scene.h"
#include "rd_schema.h"
#include "rd_static.h"

static const char *cbase_of(const rd_block *block, const struct rd_scene *s)
{
    return block->in_opts ? (const char *)s->opts : (const char *)s;
}

/* ---- echo ---------------------------------------------------------------- */

/* json_object_set_new that also fails on a NULL value (out of memory);
 * the value is released either way. */
static int set_new(json_t *o, const char *key, json_t *v)
{
    if (!v)
        return -1;
    return json_object_set_new(o, key, v);
}

static json_t *table_echo(const struct rd_table *t)
{
    json_t *a = json_array();
    for (int i = 0; a && i < t->n; i++)
        if (json_array_append_new(a, rd_result_real(t->v[i])) != 0) {
            json_decref(a);
            a = NULL;
        }
    return a;
}

static json_t *distortion_echo(const rd_bore *c)
{
    json_t *a = json_array();
    for (int i = 0; a && i < c->n_distortion; i++) {
        const rd_distortion *d = &c->distortion[i];
        if (json_array_append_new(a, json_pack("{s:i, s:o, s:o}", "order", d->order, "amplitude",
                                               rd_result_real(d->amplitude), "phase_deg",
                                               rd_result_real(d->phase_deg))) != 0) {
            json_decref(a);
            a = NULL;
        }
    }
    return a;
}

static json_t *choice_echo(const rd_field *f, int k)
{
    int n = 0;
    while (f->choices[n])
        n++;
    return json_string(k >= 0 && k < n ? f->choices[k] : "unknown");
}

/* The echo of one field; *skip set when it is not echoed at all. */
static json_t *field_echo(const rd_field *f, const char *at, const struct rd_scene *s, int *skip)
{
    *skip = 0;
    if (f->type == RD_F_CUSTOM) { /* JSON null: not echoed */
        json_t *v = f->echo(s);
        *skip = json_is_null(v);
        if (*skip)
            json_decref(v);
        return *skip ? NULL : v;
    }
    if (f->echo)
        return f->echo(s);
    switch (f->type) {
    case RD_F_ANALYSIS: /* echoed by its hook */
        break;
    case RD_F_NUMBER:
        if (f->word && *(const double *)at == 0.0)
            return json_string(f->word);
        return rd_result_real(*(const double *)at);
    case RD_F_INTEGER:
        return json_integer(*(const int *)at);
    case RD_F_BOOL:
        return json_boolean(*(const int *)at);
    case RD_F_STRING:
        *skip = *(char *const *)at == NULL;
        return *skip ? NULL : json_string(*(char *const *)at);
    case RD_F_CHOICE:
        return choice_echo(f, *(const int *)at);
    case RD_F_OPTBLOCK:
        *skip = !*(const int *)at;
        if (*skip)
            return NULL;
        /* fall through */
    case RD_F_BLOCK: {
        json_t *o = json_object();
        if (o && rd_schema_echo(f->block, s, o) != 0) {
            json_decref(o);
            o = NULL;
        }
        return o;
    }
    case RD_F_TABLE: /* one that was not given (valid ones have items) is not echoed */
        *skip = ((const struct rd_table *)at)->n == 0;
        return *skip ? NULL : table_echo((const struct rd_table *)at);
    case RD_F_DISTORTION:
        return distortion_echo((const rd_bore *)at);
    case RD_F_ITEMS: /* echoed by its hook */
    case RD_F_CUSTOM:
        break;
    }
    return NULL;
}

int rd_schema_echo(const rd_block *block, const struct rd_scene *s, json_t *out)
{
    const char *base = cbase_of(block, s);
    for (const rd_field *f = block->fields; f->key; f++) {
        int skip;
        const char *at = f->in_opts ? (const char *)s->opts : f->in_scene ? (const char *)s : base;
        json_t *v = field_echo(f, at + f->offset, s, &skip);
        if (!skip && set_new(out, f->key, v) != 0)
            return -1;
    }
    return 0;
}

/* ---- OpenAPI ------------------------------------------------------------- */

static int add_bounds(json_t *o, const rd_field *f, int count)
{
    int bad = 0;
    const char *lo = count ? "minItems" : "minimum", *hi = count ? "maxItems" : "maximum";
    if (f->has_min)
        bad |= set_new(o, lo,
                       count || f->type == RD_F_INTEGER ? json_integer((json_int_t)f->min)
                                                        : json_real(f->min));
    if (f->has_min == RD_BOUND_EX)
        bad |= set_new(o, "exclusiveMinimum", json_true());
    if (f->has_max)
        bad |= set_new(o, hi,
                       count || f->type == RD_F_INTEGER ? json_integer((json_int_t)f->max)
                                                        : json_real(f->max));
    if (f->has_max == RD_BOUND_EX)
        bad |= set_new(o, "exclusiveMaximum", json_true());
    return bad;
}

static json_t *choices_array(const rd_field *f)
{
    json_t *a = json_array();
    for (int k = 0; a && f->choices[k]; k++)
        if (json_array_append_new(a, json_string(f->choices[k])) != 0) {
            json_decref(a);
            a = NULL;
        }
    return a;
}

/* "default": the value a defaults-filled scene holds (`at`), for the
 * scalar types; required fields and tables have none. */
static int add_default(json_t *o, const rd_field *f, const char *at)
{
    if (f->required)
        return 0;
    switch (f->type) {
    case RD_F_NUMBER:
        return set_new(o, "default", json_real(*(const double *)at));
    case RD_F_INTEGER:
        return set_new(o, "default", json_integer(*(const int *)at));
    case RD_F_BOOL:
        return set_new(o, "default", json_boolean(*(const int *)at));
    case RD_F_CHOICE:
        return set_new(o, "default", choice_echo(f, *(const int *)at));
    case RD_F_DISTORTION:
        return set_new(o, "default", json_array());
    default:
        return 0;
    }
}

static const char *type_name(enum rd_field_type t)
{
    switch (t) {
    case RD_F_NUMBER:
        return "number";
    case RD_F_INTEGER:
        return "integer";
    case RD_F_BOOL:
        return "boolean";
    case RD_F_TABLE:
    case RD_F_DISTORTION:
    case RD_F_ITEMS:
    case RD_F_CUSTOM: /* with a block; without one, `extra` is the schema */
        return "array";
    default:
        return "string";
    }
}

/* {"$ref": ...} to a named block (adding its component once), or the
 * block inline; with `extra`, both combined under the field's description. */
static json_t *block_ref(const rd_field *f, const struct rd_scene *defaults, json_t *components)
{
    const rd_block *b = f->block;
    if (!b->name)
        return rd_schema_block_openapi(b, defaults, components);
    if (!json_object_get(components, b->name) &&
        set_new(components, b->name, rd_schema_block_openapi(b, defaults, components)) != 0)
        return NULL;
    char ref[128];
    snprintf(ref, sizeof ref, "#/components/schemas/%s", b->name);
    if (!f->extra)
        return json_pack("{s:s}", "$ref", ref);
    return json_pack("{s:s, s:[{s:s}, o]}", "description", f->desc ? f->desc : "", "allOf", "$ref",
                     ref, json_loads(f->extra, 0, NULL));
}

/* The keywords of a non-block field after "type"; nonzero on out of memory. */
static int field_keywords(json_t *o, const rd_field *f, const char *at,
                          const struct rd_scene *defaults, json_t *components)
{
    if (f->type == RD_F_ANALYSIS) /* the one name its echo gives */
        return set_new(o, "enum", f->echo ? json_pack("[o]", f->echo(defaults)) : NULL);
    int bad = 0;
    if (f->desc)
        bad |= set_new(o, "description", json_string(f->desc));
    if (f->type == RD_F_CHOICE)
        bad |= set_new(o, "enum", choices_array(f));
    if (f->nullable) { /* OpenAPI 3.0: "nullable", and null among the choices */
        bad |= set_new(o, "nullable", json_true());
        json_t *choices = json_object_get(o, "enum");
        if (choices)
            bad |= json_array_append_new(choices, json_null());
    }
    if (f->only_false)
        bad |= set_new(o, "enum", json_pack("[b]", 0));
    if (f->type == RD_F_TABLE)
        bad |= set_new(o, "items", json_pack("{s:s}", "type", "number"));
    if (f->type == RD_F_DISTORTION || f->type == RD_F_ITEMS || f->type == RD_F_CUSTOM) {
        rd_field item = {.key = f->key, .block = f->block};
        bad |= set_new(o, "items", block_ref(&item, defaults, components));
    }
    int count = f->type == RD_F_TABLE || f->type == RD_F_DISTORTION || f->type == RD_F_ITEMS ||
                f->type == RD_F_CUSTOM;
    return bad | add_default(o, f, at) | add_bounds(o, f, count);
}

json_t *rd_schema_field_openapi(const rd_field *f, const rd_block *in,
                                const struct rd_scene *defaults, json_t *components)
{
    static const char zero_item[64]; /* the defaults of an array item: all 0 */
    if (f->type == RD_F_BLOCK || f->type == RD_F_OPTBLOCK)
        return block_ref(f, defaults, components);
    if (f->type == RD_F_CUSTOM && !f->block) { /* its own schema, with the description */
        json_t *o = json_loads(f->extra ? f->extra : "{}", 0, NULL);
        if (o && f->desc && json_object_set_new(o, "description", json_string(f->desc)) != 0) {
            json_decref(o);
            o = NULL;
        }
        return o;
    }
    if (in->items && f->offset + sizeof(double) > sizeof zero_item)
        return NULL; /* an item larger than zero_item: widen it */
    const char *at = (in->items     ? zero_item
                      : f->in_opts  ? (const char *)defaults->opts
                      : f->in_scene ? (const char *)defaults
                                    : cbase_of(in, defaults)) +
                     f->offset;
    json_t *o = json_object();
    if (!o || set_new(o, "type", json_string(type_name(f->type))) != 0 ||
        field_keywords(o, f, at, defaults, components) != 0) {
        json_decref(o);
        return NULL;
    }
    if (!f->word)
        return o;
    /* a number or the word: {description, default, oneOf: [number, the word]} */
    json_t *d = json_incref(json_object_get(o, "description")),
           *v = json_incref(json_object_get(o, "default"));
    json_object_del(o, "description");
    json_object_del(o, "default");
    json_t *w = json_pack("{s:o, s:[o, {s:s, s:[s]}]}", "description", d ? d : json_string(""),
                          "oneOf", o, "type", "string", "enum", f->word);
    if (w && v && json_object_set_new(w, "default", v) != 0) {
        json_decref(w);
        return NULL;
    }
    if (!w)
        json_decref(v);
    return w;
}

json_t *rd_schema_block_openapi(const rd_block *block, const struct rd_scene *defaults,
                                json_t *components)
{
    json_t *props = json_object(), *required = json_array();
    int bad = !props || !required;
    for (const rd_field *f = block->fields; !bad && f->key; f++) {
        bad |= set_new(props, f->key, rd_schema_field_openapi(f, block, defaults, components));
        if (!bad && f->required)
            bad |= json_array_append_new(required, json_string(f->key));
    }
    json_t *o = bad ? NULL
                    : json_pack("{s:s, s:s, s:b, s:O}", "type", "object", "description",
                                block->desc ? block->desc : "", "additionalProperties", 0,
                                "properties", props);
    if (o && json_array_size(required) > 0 && json_object_set(o, "required", required) != 0) {
        json_decref(o);
        o = NULL;
    }
    json_decref(props);
    json_decref(required);
    return o;
}
