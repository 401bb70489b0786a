/*
 * fuzz_fail — allocation failures injected into the code under test, so
 * that its out-of-memory branches (`if (!x)` after every malloc, calloc,
 * realloc, strdup and jansson constructor) are taken and checked.
 *
 * How: the fuzzer is linked with -Wl,--wrap for malloc, calloc, realloc,
 * strdup and strndup (tests/fuzz/CMakeLists.txt), so every call of api/,
 * core/ and the harness reaches the __wrap_ functions below; jansson's
 * allocations come through json_set_alloc_funcs.  While armed, each
 * allocation is counted and the k-th and every later one return NULL
 * (memory that ran out stays out), except inside jansson's parser (see
 * __wrap_json_loads).  Allocations inside other libraries (libc's own,
 * LAPACK, SUNDIALS) are not counted.
 *
 * The pass (fuzz_fail_pass), after the ordinary checks of an input: each
 * step (a group of api/ calls on the input) runs once counting its
 * allocations n, then again with the allocations from k = 1 + hash % n on
 * failing.  What must hold for a step whose allocations failed: no crash,
 * leak or UB (ASan); either the same outcome as without the failure (status, message
 * and texts; a text may be NULL, each writer's out-of-memory answer), or an
 * error whose HTTP status is 5xx (out of memory, internal error) with a
 * message: an allocation failure must never pass for the client's mistake
 * (4xx) nor change an accepted scene.  When nothing failed (the step
 * allocated less than k this time), nothing may differ.  One input in
 * FAIL_SKIP has no pass, so part of the fuzzer's time still goes to the
 * normal paths alone.
 */
#define _GNU_SOURCE /* fopencookie */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <errno.h>
#include <jansson.h>

#include "fuzz.h"
#include "rd_scene_facts.h"
#include "rd_sweep_request.h"
#include "rd_warnings.h"

#define FAIL_SKIP      4
#define RUN_FAIL_EVERY 4
#define OPENAPI_FAILS  40 /* failure points spread over the OpenAPI document's allocations */

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t n);
char *__real_strdup(const char *s);
char *__real_strndup(const char *s, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t n);
char *__wrap_strdup(const char *s);
char *__wrap_strndup(const char *s, size_t n);

static struct {
    int armed, fired, enabled, in_parser, in_writer, writer_failed;
    size_t k, count;
} fail;

/* jansson's parser and writer, wrapped the same way (-Wl,--wrap) so the
 * counter knows when it is inside them.  The parser's allocations never
 * fail: jansson 2.14 aborts on an assertion (load.c, lex_unget_unsave)
 * when one fails mid-token, and reports others as a syntax error of the
 * text ("invalid token near ..."), so neither api/ nor a client could tell
 * them from a bad body.  The writer's may fail, but it ignores a failure to
 * write an object's key (dump.c: dump_string's result unchecked) and may
 * then return invalid JSON: a text it wrote after a failure is not
 * compared. */
json_t *__real_json_loads(const char *input, size_t flags, json_error_t *error);
json_t *__real_json_loadb(const char *buffer, size_t buflen, size_t flags, json_error_t *error);
json_t *__real_json_load_file(const char *path, size_t flags, json_error_t *error);
char *__real_json_dumps(const json_t *json, size_t flags);
json_t *__wrap_json_loads(const char *input, size_t flags, json_error_t *error);
json_t *__wrap_json_loadb(const char *buffer, size_t buflen, size_t flags, json_error_t *error);
json_t *__wrap_json_load_file(const char *path, size_t flags, json_error_t *error);
char *__wrap_json_dumps(const json_t *json, size_t flags);

json_t *__wrap_json_loads(const char *input, size_t flags, json_error_t *error)
{
    fail.in_parser++;
    json_t *v = __real_json_loads(input, flags, error);
    fail.in_parser--;
    return v;
}

json_t *__wrap_json_loadb(const char *buffer, size_t buflen, size_t flags, json_error_t *error)
{
    fail.in_parser++;
    json_t *v = __real_json_loadb(buffer, buflen, flags, error);
    fail.in_parser--;
    return v;
}

json_t *__wrap_json_load_file(const char *path, size_t flags, json_error_t *error)
{
    fail.in_parser++;
    json_t *v = __real_json_load_file(path, flags, error);
    fail.in_parser--;
    return v;
}

char *__wrap_json_dumps(const json_t *json, size_t flags)
{
    fail.in_writer++;
    char *t = __real_json_dumps(json, flags);
    fail.in_writer--;
    return t;
}

/* 1 when this allocation fails: the k-th and every one after it (memory
 * that ran out stays out), except inside jansson's parser. */
static int failing(void)
{
    if (!fail.armed || fail.in_parser || ++fail.count < fail.k || !fail.k)
        return 0;
    fail.writer_failed |= fail.in_writer > 0;
    fail.fired = 1;
    errno = ENOMEM;
    return 1;
}

void *__wrap_malloc(size_t n)
{
    return failing() ? NULL : __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t size)
{
    return failing() ? NULL : __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t n)
{
    return failing() ? NULL : __real_realloc(p, n);
}

char *__wrap_strdup(const char *s)
{
    return failing() ? NULL : __real_strdup(s);
}

char *__wrap_strndup(const char *s, size_t n)
{
    return failing() ? NULL : __real_strndup(s, n);
}

static void *json_alloc(size_t n)
{
    return failing() ? NULL : __real_malloc(n);
}

void fuzz_fail_init(void)
{
    json_set_alloc_funcs(json_alloc, free);
    const char *mode = getenv("RINGDYN_FUZZ_FAIL");
    fail.enabled = !(mode && !strcmp(mode, "0"));
}

void fuzz_fail_arm(size_t k)
{
    fail.armed = 1;
    fail.fired = 0;
    fail.writer_failed = 0;
    fail.k = k;
    fail.count = 0;
}

size_t fuzz_fail_disarm(void)
{
    fail.armed = 0;
    return fail.count;
}

int fuzz_fail_fired(void)
{
    return fail.fired;
}

int fuzz_fail_pause(void)
{
    int armed = fail.armed;
    fail.armed = 0;
    return armed;
}

void fuzz_fail_resume(int armed)
{
    fail.armed = armed;
}

/* ---- a stream whose writes fail after a budget ---------------------------- */

static ssize_t sink_write(void *cookie, const char *buf, size_t n)
{
    fuzz_sink *s = cookie;
    if (s->len + n > s->budget)
        return 0; /* fopencookie: 0 is a write error */
    if (s->len + n + 1 > s->cap) {
        size_t cap = 2 * (s->len + n + 1);
        char *t = __real_realloc(s->text, cap); /* the harness's, never failed */
        if (!t)
            abort();
        s->text = t;
        s->cap = cap;
    }
    memcpy(s->text + s->len, buf, n);
    s->len += n;
    s->text[s->len] = '\0';
    return (ssize_t)n;
}

FILE *fuzz_sink_open(fuzz_sink *sink, size_t budget)
{
    *sink = (fuzz_sink){NULL, 0, 0, budget};
    cookie_io_functions_t io = {NULL, sink_write, NULL, NULL};
    FILE *f = fopencookie(sink, "w", io);
    if (!f || setvbuf(f, NULL, _IONBF, 0) != 0)
        abort();
    return f;
}

/* ---- the pass ------------------------------------------------------------ */

/* What a step gives: its status, error and up to four texts. */
typedef struct outcome {
    int rc;
    rd_error err;
    char *text[4];
} outcome;

/* The scene parse: echo and canonical text, or the refusal's reports. */
static void step_scene(const char *body, size_t len, outcome *o)
{
    rd_scene *scene = NULL;
    char *report = NULL;
    o->rc = rd_scene_parse_report(body, len, &scene, &o->err, &report);
    if (o->rc == RD_OK) {
        o->text[0] = rd_scene_to_json(scene);
        o->text[1] = rd_scene_canonical_json(scene);
        rd_scene_free(scene);
        return;
    }
    o->text[2] = report;
    o->text[3] = rd_api_error_json(&o->err);
}

/* The body as a sweep request: its columns, their CSV record, point 0. */
static void step_sweep(const char *body, size_t len, outcome *o)
{
    rd_sweep_request req = {0};
    o->rc = rd_sweep_request_parse(body, len, 64, &req, &o->err);
    if (o->rc != RD_OK)
        return;
    o->text[0] = rd_sweep_columns_json(req.sweep);
    rd_error err;
    rd_error_init(&err);
    o->text[1] = o->text[0] ? rd_sweep_csv_record(o->text[0], &err) : NULL;
    rd_error_init(&err);
    o->text[2] = rd_sweep_point_scene(req.sweep, 0, &err);
    rd_sweep_request_cleanup(&req);
}

/* The body as text api/ reads back (a stored result, a sweep table): the
 * server only gives them its own texts, but they must not trust them. */
static void step_texts(const char *body, size_t len, outcome *o)
{
    char *text = __real_strndup(body, len); /* the harness's, never failed */
    if (!text)
        abort();
    rd_error err;
    rd_error_init(&err);
    o->text[0] = rd_api_result_csv(text, &err);
    rd_error_init(&err);
    o->text[1] = rd_sweep_csv_from_table(text, &err);
    rd_error_init(&err);
    o->text[2] = rd_sweep_fidelity_table(text, &err);
    o->text[3] = rd_api_json_pretty(text);
    free(text);
    o->rc = RD_OK;
}

/* The warnings of a made-up result of the scene (fuzz_result_of). */
static void step_warnings(const char *body, size_t len, outcome *o)
{
    rd_scene *scene = NULL;
    o->rc = rd_scene_parse(body, len, &scene, &o->err);
    char *echo = o->rc == RD_OK ? rd_scene_to_json(scene) : NULL;
    json_t *r = echo ? fuzz_result_of(echo, fuzz_hash((const uint8_t *)body, len, 10)) : NULL;
    if (o->rc == RD_OK && (!r || rd_warnings_add(r) != 0))
        o->rc = rd_error_set(&o->err, RD_ENOMEM, "", "out of memory");
    o->text[0] = o->rc == RD_OK ? json_dumps(r, JSON_COMPACT) : NULL;
    json_decref(r);
    free(echo);
    rd_scene_free(scene);
}

/* A clamped run of the scene (outcomes depend on the CPU budget: only the
 * contract of a failure is checked, not the texts). */
static void step_run(const char *small, size_t len, outcome *o)
{
    rd_scene *scene = NULL;
    rd_result_doc *doc = NULL;
    o->rc = rd_scene_parse(small, len, &scene, &o->err);
    double deadline;
    rd_monitor mon = fuzz_budget(&deadline);
    if (o->rc == RD_OK)
        o->rc = rd_scene_run_doc(scene, &mon, &doc, &o->err);
    if (doc) {
        rd_error err;
        rd_error_init(&err);
        o->text[0] = rd_result_doc_json(doc);
        o->text[1] = rd_result_doc_csv(doc, &err);
        rd_error_init(&err);
        o->text[2] = o->text[0] ? rd_api_result_csv(o->text[0], &err) : NULL;
        rd_result_doc_free(doc);
    }
    rd_scene_free(scene);
}

/* A sweep's first two points, their table in every form, its chunks. */
static void step_table(const char *body, size_t len, outcome *o)
{
    rd_sweep_request req = {0};
    o->rc = rd_sweep_request_parse(body, len, 64, &req, &o->err);
    if (o->rc != RD_OK)
        return;
    char *rows[2];
    size_t n = rd_sweep_points(req.sweep), m = fuzz_sweep_rows(&req, rows);
    rd_error err;
    int all = m > 0 && rows[0] && (m < 2 || rows[1]);
    rd_error_init(&err);
    o->text[0] = all ? rd_sweep_table_json(req.sweep, rows, m, &err) : NULL;
    rd_error_init(&err);
    o->text[1] = all ? rd_sweep_table_csv(req.sweep, rows, m, &err) : NULL;
    rd_error_init(&err);
    o->text[2] = o->text[0] && req.fidelity ? rd_sweep_fidelity_table(o->text[0], &err) : NULL;
    if (o->text[0] && o->text[1] && n == m)
        fuzz_files_reduce(req.sweep, rows, m, NULL, NULL, fuzz_hash((const uint8_t *)body, len, 5));
    for (size_t i = 0; i < m; i++)
        free(rows[i]);
    rd_sweep_request_cleanup(&req);
}

static void outcome_free(outcome *o)
{
    for (size_t i = 0; i < 4; i++)
        free(o->text[i]);
}

static int same_text(const char *a, const char *b)
{
    return (!a && !b) || (a && b && !strcmp(a, b));
}

/* A broken contract: what the step gave with and without the failure,
 * then abort (a finding). */
static void finding(const char *step, const char *why, const outcome *clean, const outcome *hurt)
{
    fprintf(stderr,
            "fuzz_fail: step %s, allocation %zu of %zu failing%s: %s\n"
            "  without: %d %s\n  with:    %d %s\n",
            step, fail.k, fail.count, fail.writer_failed ? " (also in jansson's writer)" : "", why,
            clean->rc, clean->err.message, hurt->rc, hurt->err.message);
    for (size_t i = 0; i < 4; i++)
        if (!same_text(clean->text[i], hurt->text[i]))
            fprintf(stderr, "  text %zu without: %.300s\n  text %zu with:    %.300s\n", i,
                    clean->text[i] ? clean->text[i] : "(null)", i,
                    hurt->text[i] ? hurt->text[i] : "(null)");
    abort();
}

/* The contract of a step whose k-th allocation failed (see the top). */
static void compare(const char *step, const outcome *clean, const outcome *hurt, int exact)
{
    if (!fuzz_fail_fired()) { /* nothing failed: nothing may differ */
        if (exact && (hurt->rc != clean->rc || strcmp(hurt->err.message, clean->err.message)))
            finding(step, "no allocation failed, yet the outcome differs", clean, hurt);
        for (size_t i = 0; exact && i < 4; i++)
            if (!same_text(hurt->text[i], clean->text[i]))
                finding(step, "no allocation failed, yet a text differs", clean, hurt);
        return;
    }
    if (hurt->rc != RD_OK && (hurt->err.code != hurt->rc || !hurt->err.message[0]))
        finding(step, "an error without its record", clean, hurt);
    if (hurt->rc != clean->rc || (exact && strcmp(hurt->err.message, clean->err.message))) {
        if (hurt->rc == RD_OK || rd_api_http_status(hurt->rc) < 500)
            finding(step, "an allocation failure changed the outcome, not to a 5xx", clean, hurt);
        return;
    }
    for (size_t i = 0; exact && i < 4; i++) {
        const char *t = hurt->text[i];
        if (!t || same_text(t, clean->text[i]) || fail.writer_failed)
            continue;
        /* The refusal's report may lose its "errors" list (rd_scene_parse_report):
         * still an error body. */
        json_t *j = i == 2 ? json_loads(t, 0, NULL) : NULL;
        int body = json_is_object(json_object_get(j, "error"));
        json_decref(j);
        if (!body)
            finding(step, "a text changed (neither the same nor NULL)", clean, hurt);
    }
}

typedef void (*step_fn)(const char *body, size_t len, outcome *o);

/* One step: counted, then with the k-th allocation failing. */
static void run_step(const char *name, step_fn step, const char *body, size_t len, uint32_t h,
                     int exact)
{
    outcome clean = {0}, hurt = {0};
    rd_error_init(&clean.err);
    rd_error_init(&hurt.err);
    fuzz_fail_arm(0);
    step(body, len, &clean);
    size_t n = fuzz_fail_disarm();
    if (n > 0) {
        fuzz_fail_arm(1 + h % n);
        step(body, len, &hurt);
        fuzz_fail_disarm();
        compare(name, &clean, &hurt, exact);
    }
    outcome_free(&clean);
    outcome_free(&hurt);
}

void fuzz_fail_openapi(const char *tmpl)
{
    rd_error err;
    rd_error_init(&err);
    fuzz_fail_arm(0);
    char *clean = rd_api_openapi_json(tmpl, &err);
    size_t n = fuzz_fail_disarm();
    for (size_t i = 0; fail.enabled && clean && i < OPENAPI_FAILS; i++) {
        rd_error_init(&err);
        fuzz_fail_arm(1 + i * n / OPENAPI_FAILS);
        char *text = rd_api_openapi_json(tmpl, &err);
        fuzz_fail_disarm();
        if (text ? strcmp(text, clean) && !fail.writer_failed
                 : rd_api_http_status(err.code) < 500 || !err.message[0])
            abort();
        free(text);
    }
    free(clean);
}

void fuzz_fail_pass(const uint8_t *data, size_t size, int ran)
{
    uint32_t h = fuzz_hash(data, size, 1);
    if (!fail.enabled || h % FAIL_SKIP == 0)
        return;
    const char *body = (const char *)data;
    run_step("scene", step_scene, body, size, fuzz_hash(data, size, 2), 1);
    run_step("sweep", step_sweep, body, size, fuzz_hash(data, size, 3), 1);
    run_step("texts", step_texts, body, size, fuzz_hash(data, size, 4), 1);
    run_step("warnings", step_warnings, body, size, fuzz_hash(data, size, 11), 1);
    /* A run costs a hundred parses or more: one ran input in RUN_FAIL_EVERY
     * runs again (twice: counted, then failing). */
    if (!ran || fuzz_hash(data, size, 12) % RUN_FAIL_EVERY)
        return;
    char *small = fuzz_clamped(body, size);
    if (small) {
        run_step("run", step_run, small, strlen(small), fuzz_hash(data, size, 6), 0);
        free(small);
    }
    run_step("table", step_table, body, size, fuzz_hash(data, size, 7), 0);
}
