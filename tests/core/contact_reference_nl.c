/*
 * contact_reference_nl.c — the split ring in a distorted bore as a
 * geometrically exact planar Timoshenko beam (Reissner's strains, any size
 * of rotation), for tests and benches (not part of ringdyn): the same ring,
 * cells, loads and contact as contact_reference.c, without its
 * linearisation.  Declared in contact_reference.h.
 *
 * Unknowns per node j (reference angle theta_j = s + j D on the centroid
 * circle of radius R): u (m) the running-face point's arc position, its
 * polar angle phi = theta + u / r_o; xi (m) its gap to the bore, its radius
 * rho = r_b(phi) - xi; beta (rad) the section's rotation.  DOF 3j + {0, 1,
 * 2}.  The centroid node is x = rho e(phi) - (b/2) e(theta + beta), e(a) =
 * (cos a, sin a): the running-face point lies on the section's radial line
 * (an unsheared section).  Contact is xi >= 0, its force lambda = dPi/dxi
 * >= 0 (the bore's push, inward), lambda xi = 0; at xi = 0 the node moves
 * along the bore surface (frictionless: the bore's force does no work in
 * u).
 *
 * Cell c (nodes a, b; length L = R D; tangent t and normal n of the
 * reference circle at its middle): with dx = x_b - x_a, dX its reference
 * value, bbar = (beta_a + beta_b) / 2, v = Rot(-bbar) dx - dX,
 *   eps = t.v / L,  gamma = n.v / L,  kappa = (beta_b - beta_a) / L,
 * energy L/2 (EA eps^2 + GA/f_s gamma^2 + EI kappa^2) (f_s = 1.2): zero for
 * every rigid motion of any size; linearised, the curved-beam strains of
 * contact_reference.c to O(D^2).  Displacements are formed from differences
 * (1 - cos by 2 sin^2) so micrometres on a 38 mm ring keep their digits.
 * Loads: F_t on the two end nodes along the end sections' normal,
 * following the section (as ringdyn's force method) or fixed in direction
 * (dead, as the linear reference).  Held: u = 0 at theta = pi.
 *
 * Solution: Newton's method for each active set (tangent: central
 * differences of each cell's gradient, general band LU, dgbsv; the
 * follower load makes it unsymmetric), the active set updated as in the
 * linear reference (A = {j : lambda_j - c xi_j > 0}, every node at once)
 * until it no longer changes, starting from the linear reference's
 * converged set (ref_contact_active_set).
 */
#include "contact_reference.h"

#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define KB   5            /* half bandwidth: node j couples with j +- 1 */
#define LDAB (3 * KB + 1) /* dgbsv's band storage: 2 kl + ku + 1 rows */

typedef struct nl_model {
    int N, ndof, follower;
    double R, ro, half_b, s, D, L, EA, GAs, EI, Ft, dD, kf;
    const rd_contact_opts *o;
} nl_model;

static double theta_of(const nl_model *m, int j)
{
    return m->s + j * m->D;
}

/* The bore's departure from r_o at phi and its derivative. */
static void departure(const nl_model *m, double phi, double *a, double *da)
{
    *a = m->dD, *da = 0.0;
    for (int k = 0; k < m->o->bore.n_distortion; k++) {
        const rd_distortion *d = &m->o->bore.distortion[k];
        double arg = d->order * (phi - d->phase_deg * M_PI / 180.0);
        *a += d->amplitude * cos(arg);
        *da -= d->amplitude * d->order * sin(arg);
    }
}

/* e(th + dl) - e(th), accurate for small dl. */
static void de(double th, double dl, double out[2])
{
    double c = -2.0 * sin(0.5 * dl) * sin(0.5 * dl), sn = sin(dl);
    out[0] = c * cos(th) - sn * sin(th);
    out[1] = c * sin(th) + sn * cos(th);
}

/* The centroid node's displacement x - X and its Jacobian J (columns u,
 * xi, beta) at node j with state q (3 values). */
static void node(const nl_model *m, int j, const double *q, double d[2], double J[2][3])
{
    double th = theta_of(m, j), phi = th + q[0] / m->ro, a, da;
    departure(m, phi, &a, &da);
    double rho = m->ro + a - q[1], e1[2], e2[2];
    de(th, q[0] / m->ro, e1);
    de(th, q[2], e2);
    double ep[2] = {cos(phi), sin(phi)}, tp[2] = {-sin(phi), cos(phi)};
    double tb[2] = {-sin(th + q[2]), cos(th + q[2])};
    for (int i = 0; i < 2; i++) {
        d[i] = (a - q[1]) * ep[i] + m->ro * e1[i] - m->half_b * e2[i];
        J[i][0] = (da * ep[i] + rho * tp[i]) / m->ro;
        J[i][1] = -ep[i];
        J[i][2] = -m->half_b * tb[i];
    }
}

/* Gradient g (6) of cell c's energy in the states qa, qb of its nodes. */
static void cell_grad(const nl_model *m, int c, const double *qa, const double *qb, double g[6])
{
    double da[2], db[2], Ja[2][3], Jb[2][3];
    node(m, c, qa, da, Ja);
    node(m, c + 1, qb, db, Jb);
    double tm = theta_of(m, c) + 0.5 * m->D, cb = 0.5 * (qa[2] + qb[2]);
    double t[2] = {-sin(tm), cos(tm)}, n[2] = {cos(tm), sin(tm)};
    double X[2] = {m->R * (cos(tm + 0.5 * m->D) - cos(tm - 0.5 * m->D)),
                   m->R * (sin(tm + 0.5 * m->D) - sin(tm - 0.5 * m->D))};
    double dd[2] = {db[0] - da[0], db[1] - da[1]}, dx[2] = {X[0] + dd[0], X[1] + dd[1]};
    double cm = -2.0 * sin(0.5 * cb) * sin(0.5 * cb), sn = sin(cb);
    /* Rot(-cb) = [[1 + cm, sn], [-sn, 1 + cm]] */
    double v[2] = {cm * X[0] + sn * X[1] + (1 + cm) * dd[0] + sn * dd[1],
                   -sn * X[0] + cm * X[1] - sn * dd[0] + (1 + cm) * dd[1]};
    double eps = (t[0] * v[0] + t[1] * v[1]) / m->L, gam = (n[0] * v[0] + n[1] * v[1]) / m->L;
    double kap = (qb[2] - qa[2]) / m->L;
    double f[2] = {m->EA * eps * t[0] + m->GAs * gam * n[0],
                   m->EA * eps * t[1] + m->GAs * gam * n[1]}; /* dU/dv */
    /* dU/dx_b = Rot(cb) f, dU/dx_a = -Rot(cb) f */
    double fx[2] = {(1 + cm) * f[0] - sn * f[1], sn * f[0] + (1 + cm) * f[1]};
    /* dv/dbbar = -Jrot Rot(-cb) dx, Jrot = [[0, -1], [1, 0]] */
    double r0 = (1 + cm) * dx[0] + sn * dx[1], r1 = -sn * dx[0] + (1 + cm) * dx[1];
    double dUdb = f[0] * r1 - f[1] * r0;
    for (int k = 0; k < 3; k++) {
        g[k] = -(Ja[0][k] * fx[0] + Ja[1][k] * fx[1]);
        g[3 + k] = Jb[0][k] * fx[0] + Jb[1][k] * fx[1];
    }
    g[2] += 0.5 * dUdb - m->EI * kap;
    g[5] += 0.5 * dUdb + m->EI * kap;
}

/* Generalized force of F_t on end node j (0 or N) with state q. */
static void end_load(const nl_model *m, int j, const double *q, double g[3])
{
    double d[2], J[2][3], sg = j == 0 ? 1.0 : -1.0;
    node(m, j, q, d, J);
    double a = theta_of(m, j) + (m->follower ? q[2] : 0.0);
    double F[2] = {-sg * m->Ft * sin(a), sg * m->Ft * cos(a)};
    for (int k = 0; k < 3; k++)
        g[k] = F[0] * J[0][k] + F[1] * J[1][k];
}

/* r = dPi/dq (internal minus external, plus the tiny foundation on xi). */
static void residual(const nl_model *m, const double *q, double *r)
{
    memset(r, 0, (size_t)m->ndof * sizeof *r);
    for (int c = 0; c < m->N; c++) {
        double g[6];
        cell_grad(m, c, q + 3 * c, q + 3 * c + 3, g);
        for (int k = 0; k < 6; k++)
            r[3 * c + k] += g[k];
    }
    for (int e = 0; e < 2; e++) {
        int j = e ? m->N : 0;
        double g[3];
        end_load(m, j, q + 3 * j, g);
        for (int k = 0; k < 3; k++)
            r[3 * j + k] -= g[k];
    }
    for (int j = 0; j <= m->N; j++)
        r[3 * j + 1] += m->kf * q[3 * j + 1];
}

static void band_add(double *ab, int i, int j, double v)
{
    ab[(size_t)j * LDAB + 2 * KB + i - j] += v;
}

/* Central-difference tangent of each cell and end load, rows and columns of
 * the held DOFs replaced by the identity. */
static void tangent(const nl_model *m, const double *q, const char *held, double *ab)
{
    memset(ab, 0, (size_t)m->ndof * LDAB * sizeof *ab);
    const double h[3] = {1e-9, 1e-9, 1e-9 / m->R};
    for (int c = 0; c < m->N; c++) {
        double s[6];
        memcpy(s, q + 3 * c, sizeof s);
        for (int k = 0; k < 6; k++) {
            double gp[6], gm[6], keep = s[k];
            s[k] = keep + h[k % 3];
            cell_grad(m, c, s, s + 3, gp);
            s[k] = keep - h[k % 3];
            cell_grad(m, c, s, s + 3, gm);
            s[k] = keep;
            for (int i = 0; i < 6; i++)
                band_add(ab, 3 * c + i, 3 * c + k, (gp[i] - gm[i]) / (2 * h[k % 3]));
        }
    }
    for (int e = 0; e < 2; e++) {
        int j = e ? m->N : 0;
        double s[3];
        memcpy(s, q + 3 * j, sizeof s);
        for (int k = 0; k < 3; k++) {
            double gp[3], gm[3], keep = s[k];
            s[k] = keep + h[k];
            end_load(m, j, s, gp);
            s[k] = keep - h[k];
            end_load(m, j, s, gm);
            s[k] = keep;
            for (int i = 0; i < 3; i++)
                band_add(ab, 3 * j + i, 3 * j + k, -(gp[i] - gm[i]) / (2 * h[k]));
        }
    }
    for (int j = 0; j <= m->N; j++)
        band_add(ab, 3 * j + 1, 3 * j + 1, m->kf);
    for (int i = 0; i < m->ndof; i++) {
        if (!held[i])
            continue;
        for (int k = (i > KB ? i - KB : 0); k < m->ndof && k <= i + KB; k++) {
            ab[(size_t)k * LDAB + 2 * KB + i - k] = 0.0; /* row i */
            ab[(size_t)i * LDAB + 2 * KB + k - i] = 0.0; /* column i */
        }
        ab[(size_t)i * LDAB + 2 * KB] = 1.0;
    }
}

/* Newton's method with the held DOFs at their values in q: until the
 * largest force residual is under 1e-9 F_t and the moment residual under
 * 1e-9 F_t R (the rounding floor is 1.1e-10 at 2880 cells, measured; a node
 * carries ~F_t D, 2e-2 N at 1440 cells, so 1e-8 N is 5e-7 of it), past
 * 2880 cells 1e-9 times (cells / 2880)^2: the floor grows with the cells
 * (order 2 at 2.8 x the bound, 17 deg, did not converge on 11520 cells at
 * 1e-9; at 16e-9 it does, its bins within 0.0002 p0 of 5760 cells').  The
 * tests' 1440 and 2880 cells are as before, bit for bit.
 * Returns 0 or -1. */
static int newton(const nl_model *m, double *q, const char *held, double *r, double *ab, int *piv)
{
    for (int it = 0; it < 40; it++) {
        residual(m, q, r);
        double worst = 0.0;
        for (int i = 0; i < m->ndof; i++) {
            if (held[i])
                r[i] = 0.0;
            worst = fmax(worst, fabs(r[i]) / (i % 3 == 2 ? m->Ft * m->R : m->Ft));
        }
        double tol = 1e-9 * fmax(1.0, (double)m->N * m->N / (2880.0 * 2880.0));
        if (worst <= tol)
            return 0;
        tangent(m, q, held, ab);
        if (LAPACKE_dgbsv(LAPACK_COL_MAJOR, m->ndof, KB, KB, 1, ab, LDAB, piv, r, m->ndof) != 0)
            return -1;
        for (int i = 0; i < m->ndof; i++)
            q[i] -= r[i];
    }
    return -1;
}

/* Work arrays of one solve. */
typedef struct nl_work {
    double *q, *r, *ab, *lam;
    int *piv;
    char *held, *act;
} nl_work;

/* Active-set passes from the contact states w->act and the state w->q: each
 * pass Newton's method with the active nodes held on the bore, then every
 * node's state set at once to lambda_j - c xi_j > 0, until none changes
 * (then lambda >= 0, xi >= 0, lambda xi = 0 hold to Newton's tolerance).
 * Returns the passes taken, or -1 (Newton failed, or no fixed point within
 * max_passes). */
static int active_set(const nl_model *m, double c, int max_passes, nl_work *w)
{
    for (int it = 0; it < max_passes; it++) {
        for (int j = 0; j <= m->N; j++) {
            w->held[3 * j + 1] = w->act[j];
            if (w->act[j])
                w->q[3 * j + 1] = 0.0;
        }
        if (newton(m, w->q, w->held, w->r, w->ab, w->piv) != 0)
            return -1;
        residual(m, w->q, w->r);
        int changed = 0;
        for (int j = 0; j <= m->N; j++) {
            w->lam[j] = w->act[j] ? w->r[3 * j + 1] : 0.0;
            char now = w->lam[j] - c * w->q[3 * j + 1] > 0.0;
            changed += now != w->act[j];
            w->act[j] = now;
        }
        if (!changed)
            return it + 1;
    }
    return -1;
}

int ref_contact_solve_nl(const rd_ring_params *p, const rd_contact_opts *o, int cells, int follower,
                         double bin_deg, double gap_floor, ref_result *out)
{
    nl_model m = {0};
    double E = p->youngs_modulus, G = E / (2.0 * (1.0 + p->poisson_ratio));
    double b = p->radial_width, h = p->axial_height, A = b * h;
    m.N = cells, m.ndof = 3 * (cells + 1), m.follower = follower, m.o = o;
    m.R = 0.5 * (p->diameter - b), m.ro = 0.5 * p->diameter, m.half_b = 0.5 * b;
    m.s = p->closed_gap / (2.0 * m.R), m.D = (2.0 * M_PI - 2.0 * m.s) / cells, m.L = m.R * m.D;
    m.EA = E * A, m.GAs = G * A / 1.2, m.EI = E * h * b * b * b / 12.0, m.Ft = p->tangential_force;
    m.dD = (o->bore.diameter > 0 ? 0.5 * o->bore.diameter : m.ro) - m.ro;
    /* the linear reference's foundation, 1e-12 of the radial stiffness (see
     * there): keeps an iterate's too-small active set solvable */
    m.kf = 1e-12 * m.EA / m.R * m.D;
    int n = m.ndof, rc = -1;
    nl_work w = {calloc(n, sizeof(double)),
                 malloc(n * sizeof(double)),
                 malloc((size_t)n * LDAB * sizeof(double)),
                 calloc(cells + 1, sizeof(double)),
                 malloc(n * sizeof(int)),
                 calloc(n, 1),
                 malloc(cells + 1)};
    double *gap = malloc((cells + 1) * sizeof *gap);
    if (!w.q || !w.r || !w.ab || !w.lam || !gap || !w.piv || !w.held || !w.act || cells % 2)
        goto out;
    w.held[3 * (cells / 2)] = 1;
    double c = 2.0 * m.Ft / p->diameter * m.D / 1e-6; /* as the linear reference */
    /* Started from the linear reference's contact states, which differ from
     * these by a node or two at an edge: 1 to 4 passes on bench_static's 32
     * battery bores at 1440 cells, where the all-touching start took 3 to
     * 255 (the set grows or shrinks by about a node per pass near each edge,
     * the edge node's force moving to its neighbour); 0.04 s a bore instead
     * of 0.8 (Release), the linear solve included.  The start changes the
     * path, not the fixed point: bins, gaps, edges and tip forces agree
     * with the all-touching start's within 3e-9 relative (Newton's
     * tolerance).  Should the warm start fail (no fixed point in 100
     * passes, or Newton failing from it), the all-touching start is taken. */
    int passes = -1;
    if (ref_contact_active_set(p, o, cells, w.act) == 0)
        passes = active_set(&m, c, 100, &w);
    if (passes < 0) {
        memset(w.q, 0, (size_t)n * sizeof *w.q);
        memset(w.act, 1, (size_t)cells + 1);
        passes = active_set(&m, c, 4 * cells, &w);
    }
    if (passes > 0) {
        rc = 0;
        out->iterations = passes;
        for (int j = 0; j <= cells; j++) {
            if (!w.act[j])
                w.lam[j] = 0.0;
            gap[j] = w.q[3 * j + 1];
        }
        out->cells = cells;
        out->p0 = 2.0 * m.Ft / (p->diameter * h);
        /* where on the bore: the nodes' polar angles phi_j */
        double *shift = malloc((cells + 1) * sizeof *shift);
        if (!shift) {
            rc = -1;
            goto out;
        }
        for (int j = 0; j <= cells; j++)
            shift[j] = w.q[3 * j] / m.ro;
        ref_mesh mesh = {cells, m.s, m.D, h, m.ro, shift};
        ref_post(&mesh, w.act, gap, w.lam, bin_deg, gap_floor, out);
        free(shift);
    }
out:
    free(w.q), free(w.r), free(w.ab), free(w.lam), free(gap), free(w.piv), free(w.held);
    free(w.act);
    return rc;
}
