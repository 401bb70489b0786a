/*
 * rd_sweep_over — what a sweep's "over" member (rd_sweep.h, issue 42) asks
 * of the rest of the spec, and the names of its columns: each output O
 * becomes  min:O max:O mean:O argmin:O argmax:O  (the aggregates over the
 * over values; rd_sweep_run.c runs a point over them and computes them).
 * rd_sweep.c parses the member as a parameter and validates its values.
 */
#include <jansson.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_sweep_int.h"

static const char *const prefixes[RD_SWEEP_OVER_COLUMNS] = {
    "min:", "max:", "mean:", "argmin:", "argmax:"};

static int over_error(rd_error *err, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int over_error(rd_error *err, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = rd_error_setv(err, RD_EREQUEST, path, fmt, ap);
    va_end(ap);
    return rc;
}

/* The over path against the parameters': not one of them, not above one
 * (each over value would replace that parameter's value). */
static int check_paths(const rd_sweep *s, rd_error *err)
{
    const char *o = s->over.path;
    size_t n = strlen(o);
    for (int p = 0; p < s->np; p++) {
        const char *q = s->p[p].path;
        if (strcmp(q, o) == 0)
            return over_error(err, "/over/path",
                              "/over/path %s is also the path of /parameters/%d: a point cannot "
                              "both set it and run over it",
                              o, p);
        if (strncmp(q, o, n) == 0 && q[n] == '/')
            return over_error(err, "/over/path",
                              "/over/path %s holds %s, the path of /parameters/%d: each over "
                              "value would replace that parameter's value",
                              o, q, p);
    }
    return RD_OK;
}

int rd_sweep_over_check(const rd_sweep *s, json_t *spec, rd_error *err)
{
    if (!s->over.n)
        return RD_OK;
    if (check_paths(s, err))
        return err->code;
    if (s->np == 0 && json_object_get(spec, "combine"))
        return over_error(err, "/combine",
                          "/combine combines parameters: a sweep without /parameters has one "
                          "point, run once per over value");
    for (int k = 0; k < s->no; k++) {
        char at[64];
        snprintf(at, sizeof at, "/outputs/%d", k);
        if (s->o[k].kind == O_ALL)
            return over_error(err, at,
                              "%s = %s is a list, not a number: an over sweep tabulates min, max, "
                              "mean, argmin and argmax of each output; use max(P), min(P) or "
                              "mean(P), or a sweep without \"over\"",
                              at, s->o[k].text);
    }
    return RD_OK;
}

void rd_sweep_over_columns(const rd_sweep *s, const output *o, json_t *cols)
{
    if (!s->over.n) {
        json_array_append_new(cols, json_string(o->text));
        return;
    }
    for (int c = 0; c < RD_SWEEP_OVER_COLUMNS; c++) {
        size_t n = strlen(prefixes[c]) + strlen(o->text) + 1;
        char *name = malloc(n);
        if (name)
            snprintf(name, n, "%s%s", prefixes[c], o->text);
        json_array_append_new(cols, name ? json_string(name) : NULL);
        free(name);
    }
}
