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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_accuracy.h"
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
    int N, p;              /* DOF, block size */
    double noise;          /* Rayleigh-quotient rounding level, 10 eps lambda_max */
    double lambda_ref;     /* shift: first thin-ring eigenvalue */
    double tau;            /* rigid-body threshold sqrt(noise lambda_ref) */
    uint64_t rng;
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

/* Assembles K and M, factors A = K + lambda_ref M, allocates the block of p
 * vectors and fills it at random. */
static int setup(const rd_ring *ring, int p, solve_ws *w, rd_error *err)
{
    int rc;
    const int N = w->N;
    if ((rc = rd_ring_assemble_band(ring, &w->K, &w->M, err)))
        return rc;
    if ((rc = rd_band_init(&w->A, N, w->K.kd, err)))
        return rc;
    double f_ref = rd_modal_thin_ring_outplane_hz(rd_ring_get_params(ring), 2);
    w->lambda_ref = pow(2.0 * M_PI * f_ref, 2);
    w->noise = 10.0 * 2.220446049250313e-16 * rd_ring_lambda_max_estimate(ring);
    w->tau = sqrt(w->noise * w->lambda_ref);
    rd_band_axpby(&w->A, &w->K, w->lambda_ref, &w->M);
    if ((rc = rd_band_cholesky(&w->A, err)))
        return rc;

    size_t blk = (size_t)N * (size_t)p;
    w->X = malloc(blk * sizeof(double));
    w->MX = malloc(blk * sizeof(double));
    w->KX = malloc(blk * sizeof(double));
    w->Y = malloc(blk * sizeof(double));
    w->Kr = malloc((size_t)p * p * sizeof(double));
    w->Mr = malloc((size_t)p * p * sizeof(double));
    w->lam = malloc((size_t)p * sizeof(double));
    w->lam_prev = malloc((size_t)p * sizeof(double));
    if (!w->X || !w->MX || !w->KX || !w->Y || !w->Kr || !w->Mr || !w->lam || !w->lam_prev)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal solver (%d DOF).", N);
    w->rng = 0x9E3779B97F4A7C15ULL;
    random_fill(&w->rng, (int)blk, w->X);
    for (int j = 0; j < p; j++)
        w->lam_prev[j] = NAN;
    return RD_OK;
}

/* Rayleigh-Ritz on the block X (columns M-normalized, MX = M X): solves
 * (X^T K X) Q = (X^T M X) Q Lambda into Kr (Q) and lam.  Returns LAPACK's info. */
static lapack_int rayleigh_ritz(solve_ws *w)
{
    const int N = w->N, p = w->p;
    for (int j = 0; j < p; j++)
        rd_band_symv(&w->K, COL(w->X, N, j), COL(w->KX, N, j));
    for (int j = 0; j < p; j++)
        for (int i = 0; i <= j; i++) {
            w->Kr[i + (size_t)j * p] = dot(N, COL(w->X, N, i), COL(w->KX, N, j));
            w->Mr[i + (size_t)j * p] = dot(N, COL(w->X, N, i), COL(w->MX, N, j));
        }
    return LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'V', 'U', p, w->Kr, p, w->Mr, p, w->lam);
}

/* One subspace iteration: X <- A^-1 M X, Rayleigh-Ritz, X <- X Q. */
static int iterate(solve_ws *w, int it, rd_error *err)
{
    const int N = w->N, p = w->p;
    size_t blk = (size_t)N * (size_t)p;
    int rc;
    for (int j = 0; j < p; j++)
        rd_band_symv(&w->M, COL(w->X, N, j), COL(w->Y, N, j));
    if ((rc = rd_band_solve(&w->A, p, w->Y, err)))
        return rc;
    memcpy(w->X, w->Y, blk * sizeof(double));
    /* From the second iteration on, A^-1 M X of Ritz vectors is nearly
     * M-orthogonal: scaling the columns is enough for a well-conditioned
     * X^T M X.  The random start, or a projected Cholesky that fails, gets a
     * full M-orthonormalization. */
    lapack_int info = 1;
    for (int attempt = it == 1 ? 1 : 0; attempt < 2 && info != 0; attempt++) {
        if (attempt == 1) {
            m_orthonormalize(&w->M, N, p, w->X, w->MX, &w->rng);
        } else {
            for (int j = 0; j < p; j++) {
                double *x = COL(w->X, N, j), *mx = COL(w->MX, N, j);
                rd_band_symv(&w->M, x, mx);
                double scale = 1.0 / sqrt(fabs(dot(N, x, mx)));
                for (int i = 0; i < N; i++) {
                    x[i] *= scale;
                    mx[i] *= scale;
                }
            }
        }
        info = rayleigh_ritz(w);
    }
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "The projected eigenproblem failed (LAPACK dsygv info %d) at "
                            "subspace iteration %d.",
                            (int)info, it);
    for (int j = 0; j < p; j++) {
        double *y = COL(w->Y, N, j);
        memset(y, 0, (size_t)N * sizeof *y);
        for (int k = 0; k < p; k++) {
            double q = w->Kr[k + (size_t)j * p];
            const double *xk = COL(w->X, N, k);
            for (int i = 0; i < N; i++)
                y[i] += q * xk[i];
        }
    }
    memcpy(w->X, w->Y, blk * sizeof(double));
    return RD_OK;
}

/* Counts the rigid modes (Ritz values below tau) into *rigid and returns 1
 * when the wanted elastic modes have converged: relative eigenvalue change
 * <= tol (largest change in *worst), and residuals at their noise floor,
 * about eps lambda_max / lambda (eigenvalues converge twice as fast as
 * vectors). */
static int converged(solve_ws *w, const rd_modal_opts *o, int *rigid, double *worst)
{
    const int N = w->N, p = w->p;
    int r = 0;
    while (r < p && w->lam[r] < w->tau)
        r++;
    *rigid = r;
    int last = r + o->modes, guard = p == N ? 0 : 2;
    if (last + guard > p) {
        *worst = INFINITY; /* too many zero modes for the block: keep iterating */
        return 0;
    }
    *worst = 0.0;
    for (int j = r; j < last; j++) {
        double change = fabs(w->lam[j] - w->lam_prev[j]) / (fabs(w->lam[j]) + w->noise);
        if (!(change <= *worst))
            *worst = isnan(change) ? INFINITY : change;
    }
    if (!(*worst <= o->tol + w->noise / w->lambda_ref))
        return 0;
    for (int j = r; j < last; j++) {
        double res = residual(w, N, COL(w->X, N, j), w->lam[j], w->KX, w->MX);
        if (!(res <= RESIDUAL_FLOOR * w->noise / w->lam[j] + o->tol))
            return 0;
    }
    return 1;
}

/* The failure message of an unconverged solve. */
static int no_convergence(const solve_ws *w, const rd_modal_opts *o, int n, int rigid,
                          double worst, rd_error *err)
{
    if (rigid + o->modes > w->p)
        return rd_error_set(err, RD_ENOCONV, "",
                            "The modal solver found %d zero-frequency modes where a free ring "
                            "has 6: the stiffness matrix is degenerate for these inputs.",
                            rigid);
    return rd_error_set(err, RD_ENOCONV, "",
                        "The modal solver did not converge in %d subspace iterations "
                        "(%d segments, %d modes): largest relative eigenvalue change %.3g, "
                        "wanted %.3g.",
                        o->max_iterations, n, o->modes, worst, o->tol);
}

/* Fills out->modes from the converged Ritz vectors after the rigid ones. */
static int collect_modes(const rd_ring *ring, solve_ws *w, int rigid, int modes,
                         rd_modal_result *out, rd_error *err)
{
    out->rigid_body_modes = rigid;
    out->modes = calloc((size_t)modes, sizeof *out->modes);
    if (!out->modes)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal results.");
    out->n_modes = modes;
    for (int e = 0; e < modes; e++) {
        int j = rigid + e;
        int rc = extract_mode(ring, w, COL(w->X, w->N, j), w->lam[j], w->KX, w->MX, &out->modes[e]);
        if (rc)
            return rd_error_set(err, rc, "", "Out of memory for the mode shapes.");
        if (out->modes[e].residual > out->max_residual)
            out->max_residual = out->modes[e].residual;
    }
    return RD_OK;
}

static int solve_ring(const rd_ring *ring, const rd_modal_opts *o, const rd_monitor *mon,
                      rd_modal_result *out, rd_error *err)
{
    solve_ws w;
    memset(&w, 0, sizeof w);
    memset(out, 0, sizeof *out);
    int rc = RD_OK;
    const int n = rd_ring_get_segments(ring), N = 6 * n;
    out->segments = n;
    out->dof = N;
    out->error_estimate = NAN;

    if ((rc = rd_modal_validate(o, n, err)))
        goto out;
    int want = 6 + o->modes;
    int p = 2 * want > want + 8 ? 2 * want : want + 8;
    w.N = N;
    w.p = out->block_size = p > N ? N : p;
    if ((rc = setup(ring, w.p, &w, err)))
        goto out;

    int done = 0, rigid = 0, it;
    double worst = INFINITY;
    for (it = 1; it <= o->max_iterations && !done; it++) {
        if ((rc = iterate(&w, it, err)))
            goto out;
        done = converged(&w, o, &rigid, &worst);
        memcpy(w.lam_prev, w.lam, (size_t)w.p * sizeof(double));
        if ((rc = rd_monitor_report(mon, 1.0 - 1.0 / (1.0 + it), err)))
            goto out;
    }
    out->iterations = it - 1;
    if (!done) {
        rc = no_convergence(&w, o, n, rigid, worst, err);
        goto out;
    }
    rc = collect_modes(ring, &w, rigid, o->modes, out, err);
out:
    ws_cleanup(&w);
    if (rc != RD_OK)
        rd_modal_result_cleanup(out);
    return rc;
}

int rd_modal_solve_ring(const rd_ring *ring, const rd_modal_opts *o, const rd_monitor *mon,
                        rd_modal_result *out, rd_error *err)
{
    return solve_ring(ring, o, mon, out, err);
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
    if (level == 1) {
        ro.modes = L->o->modes + 6 <= RD_MODAL_MODES_MAX ? L->o->modes + 6 : RD_MODAL_MODES_MAX;
        if (ro.modes > 6 * L->n[1] - 6)
            ro.modes = 6 * L->n[1] - 6;
    }
    rd_ring *ring = rd_ring_create(L->p, L->n[level], L->closed, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    int rc = solve_ring(ring, &ro, mon, L->res[level], err);
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
        md->frequency_extrapolated_hz = rd_accuracy_richardson(
            md->frequency_hz, L->n[0], ref->modes[k].frequency_hz, L->n[1], 2.0, &md->error_estimate);
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
    if ((rc = rd_ring_validate(p, segments, closed, err)) || (rc = rd_modal_validate(o, segments, err)))
        return rc;
    int m = rd_accuracy_refined_segments(segments, RD_SEGMENTS_MAX);
    char what[48];
    snprintf(what, sizeof what, "%d segments", m);
    modal_levels L = {p, {segments, m}, closed, o, {out, &ref}};
    rd_accuracy_plan plan = {level_solve, level_compare, &L, o->estimate_error,
                             (double)segments / (segments + m), what};
    rc = rd_accuracy_run(&plan, mon, NULL, err);
    rd_modal_result_cleanup(&ref);
    if (rc != RD_OK)
        rd_modal_result_cleanup(out);
    return rc;
}
