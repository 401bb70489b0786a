/*
 * rd_an_pretension — the pretension analysis in the api (the free shape of
 * the split ring, thesis 3.4.1-3.4.2): scene schema, runner, result object
 * and CSV table (rd_registry.h).  Options: struct rd_static_scene.
 */
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_static.h"

#define PI         3.14159265358979323846
#define ST(member) offsetof(struct rd_static_scene, member)

/* Indexed by enum rd_pretension_method. */
static const char *const method_names[] = {"force", "field", NULL};

static const rd_field pretension_fields[] = {
    {"method", RD_F_CHOICE, ST(pretension.method), .choices = method_names,
     .desc = "force: each gap force stays normal to its face as the face turns (follower). "
             "field: the force follows the last segment's face and the first face gets the "
             "opposite vector plus the balancing couple (thesis Fig. 3.18)."},
    {"lateral_force", RD_F_NUMBER, ST(pretension.lateral_force), RD_MIN(0.0),
     .desc = "Lateral (axial) force F_l on the gap faces, +z on the first and -z on the last, "
             "N; at most 100 * max(F_t, 1 N)."},
    {.key = NULL},
};
static const rd_block pretension_block = {
    "PretensionOptions", "/pretension: how the free shape is loaded.", 1, 0, pretension_fields};

static const rd_field scene_fields[] = {
    RD_SCENE_COMMON(rd_block_discretization_static),
    {"pretension", RD_F_BLOCK, 0, .block = &pretension_block},
    {"numerics", RD_F_BLOCK, 0, .block = &rd_block_static_numerics},
    {.key = NULL},
};
static const rd_block scene_block = {
    "PretensionScene",
    "The free (unloaded) shape of the split ring: the closed ring opened by the tangential "
    "force F_t on the gap faces, optionally with a lateral (axial) force (thesis 3.4.1-3.4.2). "
    "Reads ring, discretization (4..2000 segments, split ring only), pretension and numerics "
    "(StaticNumerics).  The load parameter F_t (D - b)^2 / (4 E I) may be at most 4 (0.5 with "
    "4 segments): beyond it the free-shape solve does not converge.",
    0, 0, scene_fields};

static int finish(struct rd_scene *s, rd_error *err)
{
    struct rd_static_scene *o = s->opts;
    o->pretension.free_shape = s->free_shape.kind != RD_FREE_CLOSED ? &s->free_shape : NULL;
    int rc = rd_free_shape_finish(s, err);
    rc = rc != RD_OK ? rc : rd_static_validate(&o->statics, s->segments, s->closed, err);
    rc = rc != RD_OK ? rc : rd_pretension_validate(&o->pretension, &s->ring, s->segments, err);
    if (rc != RD_OK)
        return rc;
    size_t m = rd_error_enter(err, "/ring");
    rc = rd_free_shape_validate(o->pretension.free_shape, &s->ring, err);
    rd_error_leave(err, m);
    return rc;
}

/* {"analysis", "scene", "gap_opening_inner", "lateral_opening",
 *  "gap_opening_neutral", "free_gap_formula", "conformability", "support",
 *  "shape":{"angle_deg","x","y","z","reference_x","reference_y"} (n + 2
 *  points), "numerics"} */
/* "section": the properties the beam used (rd_section.h): area, centroid
 * [radius, height above the section's bottom], principal angle (from the
 * radial axis toward +z), second moments about the centroid, principal
 * moments, Saint-Venant J (series, closed form, or finite elements with
 * its estimate; 0 when exact), shear factor, and the outline they are
 * integrated over. */
/* The section's outline, [u, v] per point (u radial from its inner edge, v
 * axial from its bottom, m, counter-clockwise): the rectangle's corners, the
 * circle as OUTLINE_CIRCLE points on it, a general shape's polygon
 * (rd_section_outline: what its properties are integrated over). */
#define OUTLINE_CIRCLE 48
static json_t *outline_json(const rd_ring_params *p)
{
    double pts[RD_SECTION_POINTS_MAX > OUTLINE_CIRCLE ? RD_SECTION_POINTS_MAX : OUTLINE_CIRCLE][2];
    double b = p->radial_width, h = p->axial_height;
    int n = 0;
    if (p->section == RD_SECTION_CIRCLE) {
        for (n = 0; n < OUTLINE_CIRCLE; n++) {
            double a = 2.0 * PI * n / OUTLINE_CIRCLE;
            pts[n][0] = 0.5 * b * (1.0 + cos(a));
            pts[n][1] = 0.5 * h * (1.0 + sin(a));
        }
    } else if (p->section >= RD_SECTION_TAPER_FACE) {
        rd_error err;
        rd_error_init(&err);
        if (rd_section_outline(p->section, &p->spec, b, h, pts, &n, &err) != RD_OK)
            return json_null(); /* the scene's checks ran this outline already */
    } else {
        const double box[4][2] = {{0.0, 0.0}, {b, 0.0}, {b, h}, {0.0, h}};
        memcpy(pts, box, sizeof box);
        n = 4;
    }
    json_t *a = json_array();
    for (int i = 0; a && i < n; i++)
        if (json_array_append_new(a, json_pack("[o, o]", rd_result_real(pts[i][0]),
                                               rd_result_real(pts[i][1]))) != 0) {
            json_decref(a);
            a = NULL;
        }
    return a;
}

static json_t *section_json(const rd_ring_params *p)
{
    rd_section s;
    rd_section_init(&s, p);
    double J_err = p->section >= RD_SECTION_TAPER_FACE ? p->spec.J_error : 0.0;
    return json_pack(
        "{s:s, s:o, s:[o, o], s:o, s:{s:o, s:o, s:o}, s:[o, o], s:o, s:o, s:o, s:o, s:s, s:o}",
        "shape",
        p->section == RD_SECTION_RECTANGLE ? "rectangle"
        : p->section == RD_SECTION_CIRCLE  ? "circle"
                                           : "general",
        "area_m2", rd_result_real(s.area), "centroid_m", rd_result_real(s.R),
        rd_result_real(s.z_c + 0.5 * s.h), "principal_angle_deg",
        rd_result_real(s.angle * 180.0 / PI), "second_moments_m4", "rr", rd_result_real(s.I_rr),
        "zz", rd_result_real(s.I_zz), "rz", rd_result_real(s.I_rz), "principal_moments_m4",
        rd_result_real(s.I_inplane), rd_result_real(s.I_outplane), "torsion_constant_m4",
        rd_result_real(s.J), "torsion_constant_error_m4", rd_result_real(J_err), "shear_factor",
        rd_result_real(s.shear_factor), "shear_factor_axial", rd_result_real(s.shear_factor_axial),
        "torsion_method",
        p->section == RD_SECTION_RECTANGLE ? "series"
        : p->section == RD_SECTION_CIRCLE  ? "closed form"
                                           : "finite elements (Prandtl stress function), "
                                             "Richardson-extrapolated",
        "outline_m", outline_json(p));
}

/* "free_shape": the solved free shape's running face (polar about the
 * closed ring's centre, from the point opposite the gap), the gap between
 * its tips, and the tangential force: the one that closes it (a pressure
 * distribution's shape) or F_t itself (the stress-free closed ring's). */
static json_t *free_shape_json(int made, const rd_ring_params *ring,
                               const rd_pretension_result *res)
{
    int np = res->points;
    return json_pack("{s:o, s:o, s:o, s:o}", "theta_deg",
                     rd_result_reals(res->face_theta_deg, np, 1, 1.0), "radius_m",
                     rd_result_reals(res->face_radius, np, 1, 1.0), "free_gap_m",
                     rd_result_real(res->free_gap), "tangential_force_n",
                     rd_result_real(made ? res->tangential_force : ring->tangential_force));
}

static json_t *pretension_result(const rd_scene *scene, const rd_free_run *fr,
                                 const rd_pretension_result *res, double wall_s)
{
    int np = res->points;
    const rd_ring_params *ring = &fr->ring;
    double *rx = malloc((size_t)np * sizeof *rx), *ry = malloc((size_t)np * sizeof *ry);
    json_t *out = NULL;
    if (!rx || !ry)
        goto out;
    rd_section sec;
    rd_section_init(&sec, ring);
    double R = sec.R; /* the centroid circle: 0.5 (d - b) for a rectangle */
    for (int k = 0; k < np; k++) {
        rx[k] = R * cos(res->angle_deg[k] * PI / 180.0);
        ry[k] = R * sin(res->angle_deg[k] * PI / 180.0);
    }
    out = json_pack(
        "{s:s, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:{s:o, s:o, s:o, s:o, s:o, s:o, s:o}, s:o}",
        "analysis", rd_scene_analysis(scene), "scene", rd_scene_echo(scene), "gap_opening_inner",
        rd_result_real(res->gap_opening_inner), "lateral_opening",
        rd_result_real(res->lateral_opening), "gap_opening_neutral",
        rd_result_real(res->gap_opening_neutral), "free_gap_formula",
        rd_result_real(res->free_gap_formula), "conformability",
        rd_result_real(res->conformability), "support", rd_static_result_support(&res->stats),
        "shape", "angle_deg", rd_result_reals(res->angle_deg, np, 1, 1.0), "x",
        rd_result_reals(res->x, np, 1, 1.0), "y", rd_result_reals(res->y, np, 1, 1.0), "z",
        rd_result_reals(res->z, np, 1, 1.0), "reference_x", rd_result_reals(rx, np, 1, 1.0),
        "reference_y", rd_result_reals(ry, np, 1, 1.0), "static_twist_deg",
        res->static_twist_deg ? rd_result_reals(res->static_twist_deg, np, 1, 1.0) : json_null(),
        "numerics",
        rd_static_result_numerics(&res->stats, wall_s,
                                  "Richardson extrapolation (order 2) of x_a and x_c"));
    if (out && (json_object_set_new(out, "section", section_json(ring)) != 0 ||
                json_object_set_new(out, "free_shape",
                                    free_shape_json(fr->free_shape != NULL, ring, res)) != 0 ||
                json_object_set_new(out, "free_shape_model", rd_free_shape_model(scene)) != 0 ||
                rd_free_run_result(out, fr) != 0)) {
        json_decref(out);
        out = NULL;
    }
out:
    free(rx);
    free(ry);
    return out;
}

static int run(const rd_scene *s, const rd_monitor *mon, json_t **out, rd_error *err)
{
    const struct rd_static_scene *o = s->opts;
    rd_pretension_result res;
    memset(&res, 0, sizeof res);
    double t0 = rd_clock_s();
    rd_ring_params sr = s->ring; /* a general section's J computed once, here */
    size_t m = rd_error_enter(err, "/ring");
    int rc =
        sr.section >= RD_SECTION_TAPER_FACE
            ? rd_section_spec_solve(sr.section, &sr.spec, sr.radial_width, sr.axial_height, err)
            : RD_OK;
    rd_error_leave(err, m);
    rd_free_run fr; /* the ring, fitted first to a measured free shape */
    if (rc == RD_OK)
        rc = rd_free_run_prepare(s, &sr, &o->statics, mon, &fr, err);
    const rd_ring_params *ring = &fr.ring;
    rd_pretension_opts po = o->pretension;
    po.free_shape = fr.free_shape;
    if (rc == RD_OK)
        rc = rd_pretension_solve(ring, s->segments, &po, &o->statics, mon, &res, err);
    if (rc == RD_OK)
        *out = pretension_result(s, &fr, &res, rd_clock_s() - t0);
    rd_pretension_result_cleanup(&res);
    return rc;
}

static const rd_csv_column csv_columns[] = {
    {"angle_deg", "angle_deg", 0},
    {"x_m", "x", 0},
    {"y_m", "y", 0},
    {"z_m", "z", 0},
    {"reference_x_m", "reference_x", 0},
    {"reference_y_m", "reference_y", 0},
    {NULL, NULL, 0},
};
static const rd_csv_table csv = {"shape", NULL, csv_columns};

static const char *const result_keys[] = {"analysis",
                                          "scene",
                                          "gap_opening_inner",
                                          "lateral_opening",
                                          "gap_opening_neutral",
                                          "free_gap_formula",
                                          "conformability",
                                          "support",
                                          "shape",
                                          "numerics",
                                          "warnings",
                                          "section",
                                          "free_shape",
                                          "free_shape_model",
                                          "free_shape_fit",
                                          NULL};

const rd_analysis_def rd_an_pretension = {
    .name = "pretension",
    .scene = &scene_block,
    .opts_size = sizeof(struct rd_static_scene),
    .defaults = rd_static_scene_defaults,
    .finish = finish,
    .run = run,
    .csv = &csv,
    .page = "pretension.js",
    .result_keys = result_keys,
    .general_sections = 1,
    .free_shapes = 1,
};
