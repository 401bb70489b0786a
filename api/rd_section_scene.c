/*
 * rd_section_scene — /ring/section in the api: "rectangle", "circle", or a
 * general shape as an object (issue 46's names):
 *   {"shape": "taper_face",  "angle_deg": a}
 *   {"shape": "inner_bevel" | "inner_step", "side": "top" | "bottom",
 *    "width_m": w, "height_m": t}
 *   {"shape": "keystone", "angle_deg": a, "double": true | false,
 *    "side": "top" | "bottom" (single only)}
 *   {"shape": "polygon", "points_m": [[radial, axial], ...]}
 * A key the shape does not read is refused, naming it; so is a general
 * shape in an analysis whose registry entry does not read them
 * (rd_analysis_def.general_sections).  Core checks the values
 * (rd_section_outline, through rd_ring_validate).
 */
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"

/* Indexed by enum rd_section_shape. */
static const char *const shape_names[] = {"rectangle",  "circle",   "taper_face", "inner_bevel",
                                          "inner_step", "keystone", "polygon",    NULL};
static const char *const side_names[] = {"top", "bottom", NULL};

/* The keys each general shape reads, besides "shape". */
static const char *reads(int shape)
{
    switch (shape) {
    case RD_SECTION_TAPER_FACE:
        return " angle_deg ";
    case RD_SECTION_INNER_BEVEL:
    case RD_SECTION_INNER_STEP:
        return " side width_m height_m ";
    case RD_SECTION_KEYSTONE:
        return " angle_deg double side ";
    default:
        return " points_m ";
    }
}

static int index_of(const char *const *names, const char *s)
{
    for (int k = 0; s && names[k]; k++)
        if (strcmp(names[k], s) == 0)
            return k;
    return -1;
}

static int number(json_t *o, const char *key, const char *path, double *out, int need,
                  rd_error *err)
{
    char at[RD_ERROR_PATH_MAX];
    json_t *v = json_object_get(o, key);
    rd_schema_path_join(at, sizeof at, path, key);
    if (!v)
        return need ? rd_error_set(err, RD_EINVAL, at, "%s is missing: this shape needs it.", at)
                    : RD_OK;
    if (!json_is_number(v))
        return rd_schema_type_error(err, at, "a number", v);
    *out = json_number_value(v);
    return RD_OK;
}

static int points(json_t *o, const char *path, rd_section_spec *sp, rd_error *err)
{
    char at[RD_ERROR_PATH_MAX];
    json_t *v = json_object_get(o, "points_m"), *pt;
    size_t i;
    rd_schema_path_join(at, sizeof at, path, "points_m");
    if (!v)
        return rd_error_set(err, RD_EINVAL, at, "%s is missing: a polygon needs its points.", at);
    if (!json_is_array(v) || json_array_size(v) < 3 || json_array_size(v) > RD_SECTION_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, at,
                            "%s must be an array of 3 to %d points [radial, axial] (m).", at,
                            RD_SECTION_POINTS_MAX);
    json_array_foreach(v, i, pt)
    {
        if (!json_is_array(pt) || json_array_size(pt) != 2 ||
            !json_is_number(json_array_get(pt, 0)) || !json_is_number(json_array_get(pt, 1)))
            return rd_error_set(err, RD_EINVAL, at,
                                "%s/%zu must be a point [radial, axial] of two numbers (m).", at,
                                i);
        sp->points[i][0] = json_number_value(json_array_get(pt, 0));
        sp->points[i][1] = json_number_value(json_array_get(pt, 1));
    }
    sp->n_points = (int)json_array_size(v);
    return RD_OK;
}

/* The keys of the object: known, and read by its shape. */
static int keys(json_t *o, int shape, const char *path, rd_error *err)
{
    const char *key;
    json_t *x;
    json_object_foreach(o, key, x)
    {
        char at[RD_ERROR_PATH_MAX], pad[64];
        rd_schema_path_join(at, sizeof at, path, key);
        snprintf(pad, sizeof pad, " %.60s ", key);
        if (strcmp(key, "shape") == 0 || strstr(reads(shape), pad))
            continue;
        if (strstr(" side width_m height_m angle_deg double points_m ", pad))
            return rd_error_set(err, RD_EINVAL, at,
                                "%s is not read by the %s shape (it reads:%s): remove it.", at,
                                shape_names[shape], reads(shape));
        return rd_error_set(err, RD_EINVAL, at,
                            "unknown field \"%.60s\" in %s (known: shape, side, width_m, "
                            "height_m, angle_deg, double, points_m)",
                            key, path);
    }
    return RD_OK;
}

static int fields(json_t *o, int shape, const char *path, rd_section_spec *sp, rd_error *err)
{
    char at[RD_ERROR_PATH_MAX];
    json_t *side = json_object_get(o, "side"), *dbl = json_object_get(o, "double");
    if (dbl && !json_is_boolean(dbl)) {
        rd_schema_path_join(at, sizeof at, path, "double");
        return rd_schema_type_error(err, at, "true or false", dbl);
    }
    sp->double_sided = json_is_true(dbl);
    if (side) {
        rd_schema_path_join(at, sizeof at, path, "side");
        sp->side = index_of(side_names, json_string_value(side));
        if (sp->side < 0)
            return rd_schema_type_error(err, at, "one of \"top\", \"bottom\"", side);
        if (sp->double_sided)
            return rd_error_set(err, RD_EINVAL, at,
                                "%s is not read by a double keystone (both flanks): remove it.",
                                at);
    }
    int rc = RD_OK;
    if (shape == RD_SECTION_POLYGON)
        return points(o, path, sp, err);
    if (shape == RD_SECTION_TAPER_FACE || shape == RD_SECTION_KEYSTONE)
        return number(o, "angle_deg", path, &sp->angle_deg, 1, err);
    rc = number(o, "width_m", path, &sp->width, 1, err);
    return rc != RD_OK ? rc : number(o, "height_m", path, &sp->height, 1, err);
}

int rd_section_parse(const rd_field *f, json_t *v, const char *path, rd_scene *s, rd_error *err)
{
    (void)f;
    memset(&s->ring.spec, 0, sizeof s->ring.spec);
    int shape = json_is_string(v) ? index_of(shape_names, json_string_value(v)) : -1;
    if (shape == RD_SECTION_RECTANGLE || shape == RD_SECTION_CIRCLE) {
        s->ring.section = shape;
        return RD_OK;
    }
    json_t *name = json_object_get(v, "shape");
    shape = json_is_object(v) ? index_of(shape_names, json_string_value(name)) : -1;
    if (!json_is_object(v) || shape < RD_SECTION_TAPER_FACE) {
        char at[RD_ERROR_PATH_MAX];
        if (json_is_object(v))
            rd_schema_path_join(at, sizeof at, path, "shape");
        return rd_schema_type_error(
            err, json_is_object(v) ? at : path,
            json_is_object(v) ? "one of \"taper_face\", \"inner_bevel\", \"inner_step\", "
                                "\"keystone\", \"polygon\""
                              : "one of \"rectangle\", \"circle\", or an object {\"shape\": "
                                "\"taper_face\" | \"inner_bevel\" | \"inner_step\" | \"keystone\" "
                                "| \"polygon\", ...}",
            json_is_object(v) ? (name ? name : json_null()) : v);
    }
    if (!s->an->general_sections)
        return rd_error_set(err, RD_EINVAL, path,
                            "%s: a %s section is read by the pretension analysis only (its "
                            "properties and its turned principal axes); the %s analysis models "
                            "\"rectangle\" and \"circle\" sections (their mass, faces and "
                            "contacts): give one of those.",
                            path, shape_names[shape], s->an->name);
    int rc = keys(v, shape, path, err);
    rc = rc != RD_OK ? rc : fields(v, shape, path, &s->ring.spec, err);
    if (rc == RD_OK)
        s->ring.section = shape;
    return rc;
}

json_t *rd_section_echo(const rd_scene *s)
{
    const rd_ring_params *p = &s->ring;
    const rd_section_spec *sp = &p->spec;
    int shape = p->section;
    if (shape < RD_SECTION_TAPER_FACE || shape >= RD_SECTION_SHAPES)
        return json_string(shape == RD_SECTION_CIRCLE ? "circle" : "rectangle");
    json_t *o = json_pack("{s:s}", "shape", shape_names[shape]);
    int bad = !o;
    if (!bad && shape == RD_SECTION_POLYGON) {
        json_t *a = json_array();
        for (int i = 0; a && i < sp->n_points; i++)
            json_array_append_new(a, json_pack("[o, o]", rd_result_real(sp->points[i][0]),
                                               rd_result_real(sp->points[i][1])));
        bad |= json_object_set_new(o, "points_m", a);
    } else if (!bad && (shape == RD_SECTION_TAPER_FACE || shape == RD_SECTION_KEYSTONE)) {
        bad |= json_object_set_new(o, "angle_deg", rd_result_real(sp->angle_deg));
        if (shape == RD_SECTION_KEYSTONE)
            bad |= json_object_set_new(o, "double", json_boolean(sp->double_sided));
    } else if (!bad) {
        bad |= json_object_set_new(o, "width_m", rd_result_real(sp->width));
        bad |= json_object_set_new(o, "height_m", rd_result_real(sp->height));
    }
    if (!bad && (shape == RD_SECTION_INNER_BEVEL || shape == RD_SECTION_INNER_STEP ||
                 (shape == RD_SECTION_KEYSTONE && !sp->double_sided)))
        bad |= json_object_set_new(o, "side", json_string(side_names[sp->side]));
    if (bad) {
        json_decref(o);
        o = NULL;
    }
    return o;
}
