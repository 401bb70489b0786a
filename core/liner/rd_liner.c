/*
 * rd_liner.c — the ring-liner law per point of the running face
 * (rd_liner_law.h has the equations).
 */
#include "rd_liner_law.h"

#include <math.h>

double rd_liner_ureg(const rd_engine_params *e)
{
    return RD_LINER_UREG_FRACTION * rd_engine_mean_speed(e);
}

void rd_liner_init(rd_liner *l, const rd_friction_params *f, double ureg, double h)
{
    l->model = f->model;
    l->mu = f->coefficient;
    l->ureg = ureg;
    l->eta = f->viscosity;
    l->so_lim = f->sommerfeld_transition;
    l->kh = f->hydrodynamic_slope;
    l->h = h;
}

void rd_liner_eval(const rd_liner *l, const rd_liner_point *in, rd_liner_force *out)
{
    double N = in->N, u = in->u, share = in->share;
    double T = tanh(u / l->ureg), T_u = (1.0 - T * T) / l->ureg;
    if (l->model == RD_FRICTION_COULOMB) {
        out->F_N = -l->mu * T;
        out->F_u = -l->mu * N * T_u;
        out->F = -l->mu * N * T;
        return;
    }
    /* Stribeck (2.9): B = C e^{-3 r^2.5} N, r = So_lim / So; H = K eta |u| h s_k / L */
    double sg = u >= 0.0 ? 1.0 : -1.0, au = fabs(u);
    double H = l->kh * l->eta * au * l->h * share, H_u = l->kh * l->eta * l->h * share * sg;
    double B = 0.0, B_N = 0.0, B_u = 0.0;
    if (N > 0.0) {
        double r_u = l->so_lim * l->eta * l->h * share / N; /* r / |u| */
        double r = r_u * au, r15 = pow(r, 1.5), E = exp(-3.0 * r15 * r);
        B = l->mu * E * N;
        B_N = l->mu * E * (1.0 + 7.5 * r15 * r);
        B_u = -7.5 * l->mu * E * r15 * r_u * N * sg;
    }
    out->F_N = -T * B_N;
    out->F_u = -T_u * (B + H) - T * (B_u + H_u);
    out->F = -T * (B + H);
}
