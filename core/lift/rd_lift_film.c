/*
 * rd_lift_film.c — the lubricated friction model in the lift analysis: the
 * oil film of the rigid running face over the whole run (core/liner
 * rd_film_track.h), solved once before the ring's motion, and the
 * lubrication block of the result from it.
 *
 * The film's loads at time t: the liner slides past the face at the
 * piston's speed U = ds/dt (the ring's own axial motion in its groove, um,
 * is left out of the film's sliding speed; the friction each bore point
 * feels takes its own speed, rd_liner_law.h); the radial load is the
 * ring's elastic line load 2 F_t / D plus the gas behind the ring over the
 * back face (per metre of the liner's circumference: times r_back /
 * r_run); the film's edges see the gas below (lower edge) and above (upper
 * edge).  On a tilting piston whose tilt moves (a table) a segment at arm
 * x about the pin axis (R cos theta) slides at U + beta' x: its film's
 * lever (rd_lift_film_run_history), each arm its own film.
 *
 * A round bore: one film for the whole face.  A distorted bore
 * (bore.distortion, bore.diameter): a film per segment load
 * (rd_lift_films_*, rd_lift_internal.h): the contact analysis' exact
 * contact of the same ring in the same bore gives each segment's elastic
 * load (rd_lift_bore_loads), segments of one load share a film, and the
 * force elements read each segment's film (rd_lift_segfilm.c).  A bore map:
 * each segment's load at the ring's depth (rd_lift_map_loads).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_film_track.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

typedef struct film_scene {
    const rd_lift_params *p;
    double omega, back;
    const double *z, *w_el; /* the elastic line load over nz depths (nz 1: constant) */
    int nz;
    double lever; /* m: the face's arm about the piston pin (its tilt's own sliding), 0: none */
} film_scene;

double rd_lift_lube_viscosity(const rd_lube_params *l, double deg)
{
    if (l->viscosity > 0.0)
        return l->viscosity;
    double T = l->temperature_c;
    if (l->temp_points > 0) {
        rd_gas_params g = {.points = l->temp_points, .crank_deg = l->temp_crank_deg};
        T = rd_lift_gas_at(&g, l->temp_c, deg);
    }
    return l->vogel_a * exp(l->vogel_b / (T + 273.15 - l->vogel_c));
}

static void loads_at(void *ctx, double t, double *U, double *eta, double *W, double *plo,
                     double *phi)
{
    const film_scene *fs = ctx;
    const rd_lift_params *p = fs->p;
    double alpha = fs->omega * t, deg = alpha * 180.0 / M_PI, v;
    rd_engine_piston(&p->engine, alpha, NULL, &v, NULL);
    *U = v;
    if (fs->lever != 0.0) { /* the groove's own axial speed there, beta' x (rd_lift_forces.c) */
        double b, b1, b2;
        rd_engine_tilt_at(&p->engine, deg, &b, &b1, &b2);
        *U += b1 * fs->omega * fs->lever;
    }
    *eta = rd_lift_lube_viscosity(&p->friction.lube, deg);
    *W = fs->nz > 1 ? rd_lift_depth_interp(fs->z, fs->w_el, fs->nz, rd_lift_depth_at(p, t))
                    : fs->w_el[0];
    *plo = *phi = 0.0;
    if (p->gas.points > 0) {
        *W += fs->back * rd_lift_gas_at(&p->gas, p->gas.behind, deg);
        *plo = rd_lift_gas_at(&p->gas, p->gas.below, deg);
        *phi = rd_lift_gas_at(&p->gas, p->gas.above, deg);
    }
}

int rd_lift_film_run(const rd_ring_params *rp, const rd_lift_params *p, rd_film *film,
                     rd_film_track *tr, rd_error *err)
{
    return rd_lift_film_run_at(rp, p, 1, film, tr, err);
}

int rd_lift_film_run_load(const rd_ring_params *rp, const rd_lift_params *p, double w_el, int fine,
                          rd_film *film, rd_film_track *tr, rd_error *err)
{
    return rd_lift_film_run_table(rp, p, NULL, &w_el, 1, fine, film, tr, err);
}

int rd_lift_film_run_table(const rd_ring_params *rp, const rd_lift_params *p, const double *z,
                           const double *w_el, int nz, int fine, rd_film *film, rd_film_track *tr,
                           rd_error *err)
{
    return rd_lift_film_run_history(rp, p, z, w_el, nz, 0.0, fine, film, tr, err);
}

int rd_lift_film_run_history(const rd_ring_params *rp, const rd_lift_params *p, const double *z,
                             const double *w_el, int nz, double lever, int fine, rd_film *film,
                             rd_film_track *tr, rd_error *err)
{
    rd_section s;
    rd_section_init(&s, rp);
    size_t m = rd_error_enter(err, "/ring");
    rd_error_enter(err, "/face");
    int rc = rd_film_init(film, &p->face, s.run.height, fine * (RD_FILM_NODES - 1) + 1,
                          p->bore.roughness_rq, &p->friction.lube, rp->youngs_modulus,
                          rp->poisson_ratio, err);
    rd_error_leave(err, m);
    if (rc)
        return rc;
    film->rtol /= (double)fine * fine;
    film_scene fs = {.p = p,
                     .omega = rd_engine_omega(&p->engine),
                     .z = z,
                     .w_el = w_el,
                     .nz = nz,
                     .lever = lever};
    fs.back = s.back.height * s.back.r / s.run.r;
    rd_film_loads ld = {loads_at, &fs};
    double cycle = 4.0 * M_PI / fs.omega, dt = p->film_step_deg / fine * M_PI / 180.0 / fs.omega;
    return rd_film_track_run(film, &ld, p->engine.cycles * cycle, dt, cycle, cycle, NAN, tr, err);
}

int rd_lift_film_run_at(const rd_ring_params *rp, const rd_lift_params *p, int fine, rd_film *film,
                        rd_film_track *tr, rd_error *err)
{
    return rd_lift_film_run_load(rp, p, 2.0 * rp->tangential_force / rp->diameter, fine, film, tr,
                                 err);
}

/* The friction on the ring of film point pt (N, + up): the film's shear
 * and the asperities', at the liner's speed past the piston. */
static void friction_of(const rd_film_point *pt, double circ, double mu_b, double ureg,
                        double *hydro, double *asp)
{
    *hydro = circ * (pt->Cc * pt->U + pt->Fp);
    *asp = circ * mu_b * pt->Wa * tanh(pt->U / ureg);
}

int rd_lift_film_result(const rd_ring_params *rp, const rd_lift_params *p, const rd_film *film,
                        const rd_film_track *tr, rd_lift_result *out, rd_error *err)
{
    int rc = rd_lift_lube_fill(&out->lube, film, tr, &p->friction.lube, &p->engine, rp->diameter,
                               out->crank_deg, out->samples, 0.0,
                               (int)floor(p->engine.cycles + 1e-9), err);
    out->lube.film_step_deg = p->film_step_deg;
    out->lube.load_min = out->lube.load_max = 2.0 * rp->tangential_force / rp->diameter;
    return rc;
}

/* Film g's own sliding besides the piston's at t: a tilting piston's
 * groove, beta' x (its segments' arm; 0 without). */
static double lever_speed(const rd_lube_films *fs, const rd_engine_params *e, double omega,
                          double t, int g)
{
    const rd_lift_films *src = fs->src;
    if (!src || !src->lever || !src->exact)
        return 0.0;
    double b, b1, b2;
    rd_engine_tilt_at(e, omega * t * 180.0 / M_PI, &b, &b1, &b2);
    return b1 * omega * src->lever[src->follows[g]];
}

/* Film g's share of the ring at t. */
static double share_at(const rd_lube_films *fs, double t, int g)
{
    if (fs->src && fs->src->varying)
        return rd_lift_films_share(fs->src, t, g);
    return fs->share ? fs->share[g] : 1.0;
}

/* Sample k of lb at time t: each film's point weighted by its share (the
 * first assigned, so one film gives its own numbers bit for bit); the
 * thinnest film over the films, or over the segments (fs->m). */
static void fill_sample(rd_lift_lube *lb, const rd_lube_films *fs, const rd_engine_params *e,
                        double omega, double circ, double mu_b, double ureg, double t, int k,
                        double *h0)
{
    double hf = 0.0, af = 0.0, pw = 0.0, wa = 0.0, ld = 0.0;
    for (int g = 0; g < fs->count; g++) {
        rd_film_point pt;
        double w = share_at(fs, t, g), h, a;
        rd_film_track_at(&fs->tr[g], t, &pt);
        rd_engine_piston(e, omega * t, NULL, &pt.U, NULL); /* exact, as the motion's friction */
        pt.U += lever_speed(fs, e, omega, t, g);
        friction_of(&pt, circ, mu_b, ureg, &h, &a);
        hf = g ? hf + w * h : w * h;
        af = g ? af + w * a : w * a;
        pw = g ? pw + w * (h + a) * pt.U : w * (h + a) * pt.U;
        wa = g ? wa + w * pt.Wa : w * pt.Wa;
        ld = g ? ld + w * (pt.W + pt.Wa) : w * (pt.W + pt.Wa);
        h0[g] = pt.h0;
        if (g == 0 || pt.h0 < lb->min_film[k])
            lb->min_film[k] = pt.h0;
    }
    for (int j = 0; j < fs->m; j++) { /* each segment's film */
        double h = 0.0, wj[RD_LIFT_FILMS_NODES];
        const double *w = fs->wt + (size_t)fs->stride * j;
        if (fs->src && fs->src->varying) {
            rd_lift_films_weights(fs->src, t, j, wj);
            w = wj;
        }
        for (int g = 0; g < fs->count; g++)
            h += w[g] * h0[g];
        if (j == 0 || h < lb->min_film[k]) {
            lb->min_film[k] = h;
            lb->min_film_angle_deg[k] = fs->angle_deg[j];
        }
    }
    lb->hydrodynamic_friction[k] = hf;
    lb->asperity_friction[k] = af;
    lb->power[k] = pw;
    lb->asperity_share[k] = ld > 0.0 ? wa / ld : 0.0;
    lb->regime[k] = lb->asperity_share[k] > RD_LUBE_BOUNDARY_SHARE ? RD_REGIME_BOUNDARY
                    : lb->asperity_share[k] > RD_LUBE_MIXED_SHARE  ? RD_REGIME_MIXED
                                                                   : RD_REGIME_HYDRODYNAMIC;
}

double rd_lift_film_power(const rd_film_point *pt, double circ, double mu_b, double ureg)
{
    double h, a;
    friction_of(pt, circ, mu_b, ureg, &h, &a);
    return (h + a) * pt->U;
}

/* The friction work of film g of fs over [t0, t0 + cycle], times its share
 * (at each step where it varies): the power over the film's own steps
 * (trapezoid; they land on the cycles' ends). */
static double film_work(const rd_lube_films *fs, int g, double circ, double mu_b, double ureg,
                        double t0, double cycle)
{
    const rd_film_track *tr = &fs->tr[g];
    if (!(fs->src && fs->src->varying))
        return share_at(fs, t0, g) * rd_lift_film_work(tr, circ, mu_b, ureg, t0, cycle);
    double w = 0.0;
    for (int k = 0; k < tr->steps; k++) {
        const rd_film_point *a = &tr->pt[k], *b = &tr->pt[k + 1];
        double mid = 0.5 * (a->t + b->t);
        if (mid < t0 || mid > t0 + cycle)
            continue;
        w += 0.5 * (b->t - a->t) *
             (share_at(fs, a->t, g) * rd_lift_film_power(a, circ, mu_b, ureg) +
              share_at(fs, b->t, g) * rd_lift_film_power(b, circ, mu_b, ureg));
    }
    return w;
}

/* The friction work of one film over [t0, t0 + cycle]: the power over the
 * film's own steps (trapezoid; they land on the cycles' ends). */
double rd_lift_film_work(const rd_film_track *tr, double circ, double mu_b, double ureg, double t0,
                         double cycle)
{
    double w = 0.0;
    for (int k = 0; k < tr->steps; k++) {
        const rd_film_point *a = &tr->pt[k], *b = &tr->pt[k + 1];
        double mid = 0.5 * (a->t + b->t), h0, a0, h1, a1;
        if (mid < t0 || mid > t0 + cycle)
            continue;
        friction_of(a, circ, mu_b, ureg, &h0, &a0);
        friction_of(b, circ, mu_b, ureg, &h1, &a1);
        w += 0.5 * (b->t - a->t) * ((h0 + a0) * a->U + (h1 + a1) * b->U);
    }
    return w;
}

int rd_lift_lube_fill_films(rd_lift_lube *lb, const rd_lube_films *fs, const rd_lube_params *l,
                            const rd_engine_params *e, double diameter, const double *crank_deg,
                            int S, double t_first, int C, rd_error *err)
{
    size_t n = (size_t)(S > 0 ? S : 1);
    lb->on = 1;
    lb->films = fs->count;
    lb->min_film = malloc(5 * n * sizeof(double));
    lb->regime = malloc(n * sizeof(int));
    lb->friction_work = calloc((size_t)(2 * (C > 0 ? C : 1)), sizeof(double));
    lb->min_film_angle_deg = fs->m > 0 ? malloc(n * sizeof(double)) : NULL;
    if (!lb->min_film || !lb->regime || !lb->friction_work ||
        (fs->m > 0 && !lb->min_film_angle_deg))
        return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the lubrication block).");
    lb->hydrodynamic_friction = lb->min_film + n;
    lb->asperity_friction = lb->min_film + 2 * n;
    lb->power = lb->min_film + 3 * n;
    lb->asperity_share = lb->min_film + 4 * n;
    lb->fmep = lb->friction_work + (C > 0 ? C : 1);
    lb->cycles = C;
    lb->film_error = lb->work_error = NAN;
    lb->interp_check = lb->load_depth_error = NAN;
    lb->load_depths = 1;
    lb->load_min = lb->load_max = NAN; /* the caller's */
    double omega = rd_engine_omega(e), circ = M_PI * diameter;
    double ureg = rd_liner_ureg(e), mu_b = l->boundary_coefficient;
    double *h0 = malloc((size_t)fs->count * sizeof *h0);
    if (!h0)
        return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the lubrication block).");
    for (int k = 0; k < S; k++)
        fill_sample(lb, fs, e, omega, circ, mu_b, ureg,
                    t_first + crank_deg[k] * M_PI / 180.0 / omega, k, h0);
    free(h0);
    double cycle = 4.0 * M_PI / omega, stroke = 2.0 * e->crank_radius,
           Vd = 0.25 * M_PI * diameter * diameter * stroke;
    for (int c = 0; c < C; c++) {
        double w = 0.0;
        for (int g = 0; g < fs->count; g++) {
            double f = film_work(fs, g, circ, mu_b, ureg, t_first + c * cycle, cycle);
            w = g ? w + f : f;
        }
        lb->friction_work[c] = w;
        lb->fmep[c] = w / Vd;
    }
    lb->min_film_x = fs->film->x_min;
    lb->composite_sigma = fs->film->sigma;
    lb->viscosity_min = INFINITY;
    lb->viscosity_max = 0.0;
    for (double d = 0.0; d <= 720.0; d += 1.0) {
        double v = rd_lift_lube_viscosity(l, d);
        lb->viscosity_min = fmin(lb->viscosity_min, v);
        lb->viscosity_max = fmax(lb->viscosity_max, v);
    }
    lb->periodic_change = fs->tr[0].periodic_change;
    lb->film_solves = fs->tr[0].solves;
    lb->held = fs->tr[0].held;
    for (int g = 1; g < fs->count; g++) {
        lb->periodic_change = fmax(lb->periodic_change, fs->tr[g].periodic_change);
        lb->film_solves += fs->tr[g].solves;
        lb->held += fs->tr[g].held;
    }
    return RD_OK;
}

int rd_lift_lube_fill(rd_lift_lube *lb, const rd_film *film, const rd_film_track *tr,
                      const rd_lube_params *l, const rd_engine_params *e, double diameter,
                      const double *crank_deg, int S, double t_first, int C, rd_error *err)
{
    rd_lube_films fs = {.film = film, .tr = tr, .count = 1};
    return rd_lift_lube_fill_films(lb, &fs, l, e, diameter, crank_deg, S, t_first, C, err);
}

void rd_lift_lube_compare(rd_lift_lube *lb, const rd_lift_lube *fine, int S)
{
    double fe = 0.0, we = 0.0;
    for (int k = 0; k < S; k++)
        fe = fmax(fe, fabs(lb->min_film[k] - fine->min_film[k]) /
                          fmax(fabs(fine->min_film[k]), lb->composite_sigma));
    for (int c = 0; c < lb->cycles && c < fine->cycles; c++)
        we = fmax(we, fabs(lb->friction_work[c] - fine->friction_work[c]) /
                          fmax(fabs(fine->friction_work[c]), 1e-300));
    lb->film_error = fe;
    lb->work_error = we;
}

int rd_lift_film_estimate(const rd_ring_params *rp, const rd_lift_params *p, rd_lift_result *out,
                          rd_error *err)
{
    rd_film f;
    rd_film_track tr = {0};
    rd_lift_lube fine = {0};
    int rc = rd_lift_film_run_at(rp, p, 2, &f, &tr, err);
    rc = rc ? rc
            : rd_lift_lube_fill(&fine, &f, &tr, &p->friction.lube, &p->engine, rp->diameter,
                                out->crank_deg, out->samples, 0.0, out->lube.cycles, err);
    if (!rc)
        rd_lift_lube_compare(&out->lube, &fine, out->samples);
    rd_lift_lube_cleanup(&fine);
    rd_film_track_free(&tr);
    rd_film_free(&f);
    return rc;
}

void rd_lift_lube_cleanup(rd_lift_lube *lb)
{
    free(lb->min_film_angle_deg);
    free(lb->min_film);
    free(lb->regime);
    free(lb->friction_work);
    memset(lb, 0, sizeof *lb);
}
