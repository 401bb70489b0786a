/*
 * rd_http_reply — responses (rd_http_int.h): text and job answers, gzip,
 * the error bodies of the contract, and the count of every status sent.
 */
#include "rd_http_int.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

#include <jansson.h>

#include "rd_api.h"
#include "rd_clock.h"
#include "rd_gzip.h"

/* What a cached answer puts before the cached job's JSON (minus its '{'). */
static const char cached_prefix[] = "{\"cached\":true,";

static const char oom_body[] =
    "{\"error\":{\"code\":\"out_of_memory\",\"message\":\"The server is out of memory.\"}}";

/* Queues `r` (consumed; NULL means out of memory and sends a fixed 503). */
enum MHD_Result rd_http_send_response(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                      int status, struct MHD_Response *r)
{
    if (!r) {
        r = MHD_create_response_from_buffer(sizeof oom_body - 1, (void *)oom_body,
                                            MHD_RESPMEM_PERSISTENT);
        if (!r)
            return MHD_NO;
        if (MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, RD_HTTP_JSON) != MHD_YES) {
            MHD_destroy_response(r);
            return MHD_NO;
        }
        status = MHD_HTTP_SERVICE_UNAVAILABLE;
    }
    rq->replied = 1;
    rd_http_set_busy(h, rq);
    enum MHD_Result ok = MHD_queue_response(c, (unsigned)status, r);
    MHD_destroy_response(r);
    if (ok == MHD_YES) {
        /* A page file that does not exist is not the page: any URL would
         * otherwise count as "static". */
        rd_metrics_route route = rq->metrics_route;
        if (route == RD_METRICS_ROUTE_STATIC && status == MHD_HTTP_NOT_FOUND)
            route = RD_METRICS_ROUTE_OTHER;
        rd_metrics_count_http(h->metrics, route, rq->method, status, rd_clock_mono_s() - rq->t0);
    }
    return ok;
}

/* `len` bytes at `data` gzipped for a client that accepts it, when that is
 * worth it: a malloc'd copy in *gz, else NULL. */
static void maybe_gzip(const struct request *rq, const char *data, size_t len, char **gz,
                       size_t *gz_len)
{
    *gz = NULL;
    if (rq->gzip && len >= RD_GZIP_MIN_BYTES && rd_gzip(data, len, gz, gz_len) != 0)
        *gz = NULL; /* out of memory: send it as it is */
}

static int add_gzip_headers(struct MHD_Response *r)
{
    return MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_ENCODING, "gzip") == MHD_YES &&
           MHD_add_response_header(r, MHD_HTTP_HEADER_VARY, "Accept-Encoding") == MHD_YES;
}

/* r with one more header, or NULL (r destroyed) when libmicrohttpd cannot add
 * it: the caller then answers with the out-of-memory body (rd_http_send_response). */
struct MHD_Response *rd_http_with_header(struct MHD_Response *r, const char *name,
                                         const char *value)
{
    if (r && MHD_add_response_header(r, name, value) != MHD_YES) {
        MHD_destroy_response(r);
        return NULL;
    }
    return r;
}

/* A response owning the malloc'd `body` (NULL in, NULL out), gzipped when
 * the client accepts it and the body is large enough. */
struct MHD_Response *rd_http_text_response(const struct request *rq, char *body,
                                           const char *content_type)
{
    if (!body)
        return NULL;
    size_t len = strlen(body), gz_len = 0;
    char *gz;
    maybe_gzip(rq, body, len, &gz, &gz_len);
    if (gz) {
        free(body);
        body = gz;
        len = gz_len;
    }
    struct MHD_Response *r = MHD_create_response_from_buffer(len, body, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(body);
        return NULL;
    }
    if (MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, content_type) != MHD_YES ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store") != MHD_YES ||
        (gz && !add_gzip_headers(r))) {
        MHD_destroy_response(r);
        return NULL;
    }
    return r;
}

/* A response of `len` bytes at `data`, owned by the shared `body`, which MHD
 * releases when done with it (and which is released here on failure). */
static struct MHD_Response *from_body(rd_jobs_body *body, const char *data, size_t len, int gz,
                                      const char *content_type)
{
    struct MHD_Response *r = MHD_create_response_from_buffer_with_free_callback_cls(
        len, (void *)data, rd_jobs_body_release, body);
    if (!r) {
        rd_jobs_body_release(body);
        return NULL;
    }
    if ((gz && !add_gzip_headers(r)) ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, content_type) != MHD_YES ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store") != MHD_YES) {
        MHD_destroy_response(r); /* releases the body */
        return NULL;
    }
    return r;
}

struct MHD_Response *rd_http_body_response(const struct request *rq, rd_jobs_body *body,
                                           const char *data, size_t len, int gz_form,
                                           const char *content_type)
{
    rd_error ignored;
    rd_error_init(&ignored);
    const char *gz = NULL;
    size_t gz_len = 0;
    if (rq->gzip && gz_form >= 0 && len >= RD_GZIP_MIN_BYTES &&
        rd_jobs_body_form(body, (rd_jobs_form)gz_form, &gz, &gz_len, NULL, &ignored) != RD_OK)
        gz = NULL; /* out of memory: send it as it is */
    return gz ? from_body(body, gz, gz_len, 1, content_type)
              : from_body(body, data, len, 0, content_type);
}

/* A cached job's shared JSON with "cached":true as its first member: two
 * pieces sent as they are, or its gzip, made once per body (no copy per
 * request either way). */
static struct MHD_Response *cached_response(const struct request *rq, rd_jobs_body *body)
{
    if (rq->gzip && body->len >= RD_GZIP_MIN_BYTES)
        return rd_http_body_response(rq, body, body->data, body->len, RD_JOBS_CACHED, RD_HTTP_JSON);
    struct MHD_IoVec iov[2] = {{cached_prefix, sizeof cached_prefix - 1},
                               {body->data + 1, body->len - 1}};
    struct MHD_Response *r = MHD_create_response_from_iovec(iov, 2, rd_jobs_body_release, body);
    if (!r) {
        rd_jobs_body_release(body);
        return NULL;
    }
    if (MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, RD_HTTP_JSON) != MHD_YES ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store") != MHD_YES) {
        MHD_destroy_response(r); /* releases the body */
        return NULL;
    }
    return r;
}

/* A job's answer: its shared JSON (a succeeded job: one copy for all the
 * requests sending it, released when MHD is done; gzipped once per body) or
 * the rendered `json`.  `cached`: the answer comes from the result cache. */
struct MHD_Response *rd_http_job_response(const struct request *rq, rd_jobs_body *body, char *json,
                                          int cached)
{
    if (!body)
        return rd_http_text_response(rq, json, RD_HTTP_JSON);
    if (cached)
        return cached_response(rq, body);
    return rd_http_body_response(rq, body, body->data, body->len, RD_JOBS_GZIP, RD_HTTP_JSON);
}

enum MHD_Result rd_http_send_text(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                  int status, char *body, const char *content_type)
{
    return rd_http_send_response(h, c, rq, status, rd_http_text_response(rq, body, content_type));
}

/* ---- validators: ETag, If-None-Match, 304 ---- */

void rd_http_etag_of_hash(const uint64_t hash[2], char *out)
{
    snprintf(out, RD_HTTP_ETAG_LEN, "W/\"%016llx%016llx\"", (unsigned long long)hash[0],
             (unsigned long long)hash[1]);
}

void rd_http_etag(const char *data, size_t len, char *out)
{
    uint64_t hash[2];
    rd_jobs_hash(data, len, hash);
    rd_http_etag_of_hash(hash, out);
}

/* The opaque tag of an entity tag at `p` (its quoted string, "W/" dropped):
 * start in *tag, length in *n; returns the text after it, or NULL when
 * `p` holds no well-formed tag. */
static const char *next_tag(const char *p, const char **tag, size_t *n)
{
    while (*p == ' ' || *p == '\t' || *p == ',')
        p++;
    if (p[0] == 'W' && p[1] == '/')
        p += 2;
    if (*p != '"')
        return NULL;
    const char *end = strchr(p + 1, '"');
    if (!end)
        return NULL;
    *tag = p;
    *n = (size_t)(end - p + 1);
    return end + 1;
}

int rd_http_none_match(struct MHD_Connection *c, const char *etag)
{
    const char *inm = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "If-None-Match");
    if (!inm)
        return 0;
    const char *p = inm + strspn(inm, " \t");
    if (p[0] == '*' && p[1 + strspn(p + 1, " \t")] == '\0')
        return 1;
    const char *mine = etag + (strncmp(etag, "W/", 2) == 0 ? 2 : 0), *tag;
    size_t n;
    while ((p = next_tag(p, &tag, &n)))
        if (n == strlen(mine) && memcmp(tag, mine, n) == 0)
            return 1;
    return 0;
}

struct MHD_Response *rd_http_with_etag(struct MHD_Response *r, const char *etag)
{
    if (r)
        MHD_del_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    r = rd_http_with_header(r, MHD_HTTP_HEADER_ETAG, etag);
    return rd_http_with_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-cache");
}

enum MHD_Result rd_http_send_not_modified(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                          const char *etag)
{
    struct MHD_Response *r = MHD_create_response_from_buffer(0, (void *)"", MHD_RESPMEM_PERSISTENT);
    r = rd_http_with_etag(r, etag);
    return rd_http_send_response(h, c, rq, MHD_HTTP_NOT_MODIFIED, r);
}

/* The contract's error body; `allow` (may be NULL) for 405. */
enum MHD_Result rd_http_send_error(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   const rd_error *err, const char *allow)
{
    rd_error fallback;
    if (err->code == RD_OK) { /* a callee failed without saying why: our bug */
        rd_error_init(&fallback);
        rd_error_set(&fallback, RD_EINTERNAL, "", "Internal error.");
        err = &fallback;
    }
    struct MHD_Response *r = rd_http_text_response(rq, rd_api_error_json(err), RD_HTTP_JSON);
    if (allow)
        r = rd_http_with_header(r, MHD_HTTP_HEADER_ALLOW, allow);
    if (r && err->code == RD_EBUSY) {
        char seconds[16];
        snprintf(seconds, sizeof seconds, "%d", rd_jobs_get_retry_after(h->jobs));
        r = rd_http_with_header(r, MHD_HTTP_HEADER_RETRY_AFTER, seconds);
    }
    return rd_http_send_response(h, c, rq, rd_api_http_status(err->code), r);
}

#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
enum MHD_Result
rd_http_send_fail(rd_http *h, struct MHD_Connection *c, struct request *rq, int code,
                  const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    return rd_http_send_error(h, c, rq, &err, NULL);
}

enum MHD_Result rd_http_send_not_found(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                       const char *url)
{
    char buf[128];
    return rd_http_send_fail(h, c, rq, RD_ENOTFOUND, "There is nothing at %s.",
                             rd_http_printable(url, buf, sizeof buf));
}

/* An error the status table of core/rd_error.h has no code for (401, 403,
 * 400 for a framing fault): the same {"error": {"code", "message"}} shape,
 * written here.  `header`/`value` (may be NULL) adds one response header. */
struct MHD_Response *rd_http_error_response(const struct request *rq, const char *code,
                                            const char *message)
{
    json_t *o = json_pack("{s:{s:s, s:s}}", "error", "code", code, "message", message);
    char *body = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    return rd_http_text_response(rq, body, RD_HTTP_JSON);
}

enum MHD_Result rd_http_send_server_error(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                          int status, const char *code, const char *message,
                                          const char *header, const char *value)
{
    struct MHD_Response *r = rd_http_error_response(rq, code, message);
    if (r && header && MHD_add_response_header(r, header, value) != MHD_YES) {
        MHD_destroy_response(r);
        r = NULL;
    }
    return rd_http_send_response(h, c, rq, status, r);
}

/* A body that passed RD_API_BODY_MAX while it was arriving (only a chunked
 * one can: a declared Content-Length over it is refused before the body).
 * libmicrohttpd (0.9.75, and 1.0.1 alike) queues a response only before
 * the body or after the whole of it, and a chunk may declare up to 2^64-1
 * bytes, so waiting for the end meant waiting for the request deadline.
 * The 413 is written on the socket here, in the connection's own thread
 * while MHD writes nothing on it (no response is queued), and its write
 * side shut: the client has its answer at once.  What the client still
 * sends is read and dropped until it closes, the request deadline shuts
 * the socket, or the body ends (rd_http_body_refused then closes); a close
 * at once would reset the connection under unread data, and the client
 * could lose the answer.  Returns MHD_NO (close now) when the answer could
 * not be written whole. */
enum MHD_Result rd_http_refuse_body_now(rd_http *h, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    rd_error_set(&err, RD_ETOOLARGE, "", "The body is larger than the limit of %d bytes.",
                 RD_API_BODY_MAX);
    char *json = rd_api_error_json(&err);
    char head[256];
    int n = json ? snprintf(head, sizeof head,
                            "HTTP/1.1 413 Content Too Large\r\nConnection: close\r\n"
                            "Content-Type: application/json\r\nCache-Control: no-store\r\n"
                            "Content-Length: %zu\r\n\r\n",
                            strlen(json))
                 : -1;
    int written = 0;
    rq->replied = 1;
    rq->refused_raw = 1;
    if (rq->conn && n > 0 && (size_t)n < sizeof head) {
        struct iovec iov[2] = {{head, (size_t)n}, {json, strlen(json)}};
        struct msghdr msg = {.msg_iov = iov, .msg_iovlen = 2};
        ssize_t sent = sendmsg(rq->conn->fd, &msg, MSG_NOSIGNAL | MSG_DONTWAIT);
        written = sent == (ssize_t)((size_t)n + strlen(json));
        if (written) {
            shutdown(rq->conn->fd, SHUT_WR);
            rd_metrics_count_http(h->metrics, rq->metrics_route, rq->method,
                                  MHD_HTTP_CONTENT_TOO_LARGE, rd_clock_mono_s() - rq->t0);
        }
    }
    free(json);
    return written ? MHD_YES : MHD_NO;
}
