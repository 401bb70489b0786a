/*
 * rd_jobs_list — the bottom of the job pool (rd_jobs_int.h): status names,
 * the hash of the result cache, the job list with its references, the
 * lookup under `mu` and the snapshot a request renders.  Calls nothing else
 * of the pool.
 */
#include "rd_jobs_int.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const status_names[RD_JOB_NSTATUS] = {"queued", "running",   "succeeded",
                                                         "failed", "cancelled", "interrupted"};

const char *rd_jobs_status_name(int status)
{
    if (status < 0 || status >= RD_JOB_NSTATUS)
        return "unknown";
    return status_names[status];
}

void rd_jobs_hash(const char *data, size_t len, uint64_t out[2])
{
    uint64_t a = 0xcbf29ce484222325u; /* FNV-1a 64 offset basis and prime */
    uint64_t b = 0x9e3779b97f4a7c15u;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)data[i];
        a = (a ^ c) * 0x100000001b3u;
        b = (b ^ c) * 0xff51afd7ed558ccdu;
        b ^= b >> 29;
    }
    out[0] = a;
    out[1] = b ^ (uint64_t)len;
}

static int id_is_wellformed(const char *id)
{
    size_t n = 0;
    for (; id[n]; n++)
        if (n >= RD_JOBS_ID_LEN ||
            !((id[n] >= '0' && id[n] <= '9') || (id[n] >= 'a' && id[n] <= 'f')))
            return 0;
    return n == RD_JOBS_ID_LEN;
}

int rd_jobs_not_found(rd_error *err, const char *id)
{
    if (!id_is_wellformed(id))
        return rd_error_set(err, RD_ENOTFOUND, "", "There is no job with this id.");
    return rd_error_set(err, RD_ENOTFOUND, "",
                        "There is no job %s (the server keeps only the most recent finished jobs).",
                        id);
}

struct job *rd_jobs_find_locked(rd_jobs *jobs, const char *id)
{
    for (struct job *j = jobs->head; j; j = j->next)
        if (strcmp(j->id, id) == 0)
            return j;
    return NULL;
}

void rd_jobs_job_free(struct job *job)
{
    if (job->body)
        job->body->owner = NULL;
    rd_scene_free(job->scene);
    free(job->error);
    free(job->name);
    free(job->idem_key);
    free(job->unstored_echo);
    free(job);
}

void rd_jobs_release_locked(struct job *job)
{
    if (--job->refs == 0)
        rd_jobs_job_free(job);
}

void rd_jobs_set_status_locked(rd_jobs *jobs, struct job *job, int status)
{
    jobs->counts[job->status]--;
    jobs->counts[status]++;
    job->status = status;
}

void rd_jobs_push_locked(rd_jobs *jobs, struct job *job)
{
    job->seq = ++jobs->next_seq;
    job->next = jobs->head;
    if (jobs->head)
        jobs->head->prev = job;
    else
        jobs->tail = job;
    jobs->head = job;
    jobs->counts[job->status]++;
}

void rd_jobs_unlink_locked(rd_jobs *jobs, struct job *job)
{
    if (job->prev)
        job->prev->next = job->next;
    else
        jobs->head = job->next;
    if (job->next)
        job->next->prev = job->prev;
    else
        jobs->tail = job->prev;
    job->prev = job->next = NULL;
    jobs->counts[job->status]--;
}

struct job *rd_jobs_oldest_queued_locked(rd_jobs *jobs)
{
    for (struct job *j = jobs->tail; j; j = j->prev)
        if (j->status == RD_JOB_QUEUED)
            return j;
    return NULL;
}

/* 64 random bits as hex, unique in the store. */
int rd_jobs_new_id_locked(rd_jobs *jobs, char *id, rd_error *err)
{
    static const char hex[] = "0123456789abcdef";
    for (int attempt = 0; attempt < 8; attempt++) {
        unsigned char bytes[RD_JOBS_ID_LEN / 2];
        ssize_t n = read(jobs->random_fd, bytes, sizeof bytes);
        if (n != (ssize_t)sizeof bytes)
            return rd_error_set(err, RD_EINTERNAL, "", "Could not read random bytes for a job id.");
        for (size_t i = 0; i < sizeof bytes; i++) {
            id[2 * i] = hex[bytes[i] >> 4];
            id[2 * i + 1] = hex[bytes[i] & 15];
        }
        id[RD_JOBS_ID_LEN] = '\0';
        if (!rd_jobs_find_locked(jobs, id))
            return RD_OK;
    }
    return rd_error_set(err, RD_EINTERNAL, "", "Could not find a free job id.");
}

int rd_jobs_snapshot_locked(const rd_jobs *jobs, const struct job *job, struct snap *s)
{
    memcpy(s->id, job->id, sizeof s->id);
    memcpy(s->analysis, job->analysis, sizeof s->analysis);
    s->status = job->status;
    s->progress = job->progress;
    s->created = job->created;
    s->started = job->started;
    s->finished = job->finished;
    s->error = NULL;
    s->name = NULL;
    s->predicted_s = job->predicted_s * (jobs->cost_scale > 0 ? jobs->cost_scale : 1);
    if (is_final(job->status) && job->error && !(s->error = strdup(job->error)))
        return -1;
    if (job->name && !(s->name = strdup(job->name))) {
        free(s->error);
        s->error = NULL;
        return -1;
    }
    return 0;
}

/* Locks the store and finds job `id`, taking a reference: on RD_OK *out is the
 * job and the mutex is held (drop the job with rd_jobs_release_locked); otherwise the
 * mutex is released and the status is RD_ENOTFOUND. */
int rd_jobs_acquire_locked(rd_jobs *jobs, const char *id, struct job **out, rd_error *err)
{
    pthread_mutex_lock(&jobs->mu);
    *out = rd_jobs_find_locked(jobs, id);
    if (!*out) {
        pthread_mutex_unlock(&jobs->mu);
        return rd_jobs_not_found(err, id);
    }
    (*out)->refs++;
    return RD_OK;
}
