/*
 * rd_json — a compact JSON writer over jansson values (rd_json.h), for the
 * per-job texts of the server's hot path: the result, the echoed scene and
 * the canonical scene of the result cache.
 *
 * The text grows in one buffer (doubling); strings are escaped as jansson
 * escapes them: '"', '\\' and the control characters below 0x20 (\b \f \n
 * \r \t by name, the others as \u00XX with upper-case hex); everything else,
 * UTF-8 included, is copied (jansson validated it when the string was made).
 *
 * Also the reals every writer above makes: a non-finite one as null.
 */
#include "rd_json.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_dtoa.h"

typedef struct out {
    char *p;
    size_t len, cap;
    int digits, sort, failed;
} out;

/* Room for `need` more bytes and a NUL; 0, or -1 (failed sticks). */
static int reserve(out *o, size_t need)
{
    if (o->failed)
        return -1;
    if (o->len + need + 1 <= o->cap)
        return 0;
    size_t cap = o->cap;
    while (cap < o->len + need + 1)
        cap *= 2;
    char *p = realloc(o->p, cap);
    if (!p) {
        o->failed = 1;
        return -1;
    }
    o->p = p;
    o->cap = cap;
    return 0;
}

static void put(out *o, const char *s, size_t n)
{
    if (reserve(o, n) == 0) {
        memcpy(o->p + o->len, s, n);
        o->len += n;
    }
}

static void put_char(out *o, char c)
{
    if (reserve(o, 1) == 0)
        o->p[o->len++] = c;
}

static void put_string(out *o, const char *s, size_t n)
{
    put_char(o, '"');
    size_t run = 0; /* bytes copied as they are, pending */
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 0x20 && c != '"' && c != '\\') {
            run++;
            continue;
        }
        put(o, s + i - run, run);
        run = 0;
        char esc[8];
        const char *named = c == '"'    ? "\\\""
                            : c == '\\' ? "\\\\"
                            : c == '\b' ? "\\b"
                            : c == '\f' ? "\\f"
                            : c == '\n' ? "\\n"
                            : c == '\r' ? "\\r"
                            : c == '\t' ? "\\t"
                                        : NULL;
        if (!named) {
            snprintf(esc, sizeof esc, "\\u%04X", (unsigned)c);
            named = esc;
        }
        put(o, named, strlen(named));
    }
    put(o, s + n - run, run);
    put_char(o, '"');
}

static void put_real(out *o, double x)
{
    if (reserve(o, RD_DTOA_SIZE + 2) != 0)
        return;
    char *p = o->p + o->len;
    int n = o->digits ? rd_dtoa_digits(x, o->digits, p) : rd_dtoa_shortest(x, p);
    if (!memchr(p, '.', (size_t)n) && !memchr(p, 'e', (size_t)n)) {
        p[n++] = '.'; /* so that it reads back as a real */
        p[n++] = '0';
    }
    o->len += (size_t)n;
}

static void put_value(out *o, const json_t *v, int depth);

static int compare_keys(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static void put_object(out *o, const json_t *v, int depth)
{
    size_t n = json_object_size(v), i = 0;
    const char **keys = o->sort && n > 1 ? malloc(n * sizeof *keys) : NULL;
    const char *key;
    json_t *member;
    if (o->sort && n > 1 && !keys) {
        o->failed = 1;
        return;
    }
    put_char(o, '{');
    if (keys) {
        json_object_foreach((json_t *)v, key, member) keys[i++] = key;
        qsort(keys, n, sizeof *keys, compare_keys);
        for (i = 0; i < n; i++) {
            if (i)
                put_char(o, ',');
            put_string(o, keys[i], strlen(keys[i]));
            put_char(o, ':');
            put_value(o, json_object_get(v, keys[i]), depth + 1);
        }
        free(keys);
    } else {
        json_object_foreach((json_t *)v, key, member)
        {
            if (i++)
                put_char(o, ',');
            put_string(o, key, strlen(key));
            put_char(o, ':');
            put_value(o, member, depth + 1);
        }
    }
    put_char(o, '}');
}

static void put_value(out *o, const json_t *v, int depth)
{
    char num[32];
    if (depth > RD_JSON_MAX_DEPTH || !v) {
        o->failed = 1;
        return;
    }
    switch (json_typeof(v)) {
    case JSON_OBJECT:
        put_object(o, v, depth);
        break;
    case JSON_ARRAY:
        put_char(o, '[');
        for (size_t i = 0, n = json_array_size(v); i < n; i++) {
            if (i)
                put_char(o, ',');
            put_value(o, json_array_get(v, i), depth + 1);
        }
        put_char(o, ']');
        break;
    case JSON_STRING:
        put_string(o, json_string_value(v), json_string_length(v));
        break;
    case JSON_INTEGER:
        put(o, num,
            (size_t)snprintf(num, sizeof num, "%" JSON_INTEGER_FORMAT, json_integer_value(v)));
        break;
    case JSON_REAL:
        put_real(o, json_real_value(v));
        break;
    case JSON_TRUE:
        put(o, "true", 4);
        break;
    case JSON_FALSE:
        put(o, "false", 5);
        break;
    case JSON_NULL:
        put(o, "null", 4);
        break;
    }
}

char *rd_json_dumps(const json_t *v, int digits, int sort)
{
    if (!json_is_object(v) && !json_is_array(v))
        return NULL;
    out o = {malloc(4096), 0, 4096, digits, sort, 0};
    if (!o.p)
        return NULL;
    put_value(&o, v, 0);
    if (o.failed) {
        free(o.p);
        return NULL;
    }
    o.p[o.len] = '\0';
    return o.p;
}

json_t *rd_json_copy(json_t *v)
{
    json_t *c = json_copy(v);
    size_t want = json_is_object(v) ? json_object_size(v) : json_array_size(v);
    size_t got = json_is_object(c) ? json_object_size(c) : json_array_size(c);
    if (c && got != want) {
        json_decref(c);
        c = NULL;
    }
    return c;
}

json_t *rd_result_real(double x)
{
    return isfinite(x) ? json_real(x) : json_null();
}

json_t *rd_result_reals(const double *x, int n, int stride, double scale)
{
    json_t *a = json_array();
    for (int i = 0; a && i < n; i++) {
        if (json_array_append_new(a, rd_result_real(scale * x[(size_t)i * (size_t)stride])) != 0) {
            json_decref(a);
            a = NULL;
        }
    }
    return a;
}
