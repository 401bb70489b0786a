/*
 * rd_sweeps_state — the sweeps' list and each sweep's end: rendering (its
 * JSON, CSV and list entry), settling a sweep whose points are all done or
 * that was cancelled, failed or interrupted, storing and retaining the
 * finished ones (rd_sweeps_int.h).  Calls no other file of the module.
 */
#define _XOPEN_SOURCE 700

#include "rd_sweeps_int.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_api.h"
#include "rd_clock.h"
#include "rd_store.h"
#include "rd_sweep.h"
#include "rd_sweeps_reply.h"

const char *const rd_sweeps_status_names[] = {"queued", "running",   "succeeded",
                                              "failed", "cancelled", "interrupted"};

/* ---- rendering (mu held) ---- */

static json_t *iso_time(const struct timespec *ts)
{
    char buf[64];
    return rd_clock_iso8601(ts, buf, sizeof buf) == 0 ? json_string(buf) : json_null();
}

/* Where the sweep runs: "executor", and on an executor "cluster"; "error"
 * of a failed sweep.  Non-zero when out of memory. */
static int exec_members(const struct sweep *sw, json_t *o)
{
    const rd_sweep_remote_info *in = &sw->info;
    int bad = json_object_set_new(o, "executor", json_string(sw->on_exec ? "slurm" : "local"));
    if (sw->on_exec)
        bad |= json_object_set_new(
            o, "cluster",
            json_pack("{s:o,s:I,s:I,s:I,s:I,s:s,s:s}", "job_id",
                      in->job_id[0] ? json_string(in->job_id) : json_null(), "chunks",
                      (json_int_t)in->chunks, "chunks_done", (json_int_t)in->chunks_done,
                      "tasks_pending", (json_int_t)in->pending, "tasks_running",
                      (json_int_t)in->running, "scheduler", in->state, "dir", sw->dir));
    if (sw->has_error) {
        char *text = rd_api_error_json(&sw->error);
        json_t *body = text ? json_loads(text, 0, NULL) : NULL;
        json_t *inner = json_object_get(body, "error");
        bad |= !inner || json_object_set(o, "error", inner) != 0;
        json_decref(body);
        free(text);
    }
    return bad;
}

/* The sweep without its table. */
json_t *rd_sweeps_object(const struct sweep *sw)
{
    json_t *o = json_object();
    if (!o)
        return NULL;
    int bad = json_object_set_new(o, "id", json_string(sw->id));
    bad |= json_object_set_new(o, "kind", json_string(sw->fidelity ? "fidelity" : "sweep"));
    bad |= json_object_set_new(o, "status", json_string(rd_sweeps_status_names[sw->status]));
    size_t m = sw->m ? sw->m : 1, runs = sw->n * m; /* progress counts runs */
    bad |= json_object_set_new(
        o, "progress", json_real(runs ? (double)(sw->done * m + sw->partial) / (double)runs : 1));
    bad |= json_object_set_new(o, "points", json_integer((json_int_t)sw->n));
    bad |= json_object_set_new(o, "runs", json_integer((json_int_t)runs));
    bad |= json_object_set_new(o, "done", json_integer((json_int_t)sw->done));
    bad |= json_object_set_new(o, "failed", json_integer((json_int_t)sw->failed));
    bad |= json_object_set_new(o, "spec_hash", json_string(sw->hash));
    bad |= json_object_set_new(o, "created", iso_time(&sw->created));
    bad |= json_object_set_new(o, "started", iso_time(&sw->started));
    bad |= json_object_set_new(o, "finished", iso_time(&sw->finished));
    bad |= exec_members(sw, o);
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

/* The whole sweep: object, `table` with the rows done so far, and for a
 * succeeded fidelity sweep `fidelity` (rd_sweep_fidelity_table). */
char *rd_sweeps_json(const struct sweep *sw, rd_error *err)
{
    if (sw->body) {
        char *copy = strdup(sw->body);
        if (!copy)
            rd_error_set(err, RD_ENOMEM, "", "The server is out of memory.");
        return copy;
    }
    json_t *o = rd_sweeps_object(sw);
    char *text = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    char *table = rd_sweep_table_json(sw->req.sweep, sw->rows, sw->n, err);
    char *fid = NULL;
    if (table && sw->req.fidelity && sw->status == SW_SUCCEEDED)
        fid = rd_sweep_fidelity_table(table, err);
    text = rd_sweeps_splice(text, "table", table);
    if (sw->req.fidelity && sw->status == SW_SUCCEEDED)
        text = rd_sweeps_splice(text, "fidelity", fid);
    free(fid);
    free(table);
    if (!text && err->code == RD_OK)
        rd_error_set(err, RD_ENOMEM, "", "The server is out of memory.");
    return text;
}

struct sweep *rd_sweeps_find_locked(rd_sweeps *ss, const char *id)
{
    for (struct sweep *sw = ss->head; sw; sw = sw->next)
        if (strcmp(sw->id, id) == 0)
            return sw;
    return NULL;
}

/* ---- the list and the pool (mu held unless said) ---- */

void rd_sweeps_unlink_locked(rd_sweeps *ss, struct sweep *sw)
{
    if (sw->prev)
        sw->prev->next = sw->next;
    else
        ss->head = sw->next;
    if (sw->next)
        sw->next->prev = sw->prev;
    else
        ss->tail = sw->prev;
}

/* The rows and the spec of a sweep (not what rd_sweeps_freeze_locked rendered). */
void rd_sweeps_release_rows(struct sweep *sw)
{
    for (size_t i = 0; sw->rows && i < sw->n; i++)
        if (sw->rows[i] != sw->spare_row)
            free(sw->rows[i]);
    free(sw->rows);
    free(sw->spare_row);
    sw->rows = NULL;
    sw->spare_row = NULL;
    rd_sweep_request_cleanup(&sw->req);
}

void rd_sweeps_sweep_free(struct sweep *sw)
{
    if (!sw)
        return;
    rd_sweeps_release_rows(sw);
    rd_sweep_remote_free(sw->remote);
    free(sw->dir);
    free(sw->meta);
    free(sw->body);
    free(sw->csv);
    free(sw);
}

/* Removes a final sweep from memory and from the store. */
void rd_sweeps_drop_locked(rd_sweeps *ss, struct sweep *sw)
{
    rd_error err;
    rd_error_init(&err);
    rd_sweeps_unlink_locked(ss, sw);
    if (ss->cfg.store && rd_store_sweep_delete(ss->cfg.store, sw->id, &err) != RD_OK)
        fprintf(stderr, "ringdyn-server: sweep %s: %s\n", sw->id, err.message);
    rd_sweeps_sweep_free(sw);
}

/* Drops the oldest finished sweeps beyond keep_max. */
void rd_sweeps_retain_locked(rd_sweeps *ss)
{
    int finished = 0;
    for (struct sweep *sw = ss->tail; sw;) {
        struct sweep *prev = sw->prev;
        if (rd_sweeps_final_status(sw->status) && sw->running == 0 && ++finished > ss->cfg.keep_max)
            rd_sweeps_drop_locked(ss, sw);
        sw = prev;
    }
}

/* Renders a sweep that just became final once (its list entry, JSON and
 * CSV), stores it, and frees its rows and spec once no point of it runs.
 * Out of memory: it stays unrendered and is rendered at each request. */
void rd_sweeps_freeze_locked(rd_sweeps *ss, struct sweep *sw)
{
    rd_error err;
    rd_error_init(&err);
    json_t *o = rd_sweeps_object(sw);
    char *meta = o ? json_dumps(o, JSON_COMPACT) : NULL;
    json_decref(o);
    char *body = rd_sweeps_json(sw, &err);
    char *csv = rd_sweep_table_csv(sw->req.sweep, sw->rows, sw->n, &err);
    if (!meta || !body || !csv) {
        free(meta);
        free(body);
        free(csv);
        return;
    }
    sw->meta = meta;
    sw->body = body;
    sw->csv = csv;
    if (ss->cfg.store && rd_store_sweep_put(ss->cfg.store, sw->id, meta, body, csv, &err) != RD_OK)
        fprintf(stderr, "ringdyn-server: sweep %s is kept in memory only: %s\n", sw->id,
                err.message);
    if (sw->running == 0)
        rd_sweeps_release_rows(sw);
}

/* Ends `sw` if nothing of it runs and it is complete, cancelled or the
 * server stops.  Returns 1 when it became final. */
int rd_sweeps_settle_locked(rd_sweeps *ss, struct sweep *sw)
{
    if (rd_sweeps_final_status(sw->status) || sw->running > 0)
        return 0;
    if (sw->done == sw->n && !sw->cancel)
        sw->status = SW_SUCCEEDED;
    else if (ss->stopping)
        sw->status = SW_INTERRUPTED;
    else if (sw->has_error)
        sw->status = SW_FAILED;
    else if (sw->cancel)
        sw->status = SW_CANCELLED;
    else
        return 0;
    clock_gettime(CLOCK_REALTIME, &sw->finished);
    rd_sweeps_freeze_locked(ss, sw);
    rd_sweeps_retain_locked(ss);
    return 1;
}

void rd_sweeps_notify_final(rd_sweeps *ss)
{
    if (ss->cfg.on_final)
        ss->cfg.on_final(ss->cfg.on_final_ctx);
}

static const char ok_tail[] = ",\"ok\",null]";

void rd_sweeps_store_row_locked(struct sweep *sw, size_t i, char *row)
{
    size_t len = strlen(row), tail = sizeof ok_tail - 1;
    /* An ok row ends with status "ok" and error null (rd_sweep.h). */
    sw->failed += len < tail || strcmp(row + len - tail, ok_tail) != 0;
    free(sw->rows[i] != sw->spare_row ? sw->rows[i] : NULL);
    sw->rows[i] = row;
    sw->done++;
}

/* rd_store_sweep_load: a stored sweep back in memory, rendered and final. */
int rd_sweeps_load_one(void *ctx, const char *id, const char *meta, const char *body,
                       const char *csv)
{
    rd_sweeps *ss = ctx;
    json_t *m = json_loads(meta, 0, NULL);
    const char *status = json_string_value(json_object_get(m, "status"));
    struct sweep *sw = calloc(1, sizeof *sw);
    int known = 0;
    for (int k = SW_SUCCEEDED; sw && status && k <= SW_INTERRUPTED; k++)
        if (strcmp(status, rd_sweeps_status_names[k]) == 0) {
            sw->status = k;
            known = 1;
        }
    if (sw && known && strlen(id) == RD_SWEEPS_ID_LEN) {
        memcpy(sw->id, id, sizeof sw->id);
        const char *kind = json_string_value(json_object_get(m, "kind"));
        sw->fidelity = kind && strcmp(kind, "fidelity") == 0;
        sw->meta = strdup(meta);
        sw->body = strdup(body);
        sw->csv = strdup(csv);
    }
    json_decref(m);
    if (!sw || !sw->meta || !sw->body || !sw->csv) { /* unreadable row: left out */
        rd_sweeps_sweep_free(sw);
        return RD_OK;
    }
    rd_sweeps_link_locked(ss, sw);
    return RD_OK;
}

void rd_sweeps_notify_final_locked(rd_sweeps *ss)
{
    ss->notifying++;
    pthread_mutex_unlock(&ss->mu);
    rd_sweeps_notify_final(ss);
    pthread_mutex_lock(&ss->mu);
    ss->notifying--;
    pthread_cond_broadcast(&ss->idle);
}

void rd_sweeps_link_locked(rd_sweeps *ss, struct sweep *sw)
{
    sw->prev = ss->tail;
    if (ss->tail)
        ss->tail->next = sw;
    else
        ss->head = sw;
    ss->tail = sw;
}
