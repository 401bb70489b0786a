/*
 * fuzz_files — the files api/ reads, written by the fuzzer: the chunk files
 * of `ringdyn sweep run` that rd_sweep_reduce joins (well formed, or broken
 * one of ten ways), and example directories (rd_api_examples_json,
 * rd_api_example_scene) holding the input or odd files.
 *
 * Each process works in two directories of its own under /tmp, emptied
 * after each use and removed at exit.
 */
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <jansson.h>

#include "fuzz.h"
#include "rd_examples.h"

/* One input in EXAMPLE_EVERY is also written as an example file. */
#define EXAMPLE_EVERY 4

static char chunk_dir[64], example_dir[64];

static void empty_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[512];
    while (d && (e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (remove(path) != 0)
            abort();
    }
    if (d)
        closedir(d);
}

static void remove_dirs(void)
{
    empty_dir(chunk_dir);
    empty_dir(example_dir);
    rmdir(chunk_dir);
    rmdir(example_dir);
}

static void make_dirs(void)
{
    if (chunk_dir[0])
        return;
    snprintf(chunk_dir, sizeof chunk_dir, "/tmp/ringdyn-fuzz-chunks.%ld", (long)getpid());
    snprintf(example_dir, sizeof example_dir, "/tmp/ringdyn-fuzz-examples.%ld", (long)getpid());
    if ((mkdir(chunk_dir, 0700) != 0 && errno != EEXIST) ||
        (mkdir(example_dir, 0700) != 0 && errno != EEXIST) || atexit(remove_dirs) != 0)
        abort();
}

static void write_file(const char *dir, const char *name, const char *text, size_t len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(text, 1, len, f) != len || fclose(f) != 0)
        abort();
}

/* ---- chunks -------------------------------------------------------------- */

/* Chunk c of k holding rows [first, end) (the harness's own writer: the
 * reducer must not depend on ringdyn's). */
static char *chunk_text(const rd_sweep *s, char **rows, size_t c, size_t k)
{
    size_t first, end;
    char *head = rd_sweep_chunk_head(s, c, k);
    if (!head || rd_sweep_chunk_range(s, c, k, &first, &end, NULL) != RD_OK)
        abort();
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        abort();
    fputs(head, f);
    for (size_t i = first; i < end; i++)
        fprintf(f, "%s%s", i > first ? ",\n" : "", rows[i]);
    fputs("]}\n", f);
    if (fclose(f) != 0)
        abort();
    free(head);
    return text;
}

static void write_chunk(const char *text, size_t c, size_t k)
{
    char name[64];
    snprintf(name, sizeof name, "chunk-%06zu-of-%06zu.json", c, k);
    write_file(chunk_dir, name, text, strlen(text));
}

/* The chunk with one member wrong (by h): every one is refused. */
static void write_wrong_member(const char *text, uint32_t h)
{
    json_t *doc = json_loads(text, 0, NULL), *rows = json_object_get(doc, "rows");
    json_t *cols = json_object_get(doc, "columns");
    size_t points = (size_t)json_integer_value(json_object_get(doc, "points"));
    if (!doc)
        abort();
    switch (h % 9) {
    case 0:
        json_object_set_new(doc, "format", json_string("ringdyn-sweep-chunk/0"));
        break;
    case 1:
        json_object_set_new(doc, "points", json_integer((json_int_t)points + 1));
        break;
    case 2:
        json_object_set_new(doc, "chunk", json_integer(1));
        break;
    case 3:
        json_object_set_new(doc, "first", json_integer(1));
        break;
    case 4:
        json_object_set_new(doc, "end", json_integer((json_int_t)points + 1));
        break;
    case 5:
        json_array_append_new(cols, json_string("extra"));
        break;
    case 6:
        json_array_remove(rows, json_array_size(rows) - 1);
        break;
    case 7:
        json_array_append_new(json_array_get(rows, 0), json_null());
        break;
    default:
        json_object_set_new(doc, "rows", json_string("none"));
    }
    char *out = json_dumps(doc, JSON_COMPACT);
    if (!out)
        abort();
    write_chunk(out, 0, 1);
    free(out);
    json_decref(doc);
}

/* Writes the chunk files of case `h % 12`; *ok: 1 the reduction must
 * succeed, 0 fail, 2 either (a write budget the table may fit in).  Returns
 * the sink's write budget (SIZE_MAX: no write failure). */
static size_t write_case(const rd_sweep *s, char **rows, size_t m, uint32_t h, int *ok)
{
    char *one = chunk_text(s, rows, 0, 1);
    size_t len = strlen(one), budget = SIZE_MAX;
    *ok = 0;
    switch (h % 12) {
    case 0: /* a hash of the other spec in chunk 1 (with one point: a corrupt file) */
        if (m == 2) {
            char *c0 = chunk_text(s, rows, 0, 2), *c1 = chunk_text(s, rows, 1, 2);
            char *hash = strstr(c1, "\"spec_hash\":\"") + 13;
            *hash = *hash == '0' ? '1' : '0';
            write_chunk(c0, 0, 2);
            write_chunk(c1, 1, 2);
            free(c0);
            free(c1);
            break;
        }
        /* fall through */
    case 1: /* truncated (never after the last bracket) */
        write_file(chunk_dir, "chunk-000000-of-000001.json", one, (h >> 8) % (len - 2));
        break;
    case 2: /* a chunk missing */
        write_chunk(one, 0, 2);
        break;
    case 3:
        write_wrong_member(one, h >> 8);
        break;
    case 4: /* two splits in one directory */
        write_chunk(one, 0, 1);
        write_chunk(one, 0, 3);
        break;
    case 5: /* none (and names that only look like chunks) */
        write_file(chunk_dir, "chunk-0-of-1.json", one, len);
        write_file(chunk_dir, "notes.txt", "x", 1);
        break;
    case 6: /* the table's writes fail after some bytes */
        write_chunk(one, 0, 1);
        budget = (h >> 8) % (len + 1);
        *ok = 2;
        break;
    case 7: /* split in two */
        if (m == 2) {
            char *c0 = chunk_text(s, rows, 0, 2), *c1 = chunk_text(s, rows, 1, 2);
            write_chunk(c0, 0, 2);
            write_chunk(c1, 1, 2);
            free(c0);
            free(c1);
            *ok = 1;
            break;
        }
        /* fall through */
    default: /* (case 8: read from a directory that does not exist) */
        write_chunk(one, 0, 1);
        write_file(chunk_dir, ".chunk-000000-of-000002.json", "{", 1);
        *ok = h % 12 != 8;
    }
    free(one);
    return budget;
}

void fuzz_files_reduce(const rd_sweep *sweep, char **rows, size_t m, const char *csv,
                       const char *table_json, uint32_t h)
{
    int armed = fuzz_fail_pause(); /* only the reducer's allocations may fail */
    make_dirs();
    int ok, as_csv = (h >> 4) % 2;
    size_t budget = write_case(sweep, rows, m, h, &ok);
    fuzz_sink sink;
    FILE *out = fuzz_sink_open(&sink, budget);
    rd_error err;
    rd_error_init(&err);
    fuzz_fail_resume(armed);
    int rc = rd_sweep_reduce(h % 12 == 8 ? "/nonexistent/ringdyn" : chunk_dir, as_csv, out, &err);
    fuzz_fail_pause();
    fclose(out);
    empty_dir(chunk_dir);
    /* csv NULL: a failure was injected, any refusal with a message will do */
    if (rc != RD_OK ? !err.message[0] || (csv && ok == 1) : csv && !ok)
        abort();
    if (csv && rc == RD_OK) {
        size_t n = strlen(table_json);
        const char *want = as_csv ? csv : table_json;
        if (rc != RD_OK || !sink.text || strncmp(sink.text, want, n) ||
            strcmp(sink.text + strlen(want), as_csv ? "" : "\n"))
            abort();
    }
    free(sink.text);
    fuzz_fail_resume(armed);
}

/* ---- examples ------------------------------------------------------------ */

/* Lists and reads `dir`: the listing succeeds exactly when `valid`, and
 * then example `name` reads back as a scene. */
static void check_examples(const char *dir, const char *name, int valid)
{
    rd_error err;
    rd_error_init(&err);
    char *list = rd_api_examples_json(dir, &err);
    if (!list != !valid || (!list && !err.message[0]))
        abort();
    rd_error_init(&err);
    char *text = rd_api_example_scene(dir, name, &err);
    rd_scene *scene = NULL;
    if (!text != !valid || (!text && !err.message[0]) ||
        (text && rd_scene_parse(text, strlen(text), &scene, &err) != RD_OK))
        abort();
    rd_scene_free(scene);
    free(text);
    free(list);
}

void fuzz_files_example(const uint8_t *data, size_t size)
{
    if (fuzz_hash(data, size, 8) % EXAMPLE_EVERY)
        return;
    make_dirs();
    rd_scene *scene = NULL;
    rd_error err;
    rd_error_init(&err);
    int valid = rd_scene_parse((const char *)data, size, &scene, &err) == RD_OK;
    rd_scene_free(scene);
    write_file(example_dir, "fuzz.json", (const char *)data, size);
    check_examples(example_dir, "fuzz", valid);
    empty_dir(example_dir);
}

/* Every allocation of listing a small catalogue failing in turn. */
static void fail_each_allocation(const char *dir)
{
    fuzz_fail_arm(0);
    check_examples(dir, "a", 1);
    size_t n = fuzz_fail_disarm();
    for (size_t k = 1; k <= n; k++) {
        rd_error err;
        rd_error_init(&err);
        fuzz_fail_arm(k);
        char *list = rd_api_examples_json(dir, &err);
        char *text = rd_api_example_scene(dir, "a", &err);
        fuzz_fail_disarm();
        if ((!list || !text) && rd_api_http_status(err.code) < 500)
            abort();
        free(list);
        free(text);
    }
}

void fuzz_files_init(void)
{
    for (int code = RD_ETIMEOUT; code <= RD_OK; code++)
        if (rd_api_http_status(code) < 200 || rd_api_http_status(code) > 599 ||
            (code != RD_OK) != (rd_api_http_status(code) >= 400))
            abort();
    rd_api_http_status(1); /* not a code: still a status */
    make_dirs();
    const char *scene = "{\"analysis\":\"modal\",\"description\":\"d\"}";
    write_file(example_dir, "a.json", scene, strlen(scene));
    write_file(example_dir, "b.json", scene, strlen(scene));
    fail_each_allocation(example_dir);
    /* More names than the first list holds, hidden files, other files, a
     * directory and a dangling link named *.json: all skipped. */
    char name[32];
    for (int i = 0; i < 18; i++) {
        snprintf(name, sizeof name, "e%02d.json", i);
        write_file(example_dir, name, scene, strlen(scene));
    }
    write_file(example_dir, ".hidden.json", "{", 1);
    write_file(example_dir, "readme.txt", "x", 1);
    char path[512];
    snprintf(path, sizeof path, "%s/sub.json", example_dir);
    if (mkdir(path, 0700) != 0)
        abort();
    snprintf(path, sizeof path, "%s/gone.json", example_dir);
    if (symlink("/nonexistent/x.json", path) != 0)
        abort();
    check_examples(example_dir, "e17", 1);
    rd_error err;
    rd_error_init(&err);
    if (rd_api_example_scene(example_dir, "sub", &err) || err.code != RD_ENOTFOUND)
        abort();
    rd_error_init(&err);
    if (rd_api_example_scene(example_dir, "gone", &err) || err.code != RD_ENOTFOUND)
        abort();
    /* Files that are no example: each makes the listing fail. */
    static const char *const bad[][3] = {{"bad name.json", "bad", "{}"},
                                         {"j.json", "j", "{"},
                                         {"s.json", "s", "{\"analysis\":\"x\"}"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_file(example_dir, bad[i][0], bad[i][2], strlen(bad[i][2]));
        check_examples(example_dir, bad[i][1], 0);
        snprintf(path, sizeof path, "%s/%s", example_dir, bad[i][0]);
        remove(path);
    }
    char *big = malloc(RD_EXAMPLE_FILE_MAX + 2);
    if (!big)
        abort();
    memset(big, ' ', RD_EXAMPLE_FILE_MAX + 1);
    write_file(example_dir, "big.json", big, RD_EXAMPLE_FILE_MAX + 1);
    free(big);
    check_examples(example_dir, "big", 0);
    empty_dir(example_dir);
    check_examples("/nonexistent/ringdyn", "a", 0);
}
