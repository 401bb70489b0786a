/*
 * rd_http_util — the bottom of the HTTP layer (rd_http_int.h): text checks,
 * the parsing of paths, media types and query values, and the buffers of
 * request bodies.  Calls nothing else of the server.
 *
 * Paths arrive percent-decoded by rd_http_unescape_path, which turns an
 * encoded NUL into DEL (0x7f) so that it cannot cut the C string short;
 * every path with a control character is then refused (404).
 *
 * Request bodies past BODY_HEAP_MAX live in a mapping of their own: a burst
 * of 1 MiB bodies, freed into the HTTP threads' arenas, stayed there (an
 * arena keeps up to main.c's trim threshold at its top, and malloc_trim
 * cannot return an arena's top other than the main one's); a mapping goes
 * back to the kernel when the request ends, and only the pages a body fills
 * are touched.
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */
#include "rd_http_int.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/mman.h>
#include <unistd.h>

/* Bodies up to this are malloc'd (a scene is a few kB). */
#define BODY_HEAP_MAX (64 * 1024)

/* A copy of `s` fit for a message: rd_http_printable ASCII only, at most n-1 bytes.
 * (Error bodies must be valid UTF-8; request text need not be.) */
const char *rd_http_printable(const char *s, char *buf, size_t n)
{
    size_t i = 0;
    for (; s[i] && i + 1 < n; i++)
        buf[i] = (s[i] >= 0x20 && s[i] < 0x7f) ? s[i] : '?';
    buf[i] = '\0';
    if (s[i] && n > 4)
        memcpy(buf + n - 4, "...", 4);
    return buf;
}

int rd_http_has_control_char(const char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f)
            return 1;
    return 0;
}

static int hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* MHD_OPTION_UNESCAPE_CALLBACK: decodes %HH in place, as MHD's default does,
 * except that %00 becomes DEL (see the file comment). */
size_t rd_http_unescape_path(void *cls, struct MHD_Connection *c, char *s)
{
    (void)cls;
    (void)c;
    char *w = s;
    const char *r = s;
    while (*r) {
        int hi, lo;
        if (r[0] == '%' && (hi = hex_value(r[1])) >= 0 && (lo = hex_value(r[2])) >= 0) {
            int v = hi * 16 + lo;
            *w++ = v == 0 ? (char)0x7f : (char)v;
            r += 3;
        } else {
            *w++ = *r++;
        }
    }
    *w = '\0';
    return (size_t)(w - s);
}

/* "application/json", optionally "; charset=utf-8" (any case, optional
 * quotes).  Any other parameter or charset is refused: the api reads UTF-8. */
int rd_http_is_json_media_type(const char *ct)
{
    if (!ct)
        return 0;
    while (*ct == ' ' || *ct == '\t')
        ct++;
    if (strncasecmp(ct, "application/json", 16) != 0)
        return 0;
    const char *p = ct + 16;
    while (*p == ' ' || *p == '\t')
        p++;
    if (*p == '\0')
        return 1;
    if (*p++ != ';')
        return 0;
    while (*p == ' ' || *p == '\t')
        p++;
    if (strncasecmp(p, "charset=", 8) != 0)
        return 0;
    p += 8;
    int quoted = *p == '"';
    p += quoted;
    if (strncasecmp(p, "utf-8", 5) != 0)
        return 0;
    p += 5;
    if (quoted && *p++ != '"')
        return 0;
    while (*p == ' ' || *p == '\t')
        p++;
    return *p == '\0';
}

/* Plain decimal seconds ("2", "0.5") in [0, max]. */
int rd_http_parse_seconds(const char *s, double max, double *out)
{
    if (!*s || strspn(s, "0123456789.") != strlen(s))
        return 0;
    char *end;
    double v = strtod(s, &end);
    if (*end || !(v >= 0 && v <= max))
        return 0;
    *out = v;
    return 1;
}

/* Plain decimal integer in [min, max]. */
int rd_http_parse_count(const char *s, long min, long max, long *out)
{
    if (!*s || strlen(s) > 9 || strspn(s, "0123456789") != strlen(s))
        return 0;
    long v = strtol(s, NULL, 10);
    if (v < min || v > max)
        return 0;
    *out = v;
    return 1;
}

const char *rd_http_after_prefix(const char *s, const char *prefix)
{
    size_t n = strlen(prefix);
    return strncmp(s, prefix, n) == 0 ? s + n : NULL;
}

/* Is `method` one of the comma-separated tokens in `allow`? */
int rd_http_method_allowed(const char *allow, const char *method)
{
    size_t n = strlen(method);
    for (const char *p = allow; *p;) {
        size_t len = strcspn(p, ",");
        if (len == n && strncmp(p, method, n) == 0)
            return 1;
        p += len;
        while (*p == ',' || *p == ' ')
            p++;
    }
    return 0;
}

int rd_http_body_reserve(struct request *rq, size_t need)
{
    if (need <= rq->cap)
        return 0;
    if (need <= BODY_HEAP_MAX) {
        size_t cap = rq->cap ? rq->cap : 4096;
        while (cap < need)
            cap *= 2;
        if (cap > BODY_HEAP_MAX)
            cap = BODY_HEAP_MAX;
        char *body = realloc(rq->body, cap);
        if (!body)
            return -1;
        rq->body = body;
        rq->cap = cap;
        return 0;
    }
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    size_t cap = (RD_API_BODY_MAX + 1 + page - 1) / page * page;
    if (need > cap || rq->body_mapped)
        return -1; /* a mapping already holds the most a body may be */
    char *body = mmap(NULL, cap, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (body == MAP_FAILED)
        return -1;
    if (rq->body)
        memcpy(body, rq->body, rq->len + 1);
    free(rq->body);
    rq->body = body;
    rq->cap = cap;
    rq->body_mapped = 1;
    return 0;
}

void rd_http_body_free(struct request *rq)
{
    if (rq->body_mapped)
        munmap(rq->body, rq->cap);
    else
        free(rq->body);
    rq->body = NULL;
    rq->len = rq->cap = 0;
    rq->body_mapped = 0;
}
