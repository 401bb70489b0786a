/* rd_lift_partial — what a stopped lift run returns (issue 10, item 5).
 *
 * A run stops early when /numerics/max_steps runs out (RD_ELIMIT) or when
 * its monitor asks it to (RD_ECANCELED: a cancel or the job's time limit).
 * The samples and flank changes up to the end of the last whole 720 deg
 * cycle it finished are exact (the same steps as an uninterrupted run), so
 * they are returned, marked partial, with the angle reached and a warning
 * naming the stop and what would make the run cheaper; no error estimate
 * (its rtol/10 run would need the same work again).  A max_steps stop then
 * succeeds; a monitor stop keeps its error code (the caller decides: the
 * server keeps the partial result beside the job's error).  Stopped in the
 * error-estimate run (by a stop or by max_steps: at rtol/10 a free-flying
 * elastic ring may need ~3x the main run's steps), every cycle is there and
 * only the estimate is lost. */
#include <math.h>
#include <stdio.h>

#include "rd_lift_model.h"

/* A level-0 run stopped early keeps its whole cycles, if any
 * (rd_lift_result.partial): the samples and events up to their end.  `why`
 * is the stop: RD_ELIMIT (/numerics/max_steps; the run then succeeds with
 * those cycles) or RD_ECANCELED (the monitor asked to stop: a cancel or a
 * time limit; the stop stands and the cycles come with it).  Returns the
 * code the run ends with; err keeps the stop's message unless it succeeds. */
int rd_lift_keep_partial(rd_lift_result *out, const rd_lift_params *p, const rd_lift_pass *r,
                         int why, rd_error *err)
{
    double step = p->step_deg, stored = (r->done - 1) * step;
    int cycles = (int)floor(fmin(r->reached_deg, stored) / 720.0 + 1e-9);
    if (cycles < 1)
        return why; /* nothing whole to return: the error stands */
    double end = 720.0 * cycles;
    out->partial = 1;
    out->partial_stop = why;
    out->crank_deg_reached = r->reached_deg;
    out->samples = (int)floor(end / step + 1e-9) + 1;
    char stop[120];
    if (why == RD_ELIMIT)
        snprintf(stop, sizeof stop, "/numerics/max_steps = %ld ran out", p->max_steps);
    else
        snprintf(stop, sizeof stop, "the run was stopped (cancelled or out of time)");
    snprintf(out->warning, sizeof out->warning,
             "Partial result: %s at crank angle %.1f deg of %.1f; the %d complete cycle%s (to "
             "%.0f deg) are returned.  To finish the run, %s or make it cheaper: fewer cycles, "
             "a cheaper model (/numerics/model), or a looser /numerics/rtol.",
             stop, r->reached_deg, 720.0 * p->engine.cycles, cycles, cycles > 1 ? "s" : "", end,
             why == RD_ELIMIT ? "raise max_steps" : "allow it more time");
    if (why != RD_ELIMIT)
        return why;
    rd_error_init(err);
    return RD_OK;
}

/* Stopped in the error-estimate run: every cycle is there, the estimate is
 * not; the result is partial (at the run's end) and says so.  `why` is the
 * stop (RD_ELIMIT: /numerics/max_steps ran out at `reached_deg` in the
 * rtol/10 or n/2 run, which costs more steps than the main one; the run
 * then succeeds, as a max_steps stop after whole cycles does), `err` is
 * cleared for RD_ELIMIT.  Returns the code the run ends with. */
int rd_lift_estimate_stopped(rd_lift_result *out, const rd_lift_params *p, int why,
                             double reached_deg, rd_error *err)
{
    out->partial = 1;
    out->partial_stop = why == RD_ELIMIT ? RD_ELIMIT : RD_ECANCELED;
    out->crank_deg_reached = 720.0 * p->engine.cycles;
    out->error_estimate = NAN;
    out->event_error_deg = NAN;
    if (why != RD_ELIMIT) {
        snprintf(out->warning, sizeof out->warning,
                 "Partial result: the run was stopped (cancelled or out of time) in its "
                 "error-estimate run (rtol/10); every cycle is returned, without an error "
                 "estimate.  To get one, allow it more time or make it cheaper: fewer cycles, a "
                 "cheaper model (/numerics/model), or a looser /numerics/rtol.");
        return why;
    }
    snprintf(out->warning, sizeof out->warning,
             "Partial result: the error-estimate run (rtol/10, or n/2 segments) used its "
             "/numerics/max_steps = %ld steps by crank angle %.1f deg of %.1f; every cycle of "
             "the main run is returned, without an error estimate.  To get one, raise max_steps "
             "or make the run cheaper: fewer cycles, a cheaper model (/numerics/model), or a "
             "looser /numerics/rtol.",
             p->max_steps, reached_deg, 720.0 * p->engine.cycles);
    rd_error_init(err);
    return RD_OK;
}
