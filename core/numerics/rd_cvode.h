/*
 * rd_cvode.h — one CVODE session as ringdyn's integrators use it (the lift
 * driver, the ring pack's driver): the SUNDIALS context and the solver, the
 * silent error handler that keeps CVODE's last message, the solver's
 * counters, a custom linear solver around a caller's Newton solve, and one
 * translation of CVODE's failures into rd_error statuses:
 *   - a set-up, query or restart call fails only on misuse: RD_EINTERNAL,
 *     with CVODE's flag name and message (rd_cvode_misuse);
 *   - an integration that used its step budget: RD_ELIMIT at "/max_steps"
 *     of the numerics block, which the caller enters for flag
 *     CV_TOO_MUCH_WORK; any other integration failure: RD_ENOCONV at "";
 *     both dated at the crank angle the integrator reached, with what the
 *     flag means in words (rd_cvode_failure).
 *
 * Usage (the caller owns the vectors, matrices and linear solver; they are
 * created with s.ctx and destroyed before rd_cvode_close_context):
 *     rd_cvode s = {0};
 *     if (rd_cvode_open(&s, deg_per_s, err)) goto out;    the context
 *     y = N_VNew_Serial(N, s.ctx); ...
 *     if (rd_cvode_create(&s, err)) goto out;             BDF, silent handler
 *     if ((flag = CVodeInit(s.cv, rhs, 0.0, y)) || ...) return rd_cvode_misuse(&s, flag, "set-up", err);
 *     flag = CVode(s.cv, tout, y, &t, CV_NORMAL);
 *     if (flag < 0) return rd_cvode_failure(&s, flag, t_reached, &limit, err);
 *   out:
 *     rd_cvode_close(&s);            CVodeFree
 *     N_VDestroy(y); ...
 *     rd_cvode_close_context(&s);    SUNContext_Free, last
 */
#ifndef RD_CVODE_H
#define RD_CVODE_H

#include <cvode/cvode.h>
#include <sundials/sundials_linearsolver.h>

#include "rd_error.h"

#define RD_CVODE_COUNTERS 8

typedef struct rd_cvode {
    SUNContext ctx;
    void *cv;         /* CVODE's memory */
    double deg_per_s; /* crank degrees per second of the integrated time */
    char msg[200];    /* CVODE's last error message */
} rd_cvode;

/* What an exhausted step budget is reported as (rd_cvode_failure). */
typedef struct rd_cvode_limit {
    const char *analysis; /* "lift", "ring-pack": "the <analysis> integration failed" */
    const char *motion;   /* "ring's motion": "the <motion> needs more work than allowed" */
    long max_steps;       /* the budget, /numerics/max_steps */
    double total_deg;     /* the crank angle the run was to reach */
    long steps;           /* the steps taken (the caller's count, over restarts) */
} rd_cvode_limit;

/* The context (s zeroed by the caller); RD_ENOMEM. */
int rd_cvode_open(rd_cvode *s, double deg_per_s, rd_error *err);
/* The BDF solver with the silent handler; RD_ENOMEM, RD_EINTERNAL. */
int rd_cvode_create(rd_cvode *s, rd_error *err);
/* Frees the solver (not the context); s->cv NULL after.  NULL-safe. */
void rd_cvode_close(rd_cvode *s);
/* Frees the context: after every vector, matrix and solver made with it. */
void rd_cvode_close_context(rd_cvode *s);

/* A set-up, query or restart call failed (misuse): RD_EINTERNAL. */
int rd_cvode_misuse(const rd_cvode *s, int flag, const char *what, rd_error *err);
/* The integration failed with `flag` (< 0) at time t (s, the integrator's
 * own): RD_ELIMIT or RD_ENOCONV, dated at its crank angle. */
int rd_cvode_failure(const rd_cvode *s, int flag, double t, const rd_cvode_limit *lim,
                     rd_error *err);
/* What a failure flag means, in words. */
const char *rd_cvode_flag_words(int flag);

/* Counters since the last (re)start: steps, right-hand sides, Jacobians,
 * linear set-ups, Newton iterations, Newton failures, error-test failures,
 * root-function evaluations.  Returns CVODE's flag. */
int rd_cvode_counters(const rd_cvode *s, long c[RD_CVODE_COUNTERS]);

/* A linear solver of custom type with the given operations around
 * `content` (which its free op releases); NULL when content is NULL or out
 * of memory. */
SUNLinearSolver rd_linsol_wrap(SUNContext ctx, void *content,
                               const struct _generic_SUNLinearSolver_Ops *ops);

#endif
