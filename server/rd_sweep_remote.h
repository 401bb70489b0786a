/*
 * rd_sweep_remote — one sweep run by an executor (rd_sweep_exec.h): its
 * directory under the shared directory, the submission, the polls, and
 * collect: the rows read from each chunk file as it appears.
 *
 * The sweeps' executor thread (rd_sweeps.c) calls rd_sweep_remote_step
 * about once a second without holding the sweeps' lock; then, holding it,
 * takes the rows read so far (rd_sweep_remote_next_row) and the state to
 * show (rd_sweep_remote_get_info).  A handle is used by one thread at a
 * time.  The directory DIR = SHARED/sweep-<id> holds spec.json (the spec as
 * posted), the chunk files and logs/; it is removed when the sweep
 * succeeds or is cancelled, and kept when it fails (the logs say why).
 */
#ifndef RD_SWEEP_REMOTE_H
#define RD_SWEEP_REMOTE_H

#include <stddef.h>

#include "rd_error.h"
#include "rd_sweep.h"
#include "rd_sweep_exec.h"

enum { RD_REMOTE_RUNNING, RD_REMOTE_DONE, RD_REMOTE_FAILED, RD_REMOTE_CANCELLED };

/* What GET shows of a sweep on an executor. */
typedef struct rd_sweep_remote_info {
    char job_id[RD_SWEEP_EXEC_ID_MAX]; /* "" until submitted */
    size_t chunks, chunks_done;
    size_t pending, running;                  /* tasks, at the last poll */
    char state[RD_SWEEP_EXEC_STATE_MAX + 64]; /* the scheduler's state, or why it is not known */
} rd_sweep_remote_info;

typedef struct rd_sweep_remote rd_sweep_remote;

/* A sweep `id` of `sweep` (borrowed, must outlive the handle) to run as
 * `chunks` tasks (at most its points) on `exec` (borrowed) in
 * shared_dir/sweep-<id>; `spec` (len bytes, copied) is the spec as posted.
 * NULL when out of memory. */
rd_sweep_remote *rd_sweep_remote_create(const rd_sweep_exec *exec, const char *shared_dir,
                                        const char *id, const rd_sweep *sweep, size_t chunks,
                                        const char *spec, size_t len);

/* Submits (the first call), polls, reads the chunk files that appeared,
 * and, with `cancel`, cancels the tasks (and ends once none is left).
 * Returns RD_REMOTE_RUNNING until the sweep ends: DONE (every row read),
 * FAILED (`why` says why) or CANCELLED. */
int rd_sweep_remote_step(rd_sweep_remote *r, int cancel, rd_error *why);

/* Cancels the tasks of a sweep the server abandons (it stops), without
 * waiting. */
void rd_sweep_remote_abandon(rd_sweep_remote *r);

/* The next row read and not yet taken: 1 with point *i and *row (the
 * caller owns it), 0 when none is left. */
int rd_sweep_remote_next_row(rd_sweep_remote *r, size_t *i, char **row);

void rd_sweep_remote_get_info(const rd_sweep_remote *r, rd_sweep_remote_info *info);

/* The sweep's directory (for GET). */
const char *rd_sweep_remote_get_dir(const rd_sweep_remote *r);

/* Frees the handle and the rows not taken; the directory is left as it is. */
void rd_sweep_remote_free(rd_sweep_remote *r);

#endif
