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
    for (int g = 0; fs->solved && g < fs->cap; g++)
        if (fs->solved[g]) {
            rd_film_track_free(&fs->tr[g]);
            rd_film_free(&fs->film[g]);
        }
    free(fs->load);
    free(fs->follows);
    free(fs->film);
    free(fs->tr);
    memset(fs, 0, sizeof *fs);
}

/* fs's arrays for m segments over D depths and cap films. */
static int films_alloc(rd_lift_films *fs, int m, int D, int cap, rd_error *err)
{
    size_t c = (size_t)cap;
    fs->cap = cap;
    fs->load = malloc((3 * c + (size_t)m * (c + 2 + (size_t)D)) * sizeof *fs->load);
    fs->follows = calloc(2 * c, sizeof *fs->follows);
    fs->film = calloc(c, sizeof *fs->film);
    fs->tr = calloc(c, sizeof *fs->tr);
    if (!fs->load || !fs->follows || !fs->film || !fs->tr)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the films of %d segments.", m);
    fs->share = fs->load + c;
    fs->acc = fs->share + c;
    fs->wt = fs->acc + c;
    fs->seg_load = fs->wt + (size_t)m * c;
    fs->angle_deg = fs->seg_load + (size_t)m * (size_t)D;
    fs->lever_buf = fs->angle_deg + m;
    fs->solved = fs->follows + c;
    return RD_OK;
}

/* Segment j's loads (depths values). */
static const double *row(const rd_lift_films *fs, int j)
{
    return fs->seg_load + (size_t)fs->depths * j;
}

/* Segments j and k have the same loads at every depth. */
static int same_loads(const rd_lift_films *fs, int j, int k)
{
    if (fs->lever && fabs(fs->lever[j] - fs->lever[k]) > 1e-12)
        return 0; /* another sliding speed (a tilting piston) */
    for (int d = 0; d < fs->depths; d++)
        if (fabs(row(fs, j)[d] - row(fs, k)[d]) > RD_LIFT_FILMS_SAME * fs->scale)
            return 0;
    return 1;
}

/* The segments of distinct loads (within RD_LIFT_FILMS_SAME x scale at
 * every depth) into fs->follows, up to `cap`; returns their number (cap + 1:
 * more). */
static int distinct_loads(rd_lift_films *fs, int cap)
{
    int D = 0;
    for (int j = 0; j < fs->m && D <= cap; j++) {
        int g = 0;
        while (g < D && !same_loads(fs, j, fs->follows[g]))
            g++;
        if (g == D && D < cap) {
            fs->follows[g] = j;
            fs->load[g] = row(fs, j)[0];
        }
        if (g == D)
            D++;
    }
    return D;
}

/* Each segment's weights over the count films (one-hot on its own loads
 * when exact, else the interpolation at its coordinate; along a map, the
 * first depth's, read at each time instead) and the films' shares. */
static void films_weights(rd_lift_films *fs)
{
    const int N = fs->cap;
    memset(fs->share, 0, (size_t)N * sizeof *fs->share);
    for (int j = 0; j < fs->m; j++) {
        double *w = fs->wt + (size_t)N * j;
        memset(w, 0, (size_t)N * sizeof *w);
        if (fs->exact) {
            int g = 0;
            while (g + 1 < fs->count && !same_loads(fs, j, fs->follows[g]))
                g++;
            w[g] = 1.0;
        } else
            rd_lift_films_cheb(fs->xs, fs->count, rd_lift_films_coord(row(fs, j)[0], fs->scale), w);
        for (int g = 0; g < fs->count; g++)
            fs->share[g] += w[g] / fs->m;
    }
}

/* Film g's track solved (fs->count counts the solved): exact along a map,
 * under its segment's loads; else at fs->load[g]. */
static int solve_film(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_films *fs, int g,
                      int fine, const rd_monitor *mon, rd_error *err)
{
    int rc = rd_monitor_report(mon, 0.0, err);
    if (rc)
        return rc;
    if (fs->exact && (fs->depths > 1 || fs->lever))
        rc = rd_lift_film_run_history(rp, p, fs->z, row(fs, fs->follows[g]), fs->depths,
                                      fs->lever ? fs->lever[fs->follows[g]] : 0.0, fine,
                                      &fs->film[g], &fs->tr[g], err);
    else
        rc = rd_lift_film_run_load(rp, p, fs->load[g], fine, &fs->film[g], &fs->tr[g], err);
    fs->solved[g] = 1;
    return rc;
}

/* The relative miss of work `got` against `want`. */
static double work_miss(double got, double want)
{
    return fabs(got - want) / fmax(fabs(want), 1e-300);
}

/* How far the interpolation over the nodes old[0..K) misses the film of
 * node g: the film relative to max(|h0|, sigma) over its steps, and the
 * friction work per cycle relative; the larger. */
static double miss_at(const rd_lift_params *p, const rd_ring_params *rp, const rd_lift_films *fs,
                      const int *old, int K, const double *xo, double x, int g)
{
    double w[RD_LIFT_FILMS_NODES], fe = 0.0, we = 0.0;
    rd_lift_films_cheb(xo, K, x, w);
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
        we = fmax(we, work_miss(got, want));
    }
    return fmax(fe, we);
}

/* The interpolated films: Chebyshev-Lobatto nodes in the coordinate over
 * the segments' loads, 3, then 5, 9, 17 (each level's nodes the next's
 * even ones), until the coarser level misses the new nodes' films by no
 * more than RD_LIFT_FILMS_TOL; the finer level is used, fs->interp_check
 * is that miss (an estimate of the films' miss against each segment's own film). */
static int films_interpolated(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_films *fs,
                              int fine, const rd_monitor *mon, rd_error *err)
{
    double lo = INFINITY, hi = -INFINITY, *xs = fs->xs;
    for (int j = 0; j < fs->m * fs->depths; j++) {
        lo = fmin(lo, rd_lift_films_coord(fs->seg_load[j], fs->scale));
        hi = fmax(hi, rd_lift_films_coord(fs->seg_load[j], fs->scale));
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
            fs->load[k] = exp(xs[k]) - 0.1 * fs->scale;
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
        films_weights(fs);
    return rc;
}

/* The quasi-static interpolation's miss on segment j along a map: its film
 * under its own loads (tr) against the films' interpolation at its load
 * at each time; as miss_at. */
static double history_miss(const rd_lift_params *p, const rd_ring_params *rp,
                           const rd_lift_films *fs, int j, const rd_film_track *tr, double sigma)
{
    double fe = 0.0, we = 0.0, w[RD_LIFT_FILMS_NODES];
    for (int k = 0; k <= tr->steps; k++) {
        double h = 0.0;
        rd_lift_films_weights(fs, tr->pt[k].t, j, w);
        for (int g = 0; g < fs->count; g++) {
            rd_film_point pt;
            rd_film_track_at(&fs->tr[g], tr->pt[k].t, &pt);
            h += w[g] * pt.h0;
        }
        fe = fmax(fe, fabs(h - tr->pt[k].h0) / fmax(fabs(tr->pt[k].h0), sigma));
    }
    double omega = rd_engine_omega(&p->engine), cycle = 4.0 * M_PI / omega;
    double circ = M_PI * rp->diameter, ureg = rd_liner_ureg(&p->engine);
    double mu_b = p->friction.lube.boundary_coefficient;
    for (int c = 0; c < (int)floor(p->engine.cycles + 1e-9); c++) {
        double want = rd_lift_film_work(tr, circ, mu_b, ureg, c * cycle, cycle), got = 0.0;
        for (int g = 0; g < fs->count; g++) {
            const rd_film_track *t = &fs->tr[g];
            for (int k = 0; k < t->steps; k++) { /* film g's power times j's weight, trapezoid */
                const rd_film_point *a = &t->pt[k], *b = &t->pt[k + 1];
                double mid = 0.5 * (a->t + b->t), wa[RD_LIFT_FILMS_NODES], wb[RD_LIFT_FILMS_NODES];
                if (mid < c * cycle || mid > (c + 1) * cycle)
                    continue;
                rd_lift_films_weights(fs, a->t, j, wa);
                rd_lift_films_weights(fs, b->t, j, wb);
                got += 0.5 * (b->t - a->t) *
                       (wa[g] * rd_lift_film_power(a, circ, mu_b, ureg) +
                        wb[g] * rd_lift_film_power(b, circ, mu_b, ureg));
            }
        }
        we = fmax(we, work_miss(got, want));
    }
    return fmax(fe, we);
}

/* Along a map: the RD_LIFT_FILMS_CHECKS segments whose coordinate swings
 * most over the depths, each solved under its own loads and measured
 * against the quasi-static interpolation; fs->interp_check the larger. */
static int check_histories(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_films *fs,
                           int fine, const rd_monitor *mon, rd_error *err)
{
    int pick[RD_LIFT_FILMS_CHECKS], picked = 0, rc = RD_OK;
    for (int c = 0; c < RD_LIFT_FILMS_CHECKS; c++) {
        double best = 0.0;
        pick[c] = -1;
        for (int j = 0; j < fs->m; j++) {
            double lo = INFINITY, hi = -INFINITY;
            int taken = 0;
            for (int q = 0; q < picked; q++)
                taken |= same_loads(fs, j, pick[q]);
            for (int d = 0; d < fs->depths && !taken; d++) {
                lo = fmin(lo, rd_lift_films_coord(row(fs, j)[d], fs->scale));
                hi = fmax(hi, rd_lift_films_coord(row(fs, j)[d], fs->scale));
            }
            if (!taken && hi - lo > best) {
                best = hi - lo;
                pick[c] = j;
            }
        }
        if (pick[c] >= 0)
            picked++;
        else
            break;
    }
    for (int c = 0; rc == RD_OK && c < picked; c++) {
        rd_film f = {0};
        rd_film_track tr = {0};
        rc = rd_monitor_report(mon, 0.0, err);
        rc = rc ? rc
                : rd_lift_film_run_table(rp, p, fs->z, row(fs, pick[c]), fs->depths, fine, &f, &tr,
                                         err);
        if (rc == RD_OK)
            fs->interp_check =
                fmax(fs->interp_check, history_miss(p, rp, fs, pick[c], &tr, f.sigma));
        rd_film_track_free(&tr);
        rd_film_free(&f);
    }
    return rc;
}

/* Every distinct history its own film (fs->exact): up to fs->cap. */
static int films_exact(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_films *fs,
                       int fine, const rd_monitor *mon, rd_error *err)
{
    int distinct = distinct_loads(fs, fs->cap), rc = RD_OK;
    fs->exact = 1;
    fs->varying = 0;
    fs->count = 0;
    fs->interp_check = NAN;
    for (int g = 0; rc == RD_OK && g < distinct; g++, fs->count++)
        rc = solve_film(rp, p, fs, g, fine, mon, err);
    if (rc == RD_OK)
        films_weights(fs);
    return rc;
}

/* The interpolated films dropped (to solve them exactly instead). */
static void drop_films(rd_lift_films *fs)
{
    for (int g = 0; g < fs->cap; g++)
        if (fs->solved[g]) {
            rd_film_track_free(&fs->tr[g]);
            rd_film_free(&fs->film[g]);
            fs->solved[g] = 0;
        }
}

int rd_lift_films_run(const rd_ring_params *rp, const rd_lift_params *p,
                      const rd_lift_film_loads *ld, int fine, const rd_monitor *mon,
                      rd_lift_films *fs, rd_error *err)
{
    memset(fs, 0, sizeof *fs);
    int m = ld->m, D = ld->depths > 1 ? ld->depths : 1;
    fs->p = p;
    fs->m = m;
    fs->depths = D;
    fs->interp_check = fs->depth_check = NAN;
    fs->scale = 2.0 * rp->tangential_force / rp->diameter;
    for (int d = 0; d < D && D > 1; d++)
        fs->z[d] = ld->z[d];
    /* each distinct history its own film: up to m along a map or on a tilting piston */
    int own = (D > 1 || ld->lever || ld->exact > 0) && m > RD_LIFT_FILMS_NODES;
    int rc = films_alloc(fs, m, D, own ? m : RD_LIFT_FILMS_NODES, err);
    if (rc)
        return rc;
    memcpy(fs->seg_load, ld->load, (size_t)m * D * sizeof *ld->load);
    memcpy(fs->angle_deg, ld->angle_deg, (size_t)m * sizeof *ld->angle_deg);
    for (int j = 0; ld->lever && j < m; j++)
        fs->lever = ld->lever[j] != 0.0 ? fs->lever_buf : fs->lever;
    if (fs->lever)
        memcpy(fs->lever, ld->lever, (size_t)m * sizeof *ld->lever);
    if (ld->exact > 0 || fs->lever ||
        distinct_loads(fs, RD_LIFT_FILMS_EXACT) <= RD_LIFT_FILMS_EXACT)
        return films_exact(rp, p, fs, fine, mon, err);
    for (int j = 0; j < m && D > 1 && !fs->varying; j++)
        for (int d = 1; d < D; d++)
            fs->varying |= row(fs, j)[d] != row(fs, j)[0];
    rc = films_interpolated(rp, p, fs, fine, mon, err);
    if (rc || !fs->varying || fine > 1)
        return rc;
    rc = check_histories(rp, p, fs, fine, mon, err);
    if (rc || !(fs->interp_check > RD_LIFT_FILMS_TOL) || ld->exact < 0)
        return rc;
    drop_films(fs); /* quasi-static in the load misses: each history its own film */
    return films_exact(rp, p, fs, fine, mon, err);
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

/* The contact solve's segments for a lift ring of n: 16 n within 64 ..
 * RD_LIFT_FILMS_CONTACT_SEGMENTS. */
static int contact_segments(int n)
{
    int m = 16 * n;
    return m < 64 ? 64 : (m > RD_LIFT_FILMS_CONTACT_SEGMENTS ? RD_LIFT_FILMS_CONTACT_SEGMENTS : m);
}

int rd_lift_bore_loads(const rd_ring *ring, const rd_lift_params *p, double *load,
                       double *angle_deg, rd_error *err)
{
    return rd_lift_bore_loads_at(ring, &p->bore, contact_segments(rd_ring_get_segments(ring)), NULL,
                                 load, angle_deg, err);
}

int rd_lift_bore_loads_at(const rd_ring *ring, const rd_bore *b, int segments,
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
    o.bore = *b;
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

/* A map's loads being refined: depths so far in order, each one's n loads
 * (column d at col + d n). */
typedef struct depth_set {
    const struct rd_ring *ring;
    const rd_lift_params *p;
    int n, segments, count, reserve; /* reserve: the layers still to append */
    const rd_monitor *mon;
    double *z, *col, *angle, w_el, miss;
} depth_set;

/* The loads at depth z into l: the map's bore there (rd_bore_map_at). */
static int loads_at_depth(depth_set *ds, double z, double *l, rd_error *err)
{
    rd_bore b;
    int rc = rd_bore_map_at(ds->p->bore_map, z, rd_ring_get_params(ds->ring)->diameter, &b, err);
    return rc ? rc : rd_lift_bore_loads_at(ds->ring, &b, ds->segments, ds->mon, l, ds->angle, err);
}

/* Appends depth z with loads l. */
static void append(depth_set *ds, double z, const double *l)
{
    ds->z[ds->count] = z;
    memcpy(ds->col + (size_t)ds->count * ds->n, l, (size_t)ds->n * sizeof *l);
    ds->count++;
}

/* Between depths za (loads la) and zb (lb, not yet appended): the loads at
 * the middle against the straight line; beyond RD_LIFT_FILMS_DEPTH_TOL the
 * middle becomes a depth and both halves are refined, to
 * RD_LIFT_FILMS_DEPTH_LEVELS. */
static int refine(depth_set *ds, double za, const double *la, double zb, const double *lb,
                  int level, rd_error *err)
{
    if (level >= RD_LIFT_FILMS_DEPTH_LEVELS || ds->count + 2 + ds->reserve > RD_BORE_LAYERS_MAX)
        return RD_OK; /* (the map's own layers are at most RD_BORE_LAYERS_MAX) */
    double zm = 0.5 * (za + zb), miss = 0.0;
    double *lm = malloc((size_t)ds->n * sizeof *lm);
    if (!lm)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the films' loads.");
    int rc = loads_at_depth(ds, zm, lm, err);
    for (int j = 0; rc == RD_OK && j < ds->n; j++)
        miss = fmax(miss, fabs(lm[j] - 0.5 * (la[j] + lb[j])) / ds->w_el);
    if (rc == RD_OK && miss > RD_LIFT_FILMS_DEPTH_TOL) {
        rc = refine(ds, za, la, zm, lm, level + 1, err);
        if (rc == RD_OK)
            append(ds, zm, lm);
        rc = rc ? rc : refine(ds, zm, lm, zb, lb, level + 1, err);
    } else if (rc == RD_OK)
        ds->miss = fmax(ds->miss, miss);
    free(lm);
    return rc;
}

int rd_lift_map_loads(const rd_ring *ring, const rd_lift_params *p, int segments,
                      const rd_monitor *mon, double *load, double *angle_deg, double *z,
                      int *depths, double *miss, rd_error *err)
{
    const rd_bore_map *mp = p->bore_map;
    int n = rd_ring_get_segments(ring), nl = mp->n_layers, i0 = 0, i1 = nl - 1, rc = RD_OK;
    double top = p->ring_z_tdc, bottom = top + 2.0 * p->engine.crank_radius;
    while (i0 + 1 < nl && mp->layer[i0 + 1].z <= top)
        i0++;
    while (i1 > i0 + 1 && mp->layer[i1 - 1].z >= bottom)
        i1--;
    const rd_ring_params *rp = rd_ring_get_params(ring);
    depth_set ds = {.ring = ring,
                    .p = p,
                    .n = n,
                    .segments = segments,
                    .mon = mon,
                    .z = z,
                    .angle = angle_deg,
                    .w_el = 2.0 * rp->tangential_force / rp->diameter};
    ds.col = malloc((size_t)n * (RD_BORE_LAYERS_MAX + 1) * sizeof *ds.col);
    if (!ds.col)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the films' loads.");
    double *l = ds.col + (size_t)n * RD_BORE_LAYERS_MAX;
    for (int i = i0; rc == RD_OK && i <= i1; i++) {
        ds.reserve = i1 - i;
        rc = rd_lift_bore_loads_at(ring, &mp->layer[i].bore, segments, mon, l, angle_deg, err);
        if (rc == RD_OK && i > i0 && ds.w_el > 0.0)
            rc = refine(&ds, ds.z[ds.count - 1], ds.col + (size_t)(ds.count - 1) * n,
                        mp->layer[i].z, l, 0, err);
        if (rc == RD_OK)
            append(&ds, mp->layer[i].z, l);
    }
    *depths = ds.count;
    for (int j = 0; rc == RD_OK && j < n; j++)
        for (int d = 0; d < ds.count; d++)
            load[(size_t)j * ds.count + (size_t)d] = ds.col[(size_t)d * n + (size_t)j];
    *miss = ds.miss;
    free(ds.col);
    return rc;
}

int rd_lift_films_needed(const rd_lift_params *p, double d)
{
    return rd_lift_bore_distorted(p, d) || p->engine.tilt_points > 1;
}

int rd_lift_films_bore(const rd_ring *ring, const rd_lift_params *p, const rd_monitor *mon,
                       rd_lift_films *fs, rd_error *err)
{
    const rd_ring_params *rp = rd_ring_get_params(ring);
    int n = rd_ring_get_segments(ring), m = contact_segments(n);
    memset(fs, 0, sizeof *fs);
    double *load = malloc((size_t)n * (RD_BORE_LAYERS_MAX + 2) * sizeof *load),
           z[RD_BORE_LAYERS_MAX];
    if (!load)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the films' loads.");
    double *angle = load + (size_t)n * RD_BORE_LAYERS_MAX, *lever = angle + n;
    rd_lift_film_loads ld = {.m = n, .depths = 1, .z = z, .load = load, .angle_deg = angle};
    double miss = NAN, R = rd_ring_get_section(ring)->R;
    int rc = RD_OK;
    if (p->bore_map)
        rc = rd_lift_map_loads(ring, p, m, mon, load, angle, z, &ld.depths, &miss, err);
    else if (rd_lift_bore_distorted(p, rp->diameter))
        rc = rd_lift_bore_loads_at(ring, &p->bore, m, mon, load, angle, err);
    else /* a round bore (a tilting piston's films): 2 F_t / D all round */
        for (int i = 0; i < n; i++) {
            double a = rd_ring_get_segment_angle(ring, i) * 180.0 / M_PI;
            angle[i] = a < 0.0 ? a + 360.0 : a;
            load[i] = 2.0 * rp->tangential_force / rp->diameter;
        }
    if (p->engine.tilt_points > 1) { /* a tilt that moves: each segment's arm about the pin */
        for (int i = 0; i < n; i++)
            lever[i] = R * cos(angle[i] * M_PI / 180.0);
        ld.lever = lever;
    }
    if (rc == RD_OK)
        rc = rd_lift_films_run(rp, p, &ld, 1, mon, fs, err);
    fs->depth_check = miss;
    free(load);
    return rc;
}

rd_lube_films rd_lift_films_view(const rd_lift_films *fs)
{
    return (rd_lube_films){.film = &fs->film[0],
                           .tr = fs->tr,
                           .count = fs->count,
                           .share = fs->share,
                           .m = fs->count > 1 || !fs->exact ? fs->m : 0,
                           .wt = fs->wt,
                           .angle_deg = fs->angle_deg,
                           .stride = fs->cap,
                           .src = fs};
}

int rd_lift_films_result(const rd_ring_params *rp, const rd_lift_params *p, const rd_lift_films *fs,
                         rd_lift_result *out, rd_error *err)
{
    rd_lube_films set = rd_lift_films_view(fs);
    int rc = rd_lift_lube_fill_films(&out->lube, &set, &p->friction.lube, &p->engine, rp->diameter,
                                     out->crank_deg, out->samples, 0.0,
                                     (int)floor(p->engine.cycles + 1e-9), err);
    out->lube.film_step_deg = p->film_step_deg;
    out->lube.load_min = INFINITY;
    out->lube.load_max = -INFINITY;
    for (int j = 0; j < fs->m * fs->depths; j++) {
        out->lube.load_min = fmin(out->lube.load_min, fs->seg_load[j]);
        out->lube.load_max = fmax(out->lube.load_max, fs->seg_load[j]);
    }
    out->lube.interp_check = fs->interp_check;
    out->lube.load_depths = fs->depths;
    out->lube.tilt_films = fs->lever != NULL;
    out->lube.load_depth_error = fs->depth_check;
    return rc;
}

int rd_lift_films_estimate(const rd_ring_params *rp, const rd_lift_params *p,
                           const rd_lift_films *fs, const rd_monitor *mon, rd_lift_result *out,
                           rd_error *err)
{
    rd_lift_films f2;
    rd_lift_lube fine = {0};
    rd_lift_film_loads ld = {fs->m,         fs->depths,    fs->z,    fs->seg_load,
                             fs->angle_deg, fs->exact > 0, fs->lever};
    int rc = rd_lift_films_run(rp, p, &ld, 2, mon, &f2, err);
    rd_lube_films set = rd_lift_films_view(&f2);
    rc = rc ? rc
            : rd_lift_lube_fill_films(&fine, &set, &p->friction.lube, &p->engine, rp->diameter,
                                      out->crank_deg, out->samples, 0.0, out->lube.cycles, err);
    if (!rc)
        rd_lift_lube_compare(&out->lube, &fine, out->samples);
    rd_lift_lube_cleanup(&fine);
    rd_lift_films_free(&f2);
    return rc;
}
