/* lift_segments.h — per-segment flank changes of a lift result, and how the
 * segments of two results at different segment counts differ (for the lift
 * benchmark's distorted-bore table and test_lift_bore).  The analysis
 * reports the flank changes of the ring's mean lift only; in a distorted
 * bore (or a tilting piston) the segments land and leave at different
 * angles, and these are defined here from `lift_segments`.
 *
 * A segment's flank changes (seg_events_of), from its lift history l(deg):
 *  - a seated segment leaves where its lift has moved eps = 1e-2 c_a off the
 *    flank: the mean lift's confirmation threshold (rd_lift_driver.c).  The
 *    mean lift's leave is dated by the ring's load, which a segment does not
 *    have, and the geometric separation is ill-conditioned; the eps crossing
 *    is not (the lift rises ~2 % of c_a per degree there);
 *  - a free segment lands where it comes within ARRIVE = 5e-3 c_a of a
 *    flank, not where it touches it: in the distorted examples the segments
 *    touch, bounce back by up to 0.4 % of c_a and settle, and a first touch
 *    that comes nanometres short in one run and not in the other moved the
 *    touch by up to 0.8 deg between rtol 1e-6 and 1e-8 (n = 40), while the
 *    approach crosses ARRIVE at ~35 % of c_a per degree;
 *  - bounces that stay within eps of the flank are no flank changes (as for
 *    the mean lift).
 * Crossings are linear between samples.  Sampled every 0.02 deg (the
 * benchmark), a landing's crossing lies near the impact's kink (ARRIVE is
 * ~0.015 deg of approach), so the interpolation error is first order
 * there: every other sample (0.04 deg) moved the 160 flank changes of
 * lift_distorted at n = 40 by at most 0.0066 deg, so at 0.02 deg they are
 * within ~0.003 deg.  At the output's 1 deg, two runs whose lifts agree
 * (test_lift_bore: modal with every mode and full) still give the same
 * crossings, but not the crossings' true angles.
 *
 * Two results (compare_segments): segment j of a's n segments lies at
 * x = (j + 1/2) n_ref / n - 1/2 in units of ref's segments (the mid-angles
 * are equally spaced over the same span: for n = 20 against 40, halfway
 * between ref's segments 2j and 2j + 1).  There ref's flank changes are
 * those of its two nearest segments, their angles interpolated linearly
 * (both segments must have the same list), and compared in order with the
 * segment's.  Not the lift interpolated between the two segments: a landing
 * is an impact, and the mean of a landed segment's lift and one still
 * approaching comes within ARRIVE of the flank only when the later one is
 * within 2 ARRIVE, so it dates the landing by the later segment, not
 * between the two (on the lift_distorted example, n = 20 against 40, the
 * two choices give 0.116 and 0.108 deg).  Header-only; static functions. */
#ifndef RD_LIFT_SEGMENTS_H
#define RD_LIFT_SEGMENTS_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_lift.h"

#define SEG_MAX_EV 32 /* flank changes kept per segment */
#define SEG_EPS    1e-2
#define SEG_ARRIVE 5e-3

typedef struct seg_events {
    int n, overflow; /* overflow: more than SEG_MAX_EV */
    double deg[SEG_MAX_EV];
    int kind[SEG_MAX_EV]; /* enum rd_lift_event_kind */
} seg_events;

/* Crossing of level `lv` between samples k-1 and k. */
static double seg_crossing(const double *deg, const double *l, int k, double lv)
{
    return deg[k - 1] + (lv - l[k - 1]) / (l[k] - l[k - 1]) * (deg[k] - deg[k - 1]);
}

static void seg_push(seg_events *e, double deg, int kind)
{
    if (e->n == SEG_MAX_EV) {
        e->overflow = 1;
        return;
    }
    e->deg[e->n] = deg;
    e->kind[e->n++] = kind;
}

/* The flank changes of one lift history l (m, `samples` values at deg) in a
 * groove of axial clearance ca (file comment). */
static void seg_events_of(const double *deg, const double *l, int samples, double ca, seg_events *e)
{
    double eps = SEG_EPS * ca, arrive = SEG_ARRIVE * ca;
    int state = l[0] > ca - eps ? RD_FLANK_UPPER : l[0] < eps ? RD_FLANK_LOWER : RD_FLANK_FREE;
    e->n = e->overflow = 0;
    for (int k = 1; k < samples; k++) {
        if (state == RD_FLANK_LOWER && l[k] >= eps) {
            seg_push(e, seg_crossing(deg, l, k, eps), RD_EVENT_LEAVE_LOWER);
            state = RD_FLANK_FREE;
        } else if (state == RD_FLANK_UPPER && l[k] <= ca - eps) {
            seg_push(e, seg_crossing(deg, l, k, ca - eps), RD_EVENT_LEAVE_UPPER);
            state = RD_FLANK_FREE;
        } else if (state == RD_FLANK_FREE && l[k] <= arrive) {
            seg_push(e, seg_crossing(deg, l, k, arrive), RD_EVENT_REACH_LOWER);
            state = RD_FLANK_LOWER;
        } else if (state == RD_FLANK_FREE && l[k] >= ca - arrive) {
            seg_push(e, seg_crossing(deg, l, k, ca - arrive), RD_EVENT_REACH_UPPER);
            state = RD_FLANK_UPPER;
        }
    }
}

/* The flank changes of r's segment i (h: scratch of r->samples values). */
static void seg_events_at(const rd_lift_result *r, int i, double ca, double *h, seg_events *e)
{
    for (int k = 0; k < r->samples; k++)
        h[k] = r->lift_segments[(size_t)k * r->segments + i];
    seg_events_of(r->crank_deg, h, r->samples, ca, e);
}

/* The flank changes of r at ring position x, in units of r's segments
 * (segment i's mid-angle at x = i): the two nearest segments' angles,
 * interpolated linearly; 0 if their lists differ (or overflow). */
static int seg_events_between(const rd_lift_result *r, double x, double ca, double *h,
                              seg_events *e)
{
    int n = r->segments, i = (int)floor(x);
    i = i < 0 ? 0 : i > n - 2 ? n - 2 : i;
    double w = fmin(fmax(x - i, 0.0), 1.0);
    seg_events e1;
    seg_events_at(r, w < 1.0 ? i : i + 1, ca, h, e);
    if (w == 0.0 || w == 1.0) /* on a segment's mid-angle */
        return !e->overflow;
    seg_events_at(r, i + 1, ca, h, &e1);
    if (e->overflow || e1.overflow || e->n != e1.n)
        return 0;
    for (int k = 0; k < e->n; k++) {
        if (e->kind[k] != e1.kind[k])
            return 0;
        e->deg[k] = (1.0 - w) * e->deg[k] + w * e1.deg[k];
    }
    return 1;
}

typedef struct seg_cmp {
    double max_deg;     /* largest change of a matched flank change */
    int events, differ; /* a's per-segment flank changes; segments whose lists differ */
    int worst_seg, worst_kind;
} seg_cmp;

/* How a's segments differ from ref's at the same positions (file comment);
 * 0, or 1 when out of memory.  ref needs at least 2 segments. */
static int compare_segments(const rd_lift_result *a, const rd_lift_result *ref, double ca,
                            seg_cmp *c)
{
    int m = a->samples > ref->samples ? a->samples : ref->samples;
    double *h = malloc((size_t)m * sizeof *h);
    if (!h)
        return 1;
    memset(c, 0, sizeof *c);
    c->worst_seg = -1;
    for (int j = 0; j < a->segments; j++) {
        seg_events ea, er;
        seg_events_at(a, j, ca, h, &ea);
        double x = (j + 0.5) * ref->segments / a->segments - 0.5;
        int same = seg_events_between(ref, x, ca, h, &er) && !ea.overflow && ea.n == er.n;
        c->events += ea.n;
        for (int i = 0; same && i < ea.n; i++)
            same = ea.kind[i] == er.kind[i];
        if (!same) {
            c->differ++;
            continue;
        }
        for (int i = 0; i < ea.n; i++)
            if (fabs(ea.deg[i] - er.deg[i]) > c->max_deg) {
                c->max_deg = fabs(ea.deg[i] - er.deg[i]);
                c->worst_seg = j;
                c->worst_kind = ea.kind[i];
            }
    }
    free(h);
    return 0;
}

#endif
