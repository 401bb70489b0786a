/*
 * rd_lube_json — the lubrication block of a result (rd_lube_json.h).
 */
#include "rd_lube_json.h"

#include <jansson.h>

#include "rd_json.h"

static const char *const regime_names[] = {"hydrodynamic", "mixed", "boundary"};

json_t *rd_result_lube(const rd_lift_lube *lb, int N, const char *method)
{
    json_t *reg = json_array();
    for (int k = 0; reg && k < N; k++)
        if (json_array_append_new(reg, json_string(regime_names[lb->regime[k]])))
            return json_decref(reg), NULL;
    json_t *angle =
        lb->min_film_angle_deg ? rd_result_reals(lb->min_film_angle_deg, N, 1, 1.0) : json_null();
    return json_pack(
        "{s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:{s:o, s:o}, s:o, s:I, s:o, s:i, "
        "s:o, s:o, s:i, s:{s:o, s:o, s:i, s:o}, s:o, s:o, s:s}",
        "min_film_m", rd_result_reals(lb->min_film, N, 1, 1.0), "hydrodynamic_friction_n",
        rd_result_reals(lb->hydrodynamic_friction, N, 1, 1.0), "asperity_friction_n",
        rd_result_reals(lb->asperity_friction, N, 1, 1.0), "friction_power_w",
        rd_result_reals(lb->power, N, 1, 1.0), "asperity_share",
        rd_result_reals(lb->asperity_share, N, 1, 1.0), "regime", reg, "friction_work_j",
        rd_result_reals(lb->friction_work, lb->cycles, 1, 1.0), "fmep_pa",
        rd_result_reals(lb->fmep, lb->cycles, 1, 1.0), "min_film_at_m",
        rd_result_real(lb->min_film_x), "composite_roughness_m",
        rd_result_real(lb->composite_sigma), "viscosity_pa_s", "min",
        rd_result_real(lb->viscosity_min), "max", rd_result_real(lb->viscosity_max),
        "film_step_deg", rd_result_real(lb->film_step_deg), "film_solves",
        (json_int_t)lb->film_solves, "periodic_change", rd_result_real(lb->periodic_change),
        "held_steps", lb->held, "film_error", rd_result_real(lb->film_error), "friction_work_error",
        rd_result_real(lb->work_error), "films", lb->films, "film_load_n_per_m", "min",
        rd_result_real(lb->load_min), "max", rd_result_real(lb->load_max), "depths",
        lb->load_depths, "depth_error", rd_result_real(lb->load_depth_error), "min_film_angle_deg",
        angle, "film_interpolation_error", rd_result_real(lb->interp_check), "method", method);
}
