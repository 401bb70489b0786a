/*
 * rd_modal — free-free natural frequencies of the discretized ring
 * (thesis 3.3, eqs. 3.20-3.27): K phi = omega^2 M phi.
 *
 * Solved by shift-invert Lanczos on banded matrices (LAPACK banded
 * Cholesky), the in-plane and out-of-plane problems separately where they
 * decouple (every flat ring), so cost grows linearly with the segment count.
 * A closed ring is renumbered so its matrices stay banded.
 *
 * The six rigid-body modes are deflated explicitly and counted with any
 * further eigenvalue indistinguishable from zero; the requested elastic
 * modes are returned ascending, each classified in-plane / out-of-plane
 * from its kinetic-energy split.
 *
 * Error estimate: a second solve at a reference segment count m (2n, or n/2
 * when 2n exceeds RD_SEGMENTS_MAX) and the model's convergence order 2
 * (f_n = f_inf (1 + C n^-2)) give per mode the Richardson-extrapolated
 * frequency and the estimated relative error of f_n against n -> infinity.
 */
#ifndef RD_MODAL_H
#define RD_MODAL_H

#include "rd_error.h"
#include "rd_ring.h"

#define RD_MODAL_MODES_MAX 60

enum rd_mode_kind { RD_MODE_IN_PLANE = 0, RD_MODE_OUT_OF_PLANE = 1 };

typedef struct rd_modal_opts {
    int modes;          /* elastic modes wanted, 1..RD_MODAL_MODES_MAX */
    int estimate_error; /* 1: second solve for the error estimate */
    double tol;         /* relative residual tolerance on top of its rounding floor, default
                         * 1e-12 (the eigenvalue error is of the order of its square) */
    int max_iterations; /* Lanczos steps allowed per sub-problem, default 300 (at most
                         * 600 are taken: the basis is kept whole, memory ~ 600 x DOF) */
    int coupled;        /* 1: solve the 6n problem whole even where in-plane and
                         * out-of-plane decouple (a second path for the tests); default 0 */
} rd_modal_opts;

typedef struct rd_mode {
    double frequency_hz;
    int kind;                         /* enum rd_mode_kind */
    double in_plane_fraction;         /* share of kinetic energy in in-plane DOFs */
    double residual;                  /* ||K phi - w^2 M phi|| / (w^2 ||M phi||) */
    double error_estimate;            /* relative, vs n -> infinity; NAN if not estimated */
    double frequency_extrapolated_hz; /* Richardson estimate of the limit; NAN if none */
    /* Shape per segment in the segment's local cylindrical frame, normalized so
     * the largest translation is 1 (sign: the first translation, in segment
     * order, whose size is within 1e-6 of the largest, is positive):
     * shape[6i + 0..2] = radial, tangential, axial translation (-),
     * shape[6i + 3..5] = rotation about radial, tangential, axial axes (1/m). */
    double *shape;
} rd_mode;

typedef struct rd_modal_result {
    int segments, dof;
    int rigid_body_modes; /* eigenvalues found at zero (6 for a free ring) */
    int n_modes;
    rd_mode *modes;         /* n_modes elastic modes, ascending */
    int iterations;         /* Lanczos steps of the main solve (sum over its parts) */
    int block_size;         /* Lanczos block size: 2 for a closed ring, else 1 */
    double max_residual;    /* largest mode residual */
    int reference_segments; /* m of the error-estimate solve; 0 if none */
    double error_estimate;  /* largest per-mode estimate; NAN if none */
    double factor_s;        /* wall time of the factorizations, s */
} rd_modal_result;

void rd_modal_opts_default(rd_modal_opts *o);
/* Checks opts against the ring (paths relative to the modal block: "/modes"). */
int rd_modal_validate(const rd_modal_opts *o, int segments, rd_error *err);

/* The ring's slenderness at n segments, n R / min(b, h) x sqrt(max(1, G / E)):
 * the eigen-solve's condition number (stiffest spring over softest mode)
 * grows as its square, and so does the rounding error of the low modes.
 * rd_modal_validate_ring refuses a ring above RD_MODAL_SLENDERNESS_MAX when
 * the error estimate is wanted (it needs the difference of two solves to
 * well below the discretization error) and above
 * RD_MODAL_SLENDERNESS_MAX_FREQ without it (frequencies to about 1e-3);
 * paths relative to the scene's root: "/discretization/segments", or "/ring"
 * when even 3 segments are too many. */
#define RD_MODAL_SLENDERNESS_MAX      3e5
#define RD_MODAL_SLENDERNESS_MAX_FREQ 3e6
double rd_modal_slenderness(const rd_ring_params *p, int segments);
int rd_modal_validate_ring(const rd_ring_params *p, int segments, int estimate_error,
                           rd_error *err);

/* Solves; `out` is overwritten and owns its arrays (free with
 * rd_modal_result_cleanup, also after a failure). */
int rd_modal_solve(const rd_ring_params *p, int segments, int closed, const rd_modal_opts *o,
                   const rd_monitor *mon, rd_modal_result *out, rd_error *err);

/* The eigen-solve alone on a built ring, without the error estimate. */
int rd_modal_solve_ring(const rd_ring *ring, const rd_modal_opts *o, const rd_monitor *mon,
                        rd_modal_result *out, rd_error *err);

void rd_modal_result_cleanup(rd_modal_result *r);

/* Predicted CPU time, s, of rd_modal_solve with these options, before any
 * work: for a caller deciding whether a job is small enough to run at once
 * (a server answering on its own thread).  A model of the solver's work
 * (Lanczos steps ~ wanted modes, band and reorthogonalisation work per step,
 * projected eigenproblems, mode extraction) whose five constants are fitted to
 * CPU-time medians of one core of the reference machine (bench_modal
 * --predict compares); within a factor 2 over n = 5..1000, modes 1..60,
 * split and closed rings, with and without the estimate.  Scale it by the
 * ratio of a measured solve on another machine.  Invalid options or sizes
 * give NAN. */
double rd_modal_cost_predict(const rd_modal_opts *o, int segments, int closed);

/* Thin-ring closed-form frequencies (Hz) of the complete ring, mode order k >= 2
 * (MODEL.md): in-plane and out-of-plane. */
double rd_modal_thin_ring_inplane_hz(const rd_ring_params *p, int k);
double rd_modal_thin_ring_outplane_hz(const rd_ring_params *p, int k);

#endif
