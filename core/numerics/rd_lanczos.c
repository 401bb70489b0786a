/*
 * rd_lanczos — shift-invert block Lanczos with full reorthogonalisation and
 * explicit deflation (contract in rd_lanczos.h).
 *
 * Operator: Op = A^-1 M with A = K + sigma M, sigma > 0, so A is positive
 * definite although K is singular (LAPACK dpbtrf once, dpbtrs per step).  Op
 * is self-adjoint in the M inner product <x, y> = x^T M y; its eigenvalues
 * theta = 1 / (lambda + sigma) put the lowest lambda at the large, well
 * separated end of its spectrum, where Lanczos converges first; the high
 * modes crowd near theta = 0.
 *
 * Deflation: the null vectors Z of K (the ring's rigid-body motions) are
 * eigenvectors of Op with theta = 1/sigma, above every elastic theta.  Left
 * in the Krylov space, their rounding-level copies would keep converging and
 * show up as spurious low modes.  So Z is M-orthonormalized once, each
 * candidate is confirmed as a null vector (||K z|| at the rounding floor),
 * and every new Lanczos vector is M-orthogonalized against Z.
 *
 * Block Lanczos, block size b: M-orthonormal basis q_0, q_1, ...; q_{j+b} is
 * Op q_j M-orthogonalized (two Gram-Schmidt passes: full
 * reorthogonalisation) against Z and q_0 .. q_{j+b-1}.  H(i, j) holds the
 * coefficient of q_i in Op q_j, so T = Q^T M Op Q is banded with half
 * bandwidth b, and after s expanded columns the Ritz pairs (theta, z) of its
 * leading s x s block have the residual
 *     ||Op y - theta y||_M = ||H(s .. s+b-1, 0 .. s-1) z||,   y = Q z,
 * for free.  b = 2 finds both members of the degenerate pairs of a closed
 * ring (single-vector Lanczos sees only one vector of each eigenspace).
 * When the new direction vanishes the Krylov space is invariant and a random
 * vector, orthogonal to all before it, continues the basis.
 *
 * Convergence: when the top pairs' cheap residuals ||Op y - theta y|| / theta
 * are below the floor, their Ritz vectors get one refining step of subspace
 * iteration (polish) and are then checked explicitly, ||K y - lambda M y|| /
 * (lambda ||M y||) <= floor_abs / lambda + tol.  floor_abs is an estimate of
 * the rounding level; residuals that stop falling a little above it (at most
 * STALL_MAX times) are rounding too and are accepted.
 */
#include "rd_lanczos.h"

#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define COL(X, N, j) ((X) + (size_t)(j) * (size_t)(N))
#define HT(w, i, j)  ((w)->H[(size_t)(i) + (size_t)(j) * (size_t)(w)->cap])

/* A new direction shorter than BREAKDOWN times Op q_j (M-norms) is rounding
 * noise of an invariant Krylov space, not a direction of Op. */
#define BREAKDOWN 1e-8
/* Explicit residuals that stall (fall less than 2x between checks) are
 * accepted up to this multiple of their floor estimate. */
#define STALL_MAX 100.0
/* The whole basis is kept (full reorthogonalisation): at most this many
 * vectors, 2 x 58 MB at the largest part (6000 DOF).  Convergence of 60
 * modes takes about 130. */
#define BASIS_MAX 600

typedef struct lz {
    const rd_lanczos_problem *pb;
    int N, b, cap, k, r;           /* basis capacity and size; deflated null vectors */
    int D;                         /* N - r: dimension of the deflated space */
    double prev_expl;              /* largest explicit residual / floor at the previous check */
    rd_band A;                     /* Cholesky factor of K + sigma M */
    double *Z, *MZ;                /* N x r: null vectors, M-orthonormal, and M Z */
    double *Q, *MQ;                /* N x cap: Lanczos basis and M Q */
    double *H;                     /* cap x cap */
    double *v, *mv, *coef;         /* N, N, cap: work vector, M v, its coefficients */
    double *theta, *S, *ab;        /* Ritz values and vectors of T_s, T_s in band storage */
    double *t1, *t2;               /* N scratch */
    double *X, *KX, *MX, *Kr, *Mr; /* polish: N x want (three), want x want (two) */
    uint64_t rng;
} lz;

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

static void lz_cleanup(lz *w)
{
    rd_band_cleanup(&w->A);
    free(w->Z);
    free(w->MZ);
    free(w->Q);
    free(w->MQ);
    free(w->H);
    free(w->v);
    free(w->mv);
    free(w->coef);
    free(w->theta);
    free(w->S);
    free(w->ab);
    free(w->t1);
    free(w->t2);
    free(w->X);
    free(w->KX);
    free(w->MX);
    free(w->Kr);
    free(w->Mr);
}

void rd_lanczos_result_cleanup(rd_lanczos_result *r)
{
    if (!r)
        return;
    free(r->lambda);
    free(r->x);
    memset(r, 0, sizeof *r);
}

/* x -= sum_i <v_i, x>_M v_i over the m columns of V (MV = M V), adding the
 * coefficients to coef when it is not NULL. */
static void project_out(int N, int m, const double *V, const double *MV, double *x, double *coef)
{
    for (int i = 0; i < m; i++) {
        double c = dot(N, COL(MV, N, i), x);
        const double *vi = COL(V, N, i);
        for (int t = 0; t < N; t++)
            x[t] -= c * vi[t];
        if (coef)
            coef[i] += c;
    }
}

/* M-orthogonalizes w->v against Z and the basis (two passes), fills w->mv =
 * M v and returns ||v||_M.  With `record`, w->coef[0 .. k-1] gets the
 * coefficients along the basis. */
static double orthogonalize(lz *w, int record)
{
    const int N = w->N;
    if (record)
        memset(w->coef, 0, (size_t)w->k * sizeof *w->coef);
    for (int pass = 0; pass < 2; pass++) {
        project_out(N, w->r, w->Z, w->MZ, w->v, NULL);
        project_out(N, w->k, w->Q, w->MQ, w->v, record ? w->coef : NULL);
    }
    rd_band_symv(w->pb->M, w->v, w->mv);
    double nn = dot(N, w->v, w->mv);
    return nn > 0.0 ? sqrt(nn) : 0.0;
}

/* Appends v / beta (and M v / beta) to the basis. */
static void append(lz *w, double beta)
{
    const int N = w->N;
    double *q = COL(w->Q, N, w->k), *mq = COL(w->MQ, N, w->k);
    for (int t = 0; t < N; t++) {
        q[t] = w->v[t] / beta;
        mq[t] = w->mv[t] / beta;
    }
    w->k++;
}

/* Appends a random vector orthogonal to Z and the basis.  Returns 0, or -1
 * when no new direction is left (the basis spans the deflated space). */
static int append_random(lz *w)
{
    for (int attempt = 0; attempt < 8; attempt++) {
        random_fill(&w->rng, w->N, w->v);
        rd_band_symv(w->pb->M, w->v, w->mv);
        double before = sqrt(dot(w->N, w->v, w->mv));
        double after = orthogonalize(w, 0);
        if (after > 1e-3 * before) {
            append(w, after);
            return 0;
        }
    }
    return -1;
}

/* M-orthonormalizes the candidate null vectors into Z and keeps those with
 * ||K z|| <= floor_abs ||M z|| (a rigid motion gives rounding only). */
static void deflate_null(lz *w)
{
    const rd_lanczos_problem *pb = w->pb;
    const int N = w->N;
    w->r = 0;
    for (int j = 0; j < pb->r; j++) {
        double *z = COL(w->Z, N, w->r), *mz = COL(w->MZ, N, w->r);
        memcpy(z, COL(pb->null, N, j), (size_t)N * sizeof *z);
        rd_band_symv(pb->M, z, mz);
        double before = sqrt(dot(N, z, mz));
        for (int pass = 0; pass < 2; pass++)
            project_out(N, w->r, w->Z, w->MZ, z, NULL);
        rd_band_symv(pb->M, z, mz);
        double norm = sqrt(fabs(dot(N, z, mz)));
        if (!(norm > 1e-8 * before))
            continue; /* dependent on the ones before */
        for (int t = 0; t < N; t++) {
            z[t] /= norm;
            mz[t] /= norm;
        }
        rd_band_symv(pb->K, z, w->t1);
        if (sqrt(dot(N, w->t1, w->t1)) <= pb->floor_abs * sqrt(dot(N, mz, mz)))
            w->r++;
    }
}

static int lz_alloc(lz *w, rd_error *err)
{
    const int N = w->N;
    size_t cap = (size_t)w->cap, r = (size_t)(w->pb->r > 0 ? w->pb->r : 1);
    if (cap > SIZE_MAX / sizeof(double) / (size_t)N / 2)
        return rd_error_set(err, RD_ELIMIT, "", "The Lanczos basis (%d x %d) is too large.", N,
                            w->cap);
    w->Z = malloc((size_t)N * r * sizeof(double));
    w->MZ = malloc((size_t)N * r * sizeof(double));
    w->Q = malloc((size_t)N * cap * sizeof(double));
    w->MQ = malloc((size_t)N * cap * sizeof(double));
    w->H = calloc(cap * cap, sizeof(double));
    w->v = malloc((size_t)N * sizeof(double));
    w->mv = malloc((size_t)N * sizeof(double));
    w->t1 = malloc((size_t)N * sizeof(double));
    w->t2 = malloc((size_t)N * sizeof(double));
    w->coef = malloc(cap * sizeof(double));
    w->theta = malloc(cap * sizeof(double));
    w->S = malloc(cap * cap * sizeof(double));
    w->ab = malloc(3 * cap * sizeof(double));
    size_t want = (size_t)(w->pb->want > 0 ? w->pb->want : 1);
    w->X = malloc((size_t)N * want * sizeof(double));
    w->KX = malloc((size_t)N * want * sizeof(double));
    w->MX = malloc((size_t)N * want * sizeof(double));
    w->Kr = malloc(want * want * sizeof(double));
    w->Mr = malloc(want * want * sizeof(double));
    if (!w->Z || !w->MZ || !w->Q || !w->MQ || !w->H || !w->v || !w->mv || !w->t1 || !w->t2 ||
        !w->coef || !w->theta || !w->S || !w->ab || !w->X || !w->KX || !w->MX || !w->Kr || !w->Mr)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the Lanczos basis (%d x %d).", N,
                            w->cap);
    return RD_OK;
}

/* Expands column j: v = Op q_j orthogonalized, H(., j), and the next basis
 * vector (or a random one after a breakdown). */
static int expand(lz *w, int j, rd_error *err)
{
    const int N = w->N;
    memcpy(w->v, COL(w->MQ, N, j), (size_t)N * sizeof *w->v);
    int rc = rd_band_solve(&w->A, 1, w->v, err);
    if (rc)
        return rc;
    double beta = orthogonalize(w, 1), before = beta * beta;
    for (int i = 0; i < w->k; i++) {
        HT(w, i, j) = w->coef[i];
        before += w->coef[i] * w->coef[i];
    }
    if (w->k >= w->cap)
        return RD_OK; /* the basis spans the deflated space (or the step budget) */
    if (beta > BREAKDOWN * sqrt(before)) {
        HT(w, w->k, j) = beta;
        append(w, beta);
    } else if (append_random(w) != 0) {
        w->cap = w->k;
    }
    return RD_OK;
}

/* Ritz pairs of the leading s x s block of T (LAPACK dsbev), ascending. */
static int ritz(lz *w, int s, rd_error *err)
{
    int kd = w->b < s - 1 ? w->b : s - 1, ld = kd + 1;
    for (int j = 0; j < s; j++)
        for (int i = j - kd < 0 ? 0 : j - kd; i <= j; i++)
            w->ab[(kd + i - j) + j * ld] = i == j ? HT(w, i, i) : 0.5 * (HT(w, i, j) + HT(w, j, i));
    lapack_int info =
        LAPACKE_dsbev(LAPACK_COL_MAJOR, 'V', 'U', s, kd, w->ab, ld, w->theta, w->S, s);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "The projected Lanczos eigenproblem failed (LAPACK dsbev info %d, "
                            "size %d).",
                            (int)info, s);
    return RD_OK;
}

/* ||Op y - theta y||_M of Ritz vector p of T_s. */
static double cheap_residual(const lz *w, int s, int p)
{
    double rr = 0.0;
    for (int i = s; i < w->k && i < s + w->b; i++) {
        double c = 0.0;
        for (int j = i - w->b < 0 ? 0 : i - w->b; j < s; j++)
            c += HT(w, i, j) * w->S[j + (size_t)p * s];
        rr += c * c;
    }
    return sqrt(rr);
}

/* ||K y - lambda M y|| / (lambda ||M y||). */
static double explicit_residual(lz *w, const double *y, double lambda)
{
    rd_band_symv(w->pb->K, y, w->t1);
    rd_band_symv(w->pb->M, y, w->t2);
    double rr = 0.0;
    for (int t = 0; t < w->N; t++) {
        double d = w->t1[t] - lambda * w->t2[t];
        rr += d * d;
    }
    return sqrt(rr) / (fabs(lambda) * sqrt(dot(w->N, w->t2, w->t2)));
}

/* One step of subspace iteration on the Ritz vectors out->x (m of them):
 * X = A^-1 M Y, deflated, then Rayleigh-Ritz (X^T K X) C = (X^T M X) C L
 * (LAPACK dsygv), Y = X C.  A Ritz vector is a sum of s basis vectors, each
 * carrying rounding along the stiff high modes, which K amplifies by up to
 * lambda_max; one application of A^-1 damps those by (lambda + sigma) /
 * (lambda_high + sigma), so the residual drops to the rounding level of a
 * single solve. */
static int polish(lz *w, int m, rd_lanczos_result *out, rd_error *err)
{
    const int N = w->N;
    for (int e = 0; e < m; e++)
        rd_band_symv(w->pb->M, COL(out->x, N, e), COL(w->X, N, e));
    int rc = rd_band_solve(&w->A, m, w->X, err);
    if (rc)
        return rc;
    for (int e = 0; e < m; e++) {
        double *x = COL(w->X, N, e);
        for (int pass = 0; pass < 2; pass++)
            project_out(N, w->r, w->Z, w->MZ, x, NULL);
        /* M-normalized: A^-1 shrinks mode j by 1 / (lambda_j + sigma), and
         * unscaled columns would make X^T M X as ill-conditioned as A */
        double *mx = COL(w->MX, N, e);
        rd_band_symv(w->pb->M, x, mx);
        double scale = 1.0 / sqrt(dot(N, x, mx));
        for (int t = 0; t < N; t++) {
            x[t] *= scale;
            mx[t] *= scale;
        }
        rd_band_symv(w->pb->K, x, COL(w->KX, N, e));
    }
    for (int j = 0; j < m; j++)
        for (int i = 0; i <= j; i++) {
            w->Kr[i + (size_t)j * m] = dot(N, COL(w->X, N, i), COL(w->KX, N, j));
            w->Mr[i + (size_t)j * m] = dot(N, COL(w->X, N, i), COL(w->MX, N, j));
        }
    lapack_int info =
        LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'V', 'U', m, w->Kr, m, w->Mr, m, out->lambda);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "The Ritz refinement failed (LAPACK dsygv info %d, %d vectors).",
                            (int)info, m);
    for (int e = 0; e < m; e++) {
        double *y = COL(out->x, N, e);
        memset(y, 0, (size_t)N * sizeof *y);
        for (int j = 0; j < m; j++) {
            double c = w->Kr[j + (size_t)e * m];
            const double *x = COL(w->X, N, j);
            for (int t = 0; t < N; t++)
                y[t] += c * x[t];
        }
    }
    return RD_OK;
}

/* Checks the wanted pairs after s expanded columns: returns 1 (and fills
 * out->lambda, out->x) when all passed, 0 when more steps are needed. */
static int check(lz *w, int s, rd_lanczos_result *out, rd_error *err)
{
    const rd_lanczos_problem *pb = w->pb;
    int rc = ritz(w, s, err);
    if (rc)
        return rc;
    int zeros = 0, found = 0;
    out->worst = 0.0;
    for (int p = s - 1; p >= 0 && found < pb->want; p--) {
        double lambda = 1.0 / w->theta[p] - pb->shift;
        if (lambda < pb->zero) {
            zeros++;
            continue;
        }
        double floor = pb->floor_abs / lambda + pb->tol;
        double ratio = cheap_residual(w, s, p) / w->theta[p] / floor;
        if (!(ratio <= out->worst))
            out->worst = isnan(ratio) ? INFINITY : ratio;
        out->lambda[found++] = lambda;
    }
    if (found < pb->want)
        out->worst = INFINITY; /* not enough Ritz values yet */
    if (!(out->worst <= 1.0))
        return 0;
    for (int e = 0, p = s - 1 - zeros; e < found; e++, p--) {
        double *y = COL(out->x, w->N, e);
        memset(y, 0, (size_t)w->N * sizeof *y);
        for (int j = 0; j < s; j++) {
            double c = w->S[j + (size_t)p * s];
            const double *q = COL(w->Q, w->N, j);
            for (int t = 0; t < w->N; t++)
                y[t] += c * q[t];
        }
    }
    if ((rc = polish(w, found, out, err)))
        return rc;
    double expl = 0.0;
    for (int e = 0; e < found; e++) {
        double ratio = explicit_residual(w, COL(out->x, w->N, e), out->lambda[e]) /
                       (pb->floor_abs / out->lambda[e] + pb->tol);
        if (!(ratio <= expl))
            expl = isnan(ratio) ? INFINITY : ratio;
    }
    /* Accepted: residuals at the floor; or a basis that spans the whole
     * deflated space (a dense solve: nothing left to converge); or residuals
     * that stopped falling between checks while the Krylov residuals are
     * below the floor: rounding, a little above the floor's estimate. */
    int stalled = expl <= STALL_MAX && expl > 0.5 * w->prev_expl;
    w->prev_expl = expl;
    out->worst = expl;
    if (!(expl <= 1.0 || (s == w->k && w->k >= w->D) || stalled))
        return 0;
    out->zeros = zeros;
    out->found = found;
    return 1;
}

/* Factors A, deflates the null vectors, starts the basis with b random vectors. */
static int start(lz *w, rd_lanczos_result *out, rd_error *err)
{
    const rd_lanczos_problem *pb = w->pb;
    int rc;
    if ((rc = rd_band_init(&w->A, w->N, pb->K->kd, err)))
        return rc;
    rd_band_axpby(&w->A, pb->K, pb->shift, pb->M);
    if ((rc = rd_band_cholesky(&w->A, err)))
        return rc;
    deflate_null(w);
    out->deflated = w->r;
    w->D = w->N - w->r;
    if (pb->want < 1 || pb->want > w->D)
        return rd_error_set(err, RD_EINTERNAL, "",
                            "Lanczos asked for %d eigenpairs of a %d-dimensional space.", pb->want,
                            w->D);
    if (w->cap > w->D)
        w->cap = w->D;
    out->lambda = malloc((size_t)pb->want * sizeof *out->lambda);
    out->x = malloc((size_t)w->N * (size_t)pb->want * sizeof *out->x);
    if (!out->lambda || !out->x)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d eigenvectors.", pb->want);
    w->rng = 0x9E3779B97F4A7C15ULL;
    w->prev_expl = INFINITY;
    for (int c = 0; c < w->b && w->k < w->cap; c++)
        if (append_random(w) != 0)
            break;
    return RD_OK;
}

int rd_lanczos_solve(const rd_lanczos_problem *pb, rd_lanczos_result *out, rd_error *err)
{
    lz w;
    memset(&w, 0, sizeof w);
    memset(out, 0, sizeof *out);
    w.pb = pb;
    w.N = pb->K->n;
    w.b = pb->block == 2 ? 2 : 1;
    int max_steps = pb->max_steps < 1 ? 1 : pb->max_steps > BASIS_MAX ? BASIS_MAX : pb->max_steps;
    w.cap = max_steps + w.b;
    if (w.cap > w.N)
        w.cap = w.N;
    int rc = lz_alloc(&w, err);
    if (rc == RD_OK)
        rc = start(&w, out, err);
    int s = 0, next = pb->want + w.b, done = 0;
    while (rc == RD_OK && !done && s < max_steps && s < w.k) {
        if ((rc = expand(&w, s, err)))
            break;
        s++;
        double frac = 1.0 - 1.0 / (1.0 + s / 8.0);
        if ((rc = rd_monitor_report(pb->mon, pb->mon_lo + (pb->mon_hi - pb->mon_lo) * frac, err)))
            break;
        if (s >= next || s == w.k || s == max_steps) {
            rc = check(&w, s, out, err);
            done = rc == 1;
            rc = rc == 1 ? RD_OK : rc;
            next = s + 1 + s / 8;
        }
    }
    out->steps = s;
    if (rc == RD_OK && !done)
        rc = rd_error_set(err, RD_ENOCONV, "",
                          "The Lanczos solver did not converge in %d steps: the largest residual "
                          "is %.3g times its rounding floor.",
                          s, out->worst);
    lz_cleanup(&w);
    if (rc != RD_OK) {
        double worst = out->worst;
        int steps = out->steps;
        rd_lanczos_result_cleanup(out);
        out->worst = worst;
        out->steps = steps;
    }
    return rc;
}
