/*
 * rd_ringpack_json.h — the ring pack analysis' result writer
 * (rd_ringpack_json.c), private to rd_an_ringpack.c.
 */
#ifndef RD_RINGPACK_JSON_H
#define RD_RINGPACK_JSON_H

#include "rd_ringpack.h"
#include "rd_scene.h"

struct json_t;

/* The result object of a run of `p` (the scene echoed), wall_s its time. */
struct json_t *rd_ringpack_json(const rd_scene *scene, const rd_ringpack_params *p,
                                const rd_ringpack_result *r, double wall_s);

#endif
