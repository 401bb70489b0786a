/*
 * rd_lift_forces.c — the force elements of the full lift model (file map and
 * state layout: rd_lift_model.h; frame and piston: rd_lift.c).  Each element
 * is one small function that adds, for segment i, its generalized force to
 * f_i and its local derivatives to df_i/dq_i (dq) and df_i/dv_i (dv), and,
 * when asked, its share of the energy bookkeeping (rd_lift_internal.h).
 * Order of the sums (kept from the single-file version, so the goldens hold
 * bit for bit): inertia and gravity, flanks, bore, groove back, gas.
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
 * Default stiffness k: rd_lift_scales.c (k_load and k_dyn; both shift the
 * flank-change angles by far less than the flight times: test_lift checks
 * them over 2 decades of k).
 * Optional landing law (/physics/squeeze_film): the oil squeeze film on
 * each flank point, added after the penalty (rd_lift_landing.c).
 *
 *
 * Friction (model != NONE), on each bore point, axial: the liner's law
 * (core/liner/rd_liner_law.h: Coulomb or Stribeck 2.9, regularized by
 * u_reg), given the point's bore normal force N, its share s_k / L of the
 * running face and the sliding speed of the ring on the liner: ring
 * velocity in the piston frame plus the piston's velocity in the cylinder
 * frame (-ds/dt), u = w' - s'.
 *
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
 *   linear (the classic ring-pack models'): every face, sealing or open,
 *   carries the linear fall from the groove-back pressure (inner edge) to
 *   its own side's (outer edge): the mean (p_behind + p_own) / 2 at the
 *   face centroid, and the slope's first moment, per face A b (p_outer -
 *   p_inner) / 12, as a couple about the segment's tangential axis: for
 *   the two faces together (the load up from below, down from above) A b
 *   (p_below - p_above) / 12, the groove's share cancelling; applied as
 *   opposite axial forces at the inner and outer flank points (b apart).
 *
 */
#include <math.h>
#include <string.h>

#include "rd_lift_model.h"

#define ARC_POINTS   RD_LIFT_ARC_POINTS
#define FLANK_POINTS RD_LIFT_FLANK_POINTS
#define Q            RD_LIFT_Q
#define V            RD_LIFT_V

double rd_lift_gas_at(const rd_gas_params *g, const double *val, double deg)
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

/* contact_pressure for a closed contact, d > 0. */
static double contact_closed(const rd_lift_model *c, double d, double dd, double cdamp, double *p_d,
                             double *p_dd)
{
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
    if (pe <= 0.0) {
        *p_d = *p_dd = 0.0;
        return 0.0;
    }
    /* opening fast: pe phi(x), x = pd / pe, phi = e^{2x + 1} / 2 for x < -1/2 */
    double E = exp(2.0 * pd / pe + 1.0);
    *p_d = 0.5 * pe_d * E + E * (pd_d - pd * pe_d / pe);
    *p_dd = E * pd_dd;
    return 0.5 * pe * E;
}

/* Contact pressure p(delta, delta') of the header comment, and its partial
 * derivatives p_d = dp/d delta, p_dd = dp/d delta' (for the Jacobian).  The
 * open contact, the common case (most points of most calls), inline. */
static inline double contact_pressure(const rd_lift_model *c, double d, double dd, double cdamp,
                                      double *p_d, double *p_dd)
{
    if (d <= 0.0) {
        *p_d = *p_dd = 0.0;
        return 0.0;
    }
    return contact_closed(c, d, dd, cdamp, p_d, p_dd);
}

double rd_lift_contact_inverse(const rd_lift_model *c, double p)
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
static double contact_elastic(const rd_lift_model *c, double d, double *U)
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
static void book_contact(rd_lift_model *c, double p, double d, double dd, double A)
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

/* Generalized directions: axial force at in-plane offset d, and radial
 * force along e at offset d (so that w = a . q, u_r = b . q).  Each has
 * three entries that are not structurally zero (axial: z, rx, ry; radial:
 * x, y, rz), kept with their indices in ascending order: the sums and
 * rank-one updates below visit only those, in the order of the full 6-term
 * sums (the terms left out are exact zeros, so the results are the same to
 * the bit), at half the work. */
typedef struct dir3 {
    int k[3];
    double a[3];
} dir3;

static dir3 axial_dir(const double *d)
{
    return (dir3){{2, 3, 4}, {1.0, d[1], -d[0]}};
}

static dir3 radial_dir(const double *d, const double *e)
{
    return (dir3){{0, 1, 5}, {e[0], e[1], d[0] * e[1] - d[1] * e[0]}};
}

static double dot3(const dir3 *a, const double *q)
{
    return a->a[0] * q[a->k[0]] + a->a[1] * q[a->k[1]] + a->a[2] * q[a->k[2]];
}

static void add3(double *f, const dir3 *a, double F)
{
    for (int u = 0; u < 3; u++)
        f[a->k[u]] += F * a->a[u];
}

/* D += s a b^T (6x6 row-major); D may be NULL. */
static void rank1(double *D, double s, const dir3 *a, const dir3 *b)
{
    if (!D || s == 0.0)
        return;
    for (int u = 0; u < 3; u++)
        if (a->a[u] != 0.0)
            for (int w = 0; w < 3; w++)
                D[6 * a->k[u] + b->k[w]] += s * a->a[u] * b->a[w];
}

/* D += s a b^T with a full 6-vector b. */
static void rank1_full(double *D, double s, const dir3 *a, const double *b)
{
    if (!D || s == 0.0)
        return;
    for (int u = 0; u < 3; u++)
        if (a->a[u] != 0.0)
            for (int k = 0; k < 6; k++)
                D[6 * a->k[u] + k] += s * a->a[u] * b[k];
}

/* The time-dependent inputs of all elements at one time, computed once per
 * force call. */
typedef struct force_env {
    double sd, acc;                 /* piston velocity ds/dt; pseudo-acceleration s'' - g */
    int tilt;                       /* the piston tilts (rd_lift_tilt.c) */
    double cb, sb, bd, bdd;         /* cos, sin of the tilt; its rate (1/s), acceleration (1/s^2) */
    double pa, pbh, pbl;            /* gas: above, behind, below, Pa */
    int gas, dynamic, linear, fric; /* which elements the scene asks for */
    rd_film_point film;             /* lubricated: the face's film at t (rd_lift_film.c) */
    const rd_film_point *seg_film;  /* a distorted bore's: each segment's film at t, or NULL */
} force_env;

/* One segment's view: its state, its force and local Jacobian blocks (dq,
 * dv NULL when not wanted), and the dynamic-area sealing weights the flank
 * element leaves for the gas element. */
typedef struct seg_view {
    int i;
    const double *q, *v;
    double *f, *dq, *dv;
    double seal_lo, seal_up, g_lo[6], g_up[6];
} seg_view;

/* Inertia pseudo-force and gravity: M_i e_z (s'' - g); no state dependence.
 * A tilted piston: the state is measured in the tilted groove's frame
 * (rotated by beta about the pin axis y: a frame point at x rises by
 * beta x), so the cylinder axis there is (sin beta, 0, cos beta) and the
 * pseudo-force is M_i (sin beta e_x + cos beta e_z)(s'' - g), plus the
 * frame's Euler force -beta'' M_i phi_i with phi_i = (0, 0, x_i, 0, -1, 0)
 * its motion per unit tilt at P_i (x_i = R e_r,x); the centrifugal and
 * Coriolis terms, beta'^2 and beta' v, are dropped (second order). */
static void add_inertia_gravity(const rd_lift_model *c, const force_env *env, seg_view *s)
{
    if (!env->tilt) {
        for (int k = 0; k < 6; k++)
            s->f[k] = c->Mez[6 * s->i + k] * env->acc;
        return;
    }
    const double *Mi = rd_ring_segment_mass_matrix(c->ring, s->i);
    double x = rd_ring_get_section(c->ring)->R * c->e_r[2 * s->i];
    for (int k = 0; k < 6; k++)
        s->f[k] = (env->cb * Mi[6 * k + 2] + env->sb * Mi[6 * k]) * env->acc -
                  env->bdd * (x * Mi[6 * k + 2] - Mi[6 * k + 4]);
}

/* The squeeze films (rd_lift_landing.c) under and over a face point at
 * axial displacement w (rate wd): the lower gap w closes at -wd, the upper
 * gap c_a - w at wd; their power on the ring is dissipation. */
static void add_squeeze(rd_lift_model *c, seg_view *s, const dir3 *a, double w, double wd, double A)
{
    double lg, lv, ug, uv;
    double pl = rd_lift_squeeze(c, w, -wd, &lg, &lv);
    double pu = rd_lift_squeeze(c, c->ca - w, wd, &ug, &uv);
    add3(s->f, a, (pl - pu) * A);
    if (c->energy)
        c->energy->damping_power += (pl - pu) * A * wd;
    rank1(s->dq, A * (lg + ug), a, a);
    rank1(s->dv, -A * (lv + uv), a, a);
}

/* Lower and upper flank contacts at the face points; with dynamic gas areas
 * also the sealing weights and their gradients. */
static void add_flanks(rd_lift_model *c, const force_env *env, seg_view *s)
{
    double pl_d, pl_dd, pu_d, pu_dd;
    for (int k = 0; k < FLANK_POINTS; k++) {
        dir3 a = axial_dir(c->fl_d + 2 * (FLANK_POINTS * (size_t)s->i + k));
        double w = dot3(&a, s->q), wd = dot3(&a, s->v), A = c->fl_area[k];
        double plo = contact_pressure(c, -w, -wd, c->c_flank, &pl_d, &pl_dd);
        double pup = contact_pressure(c, w - c->ca, wd, c->c_flank, &pu_d, &pu_dd);
        add3(s->f, &a, (plo - pup) * A);
        if (c->energy) {
            book_contact(c, plo, -w, -wd, A);
            book_contact(c, pup, w - c->ca, wd, A);
        }
        rank1(s->dq, -A * (pl_d + pu_d), &a, &a);
        rank1(s->dv, -A * (pl_dd + pu_dd), &a, &a);
        if (c->sq_on)
            add_squeeze(c, s, &a, w, wd, A);
        if (env->dynamic) {
            double sl_d, su_d;
            s->seal_lo += A * smoothstep(-w / c->d0, &sl_d);
            s->seal_up += A * smoothstep((w - c->ca) / c->d0, &su_d);
            add3(s->g_lo, &a, -A * sl_d / c->d0);
            add3(s->g_up, &a, A * su_d / c->d0);
        }
    }
}

/* Bore: the pretension outward, the contact inward, and the axial friction
 * driven by its normal force, added point by point to *ftot (N). */
static void add_bore(rd_lift_model *c, const force_env *env, seg_view *s, double *ftot)
{
    for (int k = 0; k < ARC_POINTS; k++) {
        size_t o = 2 * (ARC_POINTS * (size_t)s->i + k);
        const double *d = c->bo_d + o;
        dir3 b = radial_dir(d, c->bo_e + o);
        double ur = dot3(&b, s->q), urd = dot3(&b, s->v), P_d, P_dd;
        if (c->bo_gap) /* a distorted bore: its offset at the point (rd_lift_bore.c) */
            ur -= c->bo_gap[ARC_POINTS * (size_t)s->i + k];
        double N = c->bo_area * contact_pressure(c, c->delta_pre + ur, urd, c->c_rad, &P_d, &P_dd);
        add3(s->f, &b, c->p0 * c->bo_area - N);
        if (c->energy) {
            book_contact(c, N / c->bo_area, c->delta_pre + ur, urd, c->bo_area);
            c->energy->contact -= c->p0 * c->bo_area * ur;
        }
        rank1(s->dq, -c->bo_area * P_d, &b, &b);
        rank1(s->dv, -c->bo_area * P_dd, &b, &b);
        if (env->fric) {
            dir3 a = axial_dir(d);
            double u = dot3(&a, s->v) - env->sd;
            if (env->tilt) /* the groove frame's own axial speed at the point, beta' x */
                u += env->bd * (rd_ring_get_section(c->ring)->R * c->e_r[2 * s->i] + d[0]);
            rd_liner_force lf;
            const rd_film_point *fm = env->seg_film ? env->seg_film + s->i : &env->film;
            rd_liner_eval(&c->liner, &(rd_liner_point){N, u, c->bo_area / (c->h * c->L_run), fm},
                          &lf);
            double F = lf.F, F_N = lf.F_N, F_u = lf.F_u;
            add3(s->f, &a, F);
            if (c->energy)
                c->energy->friction_power += F * u;
            *ftot += F;
            rank1(s->dq, F_N * c->bo_area * P_d, &a, &b);
            rank1(s->dv, F_N * c->bo_area * P_dd, &a, &b);
            rank1(s->dv, F_u, &a, &a);
        }
    }
}

/* Groove back contact on the inner face. */
static void add_back(rd_lift_model *c, seg_view *s)
{
    for (int k = 0; k < ARC_POINTS; k++) {
        size_t o = 2 * (ARC_POINTS * (size_t)s->i + k);
        dir3 b = radial_dir(c->ba_d + o, c->bo_e + o);
        double P_d, P_dd;
        double pen = -dot3(&b, s->q) - c->cr;
        double P = contact_pressure(c, pen, -dot3(&b, s->v), c->c_rad, &P_d, &P_dd);
        add3(s->f, &b, P * c->ba_area);
        if (c->energy)
            book_contact(c, P, pen, -dot3(&b, s->v), c->ba_area);
        rank1(s->dq, -c->ba_area * P_d, &b, &b);
        rank1(s->dv, -c->ba_area * P_dd, &b, &b);
    }
}

/* The couple of the linear flank pressure (header comment): on each of the
 * segment's arc thirds, +F at its outer flank point and -F at its inner
 * one, F b = (A/3) b (p_below - p_above) / 12, the first moment of the two
 * faces' pressure slopes (the groove's share cancels).  No state
 * dependence: the points' directions are the reference's. */
static void add_gas_couple(const rd_lift_model *c, const force_env *env, seg_view *s)
{
    double F = c->face_area / ARC_POINTS * (env->pbl - env->pa) / 12.0;
    for (int k = 0; k < ARC_POINTS; k++) {
        size_t o = 2 * (FLANK_POINTS * (size_t)s->i + 2 * k);
        dir3 in = axial_dir(c->fl_d + o), out = axial_dir(c->fl_d + o + 2);
        add3(s->f, &out, F);
        add3(s->f, &in, -F);
    }
}

/* Gas on the top, bottom and back faces (fixed, dynamic or linear areas);
 * returns its axial force on the segment, N. */
static double add_gas(const rd_lift_model *c, const force_env *env, seg_view *s)
{
    double ptop = env->pa, pbot = env->pbl;
    dir3 a = axial_dir(c->cen_d + 2 * s->i);
    if (env->linear) {
        ptop = 0.5 * (env->pa + env->pbh);
        pbot = 0.5 * (env->pbl + env->pbh);
        add_gas_couple(c, env, s);
    }
    if (env->dynamic) {
        double wl = s->seal_lo / c->face_area, wu = s->seal_up / c->face_area;
        pbot += wl * 0.5 * (env->pbh - env->pbl);
        ptop += wu * 0.5 * (env->pbh - env->pa);
        /* d(pbot - ptop) A_face / dq = (pbh - pbl)/2 g_lo - (pbh - pa)/2 g_up */
        rank1_full(s->dq, 0.5 * (env->pbh - env->pbl), &a, s->g_lo);
        rank1_full(s->dq, -0.5 * (env->pbh - env->pa), &a, s->g_up);
    }
    add3(s->f, &a, (pbot - ptop) * c->face_area);
    dir3 b = radial_dir(c->cen_d + 2 * s->i, c->e_r + 2 * s->i);
    add3(s->f, &b, env->pbh * c->back_chord_area);
    return (pbot - ptop) * c->face_area;
}

/* The piston's kinematics at t into env (sd, acc; with a tilting piston
 * cb, sb, bd, bdd), from the model's copy when its last force call was at
 * the same t (rd_lift_model.kin_t): the same values. */
static void kinematics_at(rd_lift_model *c, double t, force_env *env)
{
    const rd_lift_params *p = c->p;
    double *k = c->kin;
    env->tilt = rd_engine_tilted(&p->engine);
    if (t != c->kin_t) {
        double s = 0.0, sdd = 0.0, deg = c->omega * t * 180.0 / M_PI;
        k[0] = 0.0;
        if (!c->piston_fixed)
            rd_engine_piston(&p->engine, c->omega * t, &s, &k[0], &sdd);
        k[1] = sdd - c->g_on;
        if (c->bo_layers) /* a bore map: the bore at the ring's depth now */
            rd_lift_bore_at_travel(c, s);
        if (env->tilt) {
            double b, b1, b2, dps = c->omega * 180.0 / M_PI, r = M_PI / 180.0;
            rd_engine_tilt_at(&p->engine, deg, &b, &b1, &b2);
            k[2] = cos(b * r);
            k[3] = sin(b * r);
            k[4] = b1 * dps * r;
            k[5] = b2 * dps * dps * r;
        }
        c->kin_t = t;
    }
    env->sd = k[0];
    env->acc = k[1];
    env->cb = k[2];
    env->sb = k[3];
    env->bd = k[4];
    env->bdd = k[5];
}

static void force_env_at(rd_lift_model *c, double t, force_env *env)
{
    const rd_lift_params *p = c->p;
    double deg = c->omega * t * 180.0 / M_PI;
    kinematics_at(c, t, env);
    env->gas = p->gas.points > 0 || c->gas_now;
    env->dynamic = env->gas && p->gas.active_area == RD_GAS_AREA_DYNAMIC;
    env->linear = env->gas && p->gas.active_area == RD_GAS_AREA_LINEAR;
    env->fric = p->friction.model != RD_FRICTION_NONE;
    env->seg_film = NULL;
    if (p->films && c->film_seg) { /* a distorted bore: each segment's film now */
        rd_lift_films_at(p->films, t, c->n, c->film_grp, c->film_seg);
        env->seg_film = c->film_seg;
        env->film = (rd_film_point){0};
    } else if (p->film) /* lubricated: the face's film now (rd_lift_film.c) */
        rd_film_track_at(p->film, t, &env->film);
    else /* none solved (a caller below rd_lift_solve_setup): no film force */
        env->film = (rd_film_point){0};
    env->pa = env->pbh = env->pbl = 0.0;
    if (c->gas_now) { /* the caller's pressures (rd_lift_model.h) */
        env->pa = c->gas_now[0];
        env->pbh = c->gas_now[1];
        env->pbl = c->gas_now[2];
    } else if (env->gas) {
        env->pa = rd_lift_gas_at(&p->gas, p->gas.above, deg);
        env->pbh = rd_lift_gas_at(&p->gas, p->gas.behind, deg);
        env->pbl = rd_lift_gas_at(&p->gas, p->gas.below, deg);
    }
}

void rd_lift_bore_pressure(rd_lift_model *c, double t, const double *y, double *seg)
{
    force_env env;
    kinematics_at(c, t, &env); /* the bore at the ring's depth */
    for (int i = 0; i < c->n; i++) {
        double sum = 0.0;
        for (int k = 0; k < ARC_POINTS; k++) { /* as add_bore */
            size_t o = 2 * (ARC_POINTS * (size_t)i + k);
            dir3 b = radial_dir(c->bo_d + o, c->bo_e + o);
            double ur = dot3(&b, Q(y, i)), urd = dot3(&b, V(y, i)), P_d, P_dd;
            if (c->bo_gap)
                ur -= c->bo_gap[ARC_POINTS * (size_t)i + k];
            sum += contact_pressure(c, c->delta_pre + ur, urd, c->c_rad, &P_d, &P_dd);
        }
        seg[i] = sum / ARC_POINTS;
    }
}

/* Every element on one segment, in the order of the sums (file head): the
 * one list of the full forces, for every model (rd_lift_forces,
 * rd_lift_forces_segment).  *ftot gathers the bore friction, *fz the axial
 * loads other than the flanks'. */
static void add_elements(rd_lift_model *c, const force_env *env, seg_view *s, double *ftot,
                         double *fz)
{
    add_inertia_gravity(c, env, s);
    *fz += s->f[2];
    add_flanks(c, env, s);
    add_bore(c, env, s, ftot);
    add_back(c, s);
    if (env->gas)
        *fz += add_gas(c, env, s);
}

void rd_lift_forces(rd_lift_model *c, double t, const double *y, double *Dq, double *Dv)
{
    force_env env;
    force_env_at(c, t, &env);
    double ftot = 0.0, fz = 0.0;
    for (int i = 0; i < c->n; i++) {
        seg_view s = {.i = i, .q = Q(y, i), .v = V(y, i), .f = c->fbuf + 6 * i};
        if (Dq) {
            s.dq = Dq + 36 * (size_t)i;
            s.dv = Dv + 36 * (size_t)i;
            memset(s.dq, 0, 36 * sizeof *s.dq);
            memset(s.dv, 0, 36 * sizeof *s.dv);
        }
        add_elements(c, &env, &s, &ftot, &fz);
    }
    c->friction = ftot;
    c->fz_ext = fz + ftot;
}

/* The elements of m->friction and m->fz_ext on one segment (rd_lift_loads):
 * the flanks only for the dynamic gas areas' sealing weights, the bore only
 * for the friction its normal force drives. */
static void add_loads(rd_lift_model *c, const force_env *env, seg_view *s, double *ftot, double *fz)
{
    add_inertia_gravity(c, env, s);
    *fz += s->f[2];
    if (env->dynamic)
        add_flanks(c, env, s);
    if (env->fric)
        add_bore(c, env, s, ftot);
    if (env->gas)
        *fz += add_gas(c, env, s);
}

void rd_lift_loads(rd_lift_model *c, double t, const double *y)
{
    force_env env;
    force_env_at(c, t, &env);
    double ftot = 0.0, fz = 0.0;
    for (int i = 0; i < c->n; i++) {
        seg_view s = {.i = i, .q = Q(y, i), .v = V(y, i), .f = c->fbuf + 6 * i};
        add_loads(c, &env, &s, &ftot, &fz);
    }
    c->friction = ftot;
    c->fz_ext = fz + ftot;
}

void rd_lift_loads_segment(rd_lift_model *c, double t, int i, const double *q, const double *v,
                           double *f)
{
    force_env env;
    force_env_at(c, t, &env);
    double ftot = 0.0, fz = 0.0;
    seg_view s = {.i = i, .q = q, .v = v, .f = f};
    add_loads(c, &env, &s, &ftot, &fz);
    c->friction = ftot;
    c->fz_ext = fz + ftot;
}

void rd_lift_forces_segment(rd_lift_model *c, double t, int i, const double *q, const double *v,
                            double *f, double *dq, double *dv)
{
    force_env env;
    force_env_at(c, t, &env);
    double ftot = 0.0, fz = 0.0;
    seg_view s = {.i = i, .q = q, .v = v, .f = f, .dq = dq, .dv = dv};
    if (dq) {
        memset(dq, 0, 36 * sizeof *dq);
        memset(dv, 0, 36 * sizeof *dv);
    }
    add_elements(c, &env, &s, &ftot, &fz);
    c->friction = ftot;
    c->fz_ext = fz + ftot;
}
