/*
 * rd_film_jfo.c — the film with mass-conserving cavitation: the
 * Jakobsson-Floberg-Olsson conditions in Elrod and Adams' form (rd_film.h).
 *
 * Finite volumes on the nodes.  The flow through the face j between the
 * nodes j and j + 1, per metre of circumference,
 *     q_j = -k_j (p_{j+1} - p_j) / dx + (U / 2) theta_up e_j,
 *     e_j = h_T + sigma w_s phi_s at the face,
 * theta_up the content of the node the liner comes from (upwind: in a
 * cavity the oil sits in streamers carried at the mean of the surfaces'
 * speeds, U / 2); at each inner node
 *     (q_i - q_{i-1}) / dx + d(theta_i h_T,i)/dt = 0,
 * the time derivative the track's step c1_dt theta h_T - hist_dt, or
 * theta (dh_T/dh) dh0/dt for the film alone (c1_dt = 0).  A node is full
 * (theta = 1, its pressure p >= p_c the unknown) or in a cavity (p = p_c,
 * its content theta the unknown): for a given split the rows are linear and
 * tridiagonal (LAPACK dgtsv, with pivoting: a cavity's row is not
 * diagonally dominant), the split found by the active-set iteration (a full
 * node whose pressure falls below p_c joins the cavity, a cavity node whose
 * content rises above 1 fills).  With every node full the rows are those of
 * the Reynolds solve (rd_film.c): the two agree where no cavity forms.
 *
 * The cavity pressure p_c is 0 (the film's reference, as the Reynolds
 * condition's), but in a starved inlet's gas, the cavity connected to the
 * inlet edge: the inlet's gas pressure.  The inlet edge's content is 1
 * flooded; starved, the liner's film brought in, 2 h_s / e at the inlet
 * face (at most 1).
 */
#include "rd_film.h"

#include <lapacke.h>
#include <math.h>

/* The node i's index counted from the inlet edge (0). */
static int from_inlet(int n, int dir, int i)
{
    return dir > 0 ? i : n - 1 - i;
}

typedef struct jfo_edge {
    int dir, starved, run; /* liner direction, inlet starved, cavity nodes next to the inlet */
    double pin;
} jfo_edge;

static double cavity_pressure(const rd_film *f, const jfo_edge *e, int i)
{
    return e->starved && from_inlet(f->n, e->dir, i) <= e->run ? e->pin : 0.0;
}

/* The row of node i for the current split into f->a, b, c, r. */
static void row(rd_film *f, const rd_film_nodes *in, const jfo_edge *e, int i)
{
    int n = f->n;
    double idx2 = 1.0 / (f->dx * f->dx), hu = 0.5 * in->U / f->dx, sg = f->sigma;
    double cp[3] = {-f->kf[i - 1] * idx2, (f->kf[i - 1] + f->kf[i]) * idx2, -f->kf[i] * idx2};
    double el = in->hTf[i - 1] + sg * in->sf[i - 1], er = in->hTf[i] + sg * in->sf[i];
    double ct[3] = {0.0, 0.0, 0.0}, coef[3] = {0.0, 0.0, 0.0}, r = 0.0;
    if (e->dir > 0) {
        ct[0] = -hu * el;
        ct[1] = hu * er;
    } else {
        ct[1] = -hu * el;
        ct[2] = hu * er;
    }
    if (f->c1_dt > 0.0) { /* the track's step */
        ct[1] += f->c1_dt * in->hT[i];
        r += f->hist_dt[i];
    } else
        ct[1] += in->g[i] * in->h0_dot;
    for (int d = 0; d < 3; d++) {
        int j = i + d - 1;
        if (j == 0 || j == n - 1)
            r -= cp[d] * f->p[j] + ct[d] * f->theta[j];
        else if (!f->cav[j]) {
            coef[d] += cp[d];
            r -= ct[d];
        } else {
            coef[d] += ct[d];
            r -= cp[d] * cavity_pressure(f, e, j);
        }
    }
    if (coef[1] == 0.0) { /* a cavity without transport or time: its content kept full */
        coef[0] = coef[2] = 0.0;
        coef[1] = 1.0;
        r = 1.0;
    }
    f->a[i] = coef[0];
    f->b[i] = coef[1];
    f->c[i] = coef[2];
    f->r[i] = r;
}

/* Solves the split's rows into p and theta; 0 when LAPACK found them singular. */
static int solve_split(rd_film *f, const rd_film_nodes *in, jfo_edge *e)
{
    int n = f->n;
    e->run = 0;
    while (e->run + 1 <= n - 2 && f->cav[from_inlet(n, e->dir, e->run + 1)])
        e->run++;
    for (int i = 1; i <= n - 2; i++)
        row(f, in, e, i);
    lapack_int info = LAPACKE_dgtsv_work(LAPACK_COL_MAJOR, n - 2, 1, f->a + 2, f->b + 1, f->c + 1,
                                         f->r + 1, n - 2);
    if (info != 0)
        return 0;
    for (int i = 1; i <= n - 2; i++) {
        if (f->cav[i]) {
            f->theta[i] = f->r[i];
            f->p[i] = cavity_pressure(f, e, i);
        } else {
            f->theta[i] = 1.0;
            f->p[i] = f->r[i];
        }
    }
    return 1;
}

/* The active-set iteration on the split, from the last solve's. */
static void split(rd_film *f, const rd_film_nodes *in, jfo_edge *e)
{
    int n = f->n;
    for (int it = 0; it < 4 * n; it++) {
        if (!solve_split(f, in, e)) { /* singular: again from a full film */
            for (int i = 0; i < n; i++)
                f->cav[i] = 0;
            if (!solve_split(f, in, e))
                return;
        }
        int changed = 0;
        for (int i = 1; i <= n - 2; i++) {
            /* a full node next to a starved inlet's gas joins it below the gas's pressure */
            int k = from_inlet(n, e->dir, i);
            double pc = e->starved && k <= e->run + 1 ? e->pin : 0.0;
            int now = f->cav[i] ? !(f->theta[i] > 1.0) : f->p[i] < pc;
            if (now != f->cav[i]) {
                f->cav[i] = now;
                changed = 1;
            }
        }
        if (!changed)
            return;
    }
}

void rd_film_jfo_solve(rd_film *f, const rd_film_nodes *in, rd_film_out *o)
{
    int n = f->n, dir = in->U >= 0.0 ? 1 : -1;
    int ie = dir > 0 ? 0 : n - 1, oe = n - 1 - ie, fin = dir > 0 ? 0 : n - 2;
    double dx = f->dx, sg = f->sigma;
    jfo_edge e = {dir, 0, 0, fmax(dir > 0 ? in->p_lo : in->p_hi, 0.0)};
    double th_in = 1.0;
    if (f->supply > 0.0 && in->U != 0.0)
        th_in = fmin(1.0, 2.0 * f->supply / (in->hTf[fin] + sg * in->sf[fin]));
    e.starved = th_in < 1.0;
    f->p[ie] = e.pin;
    f->p[oe] = fmax(dir > 0 ? in->p_hi : in->p_lo, 0.0);
    f->theta[ie] = th_in;
    f->theta[oe] = 1.0;
    split(f, in, &e);
    double W = 0.0, Fp = 0.0, Cc = 0.0, cav = 0.0;
    for (int i = 0; i < n; i++) {
        double w = (i == 0 || i == n - 1) ? 0.5 : 1.0;
        f->theta[i] = fmin(fmax(f->theta[i], 0.0), 1.0);
        f->p[i] = fmax(f->p[i], 0.0);
        f->content[i] = f->theta[i] * in->hT[i];
        W += w * dx * f->p[i];
        Cc += w * dx * f->theta[i] * in->eta / in->hT[i];
        cav += (i > 0 && i < n - 1 && f->cav[i]) ? 1.0 : 0.0;
    }
    for (int j = 0; j + 1 < n; j++) {
        double dp = f->p[j + 1] - f->p[j], up = f->theta[dir > 0 ? j : j + 1];
        f->qf[j] = -f->kf[j] * dp / dx + 0.5 * in->U * up * (in->hTf[j] + sg * in->sf[j]);
        Fp -= 0.5 * fmax(in->h0 + f->drop_mid[j], 0.0) * dp;
    }
    f->dry = 0;
    o->W = W;
    o->Fp = Fp;
    o->Cc = Cc;
    o->cavitated = cav / (n - 2);
    o->h_min = in->h0;
}
