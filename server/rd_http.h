/*
 * rd_http — the HTTP face of ringdyn (../shared/API.md): routes, request
 * limits, JSON error bodies and the static web page, on libmicrohttpd.
 *
 * Threading: libmicrohttpd's own epoll event loop on a small pool of
 * threads (limits.threads), so an open connection costs a socket and a
 * few kB, not a thread.  A request that waits for its job (?wait=S on a
 * submission or on GET of a job, or a DELETE of a running job) is suspended (MHD_suspend_connection) and
 * resumed by the timer thread when the job ends or the wait is over, so it
 * blocks no thread.  The timer thread also enforces the request deadline:
 * a connection whose request (header and body) has not arrived complete
 * within limits.request_deadline_s of its start (or of the end of the
 * previous request on the connection) is shut down, so slow-header
 * clients cannot hold connections.  The server parses no scene field:
 * bodies go to rd_scene_parse, results come from rd_jobs, error bodies
 * from rd_api_error_json.
 */
#ifndef RD_HTTP_H
#define RD_HTTP_H

#include "rd_error.h"
#include "rd_jobs.h"
#include "rd_metrics.h"
#include "rd_sweeps.h"

/* Longest ?wait= a client may ask for, seconds. */
#define RD_HTTP_WAIT_MAX 300
/* Longest ?wait= of GET /api/v1/jobs/{id} (the long poll), seconds: below
 * the idle timeouts of common proxies (60 s), so that a poll is answered
 * rather than cut; a client that wants longer polls again. */
#define RD_HTTP_POLL_MAX 60

typedef struct rd_http_limits {
    int threads;               /* event-loop threads, >= 1 */
    int connections_max;       /* open connections in all (more are refused at accept) */
    int per_ip_max;            /* open connections from one client address */
    double request_deadline_s; /* a request's header and body must arrive within this */
    int idle_timeout_s;        /* a connection with no traffic at all is closed after this */
} rd_http_limits;

typedef struct rd_http_config {
    const char *host;         /* numeric IPv4/IPv6 address or name to bind */
    int port;                 /* 0: any free port */
    const char *static_dir;   /* the web page, or NULL to serve none */
    const char *examples_dir; /* example scenes, or NULL for none */
    /* Host-header names served besides the loopback names (127.0.0.1,
     * localhost, [::1]) and the bound address; any port.  May be NULL. */
    const char *const *allow_hosts;
    int n_allow_hosts;
    /* Bearer token every /api/v1/jobs*, /api/v1/sweeps*, /api/v1/examples* and /metrics
     * request must send (Authorization: Bearer TOKEN), or NULL for none.
     * Required when `host` is not a loopback address. */
    const char *token;
    rd_http_limits limits;
    rd_sweeps *sweeps;    /* /api/v1/sweeps*, borrowed; NULL: those routes are 404 */
    double job_timeout_s; /* the job pool's run time limit: the largest ?time_limit_s= */
} rd_http_config;

typedef struct rd_http rd_http;

/* Binds and starts serving.  `jobs` and `metrics` are borrowed and must
 * outlive the server.  On success *out owns it; free with rd_http_free. */
int rd_http_create(const rd_http_config *cfg, rd_jobs *jobs, rd_metrics *metrics, rd_http **out,
                   rd_error *err);

/* The bound address as text (IPv6 in brackets) and the real port. */
const char *rd_http_get_host(const rd_http *http);
int rd_http_get_port(const rd_http *http);

/* Stops accepting new connections; open ones are served on. */
void rd_http_quiesce(rd_http *http);

/* rd_jobs_config.on_final: a job ended, wake the requests waiting for it.
 * `http` is the rd_http (void * for the callback). */
void rd_http_job_ended(void *http);

/* Waits up to `seconds` for the requests in progress to finish sending
 * their answers (idle keep-alive connections do not count), so that
 * requests released by rd_jobs_shutdown still get their response. */
void rd_http_drain(rd_http *http, double seconds);

/* Answers the requests still waiting for a job (as they stand), closes every
 * connection, joins the threads and frees the server.  NULL is a no-op. */
void rd_http_free(rd_http *http);

#endif
