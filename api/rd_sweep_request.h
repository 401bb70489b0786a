/*
 * rd_sweep_request — the body of POST /api/v1/sweeps as the service takes it
 * (issue 16): either a sweep spec (rd_sweep.h) or a fidelity request
 *
 *   {"fidelity": {scene}, "segments": [n, ...], "rtol": [r, ...],
 *    "models": ["...", ...]}
 *
 * where only "fidelity" is required and the lists replace the defaults of
 * rd_sweep_fidelity_opts (each 1..64 entries).  A fidelity request becomes
 * the spec rd_sweep_fidelity_spec writes; its errors point into the request
 * ("/fidelity/ring/...", "/segments/2"), not into that generated spec.
 *
 * Also the row of a point the service stopped (its time limit): the same
 * shape as a row of rd_sweep_run_point, outputs null.  Keeps the JSON of
 * requests and rows in api/, so the server parses no field.
 */
#ifndef RD_SWEEP_REQUEST_H
#define RD_SWEEP_REQUEST_H

#include <stddef.h>

#include "rd_error.h"
#include "rd_sweep.h"

/* Longest "segments", "rtol" or "models" list of a fidelity request. */
#define RD_SWEEP_REQUEST_LIST_MAX 64

typedef struct rd_sweep_request {
    rd_sweep *sweep; /* owned; rd_sweep_request_cleanup frees it */
    int fidelity;    /* 1: a fidelity sweep (its table goes through rd_sweep_fidelity_table) */
    size_t n_params; /* the table's leading parameter columns */
} rd_sweep_request;

/* Parses and validates a request body (spec or fidelity request) with the
 * service's `max_points` (rd_sweep_parse).  Errors as rd_sweep_parse, with
 * paths into the body.  On success `out` holds a new sweep. */
int rd_sweep_request_parse(const char *body, size_t len, size_t max_points, rd_sweep_request *out,
                           rd_error *err);

/* Frees the sweep; the struct may be reused.  Zeroed or cleaned up twice: no-op. */
void rd_sweep_request_cleanup(rd_sweep_request *req);

/* The row of point i stopped for `why` (its code and message): parameter
 * values as rd_sweep_run_point writes them, null outputs, status and error.
 * Caller frees; NULL + err on out of memory or i out of range. */
char *rd_sweep_request_failed_row(const rd_sweep_request *req, size_t i, const rd_error *why,
                                  rd_error *err);

/* The row of a point whose own row could not be made (memory ran out while
 * it ran): every parameter and output null, status "out_of_memory".  The
 * service makes it when a sweep is created, so that no point goes without a
 * row (rows = points).  Caller frees; NULL on out of memory. */
char *rd_sweep_request_spare_row(const rd_sweep_request *req);

#endif
