/* test_static_joint — the static solver's closed-form joint tangent
 * (rd_static_joint_tangent, the Newton tangent's chain part) against central
 * differences of the joint's forces (rd_static_joint_residual), on deformed
 * joints: every segment turned far from the reference (so Q_A is no identity),
 * the joint stretched, sheared and bent, its relative rotation |psi| from 1e-5
 * to 1.5 rad (each branch of c(th) and c'(th)/th, both sides of their
 * switches at 1e-3 and 0.1).  The differences use this file's own Rodrigues
 * formula for the rotational steps. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_static_internal.h"

/* R = exp([w]x), written out again (Rodrigues) */
static void rotation(const double w[3], double R[9])
{
    double th = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double a = th > 0 ? sin(th) / th : 1.0, b = th > 0 ? (1.0 - cos(th)) / (th * th) : 0.5;
    double W[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            double w2 = 0.0;
            for (int k = 0; k < 3; k++)
                w2 += W[3 * r + k] * W[3 * k + c];
            R[3 * r + c] = (r == c ? 1.0 : 0.0) + a * W[3 * r + c] + b * w2;
        }
}

/* out = A B (3x3 row-major) */
static void mul(const double A[9], const double B[9], double out[9])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            out[3 * r + c] = A[3 * r] * B[c] + A[3 * r + 1] * B[3 + c] + A[3 * r + 2] * B[6 + c];
}

/* Central differences of joint j's forces at (x[0], Q[0]) of A and (x[1],
 * Q[1]) of B, DOFs (dx_A, dpsi_A, dx_B, dpsi_B) with Q <- exp([w]x) Q. */
static void differences(const rd_static_problem *pb, int j, double x[2][3], double Q[2][9],
                        double hx, double hr, double Kd[144])
{
    for (int col = 0; col < 12; col++) {
        int side = col / 6, k = col % 6;
        double h = k < 3 ? hx : hr, g[2][12];
        for (int sgn = 0; sgn < 2; sgn++) {
            double xs[2][3], Qs[2][9], s = sgn ? -h : h;
            memcpy(xs, x, sizeof xs);
            memcpy(Qs, Q, sizeof Qs);
            if (k < 3) {
                xs[side][k] += s;
            } else {
                double w[3] = {0, 0, 0}, R[9];
                w[k - 3] = s;
                rotation(w, R);
                mul(R, Q[side], Qs[side]);
            }
            rd_static_joint_residual(pb, j, xs[0], Qs[0], xs[1], Qs[1], g[sgn], NULL);
        }
        for (int row = 0; row < 12; row++)
            Kd[12 * row + col] = (g[0][row] - g[1][row]) / (2.0 * h);
    }
}

/* One deformed joint: both segments turned by `turn` (rad, about a tilted
 * axis), B moved by `strain` L along a slanted direction, and turned relative
 * to A by psi of length `bend` (rad).  Returns the largest difference between
 * the closed form and the differences, entry (r, c) over sqrt(|K_rr K_cc|)
 * (the joint's own stiffness in those directions: EA/L and GJ/L lie far
 * apart, so one scale for all entries would hide the rotational ones). */
static double joint_case(rd_static_problem *pb, int j, double turn, double strain, double bend)
{
    const double *E = pb->E + 9 * j;
    double L = sqrt(pb->dP0[3 * j] * pb->dP0[3 * j] + pb->dP0[3 * j + 1] * pb->dP0[3 * j + 1] +
                    pb->dP0[3 * j + 2] * pb->dP0[3 * j + 2]);
    double x[2][3], Q[2][9], Rg[9], Rb[9], I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double wg[3] = {0.3 * turn, -0.5 * turn, 0.81 * turn}, n = sqrt(0.09 + 0.25 + 0.6561);
    for (int k = 0; k < 3; k++)
        wg[k] /= n;
    rotation(wg, Rg);
    /* psi mostly about the joint's axial and radial axes (bending), some twist */
    double wb[3], loc[3] = {0.3, 0.8, -0.52}, ln = sqrt(0.09 + 0.64 + 0.2704);
    for (int k = 0; k < 3; k++)
        wb[k] = bend * (E[k] * loc[0] + E[3 + k] * loc[1] + E[6 + k] * loc[2]) / ln;
    rotation(wb, Rb);
    const double *PA = rd_ring_reference_point(pb->ring, j);
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = pb->dP0[3 * j + k] + strain * L * (0.6 * E[k] - 0.3 * E[3 + k] + 0.74 * E[6 + k]);
    for (int r = 0; r < 3; r++) {
        x[0][r] = PA[r] + 1e-3 * L;
        x[1][r] = x[0][r] + Rg[3 * r] * d[0] + Rg[3 * r + 1] * d[1] + Rg[3 * r + 2] * d[2];
    }
    mul(Rg, I, Q[0]);
    mul(Rg, Rb, Q[1]);
    double K[144], Kd[144], worst = 0.0;
    rd_static_joint_tangent(pb, j, x[0], Q[0], x[1], Q[1], K);
    /* steps: 1e-6 of L and rad, where the differences' truncation (h^2 g''')
     * and rounding (eps g / h) errors are both ~1e-10 of the entries */
    differences(pb, j, x, Q, 1e-6 * L, 1e-6, Kd);
    for (int q = 0; q < 144; q++) {
        int row = q / 12, col = q % 12;
        worst = fmax(worst, fabs(K[q] - Kd[q]) / sqrt(fabs(Kd[13 * row]) * fabs(Kd[13 * col])));
    }
    return worst;
}

/* 72 joints: |psi| on both sides of the switches of c (1e-3) and c'/th
 * (0.1), where a wrong branch would show as a jump; no turn and large ones;
 * no strain, stretched, compressed. */
static void test_joint_tangent(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    rd_error err;
    rd_error_init(&err);
    int n = 12;
    rd_ring *ring = rd_ring_create(&p, n, 0, &err);
    rd_static_problem pb;
    CHECK(ring && rd_static_problem_init(&pb, ring, NULL) == RD_OK, "problem");
    const double bends[] = {1e-5, 9.9e-4, 1.01e-3, 0.02, 0.099, 0.101, 0.5, 1.5};
    const double turns[] = {0.0, 0.7, 2.5}, strains[] = {0.0, 1e-3, -2e-2};
    double worst = 0.0;
    int cases = 0;
    for (int b = 0; b < 8; b++)
        for (int t = 0; t < 3; t++)
            for (int s = 0; s < 3; s++) {
                int j = (b + 3 * t + s) % (n - 1);
                double e = joint_case(&pb, j, turns[t], strains[s], bends[b]);
                /* measured 5e-9 at most: the differences' own error (1e-10 of
                 * an entry, over the scale of a smaller one); leaving out H
                 * (the turn of Jl^-T) shows as 2e-5 to 40, leaving out c'
                 * as 1e-6 at |psi| = 0.1 to 0.09 at 1.5 */
                CHECK(e < 1e-7, "joint %d, turn %g, strain %g, |psi| %g: %.2e of the scale", j,
                      turns[t], strains[s], bends[b], e);
                worst = fmax(worst, e);
                cases++;
            }
    printf("joint tangent vs central differences: %d deformed joints, worst %.2e\n", cases, worst);
    rd_static_problem_cleanup(&pb);
    rd_ring_free(ring);
}

int main(void)
{
    test_joint_tangent();
    return check_done();
}
