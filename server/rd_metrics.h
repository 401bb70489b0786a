/*
 * rd_metrics — the server's counters, rendered in the Prometheus text format
 * (version 0.0.4) for GET /metrics.
 *
 * Thread-safe: every function may be called from any thread.  The registry
 * holds only numbers; gauges that live elsewhere (jobs by state) are passed
 * to rd_metrics_render by the caller.
 */
#ifndef RD_METRICS_H
#define RD_METRICS_H

#include <stddef.h>

typedef struct rd_metrics rd_metrics;

/* A new, zeroed registry, or NULL when out of memory.  Free with
 * rd_metrics_free (NULL is a no-op). */
rd_metrics *rd_metrics_create(void);
void rd_metrics_free(rd_metrics *m);

/* The route templates HTTP requests are counted by: a fixed set, never the
 * raw URL, so the label's values are bounded.  RD_METRICS_ROUTE_OTHER holds
 * whatever matches no route (and the page's files that do not exist). */
typedef enum rd_metrics_route {
    RD_METRICS_ROUTE_JOBS,         /* /api/v1/jobs */
    RD_METRICS_ROUTE_JOB,          /* /api/v1/jobs/{id} */
    RD_METRICS_ROUTE_JOB_CSV,      /* /api/v1/jobs/{id}/result.csv */
    RD_METRICS_ROUTE_SWEEPS,       /* /api/v1/sweeps */
    RD_METRICS_ROUTE_SWEEP,        /* /api/v1/sweeps/{id} */
    RD_METRICS_ROUTE_SWEEP_CSV,    /* /api/v1/sweeps/{id}/table.csv */
    RD_METRICS_ROUTE_CALIBRATIONS, /* /api/v1/calibrations */
    RD_METRICS_ROUTE_EXAMPLES,     /* /api/v1/examples */
    RD_METRICS_ROUTE_EXAMPLE,      /* /api/v1/examples/{name} */
    RD_METRICS_ROUTE_HEALTH,       /* /api/v1/health */
    RD_METRICS_ROUTE_OPENAPI,      /* /api/v1/openapi.json */
    RD_METRICS_ROUTE_METRICS,      /* /metrics */
    RD_METRICS_ROUTE_STATIC,       /* the web page: /, /static/..., /docs */
    RD_METRICS_ROUTE_OTHER,
    RD_METRICS_NROUTES
} rd_metrics_route;

/* The label value of `route` ("/api/v1/jobs/{id}", "static", "other"). */
const char *rd_metrics_route_name(rd_metrics_route route);

/* Counts one HTTP response: its route, request method (GET, HEAD, POST,
 * PUT, DELETE, PATCH, OPTIONS; any other counts as "other"), status
 * (100..599; others are ignored) and the seconds from the request's
 * arrival to its response being queued (a long poll's wait included). */
void rd_metrics_count_http(rd_metrics *m, rd_metrics_route route, const char *method, int status,
                           double seconds);

/* Records the run time (start to finish, seconds) of a job that ran, with
 * its analysis and outcome (final status name): the unlabelled histogram
 * and the labelled ones, which only ever grow (they survive eviction). */
void rd_metrics_observe_job(rd_metrics *m, const char *analysis, const char *outcome,
                            double seconds);

/* Counts one submission by what the result cache did. */
void rd_metrics_count_cache(rd_metrics *m, int hit, int bypass);

/* Counts one job run inline on the HTTP thread. */
void rd_metrics_count_inline(rd_metrics *m);

/* Gauges that live elsewhere, passed in by the caller at render time. */
typedef struct rd_metrics_gauges {
    double stop_last_s, stop_max_s; /* rd_jobs_get_stop_latency */
    size_t connections;             /* open HTTP connections */
    size_t deadline_closed;         /* connections closed by the request deadline */
    const char *version;            /* for ringdyn_build_info */
} rd_metrics_gauges;

/* The exposition text: ringdyn_jobs{state} from the caller's `n` state names
 * and counts, the gauges `g`, ringdyn_job_duration_seconds (histogram),
 * ringdyn_http_requests_total{route,method,status} and
 * ringdyn_http_request_duration_seconds{route} (histogram).  malloc'd,
 * caller frees; NULL when out of memory.  Also ringdyn_build_info{version},
 * ringdyn_job_run_seconds and ringdyn_jobs_total{analysis,outcome},
 * ringdyn_result_cache_total{result}, ringdyn_inline_runs_total. */
char *rd_metrics_render(rd_metrics *m, const char *const *state_names, const size_t *state_counts,
                        size_t n, const rd_metrics_gauges *g);

#endif
