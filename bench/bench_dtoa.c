/*
 * bench_dtoa — the cost of writing one JSON real, rd_dtoa against the C
 * library's printf (what jansson's json_dumps calls), and of writing the
 * default modal result (n = 20, 6 modes, error estimate) with rd_json
 * against json_dumps.
 *
 *   bench_dtoa [REPEATS]     (default 15; medians, ns per number / µs per text)
 *
 * Numbers: 100000 doubles spread like a result's (mantissas at random,
 * magnitudes 1e-12 .. 1e12), one pass each per repeat.  The ratios are
 * what matters: the machine is shared.
 */
#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rd_api.h"
#include "rd_dtoa.h"
#include "rd_json.h"

#define COUNT 100000

static double values[COUNT];
static volatile size_t sink; /* keeps the writes */

static double per_number_ns(int which, int repeats)
{
    double t[64];
    char buf[64];
    for (int r = 0; r < repeats; r++) {
        double t0 = bench_now();
        size_t total = 0;
        for (int i = 0; i < COUNT; i++) {
            switch (which) {
            case 0:
                total += (size_t)rd_dtoa_digits(values[i], 10, buf);
                break;
            case 1:
                total += (size_t)snprintf(buf, sizeof buf, "%.10g", values[i]);
                break;
            case 2:
                total += (size_t)rd_dtoa_shortest(values[i], buf);
                break;
            default:
                total += (size_t)snprintf(buf, sizeof buf, "%.17g", values[i]);
                break;
            }
        }
        sink = total;
        t[r] = (bench_now() - t0) / COUNT * 1e9;
    }
    return bench_median(t, repeats);
}

static double dump_us(const json_t *result, int mine, int repeats)
{
    double t[64];
    for (int r = 0; r < repeats; r++) {
        double t0 = bench_now();
        for (int k = 0; k < 100; k++) {
            char *text = mine ? rd_json_dumps(result, 10, 0)
                              : json_dumps(result, JSON_COMPACT | JSON_REAL_PRECISION(10));
            sink = strlen(text);
            free(text);
        }
        t[r] = (bench_now() - t0) / 100 * 1e6;
    }
    return bench_median(t, repeats);
}

int main(int argc, char **argv)
{
    int repeats = argc > 1 ? atoi(argv[1]) : 15;
    if (repeats < 1 || repeats > 64)
        repeats = 15;
    uint64_t s = 88172645463325252u;
    for (int i = 0; i < COUNT; i++) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        double mant = 1.0 + (double)(s >> 11) * 0x1p-53;
        values[i] = (s & 1 ? -1 : 1) * mant * pow(10.0, (double)((int)(s >> 3 & 31) - 12) * 0.75);
    }
    double mine10 = per_number_ns(0, repeats), libc10 = per_number_ns(1, repeats);
    double mine_short = per_number_ns(2, repeats), libc17 = per_number_ns(3, repeats);
    printf("per number: rd_dtoa_digits(10) %.0f ns, printf %%.10g %.0f ns (x%.1f); "
           "rd_dtoa_shortest %.0f ns, printf %%.17g %.0f ns (x%.1f)\n",
           mine10, libc10, libc10 / mine10, mine_short, libc17, libc17 / mine_short);

    char *text = NULL;
    rd_error err;
    rd_error_init(&err);
    rd_scene *scene = NULL;
    static const char body[] = "{\"analysis\":\"modal\"}";
    if (rd_scene_parse(body, strlen(body), &scene, &err) != RD_OK ||
        rd_scene_run(scene, NULL, &text, &err) != RD_OK) {
        fprintf(stderr, "bench_dtoa: the default modal job failed: %s\n", err.message);
        return 1;
    }
    json_t *result = json_loads(text, 0, NULL);
    double mine = dump_us(result, 1, repeats), theirs = dump_us(result, 0, repeats);
    printf("default modal result (%zu bytes): rd_json_dumps %.1f us, json_dumps %.1f us (x%.1f)\n",
           strlen(text), mine, theirs, theirs / mine);
    json_decref(result);
    free(text);
    rd_scene_free(scene);
    return 0;
}
