/*
 * rd_liner.c — the ring-liner law per point of the running face
 * (rd_liner_law.h has the equations).
 */
#include "rd_liner_law.h"

#include <math.h>
#include <string.h>

double rd_liner_ureg(const rd_engine_params *e)
{
    return RD_LINER_UREG_FRACTION * rd_engine_mean_speed(e);
}

void rd_liner_init(rd_liner *l, const rd_friction_params *f, double ureg, double h, double circ)
{
    l->mu_b = f->lube.boundary_coefficient;
    l->circ = circ;
    l->model = f->model;
    l->mu = f->coefficient;
    l->ureg = ureg;
    l->eta = f->viscosity;
    l->so_lim = f->sommerfeld_transition;
    l->kh = f->hydrodynamic_slope;
    l->h = h;
}

void rd_liner_eval(const rd_liner *l, const rd_liner_point *in, rd_liner_force *out)
{
    double N = in->N, u = in->u, share = in->share;
    double T = tanh(u / l->ureg), T_u = (1.0 - T * T) / l->ureg;
    if (l->model == RD_FRICTION_COULOMB) {
        out->F_N = -l->mu * T;
        out->F_u = -l->mu * N * T_u;
        out->F = -l->mu * N * T;
        return;
    }
    if (l->model == RD_FRICTION_LUBRICATED) {
        const rd_film_point *fm = in->film;
        double c = share * l->circ, Fa = l->mu_b * fm->Wa;
        out->F_N = 0.0;
        out->F_u = -c * (fm->Cc + Fa * T_u);
        out->F = c * (-fm->Cc * u + fm->Fp - Fa * T);
        return;
    }
    /* Stribeck (2.9): B = C e^{-3 r^2.5} N, r = So_lim / So; H = K eta |u| h s_k / L */
    double sg = u >= 0.0 ? 1.0 : -1.0, au = fabs(u);
    double H = l->kh * l->eta * au * l->h * share, H_u = l->kh * l->eta * l->h * share * sg;
    double B = 0.0, B_N = 0.0, B_u = 0.0;
    if (N > 0.0) {
        double r_u = l->so_lim * l->eta * l->h * share / N; /* r / |u| */
        double r = r_u * au, r15 = pow(r, 1.5), E = exp(-3.0 * r15 * r);
        B = l->mu * E * N;
        B_N = l->mu * E * (1.0 + 7.5 * r15 * r);
        B_u = -7.5 * l->mu * E * r15 * r_u * N * sg;
    }
    out->F_N = -T * B_N;
    out->F_u = -T_u * (B + H) - T * (B_u + H_u);
    out->F = -T * (B + H);
}

void rd_lube_params_default(rd_lube_params *l, rd_face_params *face)
{
    memset(l, 0, sizeof *l);
    memset(face, 0, sizeof *face);
    face->profile = RD_FACE_BARREL;
    face->crown = 5e-6;
    face->roughness_rq = 0.2e-6;
    l->vogel_a = 4.88e-5;
    l->vogel_b = 1197.0;
    l->vogel_c = 141.15;
    l->temperature_c = 100.0;
    l->asperity_density = 5e8;
    l->asperity_radius = 3e-4;
    l->boundary_coefficient = 0.1;
}

static int in_range(double v, double lo, double hi)
{
    return isfinite(v) && v >= lo && v <= hi;
}

static int check_temperature(double T, const char *path, rd_error *err)
{
    if (in_range(T, -40.0, 250.0))
        return RD_OK;
    return rd_error_set(err, RD_EINVAL, path, "@%s = %g deg C is outside [-40, 250] deg C%s.", path,
                        T,
                        T > 250.0 && T < 600.0 ? " (a temperature in kelvin? this field is in "
                                                 "deg C: subtract 273.15)"
                                               : "");
}

/* The Vogel law stays 10 K clear of its pole at T = c. */
static int check_vogel(const rd_lube_params *l, rd_error *err)
{
    if (!in_range(l->vogel_a, 1e-9, 1.0))
        return rd_error_set(err, RD_EINVAL, "/oil/vogel/a_pa_s",
                            "a_pa_s = %g is outside [1e-9, 1] Pa s.", l->vogel_a);
    if (!in_range(l->vogel_b, 0.0, 1e4))
        return rd_error_set(err, RD_EINVAL, "/oil/vogel/b_k", "b_k = %g is outside [0, 1e4] K.",
                            l->vogel_b);
    if (!in_range(l->vogel_c, 0.0, 250.0))
        return rd_error_set(err, RD_EINVAL, "/oil/vogel/c_k", "c_k = %g is outside [0, 250] K.",
                            l->vogel_c);
    double Tmin = l->temperature_c;
    for (int k = 0; k < l->temp_points; k++)
        Tmin = fmin(Tmin, l->temp_c[k]);
    if (Tmin + 273.15 - l->vogel_c < 10.0)
        return rd_error_set(err, RD_EINVAL, "/oil/vogel/c_k",
                            "the Vogel law's pole c_k = %g K is within 10 K of the lowest liner "
                            "temperature %g K: the viscosity diverges there.",
                            l->vogel_c, Tmin + 273.15);
    return RD_OK;
}

int rd_face_validate(const rd_face_params *f, rd_error *err)
{
    if (!in_range(f->crown, 0.0, 1e-4))
        return rd_error_set(err, RD_EINVAL, "/crown_m",
                            "crown_m = %g m is outside [0, 1e-4] m (the barrel's drop at the "
                            "face's edges; 0 is a flat face).",
                            f->crown);
    if (!(f->taper_deg >= 0.0 && f->taper_deg <= 5.0) ||
        (f->profile == RD_FACE_TAPER && f->taper_deg == 0.0))
        return rd_error_set(err, RD_EINVAL, "/taper_deg", "taper_deg = %g is outside (0, 5] deg.",
                            f->taper_deg);
    if (!in_range(f->edge_radius, 0.0, 1e-2))
        return rd_error_set(err, RD_EINVAL, "/edge_radius_m",
                            "edge_radius_m = %g m is outside [0, 1e-2] m.", f->edge_radius);
    if (!in_range(f->roughness_rq, 1e-9, 5e-6))
        return rd_error_set(err, RD_EINVAL, "/roughness_rq_m",
                            "roughness_rq_m = %g m is outside [1e-9, 5e-6] m (the asperity "
                            "model needs a rough face: Rq > 0).",
                            f->roughness_rq);
    return RD_OK;
}

/* The liner's roughness, in the bore's block. */
static int check_liner(double liner_rq, rd_error *err)
{
    if (!in_range(liner_rq, 1e-9, 5e-6))
        return rd_error_set(err, RD_EINVAL, "/roughness_rq_m",
                            "roughness_rq_m = %g m is outside [1e-9, 5e-6] m (the liner's Rq; "
                            "the asperity model needs Rq > 0).",
                            liner_rq);
    return RD_OK;
}

/* The oil, cavitation, supply and asperities, in the friction block. */
static int check_friction(const rd_lube_params *l, rd_error *err)
{
    int rc;
    if (l->viscosity != 0.0 && !in_range(l->viscosity, 1e-4, 10.0))
        return rd_error_set(err, RD_EINVAL, "/oil/viscosity_pa_s",
                            "viscosity_pa_s = %g is outside [1e-4, 10] Pa s%s.", l->viscosity,
                            l->viscosity > 10.0 ? " (a value in mPa s? 1 mPa s = 0.001 Pa s)" : "");
    if ((rc = check_temperature(l->temperature_c, "/oil/temperature_c", err)))
        return rc;
    for (int k = 0; k < l->temp_points; k++) {
        if ((rc = check_temperature(l->temp_c[k], "/oil/temperature_table/value_c", err)))
            return rc;
        double x = l->temp_crank_deg[k];
        if (!in_range(x, 0.0, 720.0) || (k > 0 && !(x > l->temp_crank_deg[k - 1])))
            return rd_error_set(err, RD_EINVAL, "/oil/temperature_table/crank_deg",
                                "crank_deg[%d] = %g: the angles must increase strictly within "
                                "[0, 720] deg.",
                                k, x);
    }
    if (l->viscosity == 0.0 && (rc = check_vogel(l, err)))
        return rc;
    if (l->cavitation != RD_CAVITATION_REYNOLDS && l->cavitation != RD_CAVITATION_JFO)
        return rd_error_set(err, RD_EINVAL, "/cavitation",
                            "cavitation %d is not a model: reynolds (0) or jfo (1).",
                            l->cavitation);
    if (l->supply_film != 0.0 && !in_range(l->supply_film, 1e-8, 1e-3))
        return rd_error_set(err, RD_EINVAL, "/supply/film_m",
                            "film_m = %g m is outside [1e-8, 1e-3] m (the oil film on the liner; "
                            "0 for a flooded face).",
                            l->supply_film);
    if (!in_range(l->asperity_density, 1e6, 1e14))
        return rd_error_set(err, RD_EINVAL, "/asperity/density_per_m2",
                            "density_per_m2 = %g is outside [1e6, 1e14] per m^2.",
                            l->asperity_density);
    if (!in_range(l->asperity_radius, 1e-7, 1e-2))
        return rd_error_set(err, RD_EINVAL, "/asperity/radius_m",
                            "radius_m = %g is outside [1e-7, 1e-2] m.", l->asperity_radius);
    if (!in_range(l->boundary_coefficient, 0.0, 1.0))
        return rd_error_set(err, RD_EINVAL, "/asperity/boundary_coefficient",
                            "boundary_coefficient = %g is outside [0, 1].",
                            l->boundary_coefficient);
    if (l->composite_modulus != 0.0 && !in_range(l->composite_modulus, 1e9, 1e12))
        return rd_error_set(err, RD_EINVAL, "/asperity/composite_modulus_pa",
                            "composite_modulus_pa = %g is outside [1e9, 1e12] Pa (0: from the "
                            "ring's material on cast iron).",
                            l->composite_modulus);
    return RD_OK;
}

int rd_lube_validate(const rd_lube_params *l, double liner_rq, rd_error *err)
{
    size_t m = rd_error_enter(err, "/bore");
    int rc = check_liner(liner_rq, err);
    rd_error_leave(err, m);
    if (rc)
        return rc;
    m = rd_error_enter(err, "/physics");
    rd_error_enter(err, "/friction");
    rc = check_friction(l, err);
    rd_error_leave(err, m);
    return rc;
}
