/*
 * rd_scene — scene parsing: JSON body -> type-checked, defaults-filled
 * struct rd_scene, and running it (rd_scene.h).
 *
 * Which fields exist, their types and their echo are the analyses' tables
 * (rd_registry.h, rd_schema.h); this file picks the analysis, fills the
 * defaults, runs the tables and the analysis' checks, owns the scene's
 * memory, and runs a parsed scene (its analysis' runner, then the result's
 * warnings, into a result document).  The echo back to JSON, which the
 * runners call, is rd_scene_echo.c's.
 */
#include "rd_scene.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_registry.h"
#include "rd_result.h"
#include "rd_schema.h"
#include "rd_warnings.h"

#define MAX_KEYS 64 /* top-level keys of all analyses together */

const char *rd_scene_analysis_name(int analysis)
{
    for (int i = 0; rd_registry[i]; i++)
        if (i == analysis)
            return rd_registry[i]->name;
    return "unknown";
}

static void list_analyses(char *buf, size_t size, const rd_analysis_def *const *registry)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; registry[i] && n < size; i++)
        n += (size_t)snprintf(buf + n, size - n, "%s%s", n ? ", " : "", registry[i]->name);
}

/* "analysis" decides which keys are known, so it is checked before them. */
static int parse_analysis(const rd_analysis_def *const *registry, json_t *root, int *index,
                          rd_issues *issues, rd_error *err)
{
    char all[256], q[64], hint[96] = "";
    const char *names[32];
    int n = 0;
    list_analyses(all, sizeof all, registry);
    for (; registry[n] && n < 31; n++)
        names[n] = registry[n]->name;
    names[n] = NULL;

    json_t *v = json_object_get(root, "analysis");
    if (!v) {
        rd_issues_add(issues, RD_EINVAL, "/analysis", all, NULL, "\"analysis\" is missing");
        return rd_error_set(err, RD_EINVAL, "/analysis",
                            "the scene must say which analysis to run: \"analysis\" is missing "
                            "(available: %s)",
                            all);
    }
    if (!json_is_string(v)) {
        rd_schema_type_error(err, "/analysis", "a string", v);
        rd_issues_add(issues, RD_EINVAL, "/analysis", all, NULL, "%s", err->message);
        return RD_EINVAL;
    }
    if (rd_registry_find(registry, json_string_value(v), index))
        return RD_OK;
    const char *dym = rd_schema_closest(json_string_value(v), names);
    if (dym)
        snprintf(hint, sizeof hint, "; did you mean \"%s\"?", dym);
    rd_schema_quote(q, sizeof q, json_string_value(v));
    rd_issues_add(issues, RD_EINVAL, "/analysis", all, dym, "unknown analysis %s%s", q, hint);
    return rd_error_set(err, RD_EINVAL, "/analysis",
                        "unknown analysis %s (allowed: %s; available in this version: %s)", q, all,
                        all);
}

/* A zeroed scene of `an` with the common and the analysis' defaults:
 * the thesis ring, cut as the thesis recommends (3.3). */
static const struct rd_scene_ops scene_ops = {rd_scene_parse_value, rd_scene_free};

static rd_scene *scene_new(const rd_analysis_def *an, int index)
{
    rd_scene *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->analysis = index;
    s->ops = &scene_ops;
    s->an = an;
    if (an->opts_size && !(s->opts = calloc(1, an->opts_size))) {
        free(s);
        return NULL;
    }
    rd_ring_params_default(&s->ring);
    s->segments = RD_SCENE_DEFAULT_SEGMENTS;
    s->closed = 0;
    rd_modal_opts_default(&s->modal);
    if (an->defaults)
        an->defaults(s);
    return s;
}

rd_scene *rd_scene_defaults(const rd_analysis_def *an)
{
    int index = -1;
    rd_registry_find(rd_registry, an->name, &index);
    return scene_new(an, index);
}

/* Does `an`'s scene read the top-level `key`? */
static int reads_key(const rd_analysis_def *an, const char *key)
{
    for (const rd_field *f = an->scene->fields; f->key; f++)
        if (strcmp(f->key, key) == 0)
            return 1;
    return 0;
}

/* "a, b and c": the analyses of `registry` other than `an` that read `key`;
 * returns their count. */
static int list_readers(char *buf, size_t size, const rd_analysis_def *const *registry,
                        const rd_analysis_def *an, const char *key)
{
    const char *names[32];
    int n = 0;
    for (int i = 0; registry[i] && n < 32; i++)
        if (registry[i] != an && reads_key(registry[i], key))
            names[n++] = registry[i]->name;
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && k < size; i++)
        k += (size_t)snprintf(buf + k, size - k, "%s%s",
                              i == 0       ? ""
                              : i == n - 1 ? " and "
                                           : ", ",
                              names[i]);
    return n;
}

/* Where `an` reads `key` instead (its `elsewhere` pairs), or NULL. */
static const char *elsewhere_of(const rd_analysis_def *an, const char *key)
{
    for (const char *const *p = an->elsewhere; p && p[0]; p += 2)
        if (strcmp(p[0], key) == 0)
            return p[1];
    return NULL;
}

/* Refuses every top-level key of `root` that `an` does not read but that
 * means something elsewhere: a block other analyses read (`others`), or one
 * of `an`'s `elsewhere` keys.  Such a block was once accepted and ignored,
 * so a user who typed a value there got an answer that silently did not
 * use it.  The keys refused go to refused[] (NULL-ended, at most max - 1),
 * so that the table's check does not report them again as unknown. */
static int refuse_not_read(const rd_analysis_def *const *registry, const rd_analysis_def *an,
                           json_t *root, const char *const *others, const char **refused, int max,
                           rd_issues *issues, rd_error *err)
{
    char path[RD_ERROR_PATH_MAX], reads[256], why[320], q[64];
    const char *key;
    json_t *v;
    int rc = RD_OK, n = 0;
    size_t k = 0;
    reads[0] = '\0';
    for (const rd_field *f = an->scene->fields; f->key && k < sizeof reads; f++)
        k += (size_t)snprintf(reads + k, sizeof reads - k, "%s%s", k ? ", " : "", f->key);
    json_object_foreach(root, key, v)
    {
        if (reads_key(an, key))
            continue;
        const char *where = elsewhere_of(an, key);
        int other = 0;
        for (int i = 0; others[i]; i++)
            other |= strcmp(others[i], key) == 0;
        if ((!where && !other) || n >= max - 1)
            continue;
        refused[n++] = key;
        rd_schema_path_join(path, sizeof path, "", key);
        rd_schema_quote(q, sizeof q, key);
        if (where) {
            snprintf(why, sizeof why, "%s", where);
        } else {
            char readers[128];
            int several = list_readers(readers, sizeof readers, registry, an, key) > 1;
            snprintf(why, sizeof why, "only the %s %s it; a %s scene reads: %s", readers,
                     several ? "analyses read" : "analysis reads", an->name, reads);
        }
        rd_issues_add(issues, RD_EINVAL, path, reads, NULL,
                      "%s: the %s analysis does not read a top-level %s; %s", path, an->name, q,
                      why);
        int r = rd_error_set(err, RD_EINVAL, path,
                             "%s: the %s analysis does not read a top-level %s; %s", path, an->name,
                             q, why);
        rc = rc == RD_OK ? r : rc;
    }
    refused[n] = NULL;
    return rc;
}

/* Core's first error, listed with the table's allowed values of its field;
 * the table's own note on the same field (its static range) gives way. */
static void list_core_error(const rd_scene *s, const rd_error *err, rd_issues *issues)
{
    char allowed[160] = "";
    if (!issues)
        return;
    const rd_field *f = rd_schema_find(s->an->scene, err->path);
    if (f)
        rd_schema_allowed(f, allowed, sizeof allowed);
    for (int i = 0; i < issues->n; i++)
        if (strcmp(issues->item[i].path, err->path) == 0) {
            issues->item[i] = issues->item[--issues->n];
            i--;
        }
    rd_issues_add(issues, err->code, err->path, allowed, NULL, "%s", err->message);
}

int rd_scene_parse_issues(const rd_analysis_def *const *registry, json_t *root, rd_scene **out,
                          rd_error *err, rd_issues *issues)
{
    rd_scene *s = NULL;
    const char *others[MAX_KEYS], *refused[MAX_KEYS];
    int rc, index = -1;

    *out = NULL;
    if (!json_is_object(root)) {
        char got[96];
        rd_schema_describe(root, got, sizeof got);
        rc = rd_error_set(err, RD_EJSON, "", "the scene must be a JSON object, got %s", got);
        goto out;
    }
    rc = parse_analysis(registry, root, &index, issues, err);
    if (rc != RD_OK)
        goto out;
    s = scene_new(registry[index], index);
    if (!s) {
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while reading the scene");
        goto out;
    }
    rd_registry_ignored(registry, s->an, others, MAX_KEYS);
    rc = refuse_not_read(registry, s->an, root, others, refused, MAX_KEYS, issues, err);
    s->issues = issues;
    int table_rc = rd_schema_parse(root, s->an->scene, refused, "", s, err);
    rc = rc == RD_OK ? table_rc : rc;
    s->issues = NULL;
    /* Values and ranges: core's validators, messages passed on unchanged. */
    if (rc == RD_OK) {
        rc = rd_ring_scene_validate(&s->ring, s->segments, s->closed, err);
        if (rc == RD_OK && s->an->finish)
            rc = s->an->finish(s, err);
        if (rc != RD_OK)
            list_core_error(s, err, issues);
        else if (issues)
            issues->n = issues->dropped = 0; /* notes on ranges core accepted */
    }
    if (rc != RD_OK)
        goto out;
    *out = s;
    s = NULL;
out:
    rd_scene_free(s);
    return rc;
}

int rd_scene_parse_with(const rd_analysis_def *const *registry, json_t *root, rd_scene **out,
                        rd_error *err)
{
    return rd_scene_parse_issues(registry, root, out, err, NULL);
}

int rd_scene_parse_value(json_t *root, rd_scene **out, rd_error *err)
{
    return rd_scene_parse_with(rd_registry, root, out, err);
}

int rd_scene_parse_keep(const char *body, size_t len, rd_scene **out, rd_error *err,
                        rd_issues *issues, json_t **root_out)
{
    json_error_t jerr;
    json_t *root = NULL;
    int rc;

    *out = NULL;
    if (len > RD_API_BODY_MAX) {
        rc = rd_error_set(err, RD_ETOOLARGE, "",
                          "the scene is %zu bytes, more than the limit of %d bytes", len,
                          RD_API_BODY_MAX);
        goto out;
    }
    /* DECODE_ANY so that a scalar body gets the same "must be a JSON object"
     * answer as an array; duplicate keys are rejected because which one
     * would win is not obvious to whoever wrote them. */
    root = json_loadb(body ? body : "", body ? len : 0, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY,
                      &jerr);
    if (!root) {
        rc = rd_error_set(err, RD_EJSON, "", "the body is not valid JSON: %s (line %d, column %d)",
                          jerr.text, jerr.line, jerr.column);
        goto out;
    }
    rc = rd_scene_parse_issues(rd_registry, root, out, err, issues);
out:
    if (root_out)
        *root_out = root;
    else
        json_decref(root);
    return rc;
}

int rd_scene_parse(const char *body, size_t len, rd_scene **out, rd_error *err)
{
    return rd_scene_parse_keep(body, len, out, err, NULL, NULL);
}

void rd_scene_free(rd_scene *scene)
{
    if (!scene)
        return;
    if (scene->opts && scene->an->cleanup)
        scene->an->cleanup(scene->opts);
    free(scene->opts);
    free(scene->face_table[0].v);
    free(scene->face_table[1].v);
    free(scene->lube.temp_table[0].v);
    free(scene->lube.temp_table[1].v);
    free(scene->name);
    free(scene->description);
    free(scene);
}

int rd_scene_run_doc(const rd_scene *scene, const rd_monitor *mon, rd_result_doc **out,
                     rd_error *err)
{
    json_t *result = NULL;
    *out = NULL;
    int rc = scene->an->run(scene, mon, &result, err);
    if (rc != RD_OK && !result)
        return rc;
    /* warnings never refuse: they only annotate a finished result */
    *out = result && rd_warnings_add(result) == 0 ? rd_result_doc_new(scene->an, result) : NULL;
    if (!*out) {
        json_decref(result);
        return rc != RD_OK
                   ? rc
                   : rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the result");
    }
    return rc; /* not RD_OK: a stopped run's partial result */
}

int rd_scene_run(const rd_scene *scene, const rd_monitor *mon, char **result_json, rd_error *err)
{
    rd_result_doc *doc = NULL;
    *result_json = NULL;
    int rc = rd_scene_run_doc(scene, mon, &doc, err);
    if (!doc)
        return rc;
    *result_json = rd_result_doc_json(doc);
    rd_result_doc_free(doc);
    if (!*result_json && rc == RD_OK)
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the result");
    return rc;
}
