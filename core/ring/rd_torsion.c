/*
 * rd_torsion — the Saint-Venant torsion constant of a polygonal section by
 * finite elements (rd_section.h).
 *
 * Prandtl stress function: -laplace phi = 2 in the section A, phi = 0 on
 * its boundary (a simply connected section), J = 2 int_A phi dA (Timoshenko
 * & Goodier, Theory of Elasticity, 3rd ed., sec. 104).  Linear triangles:
 * K phi = f with K_ij = int grad N_i . grad N_j, f_i = int 2 N_i, the
 * boundary nodes held at 0, and J_h = 2 int phi_h = f . phi_h = phi_h^T K
 * phi_h: the discrete energy, below J, rising as the mesh is refined.
 *
 * Mesh: the polygon cut into triangles by ear clipping (each step the ear
 * with the largest smallest angle, which keeps the triangles fat), then
 * every triangle split into four through its edge midpoints `level` times
 * (nested meshes: the boundary is exact at every level).  Solve:
 * conjugate gradients with the diagonal as preconditioner on the interior
 * nodes, to a relative residual of 1e-11.  Coordinates are scaled by the
 * polygon's size s first (J scales as s^4).
 */
#include "rd_section.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct mesh {
    int nn, nt;     /* nodes, triangles */
    double (*x)[2]; /* nodes */
    int (*t)[3];    /* triangles, counter-clockwise */
} mesh;

/* Edge table: open addressing on the (min, max) node pair. */
typedef struct edges {
    size_t cap;
    uint64_t *key; /* 0 = empty; else (a + 1) << 32 | (b + 1) */
    int *val;
} edges;

static uint64_t edge_key(int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    return ((uint64_t)(lo + 1) << 32) | (uint64_t)(hi + 1);
}

/* The slot of edge (a, b): its value, or where it goes. */
static size_t edge_slot(const edges *e, uint64_t k)
{
    size_t i = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 20) & (e->cap - 1);
    while (e->key[i] && e->key[i] != k)
        i = (i + 1) & (e->cap - 1);
    return i;
}

static int edges_init(edges *e, size_t n)
{
    e->cap = 16;
    while (e->cap < 2 * n)
        e->cap <<= 1;
    e->key = calloc(e->cap, sizeof *e->key);
    e->val = malloc(e->cap * sizeof *e->val);
    return e->key && e->val ? RD_OK : RD_ENOMEM;
}

static void edges_free(edges *e)
{
    free(e->key);
    free(e->val);
}

/* ---- ear clipping ------------------------------------------------------------ */

static double cross(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static double angle_at(const double *o, const double *a, const double *b)
{
    double ux = a[0] - o[0], uy = a[1] - o[1], vx = b[0] - o[0], vy = b[1] - o[1];
    return fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy));
}

/* Smallest angle of ear (p, q, r), or -1 when it is not an ear of the
 * remaining polygon idx[0..m) (reflex at q, or a vertex inside). */
static double ear_quality(const double (*P)[2], const int *idx, int m, int k)
{
    const double *p = P[idx[(k + m - 1) % m]], *q = P[idx[k]], *r = P[idx[(k + 1) % m]];
    if (cross(p, q, r) <= 0.0)
        return -1.0;
    for (int j = 0; j < m; j++) {
        const double *s = P[idx[j]];
        if (s == p || s == q || s == r)
            continue;
        if (cross(p, q, s) >= 0.0 && cross(q, r, s) >= 0.0 && cross(r, p, s) >= 0.0)
            return -1.0;
    }
    return fmin(angle_at(p, q, r), fmin(angle_at(q, r, p), angle_at(r, p, q)));
}

static int triangulate(const double (*P)[2], int n, mesh *M)
{
    int idx[RD_SECTION_POINTS_MAX], m = n;
    for (int i = 0; i < n; i++)
        idx[i] = i;
    M->nt = 0;
    while (m > 3) {
        int best = -1;
        double q = -1.0;
        for (int k = 0; k < m; k++) {
            double e = ear_quality(P, idx, m, k);
            if (e > q)
                q = e, best = k;
        }
        if (best < 0)
            return RD_EINVAL; /* not a simple counter-clockwise polygon */
        int *t = M->t[M->nt++];
        t[0] = idx[(best + m - 1) % m], t[1] = idx[best], t[2] = idx[(best + 1) % m];
        memmove(idx + best, idx + best + 1, (size_t)(m - best - 1) * sizeof *idx);
        m--;
    }
    int *t = M->t[M->nt++];
    t[0] = idx[0], t[1] = idx[1], t[2] = idx[2];
    return RD_OK;
}

/* ---- refinement ---------------------------------------------------------------- */

/* The midpoint node of edge (a, b), made once. */
static int midpoint(mesh *M, edges *e, int a, int b)
{
    uint64_t k = edge_key(a, b);
    size_t s = edge_slot(e, k);
    if (!e->key[s]) {
        e->key[s] = k;
        e->val[s] = M->nn;
        M->x[M->nn][0] = 0.5 * (M->x[a][0] + M->x[b][0]);
        M->x[M->nn][1] = 0.5 * (M->x[a][1] + M->x[b][1]);
        M->nn++;
    }
    return e->val[s];
}

/* Every triangle into four; M's arrays must hold the result. */
static int refine(mesh *M)
{
    edges e;
    int nt = M->nt, rc = edges_init(&e, 3 * (size_t)nt);
    for (int i = 0; rc == RD_OK && i < nt; i++) {
        int a = M->t[i][0], b = M->t[i][1], c = M->t[i][2];
        int ab = midpoint(M, &e, a, b), bc = midpoint(M, &e, b, c), ca = midpoint(M, &e, c, a);
        int q[3][3] = {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}};
        memcpy(M->t[M->nt], q, sizeof q);
        M->nt += 3;
        M->t[i][0] = ab, M->t[i][1] = bc, M->t[i][2] = ca;
    }
    edges_free(&e);
    return rc;
}

/* ---- assembly and solve ------------------------------------------------------ */

typedef struct csr {
    int n;
    int *row, *col;
    double *val, *diag;
} csr;

typedef struct entry {
    int i, j;
    double v;
} entry;

static int cmp_entry(const void *a, const void *b)
{
    const entry *x = a, *y = b;
    if (x->i != y->i)
        return (x->i > y->i) - (x->i < y->i);
    return (x->j > y->j) - (x->j < y->j);
}

/* K (CSR) and f of the mesh; bnd[i] = 1 on the boundary. */
static int assemble(const mesh *M, csr *K, double *f)
{
    size_t ne = 9 * (size_t)M->nt;
    entry *E = malloc(ne * sizeof *E);
    K->n = M->nn;
    K->row = calloc((size_t)M->nn + 1, sizeof *K->row);
    K->col = malloc(ne * sizeof *K->col);
    K->val = malloc(ne * sizeof *K->val);
    K->diag = calloc((size_t)M->nn, sizeof *K->diag);
    if (!E || !K->row || !K->col || !K->val || !K->diag) {
        free(E);
        return RD_ENOMEM;
    }
    memset(f, 0, (size_t)M->nn * sizeof *f);
    size_t k = 0;
    for (int e = 0; e < M->nt; e++) {
        const int *t = M->t[e];
        double bb[3], cc[3];
        for (int i = 0; i < 3; i++) {
            const double *pj = M->x[t[(i + 1) % 3]], *pk = M->x[t[(i + 2) % 3]];
            bb[i] = pj[1] - pk[1];
            cc[i] = pk[0] - pj[0];
        }
        double area = 0.5 * (bb[0] * cc[1] - bb[1] * cc[0]);
        for (int i = 0; i < 3; i++) {
            f[t[i]] += 2.0 * area / 3.0;
            for (int j = 0; j < 3; j++)
                E[k++] = (entry){t[i], t[j], (bb[i] * bb[j] + cc[i] * cc[j]) / (4.0 * area)};
        }
    }
    qsort(E, ne, sizeof *E, cmp_entry);
    int nz = 0;
    for (size_t q = 0; q < ne; q++) {
        if (nz > 0 && E[q].i == E[q - 1].i && E[q].j == K->col[nz - 1]) {
            K->val[nz - 1] += E[q].v;
        } else {
            K->col[nz] = E[q].j, K->val[nz] = E[q].v;
            K->row[E[q].i + 1] = ++nz;
        }
    }
    for (int i = 1; i <= M->nn; i++) /* rows are never empty: every node is in a triangle */
        K->row[i] = K->row[i] > K->row[i - 1] ? K->row[i] : K->row[i - 1];
    for (int i = 0; i < M->nn; i++)
        for (int q = K->row[i]; q < K->row[i + 1]; q++)
            if (K->col[q] == i)
                K->diag[i] = K->val[q];
    free(E);
    return RD_OK;
}

/* y = K x on the interior (x and y zero on the boundary). */
static void matvec(const csr *K, const char *bnd, const double *x, double *y)
{
    for (int i = 0; i < K->n; i++) {
        double s = 0.0;
        if (!bnd[i])
            for (int q = K->row[i]; q < K->row[i + 1]; q++)
                s += K->val[q] * x[K->col[q]];
        y[i] = s;
    }
}

static double dot(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* Preconditioned conjugate gradients for K x = f on the interior. */
static int cg(const csr *K, const char *bnd, const double *f, double *x, double *w)
{
    int n = K->n;
    double *r = w, *z = w + n, *p = w + 2 * n, *q = w + 3 * n;
    for (int i = 0; i < n; i++) {
        x[i] = 0.0;
        r[i] = bnd[i] ? 0.0 : f[i];
        z[i] = bnd[i] ? 0.0 : r[i] / K->diag[i];
        p[i] = z[i];
    }
    double rz = dot(r, z, n), r0 = sqrt(dot(r, r, n));
    for (int it = 0; it < 20 * n + 100; it++) {
        if (sqrt(dot(r, r, n)) <= 1e-11 * r0)
            return RD_OK;
        matvec(K, bnd, p, q);
        double alpha = rz / dot(p, q, n);
        for (int i = 0; i < n; i++) {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            z[i] = bnd[i] ? 0.0 : r[i] / K->diag[i];
        }
        double rz1 = dot(r, z, n);
        for (int i = 0; i < n; i++)
            p[i] = z[i] + rz1 / rz * p[i];
        rz = rz1;
    }
    return RD_ENOCONV;
}

/* Boundary nodes: those of edges in one triangle only. */
static int boundary(const mesh *M, char *bnd)
{
    edges e;
    int rc = edges_init(&e, 3 * (size_t)M->nt);
    memset(bnd, 0, (size_t)M->nn);
    for (int t = 0; rc == RD_OK && t < M->nt; t++)
        for (int i = 0; i < 3; i++) {
            uint64_t k = edge_key(M->t[t][i], M->t[t][(i + 1) % 3]);
            size_t s = edge_slot(&e, k);
            if (!e.key[s])
                e.key[s] = k, e.val[s] = 0;
            e.val[s]++;
        }
    for (size_t s = 0; rc == RD_OK && s < e.cap; s++)
        if (e.key[s] && e.val[s] == 1) {
            bnd[(e.key[s] >> 32) - 1] = 1;
            bnd[(e.key[s] & 0xffffffffu) - 1] = 1;
        }
    edges_free(&e);
    return rc;
}

/* J of the mesh M (scaled coordinates). */
static int solve_mesh(const mesh *M, double *J)
{
    csr K = {0};
    size_t n = (size_t)M->nn;
    double *f = malloc(n * sizeof *f), *x = malloc(n * sizeof *x), *w = malloc(4 * n * sizeof *w);
    char *bnd = malloc(n);
    int rc = f && x && w && bnd ? RD_OK : RD_ENOMEM;
    rc = rc != RD_OK ? rc : boundary(M, bnd);
    rc = rc != RD_OK ? rc : assemble(M, &K, f);
    rc = rc != RD_OK ? rc : cg(&K, bnd, f, x, w);
    if (rc == RD_OK)
        *J = dot(f, x, (int)n);
    free(f), free(x), free(w), free(bnd);
    free(K.row), free(K.col), free(K.val), free(K.diag);
    return rc;
}

int rd_section_torsion_polygon(const double (*pts)[2], int n, int level, double *J, rd_error *err)
{
    if (n < 3 || n > RD_SECTION_POINTS_MAX || level < 0 || level > 9)
        return rd_error_set(err, RD_EINVAL, "/section", "torsion mesh: %d points, level %d", n,
                            level);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY},
           P[RD_SECTION_POINTS_MAX][2];
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 2; k++)
            lo[k] = fmin(lo[k], pts[i][k]), hi[k] = fmax(hi[k], pts[i][k]);
    double s = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    for (int i = 0; i < n; i++)
        P[i][0] = (pts[i][0] - lo[0]) / s, P[i][1] = (pts[i][1] - lo[1]) / s;
    size_t nt = (size_t)(n - 2) << (2 * level), nn = (size_t)n + 2 * nt + 8;
    mesh M = {n, 0, malloc(nn * sizeof *M.x), malloc(nt * sizeof *M.t)};
    int rc = M.x && M.t ? RD_OK : RD_ENOMEM;
    if (rc == RD_OK) {
        memcpy(M.x, P, (size_t)n * sizeof *M.x);
        rc = triangulate((const double(*)[2])P, n, &M);
    }
    for (int l = 0; rc == RD_OK && l < level; l++)
        rc = refine(&M);
    rc = rc != RD_OK ? rc : solve_mesh(&M, J);
    free(M.x);
    free(M.t);
    if (rc == RD_OK)
        *J *= s * s * s * s;
    return rc == RD_OK       ? RD_OK
           : rc == RD_ENOMEM ? rd_error_set(err, rc, "/section",
                                            "out of memory for the torsion mesh (level %d)", level)
           : rc == RD_EINVAL ? rd_error_set(err, rc, "/section",
                                            "the section's outline could not be cut into "
                                            "triangles: it is not a simple polygon")
                             : rd_error_set(err, rc, "/section",
                                            "the torsion solve (conjugate gradients) did not "
                                            "converge at level %d",
                                            level);
}

int rd_section_torsion_solve(const double (*pts)[2], int n, double *J, double *J_error,
                             rd_error *err)
{
    int L = 2;
    while (((size_t)(n - 2) << (2 * (L + 1))) <= 40000 && L < 9)
        L++;
    double j[3];
    for (int k = 0; k < 3; k++) {
        int rc = rd_section_torsion_polygon(pts, n, L - 2 + k, &j[k], err);
        if (rc != RD_OK)
            return rc;
    }
    double e1 = j[2] + (j[2] - j[1]) / 3.0, e0 = j[1] + (j[1] - j[0]) / 3.0;
    *J = e1;
    *J_error = fabs(e1 - e0);
    return RD_OK;
}
