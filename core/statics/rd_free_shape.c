/*
 * rd_free_shape — a ring made with a free shape (rd_static.h's
 * rd_free_shape): its check, its pressure law, and the joints' rest e0 it
 * gives the static chain (rd_static_problem.h), so that the free shape is
 * the chain's stress-free state and closing it stresses the ring.
 *
 * The joints' law stays [f; m] = Kc ([d; t] - e0), e0 the [d; t] the joint
 * has in the free shape, measured with the chain's exact kinematics from
 * the closed reference: the free shape carries no force exactly, however
 * large its displacement from the closed ring (a gap of ~10 mm on a
 * 100 mm ring turns the segments by up to ~0.1 rad), and for every state
 * the strain is measured from it as today's from the closed ring.
 *
 * From a pressure (RD_FREE_PRESSURE).  Wanted: the ring closed in a round
 * bore of its diameter (its closed reference: the running face on the
 * bore, the gap at its closed width) carrying p(theta) on its running face
 * and nothing on its gap faces.  That state is statically determinate: a
 * joint carries what the pressure puts on the segments between it and its
 * free end, so its [f; m] follows by summing the segments' loads from each
 * free end up to the section opposite the gap, and e0 = -Kc^-1 [f; m]
 * makes that state an equilibrium with [d; t] = 0 (rest_of: the in-plane
 * part only, so the free shape is planar; for a section whose principal
 * axes are turned, from the compliance with the out-of-plane forces zero,
 * so that closed it carries exactly [f; m] in its plane and twists out of
 * it).  The pressure acts at the running face's radius and height (the
 * section's run.r, run.z_touch), as the contact points do.  The free shape is then
 * the chain's solution without loads (rd_pretension.c), geometrically
 * exact: no linearised free shape is closed into the bore (one from the
 * thin-ring formulas, closed exactly, misses the pressure by 5-12 %, the
 * issue notes).  A pressure over a split ring does not balance exactly
 * (uniform p over the arc less the closed gap g leaves 2 F_t g / d):
 * order-1 terms that cancel it are added (balanced_loads), and the two
 * halves are each summed from their own end.
 *
 * The installed ring (rd_free_shape_installed): the ring so made, closed
 * by that pressure as dead loads with the section opposite the gap held,
 * gives the static twist; in its plane it closes to round exactly.
 *
 * Not built: a measured free shape (a table of the running face's radius)
 * as the rest.  The pressure is the fourth derivative of the shape: at the
 * scale of a 7 mm segment of the thesis ring 1 % of p0 is 7 nm of radius
 * (E I dr / l^4 = 0.01 q), so the rest taken point by point from a table
 * of the solved free shape itself (42 to 642 points, cubic Hermite, the
 * centroid line not stretched) gave the pressure back only within 4-36 %
 * of p0; a measured shape needs a smoothed (low-order) fit and an
 * accuracy stated with it.
 */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_interp.h"
#include "rd_static_problem.h"

/* A table mirrored about the point opposite the gap: it starts at 0. */
static int mirrored(const rd_free_shape *fs)
{
    return fs->n_points > 0 && fs->theta_deg[0] == 0.0;
}

double rd_free_shape_pressure(const rd_free_shape *fs, double theta)
{
    theta = remainder(theta, 2.0 * M_PI);
    if (fs->n_points > 0) {
        double t = theta * 180.0 / M_PI;
        return rd_interp_linear(fs->theta_deg, fs->value, fs->n_points, mirrored(fs) ? fabs(t) : t);
    }
    double r = 1.0;
    for (int q = 0; q < fs->n_orders; q++)
        r += fs->amplitude[q] * cos(fs->order[q] * theta);
    return r;
}

/* The table's angles: min_points..RD_FREE_POINTS_MAX, strictly
 * increasing, from 0 or -180 to 180. */
static int table_check(const rd_free_shape *fs, const char *path, int min_points, rd_error *err)
{
    int n = fs->n_points;
    const double *t = fs->theta_deg;
    if (n < min_points || n > RD_FREE_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, path, "@%s has %d points: allowed %d to %d.", path, n,
                            min_points, RD_FREE_POINTS_MAX);
    for (int i = 0; i < n; i++) {
        if (!isfinite(t[i]) || t[i] < -180.0 || t[i] > 180.0)
            return rd_error_set(err, RD_EINVAL, path,
                                "@%s[%d] = %g deg is out of range: allowed -180 to 180 deg (from "
                                "the point opposite the gap).",
                                path, i, t[i]);
        if (i > 0 && !(t[i] > t[i - 1]))
            return rd_error_set(err, RD_EINVAL, path,
                                "@%s[%d] = %g deg does not increase (the one before is %g deg).",
                                path, i, t[i], t[i - 1]);
    }
    if (!(t[0] == 0.0 || t[0] == -180.0) || t[n - 1] != 180.0)
        return rd_error_set(err, RD_EINVAL, path,
                            "@%s runs from %g to %g deg: run from 0 (the pressure mirrored about "
                            "the point opposite the gap) or from -180 (the whole ring) to 180.",
                            path, t[0], t[n - 1]);
    return RD_OK;
}

static int pressure_check(const rd_free_shape *fs, rd_error *err)
{
    const char *path = "/pressure_distribution";
    if (fs->n_orders > 0 && fs->n_points > 0)
        return rd_error_set(err, RD_EINVAL, path,
                            "@%s has both orders and a table (theta_deg, ratio): give one.", path);
    if (fs->n_orders < 0 || fs->n_orders > RD_FREE_ORDERS_MAX)
        return rd_error_set(err, RD_EINVAL, "/pressure_distribution/orders",
                            "@/pressure_distribution/orders has %d entries: allowed 0 to %d.",
                            fs->n_orders, RD_FREE_ORDERS_MAX);
    for (int q = 0; q < fs->n_orders; q++) {
        if (fs->order[q] < 2 || fs->order[q] > 64)
            return rd_error_set(err, RD_EINVAL, "/pressure_distribution/orders",
                                "@/pressure_distribution/orders/%d/order = %d is out of "
                                "range: allowed 2 to 64 (order 1 pushes the ring off the bore's "
                                "centre; a pressure of it has no equilibrium).",
                                q, fs->order[q]);
        double a_max = fs->measured ? 5.0 : 1.0;
        if (!isfinite(fs->amplitude[q]) || fabs(fs->amplitude[q]) > a_max)
            return rd_error_set(err, RD_EINVAL, "/pressure_distribution/orders",
                                "@/pressure_distribution/orders/%d/amplitude = %g is out of "
                                "range: allowed -%g to %g (of the mean pressure p0).",
                                q, fs->amplitude[q], a_max, a_max);
    }
    if (fs->n_points > 0) {
        int rc = table_check(fs, "/pressure_distribution/theta_deg", 2, err);
        if (rc)
            return rc;
        for (int i = 0; i < fs->n_points; i++)
            if (!isfinite(fs->value[i]) || fs->value[i] < 0.0 || fs->value[i] > 20.0)
                return rd_error_set(err, RD_EINVAL, "/pressure_distribution/ratio",
                                    "@/pressure_distribution/ratio[%d] = %g is out of range: "
                                    "allowed 0 to 20 (of the mean pressure p0).",
                                    i, fs->value[i]);
    }
    if (fs->measured) /* a measured ring may leave the bore somewhere */
        return RD_OK;
    /* the pressure pushes everywhere: a ring pulled from the bore is not
     * this shape's ring */
    double lo = INFINITY, at = 0.0;
    for (int k = 0; k <= 7200; k++) {
        double t = -M_PI + 2.0 * M_PI * k / 7200.0, v = rd_free_shape_pressure(fs, t);
        if (v < lo) {
            lo = v;
            at = t;
        }
    }
    if (!(lo > 0.0))
        return rd_error_set(err, RD_EINVAL, path,
                            "@%s falls to %.4g p0 at %.1f deg from the point opposite the gap: "
                            "the pressure must stay above 0 around the ring.",
                            path, lo, at * 180.0 / M_PI);
    return RD_OK;
}

int rd_free_shape_validate(const rd_free_shape *fs, const rd_ring_params *p, rd_error *err)
{
    if (!fs || fs->kind == RD_FREE_CLOSED)
        return RD_OK;
    if (fs->kind != RD_FREE_PRESSURE)
        return rd_error_set(err, RD_EINVAL, "", "unknown free shape kind %d.", fs->kind);
    (void)p;
    return pressure_check(fs, err);
}

/* ---- the pressure's rest --------------------------------------------------- */

/* 8-point Gauss-Legendre on [-1, 1]. */
static const double gl_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                               -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                               0.7966664774136267,  0.9602898564975363};
static const double gl_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                               0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                               0.2223810344533745, 0.1012285362903763};

/* Joint j's rest for the in-plane forces fm (chord, radial, about the
 * axis: components 0, 2, 4 of [d; t]; the rest 0): a planar free shape,
 * e0_in = -(Kc^-1)_in,in fm_in, e0_out = 0.  For a symmetric section Kc
 * does not couple the two groups and this is -Kc^-1 fm.  For one whose
 * principal axes are turned it is the compliance with the out-of-plane
 * forces zero (the inverse of the in-plane Schur complement): an open ring
 * with free ends and no out-of-plane loads carries no out-of-plane force or
 * moment, so closed in the round bore it twists out of its plane until it
 * carries exactly fm in its plane (rd_free_shape.c's header). */
static int rest_of(const rd_static_problem *pb, int j, const double fm[6], double e0[6])
{
    double K[36], C[36] = {0};
    lapack_int ipiv[6];
    memcpy(K, pb->Kc + 36 * j, sizeof K);
    for (int k = 0; k < 6; k++)
        C[7 * k] = 1.0;
    lapack_int info = LAPACKE_dgesv(LAPACK_ROW_MAJOR, 6, 6, K, 6, ipiv, C, 6);
    if (info != 0) /* (row-major copies: their allocation may fail) */
        return info == LAPACK_TRANSPOSE_MEMORY_ERROR || info == LAPACK_WORK_MEMORY_ERROR
                   ? RD_ENOMEM
                   : RD_EINVAL;
    static const int in[3] = {0, 2, 4};
    memset(e0, 0, 6 * sizeof *e0);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            e0[in[r]] -= C[6 * in[r] + in[c]] * fm[in[c]];
    return RD_OK;
}

/* Each segment's load (force and moment about its reference point, 6 per
 * segment) from the pressure p0 w(theta) on its running face, at radius
 * r_o and the centroid's height, as the contact points carry it
 * (rd_contact.c): w = p / p0 (what 0), cos theta (1) or sin theta (2);
 * what 3: the balanced p / p0 (terms: balanced_loads' c, s) as 8 points a
 * segment of (offset, force), 48 values a segment, into f. */
static void pressure_loads(const rd_static_problem *pb, const rd_ring_params *p,
                           const rd_free_shape *fs, int what, const double *terms, double *f)
{
    const rd_section *sec = rd_ring_get_cross_section(pb->ring);
    double r_o = sec->run.r, z = sec->run.z_touch,
           p0 = 2.0 * p->tangential_force / (p->diameter * pb->h);
    static const double eye[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int i = 0; i < pb->n; i++) {
        double a_i = rd_ring_get_segment_angle(pb->ring, i),
               phi = rd_ring_segment_phi_at(pb->ring, i);
        const double *P = rd_ring_reference_point(pb->ring, i);
        if (what != 3)
            memset(f + 6 * i, 0, 6 * sizeof *f);
        for (int q = 0; q < 8; q++) {
            double a = a_i + 0.5 * phi * gl_x[q], w = 0.5 * phi * gl_w[q], t = a - M_PI;
            double v = what == 0 ? rd_free_shape_pressure(fs, t) : what == 1 ? cos(t) : sin(t);
            if (what == 3) /* the balanced pressure, balanced_loads' terms */
                v = rd_free_shape_pressure(fs, t) + terms[0] * cos(t) + terms[1] * sin(t);
            double pr = p0 * v * pb->h * r_o * w;
            double F[3] = {-pr * cos(a), -pr * sin(a), 0.0};
            double c[3] = {r_o * cos(a) - P[0], r_o * sin(a) - P[1], z};
            if (what == 3) { /* per point: offset, force */
                memcpy(f + 48 * i + 6 * q, c, sizeof c);
                memcpy(f + 48 * i + 6 * q + 3, F, sizeof F);
            } else {
                rd_static_add_force(eye, c, F, f + 6 * i);
            }
        }
    }
}

/* The pressure's loads balanced: a pressure over the split ring's arc
 * leaves a net force (uniform: 2 F_t sin(g / 2R) toward the gap's side),
 * which the ring in the bore cannot carry.  The order-1 terms c cos theta
 * + s sin theta that cancel it are added (uniform pressure on the thesis
 * ring: c = 2.2e-3, i.e. 0.2 % of p0); without them the net force sits on
 * the section opposite the gap, 5-11 % of its segment's pressure at 40-80
 * segments. */
static int balanced_loads(const rd_static_problem *pb, const rd_ring_params *p,
                          const rd_free_shape *fs, double *f, double terms[2])
{
    int n = pb->n;
    double *g = malloc((size_t)12 * n * sizeof *g);
    if (!g)
        return RD_ENOMEM;
    pressure_loads(pb, p, fs, 0, NULL, f);
    pressure_loads(pb, p, fs, 1, NULL, g);
    pressure_loads(pb, p, fs, 2, NULL, g + 6 * n);
    double A[4] = {0, 0, 0, 0}, r[2] = {0, 0};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 2; k++) {
            r[k] -= f[6 * i + k];
            A[2 * k] += g[6 * i + k];
            A[2 * k + 1] += g[6 * n + 6 * i + k];
        }
    double det = A[0] * A[3] - A[1] * A[2];
    double c = (r[0] * A[3] - A[1] * r[1]) / det, sn = (A[0] * r[1] - A[2] * r[0]) / det;
    for (int i = 0; i < 6 * n; i++)
        f[i] += c * g[i] + sn * g[6 * n + i];
    terms[0] = c;
    terms[1] = sn;
    free(g);
    return RD_OK;
}

/* The joints' [f; m] in the closed ring under the segments' loads f, each
 * half summed from its own free end (the header), and their rests. */
static int pressure_rest(rd_static_problem *pb, const double *f)
{
    int n = pb->n;
    double S[3] = {0, 0, 0}, Mo[3] = {0, 0, 0};
    for (int side = 0; side < 2; side++) {
        memset(S, 0, sizeof S);
        memset(Mo, 0, sizeof Mo);
        /* side 0: joints 0..pb-1 from the first end; side 1: the rest from the last */
        int first = side == 0 ? 0 : n - 2, last = side == 0 ? pb->pb - 1 : pb->pb,
            step = side ? -1 : 1;
        for (int j = first; side == 0 ? j <= last : j >= last; j += step) {
            int i = side == 0 ? j : j + 1; /* the segment this joint's sum takes in */
            const double *xi = pb->x + 3 * i;
            double xf[3];
            rd_cross3(xi, f + 6 * i, xf);
            for (int k = 0; k < 3; k++) {
                S[k] += f[6 * i + k];
                Mo[k] += f[6 * i + 3 + k] + xf[k];
            }
            const double *xA = pb->x + 3 * j, *xB = xA + 3, *E = pb->E + 9 * j;
            double F[3], Mg[3], Dx[3], t[3], u[3], fm[6];
            for (int k = 0; k < 3; k++)
                Dx[k] = xB[k] - xA[k];
            if (side == 0) { /* F = -S, Mg = F x Dx - (Mo - xA x S) */
                double FxD[3];
                for (int k = 0; k < 3; k++)
                    F[k] = -S[k];
                rd_cross3(F, Dx, FxD);
                rd_cross3(xA, S, t);
                for (int k = 0; k < 3; k++)
                    Mg[k] = FxD[k] - (Mo[k] - t[k]);
            } else { /* F = S, Mg = Mo - xB x S */
                rd_cross3(xB, S, t);
                for (int k = 0; k < 3; k++) {
                    F[k] = S[k];
                    Mg[k] = Mo[k] - t[k];
                }
            }
            rd_mv3(E, F, u);
            memcpy(fm, u, sizeof u);
            rd_mv3(E, Mg, u);
            memcpy(fm + 3, u, sizeof u);
            int rc = rest_of(pb, j, fm, pb->e0 + 6 * j);
            if (rc != RD_OK)
                return rc;
        }
    }
    return RD_OK;
}

int rd_free_shape_prestrain(rd_static_problem *pb, const rd_ring_params *p, const rd_free_shape *fs,
                            rd_error *err)
{
    if (!fs || fs->kind == RD_FREE_CLOSED)
        return RD_OK;
    int n = pb->n;
    pb->e0 = calloc((size_t)6 * n, sizeof *pb->e0);
    if (!pb->e0)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape.");
    double *f = malloc((size_t)6 * n * sizeof *f);
    if (!f)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape.");
    double terms[2];
    int rc = balanced_loads(pb, p, fs, f, terms);
    if (rc == RD_OK)
        rc = pressure_rest(pb, f);
    free(f);
    if (rc == RD_ENOMEM)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the free shape.");
    if (rc == RD_OK)
        return RD_OK;
    size_t m = rd_error_enter(err, "/ring");
    rc = rd_error_set(err, RD_EINVAL, "", "a joint's stiffness is singular.");
    rd_error_leave(err, m);
    return rc;
}

/* ---- the ring closed by the pressure it was made for --------------------- */

/* The design pressure as dead loads: per segment 8 points of (body offset,
 * global force) in pb->dead, scaled by the load factor with the rest. */
static void dead_residual(const rd_static_problem *pb, double *r)
{
    double fac = rd_static_force_factor(pb);
    for (int i = 0; i < pb->n; i++)
        for (int q = 0; q < 8; q++) {
            const double *d = pb->dead + 48 * i + 6 * q;
            double F[3] = {fac * d[3], fac * d[4], fac * d[5]}, f[6] = {0};
            rd_static_add_force(pb->Q + 9 * i, d, F, f);
            for (int k = 0; k < 6; k++)
                r[6 * i + k] -= f[k];
        }
}

/* d(moment)/d(turn w) of a dead force F at the arm a = Q c: [F]x [a]x. */
static void dead_jacobian(const rd_static_problem *pb, int i, double J[36])
{
    double fac = rd_static_force_factor(pb);
    for (int q = 0; q < 8; q++) {
        const double *d = pb->dead + 48 * i + 6 * q;
        double a[3], F[3] = {fac * d[3], fac * d[4], fac * d[5]};
        rd_mv3(pb->Q + 9 * i, d, a);
        /* [F]x [a]x v = F x (a x v) = a (F.v) - v (F.a) */
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                J[(3 + r) + 6 * (3 + c)] += a[r] * F[c] - (r == c ? rd_dot3(F, a) : 0.0);
    }
}

static const rd_static_loads dead_loads = {.residual = dead_residual,
                                           .segment_jacobian = dead_jacobian};

int rd_free_shape_installed(const rd_ring_params *p, int segments, const rd_free_shape *fs,
                            const rd_static_opts *so, double *twist_deg, rd_error *err)
{
    rd_static_problem pb;
    rd_static_stats st;
    memset(&st, 0, sizeof st);
    int rc;
    rd_ring *ring = rd_ring_create(p, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_EINVAL;
    if ((rc = rd_static_problem_init(&pb, ring, &dead_loads)) != RD_OK ||
        !(pb.dead = malloc((size_t)48 * segments * sizeof *pb.dead))) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the installed ring.");
        goto out;
    }
    if ((rc = rd_free_shape_prestrain(&pb, p, fs, err)) != RD_OK)
        goto out;
    double *f = malloc((size_t)6 * segments * sizeof *f), terms[2];
    rc = f ? balanced_loads(&pb, p, fs, f, terms) : RD_ENOMEM;
    free(f);
    if (rc != RD_OK) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory for the installed ring.");
        goto out;
    }
    pressure_loads(&pb, p, fs, 3, terms, pb.dead);
    for (int k = 0; k < 6; k++)
        pb.mask[k] = 1.0;
    pb.F_ref = p->tangential_force;
    if ((rc = rd_static_solve_path(&pb, so, NULL, &st, err)) != RD_OK) {
        if (rc == RD_ENOCONV) {
            rd_section sec;
            rd_section_init(&sec, p);
            char why[RD_ERROR_MESSAGE_MAX];
            snprintf(why, sizeof why, "%s", err ? err->message : "");
            size_t m = rd_error_enter(err, "/ring");
            rc = rd_error_set(
                err, RD_ENOCONV, "/section",
                "the ring closed by its pressure distribution has no equilibrium with this "
                "section: its principal axes are turned by %.3g deg, and the twist that closing "
                "turns them further grows without bound (the twist's coupling rises with the "
                "twist; a ring whose linear twist nears the principal angle turns over).  Lower "
                "F_t or the section's asymmetry.  (%s)",
                sec.angle * 180.0 / M_PI, why);
            rd_error_leave(err, m);
        }
        goto out;
    }
    for (int i = 0; i < segments; i++) {
        double w[3], a = rd_ring_get_segment_angle(ring, i);
        rd_static_rot_log(pb.Q + 9 * i, w);
        twist_deg[i] = (w[0] * sin(a) - w[1] * cos(a)) * 180.0 / M_PI;
    }
out:
    rd_static_problem_cleanup(&pb);
    rd_ring_free(ring);
    return rc;
}
