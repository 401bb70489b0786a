/*
 * rd_contact_law — the contact law and one contact point's evaluation
 * (the model is in rd_contact.c's header): the load path's parts (the
 * share mu of the bore's departure from round that is in place, the law's
 * smoothing length), the bore's radius at an angle or at a point, each
 * point's multiplier and its law's stiffness, and the law p(delta) with its
 * slope.  Below both the problem (rd_contact.c) and the faces
 * (rd_contact_face.c), which evaluate their points here.
 */
#include "rd_static_internal.h"

#include <math.h>

/* The load path (lambda 0..1): F_t over 0..RD_CONTACT_LF with the bore
 * still the ring's closed shape, then the bore's departure from it over
 * RD_CONTACT_LF..RD_CONTACT_BORE_DONE, the contact law smoothed over EPS_WIDE times its
 * length meanwhile (a Newton step then sees contacts change over a length
 * comparable to its own, not 1e-10 m), then the smoothing brought down to
 * eps geometrically; measured: half the Newton iterations of the unsmoothed
 * path on the hard bores of bench_static --battery, the answer unchanged
 * within the residual tolerance.  EPS_WIDE 1e4 since 0.3.8 (1e3 before):
 * the first level's path (n = 20, rigid faces) crept through the bore's
 * part in steps of 0.002 at 7-9 Newton iterations each (its step grows only
 * below 7), and was a quarter of a bore's CPU; the load steps' Newton
 * iterations over bench_static's three rings' batteries (all levels, the
 * failed tries counted) 12318, 19134, 13173 at 1e3; 7761, 8775, 7419 at
 * 1e4; 7386, 7425, 6921 at 3e4 and 8124, 9042, 7545 at 1e5, where the
 * finer levels, whose warm starts take the smoothing down from EPS_WIDE,
 * begin to need more (1404 at n >= 160 at 1e3, 1410 at 1e4, 1443 at 3e4,
 * each up to 64 times a first level's); the same targets met and the same
 * estimates tracking on all three.  Instructions of rd_contact_solve
 * (callgrind, bench_contact_cost): order 2 at 2.8 x, 17 deg 1.63 -> 1.51 G,
 * order 4 at 10 x, 17 deg 1.74 -> 1.66 G. */
#define EPS_WIDE 1e4

/* F_t first (lambda 0..RD_CONTACT_LF, the bore still the ring's closed
 * shape, so the ring is pressed on it throughout), then the bore: a bore
 * moving away from an unloaded ring would leave it floating, and Newton
 * with it. */
double rd_contact_force_factor(const rd_static_problem *pb)
{
    return fmin(1.0, pb->lambda / RD_CONTACT_LF);
}

static double bore_factor(const rd_static_problem *pb)
{
    return fmin(1.0,
                fmax(0.0, (pb->lambda - RD_CONTACT_LF) / (RD_CONTACT_BORE_DONE - RD_CONTACT_LF)));
}

/* The law's smoothing length at the current load factor. */
static double eps_now(const rd_static_problem *pb)
{
    double s = fmin(1.0, fmax(0.0, (1.0 - pb->lambda) / (1.0 - RD_CONTACT_BORE_DONE)));
    return pb->eps * pow(EPS_WIDE, s);
}

/* Bore radius and its derivative at theta, at the current load factor. */
void rd_contact_bore_radius(const rd_static_problem *pb, double theta, double *r, double *dr)
{
    double a = pb->bore_dr, da = 0.0;
    for (int k = 0; k < pb->co->bore.n_distortion; k++) {
        const rd_distortion *d = &pb->co->bore.distortion[k];
        double arg = d->order * (theta - d->phase_deg * M_PI / 180.0);
        a += d->amplitude * cos(arg);
        da -= d->amplitude * d->order * sin(arg);
    }
    double mu = bore_factor(pb);
    *r = pb->r_o + mu * a;
    *dr = mu * da;
}

/* The same at the angle of the point y, rho = |(y[0], y[1])| > 0,
 * without trigonometry: cos k theta + i sin k theta = ((y0 + i y1) /
 * rho)^k, turned by the precomputed cos, sin of k phi_k (5-9 % of a
 * distorted bore's solve, callgrind). */
static void bore_at(const rd_static_problem *pb, const double y[3], double rho, double mu,
                    double *r, double *dr)
{
    double c = y[0] / rho, s = y[1] / rho;
    double a = pb->bore_dr, da = 0.0;
    for (int q = 0; q < pb->co->bore.n_distortion; q++) {
        const rd_distortion *d = &pb->co->bore.distortion[q];
        double ck = 1.0, sk = 0.0;
        for (int j = 0; j < d->order; j++) {
            double t = ck * c - sk * s;
            sk = sk * c + ck * s;
            ck = t;
        }
        double cp = pb->bore_phase[2 * q], sp = pb->bore_phase[2 * q + 1];
        a += d->amplitude * (ck * cp + sk * sp);
        da -= d->amplitude * d->order * (sk * cp - ck * sp);
    }
    *r = pb->r_o + mu * a;
    *dr = mu * da;
}

/* Point k of segment i's multiplier: its segment's, or with tip_mult the
 * very tip's own (n on the first free end, n + 1 on the last). */
int rd_contact_mult_of(const rd_static_problem *pb, int i, int k)
{
    if (pb->tip_mult && i == 0 && k == 0)
        return pb->n;
    if (pb->tip_mult && i == pb->n - 1 && k == pb->m - 1)
        return pb->n + 1;
    return i;
}

/* The law's stiffness at multiplier q: k, or TIP_STIFFNESS k at a tip's
 * own point once the load is on (the multipliers' updates; along the load
 * path the tip's law is k's, as the warm starts from a coarser level need:
 * from the start the first flexible level, n = 80, of order 2 at 2.8 x
 * stalled after 400 iterations and took the whole path again). */
#define TIP_STIFFNESS 100.0
double rd_contact_law_stiffness(const rd_static_problem *pb, int q)
{
    return q >= pb->n && pb->lambda >= 1.0 ? TIP_STIFFNESS * pb->k : pb->k;
}

/* The smooth contact law p(delta) = k eps ln(1 + exp(delta / eps)) at
 * point q, its penetration shifted by the point's multiplier: delta +
 * lambda_q / k (the augmented Lagrangian; lambda = 0 is the plain penalty). */
double rd_contact_pressure(const rd_static_problem *pb, double delta, int q)
{
    double k = rd_contact_law_stiffness(pb, q);
    if (pb->mult)
        delta += pb->mult[q] / k;
    double e = eps_now(pb), z = delta / e;
    if (z > 0)
        return k * (delta + e * log1p(exp(-z)));
    return k * e * log1p(exp(z));
}

/* The law at one point with its slope dp/ddelta (the logistic function of
 * z; e the current smoothing length, hoisted out of the points' loop).
 * Below z = -746 exp(z) underflows to 0 (from -745.13 on), so both are
 * exactly 0 there: returned without the calls (most points of a bore with
 * light gaps).  Above z = 40 they are exactly k delta and k: q = exp(-z) <
 * 4.3e-18 is under half an ulp of 1 (1 + q rounds to 1) and e log1p(q) =
 * delta q / z under half an ulp of delta, so the calls are skipped there
 * too (a point pressing at over 2 p0; from z = 708 on exp(-z) is
 * subnormal, glibc's slow path).  Order 2 at 1.97 x, 179.8 deg (a random
 * bore over 0.2 s): 3.124 -> 3.053 G instructions (callgrind,
 * bench_contact_cost 2 1.97019 179.812); order 6 at 10 x, 0 deg: 1.026 ->
 * 1.023 G; bench_contact_cost --battery's fingerprints the same. */
static void law_and_slope(const rd_static_problem *pb, double delta, int i, double e, double *p,
                          double *dp)
{
    double k = rd_contact_law_stiffness(pb, i);
    delta += pb->mult ? pb->mult[i] / k : 0.0;
    double z = delta / e;
    if (z < -746.0) {
        *p = *dp = 0.0;
        return;
    }
    if (z > 40.0) {
        *p = k * delta;
        *dp = k;
    } else if (z > 0) {
        double q = exp(-z);
        *p = k * (delta + e * log1p(q));
        *dp = k / (1.0 + q);
    } else {
        double q = exp(z);
        *p = k * e * log1p(q);
        *dp = k * q / (1.0 + q);
    }
}

rd_contact_at rd_contact_now(const rd_static_problem *pb)
{
    return (rd_contact_at){eps_now(pb), bore_factor(pb)};
}

void rd_contact_law_again(const rd_static_problem *pb, int o, int k, double e, rd_contact_eval *pe)
{
    law_and_slope(pb, pe->delta, rd_contact_mult_of(pb, o, k), e, &pe->p, &pe->dp);
}

void rd_contact_point(const rd_static_problem *pb, int o, int k, const double y[3],
                      const rd_contact_at *at, rd_contact_eval *pe)
{
    /* sqrt, not hypot: no overflow or underflow at a ring's size, and
     * glibc's hypot was 3 % of a contact solve's instructions (callgrind,
     * order 4 at 10 x, 17 deg: 2.297 -> 2.232 G) */
    double rho = sqrt(y[0] * y[0] + y[1] * y[1]), rb, drb, *n = pe->n;
    bore_at(pb, y, rho, at->mu, &rb, &drb);
    pe->delta = rho - rb;
    rd_contact_law_again(pb, o, k, at->e, pe);
    if (!rd_contact_presses(pe))
        return; /* no force: its normal is never read */
    /* grad(delta) = e_rho - r_b'/rho e_theta */
    n[0] = y[0] / rho + drb / rho * y[1] / rho;
    n[1] = y[1] / rho - drb / rho * y[0] / rho;
    n[2] = 0.0;
}
