/*
 * rd_jobs_body — the shared JSON of a job with a result (rd_jobs_int.h):
 * read from the store on demand into one `struct body` that every request
 * sending it shares, and its other forms (gzip, the cached answer's gzip,
 * the CSV and its gzip), each made once per body and shared the same way:
 * a 30 MB lift result's 2.3 MB gzip or CSV was made again, and held, by
 * every connection sending it (issue 45).
 */
#include "rd_jobs_int.h"

#include <stdlib.h>
#include <string.h>

#include "rd_gzip.h"

struct body *rd_jobs_body_new(rd_jobs *jobs, char *data, size_t len)
{
    struct body *b = calloc(1, sizeof *b);
    if (!b || pthread_mutex_init(&b->make, NULL) != 0) {
        free(b);
        free(data);
        return NULL;
    }
    b->jobs = jobs;
    b->data = data;
    b->pub.data = data;
    b->pub.len = len;
    return b;
}

void rd_jobs_body_free(struct body *b)
{
    if (b) {
        free(b->data);
        for (size_t i = 0; i < sizeof b->forms / sizeof b->forms[0]; i++)
            free(b->forms[i].data);
        pthread_mutex_destroy(&b->make);
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
    struct body *fresh = NULL;
    if (rc == RD_OK) {
        fresh = rd_jobs_body_new(jobs, data, len); /* owns `data`, or has freed it */
        data = NULL;
        if (!fresh)
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory reading job %s.", id);
    }

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
            rd_jobs_body_free(fresh);
        } else {
            fresh->owner = job;
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

/* The CSV of the body's result into f (make held). */
static int make_csv(struct body *b, struct form *f, rd_error *err)
{
    char *result = result_of(&b->pub);
    if (!result)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory writing a result as CSV.");
    /* The input is the api's own output, so a failure here is ours, not the
     * client's: report it as internal (or out of memory) whatever the api said. */
    rd_error e;
    rd_error_init(&e);
    f->data = rd_api_result_csv(result, &e);
    free(result);
    if (!f->data)
        return rd_error_set(err, e.code == RD_ENOMEM ? RD_ENOMEM : RD_EINTERNAL, "",
                            "Cannot write the result as CSV: %s",
                            e.message[0] ? e.message : "unknown error.");
    f->len = strlen(f->data);
    rd_jobs_hash(f->data, f->len, f->hash);
    return RD_OK;
}

/* The JSON with "cached":true as its first member, gzipped, into f. */
static int make_cached(struct body *b, struct form *f, rd_error *err)
{
    static const char prefix[] = "{\"cached\":true,";
    size_t n = sizeof prefix - 1 + b->pub.len - 1;
    char *joined = b->pub.len > 1 ? malloc(n) : NULL;
    if (!joined)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for a cached answer.");
    memcpy(joined, prefix, sizeof prefix - 1);
    memcpy(joined + sizeof prefix - 1, b->data + 1, b->pub.len - 1);
    rd_jobs_hash(joined, n, f->hash);
    int rc = rd_gzip(joined, n, &f->data, &f->len);
    free(joined);
    return rc == 0 ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "Out of memory for gzip.");
}

/* Makes form `which` of b unless it is there (make held). */
static int make_form(struct body *b, rd_jobs_form which, rd_error *err)
{
    struct form *f = &b->forms[which];
    if (f->data)
        return RD_OK;
    if (which == RD_JOBS_CSV)
        return make_csv(b, f, err);
    if (which == RD_JOBS_CACHED)
        return make_cached(b, f, err);
    const char *in = b->data;
    size_t n = b->pub.len;
    if (which == RD_JOBS_CSV_GZIP) {
        int rc = make_form(b, RD_JOBS_CSV, err);
        if (rc != RD_OK)
            return rc;
        in = b->forms[RD_JOBS_CSV].data;
        n = b->forms[RD_JOBS_CSV].len;
    }
    rd_jobs_hash(in, n, f->hash);
    if (rd_gzip(in, n, &f->data, &f->len) != 0)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for gzip.");
    return RD_OK;
}

int rd_jobs_body_form(rd_jobs_body *pub, rd_jobs_form which, const char **data, size_t *len,
                      uint64_t hash[2], rd_error *err)
{
    struct body *b = (struct body *)pub;
    if ((unsigned)which >= sizeof b->forms / sizeof b->forms[0])
        return rd_error_set(err, RD_EINTERNAL, "", "No such form of a result.");
    pthread_mutex_lock(&b->make);
    int rc = make_form(b, which, err);
    const struct form *f = &b->forms[which];
    if (rc == RD_OK) {
        *data = f->data;
        *len = f->len;
        if (hash)
            memcpy(hash, f->hash, sizeof f->hash);
    }
    pthread_mutex_unlock(&b->make);
    return rc;
}

int rd_jobs_result_body(rd_jobs *jobs, const char *id, rd_jobs_body **body, char *analysis,
                        rd_error *err)
{
    *body = NULL;
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
    return rd_jobs_body_and_release(jobs, job, body, err);
}
