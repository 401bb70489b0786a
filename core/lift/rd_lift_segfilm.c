/*
 * rd_lift_segfilm.c — a distorted bore's films as the force elements read
 * them (rd_lift_internal.h, rd_lift_films_at): each film at t, and each
 * segment's film: the films of the arc it covers weighted by overlap, each
 * of those its own film or the interpolation between the films' — along a
 * bore map at the segment's load at the ring's depth at t.  Its own file:
 * the films are solved by rd_lift_film.c, which reads the gas tables of
 * rd_lift_forces.c, which reads these.
 */
#include <math.h>
#include <string.h>

#include "rd_lift_internal.h"

double rd_lift_films_coord(double load, double scale)
{
    return log(fmax(load, 0.0) + 0.1 * scale);
}

void rd_lift_films_cheb(const double *xs, int K, double x, double *w)
{
    double sum = 0.0;
    for (int k = 0; k < K; k++)
        if (x == xs[k]) {
            for (int j = 0; j < K; j++)
                w[j] = j == k;
            return;
        }
    for (int k = 0; k < K; k++) {
        w[k] = ((k % 2) ? -1.0 : 1.0) * ((k == 0 || k == K - 1) ? 0.5 : 1.0) / (x - xs[k]);
        sum += w[k];
    }
    for (int k = 0; k < K; k++)
        w[k] /= sum;
}

/* Segment j's weights at depth z: its row of wt, or where they vary (at
 * most RD_LIFT_FILMS_NODES films) the interpolation's at its load there
 * into w. */
static const double *weights_at_depth(const rd_lift_films *fs, double z, int j, double *w)
{
    if (!fs->varying)
        return fs->wt + (size_t)fs->cap * j;
    double load = rd_lift_depth_interp(fs->z, fs->seg_load + (size_t)fs->depths * j, fs->depths, z);
    rd_lift_films_cheb(fs->xs, fs->count, rd_lift_films_coord(load, fs->scale), w);
    return w;
}

void rd_lift_films_weights(const rd_lift_films *fs, double t, int j, double *w)
{
    const double *r = weights_at_depth(fs, fs->varying ? rd_lift_depth_at(fs->p, t) : 0.0, j, w);
    if (r != w)
        memcpy(w, r, (size_t)fs->count * sizeof *w);
}

double rd_lift_films_share(const rd_lift_films *fs, double t, int g)
{
    if (!fs->varying)
        return fs->share[g];
    double z = rd_lift_depth_at(fs->p, t), w[RD_LIFT_FILMS_NODES], s = 0.0;
    for (int j = 0; j < fs->m; j++)
        s += weights_at_depth(fs, z, j, w)[g];
    return s / fs->m;
}

void rd_lift_films_at(const rd_lift_films *fs, double t, int n, rd_film_point *grp,
                      rd_film_point *seg)
{
    for (int g = 0; g < fs->count; g++)
        rd_film_track_at(&fs->tr[g], t, &grp[g]);
    double z = fs->varying ? rd_lift_depth_at(fs->p, t) : 0.0, w[RD_LIFT_FILMS_NODES];
    for (int i = 0; i < n; i++) { /* segment i covers [a, b) of the m segments */
        double a = (double)i * fs->m / n, b = (double)(i + 1) * fs->m / n, *c = fs->acc;
        memset(c, 0, (size_t)fs->count * sizeof *c);
        for (int j = (int)floor(a); j < (int)ceil(b) && j < fs->m; j++) {
            double o = (fmin(b, j + 1.0) - fmax(a, (double)j)) / (b - a);
            const double *r = weights_at_depth(fs, z, j, w);
            for (int g = 0; g < fs->count; g++)
                c[g] += o * r[g];
        }
        rd_film_point *s = &seg[i];
        *s = (rd_film_point){.t = grp[0].t, .U = grp[0].U};
        for (int g = 0; g < fs->count; g++) {
            s->h0 += c[g] * grp[g].h0;
            s->W += c[g] * grp[g].W;
            s->Wa += c[g] * grp[g].Wa;
            s->Cc += c[g] * grp[g].Cc;
            s->Fp += c[g] * grp[g].Fp;
            s->cavitated += c[g] * grp[g].cavitated;
        }
    }
}
