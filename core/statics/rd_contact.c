/*
 * rd_contact — the split ring pressed by F_t (force method, on the gap faces)
 * into a round or distorted bore, thesis 3.4.3; the model is in rd_static.h,
 * the chain's mechanics and solver in rd_static.c.
 *
 * Bore: r_b(theta) = r_o + mu (D/2 - r_o + sum A_k cos(k (theta - phi_k))),
 * r_o the closed ring's running-face radius, mu = 0 while F_t is applied
 * (lambda 0..1/2) and rising to 1 over lambda 1/2..1.  Each of the m contact
 * points of a segment (running face, mid-height) carries the smooth law
 *   p(delta) = k eps ln(1 + exp(delta / eps)),  eps = 0.05 p0 / k,
 * delta = rho - r_b(theta) its penetration, over its tributary area h r_o
 * phi / m, along the bore's outward normal.  Augmented Lagrangian: at the
 * full load, delta is shifted by lambda_i / k, one multiplier per segment,
 * updated (Uzawa, rd_contact_uzawa.c) as lambda_i <- max(0, lambda_i + k dbar_i),
 * dbar_i the force-weighted mean penetration of the segment's points (the
 * updates mixed by Anderson acceleration), until no plain
 * update moves a lambda by more than 0.02 p0: the segment-level penetration goes to
 * zero at the law's own stiffness (the plain penalty's compliance cost the
 * largest light gap 5 % and spread the free ends' forces over ~2.6 deg, the
 * beam-on-foundation length (E I / (k h))^(1/4)).  One multiplier per
 * segment, not per point: the points of a rigid segment cannot all touch a
 * curved bore, so per-point multipliers converge slowly (measured: 30 outer
 * iterations not enough; per segment 3-4); with flexible faces each free
 * end's very tip has one of its own, under a stiffer law (its concentrated
 * force, contact_setup).  The points sit on the segment's
 * face: a rigid arc of radius r_o turned with the section, or
 * (rd_contact_opts.flexible_face, the default, from RD_CONTACT_FACE_MIN_SEGMENTS on) that arc bent
 * and sheared with the ring between the segment's joints, rd_contact_face.c,
 * whose loads and their derivatives (a point's force works on its
 * segment's neighbours through the face) the residual and tangent use.
 * The rigid face misfits a bore that the ring follows by ~20 nm (bend) and
 * ~4 nm (shear) at n = 160-320, against ~1 nm penetrations, so its points'
 * forces carry couples the ring has not: the smooth bins stay 0.04 p0 off
 * at n = 160 and 320 (order 4 at the bound), 0.0014 p0 with flexible faces
 * at 320 (tests/core/test_contact_face.c).  Outputs per segment: pressure
 * (resultant / (h r_o phi)), closest approach, bore radius.  The
 * refinement and the error estimates' solves are in rd_contact_refine.c,
 * the estimates themselves in rd_contact_estimate.c.
 */
#include "rd_static_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Predictor for a contact load step: every segment moves radially with the
 * bore under it from load factor l0 to l1.  Without it a bore that moves
 * away by more than the law's smoothing length eps leaves every contact on
 * the law's exp(delta / eps) tail, with no stiffness to push the ring out. */
static void follow_bore(rd_static_problem *pb, double l0, double l1)
{
    for (int i = 0; i < pb->n; i++) {
        double *x = pb->x + 3 * i, th = atan2(x[1], x[0]), r0, r1, d;
        pb->lambda = l0;
        rd_contact_bore_radius(pb, th, &r0, &d);
        pb->lambda = l1;
        rd_contact_bore_radius(pb, th, &r1, &d);
        x[0] += (r1 - r0) * cos(th);
        x[1] += (r1 - r0) * sin(th);
    }
}

void rd_contact_segment_jacobian(const rd_static_problem *pb, int i, double J[36])
{
    memset(J, 0, 36 * sizeof *J);
    for (int k = 0; k < pb->m; k++) {
        const rd_contact_eval *pe = pb->pe + pb->m * i + k;
        if (!rd_contact_presses(pe))
            continue;
        const double *arm = pe->arm, *n = pe->n, nn = pe->nn, a = -pb->area[i] * pe->dp;
        /* F = -p A n / |n|, n = grad(delta) = e_rho - r_b'/rho e_theta; a
         * unit step in DOF d moves the point by dy (and, a turn, its arm by
         * darm = dy), so dF = a (n . dy) n / |n| (the normal's own turn is
         * dropped: p / rho against k, ~1e-7), dM = darm x F + arm x dF */
        double F[3] = {-pe->p * pb->area[i] * n[0] / nn, -pe->p * pb->area[i] * n[1] / nn, 0.0};
#pragma GCC unroll 6 /* fixed DOFs: 30 % fewer of its instructions */
        for (int d = 0; d < 6; d++) {
            double ed[3] = {0, 0, 0}, dy[3], dF[3], m1[3] = {0, 0, 0}, m2[3];
            ed[d % 3] = 1.0;
            if (d < 3) { /* n . dy = n_d; darm = 0, so m1 = 0 */
                memcpy(dy, ed, sizeof dy);
            } else {
                rd_cross3(ed, arm, dy);
                rd_cross3(dy, F, m1);
            }
            double s = a * (d < 3 ? n[d] : rd_dot3(n, dy)) / nn;
            for (int q = 0; q < 3; q++)
                dF[q] = s * n[q];
            rd_cross3(arm, dF, m2);
            for (int r = 0; r < 3; r++) {
                J[r + 6 * d] += dF[r];
                J[3 + r + 6 * d] += d < 3 ? m2[r] : m1[r] + m2[r];
            }
        }
    }
}

/* The contact loads' residual: the faces at pb's state (if flexible), then
 * the points' loads (rd_contact_face.c). */
static void contact_residual(const rd_static_problem *pb, double *r)
{
    rd_contact_face_update(pb);
    rd_contact_loads(pb, r);
}

/* Flexible faces: a segment's points move with its neighbours. */
static int faces_couple(const rd_static_problem *pb)
{
    return pb->cp0 != NULL;
}

/* The stiffest contact spring: a point's k A. */
static double point_stiffness(const rd_static_problem *pb)
{
    return pb->k * pb->area_max;
}

const rd_static_loads rd_contact_static_loads = {
    .force_factor = rd_contact_force_factor,
    .residual = contact_residual,
    .residual_again = rd_contact_loads_again,
    .segment_jacobian = rd_contact_segment_jacobian,
    .coupled = faces_couple,
    .face_jacobian = rd_contact_face_jacobian,
    .predict = follow_bore,
    .stiffest = point_stiffness,
    .outer = rd_contact_uzawa,
    .full_steps = 1,
    .planar = 1,
};

/* The contact problem on `ring`: loads, law, support, contact points. */
static int contact_setup(rd_static_problem *pb, const rd_ring_params *p, const rd_contact_opts *o)
{
    int n = pb->n, m = rd_contact_points(o->points_per_segment, n);
    const rd_ring *ring = pb->ring;
    /* a ring made with a free shape: its rest pushes it out, its gap faces are free */
    int free = o->free_shape && o->free_shape->kind != RD_FREE_CLOSED;
    pb->Ft = free ? 0.0 : p->tangential_force;
    pb->method = RD_PRETENSION_FORCE;
    pb->co = o;
    for (int q = 0; q < o->bore.n_distortion; q++) {
        double kp = o->bore.distortion[q].order * o->bore.distortion[q].phase_deg * M_PI / 180.0;
        pb->bore_phase[2 * q] = cos(kp);
        pb->bore_phase[2 * q + 1] = sin(kp);
    }
    pb->m = m;
    /* the running face: radius and the height where it touches (a
     * rectangle's R + b/2 and its mid-height, the centroid's) */
    const rd_section *sec = rd_ring_get_cross_section(ring);
    pb->r_o = sec->run.r;
    pb->bore_dr = (o->bore.diameter > 0.0 ? 0.5 * o->bore.diameter : 0.5 * p->diameter) - pb->r_o;
    pb->p0 = 2.0 * p->tangential_force / (p->diameter * pb->h); /* over the running face */
    pb->k = o->stiffness > 0.0 ? o->stiffness : rd_contact_default_stiffness(p);
    pb->eps = 0.05 * pb->p0 / pb->k;
    pb->F_ref = p->tangential_force;
    /* held: tangential (y at 180 deg), axial, tilts; free: radial, in-plane turn */
    double mask[6] = {0, 1, 1, 1, 1, 0};
    memcpy(pb->mask, mask, sizeof mask);
    /* cp, then cp0, the face's caches and the points' areas */
    pb->cp = malloc(((size_t)6 * n * m + 16 * (size_t)n) * sizeof *pb->cp);
    pb->mult = calloc((size_t)n + 2, sizeof *pb->mult);
    pb->pe = malloc((size_t)n * m * sizeof *pb->pe);
    /* flexible faces: each free end's very tip has a multiplier of its own
     * and, at the full load, TIP_STIFFNESS (rd_contact_law.c) times the
     * law's stiffness (one multiplier per end segment left the tip force's
     * split to the penalty:
     * order 3, 0.1 x, n = 320, tip 1.551 N against the exact 1.473; one per
     * point of the end segments, 1.483 N, over-constrains the face, whose
     * points then traded load at every update and never met the updates'
     * tolerance, 30 updates on 5 of 6 solves at n = 320-640; the tip alone
     * at k, 1.500 N and 16-30 updates; at 100 k, 1.473 N and 3-8 updates,
     * bench_static --battery: binned pressure within 0.02 p0 on 22 bores
     * either way at n <= 320, the tip forces' worst error 300 -> 116 %) */
    pb->tip_mult = o->flexible_face && n >= RD_CONTACT_FACE_MIN_SEGMENTS && !free;
    if (!pb->cp || !pb->mult || !pb->pe)
        return RD_ENOMEM;
    pb->area = pb->cp + (size_t)6 * n * m + 14 * (size_t)n;
    pb->face_rz = pb->area + n;
    for (int i = 0; i < n; i++) {
        double phi = rd_ring_segment_phi_at(ring, i);
        pb->area[i] = pb->h * pb->r_o * phi / m;
        pb->area_max = fmax(pb->area_max, pb->area[i]);
    }
    for (int i = 0; i < n; i++) {
        const double *P = rd_ring_reference_point(ring, i);
        for (int k = 0; k < m; k++) {
            double a = rd_ring_get_segment_angle(ring, i) + rd_contact_point_offset(pb, i, k);
            double *c = pb->cp + 3 * (m * i + k);
            c[0] = pb->r_o * cos(a) - P[0];
            c[1] = pb->r_o * sin(a) - P[1];
            c[2] = sec->run.z_touch;
        }
    }
    pb->cp0 = pb->cp + 3 * n * m;
    pb->face = pb->cp0 + 3 * n * m;
    memcpy(pb->cp0, pb->cp, (size_t)3 * n * m * sizeof *pb->cp);
    if (!o->flexible_face || n < RD_CONTACT_FACE_MIN_SEGMENTS)
        pb->cp0 = NULL; /* rigid faces */
    return RD_OK;
}

/* Segment i's resultant pressure, closest approach, position angle and bore
 * radius; updates the largest penetration.  The points inside one rigid
 * segment share whatever misfit the straight-sided segment has against a
 * curved bore, so how the pressure splits between them is an artifact of
 * rigid segments; the resultant is not. */
static void segment_output(const rd_static_problem *pb, int i, rd_contact_result *out,
                           double *t_deg, double *clear, double *at)
{
    int m = pb->m;
    double moment = 0.0, force = 0.0, closest = INFINITY, mid[3], c_mid[3], rb, drb;
    double ref = rd_ring_get_segment_angle(pb->ring, i) * 180.0 / M_PI;
    for (int k = 0; k < m; k++) {
        double y[3], a;
        rd_static_point_at(pb, i, pb->cp + 3 * (m * i + k), y);
        a = atan2(y[1], y[0]);
        rd_contact_bore_radius(pb, a, &rb, &drb);
        double delta = hypot(y[0], y[1]) - rb;
        /* continuous along the ring: a free end may move past 0 deg */
        a = a * 180.0 / M_PI - ref;
        a -= 360.0 * floor((a + 180.0) / 360.0);
        t_deg[m * i + k] = ref + a;
        clear[m * i + k] = -delta;
        if (-delta < closest)
            out->max_clearance_angle_deg = t_deg[m * i + k]; /* scratch: closest point */
        double fq = rd_contact_pressure(pb, delta, rd_contact_mult_of(pb, i, k)) * pb->area[i];
        force += fq;
        moment += fq * t_deg[m * i + k];
        closest = fmin(closest, -delta);
        out->max_penetration = fmax(out->max_penetration, delta);
    }
    const double *P = rd_ring_reference_point(pb->ring, i);
    for (int k = 0; k < 3; k++)
        c_mid[k] = (pb->r_o / pb->R) * P[k] - P[k];
    rd_static_point_at(pb, i, c_mid, mid);
    double th = atan2(mid[1], mid[0]), deg = th * 180.0 / M_PI;
    rd_contact_bore_radius(pb, th, &rb, &drb);
    out->angle_deg[i] = deg < 0.0 ? deg + 360.0 : deg;
    out->pressure[i] = force / (m * pb->area[i]);
    *at = force > 0.0 ? moment / force : rd_ring_get_segment_angle(pb->ring, i) * 180.0 / M_PI;
    out->clearance[i] = closest;
    out->bore_radius[i] = rb;
}

/* In seg's gaps (between the segments' closest points), the edges beside
 * a patch wider than `wide` deg take out's (among the points): there the
 * closest points put the edge up to half a segment into the patch, and the
 * force beside it into the next bin (bench_static --ring
 * 0.05,0.002,0.001,6 --bins 4 2.27805 305.785: a patch ending at 270.13
 * deg, the reference's at 270.08, binned as ending at 269.92 at n = 640,
 * 0.11 p0 off, with an estimate of 0.0004).  `wide` is 1.5 segments: with
 * two, a 0.5 deg patch (1.8 segments) across 320 deg at n = 1280 (--bins
 * 3 5.69085 144.595 on that ring) put none of its force past 320 deg, the
 * reference on 5760 and 11520 cells 1.56 p0, ringdyn now 1.49; with one,
 * a point-like contact on 329.98-330.26 deg (one segment; order 4 at 10 x,
 * 17 deg, default ring, n = 1280) put 0.42 p0 before 330 deg where the
 * references on 2880 and 5760 cells put none.  Narrower patches keep the
 * closest points' edges, as the comment below says why. */
static void wide_patch_edges(const rd_contact_result *out, const double *lo, int n,
                             rd_contact_result *seg)
{
    for (int g = 0; g < seg->n_gaps; g++) {
        rd_contact_gap *a = &seg->gaps[g];
        for (int h = 0; h < out->n_gaps; h++) {
            const rd_contact_gap *b = &out->gaps[h];
            if (b->end_deg < a->start_deg || b->start_deg > a->end_deg)
                continue;
            /* 1.5 segments where the patch is (graded: that segment's
             * arc; equal: the mean arc on the bore) */
            double mean = 1.5 * (lo[n] - lo[0]) / n;
            double wb = out->graded ? 1.5 * rd_contact_width_at(out, b->start_deg) : mean;
            double wa = out->graded ? 1.5 * rd_contact_width_at(out, b->end_deg) : mean;
            double before = h > 0 ? b->start_deg - out->gaps[h - 1].end_deg : INFINITY;
            double after = h + 1 < out->n_gaps ? out->gaps[h + 1].start_deg - b->end_deg : INFINITY;
            if (before > wb && (g == 0 || b->start_deg > seg->gaps[g - 1].end_deg))
                a->start_deg = b->start_deg;
            if (after > wa && (g + 1 == seg->n_gaps || b->end_deg < seg->gaps[g + 1].start_deg))
                a->end_deg = b->end_deg;
            break;
        }
    }
}

/* The bins (rd_contact_gaps.c) from the segments' forces on their arcs lo
 * (n + 1 ends); the gaps already in out.  The bins put a force beside a
 * gap edge on the touching part of its segment, with the edges between
 * the segments' closest points even where the reported ones are among the
 * points: those take the law's penetration of a point-like contact (~1e-10
 * m) as contact and widen it, 0.25 deg in the reference to 0.6 at n = 640
 * (order 4 at 10 x, 17 deg), and its force then crosses the bin boundary it
 * lies beside (order 6 at 10 x, 0 deg: 0.17 -> 0.84 p0 off). */
static int contact_bins(const rd_static_problem *pb, const double *ts, const double *t,
                        const double *c, const double *lo, const double *force, const double *at,
                        rd_contact_result *out)
{
    int n = pb->n;
    rd_contact_result *seg = pb->cp0 ? calloc(1, sizeof *seg) : out;
    if (!seg)
        return RD_ENOMEM;
    if (seg != out) {
        rd_contact_gaps(ts, out->clearance, n, t, c, pb->m, 0, lo[0], lo[n], out->gap_floor, seg);
        seg->gap_floor = out->gap_floor;
        wide_patch_edges(out, lo, n, seg);
    }
    rd_contact_bins(lo, force, at, n, pb->h * pb->r_o, seg, out);
    if (seg != out)
        free(seg);
    return RD_OK;
}

/* A free end's concentrated force (into out->tip_force, from the
 * segments' forces): the end segment's and its neighbour's resultants
 * beyond what the third segment's pressure would put on them, where the end is on the bore (within the floor, as the
 * gaps: a tip touching at its very end has its closest point a hair
 * off, +1e-13 m, and was reported as 0 N on 11 of the battery's levels,
 * bench_static --dump).  The tip's force reaches into the neighbour
 * through the flexible face: order 4 at 0.1 x the bound, 17 deg, n =
 * 1280, the end segments at 11.6 and 3.9 p0 over a 0.1 p0 pressure; the
 * end segment's excess over its neighbour alone read 0.34-0.38 N at n =
 * 320-1280 against the exact reference's 0.730, the two's 0.748 at 320
 * (and the same as before, within 1e-4 N, where the neighbour carries
 * the distributed pressure only: 54 of the battery's 64 free ends). */
static void tip_forces(const rd_static_problem *pb, const double *force, rd_contact_result *out)
{
    int n = pb->n;
    for (int e = 0; e < 2; e++) {
        int i = e ? n - 1 : 0, j = e ? n - 2 : 1, q = e ? n - 3 : 2;
        q = q < 0 ? 0 : (q > n - 1 ? n - 1 : q);
        /* (the third's pressure over the two's arcs: on equal segments
         * twice its force, bit for bit) */
        double arcs = rd_ring_segment_phi_at(pb->ring, i) + rd_ring_segment_phi_at(pb->ring, j);
        double third = out->pressure[q] * pb->h * pb->r_o * arcs;
        out->tip_force[e] =
            out->clearance[i] <= out->gap_floor ? fmax(0.0, force[i] + force[j] - third) : 0.0;
    }
}

/* Light gaps, contact fraction, tip forces and bins (rd_contact_gaps.c)
 * from the point clearances t, c. */
static int contact_summaries(const rd_static_problem *pb, const double *t, const double *c,
                             const double *ts, double *at, rd_contact_result *out)
{
    int n = pb->n, m = pb->m, nm = n * m;
    double *lo = malloc((size_t)(n + 1) * sizeof *lo), *force = malloc((size_t)n * sizeof *force);
    if (!lo || !force) {
        free(lo);
        free(force);
        return RD_ENOMEM;
    }
    /* The segments' arcs on the bore (deg): their ends where the faces are,
     * between the neighbouring points of two segments and half a point
     * spacing beyond the last points at the free ends, so that the bins,
     * the gaps and the profile's angles are all where on the bore they are
     * (the ring moves along the bore by up to u_t / r_o ~ 0.3 deg in a bore
     * distorted at 0.4 % of d, order 2, more than the edges' 1 deg target's
     * tenth; the bins taken over the segments' unloaded arcs moved a
     * 2 deg patch's force across a bin boundary by 0.09 p0). */
    lo[0] = t[0] - 0.5 * (t[1] - t[0]);
    for (int i = 1; i < n; i++)
        lo[i] = 0.5 * (t[m * i - 1] + t[m * i]);
    lo[n] = t[nm - 1] + 0.5 * (t[nm - 1] - t[nm - 2]);
    for (int i = 0; i < n; i++)
        force[i] = out->pressure[i] * pb->h * pb->r_o * rd_ring_segment_phi_at(pb->ring, i);
    /* A segment's force acts at its points' force centroid only where it is
     * concentrated (over twice either neighbour's: a free end, a gap edge, a
     * point-like contact); elsewhere the split between its points is the
     * rigid face's artefact (it moves with the stiffness: 0.04 p0 in the bins
     * at 10 x), so its force is spread over its whole arc. */
    for (int i = 0; i < n; i++) {
        double nb = fmax(i > 0 ? force[i - 1] : 0.0, i < n - 1 ? force[i + 1] : 0.0);
        if (!(force[i] > 2.0 * nb))
            at[i] = 0.5 * (lo[i] + lo[i + 1]);
    }
    /* Clearances below the floor are not light gaps: rd_contact_gap_floor
     * (a property of the ring, not of the chosen stiffness: with the
     * multipliers the ring does not sink into the bore at any stiffness, so
     * the floor must not move with it), or, with rigid
     * faces (n < RD_CONTACT_FACE_MIN_SEGMENTS), the misfit of an arc of radius r_o
     * against the bore's curvature, up to (sum |A_k| k^2 + |D/2 - r_o|) /
     * r_o^2 times L^2 / 8 over a segment of length L: where the ring follows
     * the bore such faces touch it at their ends or middles only, with gaps
     * of that size between, which a bending ring does not have. */
    double bend = fabs(pb->bore_dr), L = 0.0, fine = INFINITY;
    for (int i = 0; i < n; i++) {
        L = fmax(L, pb->r_o * rd_ring_segment_phi_at(pb->ring, i));
        fine = fmin(fine, out->width_deg[i]);
    }
    for (int k = 0; k < pb->co->bore.n_distortion; k++)
        bend += fabs(pb->co->bore.distortion[k].amplitude) * pb->co->bore.distortion[k].order *
                pb->co->bore.distortion[k].order;
    out->point_spacing_deg = fine / pb->m;
    out->points_per_segment = pb->m;
    out->gap_floor = fmax(rd_contact_gap_floor(rd_ring_get_params(pb->ring)),
                          pb->cp0 ? 0.0 : bend / (pb->r_o * pb->r_o) * L * L / 8.0);
    rd_contact_gaps(ts, out->clearance, n, t, c, pb->m, pb->cp0 != NULL, lo[0], lo[n],
                    out->gap_floor, out);
    tip_forces(pb, force, out);
    rd_contact_patches(lo, force, at, n, out);
    int rc = contact_bins(pb, ts, t, c, lo, force, at, out);
    free(lo);
    free(force);
    return rc;
}

/* The result of a solved problem: profiles, summaries, bounds. */
static int contact_outputs(const rd_ring_params *p, const rd_contact_opts *o,
                           const rd_static_problem *pb, rd_contact_result *out)
{
    int n = pb->n, rc;
    out->points = n;
    out->law_share = NAN; /* rd_contact_refine.c's probe sets it */
    out->angle_deg = malloc((size_t)n * sizeof *out->angle_deg);
    out->pressure = malloc((size_t)n * sizeof *out->pressure);
    out->clearance = malloc((size_t)n * sizeof *out->clearance);
    out->bore_radius = malloc((size_t)n * sizeof *out->bore_radius);
    out->width_deg = malloc((size_t)n * sizeof *out->width_deg);
    out->twist_deg = malloc((size_t)n * sizeof *out->twist_deg);
    double *t = malloc((size_t)n * pb->m * sizeof *t), *c = malloc((size_t)n * pb->m * sizeof *c);
    double *ts = malloc((size_t)n * sizeof *ts), *at = malloc((size_t)n * sizeof *at);
    rc = RD_ENOMEM;
    if (!out->angle_deg || !out->pressure || !out->clearance || !out->bore_radius ||
        !out->width_deg || !out->twist_deg || !t || !c || !ts || !at)
        goto out;
    double sum = 0.0, wsum = 0.0, psum = 0.0;
    int graded = 0;
    out->max_penetration = 0.0;
    rd_contact_face_update(pb);
    for (int i = 0; i < n; i++) {
        segment_output(pb, i, out, t, c, at + i);
        ts[i] = out->max_clearance_angle_deg;
        out->width_deg[i] = rd_ring_segment_phi_at(pb->ring, i) * 180.0 / M_PI;
        graded |= out->width_deg[i] != out->width_deg[0];
        /* the section's turn about the ring's tangent, the ring makers' sign */
        double w[3], a = rd_ring_get_segment_angle(pb->ring, i);
        rd_static_rot_log(pb->Q + 9 * i, w);
        out->twist_deg[i] = (w[0] * sin(a) - w[1] * cos(a)) * 180.0 / M_PI;
        sum += out->pressure[i];
        psum += out->pressure[i] * out->width_deg[i];
        wsum += out->width_deg[i];
    }
    out->graded = graded;
    /* (graded: weighted by the segments' arcs) */
    out->mean_pressure = graded ? psum / wsum : sum / n;
    out->uniform_pressure = pb->p0;
    rc = contact_summaries(pb, t, c, ts, at, out);
out:
    free(at);
    free(t);
    free(c);
    free(ts);
    out->stiffness = pb->k;
    out->conformability = rd_ring_conformability(p);
    rd_ring_section sec;
    rd_ring_section_get(p, 0, &sec);
    for (int k = 0; k < o->bore.n_distortion; k++) {
        double kk = o->bore.distortion[k].order;
        out->bound[k] = kk < 2 ? NAN
                               : p->tangential_force * pow(sec.R, 3) /
                                     (p->youngs_modulus * sec.I_inplane * pow(kk * kk - 1.0, 2));
    }
    return rc;
}

void rd_contact_warm_free(rd_contact_warm *w)
{
    free(w->ang);
    free(w->ur);
    free(w->ut);
    free(w->rz);
    free(w->mult);
    memset(w, 0, sizeof *w);
}

static int warm_save(const rd_static_problem *pb, rd_contact_warm *w)
{
    rd_contact_warm_free(w);
    size_t sz = (size_t)pb->n * sizeof(double);
    w->n_mult = pb->n + 2;
    w->ang = malloc(sz), w->ur = malloc(sz), w->ut = malloc(sz), w->rz = malloc(sz);
    w->mult = malloc((size_t)w->n_mult * sizeof *w->mult);
    if (!w->ang || !w->ur || !w->ut || !w->rz || !w->mult)
        return RD_ENOMEM;
    memcpy(w->mult, pb->mult, (size_t)w->n_mult * sizeof *w->mult);
    w->n = pb->n;
    w->step = pb->lambda_start > 0.0 ? pb->step_taken : 0.0;
    for (int i = 0; i < pb->n; i++) {
        const double *P = rd_ring_reference_point(pb->ring, i), *x = pb->x + 3 * i;
        double a = rd_ring_get_segment_angle(pb->ring, i), d[2] = {x[0] - P[0], x[1] - P[1]};
        w->ang[i] = a;
        w->ur[i] = d[0] * cos(a) + d[1] * sin(a);
        w->ut[i] = -d[0] * sin(a) + d[1] * cos(a);
        w->rz[i] = atan2(pb->Q[9 * i + 3], pb->Q[9 * i]);
    }
    return RD_OK;
}

/* The state of pb interpolated (linearly in the angle, extrapolated past
 * the end segments) from a coarser level's shape.  The contact is planar
 * (in-plane loads, the support holding the axial motion and the tilts), so
 * a turn about the axis is the whole rotation.
 *
 * The multipliers too (since 0.3.8), where the coarser level's faces were
 * as these: each is a pressure (the law's pressure at zero penetration),
 * so a segment's is interpolated in the angle as the shape (held at the
 * end segments' past them) and a free end's tip keeps its own.  Started
 * from zero, each level's updates (rd_contact_uzawa.c, a rate near 1 on
 * fine chains) rebuilt them: 44 updates at n = 1280 on order 6 at 10 x, 0
 * deg, now 32.  Instructions of rd_contact_solve (callgrind,
 * bench_contact_cost K A PHASE): orders 4, 2, 6, 3 at 10, 2.8, 10, 3 x,
 * 17, 17, 0, 17 deg: 1.89, 1.87, 1.87, 1.64 G -> 1.74, 1.63, 1.54, 1.41;
 * bench_contact_cost --battery: the finest levels' Newton iterations 908
 * -> 744; bench_static --battery: the same targets met and the same
 * estimates tracking (the bins move within the updates' tolerance), and
 * on three rings' random bores (seeds 51-55) met 419 -> 421, met but
 * outside a target 2 either way.  The tips' multipliers scaled by the end
 * segments' arcs (a concentrated force over a point's area) tracked
 * worse: 23 of the battery's pressure estimates against 25. */
#define FACES_ALIKE(w, pb) ((w)->n >= RD_CONTACT_FACE_MIN_SEGMENTS || !(pb)->cp0)
static void warm_start(rd_static_problem *pb, const rd_contact_warm *w)
{
    for (int i = 0, j = 0; i < pb->n; i++) {
        double a = rd_ring_get_segment_angle(pb->ring, i);
        while (j < w->n - 2 && w->ang[j + 1] < a)
            j++;
        double t = (a - w->ang[j]) / (w->ang[j + 1] - w->ang[j]);
        double ur = w->ur[j] + t * (w->ur[j + 1] - w->ur[j]);
        double ut = w->ut[j] + t * (w->ut[j + 1] - w->ut[j]);
        double rz = w->rz[j] + t * (w->rz[j + 1] - w->rz[j]);
        const double *P = rd_ring_reference_point(pb->ring, i);
        double *x = pb->x + 3 * i, *Q = pb->Q + 9 * i;
        x[0] = P[0] + ur * cos(a) - ut * sin(a);
        x[1] = P[1] + ur * sin(a) + ut * cos(a);
        x[2] = P[2];
        double R[9] = {cos(rz), -sin(rz), 0, sin(rz), cos(rz), 0, 0, 0, 1};
        memcpy(Q, R, sizeof R);
        if (w->mult && FACES_ALIKE(w, pb)) { /* held past the end segments */
            double tm = fmin(1.0, fmax(0.0, t));
            pb->mult[i] = w->mult[j] + tm * (w->mult[j + 1] - w->mult[j]);
        }
    }
    if (w->mult && FACES_ALIKE(w, pb) && w->n_mult == w->n + 2 && pb->tip_mult)
        pb->mult[pb->n] = w->mult[w->n], pb->mult[pb->n + 1] = w->mult[w->n + 1];
    /* the bore in place, the law still wide: the path's last part; or, at
     * the same n (the same level with another law), the solved state with
     * its multipliers, at the full load */
    pb->lambda_start = RD_CONTACT_BORE_DONE;
    /* Its first step is the one the coarser level first took from its own
     * warm start, where that level's faces were as these (a rigid-faced
     * level's steps say little of a flexible one's): a level whose whole
     * step failed (40 Newton iterations, then cut to a quarter) is usually
     * followed by finer ones that fail it too (bench_static --random 51 40,
     * bore 7, order 2 at 1.12 x and 5 at 0.40 x: the whole step failed at n
     * = 320, 640 and 1280, 1.0 s CPU; from the hint, at 320 only, 0.57 s,
     * the answer the same within the solver's tolerances); the battery's
     * flexible levels take their whole step and do not change. */
    pb->step_start = FACES_ALIKE(w, pb) ? w->step : 0.0;
    int same = w->n == pb->n && w->n_mult == pb->n + 2;
    for (int i = 0; same && i < pb->n; i++) /* and the same segments (graded) */
        same = w->ang[i] == rd_ring_get_segment_angle(pb->ring, i);
    if (same) {
        memcpy(pb->mult, w->mult, (size_t)w->n_mult * sizeof *pb->mult);
        pb->lambda_start = 1.0;
    }
}

int rd_contact_once(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                    const rd_static_opts *so, const rd_monitor *mon, const rd_contact_warm *from,
                    rd_contact_warm *to, rd_contact_result *out, rd_error *err)
{
    return rd_contact_once_graded(p, segments, NULL, o, so, mon, from, to, out, err);
}

int rd_contact_once_graded(const rd_ring_params *p, int segments, const double *weights,
                           const rd_contact_opts *o, const rd_static_opts *so,
                           const rd_monitor *mon, const rd_contact_warm *from, rd_contact_warm *to,
                           rd_contact_result *out, rd_error *err)
{
    rd_static_problem pb;
    int rc;
    rd_ring *ring = rd_ring_create_graded(p, segments, 0, weights, err);
    if (!ring)
        return err ? err->code : RD_EINVAL;
    if ((rc = rd_static_problem_init(&pb, ring, &rd_contact_static_loads)) != RD_OK ||
        (rc = contact_setup(&pb, p, o)) != RD_OK ||
        (rc = rd_free_shape_prestrain(&pb, p, o->free_shape, err)) != RD_OK)
        goto out;
    if (from && from->n >= 2)
        warm_start(&pb, from);
    rc = rd_static_solve_path(&pb, so, mon, &out->stats, err);
    if (rc == RD_ENOCONV && from && from->n >= 2 && !from->only) {
        /* the coarser shape was too far off: the whole load path instead */
        rd_static_problem_cleanup(&pb);
        rd_ring_free(ring);
        if (err)
            rd_error_init(err);
        return rd_contact_once_graded(p, segments, weights, o, so, mon, NULL, to, out, err);
    }
    if (rc != RD_OK)
        goto out;
    rd_static_stats_fill(&pb, &out->stats);
    if ((rc = contact_outputs(p, o, &pb, out)) == RD_OK && to)
        rc = warm_save(&pb, to);
out:
    if (rc == RD_ENOMEM)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the %d-segment contact solve.",
                          segments);
    rd_static_problem_cleanup(&pb);
    rd_ring_free(ring);
    return rc;
}

void rd_contact_result_cleanup(rd_contact_result *r)
{
    if (!r)
        return;
    free(r->angle_deg);
    free(r->pressure);
    free(r->clearance);
    free(r->bore_radius);
    free(r->width_deg);
    free(r->twist_deg);
    r->angle_deg = r->pressure = r->clearance = r->bore_radius = r->width_deg = r->twist_deg = NULL;
}
