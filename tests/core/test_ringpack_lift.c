/*
 * test_ringpack_lift — the pack's rings on the lift analysis' models
 * (core/rd_ringpack_lift.c, rd_ringpack_newton.c).
 *
 * Second method: the lift analysis run alone on the same ring, driven by
 * the pack's computed pressures as its gauge gas tables (above: the land
 * over the ring, behind: its groove, below: the volume under it, each minus
 * the crankcase pressure), at the same contact stiffness.  The lift run has
 * no gas network: its loads are fixed tables read by linear interpolation,
 * its integration and event tracking are its own driver's.  If the pack fed
 * its ring other pressures than it reports, or the ring's lift did not
 * reach the network, or the coupled Newton solve converged to something
 * else, the flank changes would part.
 *   (1) a full (flexible, n = 20) ring without friction;
 *   (2) a rigid ring (lift, twist, radial) with Coulomb friction: the pack's
 *       axial ring misses its first leave by degrees (it cannot twist;
 *       README "Ring pack"), the rigid one must not;
 *   (3) the mass balance with a flexible ring: inflow - reverse - blow-by -
 *       stored change <= 1e-6 of the throughput, the stored gas recomputed
 *       here from the reported pressures and volumes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

#define RG 287.0

static int run(const rd_ringpack_params *p, rd_ringpack_result *r, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    return rc;
}

/* (3): the balance over the last cycle, recomputed from the output. */
static void check_mass(const rd_ringpack_params *p, const rd_ringpack_result *r, const char *what)
{
    int S = r->samples - 1;
    double stored = 0.0;
    for (int v = 1; v < r->n_volumes - 1; v++)
        stored += (r->pressure[(size_t)v * r->samples + S] - r->pressure[(size_t)v * r->samples]) *
                  r->volume_m3[v] / (RG * p->T_lands);
    double thru = r->inflow_kg + r->reverse_kg;
    double res = fabs(r->inflow_kg - r->reverse_kg - r->blowby_kg - stored) / thru;
    /* 1e-6: the bound; BDF keeps the linear invariant to round-off,
     * the output's 6-digit-free doubles leave ~1e-12 */
    CHECK(res <= 1e-6 && r->mass_residual <= 1e-6, "%s: mass balance %.3g (reported %.3g)", what,
          res, r->mass_residual);
    printf("%s: mass balance %.2e of the throughput %.3g kg\n", what, res, thru);
}

/* The pack's ring 0 against the lift analysis on the pack's pressures; the
 * largest flank-change difference for leaves and landings into dl, dg. */
static void pack_vs_lift(int model, double mu, const char *what, double *dl, double *dg)
{
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    p.engine.cycles = 2;
    p.estimate_error = 0;
    p.step_deg = 0.25;
    p.rings[0].model = model;
    p.rings[0].segments = 20;
    if (mu > 0.0) {
        p.friction.model = RD_FRICTION_COULOMB;
        p.friction.coefficient = mu;
        /* the twist-driven leave with friction is sensitive to the pressures
         * behind the ring: with the lift run's tables at 0.25 deg (linear
         * interpolation) the leaves differed by 0.06-0.10 deg, at 0.05 deg
         * and rtol 1e-8 in both runs by 0.025 deg */
        p.rtol = 1e-8;
        p.step_deg = 0.05;
    }
    rd_ringpack_result r;
    rd_lift_result l;
    memset(&l, 0, sizeof l);
    *dl = *dg = NAN;
    if (run(&p, &r, what) != RD_OK) {
        rd_ringpack_result_cleanup(&r);
        return;
    }
    check_mass(&p, &r, what);
    CHECK(r.ring_model[0] == model && r.ring_dof[0] == (model == RD_LIFT_MODEL_FULL ? 120 : 3),
          "%s: model %d, dof %d", what, r.ring_model[0], r.ring_dof[0]);
    int S = r.samples;
    double *tab = malloc(3 * (size_t)S * sizeof *tab);
    CHECK(tab != NULL, "memory");
    if (!tab)
        return;
    for (int k = 0; k < S; k++)
        for (int f = 0; f < 3; f++) /* land_1, groove_1, crankcase */
            tab[(size_t)f * S + k] = r.pressure[(size_t)(f + 1) * S + k] - p.crankcase_pa;
    rd_lift_params lp;
    rd_lift_params_default(&lp);
    lp.engine = p.engine;
    lp.engine.cycles = 1; /* the pack's last cycle starts seated at rest, as the lift run */
    lp.groove = p.rings[0].groove;
    lp.friction = p.friction;
    lp.gravity = p.gravity;
    lp.gas = (rd_gas_params){S, r.crank_deg, tab, tab + S, tab + 2 * S, RD_GAS_AREA_FIXED};
    /* the pack steps its rings with CVODE: so does the lift run here (its
     * rigid model's own integrator, rd_lift_small.c, carries the twist-driven
     * leave with friction to within ~0.1 deg at rtol 1e-6, a different
     * integration error from the same equations: test_lift_rigid checks it) */
    lp.cvode = 1;
    lp.rtol = p.rtol;
    lp.contact_stiffness = r.ring_stiffness[0];
    lp.estimate_error = 0;
    lp.model = model;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve(&p.rings[0].ring, 20, &lp, NULL, &l, &err);
    CHECK(rc == RD_OK, "%s: lift: %s", what, err.message);
    if (rc == RD_OK) {
        CHECK(l.n_events == r.n_events[0] && l.n_events >= 4, "%s: events lift %d, pack %d", what,
              l.n_events, r.n_events[0]);
        *dl = *dg = 0.0;
        for (int e = 0; e < l.n_events && e < r.n_events[0]; e++) {
            int kind = l.events[e].kind;
            CHECK(r.events[0][e].kind == kind, "%s: event %d kinds %d, %d", what, e, kind,
                  r.events[0][e].kind);
            double d = fabs(l.events[e].crank_deg - r.events[0][e].crank_deg);
            if (kind == RD_EVENT_LEAVE_LOWER || kind == RD_EVENT_LEAVE_UPPER)
                *dl = fmax(*dl, d);
            else
                *dg = fmax(*dg, d);
        }
        printf("%s: %d flank changes, leaves within %.4f deg, landings within %.4f deg\n", what,
               l.n_events, *dl, *dg);
    }
    free(tab);
    rd_ringpack_result_cleanup(&r);
    rd_lift_result_cleanup(&l);
}

/* Tolerances.  Leaving a flank is dated by the load's sign change, the
 * same sum of forces in both runs but for the table interpolation of the
 * pressures (0.25 deg samples): measured 1e-3 deg without friction; with
 * friction the load holds mu N tanh(u / u_reg) of the ring's own sliding
 * speed and the leave is decided by the twist's edge lift, which the
 * tables' interpolation moves (samples at 0.05 deg and rtol 1e-8 there:
 * 0.025 deg measured), so 0.06 deg.  A landing ends a flight whose time both integrators carry at
 * rtol 1e-6: the pack's own landing angle moves by up to 0.04 deg when only
 * its output step changes (1, 0.5, 0.25, 0.1 deg: 295.200..295.242 on the
 * full ring's scene), so 0.1 deg. */
#define TOL_LEAVE 0.06
#define TOL_LAND  0.1

static void test_full(void)
{
    double dl, dg;
    pack_vs_lift(RD_LIFT_MODEL_FULL, 0.0, "full ring", &dl, &dg);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "full ring: leaves %.4f, landings %.4f deg", dl, dg);
}

/* Friction's couple twists the ring, so it rocks off the lower flank
 * earlier than its axial load alone says: the rigid ring must follow the
 * lift rigid model (tolerances above), and the axial ring must be degrees
 * off on the same scene (so the comparison can tell them apart). */
static void test_rigid_friction(void)
{
    double dl, dg;
    pack_vs_lift(RD_LIFT_MODEL_RIGID, 0.1, "rigid ring, mu 0.1", &dl, &dg);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "rigid ring: leaves %.4f, landings %.4f deg", dl, dg);
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    p.engine.cycles = 2;
    p.estimate_error = 0;
    p.friction.model = RD_FRICTION_COULOMB;
    double first[2] = {NAN, NAN};
    for (int a = 0; a < 2; a++) {
        rd_ringpack_result r;
        p.model = a ? RD_RINGPACK_AXIAL : RD_LIFT_MODEL_AUTO;
        if (run(&p, &r, "auto / axial") == RD_OK && r.n_events[0] > 0)
            first[a] = r.events[0][0].crank_deg;
        CHECK(r.ring_model[0] == (a ? RD_RINGPACK_AXIAL : RD_LIFT_MODEL_RIGID),
              "auto with friction is rigid: %d", r.ring_model[0]);
        rd_ringpack_result_cleanup(&r);
    }
    printf("first leave with friction: rigid %.3f deg, axial %.3f deg\n", first[0], first[1]);
    CHECK(first[1] - first[0] > 2.0, "the axial ring leaves %.3f deg after the rigid one",
          first[1] - first[0]);
}

/* (3) on three rings, a flexible top ring (coarse: the balance does not
 * depend on n, and the run stays short under the sanitizers). */
static void test_mass_flexible(void)
{
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    p.n_rings = 3;
    p.engine.cycles = 2;
    p.estimate_error = 0;
    p.rings[1].ring.axial_height = 0.0015;
    p.rings[2].ring.axial_height = 0.0025;
    p.rings[0].model = RD_LIFT_MODEL_FULL;
    p.rings[0].segments = 8;
    p.rings[1].model = RD_LIFT_MODEL_MODAL;
    p.rings[1].segments = 8;
    p.rings[1].modes = 6;
    rd_ringpack_result r;
    if (run(&p, &r, "3 rings, full and modal") == RD_OK) {
        check_mass(&p, &r, "3 rings, full and modal");
        CHECK(r.ring_model[1] == RD_LIFT_MODEL_MODAL && r.ring_modes[1] == 6 &&
                  r.ring_model[2] == RD_RINGPACK_AXIAL,
              "models %d %d %d", r.ring_model[0], r.ring_model[1], r.ring_model[2]);
    }
    rd_ringpack_result_cleanup(&r);
}

int main(void)
{
    test_full();
    test_rigid_friction();
    test_mass_flexible();
    return check_done();
}
