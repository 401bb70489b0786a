/*
 * test_schema — the one schema and the registry (api/rd_registry.h):
 *   - every analysis of the registry has a scene schema, an OpenAPI entry
 *     (and every $ref of the served document resolves),
 *     an example in examples/, a CSV table and a page tab (or says "none");
 *   - the OpenAPI document's ranges are the ones core enforces: every
 *     bound of every field is probed through rd_scene_parse (at the edge:
 *     not refused for that field; just outside: refused at that field's
 *     path);
 *   - the OpenAPI document's defaults are what a parsed scene holds (the
 *     echo of {"analysis": name});
 *   - every field the README names exists in the schema, and every scene
 *     the README shows is valid; the page's form keeps no default of its own;
 *   - a toy analysis added next to the built-in ones (one rd_analysis_def
 *     and one registry line, here in the test) is parsed, echoed,
 *     described in OpenAPI, run, and written as JSON and CSV;
 *   - a lubricated lift's `lubrication` block has every member the
 *     OpenAPI document's LiftLubrication describes, of its type, and no
 *     other; a lift without the model has none.
 *
 * usage: test_schema SOURCE_DIR (the repository: examples/, static/,
 * server/openapi.json, README.md)
 */
#include <dirent.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "rd_api.h"
#include "rd_registry.h"
#include "rd_scene.h"

static const char *src; /* the repository */

static char *read_text(const char *rel)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", src, rel);
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t len;
    if (f) {
        if (rd_api_read_stream(f, 16 * 1024 * 1024, &buf, &len) != RD_OK)
            buf = NULL;
        fclose(f);
    }
    return buf;
}

/* The served OpenAPI document for `registry`, from the shipped template. */
static json_t *openapi(const rd_analysis_def *const *registry)
{
    char *template_json = read_text("server/openapi.json");
    rd_error err;
    rd_error_init(&err);
    json_t *doc = template_json ? rd_registry_openapi(registry, template_json, &err) : NULL;
    CHECK(doc != NULL, "OpenAPI document: %s", err.message);
    free(template_json);
    return doc;
}

static json_t *schemas_of(json_t *doc)
{
    return json_object_get(json_object_get(doc, "components"), "schemas");
}

/* ---- the registry walk ---------------------------------------------------- */

/* Number of examples/ scenes whose "analysis" is `name`. */
static int count_examples(const char *name)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/examples", src);
    DIR *d = opendir(dir);
    struct dirent *de;
    int n = 0;
    while (d && (de = readdir(d)) != NULL) {
        size_t len = strlen(de->d_name);
        if (len < 6 || strcmp(de->d_name + len - 5, ".json") != 0)
            continue;
        char rel[512];
        snprintf(rel, sizeof rel, "examples/%s", de->d_name);
        char *text = read_text(rel);
        json_t *scene = text ? json_loads(text, 0, NULL) : NULL;
        const char *a = json_string_value(json_object_get(scene, "analysis"));
        n += a && strcmp(a, name) == 0;
        json_decref(scene);
        free(text);
    }
    if (d)
        closedir(d);
    return n;
}

static void test_registry(void)
{
    json_t *doc = openapi(rd_registry);
    json_t *schemas = schemas_of(doc);
    char *app = read_text("static/app.js");
    CHECK(app != NULL, "static/app.js");
    int n = 0;
    for (int i = 0; rd_registry[i]; i++, n++) {
        const rd_analysis_def *an = rd_registry[i];
        char ref[128];
        CHECK(strcmp(rd_scene_analysis_name(i), an->name) == 0, "enum order: %s", an->name);
        CHECK(an->scene && an->scene->name && an->scene->fields, "%s: a scene schema", an->name);
        CHECK(an->run != NULL, "%s: a runner", an->name);
        CHECK(json_is_object(json_object_get(schemas, an->scene->name)), "%s: OpenAPI %s", an->name,
              an->scene->name);
        snprintf(ref, sizeof ref, "#/components/schemas/%s", an->scene->name);
        json_t *mapping = json_object_get(
            json_object_get(json_object_get(schemas, "Scene"), "discriminator"), "mapping");
        const char *got = json_string_value(json_object_get(mapping, an->name));
        CHECK(got && strcmp(got, ref) == 0, "%s: in the Scene discriminator", an->name);
        CHECK(count_examples(an->name) >= 1, "%s: at least one example in examples/", an->name);
        CHECK(an->csv || (an->csv_none && *an->csv_none), "%s: a CSV table or why none", an->name);
        /* result_keys (what a study's observe pointer may start with) are
         * exactly the members of its OpenAPI result schema */
        char result[128];
        size_t stem = strlen(an->scene->name) - strlen("Scene");
        snprintf(result, sizeof result, "%.*sResult", (int)stem, an->scene->name);
        json_t *props = json_object_get(json_object_get(schemas, result), "properties");
        size_t nkeys = 0;
        for (const char *const *k = an->result_keys; k && *k; k++, nkeys++)
            CHECK(json_object_get(props, *k) != NULL, "%s: result key %s in %s", an->name, *k,
                  result);
        CHECK(nkeys > 0 && nkeys == json_object_size(props), "%s: %zu result keys, %s has %zu",
              an->name, nkeys, result, json_object_size(props));
        CHECK(an->page != NULL, "%s: a page tab or \"none\"", an->name);
        if (an->page && strcmp(an->page, "none") != 0) {
            char rel[256], import[300];
            snprintf(rel, sizeof rel, "static/%s", an->page);
            char *tab = read_text(rel);
            snprintf(import, sizeof import, "'./%s'", an->page);
            CHECK(tab != NULL, "%s: page tab %s exists", an->name, rel);
            CHECK(app && strstr(app, import), "%s: static/app.js imports %s", an->name, import);
            free(tab);
        }
    }
    CHECK(n >= RD_ANALYSIS_LIFT + 1, "registry has %d analyses", n);
    free(app);
    json_decref(doc);
}

/* Every "$ref" under `v` names an existing part of `doc` (the template's
 * references to the written scene schemas included). */
static int check_refs(json_t *doc, json_t *v)
{
    int refs = 0;
    if (json_is_array(v)) {
        size_t i;
        json_t *x;
        json_array_foreach(v, i, x) refs += check_refs(doc, x);
    } else if (json_is_object(v)) {
        const char *key;
        json_t *x;
        json_object_foreach(v, key, x)
        {
            if (strcmp(key, "$ref") == 0 && json_is_string(x)) {
                char ptr[256], *save = NULL;
                snprintf(ptr, sizeof ptr, "%s", json_string_value(x) + 1); /* after '#' */
                json_t *at = doc;
                for (char *t = strtok_r(ptr, "/", &save); at && t; t = strtok_r(NULL, "/", &save))
                    at = json_object_get(at, t);
                CHECK(at != NULL, "OpenAPI $ref %s resolves", json_string_value(x));
                refs++;
            } else {
                refs += check_refs(doc, x);
            }
        }
    }
    return refs;
}

static void test_openapi_refs(void)
{
    json_t *doc = openapi(rd_registry);
    int refs = check_refs(doc, doc);
    /* the template's paths and results point at Scene and the analyses' scenes */
    CHECK(refs >= 40, "%d $refs checked", refs);
    json_decref(doc);
}

/* ---- every field, with its path ------------------------------------------- */

typedef void (*field_fn)(const rd_analysis_def *an, const rd_field *f, const char *path, int item);

/* Calls fn for every field of `block` (recursively); item: inside an array
 * item (the path then has "/0"). */
static void walk(const rd_analysis_def *an, const rd_block *block, const char *prefix, int item,
                 field_fn fn)
{
    for (const rd_field *f = block->fields; f->key; f++) {
        char path[256];
        snprintf(path, sizeof path, "%s/%s", prefix, f->key);
        if (f->type == RD_F_BLOCK || f->type == RD_F_OPTBLOCK) {
            walk(an, f->block, path, item, fn);
        } else if (f->type == RD_F_DISTORTION || (f->type == RD_F_CUSTOM && f->block)) {
            fn(an, f, path, item);
            strcat(path, "/0");
            walk(an, f->block, path, 1, fn);
        } else {
            fn(an, f, path, item);
        }
    }
}

/* Sets `v` (stolen) at JSON Pointer `path` in `root`, creating objects on
 * the way; a "0" step makes a one-item array whose item has the required
 * fields of a distortion term (of a bore layer under "layers"). */
static void set_path(json_t *root, const char *path, json_t *v)
{
    char buf[256], *save = NULL;
    snprintf(buf, sizeof buf, "%s", path + 1);
    json_t *at = root;
    char *key = strtok_r(buf, "/", &save), *next;
    for (; (next = strtok_r(NULL, "/", &save)) != NULL; key = next) {
        json_t *child = json_is_array(at) ? json_array_get(at, 0) : json_object_get(at, key);
        if (!child) {
            child = strcmp(next, "0") != 0 ? json_object()
                    : strcmp(key, "layers") == 0
                        ? json_pack("[{s:f}]", "z", 0.0)
                        : json_pack("[{s:i, s:f}]", "order", 2, "amplitude", 0.0);
            json_object_set_new(at, key, child);
        }
        at = child;
    }
    if (json_is_array(at))
        at = json_array_get(at, 0);
    json_object_set_new(at, key, v);
}

/* What a bound's probe also sets, so that a rule tying the field to
 * another one does not hide the field's own bound: a thin section needs a
 * thin width (b/h <= 20); the Stribeck parameters are read only by that
 * model; the finest output step needs a short run (at most 200000
 * samples). */
/* A calibration needs a base, parameters and measurements (no defaults). */
#define MIN_CALIBRATION                                                                        \
    "{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [{\"path\": "                       \
    "\"/ring/tangential_force\", \"min\": 5, \"max\": 20}], \"measurements\": [{\"observe\": " \
    "\"/modes/0/frequency_hz\", \"value\": 100, \"sigma\": 1}]}"

/* And a sensitivity needs a base, parameters and outputs. */
#define MIN_SENSITIVITY                                                  \
    "{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [{\"path\": " \
    "\"/ring/tangential_force\"}], \"outputs\": [\"/modes/0/frequency_hz\"]}"

/* The studies' whole scenes, for their own fields. */
static const struct {
    const char *analysis, *scene;
} study_scenes[] = {
    {"calibration", MIN_CALIBRATION},
    {"sensitivity", MIN_SENSITIVITY},
};

/* 36 points on one layer at z = 0 (enough angles for fit_order 16). */
#define POINTS36                                                                              \
    "\"theta_deg\": [0,10,20,30,40,50,60,70,80,90,100,110,120,130,140,150,160,170,180,190,"   \
    "200,210,220,230,240,250,260,270,280,290,300,310,320,330,340,350], \"z\": [0,0,0,0,0,0,"  \
    "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0], \"dr\": [0,0,0,0,0,0,0,0," \
    "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]"
static const struct {
    const char *prefix, *scene;
    const char *analysis; /* only for this analysis; NULL: any */
} companions[] = {
    {"/ring/axial_height", "{\"ring\": {\"radial_width\": 1e-5}}", NULL},
    {"/physics/friction/", "{\"physics\": {\"friction\": {\"model\": \"stribeck\"}}}", NULL},
    {"/output/step_deg", "{\"engine\": {\"cycles\": 0.1}}", NULL},
    /* the lubricated model's fields are checked when it runs */
    {"/physics/friction/oil/", "{\"physics\": {\"friction\": {\"model\": \"lubricated\"}}}", NULL},
    {"/physics/friction/asperity/", "{\"physics\": {\"friction\": {\"model\": \"lubricated\"}}}",
     NULL},
    {"/bore/roughness_rq_m", "{\"physics\": {\"friction\": {\"model\": \"lubricated\"}}}", NULL},
    {"/numerics/film_step_deg", "{\"physics\": {\"friction\": {\"model\": \"lubricated\"}}}", NULL},
    /* the ring pack's tolerance is read only when it runs to periodicity */
    {"/numerics/periodic_tolerance", "{\"engine\": {\"cycles\": \"periodic\"}}", NULL},
    /* a bore map (its layers; points with 36 angles, enough for fit_order 16)
     * needs a height */
    {"/bore/layers/", "{\"contact\": {\"height\": 0}}", "contact"},
    /* lift's and the ring pack's: the (top) ring's depth on it, a layer alone (a stroke of 0 .. 2 crank radii
     * outside it is the map's rule, refused at /bore/layers) */
    {"/bore/layers/", "{\"bore\": {\"ring_z_tdc_m\": 0}}", "lift"},
    {"/bore/layers/", "{\"bore\": {\"ring_z_tdc_m\": 0}}", "ringpack"},
    {"/bore/points/",
     "{\"contact\": {\"height\": \"all\"}, \"bore\": {\"points\": {" POINTS36 "}}}", "contact"},
    {"/bore/points/", "{\"bore\": {\"ring_z_tdc_m\": 0, \"points\": {" POINTS36 "}}}", "lift"},
    {"/bore/points/", "{\"bore\": {\"ring_z_tdc_m\": 0, \"points\": {" POINTS36 "}}}", "ringpack"},
};

/* Copies the members of `from` into `to`, merging objects. */
static void merge(json_t *to, json_t *from)
{
    const char *key;
    json_t *v;
    json_object_foreach(from, key, v)
    {
        json_t *have = json_object_get(to, key);
        if (json_is_object(have) && json_is_object(v))
            merge(have, v);
        else
            json_object_set(to, key, v);
    }
}

/* The status of parsing {"analysis": an, <path>: v} (with the path's
 * companions) and the error path. */
static int probe(const rd_analysis_def *an, const char *path, json_t *v, char *err_path)
{
    json_t *scene = json_pack("{s:s}", "analysis", an->name);
    for (size_t i = 0; i < sizeof companions / sizeof companions[0]; i++)
        if (strncmp(path, companions[i].prefix, strlen(companions[i].prefix)) == 0 &&
            (!companions[i].analysis || strcmp(companions[i].analysis, an->name) == 0)) {
            json_t *c = json_loads(companions[i].scene, 0, NULL);
            merge(scene, c);
            json_decref(c);
        }
    for (size_t i = 0; i < sizeof study_scenes / sizeof study_scenes[0]; i++)
        if (strcmp(study_scenes[i].analysis, an->name) == 0) {
            json_t *c = json_loads(study_scenes[i].scene, 0, NULL);
            merge(scene, c);
            json_decref(c);
        }
    set_path(scene, path, v);
    char *text = json_dumps(scene, JSON_COMPACT | JSON_REAL_PRECISION(17));
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_scene_parse(text, strlen(text), &s, &err);
    snprintf(err_path, RD_ERROR_PATH_MAX, "%s", rc == RD_OK ? "" : err.path);
    rd_scene_free(s);
    free(text);
    json_decref(scene);
    return rc;
}

static json_t *value(const rd_field *f, double x)
{
    return f->type == RD_F_INTEGER ? json_integer((json_int_t)x) : json_real(x);
}

static int probes;

/* One bound: at the edge (inclusive) the field itself is not refused (a
 * rule tying it to another field may still refuse the scene, at that
 * other field); one step outside it is refused, at the field's path. */
static void probe_bound(const rd_analysis_def *an, const rd_field *f, const char *path, double edge,
                        int kind, int below)
{
    char at[RD_ERROR_PATH_MAX];
    double dir = below ? -1.0 : 1.0;
    double out = f->type == RD_F_INTEGER ? edge + dir : nextafter(edge, dir * INFINITY);
    double in = f->type == RD_F_INTEGER ? edge - dir : nextafter(edge, -dir * INFINITY);
    if (kind == RD_BOUND_EX) {
        out = edge; /* the edge itself is outside */
    } else {
        in = edge;
    }
    int rc = probe(an, path, value(f, in), at);
    CHECK(rc == RD_OK || strcmp(at, path) != 0, "%s %s = %.17g (inside): refused at %s", an->name,
          path, in, at);
    rc = probe(an, path, value(f, out), at);
    CHECK(rc != RD_OK && strcmp(at, path) == 0, "%s %s = %.17g (outside): status %d at \"%s\"",
          an->name, path, out, rc, at);
    probes++;
}

/* What the analysis adds to a shared block's bound (rd_field.extra, e.g.
 * contact's tangential_force > 0): *min and *kind replaced when it says. */
static void extra_bound(const rd_analysis_def *an, const char *path, double *min, int *kind)
{
    for (const rd_field *top = an->scene->fields; top->key; top++) {
        size_t n = strlen(top->key);
        if (!top->extra || strncmp(path + 1, top->key, n) != 0 || path[n + 1] != '/')
            continue;
        json_t *extra = json_loads(top->extra, 0, NULL);
        json_t *p = json_object_get(json_object_get(extra, "properties"), path + n + 2);
        if (json_is_number(json_object_get(p, "minimum"))) {
            *min = json_number_value(json_object_get(p, "minimum"));
            *kind =
                json_is_true(json_object_get(p, "exclusiveMinimum")) ? RD_BOUND_EX : RD_BOUND_IN;
        }
        json_decref(extra);
    }
}

static void probe_field(const rd_analysis_def *an, const rd_field *f, const char *path, int item)
{
    double min = f->min;
    int min_kind = f->has_min;
    (void)item;
    extra_bound(an, path, &min, &min_kind);
    if (f->type != RD_F_NUMBER && f->type != RD_F_INTEGER) {
        if (f->only_false) {
            char at[RD_ERROR_PATH_MAX];
            int rc = probe(an, path, json_true(), at);
            CHECK(rc != RD_OK && strcmp(at, path) == 0, "%s %s = true: refused here", an->name,
                  path);
        }
        return;
    }
    if (min_kind)
        probe_bound(an, f, path, min, min_kind, 1);
    if (f->has_max)
        probe_bound(an, f, path, f->max, f->has_max, 0);
}

static void test_ranges(void)
{
    for (int i = 0; rd_registry[i]; i++)
        walk(rd_registry[i], rd_registry[i]->scene, "", 0, probe_field);
    /* 108 bounds today (the shared ring and discretization ones once per
     * analysis): a walk that silently skipped a block would probe fewer. */
    CHECK(probes >= 108, "%d bounds probed", probes);
}

/* ---- defaults ------------------------------------------------------------- */

static json_t *echo_of(const rd_analysis_def *an)
{
    char body[512];
    if (strcmp(an->name, "calibration") == 0) /* no bare study: the smallest one */
        snprintf(body, sizeof body, "{\"analysis\":\"calibration\",%s", MIN_CALIBRATION + 1);
    else if (strcmp(an->name, "sensitivity") == 0)
        snprintf(body, sizeof body, "{\"analysis\":\"sensitivity\",%s", MIN_SENSITIVITY + 1);
    else
        snprintf(body, sizeof body, "{\"analysis\":\"%s\"}", an->name);
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_scene_parse(body, strlen(body), &s, &err) == RD_OK, "%s: %s", body, err.message);
    json_t *echo = s ? rd_scene_echo(s) : NULL;
    rd_scene_free(s);
    return echo;
}

static const json_t *resolve(json_t *schemas, json_t *schema)
{
    const char *ref = json_string_value(json_object_get(schema, "$ref"));
    if (!ref)
        ref = json_string_value(
            json_object_get(json_array_get(json_object_get(schema, "allOf"), 0), "$ref"));
    return ref ? json_object_get(schemas, ref + strlen("#/components/schemas/")) : schema;
}

static int defaults_checked;

/* Every "default" of `schema` against the echo (fields whose echo is a
 * computed value, `echo` hooks, say so in their description). */
static void compare_defaults(json_t *schemas, const json_t *schema, json_t *echo, const char *path)
{
    const char *key;
    json_t *prop;
    json_object_foreach(json_object_get(schema, "properties"), key, prop)
    {
        char child[256];
        snprintf(child, sizeof child, "%s/%s", path, key);
        const json_t *sub = resolve(schemas, prop);
        json_t *want = json_object_get(sub, "default"), *got = json_object_get(echo, key);
        const char *desc = json_string_value(json_object_get(sub, "description"));
        if (json_is_object(json_object_get(sub, "properties")) && json_is_object(got))
            compare_defaults(schemas, sub, got, child);
        if (!want || (desc && strstr(desc, "The echo gives")) ||
            (desc && strstr(desc, "echoed as the value used")))
            continue;
        int same = json_equal(want, got) || (json_is_number(want) && json_is_number(got) &&
                                             json_number_value(want) == json_number_value(got));
        CHECK(same, "%s: OpenAPI default differs from the echo of a bare scene", child);
        defaults_checked++;
    }
}

static void test_defaults(void)
{
    json_t *doc = openapi(rd_registry);
    json_t *schemas = schemas_of(doc);
    for (int i = 0; rd_registry[i]; i++) {
        json_t *echo = echo_of(rd_registry[i]);
        compare_defaults(schemas, json_object_get(schemas, rd_registry[i]->scene->name), echo,
                         rd_registry[i]->name);
        json_decref(echo);
    }
    /* 69 today: ring and discretization per analysis, and the analyses' own
     * (less the three echoed as the value used) */
    CHECK(defaults_checked >= 69, "%d defaults compared", defaults_checked);
    json_decref(doc);
}

/* ---- README --------------------------------------------------------------- */

/* 1 if some analysis has the field at dotted `name` (ring.material.density). */
static int field_exists(const char *name)
{
    for (int i = 0; rd_registry[i]; i++) {
        const rd_block *b = rd_registry[i]->scene;
        char buf[128], *save = NULL;
        snprintf(buf, sizeof buf, "%s", name);
        const rd_field *found = NULL;
        for (char *k = strtok_r(buf, ".", &save); k; k = strtok_r(NULL, ".", &save)) {
            found = NULL;
            for (const rd_field *f = b ? b->fields : NULL; f && f->key; f++)
                if (strcmp(f->key, k) == 0)
                    found = f;
            if (!found)
                break;
            b = found->block;
        }
        if (found)
            return 1;
    }
    return 0;
}

static int is_top_level_key(const char *key, size_t n)
{
    for (int i = 0; rd_registry[i]; i++)
        for (const rd_field *f = rd_registry[i]->scene->fields; f->key; f++)
            if (f->type == RD_F_BLOCK && strlen(f->key) == n && strncmp(f->key, key, n) == 0)
                return 1;
    return 0;
}

/* The README and the documents it sends readers to: every `block.field`
 * they name exists, every scene they show is valid.  *names_out and
 * *scenes_out: how many were checked. */
static void check_doc(const char *path, int *names_out, int *scenes_out)
{
    char *text = read_text(path);
    CHECK(text != NULL, "%s", path);
    int names = 0, scenes = 0;
    /* `block.field` mentions */
    for (const char *p = text; p && (p = strchr(p, '`')) != NULL; p++) {
        const char *end = strchr(p + 1, '`');
        if (!end)
            break;
        size_t n = (size_t)(end - p - 1);
        const char *dot = memchr(p + 1, '.', n);
        if (dot && n < 100 && strspn(p + 1, "abcdefghijklmnopqrstuvwxyz_.") == n &&
            is_top_level_key(p + 1, (size_t)(dot - p - 1))) {
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)n, p + 1);
            CHECK(field_exists(name), "%s names `%s`, which no scene schema has", path, name);
            names++;
        }
        p = end;
    }
    /* ```json blocks that are scenes */
    for (const char *p = text; p && (p = strstr(p, "```json\n")) != NULL;) {
        p += 8;
        const char *end = strstr(p, "```");
        if (!end)
            break;
        json_t *v = json_loadb(p, (size_t)(end - p), 0, NULL);
        if (json_object_get(v, "analysis")) {
            rd_scene *s = NULL;
            rd_error err;
            rd_error_init(&err);
            CHECK(rd_scene_parse_value(v, &s, &err) == RD_OK, "%s scene: %s at %s", path,
                  err.message, err.path);
            rd_scene_free(s);
            scenes++;
        }
        json_decref(v);
        p = end + 3;
    }
    *names_out = names, *scenes_out = scenes;
    free(text);
}

static void test_readme(void)
{
    int names, scenes;
    check_doc("README.md", &names, &scenes);
    CHECK(names >= 10 && scenes >= 1, "README: %d field names, %d scenes checked", names, scenes);
    /* the documents the README links to for the details it leaves out (the
     * measurement records, the full references moved out of it, the
     * changelog): every field name they use exists too */
    /* (docs/pretension.md and docs/sweeps.md name no scene field by its dotted name) */
    static const char *const docs[] = {"docs/contact.md",  "docs/lift.md",    "docs/modal.md",
                                       "docs/ringpack.md", "docs/service.md", "docs/limits.md",
                                       "CHANGELOG.md"};
    for (size_t i = 0; i < sizeof docs / sizeof docs[0]; i++) {
        check_doc(docs[i], &names, &scenes);
        CHECK(names >= 1, "%s: %d field names checked", docs[i], names);
    }
}

/* The page holds no copy of a scene default: no input with data-path also
 * has data-default (form.js takes them from the OpenAPI document; the
 * browser test checks that it does). */
static void test_page(void)
{
    char *html = read_text("static/index.html");
    int inputs = 0;
    CHECK(html != NULL, "static/index.html");
    for (const char *p = html; p && (p = strstr(p, "data-path=")) != NULL; p++) {
        const char *start = p, *end = strchr(p, '>');
        while (start > html && *start != '<')
            start--;
        if (!end || *start != '<' || start[1] == '!') /* a comment's words */
            continue;
        char tag[1024];
        size_t n = (size_t)(end - start);
        snprintf(tag, sizeof tag, "%.*s", (int)(n < sizeof tag - 1 ? n : sizeof tag - 1), start);
        CHECK(!strstr(tag, "data-default="), "index.html keeps a default: %s", tag);
        inputs++;
    }
    CHECK(inputs >= 34, "%d scene fields in index.html", inputs);
    free(html);
}

/* ---- a toy analysis, added the way a new one is ---------------------------- */

/* Its options (rd_scene.opts) and its "core": y_k = gain * k, k = 0..count-1. */
struct toy_opts {
    double gain;
    int count;
};

static const rd_field toy_fields[] = {
    {"gain", RD_F_NUMBER, offsetof(struct toy_opts, gain), RD_MIN(0), RD_MAX(10),
     .desc = "Gain, -."},
    {"count", RD_F_INTEGER, offsetof(struct toy_opts, count), RD_MIN(1), RD_MAX(100),
     .desc = "Rows."},
    {.key = NULL},
};
static const rd_block toy_block = {"ToyOptions", "/toy.", 1, 0, toy_fields};
static const rd_field toy_scene_fields[] = {
    RD_SCENE_COMMON(rd_block_discretization_modal),
    {"toy", RD_F_BLOCK, 0, .block = &toy_block},
    {.key = NULL},
};
static const rd_block toy_scene = {"ToyScene", "A toy.", 0, 0, toy_scene_fields};

static void toy_defaults(rd_scene *s)
{
    struct toy_opts *o = s->opts;
    o->gain = 2.0;
    o->count = 3;
}

/* What a core validator does: the range, with the field's path. */
static int toy_finish(rd_scene *s, rd_error *err)
{
    const struct toy_opts *o = s->opts;
    if (!(o->gain >= 0 && o->gain <= 10))
        return rd_error_set(err, RD_EINVAL, "/toy/gain", "/toy/gain = %g: allowed 0 to 10",
                            o->gain);
    if (o->count < 1 || o->count > 100)
        return rd_error_set(err, RD_EINVAL, "/toy/count", "/toy/count = %d: allowed 1 to 100",
                            o->count);
    return RD_OK;
}

static int toy_run(const rd_scene *s, const rd_monitor *mon, json_t **out, rd_error *err)
{
    const struct toy_opts *o = s->opts;
    (void)mon;
    (void)err;
    json_t *k = json_array(), *y = json_array();
    for (int i = 0; i < o->count; i++) {
        json_array_append_new(k, json_integer(i));
        json_array_append_new(y, json_real(o->gain * i));
    }
    *out = json_pack("{s:s, s:o, s:o, s:o}", "analysis", "toy", "scene", rd_scene_echo(s), "k", k,
                     "y", y);
    return RD_OK;
}

static const rd_csv_column toy_columns[] = {{"k", "k", 0}, {"y", "y", 0}, {NULL, NULL, 0}};
static const rd_csv_table toy_csv = {NULL, NULL, toy_columns};

static const rd_analysis_def toy = {
    .name = "toy",
    .scene = &toy_scene,
    .opts_size = sizeof(struct toy_opts),
    .defaults = toy_defaults,
    .finish = toy_finish,
    .run = toy_run,
    .csv = &toy_csv,
    .page = "none",
};

static int parse_in(const rd_analysis_def *const *registry, const char *body, rd_scene **s,
                    rd_error *err)
{
    json_t *v = json_loads(body, 0, NULL);
    rd_error_init(err);
    int rc = rd_scene_parse_with(registry, v, s, err);
    json_decref(v);
    return rc;
}

static void test_toy(void)
{
    const rd_analysis_def *registry[] = {rd_registry[0], rd_registry[1], rd_registry[2],
                                         rd_registry[3], &toy,           NULL};
    rd_scene *s = NULL;
    rd_error err;

    /* parse: defaults, the block, a typo, core's range check */
    CHECK(parse_in(registry, "{\"analysis\":\"toy\",\"toy\":{\"gain\":0.5}}", &s, &err) == RD_OK,
          "toy scene: %s", err.message);
    char *echo = s ? rd_scene_to_json(s) : NULL;
    CHECK(echo && strstr(echo, "\"toy\":{\"gain\":0.5,\"count\":3}"), "toy echo: %s",
          echo ? echo : "-");
    free(echo);
    rd_scene_free(s);
    s = NULL;
    CHECK(parse_in(registry, "{\"analysis\":\"toy\",\"toy\":{\"gian\":1}}", &s, &err) ==
                  RD_EINVAL &&
              strcmp(err.path, "/toy/gian") == 0 && strstr(err.message, "known: gain, count"),
          "toy typo: %s", err.message);
    CHECK(parse_in(registry, "{\"analysis\":\"toy\",\"toy\":{\"gain\":11}}", &s, &err) ==
                  RD_EINVAL &&
              strcmp(err.path, "/toy/gain") == 0,
          "toy range: %s", err.message);
    /* the built-in analyses now refuse the toy's block, naming who reads it */
    CHECK(parse_in(registry, "{\"analysis\":\"modal\",\"toy\":{\"x\":1}}", &s, &err) == RD_EINVAL &&
              strcmp(err.path, "/toy") == 0 &&
              strstr(err.message, "the modal analysis does not read a top-level \"toy\"") &&
              strstr(err.message, "only the toy analysis reads it"),
          "modal refuses /toy: %s", err.message);
    CHECK(parse_in(rd_registry, "{\"analysis\":\"modal\",\"toy\":{}}", &s, &err) == RD_EINVAL,
          "without the toy, /toy is unknown");

    /* OpenAPI: its scene, its block with default and range, in Scene */
    json_t *doc = openapi(registry);
    json_t *gain = json_object_get(
        json_object_get(json_object_get(schemas_of(doc), "ToyOptions"), "properties"), "gain");
    CHECK(json_real_value(json_object_get(gain, "default")) == 2.0 &&
              json_real_value(json_object_get(gain, "maximum")) == 10.0,
          "ToyOptions.gain: default and maximum");
    CHECK(json_object_get(
              json_object_get(json_object_get(schemas_of(doc), "ModalScene"), "properties"),
              "toy") == NULL,
          "ModalScene does not list /toy (refused)");
    json_decref(doc);

    /* run: one result document, JSON and CSV written from it */
    CHECK(parse_in(registry, "{\"analysis\":\"toy\",\"toy\":{\"gain\":0.5,\"count\":2}}", &s,
                   &err) == RD_OK,
          "%s", err.message);
    rd_result_doc *doc_run = NULL;
    CHECK(s && rd_scene_run_doc(s, NULL, &doc_run, &err) == RD_OK, "toy run: %s", err.message);
    char *json = doc_run ? rd_result_doc_json(doc_run) : NULL;
    char *csv = doc_run ? rd_result_doc_csv(doc_run, &err) : NULL;
    CHECK(json && strstr(json, "\"y\":[0.0,0.5]"), "toy JSON: %s", json ? json : "-");
    CHECK(csv && strcmp(csv, "k,y\n0,0\n1,0.5\n") == 0, "toy CSV: %s", csv ? csv : err.message);
    free(json);
    free(csv);
    rd_result_doc_free(doc_run);
    rd_scene_free(s);
}

/* ---- result schemas: the lift's lubrication block ------------------------- */

static int conform_checked;

/* `v` has the type `schema` (resolved) says, recursively: type, nullable,
 * enum, required and properties (both ways: no member the schema lacks),
 * items; `samples` > 0: arrays described per output sample have that length. */
static void conform(json_t *schemas, json_t *schema, json_t *v, const char *path, size_t samples)
{
    const json_t *s = resolve(schemas, schema);
    const char *type = json_string_value(json_object_get(s, "type"));
    const char *desc = json_string_value(json_object_get(s, "description"));
    conform_checked++;
    CHECK(type != NULL, "%s: the schema has a type", path);
    if (!type)
        return;
    if (json_is_null(v)) {
        CHECK(json_is_true(json_object_get(s, "nullable")), "%s is null, not nullable", path);
        return;
    }
    int ok = strcmp(type, "number") == 0    ? json_is_number(v)
             : strcmp(type, "integer") == 0 ? json_is_integer(v)
             : strcmp(type, "string") == 0  ? json_is_string(v)
             : strcmp(type, "boolean") == 0 ? json_is_boolean(v)
             : strcmp(type, "array") == 0   ? json_is_array(v)
             : strcmp(type, "object") == 0  ? json_is_object(v)
                                            : 0;
    CHECK(ok, "%s is not of the schema's type %s", path, type);
    if (!ok)
        return;
    json_t *choices = json_object_get(s, "enum");
    if (choices) {
        int found = 0;
        size_t i;
        json_t *c;
        json_array_foreach(choices, i, c) found |= json_equal(c, v);
        CHECK(found, "%s: %s is not in the schema's enum", path, json_string_value(v));
    }
    char child[256];
    if (json_is_array(v)) {
        if (samples && desc && strstr(desc, "per output sample"))
            CHECK(json_array_size(v) == samples, "%s: %zu values, %zu samples", path,
                  json_array_size(v), samples);
        size_t i;
        json_t *x;
        json_array_foreach(v, i, x)
        {
            snprintf(child, sizeof child, "%s/%zu", path, i);
            conform(schemas, json_object_get((json_t *)s, "items"), x, child, 0);
        }
    } else if (json_is_object(v)) {
        json_t *props = json_object_get(s, "properties"), *x;
        const char *key;
        size_t i;
        json_array_foreach(json_object_get(s, "required"), i, x)
            CHECK(json_object_get(v, json_string_value(x)) != NULL, "%s: required %s missing", path,
                  json_string_value(x));
        json_object_foreach(v, key, x)
        {
            snprintf(child, sizeof child, "%s/%s", path, key);
            json_t *sub = json_object_get(props, key);
            CHECK(sub != NULL, "%s: not in the schema", child);
            if (sub)
                conform(schemas, sub, x, child, samples);
        }
    }
}

/* A lubricated lift's result against LiftResult.lubrication (LiftLubrication),
 * on a thin oil that passes through all three regimes; a lift without the
 * model has no such block. */
static void test_lift_lubrication_schema(void)
{
    static const char *const bodies[] = {
        "{\"analysis\":\"lift\",\"engine\":{\"speed_rpm\":2400,\"cycles\":1},"
        "\"physics\":{\"friction\":{\"model\":\"lubricated\",\"oil\":{\"viscosity_pa_s\":3e-4}}},"
        "\"numerics\":{\"model\":\"rigid\",\"error_estimate\":false},\"output\":{\"step_deg\":5}}",
        "{\"analysis\":\"lift\",\"engine\":{\"cycles\":0.25},"
        "\"numerics\":{\"model\":\"rigid\",\"error_estimate\":false},\"output\":{\"step_deg\":5}}",
    };
    json_t *doc = openapi(rd_registry);
    json_t *schemas = schemas_of(doc);
    json_t *lift = json_object_get(schemas, "LiftResult");
    json_t *prop = json_object_get(json_object_get(lift, "properties"), "lubrication");
    CHECK(prop != NULL, "LiftResult has a lubrication property");
    size_t i;
    json_t *x;
    json_array_foreach(json_object_get(lift, "required"), i, x)
        CHECK(strcmp(json_string_value(x), "lubrication") != 0,
              "lubrication is not required (lubricated runs only)");
    for (int k = 0; k < 2; k++) {
        rd_scene *s = NULL;
        rd_error err;
        char *text = NULL;
        rd_error_init(&err);
        int rc = rd_scene_parse(bodies[k], strlen(bodies[k]), &s, &err);
        if (rc == RD_OK)
            rc = rd_scene_run(s, NULL, &text, &err);
        CHECK(rc == RD_OK, "lift %d: %s", k, err.message);
        json_t *res = text ? json_loads(text, 0, NULL) : NULL;
        json_t *lub = json_object_get(res, "lubrication");
        if (k == 1) {
            CHECK(res && !lub, "a lift without the lubricated model has no lubrication block");
        } else {
            CHECK(lub != NULL, "a lubricated lift has a lubrication block");
            size_t samples = json_array_size(json_object_get(res, "crank_deg"));
            CHECK(samples == 145, "%zu samples", samples);
            if (lub && prop)
                conform(schemas, prop, lub, "/lubrication", samples);
            CHECK(json_array_size(json_object_get(lub, "fmep_pa")) == 1, "one cycle: one FMEP");
            static const char *const regimes[] = {"hydrodynamic", "mixed", "boundary"};
            json_t *reg = json_object_get(lub, "regime");
            for (int r = 0; r < 3; r++) {
                int seen = 0;
                for (size_t j = 0; j < json_array_size(reg); j++) {
                    const char *got = json_string_value(json_array_get(reg, j));
                    seen |= got && strcmp(got, regimes[r]) == 0;
                }
                CHECK(seen, "thin oil: the regime %s occurs (its name is checked)", regimes[r]);
            }
        }
        json_decref(res);
        free(text);
        rd_scene_free(s);
    }
    /* 16 members, 6 arrays of 145, 2 of 1, 2 in viscosity_pa_s */
    CHECK(conform_checked > 800, "%d values checked against the schema", conform_checked);
    json_decref(doc);
}

/* ---- example names: one rule, 404 unknown, 400 malformed, never 500 ------- */

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL, "create %s", path);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static void test_example_names(void)
{
    char dir[] = "/tmp/rd_test_schema_XXXXXX", path[256];
    CHECK(mkdtemp(dir) != NULL, "temp dir");
    snprintf(path, sizeof path, "%s/ok.json", dir);
    write_file(path, "{\"analysis\":\"modal\"}");
    snprintf(path, sizeof path, "%s/a.b.json", dir); /* present, but not a servable name */
    write_file(path, "{\"analysis\":\"modal\"}");
    snprintf(path, sizeof path, "%s/d.json", dir); /* a directory */
    CHECK(mkdir(path, 0700) == 0, "mkdir %s", path);
    static const struct {
        const char *name;
        int code, status;
    } cases[] = {
        {"ok", RD_OK, 200},
        {"a.b", RD_ENOTFOUND, 404},
        {"a.b.json", RD_ENOTFOUND, 404},
        {"d", RD_ENOTFOUND, 404},
        {"nothing", RD_ENOTFOUND, 404},
        {"bad\xff", RD_EREQUEST, 400},
        {"bad\x01", RD_EREQUEST, 400},
        {"caf\xc3\xa9", RD_ENOTFOUND, 404},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rd_error err;
        rd_error_init(&err);
        char *text = rd_api_example_scene(dir, cases[i].name, &err);
        int code = text ? RD_OK : err.code;
        CHECK(code == cases[i].code && rd_api_http_status(code) == cases[i].status,
              "example \"%s\": %d (%s), want %d", cases[i].name, code, err.message, cases[i].code);
        free(text);
    }
    rmdir(path);
    snprintf(path, sizeof path, "%s/ok.json", dir);
    remove(path);
    snprintf(path, sizeof path, "%s/a.b.json", dir);
    remove(path);
    rmdir(dir);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s SOURCE_DIR\n", argv[0]);
        return 2;
    }
    src = argv[1];
    test_registry();
    test_openapi_refs();
    test_ranges();
    test_defaults();
    test_readme();
    test_page();
    test_toy();
    test_lift_lubrication_schema();
    test_example_names();
    printf("%d range bounds probed, %d defaults compared\n", probes, defaults_checked);
    return check_done();
}
