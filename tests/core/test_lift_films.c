/*
 * test_lift_films — the lubricated lift in a distorted bore: a film per
 * segment load (core/lift/rd_lift_film.c, rd_lift_films_*).
 *
 * References:
 *  - the loads: each segment's static contact load on the liner (the
 *    contact analysis' exact contact, rd_lift_bore_loads) against the
 *    thin-ring closed form (test_lift_bore's): an order-k distortion A_k
 *    changes the contact pressure by dp_k = -E I (k^2 - 1)^2 / (R^4 h) A_k
 *    cos k (psi - phi_k) where the ring follows the bore, so the film's line
 *    load is 2 F_t / D (1 + sum dp_k / p0); away from the gap, at n = 64,
 *    within 0.05 of the range (measured 0.035; the lift's own penalty
 *    contact at its static start missed by 0.26 at 5 um and by half the
 *    range at 0.2 um: its compliance, which is why the films take the
 *    contact analysis' loads);
 *  - the films under those loads: each carries its own load at every step
 *    (its radial balance), a larger load a thinner film at every step, and
 *    at mid-stroke h0 ~ W^-alpha with alpha near 1: a rigid parabolic face
 *    in full film at steady sliding carries W = C eta U R / h0 (Martin);
 *  - a segment's film on a coarser ring (the n/2 estimate's): the ring's
 *    total (sum over segments of share x the film's loads and shear
 *    coefficients) is the same for any segment count (a conservation
 *    law), and n = m/2 is the mean of two;
 *  - the coupling: the friction the ring felt in its motion (per segment,
 *    rd_lift_forces.c add_bore) against the lubrication block's (the films'
 *    friction weighted by their shares, at the piston's speed): equal where
 *    the ring sits on a flank and moves with the piston;
 *  - a vanishing distortion gives the round bore's friction work and film
 *    (within the loads' accuracy: the contact solve's, against the same
 *    contact converged further);
 *  (bench_lube has the cost.)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fired_cycle.h"
#include "lift_distort.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

#define PI 3.14159265358979323846

static void scene(rd_ring_params *rp, rd_lift_params *p, double A)
{
    lubricated_scene(rp, p, A);
}

/* The closed form's load over 2 F_t / D at psi (rad). */
static double closed_load(const rd_ring_params *rp, const rd_lift_params *p, double psi)
{
    double b = rp->radial_width, h = rp->axial_height, R = 0.5 * (rp->diameter - b);
    double EI = rp->youngs_modulus * h * b * b * b / 12.0,
           p0 = 2.0 * rp->tangential_force / (rp->diameter * h);
    double w = 1.0;
    for (int k = 0; k < p->bore.n_distortion; k++) {
        double m = p->bore.distortion[k].order, A = p->bore.distortion[k].amplitude;
        w -= EI * pow(m * m - 1.0, 2.0) / (pow(R, 4.0) * h) * A *
             cos(m * (psi - p->bore.distortion[k].phase_deg * PI / 180.0)) / p0;
    }
    return w;
}

static void loads(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    scene(&rp, &p, 5e-6);
    int n = 64;
    rd_error err = {0};
    rd_ring *ring = rd_ring_create(&rp, n, 0, &err);
    double load[64], ang[64];
    int rc = ring ? rd_lift_bore_loads(ring, &p, load, ang, &err) : RD_ENOMEM;
    CHECK(rc == RD_OK, "the segments' loads: %s", err.message);
    double w_el = 2.0 * rp.tangential_force / rp.diameter, lo = 1e9, hi = -1e9, worst = 0.0;
    for (int i = 0; rc == RD_OK && i < n; i++) {
        double c = closed_load(&rp, &p, ang[i] * PI / 180.0);
        lo = fmin(lo, c);
        hi = fmax(hi, c);
        if (ang[i] > 45.0 && ang[i] < 315.0)
            worst = fmax(worst, fabs(load[i] / w_el - c));
    }
    printf("loads: closed form %.3f to %.3f of 2 F_t / D; the segments' off by at most %.3g "
           "(%.3g of the range) away from the gap, n = %d\n",
           lo, hi, worst, worst / (hi - lo), n);
    CHECK(hi - lo > 0.2, "the distortion moves the load by %g of 2 F_t / D", hi - lo);
    CHECK(worst < 0.05 * (hi - lo), "the loads miss the closed form by %g (range %g)", worst,
          hi - lo);
    rd_ring_free(ring);
}

/* The loads at the contact used (one solve at 16 n = 320 segments) against
 * the contact at 2000 segments, n = 20, on distortions of 2, 5 and 10 um:
 * the largest difference over 2 F_t / D. */
static void loads_converged(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    double worst = 0.0;
    for (int a = 0; a < 3; a++) {
        scene(&rp, &p, a == 0 ? 2e-6 : a == 1 ? 5e-6 : 10e-6);
        rd_error err = {0};
        rd_ring *ring = rd_ring_create(&rp, 20, 0, &err);
        double l0[20], l1[20], ang[20], w_el = 2.0 * rp.tangential_force / rp.diameter;
        int rc = ring ? rd_lift_bore_loads(ring, &p, l0, ang, &err) : RD_ENOMEM;
        rc = rc ? rc : rd_lift_bore_loads_at(ring, &p.bore, 2000, NULL, l1, ang, &err);
        CHECK(rc == RD_OK, "loads: %s", err.message);
        for (int j = 0; rc == RD_OK && j < 20; j++)
            worst = fmax(worst, fabs(l0[j] - l1[j]) / w_el);
        rd_ring_free(ring);
    }
    printf("loads: within %.3g of 2 F_t / D of the contact at 2000 segments\n", worst);
    CHECK(worst < 1e-2, "the loads are %g off the converged contact's", worst);
}

/* Films under five loads 0.6 .. 1.6 of 2 F_t / D (each its own film: up to
 * RD_LIFT_FILMS_EXACT), no gas.  Each film carries
 * its own load at every step (its radial balance W_film + W_asperity =
 * load, to the track's secant tolerance), a larger load a thinner film at
 * every step, and at mid-stroke h0 ~ W^-alpha with alpha near Martin's 1:
 * a barrel of 100 um crown (radius (h/2)^2 / (2 crown) = 1.8 mm) keeps the
 * pressure zone, about sqrt(2 R h0) = 0.07 mm, well inside the face; the
 * films on a grid 4 times finer (161 points).  (At the default 5 um crown
 * the zone spans the face and alpha is about 0.35.) */
static void films_loads(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    scene(&rp, &p, 0.0);
    p.face.crown = 100e-6;
    double w_el = 2.0 * rp.tangential_force / rp.diameter, load[5], ang[5];
    for (int i = 0; i < 5; i++) {
        load[i] = w_el * (0.6 + 0.25 * i);
        ang[i] = 72.0 * i;
    }
    rd_lift_films fs;
    rd_error err = {0};
    int rc = rd_lift_films_run(&rp, &p, &(rd_lift_film_loads){5, 1, NULL, load, ang, 0, NULL}, 4,
                               NULL, &fs, &err);
    CHECK(rc == RD_OK && fs.count == 5 && fs.exact, "five films: %s (%d)", err.message, fs.count);
    double off = 0.0, h90[5] = {0};
    int thinner = 1;
    for (int g = 0; rc == RD_OK && g < fs.count; g++) {
        for (int k = 0; k <= fs.tr[g].steps; k++) {
            const rd_film_point *pt = &fs.tr[g].pt[k];
            off = fmax(off, fabs(pt->W + pt->Wa - fs.load[g]) / fs.load[g]);
            if (g > 0) {
                rd_film_point q;
                rd_film_track_at(&fs.tr[g - 1], pt->t, &q);
                thinner &= pt->h0 < q.h0;
            }
        }
        rd_film_point pt;
        rd_film_track_at(&fs.tr[g], 0.5 * PI / (2400.0 * PI / 30.0), &pt); /* 90 deg */
        h90[g] = pt.h0;
        CHECK(pt.Wa < 1e-2 * pt.W, "film %d at 90 deg: asperity load %g of %g", g, pt.Wa, pt.W);
    }
    if (rc == RD_OK) {
        double alpha = log(h90[0] / h90[4]) / log(fs.load[4] / fs.load[0]);
        printf("films under 0.6-1.6 x 2 F_t / D: balance within %.2g; h0 at 90 deg %.3g to %.3g "
               "m, h0 ~ W^-%.3f (Martin: 1)\n",
               off, h90[0], h90[4], alpha);
        CHECK(off < 1e-4, "a film's balance is off its load by %g", off);
        CHECK(thinner, "a larger load gives a thinner film at every step");
        CHECK(alpha > 0.9 && alpha < 1.0, "h0 ~ W^-%g", alpha);
    }
    rd_lift_films_free(&fs);
}

/* Segment films of coarser rings: the ring's totals for any n, and n = m/2
 * the mean of two (segment weights one-hot and interpolating). */
static void coarse(void)
{
    enum { M = 20 };
    enum { S = RD_LIFT_FILMS_NODES };
    static double wt[S * M], acc[S];
    static rd_film_track trs[S];
    rd_lift_films fs = {.m = M, .count = 3, .cap = S, .acc = acc, .tr = trs};
    rd_film_point pts[6];
    for (int j = 0; j < M; j++) {
        double a = 0.05 * j - 0.3, b = 0.5 - 0.02 * j;
        wt[S * j] = j % 4 ? a : (j % 3 == 0);
        wt[S * j + 1] = j % 4 ? b : (j % 3 == 1);
        wt[S * j + 2] = j % 4 ? 1.0 - a - b : (j % 3 == 2);
    }
    for (int g = 0; g < 3; g++) {
        pts[2 * g] = (rd_film_point){.t = 0.0,
                                     .h0 = 1e-6 * (g + 1),
                                     .W = 100.0 + g,
                                     .Wa = g,
                                     .Cc = 0.01 * (g + 2),
                                     .Fp = -0.3 * g,
                                     .U = 1.0};
        pts[2 * g + 1] = pts[2 * g];
        pts[2 * g + 1].t = 1.0;
        pts[2 * g + 1].Cc *= 3.0;
        fs.tr[g] = (rd_film_track){.steps = 1, .cap = 2, .pt = pts + 2 * g};
    }
    fs.wt = wt;
    rd_film_point grp[3], seg[M], fine[M];
    rd_lift_films_at(&fs, 0.25, M, grp, fine);
    double want = 0.0, wantF = 0.0;
    for (int j = 0; j < M; j++) {
        double c = 0.0;
        for (int g = 0; g < 3; g++)
            c += wt[S * j + g] * grp[g].Cc;
        want += c / M;
        wantF += fine[j].Fp / M;
        CHECK(fabs(fine[j].Cc - c) < 1e-15, "n = m: segment %d takes its own film", j);
    }
    int ns[] = {7, 10, 13, 3};
    for (int c = 0; c < 4; c++) {
        int n = ns[c];
        rd_lift_films_at(&fs, 0.25, n, grp, seg);
        double got = 0.0, gotF = 0.0;
        for (int i = 0; i < n; i++) {
            got += seg[i].Cc / n;
            gotF += seg[i].Fp / n;
        }
        CHECK_REL(got, want, 1e-13, "n = %d: the ring's Couette coefficient", n);
        CHECK(fabs(gotF - wantF) < 1e-13, "n = %d: the ring's pressure shear %g vs %g", n, gotF,
              wantF);
        if (n == M / 2)
            for (int i = 0; i < n; i++)
                CHECK(fabs(seg[i].W - 0.5 * (fine[2 * i].W + fine[2 * i + 1].W)) < 1e-12,
                      "n = m / 2: segment %d the mean of two", i);
    }
}

/* The interpolated films against every segment's own film, on a battery
 * (distortions 2-10 um, orders 2 + 4 or 3, with and without the fired
 * cycle's gas, 1000 and 2400 rpm): the largest film (over max(|h0|, sigma))
 * and friction-work differences over the segments, below 1e-2 and 1e-3,
 * and the estimate the result reports (interp_check: the coarser level's
 * miss at the finer level's nodes) within x3 of them.  The miss does not
 * fall below a few 1e-3 with more nodes (17 gave the same): each film's
 * own time steps (local error 1e-4, steps chosen per film) leave it that
 * far from a film at a neighbouring load; the film's film_error is of the
 * same order. */
static fired_tables tables;

static void interpolation(void)
{
    struct {
        double A, rpm;
        int order3, gas;
    } bat[] = {{2e-6, 2400, 0, 0}, {5e-6, 2400, 0, 1},  {10e-6, 2400, 0, 1},
               {5e-6, 1000, 1, 1}, {10e-6, 1000, 0, 0}, {3e-6, 2400, 1, 1}};
    int n = 20, nb = (int)(sizeof bat / sizeof bat[0]), within = 0;
    double rmin = 1e9, rmax = 0.0;
    for (int b = 0; b < nb; b++) {
        rd_ring_params rp;
        rd_lift_params p;
        scene(&rp, &p, bat[b].A);
        p.engine.speed_rpm = bat[b].rpm;
        if (bat[b].order3) {
            p.bore.n_distortion = 1;
            p.bore.distortion[0] = (rd_distortion){.order = 3, .amplitude = bat[b].A};
        }
        if (bat[b].gas)
            p.gas = fired_cycle_gas(&tables, 0.0);
        rd_error err = {0};
        rd_ring *ring = rd_ring_create(&rp, n, 0, &err);
        double load[20], ang[20];
        rd_lift_films fs = {0};
        int rc = ring ? rd_lift_bore_loads(ring, &p, load, ang, &err) : RD_ENOMEM;
        rc = rc ? rc
                : rd_lift_films_run(&rp, &p, &(rd_lift_film_loads){n, 1, NULL, load, ang, 0, NULL},
                                    1, NULL, &fs, &err);
        CHECK(rc == RD_OK && !fs.exact, "battery %d: %s", b, err.message);
        double fe = 0.0, we = 0.0, omega = 2.0 * PI * bat[b].rpm / 60.0, cycle = 4.0 * PI / omega;
        double circ = PI * rp.diameter, ureg = rd_liner_ureg(&p.engine);
        double mu_b = p.friction.lube.boundary_coefficient;
        for (int j = 0; rc == RD_OK && j < n; j++) {
            rd_film f;
            rd_film_track tr = {0};
            const double *w = fs.wt + (size_t)fs.cap * j;
            rc = rd_lift_film_run_load(&rp, &p, load[j], 1, &f, &tr, &err);
            for (int k = 0; rc == RD_OK && k <= tr.steps; k++) {
                double h = 0.0;
                for (int g = 0; g < fs.count; g++) {
                    rd_film_point pt;
                    rd_film_track_at(&fs.tr[g], tr.pt[k].t, &pt);
                    h += w[g] * pt.h0;
                }
                fe = fmax(fe, fabs(h - tr.pt[k].h0) / fmax(fabs(tr.pt[k].h0), f.sigma));
            }
            double ww = rd_lift_film_work(&tr, circ, mu_b, ureg, 0.0, cycle), wi = 0.0;
            for (int g = 0; g < fs.count; g++)
                wi += w[g] * rd_lift_film_work(&fs.tr[g], circ, mu_b, ureg, 0.0, cycle);
            we = fmax(we, fabs(wi - ww) / fabs(ww));
            rd_film_track_free(&tr);
            rd_film_free(&f);
        }
        if (rc == RD_OK) {
            double t = fmax(fe, we);
            printf("interpolation %d (%.0f um, order%s, %.0f rpm%s): loads %.0f-%.0f N/m, %d "
                   "films; the segments' films miss by %.2g, work by %.2g; estimate %.2g\n",
                   b, bat[b].A * 1e6, bat[b].order3 ? " 3" : "s 2 + 4", bat[b].rpm,
                   bat[b].gas ? ", gas" : "", fs.load[0], fs.load[fs.count - 1], fs.count, fe, we,
                   fs.interp_check);
            rmin = fmin(rmin, fs.interp_check / t);
            rmax = fmax(rmax, fs.interp_check / t);
            within += fs.interp_check >= t / 3.0 && fs.interp_check <= 3.0 * t;
            CHECK(fe < 1e-2 && we < 1e-3,
                  "battery %d: the interpolated films miss by %g, the "
                  "work by %g",
                  b, fe, we);
        }
        rd_lift_films_free(&fs);
        rd_ring_free(ring);
    }
    printf("interpolation: the estimate %.2g-%.2g x the segments' miss; within x3 on %d of %d "
           "scenes\n",
           rmin, rmax, within, nb);
    CHECK(within == nb, "the interpolation's estimate within x3 on %d of %d scenes", within, nb);
}

/* The segments' axial speeds in their grooves at each sample, the largest
 * over the piston's speed (the sample hook). */
#define VS_MAX 2048
typedef struct vspeed {
    int n, k;
    const rd_engine_params *e;
    double rel[VS_MAX];
} vspeed;

static void vspeed_sample(void *ctx, double t, const double *y)
{
    vspeed *c = ctx;
    if (c->k >= VS_MAX)
        return;
    double v, w = 2.0 * PI * c->e->speed_rpm / 60.0, m = 0.0;
    rd_engine_piston(c->e, w * t, NULL, &v, NULL);
    for (int i = 0; i < c->n; i++)
        m = fmax(m, fabs(y[12 * i + 8]));
    c->rel[c->k++] = m / fmax(fabs(v), 1e-9);
}

/* Where the ring sits on a flank (every segment within 1e-3 c_a of it) and
 * the block's friction is above 5 % of its largest: the largest relative
 * difference between the friction the ring felt and the block's, less what
 * the segments' own speeds in their grooves explain (the Couette shear
 * sees the ring's speed on the liner, the block the piston's; v == NULL:
 * nothing subtracted). */
static double seated_mismatch(const rd_lift_result *r, double ca, const vspeed *v, int *count)
{
    const rd_lift_lube *lb = &r->lube;
    double fmax_ = 0.0, worst = 0.0;
    for (int k = 0; k < r->samples; k++)
        fmax_ = fmax(fmax_, fabs(lb->hydrodynamic_friction[k] + lb->asperity_friction[k]));
    *count = 0;
    for (int k = 0; k < r->samples; k++) {
        double f = lb->hydrodynamic_friction[k] + lb->asperity_friction[k];
        int on = r->lift_max[k] < 1e-3 * ca || r->lift_min[k] > (1.0 - 1e-3) * ca;
        if (on && fabs(f) > 0.05 * fmax_) {
            double d = fabs(r->friction_force[k] - f) / fabs(f);
            worst = fmax(worst, d - (v && k < v->k ? 1.5 * v->rel[k] : 0.0));
            (*count)++;
        }
    }
    return worst;
}

/* The lift in the distorted bore: the ring's friction (each segment its
 * film, rd_lift_forces.c) against the block's (each film its share): they
 * differ by what the segments' own speeds in their grooves explain (the
 * films' varying friction sets the ring vibrating on its flank: measured
 * 1.5e-3 of the friction, against 1.5e-5 in the round bore), and by no
 * more than the round bore's one film does beyond that. */
static void coupling(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_lift_result r, o;
    rd_error err = {0};
    scene(&rp, &p, 5e-6);
    static vspeed vs;
    vs = (vspeed){.n = 20, .e = &p.engine};
    rd_lift_setup su = {.sample = vspeed_sample, .ctx = &vs};
    int rc = rd_lift_solve_setup(&rp, 20, &p, &su, NULL, &r, &err);
    CHECK(rc == RD_OK, "lubricated lift in a distorted bore: %s", err.message);
    scene(&rp, &p, 0.0);
    int rc2 = rd_lift_solve(&rp, 20, &p, NULL, &o, &err);
    CHECK(rc2 == RD_OK, "the round bore: %s", err.message);
    if (rc == RD_OK && rc2 == RD_OK) {
        const rd_lift_lube *lb = &r.lube;
        CHECK(lb->films >= 5 && lb->films <= 17 && lb->min_film_angle_deg &&
                  isfinite(lb->interp_check),
              "interpolated films: %d", lb->films);
        CHECK(lb->load_max - lb->load_min > 0.2 * 2.0 * rp.tangential_force / rp.diameter,
              "the films' loads %g to %g N/m", lb->load_min, lb->load_max);
        int kd, kr;
        double ca = p.groove.axial_clearance, md0 = seated_mismatch(&r, ca, NULL, &kd),
               md = seated_mismatch(&r, ca, &vs, &kd), mr = seated_mismatch(&o, ca, NULL, &kr);
        printf("coupling: %d films (loads %.1f to %.1f N/m); the ring's friction vs the block's "
               "where seated: %.3g relative (%d samples), %.3g beyond the segments' speeds; the "
               "round bore's %.3g (%d); %ld film solves against the round bore's %ld\n",
               lb->films, lb->load_min, lb->load_max, md0, kd, md, mr, kr, lb->film_solves,
               o.lube.film_solves);
        CHECK(kd > 100 && kr > 100 && vs.k == r.samples, "seated samples: %d, %d", kd, kr);
        CHECK(md < 2.0 * mr + 1e-5, "the ring's friction and the films': %g relative (round %g)",
              md, mr);
    }
    rd_lift_result_cleanup(&r);
    rd_lift_result_cleanup(&o);
}

/* A vanishing distortion: the round bore's film and friction work. */
static void vanishing(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    rd_lift_result a, b;
    rd_error err = {0};
    scene(&rp, &p, 0.0);
    int rc = rd_lift_solve(&rp, 12, &p, NULL, &a, &err);
    scene(&rp, &p, 1e-10);
    int rc2 = rd_lift_solve(&rp, 12, &p, NULL, &b, &err);
    CHECK(rc == RD_OK && rc2 == RD_OK, "round and 0.1 nm: %s", err.message);
    if (rc == RD_OK && rc2 == RD_OK) {
        double dh = 0.0;
        for (int k = 0; k < a.samples; k++)
            dh = fmax(dh, fabs(a.lube.min_film[k] - b.lube.min_film[k]) / a.lube.min_film[k]);
        printf("0.1 nm distortion: %d films, film within %.3g, work %.6g vs %.6g J\n", b.lube.films,
               dh, b.lube.friction_work[0], a.lube.friction_work[0]);
        CHECK(a.lube.films == 1 && !a.lube.min_film_angle_deg, "the round bore: one film");
        /* within the loads' accuracy (2.4e-3 of 2 F_t / D, loads_converged) */
        CHECK(dh < 3e-3, "the film moves by %g", dh);
        CHECK_REL(b.lube.friction_work[0], a.lube.friction_work[0], 1e-3, "friction work");
    }
    rd_lift_result_cleanup(&a);
    rd_lift_result_cleanup(&b);
}

int main(void)
{
    loads();
    loads_converged();
    films_loads();
    coarse();
    interpolation();
    vanishing();
    coupling();
    return check_done();
}
