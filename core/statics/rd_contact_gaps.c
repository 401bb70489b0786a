/*
 * rd_contact_gaps — what a conformability study reads from one solved
 * contact problem: its light gaps, contact fraction and binned pressure,
 * and the arc of its segment at an angle (rd_contact.c calls these;
 * declarations in rd_static_internal.h).  The error estimates between two
 * refinement levels are in rd_contact_estimate.c.
 *
 * Light gaps.  The segments' closest approaches are scanned for runs of
 * lifted segments.  An edge between a touching point a and the first lifted
 * point b lies where the clearance leaves zero (with faces that bend with
 * the ring: among the contact points, m per segment, spacing phi / m,
 * angles increasing along the ring; rigid faces, whose points do not follow
 * the bore: between the segments' closest points): behind an edge that carries
 * a concentrated force the clearance grows as the cube of the distance, so
 * with c_b and the next c_{b+1}, r = (c_{b+1} / c_b)^(1/3) puts the edge
 * y = d / (r - 1) before b (d the point spacing), kept within [a, b], a
 * the end's face where the touching point is the ring's first (last): a
 * tip's concentrated force acts at the face, and from its first point,
 * half a spacing in, the edge sat half a spacing late (order 3 at 1 x the
 * bound, 0 deg: 0.264 deg at n = 640 and 1280 against the reference's
 * 0.236; the battery's contact fraction errors fell on 9 of 30 bores, by
 * up to 0.0004, and rose on 2, by up to 0.0003).  A run reaching a free end
 * starts (ends) at that end's face.  The largest clearance of a run is the
 * parabola's peak through its largest point and the two neighbours, or
 * where that point is a free end's last, the parabola through the end's
 * three points at the end's face.  Runs no deeper than the floor (the
 * contact law's penetration scale) are contact.  Contact fraction = 1 -
 * gap length / span.
 *
 * Bins.  Each segment's resultant contact force is spread evenly over the
 * widest arc inside the segment centred on its line of action (the force
 * centroid of its points): a segment pressed evenly spreads it over its
 * whole arc, one touching at a single point (a point-like contact, a gap
 * edge) puts it there, so the force and its first moment are kept and a
 * concentrated force does not straddle a bin boundary it does not cross.
 * A bin's pressure is the force inside it over h r_o times the ring's arc
 * in it.
 */
#include "rd_static_internal.h"

#include <math.h>

/* The arc of the segment nearest a (deg): 360 / n where the segments are
 * alike, its own where graded. */
double rd_contact_width_at(const rd_contact_result *r, double a)
{
    if (!r->graded)
        return 360.0 / r->points;
    int best = 0;
    for (int i = 1; i < r->points; i++)
        if (fabs(r->angle_deg[i] - a) < fabs(r->angle_deg[best] - a))
            best = i;
    return r->width_deg[best];
}

/* Edge between ta (a touching point, or a free end's face) and the first
 * lifted point tb (gap c1), c2 the gap of the next point, d beyond tb;
 * angles in deg, ta < tb (the caller negates them for a run's end). */
static double cube_edge(double ta, double tb, double d, double c1, double c2)
{
    double r = c1 > 0.0 && c2 > c1 ? cbrt(c2 / c1) : 3.0;
    return tb - fmin(d / (r - 1.0), tb - ta);
}

/* Peak of the parabola through (t[k-1..k+1], c[k-1..k+1]), if k is inside. */
static void peak(const double *t, const double *c, int k, int lo, int hi, double *cm, double *tm)
{
    *cm = c[k];
    *tm = t[k];
    if (k <= lo || k >= hi)
        return;
    double a = c[k - 1], b = c[k], d = c[k + 1], den = a - 2.0 * b + d;
    if (!(den < 0.0))
        return;
    double x = 0.5 * (a - d) / den; /* in point spacings, |x| <= 1/2 at a maximum */
    if (fabs(x) > 1.0)
        return;
    *cm = b - 0.25 * (a - d) * x;
    *tm = t[k] + x * 0.5 * (t[k + 1] - t[k - 1]);
}

/* The run of lifted segments lo..hi of n; ts, cs their closest points'
 * angles and clearances, t, c all m n points.  With points (faces that
 * bend with the ring, whose points follow the bore) the edges are found
 * among the points: from the run's outermost points outwards over the
 * lifted points of the touching neighbours (the segments' closest points
 * put the edge up to half a segment into the patch: 0.14 deg at n = 1280,
 * halving with each doubling of n, on most of bench_static's battery). */
static void one_gap(const double *ts, const double *cs, int n, const double *t, const double *c,
                    int m, int lo, int hi, double tip0, double tip1, int points, rd_contact_gap *g)
{
    if (lo == 0)
        g->start_deg = tip0;
    else if (points) {
        int q = m * lo, last = m * (hi + 1) - 1;
        while (q > m * (lo - 1) && c[q - 1] > 0.0)
            q--;
        g->start_deg = cube_edge(q - 1 == 0 ? tip0 : t[q - 1], t[q], t[q] - t[q - 1], c[q],
                                 q < last ? c[q + 1] : 0.0);
    } else
        g->start_deg =
            cube_edge(ts[lo - 1], ts[lo], ts[lo] - ts[lo - 1], cs[lo], lo < hi ? cs[lo + 1] : 0.0);
    if (hi == n - 1)
        g->end_deg = tip1;
    else if (points) {
        int q = m * (hi + 1) - 1, first = m * lo;
        while (q < m * (hi + 2) - 1 && c[q + 1] > 0.0)
            q++;
        g->end_deg = -cube_edge(q + 1 == m * n - 1 ? -tip1 : -t[q + 1], -t[q], t[q + 1] - t[q],
                                c[q], q > first ? c[q - 1] : 0.0);
    } else
        g->end_deg = -cube_edge(-ts[hi + 1], -ts[hi], ts[hi + 1] - ts[hi], cs[hi],
                                hi > lo ? cs[hi - 1] : 0.0);
    int k = m * lo;
    for (int q = m * lo; q < m * (hi + 1); q++)
        if (c[q] > c[k])
            k = q;
    peak(t, c, k, m * lo, m * (hi + 1) - 1, &g->max_clearance, &g->max_clearance_deg);
    /* largest at a free end's last point, half a spacing short of the end:
     * the parabola through the end's three points, at the end (order 6 at 3
     * x the bound, 17 deg: the last point's 2.401 um against the
     * reference's 2.409 at its end node; the clearance there grows by ~0.4
     * um a degree) */
    int last = m * (hi + 1) - 1;
    if (last - m * lo >= 2 && ((lo == 0 && k == 0) || (hi == n - 1 && k == m * n - 1))) {
        int a = k == 0 ? 0 : k - 2;
        double at = k == 0 ? tip0 : tip1, x0 = t[a], x1 = t[a + 1], x2 = t[a + 2];
        double e = c[a] * (at - x1) * (at - x2) / ((x0 - x1) * (x0 - x2)) +
                   c[a + 1] * (at - x0) * (at - x2) / ((x1 - x0) * (x1 - x2)) +
                   c[a + 2] * (at - x0) * (at - x1) / ((x2 - x0) * (x2 - x1));
        if (e > g->max_clearance)
            g->max_clearance = e, g->max_clearance_deg = at;
    }
}

void rd_contact_gaps(const double *ts, const double *cs, int n, const double *t, const double *c,
                     int m, int points, double tip0, double tip1, double gap_floor,
                     rd_contact_result *out)
{
    /* the band of depths counted or not by chance: within x2 of the floor,
     * including the runs a rigid face's misfit makes (order 3 at 1 x the
     * bound: 5.6-6.8 nm runs over 36 deg against a 9.4 nm floor count as
     * gaps at 10 x the contact stiffness, 0.13 of the contact fraction) */
    double band_lo = 0.5 * gap_floor, nearest = INFINITY;
    double length = 0.0;
    out->n_gaps = 0;
    out->marginal_gap_deg = 0.0;
    out->marginal_depth = 0.0;
    out->n_marginal = 0;
    out->max_clearance = 0.0;
    out->max_clearance_angle_deg = NAN;
    for (int i = 0; i < n;) {
        if (!(cs[i] > 0.0)) {
            i++;
            continue;
        }
        int lo = i;
        while (i < n && cs[i] > 0.0)
            i++;
        rd_contact_gap g;
        one_gap(ts, cs, n, t, c, m, lo, i - 1, tip0, tip1, points, &g);
        if (g.max_clearance > band_lo && g.max_clearance < 2.0 * gap_floor) {
            out->marginal_gap_deg += g.end_deg - g.start_deg;
            if (out->n_marginal < RD_CONTACT_GAPS_MAX)
                out->marginal_at_deg[out->n_marginal++] = g.max_clearance_deg;
            double off = fabs(log(g.max_clearance / gap_floor));
            if (off < nearest)
                nearest = off, out->marginal_depth = g.max_clearance;
        }
        if (!(g.max_clearance > gap_floor))
            continue;
        length += g.end_deg - g.start_deg;
        if (out->n_gaps < RD_CONTACT_GAPS_MAX)
            out->gaps[out->n_gaps++] = g;
        if (g.max_clearance > out->max_clearance) {
            out->max_clearance = g.max_clearance;
            out->max_clearance_angle_deg = g.max_clearance_deg;
        }
    }
    out->contact_fraction = fmax(0.0, 1.0 - length / (tip1 - tip0));
}

/* Length of [a, b] on the bore: outside out's light gaps (sorted,
 * disjoint) that are certain, deeper than twice the floor (a run about as
 * deep as the floor may be contact: order 3 at 0.1 x the bound, a 9.4 nm
 * run over 10 deg beside the free end that the reference does not have). */
static double touching(const rd_contact_result *out, double a, double b)
{
    double len = fmax(0.0, b - a);
    for (int g = 0; g < out->n_gaps; g++)
        if (out->gaps[g].max_clearance > 2.0 * out->gap_floor)
            len -= fmax(0.0, fmin(b, out->gaps[g].end_deg) - fmax(a, out->gaps[g].start_deg));
    return fmax(0.0, len);
}

/* Bin k's arc [lo, hi] (deg): the first and the last reach past 0 and
 * 360 deg, where a free end pushed along the bore beyond the gap's middle
 * still belongs to its own bin. */
static void bin_arc(int k, double *lo, double *hi)
{
    double w = RD_CONTACT_BIN_DEG;
    *lo = k > 0 ? k * w : -INFINITY;
    *hi = k < RD_CONTACT_BINS - 1 ? (k + 1) * w : INFINITY;
}

static int bin_of(double a)
{
    int k = (int)floor(a / RD_CONTACT_BIN_DEG);
    return k < 0 ? 0 : (k >= RD_CONTACT_BINS ? RD_CONTACT_BINS - 1 : k);
}

/* Adds force f spread evenly over the touching part of [a, b] (length
 * len > 0) to the bins. */
static void spread(const rd_contact_result *out, double a, double b, double len, double force,
                   double *f)
{
    for (int k = bin_of(a); k <= bin_of(b); k++) {
        double lo, hi;
        bin_arc(k, &lo, &hi);
        f[k] += force * touching(out, fmax(a, lo), fmin(b, hi)) / len;
    }
}

/* The part of force, spread evenly over the touching part of [a, b] (len),
 * that lies past a bin boundary from a gap edge inside [lo, hi] (the
 * segment): the edge's concentrated force sits at the edge, not over the
 * segment's arc (bench_static --random 32 40, bore 39, order 2 at 1.30 x,
 * 347 deg: a patch ending at 270.28 deg, the reference's at 270.34, its
 * segment's force spread from 269.9 deg, met at n = 640 with 0.010 where
 * 0.055 p0 was off).  Raises *worst to that part where it is larger, with
 * its boundary in *at. */
static void past_boundary(const rd_contact_result *gaps, double lo, double hi, double a, double b,
                          double len, double force, double *worst, double *at)
{
    for (int g = 0; g < gaps->n_gaps; g++)
        for (int side = 0; side < 2; side++) {
            double E = side ? gaps->gaps[g].end_deg : gaps->gaps[g].start_deg;
            if (E <= lo || E >= hi)
                continue;
            /* the touching side: after a gap's end, before its start */
            double from = side ? E : a, to = side ? b : E;
            for (int k = bin_of(from) + 1; k <= bin_of(to); k++) {
                double B = k * RD_CONTACT_BIN_DEG;
                double part = side ? touching(gaps, fmax(B, a), b) : touching(gaps, a, fmin(B, b));
                if (force * part / len > *worst)
                    *worst = force * part / len, *at = B;
            }
        }
}

void rd_contact_bins(const double *seg_deg, const double *force, const double *at_deg, int n,
                     double h_ro, const rd_contact_result *gaps, rd_contact_result *out)
{
    double f[RD_CONTACT_BINS] = {0}, cover[RD_CONTACT_BINS] = {0}, past = 0.0, past_at = NAN;
    for (int i = 0; i < n; i++) {
        double lo = seg_deg[i], hi = seg_deg[i + 1], width = hi - lo;
        double c = fmin(hi, fmax(lo, at_deg[i])), half = fmin(c - lo, hi - c);
        for (int k = bin_of(lo); k <= bin_of(hi); k++) {
            double a, b;
            bin_arc(k, &a, &b);
            cover[k] += fmax(0.0, fmin(hi, b) - fmax(lo, a));
        }
        if (!(force[i] > 0.0))
            continue;
        /* on the bore only: a segment beside a gap edge spreads its force
         * over the part of its arc that touches (the edge's location), not
         * over the lifted part, which may lie in the next bin */
        double len = touching(gaps, c - half, c + half);
        if (len > 1e-9 * width) {
            spread(gaps, c - half, c + half, len, force[i], f);
            past_boundary(gaps, lo, hi, c - half, c + half, len, force[i], &past, &past_at);
            continue;
        }
        len = touching(gaps, lo, hi);
        if (len > 1e-9 * width && half > 1e-9 * width) {
            spread(gaps, lo, hi, len, force[i], f);
            past_boundary(gaps, lo, hi, lo, hi, len, force[i], &past, &past_at);
        } else
            f[bin_of(c)] += force[i]; /* at one point (its centroid) */
    }
    for (int k = 0; k < RD_CONTACT_BINS; k++)
        out->bin_pressure[k] = cover[k] > 0.0 ? f[k] / (h_ro * cover[k] * M_PI / 180.0) : 0.0;
    out->edge_bin_share = past / (h_ro * RD_CONTACT_BIN_DEG * M_PI / 180.0);
    out->edge_bin_at_deg = past_at;
}
