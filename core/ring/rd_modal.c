/*
 * rd_modal — free-free modes of the segmented ring: K phi = lambda M phi,
 * lambda = omega^2 (thesis 3.20-3.27).  K (6n x 6n, positive semi-definite,
 * six rigid-body null vectors) and M (block diagonal, positive definite) are
 * banded, see rd_ring.c.
 *
 * Method: shift-invert Lanczos (rd_lanczos.c) on A = K + s M, s = the first
 * thin-ring eigenvalue, factored once by banded Cholesky; cost linear in n.
 *
 * Split: for a flat ring with a section symmetric about its plane the
 * in-plane DOFs (ux, uy, rz) and the out-of-plane DOFs (uz, rx, ry) share no
 * entry of K or M (checked entry by entry: exact zeros), so the two 3n
 * problems are solved separately, each for the wanted number of modes, and
 * merged in ascending order.  Each has half the DOFs and half the bandwidth.
 *
 * Rigid-body modes: the six rigid motions (three in each part) are built
 * exactly (rd_ring_rigid_motion), confirmed as null vectors of K and deflated
 * explicitly, so they cannot leak into the elastic spectrum.  Any further
 * eigenvalue below tau = 1e-6 lambda_ref is a mechanism of K (none exists
 * while E, G > 0) and is counted as one more zero mode; rigid_body_modes is
 * the sum.  Shift-invert resolves eigenvalues near zero to about eps *
 * lambda_ref, while the first elastic mode lies near lambda_ref / 30 for
 * the thesis ring and at 3.6e-3 lambda_ref for the flattest section
 * allowed (b/h = 0.05, where in-plane bending is the soft one), so 1e-6 is
 * far from both.  (With the rigid modes
 * at the Rayleigh-quotient noise eps lambda_max, as before deflation, the
 * threshold had to sit above that noise, and the first modes of very slender
 * rings, R/b in the thousands at n ~ 1000, fell below it.)
 *
 * Closed ring: its modes come in degenerate pairs (cos k theta, sin k theta);
 * Lanczos runs with block size 2 so that it finds both.
 *
 * Kind: in-plane DOFs (ux, uy, rz) and out-of-plane DOFs (uz, rx, ry) decouple
 * for a section symmetric about the ring plane; a mode's kind is the side that
 * holds more than half of its kinetic energy phi^T M phi.
 */
#include "rd_modal.h"

#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_accuracy.h"
#include "rd_internal.h"
#include "rd_lanczos.h"

/* Converged vectors have residual <= RESIDUAL_FLOOR * noise / lambda, noise =
 * 10 eps lambda_max (see setup): a factor 100 above the rounding level. */
#define RESIDUAL_FLOOR 100.0

void rd_modal_opts_default(rd_modal_opts *o)
{
    o->modes = 6;
    o->estimate_error = 1;
    o->tol = 1e-12;
    o->max_iterations = 300;
    o->coupled = 0;
}

int rd_modal_validate(const rd_modal_opts *o, int segments, rd_error *err)
{
    int elastic = 6 * segments - 6;
    if (o->modes < 1 || o->modes > RD_MODAL_MODES_MAX)
        return rd_error_set(err, o->modes > RD_MODAL_MODES_MAX ? RD_ELIMIT : RD_EINVAL, "/modes",
                            "@/modes = %d is out of range: allowed 1 to %d.", o->modes,
                            RD_MODAL_MODES_MAX);
    if (o->modes > elastic)
        return rd_error_set(err, RD_EINVAL, "/modes",
                            "@/modes = %d is more than the %d elastic modes a %d-segment "
                            "ring has (6 n - 6); use more segments or fewer modes.",
                            o->modes, elastic, segments);
    if (!(o->tol >= 1e-15 && o->tol <= 1e-3))
        return rd_error_set(err, RD_EINVAL, "/tolerance",
                            "modal tolerance %g is out of range: allowed 1e-15 to 1e-3.", o->tol);
    if (o->max_iterations < 1 || o->max_iterations > 10000)
        return rd_error_set(err, RD_EINVAL, "/max_iterations",
                            "modal max_iterations %d is out of range: allowed 1 to 10000.",
                            o->max_iterations);
    return RD_OK;
}

double rd_modal_slenderness(const rd_ring_params *p, int segments)
{
    rd_section s;
    rd_section_init(&s, p);
    double R = s.R;
    double g = 1.0 / (2.0 * (1.0 + p->poisson_ratio)); /* G / E */
    return segments * R / fmin(s.b, s.h) * sqrt(fmax(1.0, g));
}

/* The edges were found by solving rings of D = 0.0765 and 5 m, square and
 * flat (b/h = 1, 20) sections, split and closed, nu from -0.9999 to 0.4999,
 * at n = 10..2000 (README "Limits").  With the estimate: up to 3e5 every
 * error estimate agrees within 10 % with the one of a ring 4 times less
 * slender; at 5e5 one is 3.7 times too large (n = 1000), at 2e6 100 times.
 * Without it: up to 3e6 the frequencies (scaled by b / R^2) move by at most
 * 6e-4 against a ring 30 times less slender, at 1e7 by up to 3e-3 (split
 * rings; closed ones stay below 1e-4), at 1e8 by up to 7 %. */
int rd_modal_validate_ring(const rd_ring_params *p, int segments, int estimate_error, rd_error *err)
{
    double s = rd_modal_slenderness(p, segments);
    double s_max = estimate_error ? RD_MODAL_SLENDERNESS_MAX : RD_MODAL_SLENDERNESS_MAX_FREQ;
    if (s <= s_max)
        return RD_OK;
    int n_max = (int)floor(segments * s_max / s);
    const char *why = "the eigen-solve's condition number grows as its square, and beyond it "
                      "rounding in the stiff axial and shear springs swamps the soft bending "
                      "modes";
    const char *what = estimate_error ? " with /modal/error_estimate (3e6 without it)" : "";
    if (n_max < RD_SEGMENTS_MIN)
        return rd_error_set(err, RD_EINVAL, "/ring",
                            "/ring is too slender for the modal analysis: n R / min(b, h) x "
                            "sqrt(max(1, G / E)) is %.3g at %d segments, allowed up to %g%s even "
                            "at %d segments; %s.  Use a thicker section (radial_width, "
                            "axial_height), a smaller diameter or poisson_ratio above -0.5.",
                            s, segments, s_max, what, RD_SEGMENTS_MIN, why);
    size_t m = rd_error_enter(err, "/discretization");
    int rc = rd_error_set(err, RD_EINVAL, "/segments",
                          "@/segments = %d is too many for this ring in the modal analysis: the "
                          "slenderness n R / min(b, h) x sqrt(max(1, G / E)) is %.3g, allowed "
                          "up to %g%s, so at most %d segments here; %s.",
                          segments, s, s_max, what, n_max, why);
    rd_error_leave(err, m);
    return rc;
}

/* The modal block's checks, entered: rd_modal_validate's paths are relative
 * to it; the solves below take a scene's /modal. */
static int modal_block_validate(const rd_modal_opts *o, int segments, rd_error *err)
{
    size_t m = rd_error_enter(err, "/modal");
    int rc = rd_modal_validate(o, segments, err);
    rd_error_leave(err, m);
    return rc;
}

double rd_modal_thin_ring_inplane_hz(const rd_ring_params *p, int k)
{
    rd_ring_section s;
    rd_ring_section_get(p, 1, &s);
    double kk = (double)k * k;
    return k * (kk - 1.0) / (2.0 * M_PI * s.R * s.R * sqrt(kk + 1.0)) *
           sqrt(p->youngs_modulus * s.I_inplane / (p->density * s.area));
}

double rd_modal_thin_ring_outplane_hz(const rd_ring_params *p, int k)
{
    rd_ring_section s;
    rd_ring_section_get(p, 1, &s);
    double kk = (double)k * k, EI = p->youngs_modulus * s.I_outplane;
    return k * (kk - 1.0) / (2.0 * M_PI * s.R * s.R) *
           sqrt(EI / (p->density * s.area * (kk + EI / (s.G * s.J))));
}

void rd_modal_result_cleanup(rd_modal_result *r)
{
    if (!r)
        return;
    if (r->modes)
        for (int i = 0; i < r->n_modes; i++)
            free(r->modes[i].shape);
    free(r->modes);
    memset(r, 0, sizeof *r);
}

static double dot(int N, const double *a, const double *b)
{
    double s = 0.0;
    for (int i = 0; i < N; i++)
        s += a[i] * b[i];
    return s;
}

/* One independent sub-problem: a set of DOFs per segment, its K and M, the
 * rigid motions that live in it, and its Lanczos answer. */
typedef struct part {
    int dofs[6], ndof; /* DOF k (0..5) of every segment */
    int N, *map;       /* part index -> band index of the full problem */
    rd_band K, M;
    double *Z; /* N x nz rigid motions restricted to the part */
    int nz;
    rd_lanczos_result res;
} part;

typedef struct solve_ws {
    rd_band K, M; /* the full problem, band ordering */
    int N, nparts, block;
    part parts[2];
    double noise;            /* Rayleigh-quotient rounding level, 10 eps lambda_max */
    double lambda_ref;       /* shift: first thin-ring eigenvalue */
    double tau;              /* zero-mode threshold 1e-6 lambda_ref */
    int *inv;                /* N: band index -> part index (scratch) */
    double *x, *tmp1, *tmp2; /* N scratch */
} solve_ws;

static void ws_cleanup(solve_ws *w)
{
    rd_band_cleanup(&w->K);
    rd_band_cleanup(&w->M);
    for (int p = 0; p < 2; p++) {
        part *pt = &w->parts[p];
        free(pt->map);
        free(pt->Z);
        rd_band_cleanup(&pt->K);
        rd_band_cleanup(&pt->M);
        rd_lanczos_result_cleanup(&pt->res);
    }
    free(w->inv);
    free(w->x);
    free(w->tmp1);
    free(w->tmp2);
}

/* Relative residual ||K x - lam M x|| / (|lam| ||M x||) on the full problem;
 * tmp1, tmp2 scratch (N). */
static double residual(const solve_ws *w, int N, const double *x, double lam, double *tmp1,
                       double *tmp2)
{
    rd_band_symv(&w->K, x, tmp1);
    rd_band_symv(&w->M, x, tmp2);
    double rr = 0.0;
    for (int i = 0; i < N; i++) {
        double r = tmp1[i] - lam * tmp2[i];
        rr += r * r;
    }
    return sqrt(rr) / (fabs(lam) * sqrt(dot(N, tmp2, tmp2)));
}
/* Fills mode `md` from the band-ordered eigenvector x (eigenvalue lam). */
static int extract_mode(const rd_ring *ring, const solve_ws *w, const double *x, double lam,
                        double *tmp1, double *tmp2, rd_mode *md)
{
    int n = rd_ring_get_segments(ring), N = 6 * n;
    md->frequency_hz = sqrt(lam > 0.0 ? lam : 0.0) / (2.0 * M_PI);
    md->error_estimate = NAN;
    md->frequency_extrapolated_hz = NAN;

    md->residual = residual(w, N, x, lam, tmp1, tmp2);

    md->shape = malloc((size_t)N * sizeof *md->shape);
    if (!md->shape)
        return RD_ENOMEM;
    double e_in = 0.0, e_all = 0.0, umax = 0.0;
    static const int in_plane[6] = {1, 1, 0, 0, 0, 1};
    for (int i = 0; i < n; i++) {
        double v[6], vin[6], e_r[3], e_t[3];
        for (int k = 0; k < 6; k++) {
            v[k] = x[rd_ring_band_index(ring, i, k)];
            vin[k] = in_plane[k] ? v[k] : 0.0;
        }
        const double *Ms = rd_ring_segment_mass_matrix(ring, i);
        for (int r = 0; r < 6; r++)
            for (int c = 0; c < 6; c++) {
                e_all += v[r] * Ms[6 * r + c] * v[c];
                e_in += vin[r] * Ms[6 * r + c] * vin[c];
            }
        rd_ring_segment_frame(ring, i, e_r, e_t);
        double *s = md->shape + 6 * i;
        s[0] = v[0] * e_r[0] + v[1] * e_r[1];
        s[1] = v[0] * e_t[0] + v[1] * e_t[1];
        s[2] = v[2];
        s[3] = v[3] * e_r[0] + v[4] * e_r[1];
        s[4] = v[3] * e_t[0] + v[4] * e_t[1];
        s[5] = v[5];
        for (int k = 0; k < 3; k++)
            if (fabs(s[k]) > fabs(umax))
                umax = s[k];
    }
    /* Sign: antisymmetric modes have equal and opposite extremes, so take the
     * first translation (in segment order) within 1e-6 of the largest. */
    for (int i = 0, found = 0; i < n && !found; i++)
        for (int k = 0; k < 3 && !found; k++)
            if (fabs(md->shape[6 * i + k]) >= (1.0 - 1e-6) * fabs(umax)) {
                umax = copysign(fabs(umax), md->shape[6 * i + k]);
                found = 1;
            }
    md->in_plane_fraction = e_all > 0.0 ? e_in / e_all : 0.0;
    md->kind = md->in_plane_fraction > 0.5 ? RD_MODE_IN_PLANE : RD_MODE_OUT_OF_PLANE;
    if (umax != 0.0)
        for (int i = 0; i < N; i++)
            md->shape[i] /= umax;
    return RD_OK;
}

/* In-plane DOFs (ux, uy, rz) and out-of-plane DOFs (uz, rx, ry) decouple
 * when no entry of K or M joins the two sets: exactly zero, as for every flat
 * ring with a section symmetric about its plane (rd_ring.c). */
static const int in_plane_dof[6] = {1, 1, 0, 0, 0, 1};

static int splits(const rd_band *K, const rd_band *M)
{
    for (int j = 0; j < K->n; j++)
        for (int i = j - K->kd < 0 ? 0 : j - K->kd; i < j; i++)
            if (in_plane_dof[i % 6] != in_plane_dof[j % 6] &&
                (RD_BAND_AT(K, i, j) != 0.0 || RD_BAND_AT(M, i, j) != 0.0))
                return 0;
    return 1;
}

/* Copies the part's entries of the full K, M into its own band matrices. */
static int part_matrices(solve_ws *w, part *pt, rd_error *err)
{
    const rd_band *K = &w->K, *M = &w->M;
    for (int g = 0; g < w->N; g++)
        w->inv[g] = -1;
    for (int l = 0; l < pt->N; l++)
        w->inv[pt->map[l]] = l;
    int kd = 0, rc;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1 && ((rc = rd_band_init(&pt->K, pt->N, kd, err)) ||
                          (rc = rd_band_init(&pt->M, pt->N, kd, err))))
            return rc;
        for (int j = 0; j < w->N; j++)
            for (int i = j - K->kd < 0 ? 0 : j - K->kd; i <= j; i++) {
                int li = w->inv[i], lj = w->inv[j];
                double k = RD_BAND_AT(K, i, j), m = RD_BAND_AT(M, i, j);
                if (li < 0 || lj < 0 || (k == 0.0 && m == 0.0))
                    continue;
                int lo = li < lj ? li : lj, hi = li < lj ? lj : li;
                if (pass == 0 && hi - lo > kd)
                    kd = hi - lo;
                if (pass == 1) {
                    RD_BAND_AT(&pt->K, lo, hi) = k;
                    RD_BAND_AT(&pt->M, lo, hi) = m;
                }
            }
    }
    return RD_OK;
}

/* The part's index map, matrices and the rigid motions (unit translations
 * and rotations about the origin) whose every DOF lies in it. */
static int build_part(const rd_ring *ring, solve_ws *w, part *pt, rd_error *err)
{
    const int n = rd_ring_get_segments(ring);
    pt->N = n * pt->ndof;
    pt->map = malloc((size_t)pt->N * sizeof *pt->map);
    pt->Z = malloc((size_t)pt->N * 6 * sizeof *pt->Z);
    if (!pt->map || !pt->Z)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal solver.");
    for (int s = 0; s < n; s++)
        for (int t = 0; t < pt->ndof; t++)
            pt->map[pt->ndof * s + t] = 6 * s + pt->dofs[t];
    int rc = part_matrices(w, pt, err);
    if (rc)
        return rc;
    for (int m = 0; m < 6; m++) {
        double t[3] = {0, 0, 0}, r[3] = {0, 0, 0};
        (m < 3 ? t : r)[m % 3] = 1.0;
        rd_ring_rigid_motion(ring, t, r, w->x);
        int inside = 1;
        double *z = pt->Z + (size_t)pt->nz * pt->N;
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 6; k++) {
                int l = w->inv[rd_ring_band_index(ring, i, k)];
                if (l >= 0)
                    z[l] = w->x[6 * i + k];
                else if (w->x[6 * i + k] != 0.0)
                    inside = 0;
            }
        pt->nz += inside;
    }
    return RD_OK;
}

/* Assembles K and M, splits them into in-plane and out-of-plane parts where
 * they decouple (unless o->coupled), and sets the shift and thresholds. */
static int setup(const rd_ring *ring, const rd_modal_opts *o, solve_ws *w, rd_error *err)
{
    int rc;
    const int N = w->N;
    if ((rc = rd_ring_assemble_band(ring, &w->K, &w->M, err)))
        return rc;
    w->inv = malloc((size_t)N * sizeof *w->inv);
    w->x = malloc((size_t)N * sizeof *w->x);
    w->tmp1 = malloc((size_t)N * sizeof *w->tmp1);
    w->tmp2 = malloc((size_t)N * sizeof *w->tmp2);
    if (!w->inv || !w->x || !w->tmp1 || !w->tmp2)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal solver (%d DOF).", N);
    double f_ref = rd_modal_thin_ring_outplane_hz(rd_ring_get_params(ring), 2);
    w->lambda_ref = pow(2.0 * M_PI * f_ref, 2);
    w->noise = 10.0 * 2.220446049250313e-16 * rd_ring_lambda_max_estimate(ring);
    w->tau = 1e-6 * w->lambda_ref;
    /* single-vector Lanczos sees one vector of each eigenspace: the closed
     * ring's modes come in degenerate pairs */
    w->block = rd_ring_is_closed(ring) ? 2 : 1;
    w->nparts = !o->coupled && splits(&w->K, &w->M) ? 2 : 1;
    for (int p = 0; p < w->nparts; p++) {
        part *pt = &w->parts[p];
        for (int k = 0; k < 6; k++)
            if (w->nparts == 1 || in_plane_dof[k] == (p == 0))
                pt->dofs[pt->ndof++] = k;
        if ((rc = build_part(ring, w, pt, err)))
            return rc;
    }
    return RD_OK;
}

/* Lanczos on part p for its `want` lowest elastic modes. */
static int solve_part(solve_ws *w, int p, int want, const rd_modal_opts *o, const rd_monitor *mon,
                      rd_error *err)
{
    part *pt = &w->parts[p];
    int room = pt->N - pt->nz;
    /* Ritz vectors of modes near lambda_max do not reach their rounding
     * floor from a shift-invert Krylov space short of the whole space: when
     * the wanted modes reach that far up, take the whole (small) space. */
    if (3 * want > room)
        want = room;
    rd_lanczos_problem pb = {.K = &pt->K,
                             .M = &pt->M,
                             .null = pt->Z,
                             .r = pt->nz,
                             .shift = w->lambda_ref,
                             .zero = w->tau,
                             .want = want < room ? want : room,
                             .block = w->block,
                             .max_steps = o->max_iterations,
                             .floor_abs = RESIDUAL_FLOOR * w->noise,
                             .tol = o->tol,
                             .mon = mon,
                             .mon_lo = (double)p / w->nparts,
                             .mon_hi = (double)(p + 1) / w->nparts};
    return rd_lanczos_solve(&pb, &pt->res, err);
}

/* Fills out->modes with the `total` lowest modes of all parts, each scattered
 * to the full problem. */
static int collect_modes(const rd_ring *ring, solve_ws *w, int total, rd_modal_result *out,
                         rd_error *err)
{
    out->modes = calloc((size_t)total, sizeof *out->modes);
    if (!out->modes)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal results.");
    int next[2] = {0, 0};
    for (int e = 0; e < total; e++) {
        int best = -1;
        for (int p = 0; p < w->nparts; p++) {
            const rd_lanczos_result *r = &w->parts[p].res;
            if (next[p] < r->found &&
                (best < 0 || r->lambda[next[p]] < w->parts[best].res.lambda[next[best]]))
                best = p;
        }
        if (best < 0)
            return rd_error_set(err, RD_EINTERNAL, "", "The modal solver found %d of %d modes.", e,
                                total);
        const part *pt = &w->parts[best];
        const double *xp = pt->res.x + (size_t)next[best] * pt->N;
        memset(w->x, 0, (size_t)w->N * sizeof *w->x);
        for (int l = 0; l < pt->N; l++)
            w->x[pt->map[l]] = xp[l];
        int rc = extract_mode(ring, w, w->x, pt->res.lambda[next[best]++], w->tmp1, w->tmp2,
                              &out->modes[e]);
        out->n_modes = e + 1;
        if (rc)
            return rd_error_set(err, rc, "", "Out of memory for the mode shapes.");
        if (out->modes[e].residual > out->max_residual)
            out->max_residual = out->modes[e].residual;
    }
    return RD_OK;
}

/* Solves the ring for o->modes modes, or, when want_kind is given and the
 * problem splits, for want_kind[k] modes of kind k (the reference solve of
 * the error estimate matches modes kind by kind). */
static int solve_ring(const rd_ring *ring, const rd_modal_opts *o, const int *want_kind,
                      const rd_monitor *mon, rd_modal_result *out, rd_error *err)
{
    solve_ws w;
    memset(&w, 0, sizeof w);
    memset(out, 0, sizeof *out);
    int rc = RD_OK;
    const int n = rd_ring_get_segments(ring);
    w.N = 6 * n;
    out->segments = n;
    out->dof = w.N;
    out->error_estimate = NAN;

    if ((rc = modal_block_validate(o, n, err)) || (rc = setup(ring, o, &w, err)))
        goto out;
    out->block_size = w.block;
    int per_kind = want_kind && w.nparts == 2;
    int total = per_kind ? want_kind[0] + want_kind[1] : o->modes;
    for (int p = 0; p < w.nparts; p++) {
        if (per_kind && want_kind[p] == 0)
            continue; /* the main solve found no mode of this kind */
        rd_error sub;
        rd_error_init_local(&sub, err);
        rc = solve_part(&w, p, per_kind ? want_kind[p] : o->modes, o, mon, &sub);
        out->iterations += w.parts[p].res.steps;
        out->rigid_body_modes += w.parts[p].res.deflated + w.parts[p].res.zeros;
        if (rc == RD_ENOCONV)
            rd_error_set(err, rc, "",
                         "The modal solver did not converge in %d Lanczos steps (%d segments, "
                         "%d modes): the largest residual is %.3g times its rounding floor.",
                         w.parts[p].res.steps, n, o->modes, w.parts[p].res.worst);
        else if (rc)
            rd_error_forward(err, &sub);
        if (rc)
            goto out;
    }
    rc = collect_modes(ring, &w, total, out, err);
out:
    ws_cleanup(&w);
    if (rc != RD_OK)
        rd_modal_result_cleanup(out);
    return rc;
}

int rd_modal_solve_ring(const rd_ring *ring, const rd_modal_opts *o, const rd_monitor *mon,
                        rd_modal_result *out, rd_error *err)
{
    return solve_ring(ring, o, NULL, mon, out, err);
}

/* The k-th mode of `kind` in r (k counts from 0), or -1. */
static int nth_of_kind(const rd_modal_result *r, int kind, int k)
{
    for (int i = 0; i < r->n_modes; i++)
        if (r->modes[i].kind == kind && k-- == 0)
            return i;
    return -1;
}

/* The error estimate on the accuracy driver: level 0 solves the scene's n,
 * level 1 the reference m with 6 spare modes, so that a coarse ring's extra
 * mode of one kind still leaves the k-th mode of each kind to match. */
typedef struct modal_levels {
    const rd_ring_params *p;
    int n[2], closed;
    const rd_modal_opts *o;
    rd_modal_result *res[2];
} modal_levels;

static int level_solve(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    modal_levels *L = ctx;
    rd_modal_opts ro = *L->o;
    int want_kind[2] = {0, 0};
    if (level == 1) {
        ro.modes = L->o->modes + 6 <= RD_MODAL_MODES_MAX ? L->o->modes + 6 : RD_MODAL_MODES_MAX;
        if (ro.modes > 6 * L->n[1] - 6)
            ro.modes = 6 * L->n[1] - 6;
        for (int i = 0; i < L->res[0]->n_modes; i++)
            want_kind[L->res[0]->modes[i].kind]++;
    }
    rd_ring *ring = rd_ring_create(L->p, L->n[level], L->closed, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    int rc = solve_ring(ring, &ro, level == 1 ? want_kind : NULL, mon, L->res[level], err);
    rd_ring_free(ring);
    return rc;
}

/* Richardson with the model's order 2 (f_n = f_inf (1 + C n^-2)), mode by
 * mode, the k-th of each kind against the k-th of the same kind. */
static int level_compare(void *ctx, rd_error *err)
{
    (void)err;
    modal_levels *L = ctx;
    rd_modal_result *out = L->res[0], *ref = L->res[1];
    out->reference_segments = L->n[1];
    out->error_estimate = 0.0;
    int seen[2] = {0, 0};
    for (int i = 0; i < out->n_modes; i++) {
        rd_mode *md = &out->modes[i];
        int k = nth_of_kind(ref, md->kind, seen[md->kind]++);
        if (k < 0) {
            out->error_estimate = NAN;
            continue;
        }
        md->frequency_extrapolated_hz =
            rd_accuracy_richardson(md->frequency_hz, L->n[0], ref->modes[k].frequency_hz, L->n[1],
                                   2.0, &md->error_estimate);
        if (!(md->error_estimate <= out->error_estimate) && !isnan(out->error_estimate))
            out->error_estimate = md->error_estimate;
    }
    return RD_OK;
}

int rd_modal_solve(const rd_ring_params *p, int segments, int closed, const rd_modal_opts *o,
                   const rd_monitor *mon, rd_modal_result *out, rd_error *err)
{
    rd_modal_result ref;
    memset(&ref, 0, sizeof ref);
    memset(out, 0, sizeof *out);
    int rc;
    if ((rc = rd_ring_scene_validate(p, segments, closed, err)) ||
        (rc = modal_block_validate(o, segments, err)) ||
        (rc = rd_modal_validate_ring(p, segments, o->estimate_error, err)))
        return rc;
    int m = rd_accuracy_refined_segments(segments, RD_SEGMENTS_MAX);
    char what[48];
    snprintf(what, sizeof what, "%d segments", m);
    modal_levels L = {p, {segments, m}, closed, o, {out, &ref}};
    rd_accuracy_plan plan = {
        level_solve, level_compare, &L, o->estimate_error, (double)segments / (segments + m), what};
    rc = rd_accuracy_run(&plan, mon, NULL, err);
    rd_modal_result_cleanup(&ref);
    if (rc != RD_OK)
        rd_modal_result_cleanup(out);
    return rc;
}

/* Work of one solve_ring with `want` modes asked of each of two parts of 3n
 * DOFs: steps per part as measured (bench_modal: about 1.75 w + 8 on a split
 * ring, 2 w + 12 with the closed ring's block size 2; the whole space when
 * the wanted modes pass a third of it), then per step the band work N (kd + 1)
 * and the reorthogonalisation N s, per check the projected problem s^3, and
 * the mode extraction n modes.  Constants: relative least squares on 104
 * CPU-time medians (Release, reference BLAS); worst factor 1.8. */
static double solve_cost(int n, int want, int closed)
{
    const double c_band = 5.37e-9, c_reorth = 6.04e-10, c_small = 3.69e-9, c_extract = 5.16e-7,
                 c_fixed = 2.41e-5;
    int Np = 3 * n, room = Np - 3, kd = closed ? 8 : 5;
    int w = want < room ? want : room;
    double S = 3 * w > room ? room : (closed ? 2.0 * w + 12.0 : 1.75 * w + 8.0);
    if (S > room)
        S = room;
    return 2.0 * (c_band * Np * S * (kd + 1) + c_reorth * Np * S * S + c_small * S * S * S) +
           c_extract * n * 2.0 * w + c_fixed;
}

double rd_modal_cost_predict(const rd_modal_opts *o, int segments, int closed)
{
    if (!o || rd_modal_validate(o, segments, NULL) != RD_OK || segments < RD_SEGMENTS_MIN ||
        segments > RD_SEGMENTS_MAX)
        return NAN;
    double t = solve_cost(segments, o->modes, closed);
    if (o->estimate_error) /* the reference asks each kind for about half the modes */
        t += solve_cost(rd_accuracy_refined_segments(segments, RD_SEGMENTS_MAX), o->modes / 2 + 1,
                        closed);
    return t;
}
