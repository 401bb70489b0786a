/*
 * test_film — the ring-liner oil film (core/liner/rd_film*.c) against
 * closed forms and limits:
 *   - Greenwood-Tripp: F_5/2(0) = 0.61663, F_2(0) = 0.5 (MODEL.md), the
 *     table and the closed form F_2 against a trapezoid rule in s written
 *     here, at lambda = 1, 2, 3, 4 within 1e-4 relative (and 1e-6 between
 *     the table and its quadrature over the table's range);
 *   - the flow factors -> 1 and 0 far from the roughness, the expected gap
 *     -> h;
 *   - Martin's rigid cylinder: a barrel face sliding steadily on a smooth
 *     liner carries W = C eta U R / h0 with the Reynolds condition;
 *     C = 2.4476 for one surface moving at U (Martin 1916; 4.895 with the
 *     mean speed (u1 + u2)/2), computed here by quadrature of the
 *     integrated Reynolds equation, and the solver's finite face against
 *     the same quadrature on that face;
 *   - the squeeze film of a flat face approaching the liner under a
 *     constant load: 1/h^2 = 1/h_s^2 + 2 W t / (eta L^3).
 */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "rd_film.h"
#include "rd_film_track.h"

/* (1/sqrt(2 pi)) int_l^{l+20} (s - l)^n e^{-s^2/2} ds by the trapezoid rule
 * in t = (s - l)^(1/2)... written plainly: in s with 400000 panels. */
static double gt_trapezoid(double n, double l)
{
    int m = 400000;
    double hi = fmax(l, 0.0) + 20.0, h = (hi - l) / m, sum = 0.0;
    for (int k = 0; k <= m; k++) {
        double s = l + k * h, w = (k == 0 || k == m) ? 0.5 : 1.0;
        sum += w * pow(s - l, n) * exp(-0.5 * s * s);
    }
    return sum * h / sqrt(2.0 * M_PI);
}

static void greenwood_tripp(void)
{
    CHECK_ABS(rd_film_gt_f52(0.0), 0.61663, 1e-5, "F_5/2(0) (MODEL.md)");
    CHECK_ABS(rd_film_gt_f2(0.0), 0.5, 1e-12, "F_2(0)");
    for (int l = 1; l <= 4; l++) {
        double f52 = gt_trapezoid(2.5, l), f2 = gt_trapezoid(2.0, l);
        CHECK_REL(rd_film_gt_f52(l), f52, 1e-4, "F_5/2(%d) table vs trapezoid", l);
        CHECK_REL(rd_film_gt_f2(l), f2, 1e-4, "F_2(%d) closed form vs trapezoid", l);
        CHECK_REL(rd_film_gt_quad(2.0, l), f2, 1e-6, "F_2(%d) quadrature vs trapezoid", l);
    }
    double worst = 0.0;
    for (double l = -3.9; l < 10.0; l += 0.0137) {
        double q = rd_film_gt_quad(2.5, l), t = rd_film_gt_f52(l);
        worst = fmax(worst, fabs(t - q) / q);
    }
    CHECK(worst < 1e-6, "the F_5/2 table is %.3g off its quadrature (relative)", worst);
    double wg = 0.0, wd = 0.0, wf = 0.0;
    for (double H = -3.9; H < 11.9; H += 0.00731) {
        double g, dg, f52, dref, gref = rd_film_gap(H, &dref);
        rd_film_node_laws(H, &g, &dg, &f52);
        wg = fmax(wg, fabs(g - gref) / gref);
        wd = fmax(wd, fabs(dg - dref));
        wf = fmax(wf, fabs(f52 - rd_film_gt_f52(H)) / rd_film_gt_f52(H));
    }
    CHECK(wg < 1e-6 && wd < 1e-9 && wf < 1e-12,
          "the node laws' tables: gap %.3g, slope %.3g, F_5/2 %.3g off the direct laws", wg, wd,
          wf);
    CHECK(rd_film_gt_f52(20.0) == 0.0, "F_5/2 beyond the table's range is 0");
    /* slope: dF_5/2/dl = -2.5 F_3/2 */
    double d = (rd_film_gt_f52(1.5 + 1e-5) - rd_film_gt_f52(1.5 - 1e-5)) / 2e-5;
    CHECK_REL(d, -2.5 * gt_trapezoid(1.5, 1.5), 1e-4, "dF_5/2/dlambda at 1.5");
}

static void flow_factors(void)
{
    CHECK_ABS(rd_film_phi_x(60.0), 1.0, 1e-12, "phi_x far from the roughness");
    CHECK(rd_film_phi_s(60.0) < 1e-6, "phi_s far from the roughness: %g", rd_film_phi_s(60.0));
    CHECK_ABS(rd_film_phi_x(1.0), 1.0 - 0.9 * exp(-0.56), 1e-15, "phi_x(1), Patir-Cheng");
    CHECK_REL(rd_film_phi_s(5.0), rd_film_phi_s(5.0 + 1e-9), 2e-3, "phi_s continuous at H = 5");
    double g, gap = rd_film_gap(30.0, &g);
    CHECK_ABS(gap, 30.0, 1e-12, "expected gap -> h");
    CHECK_ABS(g, 1.0, 1e-12, "its slope -> 1");
    CHECK_ABS(rd_film_gap(0.0, NULL), 1.0 / sqrt(2.0 * M_PI), 1e-15, "expected gap at contact");
}

/* Martin: the integrated Reynolds equation for h = h0 (1 + X^2), x =
 * sqrt(2 R h0) X, from an inlet at X_in (p = 0) with the Reynolds
 * condition at X_s: p(X) = K int_{X_in}^X (t^2 - X_s^2) / (1 + t^2)^3 dt,
 * K = 6 eta U sqrt(2 R h0) / h0^2, and W = sqrt(2 R h0) int p dX =
 * 12 (eta U R / h0) w, w = int_{X_in}^{X_s} P dX with P = p / K.
 * Returns C = 12 w (W = C eta U R / h0) by Simpson in X. */
static double martin_c(double X_in)
{
    double lo = 0.05, hi = 2.0, Xs = 0.5;
    int m = 200000;
    for (int it = 0; it < 60; it++) { /* P(X_s) = 0, bisection */
        Xs = 0.5 * (lo + hi);
        double h = (Xs - X_in) / m, P = 0.0;
        for (int k = 0; k <= m; k++) {
            double t = X_in + k * h, w = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
            P += w * (t * t - Xs * Xs) / pow(1.0 + t * t, 3.0);
        }
        P *= h / 3.0;
        if (P > 0.0) /* P(X_s) falls as X_s grows */
            lo = Xs;
        else
            hi = Xs;
    }
    /* w = int P dX = int_{X_in}^{X_s} (X_s - t) dP/dt dt (by parts, P(X_in) = P(X_s) = 0) */
    double h = (Xs - X_in) / m, w = 0.0;
    for (int k = 0; k <= m; k++) {
        double t = X_in + k * h, q = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        w += q * (Xs - t) * (t * t - Xs * Xs) / pow(1.0 + t * t, 3.0);
    }
    return 12.0 * w * h / 3.0;
}

static rd_lube_params smooth_lube(void)
{
    return (rd_lube_params){.asperity_density = 5e8,
                            .asperity_radius = 3e-4,
                            .boundary_coefficient = 0.1,
                            .composite_modulus = 1e11};
}

static void martin(void)
{
    double C_inf = martin_c(-2000.0);
    CHECK_REL(C_inf, 2.4476, 2e-4, "Martin's constant, one surface moving (4.895 / 2)");
    /* a barrel face: L 2 mm, crown 10 um at the edges: R = (L/2)^2 / (2 c) = 0.05 m */
    double L = 2e-3, c = 10e-6, R = 0.25 * L * L / (2.0 * c), h0 = 1e-6, eta = 0.01, U = 10.0;
    rd_face_params face = {.profile = RD_FACE_BARREL, .crown = c, .roughness_rq = 1e-12};
    rd_lube_params lube = smooth_lube();
    double C_face = martin_c(-sqrt(c / h0));
    int nodes[3] = {2001, 401, RD_FILM_NODES};
    double tol[3] = {1e-3, 1e-3, 2e-3};
    for (int k = 0; k < 3; k++) {
        rd_film f;
        rd_error err = {0};
        CHECK(!rd_film_init(&f, &face, L, nodes[k], 1e-12, &lube, 2e11, 0.3, &err), "%s",
              err.message);
        rd_film_out o;
        rd_film_solve(&f, h0, 0.0, U, eta, 0.0, 0.0, &o);
        CHECK_REL(o.W, C_face * eta * U * R / h0, tol[k], "barrel face, %d nodes (C = %.5f)",
                  nodes[k], C_face);
        CHECK(o.Wa == 0.0, "no asperity load on smooth surfaces: %g", o.Wa);
        /* reversed sliding: the mirror image, the same load */
        rd_film_out r;
        rd_film_solve(&f, h0, 0.0, -U, eta, 0.0, 0.0, &r);
        CHECK_REL(r.W, o.W, 1e-9, "reversed sliding, %d nodes", nodes[k]);
        rd_film_free(&f);
    }
}

typedef struct sq_loads {
    double W, eta;
} sq_loads;

static void sq_at(void *ctx, double t, double *U, double *eta, double *W, double *plo, double *phi)
{
    const sq_loads *s = ctx;
    (void)t;
    *U = 0.0;
    *eta = s->eta;
    *W = s->W;
    *plo = *phi = 0.0;
}

static void squeeze(void)
{
    double L = 1e-3, eta = 0.01, W = 1000.0, hs = 2e-6;
    rd_face_params face = {.profile = RD_FACE_FLAT, .edge_radius = 0.0, .roughness_rq = 1e-12};
    rd_lube_params lube = smooth_lube();
    rd_film f;
    rd_error err = {0};
    CHECK(!rd_film_init(&f, &face, L, RD_FILM_NODES, 1e-12, &lube, 2e11, 0.3, &err), "%s",
          err.message);
    sq_loads s = {W, eta};
    rd_film_loads ld = {sq_at, &s};
    double t_end = 3.0 * eta * L * L * L / (2.0 * W * hs * hs); /* h falls to hs / 2 */
    rd_film_track tr;
    CHECK(!rd_film_track_run(&f, &ld, t_end, t_end / 50.0, t_end, 0.0, hs, &tr, &err), "%s",
          err.message);
    double worst = 0.0;
    for (int k = 1; k <= tr.steps; k++) {
        double t = tr.pt[k].t, h = 1.0 / sqrt(1.0 / (hs * hs) + 2.0 * W * t / (eta * L * L * L));
        worst = fmax(worst, fabs(tr.pt[k].h0 - h) / h);
    }
    CHECK(worst < 1e-3, "squeeze film of a flat face: %.3g from the closed form (%d steps)", worst,
          tr.steps);
    CHECK_REL(tr.pt[tr.steps].h0, 0.5 * hs, 1e-3, "the film halves at t_end");
    rd_film_track_free(&tr);
    rd_film_free(&f);
}

int main(void)
{
    greenwood_tripp();
    flow_factors();
    martin();
    squeeze();
    return check_done();
}
