/*
 * rd_gzip — one-shot gzip with zlib's deflate (rd_gzip.h).
 *
 * Level 1 (fastest): result JSON is numbers and repeated keys, which even
 * level 1 shrinks 3-6x, at a fraction of the CPU of the default level 6.
 */
#include "rd_gzip.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <zlib.h>

#define GZIP_LEVEL     1
#define GZIP_WINDOW    (15 + 16) /* 2^15 window, +16: gzip wrapper, not zlib */
#define GZIP_MEM_LEVEL 8

int rd_gzip(const char *in, size_t len, char **out, size_t *out_len)
{
    *out = NULL;
    *out_len = 0;
    z_stream z;
    memset(&z, 0, sizeof z);
    if (deflateInit2(&z, GZIP_LEVEL, Z_DEFLATED, GZIP_WINDOW, GZIP_MEM_LEVEL, Z_DEFAULT_STRATEGY) !=
        Z_OK)
        return -1;
    uLong cap = deflateBound(&z, (uLong)len);
    char *buf = malloc(cap);
    if (!buf || (uLong)len != len) {
        free(buf);
        deflateEnd(&z);
        return -1;
    }
    z.next_in = (Bytef *)(uintptr_t)in;
    z.avail_in = (uInt)len;
    z.next_out = (Bytef *)buf;
    z.avail_out = (uInt)cap;
    int rc = deflate(&z, Z_FINISH);
    size_t n = (size_t)z.total_out;
    if (deflateEnd(&z) != Z_OK || rc != Z_STREAM_END) {
        free(buf);
        return -1;
    }
    *out = buf;
    *out_len = n;
    return 0;
}

/* The q of one coding's parameters ("; q=0.5"), 1 when none is given. */
static double coding_q(const char *params, size_t n)
{
    const char *q = NULL;
    for (size_t i = 0; i + 1 < n; i++)
        if ((params[i] == 'q' || params[i] == 'Q') && params[i + 1] == '=') {
            q = params + i + 2;
            break;
        }
    return q ? strtod(q, NULL) : 1.0;
}

int rd_gzip_accepted(const char *ae)
{
    if (!ae)
        return 0;
    for (const char *p = ae; *p;) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        size_t n = strcspn(p, ",");
        size_t name = strcspn(p, ";, \t");
        if (name > n)
            name = n;
        if (((name == 4 && strncasecmp(p, "gzip", 4) == 0) || (name == 1 && *p == '*')) &&
            coding_q(p + name, n - name) > 0)
            return 1;
        p += n;
    }
    return 0;
}
