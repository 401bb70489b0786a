/*
 * rd_lift_films.c — the lubricated lift in a distorted bore: a film per
 * segment load (rd_lift_internal.h has the model and its usage).
 *
 * The loads: the contact analysis (core/statics, rd_contact_solve) solves
 * the same ring pressed into the same bore by its pretension with exact
 * contact; each lift segment's load is that pressure averaged over its arc,
 * over the uniform p0, times the round bore's 2 F_t / D.  (The lift's own
 * bore contact is a penalty whose compliance at the static start took up
 * a quarter of a 5 um distortion's load variation and half of a 0.2 um
 * one's: tests/core/test_lift_films.c.)
 *
 * The films: each distinct load its own film (rd_lift_film_run_load) while
 * there are at most RD_LIFT_FILMS_NODES of them; beyond that, films at the
 * smallest, middle and largest load and each segment's film the quadratic
 * Lagrange combination at its load, the interpolation's error measured by
 * one more film at the load where the quadratic's error peaks.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift_internal.h"
#include "rd_lift_model.h"
#include "rd_static.h"

void rd_lift_films_free(rd_lift_films *fs)
{
    for (int g = 0; g < RD_LIFT_FILMS_NODES; g++)
        if (fs->solved[g]) {
            rd_film_track_free(&fs->tr[g]);
            rd_film_free(&fs->film[g]);
        }
    free(fs->wt);
    memset(fs, 0, sizeof *fs);
}

/* The films' coordinate: the log of the load, floored at a tenth of the
 * round bore's (a segment off the bore carries no elastic load). */
static double coord(double load, double scale)
{
    return log(fmax(load, 0.0) + 0.1 * scale);
}

/* The interpolation's weights at x over the K Chebyshev-Lobatto nodes xs
 * (barycentric; a node itself one-hot) into w. */
static void cheb_weights(const double *xs, int K, double x, double *w)
{
    double sum = 0.0;
    for (int k = 0; k < K; k++)
        if (x == xs[k]) {
            for (int j = 0; j < K; j++)
                w[j] = j == k;
            return;
        }
    for (int k = 0; k < K; k++) {
        w[k] = ((k % 2) ? -1.0 : 1.0) * ((k == 0 || k == K - 1) ? 0.5 : 1.0) / (x - xs[k]);
        sum += w[k];
    }
    for (int k = 0; k < K; k++)
        w[k] /= sum;
}

/* The distinct loads of the segments (within RD_LIFT_FILMS_SAME x scale)
 * into d, up to `cap`; returns their number (cap + 1: more). */
static int distinct_loads(const rd_lift_films *fs, double scale, double *d, int cap)
{
    int D = 0;
    for (int j = 0; j < fs->m && D <= cap; j++) {
        int g = 0;
        while (g < D && fabs(fs->seg_load[j] - d[g]) > RD_LIFT_FILMS_SAME * scale)
            g++;
        if (g == D && D < cap)
            d[g] = fs->seg_load[j];
        if (g == D)
            D++;
    }
    return D;
}

/* Each segment's weights over the count films (one-hot on its own load when
 * exact, else the interpolation at its coordinate) and the films' shares. */
static void films_weights(rd_lift_films *fs, const double *xs, double scale)
{
    const int N = RD_LIFT_FILMS_NODES;
    memset(fs->share, 0, sizeof fs->share);
    for (int j = 0; j < fs->m; j++) {
        double *w = fs->wt + (size_t)N * j;
        memset(w, 0, (size_t)N * sizeof *w);
        if (fs->exact) {
            int g = 0;
            while (g + 1 < fs->count &&
                   fabs(fs->seg_load[j] - fs->load[g]) > RD_LIFT_FILMS_SAME * scale)
                g++;
            w[g] = 1.0;
        } else
            cheb_weights(xs, fs->count, coord(fs->seg_load[j], scale), w);
        for (int g = 0; g < fs->count; g++)
            fs->share[g] += w[g] / fs->m;
    }
}

/* Film g's track solved at fs->load[g] (fs->count counts the solved). */
static int solve_film(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_films *fs, int g,
                      int fine, const rd_monitor *mon, rd_error *err)
{
    int rc = rd_monitor_report(mon, 0.0, err);
    if (rc)
        return rc;
    rc = rd_lift_film_run_load(rp, p, fs->load[g], fine, &fs->film[g], &fs->tr[g], err);
    fs->solved[g] = 1;
    return rc;
}

/* How far the interpolation over the nodes old[0..K) misses the film of
 * node g: the film relative to max(|h0|, sigma) over its steps, and the
 * friction work per cycle relative; the larger. */
static double miss_at(const rd_lift_params *p, const rd_ring_params *rp, const rd_lift_films *fs,
                      const int *old, int K, const double *xo, double x, int g)
{
    double w[RD_LIFT_FILMS_NODES], fe = 0.0, we = 0.0;
    cheb_weights(xo, K, x, w);
    const rd_film_track *tr = &fs->tr[g];
    for (int k = 0; k <= tr->steps; k++) {
        double h = 0.0;
        for (int j = 0; j < K; j++) {
            rd_film_point pt;
            rd_film_track_at(&fs->tr[old[j]], tr->pt[k].t, &pt);
            h += w[j] * pt.h0;
        }
        fe = fmax(fe, fabs(h - tr->pt[k].h0) / fmax(fabs(tr->pt[k].h0), fs->film[g].sigma));
    }
    double omega = rd_engine_omega(&p->engine), cycle = 4.0 * M_PI / omega;
    double circ = M_PI * rp->diameter, ureg = rd_liner_ureg(&p->engine);
    double mu_b = p->friction.lube.boundary_coefficient;
    for (int c = 0; c < (int)floor(p->engine.cycles + 1e-9); c++) {
        double want = rd_lift_film_work(tr, circ, mu_b, ureg, c * cycle, cycle), got = 0.0;
        for (int j = 0; j < K; j++)
            got += w[j] * rd_lift_film_work(&fs->tr[old[j]], circ, mu_b, ureg, c * cycle, cycle);
        we = fmax(we, fabs(got - want) / fmax(fabs(want), 1e-300));
    }
    return fmax(fe, we);
}

/* The interpolated films: Chebyshev-Lobatto nodes in the coordinate over
 * the segments' loads, 3, then 5, 9, 17 (each level's nodes the next's
 * even ones), until the coarser level misses the new nodes' films by no
 * more than RD_LIFT_FILMS_TOL; the finer level is used, fs->interp_check
 * is that miss (an estimate of the films' miss against each segment's own film). */
static int films_interpolated(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_films *fs,
                              int fine, double scale, const rd_monitor *mon, rd_error *err)
{
    double lo = INFINITY, hi = -INFINITY, xs[RD_LIFT_FILMS_NODES];
    for (int j = 0; j < fs->m; j++) {
        lo = fmin(lo, coord(fs->seg_load[j], scale));
        hi = fmax(hi, coord(fs->seg_load[j], scale));
    }
    int rc = RD_OK, K = 3;
    for (int level = 0; rc == RD_OK; level++) {
        int Kn = level == 0 ? 3 : 2 * K - 1, old[RD_LIFT_FILMS_NODES];
        double xo[RD_LIFT_FILMS_NODES];
        for (int k = 0; k < K && level > 0; k++) { /* the coarser level, at its new places */
            old[k] = 2 * k;
            xo[k] = xs[k];
        }
        for (int k = Kn - 1; k >= 0; k--) { /* the nodes, the old ones moved to even places */
            xs[k] = 0.5 * (lo + hi) - 0.5 * (hi - lo) * cos(M_PI * k / (Kn - 1));
            if (level > 0 && k % 2 == 0) {
                fs->film[k] = fs->film[k / 2];
                fs->tr[k] = fs->tr[k / 2];
                fs->load[k] = fs->load[k / 2];
                fs->solved[k] = 1;
            } else if (level > 0)
                fs->solved[k] = 0;
        }
        fs->count = Kn;
        double miss = 0.0;
        for (int k = 0; rc == RD_OK && k < Kn; k++) {
            if (fs->solved[k] && level > 0)
                continue;
            fs->load[k] = exp(xs[k]) - 0.1 * scale;
            rc = solve_film(rp, p, fs, k, fine, mon, err);
            if (rc == RD_OK && level > 0)
                miss = fmax(miss, miss_at(p, rp, fs, old, K, xo, xs[k], k));
        }
        K = Kn;
        if (level > 0)
            fs->interp_check = miss;
        if (rc == RD_OK && level > 0 && (miss <= RD_LIFT_FILMS_TOL || K == RD_LIFT_FILMS_NODES))
            break;
    }
    if (rc == RD_OK)
        films_weights(fs, xs, scale);
    return rc;
}

int rd_lift_films_run(const rd_ring_params *rp, const rd_lift_params *p, const double *load,
                      const double *angle_deg, int m, int fine, const rd_monitor *mon,
                      rd_lift_films *fs, rd_error *err)
{
    memset(fs, 0, sizeof *fs);
    fs->m = m;
    fs->interp_check = NAN;
    fs->wt = malloc((size_t)m * (RD_LIFT_FILMS_NODES + 2) * sizeof *fs->wt);
    if (!fs->wt)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the films of %d segments.", m);
    fs->seg_load = fs->wt + (size_t)m * RD_LIFT_FILMS_NODES;
    fs->angle_deg = fs->seg_load + m;
    memcpy(fs->seg_load, load, (size_t)m * sizeof *load);
    memcpy(fs->angle_deg, angle_deg, (size_t)m * sizeof *angle_deg);
    double scale = 2.0 * rp->tangential_force / rp->diameter;
    int D = distinct_loads(fs, scale, fs->load, RD_LIFT_FILMS_EXACT);
    fs->exact = D <= RD_LIFT_FILMS_EXACT;
    if (!fs->exact)
        return films_interpolated(rp, p, fs, fine, scale, mon, err);
    int rc = RD_OK;
    for (int g = 0; rc == RD_OK && g < D; g++, fs->count++)
        rc = solve_film(rp, p, fs, g, fine, mon, err);
    if (rc == RD_OK)
        films_weights(fs, NULL, scale);
    return rc;
}

/* The mean over [a0, a1] (deg) of the contact result's segment pressures,
 * each over its arc. */
static double arc_pressure(const rd_contact_result *c, double a0, double a1)
{
    double sum = 0.0;
    for (int j = 0; j < c->points; j++) {
        double lo = c->angle_deg[j] - 0.5 * c->width_deg[j], hi = lo + c->width_deg[j];
        double w = fmin(hi, a1) - fmax(lo, a0);
        if (w > 0.0)
            sum += w * c->pressure[j];
    }
    return sum / (a1 - a0);
}

int rd_lift_bore_loads(const rd_ring *ring, const rd_lift_params *p, double *load,
                       double *angle_deg, rd_error *err)
{
    int n = rd_ring_get_segments(ring), m = 16 * n;
    m = m < 64 ? 64 : (m > RD_LIFT_FILMS_CONTACT_SEGMENTS ? RD_LIFT_FILMS_CONTACT_SEGMENTS : m);
    return rd_lift_bore_loads_at(ring, p, m, NULL, load, angle_deg, err);
}

int rd_lift_bore_loads_at(const rd_ring *ring, const rd_lift_params *p, int segments,
                          const rd_monitor *mon, double *load, double *angle_deg, rd_error *err)
{
    const rd_ring_params *rp = rd_ring_get_params(ring);
    int n = rd_ring_get_segments(ring);
    for (int i = 0; i < n; i++) {
        double a = rd_ring_get_segment_angle(ring, i) * 180.0 / M_PI;
        angle_deg[i] = a < 0.0 ? a + 360.0 : a;
        load[i] = 0.0;
    }
    if (!(rp->tangential_force > 0.0))
        return RD_OK; /* no pretension: no elastic load (the gas behind still presses) */
    rd_contact_opts o;
    rd_static_opts so;
    rd_contact_opts_default(&o);
    rd_static_opts_default(&so);
    o.bore = p->bore;
    so.estimate_error = 0; /* one solve at `segments` (test_lift_films: its accuracy) */
    rd_contact_result c;
    memset(&c, 0, sizeof c);
    int rc = rd_monitor_report(mon, 0.0, err);
    rc = rc ? rc : rd_contact_solve(rp, segments, &o, &so, mon, &c, err);
    if (rc == RD_OK) {
        double w_el = 2.0 * rp->tangential_force / rp->diameter;
        double phi = rd_ring_get_section(ring)->span / n * 180.0 / M_PI;
        for (int i = 0; i < n; i++)
            load[i] = w_el * arc_pressure(&c, angle_deg[i] - 0.5 * phi, angle_deg[i] + 0.5 * phi) /
                      c.uniform_pressure;
    }
    rd_contact_result_cleanup(&c);
    return rc;
}

int rd_lift_films_bore(const rd_ring *ring, const rd_lift_params *p, const rd_monitor *mon,
                       rd_lift_films *fs, rd_error *err)
{
    int n = rd_ring_get_segments(ring);
    memset(fs, 0, sizeof *fs);
    double *load = malloc(2 * (size_t)n * sizeof *load);
    if (!load)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the films' loads.");
    int m = 16 * n;
    m = m < 64 ? 64 : (m > RD_LIFT_FILMS_CONTACT_SEGMENTS ? RD_LIFT_FILMS_CONTACT_SEGMENTS : m);
    int rc = rd_lift_bore_loads_at(ring, p, m, mon, load, load + n, err);
    if (rc == RD_OK)
        rc = rd_lift_films_run(rd_ring_get_params(ring), p, load, load + n, n, 1, mon, fs, err);
    free(load);
    return rc;
}

static rd_lube_films lube_films(const rd_lift_films *fs)
{
    return (rd_lube_films){.film = &fs->film[0],
                           .tr = fs->tr,
                           .count = fs->count,
                           .share = fs->share,
                           .m = fs->count > 1 || !fs->exact ? fs->m : 0,
                           .wt = fs->wt,
                           .angle_deg = fs->angle_deg};
}

int rd_lift_films_result(const rd_ring_params *rp, const rd_lift_params *p, const rd_lift_films *fs,
                         rd_lift_result *out, rd_error *err)
{
    rd_lube_films set = lube_films(fs);
    int rc = rd_lift_lube_fill_films(&out->lube, &set, &p->friction.lube, &p->engine, rp->diameter,
                                     out->crank_deg, out->samples, 0.0,
                                     (int)floor(p->engine.cycles + 1e-9), err);
    out->lube.film_step_deg = p->film_step_deg;
    out->lube.load_min = INFINITY;
    out->lube.load_max = -INFINITY;
    for (int j = 0; j < fs->m; j++) {
        out->lube.load_min = fmin(out->lube.load_min, fs->seg_load[j]);
        out->lube.load_max = fmax(out->lube.load_max, fs->seg_load[j]);
    }
    out->lube.interp_check = fs->interp_check;
    return rc;
}

int rd_lift_films_estimate(const rd_ring_params *rp, const rd_lift_params *p,
                           const rd_lift_films *fs, const rd_monitor *mon, rd_lift_result *out,
                           rd_error *err)
{
    rd_lift_films f2;
    rd_lift_lube fine = {0};
    int rc = rd_lift_films_run(rp, p, fs->seg_load, fs->angle_deg, fs->m, 2, mon, &f2, err);
    rd_lube_films set = lube_films(&f2);
    rc = rc ? rc
            : rd_lift_lube_fill_films(&fine, &set, &p->friction.lube, &p->engine, rp->diameter,
                                      out->crank_deg, out->samples, 0.0, out->lube.cycles, err);
    if (!rc)
        rd_lift_lube_compare(&out->lube, &fine, out->samples);
    rd_lift_lube_cleanup(&fine);
    rd_lift_films_free(&f2);
    return rc;
}
