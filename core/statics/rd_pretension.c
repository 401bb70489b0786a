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
 *
 * A ring made with a free shape (rd_free_shape.c): the same solve without
 * gap forces finds that shape from its joints' rest; a secant on whole
 * solves (closing_force) the tangential force that closes it to the closed
 * gap, and rd_free_shape_installed its static twist; the estimate then also
 * covers the closing force (not the twist).
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
    o->free_shape = NULL;
}

/* Largest load parameter k = F_t (D - b)^2 / (4 E I) (rd_ring_conformability)
 * whose free shape the solver reaches, with its error estimate (2n
 * segments) too: found by running both methods on two rings (the thesis
 * ring and a 100 mm one) at n = 4..160.  Field fails first: from k = 6 at
 * n = 40, from k = 1 at n = 4 (force from k = 3).  Real rings have k near
 * 0.03; k = 4 already opens the ring to a gap of several diameters. */
#define PRETENSION_K_MAX    4.0
#define PRETENSION_K_MAX_N4 0.5

/* The method and the lateral force, in the pretension block. */
static int pretension_checks(const rd_pretension_opts *o, const rd_ring_params *p, rd_error *err)
{
    if (o->method != RD_PRETENSION_FORCE && o->method != RD_PRETENSION_FIELD)
        return rd_error_set(err, RD_EINVAL, "/method", "unknown method %d.", o->method);
    double hi = 100.0 * fmax(p->tangential_force, 1.0);
    if (!isfinite(o->lateral_force) || o->lateral_force < 0.0 || o->lateral_force > hi)
        return rd_error_set(err, RD_EINVAL, "/lateral_force",
                            "@/lateral_force = %g N is out of range: allowed 0 to %g N (100 "
                            "times the tangential force, at least 100 N).",
                            o->lateral_force, hi);
    return RD_OK;
}

/* The ring's load parameter, in the ring's block (a rule of the ring, not
 * of the field). */
static int load_check(const rd_ring_params *p, int segments, rd_error *err)
{
    double k = rd_ring_conformability(p);
    double k_max = segments <= 4 ? PRETENSION_K_MAX_N4 : PRETENSION_K_MAX;
    if (!(k <= k_max))
        return rd_error_set(
            err, RD_EINVAL, "",
            "@/tangential_force = %g N is too large for this ring's free shape: the load "
            "parameter F_t (D - b)^2 / (4 E I) is %.3g, allowed up to %g with %d segments "
            "(%g with 4), so F_t up to %.4g N here.  Beyond it Newton's continuation from the "
            "closed ring does not converge (the ring would open to a gap of several diameters).",
            p->tangential_force, k, k_max, segments, PRETENSION_K_MAX_N4,
            p->tangential_force * k_max / k);
    return RD_OK;
}

int rd_pretension_validate(const rd_pretension_opts *o, const rd_ring_params *p, int segments,
                           rd_error *err)
{
    size_t m = rd_error_enter(err, "/pretension");
    int rc = pretension_checks(o, p, err);
    rd_error_leave(err, m);
    m = rd_error_enter(err, "/ring");
    rc = rc ? rc : load_check(p, segments, err);
    rd_error_leave(err, m);
    return rc;
}

/* The running face's tips at the centroid's height (the free gap) and its
 * n + 2 points (rd_pretension_result.face_*; their arrays allocated). */
static void running_face(const rd_static_problem *pb, double s, const double *P0, const double *Pn,
                         rd_pretension_result *out)
{
    const rd_section *sec = rd_ring_get_cross_section(pb->ring);
    int n = pb->n;
    double ya[3], yb[3], d[3];
    double Ro = sec->shape >= RD_SECTION_TAPER_FACE ? sec->R + sec->run.d : pb->R + 0.5 * pb->b;
    double oa[3] = {Ro * cos(s) - P0[0], Ro * sin(s) - P0[1], 0.0};
    double ob[3] = {Ro * cos(s) - Pn[0], -Ro * sin(s) - Pn[1], 0.0};
    rd_static_point_at(pb, 0, oa, ya);
    rd_static_point_at(pb, n - 1, ob, yb);
    for (int k = 0; k < 3; k++)
        d[k] = ya[k] - yb[k];
    out->free_gap = sqrt(rd_dot3(d, d));
    out->tangential_force = NAN;
    for (int k = 0; k < n + 2; k++) {
        double y[3];
        if (k == 0 || k == n + 1) {
            rd_static_point_at(pb, k ? n - 1 : 0, k ? ob : oa, y);
        } else {
            const double *P = rd_ring_reference_point(pb->ring, k - 1);
            double c[3] = {(Ro / pb->R - 1.0) * P[0], (Ro / pb->R - 1.0) * P[1], 0.0};
            rd_static_point_at(pb, k - 1, c, y);
        }
        out->face_theta_deg[k] = remainder(atan2(y[1], y[0]) - M_PI, 2.0 * M_PI) * 180.0 / M_PI;
        out->face_radius[k] = hypot(y[0], y[1]);
    }
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
    out->face_theta_deg = malloc((size_t)(n + 2) * sizeof *out->face_theta_deg);
    out->face_radius = malloc((size_t)(n + 2) * sizeof *out->face_radius);
    if (!out->x || !out->y || !out->z || !out->angle_deg || !out->face_theta_deg ||
        !out->face_radius)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the deformed shape.");
    running_face(pb, s, P0, Pn, out);
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

/* The free shape of o, NULL for the stress-free closed ring. */
static const rd_free_shape *free_shape_of(const rd_pretension_opts *o)
{
    return o->free_shape && o->free_shape->kind != RD_FREE_CLOSED ? o->free_shape : NULL;
}

/* One solve at `segments` with F_t = Ft on the gap faces (the ring's own
 * without a free shape; with one 0 for the free shape, below 0 to close
 * it). */
static int pretension_once(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                           double Ft, const rd_static_opts *so, const rd_monitor *mon,
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
    pb.Ft = Ft;
    pb.Fl = o->lateral_force;
    pb.method = o->method;
    pb.jseg = segments - 1;
    for (int k = 0; k < 6; k++)
        pb.mask[k] = 1.0;
    pb.F_ref = fmax(fmax(fabs(pb.Ft), pb.Fl),
                    1e-3 * rd_ring_get_section(ring)->G * rd_ring_get_section(ring)->area * 1e-9);
    if ((rc = rd_free_shape_prestrain(&pb, p, free_shape_of(o), err)) != RD_OK)
        goto out;
    if (pb.e0) /* the free shape's scale: its largest joint force closed */
        for (int j = 0; j < segments - 1; j++) {
            double F[3] = {0, 0, 0};
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 6; c++)
                    F[r] += pb.Kc[36 * j + 6 * r + c] * pb.e0[6 * j + c];
            pb.F_ref = fmax(pb.F_ref, sqrt(rd_dot3(F, F)));
        }
    if ((rc = rd_static_solve_path(&pb, so, mon, &out->stats, err)) != RD_OK)
        goto out;
    rd_static_stats_fill(&pb, &out->stats);
    rc = pretension_outputs(p, &pb, out, err);
out:
    rd_static_problem_cleanup(&pb);
    rd_ring_free(ring);
    return rc;
}

/* The force F that closes the free shape to the closed gap: the gap
 * faces' centroids 2 R sin(s) apart, s the first face's angle, as in the
 * closed reference.  Secant from F = 0 (the free shape, *free) and the
 * thin-ring estimate E I (g - g_c) / (3 pi R^3), to 1e-9 of the opening. */
static int closing_force(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                         const rd_static_opts *so, const rd_pretension_result *free, double *F,
                         rd_error *err)
{
    rd_section sec;
    rd_section_init(&sec, p);
    double s = 0.5 * p->closed_gap / sec.R; /* the first face's angle (rd_ring.c) */
    double gc = 2.0 * sec.R * sin(s), g0 = free->gap_opening_neutral, open = g0 - gc;
    double Fa = 0.0, ga = g0,
           Fb = p->youngs_modulus * sec.I_inplane * open / (3.0 * M_PI * pow(sec.R, 3));
    for (int it = 0; it < 20; it++) {
        rd_pretension_result r;
        memset(&r, 0, sizeof r);
        int rc = pretension_once(p, segments, o, -Fb, so, NULL, &r, err);
        double gb = r.gap_opening_neutral;
        rd_pretension_result_cleanup(&r);
        if (rc)
            return rc;
        if (fabs(gb - gc) <= 1e-9 * fabs(open)) {
            *F = Fb;
            return RD_OK;
        }
        double Fn = Fb - (gb - gc) * (Fb - Fa) / (gb - ga);
        Fa = Fb;
        ga = gb;
        Fb = Fn;
    }
    return rd_error_set(err, RD_ENOCONV, "/ring",
                        "the force that closes the free shape was not found in 20 solves.");
}

/* A free shape's solve at `segments`: the shape, then the force that
 * closes it. */
static int free_once(const rd_ring_params *p, int segments, const rd_pretension_opts *o,
                     const rd_static_opts *so, const rd_monitor *mon, rd_pretension_result *out,
                     rd_error *err)
{
    int rc = pretension_once(p, segments, o, 0.0, so, mon, out, err);
    if (rc == RD_OK && free_shape_of(o))
        rc = closing_force(p, segments, o, so, out, &out->tangential_force, err);
    if (rc == RD_OK && free_shape_of(o)) {
        out->static_twist_deg = malloc((size_t)(segments + 2) * sizeof *out->static_twist_deg);
        if (!out->static_twist_deg)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the twist.");
        rc =
            rd_free_shape_installed(p, segments, o->free_shape, so, out->static_twist_deg + 1, err);
        out->static_twist_deg[0] = out->static_twist_deg[1];
        out->static_twist_deg[segments + 1] = out->static_twist_deg[segments];
    }
    return rc;
}

int rd_pretension_free_face(const rd_ring_params *p, int segments, const rd_free_shape *fs,
                            const rd_static_opts *so, rd_pretension_result *out, rd_error *err)
{
    rd_pretension_opts o;
    rd_pretension_opts_default(&o);
    o.free_shape = fs;
    memset(out, 0, sizeof *out);
    return pretension_once(p, segments, &o, 0.0, so, NULL, out, err);
}

void rd_pretension_result_cleanup(rd_pretension_result *r)
{
    if (!r)
        return;
    free(r->x);
    free(r->y);
    free(r->z);
    free(r->angle_deg);
    free(r->face_theta_deg);
    free(r->face_radius);
    free(r->static_twist_deg);
    r->static_twist_deg = NULL;
    r->x = r->y = r->z = r->angle_deg = r->face_theta_deg = r->face_radius = NULL;
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
    int n = level == 0 ? run->segments : run->ref_segments;
    rd_pretension_result *out = level == 0 ? run->out : &run->ref;
    if (free_shape_of(run->o))
        return free_once(run->p, n, run->o, run->so, mon, out, err);
    return pretension_once(run->p, n, run->o, run->p->tangential_force, run->so, mon, out, err);
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
    if (free_shape_of(run->o))
        e = fmax(e, relative_error(run->out->tangential_force, n, run->ref.tangential_force, m));
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
    if ((rc = rd_ring_scene_validate(p, segments, 0, err)) ||
        (rc = rd_static_validate(so, segments, 0, err)) ||
        (rc = rd_pretension_validate(o, p, segments, err)))
        return rc;
    size_t mark = rd_error_enter(err, "/ring");
    rc = rd_free_shape_validate(o->free_shape, p, err);
    rd_error_leave(err, mark);
    if (rc)
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
