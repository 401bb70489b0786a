/*
 * rd_sweep_exec — where a sweep's points run when not on the service's own
 * workers: an executor hands the sweep to a scheduler as tasks that each
 * run `ringdyn sweep run SPEC --index I --chunks K --out DIR` and write one
 * chunk file into DIR, a directory the service and every node share
 * (docs/cluster.md, "The service as the cluster's front end").
 *
 * An executor is this table of four operations on its own context.  They
 * run on the sweeps' executor thread (rd_sweeps.c), never on an HTTP
 * thread, and may block for the time a command-line tool takes (bounded).
 *   submit   K tasks, task t writing chunk t of K of DIR/spec.json into DIR
 *            (logs in DIR/logs/); gives the scheduler's job id;
 *   poll     how many tasks the scheduler still holds (pending, running),
 *            or that none is left (gone);
 *   explain  once gone with chunks missing: why, as the sweep's error
 *            (a task's exit status and the last line of its log, or that the
 *            scheduler lost or cancelled it);
 *   cancel   stops every task of the job, without waiting.
 * The fifth operation, collect, is the same for every executor and lives
 * in rd_sweep_remote.c: the rows are read from the chunk files present
 * (rd_sweep_chunk_read), so no reduce job runs and the table is the one
 * the service's own workers make.  Slurm: rd_sweep_slurm.h.  A Kubernetes
 * Indexed Job executor would submit one Job (completions K, the index from
 * JOB_COMPLETION_INDEX), poll its pods, explain from its podFailurePolicy's
 * exit codes and cancel by deleting the Job.
 */
#ifndef RD_SWEEP_EXEC_H
#define RD_SWEEP_EXEC_H

#include <stddef.h>

#include "rd_error.h"

#define RD_SWEEP_EXEC_ID_MAX    64  /* a job id, NUL included */
#define RD_SWEEP_EXEC_STATE_MAX 160 /* the scheduler's state in words */

typedef struct rd_sweep_exec_poll {
    size_t pending, running;             /* tasks the scheduler holds */
    int gone;                            /* no task of the job is pending or running any more */
    char state[RD_SWEEP_EXEC_STATE_MAX]; /* e.g. "2 running, 6 pending" */
} rd_sweep_exec_poll;

typedef struct rd_sweep_exec {
    const char *name; /* the sweep's "executor": "slurm" */
    void *ctx;        /* the executor's own (borrowed) */
    int (*submit)(void *ctx, const char *dir, size_t chunks, char *job_id, rd_error *err);
    /* RD_OK, or an error when the scheduler cannot be asked (the sweep waits
     * and says so in its scheduler state). */
    int (*poll)(void *ctx, const char *job_id, rd_sweep_exec_poll *out, rd_error *err);
    void (*explain)(void *ctx, const char *dir, const char *job_id, size_t missing_chunk,
                    rd_error *why);
    int (*cancel)(void *ctx, const char *job_id, rd_error *err);
} rd_sweep_exec;

#endif
