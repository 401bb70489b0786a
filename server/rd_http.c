/*
 * rd_http — routes, limits, error bodies and static files (rd_http.h).
 *
 * Request life cycle in libmicrohttpd: the access handler is called once
 * with the headers (upload_data_size 0), then once per chunk of body, then a
 * last time with upload_data_size 0.  A request without a body is handled on
 * that last call (has_body: an answer queued on the first call closes the
 * connection), one with a body on the first.  Handling checks framing, Host
 * and token (rd_http_check_framing, rd_http_host_allowed,
 * rd_http_authorized), then routes.  Everything except POST /api/v1/jobs
 * and DELETE of a running job is answered there and then.  For a POST
 * the first call checks the method, Content-Type, ?wait= and a declared
 * Content-Length, so a bad request is refused before its body is read; the
 * chunks are then collected up to RD_API_BODY_MAX bytes (beyond that they
 * are counted and dropped, never buffered) and the last call parses the
 * scene, queues it and, with ?wait, suspends the connection
 * (rd_http_suspend_for) until the job ends or the wait is over; the timer
 * thread resumes it and MHD calls the handler once more
 * (rd_routes_answer_waiter).  A succeeded job is sent from its shared JSON
 * (rd_http_job_response), its CSV and gzip from forms made once with it
 * (rd_http_body_response), never copied per request.
 *
 * This file is the top of the layer (rd_http_int.h lists the floors): the
 * route table, the handler MHD calls, and the life cycle.
 */
#include "rd_http_int.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netdb.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "rd_clock.h"
#include "rd_gzip.h"

/* Connections the kernel queues before MHD accepts them. */
#define LISTEN_BACKLOG 1024
/* Room for a job id or example name taken from a path. */
#define PATH_ARG_MAX 80

/* Maps a decoded path to a route; `arg` receives the job id or example name. */
static enum route match_route(const char *url, char *arg, size_t argsz)
{
    static const struct {
        const char *path;
        enum route route;
    } fixed[] = {{"/api/v1/jobs", ROUTE_JOBS},
                 {"/api/v1/examples", ROUTE_EXAMPLES},
                 {"/api/v1/health", ROUTE_HEALTH},
                 {"/api/v1/openapi.json", ROUTE_OPENAPI},
                 {"/metrics", ROUTE_METRICS},
                 {"/api/v1/sweeps", ROUTE_SWEEPS},
                 {"/api/v1/calibrations", ROUTE_CALIBRATIONS}};
    arg[0] = '\0';
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        if (strcmp(url, fixed[i].path) == 0)
            return fixed[i].route;

    const char *rest;
    if ((rest = rd_http_after_prefix(url, "/api/v1/jobs/"))) {
        const char *slash = strchr(rest, '/');
        size_t n = slash ? (size_t)(slash - rest) : strlen(rest);
        if (n == 0 || n >= argsz || (slash && strcmp(slash, "/result.csv") != 0))
            return ROUTE_NONE;
        memcpy(arg, rest, n);
        arg[n] = '\0';
        return slash ? ROUTE_JOB_CSV : ROUTE_JOB;
    }
    if ((rest = rd_http_after_prefix(url, "/api/v1/sweeps/"))) {
        const char *slash = strchr(rest, '/');
        size_t n = slash ? (size_t)(slash - rest) : strlen(rest);
        if (n == 0 || n >= argsz || (slash && strcmp(slash, "/table.csv") != 0))
            return ROUTE_NONE;
        memcpy(arg, rest, n);
        arg[n] = '\0';
        return slash ? ROUTE_SWEEP_CSV : ROUTE_SWEEP;
    }
    if ((rest = rd_http_after_prefix(url, "/api/v1/examples/"))) {
        size_t n = strlen(rest);
        if (n == 0 || n >= argsz || strchr(rest, '/'))
            return ROUTE_NONE;
        memcpy(arg, rest, n + 1);
        return ROUTE_EXAMPLE;
    }
    if (strcmp(url, "/api") == 0 || rd_http_after_prefix(url, "/api/"))
        return ROUTE_NONE;
    return ROUTE_STATIC;
}

/* The route template a request is counted under in /metrics (bounded:
 * never the raw URL). */
static rd_metrics_route metrics_route(const char *url)
{
    char arg[PATH_ARG_MAX];
    static const rd_metrics_route of[] = {
        [ROUTE_NONE] = RD_METRICS_ROUTE_OTHER,
        [ROUTE_JOBS] = RD_METRICS_ROUTE_JOBS,
        [ROUTE_JOB] = RD_METRICS_ROUTE_JOB,
        [ROUTE_JOB_CSV] = RD_METRICS_ROUTE_JOB_CSV,
        [ROUTE_EXAMPLES] = RD_METRICS_ROUTE_EXAMPLES,
        [ROUTE_EXAMPLE] = RD_METRICS_ROUTE_EXAMPLE,
        [ROUTE_HEALTH] = RD_METRICS_ROUTE_HEALTH,
        [ROUTE_OPENAPI] = RD_METRICS_ROUTE_OPENAPI,
        [ROUTE_METRICS] = RD_METRICS_ROUTE_METRICS,
        [ROUTE_STATIC] = RD_METRICS_ROUTE_STATIC,
        [ROUTE_SWEEPS] = RD_METRICS_ROUTE_SWEEPS,
        [ROUTE_SWEEP] = RD_METRICS_ROUTE_SWEEP,
        [ROUTE_SWEEP_CSV] = RD_METRICS_ROUTE_SWEEP_CSV,
        [ROUTE_CALIBRATIONS] = RD_METRICS_ROUTE_CALIBRATIONS,
    };
    enum route r = url ? match_route(url, arg, sizeof arg) : ROUTE_NONE;
    return (size_t)r < sizeof of / sizeof of[0] ? of[r] : RD_METRICS_ROUTE_OTHER;
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
    case ROUTE_CALIBRATIONS:
        return "POST";
    default:
        return "GET, HEAD";
    }
}

/* The query parameters a route reads with this method, comma-separated
 * (every other one is refused: a typo must not pass silently). */
static const char *allowed_params(enum route r, const char *method)
{
    int post = strcmp(method, MHD_HTTP_METHOD_POST) == 0;
    switch (r) {
    case ROUTE_JOBS:
        return post ? "wait, time_limit_s" : "limit, status, analysis, name, cursor";
    case ROUTE_CALIBRATIONS:
        return "wait, time_limit_s";
    case ROUTE_SWEEPS:
        return post ? "wait" : "limit";
    case ROUTE_JOB: /* GET and HEAD: the long poll */
        return strcmp(method, MHD_HTTP_METHOD_DELETE) == 0 ? "" : "wait";
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
    if (!rd_http_method_allowed(scan->allowed, key)) { /* the same comma-list match */
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
    enum MHD_Result framing = rd_http_check_framing(h, c, rq, version, &refused);
    if (refused)
        return framing;
    if (!rd_http_host_allowed(
            h, MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_HOST)))
        return rd_http_send_server_error(
            h, c, rq, MHD_HTTP_FORBIDDEN, "forbidden_host",
            "This server does not serve the host named in the Host header "
            "(a guard against DNS rebinding); start it with --allow-host NAME "
            "to serve that name.",
            NULL, NULL);
    if (rd_http_has_control_char(url))
        return rd_http_send_not_found(h, c, rq, url);
    enum route route = match_route(url, arg, sizeof arg);
    if (h->token && route_needs_token(route) && !rd_http_authorized(h, c))
        return rd_http_send_server_error(
            h, c, rq, MHD_HTTP_UNAUTHORIZED, "unauthorized",
            "This server needs its access token: send the header "
            "Authorization: Bearer TOKEN (the token is in the file given to "
            "--token-file).",
            MHD_HTTP_HEADER_WWW_AUTHENTICATE, "Bearer realm=\"ringdyn\"");
    if (route == ROUTE_STATIC)
        return rd_http_serve_static(h, c, rq, url, method);
    if (route == ROUTE_NONE || (route >= ROUTE_SWEEPS && !h->sweeps))
        return rd_http_send_not_found(h, c, rq, url);

    const char *allow = allowed_methods(route);
    if (!rd_http_method_allowed(allow, method)) {
        char buf[32], where[128];
        rd_error err;
        rd_error_init(&err);
        rd_error_set(&err, RD_EMETHOD, "", "Method %s is not allowed on %s; allowed: %s.",
                     rd_http_printable(method, buf, sizeof buf),
                     rd_http_printable(url, where, sizeof where), allow);
        return rd_http_send_error(h, c, rq, &err, allow);
    }
    const char *params = allowed_params(route, method);
    struct param_scan scan = {params, NULL};
    MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, scan_param, &scan);
    if (scan.unknown) {
        char buf[64], where[128];
        return rd_http_send_fail(h, c, rq, RD_EREQUEST,
                                 "Unknown query parameter \"%s\" on %s %s; %s%s.",
                                 rd_http_printable(scan.unknown, buf, sizeof buf), method,
                                 rd_http_printable(url, where, sizeof where),
                                 *params ? "allowed: " : "it takes none", params);
    }
    rq->gzip = rd_gzip_accepted(
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT_ENCODING));
    return rd_routes_begin(h, c, rq, route, method, arg, url);
}

/* The request declares a body (Content-Length above 0, or Transfer-Encoding).
 * One without is answered on MHD's last call, once it has been read whole:
 * libmicrohttpd 0.9.75 closes the connection after an answer queued on the
 * first call (the headers alone: it cannot know what follows), which
 * dropped keep-alive and every pipelined request behind a GET.  A request
 * with a body is still refused on the first call when it can be (method,
 * Content-Type, size), before its body is read; that answer closes. */
static int has_body(struct MHD_Connection *c)
{
    const char *len =
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_LENGTH);
    if (MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_TRANSFER_ENCODING))
        return 1;
    return len && len[strspn(len, "0")] != '\0';
}

/* A connection over a limit (rd_http_conn.c): 429 over --max-per-ip, 503
 * over --max-connections, with Retry-After, then closed. */
static enum MHD_Result refuse_over_limit(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                         int status)
{
    char message[200];
    int per_ip = status == MHD_HTTP_TOO_MANY_REQUESTS;
    snprintf(message, sizeof message,
             "This %s holds its limit of %d open connections (%s): close one, or retry after "
             "the time in Retry-After.",
             per_ip ? "client address" : "server",
             per_ip ? h->limits.per_ip_max : h->limits.connections_max,
             per_ip ? "--max-per-ip" : "--max-connections");
    rq->started = 1;
    struct MHD_Response *r = rd_http_error_response(rq, "too_many_connections", message);
    r = rd_http_with_header(r, MHD_HTTP_HEADER_RETRY_AFTER, "1");
    r = rd_http_with_header(r, MHD_HTTP_HEADER_CONNECTION, "close");
    return rd_http_send_response(h, c, rq, status, r);
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
        rq->t0 = rd_clock_mono_s();
        rq->metrics_route = metrics_route(url);
        if (method && strlen(method) < sizeof rq->method)
            memcpy(rq->method, method, strlen(method) + 1);
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
        return rd_routes_answer_waiter(h, c, rq);
    }
    if (!rq->started) {
        if (rq->conn && rq->conn->over)
            return refuse_over_limit(h, c, rq, rq->conn->over);
        if (!rq->deferred && !has_body(c)) {
            rq->deferred = 1; /* answered on the next, last call */
            return MHD_YES;
        }
        rq->started = 1;
        return begin_request(h, c, rq, url, method, version);
    }
    if (*upload_data_size) {
        enum MHD_Result ok = MHD_YES;
        if (!rq->replied) {
            rd_routes_take_body(rq, upload_data, *upload_data_size);
            if (rq->too_large)
                ok = rd_http_refuse_body_now(h, rq);
        }
        *upload_data_size = 0;
        return ok;
    }
    if (rq->refused_raw) /* answered on the socket: the body has ended, close */
        return MHD_NO;
    if (rq->replied)
        return MHD_YES;
    return rd_routes_finish_submit(h, c, rq);
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
    rd_http_body_free(rq);
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
    if (--h->in_flight == 0) {
        pthread_cond_broadcast(&h->idle);
        h->idle_since = rd_clock_mono_s();
        h->trim_due = 1;
    }
    pthread_mutex_unlock(&h->mu);
}

/* The locks (rd_http_free destroys them whatever happened). */
static int init_sync(rd_http *h, rd_error *err)
{
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    int sync_failed = pthread_mutex_init(&h->mu, NULL) != 0 ||
                      pthread_cond_init(&h->idle, &attr) != 0 ||
                      pthread_cond_init(&h->wake, &attr) != 0;
    pthread_condattr_destroy(&attr);
    if (sync_failed)
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot initialise the HTTP server's locks.");
    return RD_OK;
}

/* The directories, the connection limits and the port. */
static int take_config(rd_http *h, const rd_http_config *cfg, rd_error *err)
{
    int rc;
    if ((rc = rd_http_resolve_dir("--static", cfg->static_dir, &h->static_root, err)) != RD_OK ||
        (rc = rd_http_resolve_dir("--examples", cfg->examples_dir, &h->examples_dir, err)) != RD_OK)
        return rc;
    h->limits = cfg->limits;
    if (cfg->limits.threads < 1 || cfg->limits.connections_max < 1 || cfg->limits.per_ip_max < 1 ||
        !(cfg->limits.request_deadline_s > 0) || cfg->limits.idle_timeout_s < 1)
        return rd_error_set(err, RD_EINVAL, "", "Connection limits out of range.");
    if (cfg->port < 0 || cfg->port > 65535)
        return rd_error_set(err, RD_EINVAL, "", "--port %d: not a port (0..65535).", cfg->port);
    return RD_OK;
}

/* The address to bind (--host, --port) into *addr, its text into h->host,
 * and MHD's flags for it into *flags. */
static int resolve_host(rd_http *h, const rd_http_config *cfg, struct sockaddr_storage *addr,
                        unsigned int *flags, rd_error *err)
{
    struct addrinfo *ai = NULL;
    struct addrinfo hints;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    int gai = getaddrinfo(cfg->host, NULL, &hints, &ai);
    if (gai != 0)
        return rd_error_set(err, RD_EINVAL, "", "--host %s: %s.", cfg->host, gai_strerror(gai));
    memset(addr, 0, sizeof *addr);
    memcpy(addr, ai->ai_addr, ai->ai_addrlen);
    *flags = MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_EPOLL | MHD_USE_ITC |
             MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    char text[INET6_ADDRSTRLEN];
    if (ai->ai_family == AF_INET6) {
        struct sockaddr_in6 *a6 = (struct sockaddr_in6 *)addr;
        a6->sin6_port = htons((uint16_t)cfg->port);
        inet_ntop(AF_INET6, &a6->sin6_addr, text, sizeof text);
        snprintf(h->host, sizeof h->host, "[%s]", text);
        *flags |= MHD_USE_IPv6;
    } else {
        struct sockaddr_in *a4 = (struct sockaddr_in *)addr;
        a4->sin_port = htons((uint16_t)cfg->port);
        inet_ntop(AF_INET, &a4->sin_addr, text, sizeof text);
        snprintf(h->host, sizeof h->host, "%s", text);
    }
    freeaddrinfo(ai);
    return RD_OK;
}

/* Starts the timer thread, then libmicrohttpd on `addr`; the real port. */
static int start(rd_http *h, const rd_http_config *cfg, struct sockaddr_storage *addr,
                 unsigned int flags, rd_error *err)
{
    int e = pthread_create(&h->timer, NULL, rd_http_timer_main, h);
    if (e != 0)
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot start the timer thread: %s.",
                            strerror(e));
    h->timer_started = 1;
    const rd_http_limits *lim = &cfg->limits;
    h->daemon = MHD_start_daemon(
        flags, (uint16_t)cfg->port, NULL, NULL, on_request, h, MHD_OPTION_SOCK_ADDR,
        (struct sockaddr *)addr, MHD_OPTION_THREAD_POOL_SIZE, (unsigned int)lim->threads,
        MHD_OPTION_CONNECTION_LIMIT, (unsigned int)lim->connections_max + RD_HTTP_OVER_SLACK,
        MHD_OPTION_PER_IP_CONNECTION_LIMIT, (unsigned int)lim->per_ip_max + RD_HTTP_OVER_SLACK,
        MHD_OPTION_CONNECTION_TIMEOUT, (unsigned int)lim->idle_timeout_s,
        MHD_OPTION_LISTEN_BACKLOG_SIZE, (unsigned int)LISTEN_BACKLOG, MHD_OPTION_NOTIFY_COMPLETED,
        on_completed, (void *)h, MHD_OPTION_NOTIFY_CONNECTION, rd_http_on_connection, (void *)h,
        MHD_OPTION_UNESCAPE_CALLBACK, rd_http_unescape_path, (void *)NULL, MHD_OPTION_END);
    if (!h->daemon)
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot listen on %s port %d (in use?).",
                            h->host, cfg->port);
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(h->daemon, MHD_DAEMON_INFO_BIND_PORT);
    h->port = info ? info->port : cfg->port;
    return RD_OK;
}

int rd_http_create(const rd_http_config *cfg, rd_jobs *jobs, rd_metrics *metrics, rd_http **out,
                   rd_error *err)
{
    *out = NULL;
    rd_http *h = calloc(1, sizeof *h);
    if (!h)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    h->jobs = jobs;
    h->metrics = metrics;
    h->sweeps = cfg->sweeps;
    h->job_timeout_s = cfg->job_timeout_s;
    h->quiesced_fd = MHD_INVALID_SOCKET;
    struct sockaddr_storage addr;
    unsigned int flags = 0;
    int rc = init_sync(h, err);
    if (rc == RD_OK)
        rc = take_config(h, cfg, err);
    if (rc == RD_OK)
        rc = resolve_host(h, cfg, &addr, &flags, err);
    if (rc == RD_OK && !rd_http_is_loopback(&addr) && !cfg->token)
        rc = rd_error_set(err, RD_EINVAL, "",
                          "--host %s is not a loopback address: give an access token with "
                          "--token-file FILE.",
                          cfg->host);
    if (rc == RD_OK)
        rc = rd_http_set_access(h, cfg, &addr, err);
    if (rc == RD_OK)
        rc = start(h, cfg, &addr, flags, err);
    if (rc != RD_OK) {
        rd_http_free(h);
        return rc;
    }
    *out = h;
    return RD_OK;
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
