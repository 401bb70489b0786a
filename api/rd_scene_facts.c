/*
 * rd_scene_facts — name, canonical text and predicted cost of a parsed
 * scene (rd_scene_facts.h), for the server's list, result cache and inline
 * runs.
 */
#include "rd_scene_facts.h"

#include <math.h>

#include <jansson.h>

#include "rd_json.h"
#include "rd_registry.h"
#include "rd_scene.h"

const char *rd_scene_name(const rd_scene *scene)
{
    return scene->name;
}

char *rd_scene_canonical_json(const rd_scene *scene)
{
    json_t *echo = rd_scene_echo(scene);
    /* shortest round trip: every double prints as the one text that reads
     * back to it */
    char *text = echo ? rd_json_dumps(echo, 0, 1) : NULL;
    json_decref(echo);
    return text;
}

double rd_scene_cost_predict(const rd_scene *scene)
{
    return scene->an && scene->an->predict ? scene->an->predict(scene) : NAN;
}
