/*
 * rd_static_tangent — the tangent of the static chain's residual
 * (rd_static.c has the unknowns, the residual and the solver).
 *
 * Each joint's 12x12 block in closed form, the exact derivative of g
 * (rd_static.c's header) including the turn of Jl^-T(psi) (rd_static_joint.c; central differences
 * of g, 24 evaluations a joint, were 35 % of a contact solve's instructions),
 * the contact load's derivative in closed form (rd_contact_segment_jacobian,
 * with flexible faces also rd_contact_face_jacobian's neighbour blocks), the
 * gap faces' loads by central differences (6 perturbations on each of two
 * segments), the support's exactly; assembled in 6x6 blocks, block
 * tridiagonal (a joint couples two neighbours, the support holds two
 * neighbours or one segment), and factored by the block Thomas algorithm
 * (rd_blocktri.c: a third of the instructions of LAPACK's band LU of half
 * bandwidth 11).  A flexible contact face couples its segment's two
 * neighbours, i - 1 with i + 1, outside the three 6x6 block diagonals: then
 * the segments go in pairs, 12x12 blocks (n odd: a last, decoupled dummy
 * segment with an identity block), again block tridiagonal (n = 320: 2.6 M
 * instructions a factorization, LAPACK's band LU of half bandwidth 17 3.5 M).
 * The contact ring stays exactly planar, and its tangent couples no
 * in-plane DOF (dx, dy, dpsi_z) with an out-of-plane one: then the two
 * halves are factored apart (rd_blocktri_split, rd_static.c's plane_solve),
 * the same numbers at a quarter of the cost.  The factorization pivots only
 * inside the diagonal blocks; its pivot blocks are the tangents of the
 * sub-chain 0..i with segment i + 1 held, a cantilever, regular wherever the
 * chain's own stiffness outweighs its load terms; an exactly singular one
 * counts as a singular tangent (the load step is cut).  The field method
 * couples the first segment's load to the last segment's state, outside the
 * three block diagonals: that 6x6 block is added exactly by the Woodbury
 * identity on the factorization (rd_static.c's newton_step).
 *
 * The contact blocks are read from the points' evaluation of the last
 * residual (rd_contact_loads' pb->pe): rd_static_tangent is called at that
 * residual's state, as Newton's method does.
 */
#include "rd_static_internal.h"

#include <math.h>
#include <string.h>

/* Perturbed copy of one segment state: direction k (0..2 translate, 3..5
 * rotate) by h. */
void rd_static_perturb(const double *x, const double *Q, int k, double h, double xo[3],
                       double Qo[9])
{
    memcpy(xo, x, 3 * sizeof *x);
    memcpy(Qo, Q, 9 * sizeof *Q);
    if (k < 3) {
        xo[k] += h;
    } else {
        double w[3] = {0, 0, 0}, Rw[9];
        w[k - 3] = h;
        rd_static_rot_exp(w, Rw);
        rd_mm3(Rw, Q, Qo);
    }
}

/* Segments per block of the tangent: 2 with flexible faces (tangent). */
int rd_static_per_block(const rd_static_problem *pb)
{
    return pb->cp0 ? 2 : 1;
}

/* The tangent's 6x6 sub-block of the rows of segment a and the columns of
 * segment b (row stride t->bs), in block row a / s (s = t->bs / 6 segments a
 * block; a / s and b / s equal or neighbours): that block row's D, U or L. */
static double *block(rd_blocktri *t, int a, int b)
{
    int s = t->bs / 6, A = a / s, B = b / s;
    double *base = (B == A ? t->D : B > A ? t->U : t->L) + (size_t)t->bs * t->bs * A;
    return base + (size_t)t->bs * 6 * (a % s) + 6 * (b % s);
}

/* Adds segment i's flexible face's part of the contact loads' derivative:
 * the loads on segments i - 1 .. i + 1 by the DOFs of i - 1 .. i + 1. */
static void face_blocks(rd_static_problem *pb, rd_blocktri *t, int i)
{
    double K[RD_FACE_DOFS][RD_FACE_DOFS], *B[3][3];
    if (!rd_contact_face_jacobian(pb, i, K))
        return; /* none of its points presses */
    for (int b = 0; b < 3; b++)
        for (int c = 0; c < 3; c++) {
            int sb = i - 1 + b, sc = i - 1 + c;
            B[b][c] = sb < 0 || sb >= pb->n || sc < 0 || sc >= pb->n ? NULL : block(t, sb, sc);
        }
    for (int q = 0; q < RD_FACE_DOFS; q++)
        for (int c = 0; c < RD_FACE_DOFS; c++) {
            double *Bq = B[rd_face_dof_seg[q]][rd_face_dof_seg[c]];
            if (Bq)
                Bq[t->bs * rd_face_dof[q] + rd_face_dof[c]] -= K[q][c];
        }
}

/* B (row stride ld) = B + K or, add 0, = K, for the 6x6 part of the
 * row-major 12x12 K at K's pointer. */
static void put_block(double *B, int ld, const double *K, int add)
{
    for (int r = 0; r < 6; r++)
        for (int c = 0; c < 6; c++)
            B[ld * r + c] = (add ? B[ld * r + c] : 0.0) + K[12 * r + c];
}

/* The joints' blocks, exact (rd_static_joint.c, K row-major 12x12), into
 * the tangent.  With single segments joint j is the only one in U_j and
 * L_j+1 and the first in D_j+1: those are set, not added to, so only D_0 is
 * cleared (L_0 and U_n-1 are not read); with pairs all is cleared and added
 * to (and the dummy segment, n odd, gets its identity). */
static void joint_blocks(rd_static_problem *pb, rd_blocktri *t)
{
    int n = pb->n, ld = t->bs, add = ld != 6;
    size_t blocks = (size_t)t->nb * ld * ld;
    memset(t->D, 0, (add ? blocks : 36) * sizeof *t->D);
    if (add) {
        memset(t->L, 0, blocks * sizeof *t->L);
        memset(t->U, 0, blocks * sizeof *t->U);
        for (int k = 6 * n; k < t->nb * ld; k++)
            t->D[blocks - (size_t)ld * ld + (size_t)(ld + 1) * (k % ld)] = 1.0;
    }
    for (int j = 0; j < n - 1; j++) {
        double K[144];
        rd_static_joint_tangent(pb, j, pb->x + 3 * j, pb->Q + 9 * j, pb->x + 3 * (j + 1),
                                pb->Q + 9 * (j + 1), K);
        put_block(block(t, j, j), ld, K, 1);
        put_block(block(t, j, j + 1), ld, K + 6, add);
        put_block(block(t, j + 1, j), ld, K + 72, add);
        put_block(block(t, j + 1, j + 1), ld, K + 78, add);
    }
}

/* The tangent of the whole residual, in block-tridiagonal storage: 6x6
 * blocks, or 12x12 (pairs of segments) with flexible faces (work_alloc).
 * At the state of the last residual(): the contact faces and points as it
 * left them (rd_contact_loads' pb->pe). */
void rd_static_tangent(rd_static_problem *pb, rd_blocktri *t)
{
    int n = pb->n, ld = t->bs;
    double hx = 1e-6 * pb->R, hr = 1e-6;
    joint_blocks(pb, t);
    /* External loads: the contact law's derivative in closed form (differences
     * inside its bend eps were 63 % of a contact solve), the gap faces' by differences. */
    for (int i = 0; i < n; i++) {
        double J[36] = {0};
        if (pb->kind == RD_STATIC_CONTACT)
            rd_contact_segment_jacobian(pb, i, J);
        if (pb->cp0)
            face_blocks(pb, t, i);
        double *D = block(t, i, i);
        for (int k = 0; k < 6; k++) {
            double h = k < 3 ? hx : hr, fp[6] = {0}, fm[6] = {0}, xp[3], Qp[9];
            if (i == 0 || i == n - 1) {
                rd_static_perturb(pb->x + 3 * i, pb->Q + 9 * i, k, h, xp, Qp);
                rd_pretension_gap_face_load(pb, i, xp, Qp, fp);
                rd_static_perturb(pb->x + 3 * i, pb->Q + 9 * i, k, -h, xp, Qp);
                rd_pretension_gap_face_load(pb, i, xp, Qp, fm);
            }
            for (int row = 0; row < 6; row++)
                D[ld * row + k] += -J[row + 6 * k] - (fp[row] - fm[row]) / (2.0 * h);
        }
    }
    /* support: translations 1/4 k_t mask; rotations 1/4 k_r A_a mask A_c^T
     * with A = Jl^-T(psi) (the derivative of log on each side; the held mean
     * rotation is ~0 but each segment's own psi is not) */
    int s[2] = {pb->pa, pb->pb};
    double A[2][9];
    for (int q = 0; q < 2; q++) {
        double psi[3];
        rd_static_rot_log(pb->Q + 9 * s[q], psi);
        for (int k = 0; k < 3; k++) {
            double e[3] = {0, 0, 0}, col[3];
            e[k] = 1.0;
            rd_static_jl_inv_t(psi, e, col);
            for (int r = 0; r < 3; r++)
                A[q][3 * r + k] = col[r];
        }
    }
    for (int a = 0; a < 2; a++)
        for (int c = 0; c < 2; c++) {
            double *B = block(t, s[a], s[c]); /* s[0], s[1] equal or neighbours */
            for (int k = 0; k < 3; k++)
                B[(ld + 1) * k] += 0.25 * pb->k_t * pb->mask[k];
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++) {
                    double v = 0.0;
                    for (int k = 0; k < 3; k++)
                        v += A[a][3 * r + k] * pb->mask[3 + k] * A[c][3 * q + k];
                    B[ld * (3 + r) + 3 + q] += 0.25 * pb->k_r * v;
                }
        }
}

/* Adds mu |J_ii| to the tangent's diagonal (Marquardt's scaling): a step in a
 * direction the tangent barely resists (a ring losing the bore, a rigid
 * motion nothing holds) stays bounded. */
void rd_static_damp(rd_static_problem *pb, rd_blocktri *t, double mu)
{
    for (int i = 0; i < pb->n; i++)
        for (int k = 0; k < 6; k++) {
            double *d = block(t, i, i) + (t->bs + 1) * k;
            *d += mu * fabs(*d);
        }
}
