/*
 * rd-jsonq — prints a value from a JSON document, for the shell tests
 * (which cannot count on jq or python being installed).
 *
 *   rd-jsonq POINTER [FILE]      the value at the JSON Pointer (RFC 6901)
 *   rd-jsonq -n POINTER [FILE]   the number of elements of that array/object
 *
 * Reads FILE, or stdin without one.  A "*" segment maps over every element
 * of an array (one output line each): /result/modes/ * /frequency_hz.
 * Strings print raw, numbers with 17 significant digits, containers as
 * compact JSON.  Exit 1 when the input is not JSON or the pointer matches
 * nothing, 2 on bad usage.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>

/* Decodes one pointer segment (~1 -> /, ~0 -> ~) of at most n bytes. */
static void segment(const char *s, size_t n, char *out)
{
    size_t w = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '~' && i + 1 < n && (s[i + 1] == '0' || s[i + 1] == '1')) {
            out[w++] = s[i + 1] == '0' ? '~' : '/';
            i++;
        } else {
            out[w++] = s[i];
        }
    }
    out[w] = '\0';
}

static int emit(const json_t *v, int count)
{
    if (count) {
        if (json_is_array(v))
            printf("%zu\n", json_array_size(v));
        else if (json_is_object(v))
            printf("%zu\n", json_object_size(v));
        else
            return 1;
        return 0;
    }
    if (json_is_string(v)) {
        printf("%s\n", json_string_value(v));
    } else if (json_is_integer(v)) {
        printf("%" JSON_INTEGER_FORMAT "\n", json_integer_value(v));
    } else if (json_is_real(v)) {
        printf("%.17g\n", json_real_value(v));
    } else {
        char *s = json_dumps(v, JSON_COMPACT | JSON_ENCODE_ANY);
        if (!s)
            return 1;
        printf("%s\n", s);
        free(s);
    }
    return 0;
}

/* Follows `ptr` (rest of the pointer) from v; returns the number of values printed. */
static int walk(const json_t *v, const char *ptr, int count)
{
    if (*ptr == '\0')
        return emit(v, count) == 0;
    if (*ptr != '/')
        return 0;
    ptr++;
    size_t n = strcspn(ptr, "/");
    char *key = malloc(n + 1);
    if (!key)
        return 0;
    segment(ptr, n, key);
    const char *rest = ptr + n;
    int found = 0;
    if (json_is_array(v) && strcmp(key, "*") == 0) {
        for (size_t i = 0; i < json_array_size(v); i++)
            found += walk(json_array_get(v, i), rest, count);
    } else if (json_is_array(v)) {
        char *end;
        unsigned long i = strtoul(key, &end, 10);
        if (*key && !*end && i < json_array_size(v))
            found = walk(json_array_get(v, i), rest, count);
    } else if (json_is_object(v)) {
        const json_t *child = json_object_get(v, key);
        if (child)
            found = walk(child, rest, count);
    }
    free(key);
    return found;
}

int main(int argc, char **argv)
{
    int count = 0, arg = 1;
    if (arg < argc && strcmp(argv[arg], "-n") == 0) {
        count = 1;
        arg++;
    }
    if (arg >= argc || argc - arg > 2) {
        fprintf(stderr, "usage: rd-jsonq [-n] POINTER [FILE]\n");
        return 2;
    }
    const char *ptr = argv[arg];
    json_error_t jerr;
    json_t *root = arg + 1 < argc ? json_load_file(argv[arg + 1], JSON_DECODE_ANY, &jerr)
                                  : json_loadf(stdin, JSON_DECODE_ANY, &jerr);
    if (!root) {
        fprintf(stderr, "rd-jsonq: not JSON: %s (line %d)\n", jerr.text, jerr.line);
        return 1;
    }
    int found = walk(root, ptr, count);
    json_decref(root);
    return found > 0 ? 0 : 1;
}
