/* test_accuracy — the solve / refine / compare driver (rd_accuracy.h):
 * order of calls, progress split, failure wording, Richardson against a
 * sequence whose limit is known in closed form. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "rd_accuracy.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct toy {
    double value[2];
    int calls[2], compared, fail_level, fail_code;
    double last_fraction, max_fraction;
    double estimate;
} toy;

/* f_n = pi + 3 n^-2 at n = 10 (level 0) and 20 (level 1); reports 0, 0.5, 1. */
static int toy_solve(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    toy *t = ctx;
    t->calls[level]++;
    for (int k = 0; k <= 2; k++)
        if (rd_monitor_report(mon, 0.5 * k, err))
            return RD_ECANCELED;
    if (level == t->fail_level)
        return rd_error_set(err, t->fail_code, "/numerics/rtol", "level %d did not converge.",
                            level);
    int n = level ? 20 : 10;
    t->value[level] = M_PI + 3.0 / ((double)n * n);
    return RD_OK;
}

static int toy_compare(void *ctx, rd_error *err)
{
    (void)err;
    toy *t = ctx;
    t->compared++;
    rd_accuracy_richardson(t->value[0], 10, t->value[1], 20, 2.0, &t->estimate);
    return RD_OK;
}

static int record(void *ctx, double f)
{
    toy *t = ctx;
    CHECK(f >= t->last_fraction - 1e-15, "progress goes back: %g after %g", f, t->last_fraction);
    t->last_fraction = f;
    t->max_fraction = fmax(t->max_fraction, f);
    return 0;
}

static int stop_at_half(void *ctx, double f)
{
    (void)ctx;
    return f > 0.5;
}

int main(void)
{
    /* both levels, compare once, progress monotone up to exactly 1 */
    toy t = {.fail_level = -1};
    rd_monitor mon = {record, &t};
    rd_accuracy_plan plan = {toy_solve, toy_compare, &t, 1, 0.25, "2n segments"};
    rd_accuracy_cost cost;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_accuracy_run(&plan, &mon, &cost, &err) == RD_OK, "%s", err.message);
    CHECK(t.calls[0] == 1 && t.calls[1] == 1 && t.compared == 1, "calls %d %d %d", t.calls[0],
          t.calls[1], t.compared);
    CHECK_ABS(t.max_fraction, 1.0, 1e-15, "progress ends at 1");
    CHECK(cost.wall_s[0] >= 0.0 && cost.wall_s[1] >= 0.0, "cost recorded");
    /* the true relative error of f_10 is 0.03 / (pi): Richardson is exact for this sequence */
    CHECK_REL(t.estimate, 0.03 / M_PI, 1e-12, "Richardson on an exact n^-2 sequence");

    /* no estimate: one solve, no compare, progress still reaches 1 */
    toy u = {.fail_level = -1};
    rd_monitor mu = {record, &u};
    plan = (rd_accuracy_plan){toy_solve, toy_compare, &u, 0, 0.25, "2n segments"};
    CHECK(rd_accuracy_run(&plan, &mu, NULL, &err) == RD_OK, "%s", err.message);
    CHECK(u.calls[0] == 1 && u.calls[1] == 0 && u.compared == 0, "no reference solve");
    CHECK_ABS(u.max_fraction, 1.0, 1e-15, "single solve owns all the progress");

    /* a failed reference names the refinement and keeps code and path */
    toy v = {.fail_level = 1, .fail_code = RD_ENOCONV};
    plan = (rd_accuracy_plan){toy_solve, toy_compare, &v, 1, 0.5, "rtol/10"};
    rd_error_init(&err);
    CHECK(rd_accuracy_run(&plan, NULL, NULL, &err) == RD_ENOCONV, "code passes through");
    CHECK(strstr(err.message, "error-estimate solve at rtol/10 failed") != NULL, "%s", err.message);
    CHECK(strstr(err.message, "level 1 did not converge") != NULL, "%s", err.message);
    CHECK(strcmp(err.path, "/numerics/rtol") == 0, "path %s", err.path);
    CHECK(v.compared == 0, "no compare after a failure");

    /* a failed main solve is reported unchanged and stops the run */
    toy w = {.fail_level = 0, .fail_code = RD_ENOCONV};
    plan.ctx = &w;
    rd_error_init(&err);
    CHECK(rd_accuracy_run(&plan, NULL, NULL, &err) == RD_ENOCONV, "main failure");
    CHECK(strncmp(err.message, "level 0", 7) == 0, "%s", err.message);
    CHECK(w.calls[1] == 0, "no reference after a failed main solve");

    /* a cancel in the reference half is a cancel, not an estimate failure */
    toy x = {.fail_level = -1};
    rd_monitor stop = {stop_at_half, NULL};
    plan = (rd_accuracy_plan){toy_solve, toy_compare, &x, 1, 0.5, "2n segments"};
    rd_error_init(&err);
    CHECK(rd_accuracy_run(&plan, &stop, NULL, &err) == RD_ECANCELED, "cancelled");
    CHECK(strstr(err.message, "error-estimate") == NULL, "%s", err.message);

    /* Richardson: order 1 and a zero limit (absolute error) */
    double rel;
    double f = rd_accuracy_richardson(2.0 + 1.0 / 8, 8, 2.0 + 1.0 / 16, 16, 1.0, &rel);
    CHECK_REL(f, 2.0, 1e-14, "order-1 limit");
    CHECK_REL(rel, 0.125 / 2.0, 1e-12, "order-1 relative error");
    f = rd_accuracy_richardson(1.0 / 16, 4, 1.0 / 64, 8, 2.0, &rel);
    CHECK_ABS(f, 0.0, 1e-15, "zero limit");
    CHECK_REL(rel, 1.0 / 16, 1e-12, "zero limit: absolute error");
    CHECK(rd_accuracy_refined_segments(20, 2000) == 40 &&
              rd_accuracy_refined_segments(1500, 2000) == 750,
          "refined segment counts");
    return check_done();
}
