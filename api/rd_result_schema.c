/*
 * rd_result_schema — result pointers against the result schemas of the
 * embedded OpenAPI document (rd_result_schema.h).
 */
#include "rd_result_schema.h"

#include <ctype.h>
#include <jansson.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_openapi_doc.h"
#include "rd_schema.h"

#define NAMES_MAX 64 /* properties listed (and searched for the closest) */

/* The document, parsed on first use and kept (retried while out of memory). */
static json_t *doc;
static pthread_mutex_t doc_lock = PTHREAD_MUTEX_INITIALIZER;

static json_t *schemas(void)
{
    pthread_mutex_lock(&doc_lock);
    if (!doc)
        doc = json_loadb(rd_openapi_json, rd_openapi_json_len, 0, NULL);
    json_t *d = doc;
    pthread_mutex_unlock(&doc_lock);
    return json_object_get(json_object_get(d, "components"), "schemas");
}

/* The schema a $ref names (only #/components/schemas/...; NULL: not held). */
static json_t *deref(json_t *s)
{
    for (int hops = 0; s && hops < 16; hops++) {
        const char *ref = json_string_value(json_object_get(s, "$ref"));
        if (!ref)
            return s;
        static const char prefix[] = "#/components/schemas/";
        if (strncmp(ref, prefix, sizeof prefix - 1) != 0)
            return NULL;
        s = json_object_get(schemas(), ref + sizeof prefix - 1);
    }
    return NULL;
}

/* The walk's answer for one token at schema s: 1 with *next set (NULL: the
 * rest unchecked), 0 when s cannot hold it (names[] its properties). */
static int step(json_t *s, const char *tok, json_t **next, const char **names, int *n);

static int step_all(json_t *list, const char *tok, json_t **next, const char **names, int *n)
{
    size_t i;
    json_t *m;
    json_array_foreach(list, i, m)
    {
        if (step(m, tok, next, names, n))
            return 1;
    }
    return 0;
}

static int step(json_t *s, const char *tok, json_t **next, const char **names, int *n)
{
    s = deref(s);
    *next = NULL;
    if (!s)
        return 1; /* not in the template: unchecked */
    json_t *all = json_object_get(s, "allOf"), *one = json_object_get(s, "oneOf");
    json_t *any = json_object_get(s, "anyOf");
    if (all || one || any)
        return step_all(all ? all : one ? one : any, tok, next, names, n);
    json_t *props = json_object_get(s, "properties"), *items = json_object_get(s, "items");
    if (items) { /* an array: an index, or an aggregate's * (every element) */
        if (strcmp(tok, "*") == 0) {
            *next = items;
            return 1;
        }
        for (const char *c = tok; *c; c++)
            if (!isdigit((unsigned char)*c))
                return 0;
        *next = *tok ? items : NULL;
        return *tok != '\0';
    }
    if (strcmp(tok, "*") == 0)
        return 1; /* every member of an object: the rest unchecked */
    json_t *p = props ? json_object_get(props, tok) : NULL;
    if (p) {
        *next = p;
        return 1;
    }
    json_t *extra = json_object_get(s, "additionalProperties");
    if (json_is_object(extra)) {
        *next = extra;
        return 1;
    }
    const char *type = json_string_value(json_object_get(s, "type"));
    if (!props && !json_is_false(extra) && (!type || strcmp(type, "object") == 0))
        return 1; /* a free-form object: unchecked */
    if (!props) { /* a number, a string, ...: no members */
        *n = -1;
        return 0;
    }
    const char *key;
    json_t *v;
    json_object_foreach(props, key, v)
    {
        if (*n < NAMES_MAX - 1)
            names[(*n)++] = key;
    }
    return 0;
}

/* The token at ptr (unescaped ~1 ~0) into tok; the rest after it. */
static const char *token(const char *ptr, char *tok, size_t size)
{
    size_t k = 0;
    for (ptr++; *ptr && *ptr != '/'; ptr++) {
        char c = *ptr;
        if (c == '~' && (ptr[1] == '0' || ptr[1] == '1'))
            c = *++ptr == '0' ? '~' : '/';
        if (k + 1 < size)
            tok[k++] = c;
    }
    tok[k] = '\0';
    return ptr;
}

int rd_result_pointer_check(const char *analysis, const char *ptr, const char *path, rd_error *err)
{
    char name[64];
    snprintf(name, sizeof name, "%sResult", analysis ? analysis : "");
    name[0] = (char)toupper((unsigned char)name[0]);
    json_t *all = schemas(), *s = json_object_get(all, name);
    if (!all)
        return rd_error_set(err, RD_ENOMEM, path, "out of memory while checking %s", path);
    const char *at = ptr;
    while (s && at && *at == '/') {
        char tok[128];
        const char *rest = token(at, tok, sizeof tok), *names[NAMES_MAX] = {NULL};
        int n = 0;
        json_t *next;
        if (!step(s, tok, &next, names, &n)) {
            char list[400];
            size_t used = 0;
            list[0] = '\0';
            for (int k = 0; k < n && used < sizeof list; k++)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", k ? ", " : "",
                                         names[k]);
            const char *close = n > 0 ? rd_schema_closest(tok, names) : NULL;
            char where[160];
            snprintf(where, sizeof where, "%.*s", (int)(at - ptr), ptr);
            return rd_error_set(
                err, RD_EREQUEST, path, "%s = \"%s\": a %s result has no \"%s\" %s%s (%s%s%s%s%s)",
                path, ptr, analysis, tok, at == ptr ? "at its top level" : "in ", where,
                n > 0   ? "there: "
                : n < 0 ? "a value, no members"
                        : "an array: an index, 0, 1, ...",
                list, close ? "; did you mean \"" : "", close ? close : "", close ? "\"?" : "");
        }
        s = next;
        at = rest;
    }
    return RD_OK;
}
