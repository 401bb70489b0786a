/*
 * rd_lift_small.h — a one-step implicit integrator for the lift forms with
 * few states and one second-order block (the rigid model), with CVODE's
 * calling conventions so that the driver (rd_lift_driver.c) steps either
 * (rd_lift_small.c has the method, its error control and event location).
 *
 * Calls mirror CVODE's: solve to tout returns CV_SUCCESS (y at tout),
 * CV_ROOT_RETURN (y and t at the earliest root in an allowed direction;
 * root_info as CVodeGetRootInfo), CV_TOO_MUCH_WORK after max_steps steps in
 * one call (y at the integrator's time), or a CVODE failure flag
 * (CV_ERR_FAILURE, CV_CONV_FAILURE, CV_RHSFUNC_FAIL).
 */
#ifndef RD_LIFT_SMALL_H
#define RD_LIFT_SMALL_H

#include <cvode/cvode.h>

#include "rd_lift_model.h"

#define RD_LIFT_SMALL_BLOCK_MAX 8 /* positions of the form: N = 2 block <= 16 */
#define RD_LIFT_SMALL_ROOTS_MAX 8

typedef struct rd_lift_small rd_lift_small;

/* 1 if `form` can be integrated here: blocks of one row block (N = 2 block,
 * block <= RD_LIFT_SMALL_BLOCK_MAX). */
int rd_lift_small_usable(const rd_lift_form *form);

/* A new integrator at (t0, y0) (N values, copied) with tolerances rtol and
 * abstol (N values, copied), largest step hmax (s) and `ng` root functions
 * g(t, y, gout, user) with directions rootdir (CVODE's: +1 only increasing,
 * -1 only decreasing, 0 both).  `form` and `ctx` must outlive it.  NULL when
 * out of memory. */
rd_lift_small *rd_lift_small_create(const rd_lift_form *form, SUNContext ctx, double t0,
                                    const double *y0, double rtol, const double *abstol,
                                    double hmax, int ng, CVRootFn g, const int *rootdir,
                                    void *user);
void rd_lift_small_free(rd_lift_small *s);

/* Restarts at (t, y) (after a plastic landing): history and step size are
 * forgotten, the counters kept. */
int rd_lift_small_reinit(rd_lift_small *s, double t, const double *y);

void rd_lift_small_set_max_steps(rd_lift_small *s, long max_steps);

/* Integrates towards tout (CVODE's CV_NORMAL mode): *t and y (N values)
 * receive the time and state returned (header comment). */
int rd_lift_small_solve(rd_lift_small *s, double tout, double *y, double *t);

/* After CV_ROOT_RETURN: rf[i] = +1 (g_i increased through 0), -1
 * (decreased) or 0. */
void rd_lift_small_root_info(const rd_lift_small *s, int *rf);

/* The integrator's own time (the end of its last step), s. */
double rd_lift_small_time(const rd_lift_small *s);

/* Counters in rd_lift_result's order: steps, right-hand sides, Jacobians,
 * factorizations, Newton iterations, Newton failures, error-test failures,
 * root-function evaluations. */
void rd_lift_small_counters(const rd_lift_small *s, long *c);

#endif
