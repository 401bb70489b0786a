/*
 * rd_sweeps — sweeps in the service (issue 16): POST /api/v1/sweeps and the
 * routes under it, a worker pool that runs their points, progress, cancel.
 *
 * A sweep is parsed and validated whole before anything runs
 * (rd_sweep_request_parse: a spec, or {"fidelity": scene, ...}) with the
 * service's point limit (`max_points`; above it the 400 names the cluster
 * path, `ringdyn sweep run ... --chunks K`), unless an executor is
 * configured: then a sweep above the limit (or of at least
 * exec_min_points) runs on it (rd_sweep_exec.h, rd_sweeps_exec.c), its
 * rows read from the chunk files its tasks write, and it may also end
 * `failed` (a task failed or vanished; "error" says which and why).  It is then `queued`; the
 * workers (`threads` of them, the server's --threads) take its points in
 * order, several at once, one sweep after the other in submission order.
 * A point runs rd_sweep_run_point under a monitor that stops it when the
 * sweep is cancelled, the server stops, or the point passes `timeout_s` —
 * then its row says `time_limit`: a failed point is a row with its error,
 * never a failed sweep.  The sweep ends `succeeded` once every point has a
 * row, `cancelled` (DELETE; the rows done stay), or `interrupted` (the
 * server stopped).  DELETE of a finished sweep deletes it.
 *
 * A sweep that becomes final is rendered once (its JSON, its CSV, its list
 * entry), written to the job store's `sweeps` table and served from that
 * text; its rows and spec are freed.  A restart loads the finished sweeps
 * back; sweeps queued or running when the server stops end `interrupted`
 * with the rows done.  At most `queue_max` unfinished sweeps (more:
 * RD_EBUSY, 429) and `keep_max` finished ones (the oldest finished go
 * first, from memory and store).
 *
 * The HTTP layer hands each request here and turns the rd_sweeps_reply
 * into a response: this module knows no libmicrohttpd type, rd_http.c no
 * sweep.  Every function is thread-safe.
 */
#ifndef RD_SWEEPS_H
#define RD_SWEEPS_H

#include <stddef.h>

#include "rd_error.h"
#include "rd_store.h"
#include "rd_sweep_exec.h"

/* Sweep ids: 16 lowercase hex digits, as job ids. */
#define RD_SWEEPS_ID_LEN 16
/* The default service limit on points (--sweep-max-points). */
#define RD_SWEEPS_POINTS_DEFAULT 10000

typedef struct rd_sweeps_config {
    int threads;       /* workers, >= 1 */
    size_t max_points; /* points per sweep, 1..RD_SWEEP_POINTS_MAX */
    double timeout_s;  /* run time limit per point, > 0 */
    int queue_max;     /* unfinished sweeps at once, >= 1 */
    int keep_max;      /* finished sweeps kept, >= 1 */
    rd_store *store;   /* finished sweeps persist here (borrowed); NULL: memory only */
    /* An executor (borrowed; NULL: every sweep runs on the workers).  A
     * sweep of more than max_points runs, or of at least exec_min_points,
     * runs there as exec_chunks tasks (at most its points) in
     * shared_dir/sweep-<id>; a fidelity sweep always runs here. */
    const rd_sweep_exec *exec;
    const char *shared_dir; /* borrowed */
    size_t exec_min_points, exec_chunks;
    /* Called (no lock held) when a sweep reaches a final state, so that
     * requests waiting for it can be woken.  May be NULL. */
    void (*on_final)(void *ctx);
    void *on_final_ctx;
} rd_sweeps_config;

/* What to answer.  `status` 0 means: suspend the request until sweep
 * `wait_id` is final or `wait_s` pass, then call rd_sweeps_answer_wait. */
typedef struct rd_sweeps_reply {
    int status;               /* HTTP status, or 0: wait */
    char *body;               /* malloc'd (NULL for 204 and while waiting) */
    const char *content_type; /* static */
    char location[64];        /* Location header, or "" */
    char disposition[64];     /* Content-Disposition header, or "" */
    int retry_after;          /* Retry-After seconds (503), or 0 */
    char wait_id[RD_SWEEPS_ID_LEN + 1];
    double wait_s;
    int wait_submit; /* the wait answers a POST (Location; 200 or 202) */
} rd_sweeps_reply;

typedef struct rd_sweeps rd_sweeps;

int rd_sweeps_create(const rd_sweeps_config *cfg, rd_sweeps **out, rd_error *err);

/* Asks the running points to stop and takes no new ones, without waiting
 * (so that they stop while the jobs do). */
void rd_sweeps_stop(rd_sweeps *sweeps);

/* Stops taking points; unfinished sweeps end `interrupted` once their
 * running points stop (asked to at once), waiting at most `wait_s`.
 * Idempotent. */
void rd_sweeps_shutdown(rd_sweeps *sweeps, double wait_s);

/* Shuts down, joins the workers (a point inside a solver that does not
 * report is left to the process exit) and frees.  NULL is a no-op. */
void rd_sweeps_free(rd_sweeps *sweeps);

/* POST /api/v1/sweeps with `body`; `wait_s` < 0 when ?wait= was not given. */
void rd_sweeps_post(rd_sweeps *sweeps, const char *body, size_t len, double wait_s,
                    rd_sweeps_reply *reply);

/* GET /api/v1/sweeps (`limit` newest, without tables). */
void rd_sweeps_list(rd_sweeps *sweeps, size_t limit, rd_sweeps_reply *reply);

/* GET, HEAD or DELETE of /api/v1/sweeps/{id}, or (csv) GET or HEAD of
 * /api/v1/sweeps/{id}/table.csv. */
void rd_sweeps_item(rd_sweeps *sweeps, const char *method, const char *id, int csv,
                    rd_sweeps_reply *reply);

/* The answer to a request that waited (reply.status was 0): the sweep as it
 * is now; with Location and 200 (final) or 202 when `submit`. */
void rd_sweeps_answer_wait(rd_sweeps *sweeps, const char *id, int submit, rd_sweeps_reply *reply);

/* Is sweep `id` final (or gone)? */
int rd_sweeps_is_final(rd_sweeps *sweeps, const char *id);

/* Frees reply->body. */
void rd_sweeps_reply_cleanup(rd_sweeps_reply *reply);

#endif
