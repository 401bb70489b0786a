/*
 * test_film_error — the oil film's error estimate (lubrication.film_error,
 * lubrication.friction_work_error; core/lift/rd_lift_film.c): the film of
 * the default grid (RD_FILM_NODES points across the face, steps at most
 * film_step_deg, local error RD_FILM_RTOL) against the same film on a grid
 * twice as fine in each (rd_lift_film_run_at, fine 2) estimates the default
 * film's error; the true error is taken against a grid 8 times as fine
 * (321 points, film_step_deg / 8, RD_FILM_RTOL / 64).
 *
 * Battery (once with each cavitation condition, Reynolds and JFO): the
 * thesis ring, rigid lift scenes of one cycle, barrel faces
 * of crown 2, 5 and 10 um, 1000 / 2400 / 6000 rpm, with and without a fired
 * gas cycle behind and above the ring (the gas written here, as
 * bench/bench_lube.c's), the default oil and roughness.  Measured: the
 * film's max relative error (|h - h*| / max(h*, sigma) over 1 deg samples)
 * and the friction work's relative error, each estimate (the lift run's
 * lubrication.film_error and work_error, numerics.error_estimate on) within
 * x3 of its true error wherever that is above its floor (FILM_FLOOR,
 * WORK_FLOOR).  Measured: film 0.45..1.24 on 18 scenes, friction work
 * 0.35..0.90 on 16 (the film converges about first order in the grid: the
 * difference to a grid twice as fine is about half the error).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "fired_cycle.h"
#include "rd_lift_internal.h"

/* Below these the reference's own error (fine 8 against fine 4: ~10-40 %
 * of the true error, the film converging about first order in the grid)
 * and round-off blur the ratio: the film's true errors are 2.5e-3..1e-2,
 * the friction work's 3e-5..4e-3 (it cancels where the film's shear and
 * the asperities' trade). */
#define FILM_FLOOR 1e-5
#define WORK_FLOOR 1e-4

static fired_tables tables;

static void scene(rd_ring_params *rp, rd_lift_params *p, double rpm, int gas, double crown,
                  int cavitation)
{
    rd_ring_params_default(rp);
    rd_lift_params_default(p);
    p->engine.speed_rpm = rpm;
    p->engine.cycles = 1.0;
    p->friction.model = RD_FRICTION_LUBRICATED;
    p->face.crown = crown;
    p->friction.lube.cavitation = cavitation;
    if (gas) /* gauge */
        p->gas = fired_cycle_gas(&tables, 1e5);
}

/* The film of the lift run `out` (its samples) on grid `fine`: the true
 * film error of out's block (max over the samples) and friction work's. */
static int truth(const rd_ring_params *rp, const rd_lift_params *p, const rd_lift_result *out,
                 int fine, double *film_err, double *work_err)
{
    rd_film f;
    rd_film_track tr;
    rd_error err;
    rd_error_init(&err);
    rd_lift_lube lb = {0};
    int rc = rd_lift_film_run_at(rp, p, fine, &f, &tr, &err);
    rc = rc ? rc
            : rd_lift_lube_fill(&lb, &f, &tr, &p->friction.lube, &p->engine, rp->diameter,
                                out->crank_deg, out->samples, 0.0, 1, &err);
    CHECK(rc == RD_OK, "film at fine %d: %s", fine, err.message);
    if (rc == RD_OK) {
        rd_lift_lube mine = out->lube;
        rd_lift_lube_compare(&mine, &lb, out->samples);
        *film_err = mine.film_error;
        *work_err = mine.work_error;
    }
    rd_lift_lube_cleanup(&lb);
    rd_film_track_free(&tr);
    rd_film_free(&f);
    return rc;
}

/* The battery with one cavitation condition. */
static void battery(int cav)
{
    static const double rpms[] = {1000.0, 2400.0, 6000.0}, crowns[] = {2e-6, 5e-6, 10e-6};
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {0.0, 0.0};
    int counted[2] = {0, 0};
    const char *name = cav ? "JFO" : "Reynolds";
    for (int g = 0; g < 2; g++)
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                rd_ring_params rp;
                rd_lift_params p;
                scene(&rp, &p, rpms[r], g, crowns[c], cav);
                p.estimate_error = 1;
                p.model = RD_LIFT_MODEL_RIGID;
                rd_lift_result out;
                rd_error err;
                rd_error_init(&err);
                int rc = rd_lift_solve(&rp, 20, &p, NULL, &out, &err);
                CHECK(rc == RD_OK, "lift: %s", err.message);
                double ft, wt, fr, wr;
                if (rc || truth(&rp, &p, &out, 8, &ft, &wt) || truth(&rp, &p, &out, 4, &fr, &wr)) {
                    rd_lift_result_cleanup(&out);
                    continue;
                }
                double fe = out.lube.film_error, we = out.lube.work_error;
                printf("%s %4.0f rpm %s crown %2.0f um: film est %.2e true %.2e (fine 4: %.1e) "
                       "ratio %.2f; work est %.2e true %.2e ratio %.2f\n",
                       name, rpms[r], g ? "gas   " : "no gas", crowns[c] * 1e6, fe, ft, fr, fe / ft,
                       we, wt, we / wt);
                double est[2] = {fe, we}, tru[2] = {ft, wt}, floor_[2] = {FILM_FLOOR, WORK_FLOOR};
                for (int q = 0; q < 2; q++) {
                    if (!(tru[q] > floor_[q]))
                        continue;
                    double ratio = est[q] / tru[q];
                    lo[q] = fmin(lo[q], ratio);
                    hi[q] = fmax(hi[q], ratio);
                    counted[q]++;
                    CHECK(ratio >= 1.0 / 3.0 && ratio <= 3.0,
                          "%s: %s estimate %.3g against the true %.3g (%.0f rpm, %s, crown %g)",
                          name, q ? "friction work" : "film", est[q], tru[q], rpms[r],
                          g ? "gas" : "no gas", crowns[c]);
                }
                rd_lift_result_cleanup(&out);
            }
    printf("%s: film estimate / true over %d scenes: %.2f .. %.2f; friction work over %d: %.2f "
           ".. %.2f\n",
           name, counted[0], lo[0], hi[0], counted[1], lo[1], hi[1]);
    CHECK(counted[0] >= 15 && counted[1] >= 10, "%s: scenes above the floors: %d, %d", name,
          counted[0], counted[1]);
}

int main(void)
{
    battery(RD_CAVITATION_REYNOLDS);
    battery(RD_CAVITATION_JFO);
    return check_done();
}
