/*
 * rd_fit — weighted nonlinear least squares within bounds, with the
 * uncertainty and identifiability of the fitted parameters (issue 42).
 *
 * Finds x (p parameters, lo_j <= x_j <= hi_j) minimising
 *     chi^2(x) = sum_i r_i(x)^2,   r_i = (model_i(x) - y_i) / sigma_i,
 * over m >= p weighted residuals that the caller computes (the caller owns
 * the model, the data and the sigmas).  The solver is GSL's trust-region
 * Levenberg-Marquardt (gsl_multifit_nlinear, Moré's scaling, QR): a
 * maintained implementation of the method every curve-fitting tool uses,
 * where NLopt would treat chi^2 as a black box and throw away the
 * residuals' Jacobian that the uncertainty needs anyway.
 *
 * Bounds: GSL's solver has none, so it works on u with
 *     x = lo + (hi - lo) (1 + sin u) / 2
 * (the transform MINUIT documents): every u is inside the bounds and a
 * bound is reached at a finite u.  The Jacobian dr/dx is by forward
 * differences of the caller's residuals, step h_j = RD_FIT_REL_STEP
 * max(|x_j|, 0.01 (hi_j - lo_j)), taken backwards where x_j + h_j would
 * pass hi_j; it is never GSL's own (its 1.5e-8 steps are below the noise
 * of a solver's output).  All p + 1 points of one Jacobian are handed to
 * the caller in one batch, so it may run them in parallel.
 *
 * At the optimum, with J = dr/dx (columns scaled by s_j = max(|x_j|,
 * 0.01 (hi_j - lo_j)), singular values w_1 >= ... >= w_p):
 *   - covariance C = (J^T J)^-1 (the sigmas are taken as the data's
 *     standard deviations; chi2 / (m - p) near 1 says they were), standard
 *     errors sqrt(C_jj), correlations C_jk / sqrt(C_jj C_kk);
 *   - a direction with w_k < RD_FIT_RANK_TOL w_1 is one the data cannot
 *     fix (two parameters that enter only as a product, say): the
 *     parameters with |v_jk| >= 0.1 in it are marked `unidentified`, their
 *     standard error and correlations NaN (not a huge number), and C is the
 *     pseudo-inverse over the other directions;
 *   - a parameter whose standard error exceeds (hi - lo) / 4 (its +-2 sigma
 *     span more than its whole range) is marked `unidentified` too.
 *
 * Usage:
 *     rd_fit_problem fp = {.n_params = 2, .n_resid = m, .lo = lo, .hi = hi,
 *                          .start = x0, .eval = my_residuals, .ctx = &data};
 *     rd_fit_result res;
 *     int rc = rd_fit_solve(&fp, &res, &err);   // res valid when rc == RD_OK
 *     ... res.x[j], res.std_error[j], res.corr[j * p + k] ...
 *     rd_fit_result_cleanup(&res);
 */
#ifndef RD_FIT_H
#define RD_FIT_H

#include <stddef.h>

#include "rd_error.h"

#define RD_FIT_PARAMS_MAX 16
/* The forward-difference step, relative to the scale s_j: large enough that
 * a solver's own error in the residuals (rtol 1e-6 leaves ~1e-5 of a ring
 * pack's blow-by) stays ~1e-3 of the differences (at 1e-3 the Jacobian of a
 * correlated ring-pack fit was wrong enough to crawl 69 iterations where
 * this takes 7); its truncation error, ~h f''/(2 f') ~ 0.5 %, moves the
 * standard errors by that much and the optimum not at all. */
#define RD_FIT_REL_STEP 1e-2
#define RD_FIT_RANK_TOL 1e-7 /* w_k / w_1 below this: a direction the data cannot fix */

/* Evaluates the weighted residuals at `n_points` parameter vectors at once:
 * x[k] (n_params values) -> r[k] (n_resid values), k < n_points.  Returns
 * RD_OK, or an error status with `err` filled (the fit stops with it). */
typedef int (*rd_fit_eval_fn)(void *ctx, size_t n_points, const double *const *x, double *const *r,
                              rd_error *err);

typedef struct rd_fit_problem {
    size_t n_params;               /* p, 1..RD_FIT_PARAMS_MAX */
    size_t n_resid;                /* m >= p */
    const double *lo, *hi, *start; /* p values each: lo < hi, lo <= start <= hi */
    rd_fit_eval_fn eval;
    void *ctx;
    size_t max_points;     /* at most this many parameter vectors evaluated (0: 50 (p + 1)) */
    double xtol;           /* converged when a step moves every x_j by <= xtol s_j (0: 1e-8) */
    double gtol;           /* ... or the scaled gradient is below gtol (0: 1e-10) */
    double ftol;           /* ... or a step lowers chi^2 by <= ftol max(1, chi^2); 0: not used */
    double stol;           /* ... or a step moves every x_j by <= stol of its standard error
                    (from the Jacobian there); 0: not used */
    const rd_monitor *mon; /* progress (points used / max_points) and cancel; may be NULL */
} rd_fit_problem;

/* Why the fit stopped (all but RD_FIT_BUDGET are convergence). */
enum rd_fit_stop {
    RD_FIT_STEP,       /* the step fell below xtol or stol standard errors, or chi^2's fall
                          below ftol */
    RD_FIT_GRADIENT,   /* the gradient fell below gtol */
    RD_FIT_EXACT,      /* chi^2 below 1e-28 m: the data fitted exactly */
    RD_FIT_NOPROGRESS, /* no step lowers chi^2 any more (the noise of the residuals) */
    RD_FIT_BUDGET      /* max_points were used: not converged */
};

typedef struct rd_fit_result {
    size_t n_params, n_resid;
    double *x;         /* p fitted values (malloc'd) */
    double *std_error; /* p, NaN where unidentified */
    double *corr;      /* p x p row-major correlations, NaN where unidentified */
    int *unidentified; /* p flags: 1 = the data cannot fix it (above) */
    int *at_bound;     /* p flags: -1 at lo, +1 at hi, 0 inside */
    double *resid;     /* m weighted residuals at x */
    double chi2;
    double cond;      /* w_1 / w_p of the scaled Jacobian (inf when rank-deficient) */
    int identifiable; /* no parameter unidentified */
    int iterations;
    size_t points; /* parameter vectors evaluated (each is one call's worth of residuals) */
    enum rd_fit_stop stop;
} rd_fit_result;

/* Solves the problem.  RD_OK with *res filled (also when stopped by the
 * budget: res->stop says so); RD_EINVAL for a malformed problem (bounds,
 * sizes: the message names the parameter index), the eval's own error,
 * RD_ECANCELED, RD_ENOMEM, RD_ENUMERIC (GSL failed).  On error *res holds
 * nothing to free. */
int rd_fit_solve(const rd_fit_problem *fp, rd_fit_result *res, rd_error *err);
void rd_fit_result_cleanup(rd_fit_result *res);

/* "step", "gradient", "exact", "no_progress", "budget". */
const char *rd_fit_stop_name(enum rd_fit_stop stop);

#endif
