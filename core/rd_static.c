/*
 * rd_static — nonlinear statics of the segment chain: pretension and bore
 * contact (rd_static.h has the model; this file the numbers).
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
 * exp(psi) changes psi by Jl^-1(psi) w).  A force F at the point y of
 * segment i contributes (F, (y - x_i) x F) to f_ext.
 *
 * Tangent: central differences of these element residuals, element by
 * element (12 perturbations per joint, 6 per loaded segment), assembled in
 * LAPACK general band storage (half bandwidth 11) and factored by dgbtrf.
 * The field method couples the first segment's load to the last segment's
 * state, outside the band: that 6x6 block is added exactly by the Woodbury
 * identity on the band factorization (newton_step).
 */
#include "rd_internal.h"
#include "rd_static.h"

#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { PRETENSION = 0, CONTACT = 1 };

#define KL 11 /* half bandwidth of the split ring's tangent, in DOFs */

/* ---- 3-vectors and 3x3 rotations (row-major) ------------------------------ */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                   a[0] * b[1] - a[1] * b[0]};
    memcpy(out, c, sizeof c);
}

/* out = A v */
static void mv3(const double A[9], const double v[3], double out[3])
{
    double c[3];
    for (int r = 0; r < 3; r++)
        c[r] = A[3 * r] * v[0] + A[3 * r + 1] * v[1] + A[3 * r + 2] * v[2];
    memcpy(out, c, sizeof c);
}

/* out = A^T v */
static void mtv3(const double A[9], const double v[3], double out[3])
{
    double c[3];
    for (int r = 0; r < 3; r++)
        c[r] = A[r] * v[0] + A[3 + r] * v[1] + A[6 + r] * v[2];
    memcpy(out, c, sizeof c);
}

/* out = A B */
static void mm3(const double A[9], const double B[9], double out[9])
{
    double c[9];
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            c[3 * r + q] = A[3 * r] * B[q] + A[3 * r + 1] * B[3 + q] + A[3 * r + 2] * B[6 + q];
    memcpy(out, c, sizeof c);
}

/* out = A^T B */
static void mtm3(const double A[9], const double B[9], double out[9])
{
    double c[9];
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            c[3 * r + q] = A[r] * B[q] + A[3 + r] * B[3 + q] + A[6 + r] * B[6 + q];
    memcpy(out, c, sizeof c);
}

/* Rodrigues: R = exp([w]x). */
static void rot_exp(const double w[3], double R[9])
{
    double th2 = dot3(w, w), th = sqrt(th2), a, b;
    if (th < 1e-4) {
        a = 1.0 - th2 / 6.0 * (1.0 - th2 / 20.0);
        b = 0.5 - th2 / 24.0 * (1.0 - th2 / 30.0);
    } else {
        a = sin(th) / th;
        b = (1.0 - cos(th)) / th2;
    }
    double W[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0}, W2[9];
    mm3(W, W, W2);
    for (int k = 0; k < 9; k++)
        R[k] = (k % 4 == 0 ? 1.0 : 0.0) + a * W[k] + b * W2[k];
}

/* Rotation vector of R (|w| < pi; the chain's relative rotations are far
 * from pi, and the support's are held near zero). */
static void rot_log(const double R[9], double w[3])
{
    double v[3] = {0.5 * (R[7] - R[5]), 0.5 * (R[2] - R[6]), 0.5 * (R[3] - R[1])};
    double s = sqrt(dot3(v, v)), c = 0.5 * (R[0] + R[4] + R[8] - 1.0);
    double th = atan2(s, c);
    double f = s < 1e-8 ? 1.0 + th * th / 6.0 : th / s;
    for (int k = 0; k < 3; k++)
        w[k] = f * v[k];
}

/* out = Jl^-T(psi) v = v + 1/2 psi x v + c psi x (psi x v)  (Jl^-1 with the
 * sign of the middle term flipped), c = 1/th^2 - (1 + cos th)/(2 th sin th). */
static void jl_inv_t(const double psi[3], const double v[3], double out[3])
{
    double th2 = dot3(psi, psi), th = sqrt(th2), c;
    if (th < 1e-3)
        c = 1.0 / 12.0 + th2 / 720.0;
    else
        c = 1.0 / th2 - (1.0 + cos(th)) / (2.0 * th * sin(th));
    double pv[3], ppv[3];
    cross3(psi, v, pv);
    cross3(psi, pv, ppv);
    for (int k = 0; k < 3; k++)
        out[k] = v[k] + 0.5 * pv[k] + c * ppv[k];
}

/* ---- the problem ---------------------------------------------------------- */

typedef struct problem {
    const rd_ring *ring;
    int n, kind;
    double R, b, h;
    const double *Kc;
    double *E;   /* 9 per joint: rows chord, axial, radial */
    double *dP0; /* 3 per joint: P_B - P_A */
    double *x;   /* 3n */
    double *Q;   /* 9n */
    double lambda;
    /* gap-face loads */
    double Ft, Fl;
    int method;
    int jseg; /* field method: the segment whose face carries the J marker */
    double cA[3], cB[3]; /* face centroids, body offsets of segments 0, n-1 */
    double tA[3], tB[3]; /* face forces' directions, body components */
    /* support at the section opposite the gap */
    int pa, pb;
    double mask[6];
    double k_t, k_r;
    /* contact */
    int m;          /* points per segment */
    double *cp;     /* 3 per point: body offsets */
    double area;    /* tributary area of one point, m^2 */
    double r_o;     /* running-face radius of the closed ring */
    double bore_dr; /* D/2 - r_o */
    const rd_contact_opts *co;
    double k, eps, p0;
    /* scales */
    double F_ref;
} problem;

/* The load path.  Pretension: F_t and F_l grow with lambda.  Contact: the
 * pretension first (lambda 0..1/2, the bore still the ring's closed shape,
 * so the ring is pressed on it throughout), then the bore's departure from
 * that shape (lambda 1/2..1) with the ring already pressed on it: a bore
 * moving away from an unloaded ring would leave it floating, and Newton
 * with it. */
static double force_factor(const problem *pb)
{
    return pb->kind == CONTACT ? fmin(1.0, 2.0 * pb->lambda) : pb->lambda;
}

static double bore_factor(const problem *pb)
{
    return fmax(0.0, 2.0 * pb->lambda - 1.0);
}

/* Bore radius and its derivative at theta, at the current load factor. */
static void bore_radius(const problem *pb, double theta, double *r, double *dr)
{
    double a = pb->bore_dr, da = 0.0;
    for (int k = 0; k < pb->co->n_distortion; k++) {
        const rd_distortion *d = &pb->co->distortion[k];
        double arg = d->order * (theta - d->phase_deg * M_PI / 180.0);
        a += d->amplitude * cos(arg);
        da -= d->amplitude * d->order * sin(arg);
    }
    double mu = bore_factor(pb);
    *r = pb->r_o + mu * a;
    *dr = mu * da;
}

/* The smooth contact law p(delta) = k eps ln(1 + exp(delta / eps)). */
static double contact_pressure(const problem *pb, double delta)
{
    double z = delta / pb->eps;
    if (z > 0)
        return pb->k * (delta + pb->eps * log1p(exp(-z)));
    return pb->k * pb->eps * log1p(exp(z));
}

/* Elastic residual of joint j for the given end states (g: 12 values). */
static void joint_residual(const problem *pb, int j, const double *xA, const double *QA,
                           const double *xB, const double *QB, double g[12], double *energy)
{
    const double *E = pb->E + 9 * j, *dP0 = pb->dP0 + 3 * j, *Kc = pb->Kc;
    double Dx[3] = {xB[0] - xA[0], xB[1] - xA[1], xB[2] - xA[2]};
    double dl[3], Rrel[9], psi[3], dt[6], fm[6];
    mtv3(QA, Dx, dl);
    for (int k = 0; k < 3; k++)
        dl[k] -= dP0[k];
    mv3(E, dl, dt);
    mtm3(QA, QB, Rrel);
    rot_log(Rrel, psi);
    mv3(E, psi, dt + 3);
    for (int r = 0; r < 6; r++) {
        fm[r] = 0.0;
        for (int c = 0; c < 6; c++)
            fm[r] += Kc[6 * r + c] * dt[c];
    }
    if (energy) {
        double e = 0.0;
        for (int r = 0; r < 6; r++)
            e += 0.5 * dt[r] * fm[r];
        *energy = e;
    }
    double Ef[3], F[3], Em[3], Jm[3], Mg[3], FxD[3];
    mtv3(E, fm, Ef);
    mv3(QA, Ef, F);
    mtv3(E, fm + 3, Em);
    jl_inv_t(psi, Em, Jm);
    mv3(QA, Jm, Mg);
    cross3(F, Dx, FxD);
    for (int k = 0; k < 3; k++) {
        g[k] = -F[k];
        g[3 + k] = FxD[k] - Mg[k];
        g[6 + k] = F[k];
        g[9 + k] = Mg[k];
    }
}

/* Adds (F, (y - x) x F) for a force F at body offset c of a segment at (x, Q). */
static void add_force(const double *Q, const double c[3], const double F[3], double f[6])
{
    double arm[3], M[3];
    mv3(Q, c, arm);
    cross3(arm, F, M);
    for (int k = 0; k < 3; k++) {
        f[k] += F[k];
        f[3 + k] += M[k];
    }
}

/* Field method: the force on the J face (follows that face) and the point
 * where it acts. */
static void field_force(const problem *pb, const double *xJ, const double *QJ, double F[3],
                        double pJ[3])
{
    int first = pb->jseg == 0;
    double t[3], c[3];
    mv3(QJ, first ? pb->tA : pb->tB, t);
    mv3(QJ, first ? pb->cA : pb->cB, c);
    for (int k = 0; k < 3; k++) {
        F[k] = force_factor(pb) * pb->Ft * t[k];
        pJ[k] = xJ[k] + c[k];
    }
}

/* External generalized force on segment i (6 values) at state (x, Q); other
 * segments' states are read from pb (the field method's pair).  Returns 0
 * when the segment carries no load. */
/* The gap-face loads on segment i (0 or n - 1): the pretension F_t, by the
 * force or the field method, and the lateral force F_l (0 in contact). */
static void gap_face_load(const problem *pb, int i, const double *x, const double *Q,
                          double f[6])
{
    const double *c = i == 0 ? pb->cA : pb->cB;
    double F[3];
    if (pb->method == RD_PRETENSION_FIELD) {
        double FJ[3], pJ[3];
        if (i == pb->jseg) {
            field_force(pb, x, Q, F, pJ);
        } else {
            /* equal and opposite vector on the I face, plus the couple that
             * keeps the pair's moment zero */
            double arm[3], M[3];
            field_force(pb, pb->x + 3 * pb->jseg, pb->Q + 9 * pb->jseg, FJ, pJ);
            mv3(Q, c, arm);
            for (int k = 0; k < 3; k++) {
                F[k] = -FJ[k];
                arm[k] += x[k] - pJ[k];
            }
            cross3(arm, FJ, M);
            for (int k = 0; k < 3; k++)
                f[3 + k] += M[k];
        }
    } else {
        double t[3];
        mv3(Q, i == 0 ? pb->tA : pb->tB, t);
        for (int k = 0; k < 3; k++)
            F[k] = force_factor(pb) * pb->Ft * t[k];
    }
    F[2] += (i == 0 ? 1.0 : -1.0) * pb->lambda * pb->Fl;
    add_force(Q, c, F, f);
}

static int segment_load(const problem *pb, int i, const double *x, const double *Q, double f[6])
{
    int loaded = 0;
    memset(f, 0, 6 * sizeof *f);
    if (i == 0 || i == pb->n - 1) {
        gap_face_load(pb, i, x, Q, f);
        loaded = 1;
    }
    if (pb->kind == CONTACT) {
        for (int k = 0; k < pb->m; k++) {
            const double *c = pb->cp + 3 * (pb->m * i + k);
            double arm[3], y[3];
            mv3(Q, c, arm);
            for (int q = 0; q < 3; q++)
                y[q] = x[q] + arm[q];
            double rho = hypot(y[0], y[1]), th = atan2(y[1], y[0]), rb, drb;
            bore_radius(pb, th, &rb, &drb);
            double p = contact_pressure(pb, rho - rb);
            /* outward bore normal ~ grad(rho - r_b(theta)) = e_rho - r_b'/rho e_theta */
            double er[2] = {y[0] / rho, y[1] / rho}, et[2] = {-er[1], er[0]};
            double nv[3] = {er[0] - drb / rho * et[0], er[1] - drb / rho * et[1], 0.0};
            double nn = sqrt(dot3(nv, nv));
            double F[3] = {-p * pb->area * nv[0] / nn, -p * pb->area * nv[1] / nn, 0.0};
            add_force(Q, c, F, f);
        }
        loaded = 1;
    }
    return loaded;
}

/* Support residual (added to g for segments pa, pb) and its force/moment. */
static void support_terms(const problem *pb, double *g, double *force, double *moment)
{
    int s[2] = {pb->pa, pb->pb};
    double et[3] = {0, 0, 0}, er[3] = {0, 0, 0}, psi[2][3];
    for (int q = 0; q < 2; q++) {
        const double *P = rd_ring_reference_point(pb->ring, s[q]);
        rot_log(pb->Q + 9 * s[q], psi[q]);
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
        *force = sqrt(dot3(ft, ft));
    if (moment)
        *moment = sqrt(dot3(mr, mr));
    if (!g)
        return;
    for (int q = 0; q < 2; q++) {
        double jm[3];
        jl_inv_t(psi[q], mr, jm);
        for (int k = 0; k < 3; k++) {
            g[6 * s[q] + k] += 0.5 * ft[k];
            g[6 * s[q] + 3 + k] += 0.5 * jm[k];
        }
    }
}

/* Full residual r (6n) at the current state; returns the strain energy. */
static double residual(const problem *pb, double *r)
{
    int n = pb->n;
    double energy = 0.0;
    memset(r, 0, (size_t)6 * n * sizeof *r);
    for (int j = 0; j < n - 1; j++) {
        double g[12], e;
        joint_residual(pb, j, pb->x + 3 * j, pb->Q + 9 * j, pb->x + 3 * (j + 1),
                       pb->Q + 9 * (j + 1), g, &e);
        energy += e;
        for (int k = 0; k < 12; k++)
            r[6 * j + k] += g[k];
    }
    for (int i = 0; i < n; i++) {
        double f[6];
        if (segment_load(pb, i, pb->x + 3 * i, pb->Q + 9 * i, f))
            for (int k = 0; k < 6; k++)
                r[6 * i + k] -= f[k];
    }
    support_terms(pb, r, NULL, NULL);
    return energy;
}

/* Scaled infinity norm: forces / F_ref, moments / (F_ref R). */
static double residual_norm(const problem *pb, const double *r)
{
    double worst = 0.0;
    for (int k = 0; k < 6 * pb->n; k++) {
        double v = fabs(r[k]) / (k % 6 < 3 ? pb->F_ref : pb->F_ref * pb->R);
        if (!(v <= worst))
            worst = v; /* NaN propagates */
    }
    return worst;
}

/* Perturbed copy of one segment state: direction k (0..2 translate, 3..5
 * rotate) by h. */
static void perturb(const double *x, const double *Q, int k, double h, double xo[3],
                    double Qo[9])
{
    memcpy(xo, x, 3 * sizeof *x);
    memcpy(Qo, Q, 9 * sizeof *Q);
    if (k < 3) {
        xo[k] += h;
    } else {
        double w[3] = {0, 0, 0}, Rw[9];
        w[k - 3] = h;
        rot_exp(w, Rw);
        mm3(Rw, Q, Qo);
    }
}

/* Band storage for LAPACKE_dgbsv (column-major, kl = ku = KL). */
#define LDAB (3 * KL + 1)
static void band_add(double *ab, int row, int col, double v)
{
    if (abs(row - col) > KL)
        return;
    ab[(size_t)col * LDAB + (size_t)(2 * KL + row - col)] += v;
}

/* Central-difference tangent of the whole residual. */
static void tangent(problem *pb, double *ab)
{
    int n = pb->n;
    double hx = 1e-6 * pb->R, hr = 1e-6;
    memset(ab, 0, (size_t)LDAB * 6 * n * sizeof *ab);
    for (int j = 0; j < n - 1; j++) {
        double *xs[2] = {pb->x + 3 * j, pb->x + 3 * (j + 1)};
        double *Qs[2] = {pb->Q + 9 * j, pb->Q + 9 * (j + 1)};
        for (int col = 0; col < 12; col++) {
            int side = col / 6, k = col % 6;
            double h = k < 3 ? hx : hr, gp[12], gm[12], xp[3], Qp[9];
            const double *xa[2] = {xs[0], xs[1]}, *Qa[2] = {Qs[0], Qs[1]};
            perturb(xs[side], Qs[side], k, h, xp, Qp);
            xa[side] = xp;
            Qa[side] = Qp;
            joint_residual(pb, j, xa[0], Qa[0], xa[1], Qa[1], gp, NULL);
            perturb(xs[side], Qs[side], k, -h, xp, Qp);
            joint_residual(pb, j, xa[0], Qa[0], xa[1], Qa[1], gm, NULL);
            for (int row = 0; row < 12; row++)
                band_add(ab, 6 * j + row, 6 * j + col, (gp[row] - gm[row]) / (2.0 * h));
        }
    }
    /* The contact law bends over the length eps: difference well inside it. */
    double hc = pb->kind == CONTACT ? fmin(hx, 0.02 * pb->eps) : hx;
    for (int i = 0; i < n; i++) {
        double f0[6];
        if (!segment_load(pb, i, pb->x + 3 * i, pb->Q + 9 * i, f0))
            continue;
        for (int k = 0; k < 6; k++) {
            double h = k < 3 ? hc : hc / pb->R, fp[6], fm[6], xp[3], Qp[9];
            perturb(pb->x + 3 * i, pb->Q + 9 * i, k, h, xp, Qp);
            segment_load(pb, i, xp, Qp, fp);
            perturb(pb->x + 3 * i, pb->Q + 9 * i, k, -h, xp, Qp);
            segment_load(pb, i, xp, Qp, fm);
            for (int row = 0; row < 6; row++)
                band_add(ab, 6 * i + row, 6 * i + k, -(fp[row] - fm[row]) / (2.0 * h));
        }
    }
    /* support: translations 1/4 k_t mask; rotations 1/4 k_r A_a mask A_c^T
     * with A = Jl^-T(psi) (the derivative of log on each side; the held mean
     * rotation is ~0 but each segment's own psi is not) */
    int s[2] = {pb->pa, pb->pb};
    double A[2][9];
    for (int q = 0; q < 2; q++) {
        double psi[3];
        rot_log(pb->Q + 9 * s[q], psi);
        for (int k = 0; k < 3; k++) {
            double e[3] = {0, 0, 0}, col[3];
            e[k] = 1.0;
            jl_inv_t(psi, e, col);
            for (int r = 0; r < 3; r++)
                A[q][3 * r + k] = col[r];
        }
    }
    for (int a = 0; a < 2; a++)
        for (int c = 0; c < 2; c++) {
            for (int k = 0; k < 3; k++)
                band_add(ab, 6 * s[a] + k, 6 * s[c] + k, 0.25 * pb->k_t * pb->mask[k]);
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++) {
                    double v = 0.0;
                    for (int k = 0; k < 3; k++)
                        v += A[a][3 * r + k] * pb->mask[3 + k] * A[c][3 * q + k];
                    band_add(ab, 6 * s[a] + 3 + r, 6 * s[c] + 3 + q, 0.25 * pb->k_r * v);
                }
        }
}

/* Gram-Schmidt on the rows, so repeated updates do not drift from SO(3). */
static void orthonormalize(double Q[9])
{
    double *a = Q, *b = Q + 3, *c = Q + 6, na = sqrt(dot3(a, a));
    for (int k = 0; k < 3; k++)
        a[k] /= na;
    double ab = dot3(a, b);
    for (int k = 0; k < 3; k++)
        b[k] -= ab * a[k];
    double nb = sqrt(dot3(b, b));
    for (int k = 0; k < 3; k++)
        b[k] /= nb;
    cross3(a, b, c);
}

/* Applies x += a dx, Q <- exp(a dpsi) Q. */
static void apply_step(problem *pb, const double *delta, double a)
{
    for (int i = 0; i < pb->n; i++) {
        double w[3], Rw[9];
        for (int k = 0; k < 3; k++) {
            pb->x[3 * i + k] += a * delta[6 * i + k];
            w[k] = a * delta[6 * i + 3 + k];
        }
        rot_exp(w, Rw);
        mm3(Rw, pb->Q + 9 * i, pb->Q + 9 * i);
        orthonormalize(pb->Q + 9 * i);
    }
}

typedef struct work {
    double *r, *delta, *ab, *x0, *Q0, *xs, *Qs;
    double *Y; /* N x 6: the field method's Woodbury columns; NULL otherwise */
    int *ipiv;
} work;

/* The field method's coupling of the first segment's load to the last
 * segment's state: C = -d f_ext(0) / d state(n-1), 6x6 column-major, by
 * central differences. */
static void field_coupling(problem *pb, double C[36])
{
    int last = pb->n - 1;
    double hx = 1e-6 * pb->R, hr = 1e-6, x0[3], Q0[9];
    memcpy(x0, pb->x + 3 * last, sizeof x0);
    memcpy(Q0, pb->Q + 9 * last, sizeof Q0);
    for (int k = 0; k < 6; k++) {
        double h = k < 3 ? hx : hr, fp[6], fm[6];
        perturb(x0, Q0, k, h, pb->x + 3 * last, pb->Q + 9 * last);
        segment_load(pb, 0, pb->x, pb->Q, fp);
        perturb(x0, Q0, k, -h, pb->x + 3 * last, pb->Q + 9 * last);
        segment_load(pb, 0, pb->x, pb->Q, fm);
        for (int r = 0; r < 6; r++)
            C[r + 6 * k] = -(fp[r] - fm[r]) / (2.0 * h);
    }
    memcpy(pb->x + 3 * last, x0, sizeof x0);
    memcpy(pb->Q + 9 * last, Q0, sizeof Q0);
}

/* Solves J delta = -r (w->delta holds -r on entry) with the band tangent in
 * w->ab.  For the field method J = J_band + U V^T, U = C in the first
 * segment's rows, V selecting the last segment's DOFs, solved exactly by the
 * Woodbury identity on the band factorization:
 *   delta = z - Y (I + V^T Y)^-1 V^T z,  J_band z = -r,  J_band Y = U. */
static int newton_step(problem *pb, work *w)
{
    int N = 6 * pb->n, off = 6 * (pb->n - 1);
    if (LAPACKE_dgbtrf(LAPACK_COL_MAJOR, N, N, KL, KL, w->ab, LDAB, w->ipiv) != 0)
        return -1;
    if (LAPACKE_dgbtrs(LAPACK_COL_MAJOR, 'N', N, KL, KL, 1, w->ab, LDAB, w->ipiv, w->delta, N) !=
        0)
        return -1;
    if (!(pb->kind == PRETENSION && pb->method == RD_PRETENSION_FIELD && w->Y))
        return 0;
    double C[36], S[36], t[6];
    int piv[6];
    field_coupling(pb, C);
    memset(w->Y, 0, (size_t)6 * N * sizeof *w->Y);
    for (int c = 0; c < 6; c++)
        for (int r = 0; r < 6; r++)
            w->Y[(size_t)c * N + r] = C[r + 6 * c];
    if (LAPACKE_dgbtrs(LAPACK_COL_MAJOR, 'N', N, KL, KL, 6, w->ab, LDAB, w->ipiv, w->Y, N) != 0)
        return -1;
    for (int c = 0; c < 6; c++)
        for (int r = 0; r < 6; r++)
            S[r + 6 * c] = (r == c ? 1.0 : 0.0) + w->Y[(size_t)c * N + off + r];
    for (int r = 0; r < 6; r++)
        t[r] = w->delta[off + r];
    if (LAPACKE_dgesv(LAPACK_COL_MAJOR, 6, 1, S, 6, piv, t, 6) != 0)
        return -1;
    for (int k = 0; k < N; k++)
        for (int c = 0; c < 6; c++)
            w->delta[k] -= w->Y[(size_t)c * N + k] * t[c];
    return 0;
}

/* Adds mu |J_ii| to the band's diagonal (Marquardt's scaling): a step in a
 * direction the tangent barely resists (a ring losing the bore, a rigid
 * motion nothing holds) stays bounded. */
static void damp(problem *pb, double *ab, double mu)
{
    for (int k = 0; k < 6 * pb->n; k++) {
        double *d = &ab[(size_t)k * LDAB + 2 * KL];
        *d += mu * fabs(*d);
    }
}

/* Newton iterations at the current load factor, Levenberg-Marquardt damped
 * when a plain step fails.  Returns 1 converged, 0 not converged (caller
 * cuts the load step), < 0 on error. */
static int newton(problem *pb, work *w, double tol, int *budget, int *iters, double *res_out)
{
    int N = 6 * pb->n;
    double mu = 0.0;
    residual(pb, w->r);
    double res = residual_norm(pb, w->r);
    for (int it = 0; it < 40; it++) {
        if (res <= tol) {
            *res_out = res;
            return 1;
        }
        if (!isfinite(res) || *budget <= 0)
            return 0;
        (*budget)--;
        (*iters)++;
        tangent(pb, w->ab);
        if (mu > 0.0)
            damp(pb, w->ab, mu);
        for (int k = 0; k < N; k++)
            w->delta[k] = -w->r[k];
        if (newton_step(pb, w) != 0)
            return 0;
        double step_len = 0.0;
        for (int i = 0; i < pb->n; i++)
            for (int k = 0; k < 6; k++) {
                double v = fabs(w->delta[6 * i + k]) / (k < 3 ? pb->R : 1.0);
                if (v > step_len)
                    step_len = v;
            }
        /* backtracking on the residual norm */
        memcpy(w->xs, pb->x, (size_t)3 * pb->n * sizeof *pb->x);
        memcpy(w->Qs, pb->Q, (size_t)9 * pb->n * sizeof *pb->Q);
        double a = 1.0, res_new = INFINITY;
        int accepted = 0;
        for (int ls = 0; ls < 8 && !accepted; ls++) {
            apply_step(pb, w->delta, a);
            residual(pb, w->r);
            res_new = residual_norm(pb, w->r);
            /* A full step may raise the residual at first: the chain's axial
             * stiffness turns the step's second-order length error into large
             * forces that the next iteration removes.  So the first
             * iterations of a load step take it unless it explodes. */
            accepted = res_new < (1.0 - 1e-4 * a) * res || res_new <= tol ||
                       (it < 3 && a == 1.0 && res_new < 1e3 * res);
            if (!accepted) {
                memcpy(pb->x, w->xs, (size_t)3 * pb->n * sizeof *pb->x);
                memcpy(pb->Q, w->Qs, (size_t)9 * pb->n * sizeof *pb->Q);
                a *= 0.5;
            }
        }
        if (!accepted) {
            residual(pb, w->r);
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
    free(w->ab);
    free(w->x0);
    free(w->Q0);
    free(w->xs);
    free(w->Qs);
    free(w->Y);
    free(w->ipiv);
}

/* Predictor for a contact load step: every segment moves radially with the
 * bore under it from load factor l0 to l1.  Without it a bore that moves
 * away by more than the law's smoothing length eps leaves every contact on
 * the law's exp(delta / eps) tail, with no stiffness to push the ring out. */
static void follow_bore(problem *pb, double l0, double l1)
{
    for (int i = 0; i < pb->n; i++) {
        double *x = pb->x + 3 * i, th = atan2(x[1], x[0]), r0, r1, d;
        pb->lambda = l0;
        bore_radius(pb, th, &r0, &d);
        pb->lambda = l1;
        bore_radius(pb, th, &r1, &d);
        x[0] += (r1 - r0) * cos(th);
        x[1] += (r1 - r0) * sin(th);
    }
}

/* Load stepping from lambda = 0 to 1. */
static int solve_path(problem *pb, const rd_static_opts *so, const rd_monitor *mon, double frac0,
                      double frac1, rd_static_stats *st, rd_error *err)
{
    int n = pb->n, N = 6 * n, rc = RD_OK;
    work w = {0};
    w.r = malloc((size_t)N * sizeof *w.r);
    w.delta = malloc((size_t)N * sizeof *w.delta);
    w.ab = malloc((size_t)LDAB * N * sizeof *w.ab);
    w.x0 = malloc((size_t)3 * n * sizeof *w.x0);
    w.Q0 = malloc((size_t)9 * n * sizeof *w.Q0);
    w.xs = malloc((size_t)3 * n * sizeof *w.xs);
    w.Qs = malloc((size_t)9 * n * sizeof *w.Qs);
    w.ipiv = malloc((size_t)N * sizeof *w.ipiv);
    int need_y = pb->kind == PRETENSION && pb->method == RD_PRETENSION_FIELD;
    if (need_y)
        w.Y = malloc((size_t)6 * N * sizeof *w.Y);
    if ((need_y && !w.Y) || !w.r || !w.delta || !w.ab || !w.x0 || !w.Q0 || !w.xs || !w.Qs || !w.ipiv) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the %d-segment static solve.", n);
        goto out;
    }
    double lam = 0.0, dlam = 1.0, res = 0.0;
    int budget = so->max_iterations;
    /* Rounding floor: the stiffest spring (joint axial EA/L, or a contact
     * point's k A) times a position's last bits (measured: up to ~1000 eps R), over F_ref. */
    double noise = 1024.0 * DBL_EPSILON * fmax(pb->Kc[0], pb->k * pb->area) * pb->R / pb->F_ref;
    double tol = fmax(so->tol, noise);
    st->tolerance = tol;
    st->iterations = 0;
    st->load_steps = 0;
    pb->lambda = 0.0;
    while (lam < 1.0) {
        double target = fmin(1.0, lam + dlam);
        memcpy(w.x0, pb->x, (size_t)3 * n * sizeof *pb->x);
        memcpy(w.Q0, pb->Q, (size_t)9 * n * sizeof *pb->Q);
        if (pb->kind == CONTACT)
            follow_bore(pb, lam, target);
        pb->lambda = target;
        int before = st->iterations;
        int ok = newton(pb, &w, tol, &budget, &st->iterations, &res);
        if (ok) {
            lam = target;
            st->load_steps++;
            if (st->iterations - before <= 6)
                dlam = fmin(1.0, 2.0 * dlam);
            if ((rc = rd_monitor_report(mon, frac0 + (frac1 - frac0) * lam, err)) != RD_OK)
                goto out;
            continue;
        }
        memcpy(pb->x, w.x0, (size_t)3 * n * sizeof *pb->x);
        memcpy(pb->Q, w.Q0, (size_t)9 * n * sizeof *pb->Q);
        pb->lambda = lam;
        dlam *= 0.25;
        if (budget <= 0 || dlam < 1e-6) {
            rc = rd_error_set(
                err, RD_ENOCONV, "",
                "The static solve did not converge: Newton's method stalled at load factor %.4g "
                "of 1 after %d iterations (%s). The load may exceed what the model can carry "
                "(e.g. the gap ends meeting, or the ring losing the bore): check the loads, or "
                "raise /numerics/max_iterations.",
                lam, st->iterations,
                budget <= 0 ? "iteration budget used up" : "load step became too small");
            goto out;
        }
    }
    st->residual = res;
out:
    work_free(&w);
    return rc;
}

static int problem_init(problem *pb, const rd_ring *ring, int kind)
{
    int n = rd_ring_get_segments(ring);
    const rd_ring_params *p = rd_ring_get_params(ring);
    memset(pb, 0, sizeof *pb);
    pb->ring = ring;
    pb->n = n;
    pb->kind = kind;
    pb->R = rd_ring_get_section(ring)->R;
    pb->b = p->radial_width;
    pb->h = p->axial_height;
    pb->Kc = rd_ring_joint_stiffness(ring);
    pb->E = malloc((size_t)9 * n * sizeof *pb->E);
    pb->dP0 = malloc((size_t)3 * n * sizeof *pb->dP0);
    pb->x = malloc((size_t)3 * n * sizeof *pb->x);
    pb->Q = malloc((size_t)9 * n * sizeof *pb->Q);
    if (!pb->E || !pb->dP0 || !pb->x || !pb->Q)
        return RD_ENOMEM;
    for (int i = 0; i < n; i++) {
        memcpy(pb->x + 3 * i, rd_ring_reference_point(ring, i), 3 * sizeof(double));
        double eye[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(pb->Q + 9 * i, eye, sizeof eye);
    }
    for (int j = 0; j < n - 1; j++) {
        const double *PA = rd_ring_reference_point(ring, j), *PB = rd_ring_reference_point(ring, j + 1);
        double *E = pb->E + 9 * j, *d = pb->dP0 + 3 * j;
        for (int k = 0; k < 3; k++)
            d[k] = PB[k] - PA[k];
        double L = sqrt(dot3(d, d));
        double e1[3] = {d[0] / L, d[1] / L, d[2] / L}, e2[3] = {0, 0, 1}, e3[3];
        cross3(e1, e2, e3);
        memcpy(E, e1, sizeof e1);
        memcpy(E + 3, e2, sizeof e2);
        memcpy(E + 6, e3, sizeof e3);
    }
    /* gap faces: neutral-axis points and the opening directions */
    double s = rd_ring_get_segment_angle(ring, 0) - 0.5 * rd_ring_segment_phi(ring);
    double sB = 2.0 * M_PI - s;
    const double *P0 = rd_ring_reference_point(ring, 0), *Pn = rd_ring_reference_point(ring, n - 1);
    double fa[3] = {pb->R * cos(s), pb->R * sin(s), 0}, fb[3] = {pb->R * cos(sB), pb->R * sin(sB), 0};
    for (int k = 0; k < 3; k++) {
        pb->cA[k] = fa[k] - P0[k];
        pb->cB[k] = fb[k] - Pn[k];
    }
    double tA[3] = {-sin(s), cos(s), 0}, tB[3] = {sin(sB), -cos(sB), 0};
    memcpy(pb->tA, tA, sizeof tA);
    memcpy(pb->tB, tB, sizeof tB);
    /* support: the section opposite the gap */
    pb->pa = (n - 1) / 2;
    pb->pb = n / 2;
    pb->k_t = 1e3 * pb->Kc[0];
    pb->k_r = 1e3 * fmax(pb->Kc[6 * 3 + 3], fmax(pb->Kc[6 * 4 + 4], pb->Kc[6 * 5 + 5]));
    return RD_OK;
}

static void problem_cleanup(problem *pb)
{
    free(pb->E);
    free(pb->dP0);
    free(pb->x);
    free(pb->Q);
    free(pb->cp);
}

/* ---- options and validation ------------------------------------------------ */

void rd_static_opts_default(rd_static_opts *o)
{
    o->tol = 1e-9;
    o->max_iterations = 2000;
    o->estimate_error = 1;
}

void rd_pretension_opts_default(rd_pretension_opts *o)
{
    o->method = RD_PRETENSION_FORCE;
    o->lateral_force = 0.0;
}

void rd_contact_opts_default(rd_contact_opts *o)
{
    memset(o, 0, sizeof *o);
    o->points_per_segment = 10;
}

int rd_static_validate(const rd_static_opts *o, int segments, int closed, rd_error *err)
{
    if (closed)
        return rd_error_set(err, RD_EINVAL, "/discretization/closed",
                            "/discretization/closed = true joins the gap, but pretension and "
                            "contact act on the gap faces: use a split ring (closed = false).");
    if (segments < 4 || segments > RD_STATIC_SEGMENTS_MAX)
        return rd_error_set(err, segments > RD_STATIC_SEGMENTS_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/discretization/segments",
                            "/discretization/segments = %d is out of range for a static "
                            "analysis: allowed 4 to %d.",
                            segments, RD_STATIC_SEGMENTS_MAX);
    if (!isfinite(o->tol) || o->tol < 1e-13 || o->tol > 1e-3)
        return rd_error_set(err, RD_EINVAL, "/numerics/tolerance",
                            "/numerics/tolerance = %g is out of range: allowed 1e-13 to 1e-3.",
                            o->tol);
    if (o->max_iterations < 1 || o->max_iterations > 100000)
        return rd_error_set(err, o->max_iterations > 100000 ? RD_ELIMIT : RD_EINVAL,
                            "/numerics/max_iterations",
                            "/numerics/max_iterations = %d is out of range: allowed 1 to 100000.",
                            o->max_iterations);
    return RD_OK;
}

int rd_pretension_validate(const rd_pretension_opts *o, const rd_ring_params *p, rd_error *err)
{
    if (o->method != RD_PRETENSION_FORCE && o->method != RD_PRETENSION_FIELD)
        return rd_error_set(err, RD_EINVAL, "/pretension/method", "unknown method %d.", o->method);
    double hi = 100.0 * fmax(p->tangential_force, 1.0);
    if (!isfinite(o->lateral_force) || o->lateral_force < 0.0 || o->lateral_force > hi)
        return rd_error_set(err, RD_EINVAL, "/pretension/lateral_force",
                            "/pretension/lateral_force = %g N is out of range: allowed 0 to %g N "
                            "(100 times the tangential force, at least 100 N).",
                            o->lateral_force, hi);
    return RD_OK;
}

double rd_contact_default_stiffness(const rd_ring_params *p)
{
    rd_ring_section s;
    rd_ring_section_get(p, 0, &s);
    return 1e6 * p->youngs_modulus * s.I_inplane / (p->axial_height * pow(s.R, 4));
}

int rd_contact_validate(const rd_contact_opts *o, const rd_ring_params *p, rd_error *err)
{
    double d = p->diameter;
    if (p->tangential_force <= 0.0)
        return rd_error_set(err, RD_EINVAL, "/ring/tangential_force",
                            "/ring/tangential_force = %g N: the contact analysis needs a "
                            "pretension > 0 (without it the ring presses on nothing and its "
                            "place in the bore is undetermined).",
                            p->tangential_force);
    if (o->bore_diameter != 0.0 &&
        (!isfinite(o->bore_diameter) || o->bore_diameter < 0.98 * d || o->bore_diameter > 1.02 * d))
        return rd_error_set(err, RD_EINVAL, "/bore/diameter",
                            "/bore/diameter = %g m is out of range: allowed %g to %g m (within "
                            "2 %% of the ring diameter %g m).",
                            o->bore_diameter, 0.98 * d, 1.02 * d, d);
    if (o->n_distortion < 0 || o->n_distortion > RD_DISTORTION_MAX)
        return rd_error_set(err, RD_ELIMIT, "/bore/distortion",
                            "/bore/distortion has %d entries; at most %d are allowed.",
                            o->n_distortion, RD_DISTORTION_MAX);
    double total = 0.0;
    for (int k = 0; k < o->n_distortion; k++) {
        const rd_distortion *ds = &o->distortion[k];
        char path[64];
        snprintf(path, sizeof path, "/bore/distortion/%d/order", k);
        if (ds->order < 1 || ds->order > 64)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s = %d is out of range: allowed 1 to 64.", path, ds->order);
        snprintf(path, sizeof path, "/bore/distortion/%d/amplitude", k);
        if (!isfinite(ds->amplitude) || fabs(ds->amplitude) > 0.01 * d)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s = %g m is out of range: allowed -%g to %g m (1 %% of the "
                                "diameter).",
                                path, ds->amplitude, 0.01 * d, 0.01 * d);
        snprintf(path, sizeof path, "/bore/distortion/%d/phase_deg", k);
        if (!isfinite(ds->phase_deg) || fabs(ds->phase_deg) > 360.0)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s = %g deg is out of range: allowed -360 to 360 deg.", path,
                                ds->phase_deg);
        total += fabs(ds->amplitude);
    }
    if (total > 0.01 * d)
        return rd_error_set(err, RD_EINVAL, "/bore/distortion",
                            "/bore/distortion: the amplitudes add up to %g m; allowed at most "
                            "%g m (1 %% of the diameter).",
                            total, 0.01 * d);
    if (o->points_per_segment < 1 || o->points_per_segment > RD_CONTACT_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/contact/points_per_segment",
                            "/contact/points_per_segment = %d is out of range: allowed 1 to %d.",
                            o->points_per_segment, RD_CONTACT_POINTS_MAX);
    double k0 = rd_contact_default_stiffness(p);
    if (o->stiffness != 0.0 &&
        (!isfinite(o->stiffness) || o->stiffness < 1e-3 * k0 || o->stiffness > 1e2 * k0))
        return rd_error_set(err, RD_EINVAL, "/contact/stiffness",
                            "/contact/stiffness = %g Pa/m is out of range for this ring: "
                            "allowed %g to %g Pa/m (1e-3 to 1e2 times the default %g).",
                            o->stiffness, 1e-3 * k0, 1e2 * k0, k0);
    return RD_OK;
}

double rd_ring_conformability(const rd_ring_params *p)
{
    rd_ring_section s;
    rd_ring_section_get(p, 0, &s);
    double db = p->diameter - p->radial_width;
    return p->tangential_force * db * db / (4.0 * p->youngs_modulus * s.I_inplane);
}

double rd_ring_free_gap_formula(const rd_ring_params *p)
{
    /* (1.5): k = 2/(3 pi) m/(d - b), m the opening beyond the closed gap */
    double m = 1.5 * M_PI * rd_ring_conformability(p) * (p->diameter - p->radial_width);
    return p->closed_gap + m;
}

/* ---- pretension ------------------------------------------------------------ */

/* Current global position of the body offset c of segment i. */
static void point_at(const problem *pb, int i, const double c[3], double y[3])
{
    mv3(pb->Q + 9 * i, c, y);
    for (int k = 0; k < 3; k++)
        y[k] += pb->x[3 * i + k];
}

static void stats_fill(problem *pb, rd_static_stats *st)
{
    double *r = malloc((size_t)6 * pb->n * sizeof *r);
    st->segments = pb->n;
    st->dof = 6 * pb->n;
    st->strain_energy = r ? residual(pb, r) : NAN;
    free(r);
    support_terms(pb, NULL, &st->support_force, &st->support_moment);
}

static int pretension_once(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                           const rd_static_opts *so, const rd_monitor *mon, double f0, double f1,
                           rd_pretension_result *out, rd_error *err)
{
    problem pb;
    int rc;
    rd_ring *ring = rd_ring_create(p, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_EINVAL;
    if ((rc = problem_init(&pb, ring, PRETENSION)) != RD_OK) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the %d-segment ring.", segments);
        goto out;
    }
    pb.Ft = p->tangential_force;
    pb.Fl = o->lateral_force;
    pb.method = o->method;
    pb.jseg = segments - 1;
    for (int k = 0; k < 6; k++)
        pb.mask[k] = 1.0;
    pb.F_ref = fmax(fmax(pb.Ft, pb.Fl), 1e-3 * rd_ring_get_section(ring)->G *
                                            rd_ring_get_section(ring)->area * 1e-9);
    if ((rc = solve_path(&pb, so, mon, f0, f1, &out->stats, err)) != RD_OK)
        goto out;
    stats_fill(&pb, &out->stats);

    int n = segments;
    double s = rd_ring_get_segment_angle(ring, 0) - 0.5 * rd_ring_segment_phi(ring);
    double Ri = pb.R - 0.5 * pb.b;
    const double *P0 = rd_ring_reference_point(ring, 0), *Pn = rd_ring_reference_point(ring, n - 1);
    double ia[3] = {Ri * cos(s) - P0[0], Ri * sin(s) - P0[1], 0.0};
    double ib[3] = {Ri * cos(s) - Pn[0], -Ri * sin(s) - Pn[1], 0.0};
    double ya[3], yb[3], d[3];
    point_at(&pb, 0, ia, ya);
    point_at(&pb, n - 1, ib, yb);
    for (int k = 0; k < 3; k++)
        d[k] = ya[k] - yb[k];
    out->gap_opening_inner = sqrt(dot3(d, d));
    ia[2] = ib[2] = 0.5 * pb.h;
    point_at(&pb, 0, ia, ya);
    point_at(&pb, n - 1, ib, yb);
    out->lateral_opening = fabs(ya[2] - yb[2]);
    point_at(&pb, 0, pb.cA, ya);
    point_at(&pb, n - 1, pb.cB, yb);
    for (int k = 0; k < 3; k++)
        d[k] = ya[k] - yb[k];
    out->gap_opening_neutral = sqrt(dot3(d, d));
    out->conformability = rd_ring_conformability(p);
    out->free_gap_formula = rd_ring_free_gap_formula(p);

    out->points = n + 2;
    out->x = malloc((size_t)(n + 2) * sizeof *out->x);
    out->y = malloc((size_t)(n + 2) * sizeof *out->y);
    out->z = malloc((size_t)(n + 2) * sizeof *out->z);
    out->angle_deg = malloc((size_t)(n + 2) * sizeof *out->angle_deg);
    if (!out->x || !out->y || !out->z || !out->angle_deg) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the deformed shape.");
        goto out;
    }
    for (int k = 0; k < n + 2; k++) {
        double y[3], ang;
        if (k == 0) {
            point_at(&pb, 0, pb.cA, y);
            ang = s;
        } else if (k == n + 1) {
            point_at(&pb, n - 1, pb.cB, y);
            ang = 2.0 * M_PI - s;
        } else {
            memcpy(y, pb.x + 3 * (k - 1), sizeof y);
            ang = rd_ring_get_segment_angle(ring, k - 1);
        }
        out->x[k] = y[0];
        out->y[k] = y[1];
        out->z[k] = y[2];
        out->angle_deg[k] = ang * 180.0 / M_PI;
    }
out:
    problem_cleanup(&pb);
    rd_ring_free(ring);
    return rc;
}

void rd_pretension_result_cleanup(rd_pretension_result *r)
{
    if (!r)
        return;
    free(r->x);
    free(r->y);
    free(r->z);
    free(r->angle_deg);
    r->x = r->y = r->z = r->angle_deg = NULL;
}

/* Segment count of the error-estimate solve. */
static int reference_segments(int n)
{
    return 2 * n <= RD_STATIC_SEGMENTS_MAX ? 2 * n : n / 2;
}

/* Richardson: with f_n = f + C n^-2, the error of f_n is (f_n - f_m) /
 * (1 - (n/m)^2). */
static double richardson_error(double fn, double fm, int n, int m)
{
    double ratio = (double)n / m;
    return fabs((fn - fm) / (1.0 - ratio * ratio)) / fmax(fabs(fn), 1e-300);
}

int rd_pretension_solve(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                        const rd_static_opts *so, const rd_monitor *mon,
                        rd_pretension_result *out, rd_error *err)
{
    int rc;
    memset(out, 0, sizeof *out);
    out->stats.error_estimate = NAN;
    if ((rc = rd_ring_validate(p, segments, 0, err)) || (rc = rd_static_validate(so, segments, 0, err)) ||
        (rc = rd_pretension_validate(o, p, err)))
        return rc;
    double f1 = so->estimate_error ? 0.34 : 1.0;
    if ((rc = pretension_once(p, segments, o, so, mon, 0.0, f1, out, err)) != RD_OK)
        return rc;
    if (!so->estimate_error)
        return RD_OK;
    rd_pretension_result ref;
    memset(&ref, 0, sizeof ref);
    int m = reference_segments(segments);
    rc = pretension_once(p, m, o, so, mon, f1, 1.0, &ref, err);
    if (rc == RD_OK) {
        out->stats.reference_segments = m;
        double e = richardson_error(out->gap_opening_inner, ref.gap_opening_inner, segments, m);
        if (o->lateral_force > 0.0)
            e = fmax(e, richardson_error(out->lateral_opening, ref.lateral_opening, segments, m));
        out->stats.error_estimate = e;
    }
    rd_pretension_result_cleanup(&ref);
    return rc;
}

/* ---- contact --------------------------------------------------------------- */

static int contact_once(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                        const rd_static_opts *so, const rd_monitor *mon, double f0, double f1,
                        rd_contact_result *out, rd_error *err)
{
    problem pb;
    int rc;
    rd_ring *ring = rd_ring_create(p, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_EINVAL;
    if ((rc = problem_init(&pb, ring, CONTACT)) != RD_OK)
        goto nomem;
    int n = segments, m = o->points_per_segment;
    double phi = rd_ring_segment_phi(ring);
    pb.Ft = p->tangential_force;
    pb.method = RD_PRETENSION_FORCE;
    pb.co = o;
    pb.m = m;
    pb.r_o = pb.R + 0.5 * pb.b;
    pb.bore_dr = (o->bore_diameter > 0.0 ? 0.5 * o->bore_diameter : 0.5 * p->diameter) - pb.r_o;
    pb.area = pb.h * pb.r_o * phi / m;
    pb.p0 = 2.0 * p->tangential_force / (p->diameter * p->axial_height);
    pb.k = o->stiffness > 0.0 ? o->stiffness : rd_contact_default_stiffness(p);
    pb.eps = 0.05 * pb.p0 / pb.k;
    pb.F_ref = p->tangential_force;
    /* held: tangential (y at 180 deg), axial, tilts; free: radial, in-plane turn */
    double mask[6] = {0, 1, 1, 1, 1, 0};
    memcpy(pb.mask, mask, sizeof mask);
    pb.cp = malloc((size_t)3 * n * m * sizeof *pb.cp);
    out->points = n;
    out->angle_deg = malloc((size_t)n * sizeof *out->angle_deg);
    out->pressure = malloc((size_t)n * sizeof *out->pressure);
    out->clearance = malloc((size_t)n * sizeof *out->clearance);
    out->bore_radius = malloc((size_t)n * sizeof *out->bore_radius);
    if (!pb.cp || !out->angle_deg || !out->pressure || !out->clearance || !out->bore_radius)
        goto nomem;
    for (int i = 0; i < n; i++) {
        const double *P = rd_ring_reference_point(ring, i);
        for (int k = 0; k < m; k++) {
            double a = rd_ring_get_segment_angle(ring, i) + (k + 0.5 - 0.5 * m) * phi / m;
            double *c = pb.cp + 3 * (m * i + k);
            c[0] = pb.r_o * cos(a) - P[0];
            c[1] = pb.r_o * sin(a) - P[1];
            c[2] = 0.0;
        }
    }
    if ((rc = solve_path(&pb, so, mon, f0, f1, &out->stats, err)) != RD_OK)
        goto out;
    stats_fill(&pb, &out->stats);

    /* Per segment: the resultant of its points' pressures over its share of
     * the running face, and its closest approach to the bore.  The points
     * inside one rigid segment share whatever misfit the straight-sided
     * segment has against a curved bore, so how the pressure splits between
     * them is an artifact of rigid segments; the resultant is not. */
    double sum = 0.0, in_contact = 0.0;
    out->max_clearance = 0.0;
    out->max_clearance_angle_deg = NAN;
    out->max_penetration = 0.0;
    for (int i = 0; i < n; i++) {
        double force = 0.0, closest = INFINITY, mid[3];
        for (int k = 0; k < m; k++) {
            int q = m * i + k;
            double y[3], rb, drb;
            point_at(&pb, i, pb.cp + 3 * q, y);
            bore_radius(&pb, atan2(y[1], y[0]), &rb, &drb);
            double delta = hypot(y[0], y[1]) - rb;
            force += contact_pressure(&pb, delta) * pb.area;
            closest = fmin(closest, -delta);
            out->max_penetration = fmax(out->max_penetration, delta);
        }
        double c_mid[3], rb, drb;
        const double *P = rd_ring_reference_point(ring, i);
        for (int k = 0; k < 3; k++)
            c_mid[k] = (pb.r_o / pb.R) * P[k] - P[k];
        point_at(&pb, i, c_mid, mid);
        double th = atan2(mid[1], mid[0]), deg = th * 180.0 / M_PI;
        bore_radius(&pb, th, &rb, &drb);
        out->angle_deg[i] = deg < 0.0 ? deg + 360.0 : deg;
        out->pressure[i] = force / (m * pb.area);
        out->clearance[i] = closest;
        out->bore_radius[i] = rb;
        sum += out->pressure[i];
        if (closest <= 0.0)
            in_contact += 1.0;
        if (closest > out->max_clearance) {
            out->max_clearance = closest;
            out->max_clearance_angle_deg = out->angle_deg[i];
        }
    }
    out->mean_pressure = sum / n;
    out->uniform_pressure = pb.p0;
    out->contact_fraction = in_contact / n;
    out->stiffness = pb.k;
    out->conformability = rd_ring_conformability(p);
    rd_ring_section sec;
    rd_ring_section_get(p, 0, &sec);
    for (int k = 0; k < o->n_distortion; k++) {
        double kk = o->distortion[k].order;
        out->bound[k] = kk < 2 ? NAN
                               : p->tangential_force * pow(sec.R, 3) /
                                     (p->youngs_modulus * sec.I_inplane * pow(kk * kk - 1.0, 2));
    }
    goto out;
nomem:
    rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the %d-segment contact solve.",
                      segments);
out:
    problem_cleanup(&pb);
    rd_ring_free(ring);
    return rc;
}

void rd_contact_result_cleanup(rd_contact_result *r)
{
    if (!r)
        return;
    free(r->angle_deg);
    free(r->pressure);
    free(r->clearance);
    free(r->bore_radius);
    r->angle_deg = r->pressure = r->clearance = r->bore_radius = NULL;
}

/* Pressure of a result at angle a (deg), linear between its points. */
static double pressure_at(const rd_contact_result *r, double a)
{
    int np = r->points;
    if (a <= r->angle_deg[0])
        return r->pressure[0];
    for (int q = 1; q < np; q++)
        if (a <= r->angle_deg[q]) {
            double t = (a - r->angle_deg[q - 1]) / (r->angle_deg[q] - r->angle_deg[q - 1]);
            return (1.0 - t) * r->pressure[q - 1] + t * r->pressure[q];
        }
    return r->pressure[np - 1];
}

int rd_contact_solve(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                     const rd_static_opts *so, const rd_monitor *mon, rd_contact_result *out,
                     rd_error *err)
{
    int rc;
    memset(out, 0, sizeof *out);
    out->stats.error_estimate = NAN;
    if ((rc = rd_ring_validate(p, segments, 0, err)) || (rc = rd_static_validate(so, segments, 0, err)) ||
        (rc = rd_contact_validate(o, p, err)))
        return rc;
    double f1 = so->estimate_error ? 0.34 : 1.0;
    if ((rc = contact_once(p, segments, o, so, mon, 0.0, f1, out, err)) != RD_OK)
        return rc;
    if (!so->estimate_error)
        return RD_OK;
    rd_contact_result ref;
    memset(&ref, 0, sizeof ref);
    int m = reference_segments(segments);
    rc = contact_once(p, m, o, so, mon, f1, 1.0, &ref, err);
    if (rc == RD_OK) {
        /* RMS difference of the pressure profiles, relative to p0, on this
         * solution's points (angles increase along the ring). */
        double s2 = 0.0;
        for (int q = 0; q < out->points; q++) {
            double d = out->pressure[q] - pressure_at(&ref, out->angle_deg[q]);
            s2 += d * d;
        }
        out->stats.reference_segments = m;
        out->stats.error_estimate = sqrt(s2 / out->points) / out->uniform_pressure;
    }
    rd_contact_result_cleanup(&ref);
    return rc;
}
