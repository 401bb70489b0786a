/*
 * rd_schema — the field-table engine (rd_schema.h): parsing a block, with
 * every problem listed and the messages about user text.  The two writers
 * of the same tables, the echo and the OpenAPI schema, are in
 * rd_schema_write.c.
 *
 * A field's value lives at base + offset, where base is the scene, the
 * analysis' opts (rd_block.in_opts) or one array item (rd_block.items).
 * Values and ranges are core's business (its validators run after
 * parsing); this file checks shape and type, and quotes the table's range
 * only for an integer that does not even fit an int.
 */
#include "rd_schema.h"

#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_scene.h"
#include "rd_static.h"

/* How much of a user-supplied key or string a message quotes, bytes. */
#define QUOTE_MAX 40

static char *base_of(const rd_block *block, struct rd_scene *s)
{
    return block->in_opts ? (char *)s->opts : (char *)s;
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

int rd_schema_utf8_len(const unsigned char *s)
{
    unsigned char c = s[0];
    int n;
    unsigned char lo = 0x80, hi = 0xBF; /* allowed range of the 2nd byte */
    if (c < 0x80)
        return 1;
    if (c >= 0xC2 && c <= 0xDF)
        n = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        if (c == 0xE0)
            lo = 0xA0;
        if (c == 0xED)
            hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        if (c == 0xF0)
            lo = 0x90;
        if (c == 0xF4)
            hi = 0x8F;
    } else
        return 0;
    if (s[1] < lo || s[1] > hi)
        return 0;
    for (int k = 2; k < n; k++)
        if ((s[k] & 0xC0) != 0x80)
            return 0;
    return n;
}

void rd_schema_quote(char *buf, size_t size, const char *s)
{
    size_t n = utf8_prefix(s, QUOTE_MAX);
    snprintf(buf, size, "\"%.*s%s\"", (int)n, s, s[n] ? "..." : "");
}

void rd_schema_describe(const json_t *v, char *buf, size_t size)
{
    char q[QUOTE_MAX + 8];
    switch (json_typeof(v)) {
    case JSON_STRING:
        rd_schema_quote(q, sizeof q, json_string_value(v));
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

int rd_schema_type_error(rd_error *err, const char *path, const char *want, const json_t *v)
{
    char got[QUOTE_MAX + 32];
    rd_schema_describe(v, got, sizeof got);
    return rd_error_set(err, RD_EINVAL, path, "%s must be %s, got %s", path, want, got);
}

void rd_schema_path_join(char *out, size_t size, const char *parent, const char *key)
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

static const rd_field *find_field(const rd_field *fields, const char *key)
{
    for (const rd_field *f = fields; f->key; f++)
        if (strcmp(f->key, key) == 0)
            return f;
    return NULL;
}

static int in_list(const char *const *list, const char *key)
{
    for (; list && *list; list++)
        if (strcmp(*list, key) == 0)
            return 1;
    return 0;
}

/* "a, b, c": the keys of `fields`. */
static void list_known(char *buf, size_t size, const rd_field *fields)
{
    size_t n = 0;
    buf[0] = '\0';
    for (const rd_field *f = fields; f->key && n < size; f++)
        n += (size_t)snprintf(buf + n, size - n, "%s%s", n ? ", " : "", f->key);
}

/* ---- every problem: issues, allowed values, did you mean ----------------- */

void rd_issues_add(rd_issues *list, int code, const char *path, const char *allowed,
                   const char *did_you_mean, const char *fmt, ...)
{
    if (!list)
        return;
    if (list->n >= RD_ISSUES_MAX) {
        list->dropped++;
        return;
    }
    rd_issue *it = &list->item[list->n++];
    memset(it, 0, sizeof *it);
    it->code = code;
    snprintf(it->path, sizeof it->path, "%s", path);
    snprintf(it->allowed, sizeof it->allowed, "%s", allowed ? allowed : "");
    snprintf(it->did_you_mean, sizeof it->did_you_mean, "%s", did_you_mean ? did_you_mean : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(it->message, sizeof it->message, fmt, ap);
    va_end(ap);
}

/* "; did you mean "x"?" after a message, or "" without a suggestion. */
static void hint_text(char *buf, size_t size, const char *dym)
{
    if (dym)
        snprintf(buf, size, "; did you mean \"%s\"?", dym);
    else
        buf[0] = '\0';
}

/* Records one problem: the first one in `err`, every one in s->issues.
 * The listed message ends with "; did you mean ...?" when `dym` is given;
 * the first error's message stays as it always was (scripts match it),
 * its suggestion travels in the answer's "did_you_mean".  Returns `code`. */
static int report(struct rd_scene *s, rd_error *err, int code, const char *path,
                  const char *allowed, const char *dym, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;
static int report(struct rd_scene *s, rd_error *err, int code, const char *path,
                  const char *allowed, const char *dym, const char *fmt, ...)
{
    char message[RD_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    char hint[96];
    hint_text(hint, sizeof hint, dym);
    rd_issues_add(s->issues, code, path, allowed, dym, "%s%s", message, hint);
    return rd_error_set(err, code, path, "%s", message);
}

/* rd_schema_type_error, reported. */
static int type_issue(struct rd_scene *s, rd_error *err, const char *path, const char *want,
                      const json_t *v)
{
    char got[QUOTE_MAX + 32];
    rd_schema_describe(v, got, sizeof got);
    return report(s, err, RD_EINVAL, path, want, NULL, "%s must be %s, got %s", path, want, got);
}

/* A JSON type error at field `f`, allowed values as the table says them. */
static int field_type_issue(struct rd_scene *s, rd_error *err, const rd_field *f, const char *path,
                            const char *want, const json_t *v)
{
    char got[QUOTE_MAX + 32], allowed[160];
    rd_schema_describe(v, got, sizeof got);
    rd_schema_allowed(f, allowed, sizeof allowed);
    return report(s, err, RD_EINVAL, path, allowed, NULL, "%s must be %s, got %s", path, want, got);
}

/* Edit distance with swaps of neighbours (optimal string alignment);
 * words longer than WORD_MAX are never close. */
#define WORD_MAX 48
static int edit_distance(const char *a, const char *b)
{
    size_t n = strlen(a), m = strlen(b);
    if (n >= WORD_MAX || m >= WORD_MAX)
        return INT_MAX;
    int d[WORD_MAX + 1][WORD_MAX + 1];
    for (size_t i = 0; i <= n; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= m; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= n; i++)
        for (size_t j = 1; j <= m; j++) {
            int cost = a[i - 1] != b[j - 1];
            int best = d[i - 1][j - 1] + cost;
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[n][m];
}

const char *rd_schema_closest(const char *word, const char *const *names)
{
    size_t len = strlen(word);
    int limit = len <= 5 ? 1 : len <= 10 ? 2 : 3, best = INT_MAX;
    const char *found = NULL;
    for (; names && *names; names++) {
        int d = edit_distance(word, *names);
        if (d < best) {
            best = d;
            found = *names;
        }
    }
    return best <= limit && best > 0 ? found : NULL;
}

/* The closest key of `fields` to `key`, or NULL. */
static const char *closest_key(const char *key, const rd_field *fields)
{
    const char *names[96];
    int n = 0;
    for (const rd_field *f = fields; f->key && n < 95; f++)
        names[n++] = f->key;
    names[n] = NULL;
    return rd_schema_closest(key, names);
}

static void bound_text(char *buf, size_t size, const rd_field *f)
{
    size_t n = 0;
    buf[0] = '\0';
    if (f->has_min)
        n +=
            (size_t)snprintf(buf, size, "%s %.15g", f->has_min == RD_BOUND_EX ? ">" : ">=", f->min);
    if (f->has_max && n < size)
        snprintf(buf + n, size - n, "%s%s %.15g", n ? " and " : "",
                 f->has_max == RD_BOUND_EX ? "<" : "<=", f->max);
}

void rd_schema_allowed(const rd_field *f, char *buf, size_t size)
{
    char range[96];
    size_t n = 0;
    buf[0] = '\0';
    switch (f->type) {
    case RD_F_NUMBER:
    case RD_F_INTEGER:
        bound_text(range, sizeof range, f);
        snprintf(buf, size, "%s%s%s", f->type == RD_F_INTEGER ? "an integer" : "a number",
                 range[0] ? " " : "", range);
        break;
    case RD_F_BOOL:
        snprintf(buf, size, "%s", f->only_false ? "false" : "true or false");
        break;
    case RD_F_CHOICE:
        n = (size_t)snprintf(buf, size, "one of");
        for (int k = 0; f->choices[k] && n < size; k++)
            n += (size_t)snprintf(buf + n, size - n, "%s \"%s\"", k ? "," : "", f->choices[k]);
        break;
    case RD_F_TABLE:
        snprintf(buf, size, "an array of %d to %d numbers", (int)f->min, (int)f->max);
        break;
    case RD_F_DISTORTION:
        snprintf(buf, size, "an array of at most %d {order, amplitude, phase_deg}",
                 RD_BORE_ORDERS_MAX);
        break;
    case RD_F_ITEMS:
        snprintf(buf, size, "an array of objects");
        break;
    case RD_F_CUSTOM:
        snprintf(buf, size, "%s", f->block ? "an array of objects" : "see its description");
        break;
    case RD_F_STRING:
        snprintf(buf, size, "a string");
        break;
    case RD_F_BLOCK:
    case RD_F_OPTBLOCK:
        snprintf(buf, size, "an object");
        break;
    case RD_F_ANALYSIS:
        break;
    }
}

const rd_field *rd_schema_find(const rd_block *block, const char *path)
{
    char token[RD_ERROR_PATH_MAX];
    const rd_field *found = NULL;
    while (block && *path == '/') {
        path++;
        size_t n = strcspn(path, "/");
        if (n >= sizeof token)
            return NULL;
        memcpy(token, path, n);
        token[n] = '\0';
        path += n;
        if (found &&
            (found->type == RD_F_DISTORTION || (found->type == RD_F_CUSTOM && found->block)) &&
            strspn(token, "0123456789") == n)
            continue; /* the index of an item */
        found = find_field(block->fields, token);
        if (!found)
            return NULL;
        block = found->block;
    }
    return *path ? NULL : found;
}

/* A number inside the JSON type but outside the table's static range:
 * listed (core's validator will say it in its own words). */
static void range_issue(const rd_field *f, double x, const char *path, struct rd_scene *s)
{
    int low =
        (f->has_min == RD_BOUND_IN && x < f->min) || (f->has_min == RD_BOUND_EX && x <= f->min);
    int high =
        (f->has_max == RD_BOUND_IN && x > f->max) || (f->has_max == RD_BOUND_EX && x >= f->max);
    if (!s->issues || !(low || high))
        return;
    char allowed[160];
    rd_schema_allowed(f, allowed, sizeof allowed);
    int at = s->issues->n;
    rd_issues_add(s->issues, RD_EINVAL, path, allowed, NULL,
                  "%s = %.15g is out of range (allowed: %s)", path, x, allowed);
    if (at < s->issues->n)
        s->issues->item[at].range_only = 1;
}

/* ---- parsing ------------------------------------------------------------- */

/* RD_F_INTEGER: JSON integers, and reals with an integral value (20.0),
 * since many JSON writers do not distinguish the two. */
static int parse_integer(const rd_field *f, json_t *v, const char *path, int *out,
                         struct rd_scene *s, rd_error *err)
{
    double d;
    if (json_is_integer(v)) {
        d = (double)json_integer_value(v);
    } else if (json_is_real(v)) {
        d = json_real_value(v);
        if (d != floor(d)) {
            char allowed[160];
            rd_schema_allowed(f, allowed, sizeof allowed);
            return report(s, err, RD_EINVAL, path, allowed, NULL,
                          "%s must be an integer, got %.15g", path, d);
        }
    } else {
        return field_type_issue(s, err, f, path, "an integer", v);
    }
    if (d < (double)INT_MIN || d > (double)INT_MAX)
        return report(s, err, d > 0 ? RD_ELIMIT : RD_EINVAL, path, NULL, NULL,
                      "%s = %.15g is out of range (allowed: %d to %d)", path, d,
                      f->has_min ? (int)f->min : INT_MIN, f->has_max ? (int)f->max : INT_MAX);
    *out = (int)d;
    range_issue(f, d, path, s);
    return RD_OK;
}

/* RD_F_TABLE: a non-empty array of numbers, at most f->max long; every
 * item that is not a number is a problem of its own. */
static int parse_table(const rd_field *f, json_t *v, const char *path, struct rd_table *t,
                       struct rd_scene *s, rd_error *err)
{
    size_t i;
    json_t *x;
    int rc = RD_OK;
    if (!json_is_array(v))
        return type_issue(s, err, path, "an array of numbers", v);
    size_t n = json_array_size(v);
    if (n == 0 || (double)n > f->max)
        return report(s, err, n ? RD_ELIMIT : RD_EINVAL, path, NULL, NULL,
                      "%s has %zu values; allowed %d to %d.", path, n, (int)f->min, (int)f->max);
    free(t->v);
    t->n = 0;
    t->v = malloc(n * sizeof *t->v);
    if (!t->v)
        return report(s, err, RD_ENOMEM, path, NULL, NULL, "out of memory while reading %s", path);
    json_array_foreach(v, i, x)
    {
        if (!json_is_number(x)) {
            char item[RD_ERROR_PATH_MAX + 24];
            snprintf(item, sizeof item, "%s/%zu", path, i);
            if (rc == RD_OK)
                rc = type_issue(s, err, item, "a number", x);
            else
                type_issue(s, err, item, "a number", x);
            continue;
        }
        t->v[i] = json_number_value(x);
    }
    if (rc == RD_OK)
        t->n = (int)n;
    return rc;
}

/* Unknown keys of a distortion item, each a problem. */
static int item_unknown_keys(const rd_block *items, json_t *item, const char *at,
                             struct rd_scene *s, rd_error *err)
{
    char child[RD_ERROR_PATH_MAX + 48], known[128], q[QUOTE_MAX + 8];
    const char *key;
    json_t *x;
    int rc = RD_OK;
    json_object_foreach(item, key, x)
    {
        if (find_field(items->fields, key))
            continue;
        list_known(known, sizeof known, items->fields);
        const char *dym = closest_key(key, items->fields);
        rd_schema_quote(q, sizeof q, key);
        rd_schema_path_join(child, sizeof child, at, key);
        int r = report(s, err, RD_EINVAL, child, known, dym, "unknown field %s in %s (known: %s)",
                       q, at, known);
        rc = rc == RD_OK ? r : rc;
    }
    return rc;
}

/* One distortion item {order, amplitude, phase_deg} (keys from the item
 * block); `order` must be a JSON integer, clamped to +-1000 for core to
 * refuse with the value. */
static int parse_distortion_item(const rd_block *items, json_t *item, const char *at,
                                 rd_distortion *d, struct rd_scene *s, rd_error *err)
{
    char child[RD_ERROR_PATH_MAX + 48];
    if (!json_is_object(item))
        return type_issue(s, err, at, "an object {order, amplitude, phase_deg}", item);
    int rc = item_unknown_keys(items, item, at, s, err);
    if (rc != RD_OK)
        return rc;
    memset(d, 0, sizeof *d);
    json_t *order = json_object_get(item, "order"), *amp = json_object_get(item, "amplitude"),
           *phase = json_object_get(item, "phase_deg");
    rd_schema_path_join(child, sizeof child, at, "order");
    if (!order)
        return report(s, err, RD_EINVAL, child, "an integer 1 to 64", NULL,
                      "%s is missing: each distortion needs its Fourier order (1 to 64)", child);
    if (!json_is_integer(order))
        return type_issue(s, err, child, "an integer", order);
    json_int_t k = json_integer_value(order);
    d->order = k < -1000 ? -1000 : k > 1000 ? 1000 : (int)k;
    rd_schema_path_join(child, sizeof child, at, "amplitude");
    if (!amp)
        return report(s, err, RD_EINVAL, child, "a number", NULL,
                      "%s is missing: each distortion needs its amplitude (m)", child);
    if (!json_is_number(amp))
        return type_issue(s, err, child, "a number", amp);
    d->amplitude = json_number_value(amp);
    if (phase) {
        rd_schema_path_join(child, sizeof child, at, "phase_deg");
        if (!json_is_number(phase))
            return type_issue(s, err, child, "a number", phase);
        d->phase_deg = json_number_value(phase);
    }
    return RD_OK;
}

/* RD_F_DISTORTION: [{"order": k, "amplitude": A, "phase_deg": phi}, ...]. */
static int parse_distortion(const rd_field *f, json_t *v, const char *path, rd_bore *c,
                            struct rd_scene *s, rd_error *err)
{
    size_t i;
    json_t *item;
    int rc = RD_OK;
    if (!json_is_array(v))
        return type_issue(s, err, path, "an array of {order, amplitude, phase_deg}", v);
    if (json_array_size(v) > RD_BORE_ORDERS_MAX)
        return report(s, err, RD_ELIMIT, path, NULL, NULL,
                      "%s has %zu entries; at most %d are allowed.", path, json_array_size(v),
                      RD_BORE_ORDERS_MAX);
    c->n_distortion = 0;
    json_array_foreach(v, i, item)
    {
        char at[RD_ERROR_PATH_MAX + 24];
        snprintf(at, sizeof at, "%s/%zu", path, i);
        int r = parse_distortion_item(f->block, item, at, &c->distortion[i], s, err);
        if (rc == RD_OK && r != RD_OK)
            rc = r;
        if (rc == RD_OK)
            c->n_distortion = (int)i + 1;
    }
    return rc;
}

static int parse_choice(const rd_field *f, json_t *v, const char *path, int *out,
                        struct rd_scene *s, rd_error *err)
{
    char want[128], got[QUOTE_MAX + 32];
    for (int k = 0; f->choices[k]; k++)
        if (json_is_string(v) && strcmp(json_string_value(v), f->choices[k]) == 0) {
            *out = k;
            return RD_OK;
        }
    rd_schema_allowed(f, want, sizeof want);
    rd_schema_describe(v, got, sizeof got);
    const char *dym =
        json_is_string(v) ? rd_schema_closest(json_string_value(v), f->choices) : NULL;
    return report(s, err, RD_EINVAL, path, want, dym, "%s must be %s, got %s", path, want, got);
}

static int parse_field(const rd_field *f, char *at, json_t *v, const char *path, struct rd_scene *s,
                       rd_error *err)
{
    switch (f->type) {
    case RD_F_NUMBER:
        if (f->word && json_is_string(v) && strcmp(json_string_value(v), f->word) == 0) {
            *(double *)at = 0.0;
            return RD_OK;
        }
        if (!json_is_number(v)) {
            char want[64];
            snprintf(want, sizeof want, f->word ? "a number or \"%s\"" : "a number",
                     f->word ? f->word : "");
            return field_type_issue(s, err, f, path, want, v);
        }
        *(double *)at = json_number_value(v);
        range_issue(f, *(double *)at, path, s);
        return RD_OK;
    case RD_F_INTEGER:
        return parse_integer(f, v, path, (int *)at, s, err);
    case RD_F_BOOL:
        if (!json_is_boolean(v))
            return type_issue(s, err, path, "true or false", v);
        *(int *)at = json_is_true(v);
        return RD_OK;
    case RD_F_STRING: {
        if (!json_is_string(v))
            return type_issue(s, err, path, "a string", v);
        char **dst = (char **)at;
        free(*dst);
        *dst = strdup(json_string_value(v));
        if (!*dst)
            return report(s, err, RD_ENOMEM, path, NULL, NULL, "out of memory while reading %s",
                          path);
        return RD_OK;
    }
    case RD_F_CHOICE:
        return parse_choice(f, v, path, (int *)at, s, err);
    case RD_F_OPTBLOCK:
        *(int *)at = 1;
        /* fall through */
    case RD_F_BLOCK:
        if (!json_is_object(v))
            return type_issue(s, err, path, "an object", v);
        return rd_schema_parse(v, f->block, NULL, path, s, err);
    case RD_F_TABLE:
        return parse_table(f, v, path, (struct rd_table *)at, s, err);
    case RD_F_DISTORTION:
        return parse_distortion(f, v, path, (rd_bore *)at, s, err);
    case RD_F_ITEMS:
        if (!json_is_array(v))
            return type_issue(s, err, path, "an array of objects", v);
        return f->parse(f, v, path, s, err);
    case RD_F_CUSTOM:
        return f->parse(f, v, path, s, err);
    case RD_F_ANALYSIS:
        return RD_OK;
    }
    return report(s, err, RD_EINTERNAL, path, NULL, NULL, "unhandled field type for %s", path);
}

/* Every key of `obj` that neither `block` nor `also` (keys the caller
 * has refused already) knows: a problem each, with the closest of
 * `block`'s keys when one is close. */
static int unknown_keys(json_t *obj, const rd_block *block, const char *const *also,
                        const char *path, struct rd_scene *s, rd_error *err)
{
    char child[RD_ERROR_PATH_MAX], known[256], q[QUOTE_MAX + 8];
    const char *key;
    json_t *v;
    int rc = RD_OK;
    json_object_foreach(obj, key, v)
    {
        if (find_field(block->fields, key) || in_list(also, key))
            continue;
        list_known(known, sizeof known, block->fields);
        const char *dym = closest_key(key, block->fields);
        rd_schema_quote(q, sizeof q, key);
        rd_schema_path_join(child, sizeof child, path, key);
        int r = report(s, err, RD_EINVAL, child, known, dym, "unknown field %s in %s (known: %s)",
                       q, *path ? path : "the scene", known);
        rc = rc == RD_OK ? r : rc;
    }
    return rc;
}

int rd_schema_parse(json_t *obj, const rd_block *block, const char *const *also, const char *path,
                    struct rd_scene *s, rd_error *err)
{
    char child[RD_ERROR_PATH_MAX];
    /* Unknown keys first: a typo is the likeliest cause of anything else
     * that looks wrong. */
    int rc = unknown_keys(obj, block, also, path, s, err);
    char *base = base_of(block, s);
    for (const rd_field *f = block->fields; f->key; f++) {
        json_t *v = json_object_get(obj, f->key);
        if (!v)
            continue; /* absent: the default stays */
        rd_schema_path_join(child, sizeof child, path, f->key);
        char *at = f->in_opts ? (char *)s->opts : f->in_scene ? (char *)s : base;
        int r = parse_field(f, at + f->offset, v, child, s, err);
        if (rc == RD_OK)
            rc = r;
        if (r == RD_ENOMEM)
            return rc;
    }
    return rc;
}
