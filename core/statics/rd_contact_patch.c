/*
 * rd_contact_patch — the contact patches of a solved ring (since 0.3.15):
 * the runs of the running face on the bore between its light gaps, each with
 * the bore's radial force on it (N) and where that force acts.
 *
 * Where the ring touches at a few narrow patches (a bore distorted well
 * beyond the conformability bound), the binned pressure cannot say how hard
 * it touches: a patch a few hundredths of a degree from a bin boundary puts
 * its whole force in one bin or the other (bench_static --battery, order 6
 * at 10 x the bound, 0 deg: 0.11-0.28 p0 in two bins at n = 1280), while
 * the patch's force and its place are integrals that converge with n.
 *
 * A patch's force is the sum of the segments' resultants whose force
 * centroids (on the bore) lie between the deepest points of the light gaps
 * either side, not between the gaps' edges: a segment beside an edge holds
 * the edge's concentrated force, and the segments in a gap hold none, so the
 * sum does not depend on where within a segment the edge is found.  A free
 * end's concentrated force (tip_force) is in its end patch.
 */
#include "rd_static_internal.h"

#include <math.h>

/* The force a run off the bore about as deep as the floor (deepest at a,
 * deg) would move were it counted the other way: the larger part of the
 * patch it lies in (split there), or the larger of the two patches beside
 * it (a light gap that closed). */
static double marginal_move(const double *force, const double *at, int n, double a,
                            const rd_contact_result *out)
{
    for (int j = 0; j < out->n_patches; j++) {
        const rd_contact_patch *p = &out->patches[j];
        if (a > p->end_deg)
            continue;
        if (a < p->start_deg) /* in the gap before patch j */
            return fmax(p->force_n, j > 0 ? out->patches[j - 1].force_n : 0.0);
        double part = 0.0; /* patch j's force before a */
        for (int i = 0; i < n; i++)
            if (at[i] >= p->start_deg && at[i] < a)
                part += force[i];
        part = fmin(part, p->force_n);
        return fmax(part, p->force_n - part);
    }
    return out->n_patches > 0 ? out->patches[out->n_patches - 1].force_n : 0.0;
}

void rd_contact_patches(const double *lo, const double *force, const double *at, int n,
                        rd_contact_result *out)
{
    int G = out->n_gaps;
    out->n_patches = 0;
    for (int j = 0, i = 0; j <= G; j++) {
        /* the segments up to the deepest point of gap j (the last: all) */
        double upto = j < G ? out->gaps[j].max_clearance_deg : INFINITY, f = 0.0, fa = 0.0;
        for (; i < n && at[i] <= upto; i++)
            f += force[i], fa += force[i] * at[i];
        double start = j > 0 ? out->gaps[j - 1].end_deg : lo[0];
        double end = j < G ? out->gaps[j].start_deg : lo[n];
        /* a gap from a free end: nothing there, or the very tip touching */
        if (!(end > start) && !(f > 0.0))
            continue;
        rd_contact_patch *p = &out->patches[out->n_patches++];
        p->start_deg = start;
        p->end_deg = fmax(start, end);
        p->force_n = f;
        /* (within the patch: a free end's tip touching at its very end
         * has its segment's force at the segment's middle) */
        p->centroid_deg = f > 0.0 ? fmin(p->end_deg, fmax(start, fa / f)) : 0.5 * (start + end);
    }
    out->patch_marginal_n = 0.0;
    for (int k = 0; k < out->n_marginal; k++)
        out->patch_marginal_n =
            fmax(out->patch_marginal_n, marginal_move(force, at, n, out->marginal_at_deg[k], out));
}

/* The largest difference between a patch of a and a patch of b that
 * overlaps it within a segment (the wider of the two levels' there: a
 * point contact at a free end has no width, and moves with n), a patch
 * none overlaps counting by its whole force, N. */
static double moves(const rd_contact_result *a, const rd_contact_result *b)
{
    double worst = 0.0;
    for (int j = 0; j < a->n_patches; j++) {
        const rd_contact_patch *p = &a->patches[j];
        double d = NAN, w = fmax(rd_contact_width_at(a, p->centroid_deg),
                                 rd_contact_width_at(b, p->centroid_deg));
        for (int k = 0; k < b->n_patches; k++) {
            const rd_contact_patch *q = &b->patches[k];
            if (q->end_deg + w >= p->start_deg && q->start_deg - w <= p->end_deg)
                d = isnan(d) ? fabs(p->force_n - q->force_n)
                             : fmax(d, fabs(p->force_n - q->force_n));
        }
        worst = fmax(worst, isnan(d) ? p->force_n : d);
    }
    return worst;
}

double rd_contact_patch_moves(const rd_contact_result *a, const rd_contact_result *b)
{
    return fmax(moves(a, b), moves(b, a));
}
