/*
 * rd_calibration_run — a checked calibration's fit (rd_fit) and its result
 * object (rd_calibration.h):
 *   {"analysis": "calibration",
 *    "parameters": [{"path", "value", "std_error", "start", "min", "max",
 *                    "at_bound": null | "min" | "max", "identifiable"}],
 *    "correlation": p x p (null where a parameter is not identifiable),
 *    "residuals": one per measurement, in sigmas (signed for one value, the
 *                 root mean square of an array's),
 *    "measurements": [{"observe", "set", "measured", "fitted", "residual"}],
 *    "chi2", "dof", "converged", "stop", "identifiable", "runs",
 *    "notes": [...], "numerics": {"runs", "evaluations", "iterations",
 *    "threads", "cond"}}.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rd_calibration.h"
#include "rd_json.h"

typedef struct eval_ctx {
    const struct rd_calibration *c;
    const rd_monitor *mon;
    size_t evaluations, max_points;
    const char *ptrs[RD_FIT_PARAMS_MAX];
} eval_ctx;

/* The failure of measurement j's run at parameters x, named. */
static int run_error(const eval_ctx *e, size_t j, const double *x, const rd_study_run *r,
                     rd_error *err)
{
    char at[64], vals[256];
    size_t n = 0;
    vals[0] = '\0';
    for (size_t k = 0; k < e->c->np && n < sizeof vals; k++)
        n += (size_t)snprintf(vals + n, sizeof vals - n, "%s%s = %.6g", k ? ", " : "",
                              e->c->p[k].path, x[k]);
    snprintf(at, sizeof at, "/measurements/%zu", j);
    return rd_error_set(err, r->rc == RD_ECANCELED ? RD_ECANCELED : r->rc, at,
                        "measurement %zu's scene failed at %s: %s%s%s", j, vals,
                        r->err.path[0] ? r->err.path : "", r->err.path[0] ? ": " : "",
                        r->err.message);
}

/* Measurement j's residuals from its run's result into r. */
static int residuals_of(const struct rd_calibration *c, size_t j, json_t *result, double *r,
                        rd_error *err)
{
    const struct rd_calibration_meas *m = &c->m[j];
    size_t got = 0;
    char at[64];
    snprintf(at, sizeof at, "/measurements/%zu/observe", j);
    if (rd_study_values(result, m->observe, r, m->n, &got) != 0 || got != m->n)
        return rd_error_set(err, RD_EINVAL, at,
                            "%s = \"%s\" names %s in the result, where value has %zu number%s", at,
                            m->observe, got ? "a different count of numbers" : "no number", m->n,
                            m->n == 1 ? "" : "s");
    for (size_t i = 0; i < m->n; i++)
        r[i] = (r[i] - m->value[i]) / m->sigma[i];
    return RD_OK;
}

static int eval(void *ctx, size_t n_points, const double *const *x, double *const *r, rd_error *err)
{
    eval_ctx *e = ctx;
    const struct rd_calibration *c = e->c;
    size_t ng = c->ng, nr = n_points * ng;
    rd_study_run *runs = calloc(nr, sizeof *runs);
    int rc = runs ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory for the runs");
    for (size_t k = 0; k < nr && rc == RD_OK; k++)
        rc = rd_study_scene(&c->base, c->m[c->group_meas[k % ng]].set, e->ptrs, x[k / ng], c->np,
                            &runs[k].scene, err);
    double fraction = (double)e->evaluations / (double)e->max_points;
    if (rc == RD_OK)
        rc = rd_study_run_batch(&c->base, runs, nr, c->threads, e->mon, fraction, err);
    for (size_t k = 0; k < n_points && rc == RD_OK; k++)
        for (size_t j = 0, off = 0; j < c->nm && rc == RD_OK; off += c->m[j++].n) {
            const rd_study_run *run = &runs[k * ng + c->m[j].group];
            rc = run->rc != RD_OK ? run_error(e, j, x[k], run, err)
                                  : residuals_of(c, j, run->result, r[k] + off, err);
        }
    for (size_t k = 0; runs && k < nr; k++) {
        json_decref(runs[k].scene);
        json_decref(runs[k].result);
    }
    free(runs);
    e->evaluations += n_points;
    return rc;
}

static json_t *real_or_null(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

static json_t *parameters_json(const struct rd_calibration *c, const rd_fit_result *f)
{
    json_t *a = json_array();
    for (size_t i = 0; a && i < c->np; i++) {
        const char *bound = f->at_bound[i] < 0 ? "min" : f->at_bound[i] > 0 ? "max" : NULL;
        json_array_append_new(a, json_pack("{s:s, s:o, s:o, s:f, s:f, s:f, s:o, s:b}", "path",
                                           c->p[i].path, "value", json_real(f->x[i]), "std_error",
                                           real_or_null(f->std_error[i]), "start", c->p[i].start,
                                           "min", c->p[i].min, "max", c->p[i].max, "at_bound",
                                           bound ? json_string(bound) : json_null(), "identifiable",
                                           !f->unidentified[i]));
    }
    return a;
}

static json_t *correlation_json(const rd_fit_result *f)
{
    json_t *a = json_array();
    for (size_t i = 0; a && i < f->n_params; i++) {
        json_t *row = json_array();
        for (size_t k = 0; row && k < f->n_params; k++)
            json_array_append_new(row, real_or_null(f->corr[i * f->n_params + k]));
        json_array_append_new(a, row);
    }
    return a;
}

/* "residuals" and "measurements": fitted = value + sigma r. */
static int measurements_json(const struct rd_calibration *c, const rd_fit_result *f, json_t *out)
{
    json_t *res = json_array(), *ms = json_array();
    size_t off = 0;
    for (size_t j = 0; res && ms && j < c->nm; j++) {
        const struct rd_calibration_meas *m = &c->m[j];
        json_t *meas = json_array(), *fit = json_array();
        double ss = 0;
        for (size_t i = 0; meas && fit && i < m->n; i++) {
            double r = f->resid[off + i];
            ss += r * r;
            json_array_append_new(meas, json_real(m->value[i]));
            json_array_append_new(fit, json_real(m->value[i] + m->sigma[i] * r));
        }
        double rj = m->n == 1 ? f->resid[off] : sqrt(ss / (double)m->n);
        int scalar = m->n == 1;
        json_array_append_new(res, json_real(rj));
        json_array_append_new(
            ms, json_pack("{s:s, s:O, s:o, s:o, s:f}", "observe", m->observe, "set",
                          m->set ? m->set : json_null(), "measured",
                          scalar ? json_incref(json_array_get(meas, 0)) : json_incref(meas),
                          "fitted", scalar ? json_incref(json_array_get(fit, 0)) : json_incref(fit),
                          "residual", rj));
        json_decref(meas);
        json_decref(fit);
        off += m->n;
    }
    return json_object_set_new(out, "residuals", res) |
           json_object_set_new(out, "measurements", ms);
}

/* The notes: what the numbers do not cover, and what the fit found. */
static json_t *notes_json(const struct rd_calibration *c, const rd_fit_result *f, double dof)
{
    json_t *n = json_array();
    char s[600];
    json_array_append_new(n, json_string("Standard errors and correlations are linearised at the "
                                         "optimum with the sigmas as given: they cover the "
                                         "measurements' noise, not the model's own error or an "
                                         "effect the model lacks."));
    if (f->stop == RD_FIT_BUDGET) {
        snprintf(s, sizeof s,
                 "Not converged: the fit used its /numerics/max_runs (%d) first; the "
                 "values are the best found so far.",
                 c->max_runs);
        json_array_append_new(n, json_string(s));
    }
    double red = dof > 0 ? f->chi2 / dof : NAN;
    if (dof > 0 && (red > 4 || red < 0.25)) {
        snprintf(s, sizeof s, "chi2/dof = %.3g: %s", red,
                 red > 4 ? "the fit misses the data by more than the sigmas allow (an effect the "
                           "model lacks, or sigmas too small); the standard errors assume the "
                           "sigmas"
                         : "the data scatter less than the sigmas say (sigmas too large?)");
        json_array_append_new(n, json_string(s));
    }
    for (size_t i = 0; i < c->np; i++) {
        if (f->unidentified[i]) {
            snprintf(s, sizeof s,
                     "%s is not identifiable: %s; fix it in the base or add "
                     "measurements that separate it.",
                     c->p[i].path,
                     isfinite(f->cond) && f->cond < 1 / RD_FIT_RANK_TOL
                         ? "its +-2 standard errors would span more than its whole range"
                         : "the measurements fix only a combination of it with another "
                           "parameter (the Jacobian's columns are dependent)");
            json_array_append_new(n, json_string(s));
        }
        if (f->at_bound[i]) {
            snprintf(s, sizeof s,
                     "%s stopped at its %s (%g): the data would move it further; "
                     "its standard error treats it as free.",
                     c->p[i].path, f->at_bound[i] < 0 ? "min" : "max", f->x[i]);
            json_array_append_new(n, json_string(s));
        }
    }
    return n;
}

int rd_calibration_run(const struct rd_calibration *c, const rd_monitor *mon, json_t **result,
                       rd_error *err)
{
    eval_ctx e = {.c = c, .mon = mon, .max_points = (size_t)c->max_runs / c->ng};
    double lo[RD_FIT_PARAMS_MAX], hi[RD_FIT_PARAMS_MAX], x0[RD_FIT_PARAMS_MAX];
    for (size_t i = 0; i < c->np; i++) {
        e.ptrs[i] = c->p[i].path;
        lo[i] = c->p[i].min;
        hi[i] = c->p[i].max;
        x0[i] = c->p[i].start;
    }
    rd_fit_problem fp = {.n_params = c->np,
                         .n_resid = c->n_values,
                         .lo = lo,
                         .hi = hi,
                         .start = x0,
                         .eval = eval,
                         .ctx = &e,
                         .max_points = e.max_points,
                         .xtol = 1e-9,
                         .gtol = 1e-10,
                         .stol = 1e-2,
                         .ftol = 1e-8};
    rd_fit_result f;
    *result = NULL;
    int rc = rd_fit_solve(&fp, &f, err);
    if (rc != RD_OK)
        return rc;
    double dof = (double)c->n_values - (double)c->np;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    int threads = c->threads > 0 ? c->threads : cpus > 0 ? (int)cpus : 1;
    json_t *r = json_pack(
        "{s:s, s:o, s:o, s:f, s:f, s:b, s:s, s:b, s:I, s:o, s:{s:I, s:I, s:i, s:i, s:o}}",
        "analysis", "calibration", "parameters", parameters_json(c, &f), "correlation",
        correlation_json(&f), "chi2", f.chi2, "dof", dof, "converged", f.stop != RD_FIT_BUDGET,
        "stop", rd_fit_stop_name(f.stop), "identifiable", f.identifiable, "runs",
        (json_int_t)(f.points * c->ng), "notes", notes_json(c, &f, dof), "numerics", "runs",
        (json_int_t)(f.points * c->ng), "evaluations", (json_int_t)f.points, "iterations",
        f.iterations, "threads", threads, "cond", real_or_null(f.cond));
    if (r && measurements_json(c, &f, r) != 0) {
        json_decref(r);
        r = NULL;
    }
    rd_fit_result_cleanup(&f);
    *result = r;
    return r ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory for the result");
}
