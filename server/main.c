/*
 * ringdyn-server — command line, signals and the order of start and stop.
 *
 *   ringdyn-server --port N [--host 127.0.0.1] [--static DIR] [--examples DIR]
 *                  [--threads N] [--queue N] [--job-timeout S] [--keep-jobs N]
 *                  [--allow-host NAME]... [--token-file FILE]
 *
 * Binds 127.0.0.1 unless --host says otherwise; --port 0 takes a free port.
 * Prints one line "ringdyn-server listening on http://HOST:PORT" to stdout
 * once it accepts connections (scripts and tests read the port from it).
 *
 * SIGINT and SIGTERM are blocked in every thread and taken by sigwait() in
 * main, so the shutdown runs as ordinary code: stop accepting, end queued
 * jobs `interrupted`, give running ones STOP_WAIT_S to stop (what finishes
 * is stored; the rest end `interrupted`, which releases requests waiting on
 * them with a final job), let the requests in progress send their answers
 * (at most DRAIN_S), close the connections, join the workers, close the
 * store, exit 0.
 */
#define _XOPEN_SOURCE 700

#include <errno.h>
#include <math.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rd_api.h"
#include "rd_http.h"
#include "rd_jobs.h"
#include "rd_metrics.h"
#include "rd_store.h"
#include "rd_sweep.h"
#include "rd_sweep_slurm.h"
#include "rd_sweeps.h"

/* --allow-host may be given this many times. */
#define ALLOW_HOSTS_MAX 32
/* A token shorter than this is refused: it must not be guessable. */
#define TOKEN_MIN 16
#define TOKEN_MAX 4096

/* At shutdown: how long running jobs may take to stop on their own (a run
 * that ends in time keeps its result), then how long answers still being
 * sent may take; together under 1 s. */
#define STOP_WAIT_S 0.4
#define DRAIN_S     0.4
/* Sweeps queued or running at once, and finished sweeps kept (memory and store). */
#define SWEEPS_QUEUE_MAX 8
#define SWEEPS_KEEP_MAX  32

struct options {
    const char *host;
    long port; /* -1: not given */
    const char *static_dir;
    const char *examples_dir;
    long threads;
    long queue;
    double job_timeout;
    long keep_jobs;
    long keep_mb;
    double keep_days;
    const char *data_dir;
    rd_http_limits limits;
    const char *allow_hosts[ALLOW_HOSTS_MAX];
    int n_allow_hosts;
    const char *token_file;
    long sweep_max_points;
    /* --sweep-executor slurm (docs/cluster.md): 0 local, 1 slurm */
    int sweep_slurm;
    const char *sweep_shared_dir, *sweep_ringdyn, *sweep_slurm_script;
    long sweep_slurm_min_points; /* -1: above --sweep-max-points only */
    long sweep_slurm_tasks, sweep_slurm_max_running;
};

static void usage(FILE *f)
{
    fprintf(
        f,
        "usage: ringdyn-server --port N [options]\n"
        "  --port N          TCP port, 0 for any free port (required)\n"
        "  --host ADDR       address to bind (default 127.0.0.1; 0.0.0.0 for all interfaces)\n"
        "  --static DIR      serve the web page from DIR at / and /static/\n"
        "  --examples DIR    example scenes (*.json) for /api/v1/examples\n"
        "  --threads N       worker threads running jobs (default 2, 1..64)\n"
        "  --queue N         jobs that may wait for a worker (default 32, 1..10000)\n"
        "  --job-timeout S   run time limit per job in seconds (default 120)\n"
        "  --keep-jobs N     finished jobs kept for GET (default 256, 1..100000)\n"
        "  --keep-mb N       and at most N MiB of their results (default 512, 1..65536;\n"
        "                    the newest finished job is always kept)\n"
        "  --keep-days D     and none finished more than D days ago (default 30; 0: no limit)\n"
        "  --data DIR        the job store (SQLite, WAL) lives in DIR/jobs.sqlite3; default\n"
        "                    $XDG_STATE_HOME/ringdyn or ~/.local/state/ringdyn; ':memory:'\n"
        "                    keeps nothing across restarts.  Finished jobs survive a restart;\n"
        "                    jobs queued or running when the server stopped end 'interrupted'\n"
        "  --sweep-max-points N  runs (points x over values) a sweep may have (default 10000,\n"
        "                    1..1000000); a larger one is refused with the cluster path\n"
        "                    (ringdyn sweep run --chunks K), unless an executor takes it:\n"
        "  --sweep-executor local|slurm  where sweeps above --sweep-max-points run\n"
        "                    (default local: they are refused).  slurm: as one job array\n"
        "                    of SCRIPT tasks (sbatch, squeue, scancel, scontrol from PATH;\n"
        "                    SLURM_CONF as for them), the rows read from their chunk files:\n"
        "  --sweep-shared-dir DIR  a directory every node sees (required with slurm)\n"
        "  --sweep-slurm-script SCRIPT  deploy/slurm-sweep.sh, the same path on every node\n"
        "                    (required with slurm)\n"
        "  --sweep-ringdyn PATH  the ringdyn binary the tasks run (default: the ringdyn\n"
        "                    beside ringdyn-server, or ../cli/ringdyn in a build tree)\n"
        "  --sweep-slurm-min-points N  also sweeps of at least N runs go to Slurm\n"
        "                    (0: every sweep; default: only those above --sweep-max-points)\n"
        "  --sweep-slurm-tasks K  array tasks (= chunks) per sweep (default 16, 1..100000)\n"
        "  --sweep-slurm-max-running P  at most P tasks of a sweep at once (--array=...%%P;\n"
        "                    default: no limit)\n"
        "                    Sweeps run on --threads workers of their own; finished ones are "
        "stored\n"
        "connections (libmicrohttpd's epoll event loop; an open connection holds no thread):\n"
        "  --http-threads N  event-loop threads (default 4, 1..64)\n"
        "  --max-connections N  open connections in all (default 1000, 1..100000);\n"
        "                    more are closed at once when accepted\n"
        "  --max-per-ip N    open connections from one client address (default 64, 1..100000)\n"
        "  --request-deadline S  a request's header and body must arrive within S seconds of\n"
        "                    the connection's start or of the previous answer (default 10,\n"
        "                    0.1..3600); a slower one is closed without an answer.  An idle\n"
        "                    keep-alive connection is closed after S as well\n"
        "  --idle-timeout S  a connection with no traffic at all is closed after S seconds,\n"
        "                    also while an answer is being sent (default 30, 1..3600)\n"
        "access:\n"
        "  --allow-host NAME serve requests whose Host header names NAME (any port); repeatable.\n"
        "                    127.0.0.1, localhost, [::1] and the bound address are always\n"
        "                    served; any other Host gets 403 (DNS rebinding guard)\n"
        "  --token-file FILE require 'Authorization: Bearer TOKEN' on /api/v1/jobs*,\n"
        "                    /api/v1/examples* and /metrics; TOKEN is the file's first line\n"
        "                    (16..4096 printable characters).  Required with a --host that\n"
        "                    is not a loopback address\n");
}

static int parse_long(const char *s, long min, long max, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < min || v > max)
        return 0;
    *out = v;
    return 1;
}

/* "--name" of "--name value" or "--name=value": `arg` up to `name_len`. */
#define IS(name) (name_len == strlen(name) && strncmp(arg, name, name_len) == 0)

/* The connection options: 1 taken, 0 a bad value, -1 not one of them. */
static int set_limit_option(struct options *o, const char *arg, size_t name_len, const char *value)
{
    long v;
    int ok;
    if (IS("--http-threads")) {
        if ((ok = parse_long(value, 1, 64, &v)))
            o->limits.threads = (int)v;
    } else if (IS("--max-connections")) {
        if ((ok = parse_long(value, 1, 100000, &v)))
            o->limits.connections_max = (int)v;
    } else if (IS("--max-per-ip")) {
        if ((ok = parse_long(value, 1, 100000, &v)))
            o->limits.per_ip_max = (int)v;
    } else if (IS("--idle-timeout")) {
        if ((ok = parse_long(value, 1, 3600, &v)))
            o->limits.idle_timeout_s = (int)v;
    } else if (IS("--request-deadline")) {
        char *end;
        double d = strtod(value, &end);
        ok = end != value && !*end && d >= 0.1 && d <= 3600;
        if (ok)
            o->limits.request_deadline_s = d;
    } else {
        return -1;
    }
    return ok;
}

/* The sweep executor's options: 1 taken, 0 a bad value, -1 not one of them. */
static int set_sweep_option(struct options *o, const char *arg, size_t name_len, const char *value)
{
    int ok = 1;
    if (IS("--sweep-executor")) {
        ok = strcmp(value, "local") == 0 || strcmp(value, "slurm") == 0;
        o->sweep_slurm = strcmp(value, "slurm") == 0;
    } else if (IS("--sweep-shared-dir"))
        o->sweep_shared_dir = value;
    else if (IS("--sweep-ringdyn"))
        o->sweep_ringdyn = value;
    else if (IS("--sweep-slurm-script"))
        o->sweep_slurm_script = value;
    else if (IS("--sweep-slurm-min-points"))
        ok = parse_long(value, 0, RD_SWEEP_POINTS_MAX, &o->sweep_slurm_min_points);
    else if (IS("--sweep-slurm-tasks"))
        ok = parse_long(value, 1, 100000, &o->sweep_slurm_tasks);
    else if (IS("--sweep-slurm-max-running"))
        ok = parse_long(value, 1, 100000, &o->sweep_slurm_max_running);
    else
        return -1;
    return ok;
}

/* Every other option: 1 taken, 0 a bad value, -1 unknown. */
static int set_option(struct options *o, const char *arg, size_t name_len, const char *value)
{
    char *end;
    int ok = 1;
    if (IS("--host"))
        o->host = value;
    else if (IS("--port"))
        ok = parse_long(value, 0, 65535, &o->port);
    else if (IS("--static"))
        o->static_dir = value;
    else if (IS("--examples"))
        o->examples_dir = value;
    else if (IS("--threads"))
        ok = parse_long(value, 1, 64, &o->threads);
    else if (IS("--queue"))
        ok = parse_long(value, 1, 10000, &o->queue);
    else if (IS("--keep-jobs"))
        ok = parse_long(value, 1, 100000, &o->keep_jobs);
    else if (IS("--sweep-max-points"))
        ok = parse_long(value, 1, RD_SWEEP_POINTS_MAX, &o->sweep_max_points);
    else if (IS("--allow-host")) {
        ok = o->n_allow_hosts < ALLOW_HOSTS_MAX;
        if (ok)
            o->allow_hosts[o->n_allow_hosts++] = value;
    } else if (IS("--token-file"))
        o->token_file = value;
    else if (IS("--data"))
        o->data_dir = value;
    else if (IS("--keep-days")) {
        o->keep_days = strtod(value, &end);
        ok = end != value && !*end && o->keep_days >= 0 && o->keep_days <= 36500;
    } else if (IS("--keep-mb"))
        ok = parse_long(value, 1, 65536, &o->keep_mb);
    else if (IS("--job-timeout")) {
        o->job_timeout = strtod(value, &end);
        ok = end != value && !*end && o->job_timeout > 0 && o->job_timeout <= 86400;
    } else if ((ok = set_limit_option(o, arg, name_len, value)) < 0)
        return set_sweep_option(o, arg, name_len, value);
    return ok;
}
#undef IS

/* Accepts "--name value" and "--name=value".  Returns 0 on success, or
 * prints what is wrong and returns -1. */
static int parse_options(int argc, char **argv, struct options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            exit(0);
        }
        if (strncmp(arg, "--", 2) != 0) {
            fprintf(stderr, "ringdyn-server: unexpected argument '%s'\n", arg);
            return -1;
        }
        const char *eq = strchr(arg, '=');
        size_t name_len = eq ? (size_t)(eq - arg) : strlen(arg);
        const char *value = eq ? eq + 1 : (i + 1 < argc ? argv[++i] : NULL);
        if (!value) {
            fprintf(stderr, "ringdyn-server: %s needs a value\n", arg);
            return -1;
        }
        int ok = set_option(o, arg, name_len, value);
        if (ok < 0) {
            fprintf(stderr, "ringdyn-server: unknown option '%.*s'\n", (int)name_len, arg);
            return -1;
        }
        if (!ok) {
            fprintf(stderr, "ringdyn-server: bad value '%s' for %.*s\n", value, (int)name_len, arg);
            return -1;
        }
    }
    if (o->port < 0) {
        fprintf(stderr, "ringdyn-server: --port is required\n");
        return -1;
    }
    return 0;
}

/* --data's default: $XDG_STATE_HOME/ringdyn, else ~/.local/state/ringdyn
 * (the XDG base directory rules), in buf; NULL without either variable. */
static const char *default_data_dir(char *buf, size_t n)
{
    const char *state = getenv("XDG_STATE_HOME");
    const char *home = getenv("HOME");
    int w;
    if (state && state[0] == '/')
        w = snprintf(buf, n, "%s/ringdyn", state);
    else if (home && home[0])
        w = snprintf(buf, n, "%s/.local/state/ringdyn", home);
    else
        return NULL;
    return w > 0 && (size_t)w < n ? buf : NULL;
}

/* The token: the first line of `path`, without trailing blanks.  NULL after
 * printing why on stderr. */
static char *read_token(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "ringdyn-server: --token-file %s: %s\n", path, strerror(errno));
        return NULL;
    }
    char *line = calloc(1, TOKEN_MAX + 2);
    if (line && !fgets(line, TOKEN_MAX + 2, f))
        line[0] = '\0';
    fclose(f);
    if (!line) {
        fprintf(stderr, "ringdyn-server: out of memory\n");
        return NULL;
    }
    size_t n = strlen(line);
    while (n > 0 && (line[n - 1] == '\n' || line[n - 1] == '\r' || line[n - 1] == ' ' ||
                     line[n - 1] == '\t'))
        line[--n] = '\0';
    int printable = 1;
    for (size_t i = 0; i < n; i++)
        printable &= line[i] > 0x20 && line[i] < 0x7f;
    if (n < TOKEN_MIN || n > TOKEN_MAX || !printable) {
        fprintf(stderr,
                "ringdyn-server: --token-file %s: the first line must be %d..%d printable "
                "characters without blanks (e.g. head -c 24 /dev/urandom | base64)\n",
                path, TOKEN_MIN, TOKEN_MAX);
        free(line);
        return NULL;
    }
    return line;
}

/* rd_jobs' on_final: wakes the requests waiting for jobs.  Jobs start only
 * once the server serves (no job can end before `http` is set), and none
 * ends after rd_jobs_shutdown returns, which precedes rd_http_free. */
static void on_job_final(void *ctx)
{
    rd_http *const *http = ctx;
    if (*http)
        rd_http_job_ended(*http);
}

static void on_job_finish(void *ctx, const char *analysis, int status, double run_seconds)
{
    rd_metrics_observe_job(ctx, analysis, rd_jobs_status_name(status), run_seconds);
}

/* glibc returns freed memory above 128 kB at the top of a thread's arena to
 * the kernel (madvise) and maps larger blocks afresh, so every small job
 * (a modal job allocates and frees ~250 kB) paid ~60 page faults, about
 * 0.08 of its 0.9 ms of server CPU.  Kept up to 8 MiB per arena and mapped
 * only from 8 MiB, a job reuses its predecessor's pages (0.3 faults per
 * job).  (32 MiB until issue 45: an arena other than the main one gives
 * back its top only then, not even to malloc_trim, so bursts of large
 * bodies left up to 32 MiB per HTTP thread for good; rd_http_conn.c trims
 * the rest when the server goes idle.)  A refusal (a sanitizer's allocator
 * refuses every mallopt) is not an error: jobs only run slower. */
static void tune_malloc(void)
{
#if defined(__GLIBC__)
    (void)mallopt(M_TRIM_THRESHOLD, 8 << 20);
    (void)mallopt(M_MMAP_THRESHOLD, 8 << 20);
#endif
}

/* What runs, in the order it starts; freed in the order of free_server. */
struct server {
    rd_metrics *metrics;
    rd_store *store;
    rd_jobs *jobs;
    rd_sweeps *sweeps;
    rd_sweep_slurm *slurm; /* --sweep-executor slurm */
    rd_sweep_exec exec;
    char *shared_dir, *script, *ringdyn; /* its paths, resolved (realpath) */
    rd_http *http;                       /* on_job_final reads it through &http */
    char *token;
    const char *data_dir;
    char data_buf[4096];
};

/* SIGINT and SIGTERM blocked (sigwait takes them) before any thread starts,
 * so every thread inherits the mask; SIGPIPE and SIGXFSZ ignored. */
static void block_signals(sigset_t *stop)
{
    sigemptyset(stop);
    sigaddset(stop, SIGINT);
    sigaddset(stop, SIGTERM);
    pthread_sigmask(SIG_BLOCK, stop, NULL);
    struct sigaction ignore;
    memset(&ignore, 0, sizeof ignore);
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ignore, NULL); /* a client hanging up must not kill us */
    /* nor a file-size limit (ulimit -f): the store's write fails with EFBIG
     * and the job says so, where SIGXFSZ's default action killed the server */
    sigaction(SIGXFSZ, &ignore, NULL);
}

/* Prints the error that stopped the start; -1. */
static int start_failed(const rd_error *err)
{
    fprintf(stderr, "ringdyn-server: %s\n", err->message);
    return -1;
}

/* What a client would otherwise meet as an error, checked before the store
 * opens: every file of --examples is one GET /api/v1/examples can serve (its
 * name, its JSON, its scene; rd_api_examples_json), and --token-file holds a
 * token.  (--data is checked as the store opens, --static as HTTP starts.)
 * 0, or -1 after printing why, naming the option, the file and the rule. */
static int check_config(struct server *s, const struct options *opt)
{
    if (opt->examples_dir) {
        rd_error err;
        rd_error_init(&err);
        char *list = rd_api_examples_json(opt->examples_dir, &err);
        int ok = list != NULL;
        free(list);
        if (!ok) {
            fprintf(stderr, "ringdyn-server: --examples %s: %s%s\n", opt->examples_dir, err.message,
                    err.code == RD_EINVAL ? "; fix or remove that file, or leave out --examples"
                                          : "");
            return -1;
        }
    }
    if (opt->token_file && !(s->token = read_token(opt->token_file)))
        return -1;
    return 0;
}

/* `path` resolved (realpath), or NULL after printing why, naming `option`. */
static char *resolve(const char *option, const char *path, int want_dir)
{
    char *real = path ? realpath(path, NULL) : NULL;
    struct stat st;
    const char *why = !path                  ? "is required with --sweep-executor slurm"
                      : !real                ? strerror(errno)
                      : stat(real, &st) != 0 ? strerror(errno)
                      : want_dir != !!S_ISDIR(st.st_mode)
                          ? (want_dir ? "is not a directory" : "is a directory")
                          : NULL;
    if (why) {
        fprintf(stderr, "ringdyn-server: %s %s: %s\n", option, path ? path : "", why);
        free(real);
        return NULL;
    }
    return real;
}

/* --sweep-ringdyn's default: the ringdyn beside this binary, or in the build
 * tree's cli/ (ringdyn-server is in server/). */
static const char *default_ringdyn(char *buf, size_t n)
{
    char self[4096];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        return NULL;
    self[len] = '\0';
    char *slash = strrchr(self, '/');
    *slash = '\0';
    snprintf(buf, n, "%s/ringdyn", self);
    if (access(buf, X_OK) != 0)
        snprintf(buf, n, "%s/../cli/ringdyn", self);
    return buf;
}

/* The Slurm executor of --sweep-executor slurm.  0, or -1 after printing why. */
static int start_executor(struct server *s, const struct options *opt, rd_error *err)
{
    char buf[4200];
    const char *ringdyn =
        opt->sweep_ringdyn ? opt->sweep_ringdyn : default_ringdyn(buf, sizeof buf);
    if (!(s->shared_dir = resolve("--sweep-shared-dir", opt->sweep_shared_dir, 1)) ||
        !(s->script = resolve("--sweep-slurm-script", opt->sweep_slurm_script, 0)) ||
        !(s->ringdyn = resolve("--sweep-ringdyn", ringdyn, 0)))
        return -1;
    if (access(s->ringdyn, X_OK) != 0) {
        fprintf(stderr, "ringdyn-server: --sweep-ringdyn %s: not executable\n", s->ringdyn);
        return -1;
    }
    rd_sweep_slurm_config c = {.script = s->script,
                               .ringdyn = s->ringdyn,
                               .max_running = (size_t)opt->sweep_slurm_max_running};
    if (rd_sweep_slurm_create(&c, &s->slurm, &s->exec, err) != RD_OK)
        return start_failed(err);
    return 0;
}

/* The metrics, the store and the two pools.  0, or -1 after printing why. */
static int start_pools(struct server *s, const struct options *opt, rd_error *err)
{
    s->metrics = rd_metrics_create();
    if (!s->metrics) {
        fprintf(stderr, "ringdyn-server: out of memory\n");
        return -1;
    }
    s->data_dir = opt->data_dir ? opt->data_dir : default_data_dir(s->data_buf, sizeof s->data_buf);
    if (!s->data_dir) {
        fprintf(stderr,
                "ringdyn-server: neither HOME nor XDG_STATE_HOME is set: give --data DIR\n");
        return -1;
    }
    if (rd_store_create(s->data_dir, &s->store, err) != RD_OK)
        return start_failed(err);
    rd_jobs_config jc = {.threads = (int)opt->threads,
                         .queue_max = (int)opt->queue,
                         .keep_max = (int)opt->keep_jobs,
                         .keep_bytes = (size_t)opt->keep_mb << 20,
                         .keep_age_s = opt->keep_days * 86400.0,
                         .store = s->store,
                         .timeout_s = opt->job_timeout,
                         .on_finish = on_job_finish,
                         .on_finish_ctx = s->metrics,
                         .on_final = on_job_final,
                         .on_final_ctx = &s->http};
    if (rd_jobs_create(&jc, &s->jobs, err) != RD_OK)
        return start_failed(err);
    rd_sweeps_config sc = {.threads = (int)opt->threads,
                           .max_points = (size_t)opt->sweep_max_points,
                           .timeout_s = opt->job_timeout,
                           .queue_max = SWEEPS_QUEUE_MAX,
                           .keep_max = SWEEPS_KEEP_MAX,
                           .store = s->store,
                           .on_final = on_job_final,
                           .on_final_ctx = &s->http};
    if (opt->sweep_slurm) {
        if (start_executor(s, opt, err) != 0)
            return -1;
        sc.exec = &s->exec;
        sc.shared_dir = s->shared_dir;
        sc.exec_min_points = opt->sweep_slurm_min_points < 0 ? (size_t)opt->sweep_max_points + 1
                                                             : (size_t)opt->sweep_slurm_min_points;
        sc.exec_chunks = (size_t)opt->sweep_slurm_tasks;
    }
    if (rd_sweeps_create(&sc, &s->sweeps, err) != RD_OK)
        return start_failed(err);
    /* What the store's check found, one log line each. */
    for (const char *line = rd_store_get_report(s->store); *line;) {
        size_t n = strcspn(line, "\n");
        fprintf(stderr, "ringdyn-server: %.*s\n", (int)n, line);
        line += n + (line[n] == '\n');
    }
    return 0;
}

/* The HTTP server (the token was read by check_config).  0, or -1 after
 * printing why. */
static int start_http(struct server *s, const struct options *opt, rd_error *err)
{
    rd_http_config hc = {.host = opt->host,
                         .port = (int)opt->port,
                         .static_dir = opt->static_dir,
                         .examples_dir = opt->examples_dir,
                         .allow_hosts = opt->allow_hosts,
                         .n_allow_hosts = opt->n_allow_hosts,
                         .token = s->token,
                         .limits = opt->limits,
                         .sweeps = s->sweeps,
                         .job_timeout_s = opt->job_timeout};
    if (rd_http_create(&hc, s->jobs, s->metrics, &s->http, err) != RD_OK)
        return start_failed(err);
    return 0;
}

/* The shutdown of the file comment, up to the freeing. */
static void stop_server(struct server *s, int sig)
{
    fprintf(stderr, "ringdyn-server: %s, shutting down\n", sig == SIGINT ? "SIGINT" : "SIGTERM");
    rd_http_quiesce(s->http);
    rd_sweeps_stop(s->sweeps);
    rd_jobs_shutdown(s->jobs, STOP_WAIT_S);
    rd_sweeps_shutdown(s->sweeps, STOP_WAIT_S);
    rd_http_drain(s->http, DRAIN_S);
}

static void free_server(struct server *s)
{
    rd_http_free(s->http);
    rd_jobs_free(s->jobs);
    rd_sweeps_free(s->sweeps);
    rd_sweep_slurm_free(s->slurm);
    free(s->shared_dir);
    free(s->script);
    free(s->ringdyn);
    rd_store_free(s->store);
    rd_metrics_free(s->metrics);
    free(s->token);
}

int main(int argc, char **argv)
{
    struct options opt = {.host = "127.0.0.1",
                          .port = -1,
                          .threads = 2,
                          .queue = 32,
                          .job_timeout = 120.0,
                          .keep_jobs = 256,
                          .keep_mb = 512,
                          .keep_days = 30,
                          .sweep_max_points = RD_SWEEPS_POINTS_DEFAULT,
                          .sweep_slurm_min_points = -1,
                          .sweep_slurm_tasks = 16,
                          .limits = {.threads = 4,
                                     .connections_max = 1000,
                                     .per_ip_max = 64,
                                     .request_deadline_s = 10,
                                     .idle_timeout_s = 30}};
    struct server s;
    memset(&s, 0, sizeof s);
    int status = 1;
    rd_error err;
    rd_error_init(&err);
    tune_malloc();

    if (parse_options(argc, argv, &opt) != 0) {
        usage(stderr);
        return 2;
    }
    sigset_t stop;
    block_signals(&stop);
    if (check_config(&s, &opt) != 0 || start_pools(&s, &opt, &err) != 0 ||
        start_http(&s, &opt, &err) != 0)
        goto out;

    printf("ringdyn-server listening on http://%s:%d\n", rd_http_get_host(s.http),
           rd_http_get_port(s.http));
    fflush(stdout);
    fprintf(stderr,
            "ringdyn-server %s: %ld workers, queue %ld, job time limit %g s, keeps %ld finished "
            "jobs / %ld MiB of results / %g days in %s\n",
            rd_api_version(), opt.threads, opt.queue, opt.job_timeout, opt.keep_jobs, opt.keep_mb,
            opt.keep_days, s.data_dir);

    int sig = 0;
    if (sigwait(&stop, &sig) != 0)
        goto out;
    stop_server(&s, sig);
    status = 0;
out:
    free_server(&s);
    return status;
}
