/*
 * test_dtoa — rd_dtoa's texts against the C library, and rd_json's against
 * jansson.
 *
 * Independent references: strtod (a correct reader) for the round trip;
 * printf("%.<p>g") for both the shortness bound (the fewest of its digit
 * counts 1..17 that round-trip) and, digit for digit, rd_dtoa_digits; and
 * json_dumps for rd_json_dumps, byte for byte.
 *
 * Doubles: 1e6 of random bit patterns (every exponent, subnormals), 1e6 of
 * random mantissas with binary exponents -70..170 (the 128-bit fast path
 * and both its edges), 1e6 of short decimals (1..17 random digits times
 * 10^-30..10^30: the shortest text is short, the digit loop runs long), and
 * the special ones: +-0, powers of two and of ten over the whole range,
 * DBL_MAX, DBL_MIN, the smallest subnormal, each with its neighbours.  The
 * full shortness scan (17 printf + strtod per number) runs on every 16th
 * random one (its cost), on every special one.
 */
#include <float.h>
#include <inttypes.h>
#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "rd_dtoa.h"
#include "rd_json.h"

static uint64_t rng_state = 0x9E3779B97F4A7C15u;

static uint64_t rng(void) /* xorshift64* */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545F4914F6CDD1Du;
}

static double from_bits(uint64_t b)
{
    double x;
    memcpy(&x, &b, sizeof x);
    return x;
}

static int same(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* printf("%.<p>g") respelled as jansson writes exponents: no '+', no
 * leading zeros. */
static void printf_g(double x, int p, char *buf, size_t size)
{
    snprintf(buf, size, "%.*g", p, x);
    char *e = strchr(buf, 'e');
    if (!e)
        return;
    char *d = e + 1, *src = d;
    if (*src == '+')
        src++;
    else if (*src == '-')
        d++, src++;
    while (*src == '0' && src[1])
        src++;
    memmove(d, src, strlen(src) + 1);
}

static long failures_roundtrip, failures_short, failures_digits;

/* The shortest round-trip length over printf's digit counts. */
static size_t printf_shortest_len(double x)
{
    char buf[64];
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, sizeof buf, "%.*g", p, x);
        if (same(strtod(buf, NULL), x))
            return strlen(buf);
    }
    return (size_t)-1; /* not reached: 17 digits always round-trip */
}

static void check_one(double x, int full_short)
{
    char text[RD_DTOA_SIZE], ref[64];
    if (!isfinite(x))
        return; /* the neighbour of DBL_MAX */
    int n = rd_dtoa_shortest(x, text);
    if (!same(strtod(text, NULL), x) || n != (int)strlen(text)) {
        if (failures_roundtrip++ < 5)
            fprintf(stderr, "round trip: %a -> %s\n", x, text);
    }
    if (full_short && (size_t)n > printf_shortest_len(x)) {
        if (failures_short++ < 5)
            fprintf(stderr, "not shortest: %a -> %s (%zu)\n", x, text, printf_shortest_len(x));
    }
    static const int ps[] = {10, 15, 17, 1, 6};
    for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) {
        rd_dtoa_digits(x, ps[i], text);
        printf_g(x, ps[i], ref, sizeof ref);
        if (strcmp(text, ref) != 0 && failures_digits++ < 5)
            fprintf(stderr, "digits %d: %a -> %s, printf %s\n", ps[i], x, text, ref);
    }
}

static void check_set(const char *name, double (*gen)(void), long count)
{
    failures_roundtrip = failures_short = failures_digits = 0;
    for (long i = 0; i < count; i++)
        check_one(gen(), i % 16 == 0);
    CHECK(failures_roundtrip == 0, "%s: %ld of %ld do not round-trip", name, failures_roundtrip,
          count);
    CHECK(failures_short == 0, "%s: %ld of %ld longer than printf's shortest", name, failures_short,
          count / 10);
    CHECK(failures_digits == 0, "%s: %ld of %ld differ from printf %%.<p>g", name, failures_digits,
          count);
}

static double gen_bits(void)
{
    double x;
    do
        x = from_bits(rng());
    while (!isfinite(x));
    return x;
}

static double gen_fast_range(void)
{
    uint64_t b = rng();
    uint64_t exp = (uint64_t)(1023 - 70 + (int)(rng() % 241)); /* 2^-70 .. 2^170 */
    return from_bits((b & 0x800FFFFFFFFFFFFFu) | exp << 52);
}

static double gen_short_decimal(void)
{
    int digits = 1 + (int)(rng() % 17), e10 = (int)(rng() % 61) - 30;
    uint64_t d = 0;
    for (int i = 0; i < digits; i++)
        d = 10 * d + rng() % 10;
    char buf[64];
    snprintf(buf, sizeof buf, "%s%" PRIu64 "e%d", rng() % 2 ? "-" : "", d, e10);
    return strtod(buf, NULL);
}

static void check_specials(void)
{
    failures_roundtrip = failures_short = failures_digits = 0;
    double base[] = {0.0, DBL_MAX, DBL_MIN, DBL_TRUE_MIN, 1.0, 0.1, 0.0765, 125.6322658, 5e-324};
    long count = 0;
    for (size_t i = 0; i < sizeof base / sizeof base[0]; i++)
        for (int s = 0; s < 2; s++, count++) {
            double x = s ? -base[i] : base[i];
            check_one(x, 1);
            check_one(nextafter(x, INFINITY), 1);
            check_one(nextafter(x, -INFINITY), 1);
        }
    for (int e = -1074; e <= 1023; e++, count++) {
        double x = ldexp(1.0, e);
        check_one(x, 1);
        check_one(nextafter(x, 0), 1);
        check_one(nextafter(x, INFINITY), 1);
    }
    for (int e = -323; e <= 308; e++, count++) {
        char buf[16];
        snprintf(buf, sizeof buf, "1e%d", e);
        double x = strtod(buf, NULL);
        check_one(x, 1);
        check_one(nextafter(x, 0), 1);
        check_one(nextafter(x, INFINITY), 1);
    }
    CHECK(failures_roundtrip + failures_short + failures_digits == 0,
          "specials (%ld): %ld round trip, %ld shortness, %ld digits failures", count,
          failures_roundtrip, failures_short, failures_digits);
    char buf[RD_DTOA_SIZE];
    CHECK(rd_dtoa_shortest(-0.0, buf) == 2 && strcmp(buf, "-0") == 0, "-0 -> %s", buf);
    CHECK(rd_dtoa_shortest(NAN, buf) == 4 && strcmp(buf, "null") == 0, "NaN -> %s", buf);
    CHECK(rd_dtoa_shortest(1e21, buf) == 4 && strcmp(buf, "1e21") == 0, "1e21 -> %s", buf);
    CHECK(rd_dtoa_shortest(0.3, buf) == 3 && strcmp(buf, "0.3") == 0, "0.3 -> %s", buf);
    CHECK(rd_dtoa_shortest(5e-324, buf) == 6 && strcmp(buf, "5e-324") == 0, "5e-324 -> %s", buf);
}

/* ---- rd_json against jansson --------------------------------------------- */

static json_t *random_value(int depth);

static json_t *random_string(void)
{
    static const char *const parts[] = {
        "a",    "mode", "\"",     "\\",           "/",
        "\n",   "\t",   "\x01",   "\x1f",         "\xc3\xa9",
        "\x7f", "",     "\b\f\r", "\xe2\x80\xa8", "segment_angle_deg"};
    char buf[128] = "";
    int k = (int)(rng() % 6);
    for (int i = 0; i < k; i++)
        strcat(buf, parts[rng() % (sizeof parts / sizeof parts[0])]);
    return json_string(buf);
}

static json_t *random_value(int depth)
{
    int kind = (int)(rng() % (depth > 3 ? 6 : 8));
    double x = rng() % 2 ? gen_fast_range() : rng() % 2 ? gen_short_decimal() : gen_bits();
    switch (kind) {
    case 0:
        return json_null();
    case 1:
        return json_boolean(rng() % 2);
    case 2:
        return json_integer((json_int_t)(rng() % 2000001) - 1000000);
    case 3:
    case 4:
        return json_real(x);
    case 5:
        return random_string();
    case 6: {
        json_t *a = json_array();
        for (int i = (int)(rng() % 8); i > 0; i--)
            json_array_append_new(a, random_value(depth + 1));
        return a;
    }
    default: {
        json_t *o = json_object();
        for (int i = (int)(rng() % 8); i > 0; i--) {
            json_t *k = random_string();
            json_object_set_new(o, json_string_value(k), random_value(depth + 1));
            json_decref(k);
        }
        return o;
    }
    }
}

static void check_json(void)
{
    long differ = 0, unequal = 0, trees = 2000;
    for (long t = 0; t < trees; t++) {
        json_t *v = json_object();
        json_object_set_new(v, "value", random_value(0));
        json_object_set_new(v, "more", random_value(1));
        static const int ps[] = {10, 15, 17};
        for (int i = 0; i < 3; i++)
            for (int sort = 0; sort < 2; sort++) {
                size_t flags =
                    JSON_COMPACT | JSON_REAL_PRECISION(ps[i]) | (sort ? JSON_SORT_KEYS : 0);
                char *want = json_dumps(v, flags), *got = rd_json_dumps(v, ps[i], sort);
                if ((!want || !got || strcmp(want, got) != 0) && differ++ < 3)
                    fprintf(stderr, "rd_json %d %d:\n  %s\njansson:\n  %s\n", ps[i], sort, got,
                            want);
                free(want);
                free(got);
            }
        /* digits 0: the shortest spelling reads back as the same values */
        char *text = rd_json_dumps(v, 0, 1);
        json_t *back = text ? json_loads(text, 0, NULL) : NULL;
        if (!back || !json_equal(back, v))
            unequal++;
        json_decref(back);
        free(text);
        json_decref(v);
    }
    CHECK(differ == 0, "%ld of %ld trees written differently from json_dumps", differ, trees * 6);
    CHECK(unequal == 0, "%ld of %ld shortest texts do not read back equal", unequal, trees);
    json_t *scalar = json_real(1.5);
    CHECK(rd_json_dumps(scalar, 10, 0) == NULL, "a bare real is not a JSON text jansson writes");
    json_decref(scalar);
}

int main(void)
{
    check_specials();
    check_set("random bits", gen_bits, 1000000);
    check_set("fast range", gen_fast_range, 1000000);
    check_set("short decimals", gen_short_decimal, 1000000);
    check_json();
    return check_done();
}
