/*
 * rd_sweeps_int — what the files of the server's sweeps module share: a
 * sweep, the module's state, and the functions on them that more than one
 * file calls.  rd_sweeps.c (the workers, the life cycle and the requests)
 * and rd_sweeps_exec.c (the executor thread) call rd_sweeps_state.c (the
 * list, rendering, the end of a sweep), which calls neither.  Functions
 * named _locked are called with `mu` held.
 */
#ifndef RD_SWEEPS_INT_H
#define RD_SWEEPS_INT_H

#include <pthread.h>
#include <stddef.h>
#include <time.h>

#include <jansson.h>

#include "rd_error.h"
#include "rd_sweep_remote.h"
#include "rd_sweep_request.h"
#include "rd_sweeps.h"

enum { SW_QUEUED, SW_RUNNING, SW_SUCCEEDED, SW_FAILED, SW_CANCELLED, SW_INTERRUPTED };
extern const char *const rd_sweeps_status_names[]; /* by SW_* */

struct sweep {
    struct sweep *prev, *next;
    char id[RD_SWEEPS_ID_LEN + 1];
    char hash[RD_SWEEPS_ID_LEN + 1]; /* rd_sweep_hash */
    int fidelity;
    rd_sweep_request req; /* NULL sweep once frozen and released */
    size_t n, next_point, running, done, failed, m, partial; /* m: runs per point */
    char **rows;
    char *spare_row; /* rows[i] of a point whose row could not be made (shared) */
    int status, cancel;
    struct timespec created, started, finished; /* CLOCK_REALTIME; zero = not yet */
    /* A final sweep, rendered once (rd_sweeps_freeze_locked): its list entry, JSON and
     * CSV.  NULL until then (or when rendering ran out of memory). */
    char *meta, *body, *csv;
    /* On the executor (cfg.exec): its handle while unfinished (the sweep
     * counts as one point running then), what it showed last, and why it
     * failed (status failed: the executor's tasks did). */
    int on_exec, has_error;
    char *dir; /* its directory on the executor (rd_sweep_remote.h) */
    rd_sweep_remote *remote;
    rd_sweep_remote_info info;
    rd_error error;
};

struct rd_sweeps {
    rd_sweeps_config cfg;
    pthread_mutex_t mu;
    pthread_cond_t work; /* a point to run, or stop */
    pthread_cond_t idle; /* a point finished */
    struct sweep *head, *tail;
    size_t busy;   /* points running in all */
    int notifying; /* workers inside on_final (shutdown waits for them) */
    int stopping;
    int random_fd;
    pthread_t *workers;
    int nworkers;
    pthread_t exec_thread; /* steps the sweeps on cfg.exec */
    int exec_started;
};

static inline int rd_sweeps_final_status(int status)
{
    return status >= SW_SUCCEEDED;
}

/* rd_sweeps_state.c */

/* The sweep without its table (NULL: out of memory). */
json_t *rd_sweeps_object(const struct sweep *sw);
/* The whole sweep with its table (and fidelity table); NULL + err. */
char *rd_sweeps_json(const struct sweep *sw, rd_error *err);
struct sweep *rd_sweeps_find_locked(rd_sweeps *ss, const char *id);
void rd_sweeps_unlink_locked(rd_sweeps *ss, struct sweep *sw);
/* The rows and the spec of a sweep (not what freeze rendered). */
void rd_sweeps_release_rows(struct sweep *sw);
void rd_sweeps_sweep_free(struct sweep *sw);
/* Removes a final sweep from memory and from the store. */
void rd_sweeps_drop_locked(rd_sweeps *ss, struct sweep *sw);
/* Drops the oldest finished sweeps beyond keep_max. */
void rd_sweeps_retain_locked(rd_sweeps *ss);
/* Renders a sweep that just became final and stores it (rd_sweeps_state.c). */
void rd_sweeps_freeze_locked(rd_sweeps *ss, struct sweep *sw);
/* Ends `sw` if nothing of it runs and it is complete, failed, cancelled or
 * the server stops.  Returns 1 when it became final. */
int rd_sweeps_settle_locked(rd_sweeps *ss, struct sweep *sw);
void rd_sweeps_notify_final(rd_sweeps *ss);
/* The same from a caller that holds ss->mu: released around the
 * notification (counted in ss->notifying, so a stop waits for it). */
void rd_sweeps_notify_final_locked(rd_sweeps *ss);
/* Appends `sw` to the list (rd_sweeps_unlink_locked's inverse). */
void rd_sweeps_link_locked(rd_sweeps *ss, struct sweep *sw);
/* Stores point i's row (taken) and counts it done, failed unless ok. */
void rd_sweeps_store_row_locked(struct sweep *sw, size_t i, char *row);
/* rd_store_sweep_load's callback: a stored sweep back in memory. */
int rd_sweeps_load_one(void *ctx, const char *id, const char *meta, const char *body,
                       const char *csv);

/* rd_sweeps_exec.c */

/* The executor thread (pthread_create's start routine; arg: the rd_sweeps). */
void *rd_sweeps_exec_main(void *arg);
/* Whether a parsed sweep runs on the executor (sw->on_exec); RD_EREQUEST
 * for a fidelity sweep above the service's limit. */
int rd_sweeps_exec_choose(rd_sweeps *ss, struct sweep *sw, rd_error *err);
/* The executor's handle of a sweep that runs there; non-zero: out of memory. */
int rd_sweeps_exec_setup(rd_sweeps *ss, struct sweep *sw, const char *body, size_t len);

#endif
