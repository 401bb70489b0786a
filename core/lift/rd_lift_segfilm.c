/*
 * rd_lift_segfilm.c — a distorted bore's films as the force elements read
 * them (rd_lift_internal.h, rd_lift_films_at): each film at t, and each
 * segment's film: the films of the arc it covers weighted by overlap, each
 * of those its own film or the interpolation between the films'.  Its
 * own file: the films are solved by rd_lift_film.c, which reads the gas
 * tables of rd_lift_forces.c, which reads these.
 */
#include <math.h>

#include "rd_lift_internal.h"

void rd_lift_films_at(const rd_lift_films *fs, double t, int n, rd_film_point *grp,
                      rd_film_point *seg)
{
    const int N = RD_LIFT_FILMS_NODES;
    for (int g = 0; g < fs->count; g++)
        rd_film_track_at(&fs->tr[g], t, &grp[g]);
    for (int i = 0; i < n; i++) { /* segment i covers [a, b) of the m segments */
        double a = (double)i * fs->m / n, b = (double)(i + 1) * fs->m / n,
               c[RD_LIFT_FILMS_NODES] = {0.0};
        for (int j = (int)floor(a); j < (int)ceil(b) && j < fs->m; j++) {
            double w = (fmin(b, j + 1.0) - fmax(a, (double)j)) / (b - a);
            for (int g = 0; g < fs->count; g++)
                c[g] += w * fs->wt[(size_t)N * j + g];
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
