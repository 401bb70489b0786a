/*
 * rd_openapi — the OpenAPI scene schemas written from a registry
 * (rd_registry_openapi, declared in rd_registry.h): "Scene", oneOf the
 * analyses, one "<Name>Scene" per analysis (closed: the blocks only other
 * analyses read are refused), and every named block they
 * reference (rd_schema_block_openapi), with defaults read from a
 * defaults-filled scene of each analysis; and the analyses' names in the
 * template's Job and Result schemas (result_schemas).
 */
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "rd_registry.h"
#include "rd_scene.h"

static const char scene_description[] =
    "The request body: one of the analyses' shapes, chosen by `analysis`. Only the blocks an "
    "analysis reads are accepted; every field has a default (the thesis ring and engine), so "
    "{\"analysis\":\"modal\"} alone is valid. A block another analysis reads is refused (422 "
    "invalid_scene naming the block and the analysis: a value the analysis would ignore must "
    "not pass silently), and so are unknown keys (422 invalid_scene with the key's path). Note "
    "that `numerics` and `contact` mean different things per analysis: `numerics` is "
    "StaticNumerics for pretension and contact, LiftNumerics for lift (refused by modal); "
    "`contact` is ContactOptions for contact, LiftContact for lift (refused by modal and "
    "pretension). Parsing order (the first error is `error`; `errors` lists every problem the "
    "schema finds, with core's first range error): JSON object, `analysis`, blocks the analysis "
    "does not read, unknown keys and JSON types block by block, then value ranges. Integers may "
    "be written as reals with an integral value (20.0), except /bore/distortion/*/order. The "
    "job's result echoes the scene with every default filled in.";

/* "<Name>Scene": the analysis' top-level block, "analysis" required; its
 * additionalProperties false refuses the blocks only other analyses read,
 * as the parser does. */
static json_t *analysis_schema(const rd_analysis_def *an, json_t *schemas)
{
    rd_scene *defaults = rd_scene_defaults(an);
    json_t *o = defaults ? rd_schema_block_openapi(an->scene, defaults, schemas) : NULL;
    int bad = !o || json_object_set_new(o, "required", json_pack("[s]", "analysis"));
    rd_scene_free(defaults);
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

/* "Scene": oneOf the analyses, discriminated by "analysis". */
static json_t *scene_schema(const rd_analysis_def *const *registry)
{
    json_t *names = json_array(), *mapping = json_object(), *one_of = json_array();
    int bad = !names || !mapping || !one_of;
    for (int i = 0; !bad && registry[i]; i++) {
        char ref[128];
        snprintf(ref, sizeof ref, "#/components/schemas/%s", registry[i]->scene->name);
        bad |= json_array_append_new(names, json_string(registry[i]->name));
        bad |= json_object_set_new(mapping, registry[i]->name, json_string(ref));
        bad |= json_array_append_new(one_of, json_pack("{s:s}", "$ref", ref));
    }
    /* "additionalProperties": true (the default, said out loud): the keys
     * are the branches' business; validators that merge the discriminated
     * branch with this schema (Redocly's example check) otherwise judge the
     * branch's own keys as unevaluated here. */
    json_t *o =
        bad ? NULL
            : json_pack("{s:s, s:[s], s:s, s:{s:{s:s, s:s, s:O}}, s:b, s:{s:s, s:O}, s:O}", "type",
                        "object", "required", "analysis", "description", scene_description,
                        "properties", "analysis", "type", "string", "description",
                        "Which analysis to run; decides which blocks are read.", "enum", names,
                        "additionalProperties", 1, "discriminator", "propertyName", "analysis",
                        "mapping", mapping, "oneOf", one_of);
    json_decref(names);
    json_decref(mapping);
    json_decref(one_of);
    return o;
}

/* "RingpackScene" -> "RingpackResult": the result component of an analysis. */
static void result_name(const rd_analysis_def *an, char *buf, size_t size)
{
    const char *scene = an->scene->name;
    size_t n = strlen(scene);
    if (n >= 5 && strcmp(scene + n - 5, "Scene") == 0)
        n -= 5;
    snprintf(buf, size, "%.*sResult", (int)n, scene);
}

/* The result schema of an analysis the template has none for (a new one):
 * what every result holds, its own members undescribed (the contract test,
 * tests/http/contract.py, refuses them until the template describes them). */
static json_t *placeholder_result(const rd_analysis_def *an)
{
    char scene[128];
    snprintf(scene, sizeof scene, "#/components/schemas/%s", an->scene->name);
    return json_pack("{s:s, s:s, s:[s, s, s], s:{s:{s:s, s:[s]}, s:{s:s}, s:{s:s}}}", "type",
                     "object", "description",
                     "Result of this analysis: its own members are not described yet.", "required",
                     "analysis", "scene", "numerics", "properties", "analysis", "type", "string",
                     "enum", an->name, "scene", "$ref", scene, "numerics", "type", "object");
}

/* The analyses' names where the template's hand-written schemas list them:
 * Job.analysis and Result.analysis (enum), and Result's oneOf and
 * discriminator, one "<Name>Result" per analysis (placeholder_result where
 * the template has none, so the served document never leaves one out). */
static int result_schemas(const rd_analysis_def *const *registry, json_t *schemas, rd_error *err)
{
    json_t *result = json_object_get(schemas, "Result");
    json_t *job_an =
        json_object_get(json_object_get(json_object_get(schemas, "Job"), "properties"), "analysis");
    json_t *res_an = json_object_get(json_object_get(result, "properties"), "analysis");
    if (!json_is_object(job_an) || !json_is_object(res_an))
        return rd_error_set(err, RD_EINTERNAL, "",
                            "the OpenAPI template has no Job.analysis or Result.analysis");
    json_t *names = json_array(), *mapping = json_object(), *one_of = json_array();
    int bad = !names || !mapping || !one_of;
    for (int i = 0; !bad && registry[i]; i++) {
        char name[96], ref[128];
        result_name(registry[i], name, sizeof name);
        snprintf(ref, sizeof ref, "#/components/schemas/%s", name);
        if (!json_object_get(schemas, name))
            bad |= json_object_set_new(schemas, name, placeholder_result(registry[i]));
        bad |= json_array_append_new(names, json_string(registry[i]->name));
        bad |= json_object_set_new(mapping, registry[i]->name, json_string(ref));
        bad |= json_array_append_new(one_of, json_pack("{s:s}", "$ref", ref));
    }
    if (!bad) {
        bad |= json_object_set(job_an, "enum", names) | json_object_set(res_an, "enum", names);
        bad |= json_object_set_new(
            result, "discriminator",
            json_pack("{s:s, s:O}", "propertyName", "analysis", "mapping", mapping));
        bad |= json_object_set(result, "oneOf", one_of);
    }
    json_decref(names);
    json_decref(mapping);
    json_decref(one_of);
    if (bad)
        return rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the OpenAPI document");
    return RD_OK;
}

json_t *rd_registry_openapi(const rd_analysis_def *const *registry, const char *template_json,
                            rd_error *err)
{
    json_error_t jerr;
    json_t *doc = json_loads(template_json ? template_json : "", 0, &jerr);
    json_t *schemas = json_object_get(json_object_get(doc, "components"), "schemas");
    if (!json_is_object(schemas)) {
        rd_error_set(err, RD_EINTERNAL, "",
                     "the OpenAPI template is not an object with components.schemas%s%s",
                     doc ? "" : ": ", doc ? "" : jerr.text);
        json_decref(doc);
        return NULL;
    }
    int bad = json_object_set_new(schemas, "Scene", scene_schema(registry));
    for (int i = 0; !bad && registry[i]; i++)
        bad |= json_object_set_new(schemas, registry[i]->scene->name,
                                   analysis_schema(registry[i], schemas));
    if (bad) {
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the OpenAPI document");
        json_decref(doc);
        return NULL;
    }
    if (result_schemas(registry, schemas, err) != RD_OK) {
        json_decref(doc);
        return NULL;
    }
    return doc;
}
