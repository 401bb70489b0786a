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
 * edge).  A tilting piston's own sliding is left out of U.
 *
 * The film is axisymmetric (one film for the whole face): the lift's
 * round bore.  A distorted bore (the film varying around the ring) is
 * refused with the lubricated model (rd_lift.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_film_track.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

typedef struct film_scene {
    const rd_lift_params *p;
    double omega, w_el, back;
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
    *eta = rd_lift_lube_viscosity(&p->friction.lube, deg);
    *W = fs->w_el;
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

int rd_lift_film_run_at(const rd_ring_params *rp, const rd_lift_params *p, int fine, rd_film *film,
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
    film_scene fs = {.p = p, .omega = rd_engine_omega(&p->engine)};
    fs.w_el = 2.0 * rp->tangential_force / rp->diameter;
    fs.back = s.back.height * s.back.r / s.run.r;
    rd_film_loads ld = {loads_at, &fs};
    double cycle = 4.0 * M_PI / fs.omega, dt = p->film_step_deg / fine * M_PI / 180.0 / fs.omega;
    return rd_film_track_run(film, &ld, p->engine.cycles * cycle, dt, cycle, cycle, NAN, tr, err);
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
    return rc;
}

int rd_lift_lube_fill(rd_lift_lube *lb, const rd_film *film, const rd_film_track *tr,
                      const rd_lube_params *l, const rd_engine_params *e, double diameter,
                      const double *crank_deg, int S, double t_first, int C, rd_error *err)
{
    size_t n = (size_t)(S > 0 ? S : 1);
    lb->on = 1;
    lb->min_film = malloc(5 * n * sizeof(double));
    lb->regime = malloc(n * sizeof(int));
    lb->friction_work = calloc((size_t)(2 * (C > 0 ? C : 1)), sizeof(double));
    if (!lb->min_film || !lb->regime || !lb->friction_work)
        return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the lubrication block).");
    lb->hydrodynamic_friction = lb->min_film + n;
    lb->asperity_friction = lb->min_film + 2 * n;
    lb->power = lb->min_film + 3 * n;
    lb->asperity_share = lb->min_film + 4 * n;
    lb->fmep = lb->friction_work + (C > 0 ? C : 1);
    lb->cycles = C;
    lb->film_error = lb->work_error = NAN;
    double omega = rd_engine_omega(e), circ = M_PI * diameter;
    double ureg = rd_liner_ureg(e), mu_b = l->boundary_coefficient;
    for (int k = 0; k < S; k++) {
        rd_film_point pt;
        double t = t_first + crank_deg[k] * M_PI / 180.0 / omega;
        rd_film_track_at(tr, t, &pt);
        rd_engine_piston(e, omega * t, NULL, &pt.U, NULL); /* exact, as the motion's friction */
        double h, a, load = pt.W + pt.Wa;
        friction_of(&pt, circ, mu_b, ureg, &h, &a);
        lb->min_film[k] = pt.h0;
        lb->hydrodynamic_friction[k] = h;
        lb->asperity_friction[k] = a;
        lb->power[k] = (h + a) * pt.U;
        lb->asperity_share[k] = load > 0.0 ? pt.Wa / load : 0.0;
        lb->regime[k] = lb->asperity_share[k] > RD_LUBE_BOUNDARY_SHARE ? RD_REGIME_BOUNDARY
                        : lb->asperity_share[k] > RD_LUBE_MIXED_SHARE  ? RD_REGIME_MIXED
                                                                       : RD_REGIME_HYDRODYNAMIC;
    }
    /* per cycle: the power over the film's own steps (trapezoid; they land on
     * the cycles' ends) */
    double cycle = 4.0 * M_PI / omega, stroke = 2.0 * e->crank_radius,
           Vd = 0.25 * M_PI * diameter * diameter * stroke;
    for (int c = 0; c < C; c++) {
        double w = 0.0, t0 = t_first + c * cycle;
        for (int k = 0; k < tr->steps; k++) {
            const rd_film_point *a = &tr->pt[k], *b = &tr->pt[k + 1];
            double mid = 0.5 * (a->t + b->t), h0, a0, h1, a1;
            if (mid < t0 || mid > t0 + cycle)
                continue;
            friction_of(a, circ, mu_b, ureg, &h0, &a0);
            friction_of(b, circ, mu_b, ureg, &h1, &a1);
            w += 0.5 * (b->t - a->t) * ((h0 + a0) * a->U + (h1 + a1) * b->U);
        }
        lb->friction_work[c] = w;
        lb->fmep[c] = w / Vd;
    }
    lb->min_film_x = film->x_min;
    lb->composite_sigma = film->sigma;
    lb->viscosity_min = INFINITY;
    lb->viscosity_max = 0.0;
    for (double d = 0.0; d <= 720.0; d += 1.0) {
        double v = rd_lift_lube_viscosity(l, d);
        lb->viscosity_min = fmin(lb->viscosity_min, v);
        lb->viscosity_max = fmax(lb->viscosity_max, v);
    }
    lb->periodic_change = tr->periodic_change;
    lb->film_solves = tr->solves;
    lb->held = tr->held;
    return RD_OK;
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
    free(lb->min_film);
    free(lb->regime);
    free(lb->friction_work);
    memset(lb, 0, sizeof *lb);
}
