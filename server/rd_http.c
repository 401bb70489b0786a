/*
 * rd_http — routes, limits, error bodies and static files (rd_http.h).
 *
 * Request life cycle in libmicrohttpd: the access handler is called once
 * with the headers (upload_data_size 0), then once per chunk of body, then a
 * last time with upload_data_size 0.  The first call checks framing, Host
 * and token (check_framing, host_allowed, authorized), then routes.
 * Everything except POST /api/v1/jobs and DELETE of a running job is
 * answered on the first call.  For a POST the first call checks the method,
 * Content-Type, ?wait= and a declared Content-Length, so a bad request is
 * refused before its body is read; the chunks are then collected up to
 * RD_API_BODY_MAX bytes (beyond that they are counted and dropped, never
 * buffered) and the last call parses the scene, queues it and, with ?wait,
 * suspends the connection (suspend_for) until the job ends or the wait is
 * over; the timer thread resumes it and MHD calls the handler once more
 * (answer_waiter).  A succeeded job is sent from its shared JSON
 * (job_response), never copied per request.
 *
 * Paths arrive percent-decoded by unescape_path below, which turns an
 * encoded NUL into DEL (0x7f) so that it cannot cut the C string short;
 * every path with a control character is then refused (404).
 */
/* realpath() is XSI: the build defines only _POSIX_C_SOURCE. */
#define _XOPEN_SOURCE 700

#include "rd_http.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <netdb.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include <jansson.h>
#include <microhttpd.h>

#include "rd_api.h"
#include "rd_clock.h"
#include "rd_gzip.h"
#include "rd_openapi.h"

/* Connections the kernel queues before MHD accepts them. */
#define LISTEN_BACKLOG 1024
/* The timer thread's period: the latest a waiter is resumed after its
 * deadline, and the resolution of the request deadline. */
#define TICK_S 0.1
/* How often the store's age limit is applied. */
#define EXPIRE_EVERY_S 60.0
/* How long DELETE waits for a running job to acknowledge the cancellation. */
#define CANCEL_WAIT_S 5.0
/* GET /api/v1/jobs: default and largest ?limit=. */
#define LIST_LIMIT_DEFAULT 50
#define LIST_LIMIT_MAX     1000
/* Room for a job id or example name taken from a path. */
#define PATH_ARG_MAX 80
/* A submission that waits (?wait) runs on the HTTP thread, with no queue and
 * no worker hand-off, when its predicted cost (rd_scene_cost_predict) is below
 * this: the model is within a factor 2, so such a run holds the thread a few
 * ms at most, about what one large response takes to write. */
#define INLINE_BELOW_S 0.002
/* Longest Idempotency-Key accepted, bytes. */
#define IDEM_KEY_MAX 200
/* What a cached answer puts before the cached job's JSON (minus its '{'). */
static const char cached_prefix[] = "{\"cached\":true,";

static const char json_media[] = "application/json";
static const char oom_body[] =
    "{\"error\":{\"code\":\"out_of_memory\",\"message\":\"The server is out of memory.\"}}";

struct rd_http {
    struct MHD_Daemon *daemon;
    MHD_socket quiesced_fd; /* listen socket handed back by MHD_quiesce_daemon */
    rd_jobs *jobs;          /* borrowed */
    rd_metrics *metrics;    /* borrowed */
    rd_sweeps *sweeps;      /* borrowed, may be NULL */
    char *static_root;      /* realpath of the static dir, or NULL */
    char *examples_dir;     /* realpath of the examples dir, or NULL */
    char host[INET6_ADDRSTRLEN + 2];
    int port;
    char **allow; /* Host names served (lower case, IPv6 in brackets) */
    size_t n_allow;
    char *token; /* bearer token, or NULL */
    rd_http_limits limits;
    double job_timeout_s; /* the job pool's time limit: the cap of ?time_limit_s= */
    pthread_mutex_t mu;   /* guards everything below */
    pthread_cond_t idle;  /* in_flight dropped to 0 */
    int in_flight;        /* requests between their first call and on_completed */
    pthread_cond_t wake;  /* for the timer thread: a job ended, a waiter came, or stop */
    int poked, stop;
    pthread_t timer;
    int timer_started;
    struct request *waiters; /* suspended requests, waiting for their job */
    struct conn *conns;      /* every open connection */
    size_t nconns;
    size_t deadline_closed;
};

/* Per-connection state (MHD_OPTION_NOTIFY_CONNECTION), in rd_http.conns. */
struct conn {
    struct conn *prev, *next;
    MHD_socket fd;
    double since; /* CLOCK_MONOTONIC: the request now arriving began no earlier */
    int busy;     /* a complete request is being answered: no deadline */
    int shut;     /* the deadline passed and the socket was shut down */
};

enum wait_kind { WAIT_NONE, WAIT_SUBMIT, WAIT_CANCEL, WAIT_SWEEP };

/* Per-request state, kept by MHD in *req_cls between calls. */
struct request {
    struct MHD_Connection *c;
    struct conn *conn;           /* may be NULL */
    struct request *prev, *next; /* in rd_http.waiters while suspended */
    enum wait_kind waiting;      /* suspended until its job ends or `until` */
    int resumed;                 /* the timer thread resumed it */
    double until;                /* CLOCK_MONOTONIC */
    char job_id[RD_JOBS_ID_LEN + 1];
    int started;  /* the headers have been handled */
    int replied;  /* a response is queued: drop whatever body follows */
    int has_wait; /* ?wait= was given */
    double wait_s;
    char *body; /* POST body so far, NUL-terminated, <= RD_API_BODY_MAX bytes */
    size_t len, cap;
    int too_large; /* the body passed RD_API_BODY_MAX: the rest is dropped */
    int no_memory;
    int sweep;           /* a POST /api/v1/sweeps; with WAIT_SWEEP: a wait that answers it */
    int gzip;            /* the client accepts gzip */
    const char *cache;   /* X-Ringdyn-Cache of a submission: "hit", "miss", "bypass", or NULL */
    double time_limit_s; /* ?time_limit_s=, 0 when not given */
    int replayed;        /* the Idempotency-Key named an earlier job with this body */
};

enum route {
    ROUTE_NONE,
    ROUTE_JOBS,
    ROUTE_JOB,
    ROUTE_JOB_CSV,
    ROUTE_EXAMPLES,
    ROUTE_EXAMPLE,
    ROUTE_HEALTH,
    ROUTE_OPENAPI,
    ROUTE_METRICS,
    ROUTE_STATIC,
    ROUTE_SWEEPS,
    ROUTE_SWEEP,
    ROUTE_SWEEP_CSV
};

/* ---- small helpers ---- */

/* A copy of `s` fit for a message: printable ASCII only, at most n-1 bytes.
 * (Error bodies must be valid UTF-8; request text need not be.) */
static const char *printable(const char *s, char *buf, size_t n)
{
    size_t i = 0;
    for (; s[i] && i + 1 < n; i++)
        buf[i] = (s[i] >= 0x20 && s[i] < 0x7f) ? s[i] : '?';
    buf[i] = '\0';
    if (s[i] && n > 4)
        memcpy(buf + n - 4, "...", 4);
    return buf;
}

static int has_control_char(const char *s)
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
static size_t unescape_path(void *cls, struct MHD_Connection *c, char *s)
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
static int is_json_media_type(const char *ct)
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
static int parse_seconds(const char *s, double max, double *out)
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
static int parse_count(const char *s, long min, long max, long *out)
{
    if (!*s || strlen(s) > 9 || strspn(s, "0123456789") != strlen(s))
        return 0;
    long v = strtol(s, NULL, 10);
    if (v < min || v > max)
        return 0;
    *out = v;
    return 1;
}

static const char *after_prefix(const char *s, const char *prefix)
{
    size_t n = strlen(prefix);
    return strncmp(s, prefix, n) == 0 ? s + n : NULL;
}

/* Maps a decoded path to a route; `arg` receives the job id or example name. */
static enum route match_route(const char *url, char *arg, size_t argsz)
{
    static const struct {
        const char *path;
        enum route route;
    } fixed[] = {{"/api/v1/jobs", ROUTE_JOBS},     {"/api/v1/examples", ROUTE_EXAMPLES},
                 {"/api/v1/health", ROUTE_HEALTH}, {"/api/v1/openapi.json", ROUTE_OPENAPI},
                 {"/metrics", ROUTE_METRICS},      {"/api/v1/sweeps", ROUTE_SWEEPS}};
    arg[0] = '\0';
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        if (strcmp(url, fixed[i].path) == 0)
            return fixed[i].route;

    const char *rest;
    if ((rest = after_prefix(url, "/api/v1/jobs/"))) {
        const char *slash = strchr(rest, '/');
        size_t n = slash ? (size_t)(slash - rest) : strlen(rest);
        if (n == 0 || n >= argsz || (slash && strcmp(slash, "/result.csv") != 0))
            return ROUTE_NONE;
        memcpy(arg, rest, n);
        arg[n] = '\0';
        return slash ? ROUTE_JOB_CSV : ROUTE_JOB;
    }
    if ((rest = after_prefix(url, "/api/v1/sweeps/"))) {
        const char *slash = strchr(rest, '/');
        size_t n = slash ? (size_t)(slash - rest) : strlen(rest);
        if (n == 0 || n >= argsz || (slash && strcmp(slash, "/table.csv") != 0))
            return ROUTE_NONE;
        memcpy(arg, rest, n);
        arg[n] = '\0';
        return slash ? ROUTE_SWEEP_CSV : ROUTE_SWEEP;
    }
    if ((rest = after_prefix(url, "/api/v1/examples/"))) {
        size_t n = strlen(rest);
        if (n == 0 || n >= argsz || strchr(rest, '/'))
            return ROUTE_NONE;
        memcpy(arg, rest, n + 1);
        return ROUTE_EXAMPLE;
    }
    if (strcmp(url, "/api") == 0 || after_prefix(url, "/api/"))
        return ROUTE_NONE;
    return ROUTE_STATIC;
}

/* Job data, examples and metrics need the token; the page, the OpenAPI
 * document and the health check (no job data) do not, so that the page can
 * load and ask for the token and a container health check needs no secret. */
static int route_needs_token(enum route r)
{
    return r != ROUTE_STATIC && r != ROUTE_HEALTH && r != ROUTE_OPENAPI;
}

static const char *allowed_methods(enum route r)
{
    switch (r) {
    case ROUTE_JOBS:
    case ROUTE_SWEEPS:
        return "GET, HEAD, POST";
    case ROUTE_JOB:
    case ROUTE_SWEEP:
        return "GET, HEAD, DELETE";
    default:
        return "GET, HEAD";
    }
}

/* Is `method` one of the comma-separated tokens in `allow`? */
static int method_allowed(const char *allow, const char *method)
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

/* ---- connections: the request deadline and suspended waits ---- */

/* The request on this connection is complete (being answered): the
 * deadline no longer applies until the next one starts. */
static void set_busy(rd_http *h, struct request *rq)
{
    if (!rq->conn)
        return;
    pthread_mutex_lock(&h->mu);
    rq->conn->busy = 1;
    pthread_mutex_unlock(&h->mu);
}

/* MHD_OPTION_NOTIFY_CONNECTION: keeps rd_http.conns.  MHD calls CLOSED
 * before it closes the socket, and the timer thread shuts sockets down only
 * under `mu` while the connection is listed, so it never touches a
 * descriptor that has been reused. */
static void on_connection(void *cls, struct MHD_Connection *c, void **socket_context,
                          enum MHD_ConnectionNotificationCode code)
{
    rd_http *h = cls;
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        const union MHD_ConnectionInfo *info =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
        struct conn *k = calloc(1, sizeof *k);
        if (!k || !info) { /* not tracked: then only the idle timeout applies */
            free(k);
            *socket_context = NULL;
            return;
        }
        k->fd = info->connect_fd;
        k->since = rd_clock_mono_s();
        pthread_mutex_lock(&h->mu);
        k->next = h->conns;
        if (h->conns)
            h->conns->prev = k;
        h->conns = k;
        h->nconns++;
        pthread_mutex_unlock(&h->mu);
        *socket_context = k;
        return;
    }
    struct conn *k = *socket_context;
    if (!k)
        return;
    pthread_mutex_lock(&h->mu);
    if (k->prev)
        k->prev->next = k->next;
    else
        h->conns = k->next;
    if (k->next)
        k->next->prev = k->prev;
    h->nconns--;
    pthread_mutex_unlock(&h->mu);
    free(k);
    *socket_context = NULL;
}

/* Shuts down the sockets whose request is overdue (mu held).  MHD sees the
 * socket end and closes the connection in its own thread. */
static void enforce_deadline_locked(rd_http *h, double now)
{
    for (struct conn *k = h->conns; k; k = k->next)
        if (!k->busy && !k->shut && now - k->since > h->limits.request_deadline_s) {
            shutdown(k->fd, SHUT_RDWR);
            k->shut = 1;
            h->deadline_closed++;
        }
}

/* Suspends a request until job `id` ends or `seconds` pass; the timer
 * thread resumes it, and MHD then calls on_request again (answer_waiter). */
static enum MHD_Result suspend_for(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   enum wait_kind kind, const char *id, double seconds)
{
    set_busy(h, rq);
    rq->waiting = kind;
    rq->until = rd_clock_mono_s() + seconds;
    memcpy(rq->job_id, id, sizeof rq->job_id);
    MHD_suspend_connection(c);
    pthread_mutex_lock(&h->mu);
    rq->prev = NULL;
    rq->next = h->waiters;
    if (h->waiters)
        h->waiters->prev = rq;
    h->waiters = rq;
    h->poked = 1; /* the job may have ended before the request was listed */
    pthread_cond_signal(&h->wake);
    pthread_mutex_unlock(&h->mu);
    return MHD_YES;
}

/* Takes the waiters that may go on (job final, time up, or `all`) off the
 * list (mu held) and returns them chained through `next`; the caller resumes
 * them after unlocking (MHD takes its own locks in MHD_resume_connection). */
static struct request *take_ready_locked(rd_http *h, double now, int all)
{
    struct request *ready = NULL, *rq = h->waiters;
    while (rq) {
        struct request *next = rq->next;
        int final = rq->waiting == WAIT_SWEEP ? rd_sweeps_is_final(h->sweeps, rq->job_id)
                                              : rd_jobs_is_final(h->jobs, rq->job_id);
        if (all || now >= rq->until || final) {
            if (rq->prev)
                rq->prev->next = rq->next;
            else
                h->waiters = rq->next;
            if (rq->next)
                rq->next->prev = rq->prev;
            rq->prev = NULL;
            rq->next = ready;
            ready = rq;
        }
        rq = next;
    }
    return ready;
}

static void resume_all(struct request *ready)
{
    while (ready) {
        struct request *next = ready->next;
        ready->next = NULL;
        ready->resumed = 1;
        MHD_resume_connection(ready->c);
        ready = next;
    }
}

/* The timer thread: resumes waiters, enforces the request deadline, applies
 * the job store's age limit; wakes on rd_http_job_ended or every TICK_S. */
static void *timer_main(void *arg)
{
    rd_http *h = arg;
    double next_expire = rd_clock_mono_s() + EXPIRE_EVERY_S;
    pthread_mutex_lock(&h->mu);
    while (!h->stop) {
        if (!h->poked) {
            struct timespec tick = rd_clock_mono_deadline(TICK_S);
            pthread_cond_timedwait(&h->wake, &h->mu, &tick);
        }
        h->poked = 0;
        double now = rd_clock_mono_s();
        struct request *ready = take_ready_locked(h, now, 0);
        enforce_deadline_locked(h, now);
        pthread_mutex_unlock(&h->mu);
        resume_all(ready);
        if (now >= next_expire) {
            rd_jobs_expire(h->jobs);
            next_expire = now + EXPIRE_EVERY_S;
        }
        pthread_mutex_lock(&h->mu);
    }
    struct request *ready = take_ready_locked(h, 0, 1);
    pthread_mutex_unlock(&h->mu);
    resume_all(ready);
    return NULL;
}

void rd_http_job_ended(void *http)
{
    rd_http *h = http;
    pthread_mutex_lock(&h->mu);
    h->poked = 1;
    pthread_cond_signal(&h->wake);
    pthread_mutex_unlock(&h->mu);
}

/* ---- responses ---- */

/* Queues `r` (consumed; NULL means out of memory and sends a fixed 503). */
static enum MHD_Result send_response(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                     int status, struct MHD_Response *r)
{
    if (!r) {
        r = MHD_create_response_from_buffer(sizeof oom_body - 1, (void *)oom_body,
                                            MHD_RESPMEM_PERSISTENT);
        if (!r)
            return MHD_NO;
        if (MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, json_media) != MHD_YES) {
            MHD_destroy_response(r);
            return MHD_NO;
        }
        status = MHD_HTTP_SERVICE_UNAVAILABLE;
    }
    rq->replied = 1;
    set_busy(h, rq);
    enum MHD_Result ok = MHD_queue_response(c, (unsigned)status, r);
    MHD_destroy_response(r);
    if (ok == MHD_YES)
        rd_metrics_count_http(h->metrics, status);
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
 * it: the caller then answers with the out-of-memory body (send_response). */
static struct MHD_Response *with_header(struct MHD_Response *r, const char *name, const char *value)
{
    if (r && MHD_add_response_header(r, name, value) != MHD_YES) {
        MHD_destroy_response(r);
        return NULL;
    }
    return r;
}

/* A response owning the malloc'd `body` (NULL in, NULL out), gzipped when
 * the client accepts it and the body is large enough. */
static struct MHD_Response *text_response(const struct request *rq, char *body,
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

/* A cached job's shared JSON with "cached":true as its first member: two
 * pieces sent as they are (no copy), or, gzipped, one per-request copy. */
static struct MHD_Response *cached_response(const struct request *rq, rd_jobs_body *body)
{
    if (rq->gzip && body->len >= RD_GZIP_MIN_BYTES) {
        size_t n = sizeof cached_prefix - 1 + body->len - 1;
        char *joined = malloc(n + 1);
        if (joined) {
            memcpy(joined, cached_prefix, sizeof cached_prefix - 1);
            memcpy(joined + sizeof cached_prefix - 1, body->data + 1, body->len - 1);
            joined[n] = '\0';
        }
        rd_jobs_body_release(body);
        return text_response(rq, joined, json_media);
    }
    struct MHD_IoVec iov[2] = {{cached_prefix, sizeof cached_prefix - 1},
                               {body->data + 1, body->len - 1}};
    struct MHD_Response *r = MHD_create_response_from_iovec(iov, 2, rd_jobs_body_release, body);
    if (!r) {
        rd_jobs_body_release(body);
        return NULL;
    }
    if (MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, json_media) != MHD_YES ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store") != MHD_YES) {
        MHD_destroy_response(r); /* releases the body */
        return NULL;
    }
    return r;
}

/* A job's answer: its shared JSON (a succeeded job: one copy for all the
 * requests sending it, released when MHD is done; gzipped once per body) or
 * the rendered `json`.  `cached`: the answer comes from the result cache. */
static struct MHD_Response *job_response(const struct request *rq, rd_jobs_body *body, char *json,
                                         int cached)
{
    if (!body)
        return text_response(rq, json, json_media);
    if (cached)
        return cached_response(rq, body);
    const char *data = body->data;
    size_t len = body->len;
    int gz = rq->gzip && len >= RD_GZIP_MIN_BYTES && rd_jobs_body_gzip(body, &data, &len) == RD_OK;
    if (!gz) {
        data = body->data;
        len = body->len;
    }
    struct MHD_Response *r = MHD_create_response_from_buffer_with_free_callback_cls(
        len, (void *)data, rd_jobs_body_release, body);
    if (!r) {
        rd_jobs_body_release(body);
        return NULL;
    }
    if ((gz && !add_gzip_headers(r)) ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, json_media) != MHD_YES ||
        MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store") != MHD_YES) {
        MHD_destroy_response(r); /* releases the body */
        return NULL;
    }
    return r;
}

static enum MHD_Result send_text(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                 int status, char *body, const char *content_type)
{
    return send_response(h, c, rq, status, text_response(rq, body, content_type));
}

/* The contract's error body; `allow` (may be NULL) for 405. */
static enum MHD_Result send_error(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                  const rd_error *err, const char *allow)
{
    rd_error fallback;
    if (err->code == RD_OK) { /* a callee failed without saying why: our bug */
        rd_error_init(&fallback);
        rd_error_set(&fallback, RD_EINTERNAL, "", "Internal error.");
        err = &fallback;
    }
    struct MHD_Response *r = text_response(rq, rd_api_error_json(err), json_media);
    if (allow)
        r = with_header(r, MHD_HTTP_HEADER_ALLOW, allow);
    if (r && err->code == RD_EBUSY) {
        char seconds[16];
        snprintf(seconds, sizeof seconds, "%d", rd_jobs_get_retry_after(h->jobs));
        r = with_header(r, MHD_HTTP_HEADER_RETRY_AFTER, seconds);
    }
    return send_response(h, c, rq, rd_api_http_status(err->code), r);
}

#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
static enum MHD_Result
send_fail(rd_http *h, struct MHD_Connection *c, struct request *rq, int code, const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    return send_error(h, c, rq, &err, NULL);
}

static enum MHD_Result send_not_found(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                      const char *url)
{
    char buf[128];
    return send_fail(h, c, rq, RD_ENOTFOUND, "There is nothing at %s.",
                     printable(url, buf, sizeof buf));
}

/* An error the status table of core/rd_error.h has no code for (401, 403,
 * 400 for a framing fault): the same {"error": {"code", "message"}} shape,
 * written here.  `header`/`value` (may be NULL) adds one response header. */
static enum MHD_Result send_server_error(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                         int status, const char *code, const char *message,
                                         const char *header, const char *value)
{
    json_t *o = json_pack("{s:{s:s, s:s}}", "error", "code", code, "message", message);
    char *body = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    struct MHD_Response *r = text_response(rq, body, json_media);
    if (r && header && MHD_add_response_header(r, header, value) != MHD_YES) {
        MHD_destroy_response(r);
        r = NULL;
    }
    return send_response(h, c, rq, status, r);
}

/* ---- framing the handler can still judge ---- */

struct header_scan {
    const char *name;
    int count;
    int differ;        /* two of them have different values */
    const char *first; /* the first value */
};

static enum MHD_Result scan_header(void *cls, enum MHD_ValueKind kind, const char *key,
                                   const char *value)
{
    (void)kind;
    struct header_scan *scan = cls;
    if (strcasecmp(key, scan->name) != 0)
        return MHD_YES;
    if (scan->count++ == 0)
        scan->first = value ? value : "";
    else if (strcmp(scan->first, value ? value : "") != 0)
        scan->differ = 1;
    return MHD_YES;
}

static struct header_scan scan_headers(struct MHD_Connection *c, const char *name)
{
    struct header_scan scan = {name, 0, 0, NULL};
    MHD_get_connection_values(c, MHD_HEADER_KIND, scan_header, &scan);
    return scan;
}

/* Message framing libmicrohttpd lets through but HTTP/1.1 (RFC 9112 6.3)
 * says to refuse, since a proxy in front could read the body differently
 * (request smuggling): Content-Length headers that disagree, Content-Length
 * together with Transfer-Encoding, a transfer coding other than chunked;
 * and an HTTP/1.1 request without Host.  The answer closes the connection,
 * whose remaining bytes cannot be trusted.  Returns MHD_YES (with
 * *refused = 1) after queueing the refusal, or leaves *refused 0. */
static enum MHD_Result check_framing(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                     const char *version, int *refused)
{
    char buf[64];
    const char *why = NULL;
    struct header_scan length = scan_headers(c, MHD_HTTP_HEADER_CONTENT_LENGTH);
    struct header_scan coding = scan_headers(c, MHD_HTTP_HEADER_TRANSFER_ENCODING);
    struct header_scan host = scan_headers(c, MHD_HTTP_HEADER_HOST);
    char message[256];
    if (length.differ)
        why = "The request has Content-Length headers with different values; send one.";
    else if (length.count > 0 && coding.count > 0)
        why = "The request has both Content-Length and Transfer-Encoding; send one of them.";
    else if (coding.count > 1 || (coding.count == 1 && strcasecmp(coding.first, "chunked") != 0)) {
        snprintf(message, sizeof message,
                 "Transfer-Encoding %s is not supported; send the body as it is or chunked.",
                 printable(coding.first, buf, sizeof buf));
        why = message;
    } else if (host.count > 1)
        why = "The request has more than one Host header.";
    else if (host.count == 0 && strcmp(version, MHD_HTTP_VERSION_1_1) == 0)
        why = "An HTTP/1.1 request must carry a Host header.";
    *refused = why != NULL;
    if (!why)
        return MHD_YES;
    return send_server_error(h, c, rq, MHD_HTTP_BAD_REQUEST, "invalid_request", why,
                             MHD_HTTP_HEADER_CONNECTION, "close");
}

/* ---- access: Host allowlist and bearer token ---- */

/* The name part of a Host header value: "[v6]" with its brackets, or what
 * precedes ":port"; NULL when the port is not all digits or the name is
 * empty or too long.  Lower-cased into buf. */
static const char *host_name(const char *host, char *buf, size_t n)
{
    const char *end;
    if (host[0] == '[') {
        end = strchr(host, ']');
        if (!end)
            return NULL;
        end++;
    } else {
        end = host + strcspn(host, ":");
    }
    if (*end == ':' && (end[1] == '\0' || strspn(end + 1, "0123456789") != strlen(end + 1)))
        return NULL;
    if (*end != '\0' && *end != ':')
        return NULL;
    size_t len = (size_t)(end - host);
    if (len == 0 || len >= n)
        return NULL;
    for (size_t i = 0; i < len; i++)
        buf[i] = (char)((host[i] >= 'A' && host[i] <= 'Z') ? host[i] - 'A' + 'a' : host[i]);
    buf[len] = '\0';
    return buf;
}

/* A request that names no Host (HTTP/1.0; check_framing refuses HTTP/1.1
 * without one) is allowed: DNS rebinding needs a browser, and browsers
 * always send Host. */
static int host_allowed(const rd_http *h, const char *host)
{
    if (!host)
        return 1;
    char buf[256];
    const char *name = host_name(host, buf, sizeof buf);
    if (!name)
        return 0;
    for (size_t i = 0; i < h->n_allow; i++)
        if (strcmp(name, h->allow[i]) == 0)
            return 1;
    return 0;
}

/* Compares in time that depends on the lengths only, not on where they differ. */
static int token_matches(const char *given, size_t given_len, const char *want, size_t want_len)
{
    unsigned char diff = given_len != want_len;
    for (size_t i = 0; i < given_len && i < want_len; i++)
        diff |= (unsigned char)(given[i] ^ want[i]);
    return diff == 0;
}

/* "Bearer TOKEN" (scheme in any case) carrying our token. */
static int authorized(const rd_http *h, struct MHD_Connection *c)
{
    const char *auth =
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_AUTHORIZATION);
    if (!auth || strncasecmp(auth, "Bearer ", 7) != 0)
        return 0;
    const char *t = auth + 7;
    while (*t == ' ')
        t++;
    size_t n = strlen(t);
    while (n > 0 && (t[n - 1] == ' ' || t[n - 1] == '\t'))
        n--;
    return token_matches(t, n, h->token, strlen(h->token));
}

/* ---- static files ---- */

static const char *content_type_for(const char *path)
{
    static const struct {
        const char *ext, *type;
    } types[] = {{"html", "text/html; charset=utf-8"},
                 {"htm", "text/html; charset=utf-8"},
                 {"js", "text/javascript; charset=utf-8"},
                 {"mjs", "text/javascript; charset=utf-8"},
                 {"css", "text/css; charset=utf-8"},
                 {"svg", "image/svg+xml"},
                 {"json", "application/json"},
                 {"png", "image/png"},
                 {"jpg", "image/jpeg"},
                 {"jpeg", "image/jpeg"},
                 {"ico", "image/x-icon"},
                 {"txt", "text/plain; charset=utf-8"},
                 {"csv", "text/csv; charset=utf-8"},
                 {"map", "application/json"},
                 {"woff2", "font/woff2"},
                 {"wasm", "application/wasm"}};
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (dot)
        for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
            if (strcasecmp(dot + 1, types[i].ext) == 0)
                return types[i].type;
    return "application/octet-stream";
}

/* A relative path we are willing to look up: no "..", no backslash, no
 * control character, no empty or dot-led segment (hidden files, ".", ".."),
 * no trailing slash (no directory listings). */
static int static_path_ok(const char *rel)
{
    if (!*rel || strstr(rel, "..") || strchr(rel, '\\') || has_control_char(rel) ||
        strlen(rel) >= PATH_MAX)
        return 0;
    for (const char *seg = rel;;) {
        if (*seg == '\0' || *seg == '/' || *seg == '.')
            return 0;
        const char *slash = strchr(seg, '/');
        if (!slash)
            return 1;
        seg = slash + 1;
    }
}

/* GET / (index.html), /static/<path>, and also /<path> for any other path
 * outside /api/ (so a page may use relative links).  Resolved with
 * realpath, which also follows symlinks, and served only when the result is
 * a regular file inside the static dir. */
static enum MHD_Result serve_static(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                    const char *url, const char *method)
{
    enum MHD_Result ret;
    char *full = NULL, *resolved = NULL;
    int fd = -1;
    const char *rel = url[0] == '/' ? url + 1 : "";
    const char *sub = after_prefix(rel, "static/");
    if (sub)
        rel = sub;
    if (url[0] != '/' || strcmp(url, "/static") == 0) {
        ret = send_not_found(h, c, rq, url);
        goto out;
    }
    if (*rel == '\0')
        rel = "index.html";
    else if (strcmp(rel, "docs") == 0) /* the API docs page (static/docs.html) */
        rel = "docs.html";
    if (!h->static_root || !static_path_ok(rel)) {
        ret = send_not_found(h, c, rq, url);
        goto out;
    }
    size_t root_len = strlen(h->static_root);
    full = malloc(root_len + 1 + strlen(rel) + 1);
    if (!full) {
        ret = send_response(h, c, rq, 0, NULL);
        goto out;
    }
    sprintf(full, "%s/%s", h->static_root, rel);
    resolved = realpath(full, NULL);
    if (!resolved || strncmp(resolved, h->static_root, root_len) != 0 ||
        resolved[root_len] != '/') {
        ret = send_not_found(h, c, rq, url);
        goto out;
    }
    /* O_NONBLOCK: opening a FIFO someone left in the dir must not hang us. */
    fd = open(resolved, O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ret = send_not_found(h, c, rq, url);
        goto out;
    }
    if (!method_allowed("GET, HEAD", method)) {
        rd_error err;
        rd_error_init(&err);
        rd_error_set(&err, RD_EMETHOD, "", "Method %.16s is not allowed here; use GET or HEAD.",
                     method);
        ret = send_error(h, c, rq, &err, "GET, HEAD");
        goto out;
    }
    struct MHD_Response *r = MHD_create_response_from_fd64((uint64_t)st.st_size, fd);
    if (!r) {
        ret = send_response(h, c, rq, 0, NULL);
        goto out;
    }
    fd = -1; /* the response owns it now */
    r = with_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, content_type_for(resolved));
    r = with_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-cache");
    r = with_header(r, "X-Content-Type-Options", "nosniff");
    ret = send_response(h, c, rq, MHD_HTTP_OK, r);
out:
    if (fd >= 0)
        close(fd);
    free(resolved);
    free(full);
    return ret;
}

/* ---- API routes ---- */

static enum MHD_Result get_health(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    size_t counts[RD_JOB_NSTATUS];
    rd_jobs_get_counts(h->jobs, counts);
    json_t *o = json_pack("{s:s, s:s, s:{s:I, s:I}}", "status", "ok", "version", rd_api_version(),
                          "jobs", "queued", (json_int_t)counts[RD_JOB_QUEUED], "running",
                          (json_int_t)counts[RD_JOB_RUNNING]);
    char *body = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    return send_text(h, c, rq, MHD_HTTP_OK, body, json_media);
}

static enum MHD_Result get_metrics(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    size_t counts[RD_JOB_NSTATUS];
    const char *names[RD_JOB_NSTATUS];
    rd_jobs_get_counts(h->jobs, counts);
    for (int i = 0; i < RD_JOB_NSTATUS; i++)
        names[i] = rd_jobs_status_name(i);
    rd_metrics_gauges g = {0};
    rd_jobs_get_stop_latency(h->jobs, &g.stop_last_s, &g.stop_max_s);
    pthread_mutex_lock(&h->mu);
    g.connections = h->nconns;
    g.deadline_closed = h->deadline_closed;
    pthread_mutex_unlock(&h->mu);
    g.version = rd_api_version();
    char *text = rd_metrics_render(h->metrics, names, counts, RD_JOB_NSTATUS, &g);
    return send_text(h, c, rq, MHD_HTTP_OK, text, "text/plain; version=0.0.4; charset=utf-8");
}

/* The embedded template with the scene schemas written by the api from the
 * tables that parse scenes (one schema, no copy to drift). */
static enum MHD_Result get_openapi(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    char *body = rd_api_openapi_json(rd_openapi_json, &err);
    if (!body)
        return send_error(h, c, rq, &err, NULL);
    return send_text(h, c, rq, MHD_HTTP_OK, body, json_media);
}

static enum MHD_Result get_examples(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    if (!h->examples_dir)
        return send_text(h, c, rq, MHD_HTTP_OK, strdup("{\"examples\":[]}"), json_media);
    char *body = rd_api_examples_json(h->examples_dir, &err);
    if (!body) {
        /* A broken example file is the server's fault, not the client's. */
        if (err.code != RD_ENOMEM)
            err.code = RD_EINTERNAL;
        return send_error(h, c, rq, &err, NULL);
    }
    return send_text(h, c, rq, MHD_HTTP_OK, body, json_media);
}

/* The api decides which names are valid (rd_api_example_scene): unknown
 * 404, malformed 400; only a broken example file is the server's fault. */
static enum MHD_Result get_example(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   const char *name)
{
    rd_error err;
    rd_error_init(&err);
    if (!h->examples_dir)
        return send_fail(h, c, rq, RD_ENOTFOUND,
                         "There are no examples on this server; GET /api/v1/examples lists them.");
    char *body = rd_api_example_scene(h->examples_dir, name, &err);
    if (!body) {
        if (err.code != RD_ENOMEM && err.code != RD_ENOTFOUND && err.code != RD_EREQUEST)
            err.code = RD_EINTERNAL;
        return send_error(h, c, rq, &err, NULL);
    }
    return send_text(h, c, rq, MHD_HTTP_OK, body, json_media);
}

static enum MHD_Result list_jobs(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    char buf[64];
    long limit = LIST_LIMIT_DEFAULT;
    rd_jobs_filter f = {0};
    f.status = -1;
    const char *s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "limit");
    if (s && !parse_count(s, 1, LIST_LIMIT_MAX, &limit))
        return send_fail(
            h, c, rq, RD_EREQUEST,
            "The query parameter limit must be a whole number from 1 to %d, not \"%s\".",
            LIST_LIMIT_MAX, printable(s, buf, sizeof buf));
    f.limit = (size_t)limit;
    if ((s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "status"))) {
        for (int i = 0; i < RD_JOB_NSTATUS && f.status < 0; i++)
            if (strcmp(s, rd_jobs_status_name(i)) == 0)
                f.status = i;
        if (f.status < 0)
            return send_fail(
                h, c, rq, RD_EREQUEST,
                "The query parameter status must be one of queued, running, succeeded, "
                "failed, cancelled, interrupted, not \"%s\".",
                printable(s, buf, sizeof buf));
    }
    f.analysis = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "analysis");
    f.name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "name");
    if ((s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "cursor"))) {
        char *end;
        errno = 0;
        unsigned long long v = strtoull(s, &end, 10);
        if (!*s || *end || errno || v == 0 || strspn(s, "0123456789") != strlen(s))
            return send_fail(h, c, rq, RD_EREQUEST,
                             "The query parameter cursor must be the next_cursor of an earlier "
                             "page, not \"%s\".",
                             printable(s, buf, sizeof buf));
        f.before = (uint64_t)v;
    }
    char *body = NULL;
    if (rd_jobs_list(h->jobs, &f, &body, &err) != RD_OK)
        return send_error(h, c, rq, &err, NULL);
    return send_text(h, c, rq, MHD_HTTP_OK, body, json_media);
}

static enum MHD_Result job_route(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                 enum route route, const char *method, const char *id)
{
    rd_error err;
    rd_error_init(&err);
    char *body = NULL;
    int rc;
    if (route == ROUTE_JOB_CSV) {
        rc = rd_jobs_result_csv(h->jobs, id, &body, &err);
        if (rc != RD_OK)
            return send_error(h, c, rq, &err, NULL);
        struct MHD_Response *r = text_response(rq, body, "text/csv; charset=utf-8");
        if (r) {
            char disposition[64];
            snprintf(disposition, sizeof disposition, "inline; filename=\"%.16s.csv\"", id);
            r = with_header(r, "Content-Disposition", disposition);
        }
        return send_response(h, c, rq, MHD_HTTP_OK, r);
    }
    rd_jobs_body *shared = NULL;
    if (strcmp(method, MHD_HTTP_METHOD_DELETE) == 0) {
        /* A final job is deleted (204); a queued or running one is
         * cancelled and answered as it then is, as before. */
        int deleted = 0;
        if ((rc = rd_jobs_delete(h->jobs, id, &deleted, &err)) != RD_OK)
            return send_error(h, c, rq, &err, NULL);
        if (deleted)
            return send_response(
                h, c, rq, MHD_HTTP_NO_CONTENT,
                MHD_create_response_from_buffer(0, (void *)"", MHD_RESPMEM_PERSISTENT));
        if (!rd_jobs_is_final(h->jobs, id)) /* running: wait for it to stop */
            return suspend_for(h, c, rq, WAIT_CANCEL, id, CANCEL_WAIT_S);
    }
    rc = rd_jobs_get(h->jobs, id, 0, &shared, &body, NULL, &err);
    if (rc != RD_OK)
        return send_error(h, c, rq, &err, NULL);
    return send_response(h, c, rq, MHD_HTTP_OK, job_response(rq, shared, body, 0));
}

/* An rd_sweeps answer as a response, or a suspended wait (status 0). */
static enum MHD_Result sweep_reply(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   rd_sweeps_reply *sr)
{
    if (sr->status == 0) {
        rq->sweep = sr->wait_submit;
        return suspend_for(h, c, rq, WAIT_SWEEP, sr->wait_id, sr->wait_s);
    }
    struct MHD_Response *r =
        sr->body ? text_response(rq, sr->body, sr->content_type)
                 : MHD_create_response_from_buffer(0, (void *)"", MHD_RESPMEM_PERSISTENT);
    sr->body = NULL;
    char seconds[16];
    snprintf(seconds, sizeof seconds, "%d", sr->retry_after);
    if (r && ((sr->location[0] &&
               MHD_add_response_header(r, MHD_HTTP_HEADER_LOCATION, sr->location) != MHD_YES) ||
              (sr->disposition[0] &&
               MHD_add_response_header(r, "Content-Disposition", sr->disposition) != MHD_YES) ||
              (sr->retry_after &&
               MHD_add_response_header(r, MHD_HTTP_HEADER_RETRY_AFTER, seconds) != MHD_YES))) {
        MHD_destroy_response(r);
        r = NULL;
    }
    return send_response(h, c, rq, sr->status, r);
}

/* GET /api/v1/sweeps, and GET/HEAD/DELETE under it. */
static enum MHD_Result sweep_route(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   enum route route, const char *method, const char *id)
{
    rd_sweeps_reply sr = {0};
    long limit = LIST_LIMIT_DEFAULT;
    const char *s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "limit");
    if (route == ROUTE_SWEEPS && s && !parse_count(s, 1, LIST_LIMIT_MAX, &limit)) {
        char buf[32];
        return send_fail(
            h, c, rq, RD_EREQUEST,
            "The query parameter limit must be a whole number from 1 to %d, not \"%s\".",
            LIST_LIMIT_MAX, printable(s, buf, sizeof buf));
    }
    if (route == ROUTE_SWEEPS)
        rd_sweeps_list(h->sweeps, (size_t)limit, &sr);
    else
        rd_sweeps_item(h->sweeps, method, id, route == ROUTE_SWEEP_CSV, &sr);
    return sweep_reply(h, c, rq, &sr);
}

/* Cache-Control: no-cache (or no-store) among the request's directives. */
static int no_cache_asked(struct MHD_Connection *c)
{
    const char *cc = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_CACHE_CONTROL);
    if (!cc)
        return 0;
    for (const char *p = cc; *p;) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        size_t n = strcspn(p, ", \t=");
        if ((n == 8 && strncasecmp(p, "no-cache", 8) == 0) ||
            (n == 8 && strncasecmp(p, "no-store", 8) == 0))
            return 1;
        p += strcspn(p, ",");
    }
    return 0;
}

/* First call of POST /api/v1/jobs: everything that can be refused before
 * the body is read. */
static enum MHD_Result begin_submit(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    char buf[64];
    const char *type =
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_TYPE);
    if (!is_json_media_type(type))
        return send_fail(h, c, rq, RD_EMEDIA,
                         "The body must be sent as Content-Type: application/json, not %s.",
                         type ? printable(type, buf, sizeof buf) : "without a Content-Type");
    const char *wait = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "wait");
    if (wait) {
        if (!parse_seconds(wait, RD_HTTP_WAIT_MAX, &rq->wait_s))
            return send_fail(h, c, rq, RD_EREQUEST,
                             "The query parameter wait must be a number of seconds from 0 to %d, "
                             "not \"%s\".",
                             RD_HTTP_WAIT_MAX, printable(wait, buf, sizeof buf));
        rq->has_wait = 1;
    }
    const char *limit = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "time_limit_s");
    if (limit && !rq->sweep &&
        (!parse_seconds(limit, h->job_timeout_s, &rq->time_limit_s) || rq->time_limit_s <= 0))
        return send_fail(h, c, rq, RD_EREQUEST,
                         "The query parameter time_limit_s must be a number of seconds above 0 and "
                         "at most the server's limit of %g, not \"%s\".",
                         h->job_timeout_s, printable(limit, buf, sizeof buf));
    const char *key = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Idempotency-Key");
    if (key && !rq->sweep && (!*key || strlen(key) > IDEM_KEY_MAX || has_control_char(key)))
        return send_fail(h, c, rq, RD_EREQUEST,
                         "The Idempotency-Key header must be 1 to %d printable characters.",
                         IDEM_KEY_MAX);
    const char *length =
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_LENGTH);
    if (length) {
        char *end;
        errno = 0;
        unsigned long long n = strtoull(length, &end, 10);
        if (errno == 0 && *end == '\0' && n > RD_API_BODY_MAX)
            return send_fail(h, c, rq, RD_ETOOLARGE,
                             "The body has %llu bytes; the limit is %d bytes.", n, RD_API_BODY_MAX);
    }
    return MHD_YES;
}

/* Appends a body chunk, up to RD_API_BODY_MAX bytes in all. */
static void take_body(struct request *rq, const char *data, size_t n)
{
    if (rq->too_large || rq->no_memory)
        return;
    if (n > RD_API_BODY_MAX - rq->len) {
        rq->too_large = 1;
        free(rq->body);
        rq->body = NULL;
        rq->len = rq->cap = 0;
        return;
    }
    if (rq->len + n + 1 > rq->cap) {
        size_t cap = rq->cap ? rq->cap : 4096;
        while (cap < rq->len + n + 1)
            cap *= 2;
        if (cap > RD_API_BODY_MAX + 1)
            cap = RD_API_BODY_MAX + 1;
        char *body = realloc(rq->body, cap);
        if (!body) {
            rq->no_memory = 1;
            return;
        }
        rq->body = body;
        rq->cap = cap;
    }
    memcpy(rq->body + rq->len, data, n);
    rq->len += n;
    rq->body[rq->len] = '\0';
}

/* The answer to a submission: 200 and the job if ?wait was given and the
 * job is final, else 202; Location either way. */
static enum MHD_Result answer_submit(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                     const char *id)
{
    rd_error err;
    rd_error_init(&err);
    char *body = NULL;
    rd_jobs_body *shared = NULL;
    int finished = 0;
    if (rd_jobs_get(h->jobs, id, 0, &shared, &body, &finished, &err) != RD_OK)
        return send_error(h, c, rq, &err, NULL);
    struct MHD_Response *r =
        job_response(rq, shared, body, rq->cache && strcmp(rq->cache, "hit") == 0);
    char location[64];
    snprintf(location, sizeof location, "/api/v1/jobs/%s", id);
    if (r &&
        (MHD_add_response_header(r, MHD_HTTP_HEADER_LOCATION, location) != MHD_YES ||
         (rq->cache && MHD_add_response_header(r, "X-Ringdyn-Cache", rq->cache) != MHD_YES) ||
         (rq->replayed && MHD_add_response_header(r, "Idempotent-Replayed", "true") != MHD_YES))) {
        MHD_destroy_response(r);
        r = NULL;
    }
    return send_response(h, c, rq, rq->has_wait && finished ? MHD_HTTP_OK : MHD_HTTP_ACCEPTED, r);
}

/* A suspended request, resumed: answer with the job as it is now. */
static enum MHD_Result answer_waiter(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    enum wait_kind kind = rq->waiting;
    rq->waiting = WAIT_NONE;
    rq->resumed = 0;
    if (kind == WAIT_SUBMIT)
        return answer_submit(h, c, rq, rq->job_id);
    if (kind == WAIT_SWEEP) {
        rd_sweeps_reply sr = {0};
        rd_sweeps_answer_wait(h->sweeps, rq->job_id, rq->sweep, &sr);
        return sweep_reply(h, c, rq, &sr);
    }
    rd_error err;
    rd_error_init(&err);
    char *body = NULL;
    rd_jobs_body *shared = NULL;
    if (rd_jobs_get(h->jobs, rq->job_id, 0, &shared, &body, NULL, &err) != RD_OK)
        return send_error(h, c, rq, &err, NULL);
    return send_response(h, c, rq, MHD_HTTP_OK, job_response(rq, shared, body, 0));
}

/* Last call of POST /api/v1/jobs: parse, queue, maybe wait. */
static enum MHD_Result finish_submit(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    if (rq->too_large)
        return send_fail(h, c, rq, RD_ETOOLARGE, "The body is larger than the limit of %d bytes.",
                         RD_API_BODY_MAX);
    if (rq->no_memory)
        return send_response(h, c, rq, 0, NULL);
    if (rq->sweep) {
        rd_sweeps_reply sr = {0};
        rd_sweeps_post(h->sweeps, rq->body ? rq->body : "", rq->len, rq->has_wait ? rq->wait_s : -1,
                       &sr);
        return sweep_reply(h, c, rq, &sr);
    }

    rd_jobs_submit_opts opts = {0};
    opts.idem_key = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Idempotency-Key");
    if (opts.idem_key) /* "the same body": the same bytes */
        rd_jobs_hash(rq->body ? rq->body : "", rq->body ? rq->len : 0, opts.idem_hash);
    rd_scene *scene = NULL;
    char *errors = NULL; /* the error body with every problem (rd_api.h) */
    int rc = rd_scene_parse_report(rq->body ? rq->body : "", rq->len, &scene, &err, &errors);
    free(rq->body);
    rq->body = NULL;
    if (rc != RD_OK && err.code != RD_OK && errors)
        return send_text(h, c, rq, rd_api_http_status(err.code), errors, json_media);
    free(errors);
    if (rc != RD_OK) {
        if (err.code == RD_OK)
            rd_error_set(&err, rc, "", "%s.", rd_error_summary(rc));
        return send_error(h, c, rq, &err, NULL);
    }
    opts.use_cache = !no_cache_asked(c);
    opts.time_limit_s = rq->time_limit_s;
    if (rq->has_wait && rq->wait_s > 0)
        opts.inline_below_s = INLINE_BELOW_S;
    rd_jobs_submitted out;
    if (rd_jobs_submit(h->jobs, scene, &opts, &out, &err) != RD_OK) /* takes the scene */
        return send_error(h, c, rq, &err, NULL);
    if (out.conflict) {
        char message[256];
        snprintf(message, sizeof message,
                 "The Idempotency-Key was first sent with another body (it made job %s); send that "
                 "body again to get that job, or use a new key for a new scene.",
                 out.id);
        return send_server_error(h, c, rq, MHD_HTTP_CONFLICT, "idempotency_conflict", message, NULL,
                                 NULL);
    }
    /* A replay says so (Idempotent-Replayed), not what the cache did. */
    rq->cache = out.replayed ? NULL : out.cached ? "hit" : opts.use_cache ? "miss" : "bypass";
    rq->replayed = out.replayed;
    if (!out.replayed)
        rd_metrics_count_cache(h->metrics, out.cached, !opts.use_cache);
    if (out.ran_inline)
        rd_metrics_count_inline(h->metrics);

    if (rq->has_wait && rq->wait_s > 0 && !rd_jobs_is_final(h->jobs, out.id))
        return suspend_for(h, c, rq, WAIT_SUBMIT, out.id, rq->wait_s);
    return answer_submit(h, c, rq, out.id);
}

/* The query parameters a route reads with this method, comma-separated
 * (every other one is refused: a typo must not pass silently). */
static const char *allowed_params(enum route r, const char *method)
{
    int post = strcmp(method, MHD_HTTP_METHOD_POST) == 0;
    switch (r) {
    case ROUTE_JOBS:
        return post ? "wait, time_limit_s" : "limit, status, analysis, name, cursor";
    case ROUTE_SWEEPS:
        return post ? "wait" : "limit";
    default:
        return "";
    }
}

struct param_scan {
    const char *allowed;
    const char *unknown; /* the first parameter not allowed */
};

static enum MHD_Result scan_param(void *cls, enum MHD_ValueKind kind, const char *key,
                                  const char *value)
{
    (void)kind;
    (void)value;
    struct param_scan *scan = cls;
    if (!method_allowed(scan->allowed, key)) { /* the same comma-list match */
        scan->unknown = key;
        return MHD_NO;
    }
    return MHD_YES;
}

/* First call of every request: route, check the method, answer (or, for a
 * submission, prepare to read the body). */
static enum MHD_Result begin_request(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                     const char *url, const char *method, const char *version)
{
    char arg[PATH_ARG_MAX];
    int refused = 0;
    enum MHD_Result framing = check_framing(h, c, rq, version, &refused);
    if (refused)
        return framing;
    if (!host_allowed(h, MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_HOST)))
        return send_server_error(h, c, rq, MHD_HTTP_FORBIDDEN, "forbidden_host",
                                 "This server does not serve the host named in the Host header "
                                 "(a guard against DNS rebinding); start it with --allow-host NAME "
                                 "to serve that name.",
                                 NULL, NULL);
    if (has_control_char(url))
        return send_not_found(h, c, rq, url);
    enum route route = match_route(url, arg, sizeof arg);
    if (h->token && route_needs_token(route) && !authorized(h, c))
        return send_server_error(h, c, rq, MHD_HTTP_UNAUTHORIZED, "unauthorized",
                                 "This server needs its access token: send the header "
                                 "Authorization: Bearer TOKEN (the token is in the file given to "
                                 "--token-file).",
                                 MHD_HTTP_HEADER_WWW_AUTHENTICATE, "Bearer realm=\"ringdyn\"");
    if (route == ROUTE_STATIC)
        return serve_static(h, c, rq, url, method);
    if (route == ROUTE_NONE || (route >= ROUTE_SWEEPS && !h->sweeps))
        return send_not_found(h, c, rq, url);

    const char *allow = allowed_methods(route);
    if (!method_allowed(allow, method)) {
        char buf[32], where[128];
        rd_error err;
        rd_error_init(&err);
        rd_error_set(&err, RD_EMETHOD, "", "Method %s is not allowed on %s; allowed: %s.",
                     printable(method, buf, sizeof buf), printable(url, where, sizeof where),
                     allow);
        return send_error(h, c, rq, &err, allow);
    }
    const char *params = allowed_params(route, method);
    struct param_scan scan = {params, NULL};
    MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, scan_param, &scan);
    if (scan.unknown) {
        char buf[64], where[128];
        return send_fail(h, c, rq, RD_EREQUEST, "Unknown query parameter \"%s\" on %s %s; %s%s.",
                         printable(scan.unknown, buf, sizeof buf), method,
                         printable(url, where, sizeof where),
                         *params ? "allowed: " : "it takes none", params);
    }
    rq->gzip = rd_gzip_accepted(
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT_ENCODING));
    switch (route) {
    case ROUTE_JOBS:
        if (strcmp(method, MHD_HTTP_METHOD_POST) == 0)
            return begin_submit(h, c, rq);
        return list_jobs(h, c, rq);
    case ROUTE_JOB:
    case ROUTE_JOB_CSV:
        return job_route(h, c, rq, route, method, arg);
    case ROUTE_EXAMPLES:
        return get_examples(h, c, rq);
    case ROUTE_EXAMPLE:
        return get_example(h, c, rq, arg);
    case ROUTE_HEALTH:
        return get_health(h, c, rq);
    case ROUTE_OPENAPI:
        return get_openapi(h, c, rq);
    case ROUTE_METRICS:
        return get_metrics(h, c, rq);
    case ROUTE_SWEEPS:
        if (strcmp(method, MHD_HTTP_METHOD_POST) == 0) {
            rq->sweep = 1;
            return begin_submit(h, c, rq);
        }
        return sweep_route(h, c, rq, route, method, arg);
    case ROUTE_SWEEP:
    case ROUTE_SWEEP_CSV:
        return sweep_route(h, c, rq, route, method, arg);
    case ROUTE_NONE:
    case ROUTE_STATIC:
        break;
    }
    return send_not_found(h, c, rq, url);
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *c, const char *url,
                                  const char *method, const char *version, const char *upload_data,
                                  size_t *upload_data_size, void **req_cls)
{
    rd_http *h = cls;
    struct request *rq = *req_cls;
    if (!rq) {
        rq = calloc(1, sizeof *rq);
        if (!rq)
            return MHD_NO; /* closes the connection */
        *req_cls = rq;
        rq->c = c;
        const union MHD_ConnectionInfo *info =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
        rq->conn = info ? info->socket_context : NULL;
        pthread_mutex_lock(&h->mu);
        h->in_flight++;
        pthread_mutex_unlock(&h->mu);
    }
    if (rq->waiting != WAIT_NONE) {
        if (!rq->resumed) /* MHD should not call a suspended request; be safe */
            return MHD_YES;
        return answer_waiter(h, c, rq);
    }
    if (!rq->started) {
        rq->started = 1;
        return begin_request(h, c, rq, url, method, version);
    }
    if (*upload_data_size) {
        if (!rq->replied)
            take_body(rq, upload_data, *upload_data_size);
        *upload_data_size = 0;
        return MHD_YES;
    }
    if (rq->replied)
        return MHD_YES;
    return finish_submit(h, c, rq);
}

/* MHD_OPTION_NOTIFY_COMPLETED: the response has been sent (or the
 * connection died); called for every request that got a *req_cls. */
static void on_completed(void *cls, struct MHD_Connection *c, void **req_cls,
                         enum MHD_RequestTerminationCode toe)
{
    rd_http *h = cls;
    (void)c;
    (void)toe;
    struct request *rq = *req_cls;
    if (!rq)
        return;
    free(rq->body);
    pthread_mutex_lock(&h->mu);
    if (rq->waiting != WAIT_NONE && !rq->resumed) { /* still listed (daemon stop) */
        if (rq->prev)
            rq->prev->next = rq->next;
        else
            h->waiters = rq->next;
        if (rq->next)
            rq->next->prev = rq->prev;
    }
    if (rq->conn) { /* the next request on this connection starts now */
        rq->conn->busy = 0;
        rq->conn->since = rd_clock_mono_s();
    }
    free(rq);
    *req_cls = NULL;
    if (--h->in_flight == 0)
        pthread_cond_broadcast(&h->idle);
    pthread_mutex_unlock(&h->mu);
}

/* ---- life cycle ---- */

static int is_loopback(const struct sockaddr_storage *addr)
{
    if (addr->ss_family == AF_INET) {
        const struct sockaddr_in *a4 = (const struct sockaddr_in *)addr;
        return (ntohl(a4->sin_addr.s_addr) >> 24) == 127;
    }
    const struct sockaddr_in6 *a6 = (const struct sockaddr_in6 *)addr;
    return IN6_IS_ADDR_LOOPBACK(&a6->sin6_addr) ||
           (IN6_IS_ADDR_V4MAPPED(&a6->sin6_addr) && a6->sin6_addr.s6_addr[12] == 127);
}

static int is_wildcard(const struct sockaddr_storage *addr)
{
    if (addr->ss_family == AF_INET)
        return ((const struct sockaddr_in *)addr)->sin_addr.s_addr == htonl(INADDR_ANY);
    return IN6_IS_ADDR_UNSPECIFIED(&((const struct sockaddr_in6 *)addr)->sin6_addr);
}

static int add_allowed(rd_http *h, const char *name, rd_error *err)
{
    char buf[256];
    const char *lower = host_name(name, buf, sizeof buf);
    if (!lower || strlen(lower) != strlen(name)) /* a port was given */
        return rd_error_set(
            err, RD_EINVAL, "",
            "--allow-host %s: not a host name (give the name without a port; IPv6 in "
            "brackets).",
            name);
    char **grown = realloc(h->allow, (h->n_allow + 1) * sizeof *grown);
    if (!grown)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    h->allow = grown;
    if (!(h->allow[h->n_allow] = strdup(lower)))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    h->n_allow++;
    return RD_OK;
}

/* The Host allowlist (loopback names, the bound address unless it is a
 * wildcard, --allow-host) and a copy of the token. */
static int set_access(rd_http *h, const rd_http_config *cfg, const struct sockaddr_storage *addr,
                      rd_error *err)
{
    static const char *const loopback[] = {"127.0.0.1", "localhost", "[::1]"};
    int rc = RD_OK;
    for (size_t i = 0; i < sizeof loopback / sizeof loopback[0] && rc == RD_OK; i++)
        rc = add_allowed(h, loopback[i], err);
    if (rc == RD_OK && !is_wildcard(addr))
        rc = add_allowed(h, h->host, err);
    for (int i = 0; i < cfg->n_allow_hosts && rc == RD_OK; i++)
        rc = add_allowed(h, cfg->allow_hosts[i], err);
    if (rc == RD_OK && cfg->token && !(h->token = strdup(cfg->token)))
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    return rc;
}

/* realpath of a directory option, or an error naming the option. */
static int resolve_dir(const char *option, const char *dir, char **out, rd_error *err)
{
    *out = NULL;
    if (!dir)
        return RD_OK;
    char *path = realpath(dir, NULL);
    struct stat st;
    if (!path || stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        int e = errno;
        free(path);
        return rd_error_set(err, RD_EINVAL, "", "%s %s: not a readable directory (%s).", option,
                            dir, path ? "not a directory" : strerror(e));
    }
    *out = path;
    return RD_OK;
}

int rd_http_create(const rd_http_config *cfg, rd_jobs *jobs, rd_metrics *metrics, rd_http **out,
                   rd_error *err)
{
    int rc = RD_OK;
    struct addrinfo *ai = NULL;
    *out = NULL;
    rd_http *h = calloc(1, sizeof *h);
    if (!h)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    h->jobs = jobs;
    h->metrics = metrics;
    h->sweeps = cfg->sweeps;
    h->job_timeout_s = cfg->job_timeout_s;
    h->quiesced_fd = MHD_INVALID_SOCKET;
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    int sync_failed = pthread_mutex_init(&h->mu, NULL) != 0 ||
                      pthread_cond_init(&h->idle, &attr) != 0 ||
                      pthread_cond_init(&h->wake, &attr) != 0;
    pthread_condattr_destroy(&attr);
    if (sync_failed) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "Cannot initialise the HTTP server's locks.");
        goto out;
    }
    if ((rc = resolve_dir("--static", cfg->static_dir, &h->static_root, err)) != RD_OK ||
        (rc = resolve_dir("--examples", cfg->examples_dir, &h->examples_dir, err)) != RD_OK)
        goto out;
    h->limits = cfg->limits;
    if (cfg->limits.threads < 1 || cfg->limits.connections_max < 1 || cfg->limits.per_ip_max < 1 ||
        !(cfg->limits.request_deadline_s > 0) || cfg->limits.idle_timeout_s < 1) {
        rc = rd_error_set(err, RD_EINVAL, "", "Connection limits out of range.");
        goto out;
    }
    if (cfg->port < 0 || cfg->port > 65535) {
        rc = rd_error_set(err, RD_EINVAL, "", "--port %d: not a port (0..65535).", cfg->port);
        goto out;
    }

    struct addrinfo hints;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    int gai = getaddrinfo(cfg->host, NULL, &hints, &ai);
    if (gai != 0) {
        rc = rd_error_set(err, RD_EINVAL, "", "--host %s: %s.", cfg->host, gai_strerror(gai));
        goto out;
    }
    struct sockaddr_storage addr;
    memset(&addr, 0, sizeof addr);
    memcpy(&addr, ai->ai_addr, ai->ai_addrlen);
    unsigned int flags = MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_EPOLL | MHD_USE_ITC |
                         MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    char text[INET6_ADDRSTRLEN];
    if (ai->ai_family == AF_INET6) {
        struct sockaddr_in6 *a6 = (struct sockaddr_in6 *)&addr;
        a6->sin6_port = htons((uint16_t)cfg->port);
        inet_ntop(AF_INET6, &a6->sin6_addr, text, sizeof text);
        snprintf(h->host, sizeof h->host, "[%s]", text);
        flags |= MHD_USE_IPv6;
    } else {
        struct sockaddr_in *a4 = (struct sockaddr_in *)&addr;
        a4->sin_port = htons((uint16_t)cfg->port);
        inet_ntop(AF_INET, &a4->sin_addr, text, sizeof text);
        snprintf(h->host, sizeof h->host, "%s", text);
    }

    if (!is_loopback(&addr) && !cfg->token) {
        rc = rd_error_set(err, RD_EINVAL, "",
                          "--host %s is not a loopback address: give an access token with "
                          "--token-file FILE.",
                          cfg->host);
        goto out;
    }
    if ((rc = set_access(h, cfg, &addr, err)) != RD_OK)
        goto out;

    int e = pthread_create(&h->timer, NULL, timer_main, h);
    if (e != 0) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "Cannot start the timer thread: %s.", strerror(e));
        goto out;
    }
    h->timer_started = 1;
    const rd_http_limits *lim = &cfg->limits;
    h->daemon = MHD_start_daemon(
        flags, (uint16_t)cfg->port, NULL, NULL, on_request, h, MHD_OPTION_SOCK_ADDR,
        (struct sockaddr *)&addr, MHD_OPTION_THREAD_POOL_SIZE, (unsigned int)lim->threads,
        MHD_OPTION_CONNECTION_LIMIT, (unsigned int)lim->connections_max,
        MHD_OPTION_PER_IP_CONNECTION_LIMIT, (unsigned int)lim->per_ip_max,
        MHD_OPTION_CONNECTION_TIMEOUT, (unsigned int)lim->idle_timeout_s,
        MHD_OPTION_LISTEN_BACKLOG_SIZE, (unsigned int)LISTEN_BACKLOG, MHD_OPTION_NOTIFY_COMPLETED,
        on_completed, (void *)h, MHD_OPTION_NOTIFY_CONNECTION, on_connection, (void *)h,
        MHD_OPTION_UNESCAPE_CALLBACK, unescape_path, (void *)NULL, MHD_OPTION_END);
    if (!h->daemon) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "Cannot listen on %s port %d (in use?).", h->host,
                          cfg->port);
        goto out;
    }
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(h->daemon, MHD_DAEMON_INFO_BIND_PORT);
    h->port = info ? info->port : cfg->port;
out:
    if (ai)
        freeaddrinfo(ai);
    if (rc != RD_OK)
        rd_http_free(h);
    else
        *out = h;
    return rc;
}

const char *rd_http_get_host(const rd_http *http)
{
    return http->host;
}

int rd_http_get_port(const rd_http *http)
{
    return http->port;
}

void rd_http_quiesce(rd_http *http)
{
    if (http && http->daemon && http->quiesced_fd == MHD_INVALID_SOCKET)
        http->quiesced_fd = MHD_quiesce_daemon(http->daemon);
}

void rd_http_drain(rd_http *http, double seconds)
{
    if (!http)
        return;
    struct timespec deadline = rd_clock_mono_deadline(seconds);
    pthread_mutex_lock(&http->mu);
    while (http->in_flight > 0)
        if (pthread_cond_timedwait(&http->idle, &http->mu, &deadline) == ETIMEDOUT)
            break;
    pthread_mutex_unlock(&http->mu);
}

void rd_http_free(rd_http *http)
{
    if (!http)
        return;
    if (http->timer_started) { /* resumes every waiter on its way out */
        pthread_mutex_lock(&http->mu);
        http->stop = 1;
        pthread_cond_signal(&http->wake);
        pthread_mutex_unlock(&http->mu);
        pthread_join(http->timer, NULL);
    }
    if (http->daemon)
        MHD_stop_daemon(http->daemon);
    if (http->quiesced_fd != MHD_INVALID_SOCKET)
        close(http->quiesced_fd);
    pthread_cond_destroy(&http->idle);
    pthread_cond_destroy(&http->wake);
    pthread_mutex_destroy(&http->mu);
    free(http->static_root);
    free(http->examples_dir);
    for (size_t i = 0; i < http->n_allow; i++)
        free(http->allow[i]);
    free(http->allow);
    free(http->token);
    free(http);
}
