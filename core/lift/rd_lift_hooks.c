/*
 * rd_lift_hooks.c — the test hooks of the lift models (rd_lift_internal.h):
 * the Jacobian against central differences of the right-hand side, and the
 * rigid ring's twist stiffnesses.  Each validates its scene and builds its
 * own model; they sit on top of the lift folder so that no production file
 * calls back up to the validation.
 */
#include <math.h>
#include <string.h>

#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "rd_lift_model.h"

/* Entry (i, j) of the form's Newton-matrix storage (0 outside a band). */
static double jac_entry(const rd_lift_form *f, SUNMatrix J, sunindextype i, sunindextype j)
{
    if (f->dense)
        return SM_ELEMENT_D(J, i, j);
    return (i - j <= RD_LIFT_ML && j - i <= RD_LIFT_MU) ? SM_ELEMENT_B(J, i, j) : 0.0;
}

/* Central-difference step of state j: 1e-3 d0 on translations, the same at
 * 0.05 m lever arm on rotations, 1e-4 u_reg on rates: exact on the
 * penalty's quadratic and linear pieces, far from its kinks, and large
 * enough that rounding stays ~1e-6 relative. */
static double fd_step(const rd_lift_form *f, sunindextype j)
{
    const rd_lift_model *c = f->m;
    if (f->fd_step)
        return f->fd_step(f->user, j);
    if (f->dense) /* rigid: z, theta, r, then their rates */
        return j >= 3 ? 1e-4 * c->liner.ureg : (j == 1 ? 2e-2 * c->d0 : 1e-3 * c->d0);
    return (j % 12) < 6 ? (j % 12 < 3 ? 1e-3 * c->d0 : 2e-2 * c->d0) : 1e-4 * c->liner.ureg;
}

/* The largest relative difference between J and central differences. */
static double jac_compare(const rd_lift_form *f, double t, N_Vector y, N_Vector f1, N_Vector f2,
                          SUNMatrix J)
{
    sunindextype N = f->N;
    double *yy = N_VGetArrayPointer(y), jmax = 0.0, worst = 0.0;
    for (sunindextype j = 0; j < N; j++)
        for (sunindextype i = 0; i < N; i++)
            jmax = fmax(jmax, fabs(jac_entry(f, J, i, j)));
    for (sunindextype j = 0; j < N; j++) {
        double h = fd_step(f, j), keep = yy[j];
        yy[j] = keep + h;
        f->rhs(t, y, f1, f->user);
        yy[j] = keep - h;
        f->rhs(t, y, f2, f->user);
        yy[j] = keep;
        const double *a = N_VGetArrayPointer(f1), *b = N_VGetArrayPointer(f2);
        for (sunindextype i = 0; i < N; i++) {
            double fd = (a[i] - b[i]) / (2.0 * h), an = jac_entry(f, J, i, j);
            worst = fmax(worst, fabs(fd - an) / (fabs(an) + 1e-6 * jmax));
        }
    }
    return worst;
}

int rd_lift_jacobian_check(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                           double t, const double *y0, double *max_err, rd_error *err)
{
    rd_lift_model c;
    rd_lift_form form = {0};
    rd_ring *ring = NULL;
    SUNContext sunctx = NULL;
    N_Vector y = NULL, f1 = NULL, f2 = NULL;
    SUNMatrix J = NULL;
    int rc;
    memset(&c, 0, sizeof c);
    if ((rc = rd_lift_validate(p, rp, segments, err)))
        return rc;
    ring = rd_ring_create(rp, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    if ((rc = rd_lift_model_init(&c, ring, p, NULL, err)))
        goto out;
    if ((rc = rd_lift_form_open(&c, p->model, p->modes, &form, err)))
        goto out;
    sunindextype N = form.N;
    if (SUNContext_Create(NULL, &sunctx) || !(y = N_VNew_Serial(N, sunctx)) ||
        !(f1 = N_VNew_Serial(N, sunctx)) || !(f2 = N_VNew_Serial(N, sunctx)) ||
        !(J = form.dense ? SUNDenseMatrix(N, N, sunctx)
                         : SUNBandMatrix(N, RD_LIFT_MU, RD_LIFT_ML, sunctx))) {
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
        goto out;
    }
    memcpy(N_VGetArrayPointer(y), y0, (size_t)N * sizeof(double));
    if (form.jac(t, y, NULL, J, form.user, NULL, NULL, NULL)) {
        rc = rd_error_set(err, RD_EINTERNAL, "", "The lift Jacobian could not be assembled.");
        goto out;
    }
    *max_err = jac_compare(&form, t, y, f1, f2, J);
out:
    if (J)
        SUNMatDestroy(J);
    if (y)
        N_VDestroy(y);
    if (f1)
        N_VDestroy(f1);
    if (f2)
        N_VDestroy(f2);
    if (sunctx)
        SUNContext_Free(&sunctx);
    if (form.close)
        form.close(&form);
    rd_lift_model_cleanup(&c);
    rd_ring_free(ring);
    return rc;
}

int rd_lift_twist_stiffness(const rd_ring_params *rp, int segments, const rd_lift_params *p,
                            double k[3], rd_error *err)
{
    rd_lift_model m;
    memset(&m, 0, sizeof m);
    int rc = rd_lift_validate(p, rp, segments, err);
    if (rc)
        return rc;
    rd_ring *ring = rd_ring_create(rp, segments, 0, err);
    if (!ring)
        return err ? err->code : RD_ENOMEM;
    if (!(rc = rd_lift_model_init(&m, ring, p, NULL, err)))
        rc = rd_lift_rigid_twist(&m, k, err);
    rd_lift_model_cleanup(&m);
    rd_ring_free(ring);
    return rc;
}
