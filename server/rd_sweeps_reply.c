/*
 * rd_sweeps_reply — the answers of the sweeps' routes (rd_sweeps_reply.h).
 */
#include "rd_sweeps_reply.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_api.h"

/* Retry-After for a full sweep queue: a sweep takes minutes, not seconds. */
#define BUSY_RETRY_S 30

void rd_sweeps_reply_error(rd_sweeps_reply *r, const rd_error *err)
{
    r->status = rd_api_http_status(err->code);
    r->body = rd_api_error_json(err);
    r->content_type = "application/json";
    if (err->code == RD_EBUSY)
        r->retry_after = BUSY_RETRY_S;
}

void rd_sweeps_reply_fail(rd_sweeps_reply *r, int code, const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    rd_sweeps_reply_error(r, &err);
}

void rd_sweeps_reply_json(rd_sweeps_reply *r, int status, char *body)
{
    if (!body) {
        rd_sweeps_reply_fail(r, RD_ENOMEM, "The server is out of memory.");
        return;
    }
    r->status = status;
    r->body = body;
    r->content_type = "application/json";
}

void rd_sweeps_reply_cleanup(rd_sweeps_reply *reply)
{
    free(reply->body);
    reply->body = NULL;
}

char *rd_sweeps_splice(char *head, const char *key, const char *value)
{
    size_t hn = head ? strlen(head) : 0, kn = strlen(key), vn = value ? strlen(value) : 0;
    char *out = head && value && hn >= 2 ? malloc(hn + kn + vn + 6) : NULL;
    if (out) {
        memcpy(out, head, hn - 1);
        int w = sprintf(out + hn - 1, "%s\"%s\":", hn > 2 ? "," : "", key);
        memcpy(out + hn - 1 + (size_t)w, value, vn);
        strcpy(out + hn - 1 + (size_t)w + vn, "}");
    }
    free(head);
    return out;
}

void rd_sweeps_reply_not_found(rd_sweeps_reply *r, const char *id)
{
    rd_sweeps_reply_fail(
        r, RD_ENOTFOUND,
        "There is no sweep %.16s%s (finished sweeps are kept in memory until the server "
        "stops or newer ones push them out; GET /api/v1/sweeps lists them).",
        id, strlen(id) > 16 ? "..." : "");
}
