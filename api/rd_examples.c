/* rd_examples — the example scenes directory (rd_examples.h). */
#include "rd_examples.h"

#include <dirent.h>
#include <errno.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "rd_scene.h"
#include "rd_schema.h"

int rd_examples_name_ok(const char *name)
{
    size_t n = 0;
    if (!name)
        return 0;
    for (; name[n]; n++) {
        char c = name[n];
        int ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                 c == '_' || c == '-';
        if (!ok || n >= RD_EXAMPLE_NAME_MAX)
            return 0;
    }
    return n > 0;
}

/* dir + "/" + name + ".json", malloc'd; NULL when out of memory. */
static char *example_path(const char *dir, const char *name)
{
    size_t size = strlen(dir) + strlen(name) + sizeof "/.json";
    char *path = malloc(size);
    if (path)
        snprintf(path, size, "%s/%s.json", dir, name);
    return path;
}

/* The whole file at `path` (at most RD_EXAMPLE_FILE_MAX bytes), NUL-terminated. */
static int read_file(const char *path, const char *name, char **buf, size_t *len, rd_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        int e = errno;
        return rd_error_set(err, e == ENOENT ? RD_ENOTFOUND : RD_EINTERNAL, "",
                            e == ENOENT ? "no example named \"%s\"" : "cannot open example \"%s\"",
                            name);
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        fclose(f); /* a directory named <name>.json is not an example */
        return rd_error_set(err, RD_ENOTFOUND, "", "no example named \"%s\"", name);
    }
    int rc = rd_api_read_stream(f, RD_EXAMPLE_FILE_MAX, buf, len);
    fclose(f);
    switch (rc) {
    case RD_OK:
        return RD_OK;
    case RD_ENOMEM:
        return rd_error_set(err, rc, "", "out of memory while reading example \"%s\"", name);
    case RD_ETOOLARGE:
        return rd_error_set(err, RD_EINVAL, "", "example \"%s.json\" is larger than %d bytes", name,
                            RD_EXAMPLE_FILE_MAX);
    default:
        return rd_error_set(err, RD_EINTERNAL, "", "cannot read example \"%s\"", name);
    }
}

/* Reads and validates example `name`; *root is the file's JSON as written
 * (new reference).  A file that is not a valid scene is RD_EINVAL, with
 * the scene error's path and message after the file name. */
static int load_example(const char *dir, const char *name, json_t **root, rd_error *err)
{
    char *path = NULL, *text = NULL;
    size_t len;
    rd_scene *scene = NULL;
    rd_error inner;
    json_error_t jerr;
    int rc;

    *root = NULL;
    path = example_path(dir, name);
    if (!path) {
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while reading example \"%s\"", name);
        goto out;
    }
    rc = read_file(path, name, &text, &len, err);
    if (rc != RD_OK)
        goto out;
    *root = json_loadb(text, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY, &jerr);
    if (!*root) {
        rc = rd_error_set(err, RD_EINVAL, "",
                          "example \"%s.json\" is not valid JSON: %s (line %d, column %d)", name,
                          jerr.text, jerr.line, jerr.column);
        goto out;
    }
    rd_error_init(&inner);
    rc = rd_scene_parse_value(*root, &scene, &inner);
    if (rc != RD_OK && rd_api_http_status(rc) >= 500) /* out of memory: not the file's fault */
        rc = rd_error_set(err, rc, "", "%s (example \"%s.json\")", inner.message, name);
    else if (rc != RD_OK)
        rc = rd_error_set(err, RD_EINVAL, inner.path,
                          "example \"%s.json\" is not a valid scene: %s", name, inner.message);
out:
    if (rc != RD_OK) {
        json_decref(*root);
        *root = NULL;
    }
    rd_scene_free(scene);
    free(text);
    free(path);
    return rc;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The example names in `dir`, sorted: regular files <name>.json.  Hidden
 * files are skipped; any other file name that could not be served is an
 * error, so nobody wonders why their example does not show up. */
static int list_names(const char *dir, char ***names, size_t *count, rd_error *err)
{
    DIR *d = NULL;
    char **list = NULL, *path = NULL, *stem = NULL;
    size_t n = 0, cap = 0;
    struct dirent *de;
    int rc = RD_OK;

    d = opendir(dir);
    if (!d) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "cannot open the examples directory: %s",
                          strerror(errno));
        goto out;
    }
    while ((de = readdir(d)) != NULL) {
        const char *file = de->d_name;
        size_t len = strlen(file);
        struct stat st;
        if (file[0] == '.' || len <= 5 || strcmp(file + len - 5, ".json") != 0)
            continue;
        stem = strndup(file, len - 5);
        path = stem ? example_path(dir, stem) : NULL;
        if (!path) {
            rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while listing the examples");
            goto out;
        }
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) {
            free(path);
            free(stem);
            path = stem = NULL;
            continue;
        }
        if (!rd_examples_name_ok(stem)) {
            rc = rd_error_set(err, RD_EINVAL, "",
                              "example file \"%.80s\": the name before .json may only use A-Z, "
                              "a-z, 0-9, _ and - (at most %d characters)",
                              file, RD_EXAMPLE_NAME_MAX);
            goto out;
        }
        if (n == cap) {
            size_t new_cap = cap ? 2 * cap : 16;
            char **grown = realloc(list, new_cap * sizeof *grown);
            if (!grown) {
                rc = rd_error_set(err, RD_ENOMEM, "", "out of memory while listing the examples");
                goto out;
            }
            list = grown;
            cap = new_cap;
        }
        list[n++] = stem;
        stem = NULL;
        free(path);
        path = NULL;
    }
    if (n > 1)
        qsort(list, n, sizeof *list, compare_names);
out:
    if (d)
        closedir(d);
    free(path);
    free(stem);
    if (rc != RD_OK) {
        for (size_t i = 0; i < n; i++)
            free(list[i]);
        free(list);
        list = NULL;
        n = 0;
    }
    *names = list;
    *count = n;
    return rc;
}

char *rd_api_examples_json(const char *dir, rd_error *err)
{
    char **names = NULL;
    size_t n = 0;
    json_t *list = NULL, *root = NULL, *body = NULL;
    char *text = NULL;

    if (list_names(dir, &names, &n, err) != RD_OK)
        goto out;
    list = json_array();
    for (size_t i = 0; list && i < n; i++) {
        if (load_example(dir, names[i], &root, err) != RD_OK)
            goto out;
        const char *description = json_string_value(json_object_get(root, "description"));
        json_t *entry = json_pack("{s:s, s:s, s:o}", "name", names[i], "description",
                                  description ? description : "", "scene", root);
        root = NULL; /* stolen by json_pack, also when it fails */
        if (json_array_append_new(list, entry) != 0) {
            json_decref(list);
            list = NULL;
        }
    }
    body = list ? json_pack("{s:O}", "examples", list) : NULL;
    /* a scene as written, unless 15 digits would change one of its reals
     * (0.49999999999999994 to 0.5): found by tests/fuzz */
    text = body ? json_dumps(body, JSON_COMPACT | JSON_REAL_PRECISION(rd_scene_real_digits(body)))
                : NULL;
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while listing the examples");
out:
    json_decref(body);
    json_decref(list);
    json_decref(root);
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    return text;
}

int rd_examples_name_malformed(const char *name)
{
    const unsigned char *p = (const unsigned char *)(name ? name : "");
    while (*p) {
        int n = rd_schema_utf8_len(p);
        if (n == 0 || *p < 0x20 || *p == 0x7f)
            return 1;
        p += n;
    }
    return 0;
}

char *rd_api_example_scene(const char *dir, const char *name, rd_error *err)
{
    json_t *root = NULL;
    char *text = NULL;

    if (rd_examples_name_malformed(name)) {
        rd_error_set(err, RD_EREQUEST, "",
                     "an example name is printable UTF-8 text; this one is not");
        goto out;
    }
    if (!rd_examples_name_ok(name)) {
        char q[80];
        rd_schema_quote(q, sizeof q, name ? name : "");
        rd_error_set(err, RD_ENOTFOUND, "",
                     "no example named %s (names use A-Z, a-z, 0-9, _ and -; GET "
                     "/api/v1/examples lists them)",
                     q);
        goto out;
    }
    if (load_example(dir, name, &root, err) != RD_OK)
        goto out;
    text = json_dumps(root, JSON_COMPACT | JSON_REAL_PRECISION(rd_scene_real_digits(root)));
    if (!text)
        rd_error_set(err, RD_ENOMEM, "", "out of memory while writing example \"%s\"", name);
out:
    json_decref(root);
    return text;
}
