/*
 * rd_sweep_int — what the files of a sweep share and nothing else sees: the
 * parsed spec (struct rd_sweep) and the values of a point.  rd_sweep.c
 * parses, validates and expands; rd_sweep_run.c runs a point;
 * rd_sweep_over.c checks the "over" member against the spec and names its
 * columns.
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

/* Entry k of a values/range parameter (new reference; NULL out of memory). */
json_t *rd_sweep_entry(const param *q, size_t k);

/* The value of parameter p at point i (new reference; NULL out of memory). */
json_t *rd_sweep_param_value(const rd_sweep *s, int p, size_t i);

/* The scene of point i (new reference), NULL when out of memory. */
json_t *rd_sweep_point_json(const rd_sweep *s, size_t i);

/* ---- over (rd_sweep_over.c) ---- */

/* What s->over (parsed, n > 0; nothing when n = 0) asks of the rest of the
 * spec: its path is neither a parameter's nor holds one, no all() output,
 * no "combine" without parameters.  Errors RD_EREQUEST at /over/path,
 * /outputs/k or /combine. */
int rd_sweep_over_check(const rd_sweep *s, json_t *spec, rd_error *err);

/* Appends output o's column names to cols: its text, or with an over the
 * RD_SWEEP_OVER_COLUMNS names "min:O" ... "argmax:O". */
void rd_sweep_over_columns(const rd_sweep *s, const output *o, json_t *cols);

#endif
