/* lift_example.h — a lift example's scene (examples/NAME.json) read into core
 * parameters with jansson, field by field, independent of api/ (for the
 * golden test and the lift benchmark): ring, discretization, engine (with the
 * piston tilt), groove, bore, physics, output and numerics.  Header-only;
 * static functions. */
#ifndef RD_LIFT_EXAMPLE_H
#define RD_LIFT_EXAMPLE_H

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift.h"

typedef struct gcase {
    char name[64];
    rd_ring_params ring;
    rd_lift_params p;
    int n;
    double *gas[4];  /* owned tables: crank_deg, above, behind, below */
    double *tilt[2]; /* owned piston tilt table: crank_deg, tilt_deg (NULL: none) */
} gcase;

static double num(json_t *o, const char *key, double dflt)
{
    json_t *v = json_object_get(o, key);
    return json_is_number(v) ? json_number_value(v) : dflt;
}

static double *table(json_t *gas, const char *key, int *points)
{
    json_t *a = json_object_get(gas, key);
    size_t n = json_array_size(a);
    double *v = malloc((n ? n : 1) * sizeof *v);
    for (size_t i = 0; v && i < n; i++)
        v[i] = json_number_value(json_array_get(a, i));
    *points = (int)n;
    return v;
}

static void map_physics(gcase *c, json_t *ph)
{
    c->p.gravity = json_is_true(json_object_get(ph, "gravity"));
    json_t *fr = json_object_get(ph, "friction");
    if (fr) {
        const char *m = json_string_value(json_object_get(fr, "model"));
        c->p.friction.model = !m                       ? RD_FRICTION_NONE
                              : !strcmp(m, "coulomb")  ? RD_FRICTION_COULOMB
                              : !strcmp(m, "stribeck") ? RD_FRICTION_STRIBECK
                                                       : RD_FRICTION_NONE;
        c->p.friction.coefficient = num(fr, "coefficient", c->p.friction.coefficient);
    }
    json_t *gas = json_object_get(ph, "gas");
    if (gas) {
        static const char *keys[4] = {"crank_deg", "above", "behind", "below"};
        int pts = 0;
        for (int k = 0; k < 4; k++)
            c->gas[k] = table(gas, keys[k], &pts);
        c->p.gas.points = pts;
        c->p.gas.crank_deg = c->gas[0];
        c->p.gas.above = c->gas[1];
        c->p.gas.behind = c->gas[2];
        c->p.gas.below = c->gas[3];
        const char *a = json_string_value(json_object_get(gas, "active_area"));
        c->p.gas.active_area = a && !strcmp(a, "dynamic") ? RD_GAS_AREA_DYNAMIC : RD_GAS_AREA_FIXED;
    }
}

/* engine.piston_tilt_deg and the engine.piston_tilt table. */
static void map_tilt(gcase *c, json_t *e)
{
    c->p.engine.piston_tilt_deg = num(e, "piston_tilt_deg", 0.0);
    json_t *t = json_object_get(e, "piston_tilt");
    if (!t)
        return;
    int pts = 0;
    c->tilt[0] = table(t, "crank_deg", &pts);
    c->tilt[1] = table(t, "tilt_deg", &pts);
    c->p.engine.tilt_points = pts;
    c->p.engine.tilt_crank_deg = c->tilt[0];
    c->p.engine.tilt_deg = c->tilt[1];
}

/* bore.diameter and bore.distortion (at most RD_BORE_ORDERS_MAX terms). */
static void map_bore(gcase *c, json_t *b)
{
    c->p.bore.diameter = num(b, "diameter", 0.0);
    json_t *d = json_object_get(b, "distortion");
    size_t k = json_array_size(d);
    for (size_t i = 0; i < k && i < RD_BORE_ORDERS_MAX; i++) {
        json_t *t = json_array_get(d, i);
        c->p.bore.distortion[i].order = (int)num(t, "order", 0);
        c->p.bore.distortion[i].amplitude = num(t, "amplitude", 0.0);
        c->p.bore.distortion[i].phase_deg = num(t, "phase_deg", 0.0);
        c->p.bore.n_distortion = (int)i + 1;
    }
}

/* Frees the tables load_example allocated. */
static inline void free_example(gcase *c)
{
    for (int k = 0; k < 4; k++)
        free(c->gas[k]);
    free(c->tilt[0]);
    free(c->tilt[1]);
}

/* Reads dir/file into c (the full model, no error estimate); 0 if the file
 * cannot be read.  Free its tables after use (free_example). */
static int load_example(gcase *c, const char *dir, const char *file)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    json_error_t je;
    json_t *s = json_load_file(path, 0, &je);
    if (!s)
        return 0;
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "%s", file);
    rd_ring_params_default(&c->ring);
    rd_lift_params_default(&c->p);
    c->p.model = RD_LIFT_MODEL_FULL; /* the goldens are the full model's */
    c->p.estimate_error = 0;
    json_t *r = json_object_get(s, "ring"), *m = json_object_get(r, "material");
    c->ring.diameter = num(r, "diameter", c->ring.diameter);
    c->ring.radial_width = num(r, "radial_width", c->ring.radial_width);
    c->ring.axial_height = num(r, "axial_height", c->ring.axial_height);
    c->ring.closed_gap = num(r, "closed_gap", c->ring.closed_gap);
    c->ring.tangential_force = num(r, "tangential_force", c->ring.tangential_force);
    c->ring.youngs_modulus = num(m, "youngs_modulus", c->ring.youngs_modulus);
    c->ring.poisson_ratio = num(m, "poisson_ratio", c->ring.poisson_ratio);
    c->ring.density = num(m, "density", c->ring.density);
    c->n = (int)num(json_object_get(s, "discretization"), "segments", 20);
    json_t *e = json_object_get(s, "engine");
    c->p.engine.speed_rpm = num(e, "speed_rpm", c->p.engine.speed_rpm);
    c->p.engine.crank_radius = num(e, "crank_radius", c->p.engine.crank_radius);
    c->p.engine.rod_length = num(e, "rod_length", c->p.engine.rod_length);
    c->p.engine.cycles = num(e, "cycles", c->p.engine.cycles);
    const char *kin = json_string_value(json_object_get(e, "kinematics"));
    c->p.engine.kinematics =
        kin && !strcmp(kin, "approximate") ? RD_KINEMATICS_APPROXIMATE : RD_KINEMATICS_EXACT;
    map_tilt(c, e);
    map_bore(c, json_object_get(s, "bore"));
    json_t *g = json_object_get(s, "groove");
    c->p.groove.axial_clearance = num(g, "axial_clearance", c->p.groove.axial_clearance);
    c->p.groove.radial_clearance = num(g, "radial_clearance", c->p.groove.radial_clearance);
    map_physics(c, json_object_get(s, "physics"));
    c->p.step_deg = num(json_object_get(s, "output"), "step_deg", c->p.step_deg);
    json_t *nu = json_object_get(s, "numerics");
    c->p.rtol = num(nu, "rtol", c->p.rtol);
    c->p.atol = num(nu, "atol", c->p.atol);
    json_decref(s);
    return 1;
}

#endif
