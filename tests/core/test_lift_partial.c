/* test_lift_partial — a lift run stopped by its monitor (a cancel, the
 * job's time limit) returns the whole cycles it finished (issue 10, item 5).
 *
 * Reference: the same scene run without a stop.  Up to the angle where the
 * stop was asked, the stopped run took exactly the same steps as the
 * uninterrupted one (same tolerances, same output grid, same code path), so
 * the samples it keeps must agree with it bit for bit, and so must its
 * flank changes; a test with a tolerance would hide a run that restarted or
 * re-integrated.  The stop is asked from inside the monitor, as the server's
 * rd_jobs does, at a progress fraction chosen so that it falls inside the
 * second of three cycles (main run only) or inside the error-estimate run. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_lift.h"

/* Asks to stop once the reported progress reaches `at`. */
typedef struct stopper {
    double at;
    int asked;
} stopper;

static int stop_at(void *ctx, double fraction)
{
    stopper *s = ctx;
    if (fraction >= s->at)
        s->asked = 1;
    return s->asked;
}

static int run(int model, int estimate, double stop, rd_lift_result *r, rd_error *err)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.model = model;
    p.engine.cycles = 3;
    p.estimate_error = estimate;
    stopper s = {stop, 0};
    rd_monitor mon = {stop_at, &s};
    rd_error_init(err);
    return rd_lift_solve(&rp, 8, &p, stop < 1.0 ? &mon : NULL, r, err);
}

/* The kept samples and events against the uninterrupted run's. */
static void check_prefix(const rd_lift_result *cut, const rd_lift_result *all, const char *what)
{
    int same = cut->samples <= all->samples;
    for (int k = 0; same && k < cut->samples; k++)
        same = cut->crank_deg[k] == all->crank_deg[k] && cut->lift[k] == all->lift[k] &&
               cut->twist[k] == all->twist[k] && cut->flank[k] == all->flank[k];
    CHECK(same, "%s: the kept samples are the uninterrupted run's, bit for bit", what);
    double end = cut->crank_deg[cut->samples - 1];
    int events = 0;
    while (events < all->n_events && all->events[events].crank_deg <= end)
        events++;
    CHECK(cut->n_events == events, "%s: %d flank changes kept, %d before %.0f deg", what,
          cut->n_events, events, end);
    for (int j = 0; j < cut->n_events && j < events; j++)
        CHECK(cut->events[j].crank_deg == all->events[j].crank_deg &&
                  cut->events[j].kind == all->events[j].kind,
              "%s: flank change %d", what, j);
}

static void test_model(int model, const char *name)
{
    rd_lift_result all, cut, late;
    rd_error err;
    int rc = run(model, 0, 2.0, &all, &err);
    CHECK(rc == RD_OK && !all.partial && all.n_events >= 6, "%s: uninterrupted: %s, %d events",
          name, err.message, all.n_events);

    /* stopped at 50 % of three cycles: inside the second one */
    rc = run(model, 0, 0.5, &cut, &err);
    CHECK(rc == RD_ECANCELED && err.code == RD_ECANCELED, "%s: the stop stands (%d: %s)", name, rc,
          err.message);
    CHECK(cut.partial == 1 && cut.crank_deg[cut.samples - 1] == 720.0,
          "%s: partial, one whole cycle (%d samples, last %.1f deg)", name, cut.samples,
          cut.samples > 0 ? cut.crank_deg[cut.samples - 1] : -1.0);
    /* the stop is asked at 50 % of 3 x 720 deg = 1080 deg and honoured at the
     * next report: after the next output sample (step_deg = 1 by default) or
     * chunk of steps, so within a few degrees; 20 deg bounds it loosely */
    CHECK(cut.crank_deg_reached >= 1080.0 && cut.crank_deg_reached < 1100.0,
          "%s: reached %.2f deg, stopped at 1080", name, cut.crank_deg_reached);
    CHECK(strstr(cut.warning, "stopped") && strstr(cut.warning, "1 complete cycle"),
          "%s: warning names the stop: %s", name, cut.warning);
    CHECK(isnan(cut.error_estimate), "%s: no estimate", name);
    if (rc == RD_ECANCELED && cut.partial && all.samples > 0)
        check_prefix(&cut, &all, name);
    rd_lift_result_cleanup(&cut);

    /* stopped before the first cycle ends: nothing whole, the error alone */
    rc = run(model, 0, 0.2, &cut, &err);
    CHECK(rc == RD_ECANCELED && !cut.partial, "%s: stopped in cycle 1: no partial result", name);
    rd_lift_result_cleanup(&cut);

    /* with the estimate (main run 40 % of the progress): stopped in the
     * rtol/10 run, every cycle is kept, without an estimate */
    rd_lift_result est;
    rc = run(model, 1, 2.0, &est, &err);
    CHECK(rc == RD_OK && isfinite(est.error_estimate), "%s: with estimate: %s", name, err.message);
    rc = run(model, 1, 0.7, &late, &err);
    CHECK(rc == RD_ECANCELED && late.partial && late.samples == all.samples &&
              isnan(late.error_estimate) && late.crank_deg_reached == 3 * 720.0 &&
              strstr(late.warning, "error-estimate"),
          "%s: stopped in the estimate run: partial %d, %d of %d samples, estimate %g, %s", name,
          late.partial, late.samples, all.samples, late.error_estimate, late.warning);
    if (late.partial && late.samples == all.samples)
        check_prefix(&late, &all, name);
    rd_lift_result_cleanup(&est);
    rd_lift_result_cleanup(&late);
    rd_lift_result_cleanup(&all);
}

int main(void)
{
    test_model(RD_LIFT_MODEL_RIGID, "rigid");
    test_model(RD_LIFT_MODEL_FULL, "full");
    return check_done();
}
