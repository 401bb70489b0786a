/*
 * bench_newton — what one Newton set-up and solve of the full lift model
 * costs: the second-order matrix S = I - gamma B - gamma^2 A (6 n unknowns,
 * block tridiagonal with 6x6 blocks) factored and solved by the block
 * Thomas LU of core/rd_blocktri.c (through the lift's own SUNLinearSolver,
 * core/rd_lift_newton.c), against the same S in a SUNDIALS band matrix
 * (half bandwidths 11) zeroed, filled and factored by SUNDIALS' band LU (the
 * lift's linear algebra before the block LU).
 *
 *   bench_newton [--reps R]
 *     The thesis ring seated at rest, 6000 rpm with Coulomb friction 0.1, at
 *     t = 0 and gamma = 1e-5 s (a step of ~0.36 crank degrees), n = 20 ..
 *     1000: microseconds per set-up (assemble + factor) and per solve, each
 *     the median of R >= 3 timings of a loop of set-ups and solves; the
 *     ratio band / block and the fitted cost exponent of both (least-squares
 *     slope of log time vs log n).  Both solutions are compared (largest
 *     difference relative to the largest entry; they agree to rounding).
 *
 * Wall times on a shared 2-core machine are noisy: medians of repeats.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include "bench_util.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

#define GAMMA 1e-5

typedef struct cost {
    double setup_us, solve_us, diff;
} cost;

/* S into the band matrix Sb (zeroed first), from the form's blocks A, B. */
static void band_fill(SUNMatrix Sb, const double *A, const double *B, int nb)
{
    double g = GAMMA, g2 = g * g;
    SUNMatZero(Sb);
    for (int i = 0; i < nb; i++)
        for (int j = i - 1; j <= i + 1; j++)
            for (int r = 0; j >= 0 && j < nb && r < 6; r++)
                for (int c = 0; c < 6; c++) {
                    double v = -g2 * A[108 * i + 36 * (j - i + 1) + 6 * r + c];
                    if (j == i)
                        v += (r == c) - g * B[36 * i + 6 * r + c];
                    SM_ELEMENT_B(Sb, 6 * i + r, 6 * j + c) = v;
                }
}

static int measure(int n, int reps, cost *out)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_ring_params_default(&rp);
    rd_lift_params_default(&p);
    p.model = RD_LIFT_MODEL_FULL;
    p.engine.speed_rpm = 6000.0;
    p.friction.model = RD_FRICTION_COULOMB;
    p.friction.coefficient = 0.1;
    rd_error err;
    rd_error_init(&err);
    rd_ring *ring = rd_ring_create(&rp, n, 0, &err);
    rd_lift_model c;
    memset(&c, 0, sizeof c);
    if (!ring || rd_lift_model_init(&c, ring, &p, NULL, &err)) {
        fprintf(stderr, "n = %d: %s\n", n, err.message);
        rd_lift_model_cleanup(&c);
        rd_ring_free(ring);
        return 1;
    }
    rd_lift_form form;
    rd_lift_full_form(&c, &form);
    int N = (int)form.N, N2 = N / 2, loops = 1 + 200000 / N, rc = 1;
    SUNContext ctx = NULL;
    SUNLinearSolver LS = NULL, LSb = NULL;
    SUNMatrix hold = NULL, Sb = NULL;
    rd_lift_newton *nw = NULL;
    N_Vector y = NULL, b = NULL, x = NULL, rb = NULL, xb = NULL;
    double *A = malloc(108 * (size_t)n * sizeof *A), *B = malloc(36 * (size_t)n * sizeof *B);
    if (!A || !B || SUNContext_Create(NULL, &ctx) || !(y = N_VNew_Serial(N, ctx)) ||
        !(b = N_VNew_Serial(N, ctx)) || !(x = N_VNew_Serial(N, ctx)) ||
        !(rb = N_VNew_Serial(N2, ctx)) || !(xb = N_VNew_Serial(N2, ctx)) ||
        !(LS = rd_lift_newton_create(&form, ctx, &hold, &nw)) ||
        !(Sb = SUNBandMatrix(N2, 11, 11, ctx)) || !(LSb = SUNLinSol_Band(rb, Sb, ctx)) ||
        SUNLinSolInitialize(LS) || SUNLinSolInitialize(LSb))
        goto out;
    N_VConst(0.0, y);
    form.blocks(form.user, 0.0, N_VGetArrayPointer(y), A, B);
    for (int k = 0; k < N2; k++)
        N_VGetArrayPointer(rb)[k] = sin(0.1 * k);
    /* the block path's reduced right-hand side equals rb when b_q = 0 */
    N_VConst(0.0, b);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 6; k++)
            N_VGetArrayPointer(b)[12 * i + 6 + k] = N_VGetArrayPointer(rb)[6 * i + k];
    double t[4][64];
    int jcur; /* the blocks once (jok = 0), then set-ups from them as the band path's */
    if (rd_lift_newton_linsys(nw, 0.0, y, 0, &jcur, GAMMA))
        goto out;
    for (int r = 0; r < reps && r < 64; r++) {
        double t0 = bench_now();
        for (int l = 0; l < loops; l++)
            if (rd_lift_newton_linsys(nw, 0.0, y, 1, &jcur, GAMMA) || SUNLinSolSetup(LS, hold))
                goto out;
        double t1 = bench_now();
        for (int l = 0; l < loops; l++)
            if (SUNLinSolSolve(LS, hold, x, b, 0.0))
                goto out;
        double t2 = bench_now();
        for (int l = 0; l < loops; l++) {
            band_fill(Sb, A, B, n);
            if (SUNLinSolSetup(LSb, Sb))
                goto out;
        }
        double t3 = bench_now();
        for (int l = 0; l < loops; l++)
            if (SUNLinSolSolve(LSb, Sb, xb, rb, 0.0))
                goto out;
        double t4 = bench_now();
        t[0][r] = (t1 - t0) / loops;
        t[1][r] = (t2 - t1) / loops;
        t[2][r] = (t3 - t2) / loops;
        t[3][r] = (t4 - t3) / loops;
    }
    double d = 0.0, s = 0.0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 6; k++) {
            double vb = N_VGetArrayPointer(x)[12 * i + 6 + k],
                   vd = N_VGetArrayPointer(xb)[6 * i + k];
            d = fmax(d, fabs(vb - vd));
            s = fmax(s, fabs(vd));
        }
    out[0].setup_us = 1e6 * bench_median(t[0], reps);
    out[0].solve_us = 1e6 * bench_median(t[1], reps);
    out[1].setup_us = 1e6 * bench_median(t[2], reps);
    out[1].solve_us = 1e6 * bench_median(t[3], reps);
    out[0].diff = out[1].diff = d / s;
    rc = 0;
out:
    if (rc)
        fprintf(stderr, "n = %d: SUNDIALS set-up or solve failed\n", n);
    if (LS)
        SUNLinSolFree(LS);
    if (LSb)
        SUNLinSolFree(LSb);
    if (Sb)
        SUNMatDestroy(Sb);
    N_Vector v[] = {y, b, x, rb, xb};
    for (int k = 0; k < 5; k++)
        if (v[k])
            N_VDestroy(v[k]);
    if (ctx)
        SUNContext_Free(&ctx);
    free(A);
    free(B);
    rd_lift_model_cleanup(&c);
    rd_ring_free(ring);
    return rc;
}

int main(int argc, char **argv)
{
    int reps = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--reps") && i + 1 < argc) {
            reps = atoi(argv[++i]);
        } else {
            fprintf(stderr, "usage: bench_newton [--reps R]\n");
            return 2;
        }
    }
    if (reps < 3)
        reps = 3;
    static const int ns[] = {20, 50, 100, 200, 500, 1000};
    enum { K = sizeof ns / sizeof ns[0] };
    double nn[K], tb[K], tband[K];
    printf("One Newton set-up (assemble + factor) and solve of the full lift model's S, gamma = "
           "%g s;\nmedian of %d timed loops (Release).\n\n"
           "| n | block set-up [us] | block solve [us] | band set-up [us] | band solve [us] | "
           "band / block (set-up + solve) | difference |\n|---|---|---|---|---|---|---|\n",
           GAMMA, reps);
    for (int k = 0; k < K; k++) {
        cost c[2];
        if (measure(ns[k], reps, c))
            return 1;
        nn[k] = ns[k];
        tb[k] = c[0].setup_us + c[0].solve_us;
        tband[k] = c[1].setup_us + c[1].solve_us;
        printf("| %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.1e |\n", ns[k], c[0].setup_us,
               c[0].solve_us, c[1].setup_us, c[1].solve_us, tband[k] / tb[k], c[0].diff);
        fflush(stdout);
    }
    printf("\ncost exponent (n = 20 .. 1000): block %.2f, band %.2f\n", bench_exponent(nn, tb, K),
           bench_exponent(nn, tband, K));
    return 0;
}
