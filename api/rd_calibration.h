/*
 * rd_calibration — a calibration's spec checked, its fit run and its result
 * written (rd_calibration.c); the scene table, hooks and registry entry are
 * rd_an_calibration.c.  api-internal.
 */
#ifndef RD_CALIBRATION_H
#define RD_CALIBRATION_H

#include <jansson.h>

#include "rd_error.h"
#include "rd_fit.h"
#include "rd_study.h"

#define RD_CALIBRATION_MEASUREMENTS_MAX 200

struct rd_calibration_param {
    const char *path; /* borrowed from params_json */
    double min, max, start;
};

struct rd_calibration_meas {
    json_t *set;         /* borrowed: the object of pointer -> value, or NULL */
    const char *observe; /* borrowed */
    double *value;       /* n (malloc'd) */
    double *sigma;       /* n (malloc'd) */
    size_t n;
    size_t group; /* the run it reads: measurements with equal sets share one */
};

/* The calibration's options (struct rd_scene.opts). */
struct rd_calibration {
    int base_given, params_given, meas_given;
    json_t *base_json, *params_json, *meas_json; /* as given (owned) */
    int max_runs, threads;                       /* /numerics */
    /* checked (finish): */
    rd_study_base base;
    size_t np, nm, n_values;
    size_t ng;                                          /* runs per evaluation: the distinct sets */
    size_t group_meas[RD_CALIBRATION_MEASUREMENTS_MAX]; /* a measurement of each */
    struct rd_calibration_param p[RD_FIT_PARAMS_MAX];
    struct rd_calibration_meas *m; /* nm (malloc'd) */
};

/* The spec's rules (rd_study.h: RD_EREQUEST at a path into the spec). */
int rd_calibration_check(struct rd_calibration *c, const struct rd_scene_ops *ops, rd_error *err);
/* The fit and its result object (without "scene" and numerics.wall_s). */
int rd_calibration_run(const struct rd_calibration *c, const rd_monitor *mon, json_t **result,
                       rd_error *err);
/* /parameters echoed with every start filled in. */
json_t *rd_calibration_echo_parameters(const struct rd_calibration *c);
void rd_calibration_cleanup(struct rd_calibration *c);

#endif
