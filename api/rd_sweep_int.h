/*
 * rd_sweep_int — what the files of a sweep share and nothing else sees: the
 * parsed spec (struct rd_sweep) and the values of a point.  rd_sweep.c
 * parses, validates and expands; rd_sweep_run.c runs a point;
 * rd_sweep_over.c parses the "over" member and runs a point over its values.
 */
#ifndef RD_SWEEP_INT_H
#define RD_SWEEP_INT_H

#include <jansson.h>
#include <stddef.h>
#include <stdint.h>

#include "rd_sweep.h"

enum { P_VALUES, P_RANGE, P_RANDOM };
enum { C_PRODUCT, C_ZIP, C_LHS };
enum { O_POINTER, O_MAX, O_MIN, O_MEAN, O_COUNT, O_ALL };

typedef struct {
    const char *path; /* scene pointer, borrowed from the spec */
    int kind;         /* P_* */
    json_t *values;   /* P_VALUES: the spec's array (borrowed) */
    double a, b;      /* range start/stop, random min/max */
    size_t n;         /* entries of values/range; 0 for random */
    int log, integer;
    size_t stride; /* product: points between two successive entries */
} param;

typedef struct {
    int kind;         /* O_* */
    const char *text; /* as written (the column name), borrowed */
    char *ptr;        /* the pointer (inside the parentheses), owned */
} output;

struct rd_sweep {
    json_t *spec;
    json_t *base; /* borrowed from spec */
    param p[RD_SWEEP_PARAMS_MAX];
    int np;
    output o[RD_SWEEP_OUTPUTS_MAX];
    int no;
    int combine;
    param over; /* "over": n = 0 when absent; never random */
    size_t points;
    double *u; /* latin_hypercube: u[p * points + i] in [0, 1) */
    char hash[17];
};

/* Parses a parameter (random only when random_ok) whose spec path is
 * `path` ("/parameters/3", "/over"); strings are borrowed from v. */
int rd_sweep_parse_param(json_t *v, const char *path, int random_ok, param *q, rd_error *err);

/* Validation of every value of q tried alone on the base (rd_sweep.h); p is
 * q's index in s->p, -1 for the over; errors at `prefix` and below. */
int rd_sweep_check_param(const rd_sweep *s, const param *q, int p, const char *prefix,
                         rd_error *err);

/* Entry k of a values/range parameter (new reference; NULL out of memory). */
json_t *rd_sweep_entry(const param *q, size_t k);

/* The value of parameter p at point i (new reference; NULL out of memory). */
json_t *rd_sweep_param_value(const rd_sweep *s, int p, size_t i);

/* The scene of point i (new reference), NULL when out of memory. */
json_t *rd_sweep_point_json(const rd_sweep *s, size_t i);

/* The cell of output o for a result (new reference; NULL out of memory). */
json_t *rd_sweep_output_value(const output *o, json_t *result);

/* Parses and runs one scene (borrowed) as a posted scene runs; on
 * RD_OK *result is the result text (caller frees), else e says why. */
int rd_sweep_run_scene(json_t *scene, const rd_monitor *mon, char **result, rd_error *e);

/* ---- over (rd_sweep_over.c) ---- */

/* Reads "over" of the spec into s->over (n = 0 when absent), after the
 * parameters and outputs: its path may not be a parameter's nor hold one,
 * and every output must give a number (all() is refused).  Errors RD_EREQUEST
 * at /over... or /outputs/k. */
int rd_sweep_over_parse(rd_sweep *s, json_t *spec, rd_error *err);

/* Appends output o's column names to cols: its text, or with an over the
 * RD_SWEEP_OVER_COLUMNS names "min:O" ... "argmax:O". */
void rd_sweep_over_columns(const rd_sweep *s, const output *o, json_t *cols);

/* Runs `scene` (point i's, borrowed) once per over value and appends the
 * aggregates, status and error to row.  RD_OK (a failed run is a row),
 * RD_ECANCELED, or RD_ENOMEM. */
int rd_sweep_over_run(const rd_sweep *s, size_t i, json_t *scene, const rd_monitor *mon,
                      json_t *row, rd_error *err);

#endif
