/*
 * rd_http_int.h — the HTTP layer's insides, shared by its files (not a
 * public header: only server/rd_http*.c and rd_routes.c include it).
 *
 * Floors, lowest first; a file calls only the ones below it:
 *   rd_http_util.c    text checks, path decoding, query values
 *   rd_http_conn.c    connections, the request deadline, suspended waits,
 *                     the timer thread
 *   rd_http_reply.c   responses, gzip, error bodies
 *   rd_http_access.c  framing, the Host allowlist, the token
 *   rd_http_static.c  the web page's files
 *   rd_routes.c       the /api/v1 handlers and /metrics
 *   rd_http.c         routing, the handler MHD calls, the life cycle
 */
#ifndef RD_HTTP_INT_H
#define RD_HTTP_INT_H

#include <arpa/inet.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/socket.h>

#include <microhttpd.h>

#include "rd_http.h"

#define RD_HTTP_JSON "application/json"

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
    size_t nover; /* of them over a connection limit (struct conn.over) */
    size_t deadline_closed;
    double idle_since; /* CLOCK_MONOTONIC when in_flight last dropped to 0 */
    int trim_due;      /* a request ended since freed memory was last returned */
};

/* Connections past --max-connections or --max-per-ip that are still accepted
 * and answered 503 / 429 (rd_http_conn.c); beyond these libmicrohttpd closes
 * them unanswered. */
#define RD_HTTP_OVER_SLACK 16

/* Per-connection state (MHD_OPTION_NOTIFY_CONNECTION), in rd_http.conns. */
struct conn {
    struct conn *prev, *next;
    MHD_socket fd;
    double since; /* CLOCK_MONOTONIC: the request now arriving began no earlier */
    int busy;     /* a complete request is being answered: no deadline */
    int shut;     /* the deadline passed and the socket was shut down */
    int over;     /* over --max-per-ip (429) or --max-connections (503): refused */
    int family;   /* the client's address (AF_INET, AF_INET6; 0 unknown) */
    unsigned char addr[16];
};

enum wait_kind { WAIT_NONE, WAIT_SUBMIT, WAIT_CANCEL, WAIT_POLL, WAIT_SWEEP };

/* Per-request state, kept by MHD in *req_cls between calls. */
struct request {
    struct MHD_Connection *c;
    struct conn *conn;           /* may be NULL */
    struct request *prev, *next; /* in rd_http.waiters while suspended */
    enum wait_kind waiting;      /* suspended until its job ends or `until` */
    int resumed;                 /* the timer thread resumed it */
    double until;                /* CLOCK_MONOTONIC */
    char job_id[RD_JOBS_ID_LEN + 1];
    int deferred; /* no body: answered on MHD's last call (keep-alive) */
    int started;  /* the headers have been handled */
    int replied;  /* a response is queued: drop whatever body follows */
    int has_wait; /* ?wait= was given */
    double wait_s;
    char *body; /* POST body so far, NUL-terminated, <= RD_API_BODY_MAX bytes */
    size_t len, cap;
    int body_mapped; /* `body` is a mapping of `cap` bytes (rd_http_body_reserve) */
    int too_large;   /* the body passed RD_API_BODY_MAX: the rest is dropped */
    int refused_raw; /* its 413 was written on the socket (rd_http_refuse_body_now) */
    int no_memory;
    int sweep;           /* a POST /api/v1/sweeps; with WAIT_SWEEP: a wait that answers it */
    const char *as;      /* a POST to a study's path: the analysis its body is ("calibration") */
    int gzip;            /* the client accepts gzip */
    const char *cache;   /* X-Ringdyn-Cache of a submission: "hit", "miss", "bypass", or NULL */
    double time_limit_s; /* ?time_limit_s=, 0 when not given */
    int replayed;        /* the Idempotency-Key named an earlier job with this body */
    double t0;           /* CLOCK_MONOTONIC at its first call: the request's duration */
    rd_metrics_route metrics_route; /* its route template for /metrics */
    char method[8];                 /* its method ("" when longer: counted as "other") */
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
    ROUTE_SWEEP_CSV,
    ROUTE_CALIBRATIONS
};

/* ---- rd_http_util.c ---- */

/* A copy of `s` fit for a message: printable ASCII only, at most n-1 bytes. */
const char *rd_http_printable(const char *s, char *buf, size_t n);
int rd_http_has_control_char(const char *s);
/* MHD_OPTION_UNESCAPE_CALLBACK: %HH decoded in place, %00 as DEL. */
size_t rd_http_unescape_path(void *cls, struct MHD_Connection *c, char *s);
/* "application/json", optionally with "; charset=utf-8". */
int rd_http_is_json_media_type(const char *ct);
/* Plain decimal seconds in [0, max]; 0 when `s` is not one. */
int rd_http_parse_seconds(const char *s, double max, double *out);
/* Plain decimal integer in [min, max]; 0 when `s` is not one. */
int rd_http_parse_count(const char *s, long min, long max, long *out);
/* `s` past `prefix`, or NULL when it does not start with it. */
const char *rd_http_after_prefix(const char *s, const char *prefix);
/* Is `method` one of the comma-separated tokens in `allow`? */
int rd_http_method_allowed(const char *allow, const char *method);
/* Room for `need` bytes (<= RD_API_BODY_MAX + 1) in rq->body, its `len`
 * bytes and NUL kept: malloc'd up to 64 KiB, past that a mapping of its
 * own.  0, or -1 when out of memory (rq unchanged). */
int rd_http_body_reserve(struct request *rq, size_t need);
/* Frees rq->body (either kind); len and cap 0. */
void rd_http_body_free(struct request *rq);

/* ---- rd_http_conn.c ---- */

/* The request is complete (being answered): no deadline until the next. */
void rd_http_set_busy(rd_http *h, struct request *rq);
/* MHD_OPTION_NOTIFY_CONNECTION: keeps rd_http.conns. */
void rd_http_on_connection(void *cls, struct MHD_Connection *c, void **socket_context,
                           enum MHD_ConnectionNotificationCode code);
/* Suspends a request until job (or sweep) `id` ends or `seconds` pass. */
enum MHD_Result rd_http_suspend_for(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                    enum wait_kind kind, const char *id, double seconds);
/* The timer thread (pthread_create's start routine; `arg` is the rd_http). */
void *rd_http_timer_main(void *arg);

/* ---- rd_http_reply.c ---- */

/* Queues `r` (consumed; NULL means out of memory and sends a fixed 503). */
enum MHD_Result rd_http_send_response(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                      int status, struct MHD_Response *r);
/* r with one more header, or NULL (r destroyed) when it cannot be added. */
struct MHD_Response *rd_http_with_header(struct MHD_Response *r, const char *name,
                                         const char *value);
/* A response owning the malloc'd `body` (NULL in, NULL out), gzipped when
 * worth it. */
struct MHD_Response *rd_http_text_response(const struct request *rq, char *body,
                                           const char *content_type);
/* A response sending `len` bytes at `data`, which the shared `body` owns
 * (a reference the response takes over: released when MHD is done with it,
 * or here on failure), or, to a client that accepts gzip when `len` is
 * worth it, the body's form `gz_form` (rd_jobs_form; -1: none), made once
 * per body. */
struct MHD_Response *rd_http_body_response(const struct request *rq, rd_jobs_body *body,
                                           const char *data, size_t len, int gz_form,
                                           const char *content_type);
/* A job's answer: its shared JSON `body` (released when sent), or `json`. */
struct MHD_Response *rd_http_job_response(const struct request *rq, rd_jobs_body *body, char *json,
                                          int cached);
enum MHD_Result rd_http_send_text(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                  int status, char *body, const char *content_type);
/* Room for an ETag: W/"<32 hex digits>" and its NUL. */
#define RD_HTTP_ETAG_LEN 40
/* The ETag of a representation whose uncompressed bytes are `len` at `data`
 * (a finished job's JSON or CSV): weak, since the same tag stands for its
 * gzip too. */
void rd_http_etag(const char *data, size_t len, char *out);
/* The same from the rd_jobs_hash of those bytes. */
void rd_http_etag_of_hash(const uint64_t hash[2], char *out);
/* Does the request's If-None-Match name `etag` (weak comparison) or "*"? */
int rd_http_none_match(struct MHD_Connection *c, const char *etag);
/* r with `etag` and Cache-Control: no-cache in place of no-store (a
 * finished result never changes: a client may keep it and revalidate);
 * NULL in, NULL out. */
struct MHD_Response *rd_http_with_etag(struct MHD_Response *r, const char *etag);
/* 304 Not Modified for `etag`, no body. */
enum MHD_Result rd_http_send_not_modified(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                          const char *etag);
/* The contract's error body; `allow` (may be NULL) for 405. */
enum MHD_Result rd_http_send_error(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   const rd_error *err, const char *allow);
#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
enum MHD_Result
rd_http_send_fail(rd_http *h, struct MHD_Connection *c, struct request *rq, int code,
                  const char *fmt, ...);
enum MHD_Result rd_http_send_not_found(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                       const char *url);
/* The contract's {"error": {"code", "message"}} body as a JSON response (NULL
 * when out of memory), for an error outside core's status table. */
struct MHD_Response *rd_http_error_response(const struct request *rq, const char *code,
                                            const char *message);
/* An error outside the status table of core (401, 403, 400 framing, 409). */
enum MHD_Result rd_http_send_server_error(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                          int status, const char *code, const char *message,
                                          const char *header, const char *value);

/* A chunked body over RD_API_BODY_MAX as it arrives: 413 written on the
 * socket at once, the rest of the body dropped; MHD_NO to close at once. */
enum MHD_Result rd_http_refuse_body_now(rd_http *h, struct request *rq);

/* ---- rd_http_access.c ---- */

/* Refuses (*refused = 1) framing HTTP/1.1 says to refuse. */
enum MHD_Result rd_http_check_framing(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                      const char *version, int *refused);
/* Does the Host header (may be NULL) name a host we serve? */
int rd_http_host_allowed(const rd_http *h, const char *host);
/* Does the request carry our bearer token? */
int rd_http_authorized(const rd_http *h, struct MHD_Connection *c);
int rd_http_is_loopback(const struct sockaddr_storage *addr);
/* The Host allowlist and a copy of the token. */
int rd_http_set_access(rd_http *h, const rd_http_config *cfg, const struct sockaddr_storage *addr,
                       rd_error *err);

/* ---- rd_http_static.c ---- */

/* GET of the web page's files. */
enum MHD_Result rd_http_serve_static(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                     const char *url, const char *method);
/* realpath of a directory option (NULL dir: *out NULL), or an error. */
int rd_http_resolve_dir(const char *option, const char *dir, char **out, rd_error *err);

/* ---- rd_routes.c ---- */

/* First call of a routed API request (method and parameters checked). */
enum MHD_Result rd_routes_begin(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                enum route route, const char *method, const char *arg,
                                const char *url);
/* Appends a chunk of a submission's body. */
void rd_routes_take_body(struct request *rq, const char *data, size_t n);
/* Last call of a submission: parse, queue, maybe wait. */
enum MHD_Result rd_routes_finish_submit(rd_http *h, struct MHD_Connection *c, struct request *rq);
/* A suspended request, resumed: its answer. */
enum MHD_Result rd_routes_answer_waiter(rd_http *h, struct MHD_Connection *c, struct request *rq);

#endif
