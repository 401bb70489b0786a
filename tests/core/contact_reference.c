/*
 * contact_reference.c — see contact_reference.h.
 *
 * Unknowns per node j at theta_j = s + j D (s the half closed-gap angle,
 * D = span / N): u (tangential, +e_theta, m), w (radial, outward, m), beta
 * (section rotation, +z, rad); DOF 3j + {0, 1, 2}.  Strains on the centroid
 * circle of radius R, ' = d/dtheta:
 *   eps = (u' + w) / R,  gamma = (u - w') / R - beta,  kappa = beta' / R,
 * (a rigid rotation c: u = c R, beta = c; a translation: u = -a sin,
 * w = a cos: all three vanish), energy 1/2 int (EA eps^2 + GA/f_s gamma^2 +
 * EI kappa^2) R dtheta, each cell's integrand at its middle (linear
 * interpolation; one point integrates the shear and membrane terms without
 * locking).  Loads: F_t along +e_theta at the first end, -e_theta at the
 * last (the gap faces pushed apart).  Held: u = 0 at theta = pi (the
 * anti-rotation pin).  Contact at each node: gap g_j = r_b(theta_j) - r_o -
 * w_j >= 0, node force lambda_j >= 0 (inward on w), lambda_j g_j = 0.
 * Active set: A = {j : lambda_j - c g_j > 0}, w_j = r_b - r_o prescribed on
 * A, solved by elimination with a banded Cholesky (LAPACK dpbsv); repeated
 * until A no longer changes.
 */
#include "contact_reference.h"

#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define KD 5 /* half bandwidth: node j couples with j +- 1 */

typedef struct model {
    int N, ndof;
    double R, ro, s, D, h, EA, GAs, EI, Ft;
    double *K;  /* full band, lower, (KD + 1) x ndof, column-major */
    double *g0; /* bore radius - r_o at each node */
} model;

static double kij(const model *m, int i, int j)
{
    if (i < j) {
        int t = i;
        i = j;
        j = t;
    }
    return i - j > KD ? 0.0 : m->K[(size_t)j * (KD + 1) + (i - j)];
}

/* Cell stiffness: B rows (eps, gamma, kappa) at the middle, 6 DOFs. */
static void assemble(model *m)
{
    double R = m->R, D = m->D;
    for (int c = 0; c < m->N; c++) {
        double B[3][6] = {{0}};
        /* eps = (u' + w) / R */
        B[0][0] = -1.0 / (D * R), B[0][3] = 1.0 / (D * R), B[0][1] = 0.5 / R, B[0][4] = 0.5 / R;
        /* gamma = (u - w') / R - beta */
        B[1][0] = 0.5 / R, B[1][3] = 0.5 / R, B[1][1] = 1.0 / (D * R), B[1][4] = -1.0 / (D * R);
        B[1][2] = -0.5, B[1][5] = -0.5;
        /* kappa = beta' / R */
        B[2][2] = -1.0 / (D * R), B[2][5] = 1.0 / (D * R);
        double C[3] = {m->EA, m->GAs, m->EI};
        for (int a = 0; a < 6; a++)
            for (int b = 0; b <= a; b++) {
                double v = 0.0;
                for (int q = 0; q < 3; q++)
                    v += B[q][a] * C[q] * B[q][b];
                int ri = 3 * c + a, cj = 3 * c + b;
                m->K[(size_t)cj * (KD + 1) + (ri - cj)] += v * R * D;
            }
    }
}

/* Solves with the DOFs in `fixed` prescribed to `val`; returns u and the
 * reactions (K u - f at the fixed DOFs). */
static int solve_fixed(const model *m, const char *fixed, const double *val, const double *f,
                       double *u, double *react, double *ab)
{
    int n = m->ndof;
    for (int j = 0; j < n; j++) {
        u[j] = fixed[j] ? val[j] : f[j];
        for (int d = 0; d <= KD && j + d < n; d++)
            ab[(size_t)j * (KD + 1) + d] = m->K[(size_t)j * (KD + 1) + d];
    }
    for (int j = 0; j < n; j++) {
        if (!fixed[j])
            continue;
        for (int i = (j > KD ? j - KD : 0); i < n && i <= j + KD; i++)
            if (!fixed[i])
                u[i] -= kij(m, i, j) * val[j];
        for (int d = 0; d <= KD && j + d < n; d++)
            ab[(size_t)j * (KD + 1) + d] = d == 0 ? 1.0 : 0.0;
        for (int d = 1; d <= KD && j - d >= 0; d++)
            ab[(size_t)(j - d) * (KD + 1) + d] = 0.0;
    }
    if (LAPACKE_dpbsv(LAPACK_COL_MAJOR, 'L', n, KD, 1, ab, KD + 1, u, n) != 0)
        return -1;
    for (int i = 0; i < n; i++) {
        react[i] = 0.0;
        if (!fixed[i])
            continue;
        for (int j = (i > KD ? i - KD : 0); j < n && j <= i + KD; j++)
            react[i] += kij(m, i, j) * u[j];
        react[i] -= f[i];
    }
    return 0;
}

static double bore(const rd_contact_opts *o, double th)
{
    double r = 0.0;
    for (int k = 0; k < o->bore.n_distortion; k++) {
        const rd_distortion *d = &o->bore.distortion[k];
        r += d->amplitude * cos(d->order * (th - d->phase_deg * M_PI / 180.0));
    }
    return r;
}

/* Lift-off point between node a (in contact) and its neighbour b (gap g1),
 * with g2 the gap one node further: the gap grows as the cube of the
 * distance from an edge that carries a point force; the cube root fit,
 * clamped to the cell. */
static double edge(double ta, double tb, double g1, double g2)
{
    /* g1 = c y^3, g2 = c (y + D)^3, y = tb - edge: y = D / (r - 1) */
    double r = g1 > 0.0 && g2 > g1 ? cbrt(g2 / g1) : 3.0;
    double x = -1.0 / (r - 1.0);
    x = x < -1.0 ? -1.0 : (x > 0.0 ? 0.0 : x);
    return tb + x * (tb - ta);
}

/* Length of the arc [a, b] (rad) outside out's gaps. */
static double on_bore(const ref_result *out, double a, double b)
{
    double len = b - a;
    for (int g = 0; g < out->n_gaps; g++) {
        double s0 = out->gaps[g].start_deg * M_PI / 180, s1 = out->gaps[g].end_deg * M_PI / 180;
        len -= fmax(0.0, fmin(b, s1) - fmax(a, s0));
    }
    return fmax(0.0, len);
}

rd_contact_opts ref_battery_bore(const rd_ring_params *p, int k, double fac, double phase)
{
    rd_ring_section sec;
    rd_ring_section_get(p, 0, &sec);
    double bound = p->tangential_force * pow(sec.R, 3) /
                   (p->youngs_modulus * sec.I_inplane * pow(k * k - 1.0, 2));
    rd_contact_opts o;
    rd_contact_opts_default(&o);
    o.bore.n_distortion = 1;
    o.bore.distortion[0] = (rd_distortion){k, fmin(fac * bound, 0.004 * p->diameter), phase};
    return o;
}

static double node_angle(const ref_mesh *m, int j)
{
    return m->s + j * m->D + (m->shift ? m->shift[j] : 0.0);
}

/* out's contact patches from its gaps: each node's force to the patch
 * between the deepest points of the gaps around it (a node in a gap holds
 * none); a patch is kept where it has width or force. */
static void ref_patches(const ref_mesh *m, const double *lam, ref_result *out)
{
    int N = m->cells, j = 0;
    out->n_patches = 0;
    for (int g = 0; g <= out->n_gaps; g++) {
        double lim = g < out->n_gaps ? out->gaps[g].at_deg : INFINITY, f = 0.0, fa = 0.0;
        for (; j <= N && node_angle(m, j) * 180 / M_PI <= lim; j++)
            f += lam[j], fa += lam[j] * node_angle(m, j) * 180 / M_PI;
        double a = g > 0 ? out->gaps[g - 1].end_deg : node_angle(m, 0) * 180 / M_PI;
        double b = g < out->n_gaps ? out->gaps[g].start_deg : node_angle(m, N) * 180 / M_PI;
        if (b <= a && f <= 0.0)
            continue;
        out->patches[out->n_patches++] =
            (ref_patch){a, fmax(a, b), f, f > 0.0 ? fa / f : 0.5 * (a + b)};
    }
}

void ref_post(const ref_mesh *m, const char *act, const double *gap, const double *lam,
              double bin_deg, double gap_floor, ref_result *out)
{
    int N = m->cells;
    double a0 = node_angle(m, 0), aN = node_angle(m, N);
    double span = aN - a0, gap_len = 0.0;
    out->n_gaps = 0;
    out->max_clearance = 0.0;
    out->max_clearance_deg = NAN;
    for (int j = 0; j <= N;) {
        if (act[j]) {
            j++;
            continue;
        }
        int a = j;
        while (j <= N && !act[j])
            j++;
        int b = j - 1; /* nodes a..b lifted */
        double th = node_angle(m, a), te = node_angle(m, b);
        double gA = gap[a], gB = gap[b];
        double start =
            a == 0 ? th : edge(node_angle(m, a - 1), th, gA, a + 1 <= b ? gap[a + 1] : 0);
        double end =
            b == N ? te : -edge(-node_angle(m, b + 1), -te, gB, b - 1 >= a ? gap[b - 1] : 0);
        double best = 0.0, at = th;
        for (int q = a; q <= b; q++)
            if (gap[q] > best)
                best = gap[q], at = node_angle(m, q);
        if (best <= gap_floor)
            continue;
        gap_len += end - start;
        ref_gap *g = out->n_gaps < 64 ? &out->gaps[out->n_gaps++] : NULL;
        if (g)
            *g = (ref_gap){start * 180 / M_PI, end * 180 / M_PI, best, at * 180 / M_PI};
        if (best > out->max_clearance)
            out->max_clearance = best, out->max_clearance_deg = at * 180 / M_PI;
    }
    out->contact_fraction = 1.0 - gap_len / span;
    out->end_deg[0] = a0 * 180 / M_PI;
    out->end_deg[1] = aN * 180 / M_PI;
    ref_patches(m, lam, out);
    out->tip_force[0] = act[0] ? lam[0] - 0.5 * lam[1] : 0.0;
    out->tip_force[1] = act[N] ? lam[N] - 0.5 * lam[N - 1] : 0.0;
    /* bins: node forces spread over the part of their tributary arcs on
     * the bore (a node beside a gap edge: up to the edge) */
    out->bins = (int)lround(360.0 / bin_deg);
    double wb = bin_deg * M_PI / 180.0, force[REF_BINS_MAX] = {0}, cover[REF_BINS_MAX] = {0};
    for (int j = 0; j <= N; j++) {
        double lo = j > 0 ? 0.5 * (node_angle(m, j - 1) + node_angle(m, j)) : a0;
        double hi = j < N ? 0.5 * (node_angle(m, j) + node_angle(m, j + 1)) : aN;
        double on = on_bore(out, lo, hi);
        for (int k = 0; k < out->bins; k++) {
            /* the first and last bins reach past 0 and 360 deg (a free end
             * pushed along the bore beyond the gap's middle) */
            double a = k > 0 ? fmax(lo, k * wb) : lo;
            double b = k < out->bins - 1 ? fmin(hi, (k + 1) * wb) : hi;
            if (b <= a)
                continue;
            cover[k] += b - a;
            force[k] += on > 0.0 ? lam[j] * on_bore(out, a, b) / on : lam[j] * (b - a) / (hi - lo);
        }
    }
    for (int k = 0; k < out->bins; k++)
        out->bin_pressure[k] = cover[k] > 0 ? force[k] / (m->h * m->ro * cover[k]) : 0.0;
}

/* The solve behind ref_contact_solve; act_out (cells + 1), when not NULL,
 * receives the converged contact states. */
static int solve_linear(const rd_ring_params *p, const rd_contact_opts *o, int cells,
                        double bin_deg, double gap_floor, ref_result *out, char *act_out)
{
    model m = {0};
    double E = p->youngs_modulus, G = E / (2.0 * (1.0 + p->poisson_ratio));
    double b = p->radial_width, h = p->axial_height, A = b * h;
    m.N = cells, m.ndof = 3 * (cells + 1);
    m.R = 0.5 * (p->diameter - b), m.ro = 0.5 * p->diameter, m.h = h;
    m.s = p->closed_gap / (2.0 * m.R), m.D = (2.0 * M_PI - 2.0 * m.s) / cells;
    m.EA = E * A, m.GAs = G * A / 1.2, m.EI = E * h * b * b * b / 12.0, m.Ft = p->tangential_force;
    double dD = (o->bore.diameter > 0 ? 0.5 * o->bore.diameter : m.ro) - m.ro;
    int n = m.ndof, rc = -1;
    m.K = calloc((size_t)n * (KD + 1), sizeof *m.K);
    m.g0 = malloc((size_t)(cells + 1) * sizeof *m.g0);
    double *ab = malloc((size_t)n * (KD + 1) * sizeof *ab), *u = malloc(n * sizeof *u);
    double *f = calloc(n, sizeof *f), *val = calloc(n, sizeof *val), *re = malloc(n * sizeof *re);
    double *lam = calloc(cells + 1, sizeof *lam);
    char *fixed = calloc(n, 1), *act = malloc(cells + 1);
    if (!m.K || !m.g0 || !ab || !u || !f || !val || !re || !lam || !fixed || !act)
        goto out;
    assemble(&m);
    /* a foundation 1e-12 of the ring's radial stiffness under every node,
     * so an active set too small to hold the ring (an iterate of a bore
     * that touches it at two points) stays solvable; it moves the answer
     * by ~1e-12 relative */
    for (int j = 0; j <= cells; j++)
        m.K[(size_t)(3 * j + 1) * (KD + 1)] += 1e-12 * m.EA / m.R * m.D;
    for (int j = 0; j <= cells; j++) {
        m.g0[j] = dD + bore(o, m.s + j * m.D);
        act[j] = 1;
    }
    f[0] = m.Ft, f[3 * cells] = -m.Ft;
    fixed[3 * (cells / 2)] = 1;                       /* u = 0 at theta = pi (cells even) */
    double c = 2.0 * m.Ft / p->diameter * m.D / 1e-6; /* node force per m of gap */
    for (int it = 0; it < 500; it++) {
        for (int j = 0; j <= cells; j++) {
            fixed[3 * j + 1] = act[j];
            val[3 * j + 1] = m.g0[j];
        }
        if (solve_fixed(&m, fixed, val, f, u, re, ab) != 0)
            goto out;
        int changed = 0;
        for (int j = 0; j <= cells; j++) {
            lam[j] = act[j] ? -re[3 * j + 1] : 0.0; /* the bore pushes inward */
            double g = m.g0[j] - u[3 * j + 1];
            char now = lam[j] - c * g > 0.0;
            changed += now != act[j];
            act[j] = now;
        }
        out->iterations = it + 1;
        if (!changed) {
            rc = 0;
            break;
        }
    }
    if (rc == 0) {
        for (int j = 0; j <= cells; j++)
            if (!act[j])
                lam[j] = 0.0;
        out->cells = cells;
        out->p0 = 2.0 * m.Ft / (p->diameter * h);
        for (int j = 0; j <= cells; j++)
            re[j] = m.g0[j] - u[3 * j + 1]; /* the gaps (re is free now) */
        /* where on the bore: the running-face points' tangential moves
         * u + (b / 2) beta over r_o (f is free now) */
        for (int j = 0; j <= cells; j++)
            f[j] = (u[3 * j] + 0.5 * b * u[3 * j + 2]) / m.ro;
        ref_mesh mesh = {cells, m.s, m.D, m.h, m.ro, f};
        ref_post(&mesh, act, re, lam, bin_deg, gap_floor, out);
        if (act_out)
            memcpy(act_out, act, (size_t)cells + 1);
    }
out:
    free(m.K), free(m.g0), free(ab), free(u), free(f), free(val), free(re), free(lam);
    free(fixed), free(act);
    return rc;
}

int ref_contact_solve(const rd_ring_params *p, const rd_contact_opts *o, int cells, double bin_deg,
                      double gap_floor, ref_result *out)
{
    return solve_linear(p, o, cells, bin_deg, gap_floor, out, NULL);
}

int ref_contact_active_set(const rd_ring_params *p, const rd_contact_opts *o, int cells, char *act)
{
    ref_result r;
    return solve_linear(p, o, cells, 10.0, 0.0, &r, act);
}

double ref_edge_error(const rd_contact_result *c, const ref_result *r)
{
    double worst = NAN;
    for (int a = 0; a < r->n_gaps; a++) {
        const ref_gap *g = &r->gaps[a];
        if (g->max_clearance <= 1e-7)
            continue;
        double best = g->end_deg - g->start_deg;
        for (int b = 0; b < c->n_gaps; b++) {
            const rd_contact_gap *h = &c->gaps[b];
            if (h->end_deg < g->start_deg || h->start_deg > g->end_deg)
                continue;
            best =
                fmin(best, fmax(fabs(g->start_deg - h->start_deg), fabs(g->end_deg - h->end_deg)));
        }
        worst = isnan(worst) ? best : fmax(worst, best);
    }
    return worst;
}

/* c's segment arc nearest the angle a, deg. */
static double seg_width(const rd_contact_result *c, double a)
{
    int best = 0;
    for (int i = 1; i < c->points; i++)
        if (fabs(c->angle_deg[i] - a) < fabs(c->angle_deg[best] - a))
            best = i;
    return c->width_deg[best];
}

/* The largest difference of r's patch p from c's patches that overlap it
 * within a segment of c there (none: p's force), and the reverse. */
static double patch_error_one(const ref_patch *p, const rd_contact_result *c, double *rel)
{
    double w = seg_width(c, p->centroid_deg), d = NAN;
    for (int k = 0; k < c->n_patches; k++) {
        const rd_contact_patch *q = &c->patches[k];
        if (q->end_deg + w >= p->start_deg && q->start_deg - w <= p->end_deg) {
            double e = fabs(q->force_n - p->force_n);
            d = isnan(d) ? e : fmax(d, e);
        }
    }
    d = isnan(d) ? p->force_n : d;
    *rel = fmax(*rel, d / fmax(p->force_n, 0.5));
    return d;
}

double ref_patch_error(const rd_contact_result *c, const ref_result *r, double *rel)
{
    double worst = 0.0;
    *rel = 0.0;
    for (int j = 0; j < r->n_patches; j++)
        worst = fmax(worst, patch_error_one(&r->patches[j], c, rel));
    for (int k = 0; k < c->n_patches; k++) { /* c's patches the reference lacks */
        const rd_contact_patch *q = &c->patches[k];
        ref_patch p = {q->start_deg, q->end_deg, q->force_n, q->centroid_deg};
        int found = 0;
        double w = seg_width(c, q->centroid_deg);
        for (int j = 0; j < r->n_patches && !found; j++)
            found = r->patches[j].end_deg + w >= p.start_deg &&
                    r->patches[j].start_deg - w <= p.end_deg;
        if (!found) {
            worst = fmax(worst, p.force_n);
            *rel = fmax(*rel, 1.0);
        }
    }
    return worst;
}

double ref_patch_floor(const ref_result *r)
{
    double big = 0.0;
    for (int j = 0; j < r->n_patches; j++)
        big = fmax(big, r->patches[j].force_n);
    return 0.01 + 1e-3 * big;
}

int ref_tracks(double est, double err, double floor)
{
    if (err <= floor && est <= floor)
        return 1;
    return est <= 3.0 * err && err <= 3.0 * est;
}
