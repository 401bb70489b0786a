/*
 * rd_lift_rigid.c — the rigid lift model: the ring as one body in its groove
 * (issue 10, numerics.model = "rigid"), exact for axisymmetric scenes (round
 * bore, aligned groove, loads uniform around the ring: every lift scene
 * today).
 *
 * Unknowns x = (z, theta, r): the uniform axial displacement of the ring
 * (m), its uniform twist (rotation of every cross-section about its own
 * tangent, rad, positive as the full model's mean twist) and its uniform
 * radial displacement (m).  Radial is needed: the gas behind the ring pushes
 * it into the bore and so raises the friction's normal force.  Segment i of
 * the full model's geometry (rd_lift_model.c) then moves by
 *     q_i = phi_z z + phi_theta,i theta + phi_r,i r,
 *     phi_z = e_z,  phi_theta,i = (0, 0, 0, e_t,i),  phi_r,i = (e_r,i, 0, 0, 0, 0),
 * and the equations are the full model's projected on these three shapes
 * (Galerkin): M_x x'' = Phi^T f(t, Phi x, Phi x') - K_x x with
 *   M_x = sum_i Phi_i^T M_i Phi_i (3x3, computed once),
 *   K_x: only the twist term phi_theta^T K phi_theta (the ring's resistance to
 *     a uniform twist, from the same K); a uniform radial expansion of the
 *     split ring costs no elastic energy at this order (the gap opens; the
 *     ring's spring-back is the constant pretension p0 of the bore contact),
 *     and a uniform axial translation is a rigid-body motion;
 *   Phi^T f = n Phi_0^T f_0: in an axisymmetric state every segment carries
 *     the same force in its own frame, so the circumferential sum is one
 *     segment's force elements (rd_lift_forces_segment) times n — the
 *     integrals around the ring are done once, not per segment.
 * Its Jacobian is the same projection of segment 0's local blocks, a dense
 * 6x6 Newton matrix.  All force elements (inertia, gravity, flanks, bore
 * contact and Coulomb/Stribeck friction, groove back, gas with fixed or
 * dynamic areas) and all outputs and events are the full model's, evaluated
 * on the uniform state; every segment's lift is the same.
 */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>

#include "rd_lift_model.h"

#define NX 3 /* z, theta, r */

typedef struct rigid {
    rd_lift_model *m;
    double phi[NX][6];                       /* segment 0's displacement per unit z, theta, r */
    int idx[NX][6], nnz[NX];                 /* the non-zero entries of each phi */
    double Minv[NX * NX];                    /* inverse generalized mass, row-major */
    double k_twist;                          /* N m / rad: phi_theta^T K phi_theta */
    double q[6], v[6], f[6], Dq[36], Dv[36]; /* segment 0 scratch */
} rigid;

/* Segment i's shape vectors (header comment). */
static void shapes(const rd_lift_model *m, int i, double phi[NX][6])
{
    memset(phi, 0, NX * 6 * sizeof(double));
    phi[0][2] = 1.0;
    phi[1][3] = m->e_t[2 * i];
    phi[1][4] = m->e_t[2 * i + 1];
    phi[2][0] = m->e_r[2 * i];
    phi[2][1] = m->e_r[2 * i + 1];
}

/* Segment 0's state (q, v) of the reduced state y = (x, x'). */
static void segment_state(rigid *r, const double *y)
{
    for (int k = 0; k < 6; k++) {
        r->q[k] = 0.0;
        r->v[k] = 0.0;
        for (int a = 0; a < NX; a++) {
            r->q[k] += r->phi[a][k] * y[a];
            r->v[k] += r->phi[a][k] * y[NX + a];
        }
    }
}

static int rigid_rhs(sunrealtype t, N_Vector yv, N_Vector ydv, void *user)
{
    rigid *r = user;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydv), G[NX];
    segment_state(r, y);
    rd_lift_forces_segment(r->m, t, 0, r->q, r->v, r->f, NULL, NULL);
    for (int a = 0; a < NX; a++)
        G[a] = r->m->n * rd_lift_dot6(r->phi[a], r->f);
    G[1] -= r->k_twist * y[1];
    for (int a = 0; a < NX; a++) {
        yd[a] = y[NX + a];
        yd[NX + a] = 0.0;
        for (int b = 0; b < NX; b++)
            yd[NX + a] += r->Minv[NX * a + b] * G[b];
    }
    for (int j = 0; j < 2 * NX; j++)
        if (!isfinite(yd[j]))
            return 1; /* recoverable: CVODE retries with a smaller step */
    return 0;
}

/* n phi_a^T D phi_b into P (NX x NX); each shape has at most two non-zero
 * entries (shapes()), so only those are visited. */
static void project(const rigid *r, const double *D, double *P)
{
    for (int a = 0; a < NX; a++)
        for (int b = 0; b < NX; b++) {
            double s = 0.0;
            for (int u = 0; u < r->nnz[a]; u++)
                for (int w = 0; w < r->nnz[b]; w++)
                    s += r->phi[a][r->idx[a][u]] * D[6 * r->idx[a][u] + r->idx[b][w]] *
                         r->phi[b][r->idx[b][w]];
            P[NX * a + b] = r->m->n * s;
        }
}

/* The second-order blocks (rd_lift_model.h): one block of NX, A = M_x^-1
 * (n Phi^T Dq Phi - K_x), B = M_x^-1 n Phi^T Dv Phi (no neighbours). */
static void rigid_blocks(void *user, double t, const double *y, double *A, double *B)
{
    rigid *r = user;
    double Gq[NX * NX], Gv[NX * NX];
    segment_state(r, y);
    rd_lift_forces_segment(r->m, t, 0, r->q, r->v, r->f, r->Dq, r->Dv);
    project(r, r->Dq, Gq);
    project(r, r->Dv, Gv);
    Gq[NX * 1 + 1] -= r->k_twist;
    double *Ad = A + NX * NX; /* the diagonal block of row block 0 */
    memset(A, 0, 3 * NX * NX * sizeof *A);
    for (int a = 0; a < NX; a++)
        for (int b = 0; b < NX; b++) {
            double sq = 0.0, sv = 0.0;
            for (int c = 0; c < NX; c++) {
                sq += r->Minv[NX * a + c] * Gq[NX * c + b];
                sv += r->Minv[NX * a + c] * Gv[NX * c + b];
            }
            Ad[NX * a + b] = sq;
            B[NX * a + b] = sv;
        }
}

/* The Jacobian as a dense 6x6 matrix from the blocks (the Jacobian check's
 * view of what the Newton solver uses). */
static int rigid_jac(sunrealtype t, N_Vector yv, N_Vector fy, SUNMatrix J, void *user, N_Vector t1,
                     N_Vector t2, N_Vector t3)
{
    (void)fy;
    (void)t1;
    (void)t2;
    (void)t3;
    double A[3 * NX * NX], B[NX * NX];
    rigid_blocks(user, t, N_VGetArrayPointer(yv), A, B);
    if (SUNMatZero(J))
        return -1;
    for (int a = 0; a < NX; a++) {
        SM_ELEMENT_D(J, a, NX + a) = 1.0;
        for (int b = 0; b < NX; b++) {
            SM_ELEMENT_D(J, NX + a, b) = A[NX * NX + NX * a + b];
            SM_ELEMENT_D(J, NX + a, NX + b) = B[NX * a + b];
        }
    }
    return 0;
}

/* Plastic landing: the face comes to rest on the flank, so its axial rate
 * z' towards it and its tilt rate theta' are arrested (the radial rate
 * keeps its value).  Arresting z' alone left the face's edge striking the
 * flank with the twist rate: on the 6000 rpm gas example that edge impact
 * threw the ring off again (a 2 deg hop at 303 deg the penalty run has not). */
static void rigid_impact(void *user, double *y, int upper)
{
    (void)user;
    if (upper ? y[NX] > 0.0 : y[NX] < 0.0) {
        y[NX] = 0.0;
        y[NX + 1] = 0.0;
    }
}

/* Every segment's lift is segment 0's: the mean over its flank points. */
static double rigid_lift(void *user, const double *y, double *seg)
{
    rigid *r = user;
    const rd_lift_model *m = r->m;
    segment_state(r, y);
    double s = 0.0;
    for (int k = 0; k < RD_LIFT_FLANK_POINTS; k++) {
        const double *d = m->fl_d + 2 * k;
        s += r->q[2] + r->q[3] * d[1] - r->q[4] * d[0];
    }
    s /= RD_LIFT_FLANK_POINTS;
    if (seg)
        for (int i = 0; i < m->n; i++)
            seg[i] = s;
    return s;
}

static void rigid_loads(void *user, double t, const double *y)
{
    rigid *r = user;
    segment_state(r, y);
    rd_lift_forces_segment(r->m, t, 0, r->q, r->v, r->f, NULL, NULL);
    r->m->friction *= r->m->n;
    r->m->fz_ext *= r->m->n;
}

static void rigid_expand(void *user, const double *y, double *full)
{
    rigid *r = user;
    double phi[NX][6];
    for (int i = 0; i < r->m->n; i++) {
        shapes(r->m, i, phi);
        double *q = RD_LIFT_Q(full, i), *v = RD_LIFT_V(full, i);
        for (int k = 0; k < 6; k++) {
            q[k] = v[k] = 0.0;
            for (int a = 0; a < NX; a++) {
                q[k] += phi[a][k] * y[a];
                v[k] += phi[a][k] * y[NX + a];
            }
        }
    }
}

/* Tolerances: atol on z and r, and on theta atol / e without friction, with
 * e the largest radial offset of a flank point from the section's reference
 * point (b / 2: a twist error then moves the face's edge, and the lift, by
 * at most atol; the full model's atol / R asks R / e ~ 26 times more of the
 * twist than of the lift, ~20 % of the steps), atol / R with friction (its
 * couple decides a leave by the twist's edge lift, which converges slowly:
 * atol / e moved that leave at 1000 rpm by 0.05 deg at rtol 1e-8); atol w_v
 * on the rates.  The ring starts seated at rest. */
static int rigid_initial(void *user, const rd_lift_setup *setup, double atol, double *y, double *at,
                         rd_error *err)
{
    rigid *r = user;
    const rd_lift_model *m = r->m;
    if (setup && setup->y0)
        return rd_error_set(err, RD_EINVAL, "/numerics/model",
                            "The rigid lift model starts seated at rest; a given initial state "
                            "needs the full model.");
    const rd_ring_params *rp = rd_ring_get_params(m->ring);
    double e = 0.0;
    for (int k = 0; k < RD_LIFT_FLANK_POINTS; k++)
        e = fmax(e, fabs(m->fl_d[2 * k] * m->e_r[0] + m->fl_d[2 * k + 1] * m->e_r[1]));
    double wv = sqrt(rd_lift_accel_scale(rp, m->p) / m->ca);
    if (m->p->friction.model != RD_FRICTION_NONE)
        e = rd_ring_get_section(m->ring)->R;
    double a[NX] = {atol, atol / e, atol};
    for (int k = 0; k < NX; k++) {
        y[k] = y[NX + k] = 0.0;
        at[k] = a[k];
        at[NX + k] = a[k] * wv;
    }
    return RD_OK;
}

/* M_x = sum_i Phi_i^T M_i Phi_i, inverted by Cholesky. */
static int rigid_mass(rigid *r, rd_error *err)
{
    const rd_lift_model *m = r->m;
    double M[NX * NX] = {0}, phi[NX][6];
    for (int i = 0; i < m->n; i++) {
        const double *Mi = rd_ring_segment_mass_matrix(m->ring, i);
        shapes(m, i, phi);
        for (int a = 0; a < NX; a++)
            for (int b = 0; b < NX; b++)
                for (int k = 0; k < 6; k++)
                    M[NX * a + b] += phi[a][k] * rd_lift_dot6(Mi + 6 * k, phi[b]);
    }
    int info = LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'U', NX, M, NX);
    if (info == 0)
        info = LAPACKE_dpotri(LAPACK_ROW_MAJOR, 'U', NX, M, NX);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "The rigid ring's mass matrix is not positive definite (LAPACK info "
                            "%d).",
                            info);
    for (int a = 0; a < NX; a++)
        for (int b = 0; b < NX; b++)
            r->Minv[NX * a + b] = a <= b ? M[NX * a + b] : M[NX * b + a];
    return RD_OK;
}

/* phi_theta^T K phi_theta over the whole ring (band order = segment order
 * for the split ring). */
static int rigid_twist_stiffness(rigid *r, rd_error *err)
{
    const rd_lift_model *m = r->m;
    size_t N = 6 * (size_t)m->n;
    double *x = calloc(2 * N, sizeof *x);
    if (!x)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the rigid lift model.");
    for (int i = 0; i < m->n; i++) {
        x[rd_ring_band_index(m->ring, i, 3)] = m->e_t[2 * i];
        x[rd_ring_band_index(m->ring, i, 4)] = m->e_t[2 * i + 1];
    }
    rd_band_symv(&m->K, x, x + N);
    double k = 0.0;
    for (size_t j = 0; j < N; j++)
        k += x[j] * x[N + j];
    r->k_twist = k;
    free(x);
    return RD_OK;
}

int rd_lift_rigid_open(rd_lift_model *m, rd_lift_form *form, rd_error *err)
{
    rigid *r = calloc(1, sizeof *r);
    int rc;
    if (!r)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the rigid lift model.");
    r->m = m;
    shapes(m, 0, r->phi);
    for (int a = 0; a < NX; a++)
        for (int k = 0; k < 6; k++)
            if (r->phi[a][k] != 0.0)
                r->idx[a][r->nnz[a]++] = k;
    *form = (rd_lift_form){.name = "rigid",
                           .N = 2 * NX,
                           .dense = 1,
                           .user = r,
                           .m = m,
                           .rhs = rigid_rhs,
                           .jac = rigid_jac,
                           .block = NX,
                           .blocks = rigid_blocks,
                           .impact = rigid_impact,
                           .lift = rigid_lift,
                           .loads = rigid_loads,
                           .expand = rigid_expand,
                           .initial = rigid_initial,
                           .close = rd_lift_rigid_close};
    if ((rc = rigid_mass(r, err)) || (rc = rigid_twist_stiffness(r, err)))
        return rc; /* the caller closes the form */
    return RD_OK;
}

void rd_lift_rigid_close(rd_lift_form *form)
{
    free(form->user);
    form->user = NULL;
}
