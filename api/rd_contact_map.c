/*
 * rd_contact_map — bore maps in the contact scene (rd_contact_map.h); the
 * layers' hooks are lift's too.
 *
 * /bore/layers is read item by item through a temporary scene whose
 * options are the layer (rd_block_bore_layer's offsets are into an
 * rd_bore_layer), as the ring pack reads its rings; /bore/points is a
 * plain block of tables; /contact/height is a number or "all".  The map is
 * built in finish (the layers as given, or the fit of the points), checked
 * by core (rd_bore_map.h), and the bore at the height found once, so a run
 * at one height is the plain contact run with that bore.
 */
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_contact_map.h"
#include "rd_json.h"
#include "rd_scene.h"

#define ST(member) offsetof(struct rd_static_scene, member)
#define LY(member) offsetof(rd_bore_layer, member)

static const rd_field distortion_fields[] = {
    {"order", RD_F_INTEGER, offsetof(rd_distortion, order), RD_MIN(1), RD_MAX(64), .required = 1,
     .desc = "Fourier order k; a JSON integer (20.0 is refused here)."},
    {"amplitude", RD_F_NUMBER, offsetof(rd_distortion, amplitude), .required = 1,
     .desc = "Radius change A_k, m; |A_k| at most 1 % of the ring diameter, their sum too, and "
             "sum |A_k| (k^2 + 2) at most the bore radius (a convex bore)."},
    {"phase_deg", RD_F_NUMBER, offsetof(rd_distortion, phase_deg), RD_MIN(-360), RD_MAX(360),
     .desc = "Phase phi_k, degrees from the gap middle."},
    {.key = NULL},
};
const rd_block rd_block_contact_distortion = {
    "BoreDistortion", "One Fourier term of the bore distortion.", 0, 1, distortion_fields};

static const rd_field layer_fields[] = {
    {"z", RD_F_NUMBER, LY(z), RD_MIN(0), RD_MAX(RD_BORE_Z_MAX), .required = 1,
     .desc = "Height of the layer, m, down from the top of the bore; strictly increasing from "
             "layer to layer."},
    {"diameter", RD_F_NUMBER, LY(bore.diameter), RD_MIN(0),
     .desc = "The layer's diameter, m (taper, thermal growth); absent or 0 = /bore/diameter "
             "(or the ring's); within 2 % of the ring's. The echo gives the diameter used."},
    {"distortion", RD_F_DISTORTION, LY(bore), .block = &rd_block_contact_distortion,
     RD_MAX(RD_BORE_ORDERS_MAX),
     .desc = "The layer's Fourier terms, as /bore/distortion (at most 16, the same rules)."},
    {.key = NULL},
};
const rd_block rd_block_bore_layer = {
    "BoreLayer",
    "One layer of a bore map: r(theta) = D/2 + sum A_k cos(k (theta - phi_k)) at height z.", 1, 1,
    layer_fields};

static const rd_field points_fields[] = {
    RD_BORE_POINTS_FIELDS(ST),
    {.key = NULL},
};
const rd_block rd_block_bore_points = {
    "BorePoints",
    "/bore/points: a measured bore (theta, z, dr), fitted per layer of equal z by least "
    "squares up to fit_order; the same length for the three tables.",
    1, 0, points_fields};

/* ---- hooks ----------------------------------------------------------------- */

static int parse_layer(json_t *item, const char *at, rd_scene *s, rd_bore_layer *L, rd_error *err)
{
    if (!json_is_object(item))
        return rd_schema_type_error(err, at, "an object {z, diameter, distortion}", item);
    rd_scene tmp = *s;
    tmp.opts = L;
    int rc = rd_schema_parse(item, &rd_block_bore_layer, NULL, at, &tmp, err);
    if (rc == RD_OK && !json_object_get(item, "z"))
        rc = rd_error_set(err, RD_EINVAL, at,
                          "%s/z is missing: each layer needs its height z (m, down from the top "
                          "of the bore).",
                          at);
    return rc;
}

int rd_contact_map_parse_layers(const rd_field *f, json_t *v, const char *path, rd_scene *s,
                                rd_error *err)
{
    /* the field's offset is the map state's layers_given in the options (rd_contact_map.h) */
    struct rd_contact_map_scene *m =
        (void *)((char *)s->opts + f->offset - offsetof(struct rd_contact_map_scene, layers_given));
    if (!json_is_array(v))
        return rd_schema_type_error(err, path, "an array of {z, diameter, distortion}", v);
    size_t n = json_array_size(v);
    if (n < (size_t)f->min || n > (size_t)f->max)
        return rd_error_set(err, n ? RD_ELIMIT : RD_EINVAL, path,
                            "%s has %zu layers; allowed %d to %d.", path, n, (int)f->min,
                            (int)f->max);
    m->layers_given = 1;
    free(m->map);
    m->map = calloc(1, sizeof *m->map);
    if (!m->map)
        return rd_error_set(err, RD_ENOMEM, path, "out of memory while reading %s", path);
    m->map->n_layers = (int)n;
    m->map->residual_rms = NAN;
    for (size_t i = 0; i < n; i++) {
        char at[RD_ERROR_PATH_MAX];
        snprintf(at, sizeof at, "%s/%zu", path, i);
        int rc = parse_layer(json_array_get(v, i), at, s, &m->map->layer[i], err);
        if (rc != RD_OK)
            return rc;
    }
    return RD_OK;
}

int rd_ring_depth_parse(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    struct rd_ring_depth *rz =
        (void *)((char *)s->opts + f->offset - offsetof(struct rd_ring_depth, given));
    if (!json_is_number(v))
        return rd_schema_type_error(err, path, "a depth in m", v);
    rz->given = 1;
    rz->z = json_number_value(v);
    return RD_OK;
}

int rd_ring_depth_finish(struct rd_contact_map_scene *m, const struct rd_ring_depth *rz, double d,
                         double D, const char *who, const rd_bore_map **map, rd_error *err)
{
    *map = NULL;
    int given = m->layers_given || m->points_given;
    if (m->layers_given && m->points_given)
        return rd_error_set(err, RD_EINVAL, "/bore/points",
                            "/bore/points and /bore/layers are two ways to give the bore map: "
                            "give one.");
    if (rz->given && !given)
        return rd_error_set(err, RD_EINVAL, "/bore/ring_z_tdc_m",
                            "/bore/ring_z_tdc_m is read with a bore map only (/bore/layers or "
                            "/bore/points: %s depth on the map): give the map or remove it.",
                            who);
    if (given && !rz->given)
        return rd_error_set(err, RD_EINVAL, "/bore/ring_z_tdc_m",
                            "/bore/ring_z_tdc_m is missing: with a bore map, give %s depth "
                            "below the top of the bore at TDC (m).",
                            who);
    if (!given)
        return RD_OK;
    if (m->points_given) {
        int rc = rd_bore_map_of_points(m, d, D, err);
        if (rc)
            return rc;
    }
    for (int i = 0; i < m->map->n_layers; i++)
        if (m->map->layer[i].bore.diameter == 0.0)
            m->map->layer[i].bore.diameter = D;
    *map = m->map;
    return RD_OK;
}

/* The layers of `m` as the scene gives them. */
json_t *rd_bore_layers_json(const rd_scene *s, const rd_bore_map *m)
{
    json_t *a = json_array();
    for (int i = 0; a && m && i < m->n_layers; i++) {
        rd_scene tmp = *s;
        rd_bore_layer L = m->layer[i];
        tmp.opts = &L;
        json_t *item = json_object();
        int bad = !item || rd_schema_echo(&rd_block_bore_layer, &tmp, item) != 0;
        if (bad || json_array_append_new(a, item) != 0) {
            if (bad)
                json_decref(item);
            json_decref(a);
            a = NULL;
        }
    }
    return a;
}

json_t *rd_contact_map_echo_layers(const rd_scene *s)
{
    const struct rd_static_scene *o = s->opts;
    return o->map.layers_given ? rd_bore_layers_json(s, o->map.map) : json_null();
}

int rd_contact_map_parse_height(const rd_field *f, json_t *v, const char *path, rd_scene *s,
                                rd_error *err)
{
    struct rd_static_scene *o = s->opts;
    (void)f;
    o->map.height_given = 1;
    if (json_is_string(v) && strcmp(json_string_value(v), "all") == 0) {
        o->map.height_all = 1;
        return RD_OK;
    }
    if (!json_is_number(v))
        return rd_schema_type_error(err, path, "a height in m, or \"all\"", v);
    o->map.height_all = 0;
    o->map.height = json_number_value(v);
    return RD_OK;
}

json_t *rd_contact_map_echo_height(const rd_scene *s)
{
    const struct rd_static_scene *o = s->opts;
    if (!o->map.height_given)
        return json_null();
    return o->map.height_all ? json_string("all") : rd_result_real(o->map.height);
}

/* ---- finish ----------------------------------------------------------------- */

/* The points' tables into core's struct (the same length). */
static int points_of(const struct rd_contact_map_scene *m, rd_bore_points *p, rd_error *err)
{
    static const char *const names[] = {"theta_deg", "z", "dr"};
    for (int k = 1; k < 3; k++)
        if (m->points[k].n != m->points[0].n) {
            char path[64];
            snprintf(path, sizeof path, "/bore/points/%s", names[k]);
            return rd_error_set(err, RD_EINVAL, path,
                                "%s has %d values but /bore/points/theta_deg has %d: one per "
                                "point, the same length, please.",
                                path, m->points[k].n, m->points[0].n);
        }
    *p = (rd_bore_points){m->points[0].n, m->points[0].v, m->points[1].v, m->points[2].v,
                          m->fit_order};
    return RD_OK;
}

/* The rules between the map's fields and the plain bore's. */
static int map_rules(const struct rd_static_scene *o, rd_error *err)
{
    const struct rd_contact_map_scene *m = &o->map;
    if (!m->layers_given && !m->points_given)
        return m->height_given ? rd_error_set(err, RD_EINVAL, "/contact/height",
                                              "/contact/height is read with a bore map only: "
                                              "give /bore/layers or /bore/points, or remove "
                                              "/contact/height.")
                               : RD_OK;
    if (m->layers_given && m->points_given)
        return rd_error_set(err, RD_EINVAL, "/bore/points",
                            "/bore/points and /bore/layers are two ways to give the bore map: "
                            "give one.");
    if (o->contact.bore.n_distortion > 0)
        return rd_error_set(err, RD_EINVAL, "/bore/distortion",
                            "/bore/distortion is not read with a bore map: give the distortion "
                            "per layer (/bore/layers/<i>/distortion) or as points.");
    if (!m->height_given)
        return rd_error_set(err, RD_EINVAL, "/contact/height",
                            "/contact/height is missing: with a bore map, give the height the "
                            "ring sits at (m, down from the top of the bore) or \"all\".");
    return RD_OK;
}

int rd_bore_map_of_points(struct rd_contact_map_scene *m, double d, double D, rd_error *err)
{
    rd_bore_points p;
    free(m->map);
    m->map = malloc(sizeof *m->map);
    if (!m->map)
        return rd_error_set(err, RD_ENOMEM, "/bore/points", "out of memory for the bore map");
    int rc = points_of(m, &p, err);
    if (rc != RD_OK)
        return rc;
    size_t mark = rd_error_enter(err, "/bore");
    rc = rd_bore_points_validate(&p, d, err);
    rc = rc != RD_OK ? rc : rd_bore_map_fit(&p, D, m->map, err);
    rd_error_leave(err, mark);
    return rc;
}

json_t *rd_bore_fit_json(const rd_scene *s, const struct rd_contact_map_scene *m)
{
    if (!m->points_given || !m->map)
        return NULL;
    return json_pack("{s:o, s:o}", "residual_rms_m", rd_result_real(m->map->residual_rms), "layers",
                     rd_bore_layers_json(s, m->map));
}

int rd_contact_map_finish(rd_scene *s, rd_error *err)
{
    struct rd_static_scene *o = s->opts;
    struct rd_contact_map_scene *m = &o->map;
    double d = s->ring.diameter, D = o->contact.bore.diameter > 0 ? o->contact.bore.diameter : d;
    int rc = map_rules(o, err);
    if (rc != RD_OK || (!m->layers_given && !m->points_given))
        return rc;
    if (m->layers_given) {
        for (int i = 0; i < m->map->n_layers; i++) /* echoed as the diameter used */
            if (m->map->layer[i].bore.diameter == 0.0)
                m->map->layer[i].bore.diameter = D;
        size_t mark = rd_error_enter(err, "/bore");
        rc = rd_bore_map_validate(m->map, d, err);
        rd_error_leave(err, mark);
    } else {
        rc = rd_bore_map_of_points(m, d, D, err);
    }
    if (rc == RD_OK && !m->height_all) {
        size_t mark = rd_error_enter(err, "/contact");
        rc = rd_bore_map_at(m->map, m->height, d, &m->at, err);
        rd_error_leave(err, mark);
    }
    return rc;
}

void rd_contact_map_cleanup(struct rd_contact_map_scene *m)
{
    for (int k = 0; k < 3; k++) {
        free(m->points[k].v);
        m->points[k].v = NULL;
    }
    free(m->map);
    m->map = NULL;
}

/* ---- run -------------------------------------------------------------------- */

/* {"diameter", "distortion": [...]} of the bore a solve used. */
static json_t *bore_json(const rd_bore *b, double d)
{
    json_t *dist = json_array();
    for (int k = 0; dist && k < b->n_distortion; k++) {
        const rd_distortion *q = &b->distortion[k];
        if (json_array_append_new(dist, json_pack("{s:i, s:o, s:o}", "order", q->order, "amplitude",
                                                  rd_result_real(q->amplitude), "phase_deg",
                                                  rd_result_real(q->phase_deg))) != 0) {
            json_decref(dist);
            dist = NULL;
        }
    }
    return json_pack("{s:o, s:o}", "diameter", rd_result_real(b->diameter > 0 ? b->diameter : d),
                     "distortion", dist);
}

/* One row of the layers table: the layer and its contact's headline numbers. */
static json_t *layer_row(const rd_bore_layer *L, const rd_contact_result *r, double d)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int b = 0; b < RD_CONTACT_BINS; b++) {
        lo = fmin(lo, r->bin_pressure[b]);
        hi = fmax(hi, r->bin_pressure[b]);
    }
    return json_pack(
        "{s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:i, s:o, s:i, s:o}", "z_m", rd_result_real(L->z),
        "diameter_m", rd_result_real(L->bore.diameter > 0 ? L->bore.diameter : d),
        "contact_fraction", rd_result_real(r->contact_fraction), "max_clearance",
        rd_result_real(r->max_clearance), "max_clearance_angle_deg",
        rd_result_real(r->max_clearance_angle_deg), "mean_pressure_pa",
        rd_result_real(r->mean_pressure), "min_bin_pressure_pa", rd_result_real(lo),
        "max_bin_pressure_pa", rd_result_real(hi), "light_gaps", r->n_gaps, "tip_forces_n",
        rd_result_reals(r->tip_force, 2, 1, 1.0), "segments", r->stats.segments, "accuracy_met",
        r->accuracy_met < 0 ? json_null() : json_boolean(r->accuracy_met));
}

/* The map's pieces added to a result built for the bore `b` at height z. */
static int add_map(json_t *out, const rd_scene *s, const rd_bore *b, double z)
{
    const struct rd_static_scene *o = s->opts;
    int bad = json_object_set_new(out, "height_m", rd_result_real(z));
    bad |= json_object_set_new(out, "bore_at_height", bore_json(b, s->ring.diameter));
    if (!bad && o->map.points_given)
        bad |= json_object_set_new(out, "bore_fit", rd_bore_fit_json(s, &o->map));
    return bad;
}

/* height "all": every layer, the full result for the largest light gap. */
static int run_all(const rd_scene *s, const rd_ring_params *ring, const rd_contact_opts *oc,
                   const rd_monitor *mon, rd_contact_build build, json_t **out, rd_error *err)
{
    const struct rd_static_scene *o = s->opts;
    const rd_bore_map *m = o->map.map;
    double t0 = rd_clock_s();
    rd_contact_result *res = calloc((size_t)m->n_layers, sizeof *res);
    if (!res)
        return rd_error_set(err, RD_ENOMEM, "", "out of memory for %d layers", m->n_layers);
    int rc = rd_contact_solve_layers(ring, s->segments, oc, m, &o->statics, mon, res, err);
    if (rc == RD_OK) {
        int w = 0;
        for (int i = 1; i < m->n_layers; i++)
            w = res[i].max_clearance > res[w].max_clearance ? i : w;
        json_t *rows = json_array();
        for (int i = 0; rows && i < m->n_layers; i++)
            if (json_array_append_new(rows, layer_row(&m->layer[i], &res[i], s->ring.diameter))) {
                json_decref(rows);
                rows = NULL;
            }
        *out = rows ? build(s, &m->layer[w].bore, &res[w], rd_clock_s() - t0) : NULL;
        int bad = !*out || add_map(*out, s, &m->layer[w].bore, m->layer[w].z);
        if (!bad) { /* the table goes to the result either way (jansson's _new) */
            bad = json_object_set_new(*out, "layers", rows) != 0;
            rows = NULL;
        }
        json_decref(rows);
        if (bad && *out) {
            json_decref(*out);
            *out = NULL;
        }
    }
    for (int i = 0; i < m->n_layers; i++)
        rd_contact_result_cleanup(&res[i]);
    free(res);
    return rc;
}

int rd_contact_map_run(const rd_scene *s, const rd_ring_params *ring, const rd_free_shape *fs,
                       const rd_monitor *mon, rd_contact_build build, json_t **out, rd_error *err)
{
    const struct rd_static_scene *o = s->opts;
    rd_contact_opts oc = o->contact;
    oc.free_shape = fs;
    if (o->map.map && o->map.height_all)
        return run_all(s, ring, &oc, mon, build, out, err);
    if (o->map.map)
        oc.bore = o->map.at;
    rd_contact_result res;
    double t0 = rd_clock_s();
    int rc = rd_contact_solve(ring, s->segments, &oc, &o->statics, mon, &res, err);
    if (rc == RD_OK) {
        *out = build(s, &oc.bore, &res, rd_clock_s() - t0);
        if (*out && o->map.map && add_map(*out, s, &oc.bore, o->map.height)) {
            json_decref(*out);
            *out = NULL;
        }
    }
    rd_contact_result_cleanup(&res);
    return rc;
}
