/*
 * rd_static_problem — the static chain's problem: its state, reference
 * geometry, gap faces and support set up from a ring (rd_static_problem_init),
 * freed (rd_static_problem_cleanup), and a body point's place
 * (rd_static_point_at); and the chain's own loads, which pretension and
 * contact both apply: a force at a body point (rd_static_add_force), F_t's
 * load factor and the gap faces' loads (rd_static_gap_face_load: F_t by
 * the force or the field method, F_l).  The residual, tangent and solver
 * are in rd_static.c and rd_static_tangent.c; the model in rd_static.h.
 */
#include "rd_static_problem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A problem whose loads are the chain's own (pretension's). */
static const rd_static_loads chain_only = {0};

int rd_static_problem_init(rd_static_problem *pb, const rd_ring *ring, const rd_static_loads *loads)
{
    int n = rd_ring_get_segments(ring);
    memset(pb, 0, sizeof *pb);
    pb->ring = ring;
    pb->loads = loads ? loads : &chain_only;
    pb->n = n;
    pb->R = rd_ring_get_section(ring)->R;
    const rd_section *sec = rd_ring_get_cross_section(ring);
    pb->b = sec->b;
    pb->h = sec->h;
    pb->Kc = rd_ring_joint_stiffness(ring, 0);
    pb->E = malloc((size_t)9 * n * sizeof *pb->E);
    pb->dP0 = malloc((size_t)3 * n * sizeof *pb->dP0);
    pb->x = malloc((size_t)3 * n * sizeof *pb->x);
    pb->Q = malloc((size_t)9 * n * sizeof *pb->Q);
    if (!pb->E || !pb->dP0 || !pb->x || !pb->Q)
        return RD_ENOMEM;
    for (int i = 0; i < n; i++) {
        memcpy(pb->x + 3 * i, rd_ring_reference_point(ring, i), 3 * sizeof(double));
        double eye[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(pb->Q + 9 * i, eye, sizeof eye);
    }
    for (int j = 0; j < n - 1; j++) {
        const double *PA = rd_ring_reference_point(ring, j),
                     *PB = rd_ring_reference_point(ring, j + 1);
        double *E = pb->E + 9 * j, *d = pb->dP0 + 3 * j;
        for (int k = 0; k < 3; k++)
            d[k] = PB[k] - PA[k];
        double L = sqrt(rd_dot3(d, d));
        double e1[3] = {d[0] / L, d[1] / L, d[2] / L}, e2[3] = {0, 0, 1}, e3[3];
        rd_cross3(e1, e2, e3);
        memcpy(E, e1, sizeof e1);
        memcpy(E + 3, e2, sizeof e2);
        memcpy(E + 6, e3, sizeof e3);
    }
    /* gap faces: neutral-axis points and the opening directions */
    double s = rd_ring_get_segment_angle(ring, 0) - 0.5 * rd_ring_segment_phi_at(ring, 0);
    double sB = 2.0 * M_PI - s;
    const double *P0 = rd_ring_reference_point(ring, 0), *Pn = rd_ring_reference_point(ring, n - 1);
    double fa[3] = {pb->R * cos(s), pb->R * sin(s), 0},
           fb[3] = {pb->R * cos(sB), pb->R * sin(sB), 0};
    for (int k = 0; k < 3; k++) {
        pb->cA[k] = fa[k] - P0[k];
        pb->cB[k] = fb[k] - Pn[k];
    }
    double tA[3] = {-sin(s), cos(s), 0}, tB[3] = {sin(sB), -cos(sB), 0};
    memcpy(pb->tA, tA, sizeof tA);
    memcpy(pb->tB, tB, sizeof tB);
    /* support: the section opposite the gap (on a graded ring the segments
     * beside pi, or the one centred on it) */
    pb->pa = (n - 1) / 2;
    pb->pb = n / 2;
    if (rd_ring_is_graded(ring)) {
        int i = 0;
        while (i < n - 1 && rd_ring_get_segment_angle(ring, i + 1) <= M_PI)
            i++;
        double a = rd_ring_get_segment_angle(ring, i);
        pb->pa = i;
        pb->pb = fabs(a - M_PI) < 1e-3 * rd_ring_segment_phi_at(ring, i) || i == n - 1 ? i : i + 1;
    }
    pb->k_t = 1e3 * pb->Kc[0];
    pb->k_r = 1e3 * fmax(pb->Kc[6 * 3 + 3], fmax(pb->Kc[6 * 4 + 4], pb->Kc[6 * 5 + 5]));
    return RD_OK;
}

void rd_static_problem_cleanup(rd_static_problem *pb)
{
    free(pb->E);
    free(pb->dP0);
    free(pb->e0);
    free(pb->dead);
    free(pb->x);
    free(pb->Q);
    free(pb->cp);
    free(pb->mult);
    free(pb->pe);
}

void rd_static_point_at(const rd_static_problem *pb, int i, const double c[3], double y[3])
{
    rd_mv3(pb->Q + 9 * i, c, y);
    for (int k = 0; k < 3; k++)
        y[k] += pb->x[3 * i + k];
}

/* ---- the chain's own loads ---------------------------------------------- */

/* Adds (F, (y - x) x F) for a force F at body offset c of a segment at (x, Q). */
void rd_static_add_force(const double *Q, const double c[3], const double F[3], double f[6])
{
    double arm[3], M[3];
    rd_mv3(Q, c, arm);
    rd_cross3(arm, F, M);
    for (int k = 0; k < 3; k++) {
        f[k] += F[k];
        f[3 + k] += M[k];
    }
}

/* The load path of F_t: the problem's (contact: rd_contact_force_factor),
 * or F_t and F_l growing with lambda (pretension). */
double rd_static_force_factor(const rd_static_problem *pb)
{
    return pb->loads->force_factor ? pb->loads->force_factor(pb) : pb->lambda;
}

/* Field method: the force on the J face (follows that face) and the point
 * where it acts. */
static void field_force(const rd_static_problem *pb, const double *xJ, const double *QJ,
                        double F[3], double pJ[3])
{
    int first = pb->jseg == 0;
    double t[3], c[3];
    rd_mv3(QJ, first ? pb->tA : pb->tB, t);
    rd_mv3(QJ, first ? pb->cA : pb->cB, c);
    for (int k = 0; k < 3; k++) {
        F[k] = rd_static_force_factor(pb) * pb->Ft * t[k];
        pJ[k] = xJ[k] + c[k];
    }
}

/* The gap-face loads on segment i (0 or n - 1): the pretension F_t, by the
 * force or the field method, and the lateral force F_l (0 in contact). */
void rd_static_gap_face_load(const rd_static_problem *pb, int i, const double *x, const double *Q,
                             double f[6])
{
    const double *c = i == 0 ? pb->cA : pb->cB;
    double F[3];
    if (pb->method == RD_PRETENSION_FIELD) {
        double FJ[3], pJ[3];
        if (i == pb->jseg) {
            field_force(pb, x, Q, F, pJ);
        } else {
            /* equal and opposite vector on the I face, plus the couple that
             * keeps the pair's moment zero */
            double arm[3], M[3];
            field_force(pb, pb->x + 3 * pb->jseg, pb->Q + 9 * pb->jseg, FJ, pJ);
            rd_mv3(Q, c, arm);
            for (int k = 0; k < 3; k++) {
                F[k] = -FJ[k];
                arm[k] += x[k] - pJ[k];
            }
            rd_cross3(arm, FJ, M);
            for (int k = 0; k < 3; k++)
                f[3 + k] += M[k];
        }
    } else {
        double t[3];
        rd_mv3(Q, i == 0 ? pb->tA : pb->tB, t);
        for (int k = 0; k < 3; k++)
            F[k] = rd_static_force_factor(pb) * pb->Ft * t[k];
    }
    F[2] += (i == 0 ? 1.0 : -1.0) * pb->lambda * pb->Fl;
    rd_static_add_force(Q, c, F, f);
}
