/*
 * rd_anderson — Anderson acceleration of a fixed-point iteration x <- G(x)
 * (Walker & Ni, SIAM J. Numer. Anal. 49 (2011), "Anderson acceleration for
 * fixed-point iterations", type II): from the last `depth` differences of
 * the residuals f = G(x) - x and of the images G(x), the next iterate is
 *   x+ = G(x) - dG gamma,  gamma = argmin || f - dF gamma ||_2,
 * which for a linear contraction G(x) = M x + c is GMRES on (I - M) x = c
 * (the plain iteration's error shrinks by the spectral radius of M a step;
 * the mixed one by the polynomial that best damps M's spectrum).
 *
 * Used by the contact solve's multiplier (Uzawa) iteration
 * (rd_contact_uzawa.c), whose plain update converges linearly at a rate that
 * approaches 1 as the segments shorten (the ring's stiffness at the
 * segment's length outgrows the contact law's): 0.95-0.96 a step at n =
 * 640-1280 on bench_static's battery, 24 to more than 30 updates.
 */
#ifndef RD_ANDERSON_H
#define RD_ANDERSON_H

#define RD_ANDERSON_DEPTH_MAX 8

typedef struct rd_anderson {
    int n, depth;
    int m;    /* differences held (<= depth) */
    int head; /* the next column to overwrite */
    int have_prev;
    double *dF, *dG;         /* depth columns of n each */
    double *f_prev, *g_prev; /* the last residual and image, n each */
} rd_anderson;

/* Vectors of n, up to depth (1..RD_ANDERSON_DEPTH_MAX) differences.
 * Returns 0, or -1 out of memory (then rd_anderson_free is still safe). */
int rd_anderson_init(rd_anderson *a, int n, int depth);
void rd_anderson_free(rd_anderson *a);

/* Forgets the history (the next mix returns g unchanged). */
void rd_anderson_reset(rd_anderson *a);

/* x the iterate G was evaluated at, g = G(x) on entry; on return g holds
 * the next iterate (G(x) itself on the first call after init or reset, or
 * when the differences are degenerate).  The caller projects it onto any
 * constraint (the multipliers: >= 0). */
void rd_anderson_mix(rd_anderson *a, const double *x, double *g);

#endif
