/*
 * rd_ringpack_record.c — the ring pack's output (rd_ringpack_model.h,
 * rd_ringpack_rec): the samples of the cycle being run, its mass balance
 * and its change against the cycle before, and where the run ends (a
 * fixed number of cycles, or the first periodic one).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rd_ringpack_model.h"

static double stored_mass(const rd_ringpack_model *m, const double *y)
{
    double s = 0.0;
    for (int v = 1; v <= m->V; v++)
        s += RP_P(m, y, v - 1) * m->vol[v] / (m->law.R * m->temp[v]);
    return s;
}

/* A lift ring's sample: mean lift, its flank as the lift analysis reports
 * it (lower below eps, upper above c_a - eps), friction. */
static void record_lift(const rd_ringpack_model *m, int i, double t, const double *y,
                        const double *pv, double *lift, int *flank, double *friction)
{
    rd_packring *L = m->lr[i];
    double f[3], up, lo, fz, eps = rd_packring_eps(L);
    rd_ringpack_faces(m, i, t, pv, f);
    rd_packring_gas(L, f);
    *lift = rd_packring_areas(L, y + m->off[i], &up, &lo);
    rd_packring_loads(L, t, y + m->off[i], &fz, friction);
    *flank =
        *lift < eps ? RD_FLANK_LOWER : (*lift > m->ca[i] - eps ? RD_FLANK_UPPER : RD_FLANK_FREE);
}

/* Balance of the recorded cycle and its change against the one before. */
static void balance(rd_ringpack_rec *d, const rd_ringpack_model *m)
{
    rd_ringpack_result *r = d->res;
    const double *a = d->cum[1], *b = d->cum[2], *o = d->cum[0];
    int S = d->S, nv = m->V + 2;
    r->inflow_kg = b[0] - a[0];
    r->reverse_kg = b[1] - a[1];
    r->blowby_kg = (b[2] - a[2]) - (b[3] - a[3]);
    r->stored_change_kg = d->stored[2] - d->stored[1];
    double thru = fmax(r->inflow_kg + r->reverse_kg, 1e-300);
    r->mass_residual =
        fabs(r->inflow_kg - r->reverse_kg - r->blowby_kg - r->stored_change_kg) / thru;
    r->blowby_l_per_min = r->blowby_kg * (m->p->engine.speed_rpm / 2.0) /
                          rd_ringpack_standard_density(m->law.R) * 1000.0;
    double before = (a[2] - o[2]) - (a[3] - o[3]), change = 0.0;
    change = fabs(r->blowby_kg - before) / fmax(fabs(r->blowby_kg), 1e-300);
    for (int v = 1; v < nv - 1; v++) {
        double top = 0.0, diff = 0.0;
        for (int k = 0; k <= S; k++) {
            double p = r->pressure[(size_t)v * (S + 1) + k];
            top = fmax(top, p);
            diff = fmax(diff, fabs(p - d->prev[(size_t)v * (S + 1) + k]));
        }
        change = fmax(change, diff / top);
    }
    r->periodicity = change;
}

void rd_ringpack_record(rd_ringpack_rec *d, const rd_ringpack_model *m, const int *flank, int k,
                        double t, const double *y)
{
    rd_ringpack_result *r = d->res;
    double pv[RD_RINGPACK_VOLUMES_MAX], mdot[RD_RINGPACK_FLOWS_MAX];
    int S = d->S, nv = m->V + 2;
    rd_ringpack_pressures(m, t, y, pv);
    if (k == 0 || k == S) { /* the cycle's start (the run's) and end */
        memcpy(d->cum[k ? 2 : 1], &RP_CUM(m, y, 0), 4 * sizeof(double));
        d->stored[k ? 2 : 1] = stored_mass(m, y);
    }
    double area[2 * RD_RINGPACK_RINGS_MAX];
    rd_ringpack_areas(m, y, area);
    rd_ringpack_flows(m, pv, area, mdot);
    r->crank_deg[k] = 720.0 * k / S;
    for (int v = 0; v < nv; v++)
        r->pressure[(size_t)v * (S + 1) + k] = pv[v];
    for (int i = 0; i < m->R; i++) {
        size_t at = (size_t)i * (S + 1) + k;
        if (m->lr[i]) {
            record_lift(m, i, t, y, pv, &r->lift[at], &r->flank[at], &r->friction[at]);
            continue;
        }
        r->lift[at] = RP_Z(m, y, i);
        r->flank[at] = flank[i];
        r->friction[at] = rd_ringpack_friction(m, i, t, y, pv);
    }
    for (int f = 0; f < m->F; f++)
        r->flow[(size_t)f * (S + 1) + k] = mdot[f];
}

/* Column S of a rows x (S + 1) array into column 0. */
static void end_to_start(double *a, int rows, int S)
{
    for (int v = 0; v < rows; v++)
        a[(size_t)v * (S + 1)] = a[(size_t)v * (S + 1) + S];
}

void rd_ringpack_cycle_end(rd_ringpack_rec *d, const rd_ringpack_model *m)
{
    rd_ringpack_result *r = d->res;
    const rd_ringpack_params *p = m->p;
    int S = d->S, nv = m->V + 2;
    if (d->cyc >= 1)
        balance(d, m);
    int settled = d->cyc >= 1 && p->periodic && r->periodicity < p->periodic_tolerance;
    if (settled || d->cyc + 1 == d->C) {
        d->done = 1;
        r->cycles = d->cyc + 1;
        r->settled = settled;
        return;
    }
    memcpy(d->prev, r->pressure, (size_t)nv * (S + 1) * sizeof *d->prev);
    memcpy(d->cum[0], d->cum[1], sizeof d->cum[0]);
    memcpy(d->cum[1], d->cum[2], sizeof d->cum[1]);
    d->stored[0] = d->stored[1];
    d->stored[1] = d->stored[2];
    end_to_start(r->pressure, nv, S);
    end_to_start(r->lift, m->R, S);
    end_to_start(r->friction, m->R, S);
    end_to_start(r->flow, m->F, S);
    for (int i = 0; i < m->R; i++) {
        r->flank[(size_t)i * (S + 1)] = r->flank[(size_t)i * (S + 1) + S];
        r->n_events[i] = 0;
    }
    d->cyc++;
}

int rd_ringpack_record_open(rd_ringpack_rec *d, const rd_ringpack_model *m, rd_ringpack_result *r,
                            rd_error *err)
{
    size_t n = (size_t)d->S + 1;
    int nv = m->V + 2;
    d->res = r;
    r->samples = d->S + 1;
    r->cycles = d->C;
    r->crank_deg = malloc(n * sizeof *r->crank_deg);
    r->pressure = malloc(n * nv * sizeof *r->pressure);
    r->lift = malloc(n * m->R * sizeof *r->lift);
    r->flank = malloc(n * m->R * sizeof *r->flank);
    r->friction = malloc(n * m->R * sizeof *r->friction);
    r->flow = malloc(n * m->F * sizeof *r->flow);
    d->prev = malloc(n * nv * sizeof *d->prev);
    if (!r->crank_deg || !r->pressure || !r->lift || !r->flank || !r->friction || !r->flow ||
        !d->prev)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory for the ring pack's output.");
    rd_ringpack_describe(m, r);
    return RD_OK;
}
