/*
 * rd_lift_model.c — the full lift model: its constants, the geometry of its
 * contact points, its mass and stiffness, and the right-hand side and
 * Jacobian assembled from the force elements (file map, state layout and the
 * Jacobian plan: rd_lift_model.h; the physics: rd_lift.c).
 *
 * Equations per segment i (linear kinematics: a point X of segment i moves
 * by u_i + r_i x (X - P_i)):
 *     dq_i/dt = v_i,   M_i dv_i/dt = -(K q)_i + f_i(t, q_i, v_i)
 * K: the ring's banded stiffness (rd_ring_assemble_band, kd = 11), M_i: the
 * segment's exact 6x6 mass matrix (inverted once by Cholesky, dpotrf/dpotri).
 * Segment i couples only to i +- 1, so d(ydot)/dy has upper bandwidth 11
 * (dv_i/dq_{i+1}) and lower bandwidth 23 (dv_{i+1}/dq_i).
 *
 * Contact points per segment (the force elements' tributary areas): on the
 * bottom and top faces 3 arc positions (centres of thirds of the segment's
 * arc) x 2 radii (inner and outer edge, each carrying its half of the face
 * width); on the running face (bore) and on the inner face (groove back) 3
 * points each at mid-height; the gas loads at the face centroids.
 */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_band.h>

#include "rd_lift_model.h"

#define ARC_POINTS      RD_LIFT_ARC_POINTS
#define FLANK_POINTS    RD_LIFT_FLANK_POINTS
#define Q               RD_LIFT_Q
#define V               RD_LIFT_V
#define SMOOTH_FRACTION 1e-4 /* d0 / c_a: quadratic start of the penalty */
#define EVENT_FRACTION  1e-2 /* eps / c_a without a band: smallest hop that is a leave */
#define DAMPING_RATIO   5.0  /* zeta of the contacts: landings do not rebound */

void rd_lift_model_cleanup(rd_lift_model *c)
{
    rd_band_cleanup(&c->K);
    free(c->Minv);
    free(c->Mez);
    free(c->fl_d);
    free(c->bo_d);
    free(c->bo_e);
    free(c->ba_d);
    free(c->cen_d);
    free(c->bo_gap);
    free(c->bo_layers);
    free(c->e_r);
    free(c->e_t);
    free(c->qbuf);
    free(c->fbuf);
    free(c->MK);
    free(c->Dq);
    free(c->Dv);
    free(c->film_grp);
}

/* The scene's constants: clearances, penalty, damping, pretension, friction. */
static void model_constants(rd_lift_model *c, const rd_ring_params *rp, const rd_lift_params *p,
                            const rd_lift_setup *setup)
{
    const rd_section *s = rd_ring_get_cross_section(c->ring);
    c->piston_fixed = setup && setup->piston_fixed;
    c->omega = rd_engine_omega(&p->engine);
    c->ca = p->groove.axial_clearance;
    c->cr = p->groove.radial_clearance;
    c->k = p->contact_stiffness > 0.0 ? p->contact_stiffness
                                      : rd_lift_contact_stiffness_default(rp, p);
    c->d0 = SMOOTH_FRACTION * c->ca;
    c->banded = p->flank_band > 0.0;
    c->eps = (c->banded ? p->flank_band : EVENT_FRACTION) * c->ca;
    c->c_flank = 2.0 * DAMPING_RATIO * sqrt(c->k * rp->density * s->h);
    c->c_rad = 2.0 * DAMPING_RATIO * sqrt(c->k * rp->density * s->b);
    c->g_on = p->gravity ? RD_LIFT_GRAVITY : 0.0;
    c->p0 = 2.0 * rp->tangential_force / (rp->diameter * s->run.height); /* (1.3) */
    c->delta_pre = rd_lift_contact_inverse(c, c->p0);
    rd_liner_init(&c->liner, &p->friction,
                  rd_liner_ureg(&p->engine) *
                      (setup && setup->ureg_scale > 0 ? setup->ureg_scale : 1.0),
                  s->run.height, M_PI * rp->diameter);
    c->h = s->run.height;
    rd_lift_landing_init(c, s, p);
}

static int model_alloc(rd_lift_model *c, rd_error *err)
{
    size_t n = (size_t)c->n, N6 = 6 * n;
    c->Minv = malloc(36 * n * sizeof *c->Minv);
    c->Mez = malloc(N6 * sizeof *c->Mez);
    c->fl_d = malloc(2 * FLANK_POINTS * n * sizeof *c->fl_d);
    c->bo_d = malloc(2 * ARC_POINTS * n * sizeof *c->bo_d);
    c->bo_e = malloc(2 * ARC_POINTS * n * sizeof *c->bo_e);
    c->ba_d = malloc(2 * ARC_POINTS * n * sizeof *c->ba_d);
    c->cen_d = malloc(2 * n * sizeof *c->cen_d);
    c->e_r = malloc(2 * n * sizeof *c->e_r);
    c->e_t = malloc(2 * n * sizeof *c->e_t);
    c->qbuf = malloc(2 * N6 * sizeof *c->qbuf);
    c->fbuf = malloc(N6 * sizeof *c->fbuf);
    c->MK = calloc(108 * n, sizeof *c->MK);
    c->Dq = malloc(36 * n * sizeof *c->Dq);
    c->Dv = malloc(36 * n * sizeof *c->Dv);
    if (rd_lift_model_films(c, err))
        return err ? err->code : RD_ENOMEM;
    if (!c->Minv || !c->Mez || !c->fl_d || !c->bo_d || !c->bo_e || !c->ba_d || !c->cen_d ||
        !c->e_r || !c->e_t || !c->qbuf || !c->fbuf || !c->MK || !c->Dq || !c->Dv)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for a %d-segment lift model.", c->n);
    return RD_OK;
}

/* Tributary areas of the contact points (header comment).  One set of flank
 * points serves both flanks: the lower flank's, the upper being alike (the
 * lift takes rectangles only). */
static void model_areas(rd_lift_model *c, const rd_section *s, const rd_ring_section *sec)
{
    double R = sec->R, ri = s->lower.r_in, ro = s->lower.r_out, phi = sec->span / c->n;
    c->L_run = s->run.r * sec->span;
    c->face_area = phi * R * s->lower.width;
    c->face_width = s->lower.width;
    c->back_chord_area = s->back.height * 2.0 * s->back.r * sin(0.5 * phi);
    c->bo_area = s->run.area_rad * phi / ARC_POINTS;
    c->ba_area = s->back.area_rad * phi / ARC_POINTS;
    for (int a = 0; a < ARC_POINTS; a++) {
        c->fl_area[2 * a] = phi / ARC_POINTS * 0.5 * (R * R - ri * ri);     /* inner half */
        c->fl_area[2 * a + 1] = phi / ARC_POINTS * 0.5 * (ro * ro - R * R); /* outer half */
    }
}

/* Segment i's frame, face centroid and contact point offsets from P_i: the
 * flank points at the lower flank's edges (model_areas), the bore and back
 * points on the running and back faces, all in the plane of P_i (the faces
 * touch at mid-height, z_touch = 0). */
static void model_points(rd_lift_model *c, int i, const rd_section *s, const rd_ring_section *sec)
{
    double R = sec->R, ri = s->lower.r_in, ro = s->lower.r_out, phi = sec->span / c->n;
    double r_run = s->run.r, r_back = s->back.r;
    double rc_com = rd_ring_get_segment_mass(c->ring, 0)->com_radius;
    double al = rd_ring_get_segment_angle(c->ring, i), er[3], et[3];
    double Px = R * cos(al), Py = R * sin(al);
    rd_ring_segment_frame(c->ring, i, er, et);
    c->e_r[2 * i] = er[0];
    c->e_r[2 * i + 1] = er[1];
    c->e_t[2 * i] = et[0];
    c->e_t[2 * i + 1] = et[1];
    c->cen_d[2 * i] = (rc_com - R) * er[0];
    c->cen_d[2 * i + 1] = (rc_com - R) * er[1];
    for (int a = 0; a < ARC_POINTS; a++) {
        double psi = al + (a - 0.5 * (ARC_POINTS - 1)) * phi / ARC_POINTS;
        double cp = cos(psi), sp = sin(psi);
        double *fd = c->fl_d + 2 * (FLANK_POINTS * (size_t)i + 2 * a);
        fd[0] = ri * cp - Px;
        fd[1] = ri * sp - Py;
        fd[2] = ro * cp - Px;
        fd[3] = ro * sp - Py;
        size_t o = 2 * (ARC_POINTS * (size_t)i + a);
        c->bo_d[o] = r_run * cp - Px;
        c->bo_d[o + 1] = r_run * sp - Py;
        c->bo_e[o] = cp;
        c->bo_e[o + 1] = sp;
        c->ba_d[o] = r_back * cp - Px;
        c->ba_d[o + 1] = r_back * sp - Py;
    }
}

/* M_i^-1 by Cholesky (dpotrf + dpotri), and M_i e_z. */
static int model_mass(rd_lift_model *c, int i, rd_error *err)
{
    const double *Ms = rd_ring_segment_mass_matrix(c->ring, i);
    double *Mi = c->Minv + 36 * (size_t)i;
    memcpy(Mi, Ms, 36 * sizeof *Mi);
    int info = LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'U', 6, Mi, 6);
    if (info == 0)
        info = LAPACKE_dpotri(LAPACK_ROW_MAJOR, 'U', 6, Mi, 6);
    if (info != 0)
        return rd_error_set(err, RD_ENUMERIC, "",
                            "The mass matrix of segment %d is not positive definite "
                            "(LAPACK info %d).",
                            i, info);
    for (int r = 0; r < 6; r++)
        for (int k = 0; k < r; k++)
            Mi[6 * r + k] = Mi[6 * k + r];
    for (int k = 0; k < 6; k++)
        c->Mez[6 * i + k] = Ms[6 * k + 2];
    return RD_OK;
}

/* -M_i^-1 K_ij for j = i-1, i, i+1 from the upper band storage (K
 * symmetric, kd = 11). */
static void model_stiffness_blocks(rd_lift_model *c, int i)
{
    for (int j = i - 1; j <= i + 1; j++) {
        if (j < 0 || j >= c->n)
            continue;
        double Kij[36];
        for (int r = 0; r < 6; r++)
            for (int k = 0; k < 6; k++) {
                int gi = rd_ring_band_index(c->ring, i, r), gj = rd_ring_band_index(c->ring, j, k);
                Kij[6 * r + k] = gi <= gj ? RD_BAND_AT(&c->K, gi, gj) : RD_BAND_AT(&c->K, gj, gi);
            }
        double *B = c->MK + 36 * (3 * (size_t)i + (j - i + 1));
        const double *Mi = c->Minv + 36 * (size_t)i;
        for (int r = 0; r < 6; r++)
            for (int k = 0; k < 6; k++) {
                double v = 0.0;
                for (int m = 0; m < 6; m++)
                    v -= Mi[6 * r + m] * Kij[6 * m + k];
                B[6 * r + k] = v;
            }
    }
}

int rd_lift_model_films(rd_lift_model *c, rd_error *err)
{
    free(c->film_grp);
    c->film_grp = c->film_seg = NULL;
    if (!c->p->films) /* a distorted bore's films (rd_lift_films_at) */
        return RD_OK;
    c->film_grp = malloc(((size_t)c->p->films->count + (size_t)c->n) * sizeof *c->film_grp);
    c->film_seg = c->film_grp ? c->film_grp + c->p->films->count : NULL;
    return c->film_grp ? RD_OK
                       : rd_error_set(err, RD_ENOMEM, "", "Out of memory for the segments' films.");
}

int rd_lift_model_init(rd_lift_model *c, const rd_ring *ring, const rd_lift_params *p,
                       const rd_lift_setup *setup, rd_error *err)
{
    const rd_ring_params *rp = rd_ring_get_params(ring);
    const rd_section *s = rd_ring_get_cross_section(ring);
    const rd_ring_section *sec = rd_ring_get_section(ring);
    int rc;
    memset(c, 0, sizeof *c);
    c->kin_t = NAN;
    c->ring = ring;
    c->p = p;
    c->n = rd_ring_get_segments(ring);
    model_constants(c, rp, p, setup);
    model_areas(c, s, sec);
    if ((rc = model_alloc(c, err)))
        return rc;
    rd_band M;
    if ((rc = rd_ring_assemble_band(ring, &c->K, &M, err)))
        return rc;
    rd_band_cleanup(&M); /* the block-diagonal M_i are used directly */
    for (int i = 0; i < c->n; i++) {
        model_points(c, i, s, sec);
        if ((rc = model_mass(c, i, err)))
            return rc;
    }
    for (int i = 0; i < c->n; i++)
        model_stiffness_blocks(c, i);
    return rd_lift_bore_init(c, err);
}

/* ------------------------------------------------ right-hand side, Jacobian */

int rd_lift_cv_rhs(sunrealtype t, N_Vector yv, N_Vector ydv, void *user)
{
    rd_lift_model *c = user;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydv);
    rd_lift_forces(c, t, y, NULL, NULL);
    for (int i = 0; i < c->n; i++)
        memcpy(c->qbuf + 6 * i, Q(y, i), 6 * sizeof(double));
    double *Kq = c->qbuf + 6 * (size_t)c->n; /* second half of the scratch */
    rd_band_symv(&c->K, c->qbuf, Kq);
    for (int i = 0; i < c->n; i++) {
        const double *Mi = c->Minv + 36 * (size_t)i;
        double fi[6];
        for (int k = 0; k < 6; k++)
            fi[k] = c->fbuf[6 * i + k] - Kq[6 * i + k];
        memcpy(Q(yd, i), V(y, i), 6 * sizeof(double));
        double *acc = V(yd, i);
        for (int r = 0; r < 6; r++)
            acc[r] = rd_lift_dot6(Mi + 6 * r, fi);
    }
    for (size_t j = 0; j < 12 * (size_t)c->n; j++)
        if (!isfinite(yd[j]))
            return 1; /* recoverable: CVODE retries with a smaller step */
    return 0;
}

/* The second-order blocks (rd_lift_model.h, rd_lift_form.blocks):
 *   A_ij = -M_i^-1 K_ij (+ M_i^-1 df_i/dq_i for j = i),  B_i = M_i^-1 df_i/dv_i. */
static void full_blocks(void *user, double t, const double *y, double *A, double *B)
{
    rd_lift_model *c = user;
    rd_lift_forces(c, t, y, c->Dq, c->Dv);
    for (int i = 0; i < c->n; i++) {
        const double *Mi = c->Minv + 36 * (size_t)i;
        const double *dq = c->Dq + 36 * (size_t)i, *dv = c->Dv + 36 * (size_t)i;
        double *Ai = A + 108 * (size_t)i, *Bi = B + 36 * (size_t)i;
        memcpy(Ai, c->MK + 108 * (size_t)i, 108 * sizeof *Ai);
        for (int r = 0; r < 6; r++)
            for (int k = 0; k < 6; k++) {
                double aq = 0.0, av = 0.0;
                for (int m = 0; m < 6; m++) {
                    aq += Mi[6 * r + m] * dq[6 * m + k];
                    av += Mi[6 * r + m] * dv[6 * m + k];
                }
                Ai[36 + 6 * r + k] += aq;
                Bi[6 * r + k] = av;
            }
    }
}

/* Jacobian d(ydot)/dy as a band matrix (MU, ML) from the blocks (the
 * Jacobian check's view of what the Newton solver uses):
 *   d(dq_i/dt)/dv_i = I,  d(dv_i/dt)/dq_j = A_ij,  d(dv_i/dt)/dv_i = B_i. */
int rd_lift_cv_jac(sunrealtype t, N_Vector yv, N_Vector fy, SUNMatrix J, void *user, N_Vector t1,
                   N_Vector t2, N_Vector t3)
{
    (void)fy;
    (void)t1;
    (void)t2;
    (void)t3;
    rd_lift_model *c = user;
    double *A = malloc(144 * (size_t)c->n * sizeof *A), *B = A ? A + 108 * (size_t)c->n : NULL;
    if (!A || SUNMatZero(J)) {
        free(A);
        return -1; /* unrecoverable */
    }
    full_blocks(c, t, N_VGetArrayPointer(yv), A, B);
    for (int i = 0; i < c->n; i++) {
        sunindextype rq = 12 * (sunindextype)i, rv = rq + 6;
        for (int k = 0; k < 6; k++)
            SM_ELEMENT_B(J, rq + k, rv + k) = 1.0;
        for (int j = i - 1; j <= i + 1; j++) {
            if (j < 0 || j >= c->n)
                continue;
            const double *Aij = A + 36 * (3 * (size_t)i + (j - i + 1));
            for (int r = 0; r < 6; r++)
                for (int k = 0; k < 6; k++)
                    SM_ELEMENT_B(J, rv + r, 12 * (sunindextype)j + k) = Aij[6 * r + k];
        }
        for (int r = 0; r < 6; r++)
            for (int k = 0; k < 6; k++)
                SM_ELEMENT_B(J, rv + r, rv + k) = B[36 * (size_t)i + 6 * r + k];
    }
    free(A);
    return 0;
}

double rd_lift_model_mean_lift(const rd_lift_model *c, const double *y, double *seg)
{
    double sum = 0.0;
    for (int i = 0; i < c->n; i++) {
        const double *u = Q(y, i);
        double s = 0.0;
        for (int k = 0; k < FLANK_POINTS; k++) {
            const double *d = c->fl_d + 2 * (FLANK_POINTS * (size_t)i + k);
            s += u[2] + u[3] * d[1] - u[4] * d[0]; /* axial displacement at d */
        }
        s /= FLANK_POINTS;
        if (seg)
            seg[i] = s;
        sum += s;
    }
    return sum / c->n;
}

/* ------------------------------------------------ the full formulation */

static double full_lift(void *user, const double *y, double *seg)
{
    return rd_lift_model_mean_lift(user, y, seg);
}

static void full_loads(void *user, double t, const double *y)
{
    rd_lift_loads(user, t, y);
}

/* Plastic landing of the full ring: the mean axial rate of the segments
 * (equal masses) towards the flank is removed from every segment, so the
 * ring's rigid axial motion stops and its elastic motion keeps going. */
static void full_impact(void *user, double *y, int upper)
{
    rd_lift_model *c = user;
    double mean = 0.0;
    for (int i = 0; i < c->n; i++)
        mean += V(y, i)[2];
    mean /= c->n;
    if (upper ? mean <= 0.0 : mean >= 0.0)
        return;
    for (int i = 0; i < c->n; i++)
        V(y, i)[2] -= mean;
}

/* atol on the translations (m), atol / R on the rotations, and atol w_v on
 * their rates (rd_lift_driver.c); the seated ring at rest unless given. */
static int full_initial(void *user, const rd_lift_setup *setup, double atol, double *y, double *at,
                        rd_error *err)
{
    (void)err;
    const rd_lift_model *c = user;
    const rd_ring_params *rp = rd_ring_get_params(c->ring);
    double R = rd_ring_get_section(c->ring)->R;
    double wv = sqrt(rd_lift_accel_scale(rp, c->p) / c->ca); /* velocity / position ratio */
    for (int i = 0; i < c->n; i++)
        for (int k = 0; k < 6; k++) {
            double a = k < 3 ? atol : atol / R;
            Q(at, i)[k] = a;
            V(at, i)[k] = a * wv;
        }
    size_t N = 12 * (size_t)c->n;
    if (setup && setup->y0)
        memcpy(y, setup->y0, N * sizeof *y);
    else
        memset(y, 0, N * sizeof *y);
    return RD_OK;
}

void rd_lift_full_form(rd_lift_model *m, rd_lift_form *form)
{
    *form = (rd_lift_form){.name = "full",
                           .N = 12 * (sunindextype)m->n,
                           .dense = 0,
                           .user = m,
                           .m = m,
                           .rhs = rd_lift_cv_rhs,
                           .jac = rd_lift_cv_jac,
                           .block = 6,
                           .blocks = full_blocks,
                           .impact = full_impact,
                           .lift = full_lift,
                           .loads = full_loads,
                           .expand = NULL,
                           .initial = full_initial};
}
