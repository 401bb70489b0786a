/*
 * rd_accuracy — the one accuracy driver of ringdyn: "solve at the user's
 * settings S, solve again at refined settings S', report the estimate (a
 * difference, or Richardson extrapolation) with the cost of both".
 *
 * Every analysis estimates its own error this way; what differs between them
 * is only what "refined" means (2n segments, rtol/10, more modes) and how the
 * two answers are compared.  The analysis supplies both as callbacks; the
 * driver owns the rest: the split of progress between the two solves (each
 * solve sees a monitor that reports 0..1 of its own work), the timing, the
 * wording of a failed reference solve, and the order of calls.
 *
 * Use:
 *     rd_accuracy_plan plan = {.solve = my_solve, .compare = my_compare,
 *                              .ctx = &my_state, .estimate = opts->estimate_error,
 *                              .main_share = 0.34, .reference = "2n segments"};
 *     rc = rd_accuracy_run(&plan, mon, &cost, err);
 *
 * Level 0 is always solved first, with the caller's rd_error: its failure is
 * the run's failure, unchanged.  Level 1 (only when plan.estimate) is solved
 * with a private rd_error; a failure there is reported as "The error-estimate
 * solve at <reference> failed: <its message>" with its path and code (a
 * cancellation passes through unchanged).  compare() runs only when both
 * solves succeeded.  The callbacks keep their results in ctx; the driver
 * allocates nothing.
 */
#ifndef RD_ACCURACY_H
#define RD_ACCURACY_H

#include "rd_error.h"

/* One solve at fidelity `level` (0 = the scene's settings, 1 = the refined
 * reference).  `mon` reports 0..1 of this solve's own work.  Returns RD_OK or
 * a negative status with err filled. */
typedef int (*rd_accuracy_solve_fn)(void *ctx, int level, const rd_monitor *mon, rd_error *err);
/* Compares the two solves and stores the estimate in ctx.  May fail (an
 * internal inconsistency, out of memory). */
typedef int (*rd_accuracy_compare_fn)(void *ctx, rd_error *err);

typedef struct rd_accuracy_plan {
    rd_accuracy_solve_fn solve;
    rd_accuracy_compare_fn compare; /* may be NULL: nothing to compare */
    void *ctx;                      /* borrowed; passed to both callbacks */
    int estimate;                   /* 0: level 0 only */
    double main_share;              /* progress share of level 0 when estimating, (0, 1) */
    const char *reference;          /* what level 1 is, for messages ("2n segments") */
} rd_accuracy_plan;

/* What the two solves cost (wall clock, s; CPU time of the calling thread, s).
 * Level 1 is 0 when it did not run. */
typedef struct rd_accuracy_cost {
    double wall_s[2];
    double cpu_s[2];
} rd_accuracy_cost;

/* Runs the plan: see the file comment.  `cost` may be NULL. */
int rd_accuracy_run(const rd_accuracy_plan *plan, const rd_monitor *mon, rd_accuracy_cost *cost,
                    rd_error *err);

/* Richardson extrapolation of a quantity that converges as f_n = f + C n^-p:
 * from f_n (at n) and f_m (at m != n) returns the extrapolated limit f and
 * stores in *rel_error the estimated relative error |f_n - f| / |f| of f_n
 * (NULL allowed).  A zero limit gives the absolute error instead. */
double rd_accuracy_richardson(double fn, int n, double fm, int m, double order, double *rel_error);

/* The segment count of a refined solve: 2n, or n/2 when 2n exceeds max_n. */
int rd_accuracy_refined_segments(int n, int max_n);

/* Wall-clock and thread CPU time now, in s (monotonic; for cost reports). */
double rd_accuracy_wall_now(void);
double rd_accuracy_cpu_now(void);

#endif
