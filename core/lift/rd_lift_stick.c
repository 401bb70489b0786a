/*
 * rd_lift_stick.c — the rigid ring's sticking phase (issue 10): while the
 * ring sits on a flank and its load presses it there, its state is
 * algebraic, so no integrator steps are spent on it.
 *
 * The rigid form's state is y = (x, x'), x = (z, theta, r) (rd_lift_rigid.c)
 * with x'' = a(t, x, x').  Seated and at rest (x' = 0), x(t) is the root of
 * a(t, x, 0) = 0: the flank penalty balances the load, the twist stiffness
 * the flank moment, the bore contact the radial gas load.  Newton on it
 * uses the form's own second-order block A = da/dx (rd_lift_model.h), a
 * 3x3 system.  The quasi-static state lags the true seated motion only by
 * the penalty's settling (its natural period is ~1e-5 of a cycle), so the
 * lift differs from the integrated one by far less than the tolerances.
 *
 * The phase ends where the total axial load without the flanks, F =
 * m->fz_ext at the quasi-static state, turns away from the flank: the
 * driver's leave date (rd_lift_driver.c, header comment).  F is scanned in
 * steps of at most STICK_SCAN_DEG crank degrees (the integrator's step
 * bound, so no load feature shorter than it is missed that the integrated
 * model would have seen) and the sign change is bisected to STICK_TOL_DEG.
 * Friction makes a seated ring's state depend on its velocity (the Coulomb
 * law is set-valued at rest), so the phase is used only without friction.
 */
#include <math.h>

#include "rd_lift_model.h"
#include "rd_lift_stick.h"

#define NX             3
#define NEWTON_MAX     30
#define STICK_SCAN_DEG 1.0  /* scan step, crank degrees (header comment) */
#define STICK_TOL_DEG  1e-6 /* bisection width of the leave date, crank degrees */

/* Solves the 3x3 system P u = b (row-major P) by Gaussian elimination with
 * partial pivoting; 1 if P is singular. */
static int solve3(double *P, double *b)
{
    for (int c = 0; c < NX; c++) {
        int p = c;
        for (int i = c + 1; i < NX; i++)
            if (fabs(P[NX * i + c]) > fabs(P[NX * p + c]))
                p = i;
        if (P[NX * p + c] == 0.0)
            return 1;
        for (int j = 0; j < NX; j++) {
            double s = P[NX * c + j];
            P[NX * c + j] = P[NX * p + j];
            P[NX * p + j] = s;
        }
        double s = b[c];
        b[c] = b[p];
        b[p] = s;
        for (int i = c + 1; i < NX; i++) {
            double l = P[NX * i + c] / P[NX * c + c];
            for (int j = c; j < NX; j++)
                P[NX * i + j] -= l * P[NX * c + j];
            b[i] -= l * b[c];
        }
    }
    for (int c = NX - 1; c >= 0; c--) {
        for (int j = c + 1; j < NX; j++)
            b[c] -= P[NX * c + j] * b[j];
        b[c] /= P[NX * c + c];
    }
    return 0;
}

int rd_lift_stick_usable(const rd_lift_form *f)
{
    return f->N == 2 * NX && f->block == NX && f->blocks &&
           f->m->p->friction.model == RD_FRICTION_NONE;
}

int rd_lift_stick_solve(const rd_lift_form *f, double t, N_Vector y, N_Vector yd,
                        const double *atol)
{
    double *x = N_VGetArrayPointer(y), A[3 * NX * NX], B[NX * NX];
    const double *a = N_VGetArrayPointer(yd);
    for (int k = 0; k < NX; k++)
        x[NX + k] = 0.0;
    for (int it = 0; it < NEWTON_MAX; it++) {
        if (f->rhs(t, y, yd, f->user))
            return 1;
        f->blocks(f->user, t, x, A, B);
        double u[NX];
        for (int k = 0; k < NX; k++)
            u[k] = -a[NX + k];
        if (solve3(A + NX * NX, u))
            return 1;
        int done = 1;
        for (int k = 0; k < NX; k++) {
            x[k] += u[k];
            done &= fabs(u[k]) <= 1e-3 * atol[k]; /* well below the integration error */
        }
        if (done)
            return 0;
    }
    return 1;
}

/* F at the quasi-static state at t (left in y); NAN if Newton failed. */
static double stick_load(const rd_lift_form *f, double t, N_Vector y, N_Vector yd,
                         const double *atol)
{
    if (rd_lift_stick_solve(f, t, y, yd, atol))
        return NAN;
    f->loads(f->user, t, N_VGetArrayPointer(y));
    return f->m->fz_ext;
}

int rd_lift_stick_advance(const rd_lift_form *f, double t0, double t1, int away, N_Vector y,
                          N_Vector yd, const double *atol, double *tleave)
{
    double deg_per_s = f->m->omega * 180.0 / M_PI;
    int steps = (int)ceil((t1 - t0) * deg_per_s / STICK_SCAN_DEG);
    double ta = t0;
    for (int s = 1; s <= (steps > 1 ? steps : 1); s++) {
        double tb = s == steps ? t1 : t0 + (t1 - t0) * s / steps;
        double F = stick_load(f, tb, y, yd, atol);
        if (isnan(F))
            return -1;
        if (F * away > 0.0) { /* turned away in (ta, tb]: bisect */
            while ((tb - ta) * deg_per_s > STICK_TOL_DEG) {
                double tm = 0.5 * (ta + tb), Fm = stick_load(f, tm, y, yd, atol);
                if (isnan(Fm))
                    return -1;
                if (Fm * away > 0.0)
                    tb = tm;
                else
                    ta = tm;
            }
            if (isnan(stick_load(f, tb, y, yd, atol)))
                return -1;
            *tleave = tb; /* the load already points away: y is the start of the flight */
            return 1;
        }
        ta = tb;
    }
    return 0;
}
