/*
 * rd_jobs_body — the shared JSON of a job with a result (rd_jobs_int.h):
 * read from the store on demand into one `struct body` that every request
 * sending it shares, its gzip made once, and the result as CSV.
 */
#include "rd_jobs_int.h"

#include <stdlib.h>
#include <string.h>

#include "rd_gzip.h"

void rd_jobs_body_free(struct body *b)
{
    if (b) {
        free(b->data);
        free(b->gz);
        free(b);
    }
}

void rd_jobs_body_release(void *pub)
{
    struct body *b = pub;
    if (!b)
        return;
    rd_jobs *jobs = b->jobs;
    pthread_mutex_lock(&jobs->mu);
    int last = --b->refs == 0;
    if (last && b->owner)
        b->owner->body = NULL;
    pthread_mutex_unlock(&jobs->mu);
    if (last)
        rd_jobs_body_free(b);
}

/* Holds `b` as the most recently read body, dropping the one held before;
 * returns that one when this was its last reference (the caller frees it
 * after unlocking).  So a job read again and again (a page polling it,
 * clients whose socket buffers swallow the whole answer) is read from the
 * store once, at the cost of one result held while nobody reads it. */
struct body *rd_jobs_keep_recent_locked(rd_jobs *jobs, struct body *b)
{
    struct body *old = jobs->recent;
    if (old == b)
        return NULL;
    b->refs++;
    jobs->recent = b;
    if (!old || --old->refs > 0)
        return NULL;
    if (old->owner)
        old->owner->body = NULL;
    return old;
}

/* Called with `mu` held and a reference on a `job` with a body: its shared
 * body, read from the store unless some request holds it already.  Returns
 * with `mu` released and the job's reference dropped. */
int rd_jobs_body_and_release(rd_jobs *jobs, struct job *job, rd_jobs_body **out, rd_error *err)
{
    struct body *b = job->body;
    if (b) {
        b->refs++;
        struct body *dropped = rd_jobs_keep_recent_locked(jobs, b);
        rd_jobs_release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        rd_jobs_body_free(dropped);
        *out = &b->pub;
        return RD_OK;
    }
    char id[RD_JOBS_ID_LEN + 1];
    memcpy(id, job->id, sizeof id);
    pthread_mutex_unlock(&jobs->mu);

    char *data = NULL;
    size_t len = 0;
    rd_error read_err;
    rd_error_init(&read_err);
    int rc = rd_store_read_body(jobs->cfg.store, id, &data, &len, &read_err);
    struct body *fresh = rc == RD_OK ? calloc(1, sizeof *fresh) : NULL;
    if (rc == RD_OK && !fresh)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory reading job %s.", id);

    pthread_mutex_lock(&jobs->mu);
    if (rc == RD_ENOTFOUND && !rd_jobs_find_locked(jobs, id)) /* retention took it meanwhile */
        rc = rd_jobs_not_found(err, id);
    else if (rc == RD_ENOTFOUND) /* a succeeded job's row has a body: ours to explain */
        rc = rd_error_set(err, RD_EINTERNAL, "", "The result of job %s is missing from the store.",
                          id);
    else if (rc != RD_OK && read_err.code != RD_OK)
        rc = rd_error_set(err, read_err.code, "", "%s", read_err.message);
    if (rc == RD_OK) {
        if (job->body) { /* another request read it meanwhile: share that one */
            free(data);
            free(fresh);
        } else {
            fresh->jobs = jobs;
            fresh->owner = job;
            fresh->data = data;
            fresh->pub.data = data;
            fresh->pub.len = len;
            job->body = fresh;
        }
        job->body->refs++;
        *out = &job->body->pub;
    } else {
        free(data);
    }
    struct body *dropped = rc == RD_OK ? rd_jobs_keep_recent_locked(jobs, job->body) : NULL;
    rd_jobs_release_locked(job);
    pthread_mutex_unlock(&jobs->mu);
    rd_jobs_body_free(dropped);
    return rc;
}

int rd_jobs_body_gzip(rd_jobs_body *pub, const char **data, size_t *len)
{
    struct body *b = (struct body *)pub;
    rd_jobs *jobs = b->jobs;
    pthread_mutex_lock(&jobs->mu);
    int have = b->gz != NULL;
    pthread_mutex_unlock(&jobs->mu);
    if (!have) { /* compressed without the lock; a racing reader's copy is dropped */
        char *gz;
        size_t n;
        if (rd_gzip(b->data, pub->len, &gz, &n) != 0)
            return RD_ENOMEM;
        pthread_mutex_lock(&jobs->mu);
        if (!b->gz) {
            b->gz = gz;
            b->gz_len = n;
            gz = NULL;
        }
        pthread_mutex_unlock(&jobs->mu);
        free(gz);
    }
    *data = b->gz; /* never changes once set, and lives as long as the body */
    *len = b->gz_len;
    return RD_OK;
}

/* The result member of a succeeded job's JSON, which rd_jobs_render_with_result
 * wrote as the last member: a NUL-terminated copy, or NULL. */
static char *result_of(const rd_jobs_body *b)
{
    static const char key[] = ",\"result\":";
    const char *p = strstr(b->data, key);
    if (!p || b->len < 1)
        return NULL;
    p += sizeof key - 1;
    size_t n = (size_t)(b->data + b->len - 1 - p); /* up to the closing '}' */
    char *copy = malloc(n + 1);
    if (copy) {
        memcpy(copy, p, n);
        copy[n] = '\0';
    }
    return copy;
}

int rd_jobs_result_csv(rd_jobs *jobs, const char *id, char **csv, char *analysis, rd_error *err)
{
    *csv = NULL;
    struct job *job;
    int acquired = rd_jobs_acquire_locked(jobs, id, &job, err);
    if (acquired != RD_OK)
        return acquired;
    if (analysis)
        memcpy(analysis, job->analysis, sizeof job->analysis);
    if (!has_body(job)) {
        int rc = rd_error_set(err, RD_ENOTFOUND, "", "Job %s has no result (status %s).", job->id,
                              rd_jobs_status_name(job->status));
        rd_jobs_release_locked(job);
        pthread_mutex_unlock(&jobs->mu);
        return rc;
    }
    rd_jobs_body *body = NULL;
    int rc = rd_jobs_body_and_release(jobs, job, &body, err);
    if (rc != RD_OK)
        return rc;
    char *result = result_of(body);
    rd_jobs_body_release(body);
    if (!result)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory reading job %s.", id);

    /* The input is the api's own output, so a failure here is ours, not the
     * client's: report it as internal (or out of memory) whatever the api said. */
    rd_error e;
    rd_error_init(&e);
    *csv = rd_api_result_csv(result, &e);
    free(result);
    if (!*csv)
        return rd_error_set(err, e.code == RD_ENOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                            "Cannot write the result of job %s as CSV: %s", id,
                            e.message[0] ? e.message : "unknown error.");
    return RD_OK;
}
