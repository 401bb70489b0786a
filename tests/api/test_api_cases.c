/*
 * test_api_cases — API cases as data: every folder CASES_DIR/<name>/ holds
 * request.json (the body, sent as bytes, so it may be broken JSON) and
 * expected.json, a subset of the answer:
 *
 *   {"status": 422, "error": {"code": "invalid_scene", "path": "/ring/diameter"},
 *    "message_contains": "must be a number",       (string or array of strings)
 *    "tolerance": {"rel": 1e-9, "abs": 0},          (for numbers; default rel 1e-9)
 *    "comment": "..."}                              (ignored)
 *   {"status": 200, "result": {"rigid_body_modes": 6, "modes": [{...}, ...]}}
 *
 * The answer is built in-process as the server would: rd_scene_parse_report,
 * then rd_scene_run; status = rd_api_http_status of the error (200 on
 * success), "error" and "errors" = the error body's, "result" = the result
 * JSON.  Matching:
 * every key of an expected object must be present and match; arrays must
 * have the same length and match element by element; numbers within the
 * tolerance; everything else equal.
 *
 * usage: test_api_cases CASES_DIR [case ...]
 */
#include <dirent.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "rd_api.h"

#define MIN_CASES 15

typedef struct tolerance {
    double rel, abs;
} tolerance;

/* Recursive "expected is a subset of actual"; prints the first mismatch
 * with its JSON Pointer.  Returns 1 on a match. */
static int match(json_t *want, json_t *got, const char *path, const tolerance *tol,
                 const char *name)
{
    char child[512];
    if (json_is_number(want)) {
        double w = json_number_value(want), g = json_number_value(got);
        if (!json_is_number(got) || !(fabs(g - w) <= tol->abs + tol->rel * fabs(w))) {
            char *text = got ? json_dumps(got, JSON_ENCODE_ANY | JSON_COMPACT) : NULL;
            fprintf(stderr, "case %s: %s is %.200s, want %.17g (rel %g, abs %g)\n", name,
                    path[0] ? path : "/", text ? text : "(missing)", w, tol->rel, tol->abs);
            free(text);
            return 0;
        }
        return 1;
    }
    if (json_is_object(want)) {
        const char *key;
        json_t *v;
        if (!json_is_object(got)) {
            fprintf(stderr, "case %s: %s is not an object\n", name, path[0] ? path : "/");
            return 0;
        }
        json_object_foreach(want, key, v)
        {
            snprintf(child, sizeof child, "%s/%s", path, key);
            if (!match(v, json_object_get(got, key), child, tol, name))
                return 0;
        }
        return 1;
    }
    if (json_is_array(want)) {
        size_t i;
        json_t *v;
        if (!json_is_array(got) || json_array_size(got) != json_array_size(want)) {
            fprintf(stderr, "case %s: %s has %zu elements, want %zu\n", name, path,
                    json_array_size(got), json_array_size(want));
            return 0;
        }
        json_array_foreach(want, i, v)
        {
            snprintf(child, sizeof child, "%s/%zu", path, i);
            if (!match(v, json_array_get(got, i), child, tol, name))
                return 0;
        }
        return 1;
    }
    if (!got || !json_equal(want, got)) {
        char *w = json_dumps(want, JSON_ENCODE_ANY);
        char *g = got ? json_dumps(got, JSON_ENCODE_ANY) : NULL;
        fprintf(stderr, "case %s: %s is %.200s, want %s\n", name, path, g ? g : "(missing)",
                w ? w : "?");
        free(w);
        free(g);
        return 0;
    }
    return 1;
}

static char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t cap = 0, n = 0;
    if (!f)
        return NULL;
    for (;;) {
        if (n + 4096 + 1 > cap) {
            cap = 2 * cap + 8192;
            char *b = realloc(buf, cap);
            if (!b) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = b;
        }
        size_t got = fread(buf + n, 1, 4096, f);
        n += got;
        if (got < 4096)
            break;
    }
    fclose(f);
    buf[n] = '\0';
    *len = n;
    return buf;
}

/* Every accepted scene's echo (rd_scene_to_json, what the server stores
 * and a client may submit again) parses back into a scene with the same
 * echo.  Returns 1 when it does. */
static int echo_round_trips(const rd_scene *scene, const char *name)
{
    char *echo = rd_scene_to_json(scene), *again_echo = NULL;
    rd_scene *again = NULL;
    rd_error err;
    rd_error_init(&err);
    int ok = echo && rd_scene_parse(echo, strlen(echo), &again, &err) == RD_OK &&
             (again_echo = rd_scene_to_json(again)) && strcmp(echo, again_echo) == 0;
    if (!ok)
        fprintf(stderr, "case %s: the echo %.300s does not parse back into itself (%s)\n", name,
                echo ? echo : "(none)", err.message);
    free(again_echo);
    rd_scene_free(again);
    free(echo);
    return ok;
}

/* The answer to `body` as {"status", "error", "errors"[, "errors_omitted"]}
 * (the error body of rd_scene_parse_report, or rd_api_error_json's for a
 * failed run) or {"status", "result"}.  *echo_ok: 0 when the scene was
 * accepted and its echo does not round-trip (echo_round_trips). */
static json_t *answer(const char *body, size_t len, const char *name, int *echo_ok)
{
    rd_error err;
    rd_scene *scene = NULL;
    char *result = NULL, *e = NULL;
    json_t *out = NULL;

    rd_error_init(&err);
    *echo_ok = 1;
    if (rd_scene_parse_report(body, len, &scene, &err, &e) == RD_OK)
        *echo_ok = echo_round_trips(scene, name);
    if (scene && rd_scene_run(scene, NULL, &result, &err) == RD_OK) {
        out = json_pack("{s:i, s:o}", "status", 200, "result", json_loads(result, 0, NULL));
    } else {
        if (!e)
            e = rd_api_error_json(&err);
        out = e ? json_loads(e, 0, NULL) : NULL;
        if (out)
            json_object_set_new(out, "status", json_integer(rd_api_http_status(err.code)));
        free(e);
    }
    free(result);
    rd_scene_free(scene);
    return out;
}

static int contains(json_t *answer_json, const char *needle, const char *name)
{
    const char *message =
        json_string_value(json_object_get(json_object_get(answer_json, "error"), "message"));
    if (!message || !strstr(message, needle)) {
        fprintf(stderr, "case %s: message \"%s\" lacks \"%s\"\n", name,
                message ? message : "(none)", needle);
        return 0;
    }
    return 1;
}

/* Every error answer lists its first problem again as errors[0], with the
 * same code, path and message (what scripts reading "error" rely on). */
static int first_is_error(json_t *got, const char *name)
{
    json_t *error = json_object_get(got, "error");
    if (!error)
        return 1;
    json_t *first = json_array_get(json_object_get(got, "errors"), 0);
    const char *keys[] = {"code", "path", "message"};
    for (int k = 0; k < 3; k++) {
        json_t *a = json_object_get(error, keys[k]), *b = json_object_get(first, keys[k]);
        int same = a ? b && json_equal(a, b) : !b || strcmp(json_string_value(b), "") == 0;
        if (!first || !same) {
            fprintf(stderr, "case %s: errors[0].%s differs from error.%s\n", name, keys[k],
                    keys[k]);
            return 0;
        }
    }
    return 1;
}

static int run_case(const char *dir, const char *name)
{
    char path[1024];
    size_t len = 0;
    json_error_t jerr;
    int ok = 1;

    snprintf(path, sizeof path, "%s/%s/request.json", dir, name);
    char *body = read_all(path, &len);
    snprintf(path, sizeof path, "%s/%s/expected.json", dir, name);
    json_t *expected = json_load_file(path, JSON_REJECT_DUPLICATES, &jerr);
    if (!body || !json_is_object(expected)) {
        fprintf(stderr, "case %s: cannot read request.json / expected.json (%s)\n", name,
                jerr.text);
        free(body);
        json_decref(expected);
        return 0;
    }

    tolerance tol = {1e-9, 0.0};
    json_t *t = json_object_get(expected, "tolerance");
    if (json_is_number(json_object_get(t, "rel")))
        tol.rel = json_number_value(json_object_get(t, "rel"));
    if (json_is_number(json_object_get(t, "abs")))
        tol.abs = json_number_value(json_object_get(t, "abs"));
    json_t *needles = json_object_get(expected, "message_contains");
    json_incref(needles);
    json_object_del(expected, "tolerance");
    json_object_del(expected, "message_contains");
    json_object_del(expected, "comment");
    if (!json_is_integer(json_object_get(expected, "status"))) {
        fprintf(stderr, "case %s: expected.json needs an integer \"status\"\n", name);
        ok = 0;
    }

    int echo_ok;
    json_t *got = answer(body, len, name, &echo_ok);
    ok = ok && echo_ok && got && match(expected, got, "", &tol, name) && first_is_error(got, name);
    if (json_is_string(needles))
        ok = contains(got, json_string_value(needles), name) && ok;
    size_t i;
    json_t *v;
    json_array_foreach(needles, i, v) ok = contains(got, json_string_value(v), name) && ok;
    if (!ok && got) {
        char *text = json_dumps(got, JSON_COMPACT);
        fprintf(stderr, "case %s: answer was %.600s%s\n", name, text ? text : "?",
                text && strlen(text) > 600 ? "..." : "");
        free(text);
    }
    printf("%s %s\n", ok ? "ok  " : "FAIL", name);

    json_decref(got);
    json_decref(needles);
    json_decref(expected);
    free(body);
    return ok;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s CASES_DIR [case ...]\n", argv[0]);
        return 2;
    }
    const char *dir = argv[1];
    if (argc > 2) {
        for (int i = 2; i < argc; i++)
            CHECK(run_case(dir, argv[i]), "case %s", argv[i]);
        return check_done();
    }

    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "cannot open %s\n", dir);
        return 2;
    }
    char **names = NULL;
    size_t n = 0;
    struct dirent *de;
    while ((de = readdir(d)) != NULL) {
        char path[1024];
        struct stat st;
        if (de->d_name[0] == '.')
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode))
            continue;
        char **grown = realloc(names, (n + 1) * sizeof *names);
        if (!grown)
            break;
        names = grown;
        names[n++] = strdup(de->d_name);
    }
    closedir(d);
    if (n)
        qsort(names, n, sizeof *names, by_name);
    CHECK(n >= MIN_CASES, "%zu cases in %s, want at least %d", n, dir, MIN_CASES);
    for (size_t i = 0; i < n; i++) {
        CHECK(names[i] && run_case(dir, names[i]), "case %s", names[i] ? names[i] : "?");
        free(names[i]);
    }
    free(names);
    return check_done();
}
