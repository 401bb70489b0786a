/*
 * rd_film.h — the oil film between a ring's running face and the liner
 * (private to core; the scene's inputs are rd_liner.h's rd_face_params and
 * rd_lube_params).  MODEL.md "Ring-liner lubrication".
 *
 * The face, seen from the ring (x axial, 0 at the face's lower edge, L at
 * its upper edge): a rigid profile h(x) = h0 + drop(x) over the liner, the
 * liner sliding past at U (m/s, + upwards), the face approaching or leaving
 * at dh0/dt.  Per unit of circumference, at one instant:
 *   - the average Reynolds equation (Patir-Cheng 1978, Peklenik gamma = 1)
 *       d/dx(phi_x h^3 / (12 eta) dp/dx) = U/2 dh_T/dx + U sigma/2 w_s dphi_s/dx
 *                                          + dh_T/dh dh0/dt,
 *     h_T the expected gap of a Gaussian roughness of composite Rq sigma,
 *     w_s = (sigma_liner^2 - sigma_ring^2) / sigma^2 (the liner slides, the
 *     ring does not), phi_x = 1 - 0.90 e^{-0.56 H} and phi_s the Patir-Cheng
 *     fits at H = h / sigma (phi_x's fit is for H >= 0.5: held there below);
 *     p = the gas pressures at the edges, the Reynolds
 *     (Swift-Stieber) condition p >= 0 inside (by default), solved as the discrete
 *     obstacle problem on `nodes` points (finite volumes, primal-dual active
 *     set: dp/dx = 0 where the film ruptures follows from it);
 *   - a starved inlet (supply > 0, the oil film h_s on the liner ahead of
 *     the face): where the flooded film would take in more than the liner
 *     brings, U h_s, the film starts at a meniscus x_m inside the face,
 *     the inlet edge's gas pressure from the edge to x_m (dry: no film, no
 *     shear), x_m found so that the flow into the film at x_m is U h_s:
 *     between the last node (from the inlet) whose film, dry up to it,
 *     would still take in more and the next, the two films' loads blended
 *     linearly in their inflows; with less oil than half the thinnest gap the
 *     whole face is dry (the oil passes under it);
 *   - with cavitation "jfo" (f->jfo) the mass-conserving conditions
 *     instead of the Reynolds condition and the meniscus above
 *     (rd_film_jfo.c): each node full (p >= the cavity's pressure) or in a
 *     cavity (its oil content theta h_T, 0 <= theta < 1, carried by the
 *     liner at U/2 and kept in time), the flow conserved through every
 *     rupture and reformation; a starved inlet brings the content 2 h_s / h_T;
 *   - the asperity pressure of Greenwood-Tripp, K F_5/2(h / sigma),
 *     K = (16 sqrt(2) / 15) pi (n beta sigma)^2 sqrt(sigma / beta) E', E' the
 *     composite modulus 1/E' = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2;
 *   - the shear on the ring: tau = theta eta U / h_T - (h / 2) dp/dx, theta
 *     = 1 in the full film and the film's share 2 q / (U h_T) downstream of
 *     a rupture (q the flow that crosses it); the asperity friction
 *     mu_b W_a.  Patir-Cheng's shear-stress factors are not applied (the
 *     smooth-surface shear with the expected gap).
 *
 * Usage:
 *     rd_film f;
 *     if (rd_film_init(&f, &face, L, RD_FILM_NODES, liner_rq, &lube, E, nu, err)) ...
 *     rd_film_out o;
 *     rd_film_solve(&f, h0, h0_dot, U, eta, p_lower_edge, p_upper_edge, &o);
 *     ... o.W + o.Wa carries the radial load; friction on the ring per
 *     metre of circumference: -o.Cc u + o.Fp - mu_b o.Wa sign(u), u the
 *     ring's speed on the liner (= -U) ...
 *     rd_film_free(&f);
 */
#ifndef RD_FILM_H
#define RD_FILM_H

#include "rd_error.h"
#include "rd_liner.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#ifndef M_SQRT2
#define M_SQRT2 1.41421356237309504880
#endif

#define RD_FILM_NODES \
    41 /* points across the face, default (0.2 % of the film, docs/lubrication.md) */
#define RD_FILM_NODES_MAX     2001
#define RD_FILM_RTOL          1e-4   /* a film track's local error on h0, relative (rd_film.rtol) */
#define RD_FILM_PHI_X_H_MIN   0.5    /* phi_x's fit holds above this H */
#define RD_FILM_GT_LAMBDA_MIN (-4.0) /* Greenwood-Tripp table range of h / sigma */
#define RD_FILM_GT_LAMBDA_MAX 12.0

typedef struct rd_film {
    double rtol;               /* the film track's local error on h0 (RD_FILM_RTOL by init) */
    int n;                     /* nodes */
    double L, dx;              /* face height, node spacing, m */
    double sigma;              /* composite Rq, m */
    double w_s;                /* shear-flow weight (sigma_l^2 - sigma_r^2) / sigma^2 */
    double gt_k;               /* Greenwood-Tripp K, Pa */
    double mu_b;               /* boundary friction coefficient */
    double x_min;              /* where the profile is thinnest, m from the lower edge */
    double *drop, *drop_mid;   /* the profile at the nodes and between them, m */
    double *a, *b, *c, *r, *p; /* the tridiagonal system and the pressures */
    double *kf, *qf;           /* the faces' flow coefficients and flows */
    int *cav;                  /* 1: node in the cavitated set (kept between solves) */
    double supply;             /* the liner's oil film ahead of the face, m; 0: flooded */
    int dry; /* the last solve: nodes dry at the inlet (a starved inlet), from the edge the
              * liner comes from */
    /* cavitation "jfo": the content theta h_T (m) at the nodes after the
     * last solve, and the time step that the next solve closes: d(theta
     * h_T)/dt = c1_dt theta h_T - hist_dt (set by the film's track from its
     * BDF history; c1_dt = 0: the film alone, d(theta h_T)/dt = theta dh_T/dh
     * dh0/dt) */
    int jfo;
    double *theta, *content, *hist_dt;
    double c1_dt;
} rd_film;

/* One solve's nodes and faces (rd_film_solve fills them for the solvers). */
typedef struct rd_film_nodes {
    const double *hT, *g;   /* nodes: the expected gap, m; its slope dh_T/dh */
    const double *hTf, *sf; /* faces: the expected gap, m; w_s phi_s */
    double h0, h0_dot, U, eta, p_lo, p_hi;
} rd_film_nodes;

/* One solve, per metre of circumference. */
typedef struct rd_film_out {
    double W;         /* film load, N/m: the integral of p over the face */
    double Wa;        /* asperity load, N/m */
    double Cc;        /* Couette coefficient: integral of theta eta / h_T, N s/m^3 */
    double Fp;        /* the pressure gradient's shear on the ring, N/m (+ upwards) */
    double cavitated; /* share of the face that is cavitated */
    double h_min;     /* nominal film at the thinnest point, m (= h0) */
} rd_film_out;

/* Builds the face of height L (m) on `nodes` points (3 ..
 * RD_FILM_NODES_MAX) and checks the profile (paths relative to the face's
 * block: "/table/x_m"); E,
 * nu: the ring's material (for E' when lube's composite_modulus is 0). */
/* The profile's fit to a face of height L alone (rd_film_init's first check). */
int rd_film_face_validate(const rd_face_params *face, double L, rd_error *err);
int rd_film_init(rd_film *f, const rd_face_params *face, double L, int nodes, double liner_rq,
                 const rd_lube_params *lube, double E, double nu, rd_error *err);
void rd_film_free(rd_film *f);

/* The film at minimum nominal thickness h0 (m), its rate (m/s), the liner's
 * speed U past the ring (m/s, + upwards), viscosity eta (Pa s) and the gas
 * pressures at the lower and upper edges (Pa; cavitation at 0). */
void rd_film_solve(rd_film *f, double h0, double h0_dot, double U, double eta, double p_lo,
                   double p_hi, rd_film_out *o);

/* The mass-conserving solve (rd_film_jfo.c), rd_film_solve's with f->jfo:
 * o's film loads (not Wa). */
void rd_film_jfo_solve(rd_film *f, const rd_film_nodes *in, rd_film_out *o);

/* The laws, for the tests and the cycle (H = h / sigma): */
double rd_film_phi_x(double H);
double rd_film_phi_s(double H);
double rd_film_gap(double H, double *dgap); /* h_T / sigma and d(h_T / sigma)/dH */
/* The node laws at H from tables on the F_5/2 table's grid (cubic Hermite
 * with the exact slopes; within 1e-7 of rd_film_gap): the expected gap, its
 * slope and F_5/2; their far limits H, 1, 0 above RD_FILM_GT_LAMBDA_MAX. */
void rd_film_node_laws(double H, double *gap, double *dgap, double *f52);
/* Greenwood-Tripp F_n(lambda) = (1/sqrt(2 pi)) int_lambda^inf (s - lambda)^n
 * e^{-s^2/2} ds: F_5/2 from a table of ln F_5/2 (cubic Hermite, built once
 * by Gauss-Legendre quadrature; 0 above RD_FILM_GT_LAMBDA_MAX; the table's
 * end below RD_FILM_GT_LAMBDA_MIN), F_2 in closed form. */
double rd_film_gt_f52(double lambda);
double rd_film_gt_f2(double lambda);
/* The same integral by direct quadrature, any n > -1 (slow; the table's source). */
double rd_film_gt_quad(double n, double lambda);

/* The composite modulus E' of a ring (E, nu) on a grey cast-iron liner
 * (RD_LINER_E, RD_LINER_NU). */
#define RD_LINER_E  120e9
#define RD_LINER_NU 0.26
double rd_film_composite_modulus(double E, double nu);

#endif
