/*
 * rd_static_joint — one joint of the segment chain: its generalized forces
 * (the residual's part) and their exact derivative (the Newton tangent's
 * part), and the SO(3) maps the static solver uses.  rd_static.c has the
 * state layout and the solver; rd_static.h the model.
 *
 * Joint j joins segments A = j and B = j + 1 (positions x, rotations Q,
 * body to global, row-major).  With Dx = x_B - x_A, psi = log(Q_A^T Q_B),
 *   d = E (Q_A^T Dx - dP0),   t = E psi,   [f; m] = Kc [d; t],
 *   F = P f,   Mg = G m,   P = Q_A E^T,   G = Q_A Jl^-T(psi) E^T,
 *   g_A = (-F, F x Dx - Mg),   g_B = (F, Mg),
 * Jl^-1 the inverse left Jacobian of SO(3): a left perturbation w of
 * exp(psi) changes psi by Jl^-1(psi) w, and
 *   Jl^-T(psi) v = v + 1/2 psi x v + c(th) psi x (psi x v),
 *   c(th) = 1/th^2 - (1 + cos th) / (2 th sin th),   th = |psi|.
 *
 * Tangent.  For increments (u_A, w_A, u_B, w_B), w spatial (Q <- exp([w]x) Q),
 *   du = u_B - u_A + [Dx] w_A,   dw = w_B - w_A,
 *   d(d) = P^T du,   dpsi = Jl^-T(psi)^T Q_A^T dw,   d(t) = G^T dw,
 *   dF   = -[F] w_A + S_ff du + S_ft dw,
 *   dMg  = -[Mg] w_A + S_tf du + (S_tt + H) dw,
 *   d(F x Dx) = -[Dx] dF + [F] (u_B - u_A),
 * [S_ff S_ft; S_tf S_tt] = diag(P, G) Kc diag(P, G)^T, [a] the cross-product
 * matrix, and H = Q_A D(psi; E^T m) Jl^-T(psi)^T Q_A^T the turn of Jl^-T,
 *   D(psi; v) = d(Jl^-T(psi) v)/dpsi
 *             = -[v]/2 + (c'/th) (psi x (psi x v)) psi^T - c ([psi x v] + [psi][v]).
 * H is of the order of the joint's moment, |m| / K_rot ~ its strain relative
 * to the rest; kept, so the tangent is the exact derivative of g.
 */
#include <math.h>
#include <string.h>

#include "rd_static_problem.h"

/* out = A^T v */
static void mtv3(const double A[9], const double v[3], double out[3])
{
    double c[3];
    for (int r = 0; r < 3; r++)
        c[r] = A[r] * v[0] + A[3 + r] * v[1] + A[6 + r] * v[2];
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

/* out = A B^T */
static void mmt3(const double A[9], const double B[9], double out[9])
{
    double c[9];
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            c[3 * r + q] =
                A[3 * r] * B[3 * q] + A[3 * r + 1] * B[3 * q + 1] + A[3 * r + 2] * B[3 * q + 2];
    memcpy(out, c, sizeof c);
}

/* [a]: [a] v = a x v */
static void skew3(const double a[3], double S[9])
{
    double s[9] = {0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0};
    memcpy(S, s, sizeof s);
}

void rd_static_rot_exp(const double w[3], double R[9])
{
    double th2 = rd_dot3(w, w), th = sqrt(th2), a, b;
    if (th < 1e-4) {
        a = 1.0 - th2 / 6.0 * (1.0 - th2 / 20.0);
        b = 0.5 - th2 / 24.0 * (1.0 - th2 / 30.0);
    } else {
        a = sin(th) / th;
        b = (1.0 - cos(th)) / th2;
    }
    double W[9], W2[9];
    skew3(w, W);
    rd_mm3(W, W, W2);
    for (int k = 0; k < 9; k++)
        R[k] = (k % 4 == 0 ? 1.0 : 0.0) + a * W[k] + b * W2[k];
}

void rd_static_rot_log(const double R[9], double w[3])
{
    double v[3] = {0.5 * (R[7] - R[5]), 0.5 * (R[2] - R[6]), 0.5 * (R[3] - R[1])};
    double s = sqrt(rd_dot3(v, v)), c = 0.5 * (R[0] + R[4] + R[8] - 1.0);
    double th = atan2(s, c);
    double f = s < 1e-8 ? 1.0 + th * th / 6.0 : th / s;
    for (int k = 0; k < 3; k++)
        w[k] = f * v[k];
}

/* c(th) of the header; with dc = c'(th) / th when dc is not NULL.  Below
 * th = 0.1 dc by its series (the closed form loses ~720 eps / th^4 to
 * cancellation there; the series' first omitted term is 5e-14 of it). */
static double jl_coeff(double th2, double *dc)
{
    double th = sqrt(th2);
    if (dc)
        *dc = th < 0.1
                  ? 1.0 / 360.0 + th2 * (1.0 / 7560.0 + th2 * (1.0 / 201600.0 + th2 / 5987520.0))
                  : (-2.0 / (th2 * th) + 0.25 / (th * pow(sin(0.5 * th), 2)) +
                     0.5 / (th2 * tan(0.5 * th))) /
                        th;
    if (th < 1e-3)
        return 1.0 / 12.0 + th2 / 720.0;
    return 1.0 / th2 - (1.0 + cos(th)) / (2.0 * th * sin(th));
}

void rd_static_jl_inv_t(const double psi[3], const double v[3], double out[3])
{
    double c = jl_coeff(rd_dot3(psi, psi), NULL), pv[3], ppv[3];
    rd_cross3(psi, v, pv);
    rd_cross3(psi, pv, ppv);
    for (int k = 0; k < 3; k++)
        out[k] = v[k] + 0.5 * pv[k] + c * ppv[k];
}

/* Everything of one joint's state that g and its tangent read. */
typedef struct joint_state {
    double Dx[3], psi[3], fm[6]; /* fm = Kc [d; t] */
    double energy;
} joint_state;

/* [d; t] of joint j, with Dx and psi. */
static void joint_strain(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                         const double *xB, const double *QB, double Dx[3], double psi[3],
                         double dt[6])
{
    const double *E = pb->E + 9 * j, *dP0 = pb->dP0 + 3 * j;
    double dl[3], Rrel[9];
    for (int k = 0; k < 3; k++)
        Dx[k] = xB[k] - xA[k];
    mtv3(QA, Dx, dl);
    for (int k = 0; k < 3; k++)
        dl[k] -= dP0[k];
    rd_mv3(E, dl, dt);
    mtm3(QA, QB, Rrel);
    rd_static_rot_log(Rrel, psi);
    rd_mv3(E, psi, dt + 3);
}

void rd_static_joint_strain(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                            const double *xB, const double *QB, double dt[6])
{
    double Dx[3], psi[3];
    joint_strain(pb, j, xA, QA, xB, QB, Dx, psi, dt);
}

static void joint_state_fill(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                             const double *xB, const double *QB, joint_state *s)
{
    const double *Kc = pb->Kc + 36 * j;
    double dt[6];
    joint_strain(pb, j, xA, QA, xB, QB, s->Dx, s->psi, dt);
    if (pb->e0) { /* a free shape: its strain is the rest (rd_free_shape.c) */
        double f = rd_static_force_factor(pb);
        for (int k = 0; k < 6; k++)
            dt[k] -= f * pb->e0[6 * j + k];
    }
    s->energy = 0.0;
    for (int r = 0; r < 6; r++) {
        s->fm[r] = 0.0;
        for (int c = 0; c < 6; c++)
            s->fm[r] += Kc[6 * r + c] * dt[c];
        s->energy += 0.5 * dt[r] * s->fm[r];
    }
}

void rd_static_joint_residual(const rd_static_problem *pb, int j, const double *xA,
                              const double *QA, const double *xB, const double *QB, double g[12],
                              double *energy)
{
    const double *E = pb->E + 9 * j;
    joint_state s;
    joint_state_fill(pb, j, xA, QA, xB, QB, &s);
    if (energy)
        *energy = s.energy;
    double Ef[3], F[3], Em[3], Jm[3], Mg[3], FxD[3];
    mtv3(E, s.fm, Ef);
    rd_mv3(QA, Ef, F);
    mtv3(E, s.fm + 3, Em);
    rd_static_jl_inv_t(s.psi, Em, Jm);
    rd_mv3(QA, Jm, Mg);
    rd_cross3(F, s.Dx, FxD);
    for (int k = 0; k < 3; k++) {
        g[k] = -F[k];
        g[3 + k] = FxD[k] - Mg[k];
        g[6 + k] = F[k];
        g[9 + k] = Mg[k];
    }
}

/* Jt = Jl^-T(psi) as a matrix, and H = D(psi; v) Jt^T (the header's H
 * before the turn to global axes). */
static void jl_parts(const double psi[3], const double v[3], double Jt[9], double H[9])
{
    double dc, c = jl_coeff(rd_dot3(psi, psi), &dc), P[9], P2[9], V[9], pv[3], ppv[3], PV[9],
               PVm[9], D[9];
    skew3(psi, P);
    rd_mm3(P, P, P2);
    for (int k = 0; k < 9; k++)
        Jt[k] = (k % 4 == 0 ? 1.0 : 0.0) + 0.5 * P[k] + c * P2[k];
    skew3(v, V);
    rd_cross3(psi, v, pv);
    rd_cross3(psi, pv, ppv);
    skew3(pv, PV);
    rd_mm3(P, V, PVm);
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            D[3 * r + q] =
                -0.5 * V[3 * r + q] + dc * ppv[r] * psi[q] - c * (PV[3 * r + q] + PVm[3 * r + q]);
    mmt3(D, Jt, H);
}

/* K's 3x3 block at block row br, block column bc = B (row-major). */
static void set3(double K[144], int br, int bc, const double B[9])
{
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            K[12 * (3 * br + r) + 3 * bc + q] = B[3 * r + q];
}

/* The header's dF (a = 0) and dMg (a = 1) by increment b = (u_A, w_A, u_B,
 * w_B): out[a][b], 3x3 row-major, from S (6x6 row-major) and Hg. */
static void force_blocks(const double S[36], const double Hg[9], const double F[3],
                         const double Mg[3], const double Dx[3], double out[2][4][9])
{
    double X[9], FM[2][9];
    skew3(Dx, X);
    skew3(F, FM[0]);
    skew3(Mg, FM[1]);
    for (int a = 0; a < 2; a++)
        for (int r = 0; r < 3; r++)
            for (int q = 0; q < 3; q++) {
                const double *Su = S + 6 * (3 * a + r), *Sw = Su + 3; /* S_ff | S_ft rows */
                double h = a ? Hg[3 * r + q] : 0.0;
                out[a][0][3 * r + q] = -Su[q];
                out[a][1][3 * r + q] = Su[0] * X[q] + Su[1] * X[3 + q] + Su[2] * X[6 + q] - Sw[q] -
                                       FM[a][3 * r + q] - h;
                out[a][2][3 * r + q] = Su[q];
                out[a][3][3 * r + q] = Sw[q] + h;
            }
}

void rd_static_joint_tangent(const rd_static_problem *pb, int j, const double *xA, const double *QA,
                             const double *xB, const double *QB, double K[144])
{
    const double *E = pb->E + 9 * j, *Kc = pb->Kc + 36 * j;
    joint_state s;
    joint_state_fill(pb, j, xA, QA, xB, QB, &s);
    double Em[3], Jt[9], H[9], P[9], G[9], X[2][9], F[3], Mg[3], S[36], Hg[9], T[9];
    mtv3(E, s.fm + 3, Em);
    jl_parts(s.psi, Em, Jt, H);
    mmt3(QA, E, P); /* Q_A E^T (E row-major: its rows are the local axes) */
    rd_mm3(QA, Jt, T);
    mmt3(T, E, G);
    memcpy(X[0], P, sizeof P);
    memcpy(X[1], G, sizeof G);
    rd_mv3(P, s.fm, F);
    rd_mv3(G, s.fm + 3, Mg);
    /* S = diag(P, G) Kc diag(P, G)^T, block by block */
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            double Kab[9], XK[9], Sab[9];
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++)
                    Kab[3 * r + q] = Kc[6 * (3 * a + r) + 3 * b + q];
            rd_mm3(X[a], Kab, XK);
            mmt3(XK, X[b], Sab);
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++)
                    S[6 * (3 * a + r) + 3 * b + q] = Sab[3 * r + q];
        }
    /* Hg = Q_A H Q_A^T */
    rd_mm3(QA, H, T);
    mmt3(T, QA, Hg);
    double d[2][4][9], Xd[9], Fx[9], XdF[9]; /* d[0]: dF, d[1]: dMg */
    force_blocks(S, Hg, F, Mg, s.Dx, d);
    skew3(s.Dx, Xd);
    skew3(F, Fx);
    /* rows: -dF, d(F x Dx) - dMg = -[Dx] dF + [F] (u_B - u_A) - dMg, dF, dMg */
    for (int b = 0; b < 4; b++) {
        double neg[9], row1[9];
        rd_mm3(Xd, d[0][b], XdF);
        for (int k = 0; k < 9; k++) {
            neg[k] = -d[0][b][k];
            row1[k] = -XdF[k] - d[1][b][k] + (b == 0 ? -Fx[k] : b == 2 ? Fx[k] : 0.0);
        }
        set3(K, 0, b, neg);
        set3(K, 1, b, row1);
        set3(K, 2, b, d[0][b]);
        set3(K, 3, b, d[1][b]);
    }
}
