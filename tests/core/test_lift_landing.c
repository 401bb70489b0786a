/* test_lift_landing — the landing laws: the squeeze film (rd_lift_landing.c,
 * /physics/squeeze_film) against its closed form, its Jacobian, its limit
 * and its effect on a lift scene's flank changes; the plastic landing
 * (/contact/landing) against the penalty's flank changes.
 *
 * Closed form: a ring at rest in mid-groove, the piston fixed, gravity on,
 * sinks on the film under its weight F = m g over its face area A.  With
 * inertia negligible (relaxation time m / c = rho h h_e^3 / (mu b^2), below
 * 1e-4 of the sink time here), F = mu b^2 A V / h_e^3 with h_e = h_min + h:
 *     1 / h_e(t)^2 = 1 / h_e0^2 + 2 rho h g t / (mu b^2),
 * (m / A = rho h) and the ring reaches the flank (h = 0) at
 *     t_land = mu b^2 (1 / h_min^2 - 1 / h_e0^2) / (2 rho h g). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_lift.h"
#include "rd_lift_internal.h"

#define G0 9.80665

static void base_params(rd_lift_params *p, double rpm, double cycles)
{
    rd_lift_params_default(p);
    p->model = RD_LIFT_MODEL_FULL;
    p->engine.speed_rpm = rpm;
    p->engine.cycles = cycles;
    p->estimate_error = 0;
}

/* Sinking on the film: h_e(t) at every sample and the landing time. */
static void test_closed_form(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    int n = 8;
    rd_lift_params p;
    base_params(&p, 100.0, 0.5); /* 100 rpm: 0.6 s */
    p.gravity = 1;
    p.squeeze.on = 1;
    p.squeeze.viscosity = 1e-3;
    p.squeeze.min_film = 1e-5;
    p.rtol = 1e-8;
    p.atol = 1e-12;
    double ca = p.groove.axial_clearance, h0 = 0.5 * ca, hm = p.squeeze.min_film;
    double b = rp.radial_width,
           rate = 2.0 * rp.density * rp.axial_height * G0 / (p.squeeze.viscosity * b * b);
    double t_land = (1.0 / (hm * hm) - 1.0 / ((hm + h0) * (hm + h0))) / rate;
    double *y0 = calloc(12 * (size_t)n, sizeof *y0);
    for (int i = 0; i < n; i++)
        y0[12 * i + 2] = h0;
    rd_lift_setup su = {.y0 = y0, .piston_fixed = 1};
    rd_lift_result r;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve_setup(&rp, n, &p, &su, NULL, &r, &err);
    CHECK(rc == RD_OK, "squeeze closed form: %s", err.message);
    if (rc == RD_OK) {
        double w_s = 100.0 * 6.0; /* crank degrees per second */
        double worst = 0.0;
        for (int k = 1; k < r.samples; k++) {
            double t = r.crank_deg[k] / w_s;
            if (t > 0.95 * t_land)
                break; /* the dry penalty takes over at contact */
            double he = hm + r.lift[k];
            double want = 1.0 / sqrt(1.0 / ((hm + h0) * (hm + h0)) + rate * t);
            worst = fmax(worst, fabs(he - want) / want);
        }
        /* inertia (relaxation 4e-5 of the sink time) and the twist from the
         * face's centroid offset (the film under the inner and outer halves
         * differs): measured 1.1e-4 relative; 1e-3 */
        CHECK(worst < 1e-3, "h_e(t) misses the closed form by %.3g (relative)", worst);
        double got = NAN;
        for (int e = 0; e < r.n_events; e++)
            if (r.events[e].kind == RD_EVENT_REACH_LOWER && isnan(got))
                got = r.events[e].touch_deg / w_s; /* where it touched, not the band */
        /* the landing is dated where the mean lift reaches the flank; the
         * tilted face's closer edge meets the stiffer film (h^-3) first and
         * the mean slows: measured 9e-4 relative; 2e-3 */
        CHECK(fabs(got - t_land) < 2e-3 * t_land, "landing at %.6g s, closed form %.6g s", got,
              t_land);
        fprintf(stderr,
                "    squeeze sink: h_e(t) within %.2g of the closed form; landing %.6g s "
                "(closed form %.6g s)\n",
                worst, got, t_land);
    }
    rd_lift_result_cleanup(&r);
    free(y0);
}

/* The law's Jacobian against central differences: faces inside the film,
 * closing in the ramp (v < v_r) and the linear range, one opening (no
 * pressure), for the full and the rigid model.  Tolerance as test_lift's
 * Jacobian test (1e-4: central differences carry ~1e-5 relative rounding);
 * in the cubic ramp their truncation error is (delta / v_r)^2 / r' = 6.5e-5
 * at V = 2/3 v_r (the check's rate step delta = 1e-4 u_reg = 0.09 v_r). */
static void test_jacobian(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    for (int model = 0; model < 2; model++) {
        rd_lift_params p;
        base_params(&p, 1000.0, 1.0);
        p.gravity = 1;
        p.squeeze.on = 1;
        p.squeeze.viscosity = 1e-3;
        p.squeeze.min_film = 1e-6;
        p.model = model ? RD_LIFT_MODEL_RIGID : RD_LIFT_MODEL_FULL;
        double ca = p.groove.axial_clearance,
               vr = 1e-2 * ca * 1000.0 * 2.0 * 3.14159265358979323846 / 60.0;
        double err_max = 1e9;
        rd_error err;
        rd_error_init(&err);
        int rc;
        if (model) {
            double y[6] = {0.1 * ca, 1e-7, 1e-7, -3.0 * vr, 1e-5, 0.0};
            rc = rd_lift_jacobian_check(&rp, 8, &p, 1e-3, y, &err_max, &err);
        } else {
            int n = 6;
            double *y = calloc(12 * (size_t)n, sizeof *y);
            for (int i = 0; i < n; i++) {
                double *q = y + 12 * i, *v = q + 6;
                q[2] = (i % 2 ? 0.9 : 0.05) * ca + 1e-7 * i;
                q[3] = 1e-9 * (i - 2);
                v[2] = (i % 3 == 0 ? (2.0 / 3.0) * vr : (i % 3 == 1 ? -5.0 * vr : 2.0 * vr)) *
                       (i % 2 ? 1.0 : -1.0);
            }
            rc = rd_lift_jacobian_check(&rp, n, &p, 1e-3, y, &err_max, &err);
            free(y);
        }
        CHECK(rc == RD_OK, "squeeze Jacobian: %s", err.message);
        CHECK(err_max < 1e-4, "%s model with the squeeze film: Jacobian differs by %g",
              model ? "rigid" : "full", err_max);
    }
}

/* Flank changes of the thesis scene (1000 rpm, inertia): a film of
 * vanishing viscosity gives the penalty's angles (within 0.01 deg, the
 * runs' integration noise at rtol 1e-8), a real one leaves the leaves
 * (dated by the load's sign change: the film cavitates, it does not hold
 * the ring) and delays every landing. */
static void test_scene(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_result r[3];
    double mu[3] = {0.0, 1e-8, 1e-5};
    int ok = 1;
    for (int k = 0; k < 3; k++) {
        rd_lift_params p;
        base_params(&p, 1000.0, 1.0);
        p.model = RD_LIFT_MODEL_RIGID;
        p.rtol = 1e-8;
        p.atol = 1e-11;
        p.squeeze.on = mu[k] > 0.0;
        p.squeeze.viscosity = mu[k] > 0.0 ? mu[k] : 0.01;
        rd_error err;
        rd_error_init(&err);
        int rc = rd_lift_solve(&rp, 8, &p, NULL, &r[k], &err);
        CHECK(rc == RD_OK, "scene with mu = %g: %s", mu[k], err.message);
        ok = ok && rc == RD_OK;
    }
    if (ok) {
        CHECK(r[1].n_events == r[0].n_events, "vanishing film: %d flank changes, penalty %d",
              r[1].n_events, r[0].n_events);
        double d = 0.0;
        for (int e = 0; e < r[0].n_events && e < r[1].n_events; e++)
            d = fmax(d, fabs(r[1].events[e].crank_deg - r[0].events[e].crank_deg));
        CHECK(d < 0.01, "vanishing film moves flank changes by %.3g deg", d);
        int n = r[2].n_events < r[0].n_events ? r[2].n_events : r[0].n_events;
        CHECK(n >= 4, "with the film only %d flank changes", r[2].n_events);
        for (int e = 0; e < n; e++) {
            const rd_lift_event *a = &r[0].events[e], *s = &r[2].events[e];
            CHECK(a->kind == s->kind, "flank change %d: kind %d with the film, %d without", e,
                  s->kind, a->kind);
            int landing = a->kind == RD_EVENT_REACH_LOWER || a->kind == RD_EVENT_REACH_UPPER;
            if (landing)
                CHECK(s->crank_deg > a->crank_deg + 1.0,
                      "landing %d not delayed by the film: %.3f vs %.3f deg", e, s->crank_deg,
                      a->crank_deg);
            fprintf(stderr, "    flank change %d (kind %d): %.3f deg, with the film %.3f deg\n", e,
                    a->kind, a->crank_deg, s->crank_deg);
        }
        fprintf(stderr, "    steps per cycle: %ld without, %ld with the film (mu = %g Pa s)\n",
                r[0].steps, r[2].steps, mu[2]);
    }
    for (int k = 0; k < 3; k++)
        rd_lift_result_cleanup(&r[k]);
}

/* The plastic landing (contact.landing = plastic) against the penalty's
 * landings on the thesis scene (1000 rpm, inertia): the same flank changes
 * within 0.05 deg (the bound for a landing law; the landing dates
 * are the same roots, the leaves the load's sign changes, and what moves is
 * the settling the arrest skips), for the rigid and the full model. */
static void test_plastic(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    for (int model = 0; model < 2; model++) {
        rd_lift_result r[2];
        int ok = 1;
        for (int k = 0; k < 2; k++) {
            rd_lift_params p;
            base_params(&p, 1000.0, 1.0);
            p.model = model ? RD_LIFT_MODEL_RIGID : RD_LIFT_MODEL_FULL;
            p.landing = k ? RD_LANDING_PLASTIC : RD_LANDING_PENALTY;
            /* dated at the band, a leave is where the lift has risen 1 % of the
             * clearance from rest: atol 1e-9 m (3e-3 of that) left the full
             * model's leaves 0.15 deg apart, the integration's error, not the
             * law's (its rtol/10 estimate says 0.11 deg) */
            p.atol = 1e-11;
            rd_error err;
            rd_error_init(&err);
            int rc = rd_lift_solve(&rp, 8, &p, NULL, &r[k], &err);
            CHECK(rc == RD_OK, "plastic landing: %s", err.message);
            ok = ok && rc == RD_OK;
        }
        if (ok) {
            CHECK(r[0].n_events == r[1].n_events, "%s: %d flank changes plastic, %d penalty",
                  model ? "rigid" : "full", r[1].n_events, r[0].n_events);
            double d = 0.0, dt = 0.0;
            for (int e = 0; e < r[0].n_events && e < r[1].n_events; e++) {
                CHECK(r[0].events[e].kind == r[1].events[e].kind, "flank change %d kind", e);
                d = fmax(d, fabs(r[1].events[e].crank_deg - r[0].events[e].crank_deg));
                dt = fmax(dt, fabs(r[1].events[e].touch_deg - r[0].events[e].touch_deg));
            }
            CHECK(dt < 0.05, "%s: the plastic landing moves the touches by %.3g deg",
                  model ? "rigid" : "full", dt);
            CHECK(d < 0.05, "%s: the plastic landing moves flank changes by %.3g deg",
                  model ? "rigid" : "full", d);
            fprintf(stderr,
                    "    %s: plastic landing moves flank changes by %.3g deg, touches by %.3g "
                    "deg; steps %ld (penalty %ld)\n",
                    model ? "rigid" : "full", d, dt, r[1].steps, r[0].steps);
        }
        for (int k = 0; k < 2; k++)
            rd_lift_result_cleanup(&r[k]);
    }
}

/* Out-of-range film parameters and an unknown landing name their field. */
static void test_validation(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_lift_params p;
    base_params(&p, 1000.0, 1.0);
    p.squeeze.on = 1;
    p.squeeze.min_film = 0.0;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL, "min_film 0 accepted");
    CHECK(strstr(err.path, "/physics/squeeze_film/min_film") != NULL, "error names %s", err.path);
    p.squeeze.min_film = 1e-6;
    p.squeeze.viscosity = 100.0;
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && strstr(err.path, "/physics/squeeze_film/viscosity") != NULL,
          "viscosity 100 Pa s: %s", err.message);
    p.squeeze.viscosity = 0.01;
    p.landing = 7;
    rd_error_init(&err);
    rc = rd_lift_validate(&p, &rp, 8, &err);
    CHECK(rc == RD_EINVAL && strcmp(err.path, "/contact/landing") == 0, "landing 7: %s",
          err.message);
}

int main(void)
{
    test_validation();
    test_jacobian();
    test_closed_form();
    test_scene();
    test_plastic();
    return check_done();
}
