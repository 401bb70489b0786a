/*
 * rd_pretension — the free shape of the split ring opened by F_t on its gap
 * faces (and the lateral F_l), thesis 3.4.1-3.4.2; the model is in
 * rd_static.h, the chain's mechanics and solver in rd_static.c.
 *
 * Loads (lambda the load factor): F_t lambda on each gap face at the neutral
 * axis, pushing the faces apart, by the force method (each force normal to
 * its own face as it turns) or the field method (the J face's force, equal
 * and opposite on the I face, plus the couple that keeps the pair's moment
 * zero); F_l lambda along +z on the first face and -z on the last (both
 * the chain's own loads, rd_static_problem.c's rd_static_gap_face_load).
 * Outputs (m): x_a between the inner gap corners at mid-height, x_c the axial
 * separation of the inner top corners, the face centroids' distance, and the
 * deformed centroid line.  Error estimate: Richardson (order 2 in n) from a
 * second solve at 2n (n/2 above the segment limit), by rd_accuracy.
 */
#include "rd_accuracy.h"
#include "rd_static_problem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void rd_pretension_opts_default(rd_pretension_opts *o)
{
    o->method = RD_PRETENSION_FORCE;
    o->lateral_force = 0.0;
}

/* Largest load parameter k = F_t (D - b)^2 / (4 E I) (rd_ring_conformability)
 * whose free shape the solver reaches, with its error estimate (2n
 * segments) too: found by running both methods on two rings (the thesis
 * ring and a 100 mm one) at n = 4..160.  Field fails first: from k = 6 at
 * n = 40, from k = 1 at n = 4 (force from k = 3).  Real rings have k near
 * 0.03; k = 4 already opens the ring to a gap of several diameters. */
#define PRETENSION_K_MAX    4.0
#define PRETENSION_K_MAX_N4 0.5

int rd_pretension_validate(const rd_pretension_opts *o, const rd_ring_params *p, int segments,
                           rd_error *err)
{
    if (o->method != RD_PRETENSION_FORCE && o->method != RD_PRETENSION_FIELD)
        return rd_error_set(err, RD_EINVAL, "/pretension/method", "unknown method %d.", o->method);
    double hi = 100.0 * fmax(p->tangential_force, 1.0);
    if (!isfinite(o->lateral_force) || o->lateral_force < 0.0 || o->lateral_force > hi)
        return rd_error_set(err, RD_EINVAL, "/pretension/lateral_force",
                            "/pretension/lateral_force = %g N is out of range: allowed 0 to %g N "
                            "(100 times the tangential force, at least 100 N).",
                            o->lateral_force, hi);
    double k = rd_ring_conformability(p);
    double k_max = segments <= 4 ? PRETENSION_K_MAX_N4 : PRETENSION_K_MAX;
    if (!(k <= k_max))
        return rd_error_set(
            err, RD_EINVAL, "/ring",
            "/ring/tangential_force = %g N is too large for this ring's free shape: the load "
            "parameter F_t (D - b)^2 / (4 E I) is %.3g, allowed up to %g with %d segments "
            "(%g with 4), so F_t up to %.4g N here.  Beyond it Newton's continuation from the "
            "closed ring does not converge (the ring would open to a gap of several diameters).",
            p->tangential_force, k, k_max, segments, PRETENSION_K_MAX_N4,
            p->tangential_force * k_max / k);
    return RD_OK;
}

/* Openings and the deformed centroid line of a solved problem. */
static int pretension_outputs(const rd_ring_params *p, const rd_static_problem *pb,
                              rd_pretension_result *out, rd_error *err)
{
    const rd_ring *ring = pb->ring;
    int n = pb->n;
    double s = rd_ring_get_segment_angle(ring, 0) - 0.5 * rd_ring_segment_phi_at(ring, 0);
    /* the inner face: R - b/2 (rectangle, circle), or where a general
     * section's box has it, at the box's mid-height and top (rd_section.h:
     * the centroid is the origin) */
    const rd_section *sec = rd_ring_get_cross_section(ring);
    double Ri = sec->shape >= RD_SECTION_TAPER_FACE ? sec->R + sec->back.d : pb->R - 0.5 * pb->b;
    double zc = sec->z_c;
    const double *P0 = rd_ring_reference_point(ring, 0), *Pn = rd_ring_reference_point(ring, n - 1);
    double ia[3] = {Ri * cos(s) - P0[0], Ri * sin(s) - P0[1], zc != 0.0 ? -zc : 0.0};
    double ib[3] = {Ri * cos(s) - Pn[0], -Ri * sin(s) - Pn[1], ia[2]};
    double ya[3], yb[3], d[3];
    rd_static_point_at(pb, 0, ia, ya);
    rd_static_point_at(pb, n - 1, ib, yb);
    for (int k = 0; k < 3; k++)
        d[k] = ya[k] - yb[k];
    out->gap_opening_inner = sqrt(rd_dot3(d, d));
    ia[2] = ib[2] = 0.5 * pb->h - zc;
    rd_static_point_at(pb, 0, ia, ya);
    rd_static_point_at(pb, n - 1, ib, yb);
    out->lateral_opening = fabs(ya[2] - yb[2]);
    rd_static_point_at(pb, 0, pb->cA, ya);
    rd_static_point_at(pb, n - 1, pb->cB, yb);
    for (int k = 0; k < 3; k++)
        d[k] = ya[k] - yb[k];
    out->gap_opening_neutral = sqrt(rd_dot3(d, d));
    out->conformability = rd_ring_conformability(p);
    out->free_gap_formula = rd_ring_free_gap_formula(p);

    out->points = n + 2;
    out->x = malloc((size_t)(n + 2) * sizeof *out->x);
    out->y = malloc((size_t)(n + 2) * sizeof *out->y);
    out->z = malloc((size_t)(n + 2) * sizeof *out->z);
    out->angle_deg = malloc((size_t)(n + 2) * sizeof *out->angle_deg);
    if (!out->x || !out->y || !out->z || !out->angle_deg)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the deformed shape.");
    for (int k = 0; k < n + 2; k++) {
        double y[3], ang;
        if (k == 0) {
            rd_static_point_at(pb, 0, pb->cA, y);
            ang = s;
        } else if (k == n + 1) {
            rd_static_point_at(pb, n - 1, pb->cB, y);
            ang = 2.0 * M_PI - s;
        } else {
            memcpy(y, pb->x + 3 * (k - 1), sizeof y);
            ang = rd_ring_get_segment_angle(ring, k - 1);
        }
        out->x[k] = y[0];
        out->y[k] = y[1];
        out->z[k] = y[2];
        out->angle_deg[k] = ang * 180.0 / M_PI;
    }
    return RD_OK;
}

static int pretension_once(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                           const rd_static_opts *so, const rd_monitor *mon,
                           rd_pretension_result *out, rd_error *err)
{
    rd_static_problem pb;
    int rc;
    rd_ring *ring = rd_ring_create(p, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_EINVAL;
    if ((rc = rd_static_problem_init(&pb, ring, NULL)) != RD_OK) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the %d-segment ring.", segments);
        goto out;
    }
    pb.Ft = p->tangential_force;
    pb.Fl = o->lateral_force;
    pb.method = o->method;
    pb.jseg = segments - 1;
    for (int k = 0; k < 6; k++)
        pb.mask[k] = 1.0;
    pb.F_ref = fmax(fmax(pb.Ft, pb.Fl),
                    1e-3 * rd_ring_get_section(ring)->G * rd_ring_get_section(ring)->area * 1e-9);
    if ((rc = rd_static_solve_path(&pb, so, mon, &out->stats, err)) != RD_OK)
        goto out;
    rd_static_stats_fill(&pb, &out->stats);
    rc = pretension_outputs(p, &pb, out, err);
out:
    rd_static_problem_cleanup(&pb);
    rd_ring_free(ring);
    return rc;
}

void rd_pretension_result_cleanup(rd_pretension_result *r)
{
    if (!r)
        return;
    free(r->x);
    free(r->y);
    free(r->z);
    free(r->angle_deg);
    r->x = r->y = r->z = r->angle_deg = NULL;
}

/* The accuracy driver's view of one pretension run. */
typedef struct pretension_run {
    const rd_ring_params *p;
    int segments, ref_segments;
    const rd_pretension_opts *o;
    const rd_static_opts *so;
    rd_pretension_result *out, ref;
} pretension_run;

static int pretension_level(void *ctx, int level, const rd_monitor *mon, rd_error *err)
{
    pretension_run *run = ctx;
    if (level == 0)
        return pretension_once(run->p, run->segments, run->o, run->so, mon, run->out, err);
    return pretension_once(run->p, run->ref_segments, run->o, run->so, mon, &run->ref, err);
}

/* Relative error of f_n from f_n and f_m, Richardson with order 2 in n. */
static double relative_error(double fn, int n, double fm, int m)
{
    double f = rd_accuracy_richardson(fn, n, fm, m, 2.0, NULL);
    return fabs(fn - f) / fmax(fabs(fn), 1e-300);
}

static int pretension_compare(void *ctx, rd_error *err)
{
    (void)err;
    pretension_run *run = ctx;
    int n = run->segments, m = run->ref_segments;
    double e = relative_error(run->out->gap_opening_inner, n, run->ref.gap_opening_inner, m);
    if (run->o->lateral_force > 0.0)
        e = fmax(e, relative_error(run->out->lateral_opening, n, run->ref.lateral_opening, m));
    run->out->stats.reference_segments = m;
    run->out->stats.error_estimate = e;
    return RD_OK;
}

int rd_pretension_solve(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                        const rd_static_opts *so, const rd_monitor *mon, rd_pretension_result *out,
                        rd_error *err)
{
    int rc;
    memset(out, 0, sizeof *out);
    out->stats.error_estimate = NAN;
    if ((rc = rd_ring_validate(p, segments, 0, err)) ||
        (rc = rd_static_validate(so, segments, 0, err)) ||
        (rc = rd_pretension_validate(o, p, segments, err)))
        return rc;
    int m = rd_accuracy_refined_segments(segments, RD_STATIC_SEGMENTS_MAX);
    pretension_run run = {
        .p = p, .segments = segments, .ref_segments = m, .o = o, .so = so, .out = out};
    char what[32];
    snprintf(what, sizeof what, "%d segments", m);
    rd_accuracy_plan plan = {.solve = pretension_level,
                             .compare = pretension_compare,
                             .ctx = &run,
                             .estimate = so->estimate_error,
                             .main_share = 0.34,
                             .reference = what};
    rc = rd_accuracy_run(&plan, mon, NULL, err);
    rd_pretension_result_cleanup(&run.ref);
    return rc;
}
