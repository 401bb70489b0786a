/* test_contact — the ring in a distorted bore against two independent
 * references written apart from core's segment chain, on 1440 cells with
 * exact frictionless unilateral contact (contact_reference.c, a linear
 * curved Timoshenko beam; contact_reference_nl.c, the same beam
 * geometrically exact, which ringdyn converges to):
 *  - the reference itself against closed forms: uniform pressure 2 F_t/(d h)
 *    in a round bore, the thin-ring pressure p0 (1 - (A / bound) cos k theta)
 *    of a conforming ring below the bound;
 *  - core's light gaps, contact fraction and largest gap on a battery of
 *    bores (orders 3, 4, 6; 0.1 to 10 x the thin-ring bound; two phases)
 *    at n = 160 against the linear reference;
 *  - at the default settings on bench_static's battery (orders 2, 3, 4, 6)
 *    against the exact reference, with tighter bounds, and the binned
 *    pressure within twice its estimate;
 *  - the accuracy target: met in a round bore, refused with a reason when
 *    the segment cap stops the refinement; the estimates not understating
 *    the true errors (contact fraction, edges, largest gap) by more than x3;
 *  - the contact stiffness moves the answer by less than the estimates;
 *  - the contact load's closed-form derivative (the Newton tangent) against
 *    central differences of the load itself. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "contact_reference.h"
#include "rd_static.h"
#include "rd_static_internal.h"

#define PI 3.14159265358979323846

static double bound_of(const rd_ring_params *p, int k)
{
    rd_ring_section s;
    rd_ring_section_get(p, 0, &s);
    return p->tangential_force * pow(s.R, 3) /
           (p->youngs_modulus * s.I_inplane * pow(k * k - 1.0, 2));
}

static rd_contact_opts bore(const rd_ring_params *p, int k, double factor, double phase)
{
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    o.bore.n_distortion = 1;
    /* 0.4 % of the diameter caps the largest amplitudes (the limit is 1 %) */
    o.bore.distortion[0] =
        (rd_distortion){k, fmin(factor * bound_of(p, k), 0.004 * p->diameter), phase};
    return o;
}

static double floor_of(const rd_ring_params *p)
{
    return rd_contact_gap_floor(p);
}

static void test_reference(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    ref_result r;
    CHECK(ref_contact_solve(&p, &o, 1440, 10.0, floor_of(&p), &r) == 0, "reference, round bore");
    /* the hoop force F_t balances p h r_o: p = 2 F_t / (d h) away from the
     * free ends, within 1e-3 (measured -5.2e-4 here, uniform along the ring:
     * the ends' share, which core's mean pressure shows too, -5e-4 at
     * n >= 320 in docs/contact.md) */
    for (int b = 1; b < r.bins - 1; b++)
        CHECK(fabs(r.bin_pressure[b] / r.p0 - 1) < 1e-3, "round bore bin %d: %g p0", b,
              r.bin_pressure[b] / r.p0);
    CHECK(r.n_gaps == 0 && r.contact_fraction == 1.0, "round bore: %d gaps", r.n_gaps);

    /* below the bound the ring conforms and p = p0 (1 - f cos k theta), f =
     * A / bound (thin ring); away from the free ends the bin means agree
     * within 0.03 p0: the thin-ring formula leaves out b / R (r_o / R = 1.04,
     * so ~4 % of the 0.5 p0 swing) and the shear and extension. */
    for (int k = 3; k <= 4; k++) {
        o = bore(&p, k, 0.5, 0.0);
        if (ref_contact_solve(&p, &o, 1440, 10.0, floor_of(&p), &r) != 0) {
            CHECK(0, "reference, order %d", k);
            continue;
        }
        for (int b = 6; b < 30; b++) {
            double a0 = b * 10 * PI / 180, a1 = (b + 1) * 10 * PI / 180;
            double thin = 1 - 0.5 * (sin(k * a1) - sin(k * a0)) / (k * (a1 - a0));
            CHECK(fabs(r.bin_pressure[b] / r.p0 - thin) < 0.03,
                  "order %d bin %d: %.4f p0, thin ring %.4f", k, b, r.bin_pressure[b] / r.p0, thin);
        }
    }
}

/* ref_edge_error, 0 where the reference has no gap over 0.1 um */
static double edge_or_0(const rd_contact_result *c, const ref_result *r)
{
    double e = ref_edge_error(c, r);
    return isnan(e) ? 0.0 : e;
}

static void test_battery(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    const int orders[] = {3, 4, 6};
    const double factors[] = {0.1, 1, 3, 10}, phases[] = {0, 17};
    rd_static_opts so;
    rd_static_opts_default(&so);
    so.estimate_error = 0;
    for (int oi = 0; oi < 3; oi++)
        for (int fi = 0; fi < 4; fi++)
            for (int pi = 0; pi < 2; pi++) {
                int k = orders[oi];
                rd_contact_opts o = bore(&p, k, factors[fi], phases[pi]);
                ref_result r;
                rd_contact_result c;
                rd_error err;
                rd_error_init(&err);
                if (ref_contact_solve(&p, &o, 1440, 10.0, floor_of(&p), &r) != 0) {
                    CHECK(0, "reference k=%d x%g", k, factors[fi]);
                    continue;
                }
                /* n = 160 (2.25 deg segments) */
                if (rd_contact_solve(&p, 160, &o, &so, NULL, &c, &err) != RD_OK) {
                    CHECK(0, "k=%d x%g: %s", k, factors[fi], err.message);
                    continue;
                }
                /* bounds measured on this battery at n = 160 (bench_static
                 * --battery has them at the default settings): the edge
                 * locator is good to about one segment, 2.25 deg, which with
                 * up to 14 edges bounds the contact fraction; a run off the
                 * bore about as deep as the floor (k = 3 at 0.1 x: 9.4 nm
                 * here, 7.3 in the reference, floor 9.4) may count in one
                 * and not the other, so its width is allowed too; edges:
                 * measured at most 1.08 deg here (k = 3 at 3 x) */
                CHECK(fabs(c.contact_fraction - r.contact_fraction) <
                          0.02 + c.marginal_gap_deg / 360.0,
                      "k=%d x%g ph %g: contact fraction %.4f, reference %.4f", k, factors[fi],
                      phases[pi], c.contact_fraction, r.contact_fraction);
                if (r.max_clearance > 1e-7)
                    CHECK_REL(c.max_clearance, r.max_clearance, 0.05,
                              "k=%d x%g ph %g: largest light gap", k, factors[fi], phases[pi]);
                CHECK(edge_or_0(&c, &r) < 1.5, "k=%d x%g ph %g: gap edges off by %.2f deg", k,
                      factors[fi], phases[pi], edge_or_0(&c, &r));
                rd_contact_result_cleanup(&c);
            }
}

/* The battery of bench_static --battery at the default settings (n from
 * 20, a = 0.01, refined to at most 1280) against the geometrically exact
 * reference (contact_reference_nl.c, 2880 cells as the bench, F_t following
 * the end sections as in ringdyn), which ringdyn converges to; its 30
 * distinct bores take ~15 s in a sanitizer build (the reference started
 * from the linear reference's contact states; on 1440 cells its own bins
 * were 0.031 p0 off on order 2 at 3 x, 17 deg, and 0.39 on order 4 at 10 x,
 * 17 deg, the estimates' errors the check below counted).  The bounds are
 * tighter than test_battery's against the linear reference at n = 160
 * (0.02, 5 %, 1.5 deg), which ringdyn does not converge to. */
/* The pressure estimate's place (since 0.3.4): a bin's middle for the
 * levels' and the law's parts, a bin boundary for the others; and where
 * the bins are off by more than the 0.02 p0 against the reference
 * (dp, the largest), one of the bins at that place is off by at least a
 * third of dp (order 6 at 10 x, 0 deg: 0.140 p0 by 150 and 210 deg, the
 * estimate's place 270 deg, where the bins are 0.11 off). */
static void check_where(const rd_contact_result *c, const ref_result *x, double dp)
{
    const rd_contact_estimates *e = &c->estimates;
    double w = RD_CONTACT_BIN_DEG, at = e->pressure_at_deg;
    int mid = e->pressure_source == RD_EST_LEVELS || e->pressure_source == RD_EST_LAW;
    double off = fabs(remainder(at - (mid ? 0.5 * w : 0.0), w));
    CHECK(e->pressure_source != RD_EST_NONE && off < 1e-9 && at >= 0.0 && at <= 360.0,
          "the pressure estimate's place %g deg, source %d", at, e->pressure_source);
    if (!(dp > 0.02) || !(off < 1e-9))
        return;
    int k0 = (int)floor(at / w - (mid ? 0.0 : 0.5)), k1 = mid ? k0 : k0 + 1;
    double there = 0.0;
    for (int k = k0; k <= k1; k++)
        if (k >= 0 && k < RD_CONTACT_BINS)
            there = fmax(there, fabs(c->bin_pressure[k] - x->bin_pressure[k]) / x->p0);
    printf(
        "  the pressure estimate's place %g deg (%s): bins there %.3f p0 off, the largest %.3f\n",
        at, rd_contact_est_source_name(e->pressure_source), there, dp);
    CHECK(there >= dp / 3, "the pressure estimate's place %g deg: bins there %.3f p0 off of %.3f",
          at, there, dp);
}

/* The bore o at a looser target, a = 0.05 (the refinement stops sooner):
 * if its answer says the target is met, the largest of its true errors
 * against x over its target (rd_contact_target.c: bins a p0, contact
 * fraction 2 a, largest gap 5 a of itself where over 0.1 um, gap edges
 * 100 a deg) into *worst; *met counts them. */
static void loose_target(const rd_ring_params *p, const rd_contact_opts *o, const ref_result *x,
                         int *met, double *worst)
{
    rd_contact_opts o2 = *o;
    o2.accuracy = 0.05;
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result c;
    rd_error err;
    rd_error_init(&err);
    if (rd_contact_solve(p, 20, &o2, &so, NULL, &c, &err) != RD_OK) {
        CHECK(0, "accuracy 0.05: %s", err.message);
        return;
    }
    if (c.accuracy_met == 1) {
        double a = o2.accuracy, dp = 0;
        for (int b = 0; b < RD_CONTACT_BINS; b++)
            dp = fmax(dp, fabs(c.bin_pressure[b] - x->bin_pressure[b]) / x->p0);
        double q = fmax(dp / a, fabs(c.contact_fraction - x->contact_fraction) / (2 * a));
        if (x->max_clearance > 1e-7)
            q = fmax(q, fabs(c.max_clearance / x->max_clearance - 1) / (5 * a));
        q = fmax(q, edge_or_0(&c, x) / (100 * a));
        *worst = fmax(*worst, q);
        ++*met;
    }
    rd_contact_result_cleanup(&c);
}

/* c's contact patches against the exact reference x's: as many, each
 * patch's force within 1 % of the larger of its force and 0.5 N (measured
 * at most 0.4 %, order 3 at 10 x, 17 deg, n = 160: 0.011 N; x2.5), and
 * the estimate not understating the error beyond x3 over the floor;
 * returns whether the estimate tracks the error (ref_tracks). */
static int patches_against(const rd_ring_params *p, const rd_contact_result *c, const ref_result *x,
                           int k, double fac, double ph)
{
    double rel, d = ref_patch_error(c, x, &rel), fl = ref_patch_floor(x);
    /* every segment's force in one patch: the patches' sum is the
     * segments' resultants' (pressure x h x r_o x arc, r_o = d / 2 for a
     * rectangular section), to rounding */
    double all = 0.0, sum = 0.0;
    for (int i = 0; i < c->points; i++)
        all += c->pressure[i] * p->axial_height * 0.5 * p->diameter * c->width_deg[i] * PI / 180.0;
    for (int j = 0; j < c->n_patches; j++)
        sum += c->patches[j].force_n;
    CHECK(fabs(sum - all) <= 1e-9 * all, "k=%d x%g ph %g: patches sum to %.12g N, segments %.12g N",
          k, fac, ph, sum, all);
    printf("  patches %d (exact %d): forces off by %.4f N, %.2f %% (est. %.4f N)\n", c->n_patches,
           x->n_patches, d, 100 * rel, c->estimates.patch_forces_n);
    CHECK(c->n_patches == x->n_patches && rel <= 0.01,
          "k=%d x%g ph %g: %d patches (exact %d), a force %.4f N off (%.2f %%)", k, fac, ph,
          c->n_patches, x->n_patches, d, 100 * rel);
    CHECK(d <= fl || d <= 3.0 * c->estimates.patch_forces_n,
          "k=%d x%g ph %g: patch forces %.4f N off, estimate %.4f N", k, fac, ph, d,
          c->estimates.patch_forces_n);
    return ref_tracks(c->estimates.patch_forces_n, d, fl);
}

static void test_battery_exact(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    const int orders[] = {2, 3, 4, 6};
    const double factors[] = {0.1, 1, 3, 10}, phases[] = {0, 17};
    rd_static_opts so;
    rd_static_opts_default(&so);
    int under_p = 0, under_g = 0, bores = 0, track[4] = {0}, graded = 0, met = 0, loose_met = 0;
    int patch_track = 0;
    double loose_worst = 0.0;
    for (int oi = 0; oi < 4; oi++)
        for (int fi = 0; fi < 4; fi++)
            for (int pi = 0; pi < 2; pi++) {
                int k = orders[oi];
                if (k == 2 && factors[fi] == 10)
                    continue; /* capped at 0.4 % of d: the 3 x bore again */
                rd_contact_opts o = bore(&p, k, factors[fi], phases[pi]);
                ref_result x;
                rd_contact_result c;
                rd_error err;
                rd_error_init(&err);
                if (ref_contact_solve_nl(&p, &o, 2880, 1, 10.0, floor_of(&p), &x) != 0) {
                    CHECK(0, "exact reference k=%d x%g ph %g", k, factors[fi], phases[pi]);
                    continue;
                }
                if (rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err) != RD_OK) {
                    CHECK(0, "k=%d x%g ph %g: %s", k, factors[fi], phases[pi], err.message);
                    continue;
                }
                double dp = 0, dcf = fabs(c.contact_fraction - x.contact_fraction);
                for (int b = 0; b < RD_CONTACT_BINS; b++)
                    dp = fmax(dp, fabs(c.bin_pressure[b] - x.bin_pressure[b]) / x.p0);
                double dg = x.max_clearance > 1e-7 ? c.max_clearance / x.max_clearance - 1 : 0;
                double de = edge_or_0(&c, &x);
                printf("k=%d x%g ph %g, n %d vs exact: contact fraction %.5f (est. %.5f), largest "
                       "gap %+.2f %%, edges %.2f deg (est. %.2f), bins %.3f p0 (est. %.3f)\n",
                       k, factors[fi], phases[pi], c.stats.segments, dcf,
                       c.estimates.contact_fraction, 100 * dg, de, c.estimates.gap_edges_deg, dp,
                       c.estimates.pressure);
                /* measured at most 0.0039 (order 6 at 3 x, 0 deg, n = 320)
                 * besides a run off the bore as deep as the floor, counted
                 * in one and not the other (order 3 at 0.1 x, 0 deg:
                 * 0.0545, its width 20 deg): 0.005 is x1.3 the worst, the
                 * issue's target 0.02 */
                CHECK(dcf < 0.005 + c.marginal_gap_deg / 360.0,
                      "k=%d x%g ph %g: contact fraction %.4f, exact %.4f", k, factors[fi],
                      phases[pi], c.contact_fraction, x.contact_fraction);
                /* measured at most 0.41 % (order 4 at 1 x, 0 deg, a 0.5 um
                 * gap; 0.47 % before the free ends' gaps were read at the
                 * end) where the gap exceeds 0.1 um: 1 % (the 5) */
                CHECK(fabs(dg) < 0.01, "k=%d x%g ph %g: largest gap %+.2f %% off", k, factors[fi],
                      phases[pi], 100 * dg);
                /* measured at most 0.49 deg (order 2 at 3 x, 0 deg, n =
                 * 160; 0.89 before the angles were taken on the bore):
                 * 0.65 deg, x1.3 the worst (the target: 1) */
                CHECK(de < 0.65, "k=%d x%g ph %g: gap edges off by %.2f deg", k, factors[fi],
                      phases[pi], de);
                /* the bins are not all converged (0.171 p0 on order 6 at
                 * 10 x, 0 deg: point contacts on the 90 and 270 deg
                 * boundaries, where the reference's own bins move as much
                 * between 1440 and 2880 cells; every other bore within
                 * 0.016), but the pressure's estimate covers them within
                 * x2 where they miss half the default target (errors under
                 * 0.01 p0 against estimates of 0.002-0.005 are not
                 * counted: order 4 at 0.1 x, 0 deg, 0.005 against 0.003);
                 * one bore may be at the edge of it: order 2 at 3 x, 17
                 * deg, 0.016 against 0.008 */
                int under = dp > 2 * c.estimates.pressure && dp > 0.01;
                under_p += under;
                check_where(&c, &x, dp);
                if (under)
                    printf("  k=%d x%g ph %g: the pressure's estimate understates x%.1f\n", k,
                           factors[fi], phases[pi], dp / c.estimates.pressure);
                /* the largest gap's (where over 0.1 um) never by more
                 * than x3 where the error exceeds 0.1 %, a fiftieth of the
                 * issue's target (measured at most 0.41 %: order 4 at 1 x,
                 * 0 deg, estimate 0.2 %).  Until 0.3.2 a largest gap at a
                 * free end was read at the last point, half a spacing short
                 * of the end, and differed from the reference by a settled
                 * 0.03-0.5 %, which the estimate did not see, so this
                 * counted only errors over 0.5 % */
                if (x.max_clearance > 1e-7) {
                    double eg = fabs(c.max_clearance - x.max_clearance);
                    int low = c.estimates.max_clearance < eg / 3 && eg > 1e-3 * x.max_clearance;
                    under_g += low;
                    if (low)
                        printf("  k=%d x%g ph %g: the largest gap's estimate understates x%.1f\n",
                               k, factors[fi], phases[pi], eg / c.estimates.max_clearance);
                }
                /* the contact fraction's and the edges' estimates do not
                 * understate the error by more than x3 (as test_estimates
                 * against the linear reference; measured at most x2.5 and
                 * x1.4, both order 4 at 1 x, 0 deg: 0.0011 against
                 * 0.00044, 0.17 deg against 0.12) */
                CHECK(c.estimates.contact_fraction >= dcf / 3 || dcf < 1e-3,
                      "k=%d x%g ph %g: contact fraction error %.4f, estimate %.4f", k, factors[fi],
                      phases[pi], dcf, c.estimates.contact_fraction);
                CHECK(c.estimates.gap_edges_deg >= de / 3,
                      "k=%d x%g ph %g: edge error %.3f deg, estimate %.3f", k, factors[fi],
                      phases[pi], de, c.estimates.gap_edges_deg);
                /* est / err within x3, as bench_static --battery counts */
                bores++;
                graded += c.grade_factor > 1;
                met += c.accuracy_met == 1;
                track[0] += ref_tracks(c.estimates.contact_fraction, dcf, 1e-3);
                track[1] += x.max_clearance <= 1e-7 ||
                            ref_tracks(c.estimates.max_clearance / c.max_clearance, fabs(dg), 1e-3);
                track[2] +=
                    x.max_clearance <= 1e-7 || ref_tracks(c.estimates.gap_edges_deg, de, 0.05);
                track[3] += ref_tracks(c.estimates.pressure, dp, 1e-3);
                /* the free ends' concentrated forces within 2 % + 0.01 N of
                 * the reference's (the bench's count), or their error
                 * within x3 of its estimate where they are not (the light
                 * tips of the 0.1 x bores and order 6 at 1 x, 17 deg,
                 * which the refinement stops short of: their estimates
                 * 0.05-0.4 N) */
                for (int e = 0; e < 2; e++) {
                    double dt = fabs(c.tip_force[e] - x.tip_force[e]);
                    printf("  tip %d: %.4f N, exact %.4f (est. %.4f)\n", e, c.tip_force[e],
                           x.tip_force[e], c.estimates.tip_forces_n);
                    CHECK(dt <= 0.02 * x.tip_force[e] + 0.01 || dt <= 3 * c.estimates.tip_forces_n,
                          "k=%d x%g ph %g: tip %d %.4f N, exact %.4f, estimate %.4f", k,
                          factors[fi], phases[pi], e, c.tip_force[e], x.tip_force[e],
                          c.estimates.tip_forces_n);
                }
                patch_track += patches_against(&p, &c, &x, k, factors[fi], phases[pi]);
                rd_contact_result_cleanup(&c);
                loose_target(&p, &o, &x, &loose_met, &loose_worst);
            }
    printf("estimates within x3 of the true error on %d bores: contact fraction %d, largest gap "
           "%d, edges %d, binned pressure %d\n",
           bores, track[0], track[1], track[2], track[3]);
    /* a looser target (0.05): measured 29 met, none with a true error over
     * 1.55 x its target (order 3 at 3 x, 17 deg: bins 0.077 p0 against
     * 0.05); x3 the tracking bound, one bore's room on the count */
    printf("at accuracy 0.05: %d met, the worst true error %.2f x its target\n", loose_met,
           loose_worst);
    CHECK(loose_met >= 28 && loose_worst <= 3.0,
          "accuracy 0.05: %d met, a true error %.2f x its target", loose_met, loose_worst);
    /* measured 28, 26, 26, 26 of the 30 (0.3.10: the shifted meshes' estimate,
     * test_shifted_meshes: order 6 at 3 x, 17 deg, 0.005 p0 off, estimated
     * 0.010 where d / 2 said 0.020; 28, 26, 26, 25 since 0.3.8;
     * 27, 26, 26, 25 at 0.3.7: order 4 at 10 x, 17 deg,
     * graded by 330 deg, meets the target at 654 segments with 0.006 p0
     * against a true 0.004, where 1280 equal segments gave 0.578); 27, 26,
     * 26, 24 at 0.3.6 (0.3.5: the multipliers' chord
     * step moved one largest gap's overstatement past x3, its estimate under
     * a tenth of the 5 % target; 27, 27, 26, 24 at 0.3.4, half the edges'
     * move in their estimate; 23, 27, 26, 24 at 0.3.3; 24, 27, 26, 26 at 0.3.2,
     * 26, 29, 27, 26 before the three bores whose default law missed the
     * target were solved again at 4 x: their answers came closer to the
     * reference than their new estimates, e.g. order 3 at 10 x, 17 deg,
     * contact fraction 0.0019 -> 0.0003 off, estimated 0.0024; 0.3.3's
     * unresolved-patch share refines order 4 at 10 x, 17 deg from 640 to
     * 1280, closer again, its estimates not; edge_bin_share raises order 6
     * at 10 x, 0 deg from 0.38 to 0.82 p0 against a true 0.14): one bore's
     * room each, as a ratio near x3 may flip with the build's rounding */
    /* the patch forces' estimate: measured within x3 of the error, or both
     * under the floor (ref_patch_floor), on all 30 (28 with a 0.01 N floor
     * alone: order 3 at 10 x, 0 deg, and order 4 at 10 x, 0 deg, estimates
     * 0.020 and 0.018 N at n = 160 against 0.003 and 0.006), never
     * understated beyond x3 (patches_against): two bores' room */
    CHECK(patch_track >= 28, "patch forces' estimate within x3 on %d of %d bores", patch_track,
          bores);
    CHECK(track[0] >= 26 && track[1] >= 25 && track[2] >= 25 && track[3] >= 25,
          "estimates within x3 of the true error: contact fraction %d, largest gap %d, edges %d, "
          "binned pressure %d of %d bores",
          track[0], track[1], track[2], track[3], bores);
    /* the local refinement ran (measured: order 4 at 10 x, 17 deg) and its
     * answers were held to the checks above */
    CHECK(graded >= 1, "no bore of the battery graded");
    /* the target met on 28 of the 30 (26 before 0.3.10's shifted meshes:
     * order 3 at 3 x, 0 deg, and order 6 at 3 x, 17 deg, stopped at the
     * cap on half the levels' change, 0.008 and 0.005 p0 off the reference,
     * now estimated at 0.009 and 0.010; not met: order 3 at 3 x, 17 deg,
     * 0.004 off, estimated 0.012, and order 6 at 10 x, 0 deg, point
     * contacts on the bin boundaries); one bore's room, as two of them
     * are within 10 % of the target */
    CHECK(met >= 27, "the target met on %d of the %d bores", met, bores);
    CHECK(under_p <= 1 && under_g == 0,
          "estimates understating the true error: the binned pressure's x2 on %d bores (1 "
          "may be), the largest gap's x3 on %d",
          under_p, under_g);
}

/* Multipliers stopped at the updates' limit still moving (after 2 of them,
 * far over twice the tolerance): the answer says so in its note, with the
 * last change, and does not call its target met (order 3 at 1 x, 17 deg,
 * meets it at the default limit, at 640 segments); without estimates the
 * note alone (accuracy_met stays -1, not judged). */
static void unsettled_note(const rd_ring_params *p)
{
    rd_contact_opts o = bore(p, 3, 1.0, 17.0);
    rd_static_opts so;
    rd_static_opts_default(&so);
    for (int limit = 0; limit < 2; limit++)
        for (int est = 0; est < 2; est++) {
            rd_contact_result c;
            rd_error err;
            rd_error_init(&err);
            so.max_updates = limit ? 2 : 60, so.estimate_error = est;
            if (rd_contact_solve(p, est ? 40 : 320, &o, &so, NULL, &c, &err) != RD_OK) {
                CHECK(0, "limit %d, estimates %d: %s", so.max_updates, est, err.message);
                continue;
            }
            int noted = strstr(c.accuracy_note, "still moving") != NULL;
            CHECK(noted == limit && (limit ? c.stats.outer_change > 2 * c.stats.outer_tolerance
                                           : c.stats.outer_change <= c.stats.outer_tolerance),
                  "limit %d updates, estimates %d: note %d, last change %g (tolerance %g): %s",
                  so.max_updates, est, noted, c.stats.outer_change, c.stats.outer_tolerance,
                  c.accuracy_note);
            CHECK(c.accuracy_met == (est ? !limit : -1), "limit %d, estimates %d: met %d",
                  so.max_updates, est, c.accuracy_met);
            /* stopped at the limit after a loose update (rd_static.c's
             * uzawa): the state is solved to the tolerance all the same */
            CHECK(c.stats.residual <= c.stats.tolerance,
                  "limit %d updates, estimates %d: residual %g over the tolerance %g",
                  so.max_updates, est, c.stats.residual, c.stats.tolerance);
            rd_contact_result_cleanup(&c);
        }
}

/* Largest bin difference of a and b, / p0. */
static double bins_apart(const rd_contact_result *a, const rd_contact_result *b)
{
    double d = 0.0;
    for (int k = 0; k < RD_CONTACT_BINS; k++)
        d = fmax(d, fabs(a->bin_pressure[k] - b->bin_pressure[k]) / a->uniform_pressure);
    return d;
}

/* The multipliers' (Uzawa) updates converge: order 3 at 3 x the bound,
 * 17 deg, n = 640 from the load path, is bench_static's hardest at that n.
 * The plain update converges linearly at 0.95-0.96 a step there: from the
 * same start it took 25 updates to its former 0.1 p0 test (30, the cap,
 * at 0.3.0's stiffness), stopping ~2 p0 short of the fixed point; the
 * mixed one (rd_anderson.h) meets the 0.02 p0 test in 15 (the bound, 20:
 * 8-16 over the battery at n = 640-1280).  What it stops at is the fixed
 * point: solved again from its own state and multipliers, one more update
 * moves the bins by 1.4e-4 p0 (bound 0.01, the target's).  On the battery
 * the converged multipliers moved order 2 at 2.8 x, 17 deg, from 0.199 to
 * 0.071 p0 off the reference at n = 640. */
static void test_uzawa(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 3, 3.0, 17.0);
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result c, r;
    rd_contact_warm w = {0};
    rd_error err;
    rd_error_init(&err);
    if (rd_contact_once(&p, 640, &o, &so, NULL, NULL, &w, &c, &err) != RD_OK) {
        CHECK(0, "n = 640: %s", err.message);
        rd_contact_warm_free(&w);
        return;
    }
    CHECK(c.stats.outer_iterations >= 1 && c.stats.outer_iterations <= 20,
          "multiplier updates at n = 640: %d", c.stats.outer_iterations);
    if (rd_contact_once(&p, 640, &o, &so, NULL, &w, NULL, &r, &err) != RD_OK) {
        CHECK(0, "again: %s", err.message);
        rd_contact_result_cleanup(&c);
        rd_contact_warm_free(&w);
        return;
    }
    double d = bins_apart(&c, &r);
    CHECK(d < 0.01, "solved again from its own state: bins %.4f p0 apart", d);
    printf("Uzawa at n = 640: %d updates; solved again, %d more, the bins %.2e p0 apart\n",
           c.stats.outer_iterations, r.stats.outer_iterations, d);
    CHECK(c.stats.outer_change <= c.stats.outer_tolerance && c.stats.outer_tolerance > 0.0,
          "converged, yet the last update's change %g above %g", c.stats.outer_change,
          c.stats.outer_tolerance);
    rd_contact_result_cleanup(&c);
    rd_contact_result_cleanup(&r);
    rd_contact_warm_free(&w);
    unsettled_note(&p);
}

/* Inexact multiplier updates (since 0.3.14, rd_static.c's uzawa): while
 * the updates are far from converged, each one's Newton solve stops at
 * 0.03 times its change's force on one segment, not at the full tolerance.
 * The same bore as test_uzawa (order 3 at 3 x, 17 deg, n = 640 from the
 * load path) against every update solved to the tolerance (update_eta 0,
 * 0.3.13's way): the same fixed point (bins within 0.01 p0, the target's
 * bound; each stops within 0.02 p0 of it; measured 5.5e-4 p0 apart), solved
 * to the tolerance at the end, with fewer Newton iterations (the load
 * path's are the same in both: measured 118 against 126 in all, 15 updates
 * each).  The CPU it saves is measured by bench_static --exact-updates. */
static void test_inexact_updates(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 3, 3.0, 17.0);
    rd_contact_result r[2];
    memset(r, 0, sizeof r);
    rd_error err;
    rd_error_init(&err);
    int rc = RD_OK;
    for (int k = 0; k < 2 && rc == RD_OK; k++) {
        rd_static_opts so;
        rd_static_opts_default(&so);
        if (k == 1)
            so.update_eta = 0.0;
        rc = rd_contact_once(&p, 640, &o, &so, NULL, NULL, NULL, &r[k], &err);
    }
    CHECK(rc == RD_OK, "%s", err.message);
    if (rc == RD_OK) {
        double d = bins_apart(&r[0], &r[1]);
        CHECK(d < 0.01, "inexact against exact updates: bins %.4f p0 apart", d);
        for (int k = 0; k < 2; k++)
            CHECK(r[k].stats.residual <= r[k].stats.tolerance &&
                      r[k].stats.outer_change <= r[k].stats.outer_tolerance,
                  "%s updates: residual %g (tolerance %g), last change %g p0",
                  k ? "exact" : "inexact", r[k].stats.residual, r[k].stats.tolerance,
                  r[k].stats.outer_change);
        CHECK(r[0].stats.iterations < r[1].stats.iterations,
              "inexact updates took %d Newton iterations, exact ones %d", r[0].stats.iterations,
              r[1].stats.iterations);
        printf("n = 640, inexact updates: %d Newton iterations (%d updates), exact: %d (%d); "
               "bins %.1e p0 apart\n",
               r[0].stats.iterations, r[0].stats.outer_iterations, r[1].stats.iterations,
               r[1].stats.outer_iterations, d);
    }
    for (int k = 0; k < 2; k++)
        rd_contact_result_cleanup(&r[k]);
}

/* Order k at fac x the bound, phase deg, on the default ring: n = 320 along
 * the load path, then 640 from each start kinds names ('w' 320's solved
 * state, 'b' its shape alone, 'p' the whole load path) into r (zeroed by
 * the caller); RD_OK or the first failure's code, err saying why. */
static int from_320(int k, double fac, double phase, const char *kinds, rd_contact_result *r,
                    rd_error *err)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, k, fac, phase);
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result c;
    memset(&c, 0, sizeof c);
    rd_contact_warm w = {0};
    rd_error_init(err);
    int rc = rd_contact_once(&p, 320, &o, &so, NULL, NULL, &w, &c, err);
    rd_contact_warm bare = w;
    bare.mult = NULL; /* the shape alone */
    for (int i = 0; kinds[i] && rc == RD_OK; i++) {
        const rd_contact_warm *from = kinds[i] == 'w' ? &w : (kinds[i] == 'b' ? &bare : NULL);
        rc = rd_contact_once(&p, 640, &o, &so, NULL, from, NULL, &r[i], err);
    }
    rd_contact_result_cleanup(&c);
    rd_contact_warm_free(&w);
    return rc;
}

/* A level started from the one below (since 0.3.8) takes its multipliers
 * too: order 6 at 3 x the bound, 17 deg, n = 640 from 320's state, against
 * the same state without them (each level rebuilt them from zero before)
 * and against the whole load path: the same fixed point (bins within 0.01
 * p0, the target's bound; the updates stop within 0.02 p0 of it, measured
 * 0.0014 p0 apart).  Fewer updates is not a property of every bore (here
 * 16 with them against 14 without; order 6 at 10 x, 0 deg, n = 1280: 32
 * against 44; bench_contact_cost --battery's finest levels, 744 Newton
 * iterations against 908), so it is measured there, not checked here. */
static void test_warm_multipliers(void)
{
    rd_contact_result r[3];
    memset(r, 0, sizeof r);
    rd_error err;
    int rc = from_320(6, 3.0, 17.0, "wbp", r, &err);
    CHECK(rc == RD_OK, "%s", err.message);
    if (rc == RD_OK) {
        double d1 = bins_apart(&r[0], &r[1]), d2 = bins_apart(&r[0], &r[2]);
        CHECK(d1 < 0.01 && d2 < 0.01, "from the multipliers: bins %.4f, %.4f p0 from the others",
              d1, d2);
        printf("n = 640 from 320: %d multiplier updates with its multipliers, %d without, %d "
               "from the load path; bins %.1e, %.1e p0 apart\n",
               r[0].stats.outer_iterations, r[1].stats.outer_iterations,
               r[2].stats.outer_iterations, d1, d2);
    }
    for (int k = 0; k < 3; k++)
        rd_contact_result_cleanup(&r[k]);
}

/* Contact's Newton takes full steps within 1e3 x its best residual (since
 * 0.3.13, rd_static.c's line_search): order 3 at 1.16848 x the bound,
 * 48.3412 deg (bench_static --single --random 82 40 1), whose long light
 * gaps of a few nm put many points at the law's switch.  n = 640 from
 * 320's state: the whole step from the warm start (0.8 -> 1) converges,
 * where the backtracked steps crawled, failed it after 40 iterations and
 * took four steps of 0.05 (102 Newton iterations against 32, the
 * multipliers' updates' included); and it lands on the whole load path's
 * fixed point (bins within 0.01 p0, the target's bound; measured 7e-5 p0
 * apart). */
static void test_full_steps(void)
{
    rd_contact_result r[2];
    memset(r, 0, sizeof r);
    rd_error err;
    int rc = from_320(3, 1.16848, 48.3412, "wp", r, &err);
    CHECK(rc == RD_OK, "%s", err.message);
    if (rc == RD_OK) {
        double d = bins_apart(&r[0], &r[1]);
        CHECK(r[0].stats.load_steps == 1,
              "n = 640 from 320: %d load steps (the whole step failed?)", r[0].stats.load_steps);
        CHECK(d < 0.01, "n = 640 from 320: bins %.4f p0 from the whole load path's", d);
        printf("full steps: n = 640 from 320 in %d load step(s), %d Newton iterations (%d "
               "updates); bins %.1e p0 from the load path's\n",
               r[0].stats.load_steps, r[0].stats.iterations, r[0].stats.outer_iterations, d);
    }
    rd_contact_result_cleanup(&r[0]);
    rd_contact_result_cleanup(&r[1]);
}

/* A graded ring (rd_contact_once_graded, the refinement's local levels):
 * base n = 320 with its segments over 25-65 deg in eight (0.14 deg, as n
 * = 2560) and one or two base segments either side in four and two, the
 * rest alike, so nothing is symmetric about 180 deg.  Against the exact
 * reference: the gap edges inside the fine arc located as well as n =
 * 2560 would, and those outside no worse than the equal ring's at 320,
 * which must see the same ring: held where it is held (opposite the gap)
 * and with each segment's force over its own arc (the bins). */

static void test_graded(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 4, 3.0, 17.0);
    rd_static_opts so;
    rd_static_opts_default(&so);
    int base = 320, n = 0;
    double *w = malloc(8 * base * sizeof *w),
           start = 0.5 * p.closed_gap / (0.5 * (p.diameter - p.radial_width)) * 180.0 / PI;
    double phi = (360.0 - 2.0 * start) / base;
    for (int i = 0; i < base; i++) {
        double lo = start + i * phi, hi = lo + phi;
        int r = hi > 25.0 && lo < 65.0
                    ? 3
                    : (hi > 25.0 - phi && lo < 65.0 + phi
                           ? 2
                           : (hi > 25.0 - 2 * phi && lo < 65.0 + 2 * phi ? 1 : 0));
        for (int k = 0; k < (1 << r); k++)
            w[n++] = 1.0 / (1 << r);
    }
    ref_result x;
    rd_contact_result g, u;
    rd_error err;
    rd_error_init(&err);
    int ok = ref_contact_solve_nl(&p, &o, 2880, 1, 10.0, floor_of(&p), &x) == 0;
    CHECK(ok, "exact reference");
    ok = ok && rd_contact_once_graded(&p, n, w, &o, &so, NULL, NULL, NULL, &g, &err) == RD_OK;
    CHECK(ok, "graded solve: %s", err.message);
    ok = ok && rd_contact_once(&p, base, &o, &so, NULL, NULL, NULL, &u, &err) == RD_OK;
    CHECK(ok, "equal solve: %s", err.message);
    free(w);
    if (!ok)
        return;
    CHECK(g.graded && !u.graded && g.points == n, "graded %d (%d segments), equal %d", g.graded,
          g.points, u.graded);
    double span = 0.0;
    for (int i = 0; i < g.points; i++)
        span += g.width_deg[i];
    CHECK(fabs(span - (360.0 - 2.0 * start)) < 1e-9, "the widths fill the span: %.12f deg", span);
    /* edges in and out of the fine arc, each against the reference's
     * nearest */
    double in[2] = {0, 0}, out[2] = {0, 0};
    const rd_contact_result *r[2] = {&g, &u};
    for (int v = 0; v < 2; v++)
        for (int q = 0; q < r[v]->n_gaps; q++)
            for (int side = 0; side < 2; side++) {
                double E = side ? r[v]->gaps[q].end_deg : r[v]->gaps[q].start_deg, d = INFINITY;
                if (E < 1.0 || E > 359.0)
                    continue;
                for (int h = 0; h < x.n_gaps; h++)
                    d = fmin(d, fabs(E - (side ? x.gaps[h].end_deg : x.gaps[h].start_deg)));
                if (E > 27.0 && E < 63.0)
                    in[v] = fmax(in[v], d);
                else
                    out[v] = fmax(out[v], d);
            }
    double dp[2] = {0, 0};
    for (int v = 0; v < 2; v++)
        for (int b = 0; b < RD_CONTACT_BINS; b++)
            dp[v] = fmax(dp[v], fabs(r[v]->bin_pressure[b] - x.bin_pressure[b]) / x.p0);
    printf("graded (%d segments) against equal (%d): edges in the fine arc %.4f / %.4f deg off, "
           "outside %.4f / %.4f; bins %.4f / %.4f p0; contact fraction %.5f / %.5f off\n",
           n, base, in[0], in[1], out[0], out[1], dp[0], dp[1],
           fabs(g.contact_fraction - x.contact_fraction),
           fabs(u.contact_fraction - x.contact_fraction));
    /* measured 0.018 deg against 0.129: the fine arc's edges within two of
     * its point spacings (0.056 deg), and x3 better than the equal ring's */
    CHECK(in[0] < 0.056 && in[0] < in[1] / 3, "edges in the fine arc %.4f deg off (equal: %.4f)",
          in[0], in[1]);
    /* outside it the same base: measured alike to 1e-4 deg (held at the
     * wrong section, the whole ring turned 0.15 deg) */
    CHECK(fabs(out[0] - out[1]) < 0.01, "edges outside the fine arc %.4f deg off, equal %.4f",
          out[0], out[1]);
    /* bins and fraction no worse than the equal ring's beyond 0.005 (the
     * battery's fraction bound; measured 0.0608 / 0.0610 p0, 0.0012 /
     * 0.0010) */
    CHECK(dp[0] <= dp[1] + 0.005, "bins %.4f p0 off, equal %.4f", dp[0], dp[1]);
    CHECK(fabs(g.contact_fraction - x.contact_fraction) < 0.005, "contact fraction %.5f off",
          fabs(g.contact_fraction - x.contact_fraction));
    rd_contact_result_cleanup(&g);
    rd_contact_result_cleanup(&u);
}

/* A graded pair that fails leaves the last equal pair's answer standing
 * (rd_contact_refine.c's fall_back): its finer level's bins, fraction and
 * gaps bit for bit as a run capped at that level, the target reported
 * missed and the note saying why.  The bore (the 50 mm ring, orders 8 and
 * 7: bench_static --ring 0.05,0.002,0.001,6 --random 55 40 10) grades its
 * (320, 640) pair at default settings, and its graded finer level takes
 * more Newton iterations than any level before it (57 when this was
 * written; the same bore drawn by the bench, its amplitudes unrounded, 65
 * against at most 35): a budget of one fewer than that level's stops it
 * alone, and the checks below say so if another level stops first. */
static void test_graded_falls_back(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    p.diameter = 0.05, p.radial_width = 0.002, p.axial_height = 0.001, p.tangential_force = 6;
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    o.bore.n_distortion = 2; /* each capped at 0.2 % of d, as the bench's */
    o.bore.distortion[0] =
        (rd_distortion){8, fmin(9.44928 * bound_of(&p, 8), 0.002 * p.diameter), 70.5586};
    o.bore.distortion[1] =
        (rd_distortion){7, fmin(2.19252 * bound_of(&p, 7), 0.002 * p.diameter), 301.834};
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result g, f, e;
    memset(&f, 0, sizeof f), memset(&e, 0, sizeof e);
    rd_error err;
    rd_error_init(&err);
    int ok = rd_contact_solve(&p, 20, &o, &so, NULL, &g, &err) == RD_OK;
    CHECK(ok, "default solve: %s", err.message);
    if (!ok)
        return;
    printf("graded fall-back bore: %d segments (%d base, x%d on %d arcs), %d Newton iterations "
           "at that level\n",
           g.points, g.grade_base, g.grade_factor, g.grade_arcs, g.stats.iterations);
    CHECK(g.graded && g.grade_base == 640,
          "the case misses its point: not graded from 640 (%d, %d)", g.graded, g.grade_base);
    so.max_iterations = g.stats.iterations - 1;
    ok = rd_contact_solve(&p, 20, &o, &so, NULL, &f, &err) == RD_OK;
    CHECK(ok, "solve with %d iterations a level: %s", so.max_iterations, err.message);
    rd_static_opts_default(&so);
    o.max_segments = 640;
    ok = ok && rd_contact_solve(&p, 20, &o, &so, NULL, &e, &err) == RD_OK;
    CHECK(ok, "solve capped at 640: %s", err.message);
    if (ok) {
        CHECK(f.points == 640 && !f.graded && e.points == 640, "answered at %d (graded %d), %d",
              f.points, f.graded, e.points);
        CHECK(f.accuracy_met == 0 &&
                  strstr(f.accuracy_note, "The local refinement near the bin boundaries failed"),
              "met %d, note: %s", f.accuracy_met, f.accuracy_note);
        CHECK(memcmp(f.bin_pressure, e.bin_pressure, sizeof f.bin_pressure) == 0 &&
                  f.contact_fraction == e.contact_fraction && f.n_gaps == e.n_gaps,
              "not the 640-segment answer: fraction %.6f against %.6f, %d gaps against %d",
              f.contact_fraction, e.contact_fraction, f.n_gaps, e.n_gaps);
    }
    rd_contact_result_cleanup(&g);
    rd_contact_result_cleanup(&f);
    rd_contact_result_cleanup(&e);
}

static void test_accuracy_target(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result c;
    rd_error err;
    rd_error_init(&err);
    /* round bore: no gap at any level, pressure differences of order 1e-3 */
    int rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    CHECK(rc == RD_OK && c.accuracy_met == 1 && c.estimates.pressure <= 0.01 &&
              c.stats.reference_segments == c.stats.segments / 2,
          "round bore: met %d, estimate %g, n %d from %d", c.accuracy_met, c.estimates.pressure,
          c.stats.segments, c.stats.reference_segments);
    /* one patch, the whole ring: under the thin-ring uniform pressure
     * (1.3) the bore's radial force is p0 h r_o per radian, F_t, over the
     * running face's span 2 pi - g / r_o (the closed gap g), 62.753 N; the
     * thick ring departs from it as its mean pressure does from p0
     * (measured -6.9e-5 at the default n = 80, -5.7e-4 converged at n =
     * 1280, the mean pressure -5.2e-4): 1e-3; its force acting in the
     * middle, 180 deg (measured to 2e-7 deg) */
    double span = 2.0 * PI - p.closed_gap / (0.5 * p.diameter);
    CHECK(rc == RD_OK && c.n_patches == 1 &&
              fabs(c.patches[0].force_n / (p.tangential_force * span) - 1.0) < 1e-3 &&
              fabs(c.patches[0].centroid_deg - 180.0) < 1e-3,
          "round bore: %d patches, force %.6g N against F_t (2 pi - g / r_o) = %.6g N, at %.4f deg",
          c.n_patches, c.n_patches ? c.patches[0].force_n : NAN, p.tangential_force * span,
          c.n_patches ? c.patches[0].centroid_deg : NAN);
    rd_contact_result_cleanup(&c);
    /* a target the cap cannot reach: the answer comes with the reason */
    o = bore(&p, 4, 3.0, 0.0);
    o.accuracy = 1e-4;
    o.max_segments = 80;
    rd_error_init(&err);
    rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    /* ... naming the estimates that miss it (at a = 1e-4 all four: the
     * binned pressure's 0.008 p0 against 1e-4 among them) */
    CHECK(rc == RD_OK && c.accuracy_met == 0 && c.stats.segments == 80 &&
              strstr(c.accuracy_note, "/contact/max_segments") != NULL &&
              strstr(c.accuracy_note, "binned pressure") != NULL,
          "unreachable target: met %d at n %d, note '%s'", c.accuracy_met, c.stats.segments,
          c.accuracy_note);
    rd_contact_result_cleanup(&c);
    o.accuracy = 0.9;
    rd_error_init(&err);
    CHECK(rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err) == RD_EINVAL &&
              strcmp(err.path, "/numerics/accuracy") == 0,
          "accuracy 0.9 refused: %s", err.message);
}

/* Largest edge move between a's and b's light gaps, matched in order
 * (their counts must agree), deg; INFINITY if they do not. */
static double gaps_move(const rd_contact_result *a, const rd_contact_result *b)
{
    if (a->n_gaps != b->n_gaps)
        return INFINITY;
    double m = 0.0;
    for (int g = 0; g < a->n_gaps; g++)
        m = fmax(m, fmax(fabs(a->gaps[g].start_deg - b->gaps[g].start_deg),
                         fabs(a->gaps[g].end_deg - b->gaps[g].end_deg)));
    return m;
}

/* The re-solve at 4 x (a, from the default law's solved states) against
 * the same stiffness asked for explicitly (b, from the load path): two
 * starts of one problem, each answer within its estimates of the stiff
 * limit, so they may differ by no more than the two estimates together. */
static void check_starts_agree(const rd_contact_result *a, const rd_contact_result *b)
{
    double dp = bins_apart(a, b);
    const rd_contact_estimates *ea = &a->estimates, *eb = &b->estimates;
    double df = fabs(a->contact_fraction - b->contact_fraction);
    double dg = fabs(a->max_clearance - b->max_clearance), de = gaps_move(a, b);
    printf("  4 x from the states against from the load path (n = %d, %d): bins %.4f p0 (%.4f), "
           "fraction %.5f (%.5f), largest gap %.3g m (%.3g), edges %.3f deg (%.3f)\n",
           a->stats.segments, b->stats.segments, dp, ea->pressure + eb->pressure, df,
           ea->contact_fraction + eb->contact_fraction, dg, ea->max_clearance + eb->max_clearance,
           de, ea->gap_edges_deg + eb->gap_edges_deg);
    CHECK(dp <= ea->pressure + eb->pressure && df <= ea->contact_fraction + eb->contact_fraction &&
              dg <= ea->max_clearance + eb->max_clearance &&
              de <= ea->gap_edges_deg + eb->gap_edges_deg,
          "4 x from the states and from the load path differ beyond their estimates: bins %.4f "
          "p0, fraction %.5f, gap %.3g m, edges %.3f deg",
          dp, df, dg, de);
}

/* The default law's share alone misses the target (order 6 at 10 x the
 * bound, 17 deg: 0.014 p0 of the pressure's 0.018 at n = 160): with the
 * default stiffness the refinement is repeated at 4 x and meets it; with
 * the same stiffness asked for explicitly it is not, and the note says to
 * raise it.  The repeat starts from the default law's solved states (since
 * 0.3.4); 4 x asked for explicitly starts from the load path, and the two
 * agree within their estimates. */
static void test_stiffen(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 6, 10.0, 17.0);
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result c;
    rd_error err;
    rd_error_init(&err);
    double k0 = rd_contact_default_stiffness(&p);
    int rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    CHECK(rc == RD_OK && c.accuracy_met == 1 && fabs(c.stiffness / k0 - 4.0) < 1e-12,
          "default law, deep distortion: %s (met %d, k %g k0)", err.message,
          rc == RD_OK ? c.accuracy_met : -2, rc == RD_OK ? c.stiffness / k0 : 0.0);
    if (rc == RD_OK) {
        rd_contact_result b;
        o.stiffness = 4.0 * k0;
        rd_error_init(&err);
        int rb = rd_contact_solve(&p, 20, &o, &so, NULL, &b, &err);
        CHECK(rb == RD_OK, "4 x asked for: %s", err.message);
        if (rb == RD_OK) {
            check_starts_agree(&c, &b);
            rd_contact_result_cleanup(&b);
        }
        rd_contact_result_cleanup(&c);
    }
    /* the default law asked for explicitly is not stiffened: the
     * refinement goes on past 160 segments (since 0.3.12) and meets the
     * target there; where n cannot double, the note says to raise it */
    o.stiffness = k0;
    rd_error_init(&err);
    rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    printf("explicit default law: n %d, met %d, estimate %.4f (the law's %.4f)\n",
           rc == RD_OK ? c.stats.segments : 0, rc == RD_OK ? c.accuracy_met : -2,
           rc == RD_OK ? c.estimates.pressure : 0.0, rc == RD_OK ? c.law_share : 0.0);
    CHECK(rc == RD_OK && c.accuracy_met == 1 && c.stiffness == k0 && c.stats.segments > 160,
          "explicit default law: %s (met %d at n %d)", err.message,
          rc == RD_OK ? c.accuracy_met : -2, rc == RD_OK ? c.stats.segments : 0);
    if (rc == RD_OK)
        rd_contact_result_cleanup(&c);
    o.max_segments = 160;
    rd_error_init(&err);
    rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    CHECK(rc == RD_OK && c.accuracy_met == 0 && c.stiffness == k0 && c.stats.segments == 160 &&
              strstr(c.accuracy_note, "Raise /contact/stiffness") != NULL &&
              strstr(c.accuracy_note, "binned pressure") != NULL,
          "explicit default law at a cap of 160: %s (met %d, note '%s')", err.message,
          rc == RD_OK ? c.accuracy_met : -2, rc == RD_OK ? c.accuracy_note : "");
    if (rc == RD_OK)
        rd_contact_result_cleanup(&c);
}

/* Shifted meshes (0.3.10, rd_contact_refine.c): order 6 at 3 x the bound,
 * 17 deg, reaches the 1280-segment cap with half the levels' change 0.017
 * p0 (0.020 with the law's share, not met) where the bins are 0.005 p0 off
 * the exact reference.  The pair solved again with its segments shifted by
 * half a segment tells the coarser level's placing error from the finer's:
 * the estimate is within x3 of the true error, its levels' part under the
 * target (the whole, 0.0099, meets it).  At a target the shifted coarser
 * level alone shows out of reach (0.002: without the finer's move 0.0064),
 * the finer is not shifted and d / 2 stands. */
static void test_shifted_meshes(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 6, 3.0, 17.0);
    rd_static_opts so;
    rd_static_opts_default(&so);
    ref_result x;
    if (ref_contact_solve_nl(&p, &o, 2880, 1, 10.0, floor_of(&p), &x) != 0) {
        CHECK(0, "exact reference, order 6 at 3 x, 17 deg");
        return;
    }
    rd_contact_result c;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    CHECK(rc == RD_OK, "order 6 at 3 x, 17 deg: %s", err.message);
    if (rc != RD_OK)
        return;
    double dp = 0;
    for (int b = 0; b < RD_CONTACT_BINS; b++)
        dp = fmax(dp, fabs(c.bin_pressure[b] - x.bin_pressure[b]) / x.p0);
    printf("shifted meshes: n %d, met %d, shifted %d, bins %.4f p0 off, estimate %.4f\n",
           c.stats.segments, c.accuracy_met, c.estimates.pressure_shifted, dp,
           c.estimates.pressure);
    /* measured 0.0050 off against 0.0099 (its levels' part 0.0064, d / 2's
     * 0.0167; with the law's share 0.020); the levels' part is held to
     * 0.008, under the target with room for rounding, and the whole to x3 */
    CHECK(c.stats.segments == 1280 && c.estimates.pressure_shifted == 1 &&
              c.estimates.pressure_levels <= 0.008 && ref_tracks(c.estimates.pressure, dp, 1e-3),
          "n %d, met %d, shifted %d: bins %.4f p0 off, estimate %.4f (levels %.4f)",
          c.stats.segments, c.accuracy_met, c.estimates.pressure_shifted, dp, c.estimates.pressure,
          c.estimates.pressure_levels);
    rd_contact_result_cleanup(&c);
    o.accuracy = 0.002;
    rd_error_init(&err);
    rc = rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err);
    CHECK(rc == RD_OK && c.accuracy_met == 0 && c.estimates.pressure_shifted == 0 &&
              c.estimates.pressure_levels > 0.002,
          "target 0.002: %s (met %d, shifted %d, levels %.4f)", err.message,
          rc == RD_OK ? c.accuracy_met : -2, rc == RD_OK ? c.estimates.pressure_shifted : -1,
          rc == RD_OK ? c.estimates.pressure_levels : 0.0);
    if (rc == RD_OK)
        rd_contact_result_cleanup(&c);
}

/* Ten times the contact stiffness moves each reported quantity by less than
 * its estimate (the penetration p / k is 1e-3 of the gaps here). */
static void test_stiffness(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 4, 3.0, 0.0);
    o.max_segments = 160;
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result a, b;
    rd_error err;
    rd_error_init(&err);
    if (rd_contact_solve(&p, 80, &o, &so, NULL, &a, &err) != RD_OK) {
        CHECK(0, "stiffness k0: %s", err.message);
        return;
    }
    o.stiffness = 10 * rd_contact_default_stiffness(&p);
    if (rd_contact_solve(&p, 80, &o, &so, NULL, &b, &err) != RD_OK) {
        CHECK(0, "stiffness 10 k0: %s", err.message);
        rd_contact_result_cleanup(&a);
        return;
    }
    double dp = bins_apart(&a, &b);
    CHECK(a.stats.segments == b.stats.segments, "same level: %d, %d", a.stats.segments,
          b.stats.segments);
    CHECK(dp <= a.estimates.pressure, "bins move %g p0, estimate %g", dp, a.estimates.pressure);
    CHECK(fabs(a.contact_fraction - b.contact_fraction) <= a.estimates.contact_fraction,
          "contact fraction moves %g, estimate %g", fabs(a.contact_fraction - b.contact_fraction),
          a.estimates.contact_fraction);
    CHECK(fabs(a.max_clearance - b.max_clearance) <= a.estimates.max_clearance,
          "largest gap moves %g m, estimate %g", fabs(a.max_clearance - b.max_clearance),
          a.estimates.max_clearance);
    rd_contact_result_cleanup(&a);
    rd_contact_result_cleanup(&b);
    /* a stiff law in a deep distortion: the coarse levels of rigid faces do
     * not converge (order 2 at 2.8 x the bound, 17 deg, 10 x k0: n = 20 and
     * 40 stall), the refinement starts from the first pair that does */
    o = bore(&p, 2, 2.8, 17.0);
    o.stiffness = 10 * rd_contact_default_stiffness(&p);
    rd_error_init(&err);
    int rc = rd_contact_solve(&p, 20, &o, &so, NULL, &a, &err);
    CHECK(rc == RD_OK && a.stats.segments >= 160 && a.n_gaps == 3,
          "stiff law, deep distortion from n = 20: %s (n %d, %d gaps)", err.message,
          rc == RD_OK ? a.stats.segments : 0, rc == RD_OK ? a.n_gaps : 0);
    if (rc == RD_OK)
        rd_contact_result_cleanup(&a);
    /* the same bore at 0 deg: n = 20 of rigid faces converges (after 1143
     * Newton iterations), n = 40 does not; the answer stayed at n = 20, its
     * first gap ending 10 deg short of the default law's 93.9 deg, until a
     * failed level below 80 segments handed over to the pair (80, 160) */
    o = bore(&p, 2, 2.8, 0.0);
    o.stiffness = 10 * rd_contact_default_stiffness(&p);
    o.max_segments = 160;
    rd_error_init(&err);
    rc = rd_contact_solve(&p, 20, &o, &so, NULL, &a, &err);
    CHECK(rc == RD_OK && a.stats.segments == 160 && a.n_gaps == 3 &&
              fabs(a.gaps[0].end_deg - 93.9) < 1.0,
          "stiff law at 0 deg from n = 20: %s (n %d, first gap ends at %.2f deg)", err.message,
          rc == RD_OK ? a.stats.segments : 0, rc == RD_OK && a.n_gaps ? a.gaps[0].end_deg : 0.0);
    if (rc == RD_OK)
        rd_contact_result_cleanup(&a);
    /* ... and with a cap the first such pair would pass (120): the last
     * good level stands and says why */
    o.max_segments = 120;
    rd_error_init(&err);
    rc = rd_contact_solve(&p, 20, &o, &so, NULL, &a, &err);
    CHECK(rc == RD_OK && a.stats.segments <= 120 && a.accuracy_met == 0,
          "stiff law, cap 120: %s (n %d)", err.message, rc == RD_OK ? a.stats.segments : 0);
    if (rc == RD_OK)
        rd_contact_result_cleanup(&a);
}

/* The contact law's share of the pressure estimate (the reported level
 * solved again at twice the stiffness from its own state and multipliers)
 * against the same two solves made apart, each from the whole load path:
 * twice the largest bin move between k0 and 2 k0.  Order 3 at 3 x, 17 deg,
 * where the law matters (patches a few segments wide). */
static void test_law_share(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 3, 3.0, 17.0);
    o.max_segments = 160;
    rd_static_opts so;
    rd_static_opts_default(&so);
    rd_contact_result c, a, b;
    rd_error err;
    rd_error_init(&err);
    if (rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err) != RD_OK) {
        CHECK(0, "law share: %s", err.message);
        return;
    }
    so.estimate_error = 0;
    int n = c.stats.segments;
    int ra = rd_contact_solve(&p, n, &o, &so, NULL, &a, &err);
    o.stiffness = 2.0 * c.stiffness;
    int rb = ra == RD_OK ? rd_contact_solve(&p, n, &o, &so, NULL, &b, &err) : ra;
    if (rb != RD_OK) {
        CHECK(0, "law share, the solves apart: %s", err.message);
        if (ra == RD_OK)
            rd_contact_result_cleanup(&a);
        rd_contact_result_cleanup(&c);
        return;
    }
    double dp = 0.0;
    for (int k = 0; k < RD_CONTACT_BINS; k++)
        dp = fmax(dp, fabs(a.bin_pressure[k] - b.bin_pressure[k]));
    double apart = 2.0 * dp / c.uniform_pressure;
    printf("law share at n = %d: %.4f p0 (the solves apart: %.4f), of the estimate %.4f\n", n,
           c.law_share, apart, c.estimates.pressure);
    /* the two stiff solves stop their multipliers' updates at different
     * states (from the solved one or from the load path), each within the
     * updates' 0.02 p0 test since their Anderson mixing (0.1 p0, plain,
     * before: 0.0851 against 0.0913 apart); measured 0.0825 both, to four
     * digits: 5 % plus 0.002 p0 (a tenth of the updates' test) of room */
    CHECK(fabs(c.law_share - apart) <= 0.05 * apart + 2e-3 && c.law_share > 0.0 &&
              c.law_share <= c.estimates.pressure,
          "law share %.4f p0 against %.4f apart", c.law_share, apart);
    rd_contact_result_cleanup(&a);
    rd_contact_result_cleanup(&b);
    rd_contact_result_cleanup(&c);
}

/* rd_contact_segment_jacobian against central differences of
 * rd_contact_segment_load, on a 40-segment ring in a 3rd-order bore at the
 * full load, its segments moved by up to 3 eps radially (each point on the
 * law's curved part or past it) and turned by up to 2e-8 rad. */
static void test_jacobian(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts o = bore(&p, 3, 1.0, 17.0);
    rd_error err;
    rd_error_init(&err);
    int n = 40, m = 5;
    rd_ring *ring = rd_ring_create(&p, n, 0, &err);
    rd_static_problem pb;
    CHECK(ring && rd_static_problem_init(&pb, ring, &rd_contact_static_loads) == RD_OK, "problem");
    double phi = rd_ring_segment_phi(ring);
    pb.co = &o, pb.m = m, pb.r_o = pb.R + 0.5 * pb.b, pb.bore_dr = 0.5 * p.diameter - pb.r_o;
    double area[40];
    for (int i = 0; i < n; i++)
        area[i] = pb.h * pb.r_o * phi / m;
    pb.area = area, pb.area_max = area[0];
    pb.p0 = 2 * p.tangential_force / (p.diameter * p.axial_height);
    pb.k = rd_contact_default_stiffness(&p), pb.eps = 0.05 * pb.p0 / pb.k, pb.lambda = 1.0;
    /* bore_at's cos, sin of k phi_k (contact_setup's) */
    pb.bore_phase[0] = cos(3 * 17.0 * PI / 180), pb.bore_phase[1] = sin(3 * 17.0 * PI / 180);
    double cp[3 * 40 * 5], mult[40], res[6 * 40] = {0};
    rd_contact_eval pe[40 * 5];
    pb.cp = cp, pb.mult = mult, pb.pe = pe;
    double worst = 0.0;
    for (int i = 0; i < n; i++) {
        const double *P = rd_ring_reference_point(ring, i);
        for (int k = 0; k < m; k++) {
            double a = rd_ring_get_segment_angle(ring, i) + (k + 0.5 - 0.5 * m) * phi / m;
            cp[3 * (m * i + k)] = pb.r_o * cos(a) - P[0];
            cp[3 * (m * i + k) + 1] = pb.r_o * sin(a) - P[1];
            cp[3 * (m * i + k) + 2] = 0.0;
        }
        mult[i] = (i % 3) * 0.5 * pb.p0;
        /* on the bore (its radius at the segment's angle), then moved */
        double a = rd_ring_get_segment_angle(ring, i), A = o.bore.distortion[0].amplitude;
        double dr = A * cos(3 * (a - 17 * PI / 180)) + 3 * pb.eps * sin(7.0 * i);
        double *x = pb.x + 3 * i, *Q = pb.Q + 9 * i, w = 2e-8 * cos(5.0 * i);
        x[0] += dr * cos(a), x[1] += dr * sin(a);
        double R[9] = {cos(w), -sin(w), 0, sin(w), cos(w), 0, 0, 0, 1}, Q0[9];
        memcpy(Q0, Q, sizeof Q0);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                Q[3 * r + c] =
                    R[3 * r] * Q0[c] + R[3 * r + 1] * Q0[3 + c] + R[3 * r + 2] * Q0[6 + c];
        double J[36], scale = 0.0;
        rd_contact_loads(&pb, res); /* the points at this state, for the derivative */
        rd_contact_segment_jacobian(&pb, i, J);
        double Jd[36];
        for (int d = 0; d < 6; d++) {
            /* steps well inside the law's bend (eps) and its turn equivalent */
            double h = d < 3 ? 0.01 * pb.eps : 0.01 * pb.eps / pb.r_o, fp[6] = {0}, fm[6] = {0};
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double xs[3] = {x[0], x[1], x[2]}, Qs[9], W[9] = {0}, *f = sgn > 0 ? fp : fm;
                if (d < 3)
                    xs[d] += sgn * h;
                int a0 = (d - 3 + 1) % 3, a1 = (d - 3 + 2) % 3;
                if (d >= 3) { /* I + [w]x + [w]x^2 / 2, w = sgn h e_(d-3) */
                    W[3 * a1 + a0] = sgn * h, W[3 * a0 + a1] = -sgn * h;
                }
                for (int r = 0; r < 3; r++)
                    for (int c = 0; c < 3; c++) {
                        double v = Q[3 * r + c];
                        for (int q = 0; q < 3; q++)
                            v += (W[3 * r + q] + 0.5 * (d >= 3 ? W[3 * r + a0] * W[3 * a0 + q] +
                                                                     W[3 * r + a1] * W[3 * a1 + q]
                                                               : 0.0)) *
                                 Q[3 * q + c];
                        Qs[3 * r + c] = v;
                    }
                rd_contact_segment_load(&pb, i, xs, Qs, f);
            }
            for (int r = 0; r < 6; r++)
                Jd[r + 6 * d] = (fp[r] - fm[r]) / (2 * h);
        }
        for (int q = 0; q < 36; q++)
            scale = fmax(scale, fabs(Jd[q]) * (q % 6 < 3 ? 1.0 : 1.0 / pb.r_o) *
                                    (q / 6 < 3 ? 1.0 : 1.0 / pb.r_o));
        for (int q = 0; q < 36; q++)
            worst = fmax(worst, fabs(J[q] - Jd[q]) * (q % 6 < 3 ? 1.0 : 1.0 / pb.r_o) *
                                    (q / 6 < 3 ? 1.0 : 1.0 / pb.r_o) / fmax(scale, 1e-300));
    }
    /* the closed form leaves out the bore normal's turn, p / (k r_o) ~ 1e-7
     * of the law's stiffness; the differences' own error at steps of eps /
     * 100 is ~1e-4 of it (the law's curvature over eps); measured 5e-5, and
     * a 1 % error in the law's slope shows as 1e-2 */
    CHECK(worst < 1e-3, "contact load's derivative vs central differences: %.2e of the largest",
          worst);
    pb.cp = NULL, pb.mult = NULL, pb.pe = NULL;
    rd_static_problem_cleanup(&pb);
    rd_ring_free(ring);
}

/* rd_contact_bins: a segment beside a gap edge puts its force on the part
 * of its arc that touches.  Segment [89.5, 91.5] deg, its force spread over
 * its arc (centroid in the middle), a light gap from 80 to 89.8 deg: 0.2 of
 * its 1.7 touching degrees lie in bin 8 (80-90), 1.5 in bin 9.  A run no
 * deeper than twice the floor may be contact: then the whole arc, 0.5 of 2
 * degrees in bin 8. */
static void test_bins_touching(void)
{
    double lo[3] = {87.5, 89.5, 91.5}, force[2] = {0.0, 3.0}, at[2] = {88.5, 90.5};
    const double deg = M_PI / 180.0;
    for (int deep = 0; deep < 2; deep++) {
        rd_contact_result r;
        memset(&r, 0, sizeof r);
        r.gap_floor = 1e-9;
        r.n_gaps = 1;
        r.gaps[0] = (rd_contact_gap){80.0, 89.8, deep ? 1e-6 : 1.5e-9, 85.0};
        rd_contact_bins(lo, force, at, 2, 1.0, &r, &r);
        /* bin 8 holds 2.5 deg of the ring's arc (87.5-90), bin 9 1.5 deg */
        double in8 = deep ? 0.2 / 1.7 : 0.5 / 2.0;
        CHECK_REL(r.bin_pressure[8], 3.0 * in8 / (2.5 * deg), 1e-12, "bin 8 (deep %d)", deep);
        CHECK_REL(r.bin_pressure[9], 3.0 * (1.0 - in8) / (1.5 * deg), 1e-12, "bin 9 (deep %d)",
                  deep);
    }
}

/* Bores, on the default ring and on two others (bench_static --ring
 * D,B,H,FT), whose estimates once met the target far from the error: the
 * first from the 50 mm ring's battery, the rest from random bores
 * (bench/contact_random.sh; bench_static --bins K A PHASE runs one again).
 * Against the exact reference: each estimate (bins, edges, tip forces) at
 * least a third of its error (and, with `both`, the bins' at most three
 * times it or both under 1e-3 p0), and a bore outside the bins' or the
 * edges' target not reported as met.  Several of these references are
 * themselves unsettled at 2880 cells (a point-like contact across a bin
 * boundary), which loosens the x3 checks but not the "not met" ones. */
/* A miss from a bin boundary's share says it is a bound (since 0.3.6),
 * the whole sentence kept within the note; counted into *notes. */
static void check_bound_note(const rd_contact_result *c, const char *why, int *notes)
{
    int boundary = c->estimates.pressure_source == RD_EST_EDGE ||
                   c->estimates.pressure_source == RD_EST_EDGE_SEGMENT ||
                   c->estimates.pressure_source == RD_EST_PATCH;
    if (boundary && strstr(c->accuracy_note, "of p0 (at most") != NULL) {
        ++*notes;
        CHECK(strstr(c->accuracy_note, "the bins may still be right)") != NULL,
              "%s: the note does not say the estimate is a bound: %s", why, c->accuracy_note);
    }
}

static void test_other_ring(void)
{
    int bound_notes = 0;
    static const struct {
        double d, b, h, ft;
        int k;
        double fac, phase;
        int both;
        const char *why;
        double est_below; /* the pressure's estimate stays under it (0: not checked) */
        int cells;        /* the reference's (0: 2880) */
    } cases[] = {
        /* an edge 0.007 deg short of the 60 deg boundary, 0.014 deg from the
         * reference's, beside 8.4 p0 rising into the patch: met with 0.008
         * where 0.031 p0 was off (edge_share's distributed term) */
        {0.05, 0.002, 0.001, 6, 4, 3.0, 17.0, 0, "edge beside a rising pressure", 0, 0},
        /* a patch on 39.98-40.88 deg at n = 160 put none of its force below
         * 40 deg, the reference a tenth: met with 0.009 where 0.51 p0 was
         * off (straddle_share) */
        {0.05, 0.002, 0.001, 6, 7, 9.70363, 117.806, 0, "patch across a boundary", 0, 0},
        /* a patch's end 0.13 deg past 270 deg binned from the segments'
         * closest points, 0.2 deg short of it: met at n = 640 with 0.0004
         * where 0.11 p0 was off (wide_patch_edges, rd_contact.c) */
        {0.05, 0.002, 0.001, 6, 4, 2.27805, 305.785, 1, "patch end past a boundary", 0, 0},
        /* a point-like patch on 319.29-319.96 deg at n = 160 beside 320
         * deg, the reference's across it: met with 0.007 where 0.9 p0 was
         * off (straddle_share with B outside; wide_patch_edges at 1.5 segments
         * bins the patch's 1.49 p0 past 320 deg at n = 1280, the reference
         * on 5760 and 11520 cells 1.56, on 2880 cells 0.93: against 5760,
         * whose bins are 0.001 p0 from 11520's; graded since 0.3.7, 640
         * base segments four times finer by 320 deg: 1.19, estimate 1.33,
         * not met) */
        {0.05, 0.002, 0.001, 6, 3, 5.69085, 144.595, 0, "patch beside a boundary", 0, 5760},
        /* a patch on 309.78-310.45 deg at n = 160, less than a segment
         * wide, across 310 deg: binned all past 310 where the reference
         * puts 58 % before it, and levels 80 and 160 agreed: met with 0.007
         * where 5.1 p0 was off (straddle_share: B inside an unresolved patch) */
        {0.05, 0.002, 0.001, 6, 4, 8.7604, 352.54, 0, "unresolved patch across a boundary", 0, 0},
        /* a point-like patch on 330.13-331.02 deg at n = 160 (0.4 segments),
         * the reference's on 329.96-331.21 around the same middle: met with
         * 0.008 where 0.085 p0 lay across 330 deg, the patch's middle alone
         * taken as uncertain (straddle_share with B outside: its near edge
         * too, since 0.3.11) */
        {0.05, 0.002, 0.001, 6, 6, 7.17111, 58.7121, 0, "point-like patch beside a boundary", 0, 0},
        /* a patch ending 0.11 deg short of 80 deg, the reference's 0.11
         * past: the edge's share must hold at n = 160 (a rule that let a
         * patch two segments wide off it met the target with 0.003 where
         * 0.42 p0 was off) */
        {0.0765, 0.0029, 0.0012, 10, 2, 2.83031, 342.015, 0, "patch end short of a boundary", 0, 0},
        /* a patch ending at 270.28 deg (the reference's 270.34) whose
         * segment's force was spread from 269.9 deg: met at n = 640 with
         * 0.010 where 0.055 p0 was off (edge_bin_share) */
        {0.0765, 0.0029, 0.0012, 10, 2, 1.30134, 346.801, 0, "edge segment across a boundary", 0,
         0},
        /* a patch on 99.86-100.48 deg at n = 640, 1.1 segments wide, binned
         * all past 100 deg where the reference puts 14 % before it: met
         * with 0.001 where 1.03 p0 was off (straddle_share up to the 1.5
         * segments wide_patch_edges bins by the closest points) */
        {0.13, 0.0045, 0.003, 40, 5, 6.40487, 352.294, 0, "patch of 1.1 segments across 100 deg", 0,
         0},
        /* n = 160 pressed its first end's tip (17.3 N) where the reference
         * is 0.35 um clear to 2.23 deg: levels 80 and 160 agreed, and the
         * edges 2.1 deg off met the target (unresolved_tips) */
        {0.13, 0.0045, 0.003, 40, 6, 9.44982, 208.024, 0, "tip pressed, lifted in truth", 0, 0},
        /* a heavy 0.55 deg patch (12.4 p0 of its bin) ending 0.07 deg short
         * of 320 deg at n = 1280, its end moved 0.17 deg from 640, the
         * reference's bins within 0.0004 p0: the edge's share takes half
         * the move, 0.76 p0 (the whole move, before 0.3.6: 3.5; bench_static
         * --random 52 40, bore 39).  Still not met: the edge could cross.
         * (Graded to 0.035 deg, as a variant grading from n = 320 did,
         * ringdyn's end settles at 320.04 deg, 0.52 p0 past 320, where the
         * reference's, on cells of 0.125 deg, is at 319.993: its bins
         * could not have judged that split) */
        {0.0765, 0.0029, 0.0012, 10, 2, 2.83031, 254.83, 0, "heavy patch end short of a boundary",
         1.5, 0},
    };
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        rd_ring_params p;
        rd_ring_params_default(&p);
        p.diameter = cases[t].d, p.radial_width = cases[t].b, p.axial_height = cases[t].h;
        p.tangential_force = cases[t].ft;
        rd_contact_opts o = bore(&p, cases[t].k, cases[t].fac, cases[t].phase);
        rd_static_opts so;
        rd_static_opts_default(&so);
        ref_result x;
        rd_contact_result c;
        rd_error err;
        rd_error_init(&err);
        int cells = cases[t].cells ? cases[t].cells : 2880;
        if (ref_contact_solve_nl(&p, &o, cells, 1, 10.0, floor_of(&p), &x) != 0) {
            CHECK(0, "%s: exact reference", cases[t].why);
            continue;
        }
        if (rd_contact_solve(&p, 20, &o, &so, NULL, &c, &err) != RD_OK) {
            CHECK(0, "%s: %s", cases[t].why, err.message);
            continue;
        }
        double dp = 0;
        for (int b = 0; b < RD_CONTACT_BINS; b++)
            dp = fmax(dp, fabs(c.bin_pressure[b] - x.bin_pressure[b]) / x.p0);
        double est = c.estimates.pressure;
        printf("ring %g mm, %s (order %d at %g x, %g deg): n %d, bins %.4f p0 off (est. "
               "%.4f), met %d\n",
               1e3 * cases[t].d, cases[t].why, cases[t].k, cases[t].fac, cases[t].phase,
               c.stats.segments, dp, est, c.accuracy_met);
        /* x3: the tracking bound */
        CHECK(dp <= 3 * est, "%s: bins %.4f p0 off, estimate %.4f", cases[t].why, dp, est);
        check_where(&c, &x, dp);
        CHECK(!(cases[t].est_below > 0) || est < cases[t].est_below,
              "%s: bins %.4f p0 off, estimate %.4f (at most %g)", cases[t].why, dp, est,
              cases[t].est_below);
        check_bound_note(&c, cases[t].why, &bound_notes);
        /* and at a cap of 320 segments, where no pair can be graded (from
         * n = 320 on, within the cap): the bin-boundary shares stand */
        rd_contact_result c3;
        o.max_segments = 320;
        if (rd_contact_solve(&p, 20, &o, &so, NULL, &c3, &err) == RD_OK) {
            check_bound_note(&c3, cases[t].why, &bound_notes);
            rd_contact_result_cleanup(&c3);
        } else
            CHECK(0, "%s at 320: %s", cases[t].why, err.message);
        CHECK(!cases[t].both || ref_tracks(est, dp, 1e-3), "%s: estimate %.4f against %.4f off",
              cases[t].why, est, dp);
        CHECK(dp <= c.accuracy || c.accuracy_met == 0,
              "%s: bins %.4f p0 off, over the target %g, reported as met", cases[t].why, dp,
              c.accuracy);
        /* and the edges and tip forces: within x3 of their estimates, and
         * no bore with an edge past the 1 deg reported as met */
        double de = ref_edge_error(&c, &x), dtip = 0;
        for (int e = 0; e < 2; e++)
            dtip = fmax(dtip, fabs(c.tip_force[e] - x.tip_force[e]));
        CHECK(!(de > 3 * c.estimates.gap_edges_deg), "%s: edges %.3f deg off, estimate %.3f",
              cases[t].why, de, c.estimates.gap_edges_deg);
        CHECK(!(de > 1.0) || c.accuracy_met == 0, "%s: edges %.3f deg off, reported as met",
              cases[t].why, de);
        /* + 0.01 N: the tracking floor bench_static --battery counts tip
         * forces with (both under 0.01 N), a tip touching by a hair */
        CHECK(dtip <= 3 * c.estimates.tip_forces_n + 0.01,
              "%s: tip forces %.3f N off, estimate %.3f", cases[t].why, dtip,
              c.estimates.tip_forces_n);
        rd_contact_result_cleanup(&c);
    }
    /* measured 2 (the heavy patch's edge, and the rising pressure's edge
     * segment by 60 deg on the 50 mm ring) before 0.3.7 graded such bores;
     * at the cap of 320, where none can be graded, 9 (0.3.7): the check
     * above ran */
    printf("bin-boundary misses with a note: %d\n", bound_notes);
    CHECK(bound_notes >= 2, "bin-boundary misses with a note: %d", bound_notes);
}

int main(void)
{
    test_bins_touching();
    test_jacobian();
    test_reference();
    test_accuracy_target();
    test_uzawa();
    test_inexact_updates();
    test_warm_multipliers();
    test_full_steps();
    test_graded();
    test_graded_falls_back();
    test_stiffness();
    test_stiffen();
    test_shifted_meshes();
    test_law_share();
    test_battery();
    test_battery_exact();
    test_other_ring();
    return check_done();
}
