/*
 * rd_contact_face — the running face of a contact segment as the bent,
 * sheared ring would have it, not as a rigid arc.
 *
 * A segment is rigid: its face is an arc of the closed ring's radius r_o
 * turned with the section (Q_i).  The ring it stands for bends and shears
 * between its joints, and in a bore it follows the bore's curvature; a rigid
 * face then misfits the bore by (curvature change) L^2 / 8 (~20 nm at 1 x
 * the thin-ring bound, n = 160-320) and, turned with the section rather
 * than with the centreline, by the shear angle gamma = V / (k G A) times
 * L / 2 (~1e-5 rad: ~4 nm at n = 320), both far above the law's
 * penetrations (~p0 / k = 1 nm).  The face then touches at its ends, its
 * middle or one end, and the segment's contact force carries a couple the
 * ring does not have: the binned pressure missed the reference by 0.04 p0
 * at both n = 160 and 320 (bench_static --bins 4 1 0 N).
 *
 * The face here: each contact point k at arc length s (at the neutral
 * radius R, from the segment's centre) is moved outward by
 *   u(s) = -(kap_c s^2 / 2 + kap' s^3 / 6) - (gam_c s + gam' s^2 / 2),
 * kap the curvature change and gam the shear angle, each interpolated
 * linearly between the segment's two joints (at s = -L/2, +L/2, L = R phi):
 * the centreline through the segment's centre x_i, its tangent there the
 * section's turn plus the shear.  At joint j (segments j, j + 1, planar: a
 * turn rz about the axis; the second term of kap the chord's stretch, which
 * curves the face as a uniformly expanded ring's)
 *   kap_j = (rz_(j+1) - rz_j) / L_j - (|x_(j+1) - x_j| / |P_(j+1) - P_j| - 1) / R,
 *   gam_j = (turn of the chord x_(j+1) - x_j) - (rz_j + rz_(j+1)) / 2,
 * L_j = R (phi_j + phi_(j+1)) / 2 the arc between the two middles (R phi
 * on equal segments; a graded ring's segments each have their own phi and
 * L, so their points' weights too, face_weights); at a free end kap = 0
 * (no moment on the gap face) and gam is the inner joint's.  u depends on
 * the planar DOFs (dx, dy, dpsi_z) of segments i - 1, i, i + 1 (face_du);
 * the face's block of the contact loads' derivative
 * (rd_contact_face_jacobian) puts that into the tangent, so Newton sees the
 * face it solves with.
 *
 * The contact loads of all segments are computed here in one pass
 * (rd_contact_loads), which keeps each point's evaluation (pb->pe,
 * rd_contact_eval) for the tangent and the multipliers' update: a Newton
 * iteration evaluates each point once.  Points off the bore (law and slope
 * exactly 0) are skipped past their penetration.
 */
#include "rd_static_internal.h"

#include <math.h>

/* Joint j's values v = (kap, gam) and their derivatives by the planar DOFs
 * (dx, dy, dpsi_z) of its segments j (dA) and j + 1 (dB); zero past the
 * ends.  The segments' turns from pb->face_rz (rd_contact_face_update). */
static void joint_face(const rd_static_problem *pb, int j, double v[2], double dA[2][3],
                       double dB[2][3])
{
    memset(v, 0, 2 * sizeof *v);
    memset(dA, 0, 6 * sizeof **dA);
    memset(dB, 0, 6 * sizeof **dB);
    if (j < 0 || j >= pb->n - 1)
        return;
    /* the arc between the two segments' middles */
    double L = pb->R * 0.5 *
               (rd_ring_segment_phi_at(pb->ring, j) + rd_ring_segment_phi_at(pb->ring, j + 1));
    const double *d0 = pb->dP0 + 3 * j, *xa = pb->x + 3 * j, *xb = pb->x + 3 * (j + 1);
    double turn = remainder(pb->face_rz[j + 1] - pb->face_rz[j], 2.0 * M_PI);
    double d[2] = {xb[0] - xa[0], xb[1] - xa[1]}, dd = d[0] * d[0] + d[1] * d[1];
    double chord = atan2(d0[0] * d[1] - d0[1] * d[0], d0[0] * d[0] + d0[1] * d[1]);
    double len = sqrt(dd), len0 = hypot(d0[0], d0[1]), e = (len / len0 - 1.0) / pb->R;
    v[0] = turn / L - e;
    v[1] = chord - pb->face_rz[j] - 0.5 * turn;
    dA[0][0] = d[0] / (len * len0 * pb->R), dA[0][1] = d[1] / (len * len0 * pb->R);
    dB[0][0] = -dA[0][0], dB[0][1] = -dA[0][1];
    dA[0][2] = -1.0 / L;
    dB[0][2] = 1.0 / L;
    dA[1][0] = d[1] / dd, dA[1][1] = -d[0] / dd, dA[1][2] = -0.5;
    dB[1][0] = -d[1] / dd, dB[1][1] = d[0] / dd, dB[1][2] = -0.5;
}

/* du / d(kap_L, kap_R, gam_L, gam_R) of each point k of an inner segment
 * of segment i's length (the same for all of that length: evenly spaced
 * points), kept in c and computed again only for another length. */
typedef struct face_w {
    double phi;
    double w[RD_CONTACT_POINTS_MAX][4];
} face_w;

static const double (*face_weights(const rd_static_problem *pb, int i, face_w *c))[4]
{
    double phi = rd_ring_segment_phi_at(pb->ring, i), L = pb->R * phi;
    if (phi == c->phi)
        return c->w;
    c->phi = phi;
    double(*w)[4] = c->w;
    for (int k = 0; k < pb->m; k++) {
        double s = pb->R * rd_contact_point_offset(pb, i, k);
        w[k][0] = -(s * s / 4.0 - s * s * s / (6.0 * L));
        w[k][1] = -(s * s / 4.0 + s * s * s / (6.0 * L));
        w[k][2] = -(s / 2.0 - s * s / (2.0 * L));
        w[k][3] = -(s / 2.0 + s * s / (2.0 * L));
    }
    return c->w;
}

/* The weights of a point of segment i from an inner segment's wk: a free
 * end's gam is its inner joint's. */
static const double *end_weights(const rd_static_problem *pb, int i, const double wk[4],
                                 double w[4])
{
    if (i != 0 && i != pb->n - 1)
        return wk;
    memcpy(w, wk, 4 * sizeof *w);
    if (i == 0)
        w[3] += w[2], w[2] = 0.0;
    if (i == pb->n - 1)
        w[2] += w[3], w[3] = 0.0;
    return w;
}

double rd_contact_point_offset(const rd_static_problem *pb, int i, int k)
{
    /* evenly spaced, each at the middle of its share */
    return (k + 0.5 - 0.5 * pb->m) * rd_ring_segment_phi_at(pb->ring, i) / pb->m;
}

/* Joint j's cached values and derivatives (rd_contact_face_update), zeros
 * past the ends. */
static const double *joint_cached(const rd_static_problem *pb, int j)
{
    static const double none[14];
    return j < 0 || j >= pb->n - 1 ? none : pb->face + 14 * j;
}

/* Point move u of segment i with weights w and, if du is not NULL,
 * du[b][d] its derivative by the planar DOF d (dx, dy, dpsi_z) of segment
 * i - 1 + b. */
static void face_du(const rd_static_problem *pb, int i, const double w[4], double *u,
                    double du[3][3])
{
    const double *l = joint_cached(pb, i - 1), *r = joint_cached(pb, i);
    *u = w[0] * l[0] + w[1] * r[0] + w[2] * l[1] + w[3] * r[1];
    if (!du)
        return;
    /* cache layout: kap, gam, dA[2][3], dB[2][3] */
    for (int d = 0; d < 3; d++) {
        du[0][d] = w[0] * l[2 + d] + w[2] * l[5 + d];
        du[1][d] = w[0] * l[8 + d] + w[2] * l[11 + d] + w[1] * r[2 + d] + w[3] * r[5 + d];
        du[2][d] = w[1] * r[8 + d] + w[3] * r[11 + d];
    }
}

void rd_contact_face_update(const rd_static_problem *pb)
{
    if (!pb->cp0)
        return;
    face_w fw = {.phi = -1.0};
    double wend[4];
    /* each segment's turn once (joint_face reads two a joint: the atan2
     * calls were 5 % of a contact solve's instructions) */
    for (int i = 0; i < pb->n; i++)
        pb->face_rz[i] = atan2(pb->Q[9 * i + 3], pb->Q[9 * i]);
    for (int j = 0; j < pb->n - 1; j++) {
        double *f = pb->face + 14 * j;
        joint_face(pb, j, f, (double(*)[3])(f + 2), (double(*)[3])(f + 8));
    }
    for (int i = 0; i < pb->n; i++) {
        const double *P = rd_ring_reference_point(pb->ring, i);
        const double(*wk)[4] = face_weights(pb, i, &fw);
        for (int k = 0; k < pb->m; k++) {
            const double *c0 = pb->cp0 + 3 * (pb->m * i + k);
            double *c = pb->cp + 3 * (pb->m * i + k), u;
            face_du(pb, i, end_weights(pb, i, wk[k], wend), &u, NULL);
            /* outward: the point's reference position over r_o */
            for (int q = 0; q < 2; q++)
                c[q] = c0[q] + u * (c0[q] + P[q]) / pb->r_o;
        }
    }
}

/* Point k of segment o at (x, Q), at the load factor's smoothing and bore
 * (at), into pe (rd_contact_eval); w the point's face weights (flexible
 * faces). */
static void point_at(const rd_static_problem *pb, int o, int k, const double *x, const double *Q,
                     const rd_contact_at *at, const double w[4], rd_contact_eval *pe)
{
    const double *c = pb->cp + 3 * (pb->m * o + k);
    double y[3], u;
    rd_mv3(Q, c, pe->arm);
    for (int q = 0; q < 3; q++)
        y[q] = x[q] + pe->arm[q];
    rd_contact_point(pb, o, k, y, at, pe);
    if (!rd_contact_presses(pe))
        return;
    pe->nn = sqrt(rd_dot3(pe->n, pe->n));
    if (pb->cp0) {
        const double *c0 = pb->cp0 + 3 * (pb->m * o + k), *P = rd_ring_reference_point(pb->ring, o);
        double out[3] = {(c0[0] + P[0]) / pb->r_o, (c0[1] + P[1]) / pb->r_o, 0.0};
        rd_mv3(Q, out, pe->dyu);
        face_du(pb, o, w, &u, pe->du);
    }
}

/* The planar DOFs (dx, dy, dpsi_z) among a segment's six. */
static const int planar[3] = {0, 1, 5};

/* Adds sg times the load of the point pe of segment o to f[b], the
 * generalized forces of segment o - 1 + b (NULL: not wanted).  The point's
 * force F at y_k works on every DOF y_k moves with: its own segment's as a
 * rigid body's, and through the face (u_k) the planar DOFs of segments
 * o - 1 .. o + 1. */
static void point_load(const rd_static_problem *pb, int o, const rd_contact_eval *pe, double sg,
                       double *f[3])
{
    if (pe->p == 0.0) /* F = 0 */
        return;
    double s = -sg * pe->p * pb->area[o] / pe->nn, F[3] = {s * pe->n[0], s * pe->n[1], 0.0}, M[3];
    if (f[1]) {
        rd_cross3(pe->arm, F, M);
        for (int q = 0; q < 3; q++)
            f[1][q] += F[q], f[1][3 + q] += M[q];
    }
    if (!pb->cp0)
        return;
    double fu = rd_dot3(F, pe->dyu);
    for (int b = 0; b < 3; b++)
        for (int d = 0; d < 3 && f[b]; d++)
            f[b][planar[d]] += fu * pe->du[b][d];
}

void rd_contact_segment_load(const rd_static_problem *pb, int i, const double *x, const double *Q,
                             double f[6])
{
    rd_contact_at at = rd_contact_now(pb);
    double wend[4];
    face_w fw = {.phi = -1.0};
    for (int o = i - 1; o <= i + 1; o++) {
        if (o < 0 || o >= pb->n || (o != i && !pb->cp0))
            continue;
        const double(*wk)[4] = face_weights(pb, o, &fw);
        double *fb[3] = {NULL, NULL, NULL};
        fb[i - o + 1] = f;
        for (int k = 0; k < pb->m; k++) {
            rd_contact_eval pe;
            point_at(pb, o, k, o == i ? x : pb->x + 3 * o, o == i ? Q : pb->Q + 9 * o, &at,
                     end_weights(pb, o, wk[k], wend), &pe);
            point_load(pb, o, &pe, 1.0, fb);
        }
    }
}

/* rd_contact_loads (again 0) and rd_contact_loads_again (1): a point that
 * pressed keeps the place, normal and face terms point_at found for it
 * and has its law evaluated again; one that did not is evaluated whole if
 * it presses now (its geometry was never filled). */
static void loads(const rd_static_problem *pb, double *r, int again)
{
    rd_contact_at at = rd_contact_now(pb);
    double wend[4];
    face_w fw = {.phi = -1.0};
    for (int o = 0; o < pb->n; o++) {
        const double(*wk)[4] = face_weights(pb, o, &fw);
        double *fb[3] = {o > 0 ? r + 6 * (o - 1) : NULL, r + 6 * o,
                         o < pb->n - 1 ? r + 6 * (o + 1) : NULL};
        for (int k = 0; k < pb->m; k++) {
            rd_contact_eval *pe = pb->pe + pb->m * o + k;
            int kept = again && rd_contact_presses(pe);
            if (again)
                rd_contact_law_again(pb, o, k, at.e, pe);
            if (!kept && (!again || rd_contact_presses(pe)))
                point_at(pb, o, k, pb->x + 3 * o, pb->Q + 9 * o, &at,
                         end_weights(pb, o, wk[k], wend), pe);
            point_load(pb, o, pe, -1.0, fb);
        }
    }
}

void rd_contact_loads(const rd_static_problem *pb, double *r)
{
    loads(pb, r, 0);
}

void rd_contact_loads_again(const rd_static_problem *pb, double *r)
{
    loads(pb, r, 1);
}

int rd_contact_face_jacobian(const rd_static_problem *pb, int o,
                             double K[RD_FACE_DOFS][RD_FACE_DOFS])
{
    int pressing = 0;
    if (!pb->cp0)
        return 0;
    for (int k = 0; k < pb->m; k++) {
        const rd_contact_eval *pe = pb->pe + pb->m * o + k;
        if (!rd_contact_presses(pe))
            continue;
        if (!pressing++)
            memset(K, 0, RD_FACE_DOFS * RD_FACE_DOFS * sizeof **K);
        /* g: d delta_k / d DOF (the order of rd_face_dof); gr its rigid part,
         * the owner's six */
        double g[RD_FACE_DOFS], gr[6], am[3];
        rd_cross3(pe->arm, pe->n, am);
        for (int d = 0; d < 3; d++)
            gr[d] = pe->n[d], gr[3 + d] = am[d];
        double nu = rd_dot3(pe->n, pe->dyu), c = -pb->area[o] * pe->dp / pe->nn;
        memcpy(g + 3, gr, sizeof gr);
        for (int d = 0; d < 3; d++) {
            g[d] = nu * pe->du[0][d];
            g[3 + planar[d]] += nu * pe->du[1][d];
            g[9 + d] = nu * pe->du[2][d];
        }
        /* d f / d q' = c g(q) g(q'), less the rigid part the closed form
         * has (the face's second derivatives, p / (k L) of this, left out):
         * h h' with h = gr on the owner's DOFs, 0 elsewhere (subtracting
         * an exact 0 there); symmetric, so its upper triangle only, the
         * rows unrolled (fixed lengths: 25 % fewer instructions) */
        double h[RD_FACE_DOFS] = {0};
        memcpy(h + 3, gr, sizeof gr);
#pragma GCC unroll 12
        for (int q = 0; q < RD_FACE_DOFS; q++)
            for (int t = q; t < RD_FACE_DOFS; t++)
                K[q][t] += c * (g[q] * g[t] - h[q] * h[t]);
    }
    for (int q = 0; pressing && q < RD_FACE_DOFS; q++)
        for (int t = 0; t < q; t++)
            K[q][t] = K[t][q];
    return pressing;
}
