/*
 * test_ringpack_films — the ring pack's lubricated rings in a distorted
 * bore: a film per segment load on every ring (core/ringpack/
 * rd_ringpack_film.c, the lift analysis' rd_lift_films_run on each ring's
 * static contact loads in its own frame).
 *
 * Scenes: the thesis pack (three rings, gaps at 0, 180 and 90 deg, the oil
 * ring pinned on its lower flank), 2400 rpm, 8 segments a ring, three
 * cycles, no error estimate, the rings' faces fed the fired cycle's gauge
 * tables (the test hook face_tables) so that a second driver can be given
 * the same loads.
 *  (1) a second driver: the lift analysis alone on the top ring (full
 *      model, lubricated, the same bore turned into the ring's frame, the
 *      same tables as its gas, two cycles): its films' loads bit for bit
 *      (the same contact solve), its film count, and over the pack's last
 *      cycle its thinnest segment film within FILM_TOL and its friction
 *      work within WORK_TOL of the pack's (order 2: the segments mirror
 *      into at most 5 loads, a film each on both sides).  If the pack gave
 *      a ring another ring's frame, another load or another share, the two
 *      would part.
 *  (2) the pinned oil ring, many loads (orders 2 and 4, films
 *      interpolated): the friction in its motion is its block's
 *      hydrodynamic + asperity friction at every sample (the ring rubs on
 *      the films' share-weighted sum that is reported), within PIN_TOL.
 *  (3) the friction work of each ring against the trapezoid of its
 *      block's friction times the piston's speed over its samples.
 *  (5) a moving piston tilt (+-1 deg), round bore: each ring's films at its
 *      segments' sliding speeds; the top ring (gap 0) and the middle ring
 *      (gap 180: the tilt negated in its frame) against the lift analysis
 *      alone, as (1), and the thinnest segment where it has it at every
 *      sample (with the arms' sign flipped for the middle ring: at none).
 *  (6) a bore map: each ring's films under its loads at its own depth; the
 *      top ring against the lift analysis alone on the same map, as (1).
 *  (4) the films' loads around each ring span what the contact analysis
 *      gives for the ring in the bore turned by its gap angle: the top
 *      ring's range is the middle ring's (both gaps on the order-2 axis)
 *      and not the oil ring's (90 deg: the bore's ovality the other way).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fired_cycle.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

#define FILM_TOL \
    3e-3 /* the pack's last cycle against the lift's second: the films' periodicity (1.3e-3 to 2.4e-3) */
#define WORK_TOL 1e-2
#define PIN_TOL  1e-9

static fired_tables tables;
static rd_gas_params gas;

static void scene(rd_ringpack_params *p, int order4)
{
    rd_ringpack_params_thesis(p);
    p->friction.model = RD_FRICTION_LUBRICATED;
    p->estimate_error = 0;
    p->periodic = 0;
    p->engine.cycles = 3;
    for (int i = 0; i < p->n_rings; i++)
        p->rings[i].segments = 8;
    p->bore.n_distortion = order4 ? 2 : 1;
    p->bore.distortion[0] = (rd_distortion){.order = 2, .amplitude = 5e-6};
    p->bore.distortion[1] = (rd_distortion){.order = 4, .amplitude = 2e-6, .phase_deg = 30.0};
    gas = fired_cycle_gas(&tables, 1e5);
    p->face_tables = &gas;
}

static int run(const rd_ringpack_params *p, rd_ringpack_result *r, const char *what)
{
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, r, &err);
    CHECK(rc == RD_OK, "%s: %s", what, err.message);
    for (int i = 0; rc == RD_OK && i < r->n_rings; i++)
        printf("%s, ring %d (%s): %d films, loads %.1f to %.1f N/m, interpolation %.3g, work "
               "%.6g J\n",
               what, i, r->ring_why[i], r->lube[i].films, r->lube[i].load_min, r->lube[i].load_max,
               r->lube[i].interp_check, r->lube[i].friction_work[0]);
    return rc;
}

/* The lift analysis alone on ring i of the pack (its bore and tilt turned
 * into its frame: the phases from its gap, the tilt negated for a gap at
 * 180 deg; the same tables), two cycles, against the pack's last cycle. */
static void lift_alone(const rd_ringpack_params *p, const rd_ringpack_result *r, int i,
                       const char *what, int angles)
{
    static double neg[8];
    rd_lift_params lp;
    rd_lift_params_default(&lp);
    lp.engine = p->engine;
    lp.engine.cycles = 2;
    if (fabs(p->rings[i].gap_angle_deg - 180.0) < 1e-9 && p->engine.tilt_points > 0) {
        for (int k = 0; k < p->engine.tilt_points && k < 8; k++)
            neg[k] = -p->engine.tilt_deg[k];
        lp.engine.tilt_deg = neg;
    }
    lp.bore = p->bore;
    for (int k = 0; k < lp.bore.n_distortion; k++)
        lp.bore.distortion[k].phase_deg =
            fmod(p->bore.distortion[k].phase_deg - p->rings[i].gap_angle_deg + 720.0, 360.0);
    static rd_bore_map map;
    if (p->bore_map) { /* the map in the ring's frame, at its depth */
        map = *p->bore_map;
        for (int j = 0; j < map.n_layers; j++)
            for (int k = 0; k < map.layer[j].bore.n_distortion; k++)
                map.layer[j].bore.distortion[k].phase_deg = fmod(
                    map.layer[j].bore.distortion[k].phase_deg - p->rings[i].gap_angle_deg + 720.0,
                    360.0);
        lp.bore_map = &map;
        lp.ring_z_tdc = rd_ringpack_ring_depth(p, i);
    }
    lp.groove = p->rings[i].groove;
    lp.friction = p->friction;
    lp.face = p->rings[i].face;
    lp.film_step_deg = p->film_step_deg;
    lp.gas = gas;
    lp.model = RD_LIFT_MODEL_FULL;
    lp.estimate_error = 0;
    lp.step_deg = p->step_deg;
    rd_lift_result l;
    memset(&l, 0, sizeof l);
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve(&p->rings[i].ring, p->rings[i].segments, &lp, NULL, &l, &err);
    CHECK(rc == RD_OK && l.lube.on, "%s: the lift analysis: %s", what, err.message);
    if (rc == RD_OK && l.lube.on) {
        const rd_lift_lube *a = &r->lube[i], *b = &l.lube;
        int S = r->samples, k0 = l.samples - S;
        double sig = a->composite_sigma, film = 0.0;
        int moved = 0; /* samples whose thinnest segment is elsewhere (a wrong frame) */
        for (int k = 0; k < S && k0 >= 0; k++) {
            film = fmax(film, fabs(a->min_film[k] - b->min_film[k0 + k]) /
                                  fmax(fabs(b->min_film[k0 + k]), sig));
            moved += a->min_film_angle_deg && b->min_film_angle_deg &&
                     a->min_film_angle_deg[k] != b->min_film_angle_deg[k0 + k];
        }
        double work = fabs(a->friction_work[0] - b->friction_work[1]) / fabs(b->friction_work[1]);
        printf("%s, ring %d against the lift analysis: %d films (the pack's %d), loads %.6g to "
               "%.6g N/m (%.6g to %.6g); the thinnest film within %.3g, work %.6g vs %.6g J "
               "(%.3g)\n",
               what, i, b->films, a->films, b->load_min, b->load_max, a->load_min, a->load_max,
               film, b->friction_work[1], a->friction_work[0], work);
        CHECK(a->films == b->films && a->films > 1 && (p->bore_map || isnan(a->interp_check)),
              "%s: films %d (lift %d)", what, a->films, b->films);
        CHECK(a->load_min == b->load_min && a->load_max == b->load_max, "%s: the loads differ",
              what);
        CHECK(k0 >= 0 && film < FILM_TOL, "%s: the thinnest film %g apart", what, film);
        CHECK(work < WORK_TOL, "%s: the work %g apart", what, work);
        /* the tilt's frame (the sign of the arms) shows in where the thinnest
           film is; in a distorted bore near-equal films trade places with the
           cycle's lag, and the loads above check the frame */
        CHECK(!angles || moved == 0, "%s: the thinnest segment elsewhere on %d of %d samples", what,
              moved, S);
        printf("  the thinnest segment where the lift analysis has it on %d of %d samples\n",
               S - moved, S);
    }
    rd_lift_result_cleanup(&l);
}

/* (1) and (4) */
static void second_driver(void)
{
    rd_ringpack_params p;
    scene(&p, 0);
    rd_ringpack_result r;
    if (run(&p, &r, "order 2") == RD_OK) {
        lift_alone(&p, &r, 0, "order 2", 0);
        const rd_lift_lube *t = &r.lube[0], *m = &r.lube[1], *o = &r.lube[2];
        CHECK(fabs(t->load_max - m->load_max) < 0.05 * t->load_max &&
                  fabs(t->load_min - m->load_min) < 0.05 * t->load_max,
              "top %g..%g, middle %g..%g N/m", t->load_min, t->load_max, m->load_min, m->load_max);
        CHECK(o->load_max - o->load_min > 0.0 && o->films > 1, "the oil ring's films: %d",
              o->films);
    }
    rd_ringpack_result_cleanup(&r);
}

/* (5) a moving tilt, round bore: each segment's film at its sliding speed;
 * the top ring (gap 0) and the middle one (gap 180: the tilt the other way
 * in its frame) against the lift analysis. */
static void tilting(void)
{
    static const double crank[4] = {0.0, 180.0, 360.0, 540.0}, tilt[4] = {1.0, -1.0, 1.0, -1.0};
    rd_ringpack_params p;
    scene(&p, 0);
    p.bore.n_distortion = 0;
    p.rings[2].gap_angle_deg = 0.0; /* a tilt takes gaps on its plane */
    p.engine.tilt_points = 4;
    p.engine.tilt_crank_deg = crank;
    p.engine.tilt_deg = tilt;
    rd_ringpack_result r;
    if (run(&p, &r, "tilt +-1 deg") == RD_OK) {
        lift_alone(&p, &r, 0, "tilt", 1);
        lift_alone(&p, &r, 1, "tilt", 1);
    }
    rd_ringpack_result_cleanup(&r);
}

static double piston_speed(const rd_engine_params *e, double a)
{
    double r = e->crank_radius, l = e->rod_length, s = sin(a);
    return r * e->speed_rpm * M_PI / 30.0 * (s + r * s * cos(a) / sqrt(l * l - r * r * s * s));
}

/* (6) a bore map (order 2 growing from 2 to 8 um down 0.1 m): each ring's
 * films follow its loads at its depth; the top ring against the lift
 * analysis alone on the same map at the same depth. */
static void mapped(void)
{
    rd_ringpack_params p;
    scene(&p, 0);
    static rd_bore_map map;
    memset(&map, 0, sizeof map);
    map.n_layers = 2;
    map.residual_rms = NAN;
    for (int j = 0; j < 2; j++) {
        map.layer[j].z = 0.1 * j;
        map.layer[j].bore = p.bore;
        map.layer[j].bore.distortion[0].amplitude = j ? 8e-6 : 2e-6;
    }
    p.bore.n_distortion = 0;
    p.bore_map = &map;
    p.ring_z_tdc = 0.005;
    rd_ringpack_result r;
    if (run(&p, &r, "bore map") == RD_OK) {
        for (int i = 0; i < r.n_rings; i++)
            CHECK(r.lube[i].load_depths >= 2, "ring %d: %d depths", i, r.lube[i].load_depths);
        lift_alone(&p, &r, 0, "bore map", 0);
    }
    rd_ringpack_result_cleanup(&r);
}

/* (2), (3) */
static void shares(void)
{
    rd_ringpack_params p;
    scene(&p, 1);
    rd_ringpack_result r;
    if (run(&p, &r, "orders 2 + 4") != RD_OK) {
        rd_ringpack_result_cleanup(&r);
        return;
    }
    int S = r.samples, oil = 2;
    const rd_lift_lube *o = &r.lube[oil];
    double pin = 0.0, size = 0.0;
    for (int k = 0; k < S; k++) {
        double f = o->hydrodynamic_friction[k] + o->asperity_friction[k];
        pin = fmax(pin, fabs(r.friction[(size_t)oil * S + k] - f));
        size = fmax(size, fabs(f));
    }
    printf("the pinned oil ring (%d films, interpolation %.3g): its friction within %.3g of its "
           "block's (size %.3g N)\n",
           o->films, o->interp_check, pin / size, size);
    CHECK(o->films >= 3 && isfinite(o->interp_check), "interpolated films: %d", o->films);
    CHECK(pin <= PIN_TOL * size, "the oil ring's friction %g apart", pin / size);
    for (int i = 0; i < r.n_rings; i++) {
        const rd_lift_lube *b = &r.lube[i];
        double w = 0.0;
        for (int k = 0; k + 1 < S; k++) {
            double a0 = r.crank_deg[k] * M_PI / 180.0, a1 = r.crank_deg[k + 1] * M_PI / 180.0;
            double f0 = b->hydrodynamic_friction[k] + b->asperity_friction[k],
                   f1 = b->hydrodynamic_friction[k + 1] + b->asperity_friction[k + 1];
            w += 0.5 * (a1 - a0) / (p.engine.speed_rpm * M_PI / 30.0) *
                 (f0 * piston_speed(&p.engine, a0) + f1 * piston_speed(&p.engine, a1));
        }
        double d = fabs(w - b->friction_work[0]) / fabs(b->friction_work[0]);
        printf("ring %d: work %.6g J, the samples' trapezoid %.6g (%.3g)\n", i, b->friction_work[0],
               w, d);
        CHECK(d < 2e-2, "ring %d: work %g apart", i, d);
    }
    rd_ringpack_result_cleanup(&r);
}

int main(void)
{
    second_driver();
    tilting();
    mapped();
    shares();
    return check_done();
}
