/*
 * rd_jobs_render — a job as the JSON of API.md (rd_jobs_int.h): the job
 * object from a snapshot (no lock needed), a succeeded job's whole JSON with
 * its result spliced in, and the error bodies of the pool.
 */
#include "rd_jobs_int.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>

#include "rd_clock.h"
#include "rd_json.h"

/* An error body from rd_api_error_json, or NULL when out of memory. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
char *
rd_jobs_error_json(int code, const char *fmt, ...)
{
    rd_error err;
    rd_error_init(&err);
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(&err, code, "", fmt, ap);
    va_end(ap);
    return rd_api_error_json(&err);
}

/* The error of an interrupted job: code "interrupted", which the status
 * table of core/ (errors of a request or a run) has no entry for. */
char *rd_jobs_interrupted_json(const char *when)
{
    char message[256];
    snprintf(message, sizeof message,
             "The server stopped while the job was %s; it did not finish and is not run again. "
             "Submit the scene again.",
             when);
    json_t *o = json_pack("{s:{s:s, s:s}}", "error", "code", "interrupted", "message", message);
    char *text = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    return text;
}

/* ISO-8601 UTC with milliseconds, or null for a time not reached yet. */
static json_t *iso_time(const struct timespec *ts)
{
    char buf[64];
    return rd_clock_iso8601(ts, buf, sizeof buf) == 0 ? json_string(buf) : json_null();
}

/* Seconds a running job still needs: from the predicted cost while the run
 * is within it, else from its progress and elapsed time; null when neither
 * says anything. */
static json_t *eta(const struct snap *s)
{
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    double elapsed = (double)(now.tv_sec - s->started.tv_sec) +
                     1e-9 * (double)(now.tv_nsec - s->started.tv_nsec);
    if (!(elapsed >= 0))
        elapsed = 0;
    /* The cost model (scaled to this machine by the runs so far) first: the
     * progress of a modal run moves in uneven steps, so the rate it implies
     * is rough.  Once the run outlasts the model, the progress rate. */
    if (s->predicted_s > elapsed)
        return json_real(s->predicted_s - elapsed);
    /* Below 1 % the rate is mostly start-up cost: it would overstate. */
    if (s->progress >= 0.01 && s->progress < 1)
        return json_real(elapsed * (1 - s->progress) / s->progress);
    return json_null();
}

/* The job object without `result`; NULL when out of memory. */
json_t *rd_jobs_job_object(const struct snap *s)
{
    json_t *o = json_object();
    if (!o)
        return NULL;
    int bad = 0;
    bad |= json_object_set_new(o, "id", json_string(s->id));
    bad |= json_object_set_new(o, "status", json_string(rd_jobs_status_name(s->status)));
    bad |= json_object_set_new(o, "progress", json_real(s->progress));
    bad |= json_object_set_new(o, "analysis", json_string(s->analysis));
    bad |= json_object_set_new(o, "name", s->name ? json_string(s->name) : json_null());
    bad |= json_object_set_new(o, "created", iso_time(&s->created));
    bad |= json_object_set_new(o, "started", iso_time(&s->started));
    bad |= json_object_set_new(o, "finished", iso_time(&s->finished));
    if (s->status == RD_JOB_RUNNING)
        bad |= json_object_set_new(o, "eta_s", eta(s));
    if (s->error) {
        /* The error body is {"error": {...}}; the job carries the inner object. */
        json_t *body = json_loads(s->error, 0, NULL);
        json_t *inner = body ? json_object_get(body, "error") : NULL;
        if (inner)
            bad |= json_object_set(o, "error", inner);
        json_decref(body);
    }
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

static char *render_head(const struct snap *s)
{
    json_t *o = rd_jobs_job_object(s);
    char *head = o ? rd_json_dumps(o, 6, 0) : NULL; /* json_dumps's bytes, faster */
    json_decref(o);
    return head;
}

/* The whole succeeded job: the envelope built by jansson, then the api's
 * result text spliced in verbatim as the last member (it is already JSON,
 * and may be megabytes, so it is not parsed again).  NULL when out of memory. */
char *rd_jobs_render_with_result(const struct snap *s, const char *result, size_t *len)
{
    static const char key[] = ",\"result\":";
    char *head = render_head(s);
    if (!head)
        return NULL;
    size_t hl = strlen(head), rl = strlen(result);
    /* head is "{...}": drop its '}', append the member and close again. */
    char *out = malloc(hl - 1 + (sizeof key - 1) + rl + 2);
    if (out) {
        memcpy(out, head, hl - 1);
        memcpy(out + hl - 1, key, sizeof key - 1);
        memcpy(out + hl - 1 + sizeof key - 1, result, rl);
        memcpy(out + hl - 1 + sizeof key - 1 + rl, "}", 2);
        *len = hl - 1 + (sizeof key - 1) + rl + 1;
    }
    free(head);
    return out;
}

/* Called with `mu` held and a reference on `job`: snapshots, unlocks,
 * renders (without result), drops the reference.  Returns with `mu` released. */
int rd_jobs_view_and_release(rd_jobs *jobs, struct job *job, char **json, int *finished,
                             rd_error *err)
{
    struct snap s;
    int bad = rd_jobs_snapshot_locked(jobs, job, &s);
    pthread_mutex_unlock(&jobs->mu);
    if (finished)
        *finished = is_final(s.status);
    *json = bad ? NULL : render_head(&s);
    free(s.error);
    free(s.name);
    pthread_mutex_lock(&jobs->mu);
    rd_jobs_release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    if (!*json)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory while rendering job %s.", s.id);
    return RD_OK;
}
