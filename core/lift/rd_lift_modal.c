/*
 * rd_lift_modal.c — the modal lift model (issue 10, numerics.model =
 * "modal"): the full model (rd_lift_model.c) reduced to the ring's 6 rigid-
 * body modes and its m lowest elastic modes, for scenes whose lift varies
 * around the ring (friction on the split ring, and later distorted bores and
 * tilted grooves), where the rigid ring (rd_lift_rigid.c) is not enough.
 *
 * Modes.  The free split ring's K phi = w^2 M phi with K the full model's
 * band stiffness and M its block-diagonal segment masses M_i.  With
 * M_i = L_i L_i^T (Cholesky) the problem is the standard symmetric
 * A z = w^2 z, A = L^-1 K L^-T (dense, N = 6 n), whose r = 6 + m lowest
 * pairs come from LAPACK dsyevr (range by index: O(N^3) for the reduction,
 * so n is bounded by RD_LIFT_MODAL_SEGMENTS_MAX: 200 segments take ~1 s);
 * phi = L^-T z, so Phi^T M Phi = I.  The six lowest are the rigid-body
 * motions (w^2 at rounding level, set to 0).  A modes with the full 6 n is a
 * change of coordinates: the full model exactly.
 *
 * Unknowns x (r modal coordinates, m sqrt(kg)) and their rates; the full
 * model's segment states are q = Phi x, v = Phi x', and the equations are its
 * Galerkin projection:
 *     x'' = Phi^T f(t, Phi x, Phi x') - Lambda x,   Lambda = diag(w_a^2).
 * f is the full model's force elements evaluated on every segment
 * (rd_lift_forces: contacts, friction, gas per segment), so whatever varies
 * around the ring is kept up to the resolution of m modes.  Jacobian
 *     d x''/dx = sum_i Phi_i^T (df_i/dq_i) Phi_i - Lambda,
 *     d x''/dx' = sum_i Phi_i^T (df_i/dv_i) Phi_i,
 * into a dense 2 r Newton matrix (CVODE's dense LU).
 *
 * Tolerances: coordinate a moves a segment by at most s_a |x_a|, s_a the
 * largest of its translations and R x its rotations over the segments; its
 * atol is the full model's atol / s_a (rates: x w_v, rd_lift_driver.c).
 * Outputs (lift per segment, twist, friction, events) are the full model's,
 * on the expanded state.
 */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>

#include "rd_lift_model.h"

#define RIGID_MODES    6
#define CORRECTIONS    4    /* shapes added to the modes (correction_shapes) */
#define SHIFT_FRACTION 1e-6 /* sigma / first elastic eigenvalue of the static solves */
#define GS_DROP \
    1e-6 /* a correction shape whose M-norm falls below this\n                             * fraction by orthogonalisation is in the span already */

typedef struct modal {
    rd_lift_model *m;
    int r;           /* 6 + elastic modes */
    size_t N;        /* 6 n */
    double *Phi;     /* N x r, row-major: row 6 i + k = segment i's DOF k */
    double *lam;     /* r: w_a^2, 1/s^2 */
    double *scale;   /* r: largest displacement per unit coordinate, m */
    double *full;    /* 12 n: the expanded state */
    double *T;       /* 6 x r scratch */
    double *Gq, *Gv; /* r x r */
} modal;

static void modal_free(modal *s)
{
    if (!s)
        return;
    free(s->Phi);
    free(s->lam);
    free(s->scale);
    free(s->full);
    free(s->T);
    free(s->Gq);
    free(s->Gv);
    free(s);
}

/* The full state (q, v per segment) of y = (x, x'). */
static void expand_state(const modal *s, const double *y, double *full)
{
    int r = s->r;
    for (int i = 0; i < s->m->n; i++) {
        double *q = RD_LIFT_Q(full, i), *v = RD_LIFT_V(full, i);
        for (int k = 0; k < 6; k++) {
            const double *row = s->Phi + (6 * (size_t)i + k) * r;
            double a = 0.0, b = 0.0;
            for (int j = 0; j < r; j++) {
                a += row[j] * y[j];
                b += row[j] * y[r + j];
            }
            q[k] = a;
            v[k] = b;
        }
    }
}

static int modal_rhs(sunrealtype t, N_Vector yv, N_Vector ydv, void *user)
{
    modal *s = user;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydv);
    int r = s->r;
    expand_state(s, y, s->full);
    rd_lift_forces(s->m, t, s->full, NULL, NULL);
    for (int a = 0; a < r; a++) {
        yd[a] = y[r + a];
        yd[r + a] = -s->lam[a] * y[a];
    }
    for (size_t j = 0; j < s->N; j++) {
        const double *row = s->Phi + j * r;
        double f = s->m->fbuf[j];
        for (int a = 0; a < r; a++)
            yd[r + a] += row[a] * f;
    }
    for (int j = 0; j < 2 * r; j++)
        if (!isfinite(yd[j]))
            return 1; /* recoverable: CVODE retries with a smaller step */
    return 0;
}

/* G += Phi_i^T D Phi_i for segment i's 6x6 block D. */
static void project_block(modal *s, int i, const double *D, double *G)
{
    int r = s->r;
    const double *P = s->Phi + 6 * (size_t)i * r;
    for (int k = 0; k < 6; k++)
        for (int b = 0; b < r; b++) {
            double v = 0.0;
            for (int l = 0; l < 6; l++)
                v += D[6 * k + l] * P[l * r + b];
            s->T[k * r + b] = v;
        }
    for (int a = 0; a < r; a++)
        for (int b = 0; b < r; b++) {
            double v = 0.0;
            for (int k = 0; k < 6; k++)
                v += P[k * r + a] * s->T[k * r + b];
            G[a * r + b] += v;
        }
}

static int modal_jac(sunrealtype t, N_Vector yv, N_Vector fy, SUNMatrix J, void *user, N_Vector t1,
                     N_Vector t2, N_Vector t3)
{
    (void)fy;
    (void)t1;
    (void)t2;
    (void)t3;
    modal *s = user;
    rd_lift_model *m = s->m;
    int r = s->r;
    expand_state(s, N_VGetArrayPointer(yv), s->full);
    rd_lift_forces(m, t, s->full, m->Dq, m->Dv);
    memset(s->Gq, 0, (size_t)r * r * sizeof *s->Gq);
    memset(s->Gv, 0, (size_t)r * r * sizeof *s->Gv);
    for (int i = 0; i < m->n; i++) {
        project_block(s, i, m->Dq + 36 * (size_t)i, s->Gq);
        project_block(s, i, m->Dv + 36 * (size_t)i, s->Gv);
    }
    if (SUNMatZero(J))
        return -1;
    for (int a = 0; a < r; a++) {
        SM_ELEMENT_D(J, a, r + a) = 1.0;
        for (int b = 0; b < r; b++) {
            SM_ELEMENT_D(J, r + a, b) = s->Gq[a * r + b] - (a == b ? s->lam[a] : 0.0);
            SM_ELEMENT_D(J, r + a, r + b) = s->Gv[a * r + b];
        }
    }
    return 0;
}

static double modal_lift(void *user, const double *y, double *seg)
{
    modal *s = user;
    expand_state(s, y, s->full);
    return rd_lift_model_mean_lift(s->m, s->full, seg);
}

static void modal_loads(void *user, double t, const double *y)
{
    modal *s = user;
    expand_state(s, y, s->full);
    rd_lift_forces(s->m, t, s->full, NULL, NULL);
}

static void modal_expand(void *user, const double *y, double *full)
{
    expand_state(user, y, full);
}

/* x = Phi^T M q (the M-orthogonal projection of a full state). */
static void project_state(const modal *s, const double *full, double *y)
{
    int r = s->r;
    memset(y, 0, 2 * (size_t)r * sizeof *y);
    for (int i = 0; i < s->m->n; i++) {
        const double *Mi = rd_ring_segment_mass_matrix(s->m->ring, i);
        const double *P = s->Phi + 6 * (size_t)i * r;
        for (int k = 0; k < 6; k++) {
            double mq = rd_lift_dot6(Mi + 6 * k, RD_LIFT_Q(full, i));
            double mv = rd_lift_dot6(Mi + 6 * k, RD_LIFT_V(full, i));
            for (int a = 0; a < r; a++) {
                y[a] += P[k * r + a] * mq;
                y[r + a] += P[k * r + a] * mv;
            }
        }
    }
}

/* Tolerances (header comment); the seated ring at rest, or the projection
 * of a given full initial state. */
static int modal_initial(void *user, const rd_lift_setup *setup, double atol, double *y, double *at,
                         rd_error *err)
{
    (void)err;
    modal *s = user;
    const rd_lift_model *m = s->m;
    const rd_ring_params *rp = rd_ring_get_params(m->ring);
    double wv = sqrt(rd_lift_accel_scale(rp, m->p) / m->ca);
    for (int a = 0; a < s->r; a++) {
        at[a] = atol / s->scale[a];
        at[s->r + a] = at[a] * wv;
    }
    if (setup && setup->y0)
        project_state(s, setup->y0, y);
    else
        memset(y, 0, 2 * (size_t)s->r * sizeof *y);
    return RD_OK;
}

/* Central-difference step of coordinate j (rd_lift_jacobian_check): 1e-3 d0
 * of displacement, 1e-4 u_reg of rate. */
static double modal_fd_step(void *user, sunindextype j)
{
    modal *s = user;
    int a = (int)(j % s->r);
    return (j < s->r ? 1e-3 * s->m->d0 : 1e-4 * s->m->liner.ureg) / s->scale[a];
}

/* A = L^-1 K L^-T (row-major, N x N) and the factors L_i (n x 36, lower,
 * row-major) of the segment masses. */
static int modal_matrix(const rd_lift_model *m, double *A, double *L, rd_error *err)
{
    size_t N = 6 * (size_t)m->n;
    for (int i = 0; i < m->n; i++) {
        double *Li = L + 36 * (size_t)i;
        memcpy(Li, rd_ring_segment_mass_matrix(m->ring, i), 36 * sizeof *Li);
        int info = LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'L', 6, Li, 6);
        if (info != 0)
            return rd_error_set(err, RD_ENUMERIC, "",
                                "The mass matrix of segment %d is not positive definite "
                                "(LAPACK info %d).",
                                i, info);
    }
    memset(A, 0, N * N * sizeof *A);
    for (int i = 0; i < m->n; i++)
        for (int j = i - 1; j <= i + 1; j++) {
            if (j < 0 || j >= m->n)
                continue;
            for (int a = 0; a < 6; a++)
                for (int b = 0; b < 6; b++) {
                    int gi = rd_ring_band_index(m->ring, i, a);
                    int gj = rd_ring_band_index(m->ring, j, b);
                    double v = gi <= gj ? RD_BAND_AT(&m->K, gi, gj) : RD_BAND_AT(&m->K, gj, gi);
                    A[(6 * (size_t)i + a) * N + 6 * (size_t)j + b] = v;
                }
        }
    /* rows: L_i^-1 block; columns: L_j^-T, both by triangular solves */
    int info = 0;
    for (int i = 0; i < m->n && !info; i++)
        info = LAPACKE_dtrtrs(LAPACK_ROW_MAJOR, 'L', 'N', 'N', 6, (lapack_int)N, L + 36 * (size_t)i,
                              6, A + 6 * (size_t)i * N, (lapack_int)N);
    if (!info) { /* A := A L^-T: each row's block j solves x L_j^T = a, i.e. L_j x = a */
        double *col = malloc(N * sizeof *col);
        if (!col)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift modes.");
        for (size_t row = 0; row < N && !info; row++) {
            for (int j = 0; j < m->n && !info; j++) {
                memcpy(col, A + row * N + 6 * (size_t)j, 6 * sizeof *col);
                info = LAPACKE_dtrtrs(LAPACK_ROW_MAJOR, 'L', 'N', 'N', 6, 1, L + 36 * (size_t)j, 6,
                                      col, 1);
                memcpy(A + row * N + 6 * (size_t)j, col, 6 * sizeof *col);
            }
        }
        free(col);
    }
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "The modal reduction's triangular solve failed (LAPACK info %d).",
                            info);
    return RD_OK;
}

/* The r0 lowest eigenvectors (N x r0, row-major, M-orthonormal) into Z. */
static int lowest_modes(const rd_lift_model *m, int r0, double *Z, rd_error *err)
{
    size_t N = 6 * (size_t)m->n;
    int found = 0, rc = RD_OK;
    double *A = malloc(N * N * sizeof *A), *L = malloc(36 * (size_t)m->n * sizeof *L);
    double *w = malloc(N * sizeof *w);
    lapack_int *supp = malloc(2 * (size_t)r0 * sizeof *supp);
    if (!A || !L || !w || !supp) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift modes (%zu DOFs).", N);
        goto out;
    }
    if ((rc = modal_matrix(m, A, L, err)))
        goto out;
    int info = LAPACKE_dsyevr(LAPACK_ROW_MAJOR, 'V', 'I', 'U', (lapack_int)N, A, (lapack_int)N, 0.0,
                              0.0, 1, r0, 0.0, &found, w, Z, r0, supp);
    if (info != 0 || found != r0) {
        rc = rd_error_set(err, RD_ENUMERIC, "",
                          "The lift model's modal eigen-solve failed (LAPACK info %d, %d of %d "
                          "modes).",
                          info, found, r0);
        goto out;
    }
    for (int i = 0; i < m->n; i++) /* Phi_i = L_i^-T Z_i */
        info |= LAPACKE_dtrtrs(LAPACK_ROW_MAJOR, 'L', 'T', 'N', 6, r0, L + 36 * (size_t)i, 6,
                               Z + 6 * (size_t)i * r0, r0);
    if (info != 0)
        rc = rd_error_set(err, RD_ENUMERIC, "", "The modal back-transformation failed.");
out:
    free(A);
    free(L);
    free(w);
    free(supp);
    return rc;
}

/* <a, b>_M over the segments (vectors of N values, segment order). */
static double m_dot(const rd_lift_model *m, const double *a, const double *b)
{
    double s = 0.0;
    for (int i = 0; i < m->n; i++) {
        const double *Mi = rd_ring_segment_mass_matrix(m->ring, i);
        for (int k = 0; k < 6; k++)
            s += a[6 * i + k] * rd_lift_dot6(Mi + 6 * k, b + 6 * i);
    }
    return s;
}

/* y = K x for vectors in segment order (K in band order). */
static void k_times(const rd_lift_model *m, const double *x, double *y, double *tmp)
{
    size_t N = 6 * (size_t)m->n;
    for (int i = 0; i < m->n; i++)
        for (int k = 0; k < 6; k++)
            tmp[rd_ring_band_index(m->ring, i, k)] = x[6 * i + k];
    rd_band_symv(&m->K, tmp, tmp + N);
    for (int i = 0; i < m->n; i++)
        for (int k = 0; k < 6; k++)
            y[6 * i + k] = tmp[N + rd_ring_band_index(m->ring, i, k)];
}

/* The correction shapes (header comment) into E (N x CORRECTIONS, column
 * j at E + j N): the rigid ring's uniform twist and radial shapes, and the
 * static responses of the elastic ring to a uniform twisting couple and a
 * uniform radial load, (K + sigma M)^-1 f_e with f_e the load without its
 * rigid-body part (Z's first 6 columns) and sigma = SHIFT_FRACTION x the
 * first elastic eigenvalue (the residual rigid-body part is in the basis
 * anyway). */
static int correction_shapes(const rd_lift_model *m, const double *Z, int r0, double *E,
                             rd_error *err)
{
    size_t N = 6 * (size_t)m->n;
    for (int j = 0; j < CORRECTIONS; j++)
        memset(E + j * N, 0, N * sizeof *E);
    for (int i = 0; i < m->n; i++)
        for (int c = 0; c < 2; c++) {
            E[6 * i + 3 + c] = E[2 * N + 6 * i + 3 + c] = m->e_t[2 * i + c];
            E[N + 6 * i + c] = E[3 * N + 6 * i + c] = m->e_r[2 * i + c];
        }
    double *tmp = malloc(2 * N * sizeof *tmp), lam1 = 0.0;
    rd_band B = {0, 0, NULL};
    int rc = tmp ? rd_band_init(&B, (int)N, m->K.kd, err)
                 : rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift modes.");
    if (rc)
        goto out;
    {
        /* lam1 = phi_6^T K phi_6 for the first elastic mode (column r0 = 6 is
         * the lowest elastic one) */
        double *col = malloc(2 * N * sizeof *col);
        if (!col) {
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift modes.");
            goto out;
        }
        for (size_t j = 0; j < N; j++)
            col[j] = Z[j * r0 + RIGID_MODES];
        k_times(m, col, col + N, tmp);
        for (size_t j = 0; j < N; j++)
            lam1 += col[j] * col[N + j];
        free(col);
    }
    memcpy(B.ab, m->K.ab, (size_t)(B.kd + 1) * N * sizeof *B.ab);
    for (int i = 0; i < m->n; i++) {
        const double *Mi = rd_ring_segment_mass_matrix(m->ring, i);
        for (int a = 0; a < 6; a++)
            for (int b = 0; b < 6; b++) {
                int gi = rd_ring_band_index(m->ring, i, a), gj = rd_ring_band_index(m->ring, i, b);
                if (gi <= gj)
                    rd_band_add(&B, gi, gj, SHIFT_FRACTION * lam1 * Mi[6 * a + b]);
            }
    }
    if ((rc = rd_band_cholesky(&B, err)))
        goto out;
    for (int j = 2; j < CORRECTIONS; j++) {
        double *f = E + j * N;
        for (int a = 0; a < RIGID_MODES; a++) { /* f -= M phi_a (phi_a^T f) */
            double c = 0.0;
            for (size_t l = 0; l < N; l++)
                c += Z[l * r0 + a] * f[l];
            for (int i = 0; i < m->n; i++) {
                const double *Mi = rd_ring_segment_mass_matrix(m->ring, i);
                for (int k = 0; k < 6; k++)
                    for (int l = 0; l < 6; l++)
                        f[6 * i + k] -= c * Mi[6 * k + l] * Z[(6 * (size_t)i + l) * r0 + a];
            }
        }
        for (int i = 0; i < m->n; i++)
            for (int k = 0; k < 6; k++)
                tmp[rd_ring_band_index(m->ring, i, k)] = f[6 * i + k];
        if ((rc = rd_band_solve(&B, 1, tmp, err)))
            goto out;
        for (int i = 0; i < m->n; i++)
            for (int k = 0; k < 6; k++)
                f[6 * i + k] = tmp[rd_ring_band_index(m->ring, i, k)];
    }
out:
    rd_band_cleanup(&B);
    free(tmp);
    return rc;
}
/* Columns of V (N x cap, column j at V + j N): the r0 modes of Z, then each
 * correction shape M-orthonormalised (twice) against the columns before it,
 * kept unless it lies in their span.  Returns the number of columns. */
static int basis(const rd_lift_model *m, const double *Z, int r0, double *E, double *V)
{
    size_t N = 6 * (size_t)m->n;
    int R = r0;
    for (int a = 0; a < r0; a++)
        for (size_t l = 0; l < N; l++)
            V[a * N + l] = Z[l * r0 + a];
    for (int j = 0; j < CORRECTIONS; j++) {
        double *e = E + j * N, n0 = sqrt(m_dot(m, e, e));
        for (int pass = 0; pass < 2; pass++)
            for (int a = 0; a < R; a++) {
                double c = m_dot(m, V + a * N, e);
                for (size_t l = 0; l < N; l++)
                    e[l] -= c * V[a * N + l];
            }
        double n1 = sqrt(m_dot(m, e, e));
        if (!(n1 > GS_DROP * n0))
            continue;
        for (size_t l = 0; l < N; l++)
            V[R * N + l] = e[l] / n1;
        R++;
    }
    return R;
}

/* Rayleigh-Ritz on the M-orthonormal basis V (R columns): the eigenpairs of
 * V^T K V give Phi = V Y (M-orthonormal, K-orthogonal) and lam. */
static int ritz(modal *s, const double *V, int R, rd_error *err)
{
    const rd_lift_model *m = s->m;
    size_t N = s->N;
    double *KV = malloc(N * sizeof *KV), *tmp = malloc(2 * N * sizeof *tmp);
    double *Kr = malloc((size_t)R * R * sizeof *Kr), *w = malloc((size_t)R * sizeof *w);
    int rc = RD_OK;
    if (!KV || !tmp || !Kr || !w) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift modes.");
        goto out;
    }
    for (int b = 0; b < R; b++) {
        k_times(m, V + b * N, KV, tmp);
        for (int a = 0; a < R; a++) {
            double v = 0.0;
            for (size_t l = 0; l < N; l++)
                v += V[a * N + l] * KV[l];
            Kr[a * R + b] = v;
        }
    }
    for (int a = 0; a < R; a++) /* symmetrize the rounding */
        for (int b = 0; b < a; b++)
            Kr[a * R + b] = Kr[b * R + a] = 0.5 * (Kr[a * R + b] + Kr[b * R + a]);
    int info = LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'V', 'U', R, Kr, R, w);
    if (info != 0) {
        rc = rd_error_set(err, RD_ENUMERIC, "",
                          "The modal Rayleigh-Ritz eigen-solve failed (LAPACK info %d).", info);
        goto out;
    }
    double Rr = rd_ring_get_section(m->ring)->R;
    for (int b = 0; b < R; b++) {
        double sc = 0.0;
        for (size_t l = 0; l < N; l++) {
            double v = 0.0;
            for (int a = 0; a < R; a++)
                v += V[a * N + l] * Kr[a * R + b];
            s->Phi[l * R + b] = v;
            sc = fmax(sc, fabs(v) * (l % 6 < 3 ? 1.0 : Rr));
        }
        s->lam[b] = b < RIGID_MODES ? 0.0 : fmax(w[b], 0.0);
        s->scale[b] = sc > 0.0 ? sc : 1.0;
    }
out:
    free(KV);
    free(tmp);
    free(Kr);
    free(w);
    return rc;
}

static int modal_alloc(modal *s, rd_error *err)
{
    size_t r = (size_t)s->r;
    s->Phi = malloc(s->N * r * sizeof *s->Phi);
    s->lam = malloc(r * sizeof *s->lam);
    s->scale = malloc(r * sizeof *s->scale);
    s->full = malloc(12 * (size_t)s->m->n * sizeof *s->full);
    s->T = malloc(6 * r * sizeof *s->T);
    s->Gq = malloc(r * r * sizeof *s->Gq);
    s->Gv = malloc(r * r * sizeof *s->Gv);
    if (!s->Phi || !s->lam || !s->scale || !s->full || !s->T || !s->Gq || !s->Gv)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal lift model.");
    return RD_OK;
}

/* The basis: modes, corrections, Rayleigh-Ritz (header comment). */
static int modal_build(modal *s, int modes, rd_error *err)
{
    const rd_lift_model *m = s->m;
    size_t N = s->N;
    int r0 = RIGID_MODES + modes, rc;
    double *Z = malloc(N * (size_t)r0 * sizeof *Z), *E = malloc(N * CORRECTIONS * sizeof *E);
    double *V = malloc(N * (size_t)(r0 + CORRECTIONS) * sizeof *V);
    if (!Z || !E || !V)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift modes.");
    else if (!(rc = lowest_modes(m, r0, Z, err)) && !(rc = correction_shapes(m, Z, r0, E, err))) {
        s->r = basis(m, Z, r0, E, V);
        if (!(rc = modal_alloc(s, err)))
            rc = ritz(s, V, s->r, err);
    }
    free(Z);
    free(E);
    free(V);
    return rc;
}

int rd_lift_modal_open(rd_lift_model *m, int modes, rd_lift_form *form, rd_error *err)
{
    int n = m->n, rc = RD_OK;
    size_t mark = rd_error_enter(err, "/discretization");
    if (n > RD_LIFT_MODAL_SEGMENTS_MAX)
        rc = rd_error_set(err, RD_ELIMIT, "/segments",
                          "The modal lift model solves its modes densely and allows at most %d "
                          "segments (got %d): use fewer segments or numerics.model = full.",
                          RD_LIFT_MODAL_SEGMENTS_MAX, n);
    rd_error_leave(err, mark);
    mark = rd_error_enter(err, "/numerics");
    if (!rc && (modes < 1 || modes > 6 * n - RIGID_MODES))
        rc = rd_error_set(err, RD_EINVAL, "/modes",
                          "@/modes = %d is out of range: a ring of %d segments has 1 to %d "
                          "elastic modes.",
                          modes, n, 6 * n - RIGID_MODES);
    rd_error_leave(err, mark);
    if (rc)
        return rc;
    modal *s = calloc(1, sizeof *s);
    if (!s)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the modal lift model.");
    s->m = m;
    s->N = 6 * (size_t)n;
    *form = (rd_lift_form){.name = "modal",
                           .dense = 1,
                           .user = s,
                           .m = m,
                           .rhs = modal_rhs,
                           .jac = modal_jac,
                           .lift = modal_lift,
                           .loads = modal_loads,
                           .expand = modal_expand,
                           .initial = modal_initial,
                           .fd_step = modal_fd_step,
                           .close = rd_lift_modal_close};
    rc = modal_build(s, modes, err); /* on failure the caller closes the form */
    form->N = 2 * (sunindextype)s->r;
    return rc;
}

void rd_lift_modal_close(rd_lift_form *form)
{
    modal_free(form->user);
    form->user = NULL;
}
