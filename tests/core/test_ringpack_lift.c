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
 * else, the flank changes would part.  Both runs date the flank changes
 * at the same flank band (output.flank_band; BANDS below), and their
 * touch_deg must agree too.
 *   (1) a full (flexible, n = 20) ring without friction;
 *   (2) a rigid ring (lift, twist, radial) with Coulomb friction: the pack's
 *       axial ring misses its first leave by degrees (it cannot twist;
 *       README "Ring pack"), the rigid one must not;
 *   (3) the mass balance with a flexible ring: inflow - reverse - blow-by -
 *       stored change <= 1e-6 of the throughput, the stored gas recomputed
 *       here from the reported pressures and volumes;
 *   (4) a tilted piston and (5) a distorted bore, given to the lift run by
 *       hand in the ring's frame (its gap at 180 deg: the tilt negated; at
 *       90 deg: the bore's phases turned by -90 deg), auto's full ring;
 *   (6) dynamic active areas: a ring pressed on its lower flank by fixed
 *       face pressures, whose flank load (hence penetration) follows from
 *       the mean of the bottom face's edge pressures in closed form, and
 *       the lift run on the pack's pressures; the mass balance with all
 *       three on a 3-ring pack.
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

/* What the pack passes on to its ring beyond the default scene (cases
 * 4-6): its gap angle, the piston tilt, the bore and the active areas, and
 * the lift run's own copies of the tilt and bore, written here by hand in
 * the ring's frame (angles from its gap). */
typedef struct extras {
    double gap_deg;
    rd_engine_params tilt; /* piston_tilt_deg, table */
    rd_bore bore;
    int area;                    /* enum rd_gas_area */
    rd_engine_params lift_tilt;  /* the same tilt as the ring sees it */
    rd_bore lift_bore;           /* the same bore as the ring sees it */
    int expect;                  /* the model auto must pick */
    int segments;                /* 0: 20 */
    double rtol, atol, step_deg; /* 0: the defaults below */
    int lift_cycles;             /* the lift run's, its last compared; 0: 1 */
    double band;                 /* output.flank_band of both runs (BANDS below) */
    const rd_bore_map *map;      /* the pack's bore map (its phases from the bore's angle 0) */
    const rd_bore_map *lift_map; /* the same map as the ring sees it */
    double ring_z;               /* the ring's depth on both maps at TDC, m */
} extras;

/* The last comparison's pack events (crank deg, the first 8) and its
 * friction force's difference from the lift run's, summed over the cycle's
 * samples, over the sum of its size (a max norm would be the reversals'
 * at the dead centres, where tanh(u / u_reg) swings in a few hundredths of
 * a degree). */
static double pack_events[8], friction_gap;
static int n_pack_events;
/* The same comparison's first flank change: the angle between the runs,
 * the pack's lift slope there (m per crank deg, from its samples either
 * side), and the largest lift differences over the samples before it (from
 * 1 deg: the lift run starts at rest, the pack's last cycle pressed into
 * its flank), in m: from the first sample after the gas (every gauge
 * pressure below 1 Pa: the lift run's tables then give it the pack's loads
 * to 1 Pa) where the ring is pressed into its flank again, and before. */
static double first_gap, first_slope, calm_gap, gas_gap;

static const extras NONE = {0};

/* Tolerances.  Leaving a flank is dated by the load's sign change, the
 * same sum of forces in both runs but for the table interpolation of the
 * pressures: measured below 1e-4 deg without friction.  With friction a
 * leave can be dated instead where the twist's edge lift carries the mean
 * lift to eps (test_rigid_friction: ill-conditioned, compared there through
 * the lift); the bore's leaves, with friction, came within 0.0054 deg at
 * rtol x0.97-1.03.  0.06 deg.
 * A landing ends a flight whose start is not resolved at atol 1e-9 m (the
 * ring leaves with zero speed from a penetration below 1 nm): on the full
 * ring's, the tilted and the dynamic-area scenes the landings came
 * 0.007-0.085 deg apart at rtol x0.97-1.03 (at atol 1e-11: 1e-4 deg, but
 * twice the steps), and the pack's own landing moves by up to 0.04 deg
 * when only its output step changes (1, 0.5, 0.25, 0.1 deg: 295.200..295.242
 * on the full ring's scene), so 0.1 deg.
 * TOUCH: a full ring lands progressively, its mean lift bouncing a few nm
 * below the flank before it stays; when a bounce's peak comes within atol
 * of the flank, whether it counts as the landing is undecided by either
 * integrator (the bore's scene: peaks 0.94 deg apart, one reaching the
 * flank by 0.2 nm in one run and missing it by 0.1 nm in the other, at 3 of
 * 7 rtols x0.97-1.03).  So a landing more than TOL_LAND apart still agrees
 * when at each run's date the other run's mean lift is within atol of that
 * flank (measured 0.09-0.44 nm there): the dates' difference turned into
 * the lift's, which is well conditioned. */
#define TOL_LEAVE 0.06
#define TOL_LAND  0.1
/* BANDS: these tolerances are the touch dating's (flank_band 0), and so
 * are the touch_deg's at any band: a leave's is where the load turned
 * away, a landing's where the mean lift reached the flank.  The cases
 * below run at flank_band 0, but the full ring's and the rigid ring's with
 * friction at the default 0.01, whose dates are the mean lift crossing the
 * band's edge in flight: a landing's fast (compared as a landing's date,
 * without TOUCH), a leave's 1.8 deg after it left, at ~5e-7 m/deg; the
 * runs' lifts there agree within ~15 atol (the lift run reads the pack's
 * pressures from tables), so TOL_LEAVE holds: measured 0.031 deg on the
 * full ring (its landings 0.007 deg), 0.0007 deg on the rigid ring with
 * friction (its landings 0.0002 deg; at atol 1e-12).  The tilt, the bore
 * and the dynamic areas
 * (their landings TOUCH, their leaves' rocking) were measured at flank_band
 * 0: there the band adds bounces that leave it in one run and not in the
 * other (the bore's: 10 and 8). */
/* Landings matched by touch rather than by date, in the last comparison
 * (TOUCH above). */
static int n_touch;
static double touch_gap; /* the largest of those lift distances, every landing */

/* The mean lift L (n samples from 0 deg, `step` apart) at `deg`, linear
 * between samples (their error ~h^2 L'' / 8: 3e-11 m at 0.05 deg on the
 * ~2 nm bounces below the flank). */
static double lift_at(const double *L, int n, double step, double deg)
{
    int k = (int)floor(deg / step);
    if (k < 0 || k + 1 >= n)
        return k == n - 1 ? L[k] : NAN;
    double w = deg / step - k;
    return (1.0 - w) * L[k] + w * L[k + 1];
}

/* The pack's ring 0 against the lift analysis on the pack's pressures; the
 * largest flank-change difference for leaves and landings into dl, dg. */
static void pack_vs_lift_x(int model, double mu, const extras *x, const char *what, double *dl,
                           double *dg)
{
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    p.engine.cycles = 2;
    p.estimate_error = 0;
    p.step_deg = 0.25;
    /* the orifice passages these tolerances were measured on: the ring
     * models are compared here, under the same pressures whatever law made
     * them (with the viscous limit the full ring's leave, dated 1.8 deg
     * after it left the flank at 1 % of the clearance, came 0.066 deg apart
     * at a 0.25 deg output step and 0.17 deg at 0.1: the slower flight
     * makes the band's date worse conditioned, not the models apart) */
    p.flank_passage = RD_PASSAGE_ORIFICE;
    p.flank_pressure = RD_FLANK_PRESSURE_FULL; /* the lift run's faces: the tables' pressures */
    p.rings[0].model = model;
    int n = x->segments ? x->segments : 20;
    p.rings[0].segments = n;
    p.rings[0].gap_angle_deg = x->gap_deg;
    p.engine.piston_tilt_deg = x->tilt.piston_tilt_deg;
    p.engine.tilt_points = x->tilt.tilt_points;
    p.engine.tilt_crank_deg = x->tilt.tilt_crank_deg;
    p.engine.tilt_deg = x->tilt.tilt_deg;
    p.bore = x->bore;
    p.bore_map = x->map;
    p.ring_z_tdc = x->ring_z;
    p.active_area = x->area;
    p.flank_band = x->band;
    int want = model == RD_LIFT_MODEL_AUTO ? x->expect : model;
    if (mu > 0.0) {
        p.friction.model = RD_FRICTION_COULOMB;
        p.friction.coefficient = mu;
        /* rtol 1e-8 and the lift run's tables at 0.05 deg: the bore's case
         * was measured so (the rigid ring's sets its own, and says why,
         * test_rigid_friction) */
        p.rtol = 1e-8;
        p.step_deg = 0.05;
    }
    if (x->rtol > 0.0)
        p.rtol = x->rtol;
    if (x->atol > 0.0)
        p.atol = x->atol;
    if (x->step_deg > 0.0)
        p.step_deg = x->step_deg;
    rd_ringpack_result r;
    rd_lift_result l;
    memset(&l, 0, sizeof l);
    *dl = *dg = NAN;
    if (run(&p, &r, what) != RD_OK) {
        rd_ringpack_result_cleanup(&r);
        return;
    }
    check_mass(&p, &r, what);
    CHECK(r.ring_model[0] == want && r.ring_dof[0] == (want == RD_LIFT_MODEL_FULL ? 6 * n : 3),
          "%s: model %d, dof %d (%s)", what, r.ring_model[0], r.ring_dof[0], r.ring_why[0]);
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
    /* the pack's last cycle starts seated at rest, as a one-cycle lift run
     * (where the ring still rings at 720 deg, the lift run goes on) */
    int lc = x->lift_cycles ? x->lift_cycles : 1;
    lp.engine.cycles = lc;
    lp.engine.piston_tilt_deg = x->lift_tilt.piston_tilt_deg;
    lp.engine.tilt_points = x->lift_tilt.tilt_points;
    lp.engine.tilt_crank_deg = x->lift_tilt.tilt_crank_deg;
    lp.engine.tilt_deg = x->lift_tilt.tilt_deg;
    lp.bore = x->lift_bore;
    lp.bore_map = x->lift_map;
    lp.ring_z_tdc = x->ring_z;
    lp.groove = p.rings[0].groove;
    lp.friction = p.friction;
    lp.gravity = p.gravity;
    lp.gas = (rd_gas_params){S, r.crank_deg, tab, tab + S, tab + 2 * S, x->area};
    /* the pack steps its rings with CVODE: so does the lift run here (its
     * rigid model's own integrator, rd_lift_small.c, carries the twist-driven
     * leave with friction to within ~0.1 deg at rtol 1e-6, a different
     * integration error from the same equations: test_lift_rigid checks it) */
    lp.cvode = 1;
    lp.rtol = p.rtol;
    lp.atol = p.atol;
    lp.contact_stiffness = r.ring_stiffness[0];
    lp.estimate_error = 0;
    lp.model = want;
    lp.flank_band = x->band;
    rd_error err;
    rd_error_init(&err);
    lp.step_deg = p.step_deg; /* sample k of both runs at the same angle */
    int rc = rd_lift_solve(&p.rings[0].ring, n, &lp, NULL, &l, &err);
    CHECK(rc == RD_OK, "%s: lift: %s", what, err.message);
    if (rc == RD_OK) {
        double t0 = 720.0 * (lc - 1); /* the lift run's last cycle */
        int e0 = 0, k0 = (int)lround(t0 / p.step_deg);
        while (e0 < l.n_events && l.events[e0].crank_deg < t0)
            e0++;
        int ne = l.n_events - e0;
        CHECK(ne == r.n_events[0] && ne >= 4, "%s: events lift %d, pack %d", what, ne,
              r.n_events[0]);
        *dl = *dg = 0.0;
        n_touch = 0;
        touch_gap = 0.0;
        for (int e = 0; e < ne && e < r.n_events[0]; e++) {
            int kind = l.events[e0 + e].kind;
            CHECK(r.events[0][e].kind == kind, "%s: event %d kinds %d, %d", what, e, kind,
                  r.events[0][e].kind);
            double tl = l.events[e0 + e].crank_deg - t0, tp = r.events[0][e].crank_deg;
            double ul = l.events[e0 + e].touch_deg - t0, up = r.events[0][e].touch_deg;
            CHECK(isnan(ul) == isnan(up), "%s: event %d touched in one run only", what, e);
            if (kind == RD_EVENT_LEAVE_LOWER || kind == RD_EVENT_LEAVE_UPPER) {
                *dl = fmax(*dl, fmax(fabs(tl - tp), isnan(ul + up) ? 0.0 : fabs(ul - up)));
                continue;
            }
            if (x->band > 0.0) { /* entering the band: dated in flight (BANDS) */
                *dg = fmax(*dg, fabs(tl - tp));
                if (isnan(ul + up))
                    continue;
                tl = ul; /* the touch, as below */
                tp = up;
            }
            double d = fabs(tl - tp);
            /* TOUCH: at each run's date the other's mean lift at that flank */
            double flank = kind == RD_EVENT_REACH_UPPER ? p.rings[0].groove.axial_clearance : 0.0;
            double lp_at = lift_at(l.lift + k0, l.samples - k0, p.step_deg, tp);
            double rp_at = lift_at(r.lift, S, p.step_deg, tl);
            touch_gap = fmax(touch_gap, fmax(fabs(lp_at - flank), fabs(rp_at - flank)));
            if (d > TOL_LAND && fabs(lp_at - flank) <= p.atol && fabs(rp_at - flank) <= p.atol) {
                n_touch++;
                printf("%s: landing %d dated %.4f deg apart, but at each date the other run's "
                       "lift is %.2e, %.2e m from the flank\n",
                       what, e, d, fabs(lp_at - flank), fabs(rp_at - flank));
                continue;
            }
            *dg = fmax(*dg, d);
        }
        printf("%s: %d flank changes, leaves within %.4f deg, landings within %.4f deg (%d by "
               "touch; at the landings the other run's lift within %.2e m of the flank)\n",
               what, ne, *dl, *dg, n_touch, touch_gap);
        n_pack_events = r.n_events[0] < 8 ? r.n_events[0] : 8;
        for (int e = 0; e < n_pack_events; e++)
            pack_events[e] = r.events[0][e].crank_deg;
        first_gap = first_slope = calm_gap = gas_gap = NAN;
        if (ne > 0 && r.n_events[0] > 0) {
            double e1 = r.events[0][0].crank_deg;
            int k1 = (int)floor(e1 / p.step_deg);
            first_gap = fabs(l.events[e0].crank_deg - t0 - e1);
            first_slope = k1 + 1 < S ? (r.lift[k1 + 1] - r.lift[k1]) / p.step_deg : NAN;
            int kc = 0; /* after the last gas, the first sample pressed into the flank */
            for (int k = 0; k <= k1; k++)
                for (int f = 0; f < 3; f++)
                    if (fabs(tab[(size_t)f * S + k]) >= 1.0)
                        kc = k + 1;
            while (kc <= k1 && r.lift[kc] >= 0.0)
                kc++;
            calm_gap = gas_gap = 0.0;
            for (int k = (int)ceil(1.0 / p.step_deg); k <= k1 && k0 + k < l.samples; k++) {
                double d = fabs(l.lift[k0 + k] - r.lift[k]);
                if (k >= kc)
                    calm_gap = fmax(calm_gap, d);
                else
                    gas_gap = fmax(gas_gap, d);
            }
        }
        double size = 0.0, gap = 0.0;
        for (int k = 0; k < S && k0 + k < l.samples; k++) {
            size += fabs(l.friction_force[k0 + k]);
            gap += fabs(l.friction_force[k0 + k] - r.friction[k]);
        }
        friction_gap = size > 0.0 ? gap / size : 0.0;
    }
    free(tab);
    rd_ringpack_result_cleanup(&r);
    rd_lift_result_cleanup(&l);
}

static void pack_vs_lift(int model, double mu, const char *what, double *dl, double *dg)
{
    pack_vs_lift_x(model, mu, &NONE, what, dl, dg);
}

/* The friction force along the cycle (summed difference over summed size,
 * above) with a distorted bore: measured 1.3e-4 (the lift run's tables of
 * the pack's pressures at 0.05 deg); the bore's phase left unturned (90 deg
 * off) gives 1.5e-3 */
#define FRICTION_TOL 1e-3

static void test_full(void)
{
    double dl, dg;
    extras x = {.band = RD_LIFT_FLANK_BAND};
    pack_vs_lift_x(RD_LIFT_MODEL_FULL, 0.0, &x, "full ring, flank_band 0.01", &dl, &dg);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "full ring: leaves %.4f, landings %.4f deg", dl, dg);
}

/* Friction's couple twists the ring, so it rocks off the lower flank
 * earlier than its axial load alone says: the rigid ring must follow the
 * lift rigid model, and the axial ring must be degrees off on the same
 * scene (so the comparison can tell them apart).
 *
 * The first leave (292.43 deg) is ill-conditioned in angle: the axial load
 * does not turn away from the flank before it (the friction holds it on), so
 * it is dated where the mean lift, raised by the twist as the ring rocks
 * onto its edge, reaches eps = 1e-2 c_a = 0.3 um, which it crosses at
 * L' = 30 nm/deg.  A lift error dL moves it by
 * dL / L'.  At the default atol (1e-9 m on the lift, above the seated
 * ring's ~0.4 nm penetration) the two runs' lifts there differed by 1.2 nm,
 * the date by 0.04 deg at rtol 1e-8, and rtol changed by 1-3 % moved it by
 * up to +-0.09 deg in either run (0.02-0.18 deg apart: a coin flip against
 * 0.06 deg) and 0.17 deg from the converged date.  So both runs here hold
 * the lift to atol 1e-12 m: the date is then converged (the same to 1e-4
 * deg at rtol 0.97-1.03e-7 and 0.97-1.03e-8, output steps 0.05 and 0.1
 * deg; the pack takes 57e3 steps, 20e3 at rtol 1e-8 and atol 1e-9; ~1.5 s
 * with the sanitizers), and the
 * comparison is made where it is well conditioned, in the lift, over the
 * samples before the first leave:
 *   - after the gas (gauge pressures below 1 Pa, the ring back in its
 *     flank: from 181 deg, the rocking included) the lifts agree within DL_ROCK, a hundred atol, for the two runs'
 *     global difference grown from local errors of atol (measured 3e-11 m,
 *     the same at every rtol and output step above);
 *   - the first leave within DL_ROCK / L' (L' measured at the event from
 *     the pack's samples, ~0.003 deg; measured 7e-4 deg): the lift's
 *     agreement turned into an angle by the event's own condition;
 *   - under the gas (seated from 1 deg, a 0.14 um hop near 180 deg in the
 *     blowdown) within DL_GAS: the gas load decides the seated
 *     penetration (~9 nm at 30 deg), so a pressure missing or misplaced
 *     shows here, and nowhere else, for this scene's flank changes all come
 *     after the gas (180-480 deg, gauge 0): with the groove pressure left
 *     out of the lift run every one of them stayed within 7e-4 deg, while
 *     the lifts parted by 7e-9 m.  DL_GAS 1e-9 m: the lift run's tables cut
 *     the blowdown's pressures linearly, an O(h^2) error (measured 3e-11 m
 *     at h = 0.05 deg, 1.2e-10 at 0.1, 7.8e-10 at 0.25), so it holds for
 *     steps up to 0.25 deg and is 1/7 of the missing pressure's;
 *   - every other flank change within TOL_LEAVE / TOL_LAND (the hops' leaves
 *     are dated at their landings: the load then already pulls away);
 *   - the friction force along the cycle within FRICTION_TOL (its normal
 *     force carries the groove's gas on the back face): measured 2.2e-5,
 *     6.2e-5 with the tables at 0.25 deg; the groove pressure left out of
 *     the lift run gives 2.2, mu 2 % off 0.02. */
#define DL_ROCK 1e-10
#define DL_GAS  1e-9
static void test_rigid_friction(void)
{
    double dl, dg;
    extras x = {.rtol = 1e-7, .atol = 1e-12, .band = RD_LIFT_FLANK_BAND};
    pack_vs_lift_x(RD_LIFT_MODEL_RIGID, 0.1, &x, "rigid ring, mu 0.1", &dl, &dg);
    double tol = DL_ROCK / first_slope;
    printf("rigid ring, mu 0.1: before the first leave the lifts agree within %.2e m without gas, "
           "%.2e m under it; the first leave %.4f deg apart, L' %.3g m/deg there, so within "
           "%.4f deg; friction within %.2e of its size\n",
           calm_gap, gas_gap, first_gap, first_slope, tol, friction_gap);
    CHECK(calm_gap <= DL_ROCK && gas_gap <= DL_GAS,
          "rigid ring: lifts before the first leave %.3g m (no gas), %.3g m (gas) apart", calm_gap,
          gas_gap);
    CHECK(first_slope > 0.0 && first_gap <= tol, "rigid ring: first leave %.4f deg apart (%.4f)",
          first_gap, tol);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "rigid ring: leaves %.4f, landings %.4f deg", dl, dg);
    CHECK(friction_gap <= FRICTION_TOL, "rigid ring: friction %.3g of its size", friction_gap);
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

/* The 3-ring pack of the mass-balance cases: default rings, taller second
 * and third rings, two cycles, no estimate (short under the sanitizers). */
static void three_ring_pack(rd_ringpack_params *p)
{
    rd_ringpack_params_default(p);
    p->n_rings = 3;
    p->engine.cycles = 2;
    p->estimate_error = 0;
    p->rings[1].ring.axial_height = 0.0015;
    p->rings[2].ring.axial_height = 0.0025;
}

/* (3) on three rings, a flexible top ring (coarse: the balance does not
 * depend on n, and the run stays short under the sanitizers). */
static void test_mass_flexible(void)
{
    rd_ringpack_params p;
    three_ring_pack(&p);
    p.rings[0].model = RD_LIFT_MODEL_FULL;
    p.rings[0].segments = 8;
    p.rings[1].model = RD_LIFT_MODEL_MODAL;
    p.rings[1].segments = 8;
    p.rings[1].modes = 6;
    rd_ringpack_result r;
    if (run(&p, &r, "3 rings, full and modal") == RD_OK) {
        check_mass(&p, &r, "3 rings, full and modal");
        /* the third ring: auto, the lift's rigid ring under the linear flank
         * pressure's couple */
        CHECK(r.ring_model[1] == RD_LIFT_MODEL_MODAL && r.ring_modes[1] == 6 &&
                  r.ring_model[2] == RD_LIFT_MODEL_RIGID,
              "models %d %d %d", r.ring_model[0], r.ring_model[1], r.ring_model[2]);
    }
    rd_ringpack_result_cleanup(&r);
}

/* Piston slaps during the ring's flights (it leaves its flanks near 287
 * and 433 deg on this scene): the tilt swings by 0.1 deg within 25 deg of
 * crank (a periodic C1 spline through the points), on a constant 0.05. */
static const double TILT_DEG[] = {0, 260, 285, 310, 410, 435, 460};
static const double TILT_VAL[] = {0.0, 0.0, 0.1, 0.0, 0.0, -0.1, 0.0};
static const double TILT_NEG[] = {0.0, 0.0, -0.1, 0.0, 0.0, 0.1, 0.0};
#define TILT_N 7

/* (4) The piston tilt.  auto must run the full ring; the pack's ring with
 * its gap at 180 deg sees the tilt negated (its gap's side goes down) and
 * must reproduce the lift run given -beta by hand; at 0 deg the lift run
 * given +beta.  The tilt must move the flank changes by more than twice
 * the tolerances against the untilted pack, and so must the gap's side
 * (else the comparison could not tell them passed on).  The lift run goes
 * two cycles and its second is compared: after a slap the ring does not
 * start the pack's last cycle at rest (with a 0.3 deg swing in 15 deg, one
 * lift cycle's landings came 0.15-0.22 deg off, its second's 0.04-0.05). */
static void test_tilt(void)
{
    extras x = {.gap_deg = 180.0, .expect = RD_LIFT_MODEL_FULL, .lift_cycles = 2, .step_deg = 0.1};
    x.tilt = (rd_engine_params){.piston_tilt_deg = 0.05,
                                .tilt_points = TILT_N,
                                .tilt_crank_deg = TILT_DEG,
                                .tilt_deg = TILT_VAL};
    x.lift_tilt = x.tilt;
    x.lift_tilt.piston_tilt_deg = -0.05;
    x.lift_tilt.tilt_deg = TILT_NEG;
    double dl, dg, e180[8], e0[8], flat[8];
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.0, &x, "tilt, gap at 180", &dl, &dg);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "tilt, gap 180: leaves %.4f, landings %.4f deg", dl,
          dg);
    int n180 = n_pack_events;
    memcpy(e180, pack_events, sizeof e180);
    x.gap_deg = 0.0;
    x.lift_tilt = x.tilt;
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.0, &x, "tilt, gap at 0", &dl, &dg);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "tilt, gap 0: leaves %.4f, landings %.4f deg", dl, dg);
    int n0 = n_pack_events;
    memcpy(e0, pack_events, sizeof e0);
    pack_vs_lift(RD_LIFT_MODEL_FULL, 0.0, "no tilt", &dl, &dg);
    memcpy(flat, pack_events, sizeof flat);
    double sign = n180 != n0 ? INFINITY : 0.0, tilt = n0 != n_pack_events ? INFINITY : 0.0;
    for (int e = 0; e < n0 && e < n180; e++)
        sign = fmax(sign, fabs(e180[e] - e0[e]));
    for (int e = 0; e < n0 && e < n_pack_events; e++)
        tilt = fmax(tilt, fabs(flat[e] - e0[e]));
    printf("tilt: moves the flank changes by %.3f deg; gap 0 and 180 %.3f deg apart\n", tilt, sign);
    CHECK(tilt > 2.0 * TOL_LAND, "the tilt moves the flank changes by %.4f deg", tilt);
    CHECK(sign > 2.0 * TOL_LAND, "the gap at 0 or 180 moves the flank changes by %.4f deg", sign);
}

/* (5) The distorted bore, with friction (its normal force, hence the
 * friction, varies around the ring with the bore: without friction the
 * axial motion does not see it).  The pack's ring with its gap at 90 deg
 * in a bore of phase 30 deg sees phase -60 deg from its gap: the lift run
 * is given that by hand.  Compared: the flank changes and the friction
 * force along the cycle.  Coarse ring (n = 12; the sanitizer build's
 * time) at the friction cases' rtol 1e-8.  Its upper landing is matched by
 * TOUCH at some rtols (above). */
static void test_bore(void)
{
    extras x = {.gap_deg = 90.0, .expect = RD_LIFT_MODEL_FULL, .segments = 12};
    x.bore.n_distortion = 1;
    x.bore.distortion[0].order = 2;
    x.bore.distortion[0].amplitude = 8e-6;
    x.bore.distortion[0].phase_deg = 30.0;
    x.lift_bore = x.bore;
    x.lift_bore.distortion[0].phase_deg = -60.0;
    double dl, dg;
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.1, &x, "distorted bore, gap at 90", &dl, &dg);
    double same = friction_gap;
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "bore: leaves %.4f, landings %.4f deg", dl, dg);
    /* the phase must matter: the lift run at the pack's phase untransformed */
    x.lift_bore.distortion[0].phase_deg = 30.0;
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.1, &x, "distorted bore, lift at the bore's phase", &dl,
                   &dg);
    printf("bore: friction within %.2e of its peak (%.2e with the phase not turned); leaves "
           "%.4f deg apart then\n",
           same, friction_gap, dl);
    CHECK(same <= FRICTION_TOL, "bore: friction %.3g of its peak", same);
    CHECK(dl > 5.0 * TOL_LEAVE, "bore: the lift at the untransformed phase leaves %.4f deg apart",
          dl);
}

/* A bore map along the stroke (rd_ringpack_params.bore_map): the pack's
 * ring, its gap at 90 deg, on a map whose order 2 grows down the bore
 * (2, 10, 16 um at 0, 50, 120 mm; phase 30 deg from the bore's angle 0),
 * against the lift run (two cycles, the last compared) on the same map in
 * the ring's frame (phase -60) at the same depth (4 mm at TDC): the flank
 * changes within test_bore's tolerances, the friction within MAP_FRICTION
 * of its size (measured 8.7e-4; 1.3e-4 with every layer the same bore, as
 * test_bore).  The friction hardly depends on the depth (its normal force
 * is mostly the pretension's, whatever the bore's shape: 9.8e-4 with the
 * lift run 20 mm lower), so the depth is checked through the flank
 * changes: 20 mm lower, the landings move 0.23 deg (0.012 at the same
 * depth).  Every layer the same bore: /bore/distortion's run bit for bit
 * (lift, friction, pressures).  Ring i's depth: ring_z_tdc plus the rings
 * and lands above it. */
#define MAP_FRICTION 2e-3
static rd_bore_map map_pack, map_lift;

static void map_layers(rd_bore_map *m, double phase)
{
    const double z[3] = {0.0, 0.05, 0.12}, a[3] = {2e-6, 10e-6, 16e-6};
    memset(m, 0, sizeof *m);
    m->n_layers = 3;
    m->residual_rms = NAN;
    for (int j = 0; j < 3; j++) {
        m->layer[j].z = z[j];
        m->layer[j].bore.n_distortion = 1;
        m->layer[j].bore.distortion[0] = (rd_distortion){2, a[j], phase};
    }
}

static void test_map(void)
{
    map_layers(&map_pack, 30.0);
    map_layers(&map_lift, -60.0);
    extras x = {.gap_deg = 90.0, .expect = RD_LIFT_MODEL_FULL, .segments = 12, .lift_cycles = 2};
    x.map = &map_pack;
    x.lift_map = &map_lift;
    x.ring_z = 0.004;
    double dl, dg;
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.1, &x, "bore map, gap at 90", &dl, &dg);
    double same = friction_gap;
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "map: leaves %.4f, landings %.4f deg", dl, dg);
    CHECK(same <= MAP_FRICTION, "map: friction %.3g of its size", same);
    double dg_same = dg;
    /* the depth matters: the lift run 20 mm lower on the same map */
    rd_bore_map lower = map_lift;
    for (int j = 0; j < lower.n_layers; j++)
        lower.layer[j].z -= 0.02;
    lower.layer[0].z = 0.0;
    x.lift_map = &lower;
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.1, &x, "bore map, lift run 20 mm lower", &dl, &dg);
    printf("map: friction within %.2e of its size; landings within %.4f deg (%.2e and %.4f deg "
           "with the lift run 20 mm lower)\n",
           same, dg_same, friction_gap, dg);
    CHECK(dg > 5.0 * dg_same, "map: 20 mm lower, the landings %.4f deg apart (same depth %.4f)", dg,
          dg_same);
    /* every layer the same bore: /bore/distortion's run to the last bit */
    rd_ringpack_params q[2];
    rd_ringpack_result rr[2];
    rd_bore_map flat;
    map_layers(&flat, 30.0);
    for (int j = 0; j < flat.n_layers; j++)
        flat.layer[j].bore.distortion[0].amplitude = 8e-6;
    for (int k = 0; k < 2; k++) {
        rd_ringpack_params_default(&q[k]);
        q[k].engine.cycles = 2;
        q[k].estimate_error = 0;
        q[k].rings[0].segments = 8;
        q[k].rings[0].gap_angle_deg = 40.0;
        q[k].friction.model = RD_FRICTION_COULOMB;
        q[k].friction.coefficient = 0.1;
    }
    q[0].bore = flat.layer[0].bore;
    q[1].bore_map = &flat;
    q[1].ring_z_tdc = 0.004;
    int ok = run(&q[0], &rr[0], "plain distorted bore") == RD_OK;
    ok = (run(&q[1], &rr[1], "the same bore at every layer") == RD_OK) && ok;
    if (ok) {
        size_t S = (size_t)rr[0].samples;
        CHECK(rr[1].samples == rr[0].samples &&
                  memcmp(rr[0].lift, rr[1].lift, S * sizeof *rr[0].lift) == 0 &&
                  memcmp(rr[0].friction, rr[1].friction, S * sizeof *rr[0].friction) == 0 &&
                  memcmp(rr[0].pressure, rr[1].pressure,
                         S * (size_t)rr[0].n_volumes * sizeof *rr[0].pressure) == 0,
              "map: every layer the same bore gives /bore/distortion's run bit for bit");
    }
    rd_ringpack_result_cleanup(&rr[0]);
    rd_ringpack_result_cleanup(&rr[1]);
    rd_ringpack_params p;
    rd_ringpack_params_thesis(&p);
    p.ring_z_tdc = 0.002;
    double want = 0.002 + p.rings[0].ring.axial_height + p.rings[1].land_height +
                  p.rings[1].ring.axial_height + p.rings[2].land_height;
    CHECK(fabs(rd_ringpack_ring_depth(&p, 2) - want) < 1e-15 &&
              rd_ringpack_ring_depth(&p, 0) == 0.002,
          "ring depths: the third ring at %g m, want %g", rd_ringpack_ring_depth(&p, 2), want);
}

/* (6) Dynamic active areas, closed form.  A ring pressed on its lower
 * flank by fixed gauge face pressures (the pack's test hook): above P_a,
 * behind P_b, below 0.  Sealing on the flank, its bottom face sees across
 * its land the mean of its edge pressures, (P_b + 0) / 2; its top face,
 * free, P_a.  So its flank load, hence its penetration (the seated ring's
 * negative lift, sample by sample under the piston's inertia), must be the
 * fixed-area ring's with below = P_b / 2, and differ from the fixed-area
 * ring's with below = 0 by the load P_b / 2 makes. */
static void seated_lift(int area, double below, double *lift, int *S, int *model)
{
    static const double deg[] = {0.0, 720.0};
    const double above[] = {4e6, 4e6}, behind[] = {4e6, 4e6}, low[] = {below, below};
    rd_gas_params g = {2, deg, above, behind, low, RD_GAS_AREA_FIXED};
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    p.engine.cycles = 2;
    p.estimate_error = 0;
    p.step_deg = 5.0;
    p.atol = 1e-14; /* the penetrations are ~1e-8 m */
    p.active_area = area;
    p.flank_pressure = RD_FLANK_PRESSURE_FULL; /* dynamic areas are the lift models' own */
    p.model = area == RD_GAS_AREA_DYNAMIC ? RD_LIFT_MODEL_AUTO : RD_LIFT_MODEL_RIGID;
    p.face_tables = &g;
    rd_ringpack_result r;
    *S = 0;
    if (run(&p, &r, "seated ring") == RD_OK) {
        *S = r.samples < 200 ? r.samples : 200;
        memcpy(lift, r.lift, (size_t)*S * sizeof *lift);
        *model = r.ring_model[0];
        CHECK(r.n_events[0] == 0, "seated ring: %d flank changes", r.n_events[0]);
    }
    rd_ringpack_result_cleanup(&r);
}

static void test_dynamic_seated(void)
{
    double dyn[200], mean[200], fixed[200], gap = 0.0, size = 0.0, moved = 0.0;
    int S1, S2, S3, model = -1, unused;
    seated_lift(RD_GAS_AREA_DYNAMIC, 0.0, dyn, &S1, &model);
    seated_lift(RD_GAS_AREA_FIXED, 2e6, mean, &S2, &unused);
    seated_lift(RD_GAS_AREA_FIXED, 0.0, fixed, &S3, &unused);
    CHECK(model == RD_LIFT_MODEL_RIGID, "auto with dynamic areas: model %d", model);
    CHECK(S1 == S2 && S1 == S3 && S1 > 0, "samples %d %d %d", S1, S2, S3);
    for (int k = 0; k < S1 && S1 == S2 && S1 == S3; k++) {
        gap = fmax(gap, fabs(dyn[k] - mean[k]));
        size = fmax(size, fabs(mean[k]));
        moved = fmax(moved, fabs(dyn[k] - fixed[k]));
    }
    printf("dynamic areas, seated: penetration up to %.3g m; against below = P_b/2 with fixed "
           "areas within %.2g of it; %.3g m from fixed areas with below = 0\n",
           size, gap / size, moved);
    /* 1e-4 of the penetration, a hundred times rtol: the sealing weight is
     * 1 once a contact point is d0 = 1e-4 c_a in (here up to 1.8 d0), so
     * the runs differ only in CVODE's paths; measured 6e-7 */
    CHECK(gap <= 1e-4 * size, "dynamic vs mean pressure: %.3g of %.3g m", gap, size);
    CHECK(moved >= 0.2 * size, "dynamic vs fixed areas: %.3g of %.3g m", moved, size);
}

/* (6) dynamic areas against the lift run on the pack's pressures (auto's
 * rigid ring), and the mass balance with a tilt, a distorted bore and
 * dynamic areas on three rings (auto: full rings, coarse; the gaps at 0
 * and 180; the third pinned). */
static void test_dynamic_lift_and_mass(void)
{
    extras x = {.area = RD_GAS_AREA_DYNAMIC, .expect = RD_LIFT_MODEL_RIGID};
    double dl, dg;
    pack_vs_lift_x(RD_LIFT_MODEL_AUTO, 0.0, &x, "dynamic areas", &dl, &dg);
    CHECK(dl <= TOL_LEAVE && dg <= TOL_LAND, "dynamic: leaves %.4f, landings %.4f deg", dl, dg);
    rd_ringpack_params p;
    three_ring_pack(&p);
    p.rings[0].segments = p.rings[1].segments = 8;
    p.rings[1].gap_angle_deg = 180.0;
    p.rings[2].pinned = RD_PIN_LOWER;
    p.engine.piston_tilt_deg = 0.05;
    p.engine.tilt_points = TILT_N;
    p.engine.tilt_crank_deg = TILT_DEG;
    p.engine.tilt_deg = TILT_VAL;
    p.bore.n_distortion = 1;
    p.bore.distortion[0].order = 3;
    p.bore.distortion[0].amplitude = 4e-6;
    p.bore.distortion[0].phase_deg = 10.0;
    p.active_area = RD_GAS_AREA_DYNAMIC;
    p.flank_pressure = RD_FLANK_PRESSURE_FULL; /* dynamic areas are the lift models' own */
    rd_ringpack_result r;
    if (run(&p, &r, "3 rings, tilt, bore, dynamic") == RD_OK) {
        check_mass(&p, &r, "3 rings, tilt, bore, dynamic");
        CHECK(r.ring_model[0] == RD_LIFT_MODEL_FULL && r.ring_model[1] == RD_LIFT_MODEL_FULL &&
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
    test_tilt();
    test_bore();
    test_map();
    test_dynamic_seated();
    test_dynamic_lift_and_mass();
    return check_done();
}
