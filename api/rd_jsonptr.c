/* rd_jsonptr — JSON Pointer get/set/collect (RFC 6901), see rd_jsonptr.h. */
#include "rd_jsonptr.h"

#include <stdlib.h>
#include <string.h>

int rd_jsonptr_valid(const char *ptr)
{
    if (!ptr || (ptr[0] != '\0' && ptr[0] != '/'))
        return 0;
    for (const char *c = ptr; *c; c++)
        if (*c == '~' && c[1] != '0' && c[1] != '1')
            return 0;
    return 1;
}

/* Decodes the token that starts at `*at` (just after its '/') into a new
 * string and moves `*at` to the next '/' or the end.  NULL on out of memory. */
static char *next_token(const char **at)
{
    const char *s = *at;
    size_t n = strcspn(s, "/");
    char *tok = malloc(n + 1);
    if (!tok)
        return NULL;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '~' && i + 1 < n && (s[i + 1] == '0' || s[i + 1] == '1')) {
            tok[k++] = s[i + 1] == '0' ? '~' : '/';
            i++;
        } else {
            tok[k++] = s[i];
        }
    }
    tok[k] = '\0';
    *at = s + n;
    return tok;
}

/* An array index token: digits, no leading zero unless "0"; -1 otherwise. */
static long array_index(const char *tok)
{
    size_t n = strlen(tok);
    if (n == 0 || n > 9 || (n > 1 && tok[0] == '0'))
        return -1;
    for (size_t i = 0; i < n; i++)
        if (tok[i] < '0' || tok[i] > '9')
            return -1;
    return strtol(tok, NULL, 10);
}

/* The child `tok` names in `v`, or NULL. */
static json_t *child(json_t *v, const char *tok)
{
    if (json_is_object(v))
        return json_object_get(v, tok);
    if (json_is_array(v)) {
        long k = array_index(tok);
        return k >= 0 ? json_array_get(v, (size_t)k) : NULL;
    }
    return NULL;
}

int rd_jsonptr_lookup(json_t *root, const char *ptr, json_t **out)
{
    *out = NULL;
    if (!rd_jsonptr_valid(ptr))
        return -1;
    json_t *v = root;
    const char *at = ptr;
    while (v && *at == '/') {
        at++;
        char *tok = next_token(&at);
        if (!tok)
            return -2;
        v = child(v, tok);
        free(tok);
    }
    *out = v;
    return v ? 0 : -1;
}

json_t *rd_jsonptr_get(json_t *root, const char *ptr)
{
    json_t *v;
    rd_jsonptr_lookup(root, ptr, &v);
    return v;
}

int rd_jsonptr_set(json_t *root, const char *ptr, json_t *value)
{
    if (!rd_jsonptr_valid(ptr) || ptr[0] == '\0' || !root) {
        json_decref(value);
        return -1;
    }
    json_t *v = root;
    const char *at = ptr;
    int rc = -1, oom = !value; /* the path is valid: a failed set or object is memory */
    while (*at == '/') {
        at++;
        char *tok = next_token(&at);
        if (!tok) {
            oom = 1;
            break;
        }
        int last = *at == '\0';
        if (json_is_object(v)) {
            json_t *c = json_object_get(v, tok);
            if (last) {
                rc = json_object_set(v, tok, value);
                oom |= rc != 0;
            } else if (!c) {
                c = json_object();
                if (!c || json_object_set_new(v, tok, c) != 0) {
                    c = NULL;
                    oom = 1;
                }
            }
            v = c;
        } else if (json_is_array(v)) {
            long k = array_index(tok);
            size_t n = json_array_size(v);
            if (last && k >= 0 && (size_t)k <= n) {
                rc = (size_t)k < n ? json_array_set(v, (size_t)k, value)
                                   : json_array_append(v, value);
                oom |= rc != 0;
            }
            v = k >= 0 ? json_array_get(v, (size_t)k) : NULL;
        } else {
            v = NULL;
        }
        free(tok);
        if (last || !v)
            break;
    }
    json_decref(value);
    return rc == 0 ? 0 : oom ? -2 : -1;
}

/* Collects from `v` what the rest of the pointer, `at`, names. */
static int collect(json_t *v, const char *at, json_t *out)
{
    if (*at != '/')
        return json_array_append(out, v);
    at++;
    char *tok = next_token(&at);
    if (!tok)
        return -1;
    int rc = 0;
    if (strcmp(tok, "*") == 0 && json_is_array(v)) {
        for (size_t k = 0; rc == 0 && k < json_array_size(v); k++)
            rc = collect(json_array_get(v, k), at, out);
    } else if (strcmp(tok, "*") == 0 && json_is_object(v)) {
        const char *key;
        json_t *c;
        json_object_foreach(v, key, c)
        {
            if (rc == 0)
                rc = collect(c, at, out);
        }
    } else {
        json_t *c = child(v, tok);
        if (c)
            rc = collect(c, at, out);
    }
    free(tok);
    return rc;
}

int rd_jsonptr_collect(json_t *root, const char *ptr, json_t *out)
{
    if (!rd_jsonptr_valid(ptr) || !root || !json_is_array(out))
        return -1;
    return collect(root, ptr, out);
}
