/*
 * rd_study — what calibrations and sensitivities (issue 42) share: a base
 * scene into which numbers are written by JSON Pointer, the variations run
 * at once on threads (each exactly like a posted scene: rd_scene_parse_value,
 * then its analysis' runner), and numbers read back from their results by
 * pointer.  api-internal (rd_an_calibration.c, rd_an_sensitivity.c).
 *
 * Every spec error is RD_EREQUEST (400, like a sweep spec's) at a path into
 * the spec ("/base/ring/diameter", "/parameters/1/path").
 */
#ifndef RD_STUDY_H
#define RD_STUDY_H

#include <jansson.h>
#include <stddef.h>

#include "rd_error.h"
#include "rd_registry.h"
#include "rd_scene.h"

#define RD_STUDY_SET_MAX     32    /* pointers one measurement sets */
#define RD_STUDY_VALUES_MAX  20000 /* numbers one observation reads */
#define RD_STUDY_THREADS_MAX 64

/* The base scene of a study. */
typedef struct rd_study_base {
    const struct rd_scene_ops *ops; /* the scene module's (the study's own scene's) */
    json_t *scene;                  /* as given (owned): what the variations start from */
    json_t *echo;                   /* its echo, every default filled (owned) */
    const rd_analysis_def *an;      /* its analysis */
} rd_study_base;

/* A study's custom fields (base, parameters, ...) are kept as given and
 * checked together in its finish hook: *slot gets a deep copy of `v`,
 * *given 1 (RD_ENOMEM at `path`).  rd_study_echo is their echo (a new
 * reference; JSON null when not given). */
int rd_study_keep(json_t **slot, int *given, json_t *v, const char *path, rd_error *err);
json_t *rd_study_echo(json_t *kept);

/* `v` (at /base) into b: a scene object of an analysis that is not a study
 * (its errors at "/base" + their path), parsed with `ops` (the study's own
 * scene's).  On error b holds nothing. */
int rd_study_base_parse(json_t *v, const struct rd_scene_ops *ops, rd_study_base *b, rd_error *err);
void rd_study_base_cleanup(rd_study_base *b);

/* The number `ptr` names in the base's echo (defaults count: the ring
 * pack's /rings/0/discharge_coefficient needs not be written); else an
 * error at `path` saying what the pointer names instead. */
int rd_study_number_at(const rd_study_base *b, const char *ptr, const char *path, double *value,
                       rd_error *err);

/* The base with `set` (an object of pointer -> JSON value, or NULL)
 * written into it, then `n` numbers at `ptrs`: a new reference in *scene
 * (NULL on error: RD_EREQUEST when a pointer cannot be written, RD_ENOMEM). */
int rd_study_scene(const rd_study_base *b, json_t *set, const char *const *ptrs,
                   const double *values, size_t n, json_t **scene, rd_error *err);

/* rd_study_scene, then the scene parsed: RD_OK, or RD_EREQUEST at `path`
 * saying "<what> makes the base an invalid scene: <the scene's message at
 * its path>". */
int rd_study_try(const rd_study_base *b, json_t *set, const char *const *ptrs, const double *values,
                 size_t n, const char *path, const char *what, rd_error *err);

/* A pointer into a result of the base's analysis: well formed, and its
 * first token a member of that analysis' result (rd_analysis_def
 * result_keys), else an error at `path` listing them. */
int rd_study_check_observe(const rd_study_base *b, const char *ptr, const char *path,
                           rd_error *err);

/* The numbers `ptr` names in `result`: a number, or an array of numbers
 * (nested arrays flattened).  *n = their count (at most `max`, the rest
 * counted in *n but not written); -1 when it names nothing or something
 * else. */
int rd_study_values(json_t *result, const char *ptr, double *out, size_t max, size_t *n);

/* One run of a batch: `scene` (the caller's reference; parsed again here)
 * in, `result` (new reference, NULL when it failed) and rc/err out. */
typedef struct rd_study_run {
    json_t *scene;
    json_t *result;
    int rc;
    rd_error err;
} rd_study_run;

/* Runs every run of the batch, `threads` at once (0: the machine's online
 * processors, at most RD_STUDY_THREADS_MAX; never more than n), the calling
 * thread among them.  A run's own failure is in its rc/err; the batch
 * returns RD_ECANCELED (every run stopped) when `mon` asked to stop,
 * reporting `fraction` to it as it goes, or RD_ENOMEM. */
int rd_study_run_batch(const rd_study_base *b, rd_study_run *runs, size_t n, int threads,
                       const rd_monitor *mon, double fraction, rd_error *err);

#endif
