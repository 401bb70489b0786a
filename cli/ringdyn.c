/*
 * ringdyn — the command-line face of the api layer: the same rd_scene_parse /
 * rd_scene_run / rd_api_* calls as the server, without HTTP.
 *
 *   ringdyn run [--csv] SCENE     result JSON (or the main table as CSV) on stdout
 *   ringdyn check SCENE           the validated, defaults-filled scene on stdout
 *   ringdyn sweep ...             sweeps: count, scene, run (a chunk), reduce
 *                                 (rd_sweep_cli.c)
 *   ringdyn openapi TEMPLATE      the OpenAPI document the server serves, from
 *                                 its template (server/openapi.json)
 *   ringdyn --version | --help
 *
 * SCENE is a file or "-" for stdin.  Errors go to stderr as the same error
 * JSON the server answers with.  Exit status: 0 success, 2 invalid input
 * (anything the contract answers with a 4xx), 1 the run failed (did not
 * converge, cancelled by Ctrl-C, out of memory).
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_api.h"
#include "rd_cli.h"
#include "rd_sweep_cli.h"

enum { EXIT_INPUT = RD_CLI_EXIT_INPUT, EXIT_RUN = RD_CLI_EXIT_RUN };

static const char usage[] =
    "usage: ringdyn run [--csv] SCENE   run a scene, print the result JSON (or CSV)\n"
    "       ringdyn check SCENE         validate a scene, print it with defaults filled\n"
    "       ringdyn calibrate SPEC      fit a scene's parameters to measurements (a calibration;\n"
    "                                   \"analysis\" may be left out), print the result JSON\n"
    "       ringdyn sweep count|scene|run|reduce ...   sweeps (ringdyn sweep --help)\n"
    "       ringdyn openapi TEMPLATE    print the OpenAPI document built on TEMPLATE\n"
    "       ringdyn --version | --help\n"
    "SCENE is a JSON file, or - for stdin.  Exit status: 0 ok, 2 invalid input, 1 run failed.\n";

/* Reads the whole scene (at most RD_API_BODY_MAX bytes) from a file or stdin. */
static int read_scene(const char *name, char **buf, size_t *len, rd_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *f = strcmp(name, "-") == 0 ? stdin : fopen(name, "rb");
    if (!f)
        return rd_error_set(err, RD_EREQUEST, "", "cannot open %s: %s", name, strerror(errno));
    int rc = rd_api_read_stream(f, RD_API_BODY_MAX, buf, len);
    if (f != stdin)
        fclose(f);
    switch (rc) {
    case RD_OK:
        return RD_OK;
    case RD_ENOMEM:
        return rd_error_set(err, rc, "", "out of memory while reading %s", name);
    case RD_ETOOLARGE:
        return rd_error_set(err, rc, "", "%s is larger than the limit of %d bytes", name,
                            RD_API_BODY_MAX);
    default:
        return rd_error_set(err, RD_EREQUEST, "", "cannot read %s", name);
    }
}

/* `run`, `check` and `calibrate` (`as`: the analysis a body without one
 * is taken as): parse, then print the echo (check) or run and print
 * the result as pretty JSON or CSV.  A run stopped by a signal prints the
 * partial result it returned (a lift run's whole cycles), then fails. */
static int command(const char *file, int run, int csv, const char *as)
{
    rd_error err, stopped;
    rd_scene *scene = NULL;
    char *body = NULL, *result = NULL, *text = NULL;
    rd_result_doc *doc = NULL;
    size_t len;
    rd_monitor mon = {rd_cli_stop_requested, NULL};
    int status = 0;

    rd_error_init(&err);
    rd_error_init(&stopped);
    if (read_scene(file, &body, &len, &err) != RD_OK ||
        rd_scene_parse_report_as(body, len, as, &scene, &err, NULL) != RD_OK) {
        status = rd_cli_fail(&err);
        goto out;
    }
    if (!run) {
        result = rd_scene_to_json(scene);
    } else {
        rd_cli_catch_signals(0);
        if (rd_scene_run_doc(scene, &mon, &doc, &err) != RD_OK) {
            stopped = err;
            if (!doc) {
                status = rd_cli_fail(&err);
                goto out;
            }
            rd_error_init(&err); /* a stopped run's partial result is written, then its error */
        }
        /* the CSV straight from the result document, no JSON text between */
        result = csv ? rd_result_doc_csv(doc, &err) : rd_result_doc_json(doc);
    }
    if (!result) {
        if (err.code == RD_OK)
            rd_error_set(&err, RD_ENOMEM, "", "out of memory while writing the output");
        status = rd_cli_fail(&err);
        goto out;
    }
    /* --csv comes only with run: result is then the CSV text already */
    text = csv ? result : rd_api_json_pretty(result);
    if (text == result)
        result = NULL;
    if (!text) {
        rd_error_set(&err, RD_ENOMEM, "", "out of memory while writing the output");
        status = rd_cli_fail(&err);
        goto out;
    }
    fputs(text, stdout);
    if (!csv)
        fputc('\n', stdout);
    if (fflush(stdout) != 0) {
        fprintf(stderr, "ringdyn: cannot write the output: %s\n", strerror(errno));
        status = EXIT_RUN;
    }
    if (stopped.code != RD_OK)
        status = rd_cli_fail(&stopped);
out:
    free(text);
    free(result);
    free(body);
    rd_result_doc_free(doc);
    rd_scene_free(scene);
    return status;
}

/* `openapi`: the scene schemas written into the template, as the server
 * does (its @RINGDYN_VERSION@ becomes this version). */
static int openapi(const char *file)
{
    rd_error err;
    char *template = NULL, *doc = NULL;
    size_t len;
    rd_error_init(&err);
    if (read_scene(file, &template, &len, &err) == RD_OK)
        doc = rd_api_openapi_json(template, &err);
    free(template);
    if (!doc)
        return rd_cli_fail(&err);
    const char *at = strstr(doc, "@RINGDYN_VERSION@");
    if (at)
        printf("%.*s%s%s\n", (int)(at - doc), doc, rd_api_version(), at + 17);
    else
        printf("%s\n", doc);
    free(doc);
    return 0;
}

int main(int argc, char **argv)
{
    const char *file = NULL;
    int csv = 0;

    if (argc == 2 && strcmp(argv[1], "--version") == 0) {
        printf("ringdyn %s\n", rd_api_version());
        return 0;
    }
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        fputs(usage, stdout);
        return 0;
    }
    if (argc >= 2 && strcmp(argv[1], "sweep") == 0)
        return rd_sweep_cli_main(argc - 2, argv + 2);
    if (argc == 3 && strcmp(argv[1], "openapi") == 0)
        return openapi(argv[2]);
    if (argc == 3 && strcmp(argv[1], "calibrate") == 0)
        return command(argv[2], 1, 0, "calibration");
    if (argc < 3 || (strcmp(argv[1], "run") != 0 && strcmp(argv[1], "check") != 0))
        goto usage;
    int run = strcmp(argv[1], "run") == 0;
    for (int i = 2; i < argc; i++) {
        if (run && strcmp(argv[i], "--csv") == 0)
            csv = 1;
        else if (!file && (argv[i][0] != '-' || strcmp(argv[i], "-") == 0))
            file = argv[i];
        else
            goto usage;
    }
    if (!file)
        goto usage;
    return command(file, run, csv, NULL);
usage:
    fputs(usage, stderr);
    return EXIT_INPUT;
}
