/* rd_accuracy.c — the solve / refine / compare driver (contract in rd_accuracy.h). */
#include "rd_accuracy.h"

#include <math.h>
#include <stdio.h>
#include <time.h>

double rd_accuracy_wall_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double rd_accuracy_cpu_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One level with its own progress range and clock. */
static int solve_level(const rd_accuracy_plan *plan, int level, const rd_monitor *mon, double f0,
                       double f1, rd_accuracy_cost *cost, rd_error *err)
{
    rd_monitor_span span;
    const rd_monitor *use = rd_monitor_span_init(&span, mon, f0, f1);
    double w0 = rd_accuracy_wall_now(), c0 = rd_accuracy_cpu_now();
    int rc = plan->solve(plan->ctx, level, use, err);
    if (cost) {
        cost->wall_s[level] = rd_accuracy_wall_now() - w0;
        cost->cpu_s[level] = rd_accuracy_cpu_now() - c0;
    }
    return rc;
}

int rd_accuracy_run(const rd_accuracy_plan *plan, const rd_monitor *mon, rd_accuracy_cost *cost,
                    rd_error *err)
{
    if (cost)
        *cost = (rd_accuracy_cost){{0.0, 0.0}, {0.0, 0.0}};
    if (!plan || !plan->solve)
        return rd_error_set(err, RD_EINTERNAL, "", "The accuracy driver was given no solver.");
    double share = plan->estimate ? plan->main_share : 1.0;
    if (!(share > 0.0 && share <= 1.0))
        share = 0.5;
    int rc = solve_level(plan, 0, mon, 0.0, share, cost, err);
    if (rc != RD_OK || !plan->estimate)
        return rc;

    rd_error sub;
    rd_error_init_local(&sub, err);
    rc = solve_level(plan, 1, mon, share, 1.0, cost, &sub);
    if (rc != RD_OK) {
        if (rc == RD_ECANCELED || rc == RD_ETIMEOUT) {
            rd_error_forward(err, &sub);
            return rc;
        }
        char why[RD_ERROR_MESSAGE_MAX];
        snprintf(why, sizeof why, "%s", sub.message);
        snprintf(sub.message, sizeof sub.message, "The error-estimate solve at %s failed: %.400s",
                 plan->reference ? plan->reference : "refined settings", why);
        rd_error_forward(err, &sub);
        return rc;
    }
    return plan->compare ? plan->compare(plan->ctx, err) : RD_OK;
}

double rd_accuracy_richardson(double fn, int n, double fm, int m, double order, double *rel_error)
{
    /* f_n - f = C n^-p, f_m - f = C m^-p  =>  f = (m^p f_m - n^p f_n) / (m^p - n^p) */
    double np = pow((double)n, order), mp = pow((double)m, order);
    double f = (mp * fm - np * fn) / (mp - np);
    if (rel_error) {
        double e = fabs(fn - f);
        *rel_error = fabs(f) > 0.0 ? e / fabs(f) : e;
    }
    return f;
}

int rd_accuracy_refined_segments(int n, int max_n)
{
    return 2 * n <= max_n ? 2 * n : n / 2;
}
