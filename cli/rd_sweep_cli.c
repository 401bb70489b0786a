/*
 * rd_sweep_cli — `ringdyn sweep ...`: a sweep on one machine or split over
 * the tasks of a cluster array job, with the same binary (rd_sweep.h).
 *
 *   ringdyn sweep count SPEC              the number of points N
 *   ringdyn sweep scene SPEC I            the scene of point I
 *   ringdyn sweep run SPEC [--index I] [--chunks K] --out DIR
 *        runs points [I N/K, (I+1) N/K) and writes DIR/chunk-I-of-K.json
 *        (I from JOB_COMPLETION_INDEX or SLURM_ARRAY_TASK_ID when not given;
 *        K defaults to 1).  The file appears complete or not at all: it is
 *        written to a hidden temporary name in DIR and renamed.
 *   ringdyn sweep reduce DIR [--csv]      the whole table on stdout
 *   ringdyn sweep fidelity SCENE [--segments N,N..] [--rtol R,R..]
 *        [--model M,M..] [--spec] [--csv]
 *        the speed/accuracy table of one scene (rd_sweep.h, fidelity), run
 *        here; --spec prints the sweep spec instead, to run it as chunks and
 *        turn the reduced table into this one with --table FILE.
 *
 * Exit status as for `ringdyn run`: 0 ok, 2 invalid input (a 4xx error:
 * bad spec, missing chunks), 1 the run could not finish (interrupted, out of
 * memory, a file could not be written).  A point that fails is not a failure
 * of the sweep: it is a row with its error.
 */
#include "rd_sweep_cli.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rd_api.h"
#include "rd_cli.h"
#include "rd_sweep.h"

enum { EXIT_INPUT = RD_CLI_EXIT_INPUT, EXIT_RUN = RD_CLI_EXIT_RUN };

static const char usage[] =
    "usage: ringdyn sweep count SPEC\n"
    "       ringdyn sweep scene SPEC I\n"
    "       ringdyn sweep run SPEC [--index I] [--chunks K] --out DIR\n"
    "       ringdyn sweep reduce DIR [--csv]\n"
    "       ringdyn sweep fidelity SCENE [--segments N,..] [--rtol R,..] [--model M,..]\n"
    "                              [--spec] [--csv]\n"
    "       ringdyn sweep fidelity --table TABLE [--csv]\n"
    "I defaults to $JOB_COMPLETION_INDEX or $SLURM_ARRAY_TASK_ID, K to 1.\n";

/* Reads and parses the spec file ("-" for stdin) with the CLI's point limit. */
static int load_spec(const char *name, rd_sweep **sweep, rd_error *err)
{
    char *body = NULL;
    size_t len = 0;
    FILE *f = strcmp(name, "-") == 0 ? stdin : fopen(name, "rb");
    if (!f)
        return rd_error_set(err, RD_EREQUEST, "", "cannot open %s: %s", name, strerror(errno));
    int rc = rd_api_read_stream(f, RD_API_BODY_MAX, &body, &len);
    if (f != stdin)
        fclose(f);
    if (rc == RD_OK)
        rc = rd_sweep_parse(body, len, RD_SWEEP_POINTS_MAX, sweep, err);
    else
        rd_error_set(err, rc == RD_ETOOLARGE ? rc : RD_EREQUEST, "", "cannot read %s%s", name,
                     rc == RD_ETOOLARGE ? ": larger than 1 MiB" : "");
    free(body);
    return rc;
}

/* A non-negative decimal number; -1 when `text` is not one. */
static long long count_arg(const char *text)
{
    char *end;
    if (!text || !*text || *text == '-')
        return -1;
    errno = 0;
    long long v = strtoll(text, &end, 10);
    return *end || errno ? -1 : v;
}

/* The task index from the array job's environment, or -1. */
static long long env_index(void)
{
    const char *v = getenv("JOB_COMPLETION_INDEX");
    if (!v || !*v)
        v = getenv("SLURM_ARRAY_TASK_ID");
    return v && *v ? count_arg(v) : -1;
}

static int print_line(const char *text)
{
    if (!text || puts(text) == EOF || fflush(stdout) != 0) {
        fprintf(stderr, "ringdyn: cannot write the output\n");
        return EXIT_RUN;
    }
    return 0;
}

static int cmd_count(const char *spec)
{
    rd_error err;
    rd_error_init(&err);
    rd_sweep *s = NULL;
    if (load_spec(spec, &s, &err) != RD_OK)
        return rd_cli_fail(&err);
    char line[64];
    snprintf(line, sizeof line, "%zu", rd_sweep_points(s));
    rd_sweep_free(s);
    return print_line(line);
}

static int cmd_scene(const char *spec, const char *index)
{
    rd_error err;
    rd_error_init(&err);
    rd_sweep *s = NULL;
    long long i = count_arg(index);
    if (load_spec(spec, &s, &err) != RD_OK)
        return rd_cli_fail(&err);
    char *scene = NULL, *pretty = NULL;
    if (i < 0)
        rd_error_set(&err, RD_EREQUEST, "", "the point index must be a number >= 0, got %s", index);
    else
        scene = rd_sweep_point_scene(s, (size_t)i, &err);
    pretty = scene ? rd_api_json_pretty(scene) : NULL;
    int status = pretty ? print_line(pretty) : rd_cli_fail(&err);
    free(pretty);
    free(scene);
    rd_sweep_free(s);
    return status;
}

/* Runs points [first, end) into the open file `f` after the chunk head. */
static int run_points(const rd_sweep *s, size_t first, size_t end, FILE *f, rd_error *err)
{
    rd_monitor mon = {rd_cli_stop_requested, NULL};
    for (size_t i = first; i < end; i++) {
        char *row = NULL;
        int rc = rd_sweep_run_point(s, i, &mon, &row, err);
        if (rc != RD_OK)
            return rc;
        int bad = fputs(row, f) == EOF || fputs(i + 1 < end ? ",\n" : "\n", f) == EOF;
        free(row);
        if (bad)
            return rd_error_set(err, RD_EINTERNAL, "", "cannot write the chunk file: %s",
                                strerror(errno));
    }
    return RD_OK;
}

/* Writes DIR/<chunk name> through a temporary file and rename(2). */
static int write_chunk(const rd_sweep *s, size_t c, size_t k, const char *dir, rd_error *err)
{
    size_t first, end;
    if (rd_sweep_chunk_range(s, c, k, &first, &end, err) != RD_OK)
        return err->code;
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return rd_error_set(err, RD_EINTERNAL, "", "cannot create %s: %s", dir, strerror(errno));
    char *name = rd_sweep_chunk_name(c, k), *head = rd_sweep_chunk_head(s, c, k);
    size_t size = strlen(dir) + 200;
    char *path = malloc(size), *tmp = malloc(size);
    FILE *f = NULL;
    int rc =
        name && head && path && tmp ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory");
    if (rc == RD_OK) {
        snprintf(path, size, "%s/%s", dir, name);
        /* host and pid: in containers every pid may be 1, and a replaced
         * pod can overlap its predecessor on another node */
        char host[64] = "";
        gethostname(host, sizeof host - 1);
        host[strcspn(host, "/")] = '\0';
        snprintf(tmp, size, "%s/.%s.%.63s.%ld.tmp", dir, name, host, (long)getpid());
        f = fopen(tmp, "wb");
        if (!f || fputs(head, f) == EOF)
            rc = rd_error_set(err, RD_EINTERNAL, "", "cannot write %s: %s", tmp, strerror(errno));
    }
    if (rc == RD_OK)
        rc = run_points(s, first, end, f, err);
    if (rc == RD_OK && fputs("]}\n", f) == EOF)
        rc = rd_error_set(err, RD_EINTERNAL, "", "cannot write %s: %s", tmp, strerror(errno));
    if (f && fclose(f) != 0 && rc == RD_OK)
        rc = rd_error_set(err, RD_EINTERNAL, "", "cannot write %s: %s", tmp, strerror(errno));
    if (rc == RD_OK && rename(tmp, path) != 0)
        rc = rd_error_set(err, RD_EINTERNAL, "", "cannot rename %s to %s: %s", tmp, path,
                          strerror(errno));
    if (rc != RD_OK && f)
        remove(tmp);
    free(name);
    free(head);
    free(path);
    free(tmp);
    return rc;
}

static int cmd_run(int argc, char **argv)
{
    const char *spec = NULL, *dir = NULL;
    long long index = -2, chunks = 1;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--index") == 0 && i + 1 < argc)
            index = count_arg(argv[++i]);
        else if (strcmp(argv[i], "--chunks") == 0 && i + 1 < argc)
            chunks = count_arg(argv[++i]);
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            dir = argv[++i];
        else if (!spec && (argv[i][0] != '-' || strcmp(argv[i], "-") == 0))
            spec = argv[i];
        else
            index = -3;
    }
    if (!spec || !dir || index == -3) {
        fputs(usage, stderr);
        return EXIT_INPUT;
    }
    rd_error err;
    rd_error_init(&err);
    if (index == -1 || chunks < 1) {
        rd_error_set(&err, RD_EREQUEST, "",
                     "--index and --chunks must be whole numbers (index "
                     ">= 0, chunks >= 1)");
        return rd_cli_fail(&err);
    }
    if (index == -2)
        index = chunks == 1 && env_index() < 0 ? 0 : env_index();
    if (index < 0) {
        rd_error_set(&err, RD_EREQUEST, "",
                     "no chunk index: give --index I, or set "
                     "JOB_COMPLETION_INDEX or SLURM_ARRAY_TASK_ID");
        return rd_cli_fail(&err);
    }
    rd_sweep *s = NULL;
    if (load_spec(spec, &s, &err) != RD_OK)
        return rd_cli_fail(&err);
    rd_cli_catch_signals(1);
    int rc = write_chunk(s, (size_t)index, (size_t)chunks, dir, &err);
    rd_sweep_free(s);
    return rc == RD_OK ? 0 : rd_cli_fail(&err);
}

static int cmd_reduce(int argc, char **argv)
{
    const char *dir = NULL;
    int csv = 0, bad = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0)
            csv = 1;
        else if (!dir && argv[i][0] != '-')
            dir = argv[i];
        else
            bad = 1;
    }
    if (!dir || bad) {
        fputs(usage, stderr);
        return EXIT_INPUT;
    }
    rd_error err;
    rd_error_init(&err);
    return rd_sweep_reduce(dir, csv, stdout, &err) == RD_OK ? 0 : rd_cli_fail(&err);
}

/* Reads a whole file ("-": stdin) of at most `max` bytes. */
static int read_all(const char *name, size_t max, char **buf, size_t *len, rd_error *err)
{
    FILE *f = strcmp(name, "-") == 0 ? stdin : fopen(name, "rb");
    *buf = NULL;
    if (!f)
        return rd_error_set(err, RD_EREQUEST, "", "cannot open %s: %s", name, strerror(errno));
    int rc = rd_api_read_stream(f, max, buf, len);
    if (f != stdin)
        fclose(f);
    return rc == RD_OK
               ? RD_OK
               : rd_error_set(err, rc == RD_ENOMEM ? rc : RD_EREQUEST, "", "cannot read %s", name);
}

/* Splits a comma list in place: up to `max` items into items[]; numbers
 * too when nums != NULL.  Returns the count, or 0 on a bad list. */
static size_t split_list(char *text, const char **items, double *nums, size_t max)
{
    size_t n = 0;
    for (char *tok = strtok(text, ","); tok; tok = strtok(NULL, ",")) {
        char *end;
        if (n == max)
            return 0;
        items[n] = tok;
        if (nums) {
            nums[n] = strtod(tok, &end);
            if (*end || end == tok)
                return 0;
        }
        n++;
    }
    return n;
}

/* Runs every point of a sweep here and returns its table. */
static char *run_all(const rd_sweep *s, rd_error *err)
{
    size_t n = rd_sweep_points(s);
    char **rows = calloc(n, sizeof *rows), *table = NULL;
    rd_monitor mon = {rd_cli_stop_requested, NULL};
    int rc = rows ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory");
    for (size_t i = 0; rc == RD_OK && i < n; i++)
        rc = rd_sweep_run_point(s, i, &mon, &rows[i], err);
    if (rc == RD_OK)
        table = rd_sweep_table_json(s, rows, n, err);
    for (size_t i = 0; rows && i < n; i++)
        free(rows[i]);
    free(rows);
    return table;
}

/* The fidelity table, printed as JSON or CSV. */
static int print_fidelity(const char *table, int csv, rd_error *err)
{
    char *fid = rd_sweep_fidelity_table(table, err);
    char *text = fid && csv ? rd_sweep_csv_from_table(fid, err) : NULL;
    int status = !fid || (csv && !text) ? rd_cli_fail(err) : 0;
    if (status == 0 && (fputs(csv ? text : fid, stdout) == EOF || (!csv && puts("") == EOF) ||
                        fflush(stdout) != 0))
        status = print_line(NULL);
    free(text);
    free(fid);
    return status;
}

enum { LIST_MAX = 64 };

static int cmd_fidelity(int argc, char **argv)
{
    const char *scene = NULL, *table = NULL, *items[LIST_MAX], *models[LIST_MAX];
    double seg[LIST_MAX], rtol[LIST_MAX];
    rd_sweep_fidelity_opts o = {0};
    int csv = 0, spec_only = 0, bad = 0;
    for (int i = 0; i < argc && !bad; i++) {
        const char *a = argv[i];
        int more = i + 1 < argc;
        if (strcmp(a, "--csv") == 0)
            csv = 1;
        else if (strcmp(a, "--spec") == 0)
            spec_only = 1;
        else if (strcmp(a, "--table") == 0 && more)
            table = argv[++i];
        else if (strcmp(a, "--segments") == 0 && more)
            bad = (o.n_segments = split_list(argv[++i], items, seg, LIST_MAX)) == 0;
        else if (strcmp(a, "--rtol") == 0 && more)
            bad = (o.n_rtol = split_list(argv[++i], items, rtol, LIST_MAX)) == 0;
        else if (strcmp(a, "--model") == 0 && more)
            bad = (o.n_models = split_list(argv[++i], models, NULL, LIST_MAX)) == 0;
        else if (!scene && (a[0] != '-' || strcmp(a, "-") == 0))
            scene = a;
        else
            bad = 1;
    }
    if (bad || !!scene == !!table) {
        fputs(usage, stderr);
        return EXIT_INPUT;
    }
    o.segments = o.n_segments ? seg : NULL;
    o.rtol = o.n_rtol ? rtol : NULL;
    o.models = o.n_models ? models : NULL;
    rd_error err;
    rd_error_init(&err);
    char *body = NULL, *spec = NULL, *result = NULL;
    size_t len;
    rd_sweep *s = NULL;
    int status = 0;
    if (read_all(table ? table : scene, table ? (size_t)1 << 30 : RD_API_BODY_MAX, &body, &len,
                 &err) != RD_OK) {
        status = rd_cli_fail(&err);
    } else if (table) {
        status = print_fidelity(body, csv, &err);
    } else if (!(spec = rd_sweep_fidelity_spec(body, len, &o, &err)) ||
               rd_sweep_parse(spec, strlen(spec), RD_SWEEP_POINTS_MAX, &s, &err) != RD_OK) {
        status = rd_cli_fail(&err);
    } else if (spec_only) {
        result = rd_api_json_pretty(spec);
        status = print_line(result);
    } else {
        rd_cli_catch_signals(0);
        result = run_all(s, &err);
        status = result ? print_fidelity(result, csv, &err) : rd_cli_fail(&err);
    }
    free(result);
    free(spec);
    free(body);
    rd_sweep_free(s);
    return status;
}

int rd_sweep_cli_main(int argc, char **argv)
{
    const char *cmd = argc > 0 ? argv[0] : "";
    if (argc == 1 && (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0)) {
        fputs(usage, stdout);
        return 0;
    }
    if (strcmp(cmd, "count") == 0 && argc == 2)
        return cmd_count(argv[1]);
    if (strcmp(cmd, "scene") == 0 && argc == 3)
        return cmd_scene(argv[1], argv[2]);
    if (strcmp(cmd, "run") == 0)
        return cmd_run(argc - 1, argv + 1);
    if (strcmp(cmd, "reduce") == 0)
        return cmd_reduce(argc - 1, argv + 1);
    if (strcmp(cmd, "fidelity") == 0)
        return cmd_fidelity(argc - 1, argv + 1);
    fputs(usage, stderr);
    return EXIT_INPUT;
}
