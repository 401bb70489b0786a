/*
 * rd_gasflow.c — orifice flow and the cylinder pressure trace (equations in
 * rd_gasflow.h).
 */
#include "rd_gasflow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_internal.h"
#include "rd_interp.h"

double rd_gasflow_critical_ratio(double kappa)
{
    return pow(2.0 / (kappa + 1.0), kappa / (kappa - 1.0));
}

/* The flow function psi = mdot sqrt(R T_u) / (C_d A p_u) at pressure ratio
 * r (0 <= r <= 1) and its slope dpsi/dr into *slope (rd_gasflow.h):
 * choked below r_c, the isentropic form above it, linear in 1 - r above
 * r_lin.  The isentropic form is computed as it always was (two powers):
 * its rounding is part of the pack's trajectories, whose friction-driven
 * leaves move by 0.1 deg under a change of the flows' last bits. */
static double psi_of(const rd_gasflow_law *law, double r, double *slope)
{
    if (r > 1.0 - RD_GASFLOW_LINEAR_BAND) {
        *slope = -law->psi_lin / RD_GASFLOW_LINEAR_BAND;
        return law->psi_lin * (1.0 - r) / RD_GASFLOW_LINEAR_BAND;
    }
    if (r <= law->r_c) {
        *slope = 0.0;
        return law->psi_choked;
    }
    double a = pow(r, law->e_a), b = pow(r, law->e_b), v = a - b; /* r^(2/k), r^((k+1)/k) */
    double psi = sqrt(law->K * (v > 0.0 ? v : 0.0));
    /* dv/dr = (2/k) r^(2/k) / r - ((k+1)/k) r^((k+1)/k) / r;  dpsi/dr = K dv/dr / (2 psi) */
    if (slope)
        *slope = psi > 0.0 ? 0.5 * law->K * (law->e_a * a - law->e_b * b) / (r * psi) : 0.0;
    return psi;
}

void rd_gasflow_law_init(rd_gasflow_law *law, double kappa, double R)
{
    double slope;
    law->kappa = kappa;
    law->R = R;
    law->r_c = rd_gasflow_critical_ratio(kappa);
    law->psi_choked = sqrt(kappa) * pow(2.0 / (kappa + 1.0), (kappa + 1.0) / (2.0 * (kappa - 1.0)));
    law->e_a = 2.0 / kappa;
    law->e_b = (kappa + 1.0) / kappa;
    law->K = 2.0 * kappa / (kappa - 1.0);
    law->psi_lin = 0.0;
    law->psi_lin = psi_of(law, 1.0 - RD_GASFLOW_LINEAR_BAND, &slope);
}

double rd_gasflow_flow(const rd_gasflow_law *law, double cd, double area, double p_a, double T_a,
                       double p_b, double T_b, double d[3])
{
    if (d)
        d[0] = d[1] = d[2] = 0.0;
    if (!(cd > 0.0))
        return 0.0;
    int forward = p_a >= p_b;
    double pu = forward ? p_a : p_b, pd = forward ? p_b : p_a, Tu = forward ? T_a : T_b;
    if (!(pu > 0.0))
        return 0.0;
    double r = pd > 0.0 ? pd / pu : 0.0, slope, psi = psi_of(law, r, &slope);
    double A = area > 0.0 ? area : 0.0, sign = forward ? 1.0 : -1.0;
    if (d) { /* mdot = sign c A p_u psi(p_d / p_u), c = C_d / sqrt(R T_u) */
        double c = sign * cd / sqrt(law->R * Tu);
        double du = c * A * (psi - r * slope), dd = pd > 0.0 ? c * A * slope : 0.0;
        d[0] = forward ? du : dd;
        d[1] = forward ? dd : du;
        d[2] = c * pu * psi;
    }
    double mdot = cd * A * pu / sqrt(law->R * Tu) * psi;
    return forward ? mdot : -mdot;
}

double rd_gasflow_orifice(double cd, double area, double p_a, double T_a, double p_b, double T_b,
                          double kappa, double R)
{
    rd_gasflow_law law;
    rd_gasflow_law_init(&law, kappa, R);
    return rd_gasflow_flow(&law, cd, area, p_a, T_a, p_b, T_b, NULL);
}

double rd_gas_viscosity(double T)
{
    return RD_GAS_MU0 * pow(T / RD_GAS_T0, 1.5) * (RD_GAS_T0 + RD_GAS_SUTHERLAND) /
           (T + RD_GAS_SUTHERLAND);
}

double rd_gasflow_slot_flow(const rd_gasflow_slot *s, double R, double area, double p_a, double p_b,
                            double d[3])
{
    double A = area > 0.0 ? area : 0.0;
    /* mdot = k A^3 (p_a^2 - p_b^2), k = 1 / (w^2 24 mu R T L) */
    double k = 1.0 / (s->width * s->width * 24.0 * s->mu * R * s->T * s->length);
    double A3 = A * A * A, dp2 = p_a * p_a - p_b * p_b;
    if (d) {
        d[0] = 2.0 * k * A3 * p_a;
        d[1] = -2.0 * k * A3 * p_b;
        d[2] = 3.0 * k * A * A * dp2;
    }
    return k * A3 * dp2;
}

/* The blend (rd_gasflow.h) of two flows of the same sign: |m| = (|a|^-4 +
 * |b|^-4)^(-1/4); the weights (m/a)^5 and (m/b)^5 into wa, wb. */
static double blend(double a, double b, double *wa, double *wb)
{
    double x = fabs(a), y = fabs(b);
    if (!(x > 0.0) || !(y > 0.0)) {
        *wa = *wb = 0.0;
        return 0.0;
    }
    double r = x < y ? x / y : y / x, small = x < y ? x : y; /* r <= 1 */
    double m = small * pow(1.0 + r * r * r * r, -0.25), qa = m / x, qb = m / y;
    *wa = qa * qa * qa * qa * qa;
    *wb = qb * qb * qb * qb * qb;
    return a > 0.0 ? m : -m;
}

double rd_gasflow_limited(const rd_gasflow_law *law, const rd_gasflow_slot *s, double cd,
                          double area, double p_a, double T_a, double p_b, double T_b, double d[3])
{
    double dor[3], dsl[3], wo, ws;
    double mo = rd_gasflow_flow(law, cd, area, p_a, T_a, p_b, T_b, d ? dor : NULL);
    double ms = rd_gasflow_slot_flow(s, law->R, area, p_a, p_b, d ? dsl : NULL);
    double m = blend(mo, ms, &wo, &ws);
    if (!d)
        return m;
    if (m != 0.0) {
        for (int k = 0; k < 3; k++)
            d[k] = wo * dor[k] + ws * dsl[k];
        return m;
    }
    /* zero flow: equal pressures (the blend of the slopes), or no area or
     * no discharge (nothing flows, nothing opens at first order: the slot's
     * A^3) */
    d[2] = 0.0;
    for (int k = 0; k < 2; k++) {
        double sl = blend(dor[k], dsl[k], &wo, &ws);
        d[k] = area > 0.0 && cd > 0.0 ? sl : 0.0;
    }
    return m;
}

/* ------------------------------------------------------- pressure tables */

double rd_gasflow_table(int n, const double *x, const double *y, double deg)
{
    double t = fmod(deg, 720.0);
    if (t < 0.0)
        t += 720.0;
    return rd_interp_linear(x, y, n, t);
}

/* Fritsch-Butland slope at point k of a periodic table (the point before
 * x[0] is x[n-2] - 720, the one after x[n-1] is x[1] + 720): zero at a
 * local extremum, else a weighted harmonic mean of the two secants, which
 * keeps the cubic monotone between monotone points. */
static double trace_slope(int n, const double *x, const double *y, int k)
{
    int a = k > 0 ? k - 1 : n - 2, b = k < n - 1 ? k + 1 : 1;
    double xa = k > 0 ? x[a] : x[a] - 720.0, xb = k < n - 1 ? x[b] : x[b] + 720.0;
    double ha = x[k] - xa, hb = xb - x[k];
    double da = (y[k] - y[a]) / ha, db = (y[b] - y[k]) / hb;
    if (n < 3 || da * db <= 0.0)
        return 0.0;
    double wa = 2.0 * hb + ha, wb = hb + 2.0 * ha;
    return (wa + wb) / (wa / da + wb / db);
}

/* The interval of t = deg mod 720 (x[lo] <= t < x[lo + 1]) and t: where
 * the points were equally spaced (the synthetic trace's 0.25 deg), else
 * by bisection. */
static int trace_interval(int n, const double *x, double deg, double *t)
{
    *t = fmod(deg, 720.0);
    if (*t < 0.0)
        *t += 720.0;
    int lo = (int)(*t / 720.0 * (n - 1)), hi = n - 1;
    if (lo >= 0 && lo < n - 1 && x[lo] <= *t && *t < x[lo + 1])
        return lo;
    lo = 0;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (x[mid] <= *t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The cubic Hermite piece on [x[lo], x[lo + 1]] with end slopes s0, s1. */
static double hermite(const double *x, const double *y, int lo, double s0, double s1, double t)
{
    int hi = lo + 1;
    double h = x[hi] - x[lo], u = (t - x[lo]) / h;
    double m0 = s0 * h, m1 = s1 * h;
    double u2 = u * u, u3 = u2 * u; /* cubic Hermite basis */
    return (2 * u3 - 3 * u2 + 1) * y[lo] + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * y[hi] +
           (u3 - u2) * m1;
}

double rd_gasflow_trace(int n, const double *x, const double *y, double deg)
{
    double t;
    int lo = trace_interval(n, x, deg, &t);
    return hermite(x, y, lo, trace_slope(n, x, y, lo), trace_slope(n, x, y, lo + 1), t);
}

void rd_gasflow_trace_slopes(int n, const double *x, const double *y, double *slope)
{
    for (int k = 0; k < n; k++)
        slope[k] = trace_slope(n, x, y, k);
}

double rd_gasflow_trace_at(int n, const double *x, const double *y, const double *slope, double deg)
{
    double t;
    int lo = trace_interval(n, x, deg, &t);
    return hermite(x, y, lo, slope[lo], slope[lo + 1], t);
}

int rd_gasflow_table_validate(int n, const double *deg, const double *pa, rd_error *err)
{
    const char *at = "/crank_deg";
    if (n < 2 || !deg || !pa)
        return rd_error_set(err, RD_EINVAL, at, "@%s needs at least 2 points.", at);
    for (int k = 0; k < n; k++) {
        char f[RD_ERROR_PATH_MAX];
        snprintf(f, sizeof f, "/pressure_pa/%d", k);
        int rc = rd_error_range(pa[k], 1e3, 1e9, f, "Pa (absolute)", err);
        if (rc)
            return rc;
        if (k > 0 && !(deg[k] > deg[k - 1])) {
            snprintf(f, sizeof f, "%s/%d", at, k);
            return rd_error_set(err, RD_EINVAL, f,
                                "@%s = %g must exceed the angle before it "
                                "(%g): the angles must increase strictly.",
                                f, deg[k], deg[k - 1]);
        }
    }
    if (!(deg[0] <= 0.0 && deg[0] >= -1e-9) || !(deg[n - 1] >= 720.0 && deg[n - 1] <= 720.0 + 1e-9))
        return rd_error_set(err, RD_EINVAL, at,
                            "@%s runs from %g to %g deg but must cover the whole cycle: first "
                            "angle 0, last 720 (the trace repeats every 720 deg).",
                            at, deg[0], deg[n - 1]);
    return RD_OK;
}

/* ------------------------------------------------------ synthetic trace */

int rd_gasflow_synthetic_validate(const rd_cylinder_synthetic *s, rd_error *err)
{
    char f[RD_ERROR_PATH_MAX];
#define BAD(key, cond, range)                                                    \
    do {                                                                         \
        snprintf(f, sizeof f, "/%s", key);                                       \
        if (!(cond))                                                             \
            return rd_error_set(err, RD_EINVAL, f, "@%s must be %s.", f, range); \
    } while (0)
    BAD("compression_ratio", s->compression_ratio >= 2.0 && s->compression_ratio <= 40.0,
        "from 2 to 40");
    BAD("intake_pa", s->intake_pa >= 1e4 && s->intake_pa <= 1e7, "from 1e4 to 1e7 Pa (absolute)");
    if (s->kind == RD_CYLINDER_MOTORED)
        return RD_OK;
    BAD("peak_crank_deg", s->peak_crank_deg >= 0.0 && s->peak_crank_deg <= 60.0,
        "from 0 to 60 deg after firing TDC");
    double motored = s->intake_pa * pow(s->compression_ratio, RD_GASFLOW_POLYTROPIC);
    snprintf(f, sizeof f, "/peak_pa");
    if (!(s->peak_pa > 1.05 * motored && s->peak_pa <= 1e8))
        return rd_error_set(err, RD_EINVAL, f,
                            "@%s = %g Pa must exceed the motored peak (intake_pa * "
                            "compression_ratio^%g = %g Pa) by 5 %% and be at most 1e8 Pa.",
                            f, s->peak_pa, RD_GASFLOW_POLYTROPIC, motored);
#undef BAD
    return RD_OK;
}

/* The geometry of the trace: volumes per grid angle. */
typedef struct trace {
    const rd_engine_params *e;
    double Ap, Vc;
} trace;

static double volume(const trace *tr, double deg, double *dV)
{
    double s, v, a; /* v = ds/dalpha */
    rd_engine_piston_alpha(tr->e, deg * M_PI / 180.0, &s, &v, &a);
    if (dV)
        *dV = tr->Ap * v * M_PI / 180.0; /* per degree */
    return tr->Vc + tr->Ap * s;
}

/* Wiebe burn rate dx_b/dtheta, 1/deg. */
static double burn_rate(double deg, double theta0)
{
    double x = (deg - theta0) / RD_GASFLOW_BURN_DEG, m = RD_GASFLOW_WIEBE_M;
    if (x <= 0.0)
        return 0.0;
    return RD_GASFLOW_WIEBE_A * (m + 1.0) / RD_GASFLOW_BURN_DEG * pow(x, m) *
           exp(-RD_GASFLOW_WIEBE_A * pow(x, m + 1.0));
}

/* dp_unit/dtheta for Q = 1 J. */
static double unit_rate(const trace *tr, double deg, double p, double theta0)
{
    double dV, V = volume(tr, deg, &dV), n = RD_GASFLOW_POLYTROPIC;
    return (n - 1.0) / V * burn_rate(deg, theta0) - n * p / V * dV;
}

#define HALF (RD_GASFLOW_POINTS / 2) /* grid index of 360 deg from -180 */

/* p_unit on the grid -180..180 deg (HALF + 1 points), RK4. */
static void unit_trace(const trace *tr, double theta0, double *pu)
{
    double h = RD_GASFLOW_STEP_DEG, p = 0.0;
    pu[0] = 0.0;
    for (int k = 0; k < HALF; k++) {
        double t = -180.0 + k * h;
        double k1 = unit_rate(tr, t, p, theta0);
        double k2 = unit_rate(tr, t + 0.5 * h, p + 0.5 * h * k1, theta0);
        double k3 = unit_rate(tr, t + 0.5 * h, p + 0.5 * h * k2, theta0);
        double k4 = unit_rate(tr, t + h, p + h * k3, theta0);
        p += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        pu[k + 1] = p;
    }
}

/* The peak of pm + Q pu: value, grid index. */
static double peak_of(const double *pm, const double *pu, double Q, int *at)
{
    double best = -1.0;
    for (int k = 0; k <= HALF; k++)
        if (pm[k] + Q * pu[k] > best) {
            best = pm[k] + Q * pu[k];
            *at = k;
        }
    return best;
}

/* The heat Q giving the asked peak for the burn start theta0; the peak's
 * angle (deg after TDC) into *peak_deg. */
static double heat_for_peak(const trace *tr, double theta0, double target, const double *pm,
                            double *pu, double *peak_deg)
{
    int at = 0;
    unit_trace(tr, theta0, pu);
    double lo = 0.0, hi = 1.0;
    while (peak_of(pm, pu, hi, &at) < target && hi < 1e12)
        hi *= 2.0;
    for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi);
        if (peak_of(pm, pu, mid, &at) < target)
            lo = mid;
        else
            hi = mid;
    }
    peak_of(pm, pu, hi, &at);
    *peak_deg = -180.0 + at * RD_GASFLOW_STEP_DEG;
    return hi;
}

/* Smooth 0 -> 1 over [a, b]. */
static double smoothstep(double x, double a, double b)
{
    double u = (x - a) / (b - a);
    u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
    return u * u * (3.0 - 2.0 * u);
}

int rd_gasflow_synthetic(const rd_cylinder_synthetic *s, const rd_engine_params *e, double bore,
                         double *crank_deg, double *p, rd_error *err)
{
    int rc = rd_gasflow_synthetic_validate(s, err);
    if (rc)
        return rc;
    trace tr = {e, M_PI * bore * bore / 4.0, 0.0};
    tr.Vc = tr.Ap * 2.0 * e->crank_radius / (s->compression_ratio - 1.0);
    double *pm = malloc(2 * (size_t)(HALF + 1) * sizeof *pm), *pu = pm ? pm + HALF + 1 : NULL;
    if (!pm)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the synthetic pressure.");
    double Vb = volume(&tr, 180.0, NULL), Q = 0.0;
    for (int k = 0; k <= HALF; k++)
        pm[k] = s->intake_pa * pow(Vb / volume(&tr, -180.0 + k * RD_GASFLOW_STEP_DEG, NULL),
                                   RD_GASFLOW_POLYTROPIC);
    memset(pu, 0, (size_t)(HALF + 1) * sizeof *pu);
    if (s->kind == RD_CYLINDER_FIRED) { /* bisect the burn start on the peak angle */
        double lo = s->peak_crank_deg - 90.0, hi = s->peak_crank_deg, at;
        for (int it = 0; it < 40; it++) {
            double mid = 0.5 * (lo + hi);
            heat_for_peak(&tr, mid, s->peak_pa, pm, pu, &at);
            if (at < s->peak_crank_deg)
                lo = mid;
            else
                hi = mid;
        }
        Q = heat_for_peak(&tr, 0.5 * (lo + hi), s->peak_pa, pm, pu, &at);
    }
    for (int j = 0; j < RD_GASFLOW_POINTS; j++) {
        double deg = j * RD_GASFLOW_STEP_DEG, rel = deg <= 360.0 ? deg : deg - 720.0;
        crank_deg[j] = deg;
        p[j] = s->intake_pa;
        if (rel >= -180.0 && rel <= 180.0) {
            int k = (int)lround((rel + 180.0) / RD_GASFLOW_STEP_DEG);
            double w = smoothstep(rel, RD_GASFLOW_EVO_DEG, 180.0);
            p[j] = (1.0 - w) * (pm[k] + Q * pu[k]) + w * s->intake_pa;
        }
    }
    free(pm);
    return RD_OK;
}
