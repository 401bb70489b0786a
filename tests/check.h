/* check.h — the tiny test harness: CHECK / CHECK_CLOSE, and a summary line.
 * Each test program calls CHECK_* freely and ends with `return check_done();`,
 * which prints "N passed, N failed" and returns non-zero if any check failed. */
#ifndef RD_CHECK_H
#define RD_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed_, check_failed_;

#define CHECK(cond, ...)                                                             \
    do {                                                                             \
        if (cond) {                                                                  \
            check_passed_++;                                                         \
        } else {                                                                     \
            check_failed_++;                                                         \
            fprintf(stderr, "%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                            \
            fputc('\n', stderr);                                                     \
        }                                                                            \
    } while (0)

/* |got - want| <= tol * max(|want|, tiny): a relative tolerance. */
#define CHECK_REL(got, want, tol, ...)                                            \
    do {                                                                          \
        double g_ = (got), w_ = (want), t_ = (tol);                               \
        double s_ = fabs(w_) > 1e-300 ? fabs(w_) : 1e-300;                        \
        int ok_ = isfinite(g_) && fabs(g_ - w_) <= t_ * s_;                       \
        CHECK(ok_, "%s = %.12g, want %.12g (rel err %.3g > %.3g) ", #got, g_, w_, \
              fabs(g_ - w_) / s_, t_);                                            \
        if (!ok_) {                                                               \
            fprintf(stderr, "    ");                                              \
            fprintf(stderr, __VA_ARGS__);                                         \
            fputc('\n', stderr);                                                  \
        }                                                                         \
    } while (0)

/* |got - want| <= tol: an absolute tolerance. */
#define CHECK_ABS(got, want, tol, ...)                                   \
    do {                                                                 \
        double g_ = (got), w_ = (want), t_ = (tol);                      \
        int ok_ = isfinite(g_) && fabs(g_ - w_) <= t_;                   \
        CHECK(ok_, "%s = %.12g, want %.12g +- %.3g ", #got, g_, w_, t_); \
        if (!ok_) {                                                      \
            fprintf(stderr, "    ");                                     \
            fprintf(stderr, __VA_ARGS__);                                \
            fputc('\n', stderr);                                         \
        }                                                                \
    } while (0)

static inline int check_done(void)
{
    printf("%d passed, %d failed\n", check_passed_, check_failed_);
    return check_failed_ ? 1 : 0;
}

#endif
