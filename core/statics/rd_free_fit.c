/*
 * rd_free_fit — a measured free shape (rd_static.h's rd_free_table) turned
 * into the pressure distribution the ring was made for (rd_free_shape),
 * which every analysis then reads as if the scene had given it.
 *
 * Why a fit and not the shape itself: the pressure is the free shape's
 * fourth derivative (closed in the bore, the moment is E I times the
 * change of curvature, and the pressure the moment's second derivative), so
 * at the scale of one 7 mm segment of the thesis ring 1 % of p0 is 7 nm of
 * radius.  A rest taken point by point from a table of the solved free
 * shape itself gave the pressure back only within 4-36 % of p0.  So the
 * table is not differentiated: the unknowns are what a ring maker designs,
 *   c = (F_t, F_t a_2, ..., F_t a_K)   p / p0 = 1 + sum_k a_k cos k theta,
 * and the fit finds those whose geometrically exact free shape (the chain's
 * free solve, rd_pretension_free_face: the same model that then closes the
 * ring) is closest to the points in least squares.  The points are measured
 * about some centre and angle origin: the centre (x0, y0) and, for a whole
 * table, a turn d are fitted too (one side, mirrored: x0 only).  A point at
 * (theta_i, r_i) sits at P = (x0, y0) + r_i (cos(theta_i + d), sin(theta_i
 * + d)) in the fitted shape's frame (x toward the point opposite the gap);
 * its residual is |P| minus the fitted running face's radius at P's angle
 * (cubic Hermite through the chain's n + 2 face points).
 *
 * Gauss-Newton: the shape is nearly linear in c (the free shape's
 * displacement from the closed ring is linear in the pressure to ~2 %), so
 * the pressure's columns of the Jacobian are taken once, by K whole solves
 * at the start of the first of the two fits (at segments / 2, reused at
 * segments), and the rigid columns each iteration (no solve); each
 * iteration costs one free solve and settles by a factor ~50.
 *
 * The standard errors are those of the least-squares fit, s^2 (J^T J)^-1,
 * s^2 = SSR / (N - P): they measure the table's scatter about the model's
 * shapes, not the model's own error (test_free_shape: the chain gives a
 * pressure back within 0.3-0.8 % of p0) nor a table's systematic error.
 */
#include <lapacke.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_static_problem.h"

#define FIT_PARAMS_MAX (RD_FREE_FIT_ORDER_MAX + 3) /* F_t, the orders, x0, y0, turn */
#define FIT_ITER_MAX   30

/* An error of the fit in the ring's block (the table is its free_shape):
 * path relative to it, '@' in fmt for its pointer. */
static int ring_error(rd_error *err, int code, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int ring_error(rd_error *err, int code, const char *path, const char *fmt, ...)
{
    size_t m = rd_error_enter(err, "/ring");
    va_list ap;
    va_start(ap, fmt);
    int rc = rd_error_setv(err, code, path, fmt, ap);
    va_end(ap);
    rd_error_leave(err, m);
    return rc;
}

static int mirrored_table(const rd_free_table *t)
{
    return t->theta_deg[0] >= 0.0;
}

static int fit_parameters(const rd_free_table *t)
{
    return t->fit_order + (mirrored_table(t) ? 1 : 3);
}

int rd_free_table_validate(const rd_free_table *t, const rd_ring_params *p, rd_error *err)
{
    if (!t || t->n_points == 0)
        return RD_OK;
    const char *at = "/free_shape";
    if (t->fit_order < 2 || t->fit_order > RD_FREE_FIT_ORDER_MAX)
        return rd_error_set(err, RD_EINVAL, "/free_shape/fit_order",
                            "@/free_shape/fit_order = %d is out of range: allowed 2 to %d "
                            "(the pressure's orders 2..K fitted).",
                            t->fit_order, RD_FREE_FIT_ORDER_MAX);
    int n = t->n_points, need = fit_parameters(t) + 4;
    need = need < 8 ? 8 : need;
    if (n < need || n > RD_FREE_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/free_shape/theta_deg",
                            "@/free_shape has %d points: allowed %d to %d (%d parameters "
                            "with fit_order %d, and 4 more to measure the scatter).",
                            n, need, RD_FREE_POINTS_MAX, fit_parameters(t), t->fit_order);
    for (int i = 0; i < n; i++) {
        double th = t->theta_deg[i], r = t->radius[i], R = 0.5 * p->diameter;
        if (!isfinite(th) || th < -180.0 || th > 180.0)
            return rd_error_set(err, RD_EINVAL, "/free_shape/theta_deg",
                                "@/free_shape/theta_deg[%d] = %g deg is out of range: allowed "
                                "-180 to 180 deg (from the point opposite the gap).",
                                i, th);
        if (i > 0 && !(th > t->theta_deg[i - 1]))
            return rd_error_set(err, RD_EINVAL, "/free_shape/theta_deg",
                                "@/free_shape/theta_deg[%d] = %g deg does not increase (the "
                                "one before is %g deg).",
                                i, th, t->theta_deg[i - 1]);
        if (!isfinite(r) || fabs(r - R) > 0.3 * R)
            return rd_error_set(err, RD_EINVAL, "/free_shape/radius_m",
                                "@/free_shape/radius_m[%d] = %g m is out of range: allowed "
                                "%g to %g m (within 30 %% of the ring's radius d / 2 = %g m).",
                                i, r, 0.7 * R, 1.3 * R, R);
    }
    double lo = t->theta_deg[0], hi = t->theta_deg[n - 1];
    if (lo >= 0.0 ? (lo > 20.0 || hi < 150.0) : (lo > -150.0 || hi < 150.0))
        return rd_error_set(err, RD_EINVAL, at,
                            "@%s/theta_deg runs from %g to %g deg: give one side, from 0-20 to "
                            "150 deg or beyond (mirrored), or the whole ring, from -150 deg or "
                            "below to 150 deg or beyond (theta from the point opposite the gap).",
                            at, lo, hi);
    return RD_OK;
}

/* ---- the fitted shape's running face ---------------------------------------- */

typedef struct fit_curve {
    int m;
    double *th, *r, *d; /* rad (increasing), m, dr/dtheta */
} fit_curve;

static void curve_free(fit_curve *c)
{
    free(c->th);
    c->th = c->r = c->d = NULL;
}

/* The parabola's slope through three points at the middle one (or at an end). */
static double slope3(const double *x, const double *y, int a, int at)
{
    double x0 = x[a], x1 = x[a + 1], x2 = x[a + 2], X = x[at];
    return y[a] * (2 * X - x1 - x2) / ((x0 - x1) * (x0 - x2)) +
           y[a + 1] * (2 * X - x0 - x2) / ((x1 - x0) * (x1 - x2)) +
           y[a + 2] * (2 * X - x0 - x1) / ((x2 - x0) * (x2 - x1));
}

/* The free shape of (F_t, orders) at the fit's segment count, as a curve. */
static int curve_solve(const rd_ring_params *p, int segments, const rd_free_shape *fs, double Ft,
                       const rd_static_opts *so, fit_curve *c, rd_error *err)
{
    rd_ring_params q = *p;
    q.tangential_force = Ft;
    rd_pretension_result r;
    int rc = rd_pretension_free_face(&q, segments, fs, so, &r, err);
    if (rc == RD_OK) {
        int m = r.points;
        curve_free(c);
        c->m = m;
        c->th = malloc(3 * (size_t)m * sizeof *c->th);
        if (!c->th) {
            rd_pretension_result_cleanup(&r);
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape's fit.");
        }
        c->r = c->th + m;
        c->d = c->th + 2 * m;
        for (int k = 0; k < m; k++) {
            c->th[k] = r.face_theta_deg[k] * M_PI / 180.0;
            c->r[k] = r.face_radius[k];
            if (k > 0 && !(c->th[k] > c->th[k - 1]))
                rc = ring_error(err, RD_EINVAL, "/free_shape",
                                "the fitted free shape's running face does not turn once "
                                "round its centre (F_t %.4g N): the table is not a ring's free "
                                "shape about a centre inside it.",
                                Ft);
        }
        for (int k = 0; rc == RD_OK && k < m; k++)
            c->d[k] = slope3(c->th, c->r, k == 0 ? 0 : k == m - 1 ? m - 3 : k - 1, k);
    }
    rd_pretension_result_cleanup(&r);
    return rc;
}

/* The face's radius at angle a (cubic Hermite); *out set when a lies
 * beyond the tips (then the end's tangent line). */
static double curve_at(const fit_curve *c, double a, int *out)
{
    int m = c->m;
    if (a <= c->th[0] || a >= c->th[m - 1]) {
        int k = a <= c->th[0] ? 0 : m - 1;
        *out = 1;
        return c->r[k] + c->d[k] * (a - c->th[k]);
    }
    int lo = 0, hi = m - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (c->th[mid] <= a)
            lo = mid;
        else
            hi = mid;
    }
    double h = c->th[hi] - c->th[lo], s = (a - c->th[lo]) / h, s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * c->r[lo] + (s3 - 2 * s2 + s) * h * c->d[lo] +
           (-2 * s3 + 3 * s2) * c->r[hi] + (s3 - s2) * h * c->d[hi];
}

/* ---- the fit ------------------------------------------------------------------ */

typedef struct fitter {
    const rd_ring_params *p;
    const rd_free_table *t;
    const rd_static_opts *so;
    const rd_monitor *mon;         /* asked before each free solve: a stop ends the fit */
    int segments, K, P, N, rigid0; /* rigid0: the first rigid parameter's index (K) */
    int have_J;                    /* the pressure's columns taken (at the coarser chain) */
    double q[FIT_PARAMS_MAX];      /* F_t, F_t a_2..a_K, x0, [y0, d] */
} fitter;

static void shape_of(const fitter *f, const double *q, rd_free_shape *fs)
{
    memset(fs, 0, sizeof *fs);
    fs->kind = RD_FREE_PRESSURE;
    fs->measured = 1;
    fs->n_orders = f->K - 1;
    for (int k = 2; k <= f->K; k++) {
        fs->order[k - 2] = k;
        fs->amplitude[k - 2] = q[k - 1] / q[0];
    }
}

/* Residuals (measured minus fitted radius) of the rigid placement q on the
 * curve c; the number of points beyond the tips in *outside. */
static void residuals(const fitter *f, const double *q, const fit_curve *c, double *e, int *outside)
{
    const rd_free_table *t = f->t;
    double x0 = q[f->rigid0], y0 = f->P > f->rigid0 + 1 ? q[f->rigid0 + 1] : 0.0,
           d = f->P > f->rigid0 + 1 ? q[f->rigid0 + 2] : 0.0;
    *outside = 0;
    for (int i = 0; i < f->N; i++) {
        double a = t->theta_deg[i] * M_PI / 180.0 + d;
        double X = x0 + t->radius[i] * cos(a), Y = y0 + t->radius[i] * sin(a);
        int out = 0;
        e[i] = hypot(X, Y) - curve_at(c, atan2(Y, X), &out);
        *outside += out;
    }
}

static int fit_solve(const fitter *f, const rd_free_shape *fs, double Ft, fit_curve *c,
                     rd_error *err)
{
    if (!(Ft > 0.0))
        return ring_error(err, RD_EINVAL, "/free_shape",
                          "the fitted tangential force came out %.4g N: the table is not the "
                          "free shape of a ring opened by its pressure (its tips must stand "
                          "out from the closed ring's circle).",
                          Ft);
    int rc = rd_monitor_report(f->mon, 0.0, err);
    return rc != RD_OK ? rc : curve_solve(f->p, f->segments, fs, Ft, f->so, c, err);
}

/* The pressure's columns of the Jacobian (de/dq_j = -d(fitted radius)/dq_j),
 * by whole solves from the current q and its curve's residuals e. */
static int pressure_columns(const fitter *f, const double *e, double *J, rd_error *err)
{
    fit_curve c = {0};
    int rc = RD_OK, outside;
    double *e1 = malloc((size_t)f->N * sizeof *e1);
    if (!e1)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape's fit.");
    for (int j = 0; rc == RD_OK && j < f->K; j++) {
        double q[FIT_PARAMS_MAX], h = 0.02 * f->q[0];
        memcpy(q, f->q, sizeof q);
        q[j] += h;
        rd_free_shape fs;
        shape_of(f, q, &fs);
        if ((rc = fit_solve(f, &fs, q[0], &c, err)) == RD_OK) {
            residuals(f, q, &c, e1, &outside);
            for (int i = 0; i < f->N; i++)
                J[(size_t)i * f->P + j] = (e1[i] - e[i]) / h;
        }
    }
    curve_free(&c);
    free(e1);
    return rc;
}

/* The rigid columns, on the current curve (no solve). */
static void rigid_columns(const fitter *f, const fit_curve *c, const double *e, double *J,
                          double *e1)
{
    static const double step[3] = {1e-7, 1e-7, 1e-6}; /* m, m, rad */
    for (int j = f->rigid0; j < f->P; j++) {
        double q[FIT_PARAMS_MAX];
        int outside;
        memcpy(q, f->q, sizeof q);
        q[j] += step[j - f->rigid0];
        residuals(f, q, c, e1, &outside);
        for (int i = 0; i < f->N; i++)
            J[(size_t)i * f->P + j] = (e1[i] - e[i]) / step[j - f->rigid0];
    }
}

/* Normal equations, columns scaled: the step dq (J dq ~ -e) and, in C, the
 * unscaled (J^T J)^-1.  RD_EINVAL when J^T J is singular. */
static int normal_step(const fitter *f, const double *J, const double *e, double *dq, double *C)
{
    int P = f->P;
    double D[FIT_PARAMS_MAX], g[FIT_PARAMS_MAX];
    for (int j = 0; j < P; j++) {
        double s = 0.0;
        for (int i = 0; i < f->N; i++)
            s += J[(size_t)i * P + j] * J[(size_t)i * P + j];
        D[j] = s > 0.0 ? 1.0 / sqrt(s) : 1.0;
    }
    for (int a = 0; a < P; a++) {
        g[a] = 0.0;
        for (int i = 0; i < f->N; i++)
            g[a] -= D[a] * J[(size_t)i * P + a] * e[i];
        for (int b = 0; b < P; b++) {
            double s = 0.0;
            for (int i = 0; i < f->N; i++)
                s += J[(size_t)i * P + a] * J[(size_t)i * P + b];
            C[a * P + b] = D[a] * s * D[b];
        }
    }
    double anorm = 0.0, rcond = 0.0;
    for (int b = 0; b < P; b++) {
        double s = 0.0;
        for (int a = 0; a < P; a++)
            s += fabs(C[a * P + b]);
        anorm = fmax(anorm, s);
    }
    /* a condition beyond 1e13 (scaled): the table does not fix every parameter */
    lapack_int info = LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'U', P, C, P);
    if (info == 0)
        info = LAPACKE_dpocon(LAPACK_ROW_MAJOR, 'U', P, C, P, anorm, &rcond);
    if (info == 0 && rcond > 1e-13)
        info = LAPACKE_dpotrs(LAPACK_ROW_MAJOR, 'U', P, 1, C, P, g, 1);
    if (info == 0 && rcond > 1e-13)
        info = LAPACKE_dpotri(LAPACK_ROW_MAJOR, 'U', P, C, P);
    /* (LAPACKE's row-major copies and work arrays: their allocation may fail) */
    if (info == LAPACK_TRANSPOSE_MEMORY_ERROR || info == LAPACK_WORK_MEMORY_ERROR)
        return RD_ENOMEM;
    if (info != 0 || !(rcond > 1e-13))
        return RD_EINVAL;
    for (int a = 0; a < P; a++) {
        dq[a] = D[a] * g[a];
        for (int b = a; b < P; b++)
            C[b * P + a] = C[a * P + b] = D[a] * C[a * P + b] * D[b];
    }
    return RD_OK;
}

/* F_t and the a_k's standard errors, and the pressure's (delta method). */
static void errors_out(const fitter *f, const double *C, double s2, rd_free_fit *out)
{
    int P = f->P, K = f->K;
    double c0 = f->q[0];
    out->tangential_force_se = sqrt(s2 * C[0]);
    for (int k = 1; k < K; k++) { /* a = c_k / c0 */
        double ck = f->q[k];
        double v = C[k * P + k] / (c0 * c0) - 2.0 * ck * C[k] / (c0 * c0 * c0) +
                   ck * ck * C[0] / (c0 * c0 * c0 * c0);
        out->amplitude_se[k - 1] = sqrt(s2 * fmax(v, 0.0));
    }
    out->pressure_se_max = 0.0;
    out->pressure_min = INFINITY;
    for (int s = 0; s <= 720; s++) {
        double th = (-180.0 + 0.5 * s) * M_PI / 180.0, g[FIT_PARAMS_MAX] = {0}, pr = 1.0;
        for (int k = 1; k < K; k++) {
            double ck = cos((k + 1) * th);
            pr += f->q[k] / c0 * ck;
            g[0] -= f->q[k] * ck / (c0 * c0);
            g[k] = ck / c0;
        }
        double v = 0.0;
        for (int a = 0; a < K; a++)
            for (int b = 0; b < K; b++)
                v += g[a] * C[a * P + b] * g[b];
        out->pressure_se_max = fmax(out->pressure_se_max, sqrt(s2 * fmax(v, 0.0)));
        if (pr < out->pressure_min) {
            out->pressure_min = pr;
            out->pressure_min_deg = th * 180.0 / M_PI;
        }
    }
}

/* Settled: every parameter's last step below 1e-9 of its scale (F_t for
 * the pressure's, 1e-3 of the radius for the centre, 1e-3 rad the turn) or
 * below a thousandth of its standard error (e the residuals, C the last
 * step's (J^T J)^-1). */
static int settled(const fitter *f, const double *dq, const double *e, const double *C)
{
    double ssr = 0.0;
    for (int i = 0; i < f->N; i++)
        ssr += e[i] * e[i];
    for (int j = 0; j < f->P; j++) {
        double scale = j < f->K ? f->q[0] : j < f->rigid0 + 2 ? 5e-4 * f->p->diameter : 1e-3;
        /* or a thousandth of its standard error: the high orders' steps
         * stop at the solves' own noise times k^4 */
        double se = sqrt(ssr / (f->N - f->P) * C[j * f->P + j]);
        if (fabs(dq[j]) > fmax(1e-9 * scale, 1e-3 * se))
            return 0;
    }
    return 1;
}

static int outside_error(int outside, rd_error *err)
{
    return ring_error(err, RD_EINVAL, "/free_shape/theta_deg",
                      "%d of @/free_shape's points lie in the fitted free shape's gap "
                      "(beyond its tips): leave out the points on the gap faces and beyond.",
                      outside);
}

/* The Gauss-Newton loop (the header): f->q from its start to the fit. */
static int iterate(fitter *f, double *J, double *e, double *e1, double *C, rd_free_fit *out,
                   rd_error *err)
{
    fit_curve c = {0};
    rd_free_shape fs;
    int rc, outside = 0;
    shape_of(f, f->q, &fs);
    if ((rc = fit_solve(f, &fs, f->q[0], &c, err)) != RD_OK)
        goto out;
    residuals(f, f->q, &c, e, &outside);
    if (!f->have_J && (rc = pressure_columns(f, e, J, err)) != RD_OK)
        goto out;
    f->have_J = 1;
    double last = INFINITY;
    int retakes = 0;
    for (out->iterations = 1; out->iterations <= FIT_ITER_MAX; out->iterations++) {
        double dq[FIT_PARAMS_MAX];
        rigid_columns(f, &c, e, J, e1);
        int ns = normal_step(f, J, e, dq, C);
        if (ns == RD_ENOMEM) {
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape's fit.");
            goto out;
        }
        if (ns != RD_OK) {
            rc = ring_error(err, RD_EINVAL, "/free_shape/fit_order",
                            "@/free_shape does not fix the pressure's orders 2 to %d "
                            "(the fit is singular): give fewer orders (fit_order) or points "
                            "spread round the ring.",
                            f->K);
            goto out;
        }
        for (int j = 0; j < f->P; j++)
            f->q[j] += dq[j];
        shape_of(f, f->q, &fs);
        if ((rc = fit_solve(f, &fs, f->q[0], &c, err)) != RD_OK)
            goto out;
        residuals(f, f->q, &c, e, &outside);
        if (settled(f, dq, e, C))
            break;
        /* a step that shrank less than 3x: the pressure's columns again, here
         * (far from where they were taken, the chord settles slowly on
         * the high orders: K = 12 from twice the start's F_t took > 30) */
        double size = 0.0;
        for (int j = 0; j < f->K; j++)
            size = fmax(size, fabs(dq[j]) / f->q[0]);
        if (size > last / 3.0 && retakes < 3) {
            if ((rc = pressure_columns(f, e, J, err)) != RD_OK)
                goto out;
            retakes++;
        }
        last = size;
    }
    if (out->iterations > FIT_ITER_MAX) {
        rc = ring_error(err, RD_ENOCONV, "/free_shape",
                        "the free shape's fit did not settle in %d iterations: the table is "
                        "far from a ring's free shape of pressure orders 2 to %d.",
                        FIT_ITER_MAX, f->K);
        goto out;
    }
    if (outside) {
        rc = outside_error(outside, err);
        goto out;
    }
    rigid_columns(f, &c, e, J, e1); /* the covariance at the fit */
    double dq[FIT_PARAMS_MAX];
    int ns = normal_step(f, J, e, dq, C);
    if (ns == RD_ENOMEM)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape's fit.");
    else if (ns != RD_OK)
        rc = ring_error(err, RD_EINVAL, "/free_shape/fit_order",
                        "@/free_shape does not fix the pressure's orders 2 to %d.", f->K);
out:
    curve_free(&c);
    return rc;
}

/* The fit with a chain of `segments`. */
/* The fit with f's chain, from f->q; its outputs into out. */
static int fit_at(fitter *f, double *J, rd_free_fit *out, rd_error *err)
{
    double C[FIT_PARAMS_MAX * FIT_PARAMS_MAX], *e = J + (size_t)f->N * f->P, *e1 = e + f->N;
    memset(out, 0, sizeof *out);
    int rc = iterate(f, J, e, e1, C, out, err);
    if (rc != RD_OK)
        return rc;
    double ssr = 0.0;
    for (int i = 0; i < f->N; i++) {
        ssr += e[i] * e[i];
        out->residual_max = fmax(out->residual_max, fabs(e[i]));
    }
    out->residual_rms = sqrt(ssr / f->N);
    shape_of(f, f->q, &out->shape);
    out->tangential_force = f->q[0];
    out->centre[0] = f->q[f->rigid0];
    out->centre[1] = f->P > f->rigid0 + 1 ? f->q[f->rigid0 + 1] : 0.0;
    out->rotation_deg = f->P > f->rigid0 + 1 ? f->q[f->rigid0 + 2] * 180.0 / M_PI : 0.0;
    out->segments = f->segments;
    out->parameters = f->P;
    errors_out(f, C, ssr / (f->N - f->P), out);
    return RD_OK;
}

/* The chain at segments / 2 first (where the pressure's columns are taken,
 * and its fit is the start at `segments`), then at `segments`; the
 * difference is the chain's error (order 2 in n: Richardson). */
int rd_free_shape_fit(const rd_ring_params *p, int segments, const rd_free_table *t,
                      const rd_static_opts *so, const rd_monitor *mon, rd_free_fit *out,
                      rd_error *err)
{
    memset(out, 0, sizeof *out);
    size_t m = rd_error_enter(err, "/ring");
    int rc = rd_free_table_validate(t, p, err);
    rd_error_leave(err, m);
    if (rc != RD_OK)
        return rc;
    if (!t || t->n_points == 0)
        return ring_error(err, RD_EINVAL, "/free_shape", "@/free_shape is empty.");
    fitter f = {.p = p,
                .t = t,
                .so = so,
                .mon = mon,
                .segments = segments / 2,
                .K = t->fit_order,
                .P = fit_parameters(t),
                .N = t->n_points,
                .rigid0 = t->fit_order};
    f.q[0] = p->tangential_force > 0.0 ? p->tangential_force : 10.0; /* where J is taken */
    double *J = malloc((size_t)f.N * (f.P + 2) * sizeof *J);
    if (!J)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape's fit.");
    rd_free_fit half;
    rc = fit_at(&f, J, &half, err);
    f.segments = segments;
    if (rc == RD_OK)
        rc = fit_at(&f, J, out, err);
    free(J);
    if (rc != RD_OK)
        return rc;
    out->tangential_force_error = fabs(out->tangential_force - half.tangential_force) / 3.0;
    for (int k = 0; k < out->shape.n_orders; k++)
        out->amplitude_error[k] = fabs(out->shape.amplitude[k] - half.shape.amplitude[k]) / 3.0;
    return RD_OK;
}
