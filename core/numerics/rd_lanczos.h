/*
 * rd_lanczos — the lowest eigenpairs of K x = lambda M x for symmetric banded
 * K (positive semi-definite, with known null vectors) and M (positive
 * definite), by shift-invert block Lanczos with full reorthogonalisation and
 * explicit deflation of the null vectors.  Internal to core (rd_modal).
 *
 * Cost: one banded Cholesky of A = K + sigma M (O(N kd^2)), then per Lanczos
 * step one banded solve and two band mat-vecs (O(N kd)) and the
 * reorthogonalisation (O(N k) for k basis vectors), so O(N) per step for a
 * fixed number of wanted pairs.
 */
#ifndef RD_LANCZOS_H
#define RD_LANCZOS_H

#include "rd_band.h"
#include "rd_error.h"

typedef struct rd_lanczos_problem {
    const rd_band *K, *M; /* borrowed, N x N, same N */
    const double *null;   /* r candidate null vectors of K (N x r, column-major), or NULL */
    int r;
    double shift;  /* sigma > 0: A = K + sigma M is positive definite */
    double zero;   /* eigenvalues below this count as (extra) zero modes */
    int want;      /* lowest eigenpairs wanted above `zero`, 1..N - r */
    int block;     /* block size b, 1 or 2 (2: eigenvalues may come in pairs) */
    int max_steps; /* Lanczos steps (expanded basis vectors) allowed; at most 600 are
                           * taken, the basis is kept whole */
    /* A pair is converged when ||K x - lambda M x|| / (lambda ||M x||) <=
     * floor_abs / lambda + tol (its rounding floor plus the tolerance). */
    double floor_abs, tol;
    /* Progress: reports lo + (hi - lo) * fraction of this solve. */
    const rd_monitor *mon;
    double mon_lo, mon_hi;
} rd_lanczos_problem;

typedef struct rd_lanczos_result {
    int deflated;   /* candidate null vectors confirmed (||K z|| at rounding level) and deflated */
    int zeros;      /* further eigenvalues found below `zero` */
    int found;      /* = want on success */
    double *lambda; /* found eigenvalues above `zero`, ascending (owned) */
    double *x;      /* N x found eigenvectors, M-orthonormal, column-major (owned) */
    int steps;      /* Lanczos steps taken */
    double worst;   /* on failure: largest cheap residual over its floor */
} rd_lanczos_result;

/* Solves; `out` is overwritten and owns its arrays (free with
 * rd_lanczos_result_cleanup, also after a failure).  RD_ENOCONV when
 * max_steps run out, RD_ENUMERIC when LAPACK fails, RD_ENOMEM. */
int rd_lanczos_solve(const rd_lanczos_problem *pb, rd_lanczos_result *out, rd_error *err);
void rd_lanczos_result_cleanup(rd_lanczos_result *r);

#endif
