/*
 * rd_ringpack_lift.c — a ring of the pack on one of the lift analysis'
 * models (numerics.model rigid, full or modal; rd_lift_model.h), coupled
 * both ways with the pack's gas network (rd_ringpack.h).
 *
 * The ring is the lift analysis' own: its rd_ring of n segments, its
 * rd_lift_model (geometry, mass, stiffness, force elements) and its form
 * (rd_lift_rigid_open, rd_lift_modal_open or the full model), built from a
 * rd_lift_params that carries the pack's engine, groove, gravity and
 * friction, all made once per job (rd_packring_create: the pack's handle
 * keeps them across its runs and accuracy levels, whose parameters differ
 * only in what the model does not read: cycles, tolerances).  Its states
 * are appended to the pack's (rd_ringpack_model.h) and its right-hand side
 * is the form's, called on them.
 *
 * Gas: the lift model's gas tables are replaced by the pack's pressures of
 * the moment (rd_lift_model.gas_now), gauge against the crankcase like the
 * lift analysis' tables: above = land_i, behind = groove_i, below = the
 * volume under the ring, each minus p_cc.  The axial load depends only on
 * differences, so the reference matters only for the back face's radial
 * push (and through it the friction's normal force), which the pack's axial
 * ring also takes as p_groove - p_cc.  The lift model's default contact
 * stiffness and velocity tolerances read the largest table pressure; the
 * lift parameters carry a two-point table holding the cylinder's peak
 * (gauge) on the top face for that rule only (gas_now overrides it in the
 * forces).
 *
 * Flank passages: from the per-segment lifts L_j (rd_lift_form.lift),
 *   A_upper = pi d / n sum_j clamp(a - L_j, 0, a),
 *   A_lower = pi d / n sum_j clamp(L_j, 0, a),
 * each segment's share of the circumference open by its own gap, so a ring
 * lifted on one side leaks there (the rigid model's L_j are all equal: the
 * axial ring's pi d (a - z), pi d z).  The clamp drops the contact
 * penalty's penetration (1e-3 a) from the seated ring's passage.
 *
 * Events: the lift analysis' definitions and state machine
 * (rd_lift_track_roots, its five roots on the mean lift and the load), at
 * the pack's flank_band (the model's eps is the band's edge).
 *
 * The scene's bore, tilt and active areas (rd_ringpack.h), in the ring's
 * frame (angles from its gap middle, as the lift analysis'):
 *  - the bore r_b = D/2 + sum A_k cos(k (theta_b - phi_k)), theta_b from the
 *    bore's angle 0; ring i's gap middle at g_i = gap_angle_deg, so in its
 *    frame theta = theta_b - g_i and phi_k' = phi_k - g_i (mod 360, exact: k
 *    is whole).  A distorted bore starts the ring from its static
 *    equilibrium in it (rd_lift_bore_static), as the lift analysis does;
 *  - the tilt beta about the pin axis at 90 deg from angle 0: the lift
 *    models tilt about the axis at 90 deg from the gap, so a ring's gap must
 *    sit on the tilt plane, g_i = 0 (beta' = beta) or 180 (beta' = -beta,
 *    its gap's side goes down); other angles are refused (rd_packring_validate);
 *  - active_area: the lift model's own (fixed, or dynamic: a face sealing
 *    on a flank sees the mean of the groove's pressure and its own side's);
 *  - a bore map (rd_ringpack_params.bore_map): a copy per ring with every
 *    layer's phases turned as the bore's, met at the ring's own depth
 *    (rd_ringpack_ring_depth) as the lift analysis' ring meets its map.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "rd_ringpack_model.h"

/* What a job keeps (rd_packring_create: the parameters, ring, model and
 * form, the bore start) and what one run adds (rd_packring_open: the views,
 * the flank tracker, the events, the Newton solver; the gas and the film
 * of the moment). */
struct rd_packring {
    int kind, modes; /* its model (enum rd_lift_model_kind), a modal one's elastic modes */
    rd_ring *ring;
    rd_lift_params lp;
    double tab_deg[2], tab_top[2], tab_zero[2]; /* the stiffness rule's table */
    double *tilt;                               /* the tilt table negated (gap at 180), owned */
    double *y0;                                 /* a distorted bore's start (12 n), owned */
    rd_lift_model m;
    rd_lift_form form;
    double gas[3];
    double *seg, *seg_w, *seg_0; /* n per-segment lifts (at y, along w, at 0: once) */
    double *zero;                /* the zero state */
    N_Vector ys, yd;             /* views on the ring's part of the pack's vectors */
    double circ;                 /* pi d */
    rd_lift_flank_track track;
    rd_lift_pass events;
    rd_bore_map map; /* a bore map in the ring's frame (its gap at angle 0) */
    /* its Newton solver: the second-order one (rd_lift_newton.c) for a form
     * with blocks, else CVODE's dense or band LU of I - gamma J from the
     * form's Jacobian, as the lift driver picks (rd_lift_driver.c) */
    SUNLinearSolver LS;
    SUNMatrix S, J; /* S: the second-order solver's (owned by LS); J: owned */
    rd_lift_newton *nw;
    N_Vector x, b, t1, t2, t3; /* views (x, b) and the Jacobian's scratch */
};

/* x mod 360 into (-180, 180]. */
static double wrap_deg(double x)
{
    double r = fmod(x, 360.0);
    return r > 180.0 ? r - 360.0 : r <= -180.0 ? r + 360.0 : r;
}

/* 1 if ring i's gap sits on the tilt plane's far side (180 deg). */
static int gap_opposite(const rd_ringpack_ring *r)
{
    return fabs(fabs(wrap_deg(r->gap_angle_deg)) - 180.0) < 1e-6;
}

/* The scene's bore and tilt as ring i sees them (file comment) into lp;
 * the negated tilt table, when needed, into *neg (owned by the caller). */
static int ring_frame(const rd_ringpack_params *p, int i, rd_lift_params *lp, double **neg)
{
    const rd_ringpack_ring *r = &p->rings[i];
    lp->engine = p->engine;
    lp->bore = p->bore;
    for (int k = 0; k < lp->bore.n_distortion && k < RD_BORE_ORDERS_MAX; k++)
        lp->bore.distortion[k].phase_deg =
            wrap_deg(p->bore.distortion[k].phase_deg - r->gap_angle_deg);
    lp->gas.active_area =
        p->flank_pressure == RD_FLANK_PRESSURE_LINEAR ? RD_GAS_AREA_LINEAR : p->active_area;
    if (!rd_engine_tilted(&p->engine) || !gap_opposite(r))
        return 0;
    lp->engine.piston_tilt_deg = -p->engine.piston_tilt_deg;
    int n = p->engine.tilt_points;
    if (n <= 0 || !neg)
        return 0;
    if (!(*neg = malloc((size_t)n * sizeof **neg)))
        return -1;
    for (int k = 0; k < n; k++)
        (*neg)[k] = -p->engine.tilt_deg[k];
    lp->engine.tilt_deg = *neg;
    return 0;
}

/* The lift parameters of pack ring i. */
static int lift_params(const rd_ringpack_model *m, int i, rd_packring *L)
{
    const rd_ringpack_params *p = m->p;
    rd_lift_params *lp = &L->lp;
    rd_lift_params_default(lp);
    lp->groove = p->rings[i].groove;
    lp->gravity = p->gravity;
    lp->friction = p->friction;
    lp->face = p->rings[i].face;
    lp->film_step_deg = p->film_step_deg;
    lp->rtol = p->rtol;
    lp->atol = p->atol;
    lp->max_steps = p->max_steps;
    lp->estimate_error = 0;
    lp->flank_band = p->flank_band; /* the pack's dating (rd_ringpack.h) */
    lp->model = m->kind[i];
    lp->modes = p->rings[i].modes;
    double peak = 0.0;
    for (int k = 0; k < m->cyl_n; k++)
        peak = fmax(peak, m->cyl_pa[k] - p->crankcase_pa);
    L->tab_deg[0] = 0.0;
    L->tab_deg[1] = 720.0;
    L->tab_top[0] = L->tab_top[1] = peak;
    L->tab_zero[0] = L->tab_zero[1] = 0.0;
    lp->gas = (rd_gas_params){2, L->tab_deg, L->tab_top, L->tab_zero, L->tab_zero, p->active_area};
    if (p->bore_map) { /* the map in the ring's frame, at the ring's own depth */
        L->map = *p->bore_map;
        for (int j = 0; j < L->map.n_layers; j++) {
            rd_bore *b = &L->map.layer[j].bore;
            for (int k = 0; k < b->n_distortion && k < RD_BORE_ORDERS_MAX; k++)
                b->distortion[k].phase_deg =
                    wrap_deg(b->distortion[k].phase_deg - p->rings[i].gap_angle_deg);
        }
        lp->bore_map = &L->map;
        lp->ring_z_tdc = rd_ringpack_ring_depth(p, i);
    }
    return ring_frame(p, i, lp, &L->tilt);
}

const char *rd_ringpack_model_name(int model)
{
    return model == RD_RINGPACK_AXIAL ? "axial" : rd_lift_model_name(model);
}

int rd_packring_create(const rd_ringpack_model *m, int i, rd_packring **out, rd_error *err)
{
    const rd_ringpack_ring *pr = &m->p->rings[i];
    int n = pr->segments, rc;
    rd_packring *L = calloc(1, sizeof *L);
    *out = NULL;
    if (!L)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's lift model.", i + 1);
    L->kind = m->kind[i];
    L->modes = pr->modes ? pr->modes : (12 < 6 * n - 6 ? 12 : 6 * n - 6);
    rc = lift_params(m, i, L)
             ? rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's lift model.", i + 1)
             : RD_OK;
    rc = rc ? rc : rd_lift_validate(&L->lp, &pr->ring, n, err);
    if (!rc && !(L->ring = rd_ring_create(&pr->ring, n, 0, err)))
        rc = err ? err->code : RD_ENOMEM;
    rc = rc ? rc : rd_lift_model_init(&L->m, L->ring, &L->lp, NULL, err);
    rc = rc ? rc : rd_lift_form_open(&L->m, L->kind, L->modes, &L->form, err);
    if (rc == RD_OK) {
        L->m.gas_now = L->gas;
        L->circ = M_PI * pr->ring.diameter;
        L->seg = malloc(3 * (size_t)n * sizeof *L->seg);
        L->zero = calloc((size_t)L->form.N, sizeof *L->zero);
        L->seg_w = L->seg ? L->seg + n : NULL;
        L->seg_0 = L->seg ? L->seg + 2 * n : NULL;
        if (!L->seg || !L->zero)
            rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's lift model.", i + 1);
        else
            L->form.lift(L->form.user, L->zero, L->seg_0);
    }
    if (rc) {
        rd_packring_free(L);
        return rc;
    }
    *out = L;
    return RD_OK;
}

int rd_packring_open(rd_ringpack_model *m, int i, rd_packring *L, SUNContext ctx, int *N,
                     int *modes, double *k, rd_error *err)
{
    m->lr[i] = L;
    memset(L->gas, 0, sizeof L->gas);
    L->m.kin_t = NAN; /* as a model just made */
    L->ys = N_VMake_Serial(L->form.N, NULL, ctx);
    L->yd = N_VMake_Serial(L->form.N, NULL, ctx);
    if (!L->ys || !L->yd)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for ring %d's lift model.", i + 1);
    L->track = rd_lift_track_seated(L->m.banded, 0.0, NAN);
    *N = (int)L->form.N;
    *modes = L->modes;
    *k = L->m.k;
    return RD_OK;
}

void rd_packring_film(rd_packring *L, const rd_film_track *tr)
{
    L->lp.film = tr;
    L->lp.films = NULL;
}

int rd_packring_films(rd_packring *L, const rd_lift_films *fs, rd_error *err)
{
    L->lp.film = NULL;
    L->lp.films = fs;
    return rd_lift_model_films(&L->m, err);
}

void rd_packring_close(rd_packring *L)
{
    if (!L)
        return;
    if (L->LS)
        SUNLinSolFree(L->LS);
    if (L->J)
        SUNMatDestroy(L->J);
    N_Vector v[] = {L->ys, L->yd, L->x, L->b, L->t1, L->t2, L->t3};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (v[k])
            N_VDestroy(v[k]);
    free(L->events.events);
    L->LS = NULL;
    L->S = L->J = NULL;
    L->nw = NULL;
    L->ys = L->yd = L->x = L->b = L->t1 = L->t2 = L->t3 = NULL;
    L->events = (rd_lift_pass){0};
    L->lp.film = NULL; /* the run's film (rd_packring_film) or films */
    L->lp.films = NULL;
}

void rd_packring_free(rd_packring *L)
{
    if (!L)
        return;
    rd_packring_close(L);
    if (L->form.close)
        L->form.close(&L->form);
    rd_lift_model_cleanup(&L->m);
    rd_ring_free(L->ring);
    free(L->seg);
    free(L->zero);
    free(L->tilt);
    free(L->y0);
    free(L);
}

rd_lift_form *rd_packring_form(rd_packring *L)
{
    return &L->form;
}

int rd_packring_initial(rd_packring *L, double atol, double *y, double *ab, rd_error *err)
{
    rd_lift_setup su = {0};
    const rd_ring_params *rp = rd_ring_get_params(L->ring);
    if (rd_lift_bore_distorted(&L->lp, rp->diameter) && !L->y0) { /* its static equilibrium */
        double *y0 = malloc(12 * (size_t)L->m.n * sizeof *y0);
        int rc = y0 ? rd_lift_bore_static(L->ring, &L->lp, y0, err)
                    : rd_error_set(err, RD_ENOMEM, "", "Out of memory for the bore start.");
        if (rc) {
            free(y0);
            return rc;
        }
        L->y0 = y0; /* the same for every run: solved once */
    }
    su.y0 = L->y0;
    return L->form.initial(L->form.user, &su, atol, y, ab, err);
}

void rd_packring_gas(rd_packring *L, const double g[3])
{
    memcpy(L->gas, g, sizeof L->gas);
}

int rd_packring_rhs(rd_packring *L, double t, double *y, double *yd)
{
    N_VSetArrayPointer(y, L->ys);
    N_VSetArrayPointer(yd, L->yd);
    return L->form.rhs(t, L->ys, L->yd, L->form.user);
}

/* fmin(fmax(x, 0), a) without the library calls (a step of every
 * right-hand side and root function; NaN gives 0 as there). */
static double clamp(double x, double a)
{
    return x > 0.0 ? (x < a ? x : a) : 0.0;
}

/* The form's per-segment lifts at y into seg and their mean; a form whose
 * segments all lift alike (form.uniform: the rigid ring) gives the mean
 * only, and the loops below add that one value n times: the same sums as
 * over n equal entries, so the same areas to the last bit, without n
 * entries to fill and read at every right-hand side. */
static double lifts(rd_packring *L, const double *y, double *seg)
{
    return L->form.lift(L->form.user, y, L->form.uniform ? NULL : seg);
}

double rd_packring_areas(rd_packring *L, const double *y, double *up, double *lo)
{
    double mean = lifts(L, y, L->seg), a = L->m.ca, su = 0.0, sl = 0.0;
    int n = L->m.n;
    if (L->form.uniform) {
        double cu = clamp(a - mean, a), cl = clamp(mean, a);
        for (int j = 0; j < n; j++) {
            su += cu;
            sl += cl;
        }
    } else {
        for (int j = 0; j < n; j++) {
            su += clamp(a - L->seg[j], a);
            sl += clamp(L->seg[j], a);
        }
    }
    *up = L->circ * su / n;
    *lo = L->circ * sl / n;
    return mean;
}

void rd_packring_area_slope(rd_packring *L, const double *y, const double *w, double *du,
                            double *dl)
{
    double a = L->m.ca, su = 0.0, sl = 0.0;
    int n = L->m.n, u = L->form.uniform;
    double L_y = lifts(L, y, L->seg), L_w = lifts(L, w, L->seg_w); /* seg_0: at open */
    for (int j = 0; j < n; j++) {
        double s = u ? L_y : L->seg[j], open = s > 0.0 && s < a ? 1.0 : 0.0;
        double dL = (u ? L_w : L->seg_w[j]) - L->seg_0[j];
        su -= open * dL;
        sl += open * dL;
    }
    *du = L->circ * su / n;
    *dl = L->circ * sl / n;
}

void rd_packring_loads(rd_packring *L, double t, const double *y, double *fz, double *friction)
{
    L->form.loads(L->form.user, t, y);
    *fz = L->m.fz_ext;
    *friction = L->m.friction;
}

double rd_packring_eps(const rd_packring *L)
{
    return L->m.eps;
}

rd_lift_flank_track *rd_packring_track(rd_packring *L)
{
    return &L->track;
}

rd_lift_pass *rd_packring_events(rd_packring *L)
{
    return &L->events;
}

int rd_packring_solver_open(rd_packring *L, SUNContext ctx)
{
    sunindextype N = L->form.N;
    L->x = N_VMake_Serial(N, NULL, ctx);
    L->b = N_VMake_Serial(N, NULL, ctx);
    if (!L->x || !L->b)
        return -1;
    if (L->form.blocks) {
        L->LS = rd_lift_newton_create(&L->form, ctx, &L->S, &L->nw);
        return L->LS ? SUNLinSolInitialize(L->LS) : -1;
    }
    L->t1 = N_VNew_Serial(N, ctx);
    L->t2 = N_VNew_Serial(N, ctx);
    L->t3 = N_VNew_Serial(N, ctx);
    L->J =
        L->form.dense ? SUNDenseMatrix(N, N, ctx) : SUNBandMatrix(N, RD_LIFT_MU, RD_LIFT_ML, ctx);
    if (!L->t1 || !L->t2 || !L->t3 || !L->J)
        return -1;
    L->LS = L->form.dense ? SUNLinSol_Dense(L->t1, L->J, ctx) : SUNLinSol_Band(L->t1, L->J, ctx);
    L->S = L->J;
    return L->LS ? SUNLinSolInitialize(L->LS) : -1;
}

int rd_packring_solver_setup(rd_packring *L, double t, double *y, double gamma)
{
    int cur = 0, rc;
    N_VSetArrayPointer(y, L->b);
    if (L->nw)
        rc = rd_lift_newton_linsys(L->nw, t, L->b, 0, &cur, gamma);
    else if (!(rc = L->form.rhs(t, L->b, L->t1, L->form.user)) &&
             !(rc = L->form.jac(t, L->b, L->t1, L->J, L->form.user, L->x, L->t2, L->t3)))
        rc = SUNMatScaleAddI(-gamma, L->J);
    return rc ? rc : SUNLinSolSetup(L->LS, L->S);
}

int rd_packring_solver_solve(rd_packring *L, double *x, double *b)
{
    N_VSetArrayPointer(x, L->x);
    N_VSetArrayPointer(b, L->b);
    return SUNLinSolSolve(L->LS, L->S, L->x, L->b, 0.0);
}

/* ---- what the scene asks of a ring's model ---- */

#define BORE_WHY                                                                                   \
    "auto: the bore is distorted, so the contact pressure and the friction vary around the ring, " \
    "which neither the axial nor the rigid ring can represent: the full ring (as the lift "        \
    "analysis' auto)"
#define TILT_WHY                                                                                   \
    "auto: the piston tilt makes the flank gap vary around the ring, which neither the axial nor " \
    "the rigid ring can represent: the full ring (as the lift analysis' auto)"
#define DYNAMIC_WHY                                                                              \
    "auto: dynamic active areas weight each face's pressure by how far it seals on its flank, "  \
    "which the axial ring's hard stops do not resolve; the rigid ring's penalty flanks do, and " \
    "it "                                                                                        \
    "is exact for an axisymmetric pack"

/* The bore or a layer of its map out of round or not of the rings'
 * diameter. */
static int bore_distorted(const rd_ringpack_params *p)
{
    double d = p->rings[0].ring.diameter;
    int distorted = rd_bore_distorted(&p->bore, d);
    for (int j = 0; p->bore_map && j < p->bore_map->n_layers; j++)
        distorted |= rd_bore_distorted(&p->bore_map->layer[j].bore, d);
    return distorted;
}

static int needs_flexible(const rd_ringpack_params *p)
{
    return bore_distorted(p) || rd_engine_tilted(&p->engine);
}

int rd_packring_auto(const rd_ringpack_params *p, const char **why)
{
    if (bore_distorted(p)) {
        *why = BORE_WHY;
        return RD_LIFT_MODEL_FULL;
    }
    if (rd_engine_tilted(&p->engine)) {
        *why = TILT_WHY;
        return RD_LIFT_MODEL_FULL;
    }
    if (p->active_area == RD_GAS_AREA_DYNAMIC && p->friction.model == RD_FRICTION_NONE) {
        *why = DYNAMIC_WHY;
        return RD_LIFT_MODEL_RIGID;
    }
    return -1;
}

/* Ring i's model k against what the scene needs, at "/model" of the block
 * that asks for it (the ring's entry, or /numerics for auto). */
static int model_fits(const rd_ringpack_params *p, int k, rd_error *err)
{
    const char *name = rd_ringpack_model_name(k);
    if (needs_flexible(p) && (k == RD_RINGPACK_AXIAL || k == RD_LIFT_MODEL_RIGID)) {
        int bore = bore_distorted(p);
        return rd_error_set(err, RD_EINVAL, "/model",
                            "@/model = %s cannot represent %s: the %s varies around the ring; "
                            "use auto, modal or full.",
                            name,
                            bore ? "a distorted bore (/bore/distortion, /bore/layers, "
                                   "/bore/diameter)"
                                 : "a tilted piston (/engine/piston_tilt_deg, /engine/piston_tilt)",
                            bore ? "contact pressure" : "flank gap");
    }
    if (p->active_area == RD_GAS_AREA_DYNAMIC && k == RD_RINGPACK_AXIAL)
        return rd_error_set(err, RD_EINVAL, "/model",
                            "@/model = axial cannot carry /physics/gas/active_area = dynamic: its "
                            "hard flank stops have no sealing contact to weight the faces' "
                            "pressures; use auto, rigid, modal or full.");
    return RD_OK;
}

/* Ring i's model, asked for (not auto), against what the scene needs, and
 * its gap on the tilt plane. */
static int validate_model(const rd_ringpack_params *p, int i, rd_error *err)
{
    const rd_ringpack_ring *r = &p->rings[i];
    char at[16];
    snprintf(at, sizeof at, "/rings/%d", i % 10);
    size_t m = rd_error_enter(err, r->model != RD_LIFT_MODEL_AUTO ? at : "/numerics");
    int rc = model_fits(p, r->model != RD_LIFT_MODEL_AUTO ? r->model : p->model, err);
    rd_error_leave(err, m);
    if (rc || !rd_engine_tilted(&p->engine) || !(fabs(wrap_deg(r->gap_angle_deg)) > 1e-6) ||
        gap_opposite(r))
        return rc;
    m = rd_error_enter(err, at);
    rc = rd_error_set(err, RD_EINVAL, "/gap_angle_deg",
                      "@/gap_angle_deg = %g deg with a tilted piston: the lift models tilt the "
                      "groove about the axis 90 deg from the ring's gap, so the gap must sit on "
                      "the tilt plane: 0 or 180 deg (or a multiple of 360 from them).",
                      r->gap_angle_deg);
    rd_error_leave(err, m);
    return rc;
}

double rd_ringpack_ring_depth(const rd_ringpack_params *p, int i)
{
    double z = p->ring_z_tdc;
    for (int j = 1; j <= i && j < p->n_rings; j++) {
        rd_section s; /* the section's bounding box: its axial height */
        rd_section_init(&s, &p->rings[j - 1].ring);
        z += s.h + p->rings[j].land_height;
    }
    return z;
}

/* A bore map's own rules, then that it covers moving ring i's whole
 * travel (named by ring; the lift analysis' own check then holds). */
static int map_covers(const rd_ringpack_params *p, int i, rd_error *err)
{
    const rd_bore_map *m = p->bore_map;
    if (!m || m->n_layers < 1)
        return RD_OK;
    size_t mark = rd_error_enter(err, "/bore");
    int rc = rd_bore_map_validate(m, p->rings[0].ring.diameter, err);
    if (!rc)
        rc = rd_error_range(p->ring_z_tdc, 0.0, RD_BORE_Z_MAX, "/ring_z_tdc_m", "m", err);
    double lo = rd_ringpack_ring_depth(p, i), hi = lo + 2.0 * p->engine.crank_radius;
    double top = m->layer[0].z, bottom = m->layer[m->n_layers - 1].z;
    if (!rc && (lo < top || hi > bottom))
        rc = rd_error_set(err, RD_EINVAL, "/layers",
                          "ring %d runs from %g m (TDC: @/ring_z_tdc_m = %g m for the top ring, "
                          "plus the rings and lands above it) to %g m (BDC) down the bore, but "
                          "@/layers covers %g to %g m: the map must cover every moving ring's "
                          "whole travel.",
                          i + 1, lo, p->ring_z_tdc, hi, top, bottom);
    rd_error_leave(err, mark);
    return rc;
}

int rd_packring_validate(const rd_ringpack_params *p, rd_error *err)
{
    if (p->active_area != RD_GAS_AREA_FIXED && p->active_area != RD_GAS_AREA_DYNAMIC) {
        size_t m = rd_error_enter(err, "/physics");
        rd_error_enter(err, "/gas");
        int rc =
            rd_error_set(err, RD_EINVAL, "/active_area",
                         "@/active_area = %d is unknown: use fixed or dynamic.", p->active_area);
        rd_error_leave(err, m);
        return rc;
    }
    for (int i = 0; i < p->n_rings; i++) {
        const rd_ringpack_ring *r = &p->rings[i];
        if (r->pinned != RD_PIN_FREE)
            continue; /* held on its flank: no model */
        /* the lift analysis' checks of the tilt (/engine/...) and the bore
         * (/bore/...) on this ring, as the scene gives them */
        rd_lift_params lp;
        rd_lift_params_default(&lp);
        lp.engine = p->engine;
        lp.bore = p->bore;
        lp.groove = r->groove;
        lp.model = RD_LIFT_MODEL_FULL;
        int rc = map_covers(p, i, err);
        if (!rc && p->bore_map) {
            lp.bore_map = p->bore_map;
            lp.ring_z_tdc = rd_ringpack_ring_depth(p, i);
        }
        if (!rc)
            rc = rd_lift_validate(&lp, &r->ring, r->segments, err);
        if (!rc)
            rc = validate_model(p, i, err);
        if (rc)
            return rc;
    }
    return RD_OK;
}
