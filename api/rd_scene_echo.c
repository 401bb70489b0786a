/*
 * rd_scene_echo — a parsed scene as JSON (rd_scene.h): its analysis' name,
 * the echo (every field its analysis reads, defaults filled, written by the
 * tables) and the echo's text.  Below the registry: the analyses' runners
 * call it for their result's "scene", so it must not reach the list of
 * analyses (rd_scene.c, which parses, does).
 */
#include <jansson.h>
#include <stdlib.h>

#include "rd_dtoa.h"
#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"
#include "rd_schema.h"

const char *rd_scene_analysis(const rd_scene *scene)
{
    return scene->an ? scene->an->name : "unknown";
}

json_t *rd_scene_echo_analysis(const rd_scene *scene)
{
    return json_string(rd_scene_analysis(scene));
}

json_t *rd_scene_echo(const rd_scene *s)
{
    json_t *o = json_object();
    if (o && rd_schema_echo(s->an->scene, s, o) != 0) {
        json_decref(o);
        o = NULL;
    }
    return o;
}

/* 1 when every real in `v` reads back unchanged from RD_SCENE_REAL_DIGITS
 * significant digits (as jansson writes it: %.*g). */
static int reals_round_trip(json_t *v)
{
    if (json_is_real(v)) {
        char text[RD_DTOA_SIZE];
        rd_dtoa_digits(json_real_value(v), RD_SCENE_REAL_DIGITS, text); /* printf's %.15g */
        return strtod(text, NULL) == json_real_value(v);
    }
    const char *key;
    json_t *child;
    size_t i;
    if (json_is_object(v)) {
        json_object_foreach(v, key, child)
        {
            if (!reals_round_trip(child))
                return 0;
        }
    }
    if (json_is_array(v)) {
        json_array_foreach(v, i, child)
        {
            if (!reals_round_trip(child))
                return 0;
        }
    }
    return 1;
}

int rd_scene_real_digits(json_t *v)
{
    return reals_round_trip(v) ? RD_SCENE_REAL_DIGITS : 17;
}

/* The echo is a scene that parses back into the same scene: a value that
 * 15 digits would round (0.49999999999999994 to 0.5, out of its range),
 * found by tests/fuzz, makes the whole echo use 17, which always
 * round-trips. */
char *rd_scene_to_json(const rd_scene *scene)
{
    json_t *echo = rd_scene_echo(scene);
    int digits = rd_scene_real_digits(echo);
    char *text = echo ? rd_json_dumps(echo, digits, 0) : NULL;
    json_decref(echo);
    return text;
}
