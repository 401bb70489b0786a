/*
 * bench_static — accuracy and cost of the pretension and contact analyses.
 *
 *   bench_static            tables: (1) pretension x_a vs n: wall time
 *       (median of repeats), Newton iterations, true error vs the n -> infinity
 *       limit and the solver's own estimate; (2) contact in a round bore:
 *       mean pressure error vs 2 F_t / (d h), wall time; (3) contact points
 *       per segment at n = 40 (round and 4th-order distorted bore): wall time
 *       and the change of the pressure profile vs 20 points; fitted cost
 *       exponents (t ~ n^p over n >= 80).
 *   bench_static --once N   one contact solve at N segments (callgrind).
 *   bench_static --bins K A PHASE [N [S]]  one battery bore (order K, A x
 *       the thin-ring bound, PHASE deg) bin by bin against the reference, at
 *       default settings or at N segments (0: default), F_t scaled by S.
 *   bench_static --stiffness  the battery below at 10 x the default contact
 *       stiffness: how far each quantity moves, against its estimate at the
 *       default stiffness, and against both answers' estimates together;
 *       and 10 x solved once at the default answer's n, against its
 *       estimate (the law's own move, without another n's).
 *   bench_static --battery  contact in distorted bores (orders 2, 3, 4, 6;
 *       0.1, 1, 3, 10 x the thin-ring bound, capped at 0.4 % of the
 *       diameter, order 2 at 10 x left out as the 3 x bore again: 30 bores;
 *       phases 0 and 17 deg) at default settings against an
 *       independent reference (--ref-cells, default 2880, and half as many
 *       for its own bin uncertainty; --reference nl, the default:
 *       tests/core/contact_reference_nl.c, geometrically exact, F_t
 *       following the end faces as in ringdyn; nl-dead: F_t of fixed
 *       direction; linear: tests/core/contact_reference.c; also for --bins):
 *       true errors, the solver's estimates, wall and CPU time (median of
 *       3; the CPU time of this one-threaded process is what the solve
 *       costs on a free core when the machine is shared); last, the
 *       reference's CPU time a bore and its active-set passes (range).
 *   bench_static --dump  every battery bore: the reference (2880, 1440
 *       cells) and fixed n = 40 ... 1280 without refinement, one JSON line a
 *       bore (bins, fraction, gaps, per-segment pressure, and the fraction,
 *       largest gap and gaps at twice the stiffness: cf2, gmax2, gaps2,
 *       cf2 null where that solve fails; for the estimates).
 *   --rigid (with --battery, --bins, --stiffness, --dump): rigid running
 *       faces (rd_contact_opts.flexible_face = 0) instead of the default
 *       flexible ones (--face, the flexible ones, is accepted and changes
 *       nothing).
 *   bench_static --random SEED N  N random bores (one or two orders 2-8,
 *       0.1-10 x their bounds, any phase) at default settings against the
 *       exact reference: the targets, the bores reporting the target met
 *       while outside one, CPU, and the estimates against the true errors
 *       counted as the battery's (the battery's out-of-sample check).
 *   bench_static --random SEED N I  the same set's bore I (1..N) alone,
 *       then its bins against the reference's as --bins prints them.
 *   --kx F (with the same): the contact stiffness F times its default.
 *   --single (with --random): one order a bore, 2 to 6 (the issue's
 *       battery's orders; 0.1-10 x the bound, any phase, as above).
 *   --accuracy A (with --battery, --bins, --random): rd_contact_opts.accuracy
 *       (the default 0.01); the counts' targets stay the issue's.
 *   --ring D,B,H,FT (with the same): another ring (diameter, radial width,
 *       axial height in m, tangential force in N; the rest the default's).
 *   --cap N (with --battery, --bins, --stiffness): rd_contact_opts.max_segments
 *       N instead of its default.
 *   --exact-updates (with any): every contact multiplier update solved to the
 *       full tolerance (rd_static_opts.update_eta = 0; 0.3.13 and before).
 *   --settled (with --battery): where the reference's bins move more than
 *       0.02 p0 between half its cells and its cells, the bins also against
 *       the reference on 4 x its cells (minutes: 11520 cells).
 *
 * The x_a limit is the Richardson extrapolation from n = 2000 and 1000
 * (order 2, checked in tests/core/test_static.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"

#include "contact_reference.h"
#include "rd_static.h"

/* The reference the battery and --bins compare with: REF_NL, the
 * geometrically exact beam (F_t following the end sections, as ringdyn),
 * REF_NL_DEAD (F_t fixed in direction), REF_LINEAR (contact_reference.c). */
enum { REF_NL, REF_NL_DEAD, REF_LINEAR };
static int reference_kind = REF_NL;
static int reference_cells = 2880;
static int settle_refs; /* --settled */

/* --rigid anywhere: the contact solves with rigid faces
 * (rd_contact_opts.flexible_face = 0) instead of the default flexible ones
 * (core/rd_contact_face.c). */
static int rigid_face = 0;

/* --cap N anywhere: rd_contact_opts.max_segments (0: its default). */
static int cap = 0;

/* --kx F anywhere: the contact stiffness F times its default (0: default). */
static double stiffness_times = 0;

/* --accuracy A anywhere: rd_contact_opts.accuracy (0: its default, 0.01). */
static double accuracy_opt = 0;

/* --exact-updates anywhere: every multiplier update's Newton solve to the
 * full tolerance (rd_static_opts.update_eta = 0, 0.3.13's way). */
static int exact_updates = 0;

/* The static solver's defaults with --exact-updates applied. */
static void static_opts(rd_static_opts *so)
{
    rd_static_opts_default(so);
    if (exact_updates)
        so->update_eta = 0.0;
}

/* --single anywhere (with --random): one order a bore, 2 to 6, as the
 * issue's battery (orders 2-6, 0.1-10 x the bound, several phases). */
static int single_order = 0;

static int reference_solve(const rd_ring_params *p, const rd_contact_opts *o, double floor_m,
                           ref_result *r)
{
    if (reference_kind == REF_LINEAR)
        return ref_contact_solve(p, o, reference_cells, RD_CONTACT_BIN_DEG, floor_m, r);
    return ref_contact_solve_nl(p, o, reference_cells, reference_kind == REF_NL, RD_CONTACT_BIN_DEG,
                                floor_m, r);
}

static void die(const char *what, const rd_error *err)
{
    fprintf(stderr, "%s: %s\n", what, err->message);
    exit(1);
}

/* Median wall time of repeated pretension solves; the last result kept. */
static double time_pretension(const rd_ring_params *p, int n, int estimate,
                              rd_pretension_result *keep)
{
    double t[64];
    int reps = 0;
    double start = bench_now();
    while (reps < 64 && (reps < 5 || bench_now() - start < 0.3)) {
        rd_pretension_opts o;
        rd_pretension_opts_default(&o);
        rd_static_opts so;
        static_opts(&so);
        so.estimate_error = estimate;
        rd_error err;
        rd_error_init(&err);
        rd_pretension_result_cleanup(keep);
        double t0 = bench_now();
        if (rd_pretension_solve(p, n, &o, &so, NULL, keep, &err))
            die("pretension", &err);
        t[reps++] = bench_now() - t0;
    }
    return bench_median(t, reps);
}

static double time_contact(const rd_ring_params *p, int n, const rd_contact_opts *o,
                           rd_contact_result *keep)
{
    double t[64];
    int reps = 0;
    double start = bench_now();
    while (reps < 64 && (reps < 5 || bench_now() - start < 0.3)) {
        rd_static_opts so;
        static_opts(&so);
        so.estimate_error = 0;
        rd_error err;
        rd_error_init(&err);
        rd_contact_result_cleanup(keep);
        double t0 = bench_now();
        if (rd_contact_solve(p, n, o, &so, NULL, keep, &err))
            die("contact", &err);
        t[reps++] = bench_now() - t0;
    }
    return bench_median(t, reps);
}

static double profile_change(const rd_contact_result *a, const rd_contact_result *b, double p0)
{
    double worst = 0;
    for (int i = 0; i < a->points; i++)
        worst = fmax(worst, fabs(a->pressure[i] - b->pressure[i]) / p0);
    return worst;
}

/* The thin-ring conformability bound of order k, F_t R^3 / (E I (k^2 - 1)^2)
 * (the battery's amplitude unit). */
static double thin_ring_bound(const rd_ring_params *p, int k)
{
    rd_ring_section sec;
    rd_ring_section_get(p, 0, &sec);
    return p->tangential_force * pow(sec.R, 3) /
           (p->youngs_modulus * sec.I_inplane * pow(k * k - 1.0, 2));
}

/* A battery bore: order k, fac times the thin-ring bound (capped at 0.4 %
 * of the diameter), phase deg; the run's face and cap options.  *A_bound,
 * if not NULL, receives the amplitude over the bound. */
static rd_contact_opts battery_bore(const rd_ring_params *p, int k, double fac, double phase,
                                    double *A_bound)
{
    rd_contact_opts o = ref_battery_bore(p, k, fac, phase);
    if (rigid_face)
        o.flexible_face = 0;
    if (stiffness_times > 0)
        o.stiffness = stiffness_times * rd_contact_default_stiffness(p);
    if (cap)
        o.max_segments = cap;
    if (accuracy_opt > 0)
        o.accuracy = accuracy_opt;
    if (A_bound)
        *A_bound = o.bore.distortion[0].amplitude / thin_ring_bound(p, k);
    return o;
}

/* A tracking miss (ref_tracks false) of estimate est against error err:
 * understated beyond x3 (into *under) or overstated (over[0]; over[1] too
 * when est is under a tenth of the target, `tenth`: an overstatement that
 * cannot turn a met target into a miss). */
static void miss_kind(double est, double err, double floor, double tenth, int *under, int over[2])
{
    if (ref_tracks(est, err, floor))
        return;
    if (err > 3.0 * est)
        ++*under;
    else {
        over[0]++;
        over[1] += est < tenth;
    }
}

/* Where the reference's bins do not settle between half its cells and its
 * cells (a narrow patch beside a bin boundary), c's bins' error against the
 * reference on 4 x its cells, p0 (NAN if that solve fails; its Newton
 * tolerance grows with the cells, contact_reference_nl.c). */
static double bins_vs_finer(const rd_ring_params *p, const rd_contact_opts *o, double floor_m,
                            const rd_contact_result *c, double p0)
{
    ref_result rf;
    int cells = reference_cells;
    reference_cells *= 4;
    int rc = reference_solve(p, o, floor_m, &rf);
    reference_cells = cells;
    if (rc != 0)
        return NAN;
    double d = 0.0;
    for (int b = 0; b < RD_CONTACT_BINS; b++)
        d = fmax(d, fabs(c->bin_pressure[b] - rf.bin_pressure[b]) / p0);
    return d;
}

static void battery(const rd_ring_params *p)
{
    const int orders[] = {2, 3, 4, 6};
    const double facs[] = {0.1, 1, 3, 10}, phases[] = {0, 17};
    double p0 = 2 * p->tangential_force / (p->diameter * p->axial_height);
    double floor_m = rd_contact_gap_floor(p);
    int total = 0, ok[4] = {0}, track[5] = {0}, fast = 0, settled = 0, settled_ok = 0,
        ref_passes[2] = {1 << 30, 0}, its[3] = {1 << 30, 0, 0};
    double ref_cpu[2] = {INFINITY, 0}, tip_worst = 0, patch_worst = 0;
    int tip_ok = 0, under[4] = {0}, over[4][2] = {{0}}, patch_ok = 0, patch_track = 0,
        patch_under = 0, patches = 0, unsettled = 0, unsettled_ok = 0, unsettled_failed = 0;
    double unsettled_worst = 0.0;
    printf("## contact in distorted bores, default settings, vs the %s curved-beam reference\n\n",
           reference_kind == REF_LINEAR ? "linear"
           : reference_kind == REF_NL   ? "geometrically exact (follower F_t)"
                                        : "geometrically exact (dead F_t)");
    printf("| k | A / bound | phase | n | met | wall (s) | cpu (s) | contact fraction: error "
           "(estimate) "
           "| largest gap: error (estimate) | gap edges, deg | binned pressure / p0 | reference's "
           "own bins / p0 | tip forces: error, N | patches | patch forces: error (estimate), N "
           "|\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int oi = 0; oi < 4; oi++)
        for (int fi = 0; fi < 4; fi++)
            for (int pi = 0; pi < 2; pi++) {
                if (orders[oi] == 2 && facs[fi] == 10)
                    continue; /* capped at 0.4 % of d: the 3 x bore again */
                int k = orders[oi];
                double Ab;
                rd_contact_opts o = battery_bore(p, k, facs[fi], phases[pi], &Ab);
                ref_result r;
                clock_t r0 = clock();
                if (reference_solve(p, &o, floor_m, &r) != 0) {
                    printf("| %d | %.2g | %g | reference failed |\n", k, Ab, phases[pi]);
                    continue;
                }
                double rcpu = (double)(clock() - r0) / CLOCKS_PER_SEC;
                ref_cpu[0] = fmin(ref_cpu[0], rcpu), ref_cpu[1] = fmax(ref_cpu[1], rcpu);
                /* the reference's own bin uncertainty: its bins at half the
                 * cells against these (a point-like contact on a bin boundary
                 * moves whole p0 between bins with its location) */
                ref_result rh;
                int cells = reference_cells;
                reference_cells /= 2;
                double ref_dp = reference_solve(p, &o, floor_m, &rh) == 0 ? 0.0 : NAN;
                reference_cells = cells;
                for (int b = 0; b < RD_CONTACT_BINS; b++)
                    ref_dp = fmax(ref_dp, fabs(rh.bin_pressure[b] - r.bin_pressure[b]) / p0);
                ref_passes[0] = r.iterations < ref_passes[0] ? r.iterations : ref_passes[0];
                ref_passes[1] = r.iterations > ref_passes[1] ? r.iterations : ref_passes[1];
                rd_contact_result c;
                memset(&c, 0, sizeof c);
                double t[3], cpu[3];
                int reps = 0, rc = 0;
                rd_error err;
                while (reps < 3 && rc == 0 && (reps == 0 || t[0] < 2.0)) {
                    rd_static_opts so;
                    static_opts(&so);
                    rd_error_init(&err);
                    rd_contact_result_cleanup(&c);
                    double t0 = bench_now();
                    clock_t c0 = clock();
                    rc = rd_contact_solve(p, 20, &o, &so, NULL, &c, &err);
                    cpu[reps] = (double)(clock() - c0) / CLOCKS_PER_SEC;
                    t[reps++] = bench_now() - t0;
                }
                if (rc != 0) {
                    printf("| %d | %.2g | %g | failed: %s |\n", k, Ab, phases[pi], err.message);
                    continue;
                }
                double wall = bench_median(t, reps), cpu_s = bench_median(cpu, reps), dp = 0;
                for (int b = 0; b < RD_CONTACT_BINS; b++)
                    dp = fmax(dp, fabs(c.bin_pressure[b] - r.bin_pressure[b]) / p0);
                double dcf = fabs(c.contact_fraction - r.contact_fraction);
                double dg = r.max_clearance > 1e-7
                                ? fabs(c.max_clearance - r.max_clearance) / r.max_clearance
                                : NAN;
                double eg = c.max_clearance > 0 ? c.estimates.max_clearance / c.max_clearance : 0.0;
                double de = ref_edge_error(&c, &r), dtip = 0;
                for (int e = 0; e < 2; e++) {
                    dtip = fmax(dtip, fabs(c.tip_force[e] - r.tip_force[e]));
                    tip_worst = fmax(tip_worst, fabs(c.tip_force[e] - r.tip_force[e]) /
                                                    fmax(r.tip_force[e], 0.1));
                    tip_ok += fabs(c.tip_force[e] - r.tip_force[e]) <= 0.02 * r.tip_force[e] + 0.01;
                }
                double prel, dpf = ref_patch_error(&c, &r, &prel);
                patches += r.n_patches;
                patch_worst = fmax(patch_worst, prel);
                patch_ok += prel <= 0.02 || dpf <= 0.01;
                patch_track += ref_tracks(c.estimates.patch_forces_n, dpf, ref_patch_floor(&r));
                patch_under += 3.0 * c.estimates.patch_forces_n < dpf && dpf > ref_patch_floor(&r);
                total++;
                ok[0] += dcf <= 0.02;
                ok[1] += !(dg > 0.05);
                ok[2] += !(de > 1.0);
                ok[3] += dp <= 0.02;
                settled += ref_dp <= 0.02;
                settled_ok += ref_dp <= 0.02 && dp <= 0.02;
                if (settle_refs && !(ref_dp <= 0.02)) {
                    double df = bins_vs_finer(p, &o, floor_m, &c, p0);
                    unsettled++;
                    unsettled_ok += df <= 0.02;
                    unsettled_failed += isnan(df);
                    unsettled_worst = fmax(unsettled_worst, df);
                }
                track[0] += ref_tracks(c.estimates.contact_fraction, dcf, 1e-3);
                track[1] += isnan(dg) || ref_tracks(eg, dg, 1e-3);
                track[2] += isnan(de) || ref_tracks(c.estimates.gap_edges_deg, de, 0.05);
                track[3] += ref_tracks(c.estimates.pressure, dp, 1e-3);
                track[4] += ref_tracks(c.estimates.tip_forces_n, dtip, 0.01);
                miss_kind(c.estimates.contact_fraction, dcf, 1e-3, 0.002, &under[0], over[0]);
                if (!isnan(dg))
                    miss_kind(eg, dg, 1e-3, 0.005, &under[1], over[1]);
                if (!isnan(de))
                    miss_kind(c.estimates.gap_edges_deg, de, 0.05, 0.1, &under[2], over[2]);
                miss_kind(c.estimates.pressure, dp, 1e-3, 0.001, &under[3], over[3]);
                fast += cpu_s <= 0.2;
                its[0] = c.stats.iterations < its[0] ? c.stats.iterations : its[0];
                its[1] = c.stats.iterations > its[1] ? c.stats.iterations : its[1];
                its[2] += c.stats.iterations;
                printf(
                    "| %d | %.2g | %g | %d | %s | %.3f | %.3f | %.4f (%.4f) | %+.1f %% (%.1f %%) | "
                    "%.2f (%.2f) | %.3f (%.3f) | %.3f | %.3f | %d (%d) | %.3f (%.3f) |\n",
                    k, Ab, phases[pi], c.stats.segments, c.accuracy_met ? "yes" : "no", wall, cpu_s,
                    dcf, c.estimates.contact_fraction, 100 * dg, 100 * eg, de,
                    c.estimates.gap_edges_deg, dp, c.estimates.pressure, ref_dp, dtip, c.n_patches,
                    r.n_patches, dpf, c.estimates.patch_forces_n);
                rd_contact_result_cleanup(&c);
            }
    printf("\n%d bores. Within the targets: contact fraction (0.02) %d, largest gap (5 %%) %d, "
           "edges (1 deg) %d, binned pressure (0.02 p0) %d; cpu <= 0.2 s: %d.\n"
           "Estimate within x3 of the true error: contact fraction %d, largest gap %d, edges %d, "
           "pressure %d; tip forces %d (both under 0.01 N: counted).\n",
           total, ok[0], ok[1], ok[2], ok[3], fast, track[0], track[1], track[2], track[3],
           track[4]);
    printf("Of the rest, understated beyond x3: %d, %d, %d, %d; overstated beyond x3: %d, %d, %d, "
           "%d, of them with the estimate under a tenth of the target (0.002, 0.5 %%, 0.1 deg, "
           "0.001 p0): %d, %d, %d, %d.\n",
           under[0], under[1], under[2], under[3], over[0][0], over[1][0], over[2][0], over[3][0],
           over[0][1], over[1][1], over[2][1], over[3][1]);
    printf("Binned pressure where the reference's own bins settle within 0.02 p0 (%d cells "
           "against %d): %d of %d bores within 0.02 p0.\n",
           reference_cells / 2, reference_cells, settled_ok, settled);
    if (unsettled > 0)
        printf("Where they do not (%d bores), against the reference on %d cells: %d within 0.02 "
               "p0 (the worst %.3f p0; %d whose finer reference failed).\n",
               unsettled, 4 * reference_cells, unsettled_ok, unsettled_worst, unsettled_failed);
    printf("Tip forces within 2 %% + 0.01 N of the reference's: %d of %d free ends (worst %.1f %% "
           "of the larger of the reference's and 0.1 N).\n",
           tip_ok, 2 * total, 100 * tip_worst);
    printf("Contact patches (%d in the references): every patch's force within 2 %% or 0.01 N "
           "of the reference's on %d of %d bores (worst %.1f %% of the larger of its force and "
           "0.5 N); the estimate within x3 of the error on %d (both under 0.01 N + 1e-3 of the "
           "largest patch: counted), understated beyond x3 on %d.\n",
           patches, patch_ok, total, 100 * patch_worst, patch_track, patch_under);
    printf("The reference (%d cells): %.3f-%.3f s CPU a bore, %d-%d active-set passes.\n",
           reference_cells, ref_cpu[0], ref_cpu[1], ref_passes[0], ref_passes[1]);
    printf("Newton iterations of the finest level's solve: %d-%d a bore, %d in all.\n", its[0],
           its[1], its[2]);
}

/* The battery at the default stiffness k0 and at 10 k0 (default settings
 * otherwise): how far each reported quantity moves, against its estimate at
 * k0.  Prints the count of bores where every move is within the estimate. */
static void stiffness_battery(const rd_ring_params *p)
{
    const int orders[] = {2, 3, 4, 6};
    const double facs[] = {0.1, 1, 3, 10}, phases[] = {0, 17};
    int total = 0, within[4] = {0}, both[4] = {0}, same[4] = {0}, failed = 0;
    printf(
        "| k | A / bound | phase | fraction move (est) | largest gap move, m (est) | edges move, "
        "deg (est) | bins move / p0 (est) |\n|---|---|---|---|---|---|---|\n");
    for (int oi = 0; oi < 4; oi++)
        for (int fi = 0; fi < 4; fi++)
            for (int pi = 0; pi < 2; pi++) {
                if (orders[oi] == 2 && facs[fi] == 10)
                    continue; /* capped at 0.4 % of d: the 3 x bore again */
                int k = orders[oi];
                rd_contact_opts o = battery_bore(p, k, facs[fi], phases[pi], NULL);
                rd_contact_result a, b;
                rd_static_opts so;
                static_opts(&so);
                rd_error err;
                rd_error_init(&err);
                if (rd_contact_solve(p, 20, &o, &so, NULL, &a, &err) != RD_OK) {
                    failed++;
                    continue;
                }
                o.stiffness = 10 * rd_contact_default_stiffness(p);
                if (rd_contact_solve(p, 20, &o, &so, NULL, &b, &err) != RD_OK) {
                    failed++;
                    rd_contact_result_cleanup(&a);
                    continue;
                }
                double dp = 0, de = 0;
                for (int q = 0; q < RD_CONTACT_BINS; q++)
                    dp = fmax(dp, fabs(a.bin_pressure[q] - b.bin_pressure[q]) / a.uniform_pressure);
                for (int g = 0; g < a.n_gaps && a.n_gaps == b.n_gaps; g++)
                    de = fmax(de, fmax(fabs(a.gaps[g].start_deg - b.gaps[g].start_deg),
                                       fabs(a.gaps[g].end_deg - b.gaps[g].end_deg)));
                if (a.n_gaps != b.n_gaps)
                    de = INFINITY;
                double dcf = fabs(a.contact_fraction - b.contact_fraction);
                double dg = fabs(a.max_clearance - b.max_clearance);
                /* the law's own move: 10 k0 at the n the default answer
                 * reports, one solve (b may have stopped at another n, and
                 * then its move is two discretisation errors too) */
                rd_contact_result c;
                rd_static_opts so1 = so;
                so1.estimate_error = 0;
                if (rd_contact_solve(p, a.stats.segments, &o, &so1, NULL, &c, &err) == RD_OK) {
                    double mp = 0, me = a.n_gaps == c.n_gaps ? 0 : INFINITY;
                    for (int q = 0; q < RD_CONTACT_BINS; q++)
                        mp = fmax(mp,
                                  fabs(a.bin_pressure[q] - c.bin_pressure[q]) / a.uniform_pressure);
                    for (int g = 0; g < a.n_gaps && a.n_gaps == c.n_gaps; g++)
                        me = fmax(me, fmax(fabs(a.gaps[g].start_deg - c.gaps[g].start_deg),
                                           fabs(a.gaps[g].end_deg - c.gaps[g].end_deg)));
                    same[0] += fabs(a.contact_fraction - c.contact_fraction) <=
                               a.estimates.contact_fraction;
                    same[1] +=
                        fabs(a.max_clearance - c.max_clearance) <= a.estimates.max_clearance ||
                        a.max_clearance == 0;
                    same[2] += me <= a.estimates.gap_edges_deg || a.n_gaps == 0;
                    same[3] += mp <= a.estimates.pressure;
                    rd_contact_result_cleanup(&c);
                } else {
                    rd_error_init(&err);
                }
                total++;
                within[0] += dcf <= a.estimates.contact_fraction;
                within[1] += dg <= a.estimates.max_clearance || a.max_clearance == 0;
                within[2] += de <= a.estimates.gap_edges_deg || a.n_gaps == 0;
                within[3] += dp <= a.estimates.pressure;
                /* both answers claim to be within their estimates of the
                 * stiff law's limit: consistent if they differ by no more
                 * than the two estimates together */
                both[0] += dcf <= a.estimates.contact_fraction + b.estimates.contact_fraction;
                both[1] += dg <= a.estimates.max_clearance + b.estimates.max_clearance ||
                           a.max_clearance == 0;
                both[2] +=
                    de <= a.estimates.gap_edges_deg + b.estimates.gap_edges_deg || a.n_gaps == 0;
                both[3] += dp <= a.estimates.pressure + b.estimates.pressure;
                printf(
                    "| %d | %.2g | %g | %.4f (%.4f) | %.2e (%.2e) | %.3f (%.3f) | %.4f (%.4f) |\n",
                    k, facs[fi], phases[pi], dcf, a.estimates.contact_fraction, dg,
                    a.estimates.max_clearance, de, a.estimates.gap_edges_deg, dp,
                    a.estimates.pressure);
                rd_contact_result_cleanup(&a);
                rd_contact_result_cleanup(&b);
            }
    printf("\n%d bores (%d failed). 10 x the stiffness moves the answer by no more than its "
           "estimate: contact fraction %d, largest gap %d, edges %d, binned pressure %d.\n",
           total, failed, within[0], within[1], within[2], within[3]);
    printf("By no more than the two answers' estimates together: contact fraction %d, largest "
           "gap %d, edges %d, binned pressure %d.\n",
           both[0], both[1], both[2], both[3]);
    printf("At the default answer's n (10 x the stiffness solved there once): within its "
           "estimate: contact fraction %d, largest gap %d, edges %d, binned pressure %d.\n",
           same[0], same[1], same[2], same[3]);
}

/* A uniform deviate in [0, 1) from the 64-bit LCG state *x (Knuth's
 * MMIX constants), the same on every platform. */
static double uniform(unsigned long long *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

/* The bins' estimate's source (rd_contact_est_source_name), "none". */
static const char *source_name(int source)
{
    const char *s = rd_contact_est_source_name(source);
    return s ? s : "none";
}

/* --random SEED N: N random bores (one or two orders from 2 to 8, each
 * 0.1 to 10 x its bound log-uniformly, capped at 0.4 % of d shared, any
 * phase; kept convex) at default settings against the exact reference,
 * one line a bore and the counts: the battery's out-of-sample check;
 * only bore `only` of them if it is over 0. */
static void bins_print(const rd_ring_params *p, const rd_contact_result *c, const ref_result *r,
                       int estimates);
static void random_bores(const rd_ring_params *p, unsigned long long seed, int count, int only)
{
    int ok[4] = {0}, met = 0, met_off = 0, slow = 0, track[4] = {0}, under[4] = {0},
        over[4][2] = {0}, patch_ok = 0, patch_track = 0, patch_under = 0, tip_ok = 0, tip_ends = 0,
        tip_track = 0, tip_under = 0;
    double cpu_all = 0, patch_worst = 0;
    for (int t = 0; t < count;) {
        rd_contact_opts o = battery_bore(p, 2, 1, 0, NULL);
        o.bore.n_distortion = single_order ? 1 : 1 + (uniform(&seed) < 0.5);
        double convex = 0;
        for (int d = 0; d < o.bore.n_distortion; d++) {
            int k = 2 + (int)((single_order ? 5 : 7) * uniform(&seed));
            double fac = pow(10.0, -1.0 + 2.0 * uniform(&seed)), ph = 360.0 * uniform(&seed);
            double A = fmin(fac * thin_ring_bound(p, k), 0.004 * p->diameter / o.bore.n_distortion);
            o.bore.distortion[d] = (rd_distortion){k, A, ph};
            convex += A * (k * k + 2);
        }
        if (convex > 0.45 * p->diameter)
            continue;
        t++;
        if (only > 0 && t != only)
            continue;
        ref_result r;
        rd_contact_result c;
        rd_static_opts so;
        static_opts(&so);
        rd_error err;
        rd_error_init(&err);
        if (reference_solve(p, &o, rd_contact_gap_floor(p), &r) != 0) {
            printf("%d: reference failed\n", t);
            continue;
        }
        clock_t c0 = clock();
        if (rd_contact_solve(p, 20, &o, &so, NULL, &c, &err) != RD_OK) {
            printf("%d: %s\n", t, err.message);
            continue;
        }
        double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC, dp = 0;
        for (int b = 0; b < RD_CONTACT_BINS; b++)
            dp = fmax(dp, fabs(c.bin_pressure[b] - r.bin_pressure[b]) / r.p0);
        double dcf = fabs(c.contact_fraction - r.contact_fraction);
        double dg = r.max_clearance > 1e-7 ? fabs(c.max_clearance / r.max_clearance - 1) : 0;
        double de = ref_edge_error(&c, &r);
        int edges = !isnan(de); /* a light gap deeper than 0.1 um */
        de = edges ? de : 0;
        int in[4] = {dcf <= 0.02, dg <= 0.05, de <= 1.0, dp <= 0.02};
        for (int q = 0; q < 4; q++)
            ok[q] += in[q];
        /* the estimates against the true errors, as the battery counts them
         * (a quantity the reference lacks, a largest gap or edges under 0.1
         * um, counts as tracked; no gap in ringdyn's answer, no estimate) */
        double eg = c.max_clearance > 0 ? c.estimates.max_clearance / c.max_clearance : 0.0;
        double est[4] = {c.estimates.contact_fraction, eg, c.estimates.gap_edges_deg,
                         c.estimates.pressure},
               err4[4] = {dcf, dg, de, dp}, floor4[4] = {1e-3, 1e-3, 0.05, 1e-3},
               tenth[4] = {0.002, 0.005, 0.1, 0.001};
        int has[4] = {1, r.max_clearance > 1e-7, edges, 1};
        for (int q = 0; q < 4; q++) {
            track[q] += !has[q] || ref_tracks(est[q], err4[q], floor4[q]);
            if (has[q])
                miss_kind(est[q], err4[q], floor4[q], tenth[q], &under[q], over[q]);
        }
        double dtip = 0.0; /* the free ends' forces, as the battery counts them */
        for (int e = 0; e < 2; e++) {
            dtip = fmax(dtip, fabs(c.tip_force[e] - r.tip_force[e]));
            tip_ok += fabs(c.tip_force[e] - r.tip_force[e]) <= 0.02 * r.tip_force[e] + 0.01;
            tip_ends++;
        }
        tip_track += ref_tracks(c.estimates.tip_forces_n, dtip, 0.01);
        tip_under += 3.0 * c.estimates.tip_forces_n < dtip && dtip > 0.01;
        double prel, dpf = ref_patch_error(&c, &r, &prel);
        patch_worst = fmax(patch_worst, prel);
        patch_ok += prel <= 0.02 || dpf <= 0.01;
        patch_track += ref_tracks(c.estimates.patch_forces_n, dpf, ref_patch_floor(&r));
        patch_under += 3.0 * c.estimates.patch_forces_n < dpf && dpf > ref_patch_floor(&r);
        met += c.accuracy_met == 1;
        met_off += c.accuracy_met == 1 && !(in[0] && in[1] && in[2] && in[3]);
        slow += cpu > 0.2;
        cpu_all += cpu;
        printf("%d:", t);
        for (int d = 0; d < o.bore.n_distortion; d++)
            printf(" order %d at %.6g x, %.6g deg;", o.bore.distortion[d].order,
                   o.bore.distortion[d].amplitude / thin_ring_bound(p, o.bore.distortion[d].order),
                   o.bore.distortion[d].phase_deg);
        printf(" n %d, met %d, k %g x, cpu %.3f s; errors (estimates): fraction %.4f (%.4f), "
               "gap %.2f %% (%.2f %%), edges %.2f (%.2f) deg, bins %.3f (%.3f) p0, patches %d (%d) "
               "%.4f (%.4f) N, tips %.4f (%.4f) N; the bins' estimate from %s at %.4g deg\n",
               c.stats.segments, c.accuracy_met, c.stiffness / rd_contact_default_stiffness(p), cpu,
               dcf, c.estimates.contact_fraction, 100 * dg, 100 * eg, de, c.estimates.gap_edges_deg,
               dp, c.estimates.pressure, c.n_patches, r.n_patches, dpf, c.estimates.patch_forces_n,
               dtip, c.estimates.tip_forces_n, source_name(c.estimates.pressure_source),
               c.estimates.pressure_at_deg);
        if (only > 0)
            bins_print(p, &c, &r, 1);
        rd_contact_result_cleanup(&c);
    }
    printf("\n%d bores. Within the targets: contact fraction %d, largest gap %d, edges %d, binned "
           "pressure %d. Target met: %d, of them outside a target: %d. CPU over 0.2 s: %d, "
           "%.2f s in all.\n",
           count, ok[0], ok[1], ok[2], ok[3], met, met_off, slow, cpu_all);
    printf("Estimate within x3 of the true error: contact fraction %d, largest gap %d, edges %d, "
           "pressure %d. Understated beyond x3: %d, %d, %d, %d; overstated beyond x3: %d, %d, "
           "%d, %d, of them with the estimate under a tenth of the target: %d, %d, %d, %d.\n",
           track[0], track[1], track[2], track[3], under[0], under[1], under[2], under[3],
           over[0][0], over[1][0], over[2][0], over[3][0], over[0][1], over[1][1], over[2][1],
           over[3][1]);
    printf("Contact patches: every patch's force within 2 %% or 0.01 N of the reference's on %d "
           "bores (worst %.1f %% of the larger of its force and 0.5 N); the estimate within x3 of "
           "the error on %d (both under 0.01 N + 1e-3 of the largest patch: counted), "
           "understated beyond x3 on %d.\n",
           patch_ok, 100 * patch_worst, patch_track, patch_under);
    printf("Tip forces within 2 %% + 0.01 N of the reference's: %d of %d free ends; the estimate "
           "within x3 of the larger end's error on %d bores (both under 0.01 N: counted), "
           "understated beyond x3 on %d.\n",
           tip_ok, tip_ends, tip_track, tip_under);
}

/* One solved bore c against its reference r: each bin's pressure against
 * the reference's, the tip forces, the light gaps, and the segments of the
 * worst bin (what dominates its error); with `estimates`, the estimates
 * and the accuracy note. */
static void bins_print(const rd_ring_params *p, const rd_contact_result *c, const ref_result *r,
                       int estimates)
{
    double p0 = 2 * p->tangential_force / (p->diameter * p->axial_height);
    printf(
        "n %d, tip forces %.4g %.4g N (reference %.4g %.4g)\n| bin | ringdyn / p0 | reference / p0 "
        "| error |\n|---|---|---|---|\n",
        c->points, c->tip_force[0], c->tip_force[1], r->tip_force[0], r->tip_force[1]);
    int worst = 0;
    for (int b = 0; b < RD_CONTACT_BINS; b++) {
        double d = (c->bin_pressure[b] - r->bin_pressure[b]) / p0;
        if (fabs(d) > fabs(c->bin_pressure[worst] - r->bin_pressure[worst]) / p0)
            worst = b;
        printf("| %d | %.4f | %.4f | %+.4f |\n", b, c->bin_pressure[b] / p0,
               r->bin_pressure[b] / p0, d);
    }
    printf("\nsegments around bin %d: angle, pressure / p0, clearance (m)\n", worst);
    for (int i = 0; i < c->points; i++)
        if (c->angle_deg[i] > worst * RD_CONTACT_BIN_DEG - 3 &&
            c->angle_deg[i] < (worst + 1) * RD_CONTACT_BIN_DEG + 3)
            printf("%.3f %.4f %.3e\n", c->angle_deg[i], c->pressure[i] / p0, c->clearance[i]);
    if (estimates)
        printf("estimates at n = %d: pressure %.4f p0 (the law's share %.4f), contact fraction "
               "%.5f, largest gap %.3e m, edges %.3f deg; %d multiplier updates\n",
               c->stats.segments, c->estimates.pressure, c->law_share,
               c->estimates.contact_fraction, c->estimates.max_clearance,
               c->estimates.gap_edges_deg, c->stats.outer_iterations);
    if (estimates && c->accuracy_met != 1)
        printf("accuracy target not met: %s\n", c->accuracy_note);
    printf("gaps (ringdyn | reference):\n");
    for (int g = 0; g < c->n_gaps; g++)
        printf("  %.3f..%.3f %.3e\n", c->gaps[g].start_deg, c->gaps[g].end_deg,
               c->gaps[g].max_clearance);
    for (int g = 0; g < r->n_gaps; g++)
        printf("  | %.3f..%.3f %.3e\n", r->gaps[g].start_deg, r->gaps[g].end_deg,
               r->gaps[g].max_clearance);
    printf("patches, N at deg (ringdyn | reference; the estimate %.3g N):\n",
           c->estimates.patch_forces_n);
    for (int j = 0; j < c->n_patches; j++)
        printf("  %.3f..%.3f %.5g N at %.3f\n", c->patches[j].start_deg, c->patches[j].end_deg,
               c->patches[j].force_n, c->patches[j].centroid_deg);
    for (int j = 0; j < r->n_patches; j++)
        printf("  | %.3f..%.3f %.5g N at %.3f\n", r->patches[j].start_deg, r->patches[j].end_deg,
               r->patches[j].force_n, r->patches[j].centroid_deg);
}

/* The battery's bore of order k, amplitude fac x the bound, phase deg, at
 * default settings (or at fixed_n segments without refinement, if > 0),
 * printed by bins_print. */
static void bins_one(const rd_ring_params *p, int k, double fac, double phase, int fixed_n)
{
    rd_contact_opts o = battery_bore(p, k, fac, phase, NULL);
    ref_result r;
    rd_contact_result c;
    rd_static_opts so;
    static_opts(&so);
    rd_error err;
    rd_error_init(&err);
    if (fixed_n > 0)
        so.estimate_error = 0;
    if (reference_solve(p, &o, rd_contact_gap_floor(p), &r) != 0) {
        fprintf(stderr, "bins: the reference did not converge on %d cells\n", reference_cells);
        exit(1);
    }
    if (rd_contact_solve(p, fixed_n > 0 ? fixed_n : 20, &o, &so, NULL, &c, &err) != RD_OK)
        die("bins", &err);
    bins_print(p, &c, &r, fixed_n <= 0);
    rd_contact_result_cleanup(&c);
}

static void dump_arr(const char *name, const double *a, int n, double scale)
{
    printf("\"%s\":[", name);
    for (int i = 0; i < n; i++)
        printf("%s%.6g", i ? "," : "", a[i] / scale);
    printf("]");
}

/* --dump: every battery bore's reference (2880 and 1440 cells) and ringdyn
 * at fixed n = 40 ... 1280 without refinement, one JSON object a line (the
 * estimates' design data: bins / p0, fraction, gaps, per-segment pressure). */
static void dump_battery(const rd_ring_params *p)
{
    const int orders[] = {2, 3, 4, 6}, ns[] = {40, 80, 160, 320, 640, 1280};
    const double facs[] = {0.1, 1, 3, 10}, phases[] = {0, 17};
    double p0 = 2 * p->tangential_force / (p->diameter * p->axial_height);
    double floor_m = rd_contact_gap_floor(p);
    for (int oi = 0; oi < 4; oi++)
        for (int fi = 0; fi < 4; fi++)
            for (int pi = 0; pi < 2; pi++) {
                if (orders[oi] == 2 && facs[fi] == 10)
                    continue; /* capped at 0.4 % of d: the 3 x bore again */
                double Ab;
                rd_contact_opts o = battery_bore(p, orders[oi], facs[fi], phases[pi], &Ab);
                printf("{\"k\":%d,\"fac\":%g,\"phase\":%g,\"ref\":[", orders[oi], Ab, phases[pi]);
                for (int h = 0; h < 2; h++) {
                    ref_result r;
                    int cells = reference_cells;
                    reference_cells >>= h;
                    int rc = reference_solve(p, &o, floor_m, &r);
                    reference_cells = cells;
                    if (rc)
                        die("reference", &(rd_error){0});
                    printf("%s{\"cf\":%.8g,\"gmax\":%.6g,\"tips\":[%.6g,%.6g],", h ? "," : "",
                           r.contact_fraction, r.max_clearance, r.tip_force[0], r.tip_force[1]);
                    dump_arr("bins", r.bin_pressure, RD_CONTACT_BINS, p0);
                    printf(",\"gaps\":[");
                    for (int g = 0; g < r.n_gaps; g++)
                        printf("%s[%.6g,%.6g,%.6g]", g ? "," : "", r.gaps[g].start_deg,
                               r.gaps[g].end_deg, r.gaps[g].max_clearance);
                    printf("]}");
                }
                printf("],\"lev\":[");
                for (int li = 0; li < 6; li++) {
                    rd_contact_result c;
                    rd_static_opts so;
                    static_opts(&so);
                    so.estimate_error = 0;
                    rd_error err;
                    rd_error_init(&err);
                    if (rd_contact_solve(p, ns[li], &o, &so, NULL, &c, &err) != RD_OK)
                        die("dump", &err);
                    printf("%s{\"n\":%d,\"cf\":%.8g,\"gmax\":%.6g,\"pen\":%.6g,\"marg\":%.6g,"
                           "\"sp\":%.6g,\"its\":%d,\"tips\":[%.6g,%.6g],",
                           li ? "," : "", ns[li], c.contact_fraction, c.max_clearance,
                           c.max_penetration, c.marginal_gap_deg, c.point_spacing_deg,
                           c.stats.iterations, c.tip_force[0], c.tip_force[1]);
                    dump_arr("bins", c.bin_pressure, RD_CONTACT_BINS, p0);
                    printf(",");
                    dump_arr("ang", c.angle_deg, c.points, 1.0);
                    printf(",");
                    dump_arr("p", c.pressure, c.points, p0);
                    printf(",");
                    dump_arr("cl", c.clearance, c.points, 1.0);
                    printf(",\"gaps\":[");
                    for (int g = 0; g < c.n_gaps; g++)
                        printf("%s[%.6g,%.6g,%.6g]", g ? "," : "", c.gaps[g].start_deg,
                               c.gaps[g].end_deg, c.gaps[g].max_clearance);
                    printf("]");
                    {
                        rd_contact_opts o2 = o;
                        o2.stiffness = 2.0 * c.stiffness;
                        rd_contact_result c2;
                        if (rd_contact_solve(p, ns[li], &o2, &so, NULL, &c2, &err) != RD_OK) {
                            printf(",\"cf2\":null}");
                            rd_contact_result_cleanup(&c);
                            continue;
                        }
                        printf(",\"cf2\":%.8g,\"gmax2\":%.6g,\"gaps2\":[", c2.contact_fraction,
                               c2.max_clearance);
                        for (int g = 0; g < c2.n_gaps; g++)
                            printf("%s[%.6g,%.6g,%.6g]", g ? "," : "", c2.gaps[g].start_deg,
                                   c2.gaps[g].end_deg, c2.gaps[g].max_clearance);
                        printf("]");
                        rd_contact_result_cleanup(&c2);
                    }
                    printf("}");
                    rd_contact_result_cleanup(&c);
                }
                printf("]}\n");
                fflush(stdout);
            }
}

/* Takes the first `name` (and its value, if has_value) out of argv, so
 * options may stand anywhere; returns the value ("" for a flag), or NULL
 * when absent. */
static const char *take_option(int *argc, char **argv, const char *name, int has_value)
{
    for (int i = 1; i + has_value < *argc; i++) {
        if (strcmp(argv[i], name) != 0)
            continue;
        const char *v = has_value ? argv[i + 1] : "";
        int k = 1 + has_value;
        memmove(argv + i, argv + i + k, (size_t)(*argc - i - k + 1) * sizeof *argv);
        *argc -= k;
        return v;
    }
    return NULL;
}

int main(int argc, char **argv)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_contact_opts co;
    rd_contact_opts_default(&co);
    const char *v;
    if (take_option(&argc, argv, "--single", 0))
        single_order = 1;
    if (take_option(&argc, argv, "--exact-updates", 0))
        exact_updates = 1;
    if (take_option(&argc, argv, "--settled", 0))
        settle_refs = 1;
    if (take_option(&argc, argv, "--rigid", 0))
        rigid_face = 1;
    /* --face: the flexible faces, the default since 0.3.0 (kept so the
     * README's earlier commands still run) */
    if (take_option(&argc, argv, "--face", 0))
        rigid_face = 0;
    if ((v = take_option(&argc, argv, "--kx", 1)))
        stiffness_times = atof(v);
    if ((v = take_option(&argc, argv, "--cap", 1))) {
        cap = atoi(v);
        if (cap < 4 || cap > RD_STATIC_SEGMENTS_MAX) {
            fprintf(stderr, "--cap: 4 to %d segments, not %s\n", RD_STATIC_SEGMENTS_MAX, v);
            return 1;
        }
    }
    if ((v = take_option(&argc, argv, "--accuracy", 1))) {
        accuracy_opt = atof(v);
        if (!(accuracy_opt >= 1e-4 && accuracy_opt <= 0.5)) {
            fprintf(stderr, "--accuracy: 1e-4 to 0.5, not %s\n", v);
            return 1;
        }
    }
    if ((v = take_option(&argc, argv, "--reference", 1))) {
        reference_kind = strcmp(v, "linear") == 0    ? REF_LINEAR
                         : strcmp(v, "nl-dead") == 0 ? REF_NL_DEAD
                         : strcmp(v, "nl") == 0      ? REF_NL
                                                     : -1;
        if (reference_kind < 0) {
            fprintf(stderr, "--reference: nl, nl-dead or linear, not %s\n", v);
            return 1;
        }
    }
    /* a multiple of 4: the battery also solves the reference on half as
     * many cells, which must be even */
    if ((v = take_option(&argc, argv, "--ref-cells", 1))) {
        reference_cells = atoi(v);
        if (reference_cells < 8 || reference_cells % 4) {
            fprintf(stderr, "--ref-cells: a multiple of 4, at least 8, not %s\n", v);
            return 1;
        }
    }
    if ((v = take_option(&argc, argv, "--ring", 1))) {
        /* another ring: diameter, radial width, axial height (m), F_t (N) */
        if (sscanf(v, "%lf,%lf,%lf,%lf", &p.diameter, &p.radial_width, &p.axial_height,
                   &p.tangential_force) != 4) {
            fprintf(stderr, "--ring: D,B,H,FT (m, m, m, N), not %s\n", v);
            return 1;
        }
        rd_error err;
        rd_error_init(&err);
        if (rd_ring_scene_validate(&p, 20, 0, &err))
            die("--ring", &err);
    }
    if (rigid_face)
        co.flexible_face = 0;
    if (argc == 3 && strcmp(argv[1], "--once") == 0) {
        rd_contact_result r;
        rd_static_opts so;
        static_opts(&so);
        so.estimate_error = 0;
        rd_error err;
        rd_error_init(&err);
        if (rd_contact_solve(&p, atoi(argv[2]), &co, &so, NULL, &r, &err))
            die("contact", &err);
        rd_contact_result_cleanup(&r);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "--stiffness") == 0) {
        stiffness_battery(&p);
        return 0;
    }
    if (argc >= 5 && argc <= 7 && strcmp(argv[1], "--bins") == 0) {
        /* a load scale s: F_t and (through the bound) the amplitude times s,
         * so the linear reference's answer in p0 does not change and what
         * moves is ringdyn's geometric nonlinearity */
        if (argc == 7)
            p.tangential_force *= atof(argv[6]);
        bins_one(&p, atoi(argv[2]), atof(argv[3]), atof(argv[4]), argc >= 6 ? atoi(argv[5]) : 0);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "--dump") == 0) {
        dump_battery(&p);
        return 0;
    }
    if ((argc == 4 || argc == 5) && strcmp(argv[1], "--random") == 0) {
        random_bores(&p, strtoull(argv[2], NULL, 10), atoi(argv[3]), argc == 5 ? atoi(argv[4]) : 0);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "--battery") == 0) {
        battery(&p);
        return 0;
    }
    double p0 = 2 * p.tangential_force / (p.diameter * p.axial_height);

    rd_pretension_result r1, r2;
    memset(&r1, 0, sizeof r1);
    memset(&r2, 0, sizeof r2);
    time_pretension(&p, 2000, 0, &r1);
    time_pretension(&p, 1000, 0, &r2);
    double limit = r1.gap_opening_inner + (r1.gap_opening_inner - r2.gap_opening_inner) / 3.0;
    printf("## pretension (force method, thesis ring): x_a limit %.6f mm\n\n", limit * 1e3);
    printf("| n | x_a (mm) | true error | estimate | Newton iterations | wall (ms) | wall with "
           "estimate (ms) |\n|---|---|---|---|---|---|---|\n");
    const int ns[] = {10, 20, 40, 80, 160, 320, 640, 1280};
    const int nn = sizeof ns / sizeof ns[0];
    double xs[16], ts[16], tc[16];
    int k = 0;
    for (int i = 0; i < nn; i++) {
        double t = time_pretension(&p, ns[i], 0, &r1);
        int iters = r1.stats.iterations;
        double xa = r1.gap_opening_inner;
        double te = time_pretension(&p, ns[i], 1, &r1);
        printf("| %d | %.4f | %.2e | %.2e | %d | %.2f | %.2f |\n", ns[i], xa * 1e3,
               fabs(xa - limit) / limit, r1.stats.error_estimate, iters, t * 1e3, te * 1e3);
        if (ns[i] >= 80) {
            xs[k] = ns[i];
            ts[k++] = t;
        }
    }
    printf("\ncost exponent (t ~ n^p, n >= 80): p = %.2f\n\n", bench_exponent(xs, ts, k));

    printf("## contact, round bore (%d points per segment, the default)\n\n",
           co.points_per_segment);
    printf("| n | mean pressure / p0 - 1 | Newton iterations | wall (ms) |\n|---|---|---|---|\n");
    rd_contact_result c, c20;
    memset(&c, 0, sizeof c);
    memset(&c20, 0, sizeof c20);
    k = 0;
    for (int i = 0; i < nn; i++) {
        double t = time_contact(&p, ns[i], &co, &c);
        printf("| %d | %+.2e | %d | %.2f |\n", ns[i], c.mean_pressure / p0 - 1, c.stats.iterations,
               t * 1e3);
        if (ns[i] >= 80) {
            xs[k] = ns[i];
            tc[k++] = t;
        }
    }
    printf("\ncost exponent (t ~ n^p, n >= 80): p = %.2f\n\n", bench_exponent(xs, tc, k));

    printf("## contact points per segment, n = 40\n\n");
    printf("| points | round bore: wall (ms) | change vs 20 points (of p0) | distorted "
           "(k=4, 1.3 x bound): wall (ms) | change vs 20 points |\n|---|---|---|---|---|\n");
    rd_contact_opts cd = co;
    cd.bore.n_distortion = 1;
    cd.bore.distortion[0].order = 4;
    cd.bore.distortion[0].phase_deg = 45;
    cd.bore.distortion[0].amplitude = 1.3 * 4.3246e-6; /* 1.3 x F_t R^3 / (E I 15^2) */
    rd_contact_result d, d20;
    memset(&d, 0, sizeof d);
    memset(&d20, 0, sizeof d20);
    co.points_per_segment = cd.points_per_segment = 20;
    time_contact(&p, 40, &co, &c20);
    time_contact(&p, 40, &cd, &d20);
    const int ms[] = {1, 2, 3, 5, 10, 20};
    for (int i = 0; i < 6; i++) {
        co.points_per_segment = cd.points_per_segment = ms[i];
        double t = time_contact(&p, 40, &co, &c);
        double td = time_contact(&p, 40, &cd, &d);
        printf("| %d | %.2f | %.1e | %.2f | %.1e |\n", ms[i], t * 1e3, profile_change(&c, &c20, p0),
               td * 1e3, profile_change(&d, &d20, p0));
    }
    rd_pretension_result_cleanup(&r1);
    rd_pretension_result_cleanup(&r2);
    rd_contact_result_cleanup(&c);
    rd_contact_result_cleanup(&c20);
    rd_contact_result_cleanup(&d);
    rd_contact_result_cleanup(&d20);
    return 0;
}
