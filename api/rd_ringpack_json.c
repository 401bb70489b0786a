/*
 * rd_ringpack_json — the ring pack's result object (rd_an_ringpack.c's
 * runner writes it; its CSV columns are the `table` member's).
 */
#include <jansson.h>
#include <math.h>

#include "rd_json.h"
#include "rd_lube_json.h"
#include "rd_registry.h"
#include "rd_result.h"
#include "rd_ringpack_json.h"

static const char *const flank_names[] = {"lower", "upper", "free"};
static const char *const event_names[] = {"leave_lower", "reach_upper", "leave_upper",
                                          "reach_lower"};

static json_t *volumes_json(const rd_ringpack_result *r)
{
    json_t *a = json_array();
    int N = r->samples, bad = !a;
    for (int v = 0; !bad && v < r->n_volumes; v++) {
        int fixed = v > 0 && v < r->n_volumes - 1;
        bad |= json_array_append_new(
            a, json_pack("{s:s, s:o, s:o}", "name", r->volume_name[v], "pressure_pa",
                         rd_result_reals(r->pressure + (size_t)v * N, N, 1, 1.0), "volume_m3",
                         fixed ? rd_result_real(r->volume_m3[v]) : json_null()));
    }
    if (bad) {
        json_decref(a);
        return NULL;
    }
    return a;
}

/* A pack ring's lubrication block's method (rd_result_lube). */
#define PACK_LUBE_FILMS                                                                        \
    "in a distorted bore, on a bore map or on a moving piston tilt, a film per segment load "  \
    "and sliding speed: each segment presses on the liner with its static contact load in "    \
    "the bore turned into the ring's frame (its gap angle), the contact analysis' exact "      \
    "contact of the ring (film_load_n_per_m; 2 F_t / D in a round bore; on a map at each "     \
    "layer the ring passes, linear between them, read at the ring's depth), plus the gas "     \
    "behind it, and slides at the piston's speed plus beta' x on a tilting piston (x its arm " \
    "about the pin axis); up to 5 distinct loads a film each (each distinct arm too), more "   \
    "interpolated in log load between films at 3 to 17 loads, the number chosen on the "       \
    "films of one cycle without gas (film_interpolation_error: that choice's miss); each "     \
    "film as follows. "
#define PACK_LUBE_METHOD                                                                       \
    "the lift analysis' film (one for the whole running face: a rigid profile on a round "     \
    "bore; the average Reynolds equation across the face with Patir-Cheng flow factors, gamma" \
    " = 1, the cavitation condition and the oil supply of physics.friction, 41 points, with "  \
    "the squeeze term; Greenwood-Tripp asperity contact; the radial balance 2 F_t / D + "      \
    "groove gas behind = film + asperity load by variable-step BDF2, steps at most "           \
    "film_step_deg), loaded by the pack's own pressures and coupled a cycle at a time: each "  \
    "cycle the ring rubs on the film integrated over the cycle before's pressures (the first " \
    "cycle's: no gas, after a cycle of warm-up). film_lag: the film of the reported cycle "    \
    "against the film its own pressures give, max |h0 - h0'| / max(h0', sigma); it tracked "   \
    "the distance from the settled film within x3 (0.4-1.8, 2400 rpm fired and motored, 3-5 "  \
    "cycles) where the pack's periodicity is below 0.1. film_error and friction_work_error "   \
    "(with numerics.error_estimate): the reported cycle's film against the same film, from "   \
    "the same start, on a grid twice as fine (81 points, half the steps, a quarter of the "    \
    "local error); as the lift's, within x0.35-1.24 of the error against a grid 8 times "      \
    "finer. Not covered: a pack that has not settled (periodicity above 1e-2: run more cycles" \
    " or \"periodic\"), the model (shear-stress factors, oil passed from ring to ring "        \
    "(supply: one film for every ring), a film varying around the ring). Friction work and "   \
    "FMEP: the reported (last) cycle."

static json_t *ring_json(const rd_ringpack_result *r, int i)
{
    int N = r->samples, bad = 0;
    json_t *flank = json_array(), *events = json_array();
    bad |= !flank || !events;
    for (int k = 0; !bad && k < N; k++) {
        int f = r->flank[(size_t)i * N + k];
        bad |= json_array_append_new(flank, json_string(f >= 0 && f < 3 ? flank_names[f] : "free"));
    }
    for (int e = 0; !bad && e < r->n_events[i]; e++) {
        int kind = r->events[i][e].kind;
        bad |= json_array_append_new(
            events,
            json_pack("{s:o, s:s, s:o}", "crank_deg", rd_result_real(r->events[i][e].crank_deg),
                      "event", kind >= 0 && kind < 4 ? event_names[kind] : "unknown", "touch_deg",
                      rd_result_real(r->events[i][e].touch_deg)));
    }
    if (bad) {
        json_decref(flank);
        json_decref(events);
        return NULL;
    }
    json_t *o =
        json_pack("{s:o, s:o, s:o, s:o}", "lift",
                  rd_result_reals(r->lift + (size_t)i * N, N, 1, 1.0), "flank", flank, "events",
                  events, "friction_n", rd_result_reals(r->friction + (size_t)i * N, N, 1, 1.0));
    if (o && r->lube[i].on) {
        json_t *lb = rd_result_lube(&r->lube[i], N,
                                    r->lube[i].films > 1 || isfinite(r->lube[i].interp_check)
                                        ? PACK_LUBE_FILMS PACK_LUBE_METHOD
                                        : PACK_LUBE_METHOD);
        if (!lb || json_object_set_new(lb, "film_lag", rd_result_real(r->film_lag[i])) != 0 ||
            json_object_set_new(o, "lubrication", lb) != 0) {
            json_decref(o);
            return NULL;
        }
    }
    return o;
}

static json_t *flows_json(const rd_ringpack_result *r)
{
    json_t *a = json_array();
    int N = r->samples, bad = !a;
    for (int f = 0; !bad && f < r->n_flows; f++)
        bad |= json_array_append_new(
            a, json_pack("{s:s, s:s, s:s, s:o}", "name", r->flow_name[f], "from",
                         r->volume_name[r->flow_from[f]], "to", r->volume_name[r->flow_to[f]],
                         "mass_flow_kg_s", rd_result_reals(r->flow + (size_t)f * N, N, 1, 1.0)));
    if (bad) {
        json_decref(a);
        return NULL;
    }
    return a;
}

/* The CSV table's columns: fixed names for up to three rings, null where a
 * ring or volume is absent. */
static json_t *table_json(const rd_ringpack_result *r)
{
    static const char *const pcol[] = {"cylinder_pa",    "top_land_pa", "groove_1_pa",
                                       "second_land_pa", "groove_2_pa", "third_land_pa",
                                       "groove_3_pa"};
    static const char *const lcol[] = {"lift_1_m", "lift_2_m", "lift_3_m"};
    int N = r->samples, bad = 0;
    json_t *t = json_object(), *nulls = json_array(), *cc = json_array();
    bad |= !t || !nulls || !cc;
    for (int k = 0; !bad && k < N; k++) {
        double in = 0.0; /* into the crankcase: the last ring's lower flank and end gap */
        for (int f = 0; f < r->n_flows; f++)
            if (r->flow_to[f] == r->n_volumes - 1)
                in += r->flow[(size_t)f * N + k];
        bad |= json_array_append_new(nulls, json_null()) ||
               json_array_append_new(cc, rd_result_real(in));
    }
    bad |= !t || json_object_set_new(t, "crank_deg", rd_result_reals(r->crank_deg, N, 1, 1.0));
    for (int v = 0; !bad && v < 7; v++)
        bad |= json_object_set_new(t, pcol[v],
                                   v < r->n_volumes - 1
                                       ? rd_result_reals(r->pressure + (size_t)v * N, N, 1, 1.0)
                                       : rd_json_copy(nulls));
    for (int i = 0; !bad && i < 3; i++)
        bad |=
            json_object_set_new(t, lcol[i],
                                i < r->n_rings ? rd_result_reals(r->lift + (size_t)i * N, N, 1, 1.0)
                                               : rd_json_copy(nulls));
    bad |= json_object_set(t, "blowby_kg_s", cc);
    json_decref(nulls);
    json_decref(cc);
    if (bad) {
        json_decref(t);
        return NULL;
    }
    return t;
}

/* numerics.model: per ring {name, dof, modes, why} (as the lift analysis'
 * numerics.model). */
static json_t *ring_models(const rd_ringpack_result *r, int *lifted)
{
    json_t *a = json_array();
    int bad = !a;
    *lifted = 0;
    for (int i = 0; !bad && i < r->n_rings; i++) {
        const char *name = rd_ringpack_model_name(r->ring_model[i]);
        *lifted |= r->ring_model[i] != RD_RINGPACK_AXIAL;
        bad |= json_array_append_new(
            a, json_pack("{s:s, s:i, s:i, s:s}", "name", name ? name : "unknown", "dof",
                         r->ring_dof[i], "modes", r->ring_modes[i], "why", r->ring_why[i]));
    }
    if (bad) {
        json_decref(a);
        return NULL;
    }
    return a;
}

static json_t *pack_numerics(const rd_ringpack_params *p, const rd_ringpack_result *r,
                             double wall_s)
{
    int estimated = isfinite(r->error_estimate), lifted;
    json_t *models = ring_models(r, &lifted);
    return json_pack(
        "{s:o, s:i, s:o, s:s, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:o, s:o, s:o, s:o, s:o, s:i, "
        "s:o}",
        "model", models, "dof", r->states, "wall_s", rd_result_real(wall_s), "solver",
        lifted ? "SUNDIALS CVODE, BDF (order <= 2), Newton on the coupled system by block "
                 "elimination: each lift-model ring's own solver, the network's dense "
                 "Schur complement; root finding for the flank changes"
               : "SUNDIALS CVODE, BDF with a dense Newton linear solver (difference-quotient "
                 "Jacobian), root finding for the flank changes, restarted at each",
        "steps", (json_int_t)r->steps, "rhs_evals", (json_int_t)r->rhs_evals, "jac_evals",
        (json_int_t)r->jac_evals, "root_evals", (json_int_t)r->root_evals, "restarts",
        (json_int_t)r->restarts, "error_test_fails", (json_int_t)r->err_test_fails,
        "nonlinear_failures", (json_int_t)r->nonlin_fails, "rtol", rd_result_real(p->rtol), "atol",
        rd_result_real(p->atol), "error_estimate", rd_result_real(r->error_estimate),
        "event_error_deg", rd_result_real(r->event_error_deg), "error_method",
        estimated ? json_string("second run at rtol/10 and atol/10: the larger of "
                                "the blow-by's relative change and the largest "
                                "pressure change over the cylinder peak; the "
                                "largest shift of a matched flank change (null "
                                "when the runs' flank changes differ in number)")
                  : json_null(),
        "cycles", r->cycles, "flank_band", rd_result_real(p->flank_band));
}

json_t *rd_ringpack_json(const rd_scene *scene, const rd_ringpack_params *p,
                         const rd_ringpack_result *r, double wall_s)
{
    json_t *rings = json_array();
    for (int i = 0; rings && i < r->n_rings; i++)
        if (json_array_append_new(rings, ring_json(r, i)) != 0) {
            json_decref(rings);
            rings = NULL;
        }
    return json_pack(
        "{s:s, s:o, s:o, s:o, s:o, s:o, s:{s:o, s:o, s:o, s:o, s:o}, s:o, s:o, s:o, s:o}",
        "analysis", rd_scene_analysis(scene), "scene", rd_scene_echo(scene), "crank_deg",
        rd_result_reals(r->crank_deg, r->samples, 1, 1.0), "volumes", volumes_json(r), "rings",
        rings, "flows", flows_json(r), "blowby", "kg_per_cycle", rd_result_real(r->blowby_kg),
        "l_per_min", rd_result_real(r->blowby_l_per_min), "reverse_kg_per_cycle",
        rd_result_real(r->reverse_kg), "inflow_kg_per_cycle", rd_result_real(r->inflow_kg),
        "mass_balance_residual", rd_result_real(r->mass_residual), "periodicity",
        rd_result_real(r->periodicity), "periodic_reached",
        p->periodic ? json_boolean(r->settled) : json_null(), "table", table_json(r), "numerics",
        pack_numerics(p, r, wall_s));
}
