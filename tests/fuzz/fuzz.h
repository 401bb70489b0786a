/*
 * fuzz.h — what the three files of the scene-parser fuzzer share:
 * fuzz_scene.c (the mutator and the checks of every input), fuzz_fail.c
 * (allocation and write failures injected into a second pass over the
 * input) and fuzz_files.c (the files api/ reads: sweep chunks, examples).
 */
#ifndef FUZZ_H
#define FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "rd_api.h"
#include "rd_sweep.h"
#include "rd_sweep_request.h"

/* ---- fuzz_scene.c ---- */

/* FNV-1a of the input, salted: the harness's choices about an input (run
 * it, which allocation fails, which chunk file is broken) depend on the
 * input alone, so a finding reproduces when its input is replayed alone. */
uint32_t fuzz_hash(const uint8_t *data, size_t size, uint32_t salt);

/* The body with its size knobs clamped for a cheap run (malloc'd), or NULL. */
char *fuzz_clamped(const char *body, size_t len);

/* A made-up result of the scene `echo` for the warnings' rules: its
 * numerics (error estimate, event error, accuracy met or not) and its own
 * warnings picked by `h`; NULL when memory runs out. */
struct json_t;
struct json_t *fuzz_result_of(const char *echo, uint32_t h);

/* A monitor that cancels after the run budget of CPU time from now;
 * `deadline` is its state and must outlive the run. */
rd_monitor fuzz_budget(double *deadline);

/* A sweep request's first points (at most 2) run each under fuzz_budget,
 * as the service runs them: rows[i] the point's table row, or the row of a
 * point it stopped (rd_sweep_request_failed_row), NULL when even that could
 * not be made.  Returns how many points ran. */
size_t fuzz_sweep_rows(const rd_sweep_request *req, char *rows[2]);

/* ---- fuzz_fail.c ---- */

/* Routes jansson's allocations through the counter (before any JSON value
 * exists); RINGDYN_FUZZ_FAIL=0 turns the failure pass off. */
void fuzz_fail_init(void);

/* From now on count the allocations of api/, core/, jansson and the
 * harness; k > 0: the k-th and every later one fail (return NULL). */
void fuzz_fail_arm(size_t k);

/* Stops counting; returns the count.  fuzz_fail_fired: whether the armed
 * failure happened. */
size_t fuzz_fail_disarm(void);
int fuzz_fail_fired(void);

/* Holds the count while the harness sets up (returns the state to resume). */
int fuzz_fail_pause(void);
void fuzz_fail_resume(int armed);

/* A stream that keeps what is written (sink->text, NUL-terminated, caller
 * frees after fclose) and fails every write once `budget` bytes are in;
 * unbuffered, so each fputs of the code under test sees its own failure. */
typedef struct fuzz_sink {
    char *text;
    size_t len, cap, budget;
} fuzz_sink;
FILE *fuzz_sink_open(fuzz_sink *sink, size_t budget);

/* The OpenAPI document (from template `tmpl`) with an allocation failing
 * at each of OPENAPI_FAILS points spread over its allocations: the same
 * document or a 5xx error (once, at start-up: no body reaches it). */
void fuzz_fail_openapi(const char *tmpl);

/* The second pass over an input (most inputs, see fuzz_fail.c): each step
 * again with its allocations failing from the k-th on.  `ran`: the first
 * pass ran the input (scene or sweep), so the pass may run it too (one in
 * RUN_FAIL_EVERY). */
void fuzz_fail_pass(const uint8_t *data, size_t size, int ran);

/* ---- fuzz_files.c ---- */

/* Once per process: the example catalogue in a directory of odd files,
 * and the HTTP status of every code. */
void fuzz_files_init(void);

/* The rows of a whole sweep (m = its points, at most 2) as chunk files,
 * well formed or broken as the input's hash `h` picks, reduced by
 * rd_sweep_reduce: a well-formed set gives the table (csv, table_json), a
 * broken one an error. */
void fuzz_files_reduce(const rd_sweep *sweep, char **rows, size_t m, const char *csv,
                       const char *table_json, uint32_t h);

/* The input as the one example of a directory (one input in EXAMPLE_EVERY):
 * listed and read exactly when it is a valid scene object. */
void fuzz_files_example(const uint8_t *data, size_t size);

#endif
