/*
 * rd_lift_bore.c — the bore of a lift scene (bore.diameter, bore.distortion,
 * as in the contact analysis): r_b(theta) = D/2 + sum_k A_k cos(k (theta -
 * phi_k)), theta from the gap middle (rd_lift.h).
 *
 * The bore contact of the full model (rd_lift_forces.c) is measured from
 * the round bore of the ring's diameter d: a bore point at angle psi has
 * penetration delta_pre + u_r - g(psi), g(psi) = r_b(psi) - d/2 the bore's
 * outward offset there (precomputed per point, rd_lift_bore_init).  So the
 * radial contact pressure, and with it the friction, varies around the ring.
 *
 * Start: the ring at q = 0 is not in equilibrium in such a bore (its offsets
 * are microns, the preload penetration nanometres).  rd_lift_bore_static
 * finds the static equilibrium of the installed ring in it — the full
 * model's force elements with the piston at rest, no gravity, gas, friction
 * or tilt:  R(q) = f(q) - K q = 0 — by Newton on the band matrix
 * K - df/dq + eps M (K positive semi-definite, -df/dq of the contacts
 * positive semi-definite, eps M = EPS_M x the largest K_ii / M_ii on the
 * diagonal only fixes the free ring's rigid-body directions, along which the
 * residual is zero) with step halving while the residual grows.  The run
 * starts there at rest.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_model.h"

#define EPS_M      1e-10 /* regularization of the Newton matrix (header comment) */
#define NEWTON_MAX 60
#define RES_TOL    1e-9 /* converged: residual below this x p0 x (bore point area) */

int rd_lift_bore_distorted(const rd_lift_bore *b, double ring_diameter)
{
    return (b->diameter > 0.0 && b->diameter != ring_diameter) || b->n_distortion > 0;
}

int rd_lift_bore_init(rd_lift_model *c, rd_error *err)
{
    const rd_lift_bore *b = &c->p->bore;
    double d = rd_ring_get_params(c->ring)->diameter;
    c->bo_gap = NULL;
    if (!rd_lift_bore_distorted(b, d))
        return RD_OK;
    size_t np = (size_t)c->n * RD_LIFT_ARC_POINTS;
    c->bo_gap = malloc(np * sizeof *c->bo_gap);
    if (!c->bo_gap)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift bore.");
    double g0 = b->diameter > 0.0 ? 0.5 * (b->diameter - d) : 0.0;
    for (size_t j = 0; j < np; j++) {
        double psi = atan2(c->bo_e[2 * j + 1], c->bo_e[2 * j]), g = g0;
        for (int k = 0; k < b->n_distortion; k++)
            g += b->distortion[k].amplitude *
                 cos(b->distortion[k].order * (psi - b->distortion[k].phase_deg * M_PI / 180.0));
        c->bo_gap[j] = g;
    }
    return RD_OK;
}

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
    double tol = RES_TOL * c->p0 * c->bo_area, res = rc ? 0.0 : residual(c, y, r, tmp, R);
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
        double lam = 1.0, rnew = INFINITY;
        for (int h = 0; h < 30 && !(rnew < res); h++, lam *= 0.5) {
            memcpy(ytry, y, 12 * (size_t)c->n * sizeof *ytry);
            for (int i = 0; i < c->n; i++)
                for (int k = 0; k < 6; k++)
                    RD_LIFT_Q(ytry, i)[k] += lam * tmp[rd_ring_band_index(c->ring, i, k)];
            rnew = residual(c, ytry, r, tmp + N, R);
        }
        if (!(rnew < res))
            break;
        memcpy(y, ytry, 12 * (size_t)c->n * sizeof *y);
        res = rnew;
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
