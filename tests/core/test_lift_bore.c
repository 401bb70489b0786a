

/* test_lift_bore — the bore of a lift scene (bore.diameter, bore.distortion;
 * rd_lift_bore.c).
 *
 * References:
 *  - the ring's start in a distorted bore against the thin-ring closed
 *    form: under the constant pretension p0 an order-k distortion A_k changes
 *    the contact pressure by dp_k = -E I (k^2 - 1)^2 / (R^4 h) A_k (inextensional
 *    bending of the ring), 5 % of p0 here, so the ring stays in contact
 *    everywhere and its running face follows the bore: u_r = g(psi) up to
 *    the contact's penetration change dp_k / k (nanometres) and the split
 *    ring's free ends (which follow the bore too: they are free);
 *  - the modal model with every mode against the full model on a distorted
 *    Coulomb scene (a change of coordinates, also of the static start);
 *  - auto never runs the rigid ring on a distorted bore, and rigid asked for
 *    one is refused naming the fields;
 *  - a bore map (rd_lift_params.bore_map): two equal layers give the plain
 *    bore's run bit for bit; a distortion growing down the bore (orders 2
 *    and 4, 2 um at the top to 10 um 0.1 m down) is followed by the ring
 *    as the piston travels: at every sample of a slow downstroke each
 *    segment's middle sits on the bore of its current depth within the
 *    static start's bound (the same closed form, the amplitude there), and
 *    the segments' contact pressures away from the gap follow the closed
 *    form's dp_k at that depth (within 0.072 of its range at n = 64, 0.225
 *    at n = 24: first order in n), the range growing down the bore; a
 *    map that does not cover the stroke, or given with /bore/distortion,
 *    is refused by name;
 *  - the per-segment flank changes (lift_segments.h, the benchmark's
 *    comparison with full n = 40): on histories whose crossings are known in
 *    closed form, the modal model with every mode against the full model
 *    segment by segment, and a coarse ring's segment matched to the finer
 *    ring's lift at its mid-angle. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lift_distort.h"
#include "lift_segments.h"
#include "rd_lift.h"
#include "rd_lift_internal.h"

#define PI 3.14159265358979323846

static double bore_offset(const rd_lift_params *p, double psi)
{
    double g = 0.0;
    for (int k = 0; k < p->bore.n_distortion; k++)
        g += p->bore.distortion[k].amplitude *
             cos(p->bore.distortion[k].order * (psi - p->bore.distortion[k].phase_deg * PI / 180));
    return g;
}

typedef struct first {
    int n, done;
    double *q; /* 12 n */
} first;

static void first_sample(void *vctx, double t, const double *y)
{
    first *f = vctx;
    if (f->done || t != 0.0)
        return;
    memcpy(f->q, y, 12 * (size_t)f->n * sizeof *y);
    f->done = 1;
}

/* The start follows the bore (file comment): at every segment's middle the
 * radial displacement equals the bore's offset.  The closed form's
 * penetration change is ~1e-10 m; what remains is the segmentation: a
 * rigid segment cannot follow the bore's curvature within its own arc, so
 * its middle can sit off the bore by up to the distortion's sagitta over half
 * a segment, sum |A_k| k^2 (phi/2)^2 / 2 (phi = the segment's arc): the
 * tolerance, at n = 24 and 48 (where it is 4x smaller, 0.44 and 0.11 um). */
static void test_static_start(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    for (int n = 24; n <= 48; n *= 2) {
        rd_lift_params p;
        rd_lift_params_default(&p);
        distort(&p, 5e-6);
        p.engine.cycles = 0.01;
        p.estimate_error = 0;
        p.model = RD_LIFT_MODEL_FULL;
        double *q = malloc(12 * (size_t)n * sizeof *q);
        first f = {.n = n, .q = q};
        rd_lift_setup su = {.sample = first_sample, .ctx = &f};
        rd_lift_result r;
        rd_error err;
        rd_error_init(&err);
        int rc = rd_lift_solve_setup(&rp, n, &p, &su, NULL, &r, &err);
        CHECK(rc == RD_OK && f.done, "distorted start: %s", err.message);
        double R = 0.5 * (rp.diameter - rp.radial_width), gap = rp.closed_gap / R;
        double span = 2.0 * PI - gap, worst = 0.0, half = 0.5 * span / n, bound = 0.0;
        for (int k = 0; k < p.bore.n_distortion; k++)
            bound += fabs(p.bore.distortion[k].amplitude) * pow(p.bore.distortion[k].order, 2) *
                     half * half / 2.0;
        for (int i = 0; rc == RD_OK && i < n; i++) {
            double al = 0.5 * gap + (i + 0.5) * span / n;
            double ur = cos(al) * q[12 * i] + sin(al) * q[12 * i + 1];
            worst = fmax(worst, fabs(ur - bore_offset(&p, al)));
        }
        CHECK(worst < bound, "n = %d: the start misses the bore by %g m (bound %g m)", n, worst,
              bound);
        fprintf(stderr,
                "    distorted bore (orders 2, 4; 5 um), n = %d: the start follows it "
                "within %.3g m (bound %.3g m)\n",
                n, worst, bound);
        rd_lift_result_cleanup(&r);
        free(q);
    }
}

/* Modal with every mode = full (n = 4, Coulomb, gas-free, rtol 1e-8;
 * tolerance 0.01 deg as test_lift_modal's); auto runs full and says why. */
static void test_modal_full(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    distort(&p, 5e-6);
    p.engine.cycles = 0.5;
    p.gravity = 1;
    p.friction.model = RD_FRICTION_COULOMB;
    p.estimate_error = 0;
    p.rtol = 1e-8;
    p.atol = 1e-11;
    rd_lift_result a, b;
    rd_error err;
    rd_error_init(&err);
    p.model = RD_LIFT_MODEL_MODAL;
    p.modes = 18;
    int rc = rd_lift_solve(&rp, 4, &p, NULL, &a, &err);
    CHECK(rc == RD_OK, "modal distorted: %s", err.message);
    p.model = RD_LIFT_MODEL_AUTO;
    int rc2 = rd_lift_solve(&rp, 4, &p, NULL, &b, &err);
    CHECK(rc2 == RD_OK && b.model == RD_LIFT_MODEL_FULL && strstr(b.why, "distorted"),
          "auto distorted: rc %d model %d (%s) %s", rc2, b.model, b.why, err.message);
    if (rc == RD_OK && rc2 == RD_OK) {
        double d = a.n_events == b.n_events ? 0.0 : 1e9;
        for (int i = 0; i < a.n_events && d < 1e9; i++)
            d = a.events[i].kind != b.events[i].kind
                    ? 1e9
                    : fmax(d, fabs(a.events[i].crank_deg - b.events[i].crank_deg));
        CHECK(d < 0.01, "distorted: all-mode modal vs full flank changes differ by %g deg", d);
        fprintf(stderr,
                "    distorted Coulomb scene: %d flank changes, modal(all) - full <= "
                "%.4f deg\n",
                b.n_events, d);
        /* segment by segment (lift_segments.h), the same tolerance */
        seg_cmp c;
        CHECK(compare_segments(&a, &b, p.groove.axial_clearance, &c) == 0, "out of memory");
        CHECK(c.events >= 4 * b.segments && c.differ == 0 && c.max_deg < 0.01,
              "distorted: modal(all) vs full per segment: %d flank changes, %d segments "
              "differ, largest change %g deg",
              c.events, c.differ, c.max_deg);
        fprintf(stderr,
                "    the same per segment: %d flank changes, modal(all) - full <= %.4f deg\n",
                c.events, c.max_deg);
    }
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

/* ------------------------------------------ per-segment flank changes */

#define SEG_CA 3e-5 /* m: the thesis groove's axial clearance */

/* A segment's lift (m) at crank angle t (deg) whose flank changes are known
 * in closed form: seated on the lower flank (the penalty's nanometre inside
 * it); a parabolic flight up to the upper flank; a bounce there of 0.3 % of
 * c_a (within eps: no flank change); a parabolic flight down; a hop of 2 %
 * of c_a (beyond eps: a leave and a landing); seated again. */
static double seg_history(double t)
{
    double ca = SEG_CA;
    if (t < 10.0 || (t >= 50.0 && t < 60.0) || t >= 64.0)
        return -1e-10;
    if (t < 20.0)
        return ca * pow((t - 10.0) / 10.0, 2);
    if (t < 40.0)
        return ca * (1.0 + 1e-6) -
               (t >= 30.0 && t < 34.0 ? 3e-3 * ca * sin(PI * (t - 30.0) / 4.0) : 0.0);
    if (t < 50.0)
        return ca * (1.0 - pow((t - 40.0) / 10.0, 2));
    return 2e-2 * ca * sin(PI * (t - 60.0) / 4.0);
}

/* Its flank changes, from the thresholds of lift_segments.h: leaves at
 * eps = 1 % of c_a off the flank, landings within 0.5 % of it. */
static const struct {
    double deg;
    int kind;
} seg_expected[] = {
    {11.0, RD_EVENT_LEAVE_LOWER}, /* ca x^2 = eps, x = 0.1 */
    {0.0, RD_EVENT_REACH_UPPER},  /* 10 + 10 sqrt(0.995), set in the test */
    {41.0, RD_EVENT_LEAVE_UPPER}, {0.0, RD_EVENT_REACH_LOWER}, /* 40 + 10 sqrt(0.995) */
    {0.0, RD_EVENT_LEAVE_LOWER},                               /* 60 + 4 asin(0.5) / pi */
    {0.0, RD_EVENT_REACH_LOWER},                               /* 64 - 4 asin(0.25) / pi */
};

/* A result of n segments whose segment i follows seg_history shifted by
 * shift(i) deg, sampled every h deg over 0 .. 100 deg. */
static void seg_result(rd_lift_result *r, int n, double h, double step_shift, double offset)
{
    memset(r, 0, sizeof *r);
    r->segments = n;
    r->samples = (int)lround(100.0 / h) + 1;
    r->crank_deg = malloc((size_t)r->samples * sizeof *r->crank_deg);
    r->lift_segments = malloc((size_t)r->samples * n * sizeof *r->lift_segments);
    CHECK(r->crank_deg && r->lift_segments, "out of memory");
    for (int k = 0; r->lift_segments && r->crank_deg && k < r->samples; k++) {
        r->crank_deg[k] = k * h;
        for (int i = 0; i < n; i++)
            r->lift_segments[(size_t)k * n + i] = seg_history(k * h - offset - i * step_shift);
    }
}

/* The definition on the closed-form history, sampled every h = 0.01 deg:
 * each flank change within the linear interpolation's error between
 * samples, h^2 max|l''| / (8 |l'|) at the crossing, 1.3e-5 deg for the
 * parabolas (l''/l' <= 1/deg there), less for the hop.  Every crossing lies
 * at least 0.025 deg (2.5 h) from the history's kinks (the impacts), whose
 * interpolation across would cost up to h.  Tolerance 1e-4 deg. */
static void test_segment_events(void)
{
    double want[6];
    for (int i = 0; i < 6; i++)
        want[i] = seg_expected[i].deg;
    want[1] = 10.0 + 10.0 * sqrt(0.995);
    want[3] = 40.0 + 10.0 * sqrt(0.995);
    want[4] = 60.0 + 4.0 * asin(0.5) / PI;
    want[5] = 64.0 - 4.0 * asin(0.25) / PI;
    rd_lift_result r;
    seg_result(&r, 1, 0.01, 0.0, 0.0);
    seg_events e;
    seg_events_of(r.crank_deg, r.lift_segments, r.samples, SEG_CA, &e);
    CHECK(e.n == 6 && !e.overflow, "closed-form history: %d flank changes, want 6", e.n);
    double worst = 0.0;
    for (int i = 0; i < e.n && i < 6; i++) {
        CHECK(e.kind[i] == seg_expected[i].kind, "flank change %d: kind %d, want %d", i, e.kind[i],
              seg_expected[i].kind);
        worst = fmax(worst, fabs(e.deg[i] - want[i]));
    }
    CHECK(worst < 1e-4, "closed-form history: flank changes off by %g deg", worst);
    rd_lift_result_cleanup(&r);

    /* Matching positions: ring a (2 segments) and ref (4), segment i's
     * history delayed by 0.13 i deg in ref (off the samples' grid); a's
     * segment j, at ref's position 2j + 1/2, by 0.13 (2j + 1/2) deg, where
     * ref's flank changes
     * interpolated between its segments 2j and 2j + 1 are delayed as much:
     * each of the three within the samples' 1e-4 deg, so tolerance 3e-4 deg.
     * A segment matched to ref's 2j or 2j + 1 instead would be 0.065 deg
     * off. */
    rd_lift_result a, ref;
    seg_result(&ref, 4, 0.01, 0.13, 0.0);
    seg_result(&a, 2, 0.01, 0.26, 0.065);
    seg_cmp c;
    CHECK(compare_segments(&a, &ref, SEG_CA, &c) == 0, "out of memory");
    CHECK(c.events == 12 && c.differ == 0 && c.max_deg < 3e-4,
          "2 vs 4 segments: %d flank changes, %d segments differ, largest change %g deg", c.events,
          c.differ, c.max_deg);
    fprintf(stderr,
            "    per-segment flank changes: closed form within %.2g deg; 2 vs 4 segments at "
            "the same positions within %.2g deg\n",
            worst, c.max_deg);
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&ref);
}

static void test_validation(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    distort(&p, 5e-6);
    p.model = RD_LIFT_MODEL_RIGID;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/numerics/model") &&
              strstr(err.message, "/bore/distortion"),
          "rigid + distortion: rc %d %s: %s", rc, err.path, err.message);
    p.model = RD_LIFT_MODEL_AUTO;
    p.bore.diameter = 1.05 * rp.diameter;
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/bore/diameter"), "bore 5 %% larger: %s",
          err.message);
    p.bore.diameter = 0.0;
    p.bore.distortion[0].amplitude = 0.02 * rp.diameter;
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/bore/distortion/0/amplitude"),
          "amplitude 2 %%: %s", err.message);
    /* modal with fewer than all modes on a distorted bore says to use full
     * (measured far off: README) */
    p.bore.distortion[0].amplitude = 5e-6;
    p.model = RD_LIFT_MODEL_MODAL;
    p.modes = 6;
    p.engine.cycles = 0.01;
    p.estimate_error = 0;
    rd_lift_result r;
    rd_error_init(&err);
    rc = rd_lift_solve(&rp, 8, &p, NULL, &r, &err);
    CHECK(rc == RD_OK && strstr(r.why, "use full"), "modal on a distorted bore: %s (%s)", r.why,
          err.message);
    rd_lift_result_cleanup(&r);
}

/* The map of test_map: distort_map (lift_distort.h). */
static void map_of(rd_bore_map *m, double A_top, double A_bot)
{
    distort_map(m, A_top, A_bot);
}

typedef struct follow {
    int n, samples;
    const rd_lift_params *p;
    const rd_ring_params *rp;
    double worst, bound_at_worst, ratio; /* the largest miss over its bound */
    double a_first, a_last;              /* the bore's amplitude at the first and last sample */
} follow;

/* The bore of the map at depth z, offset at psi. */
static double map_offset(const rd_bore_map *m, double z, double psi)
{
    double w = (z - m->layer[0].z) / (m->layer[1].z - m->layer[0].z), g[2];
    for (int i = 0; i < 2; i++) {
        rd_lift_params q;
        rd_lift_params_default(&q);
        q.bore = m->layer[i].bore;
        g[i] = bore_offset(&q, psi);
    }
    return (1.0 - w) * g[0] + w * g[1];
}

static void follow_sample(void *vctx, double t, const double *y)
{
    follow *f = vctx;
    const rd_bore_map *m = f->p->bore_map;
    double s, v, a;
    rd_engine_piston(&f->p->engine, rd_engine_omega(&f->p->engine) * t, &s, &v, &a);
    double z = f->p->ring_z_tdc + s, w = z / 0.1;
    double amp = (1.0 - w) * m->layer[0].bore.distortion[0].amplitude +
                 w * m->layer[1].bore.distortion[0].amplitude;
    double R = 0.5 * (f->rp->diameter - f->rp->radial_width), gap = f->rp->closed_gap / R;
    double span = 2.0 * PI - gap, half = 0.5 * span / f->n;
    double bound = amp * (4.0 + 0.4 * 16.0) * half * half / 2.0; /* orders 2, 4 (distort) */
    for (int i = 0; i < f->n; i++) {
        double al = 0.5 * gap + (i + 0.5) * span / f->n;
        double ur = cos(al) * y[12 * i] + sin(al) * y[12 * i + 1];
        double miss = fabs(ur - map_offset(m, z, al));
        if (miss / bound > f->ratio) {
            f->ratio = miss / bound;
            f->worst = miss;
            f->bound_at_worst = bound;
        }
    }
    if (f->samples++ == 0)
        f->a_first = amp;
    f->a_last = amp;
}

/* The contact pressure of the map's downstroke against the thin ring's
 * closed form (file head): each segment's mean of p0 - sum_k dp_k cos(k
 * (theta - phi_k)) over its arc, dp_k = E I (k^2 - 1)^2 A_k(z) / (R^4 h) at
 * the ring's depth z, against the result's segment pressures at every
 * sample, on the segments more than 60 deg from the gap (the split ring's
 * free ends carry concentrated tip forces and lift off next to them, which
 * the closed ring's form does not have).  Returns the largest difference
 * over the closed form's range at that sample. */
static double pressure_check(const rd_ring_params *rp, const rd_lift_params *p,
                             const rd_lift_result *r)
{
    const rd_bore_map *m = p->bore_map;
    int n = r->segments;
    double R = 0.5 * (rp->diameter - rp->radial_width), h = rp->axial_height;
    double EI = rp->youngs_modulus * h * pow(rp->radial_width, 3) / 12.0;
    double p0 = 2.0 * rp->tangential_force / (rp->diameter * h);
    double gap = rp->closed_gap / R, span = 2.0 * PI - gap, worst = 0.0;
    for (int s = 0; s < r->samples; s++) {
        double z = r->ring_depth[s], w = (z - m->layer[0].z) / (m->layer[1].z - m->layer[0].z);
        double lo = INFINITY, hi = -INFINITY, miss = 0.0;
        for (int i = 0; i < n; i++) {
            double a0 = 0.5 * gap + i * span / n, a1 = a0 + span / n, pm = p0;
            for (int k = 0; k < 2; k++) {
                const rd_distortion *d0 = &m->layer[0].bore.distortion[k];
                double A = (1.0 - w) * d0->amplitude + w * m->layer[1].bore.distortion[k].amplitude;
                double ko = d0->order, ph = d0->phase_deg * PI / 180.0;
                double dp = EI * pow(ko * ko - 1.0, 2) * A / (pow(R, 4) * h);
                pm -= dp * (sin(ko * (a1 - ph)) - sin(ko * (a0 - ph))) / (ko * (a1 - a0));
            }
            lo = fmin(lo, pm);
            hi = fmax(hi, pm);
            double mid = 0.5 * (a0 + a1);
            if (mid > PI / 3.0 && mid < 2.0 * PI - PI / 3.0)
                miss = fmax(miss, fabs(r->bore_pressure[(size_t)s * n + i] - pm));
        }
        worst = fmax(worst, miss / (hi - lo));
    }
    return worst;
}

static void test_map(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    int n = 24;
    /* equal layers: the plain bore's run bit for bit */
    rd_lift_params p, q;
    rd_lift_params_default(&p);
    distort(&p, 5e-6);
    p.engine.cycles = 0.02;
    p.estimate_error = 0;
    p.model = RD_LIFT_MODEL_FULL;
    rd_bore_map m;
    map_of(&m, 5e-6, 5e-6);
    q = p;
    q.bore = (rd_bore){0};
    q.bore_map = &m;
    q.ring_z_tdc = 0.005;
    rd_lift_result a, b;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve(&rp, n, &p, NULL, &a, &err) || rd_lift_solve(&rp, n, &q, NULL, &b, &err);
    CHECK(rc == RD_OK, "map runs: %s", err.message);
    if (rc == RD_OK) {
        CHECK(a.samples == b.samples && a.segments == b.segments &&
                  !memcmp(a.lift_segments, b.lift_segments,
                          (size_t)a.samples * a.segments * sizeof *a.lift_segments) &&
                  !memcmp(a.twist, b.twist, (size_t)a.samples * sizeof *a.twist),
              "equal layers differ from the plain bore");
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
    /* a distortion growing down the bore, followed on a slow downstroke */
    map_of(&m, 2e-6, 10e-6);
    q.engine.speed_rpm = 300.0;
    q.engine.cycles = 0.25;
    q.step_deg = 10.0;
    follow f = {.n = n, .p = &q, .rp = &rp};
    rd_lift_setup su = {.sample = follow_sample, .ctx = &f};
    rd_error_init(&err);
    rc = rd_lift_solve_setup(&rp, n, &q, &su, NULL, &a, &err);
    CHECK(rc == RD_OK && f.samples > 10, "map downstroke: %s (%d samples)", err.message, f.samples);
    double miss24 = NAN, miss64 = NAN;
    if (rc == RD_OK) {
        miss24 = pressure_check(&rp, &q, &a);
        CHECK(a.bore_pressure_max[a.samples - 1] - a.bore_pressure_min[a.samples - 1] >
                  3.0 * (a.bore_pressure_max[0] - a.bore_pressure_min[0]),
              "the pressure range should grow down the bore: %g to %g Pa, then %g to %g Pa",
              a.bore_pressure_min[0], a.bore_pressure_max[0], a.bore_pressure_min[a.samples - 1],
              a.bore_pressure_max[a.samples - 1]);
        rd_lift_result_cleanup(&a);
    }
    rd_error_init(&err);
    rc = rd_lift_solve(&rp, 64, &q, NULL, &a, &err);
    CHECK(rc == RD_OK, "map downstroke, n = 64: %s", err.message);
    if (rc == RD_OK) {
        miss64 = pressure_check(&rp, &q, &a);
        rd_lift_result_cleanup(&a);
    }
    fprintf(stderr,
            "    bore map: segment pressures against the thin ring's closed form, away from the "
            "gap: within %.3f (n = 24), %.3f (n = 64) of its range\n",
            miss24, miss64);
    CHECK(miss64 < 0.1 && miss64 < miss24,
          "segment pressures miss the closed form by %g (n = 64), "
          "%g (n = 24) of its range",
          miss64, miss24);
    fprintf(
        stderr,
        "    bore map (orders 2, 4; %.2g um at TDC to %.2g um at BDC), n = %d: the ring follows "
        "the bore at its depth within %.3g m (%.2f of the bound %.3g m) over %d samples\n",
        1e6 * f.a_first, 1e6 * f.a_last, n, f.worst, f.ratio, f.bound_at_worst, f.samples);
    CHECK(f.ratio < 1.0, "the ring misses the bore at its depth by %g m (bound %g m)", f.worst,
          f.bound_at_worst);
    CHECK(f.a_last > 3.0 * f.a_first, "the downstroke should reach the larger distortion: %g, %g",
          f.a_first, f.a_last);
    /* refused: a map that does not cover the stroke, a map with /bore/distortion */
    q.ring_z_tdc = 0.02; /* BDC at 0.107 m, below the last layer */
    rd_error_init(&err);
    rc = rd_lift_validate(&q, &rp, n, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/bore/layers") && strstr(err.message, "0.1069"),
          "map short of the stroke: %s: %s", err.path, err.message);
    q.ring_z_tdc = 0.005;
    distort(&q, 1e-6);
    rd_error_init(&err);
    rc = rd_lift_validate(&q, &rp, n, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/bore/distortion"), "map + distortion: %s: %s",
          err.path, err.message);
    q.bore = (rd_bore){0};
    q.model = RD_LIFT_MODEL_RIGID;
    rd_error_init(&err);
    rc = rd_lift_validate(&q, &rp, n, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/numerics/model"), "map + rigid: %s: %s", err.path,
          err.message);
}

int main(void)
{
    test_map();
    test_validation();
    test_static_start();
    test_modal_full();
    test_segment_events();
    return check_done();
}
