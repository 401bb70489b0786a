/*
 * rd_metrics — counters for GET /metrics (rd_metrics.h).
 *
 * The job-duration histogram uses cumulative buckets as Prometheus expects:
 * bucket[i] counts the runs that took at most bounds[i] seconds; the +Inf
 * bucket equals the total count.
 */
#include "rd_metrics.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define HTTP_STATUS_MIN 100
#define HTTP_STATUS_MAX 599

/* Upper bounds (s) of the job-duration buckets: modal runs take milliseconds,
 * long lift runs minutes, and the default time limit is 120 s. */
static const double duration_bounds[] = {0.01, 0.05, 0.1, 0.25, 0.5, 1,  2.5,
                                         5,    10,   30,  60,   120, 300};
#define NBOUNDS (sizeof duration_bounds / sizeof duration_bounds[0])

/* Upper bounds (s) of the HTTP request-duration buckets: most answers take
 * well under a millisecond; a long poll waits up to 300 s. */
static const double request_bounds[] = {0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1,
                                        0.25,   0.5,   1,      2.5,   5,    10,    30,   300};
#define NREQ_BOUNDS (sizeof request_bounds / sizeof request_bounds[0])

static const char *const route_names[RD_METRICS_NROUTES] = {"/api/v1/jobs",
                                                            "/api/v1/jobs/{id}",
                                                            "/api/v1/jobs/{id}/result.csv",
                                                            "/api/v1/sweeps",
                                                            "/api/v1/sweeps/{id}",
                                                            "/api/v1/sweeps/{id}/table.csv",
                                                            "/api/v1/calibrations",
                                                            "/api/v1/examples",
                                                            "/api/v1/examples/{name}",
                                                            "/api/v1/health",
                                                            "/api/v1/openapi.json",
                                                            "/metrics",
                                                            "static",
                                                            "other"};

/* The methods counted by name; anything else is "other" (the last). */
static const char *const method_names[] = {"GET",    "HEAD",  "POST",    "PUT",
                                           "DELETE", "PATCH", "OPTIONS", "other"};
#define NMETHODS (sizeof method_names / sizeof method_names[0])
#define NSTATUS  (HTTP_STATUS_MAX - HTTP_STATUS_MIN + 1)

/* Series of the labelled run histogram: (analysis, outcome) pairs are few
 * (the registry's analyses x four final states); beyond this many, runs are
 * counted under analysis="other". */
#define MAX_SERIES 48

struct series {
    char analysis[32];
    char outcome[16];
    uint64_t buckets[NBOUNDS]; /* cumulative */
    uint64_t count;
    double sum;
};

enum { CACHE_HIT, CACHE_MISS, CACHE_BYPASS, CACHE_NKINDS };
static const char *const cache_names[CACHE_NKINDS] = {"hit", "miss", "bypass"};

/* One route's request counts and durations. */
struct route_stats {
    uint64_t count[NMETHODS][NSTATUS];
    uint64_t buckets[NREQ_BOUNDS]; /* cumulative */
    uint64_t total;
    double sum;
};

struct rd_metrics {
    pthread_mutex_t mu;
    struct route_stats http[RD_METRICS_NROUTES];
    uint64_t duration_buckets[NBOUNDS]; /* cumulative: runs <= bound */
    uint64_t duration_count;
    double duration_sum;
    struct series series[MAX_SERIES];
    size_t nseries;
    uint64_t cache[CACHE_NKINDS];
    uint64_t inline_runs;
};

rd_metrics *rd_metrics_create(void)
{
    rd_metrics *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    if (pthread_mutex_init(&m->mu, NULL) != 0) {
        free(m);
        return NULL;
    }
    return m;
}

void rd_metrics_free(rd_metrics *m)
{
    if (!m)
        return;
    pthread_mutex_destroy(&m->mu);
    free(m);
}

const char *rd_metrics_route_name(rd_metrics_route route)
{
    return (unsigned)route < RD_METRICS_NROUTES ? route_names[route] : "other";
}

static size_t method_index(const char *method)
{
    for (size_t i = 0; method && i + 1 < NMETHODS; i++)
        if (strcmp(method, method_names[i]) == 0)
            return i;
    return NMETHODS - 1;
}

void rd_metrics_count_http(rd_metrics *m, rd_metrics_route route, const char *method, int status,
                           double seconds)
{
    if (!m || status < HTTP_STATUS_MIN || status > HTTP_STATUS_MAX)
        return;
    if ((unsigned)route >= RD_METRICS_NROUTES)
        route = RD_METRICS_ROUTE_OTHER;
    if (!(seconds >= 0)) /* also NaN: a clock that went wrong counts as instant */
        seconds = 0;
    size_t k = method_index(method);
    pthread_mutex_lock(&m->mu);
    struct route_stats *r = &m->http[route];
    r->count[k][status - HTTP_STATUS_MIN]++;
    for (size_t i = 0; i < NREQ_BOUNDS; i++)
        if (seconds <= request_bounds[i])
            r->buckets[i]++;
    r->total++;
    r->sum += seconds;
    pthread_mutex_unlock(&m->mu);
}

/* The series of (analysis, outcome), made on first use (mu held). */
static struct series *series_locked(rd_metrics *m, const char *analysis, const char *outcome)
{
    if (m->nseries == MAX_SERIES)
        analysis = "other";
    for (size_t i = 0; i < m->nseries; i++)
        if (strcmp(m->series[i].analysis, analysis) == 0 &&
            strcmp(m->series[i].outcome, outcome) == 0)
            return &m->series[i];
    if (m->nseries == MAX_SERIES) /* "other" with a new outcome: fold into the last */
        return &m->series[MAX_SERIES - 1];
    struct series *s = &m->series[m->nseries++];
    snprintf(s->analysis, sizeof s->analysis, "%s", analysis);
    snprintf(s->outcome, sizeof s->outcome, "%s", outcome);
    return s;
}

void rd_metrics_count_cache(rd_metrics *m, int hit, int bypass)
{
    if (!m)
        return;
    pthread_mutex_lock(&m->mu);
    m->cache[bypass ? CACHE_BYPASS : hit ? CACHE_HIT : CACHE_MISS]++;
    pthread_mutex_unlock(&m->mu);
}

void rd_metrics_count_inline(rd_metrics *m)
{
    if (!m)
        return;
    pthread_mutex_lock(&m->mu);
    m->inline_runs++;
    pthread_mutex_unlock(&m->mu);
}

void rd_metrics_observe_job(rd_metrics *m, const char *analysis, const char *outcome,
                            double seconds)
{
    if (!m || !(seconds >= 0)) /* also rejects NaN */
        return;
    pthread_mutex_lock(&m->mu);
    struct series *se = series_locked(m, analysis, outcome);
    for (size_t i = 0; i < NBOUNDS; i++)
        if (seconds <= duration_bounds[i])
            se->buckets[i]++;
    se->count++;
    se->sum += seconds;
    for (size_t i = 0; i < NBOUNDS; i++)
        if (seconds <= duration_bounds[i])
            m->duration_buckets[i]++;
    m->duration_count++;
    m->duration_sum += seconds;
    pthread_mutex_unlock(&m->mu);
}

/* A growing text buffer; `failed` sticks after the first allocation failure
 * so the caller checks once at the end. */
struct text {
    char *s;
    size_t len, cap;
    int failed;
};

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void
text_printf(struct text *t, const char *fmt, ...)
{
    if (t->failed)
        return;
    for (;;) {
        size_t room = t->cap - t->len;
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(t->s ? t->s + t->len : NULL, room, fmt, ap);
        va_end(ap);
        if (n < 0) {
            t->failed = 1;
            return;
        }
        if ((size_t)n < room) {
            t->len += (size_t)n;
            return;
        }
        size_t cap = t->cap ? t->cap : 1024;
        while (cap - t->len <= (size_t)n)
            cap *= 2;
        char *s = realloc(t->s, cap);
        if (!s) {
            t->failed = 1;
            return;
        }
        t->s = s;
        t->cap = cap;
    }
}

/* The gauges: build info, stop latency, connections, jobs by state. */
static void render_gauges(struct text *t, const char *const *state_names,
                          const size_t *state_counts, size_t n, const rd_metrics_gauges *g)
{
    text_printf(t,
                "# HELP ringdyn_build_info The server's version (the value is always 1).\n"
                "# TYPE ringdyn_build_info gauge\n"
                "ringdyn_build_info{version=\"%s\"} 1\n",
                g->version ? g->version : "unknown");
    text_printf(t,
                "# HELP ringdyn_stop_latency_seconds Time from a DELETE, the time limit or a "
                "shutdown to the solver's return: the last run stopped, and the largest.\n"
                "# TYPE ringdyn_stop_latency_seconds gauge\n"
                "ringdyn_stop_latency_seconds{which=\"last\"} %.6f\n"
                "ringdyn_stop_latency_seconds{which=\"max\"} %.6f\n",
                g->stop_last_s, g->stop_max_s);
    text_printf(t,
                "# HELP ringdyn_connections Open HTTP connections.\n"
                "# TYPE ringdyn_connections gauge\n"
                "ringdyn_connections %zu\n",
                g->connections);
    text_printf(t,
                "# HELP ringdyn_connections_deadline_total Connections closed because their "
                "request did not arrive complete within the request deadline.\n"
                "# TYPE ringdyn_connections_deadline_total counter\n"
                "ringdyn_connections_deadline_total %zu\n",
                g->deadline_closed);
    text_printf(t, "# HELP ringdyn_jobs Jobs held by the server, by state.\n"
                   "# TYPE ringdyn_jobs gauge\n");
    for (size_t i = 0; i < n; i++)
        text_printf(t, "ringdyn_jobs{state=\"%s\"} %zu\n", state_names[i], state_counts[i]);
}

/* The run-time histograms, unlabelled and by analysis and outcome (mu held). */
static void render_durations(struct text *t, const rd_metrics *m)
{
    text_printf(
        t, "# HELP ringdyn_job_duration_seconds Run time of finished jobs, from start to end.\n"
           "# TYPE ringdyn_job_duration_seconds histogram\n");
    for (size_t i = 0; i < NBOUNDS; i++)
        text_printf(t, "ringdyn_job_duration_seconds_bucket{le=\"%g\"} %llu\n", duration_bounds[i],
                    (unsigned long long)m->duration_buckets[i]);
    text_printf(t, "ringdyn_job_duration_seconds_bucket{le=\"+Inf\"} %llu\n",
                (unsigned long long)m->duration_count);
    text_printf(t, "ringdyn_job_duration_seconds_sum %.9g\n", m->duration_sum);
    text_printf(t, "ringdyn_job_duration_seconds_count %llu\n",
                (unsigned long long)m->duration_count);

    text_printf(t, "# HELP ringdyn_job_run_seconds Run time of the jobs that ran, by analysis "
                   "and outcome (counted when they end; kept however jobs are evicted).\n"
                   "# TYPE ringdyn_job_run_seconds histogram\n");
    for (size_t k = 0; k < m->nseries; k++) {
        const struct series *se = &m->series[k];
        for (size_t i = 0; i < NBOUNDS; i++)
            text_printf(
                t,
                "ringdyn_job_run_seconds_bucket{analysis=\"%s\",outcome=\"%s\",le=\"%g\"} %llu\n",
                se->analysis, se->outcome, duration_bounds[i], (unsigned long long)se->buckets[i]);
        text_printf(
            t, "ringdyn_job_run_seconds_bucket{analysis=\"%s\",outcome=\"%s\",le=\"+Inf\"} %llu\n",
            se->analysis, se->outcome, (unsigned long long)se->count);
        text_printf(t, "ringdyn_job_run_seconds_sum{analysis=\"%s\",outcome=\"%s\"} %.9g\n",
                    se->analysis, se->outcome, se->sum);
        text_printf(t, "ringdyn_job_run_seconds_count{analysis=\"%s\",outcome=\"%s\"} %llu\n",
                    se->analysis, se->outcome, (unsigned long long)se->count);
    }
}

/* The counters: jobs, cache, inline runs (mu held). */
static void render_counters(struct text *t, const rd_metrics *m)
{
    text_printf(t, "# HELP ringdyn_jobs_total Jobs that ran, by analysis and outcome.\n"
                   "# TYPE ringdyn_jobs_total counter\n");
    for (size_t k = 0; k < m->nseries; k++)
        text_printf(t, "ringdyn_jobs_total{analysis=\"%s\",outcome=\"%s\"} %llu\n",
                    m->series[k].analysis, m->series[k].outcome,
                    (unsigned long long)m->series[k].count);
    text_printf(t, "# HELP ringdyn_result_cache_total Job submissions by what the result cache "
                   "did: answered (hit), missed, or was told not to look (bypass).\n"
                   "# TYPE ringdyn_result_cache_total counter\n");
    for (int k = 0; k < CACHE_NKINDS; k++)
        text_printf(t, "ringdyn_result_cache_total{result=\"%s\"} %llu\n", cache_names[k],
                    (unsigned long long)m->cache[k]);
    text_printf(t,
                "# HELP ringdyn_inline_runs_total Jobs run on the HTTP thread (predicted small, "
                "client waiting).\n"
                "# TYPE ringdyn_inline_runs_total counter\n"
                "ringdyn_inline_runs_total %llu\n",
                (unsigned long long)m->inline_runs);
}

/* HTTP responses by route, method and status, and their durations by
 * route; only the label sets seen so far (mu held). */
static void render_http(struct text *t, const rd_metrics *m)
{
    text_printf(t, "# HELP ringdyn_http_requests_total HTTP responses sent, by route template, "
                   "method and status code.\n"
                   "# TYPE ringdyn_http_requests_total counter\n");
    for (size_t r = 0; r < RD_METRICS_NROUTES; r++)
        for (size_t k = 0; m->http[r].total && k < NMETHODS; k++)
            for (int s = 0; s < (int)NSTATUS; s++)
                if (m->http[r].count[k][s])
                    text_printf(t,
                                "ringdyn_http_requests_total{route=\"%s\",method=\"%s\","
                                "status=\"%d\"} %llu\n",
                                route_names[r], method_names[k], s + HTTP_STATUS_MIN,
                                (unsigned long long)m->http[r].count[k][s]);
    text_printf(t, "# HELP ringdyn_http_request_duration_seconds Time from a request's arrival "
                   "to its response, by route template (a long poll's wait included).\n"
                   "# TYPE ringdyn_http_request_duration_seconds histogram\n");
    for (size_t r = 0; r < RD_METRICS_NROUTES; r++) {
        const struct route_stats *rs = &m->http[r];
        if (!rs->total)
            continue;
        for (size_t i = 0; i < NREQ_BOUNDS; i++)
            text_printf(t,
                        "ringdyn_http_request_duration_seconds_bucket{route=\"%s\",le=\"%g\"} "
                        "%llu\n",
                        route_names[r], request_bounds[i], (unsigned long long)rs->buckets[i]);
        text_printf(t,
                    "ringdyn_http_request_duration_seconds_bucket{route=\"%s\",le=\"+Inf\"} "
                    "%llu\n",
                    route_names[r], (unsigned long long)rs->total);
        text_printf(t, "ringdyn_http_request_duration_seconds_sum{route=\"%s\"} %.9g\n",
                    route_names[r], rs->sum);
        text_printf(t, "ringdyn_http_request_duration_seconds_count{route=\"%s\"} %llu\n",
                    route_names[r], (unsigned long long)rs->total);
    }
}

char *rd_metrics_render(rd_metrics *m, const char *const *state_names, const size_t *state_counts,
                        size_t n, const rd_metrics_gauges *g)
{
    struct text t = {0};
    render_gauges(&t, state_names, state_counts, n, g);
    pthread_mutex_lock(&m->mu);
    render_durations(&t, m);
    render_counters(&t, m);
    render_http(&t, m);
    pthread_mutex_unlock(&m->mu);

    if (t.failed) {
        free(t.s);
        return NULL;
    }
    return t.s;
}
