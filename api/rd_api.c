/*
 * rd_api — errors as JSON and HTTP statuses, the OpenAPI document, version
 * (rd_api.h).  Parsing lives in rd_scene.c (with the tables of
 * rd_schema.c), the analyses in rd_an_*.c listed by rd_registry.c, running
 * and CSV in rd_result.c, the example scenes in rd_examples.c.
 */
#include "rd_api.h"

#include <jansson.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rd_jsonptr.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_schema.h"

#ifndef RINGDYN_VERSION
#define RINGDYN_VERSION "unknown"
#endif

const char *rd_api_version(void)
{
    return RINGDYN_VERSION;
}

char *rd_api_openapi_json(const char *template_json, rd_error *err)
{
    json_t *doc = rd_registry_openapi(rd_registry, template_json, err);
    char *text =
        doc ? json_dumps(doc, JSON_INDENT(2) | JSON_REAL_PRECISION(RD_SCENE_REAL_DIGITS)) : NULL;
    if (doc && !text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing the OpenAPI document");
    json_decref(doc);
    return text;
}

char *rd_api_json_pretty(const char *json)
{
    json_t *v = json_loads(json ? json : "", JSON_DECODE_ANY, NULL);
    char *text =
        v ? json_dumps(v, JSON_INDENT(2) | JSON_REAL_PRECISION(RD_SCENE_REAL_DIGITS)) : NULL;
    json_decref(v);
    return text;
}

/* Copies s to out (size >= strlen(s) + 1) with every byte that does not
 * start a valid UTF-8 sequence replaced by '?': messages quote user text and
 * may have been cut mid-character, but JSON strings must be valid UTF-8. */
static void utf8_sanitize(const char *s, char *out)
{
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        int n = rd_schema_utf8_len(p);
        if (n == 0) {
            *out++ = '?';
            p++;
            continue;
        }
        memcpy(out, p, (size_t)n);
        out += n;
        p += n;
    }
    *out = '\0';
}

char *rd_api_error_json(const rd_error *err)
{
    char message[RD_ERROR_MESSAGE_MAX], path[RD_ERROR_PATH_MAX];
    int code = err ? err->code : RD_EINTERNAL;

    if (code == RD_OK) {
        /* A caller bug, but the client still deserves a well-formed error. */
        code = RD_EINTERNAL;
        utf8_sanitize("an error was reported without details", message);
        path[0] = '\0';
    } else if (!err) {
        utf8_sanitize(rd_error_summary(code), message);
        path[0] = '\0';
    } else {
        /* bounded copies: err's arrays need not be NUL-terminated by callers */
        char m[RD_ERROR_MESSAGE_MAX], p[RD_ERROR_PATH_MAX];
        memcpy(m, err->message, sizeof m);
        memcpy(p, err->path, sizeof p);
        m[sizeof m - 1] = '\0';
        p[sizeof p - 1] = '\0';
        utf8_sanitize(m[0] ? m : rd_error_summary(code), message);
        utf8_sanitize(p, path);
    }
    json_t *body = json_pack("{s:{s:s, s:s, s:s*}}", "error", "code", rd_error_code_name(code),
                             "message", message, "path", path[0] ? path : NULL);
    char *text = body ? json_dumps(body, JSON_COMPACT) : NULL;
    json_decref(body);
    return text;
}

/* One entry of "errors"; `root` (may be NULL) is the scene, for "value". */
static json_t *issue_json(int code, const char *path, const char *message, const char *allowed,
                          const char *dym, json_t *root)
{
    char m[RD_ERROR_MESSAGE_MAX], a[sizeof((rd_issue *)0)->allowed];
    utf8_sanitize(message, m);
    json_t *o =
        json_pack("{s:s, s:s, s:s}", "code", rd_error_code_name(code), "path", path, "message", m);
    json_t *value = root && path[0] ? rd_jsonptr_get(root, path) : NULL;
    int bad = !o || (value && json_object_set(o, "value", value) != 0);
    if (!bad && allowed && allowed[0]) {
        utf8_sanitize(allowed, a);
        bad = json_object_set_new(o, "allowed", json_string(a)) != 0;
    }
    if (!bad && dym && dym[0])
        bad = json_object_set_new(o, "did_you_mean", json_string(dym)) != 0;
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

/* {"error", "errors"[, "errors_omitted"]}: errors[0] is err, completed by
 * the issue at its path (whose suggestion also goes to error.did_you_mean:
 * the message itself stays as it was); then every issue at another path. */
static char *error_body(const rd_error *err, const rd_issues *issues, json_t *root)
{
    char *first = rd_api_error_json(err);
    json_t *body = first ? json_loads(first, 0, NULL) : NULL;
    free(first);
    json_t *error = json_object_get(body, "error"), *list = json_array();
    const char *path = json_string_value(json_object_get(error, "path"));
    path = path ? path : "";
    const rd_issue *same = NULL;
    for (int i = 0; issues && i < issues->n && !same; i++)
        if (strcmp(issues->item[i].path, path) == 0)
            same = &issues->item[i];
    int bad =
        !error || !list ||
        json_array_append_new(
            list, issue_json(err->code, path, json_string_value(json_object_get(error, "message")),
                             same ? same->allowed : NULL, same ? same->did_you_mean : NULL, root));
    for (int i = 0; !bad && issues && i < issues->n; i++) {
        const rd_issue *it = &issues->item[i];
        if (strcmp(it->path, path) != 0)
            bad = json_array_append_new(list, issue_json(it->code, it->path, it->message,
                                                         it->allowed, it->did_you_mean, root));
    }
    if (!bad && same && same->did_you_mean[0])
        bad = json_object_set_new(error, "did_you_mean", json_string(same->did_you_mean)) != 0;
    bad = bad || json_object_set(body, "errors", list) != 0;
    if (!bad && issues && issues->dropped > 0)
        bad = json_object_set_new(body, "errors_omitted", json_integer(issues->dropped)) != 0;
    size_t flags = JSON_COMPACT | JSON_REAL_PRECISION(RD_SCENE_REAL_DIGITS);
    char *text = bad ? NULL : json_dumps(body, flags);
    json_decref(list);
    json_decref(body);
    return text ? text : rd_api_error_json(err);
}

int rd_scene_parse_report(const char *body, size_t len, rd_scene **out, rd_error *err,
                          char **error_json)
{
    rd_issues *issues = calloc(1, sizeof *issues); /* NULL: no list, still the error */
    json_t *root = NULL;
    int rc = rd_scene_parse_keep(body, len, out, err, issues, &root);
    if (error_json)
        *error_json = rc != RD_OK ? error_body(err, issues, root) : NULL;
    json_decref(root);
    free(issues);
    return rc;
}

int rd_scene_parse_report_as(const char *body, size_t len, const char *analysis, rd_scene **out,
                             rd_error *err, char **error_json)
{
    json_t *root = analysis && len <= RD_API_BODY_MAX ? json_loadb(body, len, 0, NULL) : NULL;
    if (!json_is_object(root)) { /* not JSON, or not an object: the usual answer */
        json_decref(root);
        return rd_scene_parse_report(body, len, out, err, error_json);
    }
    json_t *given = json_object_get(root, "analysis");
    int rc = RD_OK;
    *out = NULL;
    if (!given)
        rc = json_object_set_new(root, "analysis", json_string(analysis)) == 0 ? RD_OK : RD_ENOMEM;
    else if (!json_is_string(given) || strcmp(json_string_value(given), analysis) != 0)
        rc = rd_error_set(err, RD_EREQUEST, "/analysis",
                          "/analysis: this path takes a %s (\"analysis\" absent or \"%s\"); "
                          "submit other scenes to /api/v1/jobs",
                          analysis, analysis);
    char *text = rc == RD_OK ? json_dumps(root, JSON_COMPACT) : NULL;
    json_decref(root);
    if (rc == RD_OK && !text)
        rc = RD_ENOMEM;
    if (rc == RD_ENOMEM)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while reading the body");
    if (rc != RD_OK) {
        if (error_json)
            *error_json = rd_api_error_json(err);
        return rc;
    }
    rc = rd_scene_parse_report(text, strlen(text), out, err, error_json);
    free(text);
    return rc;
}

int rd_api_http_status(int code)
{
    switch (code) {
    case RD_OK:
        return 200;
    case RD_EJSON:
    case RD_EREQUEST:
        return 400;
    case RD_ENOTFOUND:
        return 404;
    case RD_EMETHOD:
        return 405;
    case RD_ETOOLARGE:
        return 413;
    case RD_EMEDIA:
        return 415;
    case RD_EINVAL:
    case RD_ELIMIT:
        return 422;
    case RD_EBUSY:
        return 429;
    case RD_ENOMEM:
        return 503;
    default:
        return 500;
    }
}

int rd_api_read_stream(FILE *f, size_t max, char **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    if (max == SIZE_MAX)
        return RD_ETOOLARGE;
    char *b = malloc(max + 1);
    if (!b)
        return RD_ENOMEM;
    size_t n = fread(b, 1, max + 1, f);
    if (ferror(f)) {
        free(b);
        return RD_EREQUEST;
    }
    if (n > max) {
        free(b);
        return RD_ETOOLARGE;
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return RD_OK;
}
