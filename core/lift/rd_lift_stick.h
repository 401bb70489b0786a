/*
 * rd_lift_stick.h — the rigid ring's sticking phase (rd_lift_stick.c): a
 * seated ring pressed onto its flank advanced without integrator steps.
 */
#ifndef RD_LIFT_STICK_H
#define RD_LIFT_STICK_H

#include <nvector/nvector_serial.h>

#include "rd_lift_model.h"

/* 1 if the form can stick: the rigid ring's 3 + 3 states, no friction. */
int rd_lift_stick_usable(const rd_lift_form *f);

/* The quasi-static seated state at t into y (rates 0), Newton from y's
 * positions to within 1e-3 of atol (the run's absolute tolerances, N
 * values); yd is scratch.  0 on success, 1 if Newton failed. */
int rd_lift_stick_solve(const rd_lift_form *f, double t, N_Vector y, N_Vector yd,
                        const double *atol);

/* Advances a seated ring from t0 to t1 quasi-statically.  away: the sign of
 * the load F (m->fz_ext) that pulls the ring off its flank (+1 lower, -1
 * upper).  Returns 0 with y at t1 (still pressed), 1 with *tleave the date
 * where F turned away (y the quasi-static state there, already pulled
 * away), -1 if Newton failed (the caller integrates instead). */
int rd_lift_stick_advance(const rd_lift_form *f, double t0, double t1, int away, N_Vector y,
                          N_Vector yd, const double *atol, double *tleave);

#endif
