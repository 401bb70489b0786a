/*
 * rd_static — the nonlinear mechanics of the segment chain and its solver,
 * shared by pretension (rd_pretension.c) and bore contact (rd_contact.c),
 * and its options' defaults and checks; rd_static.h has the model.
 *
 * Unknowns: per segment i the position x_i (3, m) and the rotation Q_i
 * (3x3 row-major, body to global).  Increments are (dx_i, dpsi_i), with the
 * rotation updated multiplicatively, Q_i <- exp([dpsi_i]x) Q_i (spatial
 * rotation vector), so the DOF vector of the linear solves is
 *   Delta[6i + 0..2] = dx_i,  Delta[6i + 3..5] = dpsi_i.
 *
 * Residual r = g_int - f_ext + g_support, g the gradient of the energy with
 * respect to (dx, dpsi).  For joint j (A, B), with Dx = x_B - x_A,
 * psi = log(Q_A^T Q_B) and [f; m] = Kc [d; t] (rd_static.h):
 *   F = Q_A E^T f,   Mg = Q_A Jl^-T(psi) E^T m,
 *   g_A = (-F, F x Dx - Mg),   g_B = (F, Mg),
 * Jl^-1 the inverse left Jacobian of SO(3) (a left perturbation w of
 * exp(psi) changes psi by Jl^-1(psi) w); rd_static_joint.c evaluates it.  A
 * force F at the point y of segment i contributes (F, (y - x_i) x F) to
 * f_ext.
 *
 * Tangent (rd_static_tangent.c): each joint's 12x12 block in closed form,
 * the contact loads' and the support's derivatives, block tridiagonal,
 * factored by the block Thomas algorithm (rd_blocktri.c), the planar
 * contact ring's in two uncoupled halves (plane_solve).  The field method
 * couples the first segment's load to the last segment's state, outside the
 * three block diagonals: that 6x6 block is added exactly by the Woodbury
 * identity on the factorization (newton_step).
 */
#include "rd_static_problem.h"

#include "rd_blocktri.h"

#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Support residual (added to g for segments pa, pb) and its force/moment. */
static void support_terms(const rd_static_problem *pb, double *g, double *force, double *moment)
{
    int s[2] = {pb->pa, pb->pb};
    double et[3] = {0, 0, 0}, er[3] = {0, 0, 0}, psi[2][3];
    for (int q = 0; q < 2; q++) {
        const double *P = rd_ring_reference_point(pb->ring, s[q]);
        rd_static_rot_log(pb->Q + 9 * s[q], psi[q]);
        for (int k = 0; k < 3; k++) {
            et[k] += 0.5 * (pb->x[3 * s[q] + k] - P[k]);
            er[k] += 0.5 * psi[q][k];
        }
    }
    double ft[3], mr[3];
    for (int k = 0; k < 3; k++) {
        ft[k] = pb->k_t * pb->mask[k] * et[k];
        mr[k] = pb->k_r * pb->mask[3 + k] * er[k];
    }
    if (force)
        *force = sqrt(rd_dot3(ft, ft));
    if (moment)
        *moment = sqrt(rd_dot3(mr, mr));
    if (!g)
        return;
    for (int q = 0; q < 2; q++) {
        double jm[3];
        rd_static_jl_inv_t(psi[q], mr, jm);
        for (int k = 0; k < 3; k++) {
            g[6 * s[q] + k] += 0.5 * ft[k];
            g[6 * s[q] + 3 + k] += 0.5 * jm[k];
        }
    }
}

/* Full residual r (6n) at the current state; returns the strain energy.
 * pre (NULL: not kept): r before the problem's own loads, for
 * residual_again. */
static double residual(const rd_static_problem *pb, double *r, double *pre)
{
    int n = pb->n;
    double energy = 0.0;
    memset(r, 0, (size_t)6 * n * sizeof *r);
    for (int j = 0; j < n - 1; j++) {
        double g[12], e;
        rd_static_joint_residual(pb, j, pb->x + 3 * j, pb->Q + 9 * j, pb->x + 3 * (j + 1),
                                 pb->Q + 9 * (j + 1), g, &e);
        energy += e;
        for (int k = 0; k < 12; k++)
            r[6 * j + k] += g[k];
    }
    for (int i = 0; i < n; i += n - 1) { /* the gap faces (segments 0, n - 1) */
        double f[6] = {0};
        rd_static_gap_face_load(pb, i, pb->x + 3 * i, pb->Q + 9 * i, f);
        for (int k = 0; k < 6; k++)
            r[6 * i + k] -= f[k];
    }
    if (pb->loads->residual) {
        if (pre)
            memcpy(pre, r, (size_t)6 * n * sizeof *r);
        pb->loads->residual(pb, r);
    }
    support_terms(pb, r, NULL, NULL);
    return energy;
}

/* Scaled infinity norm: forces / F_ref, moments / (F_ref R). */
static double residual_norm(const rd_static_problem *pb, const double *r)
{
    double worst = 0.0;
    for (int k = 0; k < 6 * pb->n; k++) {
        double v = fabs(r[k]) / (k % 6 < 3 ? pb->F_ref : pb->F_ref * pb->R);
        if (!(v <= worst))
            worst = v; /* NaN propagates */
    }
    return worst;
}

/* Gram-Schmidt on the rows, so repeated updates do not drift from SO(3). */
static void orthonormalize(double Q[9])
{
    double *a = Q, *b = Q + 3, *c = Q + 6, na = sqrt(rd_dot3(a, a));
    for (int k = 0; k < 3; k++)
        a[k] /= na;
    double ab = rd_dot3(a, b);
    for (int k = 0; k < 3; k++)
        b[k] -= ab * a[k];
    double nb = sqrt(rd_dot3(b, b));
    for (int k = 0; k < 3; k++)
        b[k] /= nb;
    rd_cross3(a, b, c);
}

/* Applies x += a dx, Q <- exp(a dpsi) Q. */
static void apply_step(rd_static_problem *pb, const double *delta, double a)
{
    for (int i = 0; i < pb->n; i++) {
        double w[3], Rw[9];
        for (int k = 0; k < 3; k++) {
            pb->x[3 * i + k] += a * delta[6 * i + k];
            w[k] = a * delta[6 * i + 3 + k];
        }
        rd_static_rot_exp(w, Rw);
        rd_mm3(Rw, pb->Q + 9 * i, pb->Q + 9 * i);
        orthonormalize(pb->Q + 9 * i);
    }
}

/* Scratch of one solve, and what Newton needs to report and be cancelled. */
typedef struct rd_static_work {
    double *r, *delta, *x0, *Q0, *xs, *Qs;
    double *pre;   /* the last residual before the problem's own loads */
    double *Y;     /* N x 6: the field method's Woodbury columns; NULL otherwise */
    rd_blocktri t; /* the tangent, then its factors */
    /* a planar problem: the tangent's in-plane and out-of-plane parts
     * (plane_solve) */
    rd_blocktri part[2];
    double *xh;   /* their right-hand sides, t.nb t.bs */
    int split;    /* the last tangent went into part, not t */
    int factored; /* t or part holds the factors of a recent tangent */
    /* the outer iterations' inexact solves (rd_static_resolve): newton
     * stops at min(loose, a tenth of its first residual) where that is
     * above tol (0: at tol) */
    double loose;
    const rd_monitor *mon;
    double progress; /* accepted load factor, reported as the solve's fraction */
    rd_error *err;
} work;

/* The field method's coupling of the first segment's load to the last
 * segment's state: C = -d f_ext(0) / d state(n-1), 6x6 column-major, by
 * central differences. */
static void field_coupling(rd_static_problem *pb, double C[36])
{
    int last = pb->n - 1;
    double hx = 1e-6 * pb->R, hr = 1e-6, x0[3], Q0[9];
    memcpy(x0, pb->x + 3 * last, sizeof x0);
    memcpy(Q0, pb->Q + 9 * last, sizeof Q0);
    for (int k = 0; k < 6; k++) {
        double h = k < 3 ? hx : hr, fp[6] = {0}, fm[6] = {0};
        rd_static_perturb(x0, Q0, k, h, pb->x + 3 * last, pb->Q + 9 * last);
        rd_static_gap_face_load(pb, 0, pb->x, pb->Q, fp);
        rd_static_perturb(x0, Q0, k, -h, pb->x + 3 * last, pb->Q + 9 * last);
        rd_static_gap_face_load(pb, 0, pb->x, pb->Q, fm);
        for (int r = 0; r < 6; r++)
            C[r + 6 * k] = -(fp[r] - fm[r]) / (2.0 * h);
    }
    memcpy(pb->x + 3 * last, x0, sizeof x0);
    memcpy(pb->Q + 9 * last, Q0, sizeof Q0);
}

/* A LAPACK info: > 0 is a singular tangent (the caller cuts the load step:
 * returns 1); < 0 is a bad argument, a bug (RD_EINTERNAL). */
static int lapack_status(int info, const char *routine, rd_error *err)
{
    if (info < 0)
        return rd_error_set(err, RD_EINTERNAL, "",
                            "Internal error: LAPACK %s rejected argument %d in the static solve.",
                            routine, -info);
    return info > 0 ? 1 : 0;
}

/* The field method's off-diagonal block by the Woodbury identity (newton_step).
 * Returns 0, 1 (singular) or < 0. */
static int woodbury(rd_static_problem *pb, work *w)
{
    int N = 6 * pb->n, off = 6 * (pb->n - 1), rc;
    double C[36], S[36], t[6];
    int piv[6];
    field_coupling(pb, C);
    memset(w->Y, 0, (size_t)6 * N * sizeof *w->Y);
    for (int c = 0; c < 6; c++)
        for (int r = 0; r < 6; r++)
            w->Y[(size_t)c * N + r] = C[r + 6 * c];
    for (int c = 0; c < 6; c++)
        rd_blocktri_solve(&w->t, w->Y + (size_t)c * N);
    for (int c = 0; c < 6; c++)
        for (int r = 0; r < 6; r++)
            S[r + 6 * c] = (r == c ? 1.0 : 0.0) + w->Y[(size_t)c * N + off + r];
    for (int r = 0; r < 6; r++)
        t[r] = w->delta[off + r];
    rc = LAPACKE_dgesv(LAPACK_COL_MAJOR, 6, 1, S, 6, piv, t, 6);
    if ((rc = lapack_status(rc, "dgesv", w->err)) != 0)
        return rc;
    for (int k = 0; k < N; k++)
        for (int c = 0; c < 6; c++)
            w->delta[k] -= w->Y[(size_t)c * N + k] * t[c];
    return 0;
}

/* The tangent at the last residual's state, Marquardt-damped by mu.  A
 * planar problem's ring (loads->planar: the contact ring) stays in its
 * plane (in-plane loads; the support holds the axial motion and the tilts;
 * measured: every state and tangent of the battery exactly planar, the
 * in-plane and out-of-plane DOFs coupled by no nonzero entry), so its
 * tangent falls into two uncoupled halves, assembled
 * and factored separately (rd_static_tangent_planar) at a quarter of the
 * cost with exactly the numbers of the whole: the partial pivoting never
 * picks an exact zero over a nonzero, so it makes the same choices, and
 * every operation the whole's factorization does across the halves adds or
 * subtracts an exact zero.  Where an entry couples them, the whole. */
static void tangent(rd_static_problem *pb, work *w, double mu)
{
    w->split = w->xh && rd_static_tangent_planar(pb, w->part, mu);
    if (!w->split)
        rd_static_tangent(pb, &w->t, mu);
}

/* newton_step's solve on the halves of a split tangent: 0, or 1 (singular). */
static int plane_solve(work *w, int reuse)
{
    if (!reuse && (rd_blocktri_factor(&w->part[0]) != 0 || rd_blocktri_factor(&w->part[1]) != 0))
        return 1;
    int hs = w->part[0].bs, bs = 2 * hs; /* a block's DOFs: in a half, in all */
    for (int h = 0; h < 2; h++) {
        double *x = w->xh + (size_t)h * hs * w->t.nb;
        for (int i = 0; i < w->t.nb; i++)
            for (int r = 0; r < hs; r++)
                x[hs * i + r] = w->delta[bs * i + 6 * (r / 3) + rd_plane_dof[h][r % 3]];
        rd_blocktri_solve(&w->part[h], x);
        for (int i = 0; i < w->t.nb; i++)
            for (int r = 0; r < hs; r++)
                w->delta[bs * i + 6 * (r / 3) + rd_plane_dof[h][r % 3]] = x[hs * i + r];
    }
    return 0;
}

/* Solves J delta = -r (w->delta holds -r on entry) with the factored
 * block-tridiagonal tangent in w->t.  For the field method J = J_tri + U V^T,
 * U = C in the first segment's rows, V selecting the last segment's DOFs,
 * solved exactly by the Woodbury identity on the factorization:
 *   delta = z - Y (I + V^T Y)^-1 V^T z,  J_tri z = -r,  J_tri Y = U.
 * A non-finite tangent shows in the step, which is checked and treated as
 * singular.  (The residual is finite here: newton checks it first.)  Returns
 * 0, 1 (singular tangent) or < 0 (w->err set). */
static int newton_step(rd_static_problem *pb, work *w, int reuse)
{
    int N = 6 * pb->n, rc = w->split ? plane_solve(w, reuse) : -1;
    if (rc > 0)
        return rc;
    if (rc < 0) {
        if (!reuse && rd_blocktri_factor(&w->t) != 0)
            return 1;
        rd_blocktri_solve(&w->t, w->delta);
    }
    if (w->Y && (rc = woodbury(pb, w)) != 0) /* the field method */
        return rc;
    for (int k = 0; k < N; k++)
        if (!isfinite(w->delta[k]))
            return 1;
    return 0;
}

/* The residual into w->r where only what the loads' outer iterations
 * change (the contact multipliers) changed since the last residual: its
 * part before the problem's own loads kept (w->pre), those loads again
 * (loads->residual_again: the contact points' law evaluated again at their
 * kept penetrations), the support as before: bit for bit residual's,
 * without the faces, the joints or the points' geometry (order 6 at 10 x,
 * 0 deg: 0.5 M instructions a call against 2.8 M for the whole residuals
 * of all its levels; rd_contact_solve 1.54 -> 1.31 G). */
static void residual_again(const rd_static_problem *pb, work *w)
{
    memcpy(w->r, w->pre, (size_t)6 * pb->n * sizeof *w->r);
    pb->loads->residual_again(pb, w->r);
    support_terms(pb, w->r, NULL, NULL);
}

/* Backtracking on the residual norm along w->delta from the state saved in
 * w->xs, w->Qs (best: the smallest residual norm of this Newton solve so
 * far).  Returns 1 and the new norm when a step was taken (the state moved),
 * 0 when none was (the state restored, w->r that of the step tried last).
 * `a` returns the step fraction taken.
 *
 * A full step may raise the residual at first: the chain's axial stiffness
 * turns the step's second-order length error into large forces that the next
 * iteration removes.  So the first iterations of a load step take it unless
 * it explodes (1e3 x the residual).  Contact takes every full step within
 * 1e3 x the solve's best residual (loads->full_steps; since 0.3.13): its law
 * switches from none to k delta over 0.05 p0 / k, and where many points lie
 * near that switch (long light gaps of a few nm: orders 2-4 at 0.3-1.2 x the
 * bound) the backtracked steps crawled, a residual falling by 3-6 % an
 * iteration at a = 1/16, until the load step failed after 40 iterations and
 * was cut to a quarter (bench_static --single --random 82 40 1: the finer
 * level's step 0.8 -> 1 at n = 640 failed after 40, then four steps of 0.05
 * took 43 more; with full steps the residual rose 14 x over three iterations
 * and the step converged in 13; the bore 0.47 -> 0.10 s CPU, the answer the
 * same within the solver's tolerances).  Measured on random bores, three
 * rings (bench_static [--ring ...] [--single] --random SEED 40): one order a
 * bore, seeds 81-86, 720 bores, CPU 76.8 -> 63.4 s, over 0.2 s 59 -> 24; one
 * or two orders, seeds 51-55, 600 bores, 72.2 -> 59.2 s, 42 -> 21; the same
 * bores within the targets (669, 534) and reporting the target met
 * (592 -> 591, 434).  Full steps until the 3rd, 6th, 10th, 20th iteration:
 * 76.8, 69.4, 68.2, 64.3 s; at every iteration within 1e3 x the last
 * residual (not the best): 62.5 s. */
static int line_search(rd_static_problem *pb, work *w, int it, double res, double best, double tol,
                       double *res_new, double *a)
{
    *a = 1.0;
    for (int ls = 0; ls < 8; ls++) {
        apply_step(pb, w->delta, *a);
        residual(pb, w->r, w->pre);
        *res_new = residual_norm(pb, w->r);
        int full = *a == 1.0 && ((it < 3 && *res_new < 1e3 * res) ||
                                 (pb->loads->full_steps && *res_new < 1e3 * best));
        if (*res_new < (1.0 - 1e-4 * *a) * res || *res_new <= tol || full)
            return 1;
        memcpy(pb->x, w->xs, (size_t)3 * pb->n * sizeof *pb->x);
        memcpy(pb->Q, w->Qs, (size_t)9 * pb->n * sizeof *pb->Q);
        *a *= 0.5;
    }
    return 0;
}

/* Largest step component: translations / R, rotations in rad. */
static double step_length(const rd_static_problem *pb, const double *delta)
{
    double step_len = 0.0;
    for (int i = 0; i < pb->n; i++)
        for (int k = 0; k < 6; k++)
            step_len = fmax(step_len, fabs(delta[6 * i + k]) / (k < 3 ? pb->R : 1.0));
    return step_len;
}

/* Newton iterations at the current load factor, Levenberg-Marquardt damped
 * when a plain step fails; the monitor is called once per iteration (one
 * tangent and factorization: well under 100 ms up to 2000 segments).  The
 * first `chord` iterations may reuse the last factorization instead (a
 * chord step: the loads' outer iterations, rd_static_resolve); one whose
 * line search fails is taken again with a fresh tangent.  `again`: only
 * what the outer iterations change (the contact multipliers) changed since
 * the last residual (residual_again).
 * Returns 1 converged, 0 not converged (caller cuts the load step), < 0 on
 * error or cancellation (w->err set). */
static int newton(rd_static_problem *pb, work *w, double tol, int *budget, rd_static_stats *st,
                  double *res_out, int chord, int again)
{
    int N = 6 * pb->n, rc;
    double mu = 0.0;
    if (again)
        residual_again(pb, w);
    else
        residual(pb, w->r, w->pre);
    double res = residual_norm(pb, w->r), best = res;
    double stop = w->loose > 0.0 ? fmax(tol, fmin(w->loose, 0.1 * res)) : tol;
    for (int it = 0; it < 40; it++) {
        best = fmin(best, res);
        if (res <= stop) {
            *res_out = res;
            return 1;
        }
        if (!isfinite(res) || *budget <= 0)
            return 0;
        if ((rc = rd_monitor_report(w->mon, w->progress, w->err)) != RD_OK)
            return rc;
        (*budget)--;
        st->iterations++;
        int reuse = it < chord && w->factored && mu == 0.0;
        if (!reuse) {
            tangent(pb, w, mu);
            st->factorizations++;
        }
        for (int k = 0; k < N; k++)
            w->delta[k] = -w->r[k];
        w->factored = 0;
        if ((rc = newton_step(pb, w, reuse)) != 0)
            return rc < 0 ? rc : 0;
        w->factored = 1;
        double step_len = step_length(pb, w->delta), res_new, a;
        memcpy(w->xs, pb->x, (size_t)3 * pb->n * sizeof *pb->x);
        memcpy(w->Qs, pb->Q, (size_t)9 * pb->n * sizeof *pb->Q);
        if (!line_search(pb, w, it, res, best, tol, &res_new, &a)) {
            residual(pb, w->r, w->pre);
            if (reuse) {
                chord = 0;
                continue;
            }
            /* at the rounding floor if the step is negligible */
            if (step_len < 1e-12 && res < 1e3 * tol) {
                *res_out = res;
                return 1;
            }
            /* otherwise damp harder and try again from the same state */
            mu = mu > 0.0 ? 100.0 * mu : 1e-10;
            if (mu > 1.0)
                return 0;
            continue;
        }
        mu = mu > 1e-10 ? 0.1 * mu : 0.0;
        res = res_new;
        if (step_len * a < 1e-14 && res < 1e3 * tol) {
            *res_out = res;
            return 1;
        }
    }
    return 0;
}

static void work_free(work *w)
{
    free(w->r);
    free(w->delta);
    free(w->x0);
    free(w->Q0);
    free(w->xs);
    free(w->pre);
    free(w->Qs);
    free(w->Y);
    free(w->xh);
    rd_blocktri_cleanup(&w->t);
    rd_blocktri_cleanup(&w->part[0]);
    rd_blocktri_cleanup(&w->part[1]);
}

static int work_alloc(const rd_static_problem *pb, work *w, rd_error *err)
{
    int n = pb->n, N = 6 * n, s = rd_static_per_block(pb), nb = (n + s - 1) / s;
    w->r = malloc((size_t)N * sizeof *w->r);
    w->delta = calloc((size_t)6 * s * nb, sizeof *w->delta); /* the dummy's 6 stay 0 */
    w->x0 = malloc((size_t)3 * n * sizeof *w->x0);
    w->Q0 = malloc((size_t)9 * n * sizeof *w->Q0);
    w->xs = malloc((size_t)3 * n * sizeof *w->xs);
    w->Qs = malloc((size_t)9 * n * sizeof *w->Qs);
    int need_y = pb->method == RD_PRETENSION_FIELD; /* the gap faces' field method: woodbury */
    if (need_y)
        w->Y = malloc((size_t)6 * N * sizeof *w->Y);
    int halves = pb->loads->planar; /* plane_solve */
    if (halves)
        w->xh = malloc((size_t)6 * s * nb * sizeof *w->xh);
    int again = pb->loads->residual_again != NULL; /* residual_again */
    if (again)
        w->pre = malloc((size_t)N * sizeof *w->pre);
    if ((need_y && !w->Y) || !w->r || !w->delta || !w->x0 || !w->Q0 || !w->xs || !w->Qs ||
        rd_blocktri_init(&w->t, nb, 6 * s) != RD_OK || (again && !w->pre) ||
        (halves && (!w->xh || rd_blocktri_init(&w->part[0], nb, 3 * s) != RD_OK ||
                    rd_blocktri_init(&w->part[1], nb, 3 * s) != RD_OK)))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the %d-segment static solve.",
                            n);
    return RD_OK;
}

/* The load-stepping loop (rd_static_solve_path). */
static int load_steps(rd_static_problem *pb, work *w, double tol, int *budget_io,
                      rd_static_stats *st)
{
    int n = pb->n, budget = *budget_io;
    double lam = pb->lambda_start, dlam = pb->step_start > 0.0 ? pb->step_start : 1.0, res = 0.0;
    pb->lambda = lam;
    if (lam >= 1.0) {
        /* started at the full load (a solved state, another law): Newton
         * there first, so that the multipliers' first update reads a
         * residual's evaluation of this problem (rd_static_tangent.c's call
         * order; without it the stiffness probe read a stale store and set
         * the multipliers to ~1e18 p0 before recovering) */
        int ok = newton(pb, w, tol, &budget, st, &res, 0, 0);
        if (ok < 0)
            return ok;
        if (!ok)
            return rd_error_set(w->err, RD_ENOCONV, "",
                                "The static solve did not converge: Newton's method stalled at "
                                "the full load from the given state after %d iterations.",
                                st->iterations);
    }
    while (lam < 1.0) {
        double target = fmin(1.0, lam + dlam);
        memcpy(w->x0, pb->x, (size_t)3 * n * sizeof *pb->x);
        memcpy(w->Q0, pb->Q, (size_t)9 * n * sizeof *pb->Q);
        if (pb->loads->predict)
            pb->loads->predict(pb, lam, target);
        pb->lambda = target;
        int before = st->iterations;
        int ok = newton(pb, w, tol, &budget, st, &res, 0, 0);
        if (ok < 0)
            return ok;
        if (ok) {
            if (pb->step_taken == 0.0)
                pb->step_taken = target - lam;
            lam = target;
            st->load_steps++;
            if (st->iterations - before <= 6)
                dlam = fmin(1.0, 2.0 * dlam);
            w->progress = lam;
            continue;
        }
        memcpy(pb->x, w->x0, (size_t)3 * n * sizeof *pb->x);
        memcpy(pb->Q, w->Q0, (size_t)9 * n * sizeof *pb->Q);
        pb->lambda = lam;
        /* a quarter of the step that failed, not of dlam: a step clipped
         * at the full load (a warm start's from BORE_DONE) would otherwise
         * be tried again unchanged (order 3 at 1.22 x, 98 deg, n = 320-1280:
         * a failed try of 40 Newton iterations repeated each level; at n =
         * 1280 the level's iterations 132 -> 95) */
        dlam = 0.25 * (target - lam);
        if (budget <= 0 || dlam < 1e-6)
            return rd_error_set(
                w->err, RD_ENOCONV, "",
                "The static solve did not converge: Newton's method stalled at load factor %.4g "
                "of 1 after %d iterations (%s). The load may exceed what the model can carry "
                "(e.g. the gap ends meeting, or the ring losing the bore): check the loads, or "
                "raise /numerics/max_iterations.",
                lam, st->iterations,
                budget <= 0 ? "iteration budget used up" : "load step became too small");
    }
    st->residual = res;
    *budget_io = budget;
    return rd_monitor_report(w->mon, 1.0, w->err);
}

int rd_static_solve_path(rd_static_problem *pb, const rd_static_opts *so, const rd_monitor *mon,
                         rd_static_stats *st, rd_error *err)
{
    work w = {0};
    int rc = work_alloc(pb, &w, err);
    if (rc == RD_OK) {
        w.mon = mon;
        w.err = err;
        /* Rounding floor: the stiffest spring (joint axial EA/L, or the
         * loads', a contact point's k A) times a position's last bits
         * (measured: up to ~1000 eps R), over F_ref. */
        double kmax = pb->loads->stiffest ? pb->loads->stiffest(pb) : 0.0;
        for (int j = 0; j < rd_ring_get_joints(pb->ring); j++)
            kmax = fmax(kmax, pb->Kc[36 * j]);
        double noise = 1024.0 * DBL_EPSILON * kmax * pb->R / pb->F_ref;
        double tol = fmax(so->tol, noise);
        st->tolerance = tol;
        st->iterations = st->factorizations = 0;
        st->outer_iterations = 0;
        st->outer_change = st->outer_tolerance = 0.0;
        st->load_steps = 0;
        int budget = so->max_iterations;
        rc = load_steps(pb, &w, tol, &budget, st);
        if (rc == RD_OK && pb->loads->outer) {
            rd_static_session s = {tol, budget, so, st, err, &w};
            rc = pb->loads->outer(pb, &s);
        }
    }
    work_free(&w);
    return rc;
}

int rd_static_resolve(rd_static_problem *pb, rd_static_session *s, int chord, int again,
                      double loose, double *res)
{
    s->work->loose = loose;
    int ok = newton(pb, s->work, s->tol, &s->budget, s->st, res, chord, again);
    s->work->loose = 0.0;
    return ok;
}

void rd_static_stats_fill(rd_static_problem *pb, rd_static_stats *st)
{
    double *r = malloc((size_t)6 * pb->n * sizeof *r);
    st->segments = pb->n;
    st->dof = 6 * pb->n;
    st->strain_energy = r ? residual(pb, r, NULL) : NAN;
    free(r);
    support_terms(pb, NULL, &st->support_force, &st->support_moment);
}

/* ---- the solver's options (pretension's and contact's) ------------------- */

void rd_static_opts_default(rd_static_opts *o)
{
    o->tol = 1e-9;
    o->max_iterations = 2000;
    o->estimate_error = 1;
    o->max_updates = 60;
    o->update_eta = 0.03;
}

/* A split ring of 4..RD_STATIC_SEGMENTS_MAX segments, in the
 * discretization block. */
static int discretization_checks(int segments, int closed, rd_error *err)
{
    if (closed)
        return rd_error_set(err, RD_EINVAL, "/closed",
                            "@/closed = true joins the gap, but pretension and contact act on "
                            "the gap faces: use a split ring (closed = false).");
    if (segments < 4 || segments > RD_STATIC_SEGMENTS_MAX)
        return rd_error_set(err, segments > RD_STATIC_SEGMENTS_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/segments",
                            "@/segments = %d is out of range for a static analysis: allowed 4 "
                            "to %d.",
                            segments, RD_STATIC_SEGMENTS_MAX);
    return RD_OK;
}

/* The tolerance and the iteration bound, in the numerics block. */
static int numerics_checks(const rd_static_opts *o, rd_error *err)
{
    if (!isfinite(o->tol) || o->tol < 1e-13 || o->tol > 1e-3)
        return rd_error_set(err, RD_EINVAL, "/tolerance",
                            "@/tolerance = %g is out of range: allowed 1e-13 to 1e-3.", o->tol);
    if (o->max_iterations < 1 || o->max_iterations > 100000)
        return rd_error_set(
            err, o->max_iterations > 100000 ? RD_ELIMIT : RD_EINVAL, "/max_iterations",
            "@/max_iterations = %d is out of range: allowed 1 to 100000.", o->max_iterations);
    return RD_OK;
}

int rd_static_validate(const rd_static_opts *o, int segments, int closed, rd_error *err)
{
    size_t m = rd_error_enter(err, "/discretization");
    int rc = discretization_checks(segments, closed, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/numerics");
    rc = rc ? rc : numerics_checks(o, err);
    rd_error_leave(err, m);
    if (rc)
        return rc;
    if (o->max_updates < 1 || o->max_updates > 1000) /* core's own: not in the API */
        return rd_error_set(err, RD_EINVAL, "",
                            "rd_static_opts.max_updates = %d is out of range: allowed 1 to 1000.",
                            o->max_updates);
    if (!(o->update_eta >= 0.0 && o->update_eta <= 1.0)) /* core's own: not in the API */
        return rd_error_set(err, RD_EINVAL, "",
                            "rd_static_opts.update_eta = %g is out of range: allowed 0 to 1.",
                            o->update_eta);
    return RD_OK;
}
