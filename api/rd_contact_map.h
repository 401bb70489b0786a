/*
 * rd_contact_map — the contact analysis' bore maps in the api
 * (rd_bore_map.h): the rows of /bore/layers, /bore/points and
 * /contact/height with their hooks, the scene's checks, and the result
 * pieces (the bore at the height, the fit, the layers table).  Used by
 * rd_an_contact.c, and for /bore/layers by rd_an_lift.c; the state is
 * struct rd_contact_map_scene (rd_registry.h) in the analysis' options.
 */
#ifndef RD_CONTACT_MAP_H
#define RD_CONTACT_MAP_H

#include "rd_registry.h"

struct json_t;

/* One Fourier term of the contact bore's distortion (/bore/distortion and
 * each layer's). */
extern const rd_block rd_block_contact_distortion;

/* The rows, for the contact scene's tables (ST is offsetof into struct
 * rd_static_scene). */
#define RD_CONTACT_MAP_BORE_ROWS(ST)                                                              \
    {"layers",                                                                                    \
     RD_F_CUSTOM,                                                                                 \
     ST(map.layers_given),                                                                        \
     .block = &rd_block_bore_layer,                                                               \
     RD_MIN(1),                                                                                   \
     RD_MAX(RD_BORE_LAYERS_MAX),                                                                  \
     .parse = rd_contact_map_parse_layers,                                                        \
     .echo = rd_contact_map_echo_layers,                                                          \
     .desc = "The bore as layers down its height (a bore card): 1 to 50 {z, diameter, "           \
             "distortion}, z strictly increasing; linear in z between them. With layers or "      \
             "points, /contact/height is needed and /bore/distortion is refused; /bore/diameter " \
             "is the diameter of layers that give none."},                                        \
    {                                                                                             \
        "points", RD_F_OPTBLOCK, ST(map.points_given), .block = &rd_block_bore_points             \
    }
#define RD_CONTACT_MAP_HEIGHT_ROW(ST)                                                            \
    {                                                                                            \
        "height", RD_F_CUSTOM, ST(map.height_given),                                             \
            .parse = rd_contact_map_parse_height, .echo = rd_contact_map_echo_height,            \
            .extra = "{\"oneOf\": [{\"type\": \"number\", \"minimum\": 0, \"maximum\": 10}, "    \
                     "{\"type\": \"string\", \"enum\": [\"all\"]}]}",                            \
            .desc = "With /bore/layers or /bore/points: the height (m, down from the top of "    \
                    "the bore, within the first and last layers) the ring sits at, or \"all\": " \
                    "a contact at every layer, reported as the `layers` table (the full result " \
                    "is the layer with the largest light gap). Refused without a bore map."      \
    }

/* /bore/points' rows (AT is offsetof into the analysis' options, whose
 * struct rd_contact_map_scene is `map`): contact's block, lift's and the
 * ring pack's. */
#define RD_BORE_POINTS_FIELDS(AT)                                                                 \
    {"theta_deg",                                                                                 \
     RD_F_TABLE,                                                                                  \
     AT(map.points[0]),                                                                           \
     RD_MIN(1),                                                                                   \
     RD_MAX(RD_BORE_POINTS_MAX),                                                                  \
     .required = 1,                                                                               \
     .desc = "Angle of each point, deg from the gap middle, -720 to 720."},                       \
        {"z",                                                                                     \
         RD_F_TABLE,                                                                              \
         AT(map.points[1]),                                                                       \
         RD_MIN(1),                                                                               \
         RD_MAX(RD_BORE_POINTS_MAX),                                                              \
         .required = 1,                                                                           \
         .desc = "Height of each point, m, down from the top of the bore: points of equal z are " \
                 "one layer (at most 50 layers)."},                                               \
        {"dr",                                                                                    \
         RD_F_TABLE,                                                                              \
         AT(map.points[2]),                                                                       \
         RD_MIN(1),                                                                               \
         RD_MAX(RD_BORE_POINTS_MAX),                                                              \
         .required = 1,                                                                           \
         .desc = "The radius' departure from /bore/diameter / 2 (or the ring's) at each point, "  \
                 "m, outward positive; |dr| at most 1 % of the ring diameter."},                  \
    {                                                                                             \
        "fit_order", RD_F_INTEGER, AT(map.fit_order), RD_MIN(0), RD_MAX(RD_BORE_ORDERS_MAX),      \
            .desc = "Highest Fourier order K fitted per layer by least squares (with the "        \
                    "layer's mean radius); needs 2K + 1 points at distinct angles in every "      \
                    "layer. The result's bore_fit gives the layers and the residual."             \
    }

/* /bore/points' description in lift and the ring pack (read with ring_z_tdc_m). */
#define RD_BORE_POINTS_DESC                                                                \
    "The bore map as measured points instead of layers (not both), fitted per layer (the " \
    "result's bore_fit gives the layers and the residual); read with ring_z_tdc_m, as "    \
    "layers are."

extern const rd_block rd_block_bore_layer;  /* one layer {z, diameter, distortion} */
extern const rd_block rd_block_bore_points; /* /bore/points */

/* /bore/layers into the struct rd_contact_map_scene whose layers_given is at
 * the field's offset in the analysis' options (contact's and lift's). */
int rd_contact_map_parse_layers(const rd_field *f, struct json_t *v, const char *path,
                                struct rd_scene *s, rd_error *err);
/* The layers of m as a scene gives them (a new reference; NULL on out of memory). */
struct json_t *rd_bore_layers_json(const struct rd_scene *s, const rd_bore_map *m);
struct json_t *rd_contact_map_echo_layers(const struct rd_scene *s);
int rd_contact_map_parse_height(const rd_field *f, struct json_t *v, const char *path,
                                struct rd_scene *s, rd_error *err);
struct json_t *rd_contact_map_echo_height(const struct rd_scene *s);

/* /bore/ring_z_tdc_m of lift and the ring pack: the (top) ring's depth
 * below the top of the bore at TDC, m, read with /bore/layers. */
struct rd_ring_depth {
    int given;
    double z;
};
/* Into the struct rd_ring_depth whose `given` is at the field's offset in
 * the analysis' options. */
int rd_ring_depth_parse(const rd_field *f, struct json_t *v, const char *path, struct rd_scene *s,
                        rd_error *err);
/* Lift's and the ring pack's map: /bore/layers or /bore/points (fitted,
 * rings of diameter d about the bore's D) and /bore/ring_z_tdc_m each
 * given with the other (`who`: whose depth, for the message); the layers'
 * diameters default to D (echoed as used); *map the map, or NULL. */
int rd_ring_depth_finish(struct rd_contact_map_scene *m, const struct rd_ring_depth *rz, double d,
                         double D, const char *who, const rd_bore_map **map, rd_error *err);
/* /bore/points fitted per layer into m->map (allocated; rings of diameter
 * d about the bore's D): core's checks and fit (rd_bore_map.h). */
int rd_bore_map_of_points(struct rd_contact_map_scene *m, double d, double D, rd_error *err);
/* With /bore/points: the result's bore_fit {residual_rms_m, layers}; NULL
 * without points (or out of memory). */
struct json_t *rd_bore_fit_json(const struct rd_scene *s, const struct rd_contact_map_scene *m);

/* After the plain bore's checks: the map's rules (named in each message),
 * the fit of the points, and the bore at the height. */
int rd_contact_map_finish(struct rd_scene *s, rd_error *err);
/* Frees what the map state holds. */
void rd_contact_map_cleanup(struct rd_contact_map_scene *m);

/* Runs the scene's contact: the plain bore, the bore at the height, or
 * (height "all") every layer.  *out is the result object from `build`
 * for the solve reported (the layer with the largest light gap for
 * "all"), with the map's pieces added: height_m, bore_at_height,
 * bore_fit {residual_rms_m, layers}, layers [...].  NULL *out on success
 * means out of memory.  `ring` and `fs` are the ring solved and its free
 * shape (rd_free_run: the scene's, or fitted to a measured free shape). */
typedef struct json_t *(*rd_contact_build)(const struct rd_scene *scene, const rd_bore *bore,
                                           const rd_contact_result *res, double wall_s);
int rd_contact_map_run(const struct rd_scene *s, const rd_ring_params *ring,
                       const rd_free_shape *fs, const rd_monitor *mon, rd_contact_build build,
                       struct json_t **out, rd_error *err);

#endif
