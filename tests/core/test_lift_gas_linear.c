/* test_lift_gas_linear — the linear flank pressure's force element
 * (rd_lift_forces.c, active_area linear): against the fixed faces carrying
 * the averaged pressures (p_own + p_behind) / 2, every segment's force
 * differs by a pure couple (no net force) about its tangential axis, of
 * the first moment of the two faces' pressure slopes, A b (p_below -
 * p_above) / 12 (A = the segment's face area, b its width), within the
 * spread of the segment's three arc directions (cos of a third of its
 * span: 0.45 % at n = 20); the groove pressure does not enter it; and its
 * sign: gas from above turns the inner edge up. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "rd_internal.h"
#include "rd_lift.h"
#include "rd_lift_model.h"

#define N 20

static const double deg[2] = {0.0, 720.0};

/* The generalized forces of all segments at rest (y = 0) under constant
 * gauge pressures (above, behind, below) with the area rule `area`. */
static int forces(const rd_ring *ring, const double g[3], int area, double *f)
{
    static double above[2], behind[2], below[2], y[12 * N];
    above[0] = above[1] = g[0];
    behind[0] = behind[1] = g[1];
    below[0] = below[1] = g[2];
    rd_lift_params p;
    rd_lift_params_default(&p);
    p.gas = (rd_gas_params){2, deg, above, behind, below, area};
    rd_lift_model c;
    rd_error err;
    rd_error_init(&err);
    memset(&c, 0, sizeof c);
    int rc = rd_lift_model_init(&c, ring, &p, NULL, &err);
    CHECK(rc == RD_OK, "model: %s", err.message);
    if (rc == RD_OK) {
        memset(y, 0, sizeof y);
        rd_lift_forces(&c, 0.0, y, NULL, NULL);
        memcpy(f, c.fbuf, 6 * N * sizeof *f);
    }
    rd_lift_model_cleanup(&c);
    return rc;
}

static void check_couple(const rd_ring *ring, const rd_ring_params *rp, const double g[3])
{
    double lin[6 * N], fix[6 * N], avg[3] = {0.5 * (g[0] + g[1]), g[1], 0.5 * (g[2] + g[1])};
    if (forces(ring, g, RD_GAS_AREA_LINEAR, lin) || forces(ring, avg, RD_GAS_AREA_FIXED, fix))
        return;
    double R = 0.5 * (rp->diameter - rp->radial_width), b = rp->radial_width;
    double phi = (2.0 * M_PI - rp->closed_gap / R) / N; /* the open ring's span over n */
    double want = phi * R * b * b * (g[2] - g[0]) / 12.0, force = 0.0, off = 0.0, worst = 0.0;
    for (int i = 0; i < N; i++) {
        const double *a = lin + 6 * i, *c = fix + 6 * i;
        double er[3], et[3];
        rd_ring_segment_frame(ring, i, er, et);
        for (int k = 0; k < 3; k++)
            force = fmax(force, fabs(a[k] - c[k]));
        double m[3] = {a[3] - c[3], a[4] - c[4], a[5] - c[5]};
        double mt = m[0] * et[0] + m[1] * et[1] + m[2] * et[2]; /* about e_t */
        off = fmax(off, fabs(m[0] * er[0] + m[1] * er[1] + m[2] * er[2]) + fabs(m[2]));
        /* e_r x e_z = -e_t: an upward force outside the inner one turns about -e_t */
        worst = fmax(worst, fabs(-mt - want) / fabs(want));
    }
    CHECK(force < 1e-9 * fabs(want) / b, "linear - fixed(averaged): no net force (%.3g N)", force);
    CHECK(off < 1e-9 * fabs(want), "the couple only about e_t (%.3g N m off)", off);
    CHECK(worst < 0.006, "couple A b (p_below - p_above) / 12 = %.4g N m: worst %.3g", want, worst);
    printf("couple per segment %.5g N m (gauge %g/%g/%g Pa), within %.3g\n", want, g[0], g[1], g[2],
           worst);
}

int main(void)
{
    rd_ring_params rp;
    rd_ring_params_default(&rp);
    rd_error err;
    rd_error_init(&err);
    rd_ring *ring = rd_ring_create(&rp, N, 0, &err);
    CHECK(ring != NULL, "ring: %s", err.message);
    if (ring) {
        const double g1[3] = {5e6, 4e6, 1e6}, g2[3] = {5e6, 0.0, 1e6}, g3[3] = {0.0, 2e6, 3e6};
        check_couple(ring, &rp, g1);
        check_couple(ring, &rp, g2); /* the groove's pressure does not enter the couple */
        check_couple(ring, &rp, g3);
        /* gas from above (p_above > p_below) turns the inner edge up: the
         * couple's forces push the outer flank point down */
        double lin[6 * N], fix[6 * N], avg[3] = {4.5e6, 4e6, 2.5e6};
        if (!forces(ring, g1, RD_GAS_AREA_LINEAR, lin) &&
            !forces(ring, avg, RD_GAS_AREA_FIXED, fix)) {
            double er[3], et[3];
            rd_ring_segment_frame(ring, 0, er, et);
            double mt = (lin[3] - fix[3]) * et[0] + (lin[4] - fix[4]) * et[1];
            CHECK(mt > 0.0, "gas from above: couple about +e_t (outer edge down), %.3g", mt);
        }
        rd_ring_free(ring);
    }
    return check_done();
}
