/*
 * rd_free_shape_scene — /ring/pressure_distribution in the api (issue 46's
 * names): the ring made with the free shape of a radial pressure
 * distribution (rd_static.h's rd_free_shape):
 *   "uniform"
 *   {"orders": [{"order": k, "amplitude": a_k}, ...]}   p / p0 = 1 + sum a_k cos k theta
 *   {"theta_deg": [...], "ratio": [...]}                p / p0 as a table
 * theta from the point opposite the gap.  Absent or null: the stress-free
 * closed ring opened by F_t (every analysis' model before).  Read by the
 * pretension and contact analyses (rd_analysis_def.free_shapes), refused
 * by the others, naming them; a key it does not know is refused, naming it.
 * Core checks the values (rd_free_shape_validate, from the analyses'
 * finish).
 */
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"

static int orders(json_t *v, const char *path, rd_free_shape *fs, rd_error *err)
{
    char at[RD_ERROR_PATH_MAX];
    rd_schema_path_join(at, sizeof at, path, "orders");
    if (!json_is_array(v) || json_array_size(v) > RD_FREE_ORDERS_MAX)
        return rd_error_set(err, RD_EINVAL, at,
                            "%s must be an array of at most %d {\"order\", \"amplitude\"}.", at,
                            RD_FREE_ORDERS_MAX);
    size_t i;
    json_t *it;
    json_array_foreach(v, i, it)
    {
        json_t *k = json_object_get(it, "order"), *a = json_object_get(it, "amplitude");
        if (!json_is_object(it) || json_object_size(it) != 2 || !json_is_integer(k) ||
            !json_is_number(a))
            return rd_error_set(err, RD_EINVAL, at,
                                "%s/%zu must be {\"order\": an integer, \"amplitude\": a number} "
                                "and nothing else.",
                                at, i);
        fs->order[i] = (int)json_integer_value(k);
        fs->amplitude[i] = json_number_value(a);
    }
    fs->n_orders = (int)json_array_size(v);
    return RD_OK;
}

/* Column `key` of the table o (pair: the other column's name, for the
 * message when it is missing). */
static int column(json_t *o, const char *key, const char *pair, const char *path, double *out,
                  int *n, rd_error *err)
{
    char at[RD_ERROR_PATH_MAX];
    json_t *v = json_object_get(o, key);
    rd_schema_path_join(at, sizeof at, path, key);
    if (!v)
        return rd_error_set(err, RD_EINVAL, at, "%s is missing: a table needs theta_deg and %s.",
                            at, pair);
    if (!json_is_array(v) || json_array_size(v) < 2 || json_array_size(v) > RD_FREE_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, at, "%s must be an array of 2 to %d numbers.", at,
                            RD_FREE_POINTS_MAX);
    size_t i;
    json_t *x;
    json_array_foreach(v, i, x)
    {
        if (!json_is_number(x))
            return rd_schema_type_error(err, at, "an array of numbers", v);
        out[i] = json_number_value(x);
    }
    *n = (int)json_array_size(v);
    return RD_OK;
}

/* The object v's keys: each one of the three given (known: their words),
 * or the first other refused at its path. */
static int keys_known(json_t *v, const char *path, const char *const keys[3], const char *known,
                      rd_error *err)
{
    const char *key;
    json_t *x;
    json_object_foreach(v, key, x)
    {
        if (strcmp(key, keys[0]) && strcmp(key, keys[1]) && strcmp(key, keys[2])) {
            char at[RD_ERROR_PATH_MAX];
            rd_schema_path_join(at, sizeof at, path, key);
            return rd_error_set(err, RD_EINVAL, at, "unknown field \"%.60s\" in %s (known: %s)",
                                key, path, known);
        }
    }
    return RD_OK;
}

/* A table's theta_deg and its column `key`, as long as each other, into t
 * and y; their length in *n. */
static int angle_table(json_t *v, const char *path, const char *key, double *t, double *y, int *n,
                       rd_error *err)
{
    int nt = 0, nr = 0;
    int rc = column(v, "theta_deg", key, path, t, &nt, err);
    if (rc == RD_OK)
        rc = column(v, key, key, path, y, &nr, err);
    if (rc == RD_OK && nt != nr) {
        char at[RD_ERROR_PATH_MAX];
        rd_schema_path_join(at, sizeof at, path, key);
        return rd_error_set(err, RD_EINVAL, at, "%s has %d values for %d angles (theta_deg).", at,
                            nr, nt);
    }
    *n = nt;
    return rc;
}

/* A free-shape field given to an analysis that does not read it. */
static int refused_here(const rd_scene *s, const char *path, rd_error *err)
{
    return rd_error_set(err, RD_EINVAL, path,
                        "%s is read by the pretension and contact analyses only (the free shape "
                        "it gives the ring); the %s analysis models the stress-free closed ring: "
                        "remove it.",
                        path, s->an->name);
}

int rd_free_shape_parse(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    (void)f;
    rd_free_shape *fs = &s->free_shape;
    memset(fs, 0, sizeof *fs);
    if (json_is_null(v))
        return RD_OK;
    if (!s->an->free_shapes)
        return refused_here(s, path, err);
    fs->kind = RD_FREE_PRESSURE;
    if (json_is_string(v) && strcmp(json_string_value(v), "uniform") == 0)
        return RD_OK;
    if (!json_is_object(v))
        return rd_schema_type_error(err, path,
                                    "\"uniform\", {\"orders\": [...]} or {\"theta_deg\": [...], "
                                    "\"ratio\": [...]}",
                                    v);
    static const char *const keys[3] = {"orders", "theta_deg", "ratio"};
    int rc = keys_known(v, path, keys, "orders, or theta_deg and ratio", err);
    if (rc != RD_OK)
        return rc;
    json_t *o = json_object_get(v, "orders");
    if (o && (json_object_get(v, "theta_deg") || json_object_get(v, "ratio")))
        return rd_error_set(err, RD_EINVAL, path,
                            "%s has both orders and a table (theta_deg, ratio): give one.", path);
    if (o)
        return orders(o, path, fs, err);
    return angle_table(v, path, "ratio", fs->theta_deg, fs->value, &fs->n_points, err);
}

json_t *rd_free_shape_echo(const rd_scene *s)
{
    const rd_free_shape *fs = &s->free_shape;
    if (fs->kind == RD_FREE_CLOSED)
        return json_null();
    if (fs->n_orders == 0 && fs->n_points == 0)
        return json_string("uniform");
    json_t *o = json_object();
    if (!o)
        return NULL;
    int bad = 0;
    if (fs->n_orders > 0) {
        json_t *a = json_array();
        for (int q = 0; a && q < fs->n_orders; q++)
            bad |=
                json_array_append_new(a, json_pack("{s:i, s:o}", "order", fs->order[q], "amplitude",
                                                   rd_result_real(fs->amplitude[q])));
        bad |= json_object_set_new(o, "orders", a);
    } else {
        bad |= json_object_set_new(o, "theta_deg",
                                   rd_result_reals(fs->theta_deg, fs->n_points, 1, 1.0));
        bad |= json_object_set_new(o, "ratio", rd_result_reals(fs->value, fs->n_points, 1, 1.0));
    }
    if (bad) {
        json_decref(o);
        return NULL;
    }
    return o;
}

json_t *rd_free_shape_model(const rd_scene *s)
{
    return json_string(s->free_table.n_points > 0             ? "measured_free_shape"
                       : s->free_shape.kind == RD_FREE_CLOSED ? "stress_free_closed"
                                                              : "pressure_distribution");
}

/* ---- /ring/free_shape: a measured free shape ------------------------------ */

int rd_free_table_parse(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    (void)f;
    rd_free_table *t = &s->free_table;
    memset(t, 0, sizeof *t);
    if (json_is_null(v))
        return RD_OK;
    if (!s->an->free_shapes)
        return refused_here(s, path, err);
    if (!json_is_object(v))
        return rd_schema_type_error(
            err, path, "{\"theta_deg\": [...], \"radius_m\": [...], \"fit_order\": K}", v);
    static const char *const keys[3] = {"theta_deg", "radius_m", "fit_order"};
    int rc = keys_known(v, path, keys, "theta_deg, radius_m, fit_order", err);
    if (rc != RD_OK)
        return rc;
    json_t *k = json_object_get(v, "fit_order");
    t->fit_order = 6;
    if (k && !json_is_integer(k)) {
        char at[RD_ERROR_PATH_MAX];
        rd_schema_path_join(at, sizeof at, path, "fit_order");
        return rd_schema_type_error(err, at, "an integer (2 to 12)", k);
    }
    if (k)
        t->fit_order = (int)json_integer_value(k);
    return angle_table(v, path, "radius_m", t->theta_deg, t->radius, &t->n_points, err);
}

json_t *rd_free_table_echo(const rd_scene *s)
{
    const rd_free_table *t = &s->free_table;
    if (t->n_points == 0)
        return json_null();
    return json_pack("{s:o, s:o, s:i}", "theta_deg",
                     rd_result_reals(t->theta_deg, t->n_points, 1, 1.0), "radius_m",
                     rd_result_reals(t->radius, t->n_points, 1, 1.0), "fit_order", t->fit_order);
}

int rd_free_shape_finish(const rd_scene *s, rd_error *err)
{
    if (s->free_table.n_points == 0)
        return RD_OK;
    if (s->free_shape.kind != RD_FREE_CLOSED)
        return rd_error_set(err, RD_EINVAL, "/ring/free_shape",
                            "/ring/free_shape and /ring/pressure_distribution both describe how "
                            "the ring was made: give one (the measured shape's pressure is "
                            "fitted from it).");
    rd_ring_params d;
    rd_ring_params_default(&d);
    if (s->ring.tangential_force != d.tangential_force)
        return rd_error_set(err, RD_EINVAL, "/ring/tangential_force",
                            "/ring/tangential_force = %g N is not read with /ring/free_shape: the "
                            "measured free shape gives F_t (free_shape_fit.tangential_force_n in "
                            "the result); leave it out.",
                            s->ring.tangential_force);
    size_t m = rd_error_enter(err, "/ring");
    int rc = rd_free_table_validate(&s->free_table, &s->ring, err);
    rd_error_leave(err, m);
    return rc;
}

int rd_free_run_prepare(const rd_scene *s, const rd_ring_params *ring, const rd_static_opts *so,
                        const rd_monitor *mon, rd_free_run *r, rd_error *err)
{
    memset(r, 0, sizeof *r);
    r->ring = *ring;
    r->free_shape = s->free_shape.kind != RD_FREE_CLOSED ? &s->free_shape : NULL;
    if (s->free_table.n_points == 0)
        return RD_OK;
    rd_static_opts fo = *so;
    fo.estimate_error = 0;
    int rc = rd_free_shape_fit(ring, RD_FREE_FIT_SEGMENTS, &s->free_table, &fo, mon, &r->fit, err);
    if (rc != RD_OK)
        return rc;
    r->fitted = 1;
    r->points = s->free_table.n_points;
    r->ring.tangential_force = r->fit.tangential_force;
    r->free_shape = &r->fit.shape;
    return RD_OK;
}

int rd_free_run_result(json_t *out, const rd_free_run *r)
{
    if (!r->fitted)
        return json_object_set_new(out, "free_shape_fit", json_null()) != 0;
    const rd_free_fit *f = &r->fit;
    json_t *orders = json_array();
    for (int q = 0; orders && q < f->shape.n_orders; q++)
        if (json_array_append_new(
                orders, json_pack("{s:i, s:o, s:o, s:o}", "order", f->shape.order[q], "amplitude",
                                  rd_result_real(f->shape.amplitude[q]), "standard_error",
                                  rd_result_real(f->amplitude_se[q]), "segments_error",
                                  rd_result_real(f->amplitude_error[q]))) != 0) {
            json_decref(orders);
            orders = NULL;
        }
    json_t *o = json_pack(
        "{s:o*, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:[o, o], s:o, s:o, s:i, s:i, s:i, s:i, s:s}",
        "orders", orders, "tangential_force_n", rd_result_real(f->tangential_force),
        "tangential_force_standard_error_n", rd_result_real(f->tangential_force_se),
        "tangential_force_segments_error_n", rd_result_real(f->tangential_force_error),
        "pressure_standard_error_max", rd_result_real(f->pressure_se_max), "pressure_min_ratio",
        rd_result_real(f->pressure_min), "pressure_min_theta_deg",
        rd_result_real(f->pressure_min_deg), "residual_rms_m", rd_result_real(f->residual_rms),
        "centre_m", rd_result_real(f->centre[0]), rd_result_real(f->centre[1]), "rotation_deg",
        rd_result_real(f->rotation_deg), "residual_max_m", rd_result_real(f->residual_max),
        "points", r->points, "parameters", f->parameters, "segments", f->segments, "iterations",
        f->iterations, "note",
        "The pressure p / p0 = 1 + sum a_k cos k theta (theta from the point opposite the gap) "
        "and F_t whose exact free shape is closest to the table in least squares. "
        "standard_error: the table's scatter about that shape (s^2 (J^T J)^-1, s from the "
        "residual); segments_error: the chain's, from the fit at half the segments. Neither "
        "covers a systematic error of the table nor orders above fit_order.");
    return json_object_set_new(out, "free_shape_fit", o) != 0;
}
