/*
 * rd_bore_map.c — bore maps (rd_bore_map.h): range checks, the per-layer
 * least-squares fit of measured points, and the bore at a height.
 *
 * Fit of layer l with m points, K orders: the m x (2K + 1) system
 *     [1  cos theta_j  sin theta_j  ...  cos K theta_j  sin K theta_j] x = dr_j
 * solved by LAPACK dgels (QR; full rank when the layer has 2K + 1 distinct
 * angles: a trigonometric polynomial of degree K has at most 2K roots in a
 * period).  x = (c_0, a_1, b_1, ..., a_K, b_K).
 */
#include "rd_bore_map.h"

#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define DEG (M_PI / 180.0)
/* Angles closer than this (deg, after reduction to [0, 360)) count as one
 * in the rank rule: the fit would be ill-conditioned anyway. */
#define ANGLE_TOL 1e-6

/* Distinct orders of two bores together (0 when they are the same bore). */
static int union_orders(const rd_bore *a, const rd_bore *b, int *orders)
{
    int n = 0;
    for (int s = 0; s < 2; s++) {
        const rd_bore *x = s ? b : a;
        for (int k = 0; k < x->n_distortion; k++) {
            int o = x->distortion[k].order, seen = 0;
            for (int j = 0; j < n; j++)
                seen |= orders[j] == o;
            if (!seen && n < 2 * RD_BORE_ORDERS_MAX)
                orders[n++] = o;
        }
    }
    return n;
}

static int same_bore(const rd_bore *a, const rd_bore *b)
{
    if (a->diameter != b->diameter || a->n_distortion != b->n_distortion)
        return 0;
    for (int k = 0; k < a->n_distortion; k++)
        if (a->distortion[k].order != b->distortion[k].order ||
            a->distortion[k].amplitude != b->distortion[k].amplitude ||
            a->distortion[k].phase_deg != b->distortion[k].phase_deg)
            return 0;
    return 1;
}

int rd_bore_map_validate(const rd_bore_map *m, double d, rd_error *err)
{
    if (m->n_layers < 1 || m->n_layers > RD_BORE_LAYERS_MAX)
        return rd_error_set(err, m->n_layers < 1 ? RD_EINVAL : RD_ELIMIT, "/layers",
                            "@/layers has %d layers; allowed 1 to %d.", m->n_layers,
                            RD_BORE_LAYERS_MAX);
    for (int i = 0; i < m->n_layers; i++) {
        char path[64];
        snprintf(path, sizeof path, "/layers/%d/z", i);
        double z = m->layer[i].z;
        int rc = rd_error_range(z, 0.0, RD_BORE_Z_MAX, path, "m", err);
        if (rc != RD_OK)
            return rc;
        if (i > 0 && !(z > m->layer[i - 1].z))
            return rd_error_set(err, RD_EINVAL, path,
                                "@%s = %g m is not below the layer before it (z = %g m): the "
                                "layers go down the bore, z strictly increasing; allowed above "
                                "%g m to %g m.",
                                path, z, m->layer[i - 1].z, m->layer[i - 1].z, RD_BORE_Z_MAX);
        snprintf(path, sizeof path, "/layers/%d", i);
        size_t mark = rd_error_enter(err, path);
        rc = rd_bore_validate(&m->layer[i].bore, d, err);
        rd_error_leave(err, mark);
        if (rc != RD_OK)
            return rc;
        int orders[2 * RD_BORE_ORDERS_MAX];
        int n = i > 0 && !same_bore(&m->layer[i - 1].bore, &m->layer[i].bore)
                    ? union_orders(&m->layer[i - 1].bore, &m->layer[i].bore, orders)
                    : 0;
        snprintf(path, sizeof path, "/layers/%d/distortion", i);
        if (n > RD_BORE_ORDERS_MAX)
            return rd_error_set(err, RD_ELIMIT, path,
                                "@/layers/%d and @/layers/%d have %d distinct orders "
                                "together; allowed at most %d (a height between them combines "
                                "them).",
                                i - 1, i, n, RD_BORE_ORDERS_MAX);
    }
    return RD_OK;
}

/* ---- points ---------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The distinct values of v[0..n) sorted into out (n long); their count. */
static int distinct(const double *v, int n, double *out, double tol)
{
    memcpy(out, v, (size_t)n * sizeof *out);
    qsort(out, (size_t)n, sizeof *out, cmp_double);
    int k = 0;
    for (int i = 0; i < n; i++)
        if (k == 0 || out[i] - out[k - 1] > tol)
            out[k++] = out[i];
    return k;
}

/* Distinct angles (reduced to [0, 360)) among the points of height z. */
static int layer_angles(const rd_bore_points *p, double z, double *work)
{
    int m = 0;
    for (int j = 0; j < p->n; j++)
        if (p->z[j] == z) {
            double t = fmod(p->theta_deg[j], 360.0);
            work[m++] = t < 0.0 ? t + 360.0 : t;
        }
    double *tmp = work + p->n;
    int k = distinct(work, m, tmp, ANGLE_TOL);
    if (k > 1 && tmp[k - 1] - tmp[0] > 360.0 - ANGLE_TOL)
        k--; /* 359.9999999 and 0 are one angle */
    return k;
}

static int point_ranges(const rd_bore_points *p, double d, rd_error *err)
{
    for (int j = 0; j < p->n; j++) {
        char path[64];
        int rc;
        snprintf(path, sizeof path, "/points/theta_deg/%d", j);
        if ((rc = rd_error_range(p->theta_deg[j], -720.0, 720.0, path, "deg", err)) != RD_OK)
            return rc;
        snprintf(path, sizeof path, "/points/z/%d", j);
        if ((rc = rd_error_range(p->z[j], 0.0, RD_BORE_Z_MAX, path, "m", err)) != RD_OK)
            return rc;
        snprintf(path, sizeof path, "/points/dr/%d", j);
        if ((rc = rd_error_range(p->dr[j], -0.01 * d, 0.01 * d, path, "m", err)) != RD_OK)
            return rc;
    }
    return RD_OK;
}

/* Every layer has 2K + 1 distinct angles. */
static int layers_rank(const rd_bore_points *p, const double *zs, int nz, double *work,
                       rd_error *err)
{
    int need = 2 * p->fit_order + 1;
    for (int l = 0; l < nz; l++) {
        int k = layer_angles(p, zs[l], work);
        if (k < need)
            return rd_error_set(err, RD_EINVAL, "/points/fit_order",
                                "@/points/fit_order = %d needs at least %d points at "
                                "distinct angles in every layer, but the layer at z = %g m has "
                                "%d: allowed fit_order 0 to %d with these points (or measure "
                                "more angles).",
                                p->fit_order, need, zs[l], k, (k - 1) / 2);
    }
    return RD_OK;
}

int rd_bore_points_validate(const rd_bore_points *p, double d, rd_error *err)
{
    if (p->n < 1 || p->n > RD_BORE_POINTS_MAX)
        return rd_error_set(err, p->n < 1 ? RD_EINVAL : RD_ELIMIT, "/points/dr",
                            "@/points/dr has %d points; allowed 1 to %d.", p->n,
                            RD_BORE_POINTS_MAX);
    if (p->fit_order < 0 || p->fit_order > RD_BORE_ORDERS_MAX)
        return rd_error_set(err, RD_EINVAL, "/points/fit_order",
                            "@/points/fit_order = %d is out of range: allowed 0 to %d.",
                            p->fit_order, RD_BORE_ORDERS_MAX);
    int rc = point_ranges(p, d, err);
    if (rc != RD_OK)
        return rc;
    double *work = malloc(2 * (size_t)p->n * sizeof *work);
    if (!work)
        return rd_error_set(err, RD_ENOMEM, "/points", "out of memory reading the points");
    int nz = distinct(p->z, p->n, work, 0.0);
    if (nz > RD_BORE_LAYERS_MAX) {
        rc = rd_error_set(err, RD_ELIMIT, "/points/z",
                          "@/points/z has %d distinct heights (layers); allowed 1 to %d.", nz,
                          RD_BORE_LAYERS_MAX);
    } else {
        double zs[RD_BORE_LAYERS_MAX];
        memcpy(zs, work, (size_t)nz * sizeof *zs);
        rc = layers_rank(p, zs, nz, work, err);
    }
    free(work);
    return rc;
}

/* Least squares of the points at height z: x (2K + 1) from dgels; the sum
 * of squared residuals added to *ss. */
static int fit_layer(const rd_bore_points *p, double z, double *A, double *x, double *ss,
                     rd_error *err)
{
    int K = p->fit_order, nc = 2 * K + 1, m = 0;
    for (int j = 0; j < p->n; j++)
        m += p->z[j] == z;
    double *b = A + (size_t)m * (size_t)nc;
    for (int j = 0, r = 0; j < p->n; j++) {
        if (p->z[j] != z)
            continue;
        double t = p->theta_deg[j] * DEG;
        A[r] = 1.0;
        for (int k = 1; k <= K; k++) {
            A[(size_t)(2 * k - 1) * (size_t)m + (size_t)r] = cos(k * t);
            A[(size_t)(2 * k) * (size_t)m + (size_t)r] = sin(k * t);
        }
        b[r++] = p->dr[j];
    }
    lapack_int info = LAPACKE_dgels(LAPACK_COL_MAJOR, 'N', m, nc, 1, A, m, b, m);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "/points",
                            "the least-squares fit of the layer at z = %g m failed (LAPACK dgels "
                            "info %d).",
                            z, (int)info);
    memcpy(x, b, (size_t)nc * sizeof *x);
    for (int j = 0; j < p->n; j++) {
        if (p->z[j] != z)
            continue;
        double t = p->theta_deg[j] * DEG, f = x[0];
        for (int k = 1; k <= K; k++)
            f += x[2 * k - 1] * cos(k * t) + x[2 * k] * sin(k * t);
        *ss += (p->dr[j] - f) * (p->dr[j] - f);
    }
    return RD_OK;
}

/* Layer l of the map from its coefficients x, about diameter D. */
static void layer_from(rd_bore_layer *L, double z, const double *x, int K, double D)
{
    memset(L, 0, sizeof *L);
    L->z = z;
    L->bore.diameter = D + 2.0 * x[0];
    L->bore.n_distortion = K;
    for (int k = 1; k <= K; k++) {
        rd_distortion *t = &L->bore.distortion[k - 1];
        t->order = k;
        t->amplitude = hypot(x[2 * k - 1], x[2 * k]);
        t->phase_deg = atan2(x[2 * k], x[2 * k - 1]) / k / DEG;
    }
}

/* Each fitted layer a valid bore, else an error at the points' dr. */
static int fitted_valid(const rd_bore_map *m, double D, rd_error *err)
{
    for (int l = 0; l < m->n_layers; l++) {
        rd_error e; /* its message told as if the layer's bore were the block's */
        rd_error_init_local(&e, err);
        int rc = rd_bore_validate(&m->layer[l].bore, D, &e);
        if (rc != RD_OK)
            return rd_error_set(err, rc, "/points/dr",
                                "@/points/dr: the layer at z = %g m fits to a bore that is "
                                "refused (%s)",
                                m->layer[l].z, e.message);
    }
    return RD_OK;
}

int rd_bore_map_fit(const rd_bore_points *p, double D, rd_bore_map *m, rd_error *err)
{
    int K = p->fit_order, nc = 2 * K + 1;
    double *zs = malloc((size_t)p->n * sizeof *zs);
    double *A = malloc(((size_t)p->n * (size_t)(nc + 1) + (size_t)nc) * sizeof *A);
    int rc = RD_OK;
    if (!zs || !A) {
        rc = rd_error_set(err, RD_ENOMEM, "/points", "out of memory fitting the points");
        goto out;
    }
    memset(m, 0, sizeof *m);
    m->n_layers = distinct(p->z, p->n, zs, 0.0);
    double ss = 0.0, x[2 * RD_BORE_ORDERS_MAX + 1];
    for (int l = 0; rc == RD_OK && l < m->n_layers; l++) {
        rc = fit_layer(p, zs[l], A, x, &ss, err);
        if (rc == RD_OK)
            layer_from(&m->layer[l], zs[l], x, K, D);
    }
    m->residual_rms = sqrt(ss / p->n);
    if (rc == RD_OK)
        rc = fitted_valid(m, D, err);
out:
    free(zs);
    free(A);
    return rc;
}

/* ---- the bore at a height ------------------------------------------------- */

/* (1 - t) a + t b as one bore: each order's cosine and sine parts. */
static void blend(const rd_bore *a, const rd_bore *b, double t, double d, rd_bore *out)
{
    int orders[2 * RD_BORE_ORDERS_MAX], n = union_orders(a, b, orders);
    double Da = a->diameter > 0.0 ? a->diameter : d, Db = b->diameter > 0.0 ? b->diameter : d;
    memset(out, 0, sizeof *out);
    out->diameter = a->diameter == b->diameter ? a->diameter : (1.0 - t) * Da + t * Db;
    out->roughness_rq = a->roughness_rq;
    qsort(orders, (size_t)n, sizeof *orders, cmp_int);
    for (int j = 0; j < n && j < RD_BORE_ORDERS_MAX; j++) {
        double c = 0.0, s = 0.0;
        for (int side = 0; side < 2; side++) {
            const rd_bore *x = side ? b : a;
            double w = side ? t : 1.0 - t;
            for (int k = 0; k < x->n_distortion; k++) {
                const rd_distortion *q = &x->distortion[k];
                if (q->order != orders[j])
                    continue;
                c += w * q->amplitude * cos(q->order * q->phase_deg * DEG);
                s += w * q->amplitude * sin(q->order * q->phase_deg * DEG);
            }
        }
        out->distortion[j] = (rd_distortion){.order = orders[j],
                                             .amplitude = hypot(c, s),
                                             .phase_deg = atan2(s, c) / orders[j] / DEG};
    }
    out->n_distortion = n < RD_BORE_ORDERS_MAX ? n : RD_BORE_ORDERS_MAX;
}

int rd_bore_map_at(const rd_bore_map *m, double z, double d, rd_bore *out, rd_error *err)
{
    double lo = m->layer[0].z, hi = m->layer[m->n_layers - 1].z;
    if (!(z >= lo && z <= hi))
        return rd_error_set(err, RD_EINVAL, "/height",
                            "@/height = %g m is outside the bore map: allowed %g to %g m "
                            "(its first and last layers' z), or \"all\".",
                            z, lo, hi);
    int i = 0;
    while (i + 1 < m->n_layers && m->layer[i + 1].z <= z)
        i++;
    const rd_bore *a = &m->layer[i].bore;
    if (z == m->layer[i].z || same_bore(a, &m->layer[i + 1].bore)) {
        *out = *a;
        return RD_OK;
    }
    double t = (z - m->layer[i].z) / (m->layer[i + 1].z - m->layer[i].z);
    blend(a, &m->layer[i + 1].bore, t, d, out);
    return RD_OK;
}
