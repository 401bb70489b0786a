/*
 * rd_film_track.c — the film over a run: the face's radial balance,
 * variable-step BDF2 in time (rd_film_track.h).
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
    double last_h; /* where o was solved */
    double slope;  /* dR/dh of the last root's final secant (< 0), 0 = none */
    long solves;
} step_ctx;

static double residual(step_ctx *s, double h)
{
    rd_film_solve(s->f, h, (s->c1 * h - s->hist) / s->dt, s->U, s->eta, s->p_lo, s->p_hi, &s->o);
    s->solves++;
    s->last_h = h;
    return s->o.W + s->o.Wa - s->W_ext;
}

#define H_LOW (-3.9) /* the lowest film, sigmas: the asperity table's end */

/* The root of the falling residual from the guess h: secant steps, kept
 * inside the bracket once one is known (bisection when they leave it),
 * grown towards the root before.  RD_FILM_H_MAX when
 * the residual stays positive there (*held = 1). */
static double balance(step_ctx *s, double h, int *held)
{
    double sg = s->f->sigma, lo = -INFINITY, hi = INFINITY;
    double tol = 1e-6 * fmax(fabs(h), sg), scale = 1e-12 * fmax(s->W_ext, 1e-300);
    double x0 = fmin(fmax(h, H_LOW * sg), RD_FILM_H_MAX), r0 = residual(s, x0);
    *held = 0;
    if (r0 > 0.0)
        lo = x0;
    else
        hi = x0;
    /* the first step: Newton with the last root's slope, else a small probe */
    double probe = 1e-5 * fabs(x0) + 1e-5 * sg, x1 = x0 + (r0 > 0.0 ? probe : -probe);
    if (s->slope < 0.0) {
        double d = -r0 / s->slope, lim = 0.5 * fabs(x0) + sg;
        x1 = x0 + fmax(-lim, fmin(lim, d));
        if (fabs(x1 - x0) < probe)
            x1 = x0 + (r0 > 0.0 ? probe : -probe);
    }
    x1 = fmin(fmax(x1, H_LOW * sg), RD_FILM_H_MAX);
    double r1 = residual(s, x1);
    for (int it = 0; it < 200; it++) {
        if (r1 > 0.0)
            lo = fmax(lo, x1);
        else
            hi = fmin(hi, x1);
        if (fabs(r1) <= scale)
            return x1;
        if (r1 > 0.0 && x1 >= RD_FILM_H_MAX) {
            *held = 1;
            return x1;
        }
        if (r1 < 0.0 && x1 <= H_LOW * sg)
            return x1;
        double x = x1 - r1 * (x1 - x0) / (r1 - r0);
        if (fabs(x - x1) < tol) /* x1 is within tol of the root */
            return x1;
        int bracket = isfinite(lo) && isfinite(hi);
        if (bracket && !(x > lo && x < hi))
            x = 0.5 * (lo + hi);
        else if (!bracket) { /* grow towards the root, at most 4x the last step */
            double d = x1 - x0, lim = 4.0 * fabs(d) + 1e-3 * sg;
            if (!isfinite(x) || (r1 > 0.0) != (x > x1) || fabs(x - x1) > lim)
                x = x1 + (r1 > 0.0 ? lim : -lim);
            x = fmin(fmax(x, H_LOW * sg), RD_FILM_H_MAX);
        }
        if (bracket && hi - lo < tol)
            return s->last_h == x1 ? x1 : x;
        x0 = x1, r0 = r1;
        x1 = x;
        r1 = residual(s, x1);
        if (r1 != r0 && x1 != x0)
            s->slope = fmin((r1 - r0) / (x1 - x0), 0.0);
        if (fabs(x1 - x0) < tol)
            return x1;
    }
    return x1;
}

/* The point at t from the balance's last solve at h (solved again when the
 * root was not its last evaluation). */
static void record(rd_film_point *pt, step_ctx *s, double h, double t)
{
    if (s->last_h != h)
        residual(s, h);
    pt->t = t;
    pt->h0 = h;
    pt->W = s->o.W;
    pt->Wa = s->o.Wa;
    pt->Cc = s->o.Cc;
    pt->Fp = s->o.Fp;
    pt->U = s->U;
    pt->cavitated = s->o.cavitated;
}

static int append(rd_film_track *tr, step_ctx *s, double h, double t, rd_error *err)
{
    int n = tr->pt ? tr->steps + 1 : 0; /* points so far */
    if (n + 1 > tr->cap) {
        int cap = tr->cap ? 2 * tr->cap : 1024;
        rd_film_point *p = realloc(tr->pt, (size_t)cap * sizeof *p);
        if (!p)
            return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the film's %d steps).", cap);
        tr->pt = p;
        tr->cap = cap;
    }
    record(&tr->pt[n], s, h, t);
    tr->steps = n;
    return RD_OK;
}

/* The next step's end from t: at most h, not past the next multiple of
 * `period` nor t_end (landing on them). */
static double next_end(double t, double h, double period, double t_end)
{
    double b = period * (floor(t / period * (1.0 + 1e-12) + 1e-9) + 1.0);
    double e = fmin(t + h, fmin(b, t_end));
    if (fmin(b, t_end) - e < 0.05 * h)
        e = fmin(b, t_end);
    return e;
}

/* BDF2 for the step to te = ts[0] + hn (backward Euler with one point);
 * with cavitation "jfo" the same for the film's content at the nodes
 * (content[0] the last accepted step's, content[1] the one before). */
static void history(step_ctx *s, const double *y, const double *ts, int have, double hn,
                    double *guess, double *const content[2])
{
    s->dt = hn;
    double a0 = 1.0, a1 = 0.0;
    if (have > 1) {
        double w = hn / (ts[0] - ts[1]);
        s->c1 = (1.0 + 2.0 * w) / (1.0 + w);
        a0 = 1.0 + w;
        a1 = -w * w / (1.0 + w);
        *guess = y[0] + w * (y[0] - y[1]);
    } else {
        s->c1 = 1.0;
        *guess = y[0];
    }
    s->hist = a0 * y[0] + a1 * y[1];
    rd_film *f = s->f;
    if (!f->jfo)
        return;
    f->c1_dt = s->c1 / hn;
    for (int i = 0; i < f->n; i++)
        f->hist_dt[i] = (a0 * content[0][i] + a1 * content[1][i]) / hn;
}

/* The film's content at the accepted h into content[0] (the one before
 * into content[1]). */
static void accept_content(step_ctx *s, double h, double *const content[2])
{
    rd_film *f = s->f;
    if (!f->jfo)
        return;
    if (s->last_h != h)
        residual(s, h);
    for (int i = 0; i < f->n; i++) {
        content[1][i] = content[0][i];
        content[0][i] = f->content[i];
    }
}

/* The local error of the step to te: the corrector against the quadratic
 * through the last three points (BDF2's error constant 2/9: 2/11 of the
 * difference); 0 with fewer points. */
static double local_error(const double *y, const double *ts, int have, double te, double yn)
{
    if (have < 3)
        return 0.0;
    double a = ts[0], b = ts[1], c = ts[2];
    double pred = y[0] * (te - b) * (te - c) / ((a - b) * (a - c)) +
                  y[1] * (te - a) * (te - c) / ((b - a) * (b - c)) +
                  y[2] * (te - a) * (te - b) / ((c - a) * (c - b));
    return (2.0 / 11.0) * fabs(yn - pred);
}

/* The steps from ts[0] = -t_warm (y[0] the film there) to t_end. */
static int track(step_ctx *s_, const rd_film_loads *ld, double t_end, double dt_max, double period,
                 double t_warm, double *y, double *ts, double *const content[2], rd_film_track *tr,
                 rd_error *err)
{
    step_ctx s = *s_;
    rd_film *f = s.f;
    double t = ts[0], sg = f->sigma;
    int have = 1, held = 0, rc;
    if (t_warm <= 0.0 && (rc = append(tr, &s, y[0], 0.0, err))) /* its loads at rest */
        return rc;
    double h = fmin(dt_max, 1e-4 * period);
    /* the warm-up only brings the film near its orbit: a looser error, longer steps */
    while (t < t_end - 1e-12 * period) {
        double te = next_end(t, h, period, t_end), hn = te - t, guess;
        ld->at(ld->ctx, te, &s.U, &s.eta, &s.W_ext, &s.p_lo, &s.p_hi);
        history(&s, y, ts, have, hn, &guess, content);
        double yn = balance(&s, guess, &held), est = local_error(y, ts, have, te, yn);
        int loose = t < -0.25 * period; /* the warm-up but its last quarter period */
        double tol = (loose ? fmax(RD_FILM_WARM_RTOL, f->rtol) : f->rtol) * fabs(yn) + 1e-3 * sg;
        if (est > tol && hn > 1e-9 * period) { /* rejected: a smaller step */
            h = hn * fmax(0.2, 0.9 * cbrt(tol / est));
            continue;
        }
        y[2] = y[1], ts[2] = ts[1];
        y[1] = y[0], ts[1] = ts[0];
        y[0] = yn, ts[0] = te;
        accept_content(&s, yn, content);
        have = have < 3 ? have + 1 : 3;
        t = te;
        if (t >= -1e-9 * period) {
            if ((rc = append(tr, &s, yn, fmax(t, 0.0), err)))
                return rc;
            tr->held += held;
        }
        h = est > 0.0 ? hn * fmin(2.0, fmax(0.2, 0.9 * cbrt(tol / est))) : 2.0 * hn;
        h = fmin(h, te < -0.25 * period ? RD_FILM_WARM_STEPS * dt_max : dt_max);
    }
    tr->solves = s.solves;
    if (tr->steps > 0 &&
        t_end >= period * (1.0 - 1e-9)) { /* the last period against the one before */
        rd_film_point a;
        rd_film_track_at(tr, t_end - period, &a);
        tr->periodic_change =
            fabs(tr->pt[tr->steps].h0 - a.h0) / fmax(fabs(tr->pt[tr->steps].h0), sg);
    }
    return RD_OK;
}

int rd_film_track_run(rd_film *f, const rd_film_loads *ld, double t_end, double dt_max,
                      double period, double t_warm, double h_start, rd_film_track *tr,
                      rd_error *err)
{
    memset(tr, 0, sizeof *tr);
    step_ctx s = {.f = f, .dt = 1.0};
    double t = -t_warm, y[3] = {0}, ts[3] = {0};
    int held, rc;
    double *content[2] = {NULL, NULL};
    if (f->jfo) { /* the film alone at the start (c1_dt 0: its steady content) */
        f->c1_dt = 0.0;
        content[0] = calloc((size_t)(2 * f->n), sizeof(double));
        if (!content[0])
            return rd_error_set(err, RD_ENOMEM, NULL, "out of memory (the film's content).");
        content[1] = content[0] + f->n;
    }
    ld->at(ld->ctx, t, &s.U, &s.eta, &s.W_ext, &s.p_lo, &s.p_hi);
    y[0] = isnan(h_start) ? balance(&s, 3.0 * f->sigma, &held) : h_start;
    ts[0] = t;
    accept_content(&s, y[0], content);
    rc = track(&s, ld, t_end, dt_max, period, t_warm, y, ts, content, tr, err);
    free(content[0]);
    f->c1_dt = 0.0;
    return rc;
}

void rd_film_track_at(const rd_film_track *tr, double t, rd_film_point *out)
{
    int a = 0, b = tr->steps;
    if (b == 0 || t <= tr->pt[0].t) {
        *out = tr->pt[0];
        return;
    }
    if (t >= tr->pt[b].t) {
        *out = tr->pt[b];
        return;
    }
    while (b - a > 1) { /* pt[a].t <= t < pt[b].t */
        int m = (a + b) / 2;
        if (tr->pt[m].t <= t)
            a = m;
        else
            b = m;
    }
    const rd_film_point *p = &tr->pt[a], *q = &tr->pt[b];
    double w = (t - p->t) / (q->t - p->t);
    out->t = t;
    out->h0 = p->h0 + w * (q->h0 - p->h0);
    out->W = p->W + w * (q->W - p->W);
    out->Wa = p->Wa + w * (q->Wa - p->Wa);
    out->Cc = p->Cc + w * (q->Cc - p->Cc);
    out->Fp = p->Fp + w * (q->Fp - p->Fp);
    out->U = p->U + w * (q->U - p->U);
    out->cavitated = p->cavitated + w * (q->cavitated - p->cavitated);
}

void rd_film_track_free(rd_film_track *tr)
{
    free(tr->pt);
    memset(tr, 0, sizeof *tr);
}
