/*
 * rd_contact_uzawa — the contact problem's outer iterations: the augmented
 * Lagrangian's multipliers (rd_contact.c's header has the law and why),
 * updated at the full load and mixed by Anderson acceleration, each update
 * followed by a Newton solve from the last state through the solver's
 * rd_static_resolve, until the updates settle.  rd_contact.c's loads table
 * names rd_contact_uzawa as its outer iterations.
 */
#include "rd_anderson.h"
#include "rd_static_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The augmented Lagrangian's update at the state of the last
 * rd_contact_loads, lambda_q <- p_q (each point's current pressure);
 * returns max_q |p_q - lambda_q| / p0 before it. */
static double update_multipliers(rd_static_problem *pb)
{
    double change = 0.0;
    for (int i = 0; i < pb->n; i++) {
        double sp = 0.0, spd = 0.0;
        for (int k = 0; k < pb->m; k++) {
            const rd_contact_eval *pe = pb->pe + pb->m * i + k;
            int q = rd_contact_mult_of(pb, i, k);
            double d = pe->delta, p = pe->p;
            if (q != i) { /* a free end's tip: its own */
                double next = fmax(0.0, pb->mult[q] + rd_contact_law_stiffness(pb, q) * d);
                change = fmax(change, fabs(next - pb->mult[q]));
                pb->mult[q] = next;
                continue;
            }
            sp += p;
            spd += p * d;
        }
        double next = sp > 0.0 ? fmax(0.0, pb->mult[i] + pb->k * spd / sp) : 0.0;
        change = fmax(change, fabs(next - pb->mult[i]));
        pb->mult[i] = next;
    }
    return change / pb->p0;
}

/* The augmented Lagrangian's outer (Uzawa) iterations at the full load
 * (rd_static_loads.outer).  Each sets every point's multiplier to its
 * pressure and solves again from the last state, so the penetration where
 * the ring presses goes to zero at the law's own stiffness (no stiffer
 * Newton problem); stops when no multiplier's plain update moves it by
 * more than UZAWA_TOL p0.
 *
 * The plain update converges linearly, at a rate near 1 on fine chains
 * (0.95-0.96 a step at n = 640-1280: the ring's stiffness at a segment's
 * length outgrows the law's), so it hit its limit of 30 at n = 640 on
 * bench_static's battery, and its former test of 0.1 p0 stopped ~2 p0 short of the fixed
 * point: the answer depended on the start (0.08 p0 in a bin between two
 * starts, order 6 at 10 x).  The updates are therefore mixed by Anderson
 * acceleration (rd_anderson.h, depth UZAWA_DEPTH) and projected onto
 * lambda >= 0; a mixed step whose Newton solve fails is taken again as the
 * plain update, with the history cleared.  Order 3 at 3 x, 17 deg, n = 640:
 * 13 updates to 0.02 p0 where the plain ones took 30 to 0.1 p0.
 *
 * An update moves the state little, mostly where contact changes, so each
 * solve after one starts with a chord step on the last factorization (the
 * tangent and its factors were half of an iteration's instructions):
 * bench_contact_cost --battery 2.96 -> 2.59 s CPU, its worst bore 0.174 ->
 * 0.145 s, with 771 -> 869 Newton iterations at the finest levels (with
 * the limit below 893 iterations, 484 factorizations, where each iteration
 * had one); the answers move within the updates' tolerance (bench_static
 * --bins, each
 * battery bore, with the limit below: the largest bin change 0.015 p0, on
 * order 6 at 10 x, 0 deg, whose estimate is 0.80 p0; every other bore's
 * bins within 0.0012 p0; the same level and verdict on each).
 *
 * Inexact updates (since 0.3.14, rd_static_opts.update_eta, 0.03): while
 * the plain change is over UZAWA_LOOSE x UZAWA_TOL, an update's Newton
 * solve stops at eta times that change's force on one segment (p0 change
 * x m x area_max over F_ref, residual_norm's scale; times k0 / k for a law
 * stiffer than the default k0, which turns the same residual into a larger
 * update: without it bench_static --stiffness lost 1-2 bores a quantity),
 * or at a tenth of its first residual if that is larger (newton's
 * w->loose): at least one iteration, since an update that moved no state
 * fed Anderson a stale change and it extrapolated to 5000 p0 (the 50 mm
 * ring, order 6 at 1 x, 17 deg: 28 updates at n = 640, 0.23 s).  The multipliers a
 * few updates on do not need the digits.  The change that stops the
 * updates is read at a state solved to the full tolerance (else one more
 * update), and a run stopped at the limit after a loose solve is solved
 * to it, so the answer's residual is the tolerance as before.  Measured
 * (bench_static --exact-updates against the default, Release, two
 * processes on the two cores): the battery 1.93 -> 1.65 s CPU, its slowest
 * 0.17 -> 0.13 s, the same counts; one order a bore, seeds 81-86 on three
 * rings (720, --single --random), 63.4 -> 57.0 s, over 0.2 s 24 -> 18;
 * one or two orders, seeds 51-55 (600), 59.2 -> 52.8 s, 21 -> 15; the same
 * bores within the targets but for the updates' noise (669 -> 668, 534
 * -> 535), met 591 and 434 -> 433.  eta 0.1: -21 % on the battery (0.03:
 * -15 %); without the one-iteration rule 0.1 moved the answers at n = 1280
 * by their updates' noise (estimates 0.012 -> 0.044 p0): an update's
 * error is the residual times the ring's compliance, large for the
 * long-wave modes.
 *
 * The limit (rd_static_opts.max_updates, 60): the battery's point contacts
 * at n = 1280 (orders 4 and 6 at 10 x) take 34 and 44 updates (at 30 they
 * stopped 0.17 and 0.07 p0 short of the tolerance, and said nothing); where
 * it is reached all the same, stats->outer_change says by how much
 * (rd_contact_solve's note). */
#define UZAWA_TOL   0.02
#define UZAWA_DEPTH 3
#define UZAWA_LOOSE 2.0
int rd_contact_uzawa(rd_static_problem *pb, rd_static_session *s)
{
    if (!pb->mult)
        return RD_OK;
    const rd_static_opts *so = s->so;
    rd_static_stats *st = s->st;
    double tol = s->tol, *res = &st->residual;
    /* the force of a change of 1 p0 on one segment, over F_ref (residual_norm's
     * scale), at most the default law's: a stiffer law turns the same
     * residual into a larger update (k delta) */
    double k0 = rd_contact_default_stiffness(rd_ring_get_params(pb->ring));
    double seg = pb->p0 * pb->m * pb->area_max / pb->F_ref * fmin(1.0, k0 / pb->k);
    int loose = 0; /* the last solve stopped short of tol */
    int nm = pb->n + 2, n = pb->n, rc = RD_OK;
    /* the multipliers before and after the plain update, the state before
     * the solve */
    double *x = malloc(((size_t)2 * nm + (size_t)12 * n) * sizeof *x), *g = x ? x + nm : NULL;
    double *x0 = x ? g + nm : NULL, *Q0 = x ? x0 + 3 * n : NULL;
    rd_anderson acc = {0}; /* freed below even where x failed before its init */
    if (!x || rd_anderson_init(&acc, nm, UZAWA_DEPTH) != 0) {
        free(x);
        rd_anderson_free(&acc);
        return rd_error_set(s->err, RD_ENOMEM, "", "Out of memory for the contact multipliers.");
    }
    st->outer_tolerance = UZAWA_TOL;
    for (st->outer_iterations = 0; st->outer_iterations < so->max_updates;) {
        /* at the state the last solve left, its last residual's */
        memcpy(x, pb->mult, (size_t)nm * sizeof *x);
        double change = update_multipliers(pb);
        memcpy(g, pb->mult, (size_t)nm * sizeof *g);
        rd_anderson_mix(&acc, x, pb->mult);
        for (int i = 0; i < nm; i++)
            pb->mult[i] = fmax(0.0, pb->mult[i]);
        memcpy(x0, pb->x, (size_t)3 * n * sizeof *pb->x);
        memcpy(Q0, pb->Q, (size_t)9 * n * sizeof *pb->Q);
        st->outer_iterations++;
        /* (only the multipliers changed since the last residual) */
        int measured = !loose; /* change read at a state solved to tol */
        double stop = change > UZAWA_LOOSE * UZAWA_TOL ? so->update_eta * change * seg : 0.0;
        int ok = rd_static_resolve(pb, s, 1, 1, stop, res);
        if (ok == 0 && acc.m > 0) { /* the plain update instead */
            memcpy(pb->x, x0, (size_t)3 * n * sizeof *pb->x);
            memcpy(pb->Q, Q0, (size_t)9 * n * sizeof *pb->Q);
            memcpy(pb->mult, g, (size_t)nm * sizeof *g);
            rd_anderson_reset(&acc);
            ok = rd_static_resolve(pb, s, 1, 0, stop, res);
        }
        /* (a full-tolerance solve left at the rounding floor counts as one) */
        loose = ok > 0 && stop > 0.0 && *res > tol;
        if (ok < 0) {
            rc = ok;
            break;
        }
        if (!ok) {
            rc = rd_error_set(s->err, RD_ENOCONV, "",
                              "The contact solve did not converge: Newton's method stalled in "
                              "outer iteration %d of the contact multipliers after %d "
                              "iterations.",
                              st->outer_iterations, st->iterations);
            break;
        }
        st->outer_change = change;
        if (change <= UZAWA_TOL && measured)
            break;
    }
    if (rc == RD_OK && loose) { /* stopped at the limit after a loose solve */
        int ok = rd_static_resolve(pb, s, 0, 0, 0.0, res);
        if (ok <= 0)
            rc = ok < 0 ? ok
                        : rd_error_set(s->err, RD_ENOCONV, "",
                                       "The contact solve did not converge: Newton's method "
                                       "stalled after the last update of the contact "
                                       "multipliers (%d iterations).",
                                       st->iterations);
    }
    free(x);
    rd_anderson_free(&acc);
    return rc;
}
