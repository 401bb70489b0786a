/* test_ringpack — the ring pack (rd_gasflow, rd_ringpack): orifice branches
 * at their limits, steady series-orifice networks solved here by a separate
 * root-find, mass conservation over a cycle, the rigid ring against the
 * lift analysis' rigid model, plausible magnitudes (wide bounds, README
 * "Ring pack"), and extremes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_gasflow.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define KAPPA RD_GASFLOW_KAPPA
#define RG    RD_GASFLOW_R

/* The textbook orifice written out again (Heywood, Internal Combustion
 * Engine Fundamentals, App. C): mass flow from pu to pd, unchoked or
 * choked; within 1e-4 of equal pressures continued linearly, as
 * rd_gasflow.h documents (the top-land entry's drop falls there). */
static double nozzle(double cd, double A, double pu, double T, double pd)
{
    double k = KAPPA, r = pd / pu, rc = pow(2.0 / (k + 1.0), k / (k - 1.0));
    if (r > 1.0 - 1e-4)
        return nozzle(cd, A, pu, T, pu * (1.0 - 1e-4)) * (1.0 - r) / 1e-4;
    double base = cd * A * pu / sqrt(RG * T);
    if (r < rc)
        return base * sqrt(k) * pow(2.0 / (k + 1.0), (k + 1.0) / (2.0 * (k - 1.0)));
    return base * pow(r, 1.0 / k) * sqrt(2.0 * k / (k - 1.0) * (1.0 - pow(r, (k - 1.0) / k)));
}

static void test_orifice(void)
{
    double k = 1.4, rc = rd_gasflow_critical_ratio(k);
    CHECK_REL(rc, 0.528281787, 1e-8, "critical ratio at k = 1.4 (tables: 0.5283)");
    double A = 1e-6, cd = 0.7, T = 450.0, pu = 5e5;
    /* both branches meet at r_c: continuity to round-off (1e-9) */
    double below = rd_gasflow_orifice(cd, A, pu, T, pu * rc * (1.0 - 1e-12), T, k, RG);
    double above = rd_gasflow_orifice(cd, A, pu, T, pu * rc * (1.0 + 1e-12), T, k, RG);
    CHECK_REL(above, below, 1e-9, "branches meet at the critical ratio");
    /* choked: independent of the downstream pressure; the closed-form value */
    double choked = cd * A * pu / sqrt(RG * T) * sqrt(k) * pow(2.0 / (k + 1.0), 3.0);
    CHECK_REL(rd_gasflow_orifice(cd, A, pu, T, 0.1 * pu, T, k, RG), choked, 1e-12, "choked");
    CHECK_REL(rd_gasflow_orifice(cd, A, pu, T, 0.0, T, k, RG), choked, 1e-12, "into vacuum");
    /* unchoked against the textbook form (another algebraic arrangement) */
    for (double r = 0.55; r < 0.999; r += 0.05) {
        double got = rd_gasflow_orifice(cd, A, pu, T, r * pu, T, KAPPA, RG);
        CHECK_REL(got, nozzle(cd, A, pu, T, r * pu), 1e-12, "unchoked r = %g", r);
    }
    /* antisymmetric, zero at equal pressures and with no area */
    double f = rd_gasflow_orifice(cd, A, 2e5, T, 3e5, T, KAPPA, RG);
    CHECK_REL(f, -rd_gasflow_orifice(cd, A, 3e5, T, 2e5, T, KAPPA, RG), 1e-15, "antisymmetric");
    CHECK(rd_gasflow_orifice(cd, A, 2e5, T, 2e5, T, KAPPA, RG) == 0.0, "equal pressures");
    CHECK(rd_gasflow_orifice(cd, 0.0, 9e5, T, 1e5, T, KAPPA, RG) == 0.0, "no area");
    /* the linear band: continuous at its edge (1e-9), linear inside */
    double rl = 1.0 - RD_GASFLOW_LINEAR_BAND;
    CHECK_REL(rd_gasflow_orifice(cd, A, pu, T, pu * rl * (1 + 1e-13), T, KAPPA, RG),
              nozzle(cd, A, pu, T, pu * rl), 1e-7, "band edge");
}

/* The cylinder trace's interpolation: through the points, within its
 * neighbours' range, and with a continuous slope at the points. */
static void test_trace(void)
{
    static double x[RD_GASFLOW_POINTS], y[RD_GASFLOW_POINTS];
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_gasflow_synthetic(&p.synthetic, &p.engine, 0.0765, x, y, &err) == RD_OK, "trace");
    int bad_node = 0, bad_range = 0, bad_c1 = 0;
    for (int k = 1; k < RD_GASFLOW_POINTS - 1; k += 7) {
        bad_node |= rd_gasflow_trace(RD_GASFLOW_POINTS, x, y, x[k]) != y[k];
        double mid = rd_gasflow_trace(RD_GASFLOW_POINTS, x, y, 0.5 * (x[k] + x[k + 1]));
        bad_range |=
            mid < fmin(y[k], y[k + 1]) * (1 - 1e-12) || mid > fmax(y[k], y[k + 1]) * (1 + 1e-12);
        /* one-sided slopes 1e-6 deg each side of the node: equal to 1e-3 of the
         * local secant scale (a kink would differ by O(1)) */
        double e = 1e-6, f0 = rd_gasflow_trace(RD_GASFLOW_POINTS, x, y, x[k]);
        double sl = (f0 - rd_gasflow_trace(RD_GASFLOW_POINTS, x, y, x[k] - e)) / e;
        double sr = (rd_gasflow_trace(RD_GASFLOW_POINTS, x, y, x[k] + e) - f0) / e;
        double scale = fabs(y[k + 1] - y[k - 1]) / (x[k + 1] - x[k - 1]) + 1.0;
        bad_c1 |= fabs(sl - sr) > 1e-3 * scale;
    }
    CHECK(!bad_node && !bad_range && !bad_c1, "trace: nodes %d, range %d, C1 %d", bad_node,
          bad_range, bad_c1);
    /* the generator: the fired peak is the asked one (to the bisection's
     * 2^-60) where asked (within the 0.25 deg grid); the motored one is the
     * closed form p_in eps^1.32 at TDC (V(0) = V_c), up to round-off */
    int at = 0;
    for (int k = 0; k < RD_GASFLOW_POINTS; k++)
        at = y[k] > y[at] ? k : at;
    CHECK_REL(y[at], p.synthetic.peak_pa, 1e-9, "fired peak");
    CHECK_ABS(x[at], p.synthetic.peak_crank_deg, 0.25 + 1e-9, "fired peak angle");
    p.synthetic.kind = RD_CYLINDER_MOTORED;
    CHECK(rd_gasflow_synthetic(&p.synthetic, &p.engine, 0.0765, x, y, &err) == RD_OK, "motored");
    for (int k = 0; k < RD_GASFLOW_POINTS; k++)
        at = y[k] > y[at] ? k : at;
    CHECK_REL(y[at], p.synthetic.intake_pa * pow(p.synthetic.compression_ratio, 1.32), 1e-12,
              "motored peak");
    CHECK(x[at] == 0.0 || x[at] == 720.0, "motored peak at TDC: %g", x[at]);
    CHECK_REL(y[RD_GASFLOW_POINTS / 2], p.synthetic.intake_pa, 1e-15, "intake pressure at 360");
}

/* Pressure table: constant p over 0..720. */
static double cdeg[2] = {0.0, 720.0}, cpa[2];

static void pinned_pack(rd_ringpack_params *p, int rings, double pc)
{
    rd_ringpack_params_default(p);
    p->n_rings = rings;
    for (int i = 0; i < rings; i++)
        p->rings[i].pinned = RD_PIN_LOWER;
    cpa[0] = cpa[1] = pc;
    p->cylinder_kind = RD_CYLINDER_TABLE;
    p->table_points = 2;
    p->table_deg = cdeg;
    p->table_pa = cpa;
    /* enough cycles for the slowest volume to settle (below 1e-9) */
    p->engine.cycles = 12;
    p->rtol = 1e-9;
    p->estimate_error = 0;
}

/* Downstream pressure where the orifice passes `mdot` from pu (bisection). */
static double downstream(double mdot, double cd, double A, double pu, double T)
{
    double lo = 0.0, hi = pu;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (nozzle(cd, A, pu, T, mid) > mdot)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* Steady series network (rings pinned low: the grooves are dead ends; the
 * chain is top-land entry, then each end gap): find the mass flow whose
 * chain of pressure drops ends at the crankcase pressure.  Fills p_land. */
static double series(const rd_ringpack_params *p, double pc, double *p_land)
{
    double T = p->T_lands, d = p->rings[0].ring.diameter;
    double lo = 0.0, hi = nozzle(0.7, M_PI * d * p->rings[0].land_clearance, pc, T, 0.0);
    for (int it = 0; it < 200; it++) {
        double mdot = 0.5 * (lo + hi), pu = pc;
        int ok = 1;
        for (int i = 0; i <= p->n_rings && ok; i++) {
            const rd_ringpack_ring *r = &p->rings[i < p->n_rings ? i : 0];
            double A = i == 0 ? M_PI * d * r->land_clearance
                              : p->rings[i - 1].ring.closed_gap * p->rings[i - 1].land_clearance;
            double cd = p->rings[i == 0 ? 0 : i - 1].discharge_coefficient;
            if (nozzle(cd, A, pu, T, 0.0) < mdot) {
                ok = 0; /* cannot pass this much even choked */
                break;
            }
            pu = downstream(mdot, cd, A, pu, T);
            if (i < p->n_rings)
                p_land[i] = pu;
        }
        if (!ok || pu < p->crankcase_pa)
            hi = mdot;
        else
            lo = mdot;
    }
    return 0.5 * (lo + hi);
}

static void test_series(int rings, double pc)
{
    rd_ringpack_params p;
    rd_ringpack_result r;
    rd_error err;
    rd_error_init(&err);
    pinned_pack(&p, rings, pc);
    double pl[3];
    double mdot = series(&p, pc, pl);
    int rc = rd_ringpack_solve(&p, NULL, &r, &err);
    CHECK(rc == RD_OK, "series %d: %s", rings, err.message);
    if (rc == RD_OK) {
        int S = r.samples - 1;
        for (int i = 0; i < rings; i++) { /* land i and its groove (a dead end) */
            /* 1e-6: rtol 1e-9 and three cycles of a ~1 ms time constant */
            CHECK_REL(r.pressure[(size_t)(2 * i + 1) * r.samples + S], pl[i], 1e-6,
                      "land %d of %d rings at %g Pa", i, rings, pc);
            CHECK_REL(r.pressure[(size_t)(2 * i + 2) * r.samples + S], pl[i], 1e-6,
                      "groove %d of %d rings", i, rings);
        }
        double cycle_s = 120.0 / p.engine.speed_rpm;
        CHECK_REL(r.blowby_kg, mdot * cycle_s, 1e-5, "steady blow-by, %d rings", rings);
        CHECK(r.reverse_kg == 0.0, "no reverse flow: %g", r.reverse_kg);
    }
    rd_ringpack_result_cleanup(&r);
}

static int run(const rd_ringpack_params *p, rd_ringpack_result *r, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    return rc;
}

static void three_rings(rd_ringpack_params *p)
{
    rd_ringpack_params_default(p);
    p->n_rings = 3;
    p->estimate_error = 0;
    p->rings[0].land_height = 0.005;
    p->rings[0].land_clearance = 4e-4;
    p->rings[1].ring.axial_height = 0.0015;
    p->rings[2].ring.axial_height = 0.0025;
    p->rings[2].land_clearance = 2e-4;
}

/* Mass: inflow - reverse - blow-by - stored change over the last cycle,
 * the stored gas recomputed here from the reported pressures and volumes. */
static void test_mass(void)
{
    rd_ringpack_params p;
    rd_ringpack_result r;
    three_rings(&p);
    if (run(&p, &r, "mass") == RD_OK) {
        int S = r.samples - 1;
        double stored = 0.0;
        for (int v = 1; v < r.n_volumes - 1; v++)
            stored += (r.pressure[(size_t)v * r.samples + S] - r.pressure[(size_t)v * r.samples]) *
                      r.volume_m3[v] / (RG * p.T_lands);
        double thru = r.inflow_kg + r.reverse_kg;
        double res = fabs(r.inflow_kg - r.reverse_kg - r.blowby_kg - stored) / thru;
        CHECK(res <= 1e-6, "mass balance %.3g of the throughput %.3g kg", res, thru);
        CHECK(r.mass_residual <= 1e-6, "reported residual %.3g", r.mass_residual);
        /* magnitudes (README "Ring pack"): wide bounds, an order of magnitude */
        double peak = 0.0, land2 = 0.0;
        for (int k = 0; k <= S; k++) {
            peak = fmax(peak, r.pressure[k]);
            land2 = fmax(land2, r.pressure[(size_t)3 * r.samples + k]);
        }
        CHECK(land2 / peak > 0.05 && land2 / peak < 0.5, "second land peak %.3g of the cylinder's",
              land2 / peak);
        CHECK(r.blowby_l_per_min > 0.2 && r.blowby_l_per_min < 5.0, "blow-by %.3g L/min",
              r.blowby_l_per_min);
        double fired = r.blowby_kg;
        rd_ringpack_result_cleanup(&r);
        p.cylinder_kind = p.synthetic.kind = RD_CYLINDER_MOTORED;
        if (run(&p, &r, "motored") == RD_OK)
            CHECK(r.blowby_kg > 0.0 && r.blowby_kg < fired, "motored %.3g < fired %.3g",
                  r.blowby_kg, fired);
        rd_ringpack_result_cleanup(&r);
        three_rings(&p);
        for (int i = 0; i < 3; i++)
            p.rings[i].ring.closed_gap *= 2.0;
        if (run(&p, &r, "wider gaps") == RD_OK)
            CHECK(r.blowby_kg > 1.3 * fired, "doubled gaps %.3g vs %.3g", r.blowby_kg, fired);
    }
    rd_ringpack_result_cleanup(&r);
}

/* Finite, positive pressures, no negative stored mass. */
static void check_sane(const rd_ringpack_result *r, const char *what)
{
    int bad = 0;
    for (size_t k = 0; k < (size_t)r->samples * r->n_volumes; k++)
        bad |= !(r->pressure[k] > 0.0) || !isfinite(r->pressure[k]);
    for (size_t k = 0; k < (size_t)r->samples * r->n_rings; k++)
        bad |= !isfinite(r->lift[k]);
    CHECK(!bad && isfinite(r->blowby_kg) && r->mass_residual <= 1e-6, "%s: sane (resid %.3g)", what,
          r->mass_residual);
}

static void test_extremes(void)
{
    rd_ringpack_params p;
    rd_ringpack_result r;
    three_rings(&p);
    for (int i = 0; i < 3; i++)
        p.rings[i].ring.closed_gap = 0.0;
    if (run(&p, &r, "sealed gaps") == RD_OK) {
        check_sane(&r, "sealed gaps");
        double gapflow = 0.0;
        for (int f = 0; f < r.n_flows; f++)
            if (strstr(r.flow_name[f], "end_gap"))
                for (int k = 0; k < r.samples; k++)
                    gapflow = fmax(gapflow, fabs(r.flow[(size_t)f * r.samples + k]));
        CHECK(gapflow == 0.0, "sealed: no end-gap flow (%g)", gapflow);
    }
    rd_ringpack_result_cleanup(&r);
    /* the work bound covers the whole run, across the restarts */
    three_rings(&p);
    p.max_steps = 500;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(&p, NULL, &r, &err);
    CHECK(rc == RD_ELIMIT && strcmp(err.path, "/numerics/max_steps") == 0, "work bound: %d %s", rc,
          err.message);
    rd_ringpack_result_cleanup(&r);
    struct {
        const char *what;
        double gap, clear, rpm, peak;
    } cases[] = {{"1 mm gaps", 1e-3, 0, 0, 0},
                 {"1 um clearances", 0, 1e-6, 0, 0},
                 {"10000 rpm", 0, 0, 10000, 0},
                 {"200 bar", 0, 0, 0, 2e7}};
    for (int c = 0; c < 4; c++) {
        three_rings(&p);
        for (int i = 0; i < 3; i++) {
            if (cases[c].gap)
                p.rings[i].ring.closed_gap = cases[c].gap;
            if (cases[c].clear)
                p.rings[i].land_clearance = cases[c].clear;
        }
        if (cases[c].rpm)
            p.engine.speed_rpm = cases[c].rpm;
        if (cases[c].peak)
            p.synthetic.peak_pa = cases[c].peak;
        if (run(&p, &r, cases[c].what) == RD_OK)
            check_sane(&r, cases[c].what);
        rd_ringpack_result_cleanup(&r);
    }
}

/* The pack's rigid ring against the lift analysis' rigid model (an
 * independent formulation: penalty flank contacts, twist and radial
 * motion, friction from the bore points' penalty normal forces) on one ring
 * driven by the same gauge tables with fixed areas, without friction or
 * with Coulomb friction mu: the same flank changes at nearly the same
 * angles, dated at the band `band` (output.flank_band) in both, and the
 * same touch_deg.  Returns the pack's first flank change of the last
 * cycle, deg. */
static double against_lift(double mu, int model, double band)
{
    enum { NT = 721 };
    static double deg[NT], above[NT], below[NT];
    rd_ringpack_params p;
    rd_ringpack_params_default(&p);
    p.engine.speed_rpm = 6000.0;
    p.engine.cycles = 2;
    p.estimate_error = 0;
    p.model = model; /* axial, or the lift rigid ring in the pack (same tables) */
    p.flank_band = band;
    static double cd[RD_GASFLOW_POINTS], cp[RD_GASFLOW_POINTS];
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_gasflow_synthetic(&p.synthetic, &p.engine, 0.0765, cd, cp, &err) == RD_OK, "trace: %s",
          err.message);
    for (int k = 0; k < NT; k++) { /* below: 30 % of the cylinder's gauge, 20 deg late */
        deg[k] = k;
        above[k] = rd_gasflow_table(RD_GASFLOW_POINTS, cd, cp, k) - 1e5;
        below[k] = 0.3 * (rd_gasflow_table(RD_GASFLOW_POINTS, cd, cp, k - 20.0) - 1e5);
    }
    rd_gas_params gas = {NT, deg, above, above, below, RD_GAS_AREA_FIXED};
    p.face_tables = &gas;
    rd_lift_params lp;
    rd_lift_params_default(&lp);
    lp.engine = p.engine;
    lp.gravity = 1;
    lp.gas = gas;
    lp.model = RD_LIFT_MODEL_RIGID;
    lp.estimate_error = 0;
    lp.rtol = 1e-8;
    lp.flank_band = band;
    p.rtol = 1e-8;
    if (mu > 0.0) {
        p.friction.model = lp.friction.model = RD_FRICTION_COULOMB;
        p.friction.coefficient = lp.friction.coefficient = mu;
    }
    double first = NAN;
    rd_ringpack_result r;
    rd_lift_result l;
    int rc = run(&p, &r, "pack vs lift");
    int rc2 = rd_lift_solve(&p.rings[0].ring, 20, &lp, NULL, &l, &err);
    CHECK(rc2 == RD_OK, "lift: %s", err.message);
    if (rc == RD_OK && rc2 == RD_OK) {
        int n = 0;
        double worst = 0.0;
        for (int e = 0; e < l.n_events; e++) {
            if (l.events[e].crank_deg < 720.0)
                continue;
            int ok = n < r.n_events[0] && r.events[0][n].kind == l.events[e].kind;
            double tp = ok ? r.events[0][n].touch_deg : NAN, tl = l.events[e].touch_deg - 720.0;
            ok &= isnan(tp) == isnan(tl);
            double diff =
                ok ? fabs(r.events[0][n].crank_deg - (l.events[e].crank_deg - 720.0)) : 1e9;
            diff = fmax(diff, isnan(tp) ? 0.0 : fabs(tp - tl));
            /* 0.1 deg: leaving a flank is a sign change of the same force
             * (agrees to 1e-3 deg); a landing differs by the lift model's
             * penalty contact (penetration F/(k A) and its damping), 0.05 deg.
             * With friction 2 deg: the friction acts on the running face, so
             * its moment about the centroid twists the lift model's ring
             * (0.5 mrad at lift-off) and tilts the flank pressure outward;
             * that ring rocks off its flank 0.7 to 1.4 deg before the pack's
             * axial-only ring (the sum of the forces, which both share to
             * 0.2 %, crosses zero).  These are the touch dating's (flank_band
             * 0: the force's sign change, the landing's touch), and so are
             * the touch_deg at any band.  With the band (0.01) the dates are
             * the lift crossing its edge in flight, where the two rings
             * differ by the penalty contact (test_ringpack_band: 0.0014 deg
             * on a closed-form flight): 0.1 deg still (measured 0.005 deg). */
            /* The lift rigid ring in the pack (model rigid) twists as the
             * lift analysis' does: the 1.4 deg go, 0.1 deg as without
             * friction (measured 0.01 deg). */
            double tol = mu > 0.0 && model == RD_RINGPACK_AXIAL ? 2.0 : 0.1;
            CHECK(diff < tol, "model %d event %d (kind %d) at %.2f deg: pack %.2f", model, n,
                  l.events[e].kind, l.events[e].crank_deg - 720.0,
                  ok ? r.events[0][n].crank_deg : -1.0);
            worst = fmax(worst, diff);
            n++;
        }
        CHECK(n == r.n_events[0] && n > 0, "mu %g events: lift %d, pack %d", mu, n, r.n_events[0]);
        printf("mu %g, pack model %s, flank_band %g: %d flank changes and touches within %.4f "
               "deg of the lift's\n",
               mu, rd_ringpack_model_name(model), band, n, worst);
        if (r.n_events[0] > 0)
            first = r.events[0][0].crank_deg;
        /* the friction force along the last cycle, at the samples both have:
         * within 2 % of its peak (the lift's normal force comes from the
         * bore points' penalty contacts in radial equilibrium, 0.2 % off
         * the pack's closed form; near the dead centres the tanh sees the
         * rings' own speeds, which differ by the twist) */
        double peak = 0.0, dmax = 0.0;
        for (int k = 0; k < l.samples; k++) {
            double a = l.crank_deg[k] - 720.0, x = a / 720.0 * (r.samples - 1);
            int j = (int)lround(x);
            if (a < 0.0 || j >= r.samples || fabs(x - j) > 1e-9)
                continue;
            peak = fmax(peak, fabs(l.friction_force[k]));
            dmax = fmax(dmax, fabs(l.friction_force[k] - r.friction[j]));
        }
        printf("mu %g: friction peak %.4g N, largest difference to the lift's %.3g N\n", mu, peak,
               dmax);
        CHECK(mu > 0.0 ? peak > 10.0 && dmax < 0.02 * peak : dmax == 0.0,
              "mu %g friction: peak %.3g N, largest difference %.3g N", mu, peak, dmax);
    }
    rd_ringpack_result_cleanup(&r);
    rd_lift_result_cleanup(&l);
    return first;
}

static void test_against_lift(void)
{
    /* at the touch dating (flank_band 0) the tolerances above were derived
     * for: with friction the twisted ring's mean lift leaves the band
     * (0.01) up to 3.2 deg before the axial ring's, more than the 2 deg of
     * its rocking off the flank; the band dating without friction, and of
     * the twisting rigid ring in the pack, at 0.01 */
    double dry = against_lift(0.0, RD_RINGPACK_AXIAL, 0.0);
    double fric = against_lift(0.15, RD_RINGPACK_AXIAL, 0.0);
    against_lift(0.15, RD_LIFT_MODEL_RIGID, 0.0);
    against_lift(0.0, RD_RINGPACK_AXIAL, RD_LIFT_FLANK_BAND);
    against_lift(0.15, RD_LIFT_MODEL_RIGID, RD_LIFT_FLANK_BAND);
    /* the comparison can fail: friction (mu N ~ 0.15 x 2 pi F_t plus the
     * gas behind) must move the first flank change by more than the 2 deg
     * agreement asked above (it moves it 3.5 deg; a weak check: the
     * friction force's own comparison above is the strong one) */
    printf("first flank change: dry %.3f deg, mu 0.15 %.3f deg\n", dry, fric);
    CHECK(fabs(dry - fric) > 2.0, "friction moved the first flank change by %.3f deg only",
          fabs(dry - fric));
}

/* The error estimate (rtol/10 run) against the true error (a run at
 * rtol 1e-11), for both quantities it covers, on a battery of scenes:
 * within a factor 3 either way (the standards' bar).  auto gives the
 * lift's rigid ring under the default linear flank pressure; cases 1 and
 * 4 run the axial ring (asked for): with rigid rings there the runs at
 * rtol and rtol/10 see different numbers of the second ring's late
 * bounces, so the event estimate is null (as the result says), which this
 * battery cannot score. */
static void test_error_estimate(void)
{
    struct {
        int rings, motored;
        double rpm, rtol;
        int model; /* of the top ring; rigid: the lift model, with friction */
    } cases[] = {{1, 0, 2400, 1e-4, RD_LIFT_MODEL_AUTO}, {3, 0, 2400, 1e-5, RD_RINGPACK_AXIAL},
                 {3, 1, 2400, 1e-5, RD_LIFT_MODEL_AUTO}, {3, 0, 6000, 1e-4, RD_LIFT_MODEL_AUTO},
                 {2, 0, 4000, 1e-5, RD_RINGPACK_AXIAL},  {1, 0, 2400, 1e-4, RD_LIFT_MODEL_RIGID}};
    for (int c = 0; c < 6; c++) {
        rd_ringpack_params p;
        rd_ringpack_result r, ref;
        three_rings(&p);
        p.n_rings = cases[c].rings;
        p.engine.speed_rpm = cases[c].rpm;
        p.engine.cycles = 3;
        if (cases[c].motored)
            p.cylinder_kind = p.synthetic.kind = RD_CYLINDER_MOTORED;
        if (cases[c].model == RD_RINGPACK_AXIAL)
            p.model = RD_RINGPACK_AXIAL;
        if (cases[c].model == RD_LIFT_MODEL_RIGID) {
            p.rings[0].model = RD_LIFT_MODEL_RIGID;
            p.friction.model = RD_FRICTION_COULOMB;
        }
        p.rtol = 1e-11;
        p.atol = 1e-14;
        int ok = run(&p, &ref, "reference") == RD_OK;
        p.rtol = cases[c].rtol;
        p.atol = 1e-9;
        p.estimate_error = 1;
        ok = ok && run(&p, &r, "estimated") == RD_OK;
        if (ok) {
            double peak = 0.0, dp = 0.0;
            for (size_t k = 0; k < (size_t)r.samples * r.n_volumes; k++) {
                peak = fmax(peak, ref.pressure[k]);
                dp = fmax(dp, fabs(r.pressure[k] - ref.pressure[k]));
            }
            double truth = fmax(dp / peak, fabs(r.blowby_kg - ref.blowby_kg) / fabs(ref.blowby_kg));
            double de = 0.0; /* the flank changes' true shift, matched in order */
            int same = 1;
            for (int i = 0; i < r.n_rings; i++) {
                same &= r.n_events[i] == ref.n_events[i];
                for (int e = 0; same && e < r.n_events[i]; e++)
                    de = fmax(de, fabs(r.events[i][e].crank_deg - ref.events[i][e].crank_deg));
            }
            CHECK(same && isfinite(r.event_error_deg) && r.event_error_deg <= 3.0 * de &&
                      r.event_error_deg >= de / 3.0,
                  "case %d: event estimate %.3g deg, true %.3g deg", c, r.event_error_deg, de);
            CHECK(r.error_estimate <= 3.0 * truth && r.error_estimate >= truth / 3.0,
                  "case %d: estimate %.3g, true error %.3g", c, r.error_estimate, truth);
        }
        rd_ringpack_result_cleanup(&r);
        rd_ringpack_result_cleanup(&ref);
    }
}

int main(void)
{
    test_trace();
    test_error_estimate();
    test_against_lift();
    test_orifice();
    test_series(1, 3e5); /* unchoked */
    test_series(2, 3e6); /* the first passages choked */
    test_series(3, 6e6);
    test_mass();
    test_extremes();
    return check_done();
}
