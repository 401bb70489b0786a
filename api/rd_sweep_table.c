/*
 * rd_sweep_table — a sweep's table as JSON and CSV (RFC 4180), the chunk
 * files of a sweep split over K processes, and their reduction to the whole
 * table (rd_sweep.h).  Uses only the public rd_sweep functions.
 *
 * The JSON table is written as {"columns":[...],"rows":[row,row,...]} with
 * compact rows, the same bytes whether it is built in memory
 * (rd_sweep_table_json) or streamed from chunks (rd_sweep_reduce), so the
 * service's table and the cluster's can be compared with cmp.
 */
#include "rd_sweep.h"

#include <dirent.h>
#include <errno.h>
#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#define CHUNK_FORMAT "ringdyn-sweep-chunk/1"
#define DUMP_FLAGS   (JSON_COMPACT | JSON_REAL_PRECISION(RD_SWEEP_REAL_DIGITS))

/* ---- a growing string ---------------------------------------------------- */

typedef struct {
    char *s;
    size_t len, cap;
    int failed;
} buf;

static void put(buf *b, const char *text, size_t n)
{
    if (b->failed)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->failed = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
    }
    memcpy(b->s + b->len, text, n);
    b->len += n;
    b->s[b->len] = '\0';
}

static void puts_(buf *b, const char *text)
{
    put(b, text, strlen(text));
}

/* The finished string (caller frees), or NULL if anything failed. */
static char *take(buf *b)
{
    if (b->failed || !b->s) {
        free(b->s);
        return NULL;
    }
    return b->s;
}

/* ---- CSV ----------------------------------------------------------------- */

/* One field: quoted when it holds , " CR or LF, quotes doubled. */
static void csv_field(buf *b, const char *text)
{
    if (strpbrk(text, ",\"\r\n") == NULL) {
        puts_(b, text);
        return;
    }
    put(b, "\"", 1);
    for (const char *c = text; *c; c++) {
        put(b, c, 1);
        if (*c == '"')
            put(b, "\"", 1);
    }
    put(b, "\"", 1);
}

static void csv_value(buf *b, json_t *v)
{
    char num[40];
    switch (json_typeof(v)) {
    case JSON_NULL:
        break;
    case JSON_TRUE:
        puts_(b, "true");
        break;
    case JSON_FALSE:
        puts_(b, "false");
        break;
    case JSON_INTEGER:
        snprintf(num, sizeof num, "%" JSON_INTEGER_FORMAT, json_integer_value(v));
        puts_(b, num);
        break;
    case JSON_REAL:
        snprintf(num, sizeof num, "%.*g", RD_SWEEP_REAL_DIGITS, json_real_value(v));
        puts_(b, num);
        break;
    case JSON_STRING:
        csv_field(b, json_string_value(v));
        break;
    default: {
        char *text = json_dumps(v, DUMP_FLAGS);
        if (text)
            csv_field(b, text);
        else
            b->failed = 1;
        free(text);
    }
    }
}

static void csv_record(buf *b, json_t *array)
{
    for (size_t k = 0; k < json_array_size(array); k++) {
        if (k)
            put(b, ",", 1);
        csv_value(b, json_array_get(array, k));
    }
    put(b, "\r\n", 2);
}

char *rd_sweep_csv_record(const char *array_json, rd_error *err)
{
    json_t *a = json_loads(array_json, 0, NULL);
    if (!json_is_array(a)) {
        json_decref(a);
        rd_error_set(err, RD_EINTERNAL, "", "a table row is not a JSON array");
        return NULL;
    }
    buf b = {0};
    csv_record(&b, a);
    json_decref(a);
    char *text = take(&b);
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing CSV");
    return text;
}

/* ---- tables in memory ---------------------------------------------------- */

/* The table from row texts, as JSON (csv == 0) or CSV. */
static char *table(const rd_sweep *s, char *const *rows, size_t n, int csv, rd_error *err)
{
    buf b = {0};
    char *cols = rd_sweep_columns_json(s);
    json_t *c = cols ? json_loads(cols, 0, NULL) : NULL;
    if (csv) {
        csv_record(&b, c);
    } else {
        puts_(&b, "{\"columns\":");
        puts_(&b, cols ? cols : "");
        puts_(&b, ",\"rows\":[");
    }
    int first = 1, bad = 0;
    for (size_t i = 0; i < n && !bad && !b.failed; i++) {
        if (!rows[i])
            continue;
        json_t *r = json_loads(rows[i], 0, NULL);
        bad = !json_is_array(r);
        if (!bad && csv) {
            csv_record(&b, r);
        } else if (!bad) {
            char *text = json_dumps(r, DUMP_FLAGS);
            if (!first)
                put(&b, ",", 1);
            puts_(&b, text ? text : "");
            b.failed |= !text;
            free(text);
        }
        first = 0;
        json_decref(r);
    }
    if (!csv)
        puts_(&b, "]}");
    b.failed |= !c;
    json_decref(c);
    free(cols);
    char *text = take(&b);
    if (bad) {
        free(text);
        text = NULL;
        rd_error_set(err, RD_EINTERNAL, "", "a row is not a JSON array");
    } else if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the sweep table");
    return text;
}

char *rd_sweep_table_json(const rd_sweep *s, char *const *rows, size_t n, rd_error *err)
{
    return table(s, rows, n, 0, err);
}

char *rd_sweep_table_csv(const rd_sweep *s, char *const *rows, size_t n, rd_error *err)
{
    return table(s, rows, n, 1, err);
}

/* ---- chunks -------------------------------------------------------------- */

int rd_sweep_chunk_range(const rd_sweep *s, size_t c, size_t k, size_t *first, size_t *end,
                         rd_error *err)
{
    size_t n = rd_sweep_points(s);
    if (k == 0 || k > n)
        return rd_error_set(err, RD_EREQUEST, "",
                            "--chunks %zu is out of range: allowed 1 to "
                            "%zu (the number of points)",
                            k, n);
    if (c >= k)
        return rd_error_set(err, RD_EREQUEST, "",
                            "--index %zu is out of range: allowed 0 to %zu "
                            "(--chunks - 1)",
                            c, k - 1);
    *first = c * n / k;
    *end = (c + 1) * n / k;
    return RD_OK;
}

char *rd_sweep_chunk_name(size_t c, size_t k)
{
    char *name = malloc(64);
    if (name)
        snprintf(name, 64, "chunk-%06zu-of-%06zu.json", c, k);
    return name;
}

char *rd_sweep_chunk_head(const rd_sweep *s, size_t c, size_t k)
{
    size_t first = 0, end = 0;
    if (rd_sweep_chunk_range(s, c, k, &first, &end, NULL) != RD_OK)
        return NULL;
    char *cols = rd_sweep_columns_json(s);
    if (!cols)
        return NULL;
    buf b = {0};
    char num[320];
    snprintf(num, sizeof num,
             "{\"format\":\"%s\",\"spec_hash\":\"%s\",\"points\":%zu,"
             "\"chunk\":%zu,\"chunks\":%zu,\"first\":%zu,\"end\":%zu,\"columns\":",
             CHUNK_FORMAT, rd_sweep_hash(s), rd_sweep_points(s), c, k, first, end);
    puts_(&b, num);
    puts_(&b, cols);
    puts_(&b, ",\"rows\":[\n");
    free(cols);
    return take(&b);
}

/* ---- reduce -------------------------------------------------------------- */

/* What chunk 0 says; every other chunk must agree. */
typedef struct {
    const char *dir;
    size_t k;                        /* chunks */
    unsigned char *seen;             /* k flags */
    json_t *hash, *points, *columns; /* from chunk 0 (owned references) */
} reduce_state;

static size_t member_size(json_t *obj, const char *key)
{
    json_t *v = json_object_get(obj, key);
    return json_is_integer(v) && json_integer_value(v) >= 0 ? (size_t)json_integer_value(v)
                                                            : (size_t)-1;
}

/* Finds the chunk files of `dir`: one K, flags of the indices present. */
static int scan_dir(reduce_state *st, rd_error *err)
{
    DIR *d = opendir(st->dir);
    if (!d)
        return rd_error_set(err, RD_EREQUEST, "", "cannot read %s: %s", st->dir, strerror(errno));
    struct dirent *e;
    int rc = RD_OK;
    while (rc == RD_OK && (e = readdir(d)) != NULL) {
        size_t c, k;
        char again[64];
        if (sscanf(e->d_name, "chunk-%zu-of-%zu.json", &c, &k) != 2 || k == 0 ||
            k > RD_SWEEP_POINTS_MAX || c >= k)
            continue;
        snprintf(again, sizeof again, "chunk-%06zu-of-%06zu.json", c, k);
        if (strcmp(again, e->d_name) != 0)
            continue;
        if (st->k && st->k != k)
            rc = rd_error_set(err, RD_EINVAL, "",
                              "%s holds chunks of two splits (of %zu and of "
                              "%zu): reduce one sweep per directory",
                              st->dir, st->k, k);
        if (!st->k && (st->seen = calloc(k, 1)) == NULL)
            rc = rd_error_set(err, RD_ENOMEM, "", "out of memory");
        st->k = k;
        if (rc == RD_OK)
            st->seen[c] = 1;
    }
    closedir(d);
    if (rc == RD_OK && !st->k)
        rc = rd_error_set(err, RD_ENOTFOUND, "",
                          "no chunk files (chunk-NNNNNN-of-NNNNNN.json) "
                          "in %s",
                          st->dir);
    return rc;
}

/* All K chunks present, or RD_ENOTFOUND naming (the first 20 of) the rest. */
static int check_complete(const reduce_state *st, rd_error *err)
{
    char list[400] = "";
    size_t missing = 0, at = 0;
    for (size_t c = 0; c < st->k; c++) {
        if (st->seen[c])
            continue;
        if (++missing <= 20 && at < sizeof list)
            at +=
                (size_t)snprintf(list + at, sizeof list - at, "%s%zu", missing > 1 ? ", " : "", c);
    }
    if (missing == 0)
        return RD_OK;
    return rd_error_set(err, RD_ENOTFOUND, "", "%zu of %zu chunks missing in %s: %s%s", missing,
                        st->k, st->dir, list, missing > 20 ? ", ..." : "");
}

/* Loads chunk c and checks it against chunk 0 (which it records). */
static json_t *load_chunk(reduce_state *st, size_t c, rd_error *err)
{
    char *name = rd_sweep_chunk_name(c, st->k);
    size_t size = strlen(st->dir) + 80;
    char *path = malloc(size);
    if (!name || !path) {
        free(name);
        free(path);
        rd_error_set(err, RD_ENOMEM, "", "out of memory");
        return NULL;
    }
    snprintf(path, size, "%s/%s", st->dir, name);
    json_error_t jerr;
    json_t *doc = json_load_file(path, 0, &jerr);
    json_t *rows = json_object_get(doc, "rows");
    size_t n = member_size(doc, "points");
    if (c == 0 && doc && !st->hash) {
        st->hash = json_incref(json_object_get(doc, "spec_hash"));
        st->points = json_incref(json_object_get(doc, "points"));
        st->columns = json_incref(json_object_get(doc, "columns"));
    }
    size_t first = c * n / st->k, end = (c + 1) * n / st->k, ncol = json_array_size(st->columns);
    const char *why =
        !doc ? jerr.text
        : !json_is_string(json_object_get(doc, "format")) ||
                strcmp(json_string_value(json_object_get(doc, "format")), CHUNK_FORMAT) != 0
            ? "it is not a " CHUNK_FORMAT " file"
        : !json_is_string(st->hash) || !json_equal(json_object_get(doc, "spec_hash"), st->hash)
            ? "it comes from another spec than chunk 0 (spec_hash differs)"
        : !json_equal(json_object_get(doc, "points"), st->points) || !json_is_array(st->columns) ||
                !json_equal(json_object_get(doc, "columns"), st->columns)
            ? "its points or columns differ from chunk 0's"
        : member_size(doc, "chunk") != c || member_size(doc, "chunks") != st->k ||
                member_size(doc, "first") != first || member_size(doc, "end") != end
            ? "its chunk, chunks, first or end do not match its name"
        : !json_is_array(rows) || json_array_size(rows) != end - first
            ? "it does not hold one row per point of the chunk"
            : NULL;
    for (size_t i = 0; !why && i < json_array_size(rows); i++)
        if (json_array_size(json_array_get(rows, i)) != ncol)
            why = "a row does not have one cell per column";
    if (why) {
        rd_error_set(err, RD_EINVAL, "", "chunk file %s cannot be used: %s", path, why);
        json_decref(doc);
        doc = NULL;
    }
    free(name);
    free(path);
    return doc;
}

/* Writes the rows of one chunk; `first` says whether a row was written before. */
static int write_rows(json_t *rows, int csv, FILE *out, int *first)
{
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < json_array_size(rows); i++) {
        char *text = NULL;
        if (csv) {
            buf b = {0};
            csv_record(&b, json_array_get(rows, i));
            text = take(&b);
        } else {
            text = json_dumps(json_array_get(rows, i), DUMP_FLAGS);
        }
        rc = !text || (!csv && !*first && fputc(',', out) == EOF) || fputs(text, out) == EOF;
        *first = 0;
        free(text);
    }
    return rc;
}

/* Pass 2: the table, chunk by chunk. */
static int write_table(reduce_state *st, int csv, FILE *out, rd_error *err)
{
    int rc = 0, first = 1;
    if (csv) {
        buf b = {0};
        csv_record(&b, st->columns);
        char *head = take(&b);
        rc = !head || fputs(head, out) == EOF;
        free(head);
    } else {
        char *cols = json_dumps(st->columns, DUMP_FLAGS);
        rc = !cols || fprintf(out, "{\"columns\":%s,\"rows\":[", cols) < 0;
        free(cols);
    }
    for (size_t c = 0; rc == 0 && c < st->k; c++) {
        json_t *doc = load_chunk(st, c, err);
        if (!doc)
            return err->code;
        rc = write_rows(json_object_get(doc, "rows"), csv, out, &first);
        json_decref(doc);
    }
    if (rc == 0 && !csv)
        rc = fputs("]}\n", out) == EOF;
    if (rc == 0)
        rc = fflush(out) != 0;
    return rc ? rd_error_set(err, RD_EREQUEST, "", "cannot write the table: %s", strerror(errno))
              : RD_OK;
}

int rd_sweep_reduce(const char *dir, int csv, FILE *out, rd_error *err)
{
    reduce_state st = {dir, 0, NULL, NULL, NULL, NULL};
    int rc = scan_dir(&st, err);
    if (rc == RD_OK)
        rc = check_complete(&st, err);
    for (size_t c = 0; rc == RD_OK && c < st.k; c++) {
        json_t *doc = load_chunk(&st, c, err);
        rc = doc ? RD_OK : err->code;
        json_decref(doc);
    }
    if (rc == RD_OK)
        rc = write_table(&st, csv, out, err);
    free(st.seen);
    json_decref(st.hash);
    json_decref(st.points);
    json_decref(st.columns);
    return rc;
}

char *rd_sweep_csv_from_table(const char *table_json, rd_error *err)
{
    json_t *t = json_loads(table_json, 0, NULL), *rows = json_object_get(t, "rows");
    json_t *cols = json_object_get(t, "columns");
    if (!json_is_array(cols) || !json_is_array(rows)) {
        json_decref(t);
        rd_error_set(err, RD_EINTERNAL, "", "not a sweep table {\"columns\", \"rows\"}");
        return NULL;
    }
    buf b = {0};
    csv_record(&b, cols);
    for (size_t i = 0; i < json_array_size(rows); i++)
        csv_record(&b, json_array_get(rows, i));
    json_decref(t);
    char *text = take(&b);
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing CSV");
    return text;
}
