/*
 * test_ringpack_jacobian — the exact derivatives the pack's Newton systems
 * use (rd_gasflow_flow's partial derivatives, rd_ringpack_base_jacobian)
 * against central differences of the functions themselves.
 *   (1) the orifice: d mdot / d p_a, d p_b, d A on every branch (choked,
 *       unchoked, the linear band, reversed flow, the opening orifice at
 *       A = 0), and its value against rd_gasflow_orifice;
 *   (2) the network: every column of J = d f / d y and G = d f / d area of
 *       rd_ringpack_base_rhs for 1 to 3 rings, axial rings free (their
 *       force, friction, flank areas) and seated, at pressures that put the
 *       passages on different branches; and the mass balance's property of
 *       a Newton matrix: each column's weighted sum is zero.
 * This file includes the pack's internal header (rd_ringpack_model.h), as
 * test_blocktri does the lift model's, to reach the model's functions.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_ringpack_model.h"

#define KAPPA RD_GASFLOW_KAPPA
#define RG    RD_GASFLOW_R

/* Side b's temperature: 380 K (so a reversed flow must take it), but at
 * equal pressures 450 K as side a's: the upstream temperature switches
 * there, a kink a central difference would average. */
#define TB(x) ((x)[0] == (x)[1] ? 450.0 : 380.0)

/* Central difference of the flow in p_a (k = 0), p_b (1) or A (2) with
 * relative step h. */
static double flow_cd(const rd_gasflow_law *law, const double x[3], int k, double h)
{
    double lo[3], hi[3];
    memcpy(lo, x, sizeof lo);
    memcpy(hi, x, sizeof hi);
    double step = h * fmax(fabs(x[k]), k == 2 ? 1e-6 : 1e5);
    lo[k] -= step;
    hi[k] += step;
    if (k == 2 && lo[2] < 0.0) /* the area's one-sided difference at A = 0 */
        lo[2] = x[2];
    double f1 = rd_gasflow_flow(law, 0.7, hi[2], hi[0], 450.0, hi[1], TB(x), NULL);
    double f0 = rd_gasflow_flow(law, 0.7, lo[2], lo[0], 450.0, lo[1], TB(x), NULL);
    return (f1 - f0) / (hi[k] - lo[k]);
}

static void test_orifice(void)
{
    rd_gasflow_law law;
    rd_gasflow_law_init(&law, KAPPA, RG);
    /* (p_a, p_b, A): choked, unchoked, band, reversed unchoked and choked,
     * equal pressures, no area */
    static const double cases[][3] = {
        {5e6, 1e6, 1e-6},     {3e5, 2e5, 2e-6}, {2e5, 2e5 * (1 - 3e-5), 1e-6},
        {1.5e5, 2.5e5, 1e-6}, {1e5, 9e5, 3e-7}, {2e5, 2e5, 1e-6},
        {4e5, 1e5, 0.0}};
    int n = (int)(sizeof cases / sizeof cases[0]);
    for (int c = 0; c < n; c++) {
        double d[3];
        const double *x = cases[c];
        double f = rd_gasflow_flow(&law, 0.7, x[2], x[0], 450.0, x[1], TB(x), d);
        /* the same value as rd_gasflow_orifice, bit for bit (its rounding is
         * part of the pack's trajectories) */
        double ref = rd_gasflow_orifice(0.7, x[2], x[0], 450.0, x[1], TB(x), KAPPA, RG);
        CHECK(f == ref, "case %d: flow %.17g vs %.17g", c, f, ref);
        for (int k = 0; k < 3; k++) {
            /* steps: 1e-7 of p inside the band (its width is 1e-4 of p), else
             * 1e-6; central differences of a smooth branch are good to
             * ~h^2 + eps/h ~ 1e-10, so 1e-7 of the derivative's scale */
            double h = c == 2 && k < 2 ? 1e-9 : 1e-6, fd = flow_cd(&law, x, k, h);
            double scale = fabs(d[k]) + (k < 2 ? fabs(d[0]) + fabs(d[1]) : fabs(f / 1e-6)) + 1e-30;
            CHECK(fabs(d[k] - fd) <= 1e-6 * scale, "case %d: d/dx%d analytic %.10g, central %.10g",
                  c, k, d[k], fd);
        }
    }
}

/* The pack of bench_ringpack (the examples' thesis pack), R rings. */
static void pack(rd_ringpack_params *p, int R, int friction)
{
    static const double h[3] = {0.0012, 0.0015, 0.0025}, g[3] = {3e-4, 4e-4, 3e-4};
    static const double ca[3] = {3e-5, 4e-5, 4e-5}, lh[3] = {0.005, 0.004, 0.0035};
    rd_ringpack_params_default(p);
    p->n_rings = R;
    for (int i = 0; i < R; i++) {
        p->rings[i].ring.axial_height = h[i];
        p->rings[i].ring.closed_gap = g[i];
        p->rings[i].groove.axial_clearance = ca[i];
        p->rings[i].land_height = lh[i];
    }
    if (friction)
        p->friction.model = RD_FRICTION_COULOMB;
}

/* Central differences of base_rhs in state j (or area c when j < 0) into
 * col (N0). */
static void rhs_column(const rd_ringpack_model *m, double t, const double *y, const double *area,
                       int j, int c, double *col)
{
    double yp[64], yq[64], ap[6], aq[6], fp[64], fq[64];
    memcpy(yp, y, (size_t)m->N0 * sizeof *y);
    memcpy(yq, y, (size_t)m->N0 * sizeof *y);
    memcpy(ap, area, sizeof ap);
    memcpy(aq, area, sizeof aq);
    double h, span;
    if (j >= 0) {
        h = j < 2 * m->R ? 1e-6 * y[j] : j % 2 == 0 ? 1e-6 * m->ca[0] : 1e-6;
        yp[j] += h;
        yq[j] -= h;
        span = 2.0 * h;
    } else { /* a closed passage (A = 0): the opening side's difference */
        h = 1e-6 * m->circ[0] * m->ca[0];
        ap[c] += h;
        aq[c] = fmax(aq[c] - h, 0.0);
        span = ap[c] - aq[c];
    }
    rd_ringpack_base_rhs(m, t, yp, ap, fp);
    rd_ringpack_base_rhs(m, t, yq, aq, fq);
    for (int r = 0; r < m->N0; r++)
        col[r] = (fp[r] - fq[r]) / span;
}

/* Largest |a - b| over the column against its largest entry. */
static double column_error(const double *a, const double *b, int n)
{
    double e = 0.0, s = 1e-300;
    for (int r = 0; r < n; r++) {
        e = fmax(e, fabs(a[r] - b[r]));
        s = fmax(s, fmax(fabs(a[r]), fabs(b[r])));
    }
    return e / s;
}

/* Columns of J and G at one state (lifts z of the axial rings, mode as
 * given) against central differences; the weighted column sums. */
static void check_state(rd_ringpack_params *p, double deg, const double *pr, double z, int mode,
                        const char *what)
{
    rd_ringpack_model m;
    rd_error err;
    rd_error_init(&err);
    CHECK(rd_ringpack_model_init(&m, p, &err) == RD_OK, "%s: %s", what, err.message);
    double y[64] = {0}, area[6], J[64 * 64], G[6 * 64], fd[64], worst = 0.0, sums = 0.0;
    for (int v = 0; v < m.V; v++)
        y[v] = pr[v];
    for (int i = 0; i < m.R; i++) {
        m.mode[i] = mode;
        RP_Z(&m, y, i) = z * m.ca[i];
        RP_ZD(&m, y, i) = 0.01 * (i + 1); /* m/s: inside the friction's tanh */
    }
    double t = deg / (m.omega * 180.0 / M_PI);
    rd_ringpack_areas(&m, y, area);
    rd_ringpack_base_jacobian(&m, t, y, area, J, G);
    for (int j = 0; j < m.N0 + 2 * m.R; j++) {
        int c = j - m.N0, cum = j >= 4 * m.R && j < m.N0;
        if (cum) /* the masses feed nothing back: zero columns */
            continue;
        double *col = c < 0 ? J + (size_t)j * m.N0 : G + (size_t)c * m.N0;
        rhs_column(&m, t, y, area, c < 0 ? j : -1, c, fd);
        if (c < 0 && j >= 2 * m.R && j % 2 == 0) { /* an axial z: through its areas too */
            int i = (j - 2 * m.R) / 2;
            double zz = RP_Z(&m, y, i), du = m.ca[i] - zz > 0.0 ? -m.circ[i] : 0.0;
            double dl = zz > 0.0 ? m.circ[i] : 0.0, g0[64], g1[64];
            rhs_column(&m, t, y, area, -1, 2 * i, g0);
            rhs_column(&m, t, y, area, -1, 2 * i + 1, g1);
            for (int r = 0; r < m.N0; r++)
                fd[r] += g0[r] * du + g1[r] * dl;
        }
        worst = fmax(worst, column_error(col, fd, m.N0));
        double s = 0.0, top = 0.0; /* sum_v V/(R T) J_vj + mass rows (+-1) */
        for (int v = 1; v <= m.V; v++) {
            double w = m.vol[v] / (RG * m.temp[v]);
            s += w * col[v - 1];
            top = fmax(top, fabs(w * col[v - 1]));
        }
        double *cm = col + 4 * m.R;
        s += -cm[0] + cm[1] + cm[2] - cm[3];
        sums = fmax(sums, fabs(s) / fmax(top, 1e-300));
    }
    /* 1e-6: central differences at 1e-6 steps carry ~1e-10 truncation and
     * rounding of the flows' sums; a wrong term is O(1) of its column */
    CHECK(worst <= 1e-6, "%s: J, G against central differences: %.2e", what, worst);
    /* 1e-12: the column sums cancel to round-off of their largest term */
    CHECK(sums <= 1e-12, "%s: weighted column sums %.2e", what, sums);
    printf("%s: J, G within %.1e of central differences; column sums %.1e\n", what, worst, sums);
    rd_ringpack_model_cleanup(&m);
}

static void test_network(void)
{
    rd_ringpack_params p;
    /* one ring: choked end gap into the crankcase at 20 bar in the land */
    static const double p1[] = {2e6, 1.5e6};
    pack(&p, 1, 0);
    check_state(&p, 10.0, p1, 0.4, RD_FLANK_FREE, "1 ring, free");
    /* three rings with friction: the top land above the cylinder (reverse
     * entry, at 200 deg the cylinder is near 1 bar), unchoked inner passages */
    static const double p3[] = {3e5, 2.6e5, 2.2e5, 1.9e5, 1.4e5, 1.2e5};
    pack(&p, 3, 1);
    check_state(&p, 200.0, p3, 0.3, RD_FLANK_FREE, "3 rings, friction, free");
    check_state(&p, 200.0, p3, 0.0, RD_FLANK_LOWER, "3 rings, seated");
    /* two rings at full load near the peak: choked top entry and gap */
    static const double p2[] = {3e6, 2.8e6, 1.2e6, 1e6};
    pack(&p, 2, 1);
    check_state(&p, 15.0, p2, 0.7, RD_FLANK_FREE, "2 rings, friction, near the peak");
}

int main(void)
{
    test_orifice();
    test_network();
    return check_done();
}
