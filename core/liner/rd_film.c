/*
 * rd_film.c — the running face's profile and one solve of its film
 * (rd_film.h has the equations).
 */
#include "rd_film.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Far from the roughness the laws are their smooth limits to double
 * precision: the expected gap is h above H = 9 (Phi(-9) ~ 1e-19), phi_x is
 * 1 above H = 64 (0.9 e^{-0.56 H} < 3e-16). */
#define FAR_GAP 9.0
#define FAR_H   64.0

/* The face's drop at x (m from the lower edge), before its minimum is
 * taken off. */
static double profile_at(const rd_face_params *fp, double L, double x)
{
    switch (fp->profile) {
    case RD_FACE_BARREL: {
        double u = (x - 0.5 * L - fp->offset) / (0.5 * L);
        return fp->crown * u * u;
    }
    case RD_FACE_TAPER:
        return tan(fp->taper_deg * M_PI / 180.0) * x;
    case RD_FACE_FLAT: {
        double r = fp->edge_radius, d = fmin(x, L - x);
        if (d >= r)
            return 0.0;
        return r - sqrt(r * r - (r - d) * (r - d));
    }
    default: { /* table, x strictly increasing over [0, L] (checked) */
        int k = 1;
        while (k < fp->points - 1 && fp->x[k] < x)
            k++;
        double t = (x - fp->x[k - 1]) / (fp->x[k] - fp->x[k - 1]);
        return fp->drop[k - 1] + t * (fp->drop[k] - fp->drop[k - 1]);
    }
    }
}

int rd_film_face_validate(const rd_face_params *fp, double L, rd_error *err)
{
    if (fp->profile == RD_FACE_BARREL && fabs(fp->offset) >= 0.5 * L)
        return rd_error_set(err, RD_EINVAL, "/offset",
                            "the crown's offset %g m must lie on the face: |offset| < half the "
                            "running face's height (%g m).",
                            fp->offset, 0.5 * L);
    if (fp->profile == RD_FACE_FLAT && fp->edge_radius > 0.5 * L)
        return rd_error_set(err, RD_EINVAL, "/edge_radius",
                            "the edge radius %g m is above half the running face's height "
                            "(%g m): the two roundings would overlap.",
                            fp->edge_radius, 0.5 * L);
    if (fp->profile != RD_FACE_TABLE)
        return RD_OK;
    if (fp->points < 2)
        return rd_error_set(err, RD_EINVAL, "/table/x_m",
                            "a face table needs at least 2 points (got %d).", fp->points);
    for (int k = 0; k < fp->points; k++) {
        if (k > 0 && !(fp->x[k] > fp->x[k - 1]))
            return rd_error_set(err, RD_EINVAL, "/table/x_m",
                                "x_m must increase strictly: x_m[%d] = %g after %g.", k, fp->x[k],
                                fp->x[k - 1]);
        if (!(fp->drop[k] >= 0.0 && fp->drop[k] <= 1e-4))
            return rd_error_set(err, RD_EINVAL, "/table/drop_m",
                                "drop_m[%d] = %g m is outside [0, 1e-4] m.", k, fp->drop[k]);
    }
    if (fabs(fp->x[0]) > 1e-9 * L || fabs(fp->x[fp->points - 1] - L) > 1e-6 * L)
        return rd_error_set(err, RD_EINVAL, "/table/x_m",
                            "x_m must run from 0 (the face's lower edge) to the running face's "
                            "height %g m (got %g to %g).",
                            L, fp->x[0], fp->x[fp->points - 1]);
    return RD_OK;
}

int rd_film_init(rd_film *f, const rd_face_params *face, double L, int nodes, double liner_rq,
                 const rd_lube_params *lube, double E, double nu, rd_error *err)
{
    memset(f, 0, sizeof *f);
    f->rtol = RD_FILM_RTOL;
    int rc = rd_film_face_validate(face, L, err);
    if (rc)
        return rc;
    int n = nodes < 3 ? 3 : (nodes > RD_FILM_NODES_MAX ? RD_FILM_NODES_MAX : nodes);
    f->n = n;
    f->L = L;
    f->dx = L / (n - 1);
    double sr = face->roughness_rq, sl = liner_rq;
    f->sigma = sqrt(sr * sr + sl * sl);
    f->w_s = (sl * sl - sr * sr) / (f->sigma * f->sigma);
    double Ep =
        lube->composite_modulus > 0.0 ? lube->composite_modulus : rd_film_composite_modulus(E, nu);
    double nbs = lube->asperity_density * lube->asperity_radius * f->sigma;
    f->gt_k =
        16.0 * M_SQRT2 / 15.0 * M_PI * nbs * nbs * sqrt(f->sigma / lube->asperity_radius) * Ep;
    f->mu_b = lube->boundary_coefficient;
    f->supply = lube->supply_film;
    f->jfo = lube->cavitation == RD_CAVITATION_JFO;
    double *block = calloc((size_t)(12 * n), sizeof(double));
    f->cav = calloc((size_t)n, sizeof(int));
    if (!block || !f->cav) {
        free(block);
        free(f->cav);
        f->cav = NULL;
        return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the film's %d nodes).", n);
    }
    f->drop = block;
    f->drop_mid = block + n;
    f->a = block + 2 * n;
    f->b = block + 3 * n;
    f->c = block + 4 * n;
    f->r = block + 5 * n;
    f->p = block + 6 * n;
    f->kf = block + 7 * n;
    f->qf = block + 8 * n;
    f->theta = block + 9 * n;
    f->content = block + 10 * n;
    f->hist_dt = block + 11 * n;
    double lo = INFINITY;
    for (int i = 0; i < n; i++) {
        f->drop[i] = profile_at(face, L, i * f->dx);
        if (i + 1 < n)
            f->drop_mid[i] = profile_at(face, L, (i + 0.5) * f->dx);
        if (f->drop[i] < lo) {
            lo = f->drop[i];
            f->x_min = i * f->dx;
        }
    }
    for (int i = 0; i < n; i++) {
        f->drop[i] -= lo;
        f->drop_mid[i] = fmax(f->drop_mid[i] - lo, 0.0);
    }
    return RD_OK;
}

void rd_film_free(rd_film *f)
{
    free(f->drop);
    free(f->cav);
    memset(f, 0, sizeof *f);
}

/* Solves the tridiagonal rows 1..n-2 (a sub, b diagonal, c super, r right
 * side) in place into p (p[0], p[n-1] given). */
static void tridiag(rd_film *f)
{
    int n = f->n;
    double *a = f->a, *b = f->b, *c = f->c, *r = f->r, *p = f->p;
    r[1] -= a[1] * p[0];
    r[n - 2] -= c[n - 2] * p[n - 1];
    for (int i = 2; i <= n - 2; i++) {
        double m = a[i] / b[i - 1];
        b[i] -= m * c[i - 1];
        r[i] -= m * r[i - 1];
    }
    p[n - 2] = r[n - 2] / b[n - 2];
    for (int i = n - 3; i >= 1; i--)
        p[i] = (r[i] - c[i] * p[i + 1]) / b[i];
}

/* A starved inlet's meniscus (rd_film.h): nodes 0 .. k (counted from the
 * inlet edge, in the liner's direction dir) dry at the inlet gas pin;
 * k <= 0: none (flooded; node 0 is the edge). */
typedef struct meniscus {
    int dir, k;
    double pin;
} meniscus;

static int node_at(const rd_film *f, int dir, int k)
{
    return dir > 0 ? k : f->n - 1 - k;
}

/* The rows of the film equation -(k p')' = src (finite volumes) into the
 * system, a cavitated node's row p = 0, a dry node's p = the inlet's gas. */
static void assemble(rd_film *f, const double *src, const meniscus *mn)
{
    int n = f->n;
    double idx2 = 1.0 / (f->dx * f->dx);
    for (int i = 1; i <= n - 2; i++) {
        int k = mn->dir > 0 ? i : n - 1 - i; /* from the inlet */
        if (f->cav[i] || k <= mn->k) {
            f->a[i] = f->c[i] = 0.0;
            f->b[i] = 1.0;
            f->r[i] = k <= mn->k ? mn->pin : 0.0;
            continue;
        }
        f->a[i] = -f->kf[i - 1] * idx2;
        f->c[i] = -f->kf[i] * idx2;
        f->b[i] = (f->kf[i - 1] + f->kf[i]) * idx2;
        f->r[i] = src[i];
    }
}

/* Film content theta downstream of a rupture: the flow q that left the full
 * film, 2 q / (U h_T) (at most 1), walked in the liner's direction; the dry
 * inlet nodes none. */
static double couette(rd_film *f, const double *hT, double U, double eta)
{
    int n = f->n, dir = U >= 0.0 ? 1 : -1;
    double Cc = 0.0, q = 0.0;
    for (int k = 0; k < n; k++) {
        int i = dir > 0 ? k : n - 1 - k;
        double theta = k < f->dry ? 0.0 : 1.0;
        if (k >= f->dry && f->cav[i] && U != 0.0) {
            int up = i - dir; /* the node upstream */
            if (up >= 0 && up < n && !f->cav[up])
                q = f->qf[dir > 0 ? up : i]; /* the face between them */
            theta = fmin(fmax(2.0 * q / (U * hT[i]), 0.0), 1.0);
        }
        double w = (i == 0 || i == n - 1) ? 0.5 : 1.0;
        Cc += w * f->dx * theta * eta / hT[i];
    }
    return Cc;
}

/* The pressures (primal-dual active set on the cavitated set) with the
 * edges at p_lo, p_hi and the meniscus mn. */
static void pressures(rd_film *f, const double *src, double p_lo, double p_hi, const meniscus *mn)
{
    int n = f->n;
    double idx2 = 1.0 / (f->dx * f->dx);
    f->p[0] = fmax(p_lo, 0.0);
    f->p[n - 1] = fmax(p_hi, 0.0);
    for (int k = 0; k <= mn->k && k < n; k++)
        f->cav[node_at(f, mn->dir, k)] = 0;
    for (int it = 0; it < 4 * n; it++) {
        assemble(f, src, mn);
        tridiag(f);
        int changed = 0;
        for (int i = 1; i <= n - 2; i++) {
            if ((mn->dir > 0 ? i : n - 1 - i) <= mn->k)
                continue;
            int now = f->cav[i];
            if (now) { /* the multiplier (A p - src)_i, p_i = 0 */
                double lam = (-f->kf[i - 1] * f->p[i - 1] - f->kf[i] * f->p[i + 1]) * idx2 - src[i];
                now = lam > 0.0;
            } else
                now = f->p[i] < 0.0;
            if (now != f->cav[i]) {
                f->cav[i] = now;
                changed = 1;
            }
        }
        if (!changed)
            break;
    }
}

/* The film's loads from the pressures of the last solve (meniscus mn). */
typedef struct film_in {
    const double *src, *hT, *hTf, *sf;
    double h0, U, eta, p_lo, p_hi;
} film_in;

static void outputs(rd_film *f, const film_in *in, const meniscus *mn, rd_film_out *o)
{
    int n = f->n;
    double dx = f->dx, sg = f->sigma, W = 0.0, Fp = 0.0, cav = 0.0;
    f->dry = mn->k >= n - 2 ? n : mn->k > 0 ? mn->k + 1 : 0; /* node 0 (k 0) is the edge */
    for (int i = 0; i < n; i++) {
        if (f->cav[i] || f->p[i] < 0.0)
            f->p[i] = 0.0;
        W += ((i == 0 || i == n - 1) ? 0.5 : 1.0) * dx * f->p[i];
        cav += f->cav[i] ? 1.0 : 0.0;
    }
    for (int j = 0; j + 1 < n; j++) {
        double dp = f->p[j + 1] - f->p[j];
        f->qf[j] = -f->kf[j] * dp / dx + 0.5 * in->U * in->hTf[j] + 0.5 * in->U * sg * in->sf[j];
        Fp -= 0.5 * fmax(in->h0 + f->drop_mid[j], 0.0) * dp;
    }
    o->W = W;
    o->Fp = Fp;
    o->Cc = couette(f, in->hT, in->U, in->eta);
    o->cavitated = cav / (n - 2);
    o->h_min = in->h0;
}

/* The flow into the film past the meniscus (nodes 0..k dry from the inlet),
 * in the liner's direction: the flux through the face after node k. */
static double inflow_at(rd_film *f, const film_in *in, meniscus *mn, int k)
{
    mn->k = k;
    pressures(f, in->src, in->p_lo, in->p_hi, mn);
    int a = node_at(f, mn->dir, k), b = node_at(f, mn->dir, k + 1), face = mn->dir > 0 ? a : b;
    return -f->kf[face] * (f->p[b] - mn->pin) / f->dx +
           0.5 * fabs(in->U) * (in->hTf[face] + f->sigma * in->sf[face]);
}

/* A starved inlet (rd_film.h): where the flooded film takes in more than
 * the liner brings (U h_s), the meniscus between the last node from the
 * inlet whose film would still take in more and the next, found by
 * bisection on the nodes up to the thinnest point; the loads are those of
 * the two films blended linearly in their inflows (so they move
 * continuously with h0).  All dry when even at the thinnest point the film
 * would take in more (the oil passes under the face). */
static void starve(rd_film *f, const film_in *in, meniscus *mn, rd_film_out *o)
{
    double want = fabs(in->U) * f->supply;
    int n = f->n, kmin = 0;
    /* the thinnest point from the inlet, up to the last face (a meniscus
     * sits between nodes k and k + 1, so k <= n - 2: at the outlet node,
     * inflow_at would read past the faces) */
    for (int k = 0; k < n - 1; k++)
        if (in->hT[node_at(f, mn->dir, k)] < in->hT[node_at(f, mn->dir, kmin)])
            kmin = k;
    double glo = inflow_at(f, in, mn, 0) - want, ghi;
    if (glo <= 0.0) { /* flooded: the liner brings enough */
        outputs(f, in, mn, o);
        return;
    }
    if (kmin < 1 || (ghi = inflow_at(f, in, mn, kmin) - want) >= 0.0) {
        mn->k = n - 2; /* all dry */
        pressures(f, in->src, in->p_lo, in->p_hi, mn);
        outputs(f, in, mn, o);
        o->Fp = 0.0;
        return;
    }
    int lo = 0, hi = kmin; /* g(lo) > 0 >= g(hi) */
    while (hi - lo > 1) {
        int m = (lo + hi) / 2;
        double g = inflow_at(f, in, mn, m) - want;
        if (g > 0.0)
            lo = m, glo = g;
        else
            hi = m, ghi = g;
    }
    rd_film_out a, b;
    inflow_at(f, in, mn, hi);
    outputs(f, in, mn, &b);
    inflow_at(f, in, mn, lo);
    outputs(f, in, mn, &a);
    double w = glo / (glo - ghi); /* 0 at lo, 1 at hi */
    o->W = (1.0 - w) * a.W + w * b.W;
    o->Fp = (1.0 - w) * a.Fp + w * b.Fp;
    o->Cc = (1.0 - w) * a.Cc + w * b.Cc;
    o->cavitated = (1.0 - w) * a.cavitated + w * b.cavitated;
    o->h_min = a.h_min;
}

void rd_film_solve(rd_film *f, double h0, double h0_dot, double U, double eta, double p_lo,
                   double p_hi, rd_film_out *o)
{
    int n = f->n;
    double sg = f->sigma, dx = f->dx;
    double hT[RD_FILM_NODES_MAX], src[RD_FILM_NODES_MAX], hTf[RD_FILM_NODES_MAX],
        sf[RD_FILM_NODES_MAX], gn[RD_FILM_NODES_MAX];
    for (int j = 0; j + 1 < n; j++) { /* faces */
        double h = h0 + f->drop_mid[j], H = h / sg, hk = fmax(h, RD_FILM_PHI_X_H_MIN * sg), g, dg,
               f52;
        f->kf[j] = (H > FAR_H ? 1.0 : rd_film_phi_x(H)) * hk * hk * hk / (12.0 * eta);
        if (H > FAR_GAP)
            hTf[j] = h;
        else {
            rd_film_node_laws(H, &g, &dg, &f52);
            hTf[j] = sg * g;
        }
        sf[j] = f->w_s != 0.0 ? f->w_s * rd_film_phi_s(H) : 0.0;
    }
    double Wa = 0.0;
    for (int i = 0; i < n; i++) {
        double H = (h0 + f->drop[i]) / sg, g = 1.0, gap, f52 = 0.0;
        if (H > FAR_GAP)
            hT[i] = h0 + f->drop[i];
        else {
            rd_film_node_laws(H, &gap, &g, &f52);
            hT[i] = sg * gap;
        }
        gn[i] = g;
        if (i > 0 && i < n - 1)
            src[i] = -(0.5 * U * (hTf[i] - hTf[i - 1]) + 0.5 * U * sg * (sf[i] - sf[i - 1])) / dx -
                     g * h0_dot;
        if (H < RD_FILM_GT_LAMBDA_MAX) {
            if (H > FAR_GAP)
                f52 = rd_film_gt_f52(H);
            Wa += ((i == 0 || i == n - 1) ? 0.5 : 1.0) * dx * f->gt_k * f52;
        }
    }
    meniscus mn = {U >= 0.0 ? 1 : -1, -1, fmax(U >= 0.0 ? p_lo : p_hi, 0.0)};
    film_in in = {src, hT, hTf, sf, h0, U, eta, p_lo, p_hi};
    if (f->jfo) {
        rd_film_nodes nd = {hT, gn, hTf, sf, h0, h0_dot, U, eta, p_lo, p_hi};
        rd_film_jfo_solve(f, &nd, o);
    } else if (f->supply > 0.0 && U != 0.0) {
        starve(f, &in, &mn, o);
    } else {
        pressures(f, src, p_lo, p_hi, &mn);
        outputs(f, &in, &mn, o);
    }
    o->Wa = Wa;
}
