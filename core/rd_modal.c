/*
 * rd_modal — free-free modes of the segmented ring: K phi = lambda M phi,
 * lambda = omega^2 (thesis 3.20-3.27).  K (6n x 6n, positive semi-definite,
 * six rigid-body null vectors) and M (block diagonal, positive definite) are
 * banded, see rd_ring.c.
 *
 * Method: shift-invert subspace iteration with Rayleigh-Ritz (Bathe).  With a
 * shift s > 0, A = K + s M is positive definite; iterate on a block X of p
 * vectors
 *     X <- A^-1 M X,  M-orthonormalize X,  solve (X^T K X) Q = (X^T M X) Q Lambda,
 *     X <- X Q,
 * which converges to the p lowest eigenpairs, pair j at the rate
 * (lambda_j + s) / (lambda_{p+1} + s) per iteration.  A is factored once
 * (LAPACK dpbtrf, O(n kd^2)); each iteration costs p band solves and O(n p^2)
 * dense work, so the cost is linear in the segment count n.
 *
 * Rigid-body modes: K's null space gives Ritz values that are zero up to the
 * rounding noise of the Rayleigh quotient, about eps * lambda_max.  They are
 * counted as those below tau = sqrt(noise * lambda_ref), the geometric mean of
 * that noise and the first thin-ring eigenvalue, so both are a wide factor away.
 *
 * Kind: in-plane DOFs (ux, uy, rz) and out-of-plane DOFs (uz, rx, ry) decouple
 * for a section symmetric about the ring plane; a mode's kind is the side that
 * holds more than half of its kinetic energy phi^T M phi.
 */
#include "rd_modal.h"

#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rd_internal.h"

#define COL(X, N, j) ((X) + (size_t)(j) * (size_t)(N))

/* Converged vectors have residual <= RESIDUAL_FLOOR * noise / lambda, noise =
 * 10 eps lambda_max (see solve_ring): a factor 100 above the rounding level. */
#define RESIDUAL_FLOOR 100.0

void rd_modal_opts_default(rd_modal_opts *o)
{
    o->modes = 6;
    o->estimate_error = 1;
    o->tol = 1e-12;
    o->max_iterations = 300;
}

int rd_modal_validate(const rd_modal_opts *o, int segments, rd_error *err)
{
    int elastic = 6 * segments - 6;
    if (o->modes < 1 || o->modes > RD_MODAL_MODES_MAX)
        return rd_error_set(err, o->modes > RD_MODAL_MODES_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/modal/modes", "/modal/modes = %d is out of range: allowed 1 to %d.",
                            o->modes, RD_MODAL_MODES_MAX);
    if (o->modes > elastic)
        return rd_error_set(err, RD_EINVAL, "/modal/modes",
                            "/modal/modes = %d is more than the %d elastic modes a %d-segment "
                            "ring has (6 n - 6); use more segments or fewer modes.",
                            o->modes, elastic, segments);
    if (!(o->tol >= 1e-15 && o->tol <= 1e-3))
        return rd_error_set(err, RD_EINVAL, "/modal/tolerance",
                            "modal tolerance %g is out of range: allowed 1e-15 to 1e-3.", o->tol);
    if (o->max_iterations < 1 || o->max_iterations > 10000)
        return rd_error_set(err, RD_EINVAL, "/modal/max_iterations",
                            "modal max_iterations %d is out of range: allowed 1 to 10000.",
                            o->max_iterations);
    return RD_OK;
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

/* Deterministic pseudo-random fill in [-1, 1] (xorshift64*). */
static void random_fill(uint64_t *state, int N, double *x)
{
    for (int i = 0; i < N; i++) {
        uint64_t z = *state;
        z ^= z >> 12;
        z ^= z << 25;
        z ^= z >> 27;
        *state = z;
        x[i] = (double)((z * 0x2545F4914F6CDD1DULL) >> 11) / 9007199254740992.0 * 2.0 - 1.0;
    }
}

/* M-orthonormalizes the p columns of X (modified Gram-Schmidt, two passes),
 * MX receives M X.  A column that turns out dependent is replaced by a fresh
 * random vector. */
static void m_orthonormalize(const rd_band *M, int N, int p, double *X, double *MX,
                             uint64_t *rng)
{
    for (int j = 0; j < p; j++) {
        double *x = COL(X, N, j), *mx = COL(MX, N, j);
        for (int attempt = 0; attempt < 4; attempt++) {
            rd_band_symv(M, x, mx);
            double before = sqrt(fabs(dot(N, x, mx)));
            for (int pass = 0; pass < 2; pass++)
                for (int k = 0; k < j; k++) {
                    double c = dot(N, COL(X, N, k), mx);
                    const double *xk = COL(X, N, k), *mxk = COL(MX, N, k);
                    for (int i = 0; i < N; i++) {
                        x[i] -= c * xk[i];
                        mx[i] -= c * mxk[i];
                    }
                }
            double norm = sqrt(fabs(dot(N, x, mx)));
            if (norm > 1e-10 * before && norm > 0.0) {
                for (int i = 0; i < N; i++) {
                    x[i] /= norm;
                    mx[i] /= norm;
                }
                break;
            }
            random_fill(rng, N, x);
        }
    }
}

typedef struct solve_ws {
    rd_band K, M, A;
    double *X, *MX, *KX, *Y, *Kr, *Mr, *lam, *lam_prev;
} solve_ws;

static void ws_cleanup(solve_ws *w)
{
    rd_band_cleanup(&w->K);
    rd_band_cleanup(&w->M);
    rd_band_cleanup(&w->A);
    free(w->X);
    free(w->MX);
    free(w->KX);
    free(w->Y);
    free(w->Kr);
    free(w->Mr);
    free(w->lam);
    free(w->lam_prev);
}

/* Relative residual ||K x - lam M x|| / (|lam| ||M x||); tmp1, tmp2 scratch (N). */
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

static int solve_ring(const rd_ring *ring, const rd_modal_opts *o, const rd_monitor *mon,
                      double prog_lo, double prog_hi, rd_modal_result *out, rd_error *err)
{
    solve_ws w;
    memset(&w, 0, sizeof w);
    memset(out, 0, sizeof *out);
    int rc = RD_OK;
    const int n = rd_ring_get_segments(ring), N = 6 * n;
    const rd_ring_params *prm = rd_ring_get_params(ring);
    out->segments = n;
    out->dof = N;
    out->error_estimate = NAN;

    if ((rc = rd_modal_validate(o, n, err)))
        goto out;
    int want = 6 + o->modes;
    int p = 2 * want > want + 8 ? 2 * want : want + 8;
    if (p > N)
        p = N;
    out->block_size = p;

    if ((rc = rd_ring_assemble_band(ring, &w.K, &w.M, err)))
        goto out;
    if ((rc = rd_band_init(&w.A, N, w.K.kd, err)))
        goto out;
    double f_ref = rd_modal_thin_ring_outplane_hz(prm, 2);
    double lambda_ref = pow(2.0 * M_PI * f_ref, 2);
    double noise = 10.0 * 2.220446049250313e-16 * rd_ring_lambda_max_estimate(ring);
    double tau = sqrt(noise * lambda_ref);
    rd_band_axpby(&w.A, &w.K, lambda_ref, &w.M);
    if ((rc = rd_band_cholesky(&w.A, err)))
        goto out;

    size_t blk = (size_t)N * (size_t)p;
    w.X = malloc(blk * sizeof(double));
    w.MX = malloc(blk * sizeof(double));
    w.KX = malloc(blk * sizeof(double));
    w.Y = malloc(blk * sizeof(double));
    w.Kr = malloc((size_t)p * p * sizeof(double));
    w.Mr = malloc((size_t)p * p * sizeof(double));
    w.lam = malloc((size_t)p * sizeof(double));
    w.lam_prev = malloc((size_t)p * sizeof(double));
    if (!w.X || !w.MX || !w.KX || !w.Y || !w.Kr || !w.Mr || !w.lam || !w.lam_prev) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal solver (%d DOF).", N);
        goto out;
    }
    uint64_t rng = 0x9E3779B97F4A7C15ULL;
    random_fill(&rng, (int)blk, w.X);
    for (int j = 0; j < p; j++)
        w.lam_prev[j] = NAN;

    int converged = 0, rigid = 0, it;
    double worst = INFINITY;
    for (it = 1; it <= o->max_iterations && !converged; it++) {
        /* X <- A^-1 M X */
        for (int j = 0; j < p; j++)
            rd_band_symv(&w.M, COL(w.X, N, j), COL(w.Y, N, j));
        if ((rc = rd_band_solve(&w.A, p, w.Y, err)))
            goto out;
        memcpy(w.X, w.Y, blk * sizeof(double));
        /* From the second iteration on, A^-1 M X of Ritz vectors is nearly
         * M-orthogonal: scaling the columns is enough for a well-conditioned
         * X^T M X.  The random start, or a projected Cholesky that fails,
         * gets a full M-orthonormalization. */
        lapack_int info = 1;
        for (int attempt = it == 1 ? 1 : 0; attempt < 2 && info != 0; attempt++) {
            if (attempt == 1) {
                m_orthonormalize(&w.M, N, p, w.X, w.MX, &rng);
            } else {
                for (int j = 0; j < p; j++) {
                    double *x = COL(w.X, N, j), *mx = COL(w.MX, N, j);
                    rd_band_symv(&w.M, x, mx);
                    double scale = 1.0 / sqrt(fabs(dot(N, x, mx)));
                    for (int i = 0; i < N; i++) {
                        x[i] *= scale;
                        mx[i] *= scale;
                    }
                }
            }
            /* Rayleigh-Ritz */
            for (int j = 0; j < p; j++)
                rd_band_symv(&w.K, COL(w.X, N, j), COL(w.KX, N, j));
            for (int j = 0; j < p; j++)
                for (int i = 0; i <= j; i++) {
                    w.Kr[i + (size_t)j * p] = dot(N, COL(w.X, N, i), COL(w.KX, N, j));
                    w.Mr[i + (size_t)j * p] = dot(N, COL(w.X, N, i), COL(w.MX, N, j));
                }
            info = LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'V', 'U', p, w.Kr, p, w.Mr, p, w.lam);
        }
        if (info != 0) {
            rc = rd_error_set(err, RD_ENUMERIC, "",
                              "The projected eigenproblem failed (LAPACK dsygv info %d) at "
                              "subspace iteration %d.",
                              (int)info, it);
            goto out;
        }
        /* X <- X Q */
        for (int j = 0; j < p; j++) {
            double *y = COL(w.Y, N, j);
            memset(y, 0, (size_t)N * sizeof *y);
            for (int k = 0; k < p; k++) {
                double q = w.Kr[k + (size_t)j * p];
                const double *xk = COL(w.X, N, k);
                for (int i = 0; i < N; i++)
                    y[i] += q * xk[i];
            }
        }
        memcpy(w.X, w.Y, blk * sizeof(double));

        rigid = 0;
        while (rigid < p && w.lam[rigid] < tau)
            rigid++;
        int last = rigid + o->modes, guard = p == N ? 0 : 2;
        worst = 0.0;
        if (last + guard > p) {
            worst = INFINITY; /* too many zero modes for the block: keep iterating */
        } else {
            for (int j = rigid; j < last; j++) {
                double change = fabs(w.lam[j] - w.lam_prev[j]) / (fabs(w.lam[j]) + noise);
                if (!(change <= worst))
                    worst = isnan(change) ? INFINITY : change;
            }
        }
        converged = worst <= o->tol + noise / lambda_ref;
        /* Eigenvalues converge twice as fast as vectors: also ask every wanted
         * vector's residual to reach its noise floor, about eps * lambda_max / lambda. */
        for (int j = rigid; converged && j < last; j++) {
            double res = residual(&w, N, COL(w.X, N, j), w.lam[j], w.KX, w.MX);
            if (!(res <= RESIDUAL_FLOOR * noise / w.lam[j] + o->tol))
                converged = 0;
        }
        memcpy(w.lam_prev, w.lam, (size_t)p * sizeof(double));
        double frac = 1.0 - 1.0 / (1.0 + it);
        if ((rc = rd_monitor_report(mon, prog_lo + (prog_hi - prog_lo) * frac, err)))
            goto out;
    }
    out->iterations = it - 1;
    if (!converged) {
        if (rigid + o->modes > p)
            rc = rd_error_set(err, RD_ENOCONV, "",
                              "The modal solver found %d zero-frequency modes where a free ring "
                              "has 6: the stiffness matrix is degenerate for these inputs.",
                              rigid);
        else
            rc = rd_error_set(err, RD_ENOCONV, "",
                              "The modal solver did not converge in %d subspace iterations "
                              "(%d segments, %d modes): largest relative eigenvalue change %.3g, "
                              "wanted %.3g.",
                              o->max_iterations, n, o->modes, worst, o->tol);
        goto out;
    }

    out->rigid_body_modes = rigid;
    out->modes = calloc((size_t)o->modes, sizeof *out->modes);
    if (!out->modes) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal results.");
        goto out;
    }
    out->n_modes = o->modes;
    for (int e = 0; e < o->modes; e++) {
        int j = rigid + e;
        if ((rc = extract_mode(ring, &w, COL(w.X, N, j), w.lam[j], w.KX, w.MX, &out->modes[e]))) {
            rd_error_set(err, rc, "", "Out of memory for the mode shapes.");
            goto out;
        }
        if (out->modes[e].residual > out->max_residual)
            out->max_residual = out->modes[e].residual;
    }
out:
    ws_cleanup(&w);
    if (rc != RD_OK)
        rd_modal_result_cleanup(out);
    return rc;
}

int rd_modal_solve_ring(const rd_ring *ring, const rd_modal_opts *o, const rd_monitor *mon,
                        rd_modal_result *out, rd_error *err)
{
    return solve_ring(ring, o, mon, 0.0, 1.0, out, err);
}

/* The k-th mode of `kind` in r (k counts from 0), or -1. */
static int nth_of_kind(const rd_modal_result *r, int kind, int k)
{
    for (int i = 0; i < r->n_modes; i++)
        if (r->modes[i].kind == kind && k-- == 0)
            return i;
    return -1;
}

int rd_modal_solve(const rd_ring_params *p, int segments, int closed, const rd_modal_opts *o,
                   const rd_monitor *mon, rd_modal_result *out, rd_error *err)
{
    rd_ring *ring = NULL, *ref_ring = NULL;
    rd_modal_result ref;
    memset(&ref, 0, sizeof ref);
    memset(out, 0, sizeof *out);
    int rc;
    if ((rc = rd_ring_validate(p, segments, closed, err)) || (rc = rd_modal_validate(o, segments, err)))
        goto out;
    /* Reference segment count: 2n (cost x2) unless that exceeds the limit. */
    int m = 2 * segments <= RD_SEGMENTS_MAX ? 2 * segments : segments / 2;
    double w_main = o->estimate_error ? (double)segments / (segments + m) : 1.0;

    if (!(ring = rd_ring_create(p, segments, closed, err))) {
        rc = err ? err->code : RD_ENOMEM;
        goto out;
    }
    if ((rc = solve_ring(ring, o, mon, 0.0, w_main, out, err)))
        goto out;
    if (!o->estimate_error)
        goto out;

    rd_modal_opts ro = *o;
    ro.modes = o->modes + 6 <= RD_MODAL_MODES_MAX ? o->modes + 6 : RD_MODAL_MODES_MAX;
    if (ro.modes > 6 * m - 6)
        ro.modes = 6 * m - 6;
    if (!(ref_ring = rd_ring_create(p, m, closed, err))) {
        rc = err ? err->code : RD_ENOMEM;
        goto out;
    }
    if ((rc = solve_ring(ref_ring, &ro, mon, w_main, 1.0, &ref, err)))
        goto out;
    out->reference_segments = m;
    out->error_estimate = 0.0;
    /* f_n = f_inf (1 + C n^-2): f_inf = (m^2 f_m - n^2 f_n) / (m^2 - n^2). */
    double n2 = (double)segments * segments, m2 = (double)m * m;
    int seen[2] = {0, 0};
    for (int i = 0; i < out->n_modes; i++) {
        rd_mode *md = &out->modes[i];
        int k = nth_of_kind(&ref, md->kind, seen[md->kind]++);
        if (k < 0) {
            out->error_estimate = NAN;
            continue;
        }
        double fn = md->frequency_hz, fm = ref.modes[k].frequency_hz;
        double finf = (m2 * fm - n2 * fn) / (m2 - n2);
        md->frequency_extrapolated_hz = finf;
        md->error_estimate = fabs(fn - finf) / fabs(finf);
        if (!(md->error_estimate <= out->error_estimate) && !isnan(out->error_estimate))
            out->error_estimate = md->error_estimate;
    }
out:
    rd_modal_result_cleanup(&ref);
    rd_ring_free(ring);
    rd_ring_free(ref_ring);
    if (rc != RD_OK)
        rd_modal_result_cleanup(out);
    return rc;
}
