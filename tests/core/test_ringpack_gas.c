/* test_ringpack_gas — the ring pack's gas laws (rd_gasflow.h, rd_ringpack.h):
 * the viscous slot law and Sutherland's viscosity against their formulas
 * and a table value, the orifice/slot blend's continuity and derivatives,
 * a steady network with viscous-limited flank passages and another gas
 * against a steady solution written here (nested bisection on laws written
 * again), the end-gap area rule, the oil ring, the linear flank pressure
 * (the top ring seats on its upper flank during expansion with viscous
 * passages, chatters on its lower flank with orifices alone), and bad
 * input by field. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_gasflow.h"
#include "rd_ringpack.h"
#include "ringpack_steady.h"

static void test_laws(void)
{
    /* Sutherland: its reference point, and air at 450 K from the tables
     * (Incropera & DeWitt, Table A.4: 250.7e-7 N s/m^2 at 450 K) */
    CHECK_REL(rd_gas_viscosity(273.15), 1.716e-5, 1e-12, "Sutherland at T_0");
    CHECK_REL(rd_gas_viscosity(450.0), 2.507e-5, 0.02, "air at 450 K (table 2.507e-5)");
    /* the slot law: a number worked by hand (w 0.2314 m, h 2 um, L 2.9 mm,
     * mu 2.5e-5, R 287, T 450, 60 -> 30 bar):
     * 0.2314 * 8e-18 * 2.7e13 / (24 * 2.5e-5 * 287 * 450 * 2.9e-3) = 2.2242e-4 kg/s */
    rd_gasflow_slot s = {0.2314, 2.9e-3, 2.5e-5, 450.0};
    double d[3], h = 2e-6, A = s.width * h;
    double m = rd_gasflow_slot_flow(&s, 287.0, A, 6e6, 3e6, d);
    CHECK_REL(m, 2.2242e-4, 1e-4, "slot flow %.6g against the worked value", m);
    CHECK_REL(m, slot(s.width, h, s.length, s.mu, 287.0, 450.0, 6e6, 3e6), 1e-12, "slot formula");
    CHECK_REL(d[2], 3.0 * m / A, 1e-12, "slot: d/dA = 3 m / A");
    CHECK_REL(d[0], 2.0 * 6e6 * m / (6e6 * 6e6 - 9e12), 1e-12, "slot: d/dp_a");
    /* the orifice passes 16x more at 2 um here (at 60 -> 30 bar across a
     * 2.9 mm flank; the 25-36x at other pressures): the slot limits.
     * r = 0.5 is choked at k = 1.35 (r_c 0.537): 0.7 A p psi* / sqrt(R T),
     * psi* = sqrt(k) (2/(k+1))^((k+1)/(2(k-1))) = 0.680, is 3.67e-3 kg/s,
     * 16.5x the slot's 2.224e-4 */
    rd_gasflow_law law;
    rd_gasflow_law_init(&law, 1.35, 287.0);
    double o = rd_gasflow_flow(&law, 0.7, A, 6e6, 450.0, 3e6, 450.0, NULL);
    double l = rd_gasflow_limited(&law, &s, 0.7, A, 6e6, 450.0, 3e6, 450.0, NULL);
    CHECK(o > 15.0 * m && o < 18.0 * m, "orifice / slot at 2 um: %.1f", o / m);
    CHECK_REL(o, nozzle(1.35, 287.0, 0.7, A, 6e6, 450.0, 3e6), 1e-12, "orifice written again");
    /* the blend at o/m >= 15: (1 + (m/o)^4)^(-1/4) >= 1 - 5e-6 of the slot's */
    CHECK_REL(l, limited(o, m), 1e-12, "limited = the blend written again");
    CHECK(l <= m && l > 0.9999 * m, "limited %.6g within 1e-4 of the slot's %.6g", l, m);
    CHECK_REL(rd_gasflow_limited(&law, &s, 0.7, A, 3e6, 450.0, 6e6, 450.0, NULL), -l, 1e-14,
              "limited: antisymmetric");
    /* at large lift the orifice limits */
    double Ab = s.width * 200e-6;
    double ob = rd_gasflow_flow(&law, 0.7, Ab, 6e6, 450.0, 3e6, 450.0, NULL);
    double lb = rd_gasflow_limited(&law, &s, 0.7, Ab, 6e6, 450.0, 3e6, 450.0, NULL);
    CHECK(lb <= ob && lb > 0.999 * ob, "at 200 um the orifice: %.6g of %.6g", lb, ob);
}

/* The limited flow across the crossing: value continuous, analytic
 * derivatives against central differences, no jump in d/dA. */
static void test_blend_derivatives(void)
{
    rd_gasflow_law law;
    rd_gasflow_law_init(&law, 1.35, 287.0);
    rd_gasflow_slot s = {0.2314, 2.9e-3, rd_gas_viscosity(450.0), 450.0};
    double worst = 0.0, worst_p = 0.0, jump = 0.0, prev_d = NAN;
    for (int k = 0; k <= 400; k++) {
        double h = 1e-7 * pow(1e3, k / 400.0), A = s.width * h, d[3], dp[3];
        double pa = 2e6, pb = 1.2e6;
        rd_gasflow_limited(&law, &s, 0.7, A, pa, 450.0, pb, 450.0, d);
        double eA = 1e-6 * A, ep = 1.0;
        double fA = (rd_gasflow_limited(&law, &s, 0.7, A + eA, pa, 450.0, pb, 450.0, dp) -
                     rd_gasflow_limited(&law, &s, 0.7, A - eA, pa, 450.0, pb, 450.0, dp)) /
                    (2.0 * eA);
        double fa = (rd_gasflow_limited(&law, &s, 0.7, A, pa + ep, 450.0, pb, 450.0, dp) -
                     rd_gasflow_limited(&law, &s, 0.7, A, pa - ep, 450.0, pb, 450.0, dp)) /
                    (2.0 * ep);
        double fb = (rd_gasflow_limited(&law, &s, 0.7, A, pa, 450.0, pb + ep, 450.0, dp) -
                     rd_gasflow_limited(&law, &s, 0.7, A, pa, 450.0, pb - ep, 450.0, dp)) /
                    (2.0 * ep);
        worst = fmax(worst, fabs(fA - d[2]) / fabs(d[2]));
        worst_p = fmax(worst_p, fmax(fabs(fa - d[0]) / fabs(d[0]), fabs(fb - d[1]) / fabs(d[1])));
        /* d/dA per unit relative step of h: a jump would show against the
         * neighbours on this fine log grid (ratio 1.0174).  Smooth, A dm/dA
         * grows at most as A^3 (the slot's regime): 1.0174^3 = 1.053 a step,
         * so 0.06 passes that and fails a jump of more than ~1 % */
        double dn = d[2] * A;
        if (k > 0)
            jump = fmax(jump, fabs(dn - prev_d) / fmax(fabs(dn), fabs(prev_d)));
        prev_d = dn;
    }
    CHECK(worst < 1e-6, "d/dA against central differences: %.3g", worst);
    CHECK(worst_p < 1e-6, "d/dp against central differences: %.3g", worst_p);
    CHECK(jump < 0.06, "d/dA continuous across the crossing (largest step-to-step %.3g)", jump);
    /* equal pressures: zero flow, the slopes' blend, no area derivative */
    double d[3], d0[3], d1[3], A = s.width * 3e-6;
    double m = rd_gasflow_limited(&law, &s, 0.7, A, 2e6, 450.0, 2e6, 450.0, d);
    rd_gasflow_flow(&law, 0.7, A, 2e6, 450.0, 2e6, 450.0, d0);
    rd_gasflow_slot_flow(&s, 287.0, A, 2e6, 2e6, d1);
    CHECK(m == 0.0 && d[2] == 0.0, "equal pressures: no flow (%g), d/dA %g", m, d[2]);
    CHECK_REL(d[0], limited(d0[0], d1[0]), 1e-12, "equal pressures: the slopes' blend");
    /* and the slope is the limit of the flow's quotient there */
    double q = rd_gasflow_limited(&law, &s, 0.7, A, 2e6 + 1e-3, 450.0, 2e6, 450.0, NULL) / 1e-3;
    CHECK_REL(q, d[0], 1e-6, "equal pressures: slope %.6g, quotient %.6g", d[0], q);
}

/* ---- a steady network solved here (ringpack_steady.h) -------------------- */

static double cdeg[2] = {0.0, 720.0}, cpa[2];

/* One ring held at half its clearance (both flank passages open) under a
 * constant cylinder pressure: top entry -> land; land -> groove (upper
 * flank) -> crankcase (lower flank); land -> crankcase (end gap). */
static void held_pack(rd_ringpack_params *p, double pc)
{
    rd_ringpack_params_default(p);
    p->rings[0].pinned = RD_PIN_MIDDLE;
    cpa[0] = cpa[1] = pc;
    p->cylinder_kind = RD_CYLINDER_TABLE;
    p->table_points = 2;
    p->table_deg = cdeg;
    p->table_pa = cpa;
    p->engine.cycles = 12;
    p->rtol = 1e-10;
    p->estimate_error = 0;
}

static void check_steady(rd_ringpack_params *p, double pc, int visc, const char *what)
{
    rd_ringpack_result r;
    rd_error err;
    rd_error_init(&err);
    double pl, pg, mdot = steady(p, pc, &pl, &pg, visc);
    int rc = rd_ringpack_solve(p, NULL, &r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    if (rc == RD_OK) {
        int S = r.samples - 1;
        double land = r.pressure[(size_t)1 * r.samples + S], groove = r.pressure[2 * r.samples + S];
        CHECK_REL(land, pl, 1e-6, "%s: land %.7g Pa, steady %.7g", what, land, pl);
        CHECK_REL(groove, pg, 1e-6, "%s: groove %.7g Pa, steady %.7g", what, groove, pg);
        CHECK_REL(r.blowby_kg, mdot * 120.0 / p->engine.speed_rpm, 1e-6, "%s: blow-by", what);
        printf("%s: land %.7g, groove %.7g Pa, %.6g kg/s (steady: %.7g, %.7g)\n", what, land,
               groove, mdot, pl, pg);
    }
    rd_ringpack_result_cleanup(&r);
}

static void test_steady(void)
{
    rd_ringpack_params p;
    held_pack(&p, 5e5);
    check_steady(&p, 5e5, 1, "viscous-limited flanks, 5 bar");
    held_pack(&p, 5e5);
    p.flank_passage = RD_PASSAGE_ORIFICE;
    check_steady(&p, 5e5, 0, "orifice flanks, 5 bar");
    /* another gas: k 1.3, R 300, a given viscosity */
    held_pack(&p, 3e6);
    p.kappa = 1.3;
    p.gas_constant = 300.0;
    p.gas_viscosity = 4e-5;
    check_steady(&p, 3e6, 1, "k 1.3, R 300, mu 4e-5, 30 bar");
}

/* ---- end gap, oil ring, pack -------------------------------------------- */

static int solve(const rd_ringpack_params *p, rd_ringpack_result *r, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    return rc;
}

/* The rule's area (closed gap x the narrower land) equals the same area
 * given: the same run to the last bit; the land above differs. */
static void test_end_gap(void)
{
    rd_ringpack_params p, q;
    rd_ringpack_result a, b, c;
    rd_ringpack_params_thesis(&p);
    p.engine.cycles = 2;
    p.estimate_error = 0;
    q = p;
    for (int i = 0; i < 2; i++)
        q.rings[i].end_gap_area = q.rings[i].ring.closed_gap * q.rings[i + 1].land_clearance;
    int ok = solve(&p, &a, "rule") == RD_OK && solve(&q, &b, "explicit") == RD_OK;
    if (ok)
        CHECK(a.blowby_kg == b.blowby_kg &&
                  a.pressure[a.samples * 3 + 100] == b.pressure[b.samples * 3 + 100],
              "the rule's area given explicitly: %.9g vs %.9g kg", a.blowby_kg, b.blowby_kg);
    /* the land above's clearance (today's before the rule): more area, more blow-by */
    for (int i = 0; i < 2; i++)
        q.rings[i].end_gap_area = q.rings[i].ring.closed_gap * q.rings[i].land_clearance;
    if (ok && solve(&q, &c, "land above") == RD_OK)
        CHECK(c.blowby_kg > 1.05 * a.blowby_kg, "land above's area: %.4g > %.4g L/min",
              c.blowby_l_per_min, a.blowby_l_per_min);
    rd_ringpack_result_cleanup(&a);
    rd_ringpack_result_cleanup(&b);
    rd_ringpack_result_cleanup(&c);
}

/* The thesis pack: the oil ring held, its leak the only path below the
 * second ring besides the flanks; the top ring with viscous passages and
 * linear flank pressure seats on its upper flank during expansion after
 * one leave; with orifices alone it leaves its lower flank more than once
 * first (chatters) and seats later. */
static int upper_seat(const rd_ringpack_result *r, int *leaves)
{
    *leaves = 0;
    for (int e = 0; e < r->n_events[0]; e++) {
        const rd_lift_event *ev = &r->events[0][e];
        *leaves += ev->kind == RD_EVENT_LEAVE_LOWER;
        if (ev->kind == RD_EVENT_REACH_UPPER)
            return ev->crank_deg < 180.0 ? e : -1;
    }
    return -1;
}

static void test_thesis_pack(void)
{
    rd_ringpack_params p;
    rd_ringpack_result v, o;
    rd_ringpack_params_thesis(&p);
    p.estimate_error = 0;
    CHECK(p.n_rings == 3 && p.rings[2].kind == RD_RING_OIL && p.rings[2].pinned == RD_PIN_LOWER,
          "thesis pack: three rings, the oil ring held");
    if (solve(&p, &v, "thesis pack") == RD_OK) {
        int leaves, e = upper_seat(&v, &leaves);
        CHECK(e >= 0 && leaves == 1,
              "viscous: seated on the upper flank at %.1f deg after %d leave",
              e >= 0 ? v.events[0][e].crank_deg : NAN, leaves);
        CHECK(v.n_events[2] == 0 && v.mass_residual < 1e-6, "oil ring held; mass %.2g",
              v.mass_residual);
        CHECK(v.blowby_l_per_min > 0.5 && v.blowby_l_per_min < 5.0, "blow-by %.3g L/min",
              v.blowby_l_per_min);
        printf("thesis pack, viscous-limited: %.4g L/min, %d events of the top ring\n",
               v.blowby_l_per_min, v.n_events[0]);
    }
    p.flank_passage = RD_PASSAGE_ORIFICE;
    if (solve(&p, &o, "thesis pack, orifice") == RD_OK) {
        int leaves, e = upper_seat(&o, &leaves);
        CHECK(leaves >= 2,
              "orifice: the top ring leaves its lower flank %d times before it "
              "seats on the upper (chatter)",
              leaves);
        CHECK(e < 0 || o.events[0][e].crank_deg > v.events[0][0].crank_deg + 20.0,
              "orifice: seats on the upper flank later (%.1f deg)",
              e >= 0 ? o.events[0][e].crank_deg : NAN);
        printf("thesis pack, orifice: %.4g L/min, %d events of the top ring\n", o.blowby_l_per_min,
               o.n_events[0]);
    }
    rd_ringpack_result_cleanup(&v);
    rd_ringpack_result_cleanup(&o);
}

/* Linear flank pressure halves a ring's net gas force: the pack's full
 * and linear runs agree while pinned; moving (axial rings, so only the
 * force differs), the top ring leaves its lower flank in the expansion
 * stroke when the second land's pressure, pushing it up, overcomes the
 * piston's deceleration: with half that push it leaves later. */
static void test_flank_pressure(void)
{
    rd_ringpack_params p;
    rd_ringpack_result lin, full;
    rd_ringpack_params_thesis(&p);
    p.estimate_error = 0;
    p.engine.cycles = 3;
    for (int i = 0; i < 2; i++)
        p.rings[i].pinned = RD_PIN_LOWER;
    int ok = solve(&p, &lin, "pinned, linear") == RD_OK;
    p.flank_pressure = RD_FLANK_PRESSURE_FULL;
    if (ok && solve(&p, &full, "pinned, full") == RD_OK) {
        CHECK(lin.blowby_kg == full.blowby_kg,
              "pinned rings: the flank pressure moves nothing "
              "(%.9g, %.9g)",
              lin.blowby_kg, full.blowby_kg);
        rd_ringpack_result_cleanup(&full);
    }
    rd_ringpack_result_cleanup(&lin);
    for (int i = 0; i < 2; i++)
        p.rings[i].pinned = RD_PIN_FREE;
    p.model = RD_RINGPACK_AXIAL;
    ok = solve(&p, &full, "moving, full") == RD_OK;
    p.flank_pressure = RD_FLANK_PRESSURE_LINEAR;
    if (ok && solve(&p, &lin, "moving, linear") == RD_OK) {
        double a = lin.n_events[0] ? lin.events[0][0].crank_deg : NAN;
        double b = full.n_events[0] ? full.events[0][0].crank_deg : NAN;
        CHECK(lin.n_events[0] && lin.events[0][0].kind == RD_EVENT_LEAVE_LOWER && a > b + 1.0 &&
                  a < 180.0,
              "the top ring leaves later with half the push: %.2f deg (full: %.2f)", a, b);
        rd_ringpack_result_cleanup(&lin);
    }
    if (ok)
        rd_ringpack_result_cleanup(&full);
}

/* engine.cycles periodic: it stops at the first cycle whose change is
 * below the tolerance; the same count run as a fixed number of cycles
 * gives the same answer to the last bit, one cycle fewer a change still
 * above the tolerance. */
static void test_periodic(void)
{
    rd_ringpack_params p;
    rd_ringpack_result a, b, c;
    rd_ringpack_params_thesis(&p);
    p.estimate_error = 0;
    p.periodic = 1;
    p.engine.cycles = RD_RINGPACK_CYCLES_MAX;
    if (solve(&p, &a, "periodic") != RD_OK)
        return;
    CHECK(a.settled && a.periodicity < 1e-3 && a.cycles >= 3 && a.cycles < 20,
          "periodic: settled %d after %d cycles at %.3g", a.settled, a.cycles, a.periodicity);
    p.periodic = 0;
    p.engine.cycles = a.cycles;
    if (solve(&p, &b, "fixed, as many") == RD_OK) {
        CHECK(b.blowby_kg == a.blowby_kg && b.periodicity == a.periodicity &&
                  b.n_events[0] == a.n_events[0] && !b.settled,
              "fixed %d cycles: blow-by %.12g vs %.12g", b.cycles, b.blowby_kg, a.blowby_kg);
        rd_ringpack_result_cleanup(&b);
    }
    p.engine.cycles = a.cycles - 1;
    if (solve(&p, &c, "fixed, one fewer") == RD_OK) {
        CHECK(c.periodicity >= 1e-3, "one cycle fewer: change %.3g", c.periodicity);
        rd_ringpack_result_cleanup(&c);
    }
    printf("periodic: %d cycles, change %.3g\n", a.cycles, a.periodicity);
    rd_ringpack_result_cleanup(&a);
}

/* ---- bad input ---------------------------------------------------------- */

static void expect_bad(const rd_ringpack_params *p, const char *path, const char *what)
{
    rd_ringpack_result r;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, &r, &err);
    CHECK(rc == RD_EINVAL && strcmp(err.path, path) == 0, "%s: %d at '%s' (%s), want %s", what, rc,
          err.path, err.message, path);
    rd_ringpack_result_cleanup(&r);
}

static void test_bad_input(void)
{
    rd_ringpack_params p;
    const double bad_k[] = {1.0, 0.9, 1.67, 1.8};
    for (int k = 0; k < 4; k++) {
        rd_ringpack_params_thesis(&p);
        p.kappa = bad_k[k];
        expect_bad(&p, "/physics/gas/heat_capacity_ratio", "k out of range");
    }
    rd_ringpack_params_thesis(&p);
    p.rings[1].end_gap_area = -1e-8;
    expect_bad(&p, "/rings/1/end_gap_area_m2", "negative end-gap area");
    rd_ringpack_params_thesis(&p);
    p.rings[1].kind = RD_RING_OIL;
    expect_bad(&p, "/rings/1/kind", "an oil ring that is not last");
    rd_ringpack_params_thesis(&p);
    p.rings[2].leak_area = 0.0;
    expect_bad(&p, "/rings/2/leak_area_m2", "no leak area");
    rd_ringpack_params_thesis(&p);
    p.gas_viscosity = 1e-9;
    expect_bad(&p, "/physics/gas/viscosity_pa_s", "viscosity below range");
    rd_ringpack_params_thesis(&p);
    p.gas_constant = 10.0;
    expect_bad(&p, "/physics/gas/gas_constant", "gas constant");
    rd_ringpack_params_thesis(&p);
    p.periodic_tolerance = 0.5;
    expect_bad(&p, "/numerics/periodic_tolerance", "periodic tolerance");
    rd_ringpack_params_thesis(&p);
    p.active_area = RD_GAS_AREA_DYNAMIC;
    expect_bad(&p, "/physics/gas/flank_pressure", "linear with dynamic areas");
}

int main(void)
{
    test_laws();
    test_blend_derivatives();
    test_steady();
    test_end_gap();
    test_thesis_pack();
    test_flank_pressure();
    test_periodic();
    test_bad_input();
    return check_done();
}
