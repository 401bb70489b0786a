/*
 * test_contact_nl — the geometrically exact contact reference
 * (contact_reference_nl.c) against a closed form and against the linear
 * reference (contact_reference.c) in the small-load limit.
 *
 * Round bore: every node in contact, the centroid stays on the circle of
 * radius R, shortened by the hoop force N = -F_t (strain -F_t/EA); the bore
 * carries |N| per radian of the deformed ring, so per radian of the
 * reference ring p = p0 (1 - F_t/EA), where the linear reference has p0
 * (both less the ends' share b^2/(12 R^2), see test_contact.c).
 *
 * Small loads: F_t and the bore's amplitude scaled by s leave the linear
 * reference's pressure / p0 unchanged; the geometrically exact one differs
 * from it by a term of relative size ~ F_t R^2/(E I) (the hoop force's
 * geometric stiffness, the following load), so the difference / p0 must
 * fall as s (the difference in Pa as s^2, the load squared).
 */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "contact_reference.h"
#include "rd_static.h"

#define PI 3.14159265358979323846

/* 360 cells: 1 deg, the pressure bins of 10 deg hold 10 nodes each; a
 * sanitizer build solves each bore in ~0.1 s */
#define CELLS 360

static void test_round_bore(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    /* F_t / EA = 1e-2, so the shortening stands 100 x above the cells'
     * O(D^2) = 1e-5 terms */
    double EA = p.youngs_modulus * p.radial_width * p.axial_height;
    p.tangential_force = 1e-2 * EA;
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    ref_result nl, lin;
    CHECK(ref_contact_solve_nl(&p, &o, CELLS, 1, 10.0, 0.0, &nl) == 0, "nl, round bore");
    CHECK(ref_contact_solve(&p, &o, CELLS, 10.0, 0.0, &lin) == 0, "linear, round bore");
    double R = 0.5 * (p.diameter - p.radial_width), ends = pow(p.radial_width / R, 2) / 12.0;
    /* The ring is shortened by F_t / EA = 1e-2 and moves along the bore:
     * the centroid by u = 1e-2 R (theta - pi) from the pin at 180 deg, the
     * section turning with it (beta = u / R, no shear), so the running
     * face by u r_o / R, over r_o an angle of 1e-2 (pi - s) at either free
     * end (s the half closed-gap angle).  Within 1 %: measured 0.1 %, the
     * tips' concentrated forces bend the last few degrees. */
    double s = p.closed_gap / (2.0 * R), move = 1e-2 * (PI - s) * 180.0 / PI;
    CHECK_REL(nl.end_deg[0] - s * 180.0 / PI, move, 0.01, "round bore: first end's move");
    CHECK_REL(360.0 - s * 180.0 / PI - nl.end_deg[1], move, 0.01, "round bore: last end's move");
    /* bins 3..32: 30 deg clear of the free ends' light gaps (a few nm,
     * under the tips' concentrated forces) */
    for (int b = 3; b < nl.bins - 3; b++) {
        /* on the bore the hoop force F_t is held by the pressure p h r_o
         * per unit angle whatever the shortening, p = p0 (1 - ends): within
         * 2e-4 of p0, 2 % of the 1e-2 the shortening would have made over
         * the unloaded arcs; what is left out is O(D^2) = 1e-5 and the
         * ends' share's own change with the load, 1e-2 x 5e-4 */
        double want = 1.0 - ends;
        CHECK(fabs(nl.bin_pressure[b] / nl.p0 - want) < 2e-4,
              "round bore bin %d: %.6f p0, want %.6f", b, nl.bin_pressure[b] / nl.p0, want);
        /* the linear reference balances the hoop force over the unloaded
         * arcs, so over the shortened ring's arcs on the bore its pressure
         * stands 1e-2 higher, within the same 2e-4 */
        double d = (nl.bin_pressure[b] - lin.bin_pressure[b]) / nl.p0;
        CHECK(fabs(d + 1e-2) < 2e-4, "round bore bin %d: nl - linear %.6f p0", b, d);
    }
}

/* The bins' differences nl - linear / p0 at load scale s (F_t and the
 * amplitude times s). */
static int difference(int k, double fac, double phase, double s, double d[36])
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = ref_battery_bore(&p, k, fac, phase);
    p.tangential_force *= s;
    o.bore.distortion[0].amplitude *= s;
    ref_result nl, lin;
    if (ref_contact_solve_nl(&p, &o, CELLS, 1, 10.0, 0.0, &nl) != 0 ||
        ref_contact_solve(&p, &o, CELLS, 10.0, 0.0, &lin) != 0 || nl.bins != 36)
        return -1;
    for (int b = 0; b < nl.bins; b++)
        d[b] = (nl.bin_pressure[b] - lin.bin_pressure[b]) / nl.p0;
    return 0;
}

static double max_change(const double *a, const double *b)
{
    double worst = 0;
    for (int i = 0; i < 36; i++)
        worst = fmax(worst, fabs(a[i] - b[i]));
    return worst;
}

static void test_small_load(void)
{
    /* 0.2 x the bound: the light gaps are the free ends' few degrees, and
     * the same nodes touch in both references at every s (at 0.5 x, order
     * 2, an edge node differs at s = 1, which is no smooth function of s) */
    const int orders[] = {3, 4};
    for (int i = 0; i < 2; i++) {
        double d1[36], d2[36], d3[36], zero[36] = {0};
        int k = orders[i];
        if (difference(k, 0.2, 17.0, 1.0, d1) || difference(k, 0.2, 17.0, 0.1, d2) ||
            difference(k, 0.2, 17.0, 0.01, d3)) {
            CHECK(0, "order %d: a reference failed", k);
            continue;
        }
        /* d(s) = d0 + c s + O(s^2): d0 the two discretisations' own
         * difference (O(D^2), the same at every load), c s the geometric
         * nonlinearity; a decade of load takes a decade off the change */
        double a = max_change(d1, d2), b = max_change(d2, d3);
        double floor_d0 = 0;
        for (int q = 0; q < 36; q++)
            floor_d0 = fmax(floor_d0, fabs(d3[q] - (d2[q] - d3[q]) / 9.0));
        printf("order %d, 0.2 x bound: nl - linear, largest bin / p0 %.3e at s = 1; change "
               "1 -> 0.1: %.3e, 0.1 -> 0.01: %.3e (ratio %.3f); load-free part %.1e\n",
               k, max_change(d1, zero), a, b, a / b, floor_d0);
        /* the nonlinearity at the real load stands 5 x over the
         * discretisations' difference (measured 8e-4 and 3e-4 p0 against
         * 9e-5 and 4e-5) */
        CHECK(a > 5 * floor_d0, "order %d: change %.2e, floor %.2e", k, a, floor_d0);
        /* linear in s within 5 %: the s^2 term is ~s c (F_t R^2 / E I =
         * 0.03) of it (measured ratios 10.01, 9.96) */
        CHECK(fabs(a / b - 10.0) < 0.5, "order %d: ratio %.3f", k, a / b);
    }
}

int main(void)
{
    test_round_bore();
    test_small_load();
    return check_done();
}
