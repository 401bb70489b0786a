/*
 * rd_lift_rigid.c — the rigid lift model: the ring as one body in its groove
 * (issue 10, numerics.model = "rigid") for axisymmetric scenes (round bore,
 * aligned groove, loads uniform around the ring), exact up to what the split
 * ring's free ends do (below: "Effective twist stiffness").
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
 *   K_x: only the twist term k_theta (the ring's resistance to a twist,
 *     below); a uniform radial expansion of the
 *     split ring costs no elastic energy at this order (the gap opens; the
 *     ring's spring-back is the constant pretension p0 of the bore contact),
 *     and a uniform axial translation is a rigid-body motion;
 *   Phi^T f = n Phi_0^T f_0: in an axisymmetric state every segment carries
 *     the same force in its own frame, so the circumferential sum is one
 *     segment's force elements (rd_lift_forces_segment) times n — the
 *     integrals around the ring are done once, not per segment.
 * Effective twist stiffness.  The uniform twist shape's own stiffness,
 * k_u = phi_theta^T K phi_theta (the closed ring's "rolling" stiffness,
 * 2 pi E I_out / R in the continuum), is too stiff for the SPLIT ring: a
 * uniform couple m per unit length twists its free ends more, because the
 * out-of-plane bending moment that resists a uniform twist must vanish
 * there.  Measured on the full model (1000 rpm Coulomb, n = 40, README
 * "Lift models"): the segments' twists grow towards the gap, the mean twist
 * is 3 % above the rigid ring's, and a leave decided by the edge lift that
 * twist causes (the ring resting on one edge) comes 0.95 deg earlier; the
 * landings of the 6000 rpm gas example come 0.8 deg later for another
 * reason (the full ring's lift spreads around it in flight, which no
 * uniform shape holds).  So k_theta is the split ring's static stiffness
 * seen by a uniform couple while it rests on one edge of a flank -- a static
 * condensation of the full model's K onto the mean twist:
 *     (K + kappa sum_i p_i p_i^T + S) u = f,
 *     f = e_t,i on every segment's rotations (a unit couple per segment),
 *     p_i . q_i = q_z,i + (r_i x d_i)_z, the axial displacement of segment
 *       i's edge point d_i = -+(b/2) e_r,i (its flank contact line at the
 *       segment's middle) held by a support kappa = 1e8 k_u / (n R^2) (rigid
 *       to 1e-8 of the twist),
 *     S = 1e-6 x K's diagonal on the in-plane DOFs (x, y, rotation about
 *       z): pins the in-plane rigid-body motions the supports leave free.
 *       The plane ring's in-plane and out-of-plane DOFs are uncoupled in K
 *       (a section symmetric about the mid-plane), the supports and f act
 *       out of plane, so the in-plane part of u is 0 whatever S is (1e-2
 *       gives the same k to the last digit); S only has to stand above the
 *       factorization's round-off, ~kd eps max K_ii, which grows as n^3
 *       (K's in-plane bending over the segment length cubed).  A shift
 *       sigma M of 1e-8 k_u / (n R^2) (up to 0.3.15) fell below it past
 *       n ~ 650 (dpbtrf failed at n = 700, 800, 1000, issue 45) and
 *       stiffened the twist itself by ~1e-9,
 *     k_edge = n^2 / sum_i e_t,i . r_i(u)   (the couple n over the mean twist),
 * one band Cholesky per edge when the model opens.  The uniform twist about
 * the edge is an admissible u, so k_edge <= k_u (Rayleigh).  The rigid ring
 * uses k_edge of the edge the twist presses on the nearer flank: theta > 0
 * lowers the outer edge, so on the lower flank (z < c_a / 2) it rests on the
 * outer edge (k_outer), on the upper flank on the inner one (k_inner), and
 * the reverse for theta < 0 (k theta is continuous in theta; at z = c_a / 2,
 * in flight, it jumps by (k_outer - k_inner) theta, under 1 % of it).
 * k_edge / k_u at the thesis ring: 0.85 (n = 8), 0.95 (n = 20), 0.974
 * (n = 40), 0.986 (n = 320); the curved-beam (Vlasov) continuum with the
 * same support gives 0.988 (test_lift_rigid).  On the 1000 rpm Coulomb
 * leave this brings the rigid ring from 0.95 to 0.27 deg of full n = 40
 * (n = 8, 12, 20: from 1.3, 1.1, 0.9 to 0.39, 0.34, 0.20 deg of full at the
 * same n); the gas example's landings keep their 0.8 deg.
 *
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

#define NX              3    /* z, theta, r */
#define PIVOT_STIFFNESS 1e8  /* kappa / k_x: the support is rigid to 1e-8 of the twist */
#define IN_PLANE_SHIFT  1e-6 /* pins the in-plane motions: x (1 + this) on their diagonal */

typedef struct rigid {
    rd_lift_model *m;
    double phi[NX][6];                       /* segment 0's displacement per unit z, theta, r */
    int idx[NX][6], nnz[NX];                 /* the non-zero entries of each phi */
    double Minv[NX * NX];                    /* inverse generalized mass, row-major */
    double k_twist;                          /* N m / rad: phi_theta^T K phi_theta */
    double k_edge[2];                        /* N m / rad: seated on the inner, outer edge */
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

/* u = Phi_i x for segment i (radial unit er, tangential unit et): the
 * translation r e_r + z e_z and the rotation theta e_t (shapes()), only the
 * non-zero terms formed. */
static void segment_motion(const double *er, const double *et, const double *x, double *u)
{
    u[0] = er[0] * x[2];
    u[1] = er[1] * x[2];
    u[2] = x[0];
    u[3] = et[0] * x[1];
    u[4] = et[1] * x[1];
    u[5] = 0.0;
}

/* Segment 0's state (q, v) of the reduced state y = (x, x'). */
static void segment_state(rigid *r, const double *y)
{
    segment_motion(r->m->e_r, r->m->e_t, y, r->q);
    segment_motion(r->m->e_r, r->m->e_t, y + NX, r->v);
}

/* G = n Phi_0^T f (shapes()): the axial force, the couple about e_t and the
 * radial force, summed over the ring. */
static void project_force(const rigid *r, const double *f, double *G)
{
    const double *er = r->m->e_r, *et = r->m->e_t;
    G[0] = r->m->n * f[2];
    G[1] = r->m->n * (et[0] * f[3] + et[1] * f[4]);
    G[2] = r->m->n * (er[0] * f[0] + er[1] * f[1]);
}

/* The twist stiffness of the ring seated on the edge the twist presses on
 * the nearer flank (header comment): theta > 0 lowers the outer edge, so on
 * the lower flank it rests on the outer edge, on the upper one on the inner
 * edge.  In flight the two are blended smoothly over the middle half of the
 * groove (a C1 step in the lift): a switch at mid-groove made the twist
 * moment jump by (k_outer - k_inner) theta, and the rigid integrator's error
 * test then collapsed the step there (test_lift's friction scene). */
static double twist_stiffness(const rigid *r, const double *y)
{
    int pos = y[1] > 0.0;
    double s = fmin(fmax((y[0] / r->m->ca - 0.25) / 0.5, 0.0), 1.0);
    double up = s * s * (3.0 - 2.0 * s); /* 0 on the lower half's flank, 1 on the upper's */
    return (1.0 - up) * r->k_edge[pos] + up * r->k_edge[!pos];
}

static int rigid_rhs(sunrealtype t, N_Vector yv, N_Vector ydv, void *user)
{
    rigid *r = user;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydv), G[NX];
    segment_state(r, y);
    rd_lift_forces_segment(r->m, t, 0, r->q, r->v, r->f, NULL, NULL);
    project_force(r, r->f, G);
    G[1] -= twist_stiffness(r, y) * y[1];
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
    Gq[NX * 1 + 1] -= twist_stiffness(r, y);
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

/* Every segment's lift is segment 0's: the mean over its flank points.
 * Only q's axial entries are needed: q_k = sum_a phi_a,k x_a as in
 * segment_state (the same sums, so the same values). */
static double rigid_lift(void *user, const double *y, double *seg)
{
    rigid *r = user;
    const rd_lift_model *m = r->m;
    double q[5] = {0.0};
    for (int k = 2; k < 5; k++)
        for (int a = 0; a < NX; a++)
            q[k] += r->phi[a][k] * y[a];
    double s = 0.0;
    for (int k = 0; k < RD_LIFT_FLANK_POINTS; k++) {
        const double *d = m->fl_d + 2 * k;
        s += q[2] + q[3] * d[1] - q[4] * d[0];
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
    rd_lift_loads_segment(r->m, t, 0, r->q, r->v, r->f);
    r->m->friction *= r->m->n;
    r->m->fz_ext *= r->m->n;
}

static void rigid_expand(void *user, const double *y, double *full)
{
    const rd_lift_model *m = ((rigid *)user)->m;
    for (int i = 0; i < m->n; i++) {
        segment_motion(m->e_r + 2 * i, m->e_t + 2 * i, y, RD_LIFT_Q(full, i));
        segment_motion(m->e_r + 2 * i, m->e_t + 2 * i, y + NX, RD_LIFT_V(full, i));
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
    if (setup && setup->y0) {
        size_t mark = rd_error_enter(err, "/numerics");
        int rc = rd_error_set(err, RD_EINVAL, "/model",
                              "The rigid lift model starts seated at rest; a given initial state "
                              "needs the full model.");
        rd_error_leave(err, mark);
        return rc;
    }
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
 * for the split ring): the twist stiffness of the uniform twist shape. */
static double uniform_twist_stiffness(const rd_lift_model *m, double *x)
{
    size_t N = 6 * (size_t)m->n;
    memset(x, 0, 2 * N * sizeof *x);
    for (int i = 0; i < m->n; i++) {
        x[rd_ring_band_index(m->ring, i, 3)] = m->e_t[2 * i];
        x[rd_ring_band_index(m->ring, i, 4)] = m->e_t[2 * i + 1];
    }
    rd_band_symv(&m->K, x, x + N);
    double k = 0.0;
    for (size_t j = 0; j < N; j++)
        k += x[j] * x[N + j];
    return k;
}

/* The seated split ring's twist stiffness (header comment "Effective twist
 * stiffness"): K plus a stiff axial support kappa on every flank point of
 * one edge (edge 0 inner, 1 outer), plus sigma M for the in-plane rigid-body
 * motions the support leaves free, loaded by a unit couple about e_t on every
 * segment; k = n^2 / sum_i e_t . rot_i. */
static int pivoted_twist_stiffness(const rd_lift_model *m, int edge, double k_uniform,
                                   double *k_out, rd_error *err)
{
    size_t N = 6 * (size_t)m->n;
    rd_band B = {0, 0, NULL};
    double *x = calloc(N, sizeof *x);
    int rc = x ? rd_band_init(&B, (int)N, m->K.kd, err)
               : rd_error_set(err, RD_ENOMEM, "", "Out of memory for the rigid lift model.");
    if (rc)
        goto out;
    memcpy(B.ab, m->K.ab, (size_t)(B.kd + 1) * N * sizeof *B.ab);
    double R = rd_ring_get_section(m->ring)->R;
    double kappa = PIVOT_STIFFNESS * k_uniform / (m->n * R * R);
    for (int i = 0; i < m->n; i++) {
        double P[6][6] = {{0}};
        {
            const rd_section_flank *fl = &rd_ring_get_cross_section(m->ring)->lower;
            double rho = edge ? fl->d_out : fl->d_in; /* the pivot edge's offset */
            double d[2] = {rho * m->e_r[2 * i], rho * m->e_r[2 * i + 1]};
            double p[6] = {0.0, 0.0, 1.0, d[1], -d[0], 0.0};
            for (int u = 0; u < 6; u++)
                for (int w = 0; w < 6; w++)
                    P[u][w] += kappa * p[u] * p[w];
        }
        for (int u = 0; u < 6; u++)
            for (int w = 0; w < 6; w++) {
                int gi = rd_ring_band_index(m->ring, i, u), gj = rd_ring_band_index(m->ring, i, w);
                if (gi <= gj)
                    rd_band_add(&B, gi, gj, P[u][w]);
            }
        for (int u = 0; u < 6; u++) /* the in-plane DOFs: x, y, rotation about z */
            if (u < 2 || u == 5) {
                int g = rd_ring_band_index(m->ring, i, u);
                RD_BAND_AT(&B, g, g) *= 1.0 + IN_PLANE_SHIFT;
            }
    }
    if ((rc = rd_band_cholesky(&B, err)))
        goto out;
    for (int i = 0; i < m->n; i++) {
        x[rd_ring_band_index(m->ring, i, 3)] = m->e_t[2 * i];
        x[rd_ring_band_index(m->ring, i, 4)] = m->e_t[2 * i + 1];
    }
    if ((rc = rd_band_solve(&B, 1, x, err)))
        goto out;
    double g = 0.0;
    for (int i = 0; i < m->n; i++)
        g += m->e_t[2 * i] * x[rd_ring_band_index(m->ring, i, 3)] +
             m->e_t[2 * i + 1] * x[rd_ring_band_index(m->ring, i, 4)];
    *k_out = (double)m->n * m->n / g;
out:
    rd_band_cleanup(&B);
    free(x);
    return rc;
}

static int rigid_twist_stiffness(rigid *r, rd_error *err)
{
    const rd_lift_model *m = r->m;
    double *x = malloc(12 * (size_t)m->n * sizeof *x);
    if (!x)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the rigid lift model.");
    r->k_twist = uniform_twist_stiffness(m, x);
    free(x);
    int rc = pivoted_twist_stiffness(m, 0, r->k_twist, &r->k_edge[0], err);
    if (!rc)
        rc = pivoted_twist_stiffness(m, 1, r->k_twist, &r->k_edge[1], err);
    return rc;
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
                           .uniform = 1,
                           .loads = rigid_loads,
                           .expand = rigid_expand,
                           .initial = rigid_initial,
                           .close = rd_lift_rigid_close};
    if ((rc = rigid_mass(r, err)) || (rc = rigid_twist_stiffness(r, err)))
        return rc; /* the caller closes the form */
    return RD_OK;
}

int rd_lift_rigid_twist(rd_lift_model *m, double k[3], rd_error *err)
{
    rigid r;
    memset(&r, 0, sizeof r);
    r.m = m;
    int rc = rigid_twist_stiffness(&r, err);
    if (!rc) {
        k[0] = r.k_twist;
        k[1] = r.k_edge[0];
        k[2] = r.k_edge[1];
    }
    return rc;
}

void rd_lift_rigid_close(rd_lift_form *form)
{
    free(form->user);
    form->user = NULL;
}
