/*
 * rd_lift_start.c — the lift run's start in a distorted bore (rd_lift_bore.c
 * has the bore and its contact offsets).
 *
 * Start: the ring at q = 0 is not in equilibrium in such a bore (its offsets
 * are microns, the preload penetration nanometres).  rd_lift_bore_static
 * finds the static equilibrium of the installed ring in it — the full
 * model's force elements with the piston at rest, no gravity, gas, friction
 * or tilt:  R(q) = f(q) - K q = 0 — by Newton on the band matrix
 * K - df/dq + eps M (K positive semi-definite, -df/dq of the contacts
 * positive semi-definite, eps M = EPS_M x the largest K_ii / M_ii on the
 * diagonal only fixes the free ring's rigid-body directions, along which the
 * residual is zero), each step searched along its direction until the
 * energy's slope vanishes (line_search: the residual is minus the gradient
 * of a convex energy), converged when the residual is below RES_TOL x the
 * larger of p0 and the contact pressure of the bore's largest offset.  The
 * run starts there at rest.  (Halving the step while the residual's size
 * grew, measured against p0 alone, stalled in a bore 0.01 % larger or
 * smaller than the ring and never converged without pretension.)
 *
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

#define EPS_M      1e-10 /* regularization of the Newton matrix (header comment) */
#define NEWTON_MAX 100
#define RES_TOL    1e-9 /* converged: residual below this x pressure scale x (bore point area) */
#define SEARCH_MAX 40   /* regula falsi steps of the line search */
#define SEARCH_TOL 1e-3 /* the search's slope, relative to its start: enough for Newton */

/* R = f - K q into r (segment order), and its weighted size (moments / R). */
static double residual(rd_lift_model *c, const double *y, double *r, double *tmp, double R)
{
    size_t N = 6 * (size_t)c->n;
    rd_lift_forces(c, 0.0, y, c->Dq, c->Dv);
    for (int i = 0; i < c->n; i++)
        for (int k = 0; k < 6; k++)
            tmp[rd_ring_band_index(c->ring, i, k)] = RD_LIFT_Q(y, i)[k];
    rd_band_symv(&c->K, tmp, tmp + N);
    double s = 0.0;
    for (int i = 0; i < c->n; i++)
        for (int k = 0; k < 6; k++) {
            double v = c->fbuf[6 * i + k] - tmp[N + rd_ring_band_index(c->ring, i, k)];
            r[6 * i + k] = v;
            s = fmax(s, fabs(v) / (k < 3 ? 1.0 : R));
        }
    return s;
}

/* The trial state ytry = y + lam dq (dq in band order) and its residual r;
 * returns r . dq, the energy's slope along dq with the sign flipped. */
static double slope_at(rd_lift_model *c, const double *y, const double *dq, double lam,
                       double *ytry, double *r, double *tmp, double R, double *res)
{
    memcpy(ytry, y, 12 * (size_t)c->n * sizeof *ytry);
    for (int i = 0; i < c->n; i++)
        for (int k = 0; k < 6; k++)
            RD_LIFT_Q(ytry, i)[k] += lam * dq[rd_ring_band_index(c->ring, i, k)];
    *res = residual(c, ytry, r, tmp, R);
    double s = 0.0;
    for (int i = 0; i < c->n; i++)
        for (int k = 0; k < 6; k++)
            s += r[6 * i + k] * dq[rd_ring_band_index(c->ring, i, k)];
    return s;
}

/* The step along the Newton direction dq: the residual is minus the gradient
 * of a convex energy (the linear K, penalty contacts affine in q, constant
 * pretension), so its slope r(lam) . dq falls with lam from r . J^-1 r > 0.
 * The full step when the slope is still >= 0 there, else the slope's root by
 * regula falsi (Illinois): the energy falls at every step, where halving
 * on the residual's size stalled as contacts switched (a ring in a bore
 * larger or smaller than itself).  Leaves the state in ytry and its residual
 * in r; returns the residual's size. */
static double line_search(rd_lift_model *c, const double *y, const double *dq, double *ytry,
                          double *r, double *tmp, double R)
{
    double res, lo = 0.0, hi = 1.0, s_lo = INFINITY;
    double s_hi = slope_at(c, y, dq, 1.0, ytry, r, tmp, R, &res);
    if (!(s_hi < 0.0))
        return res;
    s_lo = slope_at(c, y, dq, 0.0, ytry, r, tmp, R, &res);
    double lam = 1.0;
    for (int it = 0, side = 0; it < SEARCH_MAX && s_lo > 0.0; it++) {
        lam = (lo * s_hi - hi * s_lo) / (s_hi - s_lo);
        double s = slope_at(c, y, dq, lam, ytry, r, tmp, R, &res);
        if (fabs(s) <= SEARCH_TOL * s_lo || hi - lo <= 1e-12 * hi)
            return res;
        if (s > 0.0) {
            lo = lam, s_lo = s;
            s_hi *= side == 1 ? 0.5 : 1.0, side = 1;
        } else {
            hi = lam, s_hi = s;
            s_lo *= side == -1 ? 0.5 : 1.0, side = -1;
        }
    }
    slope_at(c, y, dq, lam, ytry, r, tmp, R, &res);
    return res;
}

/* J = K - Dq + eps M (upper band), from the last residual's Dq. */
static void newton_matrix(const rd_lift_model *c, rd_band *J, double eps)
{
    memcpy(J->ab, c->K.ab, (size_t)(J->kd + 1) * J->n * sizeof *J->ab);
    for (int i = 0; i < c->n; i++) {
        const double *Mi = rd_ring_segment_mass_matrix(c->ring, i), *D = c->Dq + 36 * (size_t)i;
        for (int a = 0; a < 6; a++)
            for (int b = 0; b < 6; b++) {
                int gi = rd_ring_band_index(c->ring, i, a), gj = rd_ring_band_index(c->ring, i, b);
                if (gi <= gj)
                    rd_band_add(J, gi, gj, -D[6 * a + b] + eps * Mi[6 * a + b]);
            }
    }
}

static int static_newton(rd_lift_model *c, double *y, rd_error *err)
{
    size_t N = 6 * (size_t)c->n;
    double R = rd_ring_get_section(c->ring)->R, eps = 0.0;
    double *r = malloc(N * sizeof *r), *tmp = malloc(3 * N * sizeof *tmp); /* step, scratch */
    double *ytry = malloc(2 * N * sizeof *ytry);
    rd_band J = {0, 0, NULL};
    int rc = r && tmp && ytry ? rd_band_init(&J, (int)N, c->K.kd, err)
                              : rd_error_set(err, RD_ENOMEM, "", "Out of memory for the bore.");
    for (int i = 0; !rc && i < c->n; i++)
        for (int k = 0; k < 6; k++) {
            int g = rd_ring_band_index(c->ring, i, k);
            double m = rd_ring_segment_mass_matrix(c->ring, i)[7 * k];
            eps = fmax(eps, EPS_M * RD_BAND_AT(&c->K, g, g) / m);
        }
    /* the pressure scale: the pretension, or the contact pressure of the
     * bore's largest offset when that is larger (a ring without pretension,
     * or one pressed into a smaller bore, whose forces p0 would measure
     * below their rounding) */
    double gmax = 0.0;
    for (size_t j = 0; j < (size_t)c->n * RD_LIFT_ARC_POINTS; j++)
        gmax = fmax(gmax, fabs(c->bo_gap[j]));
    double tol = RES_TOL * fmax(c->p0, c->k * gmax) * c->bo_area;
    double res = rc ? 0.0 : residual(c, y, r, tmp, R);
    int it = 0;
    for (; !rc && res > tol && it < NEWTON_MAX; it++) {
        newton_matrix(c, &J, eps);
        if ((rc = rd_band_cholesky(&J, err)))
            break;
        for (int i = 0; i < c->n; i++)
            for (int k = 0; k < 6; k++)
                tmp[rd_ring_band_index(c->ring, i, k)] = r[6 * i + k];
        if ((rc = rd_band_solve(&J, 1, tmp, err)))
            break;
        /* the energy falls at every step, the residual's size need not */
        res = line_search(c, y, tmp, ytry, r, tmp + N, R);
        memcpy(y, ytry, 12 * (size_t)c->n * sizeof *y);
    }
    if (!rc && res > tol)
        rc = rd_error_set(err, RD_ENOCONV, "/bore",
                          "The ring's static equilibrium in the distorted bore was not found "
                          "(residual %.3g of its tolerance after %d Newton steps): reduce the "
                          "distortion or raise /contact/stiffness.",
                          res / tol, it);
    rd_band_cleanup(&J);
    free(r);
    free(tmp);
    free(ytry);
    return rc;
}

int rd_lift_bore_static(const rd_ring *ring, const rd_lift_params *p, double *y0, rd_error *err)
{
    rd_lift_params q = *p;
    q.gravity = 0;
    q.friction.model = RD_FRICTION_NONE;
    q.gas.points = 0;
    q.engine.piston_tilt_deg = 0.0;
    q.engine.tilt_points = 0;
    /* the default contact stiffness of the scene itself, not of the reduced copy */
    if (q.contact_stiffness <= 0.0)
        q.contact_stiffness = rd_lift_contact_stiffness_default(rd_ring_get_params(ring), p);
    rd_lift_setup su = {.piston_fixed = 1};
    rd_lift_model c;
    memset(y0, 0, 12 * (size_t)rd_ring_get_segments(ring) * sizeof *y0);
    int rc = rd_lift_model_init(&c, ring, &q, &su, err);
    if (!rc)
        rc = static_newton(&c, y0, err);
    rd_lift_model_cleanup(&c);
    return rc;
}
