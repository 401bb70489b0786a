/*
 * test_sweep_gap — the showcase of issue 42: the 3-ring pack over gap
 * positions of its second ring (examples/sweeps/ringpack_gap_positions.json,
 * 12 positions, 8 segments per ring, 6 cycles: about 28 s a run in the
 * Release build).  To keep the sanitizer build within a minute this runs the
 * same spec cut to 3 positions (0, 45 and 90 deg), 6 segments and 2 cycles:
 * a check of the machinery on the ring pack, not of the physics (2 cycles
 * are a transient, and the example's own description says what its range
 * means).  Checked: min < max, mean between them, and the over table's min
 * and max are bit for bit the blow-by of separate single runs of the scene
 * with the gap at argmin and at argmax.
 *
 *   test_sweep_gap EXAMPLES_DIR
 */
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_api.h"
#include "rd_jsonptr.h"
#include "rd_sweep.h"

/* The blow-by (L/min) of the base scene with the second ring's gap at `gap`. */
static double single_run(json_t *base, json_t *gap)
{
    json_t *scene = json_deep_copy(base);
    rd_jsonptr_set(scene, "/rings/1/gap_angle_deg", json_deep_copy(gap));
    char *text = json_dumps(scene, JSON_COMPACT | JSON_REAL_PRECISION(17)), *result = NULL;
    rd_error err;
    rd_error_init(&err);
    rd_scene *sc = NULL;
    int rc = rd_scene_parse(text, strlen(text), &sc, &err);
    if (rc == RD_OK)
        rc = rd_scene_run(sc, NULL, &result, &err);
    CHECK(rc == RD_OK, "single run at gap %g: %s", json_number_value(gap), err.message);
    json_t *r = result ? json_loads(result, 0, NULL) : NULL;
    double x = json_number_value(rd_jsonptr_get(r, "/blowby/l_per_min"));
    json_decref(r);
    free(result);
    rd_scene_free(sc);
    free(text);
    json_decref(scene);
    return x;
}

int main(int argc, char **argv)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/sweeps/ringpack_gap_positions.json", argc > 1 ? argv[1] : ".");
    json_error_t jerr;
    json_t *spec = json_load_file(path, 0, &jerr);
    CHECK(spec != NULL, "%s: %s", path, jerr.text);
    if (!spec)
        return check_done();
    json_t *base = json_object_get(spec, "base");
    CHECK(json_integer_value(rd_jsonptr_get(spec, "/over/range/count")) == 12,
          "the example runs 12 gap positions");
    for (int i = 0; i < 2; i++)
        json_object_set_new(json_array_get(json_object_get(base, "rings"), (size_t)i), "segments",
                            json_integer(6));
    json_object_set_new(json_object_get(base, "engine"), "cycles", json_integer(2));
    json_object_set_new(
        spec, "over",
        json_pack("{s:s, s:[i,i,i]}", "path", "/rings/1/gap_angle_deg", "values", 0, 45, 90));
    char *text = json_dumps(spec, JSON_COMPACT | JSON_REAL_PRECISION(17)), *row = NULL;
    rd_error err;
    rd_error_init(&err);
    rd_sweep *s = NULL;
    int rc = rd_sweep_parse(text, strlen(text), 100, &s, &err);
    CHECK(rc == RD_OK && rd_sweep_points(s) == 1 && rd_sweep_runs_per_point(s) == 3,
          "the spec parses: 1 point, 3 runs (%s)", err.message);
    if (rc == RD_OK)
        rc = rd_sweep_run_point(s, 0, NULL, &row, &err);
    json_t *r = row ? json_loads(row, 0, NULL) : NULL;
    /* columns: min, max, mean, argmin, argmax of /blowby/l_per_min, of
     * /blowby/kg_per_cycle, then status and error */
    const char *status = json_string_value(json_array_get(r, 10));
    CHECK(status && strcmp(status, "ok") == 0, "the point is ok: %s", row ? row : err.message);
    if (status && strcmp(status, "ok") == 0) {
        double lo = json_number_value(json_array_get(r, 0)),
               hi = json_number_value(json_array_get(r, 1)),
               mean = json_number_value(json_array_get(r, 2));
        printf("blow-by over gap positions 0, 45, 90 deg: %.10g .. %.10g L/min (mean %.10g), "
               "min at %g deg, max at %g deg\n",
               lo, hi, mean, json_number_value(json_array_get(r, 3)),
               json_number_value(json_array_get(r, 4)));
        CHECK(lo < hi && lo <= mean && mean <= hi, "a range: min %.10g < max %.10g", lo, hi);
        CHECK(!json_equal(json_array_get(r, 3), json_array_get(r, 4)), "argmin and argmax differ");
        double at_lo = single_run(base, json_array_get(r, 3)),
               at_hi = single_run(base, json_array_get(r, 4));
        CHECK(at_lo == lo, "min %.17g = the single run at argmin %.17g", lo, at_lo);
        CHECK(at_hi == hi, "max %.17g = the single run at argmax %.17g", hi, at_hi);
    }
    json_decref(r);
    free(row);
    free(text);
    rd_sweep_free(s);
    json_decref(spec);
    return check_done();
}
