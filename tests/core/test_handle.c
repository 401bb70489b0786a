/*
 * test_handle — the lift and ring-pack handles (rd_lift.h, rd_ringpack.h):
 * a handle's runs give, bit for bit, what rd_lift_solve / rd_ringpack_solve
 * give, and its second run what its first gave, on the scenes whose shared
 * parts the handle keeps: auto's check with its ring of n/2 segments, the
 * error estimate's n/2 run and a distorted bore's static starts, the
 * lubricated model's film (lift); the lift rings' models across the
 * accuracy levels, a distorted bore's start (ring pack).  Also: a refused
 * scene makes no handle, and rd_*_free(NULL) is a no-op.
 * Cost: ~7 s CPU in a Release build, ~2.5 min under the sanitizers.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lift_battery.h"
#include "rd_lift.h"
#include "rd_ringpack.h"

/* n doubles (or ints) alike to the bit; both NULL counts as alike. */
static int same(const void *a, const void *b, size_t bytes)
{
    if (!a || !b)
        return a == b;
    return memcmp(a, b, bytes) == 0;
}

/* Field by field: an event's padding is not part of it. */
static int same_events(const rd_lift_event *a, int na, const rd_lift_event *b, int nb)
{
    int ok = na == nb;
    for (int e = 0; ok && e < na; e++)
        ok = a[e].kind == b[e].kind && same(&a[e].crank_deg, &b[e].crank_deg, sizeof(double)) &&
             same(&a[e].touch_deg, &b[e].touch_deg, sizeof(double));
    return ok;
}

static int same_lube(const rd_lift_lube *a, const rd_lift_lube *b, int S)
{
    size_t d = (size_t)S * sizeof(double), c = (size_t)a->cycles * sizeof(double);
    return a->on == b->on && a->cycles == b->cycles && a->film_solves == b->film_solves &&
           same(a->min_film, b->min_film, d) &&
           same(a->hydrodynamic_friction, b->hydrodynamic_friction, d) &&
           same(a->asperity_friction, b->asperity_friction, d) && same(a->power, b->power, d) &&
           same(a->asperity_share, b->asperity_share, d) &&
           same(a->regime, b->regime, (size_t)S * sizeof(int)) &&
           same(a->friction_work, b->friction_work, c) && same(a->fmep, b->fmep, c) &&
           same(&a->film_error, &b->film_error, sizeof a->film_error) &&
           same(&a->work_error, &b->work_error, sizeof a->work_error);
}

/* Every number of two lift results, to the bit. */
static int same_lift(const rd_lift_result *a, const rd_lift_result *b)
{
    if (a->samples != b->samples || a->segments != b->segments || a->dof != b->dof ||
        a->model != b->model || a->modes != b->modes || strcmp(a->why, b->why) != 0 ||
        a->steps != b->steps || a->rhs_evals != b->rhs_evals || a->partial != b->partial ||
        a->segments_half != b->segments_half ||
        strcmp(a->accuracy_warning, b->accuracy_warning) != 0)
        return 0;
    size_t S = (size_t)a->samples, Sn = S * (size_t)a->segments, d = sizeof(double);
    double ea[6] = {a->error_estimate,           a->event_error_deg,       a->event_error_time_deg,
                    a->event_error_segments_deg, a->event_error_model_deg, a->crank_deg_reached};
    double eb[6] = {b->error_estimate,           b->event_error_deg,       b->event_error_time_deg,
                    b->event_error_segments_deg, b->event_error_model_deg, b->crank_deg_reached};
    return same(a->crank_deg, b->crank_deg, S * d) && same(a->lift, b->lift, S * d) &&
           same(a->lift_min, b->lift_min, S * d) && same(a->lift_max, b->lift_max, S * d) &&
           same(a->lift_segments, b->lift_segments, Sn * d) && same(a->twist, b->twist, S * d) &&
           same(a->friction_force, b->friction_force, S * d) &&
           same(a->bore_pressure, b->bore_pressure, Sn * d) &&
           same(a->flank, b->flank, S * sizeof(int)) &&
           same_events(a->events, a->n_events, b->events, b->n_events) && same(ea, eb, sizeof ea) &&
           same_lube(&a->lube, &b->lube, a->samples);
}

/* rd_lift_solve, then one handle run twice: all three alike. */
static void lift_case(const rd_ring_params *rp, int n, const rd_lift_params *p, const char *what)
{
    rd_lift_result a, b, c;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve(rp, n, p, NULL, &a, &err);
    CHECK(rc == RD_OK, "%s: rd_lift_solve: %s", what, err.message);
    rd_lift *h = NULL;
    int rh = rd_lift_create(rp, n, p, &h, &err);
    CHECK(rh == RD_OK && h, "%s: rd_lift_create: %s", what, err.message);
    int r1 = h ? rd_lift_run(h, NULL, &b, &err) : -1;
    int r2 = h ? rd_lift_run(h, NULL, &c, &err) : -1;
    CHECK(r1 == RD_OK && r2 == RD_OK, "%s: rd_lift_run: %s", what, err.message);
    if (rc == RD_OK && r1 == RD_OK && r2 == RD_OK) {
        CHECK(same_lift(&a, &b), "%s: the handle's first run differs from rd_lift_solve", what);
        CHECK(same_lift(&b, &c), "%s: the handle's second run differs from its first", what);
        printf("%s: model %s, %d flank changes, estimate %.3g deg: solve = run = run again\n", what,
               rd_lift_model_name(a.model), a.n_events, a.event_error_deg);
    }
    rd_lift_free(h);
    rd_lift_result_cleanup(&a);
    if (h) {
        rd_lift_result_cleanup(&b);
        rd_lift_result_cleanup(&c);
    }
}

static void test_lift(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_ring_params_default(&rp);
    /* auto with friction: the rigid run, its check at n and n/2 = 6 */
    lift_battery_scene(&p, 6000.0, 3e-5, 1, 1, 1e-6, 5.0);
    p.engine.cycles = 1.0;
    p.estimate_error = 1;
    lift_case(&rp, 12, &p, "auto, Coulomb, gas");
    p.accuracy_deg = 5.0; /* the rigid run kept: the check again at n/2 */
    lift_case(&rp, 12, &p, "auto, Coulomb, gas, 5 deg");
    /* a distorted bore: the full ring and its n/2 run from their static starts */
    rd_lift_params_default(&p);
    p.engine.cycles = 0.5;
    p.bore.n_distortion = 1;
    p.bore.distortion[0].order = 2;
    p.bore.distortion[0].amplitude = 4e-6;
    p.bore.distortion[0].phase_deg = 30.0;
    p.model = RD_LIFT_MODEL_FULL;
    p.estimate_error = 1;
    lift_case(&rp, 12, &p, "full, distorted bore");
    /* the lubricated model: its film solved once, by the handle's first run */
    rd_lift_params_default(&p);
    p.engine.speed_rpm = 2400.0;
    p.engine.cycles = 1.0;
    p.friction.model = RD_FRICTION_LUBRICATED;
    p.model = RD_LIFT_MODEL_RIGID;
    p.estimate_error = 1;
    lift_case(&rp, 20, &p, "rigid, lubricated");
}

/* Every number of two ring-pack results, to the bit. */
static int same_pack(const rd_ringpack_result *a, const rd_ringpack_result *b)
{
    if (a->samples != b->samples || a->n_rings != b->n_rings || a->n_volumes != b->n_volumes ||
        a->n_flows != b->n_flows || a->cycles != b->cycles || a->steps != b->steps ||
        a->rhs_evals != b->rhs_evals || a->restarts != b->restarts || a->states != b->states)
        return 0;
    size_t S = (size_t)a->samples, d = sizeof(double), R = (size_t)a->n_rings;
    int ok = same(a->crank_deg, b->crank_deg, S * d) &&
             same(a->pressure, b->pressure, (size_t)a->n_volumes * S * d) &&
             same(a->lift, b->lift, R * S * d) && same(a->flank, b->flank, R * S * sizeof(int)) &&
             same(a->friction, b->friction, R * S * d) &&
             same(a->flow, b->flow, (size_t)a->n_flows * S * d) &&
             same(&a->blowby_kg, &b->blowby_kg, d) && same(&a->periodicity, &b->periodicity, d) &&
             same(&a->error_estimate, &b->error_estimate, d) &&
             same(&a->event_error_deg, &b->event_error_deg, d);
    for (int i = 0; ok && i < a->n_rings; i++)
        ok = a->ring_model[i] == b->ring_model[i] && a->ring_dof[i] == b->ring_dof[i] &&
             same(&a->ring_stiffness[i], &b->ring_stiffness[i], d) &&
             same_events(a->events[i], a->n_events[i], b->events[i], b->n_events[i]) &&
             same_lube(&a->lube[i], &b->lube[i], a->samples);
    return ok;
}

static void pack_case(const rd_ringpack_params *p, const char *what)
{
    rd_ringpack_result a, b, c;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_ringpack_solve(p, NULL, &a, &err);
    CHECK(rc == RD_OK, "%s: rd_ringpack_solve: %s", what, err.message);
    rd_ringpack *h = NULL;
    int rh = rd_ringpack_create(p, &h, &err);
    CHECK(rh == RD_OK && h, "%s: rd_ringpack_create: %s", what, err.message);
    int r1 = h ? rd_ringpack_run(h, NULL, &b, &err) : -1;
    int r2 = h ? rd_ringpack_run(h, NULL, &c, &err) : -1;
    CHECK(r1 == RD_OK && r2 == RD_OK, "%s: rd_ringpack_run: %s", what, err.message);
    if (rc == RD_OK && r1 == RD_OK && r2 == RD_OK) {
        CHECK(same_pack(&a, &b), "%s: the handle's first run differs from rd_ringpack_solve", what);
        CHECK(same_pack(&b, &c), "%s: the handle's second run differs from its first", what);
        printf("%s: ring 1 %s, blow-by %.6g kg/cycle, estimate %.3g: solve = run = run again\n",
               what, rd_ringpack_model_name(a.ring_model[0]), a.blowby_kg, a.error_estimate);
    }
    rd_ringpack_free(h);
    rd_ringpack_result_cleanup(&a);
    if (h) {
        rd_ringpack_result_cleanup(&b);
        rd_ringpack_result_cleanup(&c);
    }
}

static void test_ringpack(void)
{
    rd_ringpack_params p;
    /* the thesis pack, linear flank pressure: auto gives the two moving
     * rings the rigid model, kept across the two accuracy levels */
    rd_ringpack_params_thesis(&p);
    p.engine.cycles = 2.0;
    p.step_deg = 2.0;
    p.estimate_error = 1;
    pack_case(&p, "thesis pack, rigid rings");
    /* one ring in a distorted bore: the full ring (8 segments) from its static start */
    rd_ringpack_params_default(&p);
    p.engine.cycles = 2.0;
    p.step_deg = 2.0;
    p.rings[0].segments = 8;
    p.bore.n_distortion = 1;
    p.bore.distortion[0].order = 2;
    p.bore.distortion[0].amplitude = 4e-6;
    p.estimate_error = 1;
    pack_case(&p, "one ring, distorted bore, full");
}

static void test_refused(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_ringpack_params q;
    rd_error err;
    rd_ring_params_default(&rp);
    rd_lift_params_default(&p);
    rd_ringpack_params_default(&q);
    p.engine.speed_rpm = -1.0;
    q.n_rings = 0;
    rd_lift *h = (rd_lift *)&p; /* not NULL: create must clear it */
    rd_ringpack *k = (rd_ringpack *)&q;
    rd_error_init(&err);
    CHECK(rd_lift_create(&rp, 20, &p, &h, &err) == RD_EINVAL && !h &&
              strcmp(err.path, "/engine/speed_rpm") == 0,
          "a refused lift scene: no handle, the field's path (%s)", err.path);
    rd_error_init(&err);
    CHECK(rd_ringpack_create(&q, &k, &err) == RD_EINVAL && !k && strcmp(err.path, "/rings") == 0,
          "a refused pack: no handle, the field's path (%s)", err.path);
    rd_lift_free(NULL);
    rd_ringpack_free(NULL);
}

int main(void)
{
    test_refused();
    test_lift();
    test_ringpack();
    return check_done();
}
