/* test_anderson — Anderson acceleration (core/rd_anderson.c) on fixed-point
 * iterations whose fixed points are known in closed form:
 *
 *  - a scalar affine map x <- a x + b: with one difference the mixed step
 *    is the secant through the last two iterates, exact for an affine map,
 *    so the second mixed iterate is b / (1 - a) to rounding;
 *  - a 4 x 4 affine contraction x <- M x + c (M upper triangular, spectral
 *    radius 0.99, so the plain iteration keeps 0.99^k of its error): with
 *    the whole history (depth 4) the mixed iteration is GMRES on
 *    (I - M) x = c (Walker & Ni 2011, Theorem 2.2), which ends in at most 4
 *    steps in exact arithmetic; after 8 the error is checked against 1e-12
 *    of the first (measured 7e-15: the normal equations square the
 *    differences' condition number and their 1e-12 regularisation caps the
 *    last digits, so 1e-12 leaves that room), where the plain iteration
 *    still holds 0.99^8 = 0.92 of it;
 *  - after rd_anderson_reset the next mix returns G(x) untouched.
 */
#include <math.h>
#include <string.h>

#include "check.h"
#include "rd_anderson.h"

static void test_scalar(void)
{
    rd_anderson acc;
    CHECK(rd_anderson_init(&acc, 1, 1) == 0, "init");
    double a = 0.9, b = 1.0, x = 0.0, want = b / (1.0 - a);
    for (int k = 0; k < 3; k++) {
        double g = a * x + b;
        rd_anderson_mix(&acc, &x, &g);
        if (k == 0)
            CHECK(g == a * x + b, "first mix: G(x) itself, %g", g);
        x = g;
    }
    CHECK(fabs(x - want) < 1e-13 * want, "scalar: %.17g, fixed point %.17g", x, want);
    rd_anderson_free(&acc);
}

static void affine(const double M[16], const double c[4], const double *x, double *g)
{
    for (int i = 0; i < 4; i++) {
        g[i] = c[i];
        for (int j = 0; j < 4; j++)
            g[i] += M[4 * i + j] * x[j];
    }
}

static void test_linear(void)
{
    const double M[16] = {0.99, 0.1, 0, 0, 0, 0.95, 0.2, 0, 0, 0, 0.9, 0.1, 0, 0, 0, 0.3};
    const double c[4] = {1, 2, 3, 4};
    /* (I - M) x* = c by back substitution */
    double xs[4];
    for (int i = 3; i >= 0; i--) {
        double s = c[i];
        for (int j = i + 1; j < 4; j++)
            s += M[4 * i + j] * xs[j];
        xs[i] = s / (1.0 - M[4 * i + i]);
    }
    double x[4] = {0}, p[4] = {0}, g[4], e0 = 0, e = 0, ep = 0;
    for (int i = 0; i < 4; i++)
        e0 = fmax(e0, fabs(x[i] - xs[i]));
    rd_anderson acc;
    CHECK(rd_anderson_init(&acc, 4, 4) == 0, "init");
    for (int k = 0; k < 8; k++) {
        affine(M, c, x, g);
        rd_anderson_mix(&acc, x, g);
        memcpy(x, g, sizeof x);
        affine(M, c, p, g); /* the plain iteration beside it */
        memcpy(p, g, sizeof p);
    }
    for (int i = 0; i < 4; i++) {
        e = fmax(e, fabs(x[i] - xs[i]));
        ep = fmax(ep, fabs(p[i] - xs[i]));
    }
    CHECK(e < 1e-12 * e0, "mixed: error %.3e of the first %.3e after 8 steps", e, e0);
    CHECK(ep > 0.9 * e0, "plain: error %.3e of the first %.3e after 8 steps", ep, e0);

    /* after a reset, the next mix is the plain step */
    rd_anderson_reset(&acc);
    double y[4] = {1, 1, 1, 1};
    affine(M, c, y, g);
    double plain[4];
    memcpy(plain, g, sizeof plain);
    rd_anderson_mix(&acc, y, g);
    CHECK(memcmp(plain, g, sizeof g) == 0, "after reset: G(x) itself");
    rd_anderson_free(&acc);

    CHECK(rd_anderson_init(&acc, 4, RD_ANDERSON_DEPTH_MAX + 1) != 0, "depth over the maximum");
    rd_anderson_free(&acc);
}

int main(void)
{
    test_scalar();
    test_linear();
    return check_done();
}
