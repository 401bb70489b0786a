/*
 * test_section_outline — the pretension result's section.outline_m is the
 * polygon its properties are integrated over: for a rectangle, a circle
 * and the general shapes (taper face, inner bevel, inner step, keystone,
 * polygon), the outline's area and centroid by the shoelace formula written
 * here against the result's area_m2 and centroid_m (radius: the inner
 * radius D/2 - b plus the outline's radial centroid; height above the
 * bottom) to 1e-9 (the result's 10 digits), the circle's 48-gon against its closed form
 * (48/(2 pi)) sin(2 pi / 48) of the circle's area; counter-clockwise
 * (positive area), inside the b x h box.
 */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_api.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static json_t *section_of(const char *ring)
{
    char scene[1024];
    snprintf(scene, sizeof scene,
             "{\"analysis\": \"pretension\", \"ring\": %s, \"discretization\": {\"segments\": "
             "20}, \"numerics\": {\"error_estimate\": false}}",
             ring);
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    char *out = NULL;
    int rc = rd_scene_parse(scene, strlen(scene), &s, &err);
    rc = rc != RD_OK ? rc : rd_scene_run(s, NULL, &out, &err);
    CHECK(rc == RD_OK, "%s: %s at %s", ring, err.message, err.path);
    json_t *r = out ? json_loads(out, 0, NULL) : NULL;
    free(out);
    rd_scene_free(s);
    json_t *sec = json_incref(json_object_get(r, "section"));
    json_decref(r);
    return sec;
}

static double num(json_t *a, size_t i, size_t k)
{
    return json_number_value(json_array_get(json_array_get(a, i), k));
}

/* area_ratio: the outline's area over the result's (1, or the 48-gon's). */
static void check(const char *what, const char *ring, double b, double h, double D,
                  double area_ratio)
{
    json_t *sec = section_of(ring), *o = json_object_get(sec, "outline_m");
    size_t n = json_array_size(o);
    CHECK(n >= 3, "%s: an outline of %zu points", what, n);
    double A = 0.0, Su = 0.0, Sv = 0.0;
    int inside = 1;
    for (size_t i = 0; i < n; i++) {
        double u0 = num(o, i, 0), v0 = num(o, i, 1);
        double u1 = num(o, (i + 1) % n, 0), v1 = num(o, (i + 1) % n, 1);
        double c = u0 * v1 - u1 * v0;
        A += 0.5 * c;
        Su += (u0 + u1) * c / 6.0;
        Sv += (v0 + v1) * c / 6.0;
        inside &= u0 >= -1e-15 && u0 <= b + 1e-15 && v0 >= -1e-15 && v0 <= h + 1e-15;
    }
    double area = json_number_value(json_object_get(sec, "area_m2"));
    json_t *c = json_object_get(sec, "centroid_m");
    CHECK(A > 0.0 && inside, "%s: counter-clockwise inside the %g x %g box", what, b, h);
    CHECK_REL(A, area * area_ratio, 1e-9, "%s: the outline's area", what);
    if (area_ratio == 1.0) {
        CHECK_REL(0.5 * D - b + Su / A, json_number_value(json_array_get(c, 0)), 1e-9,
                  "%s: centroid radius", what);
        CHECK_REL(Sv / A, json_number_value(json_array_get(c, 1)), 1e-9, "%s: centroid height",
                  what);
    }
    printf("%s: %zu points, area %.6g m^2 (result %.6g)\n", what, n, A, area);
    json_decref(sec);
}

int main(void)
{
    const double D = 0.0765, b = 0.0029, h = 0.0012;
    check("rectangle", "{\"section\": \"rectangle\"}", b, h, D, 1.0);
    check("circle",
          "{\"section\": \"circle\", \"radial_width\": 0.002, \"axial_height\": 0.002, "
          "\"tangential_force\": 2}",
          0.002, 0.002, D, 48.0 / (2.0 * M_PI) * sin(2.0 * M_PI / 48.0));
    check("taper face", "{\"section\": {\"shape\": \"taper_face\", \"angle_deg\": 2}}", b, h, D,
          1.0);
    check("inner bevel",
          "{\"section\": {\"shape\": \"inner_bevel\", \"side\": \"top\", \"width_m\": 0.0006, "
          "\"height_m\": 0.0004}}",
          b, h, D, 1.0);
    check("inner step",
          "{\"section\": {\"shape\": \"inner_step\", \"side\": \"bottom\", \"width_m\": 0.0005, "
          "\"height_m\": 0.0003}}",
          b, h, D, 1.0);
    check("keystone", "{\"section\": {\"shape\": \"keystone\", \"angle_deg\": 6}}", b, h, D, 1.0);
    check("polygon",
          "{\"section\": {\"shape\": \"polygon\", \"points_m\": [[0, 0], [0.0029, 0.0001], "
          "[0.0029, 0.0012], [0.0004, 0.0012], [0, 0.0008]]}}",
          b, h, D, 1.0);
    return check_done();
}
