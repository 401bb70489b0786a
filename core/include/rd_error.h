/*
 * rd_error — one status table for all of ringdyn, and the caller-owned error
 * record that travels down through every fallible call.
 *
 * Fallible functions return an int status: 0 (RD_OK) or one of the negative
 * RD_E* codes below.  When they fail they fill the caller's rd_error, unless an
 * earlier error is already recorded there (the first error wins, as in
 * jansson's json_error_t).  Messages are written for the user of the service:
 * what is wrong, the value, the allowed range.  `path` is a JSON Pointer to
 * the offending scene field ("/ring/radial_width") or "" when there is none.
 *
 * Error paths are relative.  Core never writes where in the scene a block
 * sits: a function writes paths relative to the block it was given, and its
 * caller enters the block's pointer first.  The record keeps that pointer
 * as `base` ("" = the scene root); rd_error_set records base + path, and in
 * its format each '@' stands for the base, so a message names the field by
 * its whole pointer wherever the block sits:
 *
 *     // the ring validator: paths relative to the ring block
 *     return rd_error_set(err, RD_EINVAL, "/axial_height",
 *                         "@/axial_height = %g m gives ...", h);
 *
 *     // its caller: the block is at /ring (a lift scene) or /rings/1/ring
 *     size_t m = rd_error_enter(err, "/ring");
 *     rc = rd_ring_validate(p, closed, err);    // "/ring/axial_height = ..."
 *     rd_error_leave(err, m);
 *
 * A record filled apart (a local rd_error whose message is kept, quoted or
 * dropped) starts at the caller's base (rd_error_init_local), so its path
 * and words are whole, and is copied back as it stands (rd_error_forward):
 * the base is applied once.
 */
#ifndef RD_ERROR_H
#define RD_ERROR_H

#include <stdarg.h>
#include <stddef.h>

/* X(name, value, code string, summary) */
#define RD_ERRNO_MAP(X)                                                           \
    X(OK, 0, "ok", "success")                                                     \
    X(EINVAL, -1, "invalid_scene", "the scene is invalid")                        \
    X(ELIMIT, -2, "limit_exceeded", "the scene asks for more work than allowed")  \
    X(EJSON, -3, "invalid_json", "the body is not valid JSON")                    \
    X(ENOMEM, -4, "out_of_memory", "out of memory")                               \
    X(ENOCONV, -5, "not_converged", "the solver did not converge")                \
    X(ENUMERIC, -6, "numerical_failure", "a numerical library call failed")       \
    X(ECANCELED, -7, "cancelled", "the job was cancelled")                        \
    X(EINTERNAL, -8, "internal_error", "internal error")                          \
    X(EREQUEST, -9, "invalid_request", "the request is malformed")                \
    X(ENOTFOUND, -10, "not_found", "no such resource")                            \
    X(EMETHOD, -11, "method_not_allowed", "method not allowed on this path")      \
    X(ETOOLARGE, -12, "payload_too_large", "the body is larger than allowed")     \
    X(EMEDIA, -13, "unsupported_media_type", "the body must be application/json") \
    X(EBUSY, -14, "queue_full", "the job queue is full, retry later")             \
    X(ETIMEOUT, -15, "time_limit", "the job ran longer than allowed")

enum rd_status {
#define RD_ENUM_(name, value, code, summary) RD_##name = value,
    RD_ERRNO_MAP(RD_ENUM_)
#undef RD_ENUM_
};

#define RD_ERROR_PATH_MAX    128
#define RD_ERROR_MESSAGE_MAX 512

typedef struct rd_error {
    int code;                           /* RD_OK while no error is recorded */
    char path[RD_ERROR_PATH_MAX];       /* JSON Pointer, or "" */
    char message[RD_ERROR_MESSAGE_MAX]; /* for the user, complete sentence */
    char base[RD_ERROR_PATH_MAX];       /* the block being checked, "" = root */
} rd_error;

/* Clears the record (code RD_OK, empty strings, the base at the root). */
void rd_error_init(rd_error *err);

/* Enters a block: appends `block` ("/ring", "/rings/1") to the base and
 * returns the base's previous length, for rd_error_leave.  err may be NULL. */
size_t rd_error_enter(rd_error *err, const char *block);
/* Leaves the blocks entered since `mark` (rd_error_enter's return). */
void rd_error_leave(rd_error *err, size_t mark);

/* Clears `local` for a sub-computation of err's: at err's base (err may be
 * NULL: the root), to be copied back with rd_error_forward. */
void rd_error_init_local(rd_error *local, const rd_error *err);
/* Copies src's error into dst as it stands (its path is whole already),
 * unless dst holds an error already; returns src's code. */
int rd_error_forward(rd_error *dst, const rd_error *src);

/* Records an error unless one is already recorded; returns `code` so callers
 * can write `return rd_error_set(err, RD_EINVAL, "/diameter", ...)`.  The
 * path recorded is base + path; each '@' in fmt stands for the base.
 * err may be NULL (then only the code is returned). */
int rd_error_set(rd_error *err, int code, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* RD_OK when v is finite and within [lo, hi]; else RD_EINVAL at `path`
 * (base + path) with the one wording every range error uses: "<base><path>
 * = v unit is out of range: allowed lo to hi unit." */
int rd_error_range(double v, double lo, double hi, const char *path, const char *unit,
                   rd_error *err);

/* rd_error_range for a field of a sub-block: `block` ("/numerics") entered
 * for the one check, `path` relative to it ("/rtol"). */
int rd_error_range_in(const char *block, double v, double lo, double hi, const char *path,
                      const char *unit, rd_error *err);

/* rd_error_set with a va_list, for callers that forward their own format. */
int rd_error_setv(rd_error *err, int code, const char *path, const char *fmt, va_list ap);

/* "invalid_scene", ... for a status; "unknown_error" for codes not in the table. */
const char *rd_error_code_name(int code);
/* One-line summary of a status. */
const char *rd_error_summary(int code);

/* Progress and cancellation for long computations.  `report` is called with a
 * fraction in [0, 1]; a non-zero return asks the computation to stop, which
 * then returns RD_ECANCELED.  A NULL monitor or NULL report is allowed. */
typedef struct rd_monitor {
    int (*report)(void *ctx, double fraction);
    void *ctx;
} rd_monitor;

/* Calls the monitor; returns RD_ECANCELED (and records it) if asked to stop. */
int rd_monitor_report(const rd_monitor *mon, double fraction, rd_error *err);

/* A sub-computation's monitor: its fractions 0..1 (clamped) reported to
 * `parent` as [f0, f1] of the parent's range.  rd_monitor_span_init fills
 * `s` and returns the monitor to hand down, or NULL when the parent has no
 * report (the sub-computation then skips its reports). */
typedef struct rd_monitor_span {
    const rd_monitor *parent;
    double f0, f1;
    rd_monitor mon;
} rd_monitor_span;
const rd_monitor *rd_monitor_span_init(rd_monitor_span *s, const rd_monitor *parent, double f0,
                                       double f1);

#endif
