/*
 * rd_film_laws.c — the rough-surface laws of the film (rd_film.h): the
 * Patir-Cheng flow factors for Peklenik gamma = 1, the expected gap of a
 * Gaussian roughness and the Greenwood-Tripp integrals F_5/2 and F_2.
 */
#include <math.h>
#include <threads.h>

#include "rd_film.h"

/* Patir & Cheng (1978), gamma = 1: phi_x = 1 - C e^{-r H}, C = 0.90, r = 0.56
 * (fitted for H > 0.5). */
double rd_film_phi_x(double H)
{
    if (H < RD_FILM_PHI_X_H_MIN)
        H = RD_FILM_PHI_X_H_MIN;
    return 1.0 - 0.90 * exp(-0.56 * H);
}

/* Patir & Cheng (1979), gamma = 1: Phi_s = A1 H^a1 e^{-a2 H + a3 H^2} for H
 * <= 5, A2 e^{-0.25 H} above; A1 1.899, a1 0.98, a2 0.92, a3 0.05, A2 1.126. */
double rd_film_phi_s(double H)
{
    if (H <= 0.0)
        return 0.0;
    if (H <= 5.0)
        return 1.899 * pow(H, 0.98) * exp(-0.92 * H + 0.05 * H * H);
    return 1.126 * exp(-0.25 * H);
}

/* h_T / sigma = int max(H - d, 0) N(d) dd = H Phi(H) + phi(H) (Gaussian
 * heights), its slope Phi(H). */
double rd_film_gap(double H, double *dgap)
{
    double Phi = 0.5 * erfc(-H / M_SQRT2), phi = exp(-0.5 * H * H) / sqrt(2.0 * M_PI);
    if (dgap)
        *dgap = Phi;
    return H * Phi + phi;
}

/* F_2 = ((1 + l^2)/2) erfc(l / sqrt 2) - l phi(l). */
double rd_film_gt_f2(double l)
{
    return 0.5 * (1.0 + l * l) * erfc(l / M_SQRT2) - l * exp(-0.5 * l * l) / sqrt(2.0 * M_PI);
}

/* F_n(l) = (1/sqrt(2 pi)) int_0^inf 2 u^(2n+1) e^{-(l + u^2)^2 / 2} du (s =
 * l + u^2: smooth in u), by 48 panels of 8-point Gauss-Legendre over [0,
 * u_max], u_max^2 = s with l s + s^2 / 2 = 60 (the integrand below e^-60 of
 * its peak beyond). */
double rd_film_gt_quad(double n, double l)
{
    static const double xg[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                 0.9602898564975363};
    static const double wg[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                 0.1012285362903763};
    double s = -l + sqrt(l * l + 120.0), umax = sqrt(s), sum = 0.0;
    int panels = 48;
    double hw = 0.5 * umax / panels;
    for (int k = 0; k < panels; k++) {
        double mid = (2 * k + 1) * hw;
        for (int j = 0; j < 8; j++) {
            double u = mid + (j < 4 ? -1.0 : 1.0) * xg[j % 4] * hw, e = l + u * u;
            sum += wg[j % 4] * hw * 2.0 * pow(u, 2.0 * n + 1.0) * exp(-0.5 * e * e);
        }
    }
    return sum / sqrt(2.0 * M_PI);
}

/* ln F_5/2 and its slope -2.5 F_3/2 / F_5/2 on a grid of GT_STEP, built once
 * per process. */
#define GT_STEP 0.02
#define GT_N    801 /* (RD_FILM_GT_LAMBDA_MAX - RD_FILM_GT_LAMBDA_MIN) / GT_STEP + 1 */
static double gt_ln[GT_N], gt_dln[GT_N];
/* the expected gap and its slope on the same grid, with their slopes */
static double tb_gap[GT_N], tb_dgap[GT_N], tb_pdf[GT_N];
static once_flag gt_once = ONCE_FLAG_INIT;

static void gt_build(void)
{
    for (int i = 0; i < GT_N; i++) {
        double l = RD_FILM_GT_LAMBDA_MIN + GT_STEP * i;
        double f52 = rd_film_gt_quad(2.5, l), f32 = rd_film_gt_quad(1.5, l);
        gt_ln[i] = log(f52);
        gt_dln[i] = -2.5 * f32 / f52;
        tb_gap[i] = rd_film_gap(l, &tb_dgap[i]);
        tb_pdf[i] = exp(-0.5 * l * l) / sqrt(2.0 * M_PI);
    }
}

/* Cubic Hermite on cell i at t in [0, 1] from values v and slopes d (per unit H). */
static double hermite(const double *v, const double *d, int i, double t)
{
    double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * v[i] + (t3 - 2 * t2 + t) * GT_STEP * d[i] +
           (-2 * t3 + 3 * t2) * v[i + 1] + (t3 - t2) * GT_STEP * d[i + 1];
}

void rd_film_node_laws(double H, double *gap, double *dgap, double *f52)
{
    call_once(&gt_once, gt_build);
    if (H >= RD_FILM_GT_LAMBDA_MAX) {
        *gap = H;
        *dgap = 1.0;
        *f52 = 0.0;
        return;
    }
    double u = (fmax(H, RD_FILM_GT_LAMBDA_MIN) - RD_FILM_GT_LAMBDA_MIN) / GT_STEP;
    int i = (int)u;
    if (i > GT_N - 2)
        i = GT_N - 2;
    double t = u - i;
    *gap = H < RD_FILM_GT_LAMBDA_MIN ? rd_film_gap(H, dgap) : hermite(tb_gap, tb_dgap, i, t);
    if (H >= RD_FILM_GT_LAMBDA_MIN)
        *dgap = hermite(tb_dgap, tb_pdf, i, t);
    *f52 = exp(hermite(gt_ln, gt_dln, i, t));
}

double rd_film_gt_f52(double l)
{
    call_once(&gt_once, gt_build);
    if (l >= RD_FILM_GT_LAMBDA_MAX)
        return 0.0;
    if (l < RD_FILM_GT_LAMBDA_MIN)
        l = RD_FILM_GT_LAMBDA_MIN;
    double u = (l - RD_FILM_GT_LAMBDA_MIN) / GT_STEP;
    int i = (int)u;
    if (i > GT_N - 2)
        i = GT_N - 2;
    double t = u - i, t2 = t * t, t3 = t2 * t;
    double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    return exp(h00 * gt_ln[i] + h10 * GT_STEP * gt_dln[i] + h01 * gt_ln[i + 1] +
               h11 * GT_STEP * gt_dln[i + 1]);
}

double rd_film_composite_modulus(double E, double nu)
{
    return 1.0 / ((1.0 - nu * nu) / E + (1.0 - RD_LINER_NU * RD_LINER_NU) / RD_LINER_E);
}
