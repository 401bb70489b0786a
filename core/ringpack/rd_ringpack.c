/*
 * rd_ringpack.c — the ring pack's parameters, validation and model: the gas
 * network's volumes and passages, the rings' forces and the right-hand side
 * (equations and state layout in rd_ringpack.h; the CVODE driver is
 * rd_ringpack_driver.c).
 */
#include "rd_ringpack.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_internal.h"
#include "rd_lift_internal.h"
#include "rd_ringpack_model.h"

#define GRAVITY 9.80665

void rd_ringpack_params_default(rd_ringpack_params *p)
{
    memset(p, 0, sizeof *p);
    p->engine.speed_rpm = 2400.0;
    p->engine.crank_radius = 0.04345;
    p->engine.rod_length = 0.130;
    p->engine.kinematics = RD_KINEMATICS_EXACT;
    p->engine.cycles = 6.0;
    p->periodic_tolerance = RD_RINGPACK_PERIODIC_TOL;
    p->n_rings = 1;
    for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++) {
        rd_ringpack_ring *r = &p->rings[i];
        rd_ring_params_default(&r->ring);
        r->groove.axial_clearance = 3e-5;
        r->groove.radial_clearance = 5e-4;
        r->land_height = 0.004;
        r->land_clearance = 3e-4;
        r->discharge_coefficient = 0.7;
        r->pinned = RD_PIN_FREE;
        r->model = RD_LIFT_MODEL_AUTO;
        r->segments = 20;
        r->kind = RD_RING_COMPRESSION;
        r->leak_area = RD_RINGPACK_OIL_LEAK;
    }
    p->cylinder_kind = RD_CYLINDER_FIRED;
    p->synthetic.kind = RD_CYLINDER_FIRED;
    p->synthetic.peak_pa = 6e6;
    p->synthetic.peak_crank_deg = 15.0;
    p->synthetic.compression_ratio = 10.5;
    p->synthetic.intake_pa = 1e5;
    p->crankcase_pa = 1e5;
    p->kappa = RD_GASFLOW_KAPPA;
    p->gas_constant = RD_GASFLOW_R;
    p->gas_viscosity = 0.0; /* Sutherland */
    p->flank_passage = RD_PASSAGE_VISCOUS_LIMITED;
    p->flank_pressure = RD_FLANK_PRESSURE_LINEAR;
    p->T_lands = 450.0;
    p->T_crankcase = 380.0;
    p->gravity = 1;
    p->step_deg = 1.0;
    p->flank_band = RD_LIFT_FLANK_BAND;
    p->rtol = 1e-6;
    p->atol = 1e-9;
    p->max_steps = 2000000;
    p->estimate_error = 1;
    p->friction.model = RD_FRICTION_NONE;
    p->friction.coefficient = 0.1; /* the lift analysis' default */
    rd_lube_params_default(&p->friction.lube, &p->rings[0].face);
    for (int i = 1; i < RD_RINGPACK_RINGS_MAX; i++)
        p->rings[i].face = p->rings[0].face;
    p->bore.roughness_rq = RD_LINER_RQ_DEFAULT;
    p->film_step_deg = RD_LIFT_FILM_STEP_DEG;
    p->model = RD_LIFT_MODEL_AUTO;
}

void rd_ringpack_params_thesis(rd_ringpack_params *p)
{
    rd_ringpack_params_default(p);
    p->n_rings = 3;
    static const struct {
        double h, gap, ft, land_h, land_c, ca, gap_deg;
    } t[3] = {{0.0012, 3e-4, 10.0, 0.005, 4e-4, 3e-5, 0.0},
              {0.0015, 4e-4, 10.0, 0.004, 3e-4, 4e-5, 180.0},
              {0.0025, 3e-4, 20.0, 0.0035, 2e-4, 4e-5, 90.0}};
    for (int i = 0; i < 3; i++) {
        rd_ringpack_ring *r = &p->rings[i];
        r->ring.axial_height = t[i].h;
        r->ring.closed_gap = t[i].gap;
        r->ring.tangential_force = t[i].ft;
        r->land_height = t[i].land_h;
        r->land_clearance = t[i].land_c;
        r->groove.axial_clearance = t[i].ca;
        r->gap_angle_deg = t[i].gap_deg;
    }
    p->rings[2].kind = RD_RING_OIL;
    p->rings[2].pinned = RD_PIN_LOWER;
}

double rd_ringpack_standard_density(double R)
{
    return 101325.0 / (R * 293.15);
}

/* Ring i's entry of /rings, paths relative to it. */
static int validate_ring(const rd_ringpack_ring *r, double bore, rd_error *err)
{
    char f[RD_ERROR_PATH_MAX];
    int rc = RD_OK;
#define FIELD(key) (snprintf(f, sizeof f, "/%s", key), f)
    if (r->ring.section != RD_SECTION_RECTANGLE)
        return rd_error_set(err, RD_EINVAL, FIELD("ring/section"),
                            "@%s must be rectangle: the ring seals with its flat faces.", f);
    if (fabs(r->ring.diameter - bore) > 1e-9 * bore)
        return rd_error_set(err, RD_EINVAL, FIELD("ring/diameter"),
                            "@%s = %g m differs from the top ring's %g m: the rings of a pack "
                            "share one bore.",
                            f, r->ring.diameter, bore);
    rc =
        rc ? rc : rd_error_range(r->ring.closed_gap, 0.0, 0.01, FIELD("ring/closed_gap"), "m", err);
    if (!rc && !(r->groove.axial_clearance > 0.0))
        return rd_error_set(err, RD_EINVAL, FIELD("groove/axial_clearance"),
                            "@%s = %g m: the groove (ring height + axial clearance) must be "
                            "taller than the ring; allowed 1e-07 to 0.005 m.",
                            f, r->groove.axial_clearance);
    rc = rc ? rc
            : rd_error_range(r->groove.axial_clearance, 1e-7, 0.005,
                             FIELD("groove/axial_clearance"), "m", err);
    rc = rc ? rc
            : rd_error_range(r->groove.radial_clearance, 1e-6, 0.01,
                             FIELD("groove/radial_clearance"), "m", err);
    rc = rc ? rc
            : rd_error_range(r->discharge_coefficient, 0.0, 1.0, FIELD("discharge_coefficient"), "",
                             err);
    rc = rc ? rc
            : rd_error_range(r->gap_angle_deg, -360.0, 360.0, FIELD("gap_angle_deg"), "deg", err);
    rc = rc ? rc : rd_error_range(r->model, 0, RD_RINGPACK_AXIAL, FIELD("model"), "", err);
    rc = rc ? rc
            : rd_error_range(r->segments, 4, RD_RINGPACK_SEGMENTS_MAX, FIELD("segments"),
                             "segments", err);
    rc = rc ? rc : rd_error_range(r->modes, 0, RD_LIFT_MODES_MAX, FIELD("modes"), "modes", err);
    if (!rc && r->modes > 6 * r->segments - 6)
        return rd_error_set(err, RD_EINVAL, FIELD("modes"),
                            "@%s = %d: a ring of %d segments has %d elastic modes; allowed 0 "
                            "(automatic) to %d.",
                            f, r->modes, r->segments, 6 * r->segments - 6, 6 * r->segments - 6);
    if (!rc && !(r->land_height > 0.0 && r->land_clearance > 0.0))
        return rd_error_set(err, RD_EINVAL,
                            FIELD(r->land_height > 0.0 ? "land/radial_clearance" : "land/height"),
                            "@%s must be > 0: the land's gas volume pi h c (d - c) must be "
                            "positive (height %g m, radial clearance %g m).",
                            f, r->land_height, r->land_clearance);
    rc = rc ? rc : rd_error_range(r->land_height, 1e-5, 0.1, FIELD("land/height"), "m", err);
    rc = rc ? rc
            : rd_error_range(r->land_clearance, 1e-7, 0.25 * bore, FIELD("land/radial_clearance"),
                             "m", err);
    rc = rc ? rc
            : rd_error_range(r->end_gap_area, 0.0, 1e-4, FIELD("end_gap_area_m2"),
                             "m^2 (0: closed gap x the narrower land clearance)", err);
    rc = rc ? rc : rd_error_range(r->kind, 0, RD_RING_OIL, FIELD("kind"), "", err);
    rc = rc ? rc : rd_error_range(r->pinned, 0, RD_PIN_MIDDLE, FIELD("pinned"), "", err);
    if (!rc && r->kind == RD_RING_OIL)
        rc = rd_error_range(r->leak_area, 1e-12, 1e-4, FIELD("leak_area_m2"), "m^2", err);
    rd_section s;
    rd_section_init(&s, &r->ring);
    if (!rc && r->groove.axial_clearance >= s.h)
        return rd_error_set(err, RD_EINVAL, FIELD("groove/axial_clearance"),
                            "@%s = %g m is not smaller than the ring's height %g m: the groove "
                            "(ring height + axial clearance) would be more than twice as tall "
                            "as the ring, outside this model.",
                            f, r->groove.axial_clearance, s.h);
#undef FIELD
    return rc;
}

/* physics.gas: the gas's properties and the flank laws, paths relative
 * to the gas block. */
static int gas_validate(const rd_ringpack_params *p, rd_error *err)
{
    const char *k = "/heat_capacity_ratio", *v = "/viscosity_pa_s";
    if (!(p->kappa > 1.0 && p->kappa < 1.67))
        return rd_error_set(err, RD_EINVAL, k,
                            "@%s = %g is out of range: allowed above 1 and below 1.67 (a "
                            "monatomic gas's 5/3 is the upper limit).",
                            k, p->kappa);
    int rc = rd_error_range(p->gas_constant, 50.0, 5000.0, "/gas_constant", "J/(kg K)", err);
    if (!rc && p->gas_viscosity != 0.0 && !(p->gas_viscosity >= 1e-6 && p->gas_viscosity <= 1e-3))
        return rd_error_set(err, RD_EINVAL, v,
                            "@%s = %g Pa s is out of range: allowed 1e-06 to 0.001 Pa s, or 0 "
                            "(absent) for Sutherland's law at the passages' temperatures.",
                            v, p->gas_viscosity);
    rc = rc ? rc
            : rd_error_range(p->flank_passage, 0, RD_PASSAGE_ORIFICE, "/flank_passage", "", err);
    rc = rc ? rc
            : rd_error_range(p->flank_pressure, 0, RD_FLANK_PRESSURE_LINEAR, "/flank_pressure", "",
                             err);
    if (!rc && p->flank_pressure == RD_FLANK_PRESSURE_LINEAR &&
        p->active_area == RD_GAS_AREA_DYNAMIC)
        return rd_error_set(err, RD_EINVAL, "/flank_pressure",
                            "@/flank_pressure = linear with @/active_area "
                            "= dynamic: both set the flanks' pressure (dynamic: the lift "
                            "models' sealing-weighted half pressure); use one.");
    return rc;
}

/* Ring i at /rings/i: its ring block (rd_ring_validate), then the entry. */
static int rings_validate(const rd_ringpack_params *p, rd_error *err)
{
    if (p->n_rings < 1 || p->n_rings > RD_RINGPACK_RINGS_MAX)
        return rd_error_set(err, RD_EINVAL, "/rings", "@/rings has %d rings; allowed 1 to %d.",
                            p->n_rings, RD_RINGPACK_RINGS_MAX);
    int rc = RD_OK;
    for (int i = 0; !rc && i < p->n_rings; i++) {
        char at[16];
        snprintf(at, sizeof at, "/rings/%d", i % 10);
        size_t m = rd_error_enter(err, at);
        rd_error_enter(err, "/ring");
        rc = rd_ring_validate(&p->rings[i].ring, 0, err);
        rd_error_leave(err, m);
        rd_error_enter(err, at);
        rc = rc ? rc : validate_ring(&p->rings[i], p->rings[0].ring.diameter, err);
        rd_error_leave(err, m);
    }
    for (int i = 0; !rc && i + 1 < p->n_rings; i++) {
        if (p->rings[i].kind != RD_RING_OIL)
            continue;
        char at[16];
        snprintf(at, sizeof at, "/rings/%d", i % 10);
        size_t m = rd_error_enter(err, at);
        rc = rd_error_set(err, RD_EINVAL, "/kind",
                          "@/kind = oil: the oil-control ring must be the last ring of the pack "
                          "(it is ring %d of %d).",
                          i + 1, p->n_rings);
        rd_error_leave(err, m);
    }
    return rc;
}

/* The cylinder pressure: a table or the synthetic trace's parameters. */
static int cylinder_validate(const rd_ringpack_params *p, rd_error *err)
{
    size_t m = rd_error_enter(err, "/cylinder_pressure");
    if (p->cylinder_kind != RD_CYLINDER_TABLE)
        rd_error_enter(err, "/synthetic");
    int rc = p->cylinder_kind == RD_CYLINDER_TABLE
                 ? rd_gasflow_table_validate(p->table_points, p->table_deg, p->table_pa, err)
                 : rd_gasflow_synthetic_validate(&p->synthetic, err);
    rd_error_leave(err, m);
    return rc;
}

/* The gas block (gas_validate) under /physics. */
static int physics_gas_validate(const rd_ringpack_params *p, rd_error *err)
{
    size_t m = rd_error_enter(err, "/physics");
    rd_error_enter(err, "/gas");
    int rc = gas_validate(p, err);
    rd_error_leave(err, m);
    return rc;
}

/* /physics/friction: the coefficient, and no Stribeck law. */
static int friction_validate(const rd_ringpack_params *p, rd_error *err)
{
    size_t m = rd_error_enter(err, "/physics");
    rd_error_enter(err, "/friction");
    int rc = RD_OK;
    if (p->friction.model != RD_FRICTION_NONE)
        rc = rd_error_range(p->friction.coefficient, 0.0, 10.0, "/coefficient", "", err);
    if (!rc && p->friction.model == RD_FRICTION_STRIBECK)
        rc = rd_error_set(err, RD_EINVAL, "/model",
                          "@/model: stribeck is the lift analysis' only; the ring pack takes "
                          "coulomb or lubricated (the oil film).");
    rd_error_leave(err, m);
    return rc;
}

int rd_ringpack_validate(const rd_ringpack_params *p, rd_error *err)
{
    const rd_engine_params *e = &p->engine;
    int rc = rd_error_range_in("/output", p->step_deg, 0.01, 90.0, "/step_deg", "deg", err);
    rc = rc ? rc
            : rd_error_range_in("/output", p->flank_band, 0.0, RD_LIFT_FLANK_BAND_MAX,
                                "/flank_band", "of the axial clearance", err);
    rc = rc ? rc
            : rd_error_range_in("/numerics", (double)p->max_steps, 100.0, 1e9, "/max_steps", "",
                                err);
    size_t m = rd_error_enter(err, "/engine");
    rc = rc ? rc : rd_engine_validate(e, err);
    rc = rc ? rc : rd_error_range(e->cycles, 2.0, RD_RINGPACK_CYCLES_MAX, "/cycles", "", err);
    if (!rc && e->cycles != floor(e->cycles))
        rc = rd_error_set(err, RD_EINVAL, "/cycles",
                          "@/cycles = %g must be a whole number of cycles (2 to 50): the last "
                          "two are compared for the periodic state.",
                          e->cycles);
    rd_error_leave(err, m);
    rc = rc ? rc
            : rd_error_range_in("/numerics", p->periodic_tolerance, 1e-6, 0.1,
                                "/periodic_tolerance", "", err);
    rc = rc ? rc : rings_validate(p, err);
    rc = rc ? rc
            : rd_error_range(p->crankcase_pa, 1e3, 1e7, "/crankcase_pressure_pa", "Pa (absolute)",
                             err);
    rc = rc ? rc : physics_gas_validate(p, err);
    rc =
        rc ? rc
           : rd_error_range_in("/gas_temperature_k", p->T_lands, 200.0, 1500.0, "/lands", "K", err);
    rc = rc ? rc
            : rd_error_range_in("/gas_temperature_k", p->T_crankcase, 200.0, 1500.0, "/crankcase",
                                "K", err);
    rc = rc ? rc : rd_error_range_in("/numerics", p->rtol, 1e-12, 0.01, "/rtol", "", err);
    rc =
        rc ? rc : rd_error_range_in("/numerics", p->model, 0, RD_RINGPACK_AXIAL, "/model", "", err);
    rc = rc ? rc : friction_validate(p, err);
    rc = rc ? rc : rd_ringpack_lube_validate(p, err);
    rc = rc ? rc : rd_error_range_in("/numerics", p->atol, 1e-16, 1e-5, "/atol", "m", err);
    rc = rc ? rc : cylinder_validate(p, err);
    return rc ? rc : rd_packring_validate(p, err); /* bore, tilt, active areas */
}

/* ------------------------------------------------------------------ model */

static const char *const land_names[] = {"top_land", "second_land", "third_land"};
static const char *const groove_names[] = {"groove_1", "groove_2", "groove_3"};

/* The ring's lumped geometry (rd_ringpack.h): its flank area and mass, the
 * pretension's and the back gas's normal forces, the volumes around it. */
static void ring_geometry(rd_ringpack_model *m, int i)
{
    const rd_ringpack_ring *r = &m->p->rings[i];
    rd_section s;
    rd_section_init(&s, &r->ring);
    double d = r->ring.diameter, h_run = s.run.height, h_back = s.back.height;
    double a = r->groove.axial_clearance, c = r->land_clearance;
    /* the back face, b inside the bore; the groove back behind it */
    double r_in = 0.5 * d - s.b, r_b = r_in - r->groove.radial_clearance;
    m->ca[i] = a;
    m->area[i] = s.lower.area_ring;
    m->mass[i] = r->ring.density * s.h * m->area[i];
    m->circ[i] = M_PI * d;
    m->cd[i] = r->discharge_coefficient;
    m->gap_cd[i] = m->cd[i];
    if (r->kind == RD_RING_OIL) { /* its effective leakage, C_d included */
        m->gap_area[i] = r->leak_area;
        m->gap_cd[i] = 1.0;
    } else if (r->end_gap_area > 0.0) {
        m->gap_area[i] = r->end_gap_area;
    } else { /* the narrower of the lands above and below (the last: above) */
        double c_below = i + 1 < m->R ? m->p->rings[i + 1].land_clearance : c;
        m->gap_area[i] = r->ring.closed_gap * fmin(c, c_below);
    }
    /* the flank passages' slots: the flank's mean circumference, the
     * ring's radial width, the mean temperature of the volumes either side
     * (the upper: land and groove; the lower: groove and the volume below) */
    for (int k = 0; k < 2; k++) {
        double T_below = k == 0 || i + 1 < m->R ? m->p->T_lands : m->p->T_crankcase;
        double T = 0.5 * (m->p->T_lands + T_below), mu = m->p->gas_viscosity;
        m->slot[2 * i + k] =
            (rd_gasflow_slot){M_PI * (d - s.b), s.b, mu > 0.0 ? mu : rd_gas_viscosity(T), T};
    }
    m->n_pre[i] =
        2.0 * r->ring.tangential_force / (d * h_run) * h_run * (M_PI * d - r->ring.closed_gap);
    m->n_back[i] = h_back * 2.0 * M_PI * r_in;
    m->vol[2 * i + 1] = M_PI * r->land_height * c * (d - c);
    m->vol[2 * i + 2] =
        M_PI * (r_in * r_in - r_b * r_b) * (s.h + a) + M_PI * (0.25 * d * d - r_in * r_in) * a;
    m->temp[2 * i + 1] = m->temp[2 * i + 2] = m->p->T_lands;
    /* flows 1 + 3i .. 3 + 3i: upper flank, lower flank, end gap */
    m->from[1 + 3 * i] = 2 * i + 1;
    m->to[1 + 3 * i] = 2 * i + 2;
    m->from[2 + 3 * i] = 2 * i + 2;
    m->to[2 + 3 * i] = rp_below(m, i);
    m->from[3 + 3 * i] = 2 * i + 1;
    m->to[3 + 3 * i] = rp_below(m, i);
}

static int cylinder_trace(rd_ringpack_model *m, rd_error *err)
{
    const rd_ringpack_params *p = m->p;
    if (p->cylinder_kind == RD_CYLINDER_TABLE) {
        m->cyl_n = p->table_points;
        m->cyl_deg = (double *)p->table_deg;
        m->cyl_pa = (double *)p->table_pa;
        return RD_OK;
    }
    m->cyl_n = RD_GASFLOW_POINTS;
    m->cyl_owned = 1;
    m->cyl_deg = malloc(2 * (size_t)RD_GASFLOW_POINTS * sizeof(double));
    if (!m->cyl_deg)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the cylinder pressure.");
    m->cyl_pa = m->cyl_deg + RD_GASFLOW_POINTS;
    size_t mark = rd_error_enter(err, "/cylinder_pressure");
    rd_error_enter(err, "/synthetic");
    int rc = rd_gasflow_synthetic(&p->synthetic, &p->engine, p->rings[0].ring.diameter, m->cyl_deg,
                                  m->cyl_pa, err);
    rd_error_leave(err, mark);
    return rc;
}

/* The trace's slopes, once (rd_ringpack_pressures reads the trace at
 * every right-hand side). */
static int cylinder_slopes(rd_ringpack_model *m, rd_error *err)
{
    m->cyl_slope = malloc((size_t)m->cyl_n * sizeof *m->cyl_slope);
    if (!m->cyl_slope)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the cylinder pressure.");
    rd_gasflow_trace_slopes(m->cyl_n, m->cyl_deg, m->cyl_pa, m->cyl_slope);
    return RD_OK;
}

int rd_ringpack_model_init(rd_ringpack_model *m, const rd_ringpack_params *p, rd_error *err)
{
    memset(m, 0, sizeof *m);
    m->p = p;
    m->R = p->n_rings;
    m->V = 2 * m->R;
    m->N = m->N0 = 4 * m->R + 4;
    m->F = 1 + 3 * m->R;
    m->omega = rd_engine_omega(&p->engine);
    m->temp[0] = p->T_lands; /* gas entering the top land takes its temperature */
    m->temp[m->V + 1] = p->T_crankcase;
    m->top_area = M_PI * p->rings[0].ring.diameter * p->rings[0].land_clearance;
    m->from[0] = 0;
    m->to[0] = 1;
    for (int i = 0; i < m->R; i++) {
        rd_section s;
        rd_section_init(&s, &p->rings[i].ring);
        rd_liner_init(&m->liner[i], &p->friction, rd_liner_ureg(&p->engine), s.run.height,
                      M_PI * p->rings[i].ring.diameter);
        ring_geometry(m, i);
        int pin = p->rings[i].pinned;
        m->mode[i] = pin == RD_PIN_UPPER    ? RD_FLANK_UPPER
                     : pin == RD_PIN_MIDDLE ? RD_FLANK_FREE
                                            : RD_FLANK_LOWER;
    }
    rd_ringpack_choose(m, NULL);
    rd_gasflow_law_init(&m->law, p->kappa, p->gas_constant);
    m->limited = p->flank_passage == RD_PASSAGE_VISCOUS_LIMITED;
    int rc = cylinder_trace(m, err);
    return rc ? rc : cylinder_slopes(m, err);
}

void rd_ringpack_model_cleanup(rd_ringpack_model *m)
{
    rd_ringpack_films_close(m);
    for (int i = 0; i < RD_RINGPACK_RINGS_MAX; i++) {
        rd_packring_close(m->lr[i]);
        m->lr[i] = NULL;
    }
    if (m->cyl_owned)
        free(m->cyl_deg);
    free(m->cyl_slope);
    m->cyl_deg = m->cyl_pa = m->cyl_slope = NULL;
    m->cyl_owned = 0;
}

void rd_ringpack_pressures(const rd_ringpack_model *m, double t, const double *y, double *pv)
{
    double deg = t * m->omega * 180.0 / M_PI;
    pv[0] = rd_gasflow_trace_at(m->cyl_n, m->cyl_deg, m->cyl_pa, m->cyl_slope, deg);
    for (int v = 0; v < m->V; v++)
        pv[v + 1] = RP_P(m, y, v);
    pv[m->V + 1] = m->p->crankcase_pa;
}

void rd_ringpack_areas(const rd_ringpack_model *m, const double *y, double *area)
{
    for (int i = 0; i < m->R; i++) {
        if (m->lr[i]) {
            rd_packring_areas(m->lr[i], y + m->off[i], &area[2 * i], &area[2 * i + 1]);
            continue;
        }
        double z = RP_Z(m, y, i);
        area[2 * i] = m->circ[i] * fmax(m->ca[i] - z, 0.0);
        area[2 * i + 1] = m->circ[i] * fmax(z, 0.0);
    }
}

/* Flow f's mass flow (kg/s, from -> to) at pressures pv and flank areas
 * fa, and its derivatives (d: rd_gasflow_flow's, or NULL): the top land's
 * entry and the end gaps orifices, the flank passages limited by their
 * slots (flank_passage). */
static double flow_of(const rd_ringpack_model *m, int f, const double *pv, const double *fa,
                      double d[3])
{
    int a = m->from[f], b = m->to[f];
    if (f == 0)
        return rd_gasflow_flow(&m->law, m->cd[0], m->top_area, pv[a], m->temp[a], pv[b], m->temp[b],
                               d);
    int i = (f - 1) / 3, kind = (f - 1) % 3;
    if (kind == 2)
        return rd_gasflow_flow(&m->law, m->gap_cd[i], m->gap_area[i], pv[a], m->temp[a], pv[b],
                               m->temp[b], d);
    double area = fa[2 * i + kind];
    if (m->limited)
        return rd_gasflow_limited(&m->law, &m->slot[2 * i + kind], m->cd[i], area, pv[a],
                                  m->temp[a], pv[b], m->temp[b], d);
    return rd_gasflow_flow(&m->law, m->cd[i], area, pv[a], m->temp[a], pv[b], m->temp[b], d);
}

void rd_ringpack_flows(const rd_ringpack_model *m, const double *pv, const double *fa, double *mdot)
{
    for (int f = 0; f < m->F; f++)
        mdot[f] = flow_of(m, f, pv, fa, NULL);
}

void rd_ringpack_faces(const rd_ringpack_model *m, int i, double t, const double *pv, double out[3])
{
    rd_ringpack_around(m, i, t, pv, out);
    if (!m->p->face_tables && m->p->flank_pressure == RD_FLANK_PRESSURE_LINEAR && !m->lr[i]) {
        /* groove -> land, linear (a lift-model ring's own: RD_GAS_AREA_LINEAR) */
        out[0] = 0.5 * (out[0] + out[1]);
        out[2] = 0.5 * (out[2] + out[1]);
    }
}

/* The liner's friction on ring i and its slopes (rd_liner_law.h). */
static void liner_force(const rd_ringpack_model *m, int i, double t, const double *y,
                        const double *pv, double *n, rd_liner_force *lf)
{
    double f[3], v_p;
    rd_film_point pt;
    rd_ringpack_faces(m, i, t, pv, f);
    rd_engine_piston(&m->p->engine, m->omega * t, NULL, &v_p, NULL);
    *n = m->n_pre[i] + m->n_back[i] * f[1];
    if (m->film[i])
        rd_ringpack_film_at(m, i, t, &pt);
    rd_liner_eval(
        &m->liner[i],
        &(rd_liner_point){fmax(*n, 0.0), RP_ZD(m, y, i) - v_p, 1.0, m->film[i] ? &pt : NULL}, lf);
}

double rd_ringpack_friction(const rd_ringpack_model *m, int i, double t, const double *y,
                            const double *pv)
{
    if (m->p->friction.model == RD_FRICTION_NONE)
        return 0.0;
    double n;
    rd_liner_force lf;
    liner_force(m, i, t, y, pv, &n, &lf);
    return lf.F;
}

double rd_ringpack_ring_force(const rd_ringpack_model *m, int i, double t, const double *y,
                              const double *pv)
{
    double f[3], a_p;
    rd_ringpack_faces(m, i, t, pv, f);
    rd_engine_piston(&m->p->engine, m->omega * t, NULL, NULL, &a_p);
    return m->mass[i] * (a_p - (m->p->gravity ? GRAVITY : 0.0)) + m->area[i] * (f[2] - f[0]) +
           rd_ringpack_friction(m, i, t, y, pv);
}

void rd_ringpack_base_rhs(const rd_ringpack_model *m, double t, const double *y, const double *area,
                          double *yd)
{
    double pv[RD_RINGPACK_VOLUMES_MAX], mdot[RD_RINGPACK_FLOWS_MAX];
    double dm[RD_RINGPACK_VOLUMES_MAX] = {0};
    rd_ringpack_pressures(m, t, y, pv);
    rd_ringpack_flows(m, pv, area, mdot);
    for (int f = 0; f < m->F; f++) {
        dm[m->from[f]] -= mdot[f];
        dm[m->to[f]] += mdot[f];
    }
    for (int v = 1; v <= m->V; v++)
        yd[v - 1] = m->law.R * m->temp[v] / m->vol[v] * dm[v];
    for (int i = 0; i < m->R; i++) {
        int free_ =
            m->mode[i] == RD_FLANK_FREE && !m->lr[i] && m->p->rings[i].pinned == RD_PIN_FREE;
        RP_Z(m, yd, i) = free_ ? RP_ZD(m, y, i) : 0.0;
        RP_ZD(m, yd, i) = free_ ? rd_ringpack_ring_force(m, i, t, y, pv) / m->mass[i] : 0.0;
    }
    double in = mdot[0], cc = dm[m->V + 1];
    RP_CUM(m, yd, 0) = fmax(in, 0.0);
    RP_CUM(m, yd, 1) = fmax(-in, 0.0);
    RP_CUM(m, yd, 2) = fmax(cc, 0.0);
    RP_CUM(m, yd, 3) = fmax(-cc, 0.0);
}

/* d F / d pv (V + 2 values into dF) and d F / d z' of axial ring i's
 * force (rd_ringpack_ring_force): its face areas, and the friction's
 * normal force (the groove pressure) and tanh (the ring's speed).  The
 * test hook's tables do not depend on the state. */
static double force_gradient(const rd_ringpack_model *m, int i, double t, const double *y,
                             const double *pv, double *dF)
{
    int tables = m->p->face_tables != NULL;
    memset(dF, 0, (size_t)(m->V + 2) * sizeof *dF);
    if (!tables) { /* A (f[2] - f[0]); linear: the groove's halves cancel */
        double w = m->p->flank_pressure == RD_FLANK_PRESSURE_LINEAR ? 0.5 : 1.0;
        dF[2 * i + 1] -= w * m->area[i];
        dF[rp_below(m, i)] += w * m->area[i];
    }
    if (m->p->friction.model == RD_FRICTION_NONE)
        return 0.0;
    double n;
    rd_liner_force lf;
    liner_force(m, i, t, y, pv, &n, &lf);
    if (!tables && n > 0.0) /* the film's F_N is 0 */
        dF[2 * i + 2] += lf.F_N * m->n_back[i];
    return lf.F_u;
}

/* Axial ring i's columns and row of J: its lift through the flank areas
 * (G's columns, set), and its motion while free. */
static void axial_jacobian(const rd_ringpack_model *m, int i, double t, const double *y,
                           const double *pv, double *J, const double *G)
{
    int N0 = m->N0, z = 2 * m->R + 2 * i, zd = z + 1;
    double dF[RD_RINGPACK_VOLUMES_MAX], lift = RP_Z(m, y, i);
    double du = m->ca[i] - lift > 0.0 ? -m->circ[i] : 0.0, dl = lift > 0.0 ? m->circ[i] : 0.0;
    for (int r = 0; r < N0; r++)
        J[(size_t)z * N0 + r] +=
            G[(size_t)(2 * i) * N0 + r] * du + G[(size_t)(2 * i + 1) * N0 + r] * dl;
    if (m->mode[i] != RD_FLANK_FREE || m->p->rings[i].pinned != RD_PIN_FREE)
        return;
    double dzd = force_gradient(m, i, t, y, pv, dF);
    J[(size_t)zd * N0 + z] = 1.0;
    for (int w = 1; w <= m->V; w++)
        J[(size_t)(w - 1) * N0 + zd] = dF[w] / m->mass[i];
    J[(size_t)zd * N0 + zd] += dzd / m->mass[i];
}

/* The volumes' and the cumulative masses' rows from D = d dm / d pv and
 * DA = d dm / d area (dm: the net inflow of each network volume, kg/s),
 * in = the cylinder's inflow and d_in its gradient, cc = the crankcase's. */
static void network_rows(const rd_ringpack_model *m, double D[][RD_RINGPACK_VOLUMES_MAX],
                         double DA[][2 * RD_RINGPACK_RINGS_MAX], double in, const double *d_in,
                         double cc, double *J, double *G)
{
    int N0 = m->N0, V = m->V, c0 = 4 * m->R;
    double scale[RD_RINGPACK_VOLUMES_MAX]; /* dp/dt per net inflow: R T / V */
    for (int v = 1; v <= V; v++)
        scale[v] = m->law.R * m->temp[v] / m->vol[v];
    for (int w = 1; w <= V; w++) { /* pressure columns */
        double *col = J + (size_t)(w - 1) * N0;
        for (int v = 1; v <= V; v++)
            col[v - 1] = scale[v] * D[v][w];
        col[c0 + 0] = in > 0.0 ? d_in[w] : 0.0; /* fmax(in, 0), fmax(-in, 0) */
        col[c0 + 1] = in > 0.0 ? 0.0 : -d_in[w];
        col[c0 + 2] = cc > 0.0 ? D[V + 1][w] : 0.0;
        col[c0 + 3] = cc > 0.0 ? 0.0 : -D[V + 1][w];
    }
    for (int c = 0; c < 2 * m->R; c++) { /* flank area columns */
        double *col = G + (size_t)c * N0;
        for (int v = 1; v <= V; v++)
            col[v - 1] = scale[v] * DA[v][c];
        col[c0 + 2] = cc > 0.0 ? DA[V + 1][c] : 0.0;
        col[c0 + 3] = cc > 0.0 ? 0.0 : -DA[V + 1][c];
    }
}

void rd_ringpack_base_jacobian(const rd_ringpack_model *m, double t, const double *y,
                               const double *area, double *J, double *G)
{
    enum { NV = RD_RINGPACK_VOLUMES_MAX };
    double pv[NV], D[NV][NV] = {{0}}, DA[NV][2 * RD_RINGPACK_RINGS_MAX] = {{0}}, d_in[NV] = {0};
    double d[3], in = 0.0, cc = 0.0;
    size_t N0 = (size_t)m->N0;
    rd_ringpack_pressures(m, t, y, pv);
    memset(J, 0, N0 * N0 * sizeof *J);
    memset(G, 0, 2 * (size_t)m->R * N0 * sizeof *G);
    for (int f = 0; f < m->F; f++) {
        int a = m->from[f], b = m->to[f];
        double mdot = flow_of(m, f, pv, area, d);
        D[a][a] -= d[0];
        D[a][b] -= d[1];
        D[b][a] += d[0];
        D[b][b] += d[1];
        cc += (b == m->V + 1 ? mdot : 0.0) - (a == m->V + 1 ? mdot : 0.0);
        if (f == 0) {
            in = mdot;
            d_in[a] = d[0];
            d_in[b] = d[1];
        } else if ((f - 1) % 3 < 2) { /* a flank passage: its area's column */
            int c = 2 * ((f - 1) / 3) + (f - 1) % 3;
            DA[a][c] -= d[2];
            DA[b][c] += d[2];
        }
    }
    network_rows(m, D, DA, in, d_in, cc, J, G);
    for (int i = 0; i < m->R; i++)
        if (!m->lr[i])
            axial_jacobian(m, i, t, y, pv, J, G);
}

int rd_ringpack_rhs(const rd_ringpack_model *m, double t, const double *y, double *yd)
{
    double area[2 * RD_RINGPACK_RINGS_MAX], pv[RD_RINGPACK_VOLUMES_MAX], g[3];
    rd_ringpack_areas(m, y, area);
    rd_ringpack_base_rhs(m, t, y, area, yd);
    if (!m->lifted)
        return 0;
    rd_ringpack_pressures(m, t, y, pv);
    for (int i = 0; i < m->R; i++) {
        if (!m->lr[i])
            continue;
        rd_ringpack_faces(m, i, t, pv, g);
        rd_packring_gas(m->lr[i], g);
        int rc = rd_packring_rhs(m->lr[i], t, (double *)y + m->off[i], yd + m->off[i]);
        if (rc)
            return rc;
    }
    return 0;
}

/* auto's reasons (rd_ringpack_choose). */
#define AXIAL_WHY                                                                                  \
    "auto: an axisymmetric pack ring without friction and with full flank pressure; the axial "    \
    "ring (lift, hard flank stops) meets the lift rigid ring's flank changes within 0.1 deg at a " \
    "third of its cost"
#define LINEAR_WHY                                                                           \
    "auto: the linear flank pressure's couple twists the ring, which the axial ring cannot " \
    "represent (3.5 % off in blow-by on the motored and 6000 rpm examples); 3-5x its cost "  \
    "(numerics.model)"
#define RIGID_WHY                                                                             \
    "auto: friction twists the ring and the twist decides when it leaves a flank, which the " \
    "axial ring cannot represent (9 deg off); the full ring costs ~50x more (numerics.model)"

void rd_ringpack_choose(rd_ringpack_model *m, char (*why)[240])
{
    for (int i = 0; i < m->R; i++) {
        const rd_ringpack_ring *r = &m->p->rings[i];
        int k = r->model != RD_LIFT_MODEL_AUTO ? r->model : m->p->model;
        char w[240];
        if (r->pinned != RD_PIN_FREE) {
            if (r->pinned == RD_PIN_MIDDLE)
                snprintf(w, sizeof w,
                         "pinned at half its axial clearance: held there (both "
                         "flank passages open), no motion integrated");
            else
                snprintf(w, sizeof w, "pinned on its %s flank: held there, no motion integrated",
                         r->pinned == RD_PIN_LOWER ? "lower" : "upper");
            k = RD_RINGPACK_AXIAL;
        } else if (k == RD_LIFT_MODEL_AUTO) {
            int fric = m->p->friction.model != RD_FRICTION_NONE;
            const char *need = NULL; /* a distorted bore, a tilt, dynamic areas */
            k = rd_packring_auto(m->p, &need);
            int lin = m->p->flank_pressure == RD_FLANK_PRESSURE_LINEAR;
            snprintf(w, sizeof w, "%s",
                     need   ? need
                     : fric ? RIGID_WHY
                     : lin  ? LINEAR_WHY
                            : AXIAL_WHY);
            k = need ? k : fric || lin ? RD_LIFT_MODEL_RIGID : RD_RINGPACK_AXIAL;
        } else {
            char at[32];
            if (r->model != RD_LIFT_MODEL_AUTO)
                snprintf(at, sizeof at, "rings/%d/model", i);
            else
                snprintf(at, sizeof at, "numerics/model");
            snprintf(w, sizeof w, "asked for (%s = %s)", at, rd_ringpack_model_name(k));
        }
        m->kind[i] = k;
        if (why)
            snprintf(why[i], 240, "%s", w);
    }
}

void rd_ringpack_describe(const rd_ringpack_model *m, rd_ringpack_result *r)
{
    r->n_rings = m->R;
    r->n_volumes = m->V + 2;
    r->n_flows = m->F;
    r->volume_name[0] = "cylinder";
    r->volume_name[m->V + 1] = "crankcase";
    for (int i = 0; i < m->R; i++) {
        r->volume_name[2 * i + 1] = land_names[i];
        r->volume_name[2 * i + 2] = groove_names[i];
    }
    for (int v = 0; v < m->V + 2; v++)
        r->volume_m3[v] = (v == 0 || v == m->V + 1) ? 0.0 : m->vol[v];
    static const char *const kind[] = {"upper_flank", "lower_flank", "end_gap"};
    snprintf(r->flow_name[0], sizeof r->flow_name[0], "cylinder_to_top_land");
    for (int f = 1; f < m->F; f++)
        snprintf(r->flow_name[f], sizeof r->flow_name[f], "ring_%d_%s", (f - 1) / 3 + 1,
                 kind[(f - 1) % 3]);
    for (int f = 0; f < m->F; f++) {
        r->flow_from[f] = m->from[f];
        r->flow_to[f] = m->to[f];
    }
}
