/*
 * fuzz_scene — libFuzzer harness of the scene parser, rd_scene_parse
 * (api/rd_api.h), with a structure-aware mutator.
 *
 * Each input is a request body.  The harness checks what must hold for every
 * body, valid or not: no crash, leak or undefined behaviour (ASan, UBSan);
 * a refusal carries a status, a message and a path that is empty or a JSON
 * Pointer, and rd_api_error_json turns it into valid JSON; an accepted scene
 * names its analysis and echoes as a JSON object.  A violation aborts (a
 * finding).
 *
 * The mutator (LLVMFuzzerCustomMutator) parses the input as JSON and changes
 * its structure: a field's value to a boundary number, another JSON type or
 * an enum word of the schema; a key removed or one of the schema's keys
 * added; "analysis" switched; an array grown or shrunk.  Byte-level
 * mutations alone rarely keep a body valid JSON, so they would stop at the
 * JSON parser and never reach the range checks behind it.  One mutation in
 * eight is libFuzzer's own byte mutation, which keeps the JSON syntax
 * errors covered.  The schema's key and enum words below are facts of
 * server/openapi.json.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <jansson.h>

#include "rd_api.h"
#include "rd_sweep.h"
#include "rd_sweep_request.h"

size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed);

static const char *const keys[] = {"base",
                                   "parameters",
                                   "path",
                                   "values",
                                   "range",
                                   "start",
                                   "stop",
                                   "count",
                                   "scale",
                                   "integer",
                                   "combine",
                                   "outputs",
                                   "samples",
                                   "seed",
                                   "min",
                                   "max",
                                   "fidelity",
                                   "models",
                                   "above",
                                   "active_area",
                                   "amplitude",
                                   "analysis",
                                   "atol",
                                   "axial_clearance",
                                   "axial_height",
                                   "behind",
                                   "below",
                                   "bore",
                                   "closed",
                                   "closed_gap",
                                   "coefficient",
                                   "contact",
                                   "crank_deg",
                                   "crank_radius",
                                   "cycles",
                                   "density",
                                   "description",
                                   "diameter",
                                   "discretization",
                                   "distortion",
                                   "engine",
                                   "error_estimate",
                                   "friction",
                                   "gas",
                                   "gravity",
                                   "groove",
                                   "hydrodynamic_slope",
                                   "kinematics",
                                   "lateral_force",
                                   "material",
                                   "max_iterations",
                                   "max_steps",
                                   "method",
                                   "modal",
                                   "model",
                                   "modes",
                                   "name",
                                   "numerics",
                                   "order",
                                   "output",
                                   "phase_deg",
                                   "physics",
                                   "points_per_segment",
                                   "poisson_ratio",
                                   "pretension",
                                   "radial_clearance",
                                   "radial_width",
                                   "ring",
                                   "rod_length",
                                   "rtol",
                                   "section",
                                   "segments",
                                   "sommerfeld_transition",
                                   "speed_rpm",
                                   "step_deg",
                                   "stiffness",
                                   "tangential_force",
                                   "tolerance",
                                   "viscosity",
                                   "youngs_modulus"};

static const char *const words[] = {"modal",
                                    "pretension",
                                    "contact",
                                    "lift",
                                    "rectangle",
                                    "circle",
                                    "force",
                                    "field",
                                    "coulomb",
                                    "stribeck",
                                    "fixed",
                                    "dynamic",
                                    "exact",
                                    "approximate",
                                    "product",
                                    "zip",
                                    "latin_hypercube",
                                    "random",
                                    "log",
                                    "linear",
                                    "/discretization/segments",
                                    "/ring/diameter",
                                    "/modes/0/frequency_hz",
                                    "max(/modes/*/frequency_hz)",
                                    "mean(/lift)",
                                    "count(/modes)",
                                    "/numerics/wall_s",
                                    ""};

/* Boundaries of the schema's ranges and of the number types. */
static const double numbers[] = {
    0,       -0.0,  1,     -1,    2,      3,     4,        0.5,          1e-5,
    1e-7,    1e-12, 1e-13, 1e-16, 1e-300, 1e300, -1e300,   0.001,        0.005,
    0.01,    5,     10,    16,    17,     20,    50,       60,           61,
    64,      65,    90,    360,   -360,   1000,  1001,     2000,         2001,
    30000,   1e5,   1e6,   1e12,  1e15,   1e20,  4.9e-324, 2147483648.0, 9007199254740993.0,
    0.499999};

static const json_int_t integers[] = {0,
                                      1,
                                      -1,
                                      2,
                                      3,
                                      4,
                                      5,
                                      16,
                                      17,
                                      20,
                                      59,
                                      60,
                                      61,
                                      64,
                                      65,
                                      99,
                                      100,
                                      1000,
                                      1001,
                                      1999,
                                      2000,
                                      2001,
                                      100000,
                                      100001,
                                      2147483647,
                                      -2147483648LL,
                                      1000000000,
                                      1000000001,
                                      9007199254740993LL};

struct rng {
    uint64_t s;
};

static uint64_t next(struct rng *r)
{
    r->s ^= r->s << 13;
    r->s ^= r->s >> 7;
    r->s ^= r->s << 17;
    return r->s;
}

static size_t pick(struct rng *r, size_t n)
{
    return (size_t)(next(r) % n);
}

/* Every value of the document, with where it hangs (parent and key/index). */
struct slot {
    json_t *parent; /* NULL for the root */
    const char *key;
    size_t index;
    json_t *value;
};

struct slots {
    struct slot v[512];
    size_t n;
};

static void collect(json_t *parent, const char *key, size_t index, json_t *value, struct slots *s)
{
    if (s->n == sizeof s->v / sizeof s->v[0])
        return;
    s->v[s->n++] = (struct slot){parent, key, index, value};
    if (json_is_object(value)) {
        const char *k;
        json_t *child;
        json_object_foreach(value, k, child) collect(value, k, 0, child, s);
    } else if (json_is_array(value)) {
        size_t i;
        json_t *child;
        json_array_foreach(value, i, child) if (i < 8) collect(value, NULL, i, child, s);
    }
}

static json_t *random_value(struct rng *r)
{
    switch (pick(r, 9)) {
    case 0:
        return json_null();
    case 1:
        return json_boolean(pick(r, 2));
    case 2:
        return json_string(words[pick(r, sizeof words / sizeof words[0])]);
    case 3:
        return json_object();
    case 4:
        return json_array();
    case 5:
        return json_integer(integers[pick(r, sizeof integers / sizeof integers[0])]);
    default:
        return json_real(numbers[pick(r, sizeof numbers / sizeof numbers[0])]);
    }
}

/* Replaces the slot's value (consumes `v`); the root stays. */
static void replace(struct slot *s, json_t *v)
{
    if (!v)
        return;
    if (!s->parent)
        json_decref(v);
    else if (json_is_object(s->parent))
        json_object_set_new(s->parent, s->key, v);
    else
        json_array_set_new(s->parent, s->index, v);
}

static json_t *tweak_number(struct rng *r, double x)
{
    switch (pick(r, 6)) {
    case 0:
        return json_real(x * 10);
    case 1:
        return json_real(x / 10);
    case 2:
        return json_real(-x);
    case 3:
        return json_real(nextafter(x, INFINITY));
    case 4:
        return json_real(nextafter(x, -INFINITY));
    default:
        return json_real(x + 0.5); /* an integer field given a fraction */
    }
}

/* A numeric table of n points (the lift's gas tables). */
static json_t *table(struct rng *r)
{
    json_t *a = json_array();
    size_t n = pick(r, 4) == 0 ? 1 + pick(r, 2000) : pick(r, 6);
    double x = numbers[pick(r, 20)];
    for (size_t i = 0; a && i < n; i++)
        json_array_append_new(
            a, json_real(x += (pick(r, 8) == 0 ? -1.0 : 1.0) * (double)(1 + pick(r, 90))));
    return a;
}

static void mutate(json_t *root, struct rng *r)
{
    struct slots s;
    s.n = 0;
    collect(NULL, NULL, 0, root, &s);
    struct slot *at = &s.v[pick(r, s.n)];
    switch (pick(r, 8)) {
    case 0: /* a boundary number */
        replace(at, json_real(numbers[pick(r, sizeof numbers / sizeof numbers[0])]));
        break;
    case 1:
        replace(at, json_is_number(at->value) ? tweak_number(r, json_number_value(at->value))
                                              : random_value(r));
        break;
    case 2: /* drop a key */
        if (at->parent && json_is_object(at->parent))
            json_object_del(at->parent, at->key);
        break;
    case 3: { /* add a schema key to some object */
        json_t *obj = json_is_object(at->value)
                          ? at->value
                          : (at->parent && json_is_object(at->parent) ? at->parent : root);
        const char *key = keys[pick(r, sizeof keys / sizeof keys[0])];
        json_t *v = pick(r, 3) == 0 ? json_object() : random_value(r);
        if (v && pick(r, 4) == 0 && json_is_object(v))
            json_object_set_new(v, keys[pick(r, sizeof keys / sizeof keys[0])], random_value(r));
        json_object_set_new(obj, key, v);
        break;
    }
    case 4:
        json_object_set_new(root, "analysis", json_string(words[pick(r, 5)]));
        break;
    case 5: /* an enum word where a string was */
        replace(at, json_string(words[pick(r, sizeof words / sizeof words[0])]));
        break;
    case 6: /* arrays: grow, shrink, or a whole table */
        if (json_is_array(at->value) && json_array_size(at->value) > 0 && pick(r, 2))
            json_array_append(at->value,
                              json_array_get(at->value, pick(r, json_array_size(at->value))));
        else if (json_is_array(at->value) && json_array_size(at->value) > 0)
            json_array_remove(at->value, pick(r, json_array_size(at->value)));
        else
            replace(at, table(r));
        break;
    default: { /* a distortion order list, the contact's own array */
        json_t *d = json_array();
        size_t n = pick(r, 20);
        for (size_t i = 0; d && i < n; i++)
            json_array_append_new(d, json_pack("{s:I, s:f}", "order", (json_int_t)(1 + pick(r, 70)),
                                               "amplitude", numbers[pick(r, 20)] * 1e-4));
        json_t *bore = json_object_get(root, "bore");
        if (!json_is_object(bore)) {
            bore = json_object();
            json_object_set_new(root, "bore", bore);
        }
        json_object_set_new(bore, "distortion", d);
        break;
    }
    }
}

size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed)
{
    struct rng r = {(uint64_t)seed * 0x9E3779B97F4A7C15ull + 1};
    json_t *root = pick(&r, 8) == 0 ? NULL : json_loadb((const char *)data, size, 0, NULL);
    if (!json_is_object(root)) {
        json_decref(root);
        return LLVMFuzzerMutate(data, size, max_size);
    }
    size_t rounds = 1 + pick(&r, 3);
    for (size_t i = 0; i < rounds; i++)
        mutate(root, &r);
    char *text = json_dumps(root, JSON_COMPACT);
    json_decref(root);
    size_t n = text ? strlen(text) : 0;
    if (!text || n > max_size) {
        free(text);
        return LLVMFuzzerMutate(data, size, max_size);
    }
    memcpy(data, text, n);
    free(text);
    return n;
}

/*
 * Running a fraction of the accepted scenes, so that the analyses' result
 * writers (JSON, CSV), the warnings and the monitor paths of api/ are
 * reached too.  A run must stay cheap (the fuzzer's speed is its coverage):
 * the scene's size knobs are clamped before it runs (at most 12 segments,
 * 4 contact points per segment, 6 modes, 2 cycles, steps of >= 1 deg,
 * 2000 steps, 50 iterations) and a monitor cancels any run after
 * RUN_BUDGET_S of wall time (a cancelled run is a valid outcome: it
 * exercises the cancel paths).  One accepted input in RUN_EVERY runs.
 */
#define RUN_EVERY    8
#define RUN_BUDGET_S 0.1

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int past_deadline(void *ctx, double fraction)
{
    (void)fraction;
    return now_s() > *(const double *)ctx;
}

/* FNV-1a of the input: the choice of what runs depends on the input only,
 * so a finding reproduces. */
static int run_selected(const uint8_t *data, size_t size)
{
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < size; i++)
        h = (h ^ data[i]) * 16777619u;
    return h % RUN_EVERY == 0;
}

static void clamp_int(json_t *v, json_int_t hi)
{
    if (json_is_integer(v) && json_integer_value(v) > hi)
        json_integer_set(v, hi);
}

/* Lowers every size knob found anywhere in the scene (see above). */
static void clamp(json_t *j)
{
    const char *key;
    json_t *v;
    size_t i;
    if (json_is_array(j)) {
        json_array_foreach(j, i, v) clamp(v);
        return;
    }
    json_object_foreach(j, key, v)
    {
        if (!strcmp(key, "segments"))
            clamp_int(v, 12);
        else if (!strcmp(key, "points_per_segment"))
            clamp_int(v, 4);
        else if (!strcmp(key, "modes"))
            clamp_int(v, 6);
        else if (!strcmp(key, "max_steps"))
            clamp_int(v, 2000);
        else if (!strcmp(key, "max_iterations"))
            clamp_int(v, 50);
        else if (!strcmp(key, "cycles") && json_is_number(v) && json_number_value(v) > 2)
            json_object_set_new(j, key, json_integer(2));
        else if (!strcmp(key, "step_deg") && json_is_number(v) && json_number_value(v) < 1)
            json_object_set_new(j, key, json_integer(1));
        else
            clamp(v);
    }
}

/* The result contract: a run either succeeds with a JSON object whose CSV
 * (when the analysis has a table) is written from the document and from
 * the text alike, or fails with a status and a message. */
static void check_run(const rd_scene *scene)
{
    double deadline = now_s() + RUN_BUDGET_S;
    rd_monitor mon = {past_deadline, &deadline};
    rd_result_doc *doc = NULL;
    rd_error err;
    rd_error_init(&err);
    if (rd_scene_run_doc(scene, &mon, &doc, &err) != RD_OK) {
        if (err.code == RD_OK || !err.message[0])
            abort();
        if (doc) { /* only a stopped run's partial result comes with an error */
            char *text = rd_result_doc_json(doc);
            json_t *o = text ? json_loads(text, 0, NULL) : NULL;
            if (err.code != RD_ECANCELED || !json_is_true(json_object_get(o, "partial")))
                abort();
            json_decref(o);
            free(text);
            rd_result_doc_free(doc);
        }
        return;
    }
    char *text = rd_result_doc_json(doc);
    json_t *o = text ? json_loads(text, 0, NULL) : NULL;
    if (!json_is_object(o))
        abort();
    json_decref(o);
    rd_error_init(&err);
    char *csv = rd_result_doc_csv(doc, &err);
    rd_error_init(&err);
    char *csv2 = rd_api_result_csv(text, &err);
    if (!csv != !csv2 || (csv && strcmp(csv, csv2)))
        abort();
    char *pretty = rd_api_json_pretty(text);
    if (!pretty)
        abort();
    free(pretty);
    free(csv);
    free(csv2);
    free(text);
    rd_result_doc_free(doc);
}

static void check_sweep(const uint8_t *data, size_t size, int run);

static void run_small(const char *body, size_t len)
{
    json_t *j = json_loadb(body, len, 0, NULL);
    if (!json_is_object(j)) {
        json_decref(j);
        return;
    }
    clamp(j);
    char *small = json_dumps(j, JSON_COMPACT);
    /* The same scene as a fidelity request of two cheap levels. */
    json_t *fid = json_pack("{s:O, s:[i, i]}", "fidelity", j, "segments", 4, 6);
    const char *analysis = json_string_value(json_object_get(j, "analysis"));
    if (fid && analysis && !strcmp(analysis, "lift"))
        json_object_set_new(fid, "rtol", json_pack("[f]", 1e-4));
    char *fid_text = fid ? json_dumps(fid, JSON_COMPACT) : NULL;
    if (fid_text)
        check_sweep((const uint8_t *)fid_text, strlen(fid_text), 1);
    free(fid_text);
    json_decref(fid);
    json_decref(j);
    rd_scene *scene = NULL;
    rd_error err;
    rd_error_init(&err);
    /* A clamp can make a scene invalid (e.g. fewer segments than rings
     * need): then there is nothing to run. */
    if (small && rd_scene_parse(small, strlen(small), &scene, &err) == RD_OK) {
        check_run(scene);
        rd_scene_free(scene);
    }
    free(small);
}

/* Once per process: the sweep parser and the example catalogue on the
 * project's files (cheap, and otherwise unreached by scene bodies). */
static void once(void)
{
    static int done;
    if (done)
        return;
    done = 1;
    rd_error err;
    rd_error_init(&err);
    char *list = rd_api_examples_json(FUZZ_EXAMPLES_DIR, &err);
    json_t *o = list ? json_loads(list, 0, NULL) : NULL;
    if (!o)
        abort();
    static const char *const names[] = {"thesis_modal", "no_such_example", "../etc",
                                        "bad\x01"
                                        "name",
                                        ""};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        rd_error_init(&err);
        char *scene = rd_api_example_scene(FUZZ_EXAMPLES_DIR, names[i], &err);
        if (!scene == (err.code == RD_OK))
            abort();
        free(scene);
    }
    json_decref(o);
    free(list);
    FILE *f = fopen(FUZZ_OPENAPI, "rb");
    char *tmpl = NULL;
    size_t len = 0;
    if (!f || rd_api_read_stream(f, 1 << 22, &tmpl, &len) != 0)
        abort();
    fclose(f);
    rd_error_init(&err);
    char *doc = rd_api_openapi_json(tmpl, &err);
    if (!doc)
        abort();
    free(doc);
    free(tmpl);
}

/* A sweep request (spec or fidelity request) that parses: its table
 * machinery on its first points (at most 2, each run under the same
 * budget as a scene), the CSV forms, the fidelity table and the chunks. */
static void check_sweep_table(const rd_sweep_request *req)
{
    size_t n = rd_sweep_points(req->sweep), m = n < 2 ? n : 2;
    char *rows[2] = {NULL, NULL};
    rd_error err;
    for (size_t i = 0; i < m; i++) {
        double deadline = now_s() + RUN_BUDGET_S;
        rd_monitor mon = {past_deadline, &deadline};
        rd_error_init(&err);
        if (rd_sweep_run_point(req->sweep, i, &mon, &rows[i], &err) != RD_OK) {
            /* The service's row of a point it stopped. */
            rd_error ferr;
            rd_error_init(&ferr);
            rows[i] = rd_sweep_request_failed_row(req, i, &err, &ferr);
            if (!rows[i])
                abort();
        }
    }
    rd_error_init(&err);
    char *table = rd_sweep_table_json(req->sweep, rows, m, &err);
    rd_error_init(&err);
    char *csv = rd_sweep_table_csv(req->sweep, rows, m, &err);
    if (!table || !csv)
        abort();
    rd_error_init(&err);
    char *csv2 = rd_sweep_csv_from_table(table, &err);
    if (!csv2 || strcmp(csv, csv2))
        abort();
    if (req->fidelity) {
        rd_error_init(&err);
        free(rd_sweep_fidelity_table(table, &err));
    }
    size_t first, end;
    rd_error_init(&err);
    if (rd_sweep_chunk_range(req->sweep, 0, m ? m : 1, &first, &end, &err) == RD_OK) {
        free(rd_sweep_chunk_name(0, m));
        free(rd_sweep_chunk_head(req->sweep, 0, m));
    }
    free(csv2);
    free(csv);
    free(table);
    for (size_t i = 0; i < m; i++)
        free(rows[i]);
}

static void check_sweep(const uint8_t *data, size_t size, int run)
{
    rd_sweep_request req = {0};
    rd_error err;
    rd_error_init(&err);
    if (rd_sweep_request_parse((const char *)data, size, 64, &req, &err) != RD_OK) {
        if (req.sweep || !err.message[0] || (err.path[0] && err.path[0] != '/'))
            abort();
        return;
    }
    if (!rd_sweep_hash(req.sweep) || rd_sweep_points(req.sweep) == 0)
        abort();
    char *columns = rd_sweep_columns_json(req.sweep);
    rd_error_init(&err);
    char *record = columns ? rd_sweep_csv_record(columns, &err) : NULL;
    rd_error_init(&err);
    char *scene = rd_sweep_point_scene(req.sweep, 0, &err);
    if (!columns || !record || !scene)
        abort();
    free(scene);
    free(record);
    free(columns);
    if (run)
        check_sweep_table(&req);
    rd_sweep_request_cleanup(&req);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    once();
    check_sweep(data, size, run_selected(data, size));
    rd_scene *scene = NULL;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_scene_parse((const char *)data, size, &scene, &err);
    if (rc == RD_OK) {
        const char *analysis = rd_scene_analysis(scene);
        char *echo = rd_scene_to_json(scene);
        json_t *o = echo ? json_loads(echo, 0, NULL) : NULL;
        if (!analysis || !json_is_object(o))
            abort();
        json_decref(o);
        free(echo);
        rd_scene_free(scene);
        if (run_selected(data, size))
            run_small((const char *)data, size);
        return 0;
    }
    if (scene || err.code == RD_OK || err.code != rc || !err.message[0] ||
        (err.path[0] && err.path[0] != '/'))
        abort();
    if (rd_api_http_status(err.code) < 400 || rd_api_http_status(err.code) > 599)
        abort();
    rd_error rerr;
    rd_error_init(&rerr);
    char *report = NULL;
    if (rd_scene_parse_report((const char *)data, size, &scene, &rerr, &report) == RD_OK ||
        rerr.code != err.code)
        abort();
    json_t *r = report ? json_loads(report, 0, NULL) : NULL;
    if (!json_is_object(json_object_get(r, "error")))
        abort();
    json_decref(r);
    free(report);
    char *body = rd_api_error_json(&err);
    json_t *o = body ? json_loads(body, 0, NULL) : NULL;
    if (!json_is_object(json_object_get(o, "error")))
        abort();
    json_decref(o);
    free(body);
    return 0;
}
