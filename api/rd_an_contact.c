/*
 * rd_an_contact — the contact analysis in the api (the installed ring in a
 * round or distorted bore, thesis 3.4.3): scene schema, runner, result
 * object and CSV table (rd_registry.h).  Options: struct rd_static_scene.
 */
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "rd_contact_map.h"
#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_static.h"

#define ST(member) offsetof(struct rd_static_scene, member)

/* The echo gives the bore diameter and contact stiffness used, where the
 * scene's 0 means "from the ring". */
static json_t *echo_bore_diameter(const rd_scene *s)
{
    const struct rd_static_scene *o = s->opts;
    double d = o->contact.bore.diameter;
    return rd_result_real(d > 0 ? d : s->ring.diameter);
}

static json_t *echo_stiffness(const rd_scene *s)
{
    const struct rd_static_scene *o = s->opts;
    double k = o->contact.stiffness;
    return rd_result_real(k > 0 ? k : rd_contact_default_stiffness(&s->ring));
}

static const rd_field bore_fields[] = {
    {"diameter", RD_F_NUMBER, ST(contact.bore.diameter), RD_MIN(0.0), .echo = echo_bore_diameter,
     .desc = "Bore diameter D, m; absent or 0 = the ring's diameter; otherwise within 2 % of it "
             "(0.98 d to 1.02 d). The echo gives the diameter used."},
    {"distortion", RD_F_DISTORTION, ST(contact.bore), .block = &rd_block_contact_distortion,
     RD_MAX(RD_BORE_ORDERS_MAX),
     .desc = "Fourier terms of the bore's out-of-roundness, at most 16; the sum of |amplitude| "
             "is at most 1 % of the ring diameter. Default: none (a round bore)."},
    RD_CONTACT_MAP_BORE_ROWS(ST),
    {.key = NULL},
};
static const rd_block bore_block = {
    "Bore",
    "/bore (contact): the bore r_b(theta) = D/2 + sum A_k cos(k (theta - phi_k)), the same at "
    "every height, or a bore map (layers or points) with /contact/height.",
    1, 0, bore_fields};

/* rd_contact_opts.flexible_face: 0 rigid, 1 flexible (the index). */
static const char *const face_names[] = {"rigid", "flexible", NULL};

static const rd_field contact_fields[] = {
    {"faces", RD_F_CHOICE, ST(contact.flexible_face), .choices = face_names,
     .desc = "Each segment's running face: flexible (default), bent and sheared with the ring "
             "between its joints from 80 segments on, or rigid, an arc turned with the segment "
             "(the thesis model; its misfit against a bore the ring follows keeps smooth bins "
             "0.04 p0 off at any n)."},
    {"points_per_segment", RD_F_INTEGER, ST(contact.points_per_segment), RD_MIN(1),
     RD_MAX(RD_CONTACT_POINTS_MAX),
     .desc = "Contact points m on each segment's running face (above 640 segments no more "
             "than keep them 360/6400 deg apart, and at least 5)."},
    {"max_segments", RD_F_INTEGER, ST(contact.max_segments), RD_MIN(4),
     RD_MAX(RD_STATIC_SEGMENTS_MAX),
     .desc = "Largest segment count the accuracy target may refine to (n, 2n, 4n ...); "
             "default 1280."},
    {"stiffness", RD_F_NUMBER, ST(contact.stiffness), RD_MIN(0.0), .echo = echo_stiffness,
     .desc = "Contact stiffness k, Pa/m. Absent or 0 = the default 2e6 E I / (h R^4) "
             "(penetration under the nominal pressure 5e-7 of the ring's radial deflection "
             "scale; 1e6 before 0.3.1); otherwise 1e-3 to 1e2 times that default. The echo "
             "gives the value asked for (the default's, where absent); with the default, if "
             "the contact law's share alone makes the error estimates miss numerics.accuracy, "
             "the refinement is repeated at 4 times it (since 0.3.2), and the result's "
             "contact_stiffness gives the stiffness used."},
    RD_CONTACT_MAP_HEIGHT_ROW(ST),
    {.key = NULL},
};
static const rd_block contact_block = {
    "ContactOptions", "/contact of a contact scene: the contact points and their law.", 1, 0,
    contact_fields};

static const rd_field scene_fields[] = {
    RD_SCENE_COMMON_WITH("The ring; the contact analysis needs tangential_force > 0.",
                         "{\"properties\": {\"tangential_force\": {\"minimum\": 0, "
                         "\"exclusiveMinimum\": true}}}",
                         rd_block_discretization_static),
    {"bore", RD_F_BLOCK, 0, .block = &bore_block},
    {"contact", RD_F_BLOCK, 0, .block = &contact_block},
    {"numerics", RD_F_BLOCK, 0, .block = &rd_block_contact_numerics},
    {.key = NULL},
};
static const rd_block scene_block = {
    "ContactScene",
    "The installed ring pressed by its pretension against a round or distorted bore: contact "
    "pressure and light gaps around the circumference (thesis 3.4.3). Reads ring "
    "(tangential_force must be > 0), discretization (4..2000 segments, split ring only), bore, "
    "contact (ContactOptions) and numerics (ContactNumerics).",
    0, 0, scene_fields};

static int finish(struct rd_scene *s, rd_error *err)
{
    struct rd_static_scene *o = s->opts;
    o->contact.free_shape = s->free_shape.kind != RD_FREE_CLOSED ? &s->free_shape : NULL;
    int rc = rd_free_shape_finish(s, err);
    rc = rc != RD_OK ? rc : rd_static_validate(&o->statics, s->segments, s->closed, err);
    rc = rc != RD_OK ? rc : rd_contact_validate(&o->contact, &s->ring, err);
    return rc != RD_OK ? rc : rd_contact_map_finish(s, err);
}

static void cleanup(void *opts)
{
    struct rd_static_scene *o = opts;
    rd_contact_map_cleanup(&o->map);
}

static json_t *distortion_bounds(const rd_bore *bore, const rd_contact_result *res)
{
    json_t *dist = json_array();
    for (int k = 0; dist && k < bore->n_distortion; k++) {
        const rd_distortion *d = &bore->distortion[k];
        if (json_array_append_new(dist,
                                  json_pack("{s:i, s:o, s:o, s:o}", "order", d->order, "amplitude",
                                            rd_result_real(d->amplitude), "phase_deg",
                                            rd_result_real(d->phase_deg), "conformability_bound",
                                            rd_result_real(res->bound[k]))) != 0) {
            json_decref(dist);
            dist = NULL;
        }
    }
    return dist;
}

/* {"analysis", "scene", "angle_deg", "pressure_pa", "clearance",
 *  "bore_radius" (n each, per segment), "mean_pressure_pa", ...,
 *  "distortion":[{"order","amplitude","phase_deg","conformability_bound"}],
 *  "support", "numerics"} */
/* [{"start_deg", "end_deg", "force_n", "centroid_deg"}] (rd_contact_patch);
 * NULL on out of memory. */
static json_t *contact_patches(const rd_contact_result *res)
{
    json_t *a = json_array();
    for (int j = 0; a && j < res->n_patches; j++) {
        const rd_contact_patch *p = &res->patches[j];
        if (json_array_append_new(a, json_pack("{s:o, s:o, s:o, s:o}", "start_deg",
                                               rd_result_real(p->start_deg), "end_deg",
                                               rd_result_real(p->end_deg), "force_n",
                                               rd_result_real(p->force_n), "centroid_deg",
                                               rd_result_real(p->centroid_deg))) != 0) {
            json_decref(a);
            a = NULL;
        }
    }
    return a;
}

/* Light gaps, patches, tip forces, bins and the accuracy record added to a contact
 * result; non-zero on out of memory. */
static int contact_accuracy(json_t *out, const rd_contact_result *res)
{
    json_t *gaps = json_array(), *num = json_object_get(out, "numerics");
    int bad = !gaps || !num;
    for (int g = 0; !bad && g < res->n_gaps; g++) {
        const rd_contact_gap *p = &res->gaps[g];
        bad |= json_array_append_new(
            gaps,
            json_pack("{s:o, s:o, s:o, s:o}", "start_deg", rd_result_real(p->start_deg), "end_deg",
                      rd_result_real(p->end_deg), "max_clearance", rd_result_real(p->max_clearance),
                      "max_clearance_angle_deg", rd_result_real(p->max_clearance_deg)));
    }
    bad |= json_object_set_new(out, "light_gaps", gaps);
    bad |= json_object_set_new(out, "tip_forces_n", rd_result_reals(res->tip_force, 2, 1, 1.0));
    bad |= json_object_set_new(out, "contact_patches", contact_patches(res));
    bad |=
        json_object_set_new(out, "pressure_bins",
                            json_pack("{s:f, s:o}", "bin_deg", RD_CONTACT_BIN_DEG, "pressure_pa",
                                      rd_result_reals(res->bin_pressure, RD_CONTACT_BINS, 1, 1.0)));
    if (bad)
        return 1;
    const rd_contact_estimates *e = &res->estimates;
    bad |= json_object_set_new(
        num, "error_estimates",
        json_pack("{s:o, s:o, s:o, s:o, s:o, s:o}", "pressure", rd_result_real(e->pressure),
                  "contact_fraction", rd_result_real(e->contact_fraction), "max_clearance",
                  rd_result_real(e->max_clearance), "gap_edges_deg",
                  rd_result_real(e->gap_edges_deg), "tip_forces_n", rd_result_real(e->tip_forces_n),
                  "patch_forces_n", rd_result_real(e->patch_forces_n)));
    /* the local refinement: base segments, factor and arcs (null: equal
     * segments) */
    json_t *grade = json_null();
    if (res->grade_factor > 1) {
        json_t *arcs = json_array();
        for (int k = 0; arcs && k < res->grade_arcs; k++)
            json_array_append_new(arcs, json_pack("[o, o]", rd_result_real(res->grade_lo_deg[k]),
                                                  rd_result_real(res->grade_hi_deg[k])));
        grade = json_pack("{s:i, s:i, s:o*}", "base_segments", res->grade_base, "factor",
                          res->grade_factor, "arcs_deg", arcs);
    }
    bad |= !grade || json_object_set_new(num, "local_refinement", grade);
    /* the contact law's part of error_estimates.pressure (of p0): twice the
     * bins' move at twice contact.stiffness; null when not solved */
    bad |= json_object_set_new(num, "pressure_law_share", rd_result_real(res->law_share));
    /* the levels' part of it from the pair solved again on shifted meshes
     * (since 0.3.10); null without an estimate */
    bad |= json_object_set_new(num, "pressure_shifted_meshes",
                               res->accuracy_met < 0 ? json_null()
                                                     : json_boolean(e->pressure_shifted));
    /* where the pressure's estimate's largest part is, and what it is */
    const char *source = rd_contact_est_source_name(e->pressure_source);
    bad |= json_object_set_new(num, "pressure_estimate_at_deg",
                               rd_result_real(source ? e->pressure_at_deg : NAN));
    bad |= json_object_set_new(num, "pressure_estimate_source",
                               source ? json_string(source) : json_null());
    bad |= json_object_set_new(num, "accuracy",
                               rd_result_real(res->accuracy_met < 0 ? NAN : res->accuracy));
    bad |= json_object_set_new(
        num, "accuracy_met", res->accuracy_met < 0 ? json_null() : json_boolean(res->accuracy_met));
    bad |=
        json_object_set_new(num, "accuracy_note",
                            res->accuracy_note[0] ? json_string(res->accuracy_note) : json_null());
    return bad;
}

static json_t *contact_result(const rd_scene *scene, const rd_bore *bore,
                              const rd_contact_result *res, double wall_s)
{
    int n = res->points;
    /* the binned pressure's estimate, as refined (since 0.3.10, where it was
     * taken from shifted meshes, rd_contact_refine.c) */
    char method[400];
    snprintf(method, sizeof method,
             "Binned pressure (of the uniform pressure): %s plus twice its change at double the "
             "contact stiffness,",
             res->estimates.pressure_shifted
                 ? "in each bin the larger of its move when the finer level's segments are "
                   "shifted by half a segment and half the smaller of its changes from the "
                   "coarser level and from the coarser level so shifted where both are of one "
                   "sign (else half the first)"
                 : "half its largest change between the last two refinement levels");
    json_t *out = json_pack(
        "{s:s, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o,"
        " s:o, s:o}",
        "analysis", rd_scene_analysis(scene), "scene", rd_scene_echo(scene), "angle_deg",
        rd_result_reals(res->angle_deg, n, 1, 1.0), "pressure_pa",
        rd_result_reals(res->pressure, n, 1, 1.0), "clearance",
        rd_result_reals(res->clearance, n, 1, 1.0), "bore_radius",
        rd_result_reals(res->bore_radius, n, 1, 1.0), "width_deg",
        rd_result_reals(res->width_deg, n, 1, 1.0), "mean_pressure_pa",
        rd_result_real(res->mean_pressure), "uniform_pressure_pa",
        rd_result_real(res->uniform_pressure), "contact_fraction",
        rd_result_real(res->contact_fraction), "max_clearance", rd_result_real(res->max_clearance),
        "max_clearance_angle_deg", rd_result_real(res->max_clearance_angle_deg), "max_penetration",
        rd_result_real(res->max_penetration), "contact_stiffness", rd_result_real(res->stiffness),
        "conformability", rd_result_real(res->conformability), "distortion",
        distortion_bounds(bore, res), "support", rd_static_result_support(&res->stats), "numerics",
        rd_static_result_numerics(&res->stats, wall_s, method));
    if (out && (contact_accuracy(out, res) != 0 ||
                json_object_set_new(out, "free_shape_model", rd_free_shape_model(scene)) != 0)) {
        json_decref(out);
        out = NULL;
    }
    return out;
}

/* The plain bore, the bore at /contact/height, or every layer; with a
 * measured free shape, the ring fitted to it first. */
static int run(const rd_scene *s, const rd_monitor *mon, json_t **out, rd_error *err)
{
    const struct rd_static_scene *o = s->opts;
    rd_free_run fr;
    int rc = rd_free_run_prepare(s, &s->ring, &o->statics, mon, &fr, err);
    if (rc == RD_OK)
        rc = rd_contact_map_run(s, &fr.ring, fr.free_shape, mon, contact_result, out, err);
    if (rc == RD_OK && *out && rd_free_run_result(*out, &fr) != 0) {
        json_decref(*out);
        *out = NULL;
    }
    return rc;
}

static const rd_csv_column csv_columns[] = {
    {"angle_deg", "angle_deg", 0},
    {"pressure_pa", "pressure_pa", 0},
    {"clearance_m", "clearance", 0},
    {"bore_radius_m", "bore_radius", 0},
    {NULL, NULL, 0},
};
static const rd_csv_table csv = {NULL, NULL, csv_columns};

static const char *const result_keys[] = {"analysis",
                                          "scene",
                                          "angle_deg",
                                          "pressure_pa",
                                          "clearance",
                                          "bore_radius",
                                          "width_deg",
                                          "mean_pressure_pa",
                                          "uniform_pressure_pa",
                                          "contact_fraction",
                                          "max_clearance",
                                          "max_clearance_angle_deg",
                                          "max_penetration",
                                          "contact_stiffness",
                                          "conformability",
                                          "distortion",
                                          "support",
                                          "numerics",
                                          "warnings",
                                          "light_gaps",
                                          "contact_patches",
                                          "tip_forces_n",
                                          "pressure_bins",
                                          "height_m",
                                          "bore_at_height",
                                          "bore_fit",
                                          "layers",
                                          "free_shape_model",
                                          "free_shape_fit",
                                          NULL};

const rd_analysis_def rd_an_contact = {
    .name = "contact",
    .scene = &scene_block,
    .opts_size = sizeof(struct rd_static_scene),
    .defaults = rd_static_scene_defaults,
    .finish = finish,
    .cleanup = cleanup,
    .run = run,
    .csv = &csv,
    .page = "contact.js",
    .result_keys = result_keys,
    .free_shapes = 1,
};
