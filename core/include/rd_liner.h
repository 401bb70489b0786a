/*
 * rd_liner — the cylinder liner as the ring meets it: the bore's shape rule
 * and the friction of the running face (the scene's physics.friction).
 * Shared by the contact, lift and ring-pack analyses; the law itself, per
 * point of the running face, is core/liner/rd_liner_law.h (private).
 */
#ifndef RD_LINER_H
#define RD_LINER_H

#include "rd_error.h"

enum rd_friction_model {
    RD_FRICTION_NONE = 0,
    RD_FRICTION_COULOMB = 1,
    RD_FRICTION_STRIBECK = 2,
    RD_FRICTION_LUBRICATED = 3 /* the oil film and asperity contact (rd_film.h) */
};

/* The running face's profile across its axial height (ring.face): x from
 * the face's lower edge (x = 0) to its upper edge (x = L, the running
 * face's height), drop(x) >= 0 the face's recess from the liner-side
 * envelope, smallest 0 (where the film is thinnest). */
enum rd_face_profile {
    RD_FACE_BARREL = 0, /* drop = crown ((x - x_c) / (L / 2))^2, x_c = L / 2 + offset */
    RD_FACE_TAPER = 1,  /* drop = tan(taper) x: the lower edge runs on the liner */
    RD_FACE_FLAT = 2,   /* flat, each edge rounded with radius edge_radius */
    RD_FACE_TABLE = 3   /* (x, drop) points, linear between them */
};
#define RD_FACE_TABLE_MAX 1000

typedef struct rd_face_params {
    int profile;        /* enum rd_face_profile */
    double crown;       /* barrel: drop at the edges of a centred crown, m */
    double offset;      /* barrel: crown position above mid-height, m */
    double taper_deg;   /* taper: angle, deg */
    double edge_radius; /* flat: radius of the rounded edges, m */
    int points;         /* table: points (borrowed arrays) */
    const double *x, *drop;
    double roughness_rq; /* the face's Rq, m */
} rd_face_params;

/* The oil and the rough contact of the lubricated model (physics.friction
 * with model "lubricated").  Viscosity: the constant `viscosity` when > 0,
 * else the Vogel law eta = a exp(b / (T - c)), T in kelvin, at the liner
 * temperature (a constant, or a periodic table vs crank angle when
 * temp_points > 0, linear between points). */
typedef struct rd_lube_params {
    double viscosity;                 /* Pa s; 0 = Vogel */
    double vogel_a, vogel_b, vogel_c; /* Pa s, K, K */
    double temperature_c;             /* liner temperature, deg C */
    int temp_points;                  /* table points (borrowed arrays) */
    const double *temp_crank_deg, *temp_c;
    double asperity_density;     /* asperities per m^2 (Greenwood-Tripp n) */
    double asperity_radius;      /* asperity tip radius beta, m */
    double boundary_coefficient; /* mu_b of the asperity load */
    double composite_modulus;    /* E' (1/E' = sum (1 - nu_i^2)/E_i), Pa; 0 = the
                                          * ring's material on a grey cast-iron liner */
    double supply_film;          /* the oil film on the liner ahead of the ring, m: a starved inlet
                           where the face would take in more (rd_film.h); 0 = fully flooded */
    int cavitation;              /* enum rd_cavitation */
} rd_lube_params;

/* Where the film ruptures (physics.friction.cavitation): the Reynolds
 * (Swift-Stieber) condition, p >= 0 with the film's flow lost downstream of
 * a rupture, or the mass-conserving Jakobsson-Floberg-Olsson condition
 * (Elrod-Adams: the cavity's oil content carried by the liner and kept in
 * time, the film reforming where its flow meets it; rd_film.h). */
enum rd_cavitation { RD_CAVITATION_REYNOLDS = 0, RD_CAVITATION_JFO = 1 };

typedef struct rd_friction_params {
    int model;                    /* enum rd_friction_model; NONE = not modelled */
    double coefficient;           /* Coulomb coefficient (also C_Coulomb of 2.9) */
    double viscosity;             /* Stribeck: oil dynamic viscosity eta, Pa s */
    double sommerfeld_transition; /* Stribeck: So_lim of 2.9 */
    double hydrodynamic_slope;    /* Stribeck: K of 2.9 */
    rd_lube_params lube;          /* lubricated */
} rd_friction_params;

/* The bore: radius r_b(theta) = D/2 + sum A_k cos(k (theta - phi_k)), theta
 * from the ring's gap middle; D = 0: the ring's diameter.  One type for the
 * contact, lift and ring-pack analyses. */
#define RD_BORE_ORDERS_MAX 16
typedef struct rd_distortion {
    int order;        /* k >= 1 */
    double amplitude; /* A_k, m (radius change) */
    double phase_deg; /* phi_k, degrees from the gap middle */
} rd_distortion;

typedef struct rd_bore {
    double diameter;     /* D, m; 0 = the ring's diameter */
    double roughness_rq; /* the liner's Rq, m (the lubricated model) */
    int n_distortion;
    rd_distortion distortion[RD_BORE_ORDERS_MAX];
} rd_bore;

/* 1 if the bore is not the round bore of the ring's diameter. */
int rd_bore_distorted(const rd_bore *b, double ring_diameter);

/* Range checks of a bore for a ring of diameter d (paths relative to the
 * bore's block, "/diameter", "/distortion/..."; the bore sits at /bore or
 * /bore/layers/3: rd_error_enter):
 * D within 2 % of d, at most RD_BORE_ORDERS_MAX terms of order 1..64,
 * |A_k| and their sum at most 1 % of d, phases within +-360 deg, and
 * convex (rd_bore_convex_validate). */
int rd_bore_validate(const rd_bore *b, double d, rd_error *err);

/* The convex-bore rule of a distorted bore r = D/2 + sum A_k cos(k (t -
 * phi_k)), shared by the contact and lift analyses: its curvature stays
 * positive when sum |A_k| (k^2 + 2) <= D/2 (to first order in A_k / D).
 * rd_bore_bend_term is one term of the sum; rd_bore_convex_validate checks
 * the sum `bend` against the bore of diameter d (path "/distortion" in the
 * bore's block).
 * A non-convex (petal-shaped) bore ends the contact solve unconverged and
 * is outside the lift model's small-offset contact geometry. */
double rd_bore_bend_term(int order, double amplitude);
int rd_bore_convex_validate(double bend, double d, rd_error *err);

/* The lubricated model's defaults: a barrel face (crown 5 um at the edges,
 * centred), Rq 0.2 um on the face (and bore->roughness_rq 0.2 um on the
 * liner), an SAE 5W-30-like oil (Vogel a 4.88e-5 Pa s, b 1197 K, c 141.15 K:
 * 51 mPa s at 40 C, 8.5 at 100 C, 3.4 at 150 C) at 100 C, asperities of
 * density 5e8 / m^2 and radius 0.3 mm (n beta sigma = 0.04, sigma / beta ~
 * 1e-3 with the default roughness), boundary coefficient 0.1, E' from the
 * ring's material on a grey cast-iron liner. */
void rd_lube_params_default(rd_lube_params *l, rd_face_params *face);
#define RD_LINER_RQ_DEFAULT 0.2e-6 /* the liner's Rq default, m */

/* Range checks of the lubricated model's inputs: roughness within
 * [1e-9, 5e-6] m, crown [0, 1e-4] m, taper (0, 5] deg, the oil's viscosity
 * [1e-4, 10] Pa s, temperatures [-40, 250] deg C (kelvin typed as Celsius
 * named as such), the Vogel law above 10 K from its pole, asperity density
 * [1e6, 1e14] / m^2, radius [1e-7, 1e-2] m, mu_b [0, 1], E' 0 or [1e9, 1e12]
 * Pa.  The face's fit to its height is rd_film_init's.  rd_face_validate:
 * the face, paths relative to its block ("/crown_m"); rd_lube_validate: the
 * liner's roughness and the oil, paths relative to the scene's root
 * ("/bore/roughness_rq_m", "/physics/friction/..."). */
int rd_face_validate(const rd_face_params *face, rd_error *err);
int rd_lube_validate(const rd_lube_params *l, double liner_rq, rd_error *err);

#endif
