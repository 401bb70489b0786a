/*
 * rd_static_tangent — the tangent of the static chain's residual
 * (rd_static.c has the unknowns, the residual and the solver).
 *
 * Each joint's 12x12 block in closed form, the exact derivative of g
 * (rd_static.c's header) including the turn of Jl^-T(psi) (rd_static_joint.c; central differences
 * of g, 24 evaluations a joint, were 35 % of a contact solve's instructions),
 * the problem's loads' derivative (pb->loads: contact's in closed form,
 * rd_contact_segment_jacobian, with flexible faces also
 * rd_contact_face_jacobian's neighbour blocks), the
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
 * halves are factored apart (rd_static.c's plane_solve), the same numbers
 * at a quarter of the cost, and rd_static_tangent_planar assembles them
 * straight into the halves, checking that every entry that would couple them
 * is exactly 0 (assembling the whole, then copying it into its halves, was
 * 17 % of a contact solve's instructions: clearing, filling and reading the
 * whole's zeros).  The factorization pivots only
 * inside the diagonal blocks; its pivot blocks are the tangents of the
 * sub-chain 0..i with segment i + 1 held, a cantilever, regular wherever the
 * chain's own stiffness outweighs its load terms; an exactly singular one
 * counts as a singular tangent (the load step is cut).  The field method
 * couples the first segment's load to the last segment's state, outside the
 * three block diagonals: that 6x6 block is added exactly by the Woodbury
 * identity on the factorization (rd_static.c's newton_step).
 *
 * The loads' blocks are read from their evaluation at the last residual
 * (contact: rd_contact_loads' pb->pe): rd_static_tangent is called at that
 * residual's state, as Newton's method does.
 */
#include "rd_static_problem.h"

#include <math.h>
#include <string.h>

#if defined(__GNUC__)
#define TG_INLINE static inline __attribute__((always_inline))
#else
#define TG_INLINE static inline
#endif

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

/* Segments per block of the tangent: 2 where the loads couple neighbours
 * (flexible contact faces; rd_static_tangent). */
int rd_static_per_block(const rd_static_problem *pb)
{
    return pb->loads->coupled && pb->loads->coupled(pb) ? 2 : 1;
}

const int rd_face_dof_seg[RD_FACE_DOFS] = {0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2};
const int rd_face_dof[RD_FACE_DOFS] = {0, 1, 5, 0, 1, 2, 3, 4, 5, 0, 1, 5};

/* A segment's DOFs (dx, dy, dz, dpsi_x, dpsi_y, dpsi_z) by half (0 in-plane,
 * 1 out-of-plane) and place in it; the DOFs of half h in order. */
static const int half_of[6] = {0, 0, 1, 1, 1, 0}, in_half[6] = {0, 1, 0, 1, 2, 2};
const int rd_plane_dof[2][3] = {{0, 1, 5}, {2, 3, 4}};

/* Where the tangent is assembled: the whole (part NULL), or its two halves
 * (part[0] in-plane, part[1] out-of-plane, 3 s DOFs a block each), and then
 * whether an entry between the halves was not 0 (the halves are void). */
typedef struct sink {
    rd_blocktri *t, *part;
    int s, coupled;
} sink;

/* The 6x6 sub-block of the rows of segment a and the columns of segment b
 * in block-tridiagonal storage m of s segments a block (a / s and b / s
 * equal or neighbours): that block row's D, U or L; its row stride m->bs. */
static double *block_in(rd_blocktri *m, int s, int a, int b)
{
    int A = a / s, B = b / s, d = m->bs / s; /* DOFs a segment: 6, or 3 in a half */
    double *base = (B == A ? m->D : B > A ? m->U : m->L) + (size_t)m->bs * m->bs * A;
    return base + (size_t)m->bs * d * (a % s) + d * (b % s);
}

/* The entry of row DOF r of segment a and column DOF c of segment b, or NULL
 * where it couples the halves. */
static double *entry(sink *k, int a, int r, int b, int c)
{
    if (!k->part)
        return block_in(k->t, k->s, a, b) + k->t->bs * r + c;
    if (half_of[r] != half_of[c])
        return NULL;
    rd_blocktri *m = k->part + half_of[r];
    return block_in(m, k->s, a, b) + m->bs * in_half[r] + in_half[c];
}

/* entry (a, r, b, c) += v; v must be 0 where the entry couples the halves. */
static void add_entry(sink *k, int a, int r, int b, int c, double v)
{
    double *e = entry(k, a, r, b, c);
    if (e)
        *e += v;
    else if (v != 0.0)
        k->coupled = 1;
}

/* put_block's half h (a literal: its DOFs then constants) into m;
 * returns 1 if an entry of K between half h's rows and the other half's
 * columns is not 0. */
TG_INLINE int put_half(rd_blocktri *m, int s, int a, int b, const double *K, int ld, int add, int h)
{
    double *B = block_in(m, s, a, b);
    const int *d = rd_plane_dof[h], *e = rd_plane_dof[1 - h];
    int coupled = 0;
    for (int r = 0; r < 3; r++) {
        const double *Kr = K + ld * d[r];
        double *Br = B + m->bs * r;
        if (add) {
            Br[0] += Kr[d[0]], Br[1] += Kr[d[1]], Br[2] += Kr[d[2]];
        } else { /* 0.0 + as the whole's put: -0.0 becomes 0.0 alike */
            Br[0] = 0.0 + Kr[d[0]], Br[1] = 0.0 + Kr[d[1]], Br[2] = 0.0 + Kr[d[2]];
        }
        coupled |= (Kr[e[0]] != 0.0) | (Kr[e[1]] != 0.0) | (Kr[e[2]] != 0.0);
    }
    return coupled;
}

/* The 6x6 block of segments a, b = that block + K or, add 0, = K, for the
 * 6x6 part of K at K's pointer (row stride ld). */
static void put_block(sink *k, int a, int b, const double *K, int ld, int add)
{
    if (!k->part) {
        double *B = block_in(k->t, k->s, a, b);
        for (int r = 0; r < 6; r++)
            for (int c = 0; c < 6; c++)
                B[k->t->bs * r + c] = (add ? B[k->t->bs * r + c] : 0.0) + K[ld * r + c];
        return;
    }
    int coupled = put_half(k->part, k->s, a, b, K, ld, add, 0);
    coupled |= put_half(k->part + 1, k->s, a, b, K, ld, add, 1);
    k->coupled |= coupled;
}

/* Adds the part of the loads' derivative that segment i's points take
 * from its neighbours (a flexible contact face): the loads on segments
 * i - 1 .. i + 1 by the DOFs of i - 1 .. i + 1. */
static void face_blocks(rd_static_problem *pb, sink *k, int i)
{
    double K[RD_FACE_DOFS][RD_FACE_DOFS];
    if (!pb->loads->face_jacobian(pb, i, K))
        return; /* none of its points presses */
    for (int q = 0; q < RD_FACE_DOFS; q++) {
        int a = i - 1 + rd_face_dof_seg[q];
        for (int c = 0; c < RD_FACE_DOFS && a >= 0 && a < pb->n; c++) {
            int b = i - 1 + rd_face_dof_seg[c];
            if (b >= 0 && b < pb->n)
                add_entry(k, a, rd_face_dof[q], b, rd_face_dof[c], -K[q][c]);
        }
    }
}

/* Each storage's blocks cleared as joint_blocks needs (add: all; else D_0),
 * and, n not a multiple of s, the dummy segment's identity. */
static void clear(rd_blocktri *m, int n, int s, int add)
{
    size_t blocks = (size_t)m->nb * m->bs * m->bs;
    memset(m->D, 0, (add ? blocks : (size_t)m->bs * m->bs) * sizeof *m->D);
    if (!add)
        return;
    memset(m->L, 0, blocks * sizeof *m->L);
    memset(m->U, 0, blocks * sizeof *m->U);
    int d = m->bs / s; /* DOFs a segment */
    for (int k = d * (n % s); n % s && k < m->bs; k++)
        m->D[blocks - (size_t)m->bs * m->bs + (size_t)(m->bs + 1) * k] = 1.0;
}

/* The joints' blocks, exact (rd_static_joint.c, K row-major 12x12), into
 * the tangent.  With single segments joint j is the only one in U_j and
 * L_j+1 and the first in D_j+1: those are set, not added to, so only D_0 is
 * cleared (L_0 and U_n-1 are not read); with pairs all is cleared and added
 * to (and the dummy segment, n odd, gets its identity). */
static void joint_blocks(rd_static_problem *pb, sink *k)
{
    int n = pb->n, add = k->s != 1;
    if (k->part) {
        clear(k->part, n, k->s, add);
        clear(k->part + 1, n, k->s, add);
    } else {
        clear(k->t, n, k->s, add);
    }
    for (int j = 0; j < n - 1; j++) {
        double K[144];
        rd_static_joint_tangent(pb, j, pb->x + 3 * j, pb->Q + 9 * j, pb->x + 3 * (j + 1),
                                pb->Q + 9 * (j + 1), K);
        put_block(k, j, j, K, 12, 1);
        put_block(k, j, j + 1, K + 6, 12, add);
        put_block(k, j + 1, j, K + 72, 12, add);
        put_block(k, j + 1, j + 1, K + 78, 12, add);
    }
}

/* The tangent of the whole residual into k (see rd_static_tangent). */
static void assemble(rd_static_problem *pb, sink *k, double mu)
{
    int n = pb->n;
    double hx = 1e-6 * pb->R, hr = 1e-6;
    joint_blocks(pb, k);
    /* External loads: the contact law's derivative in closed form (differences
     * inside its bend eps were 63 % of a contact solve), the gap faces' by differences. */
    for (int i = 0; i < n; i++) {
        double J[36] = {0}, Di[36];
        if (pb->loads->segment_jacobian)
            pb->loads->segment_jacobian(pb, i, J);
        if (k->s > 1) /* the loads couple neighbours */
            face_blocks(pb, k, i);
        for (int c = 0; c < 6; c++) {
            double h = c < 3 ? hx : hr, fp[6] = {0}, fm[6] = {0}, xp[3], Qp[9];
            if (i == 0 || i == n - 1) {
                rd_static_perturb(pb->x + 3 * i, pb->Q + 9 * i, c, h, xp, Qp);
                rd_static_gap_face_load(pb, i, xp, Qp, fp);
                rd_static_perturb(pb->x + 3 * i, pb->Q + 9 * i, c, -h, xp, Qp);
                rd_static_gap_face_load(pb, i, xp, Qp, fm);
            }
            for (int row = 0; row < 6; row++)
                Di[6 * row + c] = -J[row + 6 * c] - (fp[row] - fm[row]) / (2.0 * h);
        }
        put_block(k, i, i, Di, 6, 1);
    }
    /* support: translations 1/4 k_t mask; rotations 1/4 k_r A_a mask A_c^T
     * with A = Jl^-T(psi) (the derivative of log on each side; the held mean
     * rotation is ~0 but each segment's own psi is not) */
    int s[2] = {pb->pa, pb->pb};
    double A[2][9];
    for (int q = 0; q < 2; q++) {
        double psi[3];
        rd_static_rot_log(pb->Q + 9 * s[q], psi);
        for (int c = 0; c < 3; c++) {
            double e[3] = {0, 0, 0}, col[3];
            e[c] = 1.0;
            rd_static_jl_inv_t(psi, e, col);
            for (int r = 0; r < 3; r++)
                A[q][3 * r + c] = col[r];
        }
    }
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) { /* s[0], s[1] equal or neighbours */
            for (int c = 0; c < 3; c++)
                add_entry(k, s[a], c, s[b], c, 0.25 * pb->k_t * pb->mask[c]);
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++) {
                    double v = 0.0;
                    for (int c = 0; c < 3; c++)
                        v += A[a][3 * r + c] * pb->mask[3 + c] * A[b][3 * q + c];
                    add_entry(k, s[a], 3 + r, s[b], 3 + q, 0.25 * pb->k_r * v);
                }
        }
    /* Marquardt's scaling: mu |J_ii| added to the diagonal, so a step in a
     * direction the tangent barely resists (a ring losing the bore, a rigid
     * motion nothing holds) stays bounded. */
    for (int i = 0; i < n && mu > 0.0; i++)
        for (int c = 0; c < 6; c++) {
            double *d = entry(k, i, c, i, c);
            *d += mu * fabs(*d);
        }
}

void rd_static_tangent(rd_static_problem *pb, rd_blocktri *t, double mu)
{
    sink k = {t, NULL, rd_static_per_block(pb), 0};
    assemble(pb, &k, mu);
}

int rd_static_tangent_planar(rd_static_problem *pb, rd_blocktri part[2], double mu)
{
    sink k = {NULL, part, rd_static_per_block(pb), 0};
    assemble(pb, &k, mu);
    return !k.coupled;
}
