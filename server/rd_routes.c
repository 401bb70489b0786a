/*
 * rd_routes — the /api/v1 handlers and /metrics (rd_http_int.h): health,
 * OpenAPI, examples, jobs (list, get and long poll, CSV, DELETE, submit and
 * wait; ETag and 304 on finished ones) and
 * sweeps.  rd_http.c has routed the request and checked method, query
 * parameters, Host and token; the handlers answer (rd_http_reply.c) or
 * suspend the request (rd_http_conn.c): a submission or a job's GET with
 * ?wait, a DELETE of a running job.
 */
#include "rd_http_int.h"

#include <errno.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <jansson.h>

#include "rd_api.h"
#include "rd_openapi_doc.h"

/* How long DELETE waits for a running job to acknowledge the cancellation. */
#define CANCEL_WAIT_S 5.0
/* GET /api/v1/jobs: default and largest ?limit=. */
#define LIST_LIMIT_DEFAULT 50
#define LIST_LIMIT_MAX     1000
/* A submission that waits (?wait) runs on the HTTP thread, with no queue and
 * no worker hand-off, when its predicted cost (rd_scene_cost_predict) is below
 * this: the model is within a factor 2, so such a run holds the thread a few
 * ms at most, about what one large response takes to write. */
#define INLINE_BELOW_S 0.002
/* Longest Idempotency-Key accepted, bytes. */
#define IDEM_KEY_MAX 200

static enum MHD_Result get_health(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    size_t counts[RD_JOB_NSTATUS];
    rd_jobs_get_counts(h->jobs, counts);
    json_t *o = json_pack("{s:s, s:s, s:{s:I, s:I}}", "status", "ok", "version", rd_api_version(),
                          "jobs", "queued", (json_int_t)counts[RD_JOB_QUEUED], "running",
                          (json_int_t)counts[RD_JOB_RUNNING]);
    char *body = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    return rd_http_send_text(h, c, rq, MHD_HTTP_OK, body, RD_HTTP_JSON);
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
    return rd_http_send_text(h, c, rq, MHD_HTTP_OK, text,
                             "text/plain; version=0.0.4; charset=utf-8");
}

/* The embedded template with the scene schemas written by the api from the
 * tables that parse scenes (one schema, no copy to drift). */
static enum MHD_Result get_openapi(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    char *body = rd_api_openapi_json(rd_openapi_json, &err);
    if (!body)
        return rd_http_send_error(h, c, rq, &err, NULL);
    return rd_http_send_text(h, c, rq, MHD_HTTP_OK, body, RD_HTTP_JSON);
}

static enum MHD_Result get_examples(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    if (!h->examples_dir)
        return rd_http_send_text(h, c, rq, MHD_HTTP_OK, strdup("{\"examples\":[]}"), RD_HTTP_JSON);
    char *body = rd_api_examples_json(h->examples_dir, &err);
    if (!body) {
        /* A broken example file is the server's fault, not the client's. */
        if (err.code != RD_ENOMEM)
            err.code = RD_EINTERNAL;
        return rd_http_send_error(h, c, rq, &err, NULL);
    }
    return rd_http_send_text(h, c, rq, MHD_HTTP_OK, body, RD_HTTP_JSON);
}

/* The api decides which names are valid (rd_api_example_scene): unknown
 * 404, malformed 400; only a broken example file is the server's fault. */
static enum MHD_Result get_example(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   const char *name)
{
    rd_error err;
    rd_error_init(&err);
    if (!h->examples_dir)
        return rd_http_send_fail(
            h, c, rq, RD_ENOTFOUND,
            "There are no examples on this server; GET /api/v1/examples lists them.");
    char *body = rd_api_example_scene(h->examples_dir, name, &err);
    if (!body) {
        if (err.code != RD_ENOMEM && err.code != RD_ENOTFOUND && err.code != RD_EREQUEST)
            err.code = RD_EINTERNAL;
        return rd_http_send_error(h, c, rq, &err, NULL);
    }
    return rd_http_send_text(h, c, rq, MHD_HTTP_OK, body, RD_HTTP_JSON);
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
    if (s && !rd_http_parse_count(s, 1, LIST_LIMIT_MAX, &limit))
        return rd_http_send_fail(
            h, c, rq, RD_EREQUEST,
            "The query parameter limit must be a whole number from 1 to %d, not \"%s\".",
            LIST_LIMIT_MAX, rd_http_printable(s, buf, sizeof buf));
    f.limit = (size_t)limit;
    if ((s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "status"))) {
        for (int i = 0; i < RD_JOB_NSTATUS && f.status < 0; i++)
            if (strcmp(s, rd_jobs_status_name(i)) == 0)
                f.status = i;
        if (f.status < 0)
            return rd_http_send_fail(
                h, c, rq, RD_EREQUEST,
                "The query parameter status must be one of queued, running, succeeded, "
                "failed, cancelled, interrupted, not \"%s\".",
                rd_http_printable(s, buf, sizeof buf));
    }
    f.analysis = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "analysis");
    f.name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "name");
    if ((s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "cursor"))) {
        char *end;
        errno = 0;
        unsigned long long v = strtoull(s, &end, 10);
        if (!*s || *end || errno || v == 0 || strspn(s, "0123456789") != strlen(s))
            return rd_http_send_fail(
                h, c, rq, RD_EREQUEST,
                "The query parameter cursor must be the next_cursor of an earlier "
                "page, not \"%s\".",
                rd_http_printable(s, buf, sizeof buf));
        f.before = (uint64_t)v;
    }
    char *body = NULL;
    if (rd_jobs_list(h->jobs, &f, &body, &err) != RD_OK)
        return rd_http_send_error(h, c, rq, &err, NULL);
    return rd_http_send_text(h, c, rq, MHD_HTTP_OK, body, RD_HTTP_JSON);
}

/* The job as it is now: GET (conditional: a finished job carries an ETag
 * of its JSON, and an If-None-Match that names it gets 304 and no body), a
 * resumed long poll, a DELETE's answer (not conditional). */
static enum MHD_Result send_job(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                const char *id, int conditional)
{
    rd_error err;
    rd_error_init(&err);
    char *body = NULL, etag[RD_HTTP_ETAG_LEN] = "";
    rd_jobs_body *shared = NULL;
    int finished = 0;
    if (rd_jobs_get(h->jobs, id, 0, &shared, &body, &finished, &err) != RD_OK)
        return rd_http_send_error(h, c, rq, &err, NULL);
    if (finished && (shared || body))
        rd_http_etag(shared ? shared->data : body, shared ? shared->len : strlen(body), etag);
    if (etag[0] && conditional && rd_http_none_match(c, etag)) {
        rd_jobs_body_release(shared);
        free(body);
        return rd_http_send_not_modified(h, c, rq, etag);
    }
    struct MHD_Response *r = rd_http_job_response(rq, shared, body, 0);
    if (etag[0])
        r = rd_http_with_etag(r, etag);
    return rd_http_send_response(h, c, rq, MHD_HTTP_OK, r);
}

/* GET /api/v1/jobs/{id}/result.csv: a finished job's table (only those have
 * one), to save as ringdyn-<analysis>-<id>.csv; an ETag of the CSV, 304 on
 * a matching If-None-Match. */
static enum MHD_Result get_csv(rd_http *h, struct MHD_Connection *c, struct request *rq,
                               const char *id)
{
    rd_error err;
    rd_error_init(&err);
    char analysis[32] = "", etag[RD_HTTP_ETAG_LEN];
    rd_jobs_body *body = NULL;
    const char *csv = NULL;
    size_t len = 0;
    uint64_t hash[2];
    if (rd_jobs_result_body(h->jobs, id, &body, analysis, &err) != RD_OK)
        return rd_http_send_error(h, c, rq, &err, NULL);
    if (rd_jobs_body_form(body, RD_JOBS_CSV, &csv, &len, hash, &err) != RD_OK) {
        rd_jobs_body_release(body);
        return rd_http_send_error(h, c, rq, &err, NULL);
    }
    rd_http_etag_of_hash(hash, etag);
    if (rd_http_none_match(c, etag)) {
        rd_jobs_body_release(body);
        return rd_http_send_not_modified(h, c, rq, etag);
    }
    struct MHD_Response *r =
        rd_http_body_response(rq, body, csv, len, RD_JOBS_CSV_GZIP, "text/csv; charset=utf-8");
    char disposition[96];
    snprintf(disposition, sizeof disposition, "attachment; filename=\"ringdyn-%s-%s.csv\"",
             analysis, id);
    r = rd_http_with_header(r, "Content-Disposition", disposition);
    return rd_http_send_response(h, c, rq, MHD_HTTP_OK, rd_http_with_etag(r, etag));
}

/* GET/HEAD of a job, with ?wait=S the long poll: a job not yet final
 * suspends the request (no thread held) until it ends or S seconds pass
 * (rd_routes_answer_waiter). */
static enum MHD_Result get_job(rd_http *h, struct MHD_Connection *c, struct request *rq,
                               const char *id)
{
    const char *wait = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "wait");
    double wait_s = 0;
    if (wait && !rd_http_parse_seconds(wait, RD_HTTP_POLL_MAX, &wait_s)) {
        char buf[64];
        return rd_http_send_fail(h, c, rq, RD_EREQUEST,
                                 "The query parameter wait must be a number of seconds from 0 to "
                                 "%d (the long poll's limit; poll again for longer), not \"%s\".",
                                 RD_HTTP_POLL_MAX, rd_http_printable(wait, buf, sizeof buf));
    }
    /* An unknown id counts as final: answered (404) at once. */
    if (wait_s > 0 && !rd_jobs_is_final(h->jobs, id))
        return rd_http_suspend_for(h, c, rq, WAIT_POLL, id, wait_s);
    return send_job(h, c, rq, id, 1);
}

static enum MHD_Result job_route(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                 enum route route, const char *method, const char *id)
{
    if (route == ROUTE_JOB_CSV)
        return get_csv(h, c, rq, id);
    if (strcmp(method, MHD_HTTP_METHOD_DELETE) != 0)
        return get_job(h, c, rq, id);
    /* A final job is deleted (204); a queued or running one is cancelled
     * and answered as it then is, as before. */
    rd_error err;
    rd_error_init(&err);
    int deleted = 0;
    if (rd_jobs_delete(h->jobs, id, &deleted, &err) != RD_OK)
        return rd_http_send_error(h, c, rq, &err, NULL);
    if (deleted)
        return rd_http_send_response(
            h, c, rq, MHD_HTTP_NO_CONTENT,
            MHD_create_response_from_buffer(0, (void *)"", MHD_RESPMEM_PERSISTENT));
    if (!rd_jobs_is_final(h->jobs, id)) /* running: wait for it to stop */
        return rd_http_suspend_for(h, c, rq, WAIT_CANCEL, id, CANCEL_WAIT_S);
    return send_job(h, c, rq, id, 0);
}

/* An rd_sweeps answer as a response, or a suspended wait (status 0). */
static enum MHD_Result sweep_reply(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   rd_sweeps_reply *sr)
{
    if (sr->status == 0) {
        rq->sweep = sr->wait_submit;
        return rd_http_suspend_for(h, c, rq, WAIT_SWEEP, sr->wait_id, sr->wait_s);
    }
    struct MHD_Response *r =
        sr->body ? rd_http_text_response(rq, sr->body, sr->content_type)
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
    return rd_http_send_response(h, c, rq, sr->status, r);
}

/* GET /api/v1/sweeps, and GET/HEAD/DELETE under it. */
static enum MHD_Result sweep_route(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                   enum route route, const char *method, const char *id)
{
    rd_sweeps_reply sr = {0};
    long limit = LIST_LIMIT_DEFAULT;
    const char *s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "limit");
    if (route == ROUTE_SWEEPS && s && !rd_http_parse_count(s, 1, LIST_LIMIT_MAX, &limit)) {
        char buf[32];
        return rd_http_send_fail(
            h, c, rq, RD_EREQUEST,
            "The query parameter limit must be a whole number from 1 to %d, not \"%s\".",
            LIST_LIMIT_MAX, rd_http_printable(s, buf, sizeof buf));
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
    if (!rd_http_is_json_media_type(type))
        return rd_http_send_fail(
            h, c, rq, RD_EMEDIA, "The body must be sent as Content-Type: application/json, not %s.",
            type ? rd_http_printable(type, buf, sizeof buf) : "without a Content-Type");
    const char *wait = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "wait");
    if (wait) {
        if (!rd_http_parse_seconds(wait, RD_HTTP_WAIT_MAX, &rq->wait_s))
            return rd_http_send_fail(
                h, c, rq, RD_EREQUEST,
                "The query parameter wait must be a number of seconds from 0 to %d, "
                "not \"%s\".",
                RD_HTTP_WAIT_MAX, rd_http_printable(wait, buf, sizeof buf));
        rq->has_wait = 1;
    }
    const char *limit = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "time_limit_s");
    if (limit && !rq->sweep &&
        (!rd_http_parse_seconds(limit, h->job_timeout_s, &rq->time_limit_s) ||
         rq->time_limit_s <= 0))
        return rd_http_send_fail(
            h, c, rq, RD_EREQUEST,
            "The query parameter time_limit_s must be a number of seconds above 0 and "
            "at most the server's limit of %g, not \"%s\".",
            h->job_timeout_s, rd_http_printable(limit, buf, sizeof buf));
    const char *key = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Idempotency-Key");
    if (key && !rq->sweep && (!*key || strlen(key) > IDEM_KEY_MAX || rd_http_has_control_char(key)))
        return rd_http_send_fail(
            h, c, rq, RD_EREQUEST,
            "The Idempotency-Key header must be 1 to %d rd_http_printable characters.",
            IDEM_KEY_MAX);
    const char *length =
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_LENGTH);
    if (length) {
        char *end;
        errno = 0;
        unsigned long long n = strtoull(length, &end, 10);
        if (errno == 0 && *end == '\0' && n > RD_API_BODY_MAX)
            return rd_http_send_fail(h, c, rq, RD_ETOOLARGE,
                                     "The body has %llu bytes; the limit is %d bytes.", n,
                                     RD_API_BODY_MAX);
    }
    return MHD_YES;
}

/* Appends a body chunk, up to RD_API_BODY_MAX bytes in all. */
void rd_routes_take_body(struct request *rq, const char *data, size_t n)
{
    if (rq->too_large || rq->no_memory)
        return;
    if (n > RD_API_BODY_MAX - rq->len) {
        rq->too_large = 1;
        rd_http_body_free(rq);
        return;
    }
    if (rd_http_body_reserve(rq, rq->len + n + 1) != 0) {
        rq->no_memory = 1;
        return;
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
        return rd_http_send_error(h, c, rq, &err, NULL);
    struct MHD_Response *r =
        rd_http_job_response(rq, shared, body, rq->cache && strcmp(rq->cache, "hit") == 0);
    char location[64];
    snprintf(location, sizeof location, "/api/v1/jobs/%s", id);
    if (r &&
        (MHD_add_response_header(r, MHD_HTTP_HEADER_LOCATION, location) != MHD_YES ||
         (rq->cache && MHD_add_response_header(r, "X-Ringdyn-Cache", rq->cache) != MHD_YES) ||
         (rq->replayed && MHD_add_response_header(r, "Idempotent-Replayed", "true") != MHD_YES))) {
        MHD_destroy_response(r);
        r = NULL;
    }
    return rd_http_send_response(h, c, rq,
                                 rq->has_wait && finished ? MHD_HTTP_OK : MHD_HTTP_ACCEPTED, r);
}

/* A suspended request, resumed: answer with the job as it is now. */
enum MHD_Result rd_routes_answer_waiter(rd_http *h, struct MHD_Connection *c, struct request *rq)
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
    return send_job(h, c, rq, rq->job_id, kind == WAIT_POLL);
}

/* Last call of POST /api/v1/jobs: parse, queue, maybe wait. */
enum MHD_Result rd_routes_finish_submit(rd_http *h, struct MHD_Connection *c, struct request *rq)
{
    rd_error err;
    rd_error_init(&err);
    if (rq->too_large)
        return rd_http_send_fail(h, c, rq, RD_ETOOLARGE,
                                 "The body is larger than the limit of %d bytes.", RD_API_BODY_MAX);
    if (rq->no_memory)
        return rd_http_send_response(h, c, rq, 0, NULL);
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
    int rc =
        rd_scene_parse_report_as(rq->body ? rq->body : "", rq->len, rq->as, &scene, &err, &errors);
    rd_http_body_free(rq);
    if (rc != RD_OK && err.code != RD_OK && errors)
        return rd_http_send_text(h, c, rq, rd_api_http_status(err.code), errors, RD_HTTP_JSON);
    free(errors);
    if (rc != RD_OK) {
        if (err.code == RD_OK)
            rd_error_set(&err, rc, "", "%s.", rd_error_summary(rc));
        return rd_http_send_error(h, c, rq, &err, NULL);
    }
    opts.use_cache = !no_cache_asked(c);
    opts.time_limit_s = rq->time_limit_s;
    if (rq->has_wait && rq->wait_s > 0)
        opts.inline_below_s = INLINE_BELOW_S;
    rd_jobs_submitted out;
    if (rd_jobs_submit(h->jobs, scene, &opts, &out, &err) != RD_OK) /* takes the scene */
        return rd_http_send_error(h, c, rq, &err, NULL);
    if (out.conflict) {
        char message[256];
        snprintf(message, sizeof message,
                 "The Idempotency-Key was first sent with another body (it made job %s); send that "
                 "body again to get that job, or use a new key for a new scene.",
                 out.id);
        return rd_http_send_server_error(h, c, rq, MHD_HTTP_CONFLICT, "idempotency_conflict",
                                         message, NULL, NULL);
    }
    /* A replay says so (Idempotent-Replayed), not what the cache did. */
    rq->cache = out.replayed ? NULL : out.cached ? "hit" : opts.use_cache ? "miss" : "bypass";
    rq->replayed = out.replayed;
    if (!out.replayed)
        rd_metrics_count_cache(h->metrics, out.cached, !opts.use_cache);
    if (out.ran_inline)
        rd_metrics_count_inline(h->metrics);

    if (rq->has_wait && rq->wait_s > 0 && !rd_jobs_is_final(h->jobs, out.id))
        return rd_http_suspend_for(h, c, rq, WAIT_SUBMIT, out.id, rq->wait_s);
    return answer_submit(h, c, rq, out.id);
}

/* First call of a routed /api/v1 or /metrics request whose method and query
 * parameters are allowed: its answer, or, for a submission, the checks
 * before its body is read.  `arg` is the job id, sweep id or example name
 * of the path. */
enum MHD_Result rd_routes_begin(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                enum route route, const char *method, const char *arg,
                                const char *url)
{
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
    case ROUTE_CALIBRATIONS: /* POST only: a job whose analysis is calibration */
        rq->as = "calibration";
        return begin_submit(h, c, rq);
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
    return rd_http_send_not_found(h, c, rq, url);
}
