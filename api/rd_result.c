/*
 * rd_result — CSV tables of a result, and the CSV of a stored result text
 * without decoding all of it (rd_result.h, rd_api.h).
 *
 * A result is built once, as a jansson object, by the analysis' runner
 * (rd_scene_run_doc, rd_scene.c); its JSON text and its CSV table are both
 * written from that object (rd_result_doc).  A server that kept only the text (rd_api_result_csv)
 * gets the CSV by decoding just the members the table reads: the lift
 * result's bulk, lift_segments (samples x n numbers), is skipped over,
 * never turned into jansson values.
 */
#include "rd_result.h"

#include <jansson.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_api.h"
#include "rd_json.h"
#include "rd_jsonptr.h"
#include "rd_registry.h"

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

/* Grows b to hold at least `need` more bytes and a NUL; 0, or -1 (failed). */
static int sb_reserve(strbuf *b, size_t need)
{
    if (b->len + need + 1 <= b->cap)
        return 0;
    size_t cap = b->cap ? b->cap : 1024;
    while (cap < b->len + need + 1)
        cap *= 2;
    char *p = realloc(b->p, cap);
    if (!p) {
        b->failed = 1;
        return -1;
    }
    b->p = p;
    b->cap = cap;
    return 0;
}

/* Formats into the room left, growing and formatting again only when the
 * text did not fit (a CSV cell nearly always does: one vsnprintf each). */
static void sb_printf(strbuf *b, const char *fmt, ...)
{
    va_list ap;
    if (b->failed || sb_reserve(b, 64) != 0)
        return;
    va_start(ap, fmt);
    int need = vsnprintf(b->p + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    if (need < 0) {
        b->failed = 1;
        return;
    }
    if (b->len + (size_t)need + 1 > b->cap) {
        if (sb_reserve(b, (size_t)need) != 0)
            return;
        va_start(ap, fmt);
        vsnprintf(b->p + b->len, b->cap - b->len, fmt, ap);
        va_end(ap);
    }
    b->len += (size_t)need;
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

/* One cell: text for a text column, else a number (%.10g) or null (empty);
 * anything else (or a missing value) is malformed: -1. */
static int csv_cell(strbuf *b, const rd_csv_column *c, json_t *v, const char *sep)
{
    if (c->text & 1) {
        if (!json_is_string(v))
            return -1;
        csv_text(b, json_string_value(v), sep);
    } else if (json_is_null(v)) {
        sb_printf(b, "%s", sep);
    } else if (json_is_number(v)) {
        sb_printf(b, "%.10g%s", json_number_value(v), sep);
    } else {
        return -1;
    }
    return 0;
}

static int count_columns(const rd_csv_table *t)
{
    int n = 0;
    while (t->columns[n].header)
        n++;
    return n;
}

/* A column of one value of the whole result (its key a JSON Pointer). */
static int is_pointer(const rd_csv_column *c)
{
    return c->key[0] == '/';
}

/* A pointer column's cell: its value, an empty cell when the result has none
 * (a result written before the column was). */
static int pointer_cell(strbuf *b, json_t *result, const rd_csv_column *c, const char *sep)
{
    json_t *v = rd_jsonptr_get(result, c->key);
    if (!v || json_is_null(v)) {
        sb_printf(b, "%s", sep);
        return 0;
    }
    return csv_cell(b, c, v, sep);
}

/* Rows from an array of objects (table->rows). */
static int csv_rows(json_t *result, const rd_csv_table *t, int ncols, strbuf *b,
                    const char *analysis, rd_error *err)
{
    json_t *rows = json_object_get(result, t->rows), *row;
    size_t i;
    if (!json_is_array(rows))
        return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s is not an array",
                            analysis, t->rows);
    json_array_foreach(rows, i, row)
    {
        for (int c = 0; c < ncols; c++) {
            const rd_csv_column *col = &t->columns[c];
            const char *sep = c + 1 < ncols ? "," : "\n";
            if (is_pointer(col) ? pointer_cell(b, result, col, sep)
                                : csv_cell(b, col, json_object_get(row, col->key), sep))
                return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s/%zu/%s",
                                    analysis, t->rows, i, col->key);
        }
    }
    return RD_OK;
}

/* A column "object.member": the array `member` of the result's `object`;
 * NULL when the result has no such object (its cells are empty). */
static json_t *column_array(json_t *holder, const char *key)
{
    const char *dot = strchr(key, '.');
    if (!dot)
        return json_object_get(holder, key);
    char obj[64];
    size_t n = (size_t)(dot - key);
    if (n >= sizeof obj)
        return NULL;
    memcpy(obj, key, n);
    obj[n] = 0;
    return json_object_get(json_object_get(holder, obj), dot + 1);
}

/* Rows from columns of equal-length arrays (in table->object, if named). */
static int csv_arrays(json_t *result, const rd_csv_table *t, int ncols, strbuf *b,
                      const char *analysis, rd_error *err)
{
    json_t *holder = t->object ? json_object_get(result, t->object) : result;
    size_t rows = 0;
    int first = 1;
    for (int c = 0; c < ncols; c++) {
        if (is_pointer(&t->columns[c]))
            continue;
        json_t *a = column_array(holder, t->columns[c].key);
        if (!json_is_array(a))
            return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s is not an array",
                                analysis, t->columns[c].key);
        if (first)
            rows = json_array_size(a);
        else if (json_array_size(a) != rows)
            return rd_error_set(err, RD_EINTERNAL, "",
                                "malformed %s result: /%s has %zu rows, "
                                "not %zu",
                                analysis, t->columns[c].key, json_array_size(a), rows);
        first = 0;
    }
    for (size_t i = 0; i < rows; i++)
        for (int c = 0; c < ncols; c++) {
            const rd_csv_column *col = &t->columns[c];
            const char *sep = c + 1 < ncols ? "," : "\n";
            json_t *column = is_pointer(col) ? NULL : column_array(holder, col->key);
            if (is_pointer(col) ? pointer_cell(b, result, col, sep)
                                : csv_cell(b, col, json_array_get(column, i), sep))
                return rd_error_set(err, RD_EINTERNAL, "", "malformed %s result: /%s/%zu", analysis,
                                    col->key, i);
        }
    return RD_OK;
}

#define CSV_COLUMNS_MAX 64

char *rd_result_csv(json_t *result, const rd_csv_table *t0, const char *analysis, rd_error *err)
{
    strbuf b = {NULL, 0, 0, 0};
    /* a column "object.member" whose object the result does not have (an
     * optional block: lift's lubrication), or an optional column's absent
     * member, is left out, header and cells */
    rd_csv_column cols[CSV_COLUMNS_MAX + 1];
    rd_csv_table tt = *t0, *t = &tt;
    json_t *holder = t0->object ? json_object_get(result, t0->object) : result;
    int ncols = 0;
    for (int c = 0; c < count_columns(t0) && ncols < CSV_COLUMNS_MAX; c++) {
        const rd_csv_column *col = &t0->columns[c];
        if (!t0->rows && !is_pointer(col) &&
            (strchr(col->key, '.') || (col->text & RD_CSV_OPTIONAL)) &&
            !column_array(holder, col->key))
            continue;
        cols[ncols++] = *col;
    }
    cols[ncols] = (rd_csv_column){NULL, NULL, 0};
    tt.columns = cols;
    for (int c = 0; c < ncols; c++)
        sb_printf(&b, "%s%s", t->columns[c].header, c + 1 < ncols ? "," : "\n");
    int rc = t->rows ? csv_rows(result, t, ncols, &b, analysis, err)
                     : csv_arrays(result, t, ncols, &b, analysis, err);
    if (rc == RD_OK && b.failed)
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the CSV table");
    if (rc != RD_OK) {
        free(b.p);
        return NULL;
    }
    return b.p;
}

/* ---- the result document -------------------------------------------------- */

struct rd_result_doc {
    const rd_analysis_def *an;
    json_t *result;
};

rd_result_doc *rd_result_doc_new(const rd_analysis_def *an, json_t *result)
{
    rd_result_doc *doc = malloc(sizeof *doc);
    if (doc) {
        doc->an = an;
        doc->result = result;
    }
    return doc;
}

char *rd_result_doc_json(const rd_result_doc *doc)
{
    return rd_json_dumps(doc->result, RD_RESULT_REAL_DIGITS, 0);
}

char *rd_result_doc_csv(const rd_result_doc *doc, rd_error *err)
{
    if (!doc->an->csv) {
        rd_error_set(err, RD_ENOTFOUND, "", "a %s result has no CSV table", doc->an->name);
        return NULL;
    }
    return rd_result_csv(doc->result, doc->an->csv, doc->an->name, err);
}

void rd_result_doc_free(rd_result_doc *doc)
{
    if (!doc)
        return;
    json_decref(doc->result);
    free(doc);
}

/* ---- CSV of a result text ------------------------------------------------- */

/* A top-level member of the result text: its key (raw bytes between the
 * quotes) and the span of its value. */
typedef struct member {
    const char *key, *value;
    size_t key_len, value_len;
} member;

#define MEMBERS_MAX 64

static const char *skip_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r'))
        p++;
    return p;
}

/* p at '"': past the closing quote, or NULL. */
static const char *skip_string(const char *p, const char *end)
{
    for (p++; p < end; p++) {
        if (*p == '\\')
            p++;
        else if (*p == '"')
            return p + 1;
    }
    return NULL;
}

/* Past one value (its brackets balanced, strings skipped whole; the
 * content is checked only when a member is decoded), or NULL. */
static const char *skip_value(const char *p, const char *end)
{
    if (p < end && *p == '"')
        return skip_string(p, end);
    if (p < end && (*p == '{' || *p == '[')) {
        size_t depth = 0;
        for (; p < end; p++) {
            if (*p == '"') {
                if (!(p = skip_string(p, end)))
                    return NULL;
                p--;
            } else if (*p == '{' || *p == '[') {
                depth++;
            } else if ((*p == '}' || *p == ']') && --depth == 0) {
                return p + 1;
            }
        }
        return NULL;
    }
    const char *start = p;
    while (p < end && !strchr(",}] \t\r\n", *p))
        p++;
    return p > start ? p : NULL;
}

/* The members of the top-level object in `text`; -1 if it is not one. */
static int scan_members(const char *text, size_t len, member *m, int max)
{
    const char *p = text, *end = text + len;
    int n = 0;
    p = skip_ws(p, end);
    if (p >= end || *p != '{')
        return -1;
    p = skip_ws(p + 1, end);
    if (p < end && *p == '}')
        return 0;
    while (p < end && n < max) {
        if (*p != '"')
            return -1;
        const char *key_end = skip_string(p, end);
        if (!key_end)
            return -1;
        m[n].key = p + 1;
        m[n].key_len = (size_t)(key_end - p - 2);
        p = skip_ws(key_end, end);
        if (p >= end || *p != ':')
            return -1;
        p = skip_ws(p + 1, end);
        const char *value_end = skip_value(p, end);
        if (!value_end)
            return -1;
        m[n].value = p;
        m[n++].value_len = (size_t)(value_end - p);
        p = skip_ws(value_end, end);
        if (p < end && *p == '}')
            return skip_ws(p + 1, end) == end ? n : -1;
        if (p >= end || *p != ',')
            return -1;
        p = skip_ws(p + 1, end);
    }
    return -1;
}

/* The value of member `key` decoded (new reference), or NULL when absent
 * or not JSON. */
static json_t *member_value(const member *m, int n, const char *key)
{
    size_t k = strlen(key);
    for (int i = 0; i < n; i++)
        if (m[i].key_len == k && memcmp(m[i].key, key, k) == 0)
            return json_loadb(m[i].value, m[i].value_len, JSON_DECODE_ANY, NULL);
    return NULL;
}

/* Decodes member `key` (key_len bytes) of the text into `o`, once: 0, or
 * -1 when out of memory.  An absent or undecodable member is left out. */
static int take_member(json_t *o, const member *m, int n, const char *key, size_t key_len)
{
    for (int i = 0; i < n; i++) {
        if (m[i].key_len != key_len || memcmp(m[i].key, key, key_len) != 0)
            continue;
        char *name = malloc(key_len + 1);
        if (!name)
            return -1;
        memcpy(name, key, key_len);
        name[key_len] = '\0';
        int rc = 0;
        json_t *v = json_object_get(o, name)
                        ? NULL
                        : json_loadb(m[i].value, m[i].value_len, JSON_DECODE_ANY, NULL);
        if (v)
            rc = json_object_set_new(o, name, v);
        free(name);
        return rc ? -1 : 0;
    }
    return 0;
}

/* An object holding only the members `t` reads ("analysis" aside): what
 * rd_result_csv needs of the whole result (a pointer column: the member its
 * first token names; an "object.member" column: the object).  NULL on out
 * of memory. */
static json_t *table_members(const member *m, int n, const rd_csv_table *t)
{
    json_t *o = json_object();
    const char *holder = t->rows ? t->rows : t->object;
    int bad = !o || (holder && take_member(o, m, n, holder, strlen(holder)));
    for (int c = 0; !bad && t->columns[c].header; c++) {
        const char *key = t->columns[c].key;
        if (is_pointer(&t->columns[c]))
            bad = take_member(o, m, n, key + 1, strcspn(key + 1, "/"));
        else if (!holder)
            bad = take_member(o, m, n, key, strcspn(key, "."));
    }
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

char *rd_api_result_csv(const char *result_json, rd_error *err)
{
    member m[MEMBERS_MAX];
    const char *text = result_json ? result_json : "";
    int n = scan_members(text, strlen(text), m, MEMBERS_MAX);
    if (n < 0) {
        rd_error_set(err, RD_EINTERNAL, "", "the result is not a JSON object");
        return NULL;
    }
    json_t *name = member_value(m, n, "analysis");
    const rd_analysis_def *an =
        json_is_string(name) ? rd_registry_find(rd_registry, json_string_value(name), NULL) : NULL;
    char *csv = NULL;
    if (!json_is_string(name)) {
        rd_error_set(err, RD_EINTERNAL, "", "malformed result: no \"analysis\" string");
    } else if (!an || !an->csv) {
        rd_error_set(err, RD_ENOTFOUND, "", "a %.40s result has no CSV table",
                     json_string_value(name));
    } else {
        json_t *part = table_members(m, n, an->csv);
        csv = part ? rd_result_csv(part, an->csv, an->name, err) : NULL;
        if (!part)
            rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the CSV table");
        json_decref(part);
    }
    json_decref(name);
    return csv;
}
