/*
 * rd_sweep_remote — a sweep on an executor: submit, poll, collect, cancel
 * (rd_sweep_remote.h).
 *
 * collect: every step tries the chunk files not read yet; a chunk present is
 * complete (its writer renamed it into place), and rd_sweep_chunk_read
 * checks it belongs to this sweep and split before its rows are taken.  The
 * rows go to the sweep as they come, so its progress and table grow chunk by
 * chunk and the last chunk costs the reading of one chunk only.
 *
 * Ending: every chunk read -> done.  Otherwise the executor's tasks must
 * still be there: the first poll that finds none is taken again one step
 * later (a chunk renamed just before its task left, a shared file system
 * showing it late), then the executor explains the missing chunk -> failed.
 * After a cancel the sweep ends once no task is left, or after
 * CANCEL_POLLS_MAX steps when the scheduler cannot be asked.
 */
#define _XOPEN_SOURCE 700

#include "rd_sweep_remote.h"

#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define CANCEL_POLLS_MAX 30

struct rd_sweep_remote {
    const rd_sweep_exec *exec;
    const rd_sweep *sweep;
    char *dir, *spec;
    size_t spec_len, n, k;
    char **rows;           /* n: rows read and not yet taken */
    unsigned char *have;   /* k: chunk read */
    size_t *ready, qh, qt; /* chunks read whose rows are being taken (queue) */
    size_t next;           /* the next point of chunk ready[qh] to hand out */
    int submitted, cancel_sent, gone_seen, cancel_polls;
    rd_sweep_remote_info info;
};

rd_sweep_remote *rd_sweep_remote_create(const rd_sweep_exec *exec, const char *shared_dir,
                                        const char *id, const rd_sweep *sweep, size_t chunks,
                                        const char *spec, size_t len)
{
    rd_sweep_remote *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->exec = exec;
    r->sweep = sweep;
    r->n = rd_sweep_points(sweep);
    r->k = chunks < 1 ? 1 : chunks > r->n ? r->n : chunks;
    r->dir = malloc(strlen(shared_dir) + strlen(id) + 8);
    r->spec = malloc(len + 1);
    r->rows = calloc(r->n ? r->n : 1, sizeof *r->rows);
    r->have = calloc(r->k, 1);
    r->ready = calloc(r->k, sizeof *r->ready);
    if (!r->dir || !r->spec || !r->rows || !r->have || !r->ready) {
        rd_sweep_remote_free(r);
        return NULL;
    }
    sprintf(r->dir, "%s/sweep-%s", shared_dir, id);
    memcpy(r->spec, spec, len);
    r->spec[len] = '\0';
    r->spec_len = len;
    r->info.chunks = r->k;
    snprintf(r->info.state, sizeof r->info.state, "not submitted yet");
    return r;
}

void rd_sweep_remote_free(rd_sweep_remote *r)
{
    if (!r)
        return;
    for (size_t i = 0; r->rows && i < r->n; i++)
        free(r->rows[i]);
    free(r->rows);
    free(r->have);
    free(r->ready);
    free(r->dir);
    free(r->spec);
    free(r);
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    remove(path);
    return 0;
}

/* DIR and DIR/logs, and DIR/spec.json written whole (temporary name, rename). */
static int write_spec(rd_sweep_remote *r, rd_error *err)
{
    size_t size = strlen(r->dir) + 32;
    char *logs = malloc(size), *tmp = malloc(size), *path = malloc(size);
    int rc = logs && tmp && path ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    if (rc == RD_OK) {
        sprintf(logs, "%s/logs", r->dir);
        sprintf(tmp, "%s/.spec.json.tmp", r->dir);
        sprintf(path, "%s/spec.json", r->dir);
        FILE *f = NULL;
        if ((mkdir(r->dir, 0777) != 0 && errno != EEXIST) ||
            (mkdir(logs, 0777) != 0 && errno != EEXIST) || !(f = fopen(tmp, "wb")) ||
            fwrite(r->spec, 1, r->spec_len, f) != r->spec_len || fclose(f) != 0 ||
            rename(tmp, path) != 0)
            rc = rd_error_set(err, RD_EINTERNAL, "",
                              "The service cannot write the sweep's spec into %s (its "
                              "--sweep-shared-dir): %s.",
                              r->dir, strerror(errno));
        if (f && rc != RD_OK)
            remove(tmp);
    }
    free(logs);
    free(tmp);
    free(path);
    return rc;
}

/* Reads the chunk files that appeared since the last step. */
static int collect(rd_sweep_remote *r, rd_error *why)
{
    for (size_t c = 0; c < r->k; c++) {
        if (r->have[c])
            continue;
        rd_error err;
        rd_error_init(&err);
        int rc = rd_sweep_chunk_read(r->sweep, r->dir, c, r->k, r->rows, &err);
        if (rc == RD_ENOTFOUND)
            continue;
        if (rc != RD_OK) {
            *why = err;
            return rc;
        }
        r->have[c] = 1;
        r->ready[r->qt++] = c;
        r->info.chunks_done++;
    }
    return RD_OK;
}

static int submit(rd_sweep_remote *r, rd_error *why)
{
    if (write_spec(r, why) != RD_OK ||
        r->exec->submit(r->exec->ctx, r->dir, r->k, r->info.job_id, why) != RD_OK) {
        r->info.job_id[0] = '\0';
        snprintf(r->info.state, sizeof r->info.state, "not submitted");
        return RD_REMOTE_FAILED;
    }
    r->submitted = 1;
    snprintf(r->info.state, sizeof r->info.state, "submitted");
    return RD_REMOTE_RUNNING;
}

int rd_sweep_remote_step(rd_sweep_remote *r, int cancel, rd_error *why)
{
    if (!r->submitted)
        return cancel ? RD_REMOTE_CANCELLED : submit(r, why);
    rd_error err;
    rd_error_init(&err);
    if (cancel && !r->cancel_sent) {
        r->cancel_sent = 1;
        if (r->exec->cancel(r->exec->ctx, r->info.job_id, &err) != RD_OK)
            fprintf(stderr, "ringdyn-server: %s\n", err.message);
        rd_error_init(&err);
    }
    rd_sweep_exec_poll p;
    int polled = r->exec->poll(r->exec->ctx, r->info.job_id, &p, &err) == RD_OK;
    if (polled) {
        r->info.pending = p.pending;
        r->info.running = p.running;
        snprintf(r->info.state, sizeof r->info.state, "%s", p.state);
    } else {
        snprintf(r->info.state, sizeof r->info.state, "unknown: %.200s", err.message);
    }
    if (collect(r, why) != RD_OK) {
        r->exec->cancel(r->exec->ctx, r->info.job_id, &err);
        return RD_REMOTE_FAILED;
    }
    if (r->info.chunks_done == r->k) {
        nftw(r->dir, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
        return RD_REMOTE_DONE;
    }
    if (cancel && ((polled && p.gone) || ++r->cancel_polls > CANCEL_POLLS_MAX)) {
        nftw(r->dir, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
        return RD_REMOTE_CANCELLED;
    }
    if (cancel || !polled || !p.gone) {
        r->gone_seen = 0;
        return RD_REMOTE_RUNNING;
    }
    if (!r->gone_seen++)
        return RD_REMOTE_RUNNING; /* once more: a chunk may show a moment late */
    size_t missing = 0;
    while (missing < r->k && r->have[missing])
        missing++;
    r->exec->explain(r->exec->ctx, r->dir, r->info.job_id, missing, why);
    return RD_REMOTE_FAILED;
}

void rd_sweep_remote_abandon(rd_sweep_remote *r)
{
    rd_error err;
    rd_error_init(&err);
    if (r->submitted && r->exec->cancel(r->exec->ctx, r->info.job_id, &err) != RD_OK)
        fprintf(stderr, "ringdyn-server: %s\n", err.message);
}

int rd_sweep_remote_next_row(rd_sweep_remote *r, size_t *i, char **row)
{
    while (r->qh < r->qt) {
        size_t first, end;
        rd_sweep_chunk_range(r->sweep, r->ready[r->qh], r->k, &first, &end, NULL);
        if (r->next < first)
            r->next = first;
        if (r->next < end) {
            *i = r->next++;
            *row = r->rows[*i];
            r->rows[*i] = NULL;
            return 1;
        }
        r->qh++;
        r->next = 0;
    }
    return 0;
}

void rd_sweep_remote_get_info(const rd_sweep_remote *r, rd_sweep_remote_info *info)
{
    *info = r->info;
}

const char *rd_sweep_remote_get_dir(const rd_sweep_remote *r)
{
    return r->dir;
}
