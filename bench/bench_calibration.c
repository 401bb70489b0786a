/*
 * bench_calibration — the cost of a calibration (issue 42: the ring pack
 * fitted to blow-by at 4 operating points in <= 60 runs and <= 10 s): runs,
 * evaluations and wall time of the shipped example over repetitions (median,
 * min and max: the machine is shared), with 1 thread and with the machine's
 * processors, and the mean wall time of one of its scene runs.
 *
 *   bench_calibration EXAMPLES_DIR [--reps N]
 */
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rd_api.h"

static int run_once(json_t *spec, int threads, double *wall, long long *runs, long long *evals)
{
    json_object_set_new(spec, "numerics", json_pack("{s:i}", "threads", threads));
    char *text = json_dumps(spec, JSON_COMPACT | JSON_REAL_PRECISION(17)), *out = NULL;
    rd_scene *s = NULL;
    rd_error err;
    rd_error_init(&err);
    double t0 = bench_now();
    int rc = rd_scene_parse(text, strlen(text), &s, &err);
    if (rc == RD_OK)
        rc = rd_scene_run(s, NULL, &out, &err);
    *wall = bench_now() - t0;
    json_t *r = out ? json_loads(out, 0, NULL) : NULL;
    *runs = json_integer_value(json_object_get(r, "runs"));
    *evals = json_integer_value(json_object_get(json_object_get(r, "numerics"), "evaluations"));
    if (rc != RD_OK)
        fprintf(stderr, "bench_calibration: %s %s\n", err.path, err.message);
    json_decref(r);
    free(out);
    free(text);
    rd_scene_free(s);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_calibration EXAMPLES_DIR [--reps N]\n");
        return 2;
    }
    int reps = argc > 3 && strcmp(argv[2], "--reps") == 0 ? atoi(argv[3]) : 5;
    reps = reps < 1 ? 1 : reps > 50 ? 50 : reps;
    char path[1024];
    snprintf(path, sizeof path, "%s/calibration_ringpack_blowby.json", argv[1]);
    json_t *spec = json_load_file(path, 0, NULL);
    if (!spec) {
        fprintf(stderr, "bench_calibration: cannot read %s\n", path);
        return 2;
    }
    printf("calibration_ringpack_blowby (blow-by at 4 operating points), %d repetitions\n", reps);
    printf("threads   runs  evaluations   wall median   min      max      per run\n");
    const int threads[2] = {1, 0};
    for (int t = 0; t < 2; t++) {
        double w[50];
        long long runs = 0, evals = 0;
        for (int k = 0; k < reps; k++)
            if (run_once(spec, threads[t], &w[k], &runs, &evals) != RD_OK)
                return 1;
        double med = bench_median(w, reps);
        char per[32] = "-";
        if (threads[t])
            snprintf(per, sizeof per, "%.1f ms", 1e3 * med / (double)runs);
        printf("%-9s %4lld  %11lld   %8.3f s  %6.3f  %6.3f   %s\n", threads[t] ? "1" : "all", runs,
               evals, med, w[0], w[reps - 1], per);
    }
    json_decref(spec);
    return 0;
}
