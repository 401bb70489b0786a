/*
 * rd_lift — the flexible split ring in its piston groove over engine cycles
 * (thesis 3.5, 2.4; MODEL.md "lift").  SI units; crank angles in the API in
 * degrees, alpha = omega t inside (rad), alpha = 0 at TDC.
 *
 * Unknowns.  Per segment i (n segments of rd_ring, split ring, band order =
 * segment order) the small displacement of its reference point P_i and its
 * small rotation, global components, q_i = (ux, uy, uz, rx, ry, rz), from
 * the installed reference (closed shape centred in the bore, bottom face on
 * the groove's lower flank, z = 0 at the ring's mid-plane), and their rates
 * v_i.  The state is interleaved per segment so that the Jacobian is banded:
 *     y[12 i + k] = q_i[k],  y[12 i + 6 + k] = v_i[k],  k = 0..5   (Q(), V())
 * Equations (linear kinematics: a point X of segment i moves by
 * u_i + r_i x (X - P_i)):
 *     dq_i/dt = v_i,   M_i dv_i/dt = -(K q)_i + f_i(t, q_i, v_i)
 * K: the ring's banded stiffness (rd_ring_assemble_band, kd = 11), M_i: the
 * segment's exact 6x6 mass matrix (inverted once by Cholesky, dpotrf/dpotri).
 * Segment i couples only to i +- 1, so d(ydot)/dy has upper bandwidth 11
 * (dv_i/dq_{i+1}) and lower bandwidth 23 (dv_{i+1}/dq_i).
 *
 * Piston (thesis 1.6-1.8).  s(alpha) = distance of the piston below TDC.
 *   approximate: s = r (1 - cos a + lambda/4 (1 - cos 2a))              (1.6)
 *                v = r w (sin a + lambda/2 sin 2a)                        (1.7)
 *                a = r w^2 (cos a + lambda cos 2a),  lambda = r / l       (1.8)
 *   exact:       s = r (1 - cos a) + l (1 - Q),  Q = sqrt(1 - lambda^2 sin^2 a)
 *                ds/da = r sin a (1 + lambda cos a / Q)
 *                d2s/da2 = r (cos a + lambda (cos 2a + lambda^2 sin^4 a) / Q^3)
 * The piston height is z_p = -s, so in the piston frame each segment feels
 * the pseudo-force -m z_p'' = +m s'' along z; for a rigid segment whose
 * centre of mass is off P_i the exact generalized force is M_i e_z s'' with
 * e_z = (0, 0, 1, 0, 0, 0) the unit axial translation.  Gravity: -g M_i e_z.
 *
 * Contacts (smooth penalties, pressure in Pa on a tributary area):
 *   p(delta, delta') = k sp(delta) phi(x),  x = c w(delta) delta' / (k sp(delta))
 *   sp = delta^2 / (2 d0) (0 < delta < d0),  delta - d0/2 (delta >= d0),  0 else
 *   w = sp' = min(delta / d0, 1);  phi(x) = 1 + x (x >= -1/2),
 *   e^{2x + 1} / 2 (x < -1/2)
 * i.e. a C1 linear spring with a quadratic start over d0 = 1e-4 axial
 * clearances, with Kelvin-Voigt damping c w delta' that fades exponentially
 * when the contact opens fast, so the contact never pulls and the pressure is
 * C1 in delta'.  c = 2 zeta sqrt(k m_a) with m_a the ring's mass per contact
 * area (rho h on a flank, rho b on the bore) and zeta = 5: an overdamped
 * contact, so a landing under load is plastic, without rebound (with this
 * law zeta = 1 still rebounds with restitution 0.16, zeta = 2: 0.06, 3: 0.02,
 * >= 5: none; the thesis' slap motion, oil squeeze damps real landings).
 * The energy it takes is the landing loss.
 *   Flanks: on the bottom and top faces, 3 arc positions (centres of thirds
 *   of the segment's arc) x 2 radii (inner and outer edge, each carrying its
 *   half of the face width).  Axial displacement of a point at in-plane
 *   offset d = X - P_i:  w = uz + rx dy - ry dx.  Lower flank penetration
 *   -w, upper flank penetration w - c_a (c_a = axial clearance).
 *   Bore: 3 points on the running face (mid-height), penetration
 *   delta_pre + u_r with u_r = e_r . (u + r x d) the outward displacement
 *   and delta_pre the preload penetration p(delta_pre) = p0; the ring's
 *   pretension (its spring-back from the free shape, not carried by the
 *   linear K) is the constant outward force p0 h (arc)/3 at each point, so
 *   the reference is in equilibrium.  p0 = 2 F_t / (d h)  (thesis 1.3).
 *   Groove back: 3 points on the inner face, penetration -u_r - c_r.
 * Default stiffness k (Pa/m, contact_stiffness = 0), the larger of
 *   k_load = P_max / (1e-3 c_a): the largest pressure the scene can put on a
 *     flank (inertia rho h r w^2 (1 + lambda), gravity, friction, gas)
 *     pushes it in by at most 1e-3 of the clearance;
 *   k_dyn = rho h (3e4 w)^2: the flank contact frequency w_c = sqrt(k / (rho h))
 *     is 3e4 times the crank's, so the damped contact follows the load with
 *     a lag 2 zeta / w_c = 3.3e-4 rad = 0.02 deg of crank.
 * Both effects shift the flank-change angles by far less than the flight
 * times (degrees); test_lift checks the angles over 2 decades of k.
 *
 * Friction (model != NONE), on each bore point, axial.  Sliding velocity of
 * the ring against the liner: ring velocity in the piston frame plus the
 * piston's velocity in the cylinder frame (-ds/dt):  u = w' - s'.
 *   Coulomb:  F = -mu N tanh(u / u_reg)
 *   Stribeck (2.9) with the Sommerfeld number (1.11):
 *     F = -tanh(u / u_reg) (C e^{-3 |So_lim / So|^2.5} + K / So) N,
 *     So = N_ring / (eta |u| h),  so K / So N = K eta |u| h N / N_ring.
 *   N is the point's bore normal force; N_ring = N L / s_k is the ring-
 *   equivalent normal force at that point's local line load (s_k its arc,
 *   L the whole running face), so a uniform load gives exactly (1.11) with
 *   the ring's total force and the hydrodynamic part sums to K eta u h over
 *   the ring, independent of n.  u_reg = 1e-3 x the mean piston speed.
 *
 * Gas (points > 0), gauge pressures interpolated linearly in crank angle,
 * periodic over 720 deg: "above" presses the top face down, "below" the
 * bottom face up, "behind" the back face outward (its resultant
 * p h 2 r_i sin(phi/2) along e_r, and through the bore contact it raises the
 * friction normal force).  The running face is sealed by the oil film and
 * carries no gas load (the thesis' three forces, Fig. 3.28).  Forces act at
 * the face centroids.  Areas:
 *   fixed (thesis): full faces, A = b R phi top and bottom.
 *   dynamic (the thesis' suggested improvement): a face sealing on a flank
 *   sees, across its contact land, a pressure falling linearly from the
 *   groove-back pressure (inner edge) to its own side's pressure (outer
 *   edge), i.e. the average (p_behind + p_own) / 2; a free face sees its
 *   own pressure.  The blend weight is the face's mean smoothstep(delta/d0)
 *   (3 x^2 - 2 x^3) over its contact points, C1 in the penetration.
 *
 * Integration: SUNDIALS CVODE, BDF of order <= 2, Newton with a band matrix
 * and band LU and the analytic Jacobian (jac()), so each step costs O(n).
 * Order <= 2: the undamped elastic modes of a finely cut ring are fast and
 * on the imaginary axis, where BDF3-5 are unstable (n = 200 took 70x more
 * steps); BDF2 is A-stable.  The Jacobian is re-evaluated and factored at
 * every step: a Newton matrix kept from a closed contact carries that
 * penalty's stiffness after the contact opened, and the modified Newton
 * iteration then converges falsely and holds the ring on the flank (landings
 * came 5-40 deg late with CVODE's default reuse; with any reuse the tests'
 * 1-DOF and stiffness checks fail at rtol 1e-6).  Tolerances: rtol; atol on the translations (m),
 * atol / R on the rotations, and atol w_v on their rates with w_v =
 * sqrt(a_ref / c_a), the rate of a flight across the clearance under the
 * scene's largest acceleration a_ref.  The step is bounded by 1 crank degree
 * so no gas-table feature or short contact is stepped over.
 *
 * Events: the ring's mean lift L (mean over segments of the bottom face's
 * axial position above the lower flank) and F, the total axial force on the
 * ring without the flank contacts (inertia, gravity, gas, friction; the
 * elastic forces sum to zero).  CVODE locates the roots of L (landing on the
 * lower flank), L - eps, c_a - L (landing on the upper flank), c_a - L - eps
 * (eps = 1e-2 c_a) and F.  A landing is dated where L reaches the flank.  A
 * leave is dated where F turns away from the flank (the 1-DOF definition:
 * a seated ring separates with zero velocity and acceleration, so the
 * geometric separation time is ill-conditioned, ~(6 atol / jerk)^(1/3) =
 * 0.3 deg at 1000 rpm), and confirmed only when L has moved eps off the
 * flank; if F turns back first, nothing is reported.  So hops lower than 1 %
 * of the clearance (micro-bounces, the penalty's settling, an edge lifting
 * under a twist) are not flank changes.  A sample's flank: lower if L < eps,
 * upper if L > c_a - eps, else free.
 */
#include "rd_lift.h"

#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include "rd_internal.h"
#include "rd_lift_internal.h"

#define GRAVITY 9.80665
#define ARC_POINTS 3              /* contact positions along a segment's arc */
#define FLANK_POINTS (2 * ARC_POINTS)
#define SMOOTH_FRACTION 1e-4      /* d0 / c_a: quadratic start of the penalty */
#define EVENT_FRACTION 1e-2       /* eps / c_a: smallest hop that is a flank change */
#define DAMPING_RATIO 5.0         /* zeta of the contacts: landings do not rebound */
#define LOAD_PENETRATION 1e-3     /* largest load penetration / c_a for the default k */
#define CONTACT_FREQ_RATIO 3e4    /* flank contact frequency / crank frequency */
#define UREG_FRACTION 1e-3        /* u_reg / mean piston speed */
#define HMAX_DEG 1.0              /* largest step, crank degrees */
#define MEMORY_BOUND 2e6 /* samples x segments: 16 MB here, ~40 MB as JSON text */
#define MU 11                     /* upper half bandwidth of the Jacobian */
#define ML 23                     /* lower half bandwidth */
#define MAX_ORDER 2                /* BDF order bound (header comment) */

/* State access, cvRoberts style. */
#define Q(y, i) ((y) + 12 * (size_t)(i))
#define V(y, i) ((y) + 12 * (size_t)(i) + 6)

/* ---------------------------------------------------------------- params */

void rd_lift_params_default(rd_lift_params *p)
{
    memset(p, 0, sizeof *p);
    p->engine.speed_rpm = 1000.0;
    p->engine.crank_radius = 0.04345;
    p->engine.rod_length = 0.130;
    p->engine.kinematics = RD_KINEMATICS_EXACT;
    p->engine.cycles = 2.0;
    p->groove.axial_clearance = 3e-5;
    p->groove.radial_clearance = 5e-4;
    p->gravity = 0;
    p->friction.model = RD_FRICTION_NONE;
    p->friction.coefficient = 0.1;
    /* Stribeck defaults for the thesis ring: SAE 30-40 oil near 100 C (eta =
     * 0.01 Pa s); So_lim = 1e7 puts the mixed-to-hydrodynamic transition near
     * 0.5 m/s sliding speed (So = 63 N / (eta u h)); K = 2e4 gives about 1.2 N
     * (an effective coefficient 0.02) at 5 m/s.  Calibrate for real use. */
    p->friction.viscosity = 0.01;
    p->friction.sommerfeld_transition = 1e7;
    p->friction.hydrodynamic_slope = 2e4;
    p->gas.points = 0;
    p->gas.active_area = RD_GAS_AREA_FIXED;
    p->contact_stiffness = 0.0;
    p->step_deg = 1.0;
    p->rtol = 1e-6;
    p->atol = 1e-9;
    p->max_steps = 500000;
    p->estimate_error = 1;
}

static int check_range(double v, double lo, double hi, const char *path, const char *unit,
                       rd_error *err)
{
    if (!isfinite(v) || v < lo || v > hi)
        return rd_error_set(err, RD_EINVAL, path, "%s = %g %s is out of range: allowed %g to %g %s.",
                            path, v, unit, lo, hi, unit);
    return RD_OK;
}

static int lift_samples(const rd_lift_params *p)
{
    double total = p->engine.cycles * 720.0;
    return (int)ceil(total / p->step_deg - 1e-9) + 1;
}

static int check_table(const double *v, int n, const char *path, rd_error *err)
{
    if (!v)
        return rd_error_set(err, RD_EINVAL, path, "%s is missing (the gas table has %d points).",
                            path, n);
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]) || v[i] < -1e6 || v[i] > 1e9)
            return rd_error_set(err, RD_EINVAL, path,
                                "%s[%d] = %g Pa is out of range: allowed -1e6 to 1e9 Pa (gauge).",
                                path, i, v[i]);
    return RD_OK;
}

int rd_lift_validate(const rd_lift_params *p, const rd_ring_params *ring, int segments,
                     rd_error *err)
{
    int rc;
    if ((rc = rd_ring_validate(ring, segments, 0, err)))
        return rc;
    if (ring->section != RD_SECTION_RECTANGLE)
        return rd_error_set(err, RD_EINVAL, "/ring/section",
                            "the lift analysis needs a rectangular ring section (its faces "
                            "seal on the groove flanks).");
    if (segments < 4 || segments > RD_LIFT_SEGMENTS_MAX)
        return rd_error_set(err, segments > RD_LIFT_SEGMENTS_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/discretization/segments",
                            "/discretization/segments = %d is out of range for a lift analysis: "
                            "allowed 4 to %d.",
                            segments, RD_LIFT_SEGMENTS_MAX);
    const rd_engine_params *e = &p->engine;
    if ((rc = check_range(e->speed_rpm, 1.0, 30000.0, "/engine/speed_rpm", "rpm", err)) ||
        (rc = check_range(e->crank_radius, 1e-3, 1.0, "/engine/crank_radius", "m", err)))
        return rc;
    /* lambda = r / l <= 0.9: the exact slider-crank needs lambda < 1; real
     * engines have 0.2..0.4. */
    if (!isfinite(e->rod_length) || e->rod_length < e->crank_radius / 0.9 || e->rod_length > 10.0)
        return rd_error_set(err, RD_EINVAL, "/engine/rod_length",
                            "/engine/rod_length = %g m is out of range: allowed %g m (crank "
                            "radius / 0.9) to 10 m.",
                            e->rod_length, e->crank_radius / 0.9);
    if (e->kinematics != RD_KINEMATICS_EXACT && e->kinematics != RD_KINEMATICS_APPROXIMATE)
        return rd_error_set(err, RD_EINVAL, "/engine/kinematics",
                            "/engine/kinematics = %d is unknown: use exact or approximate.",
                            e->kinematics);
    if (!isfinite(e->cycles) || e->cycles <= 0.0 || e->cycles > RD_LIFT_CYCLES_MAX)
        return rd_error_set(err, e->cycles > RD_LIFT_CYCLES_MAX ? RD_ELIMIT : RD_EINVAL,
                            "/engine/cycles",
                            "/engine/cycles = %g is out of range: allowed above 0 up to %g.",
                            e->cycles, RD_LIFT_CYCLES_MAX);
    if ((rc = check_range(p->groove.axial_clearance, 1e-7, 5e-3, "/groove/axial_clearance", "m",
                          err)) ||
        (rc = check_range(p->groove.radial_clearance, 1e-6, 1e-2, "/groove/radial_clearance",
                          "m", err)))
        return rc;
    if (p->gravity != 0 && p->gravity != 1)
        return rd_error_set(err, RD_EINVAL, "/physics/gravity",
                            "/physics/gravity = %d: use true or false.", p->gravity);
    const rd_friction_params *f = &p->friction;
    if (f->model != RD_FRICTION_NONE && f->model != RD_FRICTION_COULOMB &&
        f->model != RD_FRICTION_STRIBECK)
        return rd_error_set(err, RD_EINVAL, "/physics/friction/model",
                            "/physics/friction/model = %d is unknown: use coulomb or stribeck.",
                            f->model);
    if (f->model != RD_FRICTION_NONE &&
        (rc = check_range(f->coefficient, 0.0, 10.0, "/physics/friction/coefficient", "", err)))
        return rc;
    if (f->model == RD_FRICTION_STRIBECK &&
        ((rc = check_range(f->viscosity, 1e-5, 10.0, "/physics/friction/viscosity", "Pa s",
                           err)) ||
         (rc = check_range(f->sommerfeld_transition, 0.0, 1e15,
                           "/physics/friction/sommerfeld_transition", "", err)) ||
         (rc = check_range(f->hydrodynamic_slope, 0.0, 1e12,
                           "/physics/friction/hydrodynamic_slope", "", err))))
        return rc;
    const rd_gas_params *g = &p->gas;
    if (g->points != 0) {
        if (g->points < 2 || g->points > RD_LIFT_TABLE_MAX)
            return rd_error_set(err, g->points > RD_LIFT_TABLE_MAX ? RD_ELIMIT : RD_EINVAL,
                                "/physics/gas/crank_deg",
                                "/physics/gas/crank_deg has %d points: allowed 2 to %d.",
                                g->points, RD_LIFT_TABLE_MAX);
        if (!g->crank_deg)
            return rd_error_set(err, RD_EINVAL, "/physics/gas/crank_deg",
                                "/physics/gas/crank_deg is missing.");
        for (int i = 0; i < g->points; i++) {
            double a = g->crank_deg[i];
            if (!isfinite(a) || a < 0.0 || a > 720.0)
                return rd_error_set(err, RD_EINVAL, "/physics/gas/crank_deg",
                                    "/physics/gas/crank_deg[%d] = %g deg is out of range: "
                                    "allowed 0 to 720 deg.",
                                    i, a);
            if (i > 0 && !(a > g->crank_deg[i - 1]))
                return rd_error_set(err, RD_EINVAL, "/physics/gas/crank_deg",
                                    "/physics/gas/crank_deg must be strictly increasing: "
                                    "[%d] = %g deg follows %g deg.",
                                    i, a, g->crank_deg[i - 1]);
        }
        if ((rc = check_table(g->above, g->points, "/physics/gas/above", err)) ||
            (rc = check_table(g->behind, g->points, "/physics/gas/behind", err)) ||
            (rc = check_table(g->below, g->points, "/physics/gas/below", err)))
            return rc;
        if (g->active_area != RD_GAS_AREA_FIXED && g->active_area != RD_GAS_AREA_DYNAMIC)
            return rd_error_set(err, RD_EINVAL, "/physics/gas/active_area",
                                "/physics/gas/active_area = %d is unknown: use fixed or dynamic.",
                                g->active_area);
    }
    if (p->contact_stiffness != 0.0 &&
        (rc = check_range(p->contact_stiffness, 1e3, 1e20, "/contact/stiffness",
                          "Pa/m (or 0 for the default)", err)))
        return rc;
    if ((rc = check_range(p->step_deg, 1e-3, 90.0, "/output/step_deg", "deg", err)) ||
        (rc = check_range(p->rtol, 1e-12, 1e-2, "/numerics/rtol", "", err)) ||
        (rc = check_range(p->atol, 1e-16, 1e-5, "/numerics/atol", "m", err)))
        return rc;
    if (p->max_steps < 100 || p->max_steps > 1000000000L)
        return rd_error_set(err, RD_EINVAL, "/numerics/max_steps",
                            "/numerics/max_steps = %ld is out of range: allowed 100 to 1e9.",
                            p->max_steps);
    if (p->estimate_error != 0 && p->estimate_error != 1)
        return rd_error_set(err, RD_EINVAL, "/numerics/error_estimate",
                            "/numerics/error_estimate = %d: use true or false.",
                            p->estimate_error);
    double samples = ceil(e->cycles * 720.0 / p->step_deg - 1e-9) + 1.0;
    if (samples > RD_LIFT_SAMPLES_MAX)
        return rd_error_set(err, RD_ELIMIT, "/output/step_deg",
                            "/output/step_deg = %g deg over %g cycles gives %.0f output samples; "
                            "at most %d are allowed: use a larger step or fewer cycles.",
                            p->step_deg, e->cycles, samples, RD_LIFT_SAMPLES_MAX);
    if (samples * segments > MEMORY_BOUND)
        return rd_error_set(err, RD_ELIMIT, "/output/step_deg",
                            "%.0f output samples x %d segments = %.3g per-segment values; at "
                            "most %g are allowed: use a larger /output/step_deg, fewer cycles or "
                            "fewer segments.",
                            samples, segments, samples * segments, MEMORY_BOUND);
    return RD_OK;
}

/* ------------------------------------------------------------- kinematics */

void rd_lift_piston(const rd_engine_params *e, double alpha, double *s, double *v, double *a)
{
    double r = e->crank_radius, lam = r / e->rod_length;
    double w = e->speed_rpm * 2.0 * M_PI / 60.0;
    double sa = sin(alpha), ca = cos(alpha);
    double s_, ds, dds; /* s and its derivatives with respect to alpha */
    if (e->kinematics == RD_KINEMATICS_APPROXIMATE) {
        s_ = r * (1.0 - ca + 0.25 * lam * (1.0 - cos(2.0 * alpha)));        /* (1.6) */
        ds = r * (sa + 0.5 * lam * sin(2.0 * alpha));                        /* (1.7) / w */
        dds = r * (ca + lam * cos(2.0 * alpha));                             /* (1.8) / w^2 */
    } else {
        double Q = sqrt(1.0 - lam * lam * sa * sa);
        /* l (1 - Q) = l lam^2 sin^2 / (1 + Q): no cancellation */
        s_ = r * (1.0 - ca) + e->rod_length * lam * lam * sa * sa / (1.0 + Q);
        ds = r * sa * (1.0 + lam * ca / Q);
        dds = r * (ca + lam * (cos(2.0 * alpha) + lam * lam * pow(sa, 4)) / (Q * Q * Q));
    }
    if (s)
        *s = s_;
    if (v)
        *v = w * ds;
    if (a)
        *a = w * w * dds;
}

/* ---------------------------------------------------------------- context */

typedef struct lift_ctx {
    const rd_ring *ring;
    const rd_lift_params *p;
    int n, piston_fixed;
    double omega;               /* crank speed, rad/s */
    double ca, cr;              /* axial and radial clearances */
    double k, d0, c_flank, c_rad;
    double eps;                 /* event threshold on the mean lift */
    double g_on;                /* gravity, m/s^2, or 0 */
    double p0, delta_pre;       /* pretension pressure and bore preload penetration */
    double ureg, mu, eta, so_lim, kh, h, L_run;
    rd_band K;
    double *Minv;               /* n x 36 row-major */
    double *Mez;                /* n x 6: M_i e_z */
    double *fl_d;               /* n x FLANK_POINTS x 2: in-plane offsets of flank points */
    double fl_area[FLANK_POINTS];
    double *bo_d, *bo_e;        /* n x ARC_POINTS x 2: bore point offsets, radial unit */
    double *ba_d;               /* n x ARC_POINTS x 2: back point offsets */
    double bo_area, ba_area;    /* per point */
    double *cen_d;              /* n x 2: face centroid offsets */
    double *e_r;                /* n x 2: segment radial unit */
    double *e_t;                /* n x 2: segment tangential unit */
    double face_area, back_chord_area;
    double *qbuf, *fbuf;        /* 12 n and 6 n scratch */
    double *MK;                 /* n x 3 x 36: -M_i^-1 K_ij, j = i-1, i, i+1 */
    double *Dq, *Dv;            /* n x 36: local force derivatives (Jacobian) */
    double friction;            /* total axial friction of the last rhs call, N */
    double fz_ext;              /* total axial force on the ring except the flanks, N */
    rd_lift_energy *energy;     /* non-NULL: segment_forces accumulates the bookkeeping */
    char cv_msg[200];           /* CVODE's last error message */
} lift_ctx;

static double gas_at(const rd_gas_params *g, const double *val, double deg)
{
    const double *x = g->crank_deg;
    int n = g->points;
    deg = fmod(deg, 720.0);
    if (deg < 0)
        deg += 720.0;
    if (deg < x[0] || deg >= x[n - 1]) {
        /* wrap-around interval [x[n-1], x[0] + 720] */
        double lo = x[n - 1], hi = x[0] + 720.0, d = deg < x[0] ? deg + 720.0 : deg;
        if (hi - lo <= 0.0)
            return val[0];
        return val[n - 1] + (val[0] - val[n - 1]) * (d - lo) / (hi - lo);
    }
    int a = 0, b = n - 1; /* x[a] <= deg < x[b] */
    while (b - a > 1) {
        int m = (a + b) / 2;
        if (x[m] <= deg)
            a = m;
        else
            b = m;
    }
    return val[a] + (val[b] - val[a]) * (deg - x[a]) / (x[b] - x[a]);
}

/* Contact pressure p(delta, delta') of the header comment, and its partial
 * derivatives p_d = dp/d delta, p_dd = dp/d delta' (for the Jacobian). */
static double contact_pressure(const lift_ctx *c, double d, double dd, double cdamp,
                               double *p_d, double *p_dd)
{
    *p_d = *p_dd = 0.0;
    if (d <= 0.0)
        return 0.0;
    double sp, w, w_d;
    if (d < c->d0) {
        sp = 0.5 * d * d / c->d0;
        w = d / c->d0;
        w_d = 1.0 / c->d0;
    } else {
        sp = d - 0.5 * c->d0;
        w = 1.0;
        w_d = 0.0;
    }
    double pe = c->k * sp, pe_d = c->k * w;
    double pd = cdamp * w * dd, pd_d = cdamp * w_d * dd, pd_dd = cdamp * w;
    if (pd >= -0.5 * pe) {
        *p_d = pe_d + pd_d;
        *p_dd = pd_dd;
        return pe + pd;
    }
    if (pe <= 0.0)
        return 0.0;
    /* opening fast: pe phi(x), x = pd / pe, phi = e^{2x + 1} / 2 for x < -1/2 */
    double E = exp(2.0 * pd / pe + 1.0);
    *p_d = 0.5 * pe_d * E + E * (pd_d - pd * pe_d / pe);
    *p_dd = E * pd_dd;
    return 0.5 * pe * E;
}

/* Inverse of the elastic part: the penetration where k sp(delta) = p. */
static double contact_inverse(const lift_ctx *c, double p)
{
    double pl = 0.5 * c->k * c->d0; /* pressure at the end of the quadratic start */
    if (p <= 0.0)
        return 0.0;
    if (p < pl)
        return sqrt(2.0 * c->d0 * p / c->k);
    return p / c->k + 0.5 * c->d0;
}

/* Elastic part k sp(delta) of the contact pressure, and its potential
 * k int_0^delta sp per unit area into *U (energy bookkeeping). */
static double contact_elastic(const lift_ctx *c, double d, double *U)
{
    *U = 0.0;
    if (d <= 0.0)
        return 0.0;
    if (d < c->d0) {
        *U = c->k * d * d * d / (6.0 * c->d0);
        return 0.5 * c->k * d * d / c->d0;
    }
    *U = c->k * (0.5 * d * d - 0.5 * c->d0 * d + c->d0 * c->d0 / 6.0);
    return c->k * (d - 0.5 * c->d0);
}

/* Adds one contact (pressure p at penetration d, rate dd, area A) to the
 * energy bookkeeping. */
static void book_contact(lift_ctx *c, double p, double d, double dd, double A)
{
    double U, pe = contact_elastic(c, d, &U);
    c->energy->contact += A * U;
    c->energy->damping_power -= (p - pe) * A * dd;
}

/* smoothstep(x) = 3 x^2 - 2 x^3 on [0, 1], and its derivative. */
static double smoothstep(double x, double *dx)
{
    *dx = 0.0;
    if (x <= 0.0)
        return 0.0;
    if (x >= 1.0)
        return 1.0;
    *dx = 6.0 * x * (1.0 - x);
    return x * x * (3.0 - 2.0 * x);
}

/* Friction force F(N, u) on one bore point (header comment) and dF/dN, dF/du. */
static double friction_force(const lift_ctx *c, double N, double u, double *F_N, double *F_u)
{
    double T = tanh(u / c->ureg), T_u = (1.0 - T * T) / c->ureg;
    if (c->p->friction.model == RD_FRICTION_COULOMB) {
        *F_N = -c->mu * T;
        *F_u = -c->mu * N * T_u;
        return -c->mu * N * T;
    }
    /* Stribeck (2.9): B = C e^{-3 r^2.5} N, r = So_lim / So; H = K eta |u| h s_k / L */
    double share = c->bo_area / (c->h * c->L_run); /* s_k / L */
    double sg = u >= 0.0 ? 1.0 : -1.0, au = fabs(u);
    double H = c->kh * c->eta * au * c->h * share, H_u = c->kh * c->eta * c->h * share * sg;
    double B = 0.0, B_N = 0.0, B_u = 0.0;
    if (N > 0.0) {
        double r_u = c->so_lim * c->eta * c->h * share / N; /* r / |u| */
        double r = r_u * au, r15 = pow(r, 1.5), E = exp(-3.0 * r15 * r);
        B = c->mu * E * N;
        B_N = c->mu * E * (1.0 + 7.5 * r15 * r);
        B_u = -7.5 * c->mu * E * r15 * r_u * N * sg;
    }
    *F_N = -T * B_N;
    *F_u = -T_u * (B + H) - T * (B_u + H_u);
    return -T * (B + H);
}

/* Generalized directions: axial force at in-plane offset d, and radial
 * force along e at offset d (so that w = a . q, u_r = b . q). */
static void axial_dir(const double *d, double a[6])
{
    a[0] = a[1] = a[5] = 0.0;
    a[2] = 1.0;
    a[3] = d[1];
    a[4] = -d[0];
}

static void radial_dir(const double *d, const double *e, double b[6])
{
    b[0] = e[0];
    b[1] = e[1];
    b[2] = b[3] = b[4] = 0.0;
    b[5] = d[0] * e[1] - d[1] * e[0];
}

static double dot6(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

/* Axial displacement w = uz + rx dy - ry dx of a point at offset d. */
static double axial(const double *u, const double *d)
{
    return u[2] + u[3] * d[1] - u[4] * d[0];
}

static void add6(double *f, const double *a, double F)
{
    for (int k = 0; k < 6; k++)
        f[k] += F * a[k];
}

/* D += s a b^T (6x6 row-major); D may be NULL. */
static void rank1(double *D, double s, const double *a, const double *b)
{
    if (!D || s == 0.0)
        return;
    for (int r = 0; r < 6; r++)
        if (a[r] != 0.0)
            for (int k = 0; k < 6; k++)
                D[6 * r + k] += s * a[r] * b[k];
}

/* Generalized forces on all segments (without -K q) into c->fbuf.  With Dq,
 * Dv (n x 36 each) also their local derivatives df_i/dq_i, df_i/dv_i. */
static void segment_forces(lift_ctx *c, double t, const double *y, double *Dq, double *Dv)
{
    const rd_lift_params *p = c->p;
    double s, sd = 0.0, sdd = 0.0, deg = c->omega * t * 180.0 / M_PI;
    if (!c->piston_fixed)
        rd_lift_piston(&p->engine, c->omega * t, &s, &sd, &sdd);
    double acc = sdd - c->g_on; /* pseudo-acceleration along +z */
    double pa = 0.0, pbh = 0.0, pbl = 0.0;
    int gas = p->gas.points > 0, dynamic = gas && p->gas.active_area == RD_GAS_AREA_DYNAMIC;
    int fric = p->friction.model != RD_FRICTION_NONE;
    if (gas) {
        pa = gas_at(&p->gas, p->gas.above, deg);
        pbh = gas_at(&p->gas, p->gas.behind, deg);
        pbl = gas_at(&p->gas, p->gas.below, deg);
    }
    double ftot = 0.0, fz = 0.0;
    for (int i = 0; i < c->n; i++) {
        const double *q = Q(y, i), *v = V(y, i);
        double *f = c->fbuf + 6 * i;
        double *dq = Dq ? Dq + 36 * (size_t)i : NULL, *dv = Dv ? Dv + 36 * (size_t)i : NULL;
        if (dq) {
            memset(dq, 0, 36 * sizeof *dq);
            memset(dv, 0, 36 * sizeof *dv);
        }
        double a[6], b[6], pl_d, pl_dd, pu_d, pu_dd;
        /* inertia pseudo-force and gravity: M_i e_z (s'' - g) */
        for (int k = 0; k < 6; k++)
            f[k] = c->Mez[6 * i + k] * acc;
        fz += f[2];
        /* flanks; dynamic gas areas: the sealing weights and their gradients */
        double seal_lo = 0.0, seal_up = 0.0, g_lo[6] = {0}, g_up[6] = {0};
        for (int k = 0; k < FLANK_POINTS; k++) {
            const double *d = c->fl_d + 2 * (FLANK_POINTS * (size_t)i + k);
            axial_dir(d, a);
            double w = dot6(a, q), wd = dot6(a, v), A = c->fl_area[k];
            double plo = contact_pressure(c, -w, -wd, c->c_flank, &pl_d, &pl_dd);
            double pup = contact_pressure(c, w - c->ca, wd, c->c_flank, &pu_d, &pu_dd);
            add6(f, a, (plo - pup) * A);
            if (c->energy) {
                book_contact(c, plo, -w, -wd, A);
                book_contact(c, pup, w - c->ca, wd, A);
            }
            rank1(dq, -A * (pl_d + pu_d), a, a);
            rank1(dv, -A * (pl_dd + pu_dd), a, a);
            if (dynamic) {
                double sl_d, su_d;
                seal_lo += A * smoothstep(-w / c->d0, &sl_d);
                seal_up += A * smoothstep((w - c->ca) / c->d0, &su_d);
                add6(g_lo, a, -A * sl_d / c->d0);
                add6(g_up, a, A * su_d / c->d0);
            }
        }
        /* bore: pretension outward, contact inward, friction axial */
        for (int k = 0; k < ARC_POINTS; k++) {
            size_t o = 2 * (ARC_POINTS * (size_t)i + k);
            const double *d = c->bo_d + o, *e = c->bo_e + o;
            radial_dir(d, e, b);
            double ur = dot6(b, q), urd = dot6(b, v), P_d, P_dd;
            double N = c->bo_area * contact_pressure(c, c->delta_pre + ur, urd, c->c_rad, &P_d,
                                                     &P_dd);
            add6(f, b, c->p0 * c->bo_area - N);
            if (c->energy) {
                book_contact(c, N / c->bo_area, c->delta_pre + ur, urd, c->bo_area);
                c->energy->contact -= c->p0 * c->bo_area * ur;
            }
            rank1(dq, -c->bo_area * P_d, b, b);
            rank1(dv, -c->bo_area * P_dd, b, b);
            if (fric) {
                axial_dir(d, a);
                double F_N, F_u, u = dot6(a, v) - sd, F = friction_force(c, N, u, &F_N, &F_u);
                add6(f, a, F);
                if (c->energy)
                    c->energy->friction_power += F * u;
                ftot += F;
                rank1(dq, F_N * c->bo_area * P_d, a, b);
                rank1(dv, F_N * c->bo_area * P_dd, a, b);
                rank1(dv, F_u, a, a);
            }
        }
        /* groove back */
        for (int k = 0; k < ARC_POINTS; k++) {
            size_t o = 2 * (ARC_POINTS * (size_t)i + k);
            radial_dir(c->ba_d + o, c->bo_e + o, b);
            double P_d, P_dd;
            double pen = -dot6(b, q) - c->cr;
            double P = contact_pressure(c, pen, -dot6(b, v), c->c_rad, &P_d, &P_dd);
            add6(f, b, P * c->ba_area);
            if (c->energy)
                book_contact(c, P, pen, -dot6(b, v), c->ba_area);
            rank1(dq, -c->ba_area * P_d, b, b);
            rank1(dv, -c->ba_area * P_dd, b, b);
        }
        /* gas */
        if (gas) {
            double ptop = pa, pbot = pbl;
            axial_dir(c->cen_d + 2 * i, a);
            if (dynamic) {
                double wl = seal_lo / c->face_area, wu = seal_up / c->face_area;
                pbot += wl * 0.5 * (pbh - pbl);
                ptop += wu * 0.5 * (pbh - pa);
                /* d(pbot - ptop) A_face / dq = (pbh - pbl)/2 g_lo - (pbh - pa)/2 g_up */
                rank1(dq, 0.5 * (pbh - pbl), a, g_lo);
                rank1(dq, -0.5 * (pbh - pa), a, g_up);
            }
            add6(f, a, (pbot - ptop) * c->face_area);
            fz += (pbot - ptop) * c->face_area;
            radial_dir(c->cen_d + 2 * i, c->e_r + 2 * i, b);
            add6(f, b, pbh * c->back_chord_area);
        }
    }
    c->friction = ftot;
    c->fz_ext = fz + ftot;
}

/* The right-hand side: ydot = (v, M^-1 (f - K q)) per segment. */
static int rhs(sunrealtype t, N_Vector yv, N_Vector ydv, void *user)
{
    lift_ctx *c = user;
    const double *y = N_VGetArrayPointer(yv);
    double *yd = N_VGetArrayPointer(ydv);
    segment_forces(c, t, y, NULL, NULL);
    for (int i = 0; i < c->n; i++)
        memcpy(c->qbuf + 6 * i, Q(y, i), 6 * sizeof(double));
    double *Kq = c->qbuf + 6 * (size_t)c->n; /* second half of the scratch */
    rd_band_symv(&c->K, c->qbuf, Kq);
    for (int i = 0; i < c->n; i++) {
        const double *Mi = c->Minv + 36 * (size_t)i;
        double fi[6];
        for (int k = 0; k < 6; k++)
            fi[k] = c->fbuf[6 * i + k] - Kq[6 * i + k];
        memcpy(Q(yd, i), V(y, i), 6 * sizeof(double));
        double *acc = V(yd, i);
        for (int r = 0; r < 6; r++)
            acc[r] = dot6(Mi + 6 * r, fi);
    }
    for (size_t j = 0; j < 12 * (size_t)c->n; j++)
        if (!isfinite(yd[j]))
            return 1; /* recoverable: CVODE retries with a smaller step */
    return 0;
}

/* Jacobian d(ydot)/dy, band (MU, ML):
 *   d(dq_i/dt)/dv_i = I,
 *   d(dv_i/dt)/dq_j = -M_i^-1 K_ij (+ M_i^-1 df_i/dq_i for j = i),
 *   d(dv_i/dt)/dv_i = M_i^-1 df_i/dv_i.
 * The constant -M_i^-1 K_ij are precomputed (c->MK). */
static int jac(sunrealtype t, N_Vector yv, N_Vector fy, SUNMatrix J, void *user, N_Vector t1,
               N_Vector t2, N_Vector t3)
{
    (void)fy;
    (void)t1;
    (void)t2;
    (void)t3;
    lift_ctx *c = user;
    const double *y = N_VGetArrayPointer(yv);
    segment_forces(c, t, y, c->Dq, c->Dv);
    SUNMatZero(J);
    for (int i = 0; i < c->n; i++) {
        sunindextype rq = 12 * (sunindextype)i, rv = rq + 6;
        const double *Mi = c->Minv + 36 * (size_t)i;
        const double *dq = c->Dq + 36 * (size_t)i, *dv = c->Dv + 36 * (size_t)i;
        for (int k = 0; k < 6; k++)
            SM_ELEMENT_B(J, rq + k, rv + k) = 1.0;
        for (int j = i - 1; j <= i + 1; j++) {
            if (j < 0 || j >= c->n)
                continue;
            const double *B = c->MK + 36 * (3 * (size_t)i + (j - i + 1));
            sunindextype cq = 12 * (sunindextype)j;
            for (int r = 0; r < 6; r++)
                for (int k = 0; k < 6; k++) {
                    double v = B[6 * r + k];
                    if (j == i)
                        for (int m = 0; m < 6; m++)
                            v += Mi[6 * r + m] * dq[6 * m + k];
                    SM_ELEMENT_B(J, rv + r, cq + k) = v;
                }
        }
        for (int r = 0; r < 6; r++)
            for (int k = 0; k < 6; k++) {
                double v = 0.0;
                for (int m = 0; m < 6; m++)
                    v += Mi[6 * r + m] * dv[6 * m + k];
                SM_ELEMENT_B(J, rv + r, rv + k) = v;
            }
    }
    return 0;
}

/* Mean lift L: mean axial position of the bottom-face contact points. */
static double mean_lift(const lift_ctx *c, const double *y, double *seg)
{
    double sum = 0.0;
    for (int i = 0; i < c->n; i++) {
        double s = 0.0;
        for (int k = 0; k < FLANK_POINTS; k++)
            s += axial(Q(y, i), c->fl_d + 2 * (FLANK_POINTS * (size_t)i + k));
        s /= FLANK_POINTS;
        if (seg)
            seg[i] = s;
        sum += s;
    }
    return sum / c->n;
}

/* Root functions (directions in ROOT_DIR): landing on the lower flank,
 * leave confirmed, landing on the upper flank, leave confirmed, and the
 * ring's total axial load without the flanks (its sign change dates a
 * leave).  An exact zero is nudged up: CVODE stops with an error when a
 * root function stays exactly zero just after a root. */
#define N_ROOTS 5
static int roots(sunrealtype t, N_Vector yv, sunrealtype *g, void *user)
{
    lift_ctx *c = user;
    const double *y = N_VGetArrayPointer(yv);
    double L = mean_lift(c, y, NULL);
    segment_forces(c, t, y, NULL, NULL);
    g[0] = L;
    g[1] = L - c->eps;
    g[2] = c->ca - L;
    g[3] = c->ca - L - c->eps;
    g[4] = c->fz_ext;
    for (int i = 0; i < N_ROOTS; i++)
        if (g[i] == 0.0)
            g[i] = 1e-300;
    return 0;
}

static void cv_silent(int code, const char *module, const char *function, char *msg, void *user)
{
    (void)code;
    (void)module;
    (void)function;
    lift_ctx *c = user;
    snprintf(c->cv_msg, sizeof c->cv_msg, "%s", msg ? msg : "");
}

/* ------------------------------------------------------- default stiffness */

static double omega_of(const rd_engine_params *e) { return e->speed_rpm * 2.0 * M_PI / 60.0; }

static double table_max_abs(const rd_gas_params *g, const double *v)
{
    double m = 0.0;
    for (int i = 0; i < g->points; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* Largest pressure the scene can put on a flank, Pa. */
static double flank_pressure_scale(const rd_ring_params *ring, const rd_lift_params *p)
{
    const rd_engine_params *e = &p->engine;
    double w = omega_of(e), lam = e->crank_radius / e->rod_length;
    double rho_h = ring->density * ring->axial_height;
    double P = rho_h * e->crank_radius * w * w * (1.0 + lam);
    if (p->gravity)
        P = fmax(P, rho_h * GRAVITY);
    if (p->friction.model != RD_FRICTION_NONE) {
        /* mu p0 h / b: the friction force per unit flank area */
        double p0 = 2.0 * ring->tangential_force / (ring->diameter * ring->axial_height);
        double pf = p->friction.coefficient * p0 * ring->axial_height / ring->radial_width;
        if (p->friction.model == RD_FRICTION_STRIBECK) {
            /* + the hydrodynamic K eta u h per unit length at the peak speed */
            double umax = e->crank_radius * w * (1.0 + lam);
            pf += p->friction.hydrodynamic_slope * p->friction.viscosity * umax *
                  ring->axial_height / (M_PI * ring->diameter * ring->radial_width);
        }
        P = fmax(P, pf);
    }
    if (p->gas.points > 0) {
        P = fmax(P, table_max_abs(&p->gas, p->gas.above));
        P = fmax(P, table_max_abs(&p->gas, p->gas.behind));
        P = fmax(P, table_max_abs(&p->gas, p->gas.below));
    }
    return P;
}

double rd_lift_contact_stiffness_default(const rd_ring_params *ring, const rd_lift_params *p)
{
    double w = omega_of(&p->engine);
    double k_load = flank_pressure_scale(ring, p) / (LOAD_PENETRATION * p->groove.axial_clearance);
    double wc = CONTACT_FREQ_RATIO * w;
    double k_dyn = ring->density * ring->axial_height * wc * wc;
    return fmax(k_load, k_dyn);
}

double rd_lift_friction_ureg(const rd_lift_params *p)
{
    /* mean piston speed = 2 x stroke x revolutions per second */
    double mean_speed = 4.0 * p->engine.crank_radius * p->engine.speed_rpm / 60.0;
    return UREG_FRACTION * mean_speed;
}

/* ------------------------------------------------------------------ setup */

static void ctx_cleanup(lift_ctx *c)
{
    rd_band_cleanup(&c->K);
    free(c->Minv);
    free(c->Mez);
    free(c->fl_d);
    free(c->bo_d);
    free(c->bo_e);
    free(c->ba_d);
    free(c->cen_d);
    free(c->e_r);
    free(c->e_t);
    free(c->qbuf);
    free(c->fbuf);
    free(c->MK);
    free(c->Dq);
    free(c->Dv);

}

static int ctx_init(lift_ctx *c, const rd_ring *ring, const rd_lift_params *p,
                    const rd_lift_setup *setup, rd_error *err)
{
    int n = rd_ring_get_segments(ring), rc;
    const rd_ring_params *rp = rd_ring_get_params(ring);
    const rd_ring_section *sec = rd_ring_get_section(ring);
    memset(c, 0, sizeof *c);
    c->ring = ring;
    c->p = p;
    c->n = n;
    c->piston_fixed = setup && setup->piston_fixed;
    c->omega = omega_of(&p->engine);
    c->ca = p->groove.axial_clearance;
    c->cr = p->groove.radial_clearance;
    c->k = p->contact_stiffness > 0.0 ? p->contact_stiffness
                                      : rd_lift_contact_stiffness_default(rp, p);
    c->d0 = SMOOTH_FRACTION * c->ca;
    c->eps = EVENT_FRACTION * c->ca;
    c->c_flank = 2.0 * DAMPING_RATIO * sqrt(c->k * rp->density * rp->axial_height);
    c->c_rad = 2.0 * DAMPING_RATIO * sqrt(c->k * rp->density * rp->radial_width);
    c->g_on = p->gravity ? GRAVITY : 0.0;
    c->p0 = 2.0 * rp->tangential_force / (rp->diameter * rp->axial_height); /* (1.3) */
    c->delta_pre = contact_inverse(c, c->p0);
    c->ureg = rd_lift_friction_ureg(p) * (setup && setup->ureg_scale > 0 ? setup->ureg_scale : 1.0);
    c->mu = p->friction.coefficient;
    c->eta = p->friction.viscosity;
    c->so_lim = p->friction.sommerfeld_transition;
    c->kh = p->friction.hydrodynamic_slope;
    c->h = rp->axial_height;

    double R = sec->R, b = rp->radial_width, h = rp->axial_height;
    double ri = R - 0.5 * b, ro = R + 0.5 * b, phi = sec->span / n;
    c->L_run = ro * sec->span;
    c->face_area = phi * R * b;
    c->back_chord_area = h * 2.0 * ri * sin(0.5 * phi);
    c->bo_area = h * ro * phi / ARC_POINTS;
    c->ba_area = h * ri * phi / ARC_POINTS;
    for (int a = 0; a < ARC_POINTS; a++) {
        c->fl_area[2 * a] = phi / ARC_POINTS * 0.5 * (R * R - ri * ri);     /* inner half */
        c->fl_area[2 * a + 1] = phi / ARC_POINTS * 0.5 * (ro * ro - R * R); /* outer half */
    }

    size_t N6 = 6 * (size_t)n;
    c->Minv = malloc(36 * (size_t)n * sizeof *c->Minv);
    c->Mez = malloc(N6 * sizeof *c->Mez);
    c->fl_d = malloc(2 * FLANK_POINTS * (size_t)n * sizeof *c->fl_d);
    c->bo_d = malloc(2 * ARC_POINTS * (size_t)n * sizeof *c->bo_d);
    c->bo_e = malloc(2 * ARC_POINTS * (size_t)n * sizeof *c->bo_e);
    c->ba_d = malloc(2 * ARC_POINTS * (size_t)n * sizeof *c->ba_d);
    c->cen_d = malloc(2 * (size_t)n * sizeof *c->cen_d);
    c->e_r = malloc(2 * (size_t)n * sizeof *c->e_r);
    c->e_t = malloc(2 * (size_t)n * sizeof *c->e_t);
    c->qbuf = malloc(2 * N6 * sizeof *c->qbuf);
    c->fbuf = malloc(N6 * sizeof *c->fbuf);
    c->MK = calloc(108 * (size_t)n, sizeof *c->MK);
    c->Dq = malloc(36 * (size_t)n * sizeof *c->Dq);
    c->Dv = malloc(36 * (size_t)n * sizeof *c->Dv);

    if (!c->Minv || !c->Mez || !c->fl_d || !c->bo_d || !c->bo_e || !c->ba_d || !c->cen_d ||
        !c->e_r || !c->e_t || !c->qbuf || !c->fbuf || !c->MK || !c->Dq || !c->Dv)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for a %d-segment lift model.", n);

    rd_band M;
    if ((rc = rd_ring_assemble_band(ring, &c->K, &M, err)))
        return rc;
    rd_band_cleanup(&M); /* the block-diagonal M_i are used directly */

    double rc_com = rd_ring_get_segment_mass(ring, 0)->com_radius;
    for (int i = 0; i < n; i++) {
        double al = rd_ring_get_segment_angle(ring, i), er[3], et[3];
        double Px = R * cos(al), Py = R * sin(al);
        rd_ring_segment_frame(ring, i, er, et);
        c->e_r[2 * i] = er[0];
        c->e_r[2 * i + 1] = er[1];
        c->e_t[2 * i] = et[0];
        c->e_t[2 * i + 1] = et[1];
        c->cen_d[2 * i] = (rc_com - R) * er[0];
        c->cen_d[2 * i + 1] = (rc_com - R) * er[1];
        for (int a = 0; a < ARC_POINTS; a++) {
            double psi = al + (a - 0.5 * (ARC_POINTS - 1)) * phi / ARC_POINTS;
            double cp = cos(psi), sp = sin(psi);
            double *fd = c->fl_d + 2 * (FLANK_POINTS * (size_t)i + 2 * a);
            fd[0] = ri * cp - Px;
            fd[1] = ri * sp - Py;
            fd[2] = ro * cp - Px;
            fd[3] = ro * sp - Py;
            size_t o = 2 * (ARC_POINTS * (size_t)i + a);
            c->bo_d[o] = ro * cp - Px;
            c->bo_d[o + 1] = ro * sp - Py;
            c->bo_e[o] = cp;
            c->bo_e[o + 1] = sp;
            c->ba_d[o] = ri * cp - Px;
            c->ba_d[o + 1] = ri * sp - Py;
        }
        /* M_i^-1 by Cholesky (dpotrf + dpotri), and M_i e_z */
        const double *Ms = rd_ring_segment_mass_matrix(ring, i);
        double *Mi = c->Minv + 36 * (size_t)i;
        memcpy(Mi, Ms, 36 * sizeof *Mi);
        int info = LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'U', 6, Mi, 6);
        if (info == 0)
            info = LAPACKE_dpotri(LAPACK_ROW_MAJOR, 'U', 6, Mi, 6);
        if (info != 0)
            return rd_error_set(err, RD_ENUMERIC, "",
                                "The mass matrix of segment %d is not positive definite "
                                "(LAPACK info %d).",
                                i, info);
        for (int r = 0; r < 6; r++)
            for (int k = 0; k < r; k++)
                Mi[6 * r + k] = Mi[6 * k + r];
        for (int k = 0; k < 6; k++)
            c->Mez[6 * i + k] = Ms[6 * k + 2];
    }
    /* -M_i^-1 K_ij from the upper band storage (K symmetric, kd = 11) */
    for (int i = 0; i < n; i++)
        for (int j = i - 1; j <= i + 1; j++) {
            if (j < 0 || j >= n)
                continue;
            double Kij[36];
            for (int r = 0; r < 6; r++)
                for (int k = 0; k < 6; k++) {
                    int gi = rd_ring_band_index(ring, i, r), gj = rd_ring_band_index(ring, j, k);
                    Kij[6 * r + k] = gi <= gj ? RD_BAND_AT(&c->K, gi, gj) : RD_BAND_AT(&c->K, gj, gi);
                }
            double *B = c->MK + 36 * (3 * (size_t)i + (j - i + 1));
            const double *Mi = c->Minv + 36 * (size_t)i;
            for (int r = 0; r < 6; r++)
                for (int k = 0; k < 6; k++) {
                    double v = 0.0;
                    for (int m = 0; m < 6; m++)
                        v -= Mi[6 * r + m] * Kij[6 * m + k];
                    B[6 * r + k] = v;
                }
        }
    return RD_OK;
}

/* Largest acceleration scale of the scene (for the velocity tolerance). */
static double accel_scale(const rd_ring_params *rp, const rd_lift_params *p)
{
    const rd_engine_params *e = &p->engine;
    double w = omega_of(e);
    double a = e->crank_radius * w * w * (1.0 + e->crank_radius / e->rod_length);
    return fmax(a, flank_pressure_scale(rp, p) / (rp->density * rp->axial_height));
}

/* -------------------------------------------------------------------- run */

typedef struct run_out {
    int samples;
    double *lift;           /* samples */
    rd_lift_event *events;
    int n_events, cap_events;
} run_out;

static int push_event(run_out *o, double deg, int kind, rd_error *err)
{
    if (o->n_events == o->cap_events) {
        int cap = o->cap_events ? 2 * o->cap_events : 16;
        rd_lift_event *e = realloc(o->events, (size_t)cap * sizeof *e);
        if (!e)
            return rd_error_set(err, RD_ENOMEM, "", "Out of memory recording flank changes.");
        o->events = e;
        o->cap_events = cap;
    }
    o->events[o->n_events].crank_deg = deg;
    o->events[o->n_events].kind = kind;
    o->n_events++;
    return RD_OK;
}

static const char *cvode_what(int flag)
{
    switch (flag) {
    case CV_TOO_MUCH_ACC:
        return "the requested accuracy is below what double precision allows";
    case CV_ERR_FAILURE:
        return "the error test failed repeatedly (the step size collapsed)";
    case CV_CONV_FAILURE:
        return "the Newton iteration failed to converge repeatedly";
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL:
        return "the banded linear solver failed (singular Newton matrix)";
    case CV_RHSFUNC_FAIL:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_UNREC_RHSFUNC_ERR:
    case CV_FIRST_RHSFUNC_ERR:
        return "the forces became non-finite";
    case CV_TOO_CLOSE:
        return "the output times are too close together";
    default:
        return "the integrator failed";
    }
}

/* Flank tracking between root returns: the committed flank and the time a
 * pending leave started (the load's sign change), NAN if none. */
typedef struct flank_track {
    int state;
    double cand;
} flank_track;

static int track_roots(flank_track *tr, const int *rf, double t, double deg_per_s, double fz,
                       run_out *o, rd_error *err)
{
    int rc = RD_OK;
    switch (tr->state) {
    case RD_FLANK_LOWER:
        if (rf[4] > 0)
            tr->cand = t;
        else if (rf[4] < 0)
            tr->cand = NAN; /* the load turned back before the ring got away */
        if (rf[1] > 0) {
            rc = push_event(o, (isnan(tr->cand) ? t : tr->cand) * deg_per_s,
                            RD_EVENT_LEAVE_LOWER, err);
            tr->state = RD_FLANK_FREE;
        }
        break;
    case RD_FLANK_UPPER:
        if (rf[4] < 0)
            tr->cand = t;
        else if (rf[4] > 0)
            tr->cand = NAN;
        if (rf[3] > 0) {
            rc = push_event(o, (isnan(tr->cand) ? t : tr->cand) * deg_per_s,
                            RD_EVENT_LEAVE_UPPER, err);
            tr->state = RD_FLANK_FREE;
        }
        break;
    default:
        if (rf[0] < 0) {
            rc = push_event(o, t * deg_per_s, RD_EVENT_REACH_LOWER, err);
            tr->state = RD_FLANK_LOWER;
            tr->cand = fz > 0.0 ? t : NAN; /* landed against its load: leaves again */
        } else if (rf[2] < 0) {
            rc = push_event(o, t * deg_per_s, RD_EVENT_REACH_UPPER, err);
            tr->state = RD_FLANK_UPPER;
            tr->cand = fz < 0.0 ? t : NAN;
        }
        break;
    }
    return rc;
}

/* One integration.  `res` (optional) receives the full per-sample results,
 * `o` the mean lift and events; counters into res when given. */
static int run(const rd_ring *ring, const rd_lift_params *p, const rd_lift_setup *setup,
               double rtol, double atol, const rd_monitor *mon, double prog_lo, double prog_hi,
               rd_lift_result *res, run_out *o, rd_error *err)
{
    lift_ctx c;
    SUNContext sunctx = NULL;
    N_Vector y = NULL, abstol = NULL;
    SUNMatrix A = NULL;
    SUNLinearSolver LS = NULL;
    void *cv = NULL;
    double *seg = NULL;
    int rc = ctx_init(&c, ring, p, setup, err);
    int n = c.n;
    sunindextype N = 12 * (sunindextype)n;
    if (rc)
        goto out;
    seg = malloc((size_t)n * sizeof *seg);
    if (!seg) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the lift output.");
        goto out;
    }
    if (SUNContext_Create(NULL, &sunctx)) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Could not create the SUNDIALS context.");
        goto out;
    }
    y = N_VNew_Serial(N, sunctx);
    abstol = N_VNew_Serial(N, sunctx);
    A = y ? SUNBandMatrix(N, MU, ML, sunctx) : NULL;
    LS = A ? SUNLinSol_Band(y, A, sunctx) : NULL;
    cv = CVodeCreate(CV_BDF, sunctx);
    if (!y || !abstol || !A || !LS || !cv) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory setting up CVODE for %d segments.",
                          n);
        goto out;
    }
    double *yy = N_VGetArrayPointer(y), *at = N_VGetArrayPointer(abstol);
    const rd_ring_params *rp = rd_ring_get_params(ring);
    double R = rd_ring_get_section(ring)->R;
    double wv = sqrt(accel_scale(rp, p) / c.ca); /* velocity / position tolerance ratio */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 6; k++) {
            double a = k < 3 ? atol : atol / R;
            Q(at, i)[k] = a;
            V(at, i)[k] = a * wv;
        }
    if (setup && setup->y0)
        memcpy(yy, setup->y0, (size_t)N * sizeof *yy);
    else
        memset(yy, 0, (size_t)N * sizeof *yy);

    double deg_per_s = c.omega * 180.0 / M_PI;
    int flag, rootdir[N_ROOTS] = {-1, +1, -1, +1, 0};
    if ((flag = CVodeSetErrHandlerFn(cv, cv_silent, &c)) ||
        (flag = CVodeInit(cv, rhs, 0.0, y)) ||
        (flag = CVodeSVtolerances(cv, rtol, abstol)) ||
        (flag = CVodeSetUserData(cv, &c)) ||
        (flag = CVodeSetLinearSolver(cv, LS, A)) ||
        (flag = CVodeSetJacFn(cv, jac)) ||
        (flag = CVodeSetMaxOrd(cv, MAX_ORDER)) ||
        (flag = CVodeSetMaxStep(cv, HMAX_DEG / deg_per_s)) ||
        (flag = CVodeSetLSetupFrequency(cv, 1)) || /* fresh Newton matrix each step */
        (flag = CVodeSetJacEvalFrequency(cv, 1)) ||
        (flag = CVodeRootInit(cv, N_ROOTS, roots)) ||
        (flag = CVodeSetRootDirection(cv, rootdir)) ||
        (flag = CVodeSetNoInactiveRootWarn(cv))) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "CVODE set-up failed: %s (%s).",
                          CVodeGetReturnFlagName(flag), c.cv_msg);
        goto out;
    }

    /* Event state machine (header comment): the seated ring starts on the
     * lower flank; a load already pulling it away dates a leave at 0. */
    flank_track tr = {RD_FLANK_LOWER, NAN};
    {
        double L0 = mean_lift(&c, yy, NULL);
        segment_forces(&c, 0.0, yy, NULL, NULL);
        if (L0 > c.ca - c.eps)
            tr.state = RD_FLANK_UPPER;
        else if (L0 > c.eps)
            tr.state = RD_FLANK_FREE;
        else if (c.fz_ext > 0.0)
            tr.cand = 0.0;
    }

    int S = o->samples;
    double total = p->engine.cycles * 720.0;
    for (int k = 0; k < S; k++) {
        double deg = fmin(k * p->step_deg, total), tout = deg / deg_per_s;
        double t = 0.0;
        if (k > 0) {
            for (;;) {
                long nst = 0;
                CVodeGetNumSteps(cv, &nst);
                long left = p->max_steps - nst;
                if (left <= 0) {
                    rc = rd_error_set(err, RD_ELIMIT, "/numerics/max_steps",
                                      "The integration used its /numerics/max_steps = %ld steps "
                                      "by crank angle %.3f deg (of %.1f): the ring's motion needs "
                                      "more work than allowed; raise max_steps or loosen rtol.",
                                      p->max_steps, t * deg_per_s, total);
                    goto out;
                }
                CVodeSetMaxNumSteps(cv, left);
                flag = CVode(cv, tout, y, &t, CV_NORMAL);
                if (flag == CV_ROOT_RETURN) {
                    int rf[N_ROOTS];
                    CVodeGetRootInfo(cv, rf);
                    segment_forces(&c, t, yy, NULL, NULL);
                    if ((rc = track_roots(&tr, rf, t, deg_per_s, c.fz_ext, o, err)))
                        goto out;
                    continue;
                }
                if (flag < 0) {
                    double tc = t;
                    CVodeGetCurrentTime(cv, &tc);
                    CVodeGetNumSteps(cv, &nst);
                    if (flag == CV_TOO_MUCH_WORK)
                        rc = rd_error_set(err, RD_ELIMIT, "/numerics/max_steps",
                                          "The integration used its /numerics/max_steps = %ld "
                                          "steps by crank angle %.3f deg (of %.1f): the ring's "
                                          "motion needs more work than allowed; raise max_steps "
                                          "or loosen rtol.",
                                          p->max_steps, tc * deg_per_s, total);
                    else
                        rc = rd_error_set(err, RD_ENOCONV, "",
                                          "The lift integration failed at crank angle %.4f deg "
                                          "after %ld steps: %s (CVODE %s: %s).",
                                          tc * deg_per_s, nst, cvode_what(flag),
                                          CVodeGetReturnFlagName(flag), c.cv_msg);
                    goto out;
                }
                break;
            }
        }
        double L = mean_lift(&c, yy, seg);
        o->lift[k] = L;
        if (res) {
            res->crank_deg[k] = deg;
            res->lift[k] = L;
            double lo = seg[0], hi = seg[0], tw = 0.0;
            for (int i = 0; i < n; i++) {
                lo = fmin(lo, seg[i]);
                hi = fmax(hi, seg[i]);
                const double *q = Q(yy, i);
                tw += q[3] * c.e_t[2 * i] + q[4] * c.e_t[2 * i + 1];
            }
            memcpy(res->lift_segments + (size_t)k * n, seg, (size_t)n * sizeof *seg);
            res->lift_min[k] = lo;
            res->lift_max[k] = hi;
            res->twist[k] = tw / n;
            segment_forces(&c, tout, yy, NULL, NULL);
            res->friction_force[k] = c.friction;
            res->flank[k] = L < c.eps ? RD_FLANK_LOWER
                                      : (L > c.ca - c.eps ? RD_FLANK_UPPER : RD_FLANK_FREE);
        }
        if (setup && setup->sample)
            setup->sample(setup->ctx, tout, yy);
        if (setup && setup->energy) {
            rd_lift_energy en = {0.0, 0.0, 0.0};
            c.energy = &en;
            segment_forces(&c, tout, yy, NULL, NULL);
            c.energy = NULL;
            setup->energy(setup->ctx, tout, &en);
        }
        if ((rc = rd_monitor_report(mon, prog_lo + (prog_hi - prog_lo) * (k + 1.0) / S, err)))
            goto out;
    }
    if (res) {
        CVodeGetNumSteps(cv, &res->steps);
        CVodeGetNumRhsEvals(cv, &res->rhs_evals);
        CVodeGetNumJacEvals(cv, &res->jac_evals);
        CVodeGetNumLinSolvSetups(cv, &res->lin_setups);
        CVodeGetNumNonlinSolvIters(cv, &res->nonlin_iters);
        CVodeGetNumNonlinSolvConvFails(cv, &res->nonlin_fails);
        CVodeGetNumErrTestFails(cv, &res->err_test_fails);
        CVodeGetNumGEvals(cv, &res->root_evals);
    }
out:
    if (cv)
        CVodeFree(&cv);
    if (LS)
        SUNLinSolFree(LS);
    if (A)
        SUNMatDestroy(A);
    if (y)
        N_VDestroy(y);
    if (abstol)
        N_VDestroy(abstol);
    if (sunctx)
        SUNContext_Free(&sunctx);
    free(seg);
    ctx_cleanup(&c);
    return rc;
}

void rd_lift_result_cleanup(rd_lift_result *r)
{
    if (!r)
        return;
    free(r->crank_deg);
    free(r->lift);
    free(r->lift_min);
    free(r->lift_max);
    free(r->lift_segments);
    free(r->twist);
    free(r->friction_force);
    free(r->flank);
    free(r->events);
    memset(r, 0, sizeof *r);
    r->error_estimate = NAN;
    r->event_error_deg = NAN;
}

int rd_lift_solve_setup(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                        const rd_lift_setup *setup, const rd_monitor *mon, rd_lift_result *out,
                        rd_error *err)
{
    rd_ring *ring = NULL;
    run_out o = {0}, oref = {0};
    int rc;
    memset(out, 0, sizeof *out);
    out->error_estimate = NAN;
    out->event_error_deg = NAN;
    if ((rc = rd_lift_validate(p, rp, segments, err)))
        return rc;
    ring = rd_ring_create(rp, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    int S = lift_samples(p), n = segments;
    out->segments = n;
    out->dof = 6 * n;
    out->samples = S;
    out->crank_deg = malloc((size_t)S * sizeof(double));
    out->lift = malloc((size_t)S * sizeof(double));
    out->lift_min = malloc((size_t)S * sizeof(double));
    out->lift_max = malloc((size_t)S * sizeof(double));
    out->lift_segments = malloc((size_t)S * n * sizeof(double));
    out->twist = malloc((size_t)S * sizeof(double));
    out->friction_force = malloc((size_t)S * sizeof(double));
    out->flank = malloc((size_t)S * sizeof(int));
    o.samples = oref.samples = S;
    o.lift = malloc((size_t)S * sizeof(double));
    if (p->estimate_error)
        oref.lift = malloc((size_t)S * sizeof(double));
    if (!out->crank_deg || !out->lift || !out->lift_min || !out->lift_max ||
        !out->lift_segments || !out->twist || !out->friction_force || !out->flank || !o.lift ||
        (p->estimate_error && !oref.lift)) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for %d lift samples x %d segments.",
                          S, n);
        goto out;
    }
    /* the reference run at rtol/10 typically costs 1.5-2x the main run */
    double split = p->estimate_error ? 0.4 : 1.0;
    if ((rc = run(ring, p, setup, p->rtol, p->atol, mon, 0.0, split, out, &o, err)))
        goto out;
    out->n_events = o.n_events;
    out->events = o.events;
    o.events = NULL;
    if (p->estimate_error) {
        rd_error sub;
        rd_error_init(&sub);
        rc = run(ring, p, setup, 0.1 * p->rtol, 0.1 * p->atol, mon, split, 1.0, NULL, &oref, &sub);
        if (rc) {
            if (rc == RD_ECANCELED)
                rd_error_set(err, rc, sub.path, "%s", sub.message);
            else
                rd_error_set(err, rc, sub.path,
                             "The error-estimate run at rtol/10 failed: %s", sub.message);
            goto out;
        }
        /* error_estimate: largest lift difference / clearance; event error: the
         * largest angle change of matched events, NAN when the two runs see a
         * different number of flank changes (the estimate cannot pair them) */
        double e = 0.0;
        for (int k = 0; k < S; k++)
            e = fmax(e, fabs(o.lift[k] - oref.lift[k]));
        out->error_estimate = e / p->groove.axial_clearance;
        if (oref.n_events == out->n_events) {
            double de = 0.0;
            for (int j = 0; j < out->n_events; j++) {
                if (oref.events[j].kind != out->events[j].kind) {
                    de = NAN;
                    break;
                }
                de = fmax(de, fabs(oref.events[j].crank_deg - out->events[j].crank_deg));
            }
            out->event_error_deg = de;
        }
    }
out:
    free(o.lift);
    free(o.events);
    free(oref.lift);
    free(oref.events);
    rd_ring_free(ring);
    return rc;
}

int rd_lift_solve(const rd_ring_params *ring, int segments, const rd_lift_params *p,
                  const rd_monitor *mon, rd_lift_result *out, rd_error *err)
{
    return rd_lift_solve_setup(ring, segments, p, NULL, mon, out, err);
}

/* ------------------------------------------------------------- test hook */

int rd_lift_jacobian_check(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                           double t, const double *y0, double *max_err, rd_error *err)
{
    lift_ctx c;
    rd_ring *ring = NULL;
    SUNContext sunctx = NULL;
    N_Vector y = NULL, f1 = NULL, f2 = NULL;
    SUNMatrix J = NULL;
    int rc;
    memset(&c, 0, sizeof c);
    if ((rc = rd_lift_validate(p, rp, segments, err)))
        return rc;
    ring = rd_ring_create(rp, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    if ((rc = ctx_init(&c, ring, p, NULL, err)))
        goto out;
    sunindextype N = 12 * (sunindextype)segments;
    if (SUNContext_Create(NULL, &sunctx) || !(y = N_VNew_Serial(N, sunctx)) ||
        !(f1 = N_VNew_Serial(N, sunctx)) || !(f2 = N_VNew_Serial(N, sunctx)) ||
        !(J = SUNBandMatrix(N, MU, ML, sunctx))) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
        goto out;
    }
    double *yy = N_VGetArrayPointer(y);
    memcpy(yy, y0, (size_t)N * sizeof *yy);
    jac(t, y, NULL, J, &c, NULL, NULL, NULL);
    double jmax = 0.0, worst = 0.0;
    for (sunindextype j = 0; j < N; j++)
        for (sunindextype i = j - MU < 0 ? 0 : j - MU; i <= j + ML && i < N; i++)
            jmax = fmax(jmax, fabs(SM_ELEMENT_B(J, i, j)));
    for (sunindextype j = 0; j < N; j++) {
        /* central differences, steps 1e-3 d0 (translations), the same at
         * 0.05 m lever arm (rotations), 1e-4 u_reg (rates): exact on the
         * penalty's quadratic and linear pieces, far from its kinks, and
         * large enough that rounding stays ~1e-6 relative */
        double h = (j % 12) < 6 ? (j % 12 < 3 ? 1e-3 * c.d0 : 2e-2 * c.d0) : 1e-4 * c.ureg;
        double keep = yy[j];
        yy[j] = keep + h;
        rhs(t, y, f1, &c);
        yy[j] = keep - h;
        rhs(t, y, f2, &c);
        yy[j] = keep;
        const double *a = N_VGetArrayPointer(f1), *b = N_VGetArrayPointer(f2);
        for (sunindextype i = 0; i < N; i++) {
            double fd = (a[i] - b[i]) / (2.0 * h);
            double an = (i - j <= ML && j - i <= MU) ? SM_ELEMENT_B(J, i, j) : 0.0;
            double e = fabs(fd - an) / (fabs(an) + 1e-6 * jmax);
            worst = fmax(worst, e);
        }
    }
    *max_err = worst;
out:
    if (J)
        SUNMatDestroy(J);
    if (y)
        N_VDestroy(y);
    if (f1)
        N_VDestroy(f1);
    if (f2)
        N_VDestroy(f2);
    if (sunctx)
        SUNContext_Free(&sunctx);
    ctx_cleanup(&c);
    rd_ring_free(ring);
    return rc;
}
