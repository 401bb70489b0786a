/*
 * rd_dtoa — shortest round-trip and fixed-precision decimal text of a
 * double (rd_dtoa.h), exactly, with 128-bit integer arithmetic.
 *
 * A positive finite double is x = m 2^e (m < 2^53).  Every real in the
 * half-open or closed interval (L, H) around it, L = x - (gap below)/2,
 * H = x + ulp/2, reads back as x (closed when m is even: strtod rounds ties
 * to even).  In quarter units, L, x, H are u 2^e2 with e2 = e - 2 and
 * u = 4m - 2 (4m - 1 when x is a power of two whose gap below is half the
 * ulp), 4m, 4m + 2.  Scaled by 10^-q, q = floor(e2 log10 2) - 1, so that a
 * quarter unit is 10..100 decimal units:
 *     v(u) = floor(u 2^e2 10^-q)    and whether it is exact,
 * computed exactly in 128 bits as u 5^-q >> (q - e2) for q <= 0 and
 * (u << (e2 - q)) / 5^q for q > 0.  Dropping trailing decimal digits while
 * the floors of L and H still differ leaves the shortest digit count whose
 * grid has a point inside the interval; the kept digits of x, rounded half
 * to even on the dropped ones (exact ties known from the exactness flags),
 * are the point nearest x, moved up by one when it fell on an excluded L.
 * (The digit-dropping loop is the one of Adams' Ryu, PLDI 2018; here the
 * products are exact rather than from truncated tables.)
 *
 * Exact 128-bit products hold for 0 <= -q <= 31 (u 5^31 < 2^128) and for
 * 0 < q <= 27 with -64 <= e2 - q <= 72 (u << (e2 - q) divided by 5^q, or u
 * by 5^q << (q - e2)): |x| from about 1e-14 to 1e44, the numbers a result
 * holds.  Outside it the text comes from the C library's correctly
 * rounded printf, whose digits then go through the same layout.
 *
 * rd_dtoa_digits(x, P) needs no shortest digits: with q such that x 10^-q
 * has P digits before the point, w = floor(2 x 10^-q) (the same exact
 * product) holds the P digits and the half bit, and its exactness tells an
 * exact tie (rounded to even, as printf rounds) from a remainder above it.
 */
#include "rd_dtoa.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

__extension__ typedef unsigned __int128 u128;

/* 5^k, k = 0..27 (5^27 < 2^63). */
static const uint64_t pow5[28] = {1u,
                                  5u,
                                  25u,
                                  125u,
                                  625u,
                                  3125u,
                                  15625u,
                                  78125u,
                                  390625u,
                                  1953125u,
                                  9765625u,
                                  48828125u,
                                  244140625u,
                                  1220703125u,
                                  6103515625u,
                                  30517578125u,
                                  152587890625u,
                                  762939453125u,
                                  3814697265625u,
                                  19073486328125u,
                                  95367431640625u,
                                  476837158203125u,
                                  2384185791015625u,
                                  11920928955078125u,
                                  59604644775390625u,
                                  298023223876953125u,
                                  1490116119384765625u,
                                  7450580596923828125u};

/* A decimal d 10^e10 with n digits in d (d has no trailing zero). */
typedef struct decimal {
    uint64_t d;
    int n, e10;
} decimal;

/* 10^k, k = 0..19. */
static const uint64_t ten_pow[20] = {1u,
                                     10u,
                                     100u,
                                     1000u,
                                     10000u,
                                     100000u,
                                     1000000u,
                                     10000000u,
                                     100000000u,
                                     1000000000u,
                                     10000000000u,
                                     100000000000u,
                                     1000000000000u,
                                     10000000000000u,
                                     100000000000000u,
                                     1000000000000000u,
                                     10000000000000000u,
                                     100000000000000000u,
                                     1000000000000000000u,
                                     10000000000000000000u};

/* Decimal digits of d (1 for 0): t = floor(bits log10 2) (1233/4096 is
 * log10 2 rounded down, exact enough below 2^64) is the count or one short. */
static int count_digits(uint64_t d)
{
    d |= 1;
    int t = ((64 - __builtin_clzll(d)) * 1233) >> 12;
    return t + (d >= ten_pow[t]);
}

static void strip_zeros(decimal *v)
{
    while (v->d != 0 && v->d % 10 == 0) {
        v->d /= 10;
        v->e10++;
    }
    v->n = count_digits(v->d);
}

/* floor(u 2^e2 10^-q) into *v, *exact = 1 when no remainder; -1 when the
 * product would not be exact in 128 bits. */
static int scale(uint64_t u, int e2, int q, uint64_t *v, int *exact)
{
    if (q <= 0) {
        int t = -q;
        if (t > 31)
            return -1;
        u128 p5 = t <= 27 ? (u128)pow5[t] : (u128)pow5[27] * pow5[t - 27];
        u128 prod = (u128)u * p5;
        int sh = e2 + t; /* 10^t = 5^t 2^t */
        if (sh >= 0) {
            *v = (uint64_t)(prod << sh);
            *exact = 1;
        } else {
            if (-sh >= 128)
                return -1;
            *v = (uint64_t)(prod >> -sh);
            *exact = (prod & (((u128)1 << -sh) - 1)) == 0;
        }
        return 0;
    }
    if (q > 27 || e2 - q > 72 || q - e2 > 64)
        return -1;
    if (e2 >= q) {
        u128 num = (u128)u << (e2 - q);
        *v = (uint64_t)(num / pow5[q]);
        *exact = num % pow5[q] == 0;
    } else { /* u / (5^q 2^(q - e2)) */
        u128 den = (u128)pow5[q] << (q - e2);
        *v = (uint64_t)(u / den);
        *exact = u % den == 0;
    }
    return 0;
}

/* The shortest round-trip digits of x > 0 (finite); -1 outside the exact
 * range. */
static int shortest_exact(double x, decimal *out)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    uint64_t frac = bits & ((UINT64_C(1) << 52) - 1);
    int bexp = (int)((bits >> 52) & 0x7ff);
    uint64_t m = bexp ? frac | (UINT64_C(1) << 52) : frac;
    int e2 = (bexp ? bexp - 1075 : -1074) - 2;
    int accept = (m & 1) == 0; /* strtod's ties to even keep the bounds */
    uint64_t mv = 4 * m, mp = 4 * m + 2, mm = 4 * m - (frac == 0 && bexp > 1 ? 1 : 2);
    int q = (int)floor(e2 * 0.30102999566398119521) - 1;
    uint64_t vm, vr, vp;
    int vm_exact, vr_exact, vp_exact;
    if (scale(mm, e2, q, &vm, &vm_exact) || scale(mv, e2, q, &vr, &vr_exact) ||
        scale(mp, e2, q, &vp, &vp_exact))
        return -1;
    if (!accept && vp_exact)
        vp--; /* H itself is excluded */
    vm_exact = vm_exact && accept;
    int removed = 0, last = 0;
    while (vp / 10 > vm / 10) {
        vm_exact = vm_exact && vm % 10 == 0;
        vr_exact = vr_exact && last == 0;
        last = (int)(vr % 10);
        vr /= 10, vp /= 10, vm /= 10;
        removed++;
    }
    while (vm_exact && vm % 10 == 0) { /* L itself is shorter still */
        vr_exact = vr_exact && last == 0;
        last = (int)(vr % 10);
        vr /= 10, vp /= 10, vm /= 10;
        removed++;
    }
    if (vr_exact && last == 5 && vr % 2 == 0)
        last = 4; /* an exact tie rounds to even */
    out->d = vr + ((vr == vm && !vm_exact) || last >= 5);
    out->e10 = q + removed;
    strip_zeros(out);
    return 0;
}

/* Digits of printf's "%.<p-1>e" of x > 0 (correctly rounded by the C
 * library). */
static void printf_digits(double x, int p, decimal *out)
{
    char buf[48];
    snprintf(buf, sizeof buf, "%.*e", p - 1, x);
    uint64_t d = 0;
    int n = 0;
    const char *s = buf;
    for (; *s && *s != 'e'; s++)
        if (*s >= '0' && *s <= '9') {
            d = 10 * d + (uint64_t)(*s - '0');
            n++;
        }
    int exp10 = *s == 'e' ? atoi(s + 1) : 0;
    out->d = d;
    out->e10 = exp10 - (n - 1);
    strip_zeros(out);
}

/* The fewest printf digits that read back as x (the fallback). */
static void shortest_printf(double x, decimal *out)
{
    for (int p = 1; p <= 17; p++) {
        printf_digits(x, p, out);
        char buf[48];
        snprintf(buf, sizeof buf, "%.*e", p - 1, x);
        if (strtod(buf, NULL) == x)
            return;
    }
}

static char *put_digits(char *p, const char *dig, int n)
{
    memcpy(p, dig, (size_t)n);
    return p + n;
}

/* The text of sign v, in exponent notation when `expo`. */
static int layout(int neg, const decimal *v, int expo, char *buf)
{
    char dig[24];
    uint64_t d = v->d;
    for (int i = v->n - 1; i >= 0; i--, d /= 10)
        dig[i] = (char)('0' + d % 10);
    int n = v->n, x10 = v->e10 + n - 1;
    char *p = buf;
    if (neg)
        *p++ = '-';
    if (expo) {
        *p++ = dig[0];
        if (n > 1) {
            *p++ = '.';
            p = put_digits(p, dig + 1, n - 1);
        }
        *p++ = 'e';
        if (x10 < 0)
            *p++ = '-';
        int ax = abs(x10);
        if (ax >= 100)
            *p++ = (char)('0' + ax / 100);
        if (ax >= 10)
            *p++ = (char)('0' + ax / 10 % 10);
        *p++ = (char)('0' + ax % 10);
    } else if (x10 < 0) {
        *p++ = '0', *p++ = '.';
        for (int i = 0; i < -x10 - 1; i++)
            *p++ = '0';
        p = put_digits(p, dig, n);
    } else if (n <= x10 + 1) {
        p = put_digits(p, dig, n);
        for (int i = n; i < x10 + 1; i++)
            *p++ = '0';
    } else {
        p = put_digits(p, dig, x10 + 1);
        *p++ = '.';
        p = put_digits(p, dig + x10 + 1, n - x10 - 1);
    }
    *p = '\0';
    return (int)(p - buf);
}

static int zero_or_special(double x, char *buf)
{
    const char *text = !isfinite(x) ? "null" : signbit(x) ? "-0" : "0";
    int n = !isfinite(x) ? 4 : signbit(x) ? 2 : 1;
    memcpy(buf, text, (size_t)n + 1);
    return n;
}

int rd_dtoa_shortest(double x, char *buf)
{
    if (!isfinite(x) || x == 0)
        return zero_or_special(x, buf);
    decimal v;
    double a = fabs(x);
    if (shortest_exact(a, &v) != 0)
        shortest_printf(a, &v);
    int x10 = v.e10 + v.n - 1, ax = abs(x10);
    int expo_len = v.n + (v.n > 1) + 1 + (x10 < 0) + (ax >= 100 ? 3 : ax >= 10 ? 2 : 1);
    int fixed_len = x10 < 0 ? v.n + 1 - x10 : v.n <= x10 + 1 ? x10 + 1 : v.n + 1;
    return layout(signbit(x) != 0, &v, expo_len < fixed_len, buf);
}

/* x > 0 (finite) rounded to p <= 17 digits, exactly: q such that x 10^-q
 * has p digits before the point, then w = floor(2 x 10^-q) and whether it
 * is exact give the digits (w / 2) and the rounding: up when the dropped
 * part is over a half, or exactly a half and the digits odd (printf's ties
 * to even).  -1 outside the exact range. */
static int round_direct(double x, int p, decimal *v)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    uint64_t frac = bits & ((UINT64_C(1) << 52) - 1);
    int bexp = (int)((bits >> 52) & 0x7ff);
    uint64_t m = bexp ? frac | (UINT64_C(1) << 52) : frac;
    int e = bexp ? bexp - 1075 : -1074;
    int lg2 = 63 - __builtin_clzll(m) + e;              /* 2^lg2 <= x < 2^(lg2+1) */
    int x10 = (int)floor(lg2 * 0.30102999566398119521); /* log10 x's floor, or one short */
    for (int attempt = 0; attempt < 2; attempt++, x10++) {
        int q = x10 - (p - 1), exact;
        uint64_t w;
        if (scale(2 * m, e, q, &w, &exact) != 0)
            return -1;
        uint64_t d = w >> 1;
        if (d >= ten_pow[p])
            continue; /* x10 was one short */
        d += (w & 1) && (!exact || (d & 1));
        if (d == ten_pow[p]) { /* rounded up to the next power of ten */
            d = ten_pow[p - 1];
            q++;
        }
        v->d = d;
        v->e10 = q;
        strip_zeros(v);
        return 0;
    }
    return -1;
}

int rd_dtoa_digits(double x, int digits, char *buf)
{
    if (!isfinite(x) || x == 0)
        return zero_or_special(x, buf);
    int p = digits < 1 ? 1 : digits > 17 ? 17 : digits;
    decimal v;
    double a = fabs(x);
    if (round_direct(a, p, &v) != 0)
        printf_digits(a, p, &v);
    int x10 = v.e10 + v.n - 1;
    return layout(signbit(x) != 0, &v, x10 < -4 || x10 >= p, buf);
}
