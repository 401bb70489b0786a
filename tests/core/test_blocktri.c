/* test_blocktri — the block-tridiagonal LU (core/rd_blocktri.c) and the lift
 * model's second-order Newton solve built on it (core/rd_lift_newton.c),
 * each against a dense LAPACK solve (dgesv: LU with partial pivoting over
 * the whole matrix, a second method written separately) of the same system.
 *
 *  - random block-tridiagonal matrices whose diagonal blocks need row
 *    pivoting inside the block (a zero in the (0, 0) corner), several block
 *    counts and sizes (1 to 7, the lift's 3 and 6 among them);
 *  - the lift's own Newton matrices S = I - gamma B - gamma^2 A, and the
 *    whole (I - gamma J) x = b solve, at states taken from a friction + gas
 *    run (seated, flying, landing: contacts closed and open), for the step
 *    sizes CVODE takes there (gamma 1e-8 .. 3e-5 s; 1 crank degree at 6000
 *    rpm is 2.8e-5 s);
 *  - exact breakdowns: a zero pivot is reported with its row, not divided by;
 *  - a matrix of two uncoupled sets of unknowns factored as two (as the
 *    planar contact ring's tangent is): the parts solve to exactly the
 *    whole's numbers.
 *
 * Tolerances: both solvers are backward stable on these matrices, so they
 * agree to the forward error bound ~ N eps cond(S); each check allows
 * 10 N eps cond_1 (cond_1 from LAPACK dgecon), reason: the bound's constant
 * with a margin of 10, and a floor of 1e-13 for the well-conditioned cases. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_blocktri.h"
#include "rd_lift_internal.h"
#include "rd_lift_model.h"

#define EPS 2.220446049250313e-16

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffffff) / (double)0x1000000 - 0.5;
}

/* The dense row-major N x N matrix of the block storage (before factoring). */
static void dense_of(const rd_blocktri *m, double *S)
{
    int bs = m->bs, N = m->nb * bs;
    size_t bb = (size_t)bs * bs;
    memset(S, 0, (size_t)N * N * sizeof *S);
    for (int i = 0; i < m->nb; i++)
        for (int r = 0; r < bs; r++)
            for (int c = 0; c < bs; c++) {
                size_t row = (size_t)N * (bs * i + r);
                S[row + bs * i + c] = m->D[bb * i + bs * r + c];
                if (i > 0)
                    S[row + bs * (i - 1) + c] = m->L[bb * i + bs * r + c];
                if (i + 1 < m->nb)
                    S[row + bs * (i + 1) + c] = m->U[bb * i + bs * r + c];
            }
}

/* Solves S x = b densely (x into b) after equilibrating S by LAPACK dgeequ,
 * R S C y = R b, x = C y (the lift's Newton matrix mixes rows in metres and
 * in metres per second: unscaled its condition number, ~1e17, would say
 * nothing).  The column scales go to cs (N values); returns the 1-norm
 * condition number of R S C, or -1 if LAPACK failed. */
static double dense_solve(int N, double *S, double *b, double *cs)
{
    double *rs = malloc((size_t)N * sizeof *rs), rowcnd, colcnd, amax, rcond = 0.0;
    lapack_int *piv = malloc((size_t)N * sizeof *piv);
    int info = rs && piv
                   ? LAPACKE_dgeequ(LAPACK_ROW_MAJOR, N, N, S, N, rs, cs, &rowcnd, &colcnd, &amax)
                   : -1;
    for (int r = 0; info == 0 && r < N; r++) {
        b[r] *= rs[r];
        for (int c = 0; c < N; c++)
            S[(size_t)N * r + c] *= rs[r] * cs[c];
    }
    double anorm = LAPACKE_dlange(LAPACK_ROW_MAJOR, '1', N, N, S, N);
    if (info == 0)
        info = LAPACKE_dgesv(LAPACK_ROW_MAJOR, N, 1, S, N, piv, b, 1);
    if (info == 0)
        info = LAPACKE_dgecon(LAPACK_ROW_MAJOR, '1', N, S, N, anorm, &rcond);
    for (int k = 0; info == 0 && k < N; k++)
        b[k] *= cs[k];
    free(piv);
    free(rs);
    return info == 0 && rcond > 0.0 ? 1.0 / rcond : -1.0;
}

/* max |x - y| / max |y| in the equilibrated unknowns x / cs */
static double rel_diff(const double *x, const double *y, const double *cs, int N)
{
    double d = 0.0, s = 0.0;
    for (int k = 0; k < N; k++) {
        d = fmax(d, fabs(x[k] - y[k]) / cs[k]);
        s = fmax(s, fabs(y[k]) / cs[k]);
    }
    return d / s;
}

static double tol_for(int N, double cond)
{
    return fmax(10.0 * N * EPS * cond, 1e-13);
}

/* Factors and solves m (filled) against dgesv for one right-hand side. */
static void compare(rd_blocktri *m, const char *what)
{
    int N = m->nb * m->bs;
    double *S = malloc((size_t)N * N * sizeof *S), *b = malloc(3 * (size_t)N * sizeof *b);
    if (!S || !b) {
        CHECK(0, "%s: out of memory", what);
        free(S);
        free(b);
        return;
    }
    unsigned seed = 7u + (unsigned)N;
    for (int k = 0; k < N; k++)
        b[k] = b[N + k] = urand(&seed);
    dense_of(m, S);
    double cond = dense_solve(N, S, b + N, b + 2 * N);
    int bad = rd_blocktri_factor(m);
    CHECK(cond > 0.0 && bad == 0, "%s: dgesv cond %g, block factor %d", what, cond, bad);
    if (cond > 0.0 && bad == 0) {
        rd_blocktri_solve(m, b);
        double e = rel_diff(b, b + N, b + 2 * N, N);
        if (getenv("RD_VERBOSE"))
            fprintf(stderr, "      %s: %.3g cond %.3g\n", what, e, cond);
        CHECK(e <= tol_for(N, cond), "%s: block solve differs from dgesv by %g (cond %.3g)", what,
              e, cond);
    }
    free(S);
    free(b);
}

/* Random matrices: D_i = random + 2 I with D_i(0,0) = 0 after swapping its
 * first two rows (so the block needs pivoting), off-diagonal blocks 0.3
 * random (block-diagonally dominant enough for the block elimination). */
static void test_random(void)
{
    int cases[][2] = {{1, 1}, {1, 6}, {2, 3}, {4, 3}, {5, 6}, {20, 6}, {3, 7}, {200, 6}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        int nb = cases[c][0], bs = cases[c][1];
        rd_blocktri m;
        if (rd_blocktri_init(&m, nb, bs) != 0) {
            CHECK(0, "init %d x %d", nb, bs);
            continue;
        }
        unsigned seed = 1u + (unsigned)(nb * 31 + bs);
        size_t bb = (size_t)bs * bs;
        for (int i = 0; i < nb; i++) {
            double *D = m.D + bb * i;
            for (size_t k = 0; k < bb; k++) {
                m.L[bb * i + k] = i > 0 ? 0.3 * urand(&seed) : 0.0;
                m.U[bb * i + k] = i + 1 < nb ? 0.3 * urand(&seed) : 0.0;
                D[k] = urand(&seed);
            }
            for (int k = 0; k < bs; k++)
                D[(bs + 1) * k] += 2.0;
            if (bs > 1) {
                D[bs] = 2.0; /* row 1 leads in column 0 ... */
                D[0] = 0.0;  /* ... and row 0 has none there: pivoting needed */
            }
        }
        char what[64];
        snprintf(what, sizeof what, "random nb %d bs %d", nb, bs);
        compare(&m, what);
        rd_blocktri_cleanup(&m);
    }
}

/* Exact breakdowns are reported with the global row, not divided by. */
static void test_singular(void)
{
    rd_blocktri m;
    if (rd_blocktri_init(&m, 2, 1) != 0) {
        CHECK(0, "init");
        return;
    }
    m.D[0] = 0.0; /* a zero first block */
    m.D[1] = 1.0;
    m.U[0] = m.L[1] = 1.0;
    CHECK(rd_blocktri_factor(&m) == 1, "zero first pivot not reported at row 1");
    m.D[0] = m.D[1] = m.U[0] = m.L[1] = 1.0; /* [1 1; 1 1]: D'_1 = 0 */
    CHECK(rd_blocktri_factor(&m) == 2, "zero Schur complement not reported at row 2");
    rd_blocktri_cleanup(&m);
    CHECK(rd_blocktri_init(&m, 0, 6) == RD_EINVAL && !m.L, "nb 0 accepted");
}

/* Two uncoupled sets: random matrices whose unknowns fall into two sets no
 * entry couples (the static tangent's in-plane {0, 1, 5} and out-of-plane
 * {2, 3, 4} DOFs of each 6-block), each set's diagonal blocks needing row
 * pivoting: each set's own factors must solve to exactly (bit for bit) the
 * whole matrix's solution, as rd_blocktri.h claims. */
static void test_split(void)
{
    static const int s0[6] = {0, 1, 5, 6, 7, 11}, s1[6] = {2, 3, 4, 8, 9, 10};
    const int *const sel[2] = {s0, s1};
    int cases[][2] = {{1, 6}, {7, 6}, {40, 12}, {3, 12}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        int nb = cases[c][0], bs = cases[c][1], N = nb * bs;
        size_t bb = (size_t)bs * bs;
        rd_blocktri m, full, part[2];
        double *x = malloc(2 * (size_t)N * sizeof *x), *xh = malloc((size_t)N * sizeof *xh);
        if (!x || !xh || rd_blocktri_init(&m, nb, bs) || rd_blocktri_init(&full, nb, bs) ||
            rd_blocktri_init(&part[0], nb, bs / 2) || rd_blocktri_init(&part[1], nb, bs / 2)) {
            CHECK(0, "split: out of memory");
            return;
        }
        int set[12] = {0};
        for (int k = 0; k < bs / 2; k++)
            set[s1[k]] = 1;
        unsigned seed = 3u + (unsigned)(nb * 17 + bs);
        for (int i = 0; i < nb; i++)
            for (int r = 0; r < bs; r++)
                for (int q = 0; q < bs; q++) {
                    size_t e = bb * i + (size_t)bs * r + q;
                    int same = set[r] == set[q];
                    m.L[e] = same && i > 0 ? 0.3 * urand(&seed) : 0.0;
                    m.U[e] = same && i + 1 < nb ? 0.3 * urand(&seed) : 0.0;
                    m.D[e] = same ? urand(&seed) + 2.0 * (r == q) : 0.0;
                }
        for (int i = 0; i < nb; i++) /* pivoting in each set: a zero (0, 0) */
            for (int h = 0; h < 2; h++) {
                double *D = m.D + bb * i;
                D[bs * sel[h][1] + sel[h][0]] = 2.0, D[bs * sel[h][0] + sel[h][0]] = 0.0;
            }
        for (int k = 0; k < N; k++)
            x[k] = urand(&seed);
        memcpy(full.L, m.L, 3 * bb * nb * sizeof *m.L); /* L, D, U are one block */
        for (int h = 0; h < 2; h++)                     /* each set's entries, block by block */
            for (size_t e = 0; e < (size_t)nb * bs * bs / 4; e++) {
                size_t i = e / (bb / 4), q = e % (bb / 4), r = q / (bs / 2), col = q % (bs / 2);
                size_t from = bb * i + (size_t)bs * sel[h][r] + sel[h][col];
                part[h].L[e] = m.L[from], part[h].D[e] = m.D[from], part[h].U[e] = m.U[from];
            }
        CHECK(rd_blocktri_factor(&full) == 0 && rd_blocktri_factor(&part[0]) == 0 &&
                  rd_blocktri_factor(&part[1]) == 0,
              "split: factors, nb %d bs %d", nb, bs);
        memcpy(x + N, x, (size_t)N * sizeof *x);
        rd_blocktri_solve(&full, x);
        for (int h = 0; h < 2; h++) {
            for (int i = 0; i < nb; i++)
                for (int r = 0; r < bs / 2; r++)
                    xh[bs / 2 * i + r] = x[N + bs * i + sel[h][r]];
            rd_blocktri_solve(&part[h], xh);
            for (int i = 0; i < nb; i++)
                for (int r = 0; r < bs / 2; r++)
                    x[N + bs * i + sel[h][r]] = xh[bs / 2 * i + r];
        }
        int same = 1;
        for (int k = 0; k < N; k++)
            same &= x[k] == x[N + k];
        CHECK(same, "split: parts' solution differs from the whole's, nb %d bs %d", nb, bs);
        rd_blocktri_cleanup(&m);
        rd_blocktri_cleanup(&full);
        rd_blocktri_cleanup(&part[0]);
        rd_blocktri_cleanup(&part[1]);
        free(x);
        free(xh);
    }
}

/* ------------------------------------------------ the lift's own matrices */

#define LIFT_N     12
#define LIFT_GAS   361
#define LIFT_STATE (12 * LIFT_N)

static double gas_tab[4][LIFT_GAS];

typedef struct states {
    int count, cap;
    double *t, *y;
} states;

static void keep_state(void *ctx, double t, const double *y)
{
    states *s = ctx;
    if (s->count < s->cap) {
        s->t[s->count] = t;
        memcpy(s->y + (size_t)LIFT_STATE * s->count, y, LIFT_STATE * sizeof *y);
        s->count++;
    }
}

/* The 6000 rpm scene of the examples (Coulomb friction 0.1, a firing
 * pulse's gas, gravity), one cycle at n = LIFT_N: its states every degree. */
static int lift_states(rd_ring_params *rp, rd_lift_params *p, states *s)
{
    rd_ring_params_default(rp);
    rd_lift_params_default(p);
    p->model = RD_LIFT_MODEL_FULL;
    p->engine.speed_rpm = 6000.0;
    p->engine.cycles = 1.0;
    p->estimate_error = 0;
    p->friction.model = RD_FRICTION_COULOMB;
    p->friction.coefficient = 0.1;
    for (int i = 0; i < LIFT_GAS; i++) {
        double d = 2.0 * i;
        gas_tab[0][i] = d;
        gas_tab[1][i] = 58e5 * exp(-pow((d - 20.0) / 25.0, 2));
        gas_tab[2][i] = 58e5 * exp(-pow((d - 22.0) / 25.0, 2));
        gas_tab[3][i] = 0.3 * 58e5 * exp(-pow((d - 40.0) / 30.0, 2));
    }
    p->gas.points = LIFT_GAS;
    p->gas.crank_deg = gas_tab[0];
    p->gas.above = gas_tab[1];
    p->gas.behind = gas_tab[2];
    p->gas.below = gas_tab[3];
    p->gas.active_area = RD_GAS_AREA_FIXED;
    s->cap = 721;
    s->t = malloc((size_t)s->cap * sizeof *s->t);
    s->y = malloc((size_t)s->cap * LIFT_STATE * sizeof *s->y);
    if (!s->t || !s->y)
        return RD_ENOMEM;
    rd_lift_setup setup = {.sample = keep_state, .ctx = s};
    rd_lift_result r;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_lift_solve_setup(rp, LIFT_N, p, &setup, NULL, &r, &err);
    CHECK(rc == RD_OK && r.n_events >= 2, "lift run: %s (%d flank changes)", err.message,
          rc == RD_OK ? r.n_events : -1);
    if (rc == RD_OK)
        rd_lift_result_cleanup(&r);
    return rc;
}

/* The block solve of S = I - gamma B - gamma^2 A (assembled here from the
 * form's blocks) and the Newton solver's (I - gamma J) x = b, each against
 * dgesv on the dense matrix. */
static void compare_lift(const rd_lift_form *form, SUNLinearSolver LS, SUNMatrix hold,
                         rd_lift_newton *nw, double t, N_Vector yv, double gamma, double *worst)
{
    enum { NB = LIFT_N, BS = 6, N2 = NB * BS, N = 2 * N2 };
    static double A[NB * 3 * 36], B[NB * 36], J[N * N], b[2 * N], cs[N];
    const double *y = N_VGetArrayPointer(yv);
    form->blocks(form->user, t, y, A, B);
    rd_blocktri m;
    if (rd_blocktri_init(&m, NB, BS) != 0) {
        CHECK(0, "init");
        return;
    }
    for (int i = 0; i < NB; i++)
        for (int k = 0; k < 36; k++) {
            m.L[36 * i + k] = -gamma * gamma * A[108 * i + k];
            m.D[36 * i + k] =
                (k % 7 == 0) - gamma * B[36 * i + k] - gamma * gamma * A[108 * i + 36 + k];
            m.U[36 * i + k] = -gamma * gamma * A[108 * i + 72 + k];
        }
    char what[96];
    snprintf(what, sizeof what, "lift S at %.1f deg, gamma %.0e", t * 36000.0 /* deg/s */, gamma);
    compare(&m, what);
    rd_blocktri_cleanup(&m);
    /* I - gamma J in the state layout [q_i, v_i]: q rows I - gamma I_v, v rows
     * -gamma A_ij on q_j and I - gamma B_i on v_i */
    memset(J, 0, sizeof J);
    for (int i = 0; i < NB; i++)
        for (int r = 0; r < BS; r++) {
            double *qrow = J + (size_t)N * (12 * i + r), *vrow = J + (size_t)N * (12 * i + 6 + r);
            qrow[12 * i + r] = 1.0;
            qrow[12 * i + 6 + r] = -gamma;
            for (int j = i - 1; j <= i + 1; j++)
                for (int c = 0; j >= 0 && j < NB && c < BS; c++)
                    vrow[12 * j + c] = -gamma * A[108 * i + 36 * (j - i + 1) + 6 * r + c];
            for (int c = 0; c < BS; c++)
                vrow[12 * i + 6 + c] = (r == c) - gamma * B[36 * i + 6 * r + c];
        }
    unsigned seed = 99u;
    for (int k = 0; k < N; k++)
        b[k] = b[N + k] = urand(&seed) * (k % 12 < 6 ? 1e-6 : 1e-2);
    double cond = dense_solve(N, J, b + N, cs);
    int jcur = 0;
    SUNContext ctx = yv->sunctx;
    N_Vector xv = N_VNew_Serial(N, ctx), bv = N_VMake_Serial(N, b, ctx);
    int rc = rd_lift_newton_linsys(nw, t, yv, 0, &jcur, gamma);
    if (!rc)
        rc = SUNLinSolSetup(LS, hold);
    if (!rc && xv && bv)
        rc = SUNLinSolSolve(LS, hold, xv, bv, 0.0);
    CHECK(xv && bv && rc == 0 && jcur && cond > 0.0, "%s: Newton solve rc %d cond %g", what, rc,
          cond);
    if (xv && bv && rc == 0 && cond > 0.0) {
        double e = rel_diff(N_VGetArrayPointer(xv), b + N, cs, N);
        if (getenv("RD_VERBOSE"))
            fprintf(stderr, "      %s Newton: %.3g cond %.3g\n", what, e, cond);
        CHECK(e <= tol_for(N, cond), "%s: Newton solve differs from dgesv by %g (cond %.3g)", what,
              e, cond);
        *worst = fmax(*worst, e / tol_for(N, cond));
    }
    if (xv)
        N_VDestroy(xv);
    if (bv)
        N_VDestroy(bv);
}

static void test_lift(void)
{
    rd_ring_params rp;
    rd_lift_params p;
    states s = {0};
    rd_ring *ring = NULL;
    rd_lift_model c;
    rd_lift_form form = {0};
    SUNContext ctx = NULL;
    SUNLinearSolver LS = NULL;
    SUNMatrix hold = NULL;
    rd_lift_newton *nw = NULL;
    N_Vector yv = NULL;
    rd_error err;
    rd_error_init(&err);
    memset(&c, 0, sizeof c);
    if (lift_states(&rp, &p, &s) != RD_OK || s.count < 720)
        goto out;
    ring = rd_ring_create(&rp, LIFT_N, 0, &err);
    if (!ring || rd_lift_model_init(&c, ring, &p, NULL, &err) != RD_OK) {
        CHECK(0, "model: %s", err.message);
        goto out;
    }
    rd_lift_full_form(&c, &form);
    if (SUNContext_Create(NULL, &ctx) || !(yv = N_VNew_Serial(form.N, ctx)) ||
        !(LS = rd_lift_newton_create(&form, ctx, &hold, &nw)) || SUNLinSolInitialize(LS)) {
        CHECK(0, "SUNDIALS set-up");
        goto out;
    }
    /* every 30 degrees: seated on either flank, in flight, and the landings
     * (the run's flank changes fall between ~290 and ~450 deg) every 2 deg */
    double gammas[] = {1e-8, 1e-6, 1e-5, 3e-5}, worst = 0.0;
    int tested = 0;
    for (int k = 0; k < s.count; k++) {
        if (k % 30 != 0 && !((k > 290 && k < 320) || (k > 430 && k < 460)))
            continue;
        if (k % 30 != 0 && k % 2 != 0)
            continue;
        memcpy(N_VGetArrayPointer(yv), s.y + (size_t)LIFT_STATE * k, LIFT_STATE * sizeof(double));
        for (size_t g = 0; g < sizeof gammas / sizeof gammas[0]; g++)
            compare_lift(&form, LS, hold, nw, s.t[k], yv, gammas[g], &worst);
        tested++;
    }
    fprintf(stderr,
            "    lift Newton solves at %d states x 4 gammas: worst error %.3g of its bound\n",
            tested, worst);
out:
    if (LS)
        SUNLinSolFree(LS);
    if (yv)
        N_VDestroy(yv);
    if (ctx)
        SUNContext_Free(&ctx);
    rd_lift_model_cleanup(&c);
    rd_ring_free(ring);
    free(s.t);
    free(s.y);
}

int main(void)
{
    test_random();
    test_singular();
    test_split();
    test_lift();
    return check_done();
}
