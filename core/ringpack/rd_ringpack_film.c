/*
 * rd_ringpack_film.c — the lubricated friction model on the pack's rings
 * (physics.friction.model lubricated; rd_ringpack.h): each ring's oil film
 * (core/liner rd_film_track.h, the lift analysis' film: one rigid face, its
 * radial balance with the squeeze film in time), coupled with the gas
 * network a cycle at a time.
 *
 * The film of ring i feels the piston's sliding speed, the oil's viscosity
 * at the crank angle, the radial load 2 F_t / D + (p_groove - p_cc) h_back
 * r_back / r_run and, at its edges, the lands' gas (below and above the
 * ring, gauge against the crankcase), as the lift analysis' film does with
 * its tables (rd_lift_film.c).  Those pressures are the network's, which
 * the rings' motion (and so the friction) decides.  The coupling is lagged
 * by one cycle: during cycle c each ring rubs on the film integrated, at
 * the end of cycle c - 1, over the pressures that cycle recorded at its
 * output samples (linear between them); the first cycle's film has no gas
 * (the volumes start at the crankcase pressure) and a cycle of warm-up.
 * Each cycle's film starts where the one before ended, so h0 is continuous.
 * As the pack settles to its periodic state the pressures of two cycles
 * agree and so does the film with the pressures it rubs under; film_lag
 * (the result) measures what is left: the last cycle's film against a film
 * integrated over the last cycle's own pressures from the same start.
 *
 * The friction is the film's (rd_liner_law.h, lubricated): the axial and
 * pinned rings' in rd_ringpack_friction, the lift rings' through their
 * lift parameters' film (rd_packring_film).  A film track holds pack time:
 * its points are shifted to the cycle they serve.
 *
 * In a distorted bore, on a bore map or on a moving piston tilt a ring has
 * a film per segment load and sliding speed instead (segment_films, the
 * lift analysis' rd_lift_films_*), each coupled as above; lift rings read
 * their segments' (rd_packring_films), axial and pinned rings the films'
 * share-weighted sum (rd_ringpack_film_at).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_film_track.h"
#include "rd_gasflow.h"
#include "rd_lift_internal.h"
#include "rd_ringpack_model.h"

/* Enters ring i's face block, /rings/i/ring/face; returns the mark to leave. */
static size_t enter_face(rd_error *err, int i)
{
    char at[16];
    snprintf(at, sizeof at, "/rings/%d", i % 10);
    size_t m = rd_error_enter(err, at);
    rd_error_enter(err, "/ring");
    rd_error_enter(err, "/face");
    return m;
}

/* The film's step, at the scene's root (a distorted bore, a bore map or a
 * moving tilt: a film per segment load and sliding speed). */
static int lube_scene_validate(const rd_ringpack_params *p, rd_error *err)
{
    int rc = rd_error_range_in("/numerics", p->film_step_deg, 0.01, RD_LIFT_FILM_STEP_MAX_DEG,
                               "/film_step_deg", "deg", err);
    size_t m = rd_error_enter(err, "/bore");
    rd_error_leave(err, m);
    return rc;
}

/* The lubricated model's inputs: each ring's face under /rings/i/ring/face
 * (the liner and the oil, shared, with the first ring's), and the round
 * bore its one film per ring needs. */
int rd_ringpack_lube_validate(const rd_ringpack_params *p, rd_error *err)
{
    if (p->friction.model != RD_FRICTION_LUBRICATED)
        return RD_OK;
    int rc = lube_scene_validate(p, err);
    for (int i = 0; !rc && i < p->n_rings; i++) {
        rd_section s;
        rd_section_init(&s, &p->rings[i].ring);
        size_t m = enter_face(err, i);
        rc = rd_face_validate(&p->rings[i].face, err);
        rd_error_leave(err, m);
        if (!rc && i == 0)
            rc = rd_lube_validate(&p->friction.lube, p->bore.roughness_rq, err);
        m = enter_face(err, i);
        if (!rc) /* the face on its ring's running face (a table's ends, ...) */
            rc = rd_film_face_validate(&p->rings[i].face, s.run.height, err);
        rd_error_leave(err, m);
    }
    return rc;
}

/* rd_film_init of ring i's face, its paths under /rings/i/ring/face. */
static int film_init(const rd_ringpack_params *p, int i, rd_film *film, int nodes, rd_error *err)
{
    const rd_ring_params *rp = &p->rings[i].ring;
    rd_section s;
    rd_section_init(&s, rp);
    size_t m = enter_face(err, i);
    int rc = rd_film_init(film, &p->rings[i].face, s.run.height, nodes, p->bore.roughness_rq,
                          &p->friction.lube, rp->youngs_modulus, rp->poisson_ratio, err);
    rd_error_leave(err, m);
    return rc;
}

void rd_ringpack_around(const rd_ringpack_model *m, int i, double t, const double *pv,
                        double out[3])
{
    const rd_gas_params *g = m->p->face_tables;
    double cc = m->p->crankcase_pa;
    if (g) { /* the test hook: the lift analysis' gauge tables */
        double deg = t * m->omega * 180.0 / M_PI;
        out[0] = rd_gasflow_table(g->points, g->crank_deg, g->above, deg);
        out[1] = rd_gasflow_table(g->points, g->crank_deg, g->behind, deg);
        out[2] = rd_gasflow_table(g->points, g->crank_deg, g->below, deg);
        return;
    }
    out[0] = pv[2 * i + 1] - cc;
    out[1] = pv[2 * i + 2] - cc;
    out[2] = pv[rp_below(m, i)] - cc;
}

struct rd_packfilm {
    rd_film film;
    rd_film_track tr;   /* the film of the cycle running (pack time) */
    rd_lift_films fs;   /* a distorted bore (fs.count > 0): a film per segment load instead */
    double *gas;        /* 3 x (S + 1): above, behind, below (gauge, Pa) at the cycle's samples */
    double w_el, back;  /* N/m: the elastic line load now (loads_at); the back face's share */
    double w_ring;      /* N/m: the ring's 2 F_t / D */
    double lever;       /* m: the film's arm about the pin now (loads_at's; 0: none) */
    const double *row;  /* a map: the film's loads over the depths now (loads_at's; NULL: w_el) */
    rd_lift_params lp;  /* the films' scene (fs.p: the ring's depth at t on a map) */
    rd_bore_map map;    /* a map in the ring's frame */
    double period, dt;  /* s: a cycle, the film's largest step */
    const double *load; /* the samples the loads read (gas, or NULL: no gas) */
    const rd_ringpack_params *p;
    int S;
};

/* f's films: one, or a distorted bore's (fs). */
static int films_n(const rd_packfilm *f)
{
    return f->fs.count > 0 ? f->fs.count : 1;
}

static rd_film *film_g(rd_packfilm *f, int g)
{
    return f->fs.count > 0 ? &f->fs.film[g] : &f->film;
}

static rd_film_track *tr_g(rd_packfilm *f, int g)
{
    return f->fs.count > 0 ? &f->fs.tr[g] : &f->tr;
}

/* Film g's elastic line load into f->w_el (loads_at's). */
static void load_g(rd_packfilm *f, int g)
{
    f->w_el = f->fs.count > 0 ? f->fs.load[g] : f->w_ring;
    f->lever = f->fs.count > 0 && f->fs.lever ? f->fs.lever[f->fs.follows[g]] : 0.0;
    f->row = f->fs.count > 0 && f->fs.exact && f->fs.depths > 1
                 ? f->fs.seg_load + (size_t)f->fs.depths * f->fs.follows[g]
                 : NULL;
}

static void loads_at(void *ctx, double t, double *U, double *eta, double *W, double *plo,
                     double *phi)
{
    const rd_packfilm *f = ctx;
    double omega = 4.0 * M_PI / f->period, v, x = t / f->period * f->S;
    rd_engine_piston(&f->p->engine, omega * t, NULL, &v, NULL);
    *U = v;
    if (f->lever != 0.0) { /* a tilting piston's groove: beta' x (rd_lift_film.c) */
        double b, b1, b2;
        rd_engine_tilt_at(&f->p->engine, t / f->period * 720.0, &b, &b1, &b2);
        *U += b1 * omega * f->lever;
    }
    *eta = rd_lift_lube_viscosity(&f->p->friction.lube, t / f->period * 720.0);
    *W = f->row ? rd_lift_depth_interp(f->fs.z, f->row, f->fs.depths, rd_lift_depth_at(&f->lp, t))
                : f->w_el;
    *plo = *phi = 0.0;
    if (!f->load)
        return;
    int k = (int)floor(x), n = f->S + 1;
    k = k < 0 ? 0 : k >= f->S ? f->S - 1 : k;
    double w = fmin(fmax(x - k, 0.0), 1.0);
    const double *g = f->load;
#define AT(row) (g[(row)*n + k] + w * (g[(row)*n + k + 1] - g[(row)*n + k]))
    *phi = AT(0);
    *W += f->back * AT(1);
    *plo = AT(2);
#undef AT
}

/* The film `film` over one cycle from h_start (NAN: the balance after a
 * cycle of warm-up) under f->load, steps at most dt (s), its points moved
 * to start at t0 (s). */
static int cycle_film_on(rd_packfilm *f, rd_film *film, double dt, double h_start, double t0,
                         rd_film_track *tr, rd_error *err)
{
    rd_film_loads ld = {loads_at, f};
    int rc = rd_film_track_run(film, &ld, f->period, dt, f->period,
                               isnan(h_start) ? f->period : 0.0, h_start, tr, err);
    for (int k = 0; !rc && k <= tr->steps; k++)
        tr->pt[k].t += t0;
    return rc;
}

static int cycle_film(rd_packfilm *f, double h_start, double t0, rd_film_track *tr, rd_error *err)
{
    return cycle_film_on(f, &f->film, f->dt, h_start, t0, tr, err);
}

/* The lubrication block of f's films (each track's first point at t0)
 * over ring i's samples into lb: one film, or a distorted bore's by their
 * shares. */
static int fill_block(rd_packfilm *f, int i, rd_film *film, rd_film_track *tr,
                      const rd_ringpack_result *r, rd_lift_lube *lb, rd_error *err)
{
    const rd_ringpack_params *p = f->p;
    double d = p->rings[i].ring.diameter, t0 = tr[0].pt[0].t;
    if (f->fs.count == 0)
        return rd_lift_lube_fill(lb, film, tr, &p->friction.lube, &p->engine, d, r->crank_deg,
                                 r->samples, t0, 1, err);
    rd_lube_films set = rd_lift_films_view(&f->fs);
    set.film = film;
    set.tr = tr;
    return rd_lift_lube_fill_films(lb, &set, &p->friction.lube, &p->engine, d, r->crank_deg,
                                   r->samples, t0, 1, err);
}

/* Ring i's film error estimate (rd_lift_lube): the last cycle's films again
 * from the same start on a grid twice as fine (points, steps, local error
 * / 4), its block against the reported one. */
static int film_estimate(rd_packfilm *f, int i, rd_ringpack_result *r, rd_error *err)
{
    int G = films_n(f), rc = RD_OK;
    rd_film *fine = calloc((size_t)G, sizeof *fine);
    rd_film_track *tr = calloc((size_t)G, sizeof *tr);
    rd_lift_lube lb = {0};
    if (!fine || !tr)
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's film estimate.", i + 1);
    f->load = f->gas;
    for (int g = 0; rc == RD_OK && g < G; g++) {
        const rd_film_track *t = tr_g(f, g);
        rc = film_init(f->p, i, &fine[g], 2 * (RD_FILM_NODES - 1) + 1, err);
        fine[g].rtol /= 4.0;
        load_g(f, g);
        rc =
            rc ? rc : cycle_film_on(f, &fine[g], 0.5 * f->dt, t->pt[0].h0, t->pt[0].t, &tr[g], err);
    }
    rc = rc ? rc : fill_block(f, i, fine, tr, r, &lb, err);
    if (!rc)
        rd_lift_lube_compare(&r->lube[i], &lb, r->samples);
    rd_lift_lube_cleanup(&lb);
    for (int g = 0; tr && fine && g < G; g++) {
        rd_film_track_free(&tr[g]);
        rd_film_free(&fine[g]);
    }
    free(tr);
    free(fine);
    return rc;
}

/* The films of ring i in a distorted bore, on a bore map or on a moving
 * tilt (rd_lift_films_bore on the scene turned into the ring's frame): its
 * segments' loads (the bore's phases from its gap; a map's at its own
 * depth; round: 2 F_t / D) and arms about the pin axis (in the scene's frame: R cos
 * theta, negated for a gap on the far side, 180 deg), the films on them
 * (rd_lift_films_run: a film per distinct load and arm, or interpolated
 * between films at 3 to 17 loads, chosen on the films of one cycle
 * without gas) into f->fs; each film's track then f's first cycle. */
static int segment_films(rd_ringpack_model *m, int i, rd_packfilm *f, rd_error *err)
{
    const rd_ringpack_params *p = m->p;
    const rd_ringpack_ring *pr = &p->rings[i];
    rd_lift_params *lp = &f->lp;
    rd_lift_params_default(lp);
    lp->engine = p->engine;
    lp->engine.cycles = 1.0;
    lp->friction = p->friction;
    lp->face = pr->face;
    lp->film_step_deg = p->film_step_deg;
    lp->bore = p->bore;
    rd_bore *turn[RD_BORE_LAYERS_MAX + 1] = {&lp->bore};
    int nb = 1;
    if (p->bore_map) { /* the map in the ring's frame, at its own depth (rd_ringpack_lift.c) */
        f->map = *p->bore_map;
        lp->bore_map = &f->map;
        lp->ring_z_tdc = rd_ringpack_ring_depth(p, i);
        for (int j = 0; j < f->map.n_layers; j++)
            turn[nb++] = &f->map.layer[j].bore;
    }
    for (int b = 0; b < nb; b++)
        for (int k = 0; k < turn[b]->n_distortion; k++) {
            double a = fmod(turn[b]->distortion[k].phase_deg - pr->gap_angle_deg, 360.0);
            turn[b]->distortion[k].phase_deg = a < 0.0 ? a + 360.0 : a;
        }
    int n = pr->segments, tilt = p->engine.tilt_points > 1;
    rd_ring *ring = rd_ring_create(&pr->ring, n, 0, err);
    rd_lift_films_free(&f->fs);
    int rc = !ring ? (err ? err->code : RD_ENOMEM)
                   : rd_lift_films_bore(ring, lp, NULL, &f->fs, err); /* loads, arms, films */
    if (rc == RD_OK && tilt && fabs(fabs(fmod(pr->gap_angle_deg, 360.0)) - 180.0) < 1e-6)
        for (int j = 0; f->fs.lever && j < f->fs.m; j++) /* a gap at 180 deg: the arms negated */
            f->fs.lever[j] = -f->fs.lever[j];
    rd_ring_free(ring);
    f->load = NULL;
    for (int g = 0; rc == RD_OK && g < f->fs.count; g++) {
        rd_film_track tr = {0};
        load_g(f, g);
        rc = cycle_film_on(f, &f->fs.film[g], f->dt, NAN, 0.0, &tr, err); /* no gas yet */
        rd_film_track_free(&f->fs.tr[g]);
        f->fs.tr[g] = tr;
    }
    return rc;
}

int rd_ringpack_films_open(rd_ringpack_model *m, int S, rd_error *err)
{
    const rd_ringpack_params *p = m->p;
    if (p->friction.model != RD_FRICTION_LUBRICATED)
        return RD_OK;
    for (int i = 0; i < m->R; i++) {
        const rd_ring_params *rp = &p->rings[i].ring;
        rd_packfilm *f = calloc(1, sizeof *f);
        if (!f || !(f->gas = calloc(3 * ((size_t)S + 1), sizeof *f->gas))) {
            free(f);
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's oil film.", i + 1);
        }
        m->film[i] = f;
        f->p = p;
        f->S = S;
        f->period = 4.0 * M_PI / m->omega;
        f->dt = p->film_step_deg * M_PI / 180.0 / m->omega;
        rd_section s;
        rd_section_init(&s, rp);
        f->w_el = f->w_ring = 2.0 * rp->tangential_force / rp->diameter;
        f->back = s.back.height * s.back.r / s.run.r;
        int rc =
            rd_bore_distorted(&p->bore, rp->diameter) || p->bore_map || p->engine.tilt_points > 1
                ? segment_films(m, i, f, err)
                : film_init(p, i, &f->film, RD_FILM_NODES, err);
        if (!rc && f->fs.count == 0)
            rc = cycle_film(f, NAN, 0.0, &f->tr, err); /* no gas yet */
        if (rc)
            return rc;
        if (m->lr[i] && f->fs.count > 1 && (rc = rd_packring_films(m->lr[i], &f->fs, err)))
            return rc;
        if (m->lr[i] && f->fs.count <= 1)
            rd_packring_film(m->lr[i], tr_g(f, 0));
    }
    return RD_OK;
}

void rd_ringpack_films_sample(rd_ringpack_model *m, int k, double t, const double *pv)
{
    for (int i = 0; i < m->R; i++) {
        rd_packfilm *f = m->film[i];
        if (!f)
            continue;
        double g[3];
        rd_ringpack_around(m, i, t, pv, g);
        for (int r = 0; r < 3; r++)
            f->gas[(size_t)r * (f->S + 1) + k] = g[r];
    }
}

int rd_ringpack_films_cycle(rd_ringpack_model *m, int next, rd_error *err)
{
    for (int i = 0; i < m->R; i++) {
        rd_packfilm *f = m->film[i];
        if (!f)
            continue;
        f->load = f->gas;
        for (int g = 0; g < films_n(f); g++) {
            rd_film_track tr, *cur = tr_g(f, g);
            load_g(f, g);
            int rc = cycle_film_on(f, film_g(f, g), f->dt, cur->pt[cur->steps].h0, next * f->period,
                                   &tr, err);
            if (rc) {
                rd_film_track_free(&tr);
                return rc;
            }
            rd_film_track_free(cur);
            *cur = tr; /* in place: the lift ring keeps its address */
        }
        for (int r = 0; r < 3; r++) /* this cycle's end starts the next */
            f->gas[(size_t)r * (f->S + 1)] = f->gas[(size_t)r * (f->S + 1) + f->S];
    }
    return RD_OK;
}

void rd_ringpack_film_at(const rd_ringpack_model *m, int i, double t, rd_film_point *pt)
{
    const rd_packfilm *f = m->film[i];
    if (f->fs.count == 0) {
        rd_film_track_at(&f->tr, t, pt);
        return;
    }
    *pt = (rd_film_point){0}; /* the ring's: the films by their shares (linear in them) */
    for (int g = 0; g < f->fs.count; g++) {
        rd_film_point q;
        double w = f->fs.share[g];
        rd_film_track_at(&f->fs.tr[g], t, &q);
        pt->t = q.t;
        pt->U = q.U;
        pt->h0 += w * q.h0;
        pt->W += w * q.W;
        pt->Wa += w * q.Wa;
        pt->Cc += w * q.Cc;
        pt->Fp += w * q.Fp;
        pt->cavitated += w * q.cavitated;
    }
}

/* Ring i's film_lag (rd_ringpack.h): each film over the last cycle's own
 * pressures from the same start, against the film the cycle used; the
 * largest. */
static int film_lag(rd_packfilm *f, double *lag, rd_error *err)
{
    int rc = RD_OK;
    *lag = 0.0;
    f->load = f->gas;
    for (int g = 0; rc == RD_OK && g < films_n(f); g++) {
        rd_film_track chk;
        const rd_film_track *tr = tr_g(f, g);
        load_g(f, g);
        rc = cycle_film_on(f, film_g(f, g), f->dt, tr->pt[0].h0, tr->pt[0].t, &chk, err);
        for (int k = 0; !rc && k <= tr->steps; k++) {
            rd_film_point a;
            rd_film_track_at(&chk, tr->pt[k].t, &a);
            *lag = fmax(*lag, fabs(tr->pt[k].h0 - a.h0) / fmax(a.h0, film_g(f, g)->sigma));
        }
        rd_film_track_free(&chk);
    }
    return rc;
}

int rd_ringpack_films_result(rd_ringpack_model *m, rd_ringpack_result *r, rd_error *err)
{
    for (int i = 0; i < m->R; i++) {
        rd_packfilm *f = m->film[i];
        if (!f)
            continue;
        const rd_ringpack_params *p = m->p;
        rd_lift_lube *lb = &r->lube[i];
        int rc = fill_block(f, i, film_g(f, 0), tr_g(f, 0), r, lb, err);
        lb->film_step_deg = p->film_step_deg;
        lb->load_min = lb->load_max = f->w_ring;
        for (int j = 0; f->fs.count > 0 && j < f->fs.m * f->fs.depths; j++) {
            lb->load_min = j ? fmin(lb->load_min, f->fs.seg_load[j]) : f->fs.seg_load[j];
            lb->load_max = j ? fmax(lb->load_max, f->fs.seg_load[j]) : f->fs.seg_load[j];
        }
        lb->interp_check = f->fs.count > 0 ? f->fs.interp_check : NAN;
        if (f->fs.count > 0) {
            lb->load_depths = f->fs.depths;
            lb->load_depth_error = f->fs.depth_check;
        }
        if (rc || (rc = film_lag(f, &r->film_lag[i], err)) ||
            (p->estimate_error && (rc = film_estimate(f, i, r, err))))
            return rc;
    }
    return RD_OK;
}

void rd_ringpack_films_close(rd_ringpack_model *m)
{
    for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++) {
        rd_packfilm *f = m->film[i];
        if (!f)
            continue;
        rd_film_track_free(&f->tr);
        rd_film_free(&f->film);
        rd_lift_films_free(&f->fs);
        free(f->gas);
        free(f);
        m->film[i] = NULL;
    }
}
