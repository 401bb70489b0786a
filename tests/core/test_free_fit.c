/* test_free_fit — a measured free shape (rd_static.h's rd_free_table)
 * fitted back to the pressure the ring was made for (rd_free_shape_fit),
 * against references written here:
 *  - the free shape of a given pressure integrated here as a planar
 *    elastica (curvature 1/R - M / (E I), M from the pressure summed from
 *    the free end in closed form, the order-1 term that balances a split
 *    ring's pressure added as a continuous integral): sampled as a
 *    table about a shifted, turned centre, the fit must give back F_t, the
 *    orders, the centre and the turn; whole and mirrored tables, uniform,
 *    positive ovality with an odd order, and twice the F_t the fit starts
 *    from;
 *  - the whole path: the table, fitted, closed into a round bore by the
 *    contact analysis, gives back the pressure the elastica was made with;
 *  - the standard errors against the true scatter: 40 tables with 1 um of
 *    normal noise; each order's error against the noise-free fit is within
 *    2 standard errors in >= 90 % of the cases and their RMS within x3;
 *  - bad tables: too few points, angles not increasing, one side short of
 *    the gap, fit_order out of range, a radius far off, a point in the gap,
 *    the tips turned in; and a circle, whose pressure falls below 0. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_static.h"
#include "seeded_normal.h"

#define PI 3.14159265358979323846

typedef struct design {
    double Ft;
    int K;
    int order[4];
    double amp[4];
} design;

static double w_of(const design *d, double th)
{
    double w = 1.0;
    for (int k = 0; k < d->K; k++)
        w += d->amp[k] * cos(d->order[k] * th);
    return w;
}

#define EL_M 24000 /* steps over the half ring */

/* The half ring's running face from the point opposite the gap (j = EL_M)
 * to the tip (j = 0), closed ring centred at 0, the back at (R, 0). */
static void elastica_face(const rd_ring_params *p, const design *d, double *fx, double *fy)
{
    double b = p->radial_width, h = p->axial_height, R = 0.5 * (p->diameter - b), r_o = R + 0.5 * b,
           EI = p->youngs_modulus * h * b * b * b / 12.0, q = 2.0 * d->Ft / p->diameter,
           phib = PI - 0.5 * p->closed_gap / R, dpsi = phib / EL_M;
    /* the order-1 balance over the split arc: int (w + c cos) cos = 0 */
    double wc = 0.0, cc = 0.0;
    for (int j = 0; j <= EL_M; j++) {
        double th = j * dpsi, t = (j == 0 || j == EL_M) ? 0.5 : 1.0;
        wc += t * w_of(d, th) * cos(th);
        cc += t * cos(th) * cos(th);
    }
    double c = -wc / cc;
    static double Mo[EL_M + 1], V[EL_M + 1];
    double Ic = 0.0, Is = 0.0; /* int_0^psi W(phib - u) (cos u, sin u) du, trapezoid */
    double Wp = w_of(d, phib) + c * cos(phib);
    Mo[0] = 0.0;
    for (int j = 1; j <= EL_M; j++) {
        double u = j * dpsi, th = phib - u, W = w_of(d, th) + c * cos(th);
        Ic += 0.5 * dpsi * (Wp * cos(u - dpsi) + W * cos(u));
        Is += 0.5 * dpsi * (Wp * sin(u - dpsi) + W * sin(u));
        Wp = W;
        Mo[j] = q * r_o * R * (sin(u) * Ic - cos(u) * Is);
        V[j] = q * r_o * (cos(u) * Ic + sin(u) * Is);
    }
    /* from the back: tangent pi/2, position (R, 0); trapezoid on the arc */
    double a = 0.5 * PI, X = R, Y = 0.0, ds = R * dpsi, EA = p->youngs_modulus * b * h,
           kGA = p->youngs_modulus / (2.0 * (1.0 + p->poisson_ratio)) * b * h * 5.0 / 6.0;
    fx[EL_M] = X + 0.5 * b * sin(a);
    fy[EL_M] = Y - 0.5 * b * cos(a);
    for (int j = EL_M; j > 0; j--) {
        double k0 = 1.0 / R - Mo[j] / EI, k1 = 1.0 / R - Mo[j - 1] / EI;
        double a1 = a + 0.5 * ds * (k0 + k1);
        a1 -= (V[j - 1] - V[j]) / kGA;
        double st = 1.0 + 0.5 * (Mo[j] + Mo[j - 1]) / (R * EA);
        X += 0.5 * ds * st * (cos(a) + cos(a1));
        Y += 0.5 * ds * st * (sin(a) + sin(a1));
        a = a1;
        fx[j - 1] = X + 0.5 * b * sin(a);
        fy[j - 1] = Y - 0.5 * b * cos(a);
    }
}

/* A table of the elastica's face every `every` steps from the back to 2 deg
 * of arc short of the tip: mirrored (theta >= 0), or whole, measured about
 * the centre C and with its angles' origin turned by rot (rad). */
static void table_of(const rd_ring_params *p, const design *d, int whole, const double C[2],
                     double rot, double noise, uint64_t seed, rd_free_table *t)
{
    static double fx[EL_M + 1], fy[EL_M + 1];
    elastica_face(p, d, fx, fy);
    int every = 150, stop = (int)(2.0 / 180.0 * EL_M) + 1, n = 0;
    double th[400], r[400];
    for (int j = EL_M; j >= stop; j -= every) {
        th[n] = atan2(fy[j], fx[j]);
        r[n++] = hypot(fx[j], fy[j]);
    }
    memset(t, 0, sizeof *t);
    t->fit_order = 6;
    uint64_t s = seed;
    for (int side = whole ? -1 : 1; side <= 1; side += 2)
        for (int i = 0; i < n; i++) {
            int k = side < 0 ? n - 1 - i : i;
            if (side < 0 && k == 0)
                continue; /* the back once */
            double X = r[k] * cos(side * th[k]) - C[0], Y = r[k] * sin(side * th[k]) - C[1];
            double a = atan2(Y, X) - rot;
            t->theta_deg[t->n_points] = (fabs(a) < 1e-12 ? 0.0 : a) * 180.0 / PI;
            t->radius[t->n_points++] = hypot(X, Y) + noise * seeded_normal(&s);
        }
}

static int fit(const rd_ring_params *p, int n, const rd_free_table *t, rd_free_fit *f,
               rd_error *err)
{
    rd_static_opts so;
    rd_static_opts_default(&so);
    so.estimate_error = 0;
    rd_error_init(err);
    return rd_free_shape_fit(p, n, t, &so, NULL, f, err);
}

/* The fitted a_k of order k (0 if not fitted). */
static double amp_of(const rd_free_fit *f, int k, double *se)
{
    for (int q = 0; q < f->shape.n_orders; q++)
        if (f->shape.order[q] == k) {
            *se = f->amplitude_se[q];
            return f->shape.amplitude[q];
        }
    *se = 0.0;
    return 0.0;
}

/* The worst |fitted a_k - designed a_k| over the fitted orders. */
static double worst_order(const rd_free_fit *f, const design *d)
{
    double worst = 0.0;
    for (int k = 2; k <= 6; k++) {
        double se, want = 0.0;
        for (int q = 0; q < d->K; q++)
            want += d->order[q] == k ? d->amp[q] : 0.0;
        worst = fmax(worst, fabs(amp_of(f, k, &se) - want));
    }
    return worst;
}

/* The worst of the chain's error estimates over F_t (relative) and the orders. */
static double worst_estimate(const rd_free_fit *f)
{
    double w = f->tangential_force_error / f->tangential_force;
    for (int q = 0; q < f->shape.n_orders; q++)
        w = fmax(w, f->amplitude_error[q]);
    return w;
}

static void recovers(const char *what, const design *d, int whole, int order, double Ct, double rot)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    static rd_free_table t;
    double C[2] = {Ct, whole ? -0.6 * Ct : 0.0};
    table_of(&p, d, whole, C, whole ? rot : 0.0, 0.0, 1, &t);
    t.fit_order = order;
    rd_free_fit f;
    rd_error err;
    int rc = fit(&p, 160, &t, &f, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    if (rc != RD_OK)
        return;
    double wo = worst_order(&f, d), wf = fabs(f.tangential_force / d->Ft - 1.0);
    double est = worst_estimate(&f), tru = fmax(wo, wf);
    printf("%s (%d points, K = %d): F_t %.6g N (want %g), worst |a_k - want| %.3g; the chain's "
           "estimate %.3g against the true %.3g; centre (%.4g, %.4g) um (table's %.4g, %.4g), "
           "turn %.4g deg (table's %.4g), residual rms %.3g nm, max %.3g nm, %d iterations\n",
           what, t.n_points, order, f.tangential_force, d->Ft, wo, est, tru, 1e6 * f.centre[0],
           1e6 * f.centre[1], 1e6 * C[0], 1e6 * C[1], f.rotation_deg, whole ? rot * 180 / PI : 0.0,
           1e9 * f.residual_rms, 1e9 * f.residual_max, f.iterations);
    CHECK_REL(f.tangential_force, d->Ft, 2e-3, "%s: F_t", what);
    CHECK(wo < 2e-3, "%s: the orders within 0.2 %% of p0 (%.3g)", what, wo);
    CHECK(est > tru / 3.0 && est < 3.0 * tru, "%s: the chain's estimate %.3g tracks %.3g (x3)",
          what, est, tru);
    /* the centre in the fitted shape's frame, whose back the chain holds
     * within a micrometre of the closed ring's */
    CHECK(fabs(f.centre[0] - C[0]) < 1e-6 && fabs(f.centre[1] - C[1]) < 1e-7,
          "%s: the centre within 1 um", what);
    CHECK(fabs(f.rotation_deg - (whole ? rot * 180 / PI : 0.0)) < 1e-3, "%s: the turn", what);
    CHECK(f.residual_rms < 2e-9, "%s: the residual below 2 nm (%.3g)", what, f.residual_rms);
}

/* The whole path: the table, fitted, closed into a round bore by the
 * contact analysis (a different solve: Newton with the contact law) gives
 * back the pressure the elastica was made with, in 10 deg bins. */
static void closed_again(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    design oval = {.Ft = 10.0, .K = 2, .order = {2, 3}, .amp = {0.15, -0.2}};
    static rd_free_table t;
    double C[2] = {0.0, 0.0};
    table_of(&p, &oval, 0, C, 0.0, 0.0, 1, &t);
    rd_free_fit f;
    rd_error err;
    int rc = fit(&p, 160, &t, &f, &err);
    CHECK(rc == RD_OK, "closed again: %s", err.message);
    if (rc != RD_OK)
        return;
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    o.free_shape = &f.shape;
    rd_static_opts so;
    rd_static_opts_default(&so);
    so.estimate_error = 0;
    rd_ring_params q = p;
    q.tangential_force = f.tangential_force;
    rd_contact_result c;
    memset(&c, 0, sizeof c);
    rc = rd_contact_solve(&q, 80, &o, &so, NULL, &c, &err);
    CHECK(rc == RD_OK, "closed again: %s", err.message);
    double p0 = 2.0 * oval.Ft / (p.diameter * p.axial_height), worst = 0.0;
    double R = 0.5 * (p.diameter - p.radial_width), s = 0.5 * p.closed_gap / R;
    for (int b = 0; rc == RD_OK && b < RD_CONTACT_BINS; b++) {
        double lo = fmax(b * 10.0 * PI / 180.0, s),
               hi = fmin((b + 1) * 10.0 * PI / 180.0, 2 * PI - s), m = 0.0;
        for (int k = 0; k < 400; k++)
            m += w_of(&oval, lo + (hi - lo) * (k + 0.5) / 400 - PI) / 400;
        worst = fmax(worst, fabs(c.bin_pressure[b] / p0 - m));
    }
    printf("a measured free shape closed in the round bore: worst |p - p_made| = %.4g p0 in the "
           "10 deg bins; largest light gap %.3g m\n",
           worst, c.max_clearance);
    CHECK(rc == RD_OK && worst < 0.01, "closed again: the pressure within 1 %% of p0 (%.4g)",
          worst);
    rd_contact_result_cleanup(&c);
}

/* The standard errors against the scatter they claim: 30 tables with
 * 1 um of normal noise on the radius; each parameter's difference from the
 * noise-free fit against its standard error. */
static void scatter(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    design oval = {.Ft = 10.0, .K = 2, .order = {2, 3}, .amp = {0.15, -0.2}};
    static rd_free_table t;
    double C[2] = {1e-4, 0.0}, sum_e2 = 0.0, sum_s2 = 0.0;
    rd_free_fit clean, f;
    rd_error err;
    table_of(&p, &oval, 1, C, 0.0, 0.0, 1, &t);
    int rc = fit(&p, 40, &t, &clean, &err), within = 0, cases = 0;
    CHECK(rc == RD_OK, "scatter: %s", err.message);
    for (int seed = 1; rc == RD_OK && seed <= 30; seed++) {
        table_of(&p, &oval, 1, C, 0.0, 1e-6, 1000u + seed, &t);
        if ((rc = fit(&p, 40, &t, &f, &err)) != RD_OK)
            break;
        for (int q = -1; q < f.shape.n_orders; q++) {
            double e = q < 0 ? f.tangential_force - clean.tangential_force
                             : f.shape.amplitude[q] - clean.shape.amplitude[q];
            double se = q < 0 ? f.tangential_force_se : f.amplitude_se[q];
            if (q < 0) { /* in units of p0, as the orders */
                e /= oval.Ft;
                se /= oval.Ft;
            }
            within += fabs(e) <= 2.0 * se;
            cases++;
            sum_e2 += e * e;
            sum_s2 += se * se;
        }
    }
    CHECK(rc == RD_OK, "scatter: %s", err.message);
    printf("1 um of scatter on %d points: standard errors F_t %.3g N", t.n_points,
           f.tangential_force_se);
    for (int q = 0; q < f.shape.n_orders; q++)
        printf(", a_%d %.2g", f.shape.order[q], f.amplitude_se[q]);
    printf("\n");
    double ratio = sqrt(sum_e2 / fmax(sum_s2, 1e-300));
    printf("1 um of scatter, 30 tables: %d of %d parameters within 2 standard errors; RMS error / "
           "RMS standard error %.3g\n",
           within, cases, ratio);
    CHECK(within >= 0.9 * cases, "within 2 standard errors in >= 90 %% (%d of %d)", within, cases);
    CHECK(ratio > 1.0 / 3.0 && ratio < 3.0, "the standard errors' size within x3 (%.3g)", ratio);
}

static void bad(const char *what, const rd_free_table *t, const char *path)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_free_fit f;
    rd_error err;
    int rc = fit(&p, 40, t, &f, &err);
    CHECK(rc == RD_EINVAL && strncmp(err.path, path, strlen(path)) == 0,
          "%s: refused at %s (rc %d, %s: %s)", what, path, rc, err.path, err.message);
}

static void bad_input(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    design uni = {.Ft = 10.0};
    double C[2] = {0.0, 0.0};
    static rd_free_table t, u;
    table_of(&p, &uni, 0, C, 0.0, 0.0, 1, &t);
    u = t;
    u.n_points = 9;
    bad("9 points for 7 parameters and 4 more", &u, "/ring/free_shape/theta_deg");
    u = t;
    u.theta_deg[5] = u.theta_deg[4];
    bad("angles not increasing", &u, "/ring/free_shape/theta_deg");
    u = t;
    while (u.theta_deg[u.n_points - 1] > 120.0)
        u.n_points--;
    bad("one side short of the gap", &u, "/ring/free_shape");
    u = t;
    u.fit_order = 13;
    bad("fit_order 13", &u, "/ring/free_shape/fit_order");
    u = t;
    u.radius[3] = 0.02;
    bad("a radius of 20 mm on a 76.5 mm ring", &u, "/ring/free_shape/radius_m");
    u = t; /* a point on the gap face, half a degree from the middle of the gap */
    u.theta_deg[u.n_points] = 179.5;
    u.radius[u.n_points] = u.radius[u.n_points - 1];
    u.n_points++;
    bad("a point in the gap", &u, "/ring/free_shape/theta_deg");
    u = t; /* the tips turned in: a ring closed by its pressure opens */
    for (int i = 0; i < u.n_points; i++)
        u.radius[i] = p.diameter - t.radius[i];
    bad("the tips turned in", &u, "/ring/free_shape");
}

/* A circle larger than the bore: closed, it carries one moment all round,
 * which its free tips cannot; the pressure sits at the tips, and orders up
 * to 6 show it as a pressure that falls below 0 (the ring leaves the bore). */
static void circle(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    static rd_free_table t;
    t.fit_order = 6;
    for (int i = 0; i <= 170; i++) {
        t.theta_deg[i] = i;
        t.radius[i] = 0.5 * p.diameter + 1e-4;
    }
    t.n_points = 171;
    rd_free_fit f;
    rd_error err;
    int rc = fit(&p, 40, &t, &f, &err);
    printf("a circle 0.1 mm over the bore: F_t %.4g N, p / p0 down to %.3g at %.1f deg, residual "
           "rms %.3g um\n",
           f.tangential_force, f.pressure_min, f.pressure_min_deg, 1e6 * f.residual_rms);
    CHECK(rc == RD_OK && f.pressure_min < 0.0, "a circle: the ring leaves the bore (%s)",
          err.message);
}

int main(void)
{
    design uni = {.Ft = 10.0};
    recovers("uniform, whole, shifted and turned", &uni, 1, 4, 2e-4, 0.01);
    design oval = {.Ft = 10.0, .K = 2, .order = {2, 3}, .amp = {0.15, -0.2}};
    recovers("1 + 0.15 cos 2t - 0.2 cos 3t, mirrored", &oval, 0, 6, 1e-4, 0.0);
    recovers("1 + 0.15 cos 2t - 0.2 cos 3t, whole", &oval, 1, 6, 1e-4, -0.005);
    design stiff = {.Ft = 20.0, .K = 2, .order = {2, 4}, .amp = {0.1, 0.05}};
    recovers("F_t 20 N, orders 2 and 4, whole", &stiff, 1, 6, 0.0, 0.0);
    recovers("the same, every order to 12", &stiff, 1, 12, 1e-4, 0.002);
    closed_again();
    scatter();
    bad_input();
    circle();
    return check_done();
}
