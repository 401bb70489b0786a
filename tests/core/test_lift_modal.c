/* test_lift_modal — the modal lift model (rd_lift_modal.c).
 *
 * References, each independent of the modal code:
 *  - the full model (6 n DOFs, band Newton, rd_lift_model.c): the modal model
 *    with every mode is a change of coordinates of it, so on a small ring
 *    (n = 4, all 18 elastic modes) its flank changes and lift must agree to
 *    the solvers' tolerance, with and without friction;
 *  - convergence in m on a friction scene (n = 8, Coulomb, 1000 rpm), where
 *    the rigid ring misses a twist-driven leave by ~1 deg: the modal error
 *    against the full model must fall as m grows and be small with m near
 *    the full count;
 *  - central differences of its own right-hand side for its Jacobian;
 *  - validation of numerics.modes against the ring. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_lift.h"
#include "rd_lift_internal.h"

static int run(const rd_lift_params *p, int model, int modes, int n, rd_lift_result *r,
               rd_error *err)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params q = *p;
    q.model = model;
    q.modes = modes;
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

static void scene(rd_lift_params *p, int friction, double cycles, double rtol)
{
    rd_lift_params_default(p);
    p->engine.cycles = cycles;
    p->gravity = 1;
    p->friction.model = friction;
    p->estimate_error = 0;
    p->rtol = rtol;
    p->atol = 1e-3 * rtol;
}

/* All modes = the full model.  At rtol 1e-8 both integrations are good to
 * ~1e-3 deg on the flank changes (the full model's rtol/10 estimate there);
 * tolerance 0.01 deg, and the lift at every sample within 1e-3 of the
 * clearance (the two solvers' error norms differ, so agreement is to their
 * tolerance, not bit for bit). */
static void test_all_modes(void)
{
    for (int fric = 0; fric < 2; fric++) {
        rd_lift_params p;
        scene(&p, fric ? RD_FRICTION_COULOMB : RD_FRICTION_NONE, 1.0, 1e-8);
        rd_lift_result a, b;
        rd_error err;
        int rc = run(&p, RD_LIFT_MODEL_MODAL, 18, 4, &a, &err);
        CHECK(rc == RD_OK, "modal, all modes: %s", err.message);
        int rc2 = run(&p, RD_LIFT_MODEL_FULL, 0, 4, &b, &err);
        CHECK(rc2 == RD_OK, "full: %s", err.message);
        if (rc == RD_OK && rc2 == RD_OK) {
            double d = event_diff(&a, &b), dl = 0.0;
            for (int k = 0; k < a.samples; k++)
                dl = fmax(dl, fabs(a.lift[k] - b.lift[k]));
            dl /= p.groove.axial_clearance;
            CHECK(d < 0.01, "friction %d: all-mode modal vs full flank changes differ by %g deg",
                  fric, d);
            CHECK(dl < 1e-3, "friction %d: lift differs by %g c_a", fric, dl);
            CHECK(a.model == RD_LIFT_MODEL_MODAL && a.modes == 18 && a.dof == 24,
                  "model %d modes %d dof %d", a.model, a.modes, a.dof);
            fprintf(stderr,
                    "    all modes, friction %d: %d flank changes, modal - full <= %.4f "
                    "deg, lift %.2e c_a\n",
                    fric, a.n_events, d, dl);
        }
        rd_lift_result_cleanup(&a);
        rd_lift_result_cleanup(&b);
    }
}

/* Convergence in m (n = 8, Coulomb, half a cycle: the twist-driven leave
 * near 327 deg is in it).  Measured at rtol 1e-7 on this half cycle: m = 4:
 * 1.38 deg, 8: 0.009, 16: 0.013, 32: 0.004 (over a whole cycle, where the
 * second such leave is harder: 1.38, 0.19, 0.10, 24: 0.029, 32: 0.004); the
 * full model's own integration error is ~0.005 deg.  Checked: the error at
 * 32 modes is below a quarter of the error at 4 and below 0.03 deg (both
 * runs' integration errors plus margin), and the error never grows by more
 * than 0.01 deg (that integration allowance) from one m to the next. */
static void test_convergence(void)
{
    rd_lift_params p;
    scene(&p, RD_FRICTION_COULOMB, 0.5, 1e-7);
    rd_lift_result f;
    rd_error err;
    int rc = run(&p, RD_LIFT_MODEL_FULL, 0, 8, &f, &err);
    CHECK(rc == RD_OK, "full: %s", err.message);
    if (rc != RD_OK) {
        rd_lift_result_cleanup(&f);
        return;
    }
    int ms[] = {4, 8, 16, 32};
    double e[4];
    for (int j = 0; j < 4; j++) {
        rd_lift_result a;
        rc = run(&p, RD_LIFT_MODEL_MODAL, ms[j], 8, &a, &err);
        CHECK(rc == RD_OK, "modal m = %d: %s", ms[j], err.message);
        e[j] = rc == RD_OK ? event_diff(&a, &f) : 1e9;
        fprintf(stderr,
                "    n = 8, Coulomb, m = %2d: modal - full <= %.4f deg (%ld steps, "
                "full %ld)\n",
                ms[j], e[j], a.steps, f.steps);
        rd_lift_result_cleanup(&a);
    }
    CHECK(e[3] < 0.03 && e[3] < 0.25 * e[0], "m = 32: %g deg vs m = 4: %g deg", e[3], e[0]);
    for (int j = 1; j < 4; j++)
        CHECK(e[j] < e[j - 1] + 0.01, "error grew from m = %d (%g) to m = %d (%g)", ms[j - 1],
              e[j - 1], ms[j], e[j]);
    rd_lift_result_cleanup(&f);
}

/* The modal Jacobian vs central differences of its right-hand side at states
 * that press the lower and upper flanks, twist and move the ring, with
 * Coulomb and Stribeck friction and dynamic gas areas; tolerance 1e-4 as for
 * the full and rigid checks (rounding of the stiff entries ~1e-5). */
static void test_jacobian(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    double deg[] = {0, 400, 720}, above[] = {2e5, 1e6, 2e5}, behind[] = {1e5, 8e5, 1e5},
           below[] = {0, 3e5, 0};
    for (int fm = 1; fm <= 2; fm++)
        for (int st = 0; st < 3; st++) {
            rd_lift_params p;
            rd_lift_params_default(&p);
            p.model = RD_LIFT_MODEL_MODAL;
            p.modes = 6;
            p.gravity = 1;
            p.friction.model = fm;
            p.gas = (rd_gas_params){3, deg, above, behind, below, RD_GAS_AREA_DYNAMIC};
            /* 6 rigid + 6 elastic + 4 corrections = 16 coordinates; the
             * coordinates' scale is ~1 / sqrt(ring mass) ~ 10 m / sqrt(kg) per m,
             * so 1e-6..1e-7 puts segments microns into the flanks */
            double y[32];
            for (int j = 0; j < 32; j++)
                y[j] = (j < 16 ? 1e-7 : 1e-4) * ((j * 7 + st * 3) % 5 - 2.0 + 0.3 * st);
            double e = 1e9;
            rd_error err;
            rd_error_init(&err);
            int rc = rd_lift_jacobian_check(&rp, 8, &p, 3e-6, y, &e, &err);
            CHECK(rc == RD_OK, "modal jacobian check: %s", err.message);
            CHECK(e < 1e-4, "modal, friction %d, state %d: Jacobian differs by %g", fm, st, e);
        }
}

static void test_validation(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.model = RD_LIFT_MODEL_MODAL;
    p.modes = 19;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_validate(&p, &rp, 4, &err);
    CHECK(rc == RD_EINVAL && !strcmp(err.path, "/numerics/modes") &&
              strstr(err.message, "18 elastic modes"),
          "modes 19 on 4 segments: rc %d %s: %s", rc, err.path, err.message);
    p.modes = 18;
    rd_error_init(&err);
    CHECK(rd_lift_validate(&p, &rp, 4, &err) == RD_OK, "modes 18 on 4 segments: %s", err.message);
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 201, &err);
    CHECK(rc == RD_ELIMIT && !strcmp(err.path, "/numerics/model"), "modal at 201 segments: %s",
          err.message);
}

int main(void)
{
    test_validation();
    test_jacobian();
    test_all_modes();
    test_convergence();
    return check_done();
}
