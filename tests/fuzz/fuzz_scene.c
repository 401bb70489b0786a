/*
 * fuzz_scene — libFuzzer harness of the scene parser, rd_scene_parse
 * (api/rd_api.h), with a structure-aware mutator.
 *
 * Each input is a request body.  The harness checks what must hold for every
 * body, valid or not: no crash, leak or undefined behaviour (ASan, UBSan);
 * a refusal carries a status, a message and a path that is empty or a JSON
 * Pointer, and rd_api_error_json turns it into valid JSON; an accepted scene
 * names its analysis and its echo is canonical (it parses back into a scene
 * with the same echo).  Every body is also tried as a sweep request.  A
 * violation aborts (a finding).
 *
 * The mutator (LLVMFuzzerCustomMutator) parses the input as JSON and changes
 * its structure, with a vocabulary read from the served OpenAPI document
 * (learn_vocabulary): a field's value to one of its schema bounds (+- one
 * ulp, +- 1 for integers), its enum words, another JSON type; a key removed,
 * duplicated, or one its object's schema knows added; "analysis" switched;
 * an array grown or shrunk; a number replaced by a token jansson cannot
 * write (1e999, NaN, -0, a 20-digit integer, a lone surrogate); the scene
 * wrapped into a sweep spec over its own fields.  Byte-level mutations alone
 * rarely keep a body valid JSON, so they would stop at the JSON parser and
 * never reach the range checks behind it.  One mutation in eight is
 * libFuzzer's own byte mutation, which keeps the JSON syntax errors covered.
 *
 * Modes: by default the accepted scenes and sweeps also run, clamped and
 * under a CPU budget (see RUN_BUDGET_S), for coverage of the result writers;
 * RINGDYN_FUZZ_RUN=0 runs none, for the long run of many executions.  RINGDYN_FUZZ_DICT=FILE writes
 * the vocabulary as a libFuzzer dictionary and exits (run.sh uses it).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <jansson.h>

#include "fuzz.h"
#include "rd_api.h"
#include "rd_scene_facts.h"
#include "rd_sweep.h"
#include "rd_sweep_request.h"
#include "rd_warnings.h"

size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed);

/* What the schema does not say: the sweep spec's own keys and words, and
 * JSON tokens that jansson's encoder cannot write (spliced into the text). */
static const char *const sweep_keys[] = {
    "base",     "parameters", "path",     "values",  "range",       "start", "stop", "count",
    "scale",    "integer",    "combine",  "outputs", "samples",     "seed",  "min",  "max",
    "fidelity", "models",     "segments", "rtol",    "description", "name"};
static const char *const sweep_words[] = {
    "product", "zip", "latin_hypercube", "random", "log", "linear", "", "max(", "count(", "*"};
static const char *const raw_tokens[] = {"1e999",
                                         "-1e999",
                                         "1e-400",
                                         "-0",
                                         "NaN",
                                         "Infinity",
                                         "1e308",
                                         "-1e308",
                                         "99999999999999999999",
                                         "-9223372036854775809",
                                         "9223372036854775807",
                                         "0e0",
                                         "\"\\u0000\"",
                                         "\"\\ud800\"",
                                         "\"\xc3\x28\""};

/* Generic boundaries of the number types, for fields the schema gives none. */
static const double numbers[] = {0,       -0.0, 1,        -1,           2,
                                 0.5,     1e-7, 1e-16,    1e-300,       1e300,
                                 -1e300,  1e20, 4.9e-324, 2147483648.0, 9007199254740993.0,
                                 0.499999};

/*
 * The vocabulary of the mutator, read at start-up from the OpenAPI document
 * the server serves (rd_api_openapi_json: written from the schema tables
 * that parse the scene, so it cannot drift from the parser).  Walking the
 * scene schemas (ModalScene ... RingpackScene) and the result schemas:
 *   keys      every property name;
 *   children  property name -> the property names of its object schema;
 *   bounds    property name -> its minimum, maximum, default, minItems,
 *             maxItems, each also one ulp and (integers) one unit either side;
 *   choices   property name -> its enum words;
 *   paths     every scene field's JSON Pointer (sweep parameter paths);
 *   outputs   result pointers with 0 and * for array items, some wrapped in
 *             an aggregate (sweep outputs).
 * The same words are the libFuzzer dictionary (RINGDYN_FUZZ_DICT, run.sh).
 */
static struct {
    json_t *doc, *keys, *words, *children, *bounds, *choices, *paths, *outputs;
} vocab;

static void add_word(json_t *array, const char *w)
{
    size_t i;
    json_t *v;
    json_array_foreach(array, i, v) if (!strcmp(json_string_value(v), w)) return;
    json_array_append_new(array, json_string(w));
}

static json_t *list_of(json_t *map, const char *key)
{
    json_t *a = json_object_get(map, key);
    if (!a) {
        a = json_array();
        json_object_set_new(map, key, a);
    }
    return a;
}

static json_t *deref(json_t *schema)
{
    const char *ref = json_string_value(json_object_get(schema, "$ref"));
    const char *prefix = "#/components/schemas/";
    if (ref && !strncmp(ref, prefix, strlen(prefix)))
        return json_object_get(json_object_get(json_object_get(vocab.doc, "components"), "schemas"),
                               ref + strlen(prefix));
    return schema;
}

static void add_bound(json_t *list, double x, int integer)
{
    json_array_append_new(list, json_real(x));
    json_array_append_new(list, json_real(nextafter(x, INFINITY)));
    json_array_append_new(list, json_real(nextafter(x, -INFINITY)));
    if (integer) {
        json_array_append_new(list, json_integer((json_int_t)x + 1));
        json_array_append_new(list, json_integer((json_int_t)x - 1));
    }
}

static void learn_field(const char *name, json_t *schema)
{
    static const char *const bound_keys[] = {"minimum", "maximum", "default", "minItems",
                                             "maxItems"};
    const char *type = json_string_value(json_object_get(schema, "type"));
    int integer = type && !strcmp(type, "integer");
    for (size_t i = 0; i < sizeof bound_keys / sizeof bound_keys[0]; i++) {
        json_t *b = json_object_get(schema, bound_keys[i]);
        if (json_is_number(b))
            add_bound(list_of(vocab.bounds, name), json_number_value(b), integer || i > 2);
    }
    size_t i;
    json_t *e;
    json_array_foreach(json_object_get(schema, "enum"), i, e) if (json_is_string(e))
    {
        add_word(list_of(vocab.choices, name), json_string_value(e));
        add_word(vocab.words, json_string_value(e));
    }
}

/* Walks a schema whose value sits at `path` (a scene pointer or, when
 * `result`, a result pointer with `*` for array items). */
static void learn(json_t *schema, const char *name, const char *path, int result, int depth)
{
    schema = deref(schema);
    if (!json_is_object(schema) || depth > 8)
        return;
    static const char *const alternatives[] = {"allOf", "oneOf", "anyOf"};
    for (size_t a = 0; a < sizeof alternatives / sizeof alternatives[0]; a++) {
        size_t i;
        json_t *s;
        json_array_foreach(json_object_get(schema, alternatives[a]), i, s)
            learn(s, name, path, result, depth + 1);
    }
    learn_field(name, schema);
    char sub[512];
    json_t *items = json_object_get(schema, "items");
    if (items) {
        snprintf(sub, sizeof sub, "%s/%s", path, result && depth % 2 ? "*" : "0");
        learn(items, name, sub, result, depth + 1);
    }
    const char *key;
    json_t *prop;
    json_object_foreach(json_object_get(schema, "properties"), key, prop)
    {
        snprintf(sub, sizeof sub, "%s/%s", path, key);
        if (!result) {
            add_word(vocab.keys, key);
            add_word(list_of(vocab.children, name), key);
            add_word(vocab.paths, sub);
        } else {
            add_word(vocab.outputs, sub);
        }
        learn(prop, key, sub, result, depth + 1);
    }
}

static void learn_vocabulary(void)
{
    FILE *f = fopen(FUZZ_OPENAPI, "rb");
    char *tmpl = NULL, *text = NULL;
    size_t len = 0;
    rd_error err;
    rd_error_init(&err);
    if (!f || rd_api_read_stream(f, 1 << 22, &tmpl, &len) != 0 ||
        !(text = rd_api_openapi_json(tmpl, &err)) || !(vocab.doc = json_loads(text, 0, NULL)))
        abort();
    fuzz_fail_openapi(tmpl);
    fclose(f);
    free(tmpl);
    free(text);
    vocab.keys = json_array(), vocab.words = json_array(), vocab.paths = json_array();
    vocab.outputs = json_array(), vocab.children = json_object(), vocab.bounds = json_object();
    vocab.choices = json_object();
    json_t *schemas = json_object_get(json_object_get(vocab.doc, "components"), "schemas");
    const char *name;
    json_t *s;
    json_object_foreach(schemas, name, s)
    {
        size_t n = strlen(name);
        if (n > 5 && !strcmp(name + n - 5, "Scene"))
            learn(s, "", "", 0, 0);
        else if (n > 6 && !strcmp(name + n - 6, "Result"))
            learn(s, "", "", 1, 0);
    }
    for (size_t i = 0; i < sizeof sweep_keys / sizeof sweep_keys[0]; i++)
        add_word(vocab.keys, sweep_keys[i]);
    for (size_t i = 0; i < sizeof sweep_words / sizeof sweep_words[0]; i++)
        add_word(vocab.words, sweep_words[i]);
    if (json_array_size(vocab.keys) < 50 || json_array_size(vocab.paths) < 50)
        abort(); /* the document lost its scene schemas: the harness must say so */
}

/* The libFuzzer dictionary: every key (quoted, as in the text) and word. */
static void write_dictionary(const char *file)
{
    FILE *f = fopen(file, "w");
    if (!f)
        abort();
    json_t *lists[] = {vocab.keys, vocab.words, vocab.paths, vocab.outputs};
    for (size_t l = 0; l < sizeof lists / sizeof lists[0]; l++) {
        size_t i;
        json_t *w;
        json_array_foreach(lists[l], i, w)
        {
            fputs("\"\\\"", f);
            for (const char *c = json_string_value(w); *c; c++)
                fprintf(f, *c == '"' || *c == '\\' ? "\\%c" : "%c", *c);
            fputs("\\\"\"\n", f);
        }
    }
    if (fclose(f))
        abort();
}

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

static const char *word_of(struct rng *r, json_t *list)
{
    size_t n = json_array_size(list);
    return n ? json_string_value(json_array_get(list, pick(r, n))) : "";
}

/* A value for the field `key` (NULL: anywhere): mostly what the schema says
 * of it (a bound, an enum word), else any JSON type. */
static json_t *random_value(struct rng *r, const char *key)
{
    json_t *bounds = key ? json_object_get(vocab.bounds, key) : NULL;
    json_t *choices = key ? json_object_get(vocab.choices, key) : NULL;
    switch (pick(r, 10)) {
    case 0:
        return json_null();
    case 1:
        return json_boolean(pick(r, 2));
    case 2:
        return json_string(pick(r, 2) ? word_of(r, vocab.words) : word_of(r, vocab.paths));
    case 3:
        return json_object();
    case 4:
        return json_array();
    case 5:
    case 6:
        if (choices)
            return json_string(word_of(r, choices));
        /* fall through */
    case 7:
    case 8:
        if (bounds)
            return json_copy(json_array_get(bounds, pick(r, json_array_size(bounds))));
        /* fall through */
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
    double x = numbers[pick(r, sizeof numbers / sizeof numbers[0])];
    for (size_t i = 0; a && i < n; i++)
        json_array_append_new(
            a, json_real(x += (pick(r, 8) == 0 ? -1.0 : 1.0) * (double)(1 + pick(r, 90))));
    return a;
}

/* The name the schema knows a slot's value by: its key, or for an array
 * item the array's key. */
static const char *name_of(const struct slots *s, const struct slot *at)
{
    if (at->key)
        return at->key;
    for (size_t i = 0; i < s->n; i++)
        if (s->v[i].value == at->parent)
            return s->v[i].key;
    return NULL;
}

/* Markers that the text splice (splice) turns into a duplicate key or a
 * raw token jansson could not have written. */
#define DUP_KEY \
    "\x01"      \
    "dup"
#define RAW_TOKEN "\x01raw"

static void add_key(json_t *root, struct rng *r, const struct slots *s, struct slot *at)
{
    json_t *obj = json_is_object(at->value)
                      ? at->value
                      : (at->parent && json_is_object(at->parent) ? at->parent : root);
    const char *name = obj == at->value ? at->key : obj == root ? "" : name_of(s, at);
    json_t *children = name ? json_object_get(vocab.children, name) : NULL;
    const char *key = children && pick(r, 4) ? word_of(r, children) : word_of(r, vocab.keys);
    json_t *v = pick(r, 4) == 0 ? json_object() : random_value(r, key);
    json_t *grand = json_object_get(vocab.children, key);
    if (v && json_is_object(v) && grand) {
        const char *k = word_of(r, grand);
        json_object_set_new(v, k, random_value(r, k));
    }
    json_object_set_new(obj, key, v);
}

/* A sweep over the scene: the root becomes the base of a spec. */
static void make_sweep(json_t *root, struct rng *r)
{
    json_t *base = json_deep_copy(root);
    json_object_clear(root);
    json_object_set_new(root, "base", base);
    json_t *params = json_array();
    for (size_t i = 0, n = 1 + pick(r, 3); i < n; i++) {
        const char *path = word_of(r, vocab.paths);
        const char *leaf = strrchr(path, '/') + 1;
        json_t *p = json_pack("{s:s}", "path", path);
        json_t *b = json_object_get(vocab.bounds, leaf);
        json_t *lo = b ? json_array_get(b, pick(r, json_array_size(b))) : json_integer(1);
        json_t *hi = b ? json_array_get(b, pick(r, json_array_size(b))) : json_integer(2);
        const char *scale = pick(r, 3) ? "linear" : "log";
        switch (pick(r, 3)) {
        case 0:
            json_object_set_new(p, "values", json_pack("[O, O]", lo, hi));
            break;
        case 1:
            json_object_set_new(p, "range",
                                json_pack("{s:O, s:O, s:i, s:s, s:b}", "start", lo, "stop", hi,
                                          "count", (int)(1 + pick(r, 4)), "scale", scale, "integer",
                                          (int)pick(r, 2)));
            break;
        default:
            json_object_set_new(p, "random",
                                json_pack("{s:O, s:O, s:s}", "min", lo, "max", hi, "scale", scale));
        }
        if (!b) {
            json_decref(lo);
            json_decref(hi);
        }
        json_array_append_new(params, p);
    }
    json_object_set_new(root, "parameters", params);
    static const char *const aggregates[] = {"max", "min", "mean", "count", "all"};
    char out[300];
    snprintf(out, sizeof out, "%s(%s)", aggregates[pick(r, 5)], word_of(r, vocab.outputs));
    json_object_set_new(root, "outputs",
                        json_pack("[s, s]", word_of(r, vocab.outputs), pick(r, 2) ? out : "/"));
    if (pick(r, 2))
        json_object_set_new(root, "combine", json_string(sweep_words[pick(r, 3)]));
    if (pick(r, 2))
        json_object_set_new(root, "samples", json_integer((json_int_t)pick(r, 5)));
    if (pick(r, 2))
        json_object_set_new(root, "seed", json_integer((json_int_t)pick(r, 1000)));
}

static void mutate(json_t *root, struct rng *r)
{
    struct slots s;
    s.n = 0;
    collect(NULL, NULL, 0, root, &s);
    struct slot *at = &s.v[pick(r, s.n)];
    const char *name = name_of(&s, at);
    switch (pick(r, 11)) {
    case 0: /* what the schema says of this field: a bound +- an ulp, a word */
    case 1:
        replace(at, random_value(r, name));
        break;
    case 2:
        replace(at, json_is_number(at->value) ? tweak_number(r, json_number_value(at->value))
                                              : random_value(r, NULL));
        break;
    case 3: /* drop a key */
        if (at->parent && json_is_object(at->parent))
            json_object_del(at->parent, at->key);
        break;
    case 4:
        add_key(root, r, &s, at);
        break;
    case 5:
        json_object_set_new(root, "analysis",
                            json_string(word_of(r, json_object_get(vocab.choices, "analysis"))));
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
    case 7: /* a key twice, or a token jansson cannot write */
        if (at->parent && json_is_object(at->parent) && pick(r, 2))
            json_object_set_new(at->parent, DUP_KEY, json_string(at->key));
        else
            replace(at, json_string(RAW_TOKEN));
        break;
    case 8:
        if (!json_object_get(root, "base") && pick(r, 4) == 0)
            make_sweep(root, r);
        else
            add_key(root, r, &s, at);
        break;
    default: { /* a distortion order list, the contact's own array */
        json_t *d = json_array();
        size_t n = pick(r, 20);
        for (size_t i = 0; d && i < n; i++)
            json_array_append_new(d, json_pack("{s:I, s:f}", "order", (json_int_t)(1 + pick(r, 70)),
                                               "amplitude", numbers[pick(r, 10)] * 1e-4));
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

/* Writes the document as text with its markers spliced: "\u0001dup":"k"
 * becomes "k":<a copy of k's value as the object has it, which the text
 * holds just before or after>; simplest and still a duplicate key: "k":null.
 * "\u0001raw" becomes a raw token.  Returns the text (malloc'd) or NULL. */
static char *splice(json_t *root, struct rng *r)
{
    char *text = json_dumps(root, JSON_COMPACT);
    if (!text)
        return NULL;
    for (;;) {
        char *m = strstr(text, "\"\\u0001");
        if (!m)
            return text;
        const char *repl;
        char buf[300];
        size_t cut;
        if (!strncmp(m, "\"\\u0001dup\":\"", 13)) {
            char *end = strchr(m + 13, '"');
            if (!end)
                return text;
            snprintf(buf, sizeof buf, "\"%.*s\":%s",
                     (int)(end - m - 13) < 200 ? (int)(end - m - 13) : 200, m + 13,
                     pick(r, 2) ? "null" : "1");
            repl = buf;
            cut = (size_t)(end + 1 - m);
        } else if (!strncmp(m, "\"\\u0001raw\"", strlen("\"\\u0001raw\""))) {
            repl = raw_tokens[pick(r, sizeof raw_tokens / sizeof raw_tokens[0])];
            cut = strlen("\"\\u0001raw\"");
        } else {
            return text; /* a marker a later mutation changed (its value no
                            longer a string): left as it is, valid JSON */
        }
        size_t head = (size_t)(m - text), tail = strlen(m + cut);
        char *out = malloc(head + strlen(repl) + tail + 1);
        if (!out) {
            free(text);
            return NULL;
        }
        memcpy(out, text, head);
        strcpy(out + head, repl);
        strcat(out + head, m + cut);
        free(text);
        text = out;
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
    char *text = splice(root, &r);
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
 * Running the accepted scenes and sweeps, so that the analyses' result
 * writers (JSON, CSV), the warnings and the monitor paths of api/ are
 * reached too.  A run must stay cheap (the fuzzer's speed is its coverage):
 * the scene's size knobs are clamped before it runs (at most 8 segments,
 * 4 contact points per segment, 6 modes, a quarter of a cycle for lift and
 * the ring pack's least, 2, steps of >= 1 deg, 2000 steps, 50 iterations:
 * a lift run then takes ~20 ms with its error estimate, a contact run a few
 * ms) and a monitor cancels any run after
 * RUN_BUDGET_S of CPU time (a cancelled run is a valid outcome: it
 * exercises the cancel paths).  A sweep runs its first two points (not
 * clamped: the budget bounds them).  Which inputs run: run_now.  A scene
 * that runs also runs as a fidelity request of two levels.
 */
#define RUN_EVERY    8
#define RUN_FIRST    12
#define RUN_BUDGET_S 0.1

/* CPU time, not wall time: a run's outcome (finished or cancelled) is the
 * same under any load of the machine, so a finding reproduces. */
static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int past_deadline(void *ctx, double fraction)
{
    (void)fraction;
    return now_s() > *(const double *)ctx;
}

uint32_t fuzz_hash(const uint8_t *data, size_t size, uint32_t salt)
{
    uint32_t h = 2166136261u ^ (salt * 0x9E3779B9u);
    for (size_t i = 0; i < size; i++)
        h = (h ^ data[i]) * 16777619u;
    return h;
}

rd_monitor fuzz_budget(double *deadline)
{
    *deadline = now_s() + RUN_BUDGET_S;
    return (rd_monitor){past_deadline, deadline};
}

/* The hash selects one input in RUN_EVERY. */
static int run_selected(const uint8_t *data, size_t size)
{
    return fuzz_hash(data, size, 0) % RUN_EVERY == 0;
}

/* Whether an accepted input of `kind` (its analysis, or "sweep") runs: the
 * first RUN_FIRST of each kind in the process (the seeds, so that every
 * analysis and sweep form reaches its writers early; and any input replayed
 * alone, so a finding reproduces), then those run_selected picks. */
static int run_now(const char *kind, const uint8_t *data, size_t size)
{
    static char kinds[16][16];
    static int counts[16];
    for (size_t i = 0; i < 16; i++) {
        if (!kinds[i][0])
            snprintf(kinds[i], sizeof kinds[i], "%s", kind);
        if (!strncmp(kinds[i], kind, sizeof kinds[i] - 1))
            return counts[i]++ < RUN_FIRST || run_selected(data, size);
    }
    return run_selected(data, size);
}

static void clamp_int(json_t *v, json_int_t hi)
{
    if (json_is_integer(v) && json_integer_value(v) > hi)
        json_integer_set(v, hi);
}

/* Lowers every size knob found anywhere in the scene (see above). */
static void clamp(json_t *j, int cycles_least)
{
    const char *key;
    json_t *v;
    size_t i;
    if (json_is_array(j)) {
        json_array_foreach(j, i, v) clamp(v, cycles_least);
        return;
    }
    json_object_foreach(j, key, v)
    {
        if (!strcmp(key, "segments"))
            clamp_int(v, 8);
        else if (!strcmp(key, "points_per_segment"))
            clamp_int(v, 4);
        else if (!strcmp(key, "modes"))
            clamp_int(v, 6);
        else if (!strcmp(key, "max_steps"))
            clamp_int(v, 2000);
        else if (!strcmp(key, "max_iterations"))
            clamp_int(v, 50);
        else if (!strcmp(key, "cycles") && json_is_number(v) && json_number_value(v) > 0.25)
            json_object_set_new(j, key, cycles_least ? json_integer(2) : json_real(0.25));
        else if (!strcmp(key, "step_deg") && json_is_number(v) && json_number_value(v) < 1)
            json_object_set_new(j, key, json_integer(1));
        else
            clamp(v, cycles_least);
    }
}

/* The result contract: a run either succeeds with a JSON object whose CSV
 * (when the analysis has a table) is written from the document and from
 * the text alike, or fails with a status and a message. */
static void check_run(const rd_scene *scene)
{
    double deadline;
    rd_monitor mon = fuzz_budget(&deadline);
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

static int check_sweep(const uint8_t *data, size_t size, int run);

char *fuzz_clamped(const char *body, size_t len)
{
    json_t *j = json_loadb(body, len, 0, NULL);
    const char *an = json_string_value(json_object_get(j, "analysis"));
    if (json_is_object(j))
        clamp(j, an && !strcmp(an, "ringpack"));
    char *small = json_is_object(j) ? json_dumps(j, JSON_COMPACT) : NULL;
    json_decref(j);
    return small;
}

/* A general cross-section (an object at any "section" key): its torsion
 * constant is a finite-element solve on up to 40000 triangles, three
 * levels, that no monitor can stop — tens of ms in Release, up to ~3 s a
 * run in this build, past the fuzzer's 10 s per input once the fidelity
 * request runs it twice more on a loaded machine.  Such scenes are parsed,
 * checked and echoed here; their runs are tested by test_section_shape and
 * the api cases. */
static int has_general_section(json_t *j)
{
    const char *key;
    json_t *v;
    size_t i;
    if (json_is_array(j)) {
        json_array_foreach(j, i, v) if (has_general_section(v)) return 1;
        return 0;
    }
    json_object_foreach(j, key, v)
    {
        if ((!strcmp(key, "section") && json_is_object(v)) || has_general_section(v))
            return 1;
    }
    return 0;
}

static void run_small(const char *body, size_t len)
{
    char *small = fuzz_clamped(body, len);
    json_t *j = small ? json_loads(small, 0, NULL) : NULL;
    if (j && has_general_section(j)) {
        json_decref(j);
        j = NULL;
    }
    if (!j) {
        free(small);
        return;
    }
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

/* 1 unless RINGDYN_FUZZ_RUN=0: the parse-only mode (parse, validate, echo,
 * refusal contract, sweep parse) runs no analysis, for the long run of
 * many executions; the default also runs a fraction, for coverage. */
static int run_mode = 1;

int LLVMFuzzerInitialize(int *argc, char ***argv);

/* Once per process: the vocabulary, the modes, and the example catalogue on
 * the project's files (cheap, and otherwise unreached by scene bodies).
 * RINGDYN_FUZZ_DICT=FILE writes the dictionary and exits. */
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fuzz_fail_init();
    learn_vocabulary();
    const char *dict = getenv("RINGDYN_FUZZ_DICT");
    if (dict) {
        write_dictionary(dict);
        exit(0);
    }
    const char *mode = getenv("RINGDYN_FUZZ_RUN");
    run_mode = !(mode && !strcmp(mode, "0"));
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
    fuzz_files_init();
    return 0;
}

/* A sweep request (spec or fidelity request) that parses: its table
 * machinery on its first points (at most 2, each run under the same
 * budget as a scene), the CSV forms, the fidelity table and, when the
 * points are the whole sweep, its chunk files (fuzz_files_reduce; `h`
 * picks how they are broken). */
size_t fuzz_sweep_rows(const rd_sweep_request *req, char *rows[2])
{
    size_t n = rd_sweep_points(req->sweep), m = n < 2 ? n : 2;
    rows[0] = rows[1] = NULL;
    for (size_t i = 0; i < m; i++) {
        double deadline;
        rd_monitor mon = fuzz_budget(&deadline);
        rd_error err;
        rd_error_init(&err);
        if (rd_sweep_run_point(req->sweep, i, &mon, &rows[i], &err) != RD_OK) {
            /* The service's row of a point it stopped. */
            rd_error ferr;
            rd_error_init(&ferr);
            rows[i] = rd_sweep_request_failed_row(req, i, &err, &ferr);
        }
    }
    return m;
}

static void check_sweep_table(const rd_sweep_request *req, uint32_t h)
{
    char *rows[2];
    size_t m = fuzz_sweep_rows(req, rows);
    for (size_t i = 0; i < m; i++)
        if (!rows[i])
            abort();
    rd_error err;
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
    if (m > 0 && rd_sweep_points(req->sweep) == m)
        fuzz_files_reduce(req->sweep, rows, m, csv, table, h);
    free(csv2);
    free(csv);
    free(table);
    for (size_t i = 0; i < m; i++)
        free(rows[i]);
}

/* run: 0 no, 1 yes, 2 when run_now says so.  Returns whether it ran. */
static int check_sweep(const uint8_t *data, size_t size, int run)
{
    rd_sweep_request req = {0};
    rd_error err;
    rd_error_init(&err);
    if (rd_sweep_request_parse((const char *)data, size, 64, &req, &err) != RD_OK) {
        if (req.sweep || !err.message[0] || (err.path[0] && err.path[0] != '/'))
            abort();
        return 0;
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
    int ran = run == 2 ? run_now("sweep", data, size) : run;
    if (ran)
        check_sweep_table(&req, fuzz_hash(data, size, 9));
    rd_sweep_request_cleanup(&req);
    return ran;
}

/* The echo is canonical: it parses back into a scene whose echo is the
 * same text (every default filled in, every number round-trips). */
static void check_echo(const char *echo)
{
    rd_scene *again = NULL;
    rd_error err;
    rd_error_init(&err);
    if (rd_scene_parse(echo, strlen(echo), &again, &err) != RD_OK)
        abort();
    char *echo2 = rd_scene_to_json(again);
    if (!echo2 || strcmp(echo, echo2))
        abort();
    free(echo2);
    rd_scene_free(again);
}

/* The job service's facts (rd_scene_facts.h): the canonical text (the
 * result cache's key) is a fixed point, as the echo is; the predicted cost
 * is NAN or a positive number. */
static void check_facts(const rd_scene *scene)
{
    (void)rd_scene_name(scene);
    double cost = rd_scene_cost_predict(scene);
    if (!isnan(cost) && !(cost > 0))
        abort();
    char *canon = rd_scene_canonical_json(scene), *canon2 = NULL;
    rd_scene *again = NULL;
    rd_error err;
    rd_error_init(&err);
    if (!canon || rd_scene_parse(canon, strlen(canon), &again, &err) != RD_OK ||
        !(canon2 = rd_scene_canonical_json(again)) || strcmp(canon, canon2))
        abort();
    free(canon2);
    free(canon);
    rd_scene_free(again);
}

json_t *fuzz_result_of(const char *echo, uint32_t h)
{
    json_t *scene = json_loads(echo, 0, NULL);
    json_t *r =
        json_pack("{s:o, s:{s:f, s:f, s:b, s:f}}", "scene", scene, "numerics", "error_estimate",
                  (double)(h % 100) / 1000.0, "event_error_deg", (double)(h >> 8 & 15),
                  "accuracy_met", (int)(h >> 12 & 1), "accuracy", 1e-3);
    json_t *numerics = json_object_get(r, "numerics");
    if (h >> 13 & 1)
        json_object_set_new(numerics, "reference_segments", json_integer(12));
    if (h >> 14 & 1)
        json_object_set_new(numerics, "accuracy_note", json_string("note"));
    if (h >> 15 & 1)
        json_object_set_new(r, "warnings", json_pack("[{s:s}]", "code", "own"));
    return r;
}

/* The result's warnings (rd_warnings.h) over the echo and made-up numerics:
 * its own (code "own") kept, then {code, path, message} of each rule. */
static void check_warnings(const char *echo, uint32_t h)
{
    json_t *r = fuzz_result_of(echo, h), *w;
    size_t i;
    if (!r || rd_warnings_add(r) != 0 || !json_is_array(json_object_get(r, "warnings")))
        abort();
    json_array_foreach(json_object_get(r, "warnings"), i, w)
    {
        const char *code = json_string_value(json_object_get(w, "code"));
        if (!code || (strcmp(code, "own") && (!json_is_string(json_object_get(w, "message")) ||
                                              !json_is_string(json_object_get(w, "path")))))
            abort();
    }
    json_decref(r);
}

/* The checks of one input (see the top); returns whether it ran. */
static int check_input(const uint8_t *data, size_t size)
{
    int ran = check_sweep(data, size, run_mode ? 2 : 0);
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
        check_echo(echo);
        check_facts(scene);
        check_warnings(echo, fuzz_hash(data, size, 10));
        free(echo);
        rd_scene_free(scene);
        if (run_mode && run_now(analysis, data, size)) {
            run_small((const char *)data, size);
            ran = 1;
        }
        return ran;
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
    return ran;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int ran = check_input(data, size);
    fuzz_files_example(data, size);
    fuzz_fail_pass(data, size, ran);
    return 0;
}
