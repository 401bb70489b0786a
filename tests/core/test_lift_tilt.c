/* test_lift_tilt — the piston tilt about the pin axis (engine.piston_tilt_deg
 * and the engine.piston_tilt table; rd_lift_tilt.c and the tilted frame's
 * pseudo-forces in rd_lift_forces.c).
 *
 * References:
 *  - the spline: through its points, periodic, and its derivatives against
 *    central differences of itself;
 *  - a closed-form motion: the free ring in mid-groove (piston fixed, no
 *    gravity, no friction) with the groove tilting as a table.  No force but
 *    the frame's acts, so the ring keeps the tilt rate it had at t = 0 in the
 *    cylinder frame; measured from the groove (the model's frame) every
 *    segment rises by (beta(0) + beta'(0) t - beta(t)) x_i (rad, x_i its
 *    position along the gap direction).  Only the rigid tilt mode is excited
 *    (the Euler force is mass-proportional in that mode, M-orthogonal to the
 *    elastic ones), so the full model must follow it to its tolerance;
 *  - the modal model with every mode against the full model on a tilted
 *    friction scene (a change of coordinates);
 *  - auto never runs the rigid ring on a tilted scene, and rigid asked for
 *    one is refused naming the fields. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_lift.h"
#include "rd_lift_internal.h"

#define PI 3.14159265358979323846

static const double tab_deg[] = {0.0, 180.0, 360.0, 540.0}, tab_tilt[] = {0.0, 0.005, 0.0, -0.005};

static void tilt_table(rd_lift_params *p)
{
    p->engine.tilt_points = 4;
    p->engine.tilt_crank_deg = tab_deg;
    p->engine.tilt_deg = tab_tilt;
}

/* Through the points (to rounding), periodic over 720 deg, and derivatives
 * within 1e-6 relative of central differences (h = 1e-3 deg: the cubic's
 * truncation error ~h^2 y''' ~ 1e-9 of its scale, rounding ~1e-13 / h). */
static void test_spline(void)
{
    rd_lift_params p;
    rd_lift_params_default(&p);
    tilt_table(&p);
    p.engine.piston_tilt_deg = 0.1;
    double b, d1, d2, bp, bm, d1p, d1m, x, y;
    for (int k = 0; k < 4; k++) {
        rd_engine_tilt_at(&p.engine, tab_deg[k], &b, &d1, &d2);
        CHECK(fabs(b - 0.1 - tab_tilt[k]) < 1e-15, "spline at point %d: %g", k, b);
        rd_engine_tilt_at(&p.engine, tab_deg[k] + 1440.0, &y, &d1, &d2);
        CHECK(fabs(y - b) < 1e-15, "not periodic at point %d", k);
    }
    double worst = 0.0, h = 1e-3;
    for (double a = 3.0; a < 720.0; a += 37.0) {
        rd_engine_tilt_at(&p.engine, a, &x, &d1, &d2);
        rd_engine_tilt_at(&p.engine, a + h, &bp, &d1p, &y);
        rd_engine_tilt_at(&p.engine, a - h, &bm, &d1m, &y);
        worst = fmax(worst, fabs((bp - bm) / (2 * h) - d1) / 1e-4);
        worst = fmax(worst, fabs((d1p - d1m) / (2 * h) - d2) / 1e-6);
    }
    /* scales: |beta'| ~ 1e-4 deg/deg, |beta''| ~ 1e-6 deg/deg^2 */
    CHECK(worst < 1e-4, "spline derivatives differ from central differences by %g", worst);
}

typedef struct track {
    const rd_lift_params *p;
    double R, omega, worst, amp;
    int n;
    const double *cx; /* n: cos of each segment's angle */
} track;

static void sample(void *vctx, double t, const double *y)
{
    track *tr = vctx;
    double deg = tr->omega * t * 180.0 / PI, b, d1, d2, b0, d10, d20;
    rd_engine_tilt_at(&tr->p->engine, deg, &b, &d1, &d2);
    rd_engine_tilt_at(&tr->p->engine, 0.0, &b0, &d10, &d20);
    double rel = (b0 + d10 * deg - b) * PI / 180.0; /* rad */
    for (int i = 0; i < tr->n; i++) {
        double want = 0.5 * tr->p->groove.axial_clearance + rel * tr->R * tr->cx[i];
        tr->worst = fmax(tr->worst, fabs(y[12 * i + 2] - want));
        tr->amp = fmax(tr->amp, fabs(rel * tr->R * tr->cx[i]));
    }
}

/* The closed-form motion (file comment), a quarter cycle at 1000 rpm.
 * Tolerance 1 % of the motion's amplitude (~0.5 um; measured 4e-4 of it): rtol 1e-8 on a motion of
 * that size, ~1e-4 relative, plus the second-order terms the model drops
 * (beta'^2 x ~ 1e-9 of the tilt acceleration's effect here). */
static void test_free_ring(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    int n = 12;
    rd_lift_params p;
    rd_lift_params_default(&p);
    tilt_table(&p);
    p.engine.cycles = 0.25;
    p.step_deg = 2.0;
    p.estimate_error = 0;
    p.model = RD_LIFT_MODEL_FULL;
    p.rtol = 1e-8;
    p.atol = 1e-12;
    double *y0 = calloc(12 * (size_t)n, sizeof *y0), cx[12];
    double R = 0.5 * (rp.diameter - rp.radial_width);
    for (int i = 0; i < n; i++)
        y0[12 * i + 2] = 0.5 * p.groove.axial_clearance;
    rd_lift_setup su = {.y0 = y0, .piston_fixed = 1};
    /* segment angles: equal arcs between the gap ends (rd_ring.h) */
    double gap = rp.closed_gap / R, span = 2.0 * PI - gap;
    for (int i = 0; i < n; i++)
        cx[i] = cos(0.5 * gap + (i + 0.5) * span / n);
    track tr = {.p = &p, .R = R, .omega = 1000.0 * PI / 30.0, .n = n, .cx = cx};
    su.sample = sample;
    su.ctx = &tr;
    rd_lift_result r;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve_setup(&rp, n, &p, &su, NULL, &r, &err);
    CHECK(rc == RD_OK, "free tilted ring: %s", err.message);
    CHECK(tr.amp > 1e-7 && tr.worst < 0.01 * tr.amp,
          "free tilted ring: segments off the closed form by %g m (amplitude %g m)", tr.worst,
          tr.amp);
    fprintf(stderr, "    free ring in a tilting groove: closed form - full <= %.3g m of %.3g m\n",
            tr.worst, tr.amp);
    rd_lift_result_cleanup(&r);
    free(y0);
}

/* Modal with all modes = full on a tilted friction scene (n = 4, rtol 1e-8:
 * tolerance 0.01 deg as test_lift_modal's), and the tilt visible: the
 * segments' lifts differ (lift_max - lift_min) while the untilted ring's
 * stay together. */
static void test_modal_full_tilted(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.engine.cycles = 0.5;
    p.engine.piston_tilt_deg = 0.05;
    static const double deg[] = {0.0, 90.0, 270.0, 450.0, 630.0},
                        tl[] = {0.0, 0.1, -0.1, 0.1, -0.1};
    p.engine.tilt_points = 5;
    p.engine.tilt_crank_deg = deg;
    p.engine.tilt_deg = tl;
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
    CHECK(rc == RD_OK, "modal tilted: %s", err.message);
    p.model = RD_LIFT_MODEL_AUTO;
    int rc2 = rd_lift_solve(&rp, 4, &p, NULL, &b, &err);
    CHECK(rc2 == RD_OK && b.model == RD_LIFT_MODEL_FULL && strstr(b.why, "tilt"),
          "auto tilted: rc %d model %d (%s) %s", rc2, b.model, b.why, err.message);
    if (rc == RD_OK && rc2 == RD_OK) {
        double d = 0.0, spread = 0.0;
        if (a.n_events != b.n_events)
            d = 1e9;
        for (int i = 0; i < a.n_events && d < 1e9; i++)
            d = a.events[i].kind != b.events[i].kind
                    ? 1e9
                    : fmax(d, fabs(a.events[i].crank_deg - b.events[i].crank_deg));
        for (int k = 0; k < b.samples; k++)
            spread = fmax(spread, b.lift_max[k] - b.lift_min[k]);
        CHECK(d < 0.01, "tilted: all-mode modal vs full flank changes differ by %g deg", d);
        /* the tilt rate ~1e-3 deg/deg moves the ring's edge (x ~ 40 mm) by ~1 um
         * per degree of crank against its inertia: its segments spread by
         * more than 1 % of the clearance in flight */
        CHECK(spread > 0.01 * p.groove.axial_clearance, "tilted: segments' spread %g m", spread);
        fprintf(stderr,
                "    tilted Coulomb scene: %d flank changes, modal(all) - full <= %.4f "
                "deg, lift spread %.3f c_a\n",
                b.n_events, d, spread / p.groove.axial_clearance);
    }
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

static void test_validation(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.engine.piston_tilt_deg = 0.1;
    p.model = RD_LIFT_MODEL_RIGID;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/numerics/model") &&
              strstr(err.message, "/engine/piston_tilt_deg"),
          "rigid + tilt: rc %d %s: %s", rc, err.path, err.message);
    p.model = RD_LIFT_MODEL_AUTO;
    p.engine.piston_tilt_deg = 3.0;
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/engine/piston_tilt_deg"), "tilt 3 deg: %s",
          err.message);
    p.engine.piston_tilt_deg = 0.0;
    static const double bad[] = {0.0, 10.0, 5.0}, vals[] = {0, 0, 0};
    p.engine.tilt_points = 3;
    p.engine.tilt_crank_deg = bad;
    p.engine.tilt_deg = vals;
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/engine/piston_tilt/crank_deg"),
          "tilt table not increasing: %s", err.message);
}

int main(void)
{
    test_validation();
    test_spline();
    test_free_ring();
    test_modal_full_tilted();
    return check_done();
}
