/*
 * test_jobs.c — the job pool (server/rd_jobs.h) on its own, without HTTP:
 * a real rd_store (SQLite) in a temporary directory and real scenes, a
 * modal run of a few milliseconds (FAST) and a lift run of seconds (SLOW,
 * 50 cycles; only ever stopped here).  Each case starts a pool on a fresh
 * store, and a "restart" is a second pool on the same directory.
 *
 * Cases: a run to success; cancel during a run (DELETE); a queue that is
 * full (RD_EBUSY, then room again once a queued job is cancelled);
 * Idempotency-Key replay and conflict, also after a restart; eviction of
 * the oldest finished jobs under keep_max (an eighth below it once passed),
 * in memory and in the store; and jobs left queued or running, by a
 * shutdown or by a process that died, `interrupted` after a restart.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <jansson.h>

#include "check.h"
#include "rd_clock.h"
#include "rd_jobs.h"
#include "rd_store.h"

static const char FAST[] = "{\"analysis\":\"modal\",\"discretization\":{\"segments\":12}}";
static const char SLOW[] =
    "{\"analysis\":\"lift\",\"engine\":{\"cycles\":50},\"discretization\":{\"segments\":20},"
    "\"numerics\":{\"model\":\"full\",\"error_estimate\":false}}";
/* Longest a test waits for a state it expects (the runs take far less). */
#define WAIT_S 60.0

/* ---- the fixture: a temporary store and a pool on it ---- */

static char dir[64];

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/rd_test_jobs.XXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        exit(2);
    }
}

static void remove_dir(void)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[512];
    while (d && (e = readdir(d)))
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            unlink(path);
        }
    if (d)
        closedir(d);
    rmdir(dir);
}

struct pool {
    rd_store *store;
    rd_jobs *jobs;
};

static rd_jobs_config config(int threads, int queue_max, int keep_max)
{
    rd_jobs_config c = {.threads = threads,
                        .queue_max = queue_max,
                        .keep_max = keep_max,
                        .keep_bytes = (size_t)64 << 20,
                        .keep_age_s = 0,
                        .timeout_s = 120};
    return c;
}

/* A pool on the store in `dir`; exits on failure (nothing else can run). */
static void start(struct pool *p, rd_jobs_config c)
{
    rd_error err;
    rd_error_init(&err);
    memset(p, 0, sizeof *p);
    if (rd_store_create(dir, &p->store, &err) != RD_OK) {
        fprintf(stderr, "rd_store_create: %s\n", err.message);
        exit(2);
    }
    c.store = p->store;
    if (rd_jobs_create(&c, &p->jobs, &err) != RD_OK) {
        fprintf(stderr, "rd_jobs_create: %s\n", err.message);
        exit(2);
    }
}

/* Shutdown that gives running jobs `wait_s` to stop, then frees all. */
static void stop(struct pool *p, double wait_s)
{
    rd_jobs_shutdown(p->jobs, wait_s);
    rd_jobs_free(p->jobs);
    rd_store_free(p->store);
    memset(p, 0, sizeof *p);
}

static rd_scene *scene(const char *text)
{
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    if (rd_scene_parse(text, strlen(text), &s, &err) != RD_OK) {
        fprintf(stderr, "rd_scene_parse: %s\n", err.message);
        exit(2);
    }
    return s;
}

/* rd_jobs_submit of `text`; the id into `id` (RD_JOBS_ID_LEN + 1 bytes). */
static int submit(rd_jobs *jobs, const char *text, const rd_jobs_submit_opts *o, char *id,
                  rd_jobs_submitted *out, rd_error *err)
{
    rd_jobs_submit_opts none = {0};
    rd_jobs_submitted got;
    if (!out)
        out = &got;
    rd_error_init(err);
    int rc = rd_jobs_submit(jobs, scene(text), o ? o : &none, out, err);
    if (id)
        memcpy(id, out->id, RD_JOBS_ID_LEN + 1);
    return rc;
}

/* ---- reading jobs ---- */

/* What a test reads of a job's JSON. */
struct seen {
    int found;         /* RD_OK from rd_jobs_get */
    char status[16];   /* "queued", ... */
    char code[32];     /* error.code, or "" */
    char message[512]; /* error.message, or "" */
    double progress;   /* 0..1 */
    int has_result;    /* a `result` member */
};

/* The job as rd_jobs_get answers it after waiting up to `wait_s`. */
static struct seen get(rd_jobs *jobs, const char *id, double wait_s)
{
    struct seen s;
    memset(&s, 0, sizeof s);
    rd_jobs_body *body = NULL;
    char *json = NULL;
    rd_error err;
    rd_error_init(&err);
    s.found = rd_jobs_get(jobs, id, wait_s, &body, &json, NULL, &err) == RD_OK;
    if (!s.found)
        return s;
    json_t *o = body ? json_loadb(body->data, body->len, 0, NULL) : json_loads(json, 0, NULL);
    const char *status = json_string_value(json_object_get(o, "status"));
    json_t *e = json_object_get(o, "error");
    snprintf(s.status, sizeof s.status, "%s", status ? status : "?");
    snprintf(s.code, sizeof s.code, "%s", e ? json_string_value(json_object_get(e, "code")) : "");
    snprintf(s.message, sizeof s.message, "%s",
             e ? json_string_value(json_object_get(e, "message")) : "");
    s.progress = json_number_value(json_object_get(o, "progress"));
    s.has_result = json_object_get(o, "result") != NULL;
    json_decref(o);
    rd_jobs_body_release(body);
    free(json);
    return s;
}

/* Polls until job `id` has `status` (and, running, some progress: the
 * solver has reported, so it is inside the run); 1 when it did. */
static int wait_for(rd_jobs *jobs, const char *id, const char *status)
{
    double until = rd_clock_mono_s() + WAIT_S;
    while (rd_clock_mono_s() < until) {
        struct seen s = get(jobs, id, 0);
        if (s.found && strcmp(s.status, status) == 0 &&
            (strcmp(status, "running") != 0 || s.progress > 0))
            return 1;
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    }
    return 0;
}

static size_t count(rd_jobs *jobs, int status)
{
    size_t counts[RD_JOB_NSTATUS];
    rd_jobs_get_counts(jobs, counts);
    return counts[status];
}

/* ---- the cases ---- */

static void test_success(void)
{
    struct pool p;
    start(&p, config(1, 4, 16));
    char id[RD_JOBS_ID_LEN + 1];
    rd_error err;
    CHECK(submit(p.jobs, FAST, NULL, id, NULL, &err) == RD_OK, "submit: %s", err.message);
    struct seen s = get(p.jobs, id, WAIT_S);
    CHECK(strcmp(s.status, "succeeded") == 0, "a modal job succeeds, not %s", s.status);
    CHECK(s.has_result && s.progress == 1, "with its result and progress 1");
    CHECK(count(p.jobs, RD_JOB_SUCCEEDED) == 1, "counted succeeded");
    stop(&p, 5);
}

static void test_cancel_running(void)
{
    struct pool p;
    start(&p, config(1, 4, 16));
    char id[RD_JOBS_ID_LEN + 1];
    rd_error err;
    CHECK(submit(p.jobs, SLOW, NULL, id, NULL, &err) == RD_OK, "submit: %s", err.message);
    CHECK(wait_for(p.jobs, id, "running"), "the lift job runs");
    CHECK(count(p.jobs, RD_JOB_RUNNING) == 1, "one job running");

    rd_jobs_body *body = NULL;
    char *json = NULL;
    double t0 = rd_clock_mono_s();
    CHECK(rd_jobs_cancel(p.jobs, id, &body, &json, &err) == RD_OK, "cancel: %s", err.message);
    double waited = rd_clock_mono_s() - t0;
    rd_jobs_body_release(body);
    free(json);
    struct seen s = get(p.jobs, id, 0);
    CHECK(strcmp(s.status, "cancelled") == 0, "cancelled during its run, not %s (after %.2f s)",
          s.status, waited);
    CHECK(strcmp(s.code, "cancelled") == 0, "error code cancelled, not '%s'", s.code);
    CHECK(strstr(s.message, "DELETE") != NULL, "the message names the DELETE: %s", s.message);
    CHECK(count(p.jobs, RD_JOB_RUNNING) == 0 && count(p.jobs, RD_JOB_CANCELLED) == 1,
          "counts: none running, one cancelled");
    double last = 0, max = 0;
    rd_jobs_get_stop_latency(p.jobs, &last, &max);
    CHECK(last > 0 && last < 5 && max >= last, "stop latency measured: %g s (max %g)", last, max);

    /* cancelling a final job changes nothing */
    CHECK(rd_jobs_request_cancel(p.jobs, id, &err) == RD_OK, "cancel again");
    s = get(p.jobs, id, 0);
    CHECK(strcmp(s.status, "cancelled") == 0, "still cancelled, not %s", s.status);
    CHECK(rd_jobs_request_cancel(p.jobs, "0123456789abcdef", &err) == RD_ENOTFOUND,
          "an unknown id is RD_ENOTFOUND");
    stop(&p, 5);
}

static void test_queue_full(void)
{
    struct pool p;
    start(&p, config(1, 1, 16));
    char a[RD_JOBS_ID_LEN + 1], b[RD_JOBS_ID_LEN + 1], c[RD_JOBS_ID_LEN + 1];
    rd_error err;
    CHECK(submit(p.jobs, SLOW, NULL, a, NULL, &err) == RD_OK, "submit A: %s", err.message);
    CHECK(wait_for(p.jobs, a, "running"), "A runs on the only worker");
    CHECK(submit(p.jobs, SLOW, NULL, b, NULL, &err) == RD_OK, "B queues: %s", err.message);
    CHECK(strcmp(get(p.jobs, b, 0).status, "queued") == 0, "B is queued");

    int rc = submit(p.jobs, FAST, NULL, NULL, NULL, &err);
    CHECK(rc == RD_EBUSY && err.code == RD_EBUSY, "C with the queue full: RD_EBUSY, not %d", rc);
    CHECK(strstr(err.message, "queue is full") != NULL, "the message says why: %s", err.message);
    int retry = rd_jobs_get_retry_after(p.jobs);
    CHECK(retry >= 1 && retry <= 300, "Retry-After %d in 1..300", retry);
    CHECK(count(p.jobs, RD_JOB_QUEUED) == 1, "C was not queued");

    /* a queued job cancelled ends at once and frees its place */
    CHECK(rd_jobs_request_cancel(p.jobs, b, &err) == RD_OK, "cancel B");
    struct seen s = get(p.jobs, b, 0);
    CHECK(strcmp(s.status, "cancelled") == 0, "queued B cancelled at once, not %s", s.status);
    CHECK(submit(p.jobs, FAST, NULL, c, NULL, &err) == RD_OK, "C queues now: %s", err.message);
    CHECK(strcmp(get(p.jobs, c, 0).status, "queued") == 0, "C waits behind A");
    CHECK(rd_jobs_request_cancel(p.jobs, a, &err) == RD_OK, "cancel A");
    s = get(p.jobs, c, WAIT_S);
    CHECK(strcmp(s.status, "succeeded") == 0, "C runs once A stopped: %s", s.status);
    CHECK(strcmp(get(p.jobs, a, 0).status, "cancelled") == 0, "A cancelled");
    stop(&p, 5);
}

static void test_idempotency(void)
{
    static const char other[] = "{\"analysis\":\"modal\",\"discretization\":{\"segments\":13}}";
    struct pool p;
    start(&p, config(1, 4, 16));
    rd_jobs_submit_opts o = {0};
    o.idem_key = "order-1";
    rd_jobs_hash(FAST, strlen(FAST), o.idem_hash);
    char first[RD_JOBS_ID_LEN + 1];
    rd_jobs_submitted out;
    rd_error err;
    CHECK(submit(p.jobs, FAST, &o, first, &out, &err) == RD_OK, "first: %s", err.message);
    CHECK(!out.replayed && !out.conflict && !out.cached, "the first is a new job");
    CHECK(strcmp(get(p.jobs, first, WAIT_S).status, "succeeded") == 0, "it succeeds");

    CHECK(submit(p.jobs, FAST, &o, NULL, &out, &err) == RD_OK, "again: %s", err.message);
    CHECK(out.replayed && !out.conflict && strcmp(out.id, first) == 0,
          "same key, same body: a replay of %s (replayed %d, id %s)", first, out.replayed, out.id);

    rd_jobs_submit_opts o2 = o;
    rd_jobs_hash(other, strlen(other), o2.idem_hash);
    CHECK(submit(p.jobs, other, &o2, NULL, &out, &err) == RD_OK, "other body: %s", err.message);
    CHECK(out.conflict && !out.replayed && strcmp(out.id, first) == 0,
          "same key, another body: a conflict naming %s (conflict %d, id %s)", first, out.conflict,
          out.id);

    rd_jobs_submit_opts o3 = o2;
    o3.idem_key = "order-2";
    CHECK(submit(p.jobs, other, &o3, NULL, &out, &err) == RD_OK, "new key: %s", err.message);
    CHECK(!out.conflict && !out.replayed && strcmp(out.id, first) != 0, "a new key: a new job");
    CHECK(strcmp(get(p.jobs, out.id, WAIT_S).status, "succeeded") == 0, "it succeeds");
    size_t jobs_before = count(p.jobs, RD_JOB_SUCCEEDED);
    CHECK(jobs_before == 2, "two jobs, not %zu", jobs_before);
    stop(&p, 5);

    /* the key is in the store: after a restart it still answers */
    start(&p, config(1, 4, 16));
    CHECK(submit(p.jobs, FAST, &o, NULL, &out, &err) == RD_OK, "after restart: %s", err.message);
    CHECK(out.replayed && strcmp(out.id, first) == 0, "replayed after a restart");
    CHECK(submit(p.jobs, other, &o2, NULL, &out, &err) == RD_OK, "conflict: %s", err.message);
    CHECK(out.conflict && strcmp(out.id, first) == 0, "a conflict after a restart");
    CHECK(count(p.jobs, RD_JOB_SUCCEEDED) == 2 && count(p.jobs, RD_JOB_QUEUED) == 0,
          "nothing new was submitted");
    stop(&p, 5);
}

/* Job i of the eviction case: a distinct scene each (no cache answers). */
static void eviction_scene(int i, char *buf, size_t n)
{
    snprintf(buf, n, "{\"analysis\":\"modal\",\"discretization\":{\"segments\":%d}}", 8 + i);
}

static void test_eviction(void)
{
    enum { KEEP = 8, RUNS = KEEP + 1 };
    struct pool p;
    start(&p, config(1, 4, KEEP));
    char ids[RUNS][RD_JOBS_ID_LEN + 1];
    char text[128];
    rd_error err;
    for (int i = 0; i < RUNS; i++) {
        eviction_scene(i, text, sizeof text);
        CHECK(submit(p.jobs, text, NULL, ids[i], NULL, &err) == RD_OK, "submit %d", i);
        CHECK(strcmp(get(p.jobs, ids[i], WAIT_S).status, "succeeded") == 0, "job %d", i);
        if (i < KEEP)
            CHECK(count(p.jobs, RD_JOB_SUCCEEDED) == (size_t)i + 1, "%d kept", i + 1);
    }
    /* one over keep_max: trimmed to an eighth below it, the oldest first */
    CHECK(count(p.jobs, RD_JOB_SUCCEEDED) == KEEP - KEEP / 8, "%zu kept, want %d",
          count(p.jobs, RD_JOB_SUCCEEDED), KEEP - KEEP / 8);
    for (int i = 0; i < RUNS; i++) {
        int gone = i < RUNS - (KEEP - KEEP / 8);
        CHECK(get(p.jobs, ids[i], 0).found == !gone, "job %d %s", i, gone ? "evicted" : "kept");
    }
    rd_jobs_body *body = NULL;
    char *json = NULL;
    CHECK(rd_jobs_get(p.jobs, ids[0], 0, &body, &json, NULL, &err) == RD_ENOTFOUND &&
              strstr(err.message, "most recent") != NULL,
          "an evicted job is RD_ENOTFOUND: %s", err.message);
    stop(&p, 5);

    /* the store evicted them too */
    start(&p, config(1, 4, KEEP));
    CHECK(count(p.jobs, RD_JOB_SUCCEEDED) == KEEP - KEEP / 8, "after a restart: %zu",
          count(p.jobs, RD_JOB_SUCCEEDED));
    CHECK(!get(p.jobs, ids[0], 0).found && get(p.jobs, ids[RUNS - 1], 0).found,
          "the same jobs after a restart");
    CHECK(get(p.jobs, ids[RUNS - 1], 0).has_result, "with their results");
    stop(&p, 5);
}

/* Jobs the shutdown found running and queued end interrupted, and so they
 * stay after a restart. */
static void test_interrupted_by_shutdown(void)
{
    struct pool p;
    start(&p, config(1, 4, 16));
    char a[RD_JOBS_ID_LEN + 1], b[RD_JOBS_ID_LEN + 1];
    rd_error err;
    CHECK(submit(p.jobs, SLOW, NULL, a, NULL, &err) == RD_OK, "submit A: %s", err.message);
    CHECK(wait_for(p.jobs, a, "running"), "A runs");
    CHECK(submit(p.jobs, FAST, NULL, b, NULL, &err) == RD_OK, "submit B: %s", err.message);
    rd_jobs_shutdown(p.jobs, WAIT_S); /* the run stops at its next report */
    CHECK(submit(p.jobs, FAST, NULL, NULL, NULL, &err) == RD_EBUSY, "no jobs after shutdown");
    struct seen sa = get(p.jobs, a, 0), sb = get(p.jobs, b, 0);
    CHECK(strcmp(sa.status, "interrupted") == 0, "running A interrupted, not %s", sa.status);
    CHECK(strcmp(sb.status, "interrupted") == 0, "queued B interrupted, not %s", sb.status);
    stop(&p, 0);

    start(&p, config(1, 4, 16));
    sa = get(p.jobs, a, 0);
    sb = get(p.jobs, b, 0);
    CHECK(strcmp(sa.status, "interrupted") == 0 && strcmp(sa.code, "interrupted") == 0 &&
              strstr(sa.message, "was running") != NULL,
          "A after a restart: %s, %s: %s", sa.status, sa.code, sa.message);
    CHECK(strcmp(sb.status, "interrupted") == 0 && strcmp(sb.code, "interrupted") == 0 &&
              strstr(sb.message, "was queued") != NULL,
          "B after a restart: %s, %s: %s", sb.status, sb.code, sb.message);
    CHECK(count(p.jobs, RD_JOB_INTERRUPTED) == 2 && count(p.jobs, RD_JOB_RUNNING) == 0,
          "two interrupted, none running");
    stop(&p, 0);
}

/* A row as a process that died would have left it. */
static void put_row(rd_store *store, const char *id, const char *status)
{
    rd_store_row row;
    memset(&row, 0, sizeof row);
    snprintf(row.id, sizeof row.id, "%s", id);
    snprintf(row.analysis, sizeof row.analysis, "modal");
    row.status = status;
    row.created_ns = (int64_t)1700000000 * 1000000000;
    if (strcmp(status, "running") == 0)
        row.started_ns = row.created_ns + 1000000;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_store_insert(store, &row, FAST, NULL, &err) == RD_OK, "insert: %s", err.message);
}

/* Rows a killed process left queued or running are interrupted at start. */
static void test_interrupted_by_crash(void)
{
    static const char running[] = "00000000000000a1", queued[] = "00000000000000a2";
    rd_store *store = NULL;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_store_create(dir, &store, &err) == RD_OK, "store: %s", err.message);
    put_row(store, running, "running");
    put_row(store, queued, "queued");
    rd_store_free(store);

    struct pool p;
    start(&p, config(1, 4, 16));
    struct seen r = get(p.jobs, running, 0), q = get(p.jobs, queued, 0);
    CHECK(strcmp(r.status, "interrupted") == 0 && strcmp(r.code, "interrupted") == 0 &&
              strstr(r.message, "was running") != NULL,
          "the running row: %s, %s: %s", r.status, r.code, r.message);
    CHECK(strcmp(q.status, "interrupted") == 0 && strstr(q.message, "was queued") != NULL,
          "the queued row: %s: %s", q.status, q.message);
    CHECK(count(p.jobs, RD_JOB_INTERRUPTED) == 2 && count(p.jobs, RD_JOB_QUEUED) == 0,
          "neither is queued or run again");
    char id[RD_JOBS_ID_LEN + 1];
    CHECK(submit(p.jobs, FAST, NULL, id, NULL, &err) == RD_OK, "the pool takes new jobs");
    CHECK(strcmp(get(p.jobs, id, WAIT_S).status, "succeeded") == 0, "and runs them");
    stop(&p, 5);
}

int main(void)
{
    static void (*const cases[])(void) = {
        test_success,  test_cancel_running,          test_queue_full,          test_idempotency,
        test_eviction, test_interrupted_by_shutdown, test_interrupted_by_crash};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        make_dir();
        cases[i]();
        remove_dir();
    }
    return check_done();
}
