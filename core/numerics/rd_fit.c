/*
 * rd_fit — weighted nonlinear least squares within bounds (rd_fit.h): GSL's
 * trust-region Levenberg-Marquardt on the unbounded u of
 * x = lo + (hi - lo) (1 + sin u) / 2, the Jacobian by batched forward
 * differences in x, then the covariance and identifiability from the SVD of
 * the column-scaled Jacobian at the optimum.
 */
#include "rd_fit.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* The status our callbacks return to GSL when the caller's eval failed or
 * the budget is spent (GSL passes it up from iterate unchanged). */
#define EVAL_STOP GSL_EBADFUNC

typedef struct fit_ctx {
    const rd_fit_problem *fp;
    size_t p, m;
    double *x;      /* scratch: x of the point being evaluated, p */
    double *xs;     /* the p + 1 points of a batch, (p + 1) x p */
    double *rs;     /* their residuals, (p + 1) x m */
    double *last_x; /* the last point whose residuals are known, p */
    double *last_r; /* its residuals, m */
    int have_last;
    double *jac;   /* dr/dx at jac_x, m x p row-major */
    double *jac_x; /* p */
    int have_jac;
    size_t points;
    int budget_spent;
    rd_error *err;
} fit_ctx;

static void once_errors_off(void)
{
    gsl_set_error_handler_off();
}

static double x_of_u(const rd_fit_problem *fp, size_t j, double u)
{
    double x = fp->lo[j] + (fp->hi[j] - fp->lo[j]) * 0.5 * (1.0 + sin(u));
    return fmin(fp->hi[j], fmax(fp->lo[j], x));
}

static double dx_du(const rd_fit_problem *fp, size_t j, double u)
{
    return (fp->hi[j] - fp->lo[j]) * 0.5 * cos(u);
}

static double u_of_x(const rd_fit_problem *fp, size_t j, double x)
{
    double t = 2.0 * (x - fp->lo[j]) / (fp->hi[j] - fp->lo[j]) - 1.0;
    return asin(fmin(1.0, fmax(-1.0, t)));
}

/* s_j: the scale of a parameter (its step, its Jacobian column's scale). */
static double scale_of(const rd_fit_problem *fp, size_t j, double x)
{
    return fmax(fabs(x), 0.01 * (fp->hi[j] - fp->lo[j]));
}

/* Evaluates n points of c->xs into c->rs, counting them and reporting. */
static int eval_batch(fit_ctx *c, size_t n)
{
    const double *xp[RD_FIT_PARAMS_MAX + 1];
    double *rp[RD_FIT_PARAMS_MAX + 1];
    for (size_t k = 0; k < n; k++) {
        xp[k] = c->xs + k * c->p;
        rp[k] = c->rs + k * c->m;
    }
    int rc = c->fp->eval(c->fp->ctx, n, xp, rp, c->err);
    c->points += n;
    if (rc == RD_OK) {
        for (size_t k = 0; k < n * c->m; k++)
            if (!isfinite(c->rs[k]))
                rc = rd_error_set(c->err, RD_ENUMERIC, "",
                                  "a residual of the fit is not finite (NaN or inf) at "
                                  "evaluation %zu",
                                  c->points);
    }
    if (rc == RD_OK)
        rc = rd_monitor_report(c->fp->mon, (double)c->points / (double)c->fp->max_points, c->err);
    return rc;
}

static void remember(fit_ctx *c, const double *x, const double *r)
{
    memcpy(c->last_x, x, c->p * sizeof *x);
    memcpy(c->last_r, r, c->m * sizeof *r);
    c->have_last = 1;
}

/* GSL's f: the residuals at u.  Keeps room in the budget for the Jacobian
 * that follows an accepted step. */
static int gsl_f(const gsl_vector *u, void *params, gsl_vector *f)
{
    fit_ctx *c = params;
    if (c->points + 1 + c->p > c->fp->max_points) {
        c->budget_spent = 1;
        return EVAL_STOP;
    }
    for (size_t j = 0; j < c->p; j++)
        c->xs[j] = x_of_u(c->fp, j, gsl_vector_get(u, j));
    if (eval_batch(c, 1) != RD_OK)
        return EVAL_STOP;
    remember(c, c->xs, c->rs);
    for (size_t i = 0; i < c->m; i++)
        gsl_vector_set(f, i, c->rs[i]);
    return GSL_SUCCESS;
}

/* dr/dx at x (p values) into c->jac: one batch of the p steps (and x itself
 * when its residuals are not the last ones known). */
static int jacobian_at(fit_ctx *c, const double *x)
{
    const rd_fit_problem *fp = c->fp;
    size_t p = c->p, m = c->m, base = 0;
    int known = c->have_last && memcmp(c->last_x, x, p * sizeof *x) == 0;
    double h[RD_FIT_PARAMS_MAX];
    if (!known) {
        memcpy(c->xs, x, p * sizeof *x);
        base = 1;
    }
    for (size_t j = 0; j < p; j++) {
        double *xj = c->xs + (base + j) * p;
        memcpy(xj, x, p * sizeof *x);
        h[j] = RD_FIT_REL_STEP * scale_of(fp, j, x[j]);
        if (x[j] + h[j] > fp->hi[j])
            h[j] = -h[j];
        xj[j] = x[j] + h[j];
        h[j] = xj[j] - x[j]; /* the step actually taken */
    }
    if (eval_batch(c, base + p) != RD_OK)
        return EVAL_STOP;
    if (!known)
        remember(c, x, c->rs);
    for (size_t j = 0; j < p; j++)
        for (size_t i = 0; i < m; i++)
            c->jac[i * p + j] = (c->rs[(base + j) * m + i] - c->last_r[i]) / h[j];
    memcpy(c->jac_x, x, p * sizeof *x);
    c->have_jac = 1;
    return GSL_SUCCESS;
}

/* GSL's df: dr/du = dr/dx dx/du. */
static int gsl_df(const gsl_vector *u, void *params, gsl_matrix *J)
{
    fit_ctx *c = params;
    for (size_t j = 0; j < c->p; j++)
        c->x[j] = x_of_u(c->fp, j, gsl_vector_get(u, j));
    if (jacobian_at(c, c->x) != GSL_SUCCESS)
        return EVAL_STOP;
    for (size_t i = 0; i < c->m; i++)
        for (size_t j = 0; j < c->p; j++)
            gsl_matrix_set(J, i, j, c->jac[i * c->p + j] * dx_du(c->fp, j, gsl_vector_get(u, j)));
    return GSL_SUCCESS;
}

static int check_problem(const rd_fit_problem *fp, rd_error *err)
{
    if (fp->n_params < 1 || fp->n_params > RD_FIT_PARAMS_MAX)
        return rd_error_set(err, RD_EINVAL, "", "a fit has 1 to %d parameters, not %zu",
                            RD_FIT_PARAMS_MAX, fp->n_params);
    if (fp->n_resid < fp->n_params)
        return rd_error_set(err, RD_EINVAL, "",
                            "a fit of %zu parameters needs at least as many measured values, "
                            "not %zu",
                            fp->n_params, fp->n_resid);
    for (size_t j = 0; j < fp->n_params; j++) {
        double lo = fp->lo[j], hi = fp->hi[j], x0 = fp->start[j];
        if (!(isfinite(lo) && isfinite(hi) && lo < hi))
            return rd_error_set(err, RD_EINVAL, "",
                                "parameter %zu: its bounds must be finite with min < max, not "
                                "min %g, max %g",
                                j, lo, hi);
        if (!(x0 >= lo && x0 <= hi))
            return rd_error_set(err, RD_EINVAL, "",
                                "parameter %zu: start %g is outside its bounds %g to %g", j, x0, lo,
                                hi);
    }
    return RD_OK;
}

static int result_alloc(rd_fit_result *res, size_t p, size_t m)
{
    memset(res, 0, sizeof *res);
    res->n_params = p;
    res->n_resid = m;
    res->x = calloc(p, sizeof *res->x);
    res->std_error = calloc(p, sizeof *res->std_error);
    res->corr = calloc(p * p, sizeof *res->corr);
    res->unidentified = calloc(p, sizeof *res->unidentified);
    res->at_bound = calloc(p, sizeof *res->at_bound);
    res->resid = calloc(m, sizeof *res->resid);
    if (res->x && res->std_error && res->corr && res->unidentified && res->at_bound && res->resid)
        return RD_OK;
    rd_fit_result_cleanup(res);
    return RD_ENOMEM;
}

void rd_fit_result_cleanup(rd_fit_result *res)
{
    if (!res)
        return;
    free(res->x);
    free(res->std_error);
    free(res->corr);
    free(res->unidentified);
    free(res->at_bound);
    free(res->resid);
    memset(res, 0, sizeof *res);
}

const char *rd_fit_stop_name(enum rd_fit_stop stop)
{
    static const char *const names[] = {"step", "gradient", "exact", "no_progress", "budget"};
    return (unsigned)stop < sizeof names / sizeof names[0] ? names[stop] : "unknown";
}

/* Covariance, standard errors, correlations and identifiability from the
 * Jacobian c->jac at res->x (rd_fit.h). */
static int uncertainty(const fit_ctx *c, rd_fit_result *res, rd_error *err)
{
    size_t p = c->p, m = c->m;
    int rc = RD_OK;
    double s[RD_FIT_PARAMS_MAX], cov[RD_FIT_PARAMS_MAX * RD_FIT_PARAMS_MAX] = {0};
    gsl_matrix *a = gsl_matrix_alloc(m, p), *v = gsl_matrix_alloc(p, p);
    gsl_vector *w = gsl_vector_alloc(p), *work = gsl_vector_alloc(p);
    if (!a || !v || !w || !work) {
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory for the fit's covariance");
        goto out;
    }
    for (size_t j = 0; j < p; j++)
        s[j] = scale_of(c->fp, j, res->x[j]);
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < p; j++)
            gsl_matrix_set(a, i, j, c->jac[i * p + j] * s[j]);
    if (gsl_linalg_SV_decomp(a, v, w, work) != GSL_SUCCESS) {
        rc = rd_error_set(err, RD_ENUMERIC, "", "the SVD of the fit's Jacobian failed");
        goto out;
    }
    double w1 = gsl_vector_get(w, 0), wp = gsl_vector_get(w, p - 1);
    res->cond = wp > 0 ? w1 / wp : INFINITY;
    for (size_t k = 0; k < p; k++) {
        double wk = gsl_vector_get(w, k);
        int null = !(w1 > 0) || wk < RD_FIT_RANK_TOL * w1;
        for (size_t j = 0; j < p; j++) {
            if (null) {
                if (fabs(gsl_matrix_get(v, j, k)) >= 0.1)
                    res->unidentified[j] = 1;
                continue;
            }
            for (size_t l = 0; l < p; l++)
                cov[j * p + l] += gsl_matrix_get(v, j, k) * gsl_matrix_get(v, l, k) / (wk * wk);
        }
    }
    for (size_t j = 0; j < p; j++) {
        double sd = sqrt(cov[j * p + j]) * s[j];
        if (sd > 0.25 * (c->fp->hi[j] - c->fp->lo[j]))
            res->unidentified[j] = 1;
        res->std_error[j] = res->unidentified[j] ? NAN : sd;
    }
    res->identifiable = 1;
    for (size_t j = 0; j < p; j++) {
        res->identifiable &= !res->unidentified[j];
        for (size_t l = 0; l < p; l++) {
            double d = cov[j * p + j] * cov[l * p + l];
            res->corr[j * p + l] = res->unidentified[j] || res->unidentified[l] || !(d > 0)
                                       ? NAN
                                       : cov[j * p + l] / sqrt(d);
        }
    }
out:
    gsl_matrix_free(a);
    gsl_matrix_free(v);
    gsl_vector_free(w);
    gsl_vector_free(work);
    return rc;
}

/* Did the last step dx move every parameter by at most stol of its
 * standard error (the covariance from GSL's Jacobian at u, mapped to x)? */
static int below_errors(const fit_ctx *c, gsl_multifit_nlinear_workspace *w, const double *dx)
{
    if (!(c->fp->stol > 0))
        return 0;
    gsl_matrix *cov = gsl_matrix_alloc(c->p, c->p);
    gsl_vector *u = gsl_multifit_nlinear_position(w);
    int ok = cov && gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, cov) == 0;
    for (size_t j = 0; ok && j < c->p; j++) {
        double sd = fabs(dx_du(c->fp, j, gsl_vector_get(u, j))) * sqrt(gsl_matrix_get(cov, j, j));
        ok = isfinite(sd) && fabs(dx[j]) <= c->fp->stol * sd;
    }
    gsl_matrix_free(cov);
    return ok;
}

/* Iterates until a convergence test, the budget or an error.  The step
 * test is on x, relative to each parameter's scale (GSL's own is on u). */
static int iterate(fit_ctx *c, gsl_multifit_nlinear_workspace *w, double xtol, double gtol,
                   rd_fit_result *res)
{
    double prev[RD_FIT_PARAMS_MAX];
    gsl_vector *u = gsl_multifit_nlinear_position(w);
    for (size_t j = 0; j < c->p; j++)
        prev[j] = x_of_u(c->fp, j, gsl_vector_get(u, j));
    double last = INFINITY;
    for (;;) {
        double chi2 = 0;
        gsl_vector *f = gsl_multifit_nlinear_residual(w);
        for (size_t i = 0; i < c->m; i++)
            chi2 += gsl_vector_get(f, i) * gsl_vector_get(f, i);
        if (c->fp->ftol > 0 && last - chi2 <= c->fp->ftol * fmax(1.0, chi2)) {
            res->stop = RD_FIT_STEP;
            return RD_OK;
        }
        last = chi2;
        if (chi2 < 1e-28 * (double)c->m) {
            res->stop = RD_FIT_EXACT;
            return RD_OK;
        }
        int status = gsl_multifit_nlinear_iterate(w);
        res->iterations++;
        if (c->budget_spent) {
            res->stop = RD_FIT_BUDGET;
            return RD_OK;
        }
        if (status == EVAL_STOP)
            return c->err->code != RD_OK
                       ? c->err->code
                       : rd_error_set(c->err, RD_EINTERNAL, "", "the fit's residuals failed");
        if (status == GSL_ENOPROG) {
            res->stop = RD_FIT_NOPROGRESS;
            return RD_OK;
        }
        if (status != GSL_SUCCESS)
            return rd_error_set(c->err, RD_ENUMERIC, "", "the least-squares solver failed: %s",
                                gsl_strerror(status));
        double step = 0, dx[RD_FIT_PARAMS_MAX];
        for (size_t j = 0; j < c->p; j++) {
            double x = x_of_u(c->fp, j, gsl_vector_get(u, j));
            dx[j] = x - prev[j];
            step = fmax(step, fabs(dx[j]) / scale_of(c->fp, j, x));
            prev[j] = x;
        }
        if (step <= xtol || below_errors(c, w, dx)) {
            res->stop = RD_FIT_STEP;
            return RD_OK;
        }
        int info = 0;
        gsl_multifit_nlinear_test(0.0, gtol, 0.0, &info, w);
        if (info == 2) {
            res->stop = RD_FIT_GRADIENT;
            return RD_OK;
        }
    }
}

static void ctx_free(fit_ctx *c)
{
    free(c->x);
    free(c->xs);
    free(c->rs);
    free(c->last_x);
    free(c->last_r);
    free(c->jac);
    free(c->jac_x);
}

static int ctx_alloc(fit_ctx *c, const rd_fit_problem *fp, rd_error *err)
{
    size_t p = fp->n_params, m = fp->n_resid;
    memset(c, 0, sizeof *c);
    c->fp = fp;
    c->p = p;
    c->m = m;
    c->err = err;
    if (m > ((size_t)1 << 40) / (p + 1))
        return rd_error_set(err, RD_EINVAL, "", "a fit of %zu residuals is too large", m);
    c->x = calloc(p, sizeof *c->x);
    c->xs = calloc((p + 1) * p, sizeof *c->xs);
    c->rs = calloc((p + 1) * m, sizeof *c->rs);
    c->last_x = calloc(p, sizeof *c->last_x);
    c->last_r = calloc(m, sizeof *c->last_r);
    c->jac = calloc(m * p, sizeof *c->jac);
    c->jac_x = calloc(p, sizeof *c->jac_x);
    if (c->x && c->xs && c->rs && c->last_x && c->last_r && c->jac && c->jac_x)
        return RD_OK;
    return rd_error_set(err, RD_ENOMEM, "", "out of memory for a fit of %zu residuals", m);
}

/* The fitted x, bounds reached and residuals; the Jacobian there if the
 * last one was taken elsewhere. */
static int finish(fit_ctx *c, gsl_multifit_nlinear_workspace *w, rd_fit_result *res)
{
    gsl_vector *u = gsl_multifit_nlinear_position(w), *f = gsl_multifit_nlinear_residual(w);
    for (size_t j = 0; j < c->p; j++) {
        double uj = gsl_vector_get(u, j);
        res->x[j] = x_of_u(c->fp, j, uj);
        double near = 1e-6 * (c->fp->hi[j] - c->fp->lo[j]);
        res->at_bound[j] = res->x[j] <= c->fp->lo[j] + near   ? -1
                           : res->x[j] >= c->fp->hi[j] - near ? 1
                                                              : 0;
        if (res->at_bound[j]) /* within 1e-6 of the range: the bound itself */
            res->x[j] = res->at_bound[j] < 0 ? c->fp->lo[j] : c->fp->hi[j];
    }
    res->chi2 = 0;
    for (size_t i = 0; i < c->m; i++) {
        res->resid[i] = gsl_vector_get(f, i);
        res->chi2 += res->resid[i] * res->resid[i];
    }
    /* x snapped to a bound (or moved since the last Jacobian): the Jacobian
     * there, after which the residuals at x are the last ones known (found
     * or evaluated by jacobian_at); they replace GSL's at the unsnapped u. */
    if (!c->have_jac || memcmp(c->jac_x, res->x, c->p * sizeof *res->x) != 0) {
        if (jacobian_at(c, res->x) != GSL_SUCCESS)
            return c->err->code != RD_OK ? c->err->code : RD_EINTERNAL;
        res->chi2 = 0;
        for (size_t i = 0; i < c->m; i++) {
            res->resid[i] = c->last_r[i];
            res->chi2 += res->resid[i] * res->resid[i];
        }
    }
    res->points = c->points;
    return uncertainty(c, res, c->err);
}

int rd_fit_solve(const rd_fit_problem *fp_in, rd_fit_result *res, rd_error *err)
{
    static pthread_once_t once = PTHREAD_ONCE_INIT;
    pthread_once(&once, once_errors_off);
    memset(res, 0, sizeof *res);
    int rc = check_problem(fp_in, err);
    if (rc != RD_OK)
        return rc;
    rd_fit_problem fp = *fp_in;
    size_t p = fp.n_params, m = fp.n_resid;
    if (fp.max_points == 0)
        fp.max_points = 50 * (p + 1);
    double xtol = fp.xtol > 0 ? fp.xtol : 1e-8, gtol = fp.gtol > 0 ? fp.gtol : 1e-10;
    fit_ctx c;
    gsl_multifit_nlinear_workspace *w = NULL;
    gsl_vector *u0 = NULL;
    rc = ctx_alloc(&c, &fp, err);
    if (rc == RD_OK && result_alloc(res, p, m) != RD_OK)
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory for the fit's result");
    if (rc != RD_OK)
        goto out;
    gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
    par.trs = gsl_multifit_nlinear_trs_lm;
    par.scale = gsl_multifit_nlinear_scale_more;
    par.solver = gsl_multifit_nlinear_solver_qr;
    gsl_multifit_nlinear_fdf fdf = {.f = gsl_f, .df = gsl_df, .n = m, .p = p, .params = &c};
    w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, m, p);
    u0 = gsl_vector_alloc(p);
    if (!w || !u0) {
        rc = rd_error_set(err, RD_ENOMEM, "", "out of memory for the least-squares solver");
        goto out;
    }
    for (size_t j = 0; j < p; j++)
        gsl_vector_set(u0, j, u_of_x(&fp, j, fp.start[j]));
    int status = gsl_multifit_nlinear_init(u0, &fdf, w);
    if (status != GSL_SUCCESS) {
        rc = err->code != RD_OK ? err->code
             : c.budget_spent
                 ? rd_error_set(err, RD_EINVAL, "",
                                "a budget of %zu evaluations cannot hold the first Jacobian (%zu)",
                                fp.max_points, p + 1)
                 : rd_error_set(err, RD_ENUMERIC, "", "the least-squares solver failed: %s",
                                gsl_strerror(status));
        goto out;
    }
    rc = iterate(&c, w, xtol, gtol, res);
    if (rc == RD_OK)
        rc = finish(&c, w, res);
out:
    if (rc != RD_OK)
        rd_fit_result_cleanup(res);
    gsl_multifit_nlinear_free(w);
    gsl_vector_free(u0);
    ctx_free(&c);
    return rc;
}
