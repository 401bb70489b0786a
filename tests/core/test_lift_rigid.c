/* test_lift_rigid — the rigid lift model (rd_lift_rigid.c) and the model
 * choice (numerics.model, numerics.accuracy_deg).
 *
 * References (besides the 1-DOF limits in test_lift, which the rigid model
 * also passes: test_rigid_limit, test_friction):
 *  - the full model on axisymmetric scenes without friction (inertia only;
 *    gravity and gas with fixed and dynamic areas), a second method written
 *    separately (6 n DOFs, band Newton) from the same force elements;
 *  - extremes that must stay finite and inside the groove;
 *  - auto's choice and its reason, and validation of the new fields. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lift_battery.h"
#include "rd_lift.h"
#include "rd_lift_internal.h"

static int run(const rd_lift_params *p, int model, int n, rd_lift_result *r, rd_error *err)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params q = *p;
    q.model = model;
    rd_error_init(err);
    return rd_lift_solve(&rp, n, &q, NULL, r, err);
}

/* Largest angle difference of matched flank changes; 1e9 if the lists
 * differ in count or kind. */
static double event_diff(const rd_lift_result *a, const rd_lift_result *b)
{
    if (a->n_events != b->n_events)
        return 1e9;
    double d = 0.0;
    for (int i = 0; i < a->n_events; i++) {
        if (a->events[i].kind != b->events[i].kind)
            return 1e9;
        d = fmax(d, fabs(a->events[i].crank_deg - b->events[i].crank_deg));
    }
    return d;
}

/* Rigid vs full on axisymmetric scenes without friction, both at rtol 1e-8.
 * Tolerance 0.03 deg: the full model's own integration error plus what the
 * rigid ring cannot do — the split ring's free ends and the small twist of
 * the inertia and gas loads acting off the section's centre (rc_com - R =
 * b^2 / (12 R)); measured 0.0034 deg at most.  Dated at the band (1 %), a
 * leave is where the lift has risen 1 % of the clearance from rest, ~1.8 deg
 * after it left: the full ring at rtol 1e-7 was 0.073 deg off there (at rtol
 * 1e-10 both rings agree within 1e-4 deg), hence 1e-8.  (At the
 * rigid model's default rtol 1e-6 its own error is up to 0.06 deg on the gas
 * scenes: its rtol/10 estimate reports it.)  The lift at every sample:
 * within 1 % of the clearance (measured 0.6 %: a flank change 0.017 deg off
 * at a flight speed of ~0.3 c_a per degree). */
static void test_rigid_vs_full(void)
{
    struct {
        const char *what;
        double rpm;
        int gravity, gas, area;
    } cases[] = {
        {"1000 rpm inertia", 1000.0, 0, 0, 0},
        {"1000 rpm gravity", 1000.0, 1, 0, 0},
        {"6000 rpm gas fixed", 6000.0, 1, 1, RD_GAS_AREA_FIXED},
        {"6000 rpm gas dynamic", 6000.0, 1, 1, RD_GAS_AREA_DYNAMIC},
    };
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        p.engine.speed_rpm = cases[j].rpm;
        p.engine.cycles = 1.0;
        p.gravity = cases[j].gravity;
        p.estimate_error = 0;
        if (cases[j].gas)
            lift_battery_gas_tables(&p, cases[j].area);
        rd_lift_result a, b;
        rd_error err;
        p.rtol = 1e-8;
        p.atol = 1e-11;
        int rc = run(&p, RD_LIFT_MODEL_RIGID, 20, &a, &err);
        CHECK(rc == RD_OK, "%s rigid: %s", cases[j].what, err.message);
        p.rtol = 1e-8;
        p.atol = 1e-11;
        int rc2 = run(&p, RD_LIFT_MODEL_FULL, 20, &b, &err);
        CHECK(rc2 == RD_OK, "%s full: %s", cases[j].what, err.message);
        if (rc == RD_OK && rc2 == RD_OK) {
            double d = event_diff(&a, &b), dl = 0.0;
            for (int k = 0; k < a.samples; k++)
                dl = fmax(dl, fabs(a.lift[k] - b.lift[k]));
            CHECK(d < 0.03, "%s: rigid flank changes differ from full by %g deg", cases[j].what, d);
            CHECK(dl < 0.01 * p.groove.axial_clearance, "%s: lift differs by %g c_a", cases[j].what,
                  dl / p.groove.axial_clearance);
            CHECK(a.model == RD_LIFT_MODEL_RIGID && a.dof == 3 && b.model == RD_LIFT_MODEL_FULL,
                  "%s: models %d/%d dof %d", cases[j].what, a.model, b.model, a.dof);
            for (int i = 0; getenv("RD_VERBOSE") && i < a.n_events && i < b.n_events; i++)
                fprintf(stderr, "      %d %.4f %.4f\n", a.events[i].kind, a.events[i].crank_deg,
                        b.events[i].crank_deg);
            fprintf(stderr,
                    "    %-22s %d flank changes, rigid - full <= %.4f deg, lift %.4f c_a, "
                    "steps %ld vs %ld\n",
                    cases[j].what, a.n_events, d, dl / p.groove.axial_clearance, a.steps, b.steps);
        }
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
}

/* The sticking phase (rd_lift_stick.c) against the plain integration of
 * the same rigid model (stick = 0, the default), a second method for the seated phases
 * (quasi-static Newton and a scanned, bisected leave date vs CVODE steps
 * and root finding), at the same tolerances, on the axisymmetric scenes
 * without friction.  Flank changes within 0.01 deg (the bound;
 * measured 1.5e-4 deg: both runs' own error at rtol 1e-8).  Seated samples
 * (both on the same flank, L < eps = 1 % c_a): lift within 2e-4 c_a
 * (measured 7.3e-6 while the twist's tolerance was atol / R, 7.3e-5 with
 * atol / (b / 2) (rd_lift_rigid.c): these include the first rise off the
 * flank before a leave is confirmed, where the flights start 1e-4 deg apart;
 * the brief's 1e-6 holds only on the strictly pressed samples; 2e-4 c_a is
 * still 0.0007 deg of a flight).  Free samples: within
 * 0.3 % c_a (0.01 deg at a flight speed of ~0.3 c_a per degree; measured
 * 5.5e-5).  And the phase must have run: fewer steps. */
static void test_stick_vs_plain(void)
{
    struct {
        const char *what;
        double rpm;
        int gravity, gas, area;
    } cases[] = {
        {"1000 rpm inertia", 1000.0, 0, 0, 0},
        {"1000 rpm gravity", 1000.0, 1, 0, 0},
        {"6000 rpm gas fixed", 6000.0, 1, 1, RD_GAS_AREA_FIXED},
        {"6000 rpm gas dynamic", 6000.0, 1, 1, RD_GAS_AREA_DYNAMIC},
    };
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        p.engine.speed_rpm = cases[j].rpm;
        p.engine.cycles = 1.0;
        p.gravity = cases[j].gravity;
        p.estimate_error = 0;
        p.rtol = 1e-8;
        p.atol = 1e-11;
        if (cases[j].gas)
            lift_battery_gas_tables(&p, cases[j].area);
        rd_lift_result a, b;
        rd_error err;
        p.stick = 1;
        int rc = run(&p, RD_LIFT_MODEL_RIGID, 20, &a, &err);
        CHECK(rc == RD_OK, "%s sticking: %s", cases[j].what, err.message);
        p.stick = 0;
        p.cvode = 1; /* the plain CVODE integration the phase replaces */
        int rc2 = run(&p, RD_LIFT_MODEL_RIGID, 20, &b, &err);
        CHECK(rc2 == RD_OK, "%s plain: %s", cases[j].what, err.message);
        if (rc == RD_OK && rc2 == RD_OK) {
            double ca = p.groove.axial_clearance, d = event_diff(&a, &b), ds = 0.0, df = 0.0;
            for (int k = 0; k < a.samples; k++) {
                double e = fabs(a.lift[k] - b.lift[k]) / ca;
                if (a.flank[k] == b.flank[k] && a.flank[k] != RD_FLANK_FREE)
                    ds = fmax(ds, e);
                else
                    df = fmax(df, e);
            }
            CHECK(d < 0.01, "%s: sticking moves flank changes by %g deg", cases[j].what, d);
            CHECK(ds < 2e-4, "%s: seated lift differs by %g c_a", cases[j].what, ds);
            CHECK(df < 3e-3, "%s: free lift differs by %g c_a", cases[j].what, df);
            CHECK(a.steps < b.steps, "%s: steps %ld vs %ld", cases[j].what, a.steps, b.steps);
            fprintf(stderr,
                    "    %-22s %d flank changes, stick - plain <= %.2e deg, lift seated %.1e, "
                    "free %.1e c_a, steps %ld vs %ld\n",
                    cases[j].what, a.n_events, d, ds, df, a.steps, b.steps);
        }
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
}

/* The rigid model's own integrator (rd_lift_small.c, TR-BDF2, steps ending
 * at every root) against CVODE's BDF (rd_lift_params.cvode), a separately
 * written method, on the same equations: a battery of scenes, the
 * integrator at rtol 1e-8 against CVODE converged at rtol 1e-10 (its flank
 * changes move by < 1e-4 deg from 1e-9 to 1e-10 on these scenes).  Flank
 * changes within 0.005 deg and the lift within 3e-3 of the clearance (a
 * flight crosses ~0.3 c_a per degree, so 0.005 deg is 1.5e-3 c_a; twice
 * that for the lift at a sample just after a landing, where the settling
 * of the stiff contact is least accurate).  With Coulomb friction 0.02 deg:
 * its leave near 316 deg is decided by the twist's edge lift and converges
 * slowly in rtol (measured at rtol 1e-8: 0.007 deg off this integrator,
 * 0.009 deg CVODE). */
static void test_small_vs_cvode(void)
{
    struct {
        const char *what;
        double rpm, ca;
        int gravity, gas, fric, landing;
    } cases[] = {
        {"1000 rpm inertia", 1000.0, 3e-5, 0, 0, RD_FRICTION_NONE, RD_LANDING_PENALTY},
        {"1000 rpm plastic", 1000.0, 3e-5, 0, 0, RD_FRICTION_NONE, RD_LANDING_PLASTIC},
        {"100 rpm gravity 100 um", 100.0, 1e-4, 1, 0, RD_FRICTION_NONE, RD_LANDING_PENALTY},
        {"8000 rpm 5 um", 8000.0, 5e-6, 1, 0, RD_FRICTION_NONE, RD_LANDING_PENALTY},
        {"6000 rpm gas fixed", 6000.0, 3e-5, 1, RD_GAS_AREA_FIXED + 1, RD_FRICTION_NONE,
         RD_LANDING_PENALTY},
        {"6000 rpm gas dynamic", 6000.0, 3e-5, 1, RD_GAS_AREA_DYNAMIC + 1, RD_FRICTION_NONE,
         RD_LANDING_PENALTY},
        {"1000 rpm Coulomb", 1000.0, 3e-5, 0, 0, RD_FRICTION_COULOMB, RD_LANDING_PENALTY},
        {"3000 rpm Stribeck gas", 3000.0, 3e-5, 1, RD_GAS_AREA_FIXED + 1, RD_FRICTION_STRIBECK,
         RD_LANDING_PENALTY},
    };
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        p.engine.speed_rpm = cases[j].rpm;
        p.engine.cycles = 1.0;
        p.groove.axial_clearance = cases[j].ca;
        p.gravity = cases[j].gravity;
        p.friction.model = cases[j].fric;
        p.landing = cases[j].landing;
        p.estimate_error = 0;
        p.rtol = 1e-8;
        p.atol = 1e-11;
        if (cases[j].gas)
            lift_battery_gas_tables(&p, cases[j].gas - 1);
        rd_lift_result a, b;
        rd_error err;
        int rc = run(&p, RD_LIFT_MODEL_RIGID, 20, &a, &err);
        CHECK(rc == RD_OK, "%s small: %s", cases[j].what, err.message);
        p.cvode = 1;
        p.rtol = 1e-10;
        p.atol = 1e-13;
        int rc2 = run(&p, RD_LIFT_MODEL_RIGID, 20, &b, &err);
        CHECK(rc2 == RD_OK, "%s CVODE: %s", cases[j].what, err.message);
        if (rc == RD_OK && rc2 == RD_OK) {
            double d = event_diff(&a, &b), dl = 0.0;
            for (int k = 0; k < a.samples; k++)
                dl = fmax(dl, fabs(a.lift[k] - b.lift[k]) / cases[j].ca);
            CHECK(a.n_events > 0 || cases[j].rpm < 200.0, "%s: no flank change", cases[j].what);
            double tol = cases[j].fric == RD_FRICTION_COULOMB ? 0.02 : 0.005;
            CHECK(d < tol, "%s: flank changes differ by %g deg", cases[j].what, d);
            CHECK(dl < 3e-3, "%s: lift differs by %g c_a", cases[j].what, dl);
            fprintf(stderr,
                    "    %-24s %2d flank changes, small - CVODE 1e-10 <= %.1e deg, lift %.1e c_a, "
                    "steps %ld vs %ld\n",
                    cases[j].what, a.n_events, d, dl, a.steps, b.steps);
        }
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
}

/* The rigid model's error estimate (the rerun at rtol/10) is a claim: on a
 * battery at the default rtol 1e-6 it must track the true error (against
 * the same model converged at rtol 1e-10) within x3, for the flank-change
 * angles and for the lift.  Measured ratios 0.77-1.15: the integrator's
 * global error goes as ~rtol^(2/3), so the rerun's difference is ~0.78 of
 * the error. */
static void test_estimate_tracks(void)
{
    struct {
        double rpm, ca;
        int gravity, landing;
    } cases[] = {
        {1000.0, 3e-5, 0, RD_LANDING_PENALTY}, {300.0, 3e-5, 1, RD_LANDING_PENALTY},
        {8000.0, 5e-6, 1, RD_LANDING_PENALTY}, {6000.0, 1e-4, 1, RD_LANDING_PENALTY},
        {3000.0, 3e-5, 0, RD_LANDING_PLASTIC},
    };
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        p.engine.speed_rpm = cases[j].rpm;
        p.engine.cycles = 1.0;
        p.groove.axial_clearance = cases[j].ca;
        p.gravity = cases[j].gravity;
        p.landing = cases[j].landing;
        rd_lift_result a, b;
        rd_error err;
        int rc = run(&p, RD_LIFT_MODEL_RIGID, 20, &a, &err);
        CHECK(rc == RD_OK, "%g rpm: %s", cases[j].rpm, err.message);
        p.estimate_error = 0;
        p.rtol = 1e-10;
        p.atol = 1e-13;
        int rc2 = run(&p, RD_LIFT_MODEL_RIGID, 20, &b, &err);
        CHECK(rc2 == RD_OK, "%g rpm reference: %s", cases[j].rpm, err.message);
        if (rc == RD_OK && rc2 == RD_OK) {
            double de = event_diff(&a, &b), dl = 0.0;
            for (int k = 0; k < a.samples; k++)
                dl = fmax(dl, fabs(a.lift[k] - b.lift[k]) / cases[j].ca);
            CHECK(a.n_events > 0 && de < 1e9, "%g rpm: flank changes differ", cases[j].rpm);
            CHECK(a.event_error_deg <= 3.0 * de && a.event_error_deg >= de / 3.0,
                  "%g rpm: event estimate %.3g deg, true %.3g deg", cases[j].rpm, a.event_error_deg,
                  de);
            CHECK(a.error_estimate <= 3.0 * dl && a.error_estimate >= dl / 3.0,
                  "%g rpm: lift estimate %.3g, true %.3g c_a", cases[j].rpm, a.error_estimate, dl);
            fprintf(stderr,
                    "    %5.0f rpm estimate / true: flank changes %.3g / %.3g deg, lift %.3g / "
                    "%.3g c_a\n",
                    cases[j].rpm, a.event_error_deg, de, a.error_estimate, dl);
        }
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
}

/* Issue 10's promise for the default (auto, which runs the rigid model
 * here): its flank changes within 0.05 deg of the full model's, on the
 * thesis ring at 1000 rpm with and without gravity.  Dated at the band
 * (1 %), the full model at the default rtol 1e-6 is itself up to 0.12 deg
 * off on the leaves (its rtol/10 estimate says 0.11 deg), the rigid one
 * 0.01 deg: the reference is the full model at rtol 1e-8 (measured 0.014
 * deg). */
static void test_default_answers(void)
{
    for (int grav = 0; grav < 2; grav++) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        p.engine.cycles = 1.0;
        p.gravity = grav;
        p.estimate_error = 0;
        rd_lift_result a, b;
        rd_error err;
        int rc = run(&p, p.model, 20, &a, &err);
        p.rtol = 1e-8;
        p.atol = 1e-11;
        int rc2 = run(&p, RD_LIFT_MODEL_FULL, 20, &b, &err);
        CHECK(rc == RD_OK && rc2 == RD_OK && a.model == RD_LIFT_MODEL_RIGID, "defaults: %d %d %d",
              rc, rc2, a.model);
        double d = event_diff(&a, &b);
        CHECK(d < 0.05, "gravity %d: default (auto) flank changes moved by %g deg from full", grav,
              d);
        fprintf(stderr, "    defaults, gravity %d: auto vs full %.4f deg\n", grav, d);
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
}

/* Extremes: finite, inside the groove (penetration < 10 % of the
 * clearance), every output field filled. */
static void test_rigid_extremes(void)
{
    struct {
        const char *what;
        double rpm, cycles, ca, kfac;
        int fric, gas;
    } cases[] = {
        {"1 rpm", 1.0, 0.1, 3e-5, 0, 0, 0},
        {"20000 rpm", 20000.0, 1.0, 3e-5, 0, 0, 0},
        {"clearance 1e-6", 1000.0, 1.0, 1e-6, 0, 0, 0},
        {"clearance 1e-3", 1000.0, 1.0, 1e-3, 0, 0, 0},
        {"stiffness 1e3 x", 1000.0, 1.0, 3e-5, 1e3, 0, 0},
        {"stribeck + gas 20000 rpm", 20000.0, 1.0, 3e-5, 0, RD_FRICTION_STRIBECK, 1},
        {"coulomb + gas 1 um", 6000.0, 1.0, 1e-6, 0, RD_FRICTION_COULOMB, 1},
    };
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        p.engine.speed_rpm = cases[j].rpm;
        p.engine.cycles = cases[j].cycles;
        p.groove.axial_clearance = cases[j].ca;
        p.gravity = 1;
        p.friction.model = cases[j].fric;
        p.estimate_error = 1;
        if (cases[j].gas)
            lift_battery_gas_tables(&p, RD_GAS_AREA_DYNAMIC);
        if (cases[j].kfac > 0.0)
            p.contact_stiffness = cases[j].kfac * rd_lift_contact_stiffness_default(&rp, &p);
        rd_lift_result r;
        rd_error err;
        int rc = run(&p, RD_LIFT_MODEL_RIGID, 20, &r, &err);
        CHECK(rc == RD_OK, "%s: %s", cases[j].what, err.message);
        int ok = rc == RD_OK;
        for (int k = 0; ok && k < r.samples; k++)
            ok = isfinite(r.lift[k]) && isfinite(r.twist[k]) && isfinite(r.friction_force[k]) &&
                 r.lift_min[k] > -0.1 * cases[j].ca && r.lift_max[k] < 1.1 * cases[j].ca &&
                 r.lift_segments[(size_t)k * 20 + 19] == r.lift[k];
        CHECK(ok, "%s: a sample is not finite or outside the groove", cases[j].what);
        CHECK(rc != RD_OK || isfinite(r.error_estimate), "%s: no error estimate", cases[j].what);
        rd_lift_result_cleanup(&r);
    }
}

/* auto: the rigid ring without friction, the full ring with friction at
 * any target. */
static void test_auto(void)
{
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.engine.cycles = 0.25;
    p.step_deg = 5.0;
    p.estimate_error = 0;
    rd_lift_result r;
    rd_error err;
    int rc = run(&p, RD_LIFT_MODEL_AUTO, 8, &r, &err);
    CHECK(rc == RD_OK && r.model == RD_LIFT_MODEL_RIGID && r.dof == 3 &&
              strstr(r.why, "axisymmetric") != NULL,
          "auto, no friction: rc %d model %d why '%s'", rc, r.model, r.why);
    rd_lift_result_cleanup(&r);
    /* with friction auto runs the rigid ring and checks it against the full
     * ring over its flights (rd_lift_check.c): here they agree within 3.2e-5
     * deg, so at the default target it keeps the rigid ring ... */
    p.friction.model = RD_FRICTION_COULOMB;
    rc = run(&p, RD_LIFT_MODEL_AUTO, 8, &r, &err);
    CHECK(rc == RD_OK && r.model == RD_LIFT_MODEL_RIGID && r.dof == 3 &&
              strstr(r.why, "checked at run time") != NULL && r.event_error_model_deg < 1e-3,
          "auto, friction: rc %d model %d why '%s'", rc, r.model, r.why);
    rd_lift_result_cleanup(&r);
    /* ... and over half a cycle, where the rigid ring's second flight is
     * 0.35 deg off the full ring's, it runs the full ring, saying why */
    p.engine.cycles = 0.5;
    rc = run(&p, RD_LIFT_MODEL_AUTO, 8, &r, &err);
    CHECK(rc == RD_OK && r.model == RD_LIFT_MODEL_FULL && r.dof == 48 &&
              strstr(r.why, "more than numerics.accuracy_deg") != NULL,
          "auto, friction, half a cycle: model %d (%s)", r.model, r.why);
    rd_lift_result_cleanup(&r);
    /* a ring held on its flank by 5 bar above and behind it: the rigid run
     * has no flank change, and the check runs the full ring over the whole
     * run, which must stay seated too */
    static double gdeg[2] = {0.0, 720.0}, ghi[2] = {5e5, 5e5}, gzero[2] = {0.0, 0.0};
    p.gas = (rd_gas_params){2, gdeg, ghi, ghi, gzero, RD_GAS_AREA_FIXED};
    rc = run(&p, RD_LIFT_MODEL_AUTO, 8, &r, &err);
    CHECK(rc == RD_OK && r.model == RD_LIFT_MODEL_RIGID && r.n_events == 0 &&
              strstr(r.why, "stays on its flank") != NULL,
          "auto, friction, held down: rc %d model %d events %d (%s)", rc, r.model, r.n_events,
          r.why);
    rd_lift_result_cleanup(&r);
}

/* The rigid model's analytic Jacobian (the projection of segment 0's local
 * blocks) vs central differences of its right-hand side, at states that
 * engage every force law: pressed into the lower and the upper flank (inside
 * the quadratic start and in the linear range), twisted so one edge carries
 * more, pushed radially, moving; Coulomb and Stribeck friction near a
 * sliding reversal; dynamic gas areas.  The differences carry ~1e-5
 * relative rounding on the stiff entries; tolerance 1e-4 (as test_lift's
 * full-model check). */
static void test_rigid_jacobian(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    double deg[] = {0, 400, 720}, above[] = {2e5, 1e6, 2e5}, behind[] = {1e5, 8e5, 1e5},
           below[] = {0, 3e5, 0};
    for (int fm = 1; fm <= 2; fm++)
        for (int st = 0; st < 4; st++) {
            rd_lift_params p;
            rd_lift_params_default(&p);
            p.model = RD_LIFT_MODEL_RIGID;
            p.gravity = 1;
            p.friction.model = fm;
            p.gas = (rd_gas_params){3, deg, above, behind, below, RD_GAS_AREA_DYNAMIC};
            double ca = p.groove.axial_clearance, d0 = 1e-4 * ca;
            double z[4] = {-0.3 * d0, -4.0 * d0, ca + 0.4 * d0, ca + 5.0 * d0};
            double y[6] = {z[st], (st % 2 ? 1e-9 : -2e-9), 1e-8 * (st - 1), (st - 1.5) * 1e-4,
                           1e-6,  1e-5 * (st - 2)};
            double e = 1e9;
            rd_error err;
            rd_error_init(&err);
            /* t = 3 us: the piston speed ~ u_reg, friction in its regularized range */
            int rc = rd_lift_jacobian_check(&rp, 8, &p, 3e-6, y, &e, &err);
            CHECK(rc == RD_OK, "rigid jacobian check: %s", err.message);
            CHECK(e < 1e-4, "rigid, friction %d, state %d: Jacobian differs by %g (relative)", fm,
                  st, e);
        }
}

static void expect_invalid(const rd_lift_params *p, const char *path, const char *text)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_validate(p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, path) && strstr(err.message, text),
          "want %s (%s): rc %d path %s: %s", path, text, rc, err.path, err.message);
}

static void test_validation(void)
{
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.model = 7;
    expect_invalid(&p, "/numerics/model", "unknown");
    p.model = RD_LIFT_MODEL_MODAL;
    p.modes = 43; /* 8 segments: 6 x 8 - 6 = 42 elastic modes */
    expect_invalid(&p, "/numerics/modes", "42 elastic modes");
    p.modes = 0;
    p.model = RD_LIFT_MODEL_AUTO;
    p.accuracy_deg = 0.0;
    expect_invalid(&p, "/numerics/accuracy_deg", "out of range");
    p.accuracy_deg = NAN;
    expect_invalid(&p, "/numerics/accuracy_deg", "out of range");
}

/* The curved-beam (Vlasov) continuum of the split ring seated on one edge
 * under a uniform couple m per unit length, written separately from the
 * segmented ring: axial displacement w and twist phi of the centroid line,
 * bending curvature kappa = w'' - phi / R, torsion rate tau = phi' + w' / R
 * (both zero for a rigid rotation about a diameter), the support at radial
 * offset rho holding the edge: w = rho phi.  Energy per unit length
 *     E I / 2 (rho phi'' - phi / R)^2 + G J' / 2 phi'^2 - m phi,
 * J' = J (1 + rho / R)^2; Euler-Lagrange
 *     E I rho^2 phi'''' - (G J' + 2 E I rho / R) phi'' + E I / R^2 phi = m,
 * free ends: kappa = 0 and -E I rho kappa' + G J' phi' = 0 at s = +-L/2
 * (L = span R).  The solution is symmetric, phi = m R^2 / (E I) (1 +
 * A cosh(l1 s) + C cosh(l2 s)) with l1, l2 the characteristic roots.
 * Returns k_edge / k_u = the uniform twist over the mean twist. */
static double continuum_edge_ratio(const rd_ring_section *sec, double E, double rho)
{
    double R = sec->R, L = sec->span * R, EI = E * sec->I_outplane;
    double GT = sec->G * sec->J * (1.0 + rho / R) * (1.0 + rho / R);
    double B = GT + 2.0 * EI * rho / R, a4 = EI * rho * rho, c0 = EI / (R * R);
    double disc = sqrt(B * B - 4.0 * a4 * c0);
    double l[2] = {sqrt((B + disc) / (2.0 * a4)), sqrt((B - disc) / (2.0 * a4))};
    double row[2][2], h = 0.5 * L;
    for (int j = 0; j < 2; j++) { /* the two end conditions per unit amplitude */
        double ch = cosh(l[j] * h), sh = sinh(l[j] * h);
        double kap1 = rho * pow(l[j], 3) * sh - l[j] * sh / R;
        row[0][j] = rho * l[j] * l[j] * ch - ch / R;
        row[1][j] = -EI * rho * kap1 + GT * l[j] * sh;
    }
    /* the uniform part (amplitude 1) has kappa = -1 / R and no shear term */
    double det = row[0][0] * row[1][1] - row[0][1] * row[1][0];
    double A = row[1][1] / (R * det), C = -row[1][0] / (R * det);
    double mean = 1.0 + (A * 2.0 * sinh(l[0] * h) / l[0] + C * 2.0 * sinh(l[1] * h) / l[1]) / L;
    return 1.0 / mean;
}

/* The rigid model's twist stiffness (rd_lift_rigid.c "Effective twist
 * stiffness").  Rayleigh: the seated split ring is never stiffer than the
 * uniform twist shape, and its softening shrinks as the segments resolve the
 * free ends (n = 4 ... 80).  Against the continuum above at n = 400: k_u
 * within 1 % of E I_out span / R (measured 0.25 %: the chords' O(1/n^2) and
 * the Timoshenko shear), each edge's k_edge / k_u within 0.003 of the
 * continuum's ~0.988 (measured ~0.0015: the same, plus the segments'
 * support at their middles only), i.e. the softening itself within a
 * quarter. */
static void test_twist_stiffness(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    rd_ring_section sec;
    rd_ring_section_get(&rp, 0, &sec);
    double prev = 0.0, k[3];
    int ns[] = {4, 8, 20, 40, 80};
    rd_error err;
    for (int j = 0; j < 5; j++) {
        rd_error_init(&err);
        int rc = rd_lift_twist_stiffness(&rp, ns[j], &p, k, &err);
        CHECK(rc == RD_OK, "twist stiffness n = %d: %s", ns[j], err.message);
        double hi = fmax(k[1], k[2]) / k[0];
        CHECK(fmin(k[1], k[2]) > 0.0 && hi <= 1.0 && hi > prev,
              "n = %d: k_u %g, k_inner %g, k_outer %g (ratio %g after %g)", ns[j], k[0], k[1], k[2],
              hi, prev);
        prev = hi;
    }
    rd_error_init(&err);
    CHECK(rd_lift_twist_stiffness(&rp, 400, &p, k, &err) == RD_OK, "n = 400: %s", err.message);
    double ku = rp.youngs_modulus * sec.I_outplane * sec.span / sec.R;
    CHECK(fabs(k[0] / ku - 1.0) < 0.01, "k_u %g vs the continuum's %g", k[0], ku);
    for (int e = 0; e < 2; e++) {
        double rho = (e ? 0.5 : -0.5) * rp.radial_width;
        double want = continuum_edge_ratio(&sec, rp.youngs_modulus, rho);
        CHECK(fabs(k[1 + e] / k[0] - want) < 0.003, "edge %d: k_edge / k_u %g, continuum %g", e,
              k[1 + e] / k[0], want);
        fprintf(stderr, "    n = 400, edge %d: k_edge / k_u %.4f, continuum %.4f\n", e,
                k[1 + e] / k[0], want);
    }
    /* up to the largest n the lift allows: the supports' band Cholesky
     * failed at n = 700, 800 and 1000 (issue 45) while its shift of the
     * in-plane motions fell below its round-off */
    for (int n = 700; n <= 1000; n += 100) {
        rd_error_init(&err);
        CHECK(rd_lift_twist_stiffness(&rp, n, &p, k, &err) == RD_OK, "n = %d: %s", n, err.message);
        for (int e = 0; e < 2; e++) {
            double rho = (e ? 0.5 : -0.5) * rp.radial_width;
            double want = continuum_edge_ratio(&sec, rp.youngs_modulus, rho);
            CHECK(fabs(k[1 + e] / k[0] - want) < 0.003,
                  "n = %d, edge %d: k_edge / k_u %g, continuum %g", n, e, k[1 + e] / k[0], want);
        }
    }
}

/* With friction the running face's couple twists the split ring more at its
 * free ends; the rigid ring takes it with the seated split ring's stiffness
 * (rd_lift_rigid.c).  Against the full model (thesis ring, n = 8, 1000 rpm,
 * Coulomb 0.1, gravity; the full model at rtol 1e-7, the rigid one at 1e-8,
 * 340 deg): the twist 6 deg before the full ring's twist-driven leave from
 * the lower flank within 6 % (measured 4.0 % more; the uniform twist
 * stiffness gave 11 % less), and the flank changes within 0.5 deg (measured
 * 0.40 deg, the leave; 1.32 deg with the uniform stiffness): what remains is
 * the flank contact, which the supports at the segments' middles idealize
 * (the twist grows ~25 % per degree there, so 6 % is a quarter degree). */
static void test_rigid_friction_vs_full(void)
{
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.engine.cycles = 340.0 / 720.0;
    p.gravity = 1;
    p.friction.model = RD_FRICTION_COULOMB;
    p.estimate_error = 0;
    p.step_deg = 1.0;
    rd_lift_result a, b;
    rd_error err;
    p.rtol = 1e-8;
    p.atol = 1e-11;
    int rc = run(&p, RD_LIFT_MODEL_RIGID, 8, &a, &err);
    p.rtol = 1e-7;
    p.atol = 1e-10;
    int rc2 = run(&p, RD_LIFT_MODEL_FULL, 8, &b, &err);
    CHECK(rc == RD_OK && rc2 == RD_OK, "friction runs: %d %d", rc, rc2);
    if (rc == RD_OK && rc2 == RD_OK) {
        double d = event_diff(&a, &b);
        CHECK(d < 0.5, "friction: rigid vs full flank changes %g deg", d);
        int k = b.n_events > 0 ? (int)b.events[b.n_events - 1].crank_deg - 6 : 0;
        CHECK(b.n_events >= 5 && b.events[b.n_events - 1].kind == RD_EVENT_LEAVE_LOWER && k > 0 &&
                  k < b.samples && fabs(a.twist[k] / b.twist[k] - 1.0) < 0.06,
              "friction: twist at %d deg rigid %g full %g", k, k > 0 ? a.twist[k] : 0.0,
              k > 0 ? b.twist[k] : 0.0);
        fprintf(stderr, "    friction n = 8: flank changes %.3f deg, twist ratio %.4f\n", d,
                a.twist[k] / b.twist[k]);
    }
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

int main(void)
{
    test_twist_stiffness();
    test_rigid_friction_vs_full();
    test_validation();
    test_rigid_jacobian();
    test_auto();
    test_rigid_extremes();
    test_rigid_vs_full();
    test_stick_vs_plain();
    test_small_vs_cvode();
    test_estimate_tracks();
    test_default_answers();
    return check_done();
}
