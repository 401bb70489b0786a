/*
 * test_fit — rd_fit against closed forms: an exponential recovered exactly,
 * the straight line's covariance written out (weighted normal equations),
 * the coverage of the standard errors over seeded noisy trials, a product
 * the data cannot split, a bound that holds, the budget, bad problems.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "rd_fit.h"
#include "seeded_normal.h"

#define NT 20

typedef struct data {
    double t[NT], y[NT], sigma[NT];
    int n;
    int model;      /* 0 line a + b t, 1 a exp(-l t) + c, 2 a b t, 3 Rosenbrock */
    int fail_after; /* > 0: the eval fails at this call */
    int calls;
} data;

static double model_at(const data *d, const double *x, int i)
{
    double t = d->t[i];
    switch (d->model) {
    case 0:
        return x[0] + x[1] * t;
    case 1:
        return x[0] * exp(-x[1] * t) + x[2];
    default:
        return x[0] * x[1] * t;
    }
}

static int eval(void *ctx, size_t n, const double *const *x, double *const *r, rd_error *err)
{
    data *d = ctx;
    if (d->fail_after > 0 && ++d->calls >= d->fail_after)
        return rd_error_set(err, RD_ENOCONV, "/measurements/1", "the scene did not converge");
    for (size_t k = 0; k < n; k++) {
        if (d->model == 3) {
            r[k][0] = 10 * (x[k][1] - x[k][0] * x[k][0]);
            r[k][1] = 1 - x[k][0];
            continue;
        }
        for (int i = 0; i < d->n; i++)
            r[k][i] = (model_at(d, x[k], i) - d->y[i]) / d->sigma[i];
    }
    return RD_OK;
}

static void fill(data *d, int model, const double *truth, double sigma, uint64_t *seed)
{
    memset(d, 0, sizeof *d);
    d->n = NT;
    d->model = model;
    for (int i = 0; i < NT; i++) {
        d->t[i] = 0.2 * i;
        d->sigma[i] = sigma * (1 + 0.05 * i); /* unequal weights */
        d->y[i] = model_at(d, truth, i) + (seed ? d->sigma[i] * seeded_normal(seed) : 0);
    }
}

static void test_exponential_exact(void)
{
    const double truth[3] = {5, 1.5, 1}, lo[3] = {0, 0.1, -10}, hi[3] = {20, 10, 10},
                 x0[3] = {1, 0.5, 0};
    data d;
    fill(&d, 1, truth, 0.01, NULL);
    rd_fit_problem fp = {
        .n_params = 3, .n_resid = NT, .lo = lo, .hi = hi, .start = x0, .eval = eval, .ctx = &d};
    rd_fit_result res;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_OK, "%s", err.message);
    for (int j = 0; j < 3; j++)
        CHECK_REL(res.x[j], truth[j], 1e-8, "exponential parameter %d from noise-free data", j);
    CHECK(res.identifiable && res.chi2 < 1e-12 && res.stop != RD_FIT_BUDGET,
          "identifiable %d chi2 %g stop %s", res.identifiable, res.chi2,
          rd_fit_stop_name(res.stop));
    CHECK(res.points <= 150, "%zu evaluations", res.points);
    rd_fit_result_cleanup(&res);
}

/* The weighted straight line: C = (A^T W A)^-1 in closed form. */
static void test_line_covariance(void)
{
    const double truth[2] = {2, -0.7}, lo[2] = {-100, -100}, hi[2] = {100, 100}, x0[2] = {0, 0};
    uint64_t seed = 7;
    data d;
    fill(&d, 0, truth, 0.1, &seed);
    double s = 0, st = 0, stt = 0, sy = 0, sty = 0;
    for (int i = 0; i < NT; i++) {
        double w = 1 / (d.sigma[i] * d.sigma[i]);
        s += w;
        st += w * d.t[i];
        stt += w * d.t[i] * d.t[i];
        sy += w * d.y[i];
        sty += w * d.t[i] * d.y[i];
    }
    double det = s * stt - st * st;
    double a = (stt * sy - st * sty) / det, b = (s * sty - st * sy) / det;
    rd_fit_problem fp = {
        .n_params = 2, .n_resid = NT, .lo = lo, .hi = hi, .start = x0, .eval = eval, .ctx = &d};
    rd_fit_result res;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_OK, "%s", err.message);
    CHECK_REL(res.x[0], a, 1e-7, "line intercept against the normal equations");
    CHECK_REL(res.x[1], b, 1e-7, "line slope against the normal equations");
    CHECK_REL(res.std_error[0], sqrt(stt / det), 1e-5, "intercept's standard error");
    CHECK_REL(res.std_error[1], sqrt(s / det), 1e-5, "slope's standard error");
    CHECK_REL(res.corr[1], -st / sqrt(s * stt), 1e-5, "their correlation");
    CHECK_REL(res.corr[0], 1.0, 1e-12, "a parameter's correlation with itself");
    rd_fit_result_cleanup(&res);
}

/* 200 seeded noisy trials of the exponential: each parameter within one
 * standard error ~68.3 %, within two ~95.4 % of the time. */
static void test_coverage(void)
{
    const double truth[3] = {5, 1.5, 1}, lo[3] = {0, 0.1, -10}, hi[3] = {20, 10, 10},
                 x0[3] = {3, 1, 0};
    int in1 = 0, in2 = 0, total = 0;
    uint64_t seed = 42;
    for (int trial = 0; trial < 200; trial++) {
        data d;
        fill(&d, 1, truth, 0.05, &seed);
        rd_fit_problem fp = {
            .n_params = 3, .n_resid = NT, .lo = lo, .hi = hi, .start = x0, .eval = eval, .ctx = &d};
        rd_fit_result res;
        rd_error err;
        rd_error_init(&err);
        if (rd_fit_solve(&fp, &res, &err) != RD_OK) {
            CHECK(0, "trial %d: %s", trial, err.message);
            continue;
        }
        for (int j = 0; j < 3; j++) {
            double z = fabs(res.x[j] - truth[j]) / res.std_error[j];
            in1 += z <= 1;
            in2 += z <= 2;
            total++;
        }
        rd_fit_result_cleanup(&res);
    }
    double f1 = (double)in1 / total, f2 = (double)in2 / total;
    printf("coverage over %d estimates: %.3f within 1 sigma, %.3f within 2\n", total, f1, f2);
    /* 600 draws: the binomial's 3 sigma is 0.057 at 68 % and 0.026 at 95 % */
    CHECK(fabs(f1 - 0.683) < 0.057, "within 1 sigma %.3f of the time, want 0.683", f1);
    CHECK(fabs(f2 - 0.954) < 0.026, "within 2 sigma %.3f of the time, want 0.954", f2);
}

/* stol: a noisy fit stopped once its steps are 1e-3 of its standard
 * errors lands within 1e-2 of them from the fully converged one. */
static void test_stol(void)
{
    const double truth[3] = {5, 1.5, 1}, lo[3] = {0, 0.1, -10}, hi[3] = {20, 10, 10},
                 x0[3] = {1, 0.5, 0};
    uint64_t seed = 3;
    data d;
    fill(&d, 1, truth, 0.05, &seed);
    rd_fit_problem fp = {.n_params = 3,
                         .n_resid = NT,
                         .lo = lo,
                         .hi = hi,
                         .start = x0,
                         .eval = eval,
                         .ctx = &d,
                         .xtol = 1e-14};
    rd_fit_result full, early;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &full, &err) == RD_OK, "%s", err.message);
    fp.stol = 1e-3;
    CHECK(rd_fit_solve(&fp, &early, &err) == RD_OK, "%s", err.message);
    for (int j = 0; j < 3; j++)
        CHECK(fabs(early.x[j] - full.x[j]) <= 1e-2 * full.std_error[j],
              "parameter %d: %.12g stopped early, %.12g converged (std error %g)", j, early.x[j],
              full.x[j], full.std_error[j]);
    CHECK(early.points <= full.points && early.stop != RD_FIT_BUDGET,
          "stol stops (%s) after %zu evaluations, not more than %zu", rd_fit_stop_name(early.stop),
          early.points, full.points);
    printf("stol 1e-3: %zu evaluations, %zu to xtol 1e-14\n", early.points, full.points);
    rd_fit_result_cleanup(&full);
    rd_fit_result_cleanup(&early);
}

static void test_product(void)
{
    const double truth[2] = {2, 3}, lo[2] = {0.1, 0.1}, hi[2] = {10, 10}, x0[2] = {1, 1};
    data d;
    fill(&d, 2, truth, 0.01, NULL);
    rd_fit_problem fp = {
        .n_params = 2, .n_resid = NT, .lo = lo, .hi = hi, .start = x0, .eval = eval, .ctx = &d};
    rd_fit_result res;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_OK, "%s", err.message);
    CHECK(!res.identifiable && res.unidentified[0] && res.unidentified[1],
          "a product is not identifiable (%d %d %d), cond %g", res.identifiable,
          res.unidentified[0], res.unidentified[1], res.cond);
    CHECK(isnan(res.std_error[0]) && isnan(res.std_error[1]) && isnan(res.corr[1]),
          "no standard error for what the data cannot fix");
    CHECK_REL(res.x[0] * res.x[1], 6.0, 1e-8, "the product itself is fitted");
    printf("product a b: cond %.3g after %zu evaluations\n", res.cond, res.points);
    rd_fit_result_cleanup(&res);
}

static void test_bound_and_rosenbrock(void)
{
    const double truth[2] = {2, -0.7}, lo[2] = {0, -0.5}, hi[2] = {10, 10}, x0[2] = {1, 0};
    data d;
    fill(&d, 0, truth, 0.01, NULL);
    rd_fit_problem fp = {
        .n_params = 2, .n_resid = NT, .lo = lo, .hi = hi, .start = x0, .eval = eval, .ctx = &d};
    rd_fit_result res;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_OK, "%s", err.message);
    CHECK(res.at_bound[1] == -1 && res.x[1] == -0.5 && res.at_bound[0] == 0,
          "a slope below its bound stops at it (%g, flag %d; intercept %g, flag %d, stop %s)",
          res.x[1], res.at_bound[1], res.x[0], res.at_bound[0], rd_fit_stop_name(res.stop));
    /* the reported residuals are those at the reported (snapped) x */
    double chi2 = 0;
    for (int i = 0; i < NT; i++) {
        double r = (model_at(&d, res.x, i) - d.y[i]) / d.sigma[i];
        chi2 += r * r;
        CHECK_REL(res.resid[i], r, 1e-12, "residual %d at the bound", i);
    }
    CHECK_REL(res.chi2, chi2, 1e-12, "chi2 at the bound");
    rd_fit_result_cleanup(&res);

    const double rlo[2] = {-5, -5}, rhi[2] = {5, 5}, r0[2] = {-1.2, 1};
    d.model = 3;
    fp = (rd_fit_problem){
        .n_params = 2, .n_resid = 2, .lo = rlo, .hi = rhi, .start = r0, .eval = eval, .ctx = &d};
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_OK, "%s", err.message);
    CHECK_ABS(res.x[0], 1.0, 1e-7, "Rosenbrock's valley to (1, 1)");
    CHECK_ABS(res.x[1], 1.0, 1e-7, "Rosenbrock's valley to (1, 1)");
    rd_fit_result_cleanup(&res);
}

static void test_budget_and_errors(void)
{
    const double truth[3] = {5, 1.5, 1}, lo[3] = {0, 0.1, -10}, hi[3] = {20, 10, 10},
                 x0[3] = {1, 0.5, 0};
    data d;
    fill(&d, 1, truth, 0.01, NULL);
    rd_fit_problem fp = {.n_params = 3,
                         .n_resid = NT,
                         .lo = lo,
                         .hi = hi,
                         .start = x0,
                         .eval = eval,
                         .ctx = &d,
                         .max_points = 12};
    rd_fit_result res;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_OK, "%s", err.message);
    CHECK(res.stop == RD_FIT_BUDGET && res.points <= 12, "budget: stop %s after %zu",
          rd_fit_stop_name(res.stop), res.points);
    rd_fit_result_cleanup(&res);

    fp.max_points = 0;
    d.fail_after = 3;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_ENOCONV && strcmp(err.path, "/measurements/1") == 0,
          "the eval's error passes through: %d %s", err.code, err.path);
    d.fail_after = 0;

    double bad_hi[3] = {20, 0.1, 10};
    fp.hi = bad_hi;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_EINVAL && strstr(err.message, "parameter 1"),
          "min == max refused: %s", err.message);
    fp.hi = hi;
    double out_x0[3] = {1, 20, 0};
    fp.start = out_x0;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_EINVAL && strstr(err.message, "outside"),
          "a start outside the bounds refused: %s", err.message);
    fp.start = x0;
    fp.n_resid = 2;
    rd_error_init(&err);
    CHECK(rd_fit_solve(&fp, &res, &err) == RD_EINVAL && strstr(err.message, "at least"),
          "fewer values than parameters refused: %s", err.message);
}

int main(void)
{
    test_exponential_exact();
    test_line_covariance();
    test_coverage();
    test_stol();
    test_product();
    test_bound_and_rosenbrock();
    test_budget_and_errors();
    return check_done();
}
