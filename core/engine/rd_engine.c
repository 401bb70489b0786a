/*
 * rd_engine.c — crank speed, piston kinematics and the engine block's
 * checks (rd_engine.h; the tilt is rd_engine_tilt.c).
 *
 * Piston (thesis 1.6-1.8).  s(alpha) = distance of the piston below TDC.
 *   approximate: s = r (1 - cos a + lambda/4 (1 - cos 2a))              (1.6)
 *                v = r w (sin a + lambda/2 sin 2a)                        (1.7)
 *                a = r w^2 (cos a + lambda cos 2a),  lambda = r / l       (1.8)
 *   exact:       s = r (1 - cos a) + l (1 - Q),  Q = sqrt(1 - lambda^2 sin^2 a)
 *                ds/da = r sin a (1 + lambda cos a / Q)
 *                d2s/da2 = r (cos a + lambda (cos 2a + lambda^2 sin^4 a) / Q^3)
 */
#include "rd_engine.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double rd_engine_omega(const rd_engine_params *e)
{
    return e->speed_rpm * 2.0 * M_PI / 60.0;
}

double rd_engine_mean_speed(const rd_engine_params *e)
{
    return 4.0 * e->crank_radius * e->speed_rpm / 60.0;
}

void rd_engine_piston_alpha(const rd_engine_params *e, double alpha, double *s, double *ds,
                            double *dds)
{
    double r = e->crank_radius, lam = r / e->rod_length;
    double sa = sin(alpha), ca = cos(alpha);
    if (e->kinematics == RD_KINEMATICS_APPROXIMATE) {
        *s = r * (1.0 - ca + 0.25 * lam * (1.0 - cos(2.0 * alpha))); /* (1.6) */
        *ds = r * (sa + 0.5 * lam * sin(2.0 * alpha));               /* (1.7) / w */
        *dds = r * (ca + lam * cos(2.0 * alpha));                    /* (1.8) / w^2 */
    } else {
        double Q = sqrt(1.0 - lam * lam * sa * sa);
        /* l (1 - Q) = l lam^2 sin^2 / (1 + Q): no cancellation */
        *s = r * (1.0 - ca) + e->rod_length * lam * lam * sa * sa / (1.0 + Q);
        *ds = r * sa * (1.0 + lam * ca / Q);
        *dds = r * (ca + lam * (cos(2.0 * alpha) + lam * lam * pow(sa, 4)) / (Q * Q * Q));
    }
}

void rd_engine_piston(const rd_engine_params *e, double alpha, double *s, double *v, double *a)
{
    double w = rd_engine_omega(e);
    double s_, ds, dds; /* s and its derivatives with respect to alpha */
    rd_engine_piston_alpha(e, alpha, &s_, &ds, &dds);
    if (s)
        *s = s_;
    if (v)
        *v = w * ds;
    if (a)
        *a = w * w * dds;
}

/* engine.piston_tilt_deg and the engine.piston_tilt table. */
static int validate_tilt(const rd_engine_params *e, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range(e->piston_tilt_deg, -RD_ENGINE_TILT_MAX_DEG, RD_ENGINE_TILT_MAX_DEG,
                             "/piston_tilt_deg", "deg", err)))
        return rc;
    if (e->tilt_points < 0 || e->tilt_points > RD_ENGINE_TABLE_MAX)
        return rd_error_set(err, RD_EINVAL, "/piston_tilt/crank_deg",
                            "@/piston_tilt has %d points: allowed 1 to %d.", e->tilt_points,
                            RD_ENGINE_TABLE_MAX);
    double big = 0.0;
    for (int i = 0; i < e->tilt_points; i++) {
        double a = e->tilt_crank_deg[i], b = e->tilt_deg[i];
        if (!isfinite(a) || a < 0.0 || a > 720.0 || (i > 0 && !(a > e->tilt_crank_deg[i - 1])))
            return rd_error_set(err, RD_EINVAL, "/piston_tilt/crank_deg",
                                "@/piston_tilt/crank_deg[%d] = %g deg: the crank angles "
                                "must be strictly increasing within 0 to 720 deg.",
                                i, a);
        if (!isfinite(b))
            return rd_error_set(err, RD_EINVAL, "/piston_tilt/tilt_deg",
                                "@/piston_tilt/tilt_deg[%d] is not a finite number.", i);
        big = fmax(big, fabs(b));
    }
    if (fabs(e->piston_tilt_deg) + big > RD_ENGINE_TILT_MAX_DEG)
        return rd_error_set(err, RD_EINVAL, "/piston_tilt/tilt_deg",
                            "@/piston_tilt_deg + the largest @/piston_tilt/tilt_deg "
                            "= %g deg: the tilt is allowed up to %g deg (small-angle model).",
                            fabs(e->piston_tilt_deg) + big, RD_ENGINE_TILT_MAX_DEG);
    return RD_OK;
}

int rd_engine_validate(const rd_engine_params *e, rd_error *err)
{
    int rc;
    if ((rc = rd_error_range(e->speed_rpm, 1.0, 30000.0, "/speed_rpm", "rpm", err)) ||
        (rc = rd_error_range(e->crank_radius, 1e-3, 1.0, "/crank_radius", "m", err)))
        return rc;
    /* lambda = r / l <= 0.9: the exact slider-crank needs lambda < 1; real
     * engines have 0.2..0.4. */
    if (!isfinite(e->rod_length) || e->rod_length < e->crank_radius / 0.9 || e->rod_length > 10.0)
        return rd_error_set(err, RD_EINVAL, "/rod_length",
                            "@/rod_length = %g m is out of range: allowed %g m (crank "
                            "radius / 0.9) to 10 m.",
                            e->rod_length, e->crank_radius / 0.9);
    if (e->kinematics != RD_KINEMATICS_EXACT && e->kinematics != RD_KINEMATICS_APPROXIMATE)
        return rd_error_set(err, RD_EINVAL, "/kinematics",
                            "@/kinematics = %d is unknown: use exact or approximate.",
                            e->kinematics);
    return validate_tilt(e, err);
}
