/*
 * rd_film_track.c — the film over a run: the face's radial balance, BDF2
 * in time (rd_film_track.h).
 */
#include "rd_film_track.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* One instant's balance: the history gives dh0/dt = (c1 h0 - hist) / dt. */
typedef struct step_ctx {
    rd_film *f;
    double U, eta, W_ext, p_lo, p_hi, c1, hist, dt;
    rd_film_out o;
    long solves;
} step_ctx;

static double residual(step_ctx *s, double h)
{
    rd_film_solve(s->f, h, (s->c1 * h - s->hist) / s->dt, s->U, s->eta, s->p_lo, s->p_hi, &s->o);
    s->solves++;
    return s->o.W + s->o.Wa - s->W_ext;
}

/* The root of the falling residual from the guess h: a bracket grown from
 * it, then secant steps kept inside the bracket (bisection when they leave
 * it or stall).  Returns the root (RD_FILM_H_MAX when the residual stays
 * positive there: *held = 1). */
static double balance(step_ctx *s, double h, int *held)
{
    double sg = s->f->sigma, lo = h, hi = h, rlo, rhi, r = residual(s, h);
    *held = 0;
    if (r > 0.0) { /* too thin: grow upwards */
        lo = h, rlo = r;
        hi = h + 0.05 * fmax(h, sg);
        while ((rhi = residual(s, hi)) > 0.0) {
            lo = hi, rlo = rhi;
            if (hi >= RD_FILM_H_MAX) {
                *held = 1;
                return RD_FILM_H_MAX;
            }
            hi = fmin(hi + 2.0 * (hi - h) + 0.05 * sg, RD_FILM_H_MAX);
        }
    } else {
        hi = h, rhi = r;
        lo = h - 0.05 * fmax(fabs(h), sg);
        while ((rlo = residual(s, lo)) < 0.0) {
            hi = lo, rhi = rlo;
            lo -= 2.0 * (h - lo) + 0.05 * sg;
        }
    }
    double tol = 1e-9 * fmax(fabs(lo), sg);
    int side = 0;
    for (int it = 0; it < 200 && hi - lo > tol; it++) {
        /* Illinois: halve the weight of an end kept twice */
        double x = (lo * rhi - hi * rlo) / (rhi - rlo);
        if (!(x > lo && x < hi))
            x = 0.5 * (lo + hi);
        double rx = residual(s, x);
        if (rx > 0.0) {
            lo = x, rlo = rx;
            if (side == -1)
                rhi *= 0.5;
            side = -1;
        } else {
            hi = x, rhi = rx;
            if (side == 1)
                rlo *= 0.5;
            side = 1;
        }
        if (fabs(rx) <= 1e-12 * s->W_ext)
            return x;
    }
    return 0.5 * (lo + hi);
}

static void record(rd_film_point *pt, const step_ctx *s, double h)
{
    residual((step_ctx *)s, h); /* the loads at the root itself */
    pt->h0 = h;
    pt->W = s->o.W;
    pt->Wa = s->o.Wa;
    pt->Cc = s->o.Cc;
    pt->Fp = s->o.Fp;
    pt->U = s->U;
    pt->cavitated = s->o.cavitated;
}

int rd_film_track_run(rd_film *f, const rd_film_loads *ld, double t_end, double dt, double t_warm,
                      double h_start, rd_film_track *tr, rd_error *err)
{
    memset(tr, 0, sizeof *tr);
    int warm = (int)ceil(t_warm / dt - 1e-9), steps = (int)ceil(t_end / dt - 1e-9);
    tr->dt = dt;
    tr->steps = steps;
    tr->pt = calloc((size_t)steps + 1, sizeof *tr->pt);
    if (!tr->pt)
        return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the film's %d steps).",
                            steps + 1);
    step_ctx s = {.f = f};
    double t = -warm * dt, h_prev = 0.0, h;
    int held;
    /* start: the steady balance at t (dh0/dt = 0: c1 = 0, hist = 0) */
    ld->at(ld->ctx, t, &s.U, &s.eta, &s.W_ext, &s.p_lo, &s.p_hi);
    s.dt = dt;
    h = h_start > 0.0 ? h_start : balance(&s, 3.0 * f->sigma, &held);
    if (warm == 0) /* t = 0 itself: its loads at rest (dh0/dt = 0) */
        record(&tr->pt[0], &s, h);
    for (int k = -warm + 1; k <= steps; k++) {
        t = k * dt;
        ld->at(ld->ctx, t, &s.U, &s.eta, &s.W_ext, &s.p_lo, &s.p_hi);
        int first = k == -warm + 1;
        s.c1 = first ? 1.0 : 1.5; /* BE: (h - h_n)/dt; BDF2: (3h - 4h_n + h_n-1)/(2 dt) */
        s.hist = first ? h : 2.0 * h - 0.5 * h_prev;
        double guess = first ? h : 2.0 * h - h_prev;
        double hn = balance(&s, guess, &held);
        tr->held += held && k >= 0;
        h_prev = h;
        h = hn;
        if (k >= 0)
            record(&tr->pt[k], &s, h);
    }
    if (warm > 0 && steps >= warm) /* the last cycle against the one before */
        tr->periodic_change = fabs(tr->pt[steps].h0 - tr->pt[steps - warm].h0) / tr->pt[steps].h0;
    tr->solves = s.solves;
    return RD_OK;
}

void rd_film_track_at(const rd_film_track *tr, double t, rd_film_point *out)
{
    double u = t / tr->dt;
    int k = (int)floor(u);
    if (k < 0)
        k = 0;
    if (k > tr->steps - 1)
        k = tr->steps - 1;
    double w = fmin(fmax(u - k, 0.0), 1.0);
    const rd_film_point *a = &tr->pt[k], *b = &tr->pt[k + 1];
    out->h0 = a->h0 + w * (b->h0 - a->h0);
    out->W = a->W + w * (b->W - a->W);
    out->Wa = a->Wa + w * (b->Wa - a->Wa);
    out->Cc = a->Cc + w * (b->Cc - a->Cc);
    out->Fp = a->Fp + w * (b->Fp - a->Fp);
    out->U = a->U + w * (b->U - a->U);
    out->cavitated = a->cavitated + w * (b->cavitated - a->cavitated);
}

void rd_film_track_free(rd_film_track *tr)
{
    free(tr->pt);
    memset(tr, 0, sizeof *tr);
}
