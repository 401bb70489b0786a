/*
 * rd_gasflow — the gas pieces of the ring pack (thesis 2.4.4, eqs. 2.22-2.25;
 * MODEL.md "Ring pack and blow-by"): compressible orifice flow, and the
 * cylinder pressure vs crank angle (a table, or a synthetic trace).
 *
 * Orifice (isentropic nozzle, ideal gas, upstream stagnation state p_u, T_u,
 * downstream p_d, ratio r = p_d / p_u, heat capacity ratio k, gas constant R):
 *   unchoked, r > r_c:  mdot = C_d A p_u / sqrt(R T_u) *
 *                              sqrt(2k/(k-1) (r^(2/k) - r^((k+1)/k)))
 *   choked,   r <= r_c: mdot = C_d A p_u / sqrt(R T_u) *
 *                              sqrt(k) (2/(k+1))^((k+1)/(2(k-1)))
 *   r_c = (2/(k+1))^(k/(k-1))   (0.528 for k = 1.4),
 * both continuous at r_c.  As r -> 1 the unchoked form behaves like
 * sqrt(2 rho dp): its derivative in dp is infinite at dp = 0, which a Newton
 * iteration cannot live with.  Above r_lin = 1 - RD_GASFLOW_LINEAR_BAND the
 * flow is continued linearly in (1 - r) from its value at r_lin (a laminar-
 * like limit for near-equal pressures; it changes a flow only where the
 * pressures differ by less than 1e-4 of the upstream one).
 *
 * Cylinder pressure (absolute, Pa) vs crank angle, 0 = firing TDC, periodic
 * over 720 deg.  The synthetic generator (rd_gasflow_synthetic):
 *   cylinder volume V(theta) = V_c + A_p s(theta), A_p = pi d^2/4, s the piston
 *   distance below TDC (rd_engine_piston), V_c = A_p 2 r / (eps - 1);
 *   motored: p = p_in (V_bdc / V)^n, n = 1.32, from 540 deg (BDC, inlet closed)
 *   through TDC to 180 deg; p_in during exhaust and intake (180..540);
 *   fired: the single-zone energy equation (no wall heat loss)
 *     dp/dtheta = (n - 1)/V Q dx_b/dtheta - n p/V dV/dtheta,
 *   with the Wiebe burn fraction x_b = 1 - exp(-a ((theta - theta_0)/D)^(m+1)),
 *   a = 5, m = 2, duration D = 50 deg.  p is affine in the heat Q, so for a
 *   start theta_0 the Q giving the asked peak pressure is a bisection on
 *   max(p_motored + Q p_unit); theta_0 is then bisected until the peak falls
 *   at the asked crank angle (within the 0.25 deg grid).
 *   Blowdown (both kinds): from 130 to 180 deg the pressure blends smoothly
 *   (smoothstep) to p_in, a stand-in for the exhaust valve opening.
 * The result is a table at 0.25 deg, so the pack reads every trace alike.
 */
#ifndef RD_GASFLOW_H
#define RD_GASFLOW_H

#include "rd_engine.h"
#include "rd_error.h"
#include "rd_lift.h"

#define RD_GASFLOW_KAPPA       1.35  /* heat capacity ratio of the hot gas, - */
#define RD_GASFLOW_R           287.0 /* specific gas constant of air, J/(kg K) */
#define RD_GASFLOW_LINEAR_BAND 1e-4  /* 1 - r below which the flow is linear */
#define RD_GASFLOW_POLYTROPIC  1.32  /* synthetic trace's compression exponent */
#define RD_GASFLOW_WIEBE_A     5.0
#define RD_GASFLOW_WIEBE_M     2.0
#define RD_GASFLOW_BURN_DEG    50.0
#define RD_GASFLOW_EVO_DEG     130.0 /* blowdown starts */
#define RD_GASFLOW_STEP_DEG    0.25  /* synthetic table spacing */
#define RD_GASFLOW_POINTS      2881  /* 720 / 0.25 + 1 */

/* Critical pressure ratio (2/(k+1))^(k/(k-1)). */
double rd_gasflow_critical_ratio(double kappa);

/* Mass flow (kg/s) from side a to side b through an orifice of area A (m^2)
 * with discharge coefficient cd; negative when the gas flows from b to a.
 * The upstream side's temperature applies.  A <= 0 or cd <= 0 gives 0. */
double rd_gasflow_orifice(double cd, double area, double p_a, double T_a, double p_b, double T_b,
                          double kappa, double R);

/* The orifice law's constants for one gas (k, R), computed once so that a
 * flow costs at most two powers instead of three (rd_gasflow_law_init). */
typedef struct rd_gasflow_law {
    double kappa, R;
    double r_c;         /* critical ratio */
    double psi_choked;  /* the flow function below r_c */
    double psi_lin;     /* its value at r_lin = 1 - RD_GASFLOW_LINEAR_BAND */
    double e_a, e_b, K; /* 2/k, (k+1)/k, 2k/(k-1) */
} rd_gasflow_law;

void rd_gasflow_law_init(rd_gasflow_law *law, double kappa, double R);

/* rd_gasflow_orifice with the law's constants (the same value, bit for
 * bit), and, when d is not NULL, its partial derivatives: d[0] =
 * d mdot/d p_a, d[1] = d mdot/d p_b (kg/(s Pa)), d[2] = d mdot/d A
 * (kg/(s m^2), the flow per area: the flow is linear in A >= 0, so at
 * A = 0 the derivative of the opening orifice).  Derivatives of the branch
 * the pressures are on; at equal pressures the linear band's (continuous:
 * the flow is linear in p_a - p_b there).  cd <= 0 or p <= 0 upstream: 0 and
 * zero derivatives. */
double rd_gasflow_flow(const rd_gasflow_law *law, double cd, double area, double p_a, double T_a,
                       double p_b, double T_b, double d[3]);

/* Gas viscosity by Sutherland's law with air's constants (mu_0 1.716e-5
 * Pa s at T_0 273.15 K, S 110.4 K):  mu = mu_0 (T/T_0)^1.5 (T_0 + S)/(T + S),
 * Pa s (2.48e-5 at 450 K). */
#define RD_GAS_MU0        1.716e-5
#define RD_GAS_T0         273.15
#define RD_GAS_SUTHERLAND 110.4
double rd_gas_viscosity(double T);

/* A flank passage's viscous limit (MODEL.md "Ring pack"; Namazian &
 * Heywood): isothermal laminar flow of an ideal gas through a slot of
 * width w, height h and length L (in the flow's direction),
 *   mdot_v = w h^3 (p_a^2 - p_b^2) / (24 mu R T L),
 * T the passage's temperature, mu its viscosity.  The passage carries the
 * smaller of that and the orifice flow mdot_o (rd_gasflow_flow), blended
 * smoothly where they cross:
 *   mdot = sign (|mdot_o|^-4 + |mdot_v|^-4)^(-1/4)
 * (within 1e-3 of the smaller where the two differ by 4x, 1.5e-2 by 2x, 0.84 of
 * either where they are equal; C1 in the pressures and the area for
 * h > 0: d mdot = (mdot/mdot_o)^5 d mdot_o + (mdot/mdot_v)^5 d mdot_v).
 * h = area / w (the slot's mean height). */
typedef struct rd_gasflow_slot {
    double width;  /* w, m */
    double length; /* L, m */
    double mu;     /* Pa s */
    double T;      /* K */
} rd_gasflow_slot;

/* The viscous slot flow alone (kg/s, a -> b positive) for the area
 * (w h, m^2); d as rd_gasflow_flow's (d[2] per area). */
double rd_gasflow_slot_flow(const rd_gasflow_slot *s, double R, double area, double p_a, double p_b,
                            double d[3]);
/* The limited flow (above): the orifice (law, cd, area, p, T as
 * rd_gasflow_flow) and the slot s; d as rd_gasflow_flow's.  At equal
 * pressures (zero flow) the derivatives in the pressures are the blend of
 * the two laws' slopes, the one in the area 0. */
double rd_gasflow_limited(const rd_gasflow_law *law, const rd_gasflow_slot *s, double cd,
                          double area, double p_a, double T_a, double p_b, double T_b, double d[3]);

enum rd_cylinder_kind { RD_CYLINDER_TABLE = 0, RD_CYLINDER_MOTORED = 1, RD_CYLINDER_FIRED = 2 };

/* The synthetic trace's inputs. */
typedef struct rd_cylinder_synthetic {
    int kind;                 /* RD_CYLINDER_MOTORED or RD_CYLINDER_FIRED */
    double peak_pa;           /* fired: peak pressure, Pa (absolute) */
    double peak_crank_deg;    /* fired: where the peak is, deg after firing TDC, 0..60 */
    double compression_ratio; /* eps, 2..40 */
    double intake_pa;         /* p_in, Pa (absolute) */
} rd_cylinder_synthetic;

/* Checks the synthetic inputs (paths relative to the synthetic block,
 * "/peak_pa"); the fired peak must exceed the motored one p_in eps^n by 5 %. */
int rd_gasflow_synthetic_validate(const rd_cylinder_synthetic *s, rd_error *err);

/* Writes the synthetic trace: RD_GASFLOW_POINTS angles (0, 0.25, ..., 720)
 * into crank_deg and pressures into p (caller's arrays).  bore: the cylinder
 * diameter, m; e: crank radius, rod length, kinematics.  Validates first
 * (rd_gasflow_synthetic_validate). */
int rd_gasflow_synthetic(const rd_cylinder_synthetic *s, const rd_engine_params *e, double bore,
                         double *crank_deg, double *p, rd_error *err);

/* Checks a measured cylinder pressure table, paths relative to the
 * cylinder_pressure block ("/crank_deg", "/pressure_pa/3"): at least 2
 * points, pressures 1e3..1e9 Pa (absolute), the angles strictly increasing
 * from 0 to 720 deg. */
int rd_gasflow_table_validate(int n, const double *deg, const double *pa, rd_error *err);

/* Linear interpolation in a table (n >= 2, x strictly increasing, covering
 * 0..720), periodic over 720 deg. */
double rd_gasflow_table(int n, const double *x, const double *y, double deg);

/* The cylinder trace between its points: a monotone C1 cubic (Hermite with
 * Fritsch-Butland slopes, periodic over 720 deg; x[0] = 0, x[n-1] = 720).
 * It passes through every point and never leaves the range of its two
 * neighbours (no overshoot: pressures stay positive), and its slope is
 * continuous, so the stiff top land, which follows the cylinder within
 * ~1e-5 s, does not force a step at every table point as the kinks of a
 * linear interpolation would (4000 steps per cycle instead of ~600). */
double rd_gasflow_trace(int n, const double *x, const double *y, double deg);

/* The trace's slopes at its n points into slope (dp/ddeg, caller's array),
 * and the trace evaluated with them: rd_gasflow_trace's value (bit for
 * bit) without computing two slopes at every call. */
void rd_gasflow_trace_slopes(int n, const double *x, const double *y, double *slope);
double rd_gasflow_trace_at(int n, const double *x, const double *y, const double *slope,
                           double deg);

#endif
