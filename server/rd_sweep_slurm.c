/*
 * rd_sweep_slurm — the Slurm executor: sbatch, squeue, scontrol and scancel
 * run with posix_spawn (rd_sweep_slurm.h).  The arguments are the job id
 * Slurm gave, the sweep's directory (made by the server from its own
 * configuration and a random id) and numbers: nothing a client sent.
 */
#define _XOPEN_SOURCE 700

#include "rd_sweep_slurm.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_spawn.h"

/* Time limits of the tools (a controller that does not answer), and how much
 * of their output is read: squeue -r lists one line a task. */
#define TOOL_TIMEOUT_S 30.0
#define OUT_MAX        ((size_t)1 << 20)
#define LOG_TAIL       2048

extern char **environ;

struct rd_sweep_slurm {
    char *script, *ringdyn;
    size_t max_running;
    char **envp; /* the server's environment with RINGDYN=<ringdyn> */
};

static void free_env(char **envp)
{
    for (size_t i = 0; envp && envp[i]; i++)
        free(envp[i]);
    free(envp);
}

static char **make_env(const char *ringdyn)
{
    size_t n = 0;
    while (environ[n])
        n++;
    char **envp = calloc(n + 2, sizeof *envp);
    size_t k = 0;
    for (size_t i = 0; envp && i < n; i++)
        if (strncmp(environ[i], "RINGDYN=", 8) != 0 && !(envp[k++] = strdup(environ[i]))) {
            free_env(envp);
            return NULL;
        }
    if (envp && (envp[k] = malloc(strlen(ringdyn) + 9)) != NULL)
        sprintf(envp[k], "RINGDYN=%s", ringdyn);
    else if (envp) {
        free_env(envp);
        envp = NULL;
    }
    return envp;
}

/* A tool's failure as the error: its exit status and first line of stderr. */
static int tool_failed(const char *tool, const rd_spawn_result *res, rd_error *err)
{
    size_t n = strcspn(res->err, "\n");
    if (res->exit_code < 0)
        return rd_error_set(err, RD_EINTERNAL, "", "%s did not answer within %g s.", tool,
                            TOOL_TIMEOUT_S);
    return rd_error_set(err, RD_EINTERNAL, "", "%s failed (exit %d): %.*s", tool, res->exit_code,
                        (int)(n > 300 ? 300 : n), res->err);
}

static int slurm_submit(void *ctx, const char *dir, size_t chunks, char *job_id, rd_error *err)
{
    rd_sweep_slurm *s = ctx;
    char array[64], out[4200], spec[4200], k[32];
    snprintf(array, sizeof array, "--array=0-%zu", chunks - 1);
    if (s->max_running)
        snprintf(array + strlen(array), sizeof array - strlen(array), "%%%zu", s->max_running);
    snprintf(out, sizeof out, "--output=%s/logs/%%A_%%a.log", dir);
    snprintf(spec, sizeof spec, "%s/spec.json", dir);
    snprintf(k, sizeof k, "%zu", chunks);
    char *argv[] = {"sbatch", "--parsable", "--job-name=ringdyn-sweep",
                    array,    out,          s->script,
                    spec,     (char *)dir,  k,
                    k,        NULL};
    rd_spawn_result res;
    int rc = rd_spawn_run(argv, s->envp, TOOL_TIMEOUT_S, 4096, &res, err);
    if (rc == RD_OK && res.exit_code != 0)
        rc = tool_failed("sbatch", &res, err);
    size_t n = rc == RD_OK ? strspn(res.out, "0123456789") : 0;
    if (rc == RD_OK && (n == 0 || n >= RD_SWEEP_EXEC_ID_MAX))
        rc = rd_error_set(err, RD_EINTERNAL, "", "sbatch gave no job id: %.200s", res.out);
    if (rc == RD_OK) {
        memcpy(job_id, res.out, n);
        job_id[n] = '\0';
    }
    rd_spawn_result_cleanup(&res);
    return rc;
}

static int slurm_poll(void *ctx, const char *job_id, rd_sweep_exec_poll *p, rd_error *err)
{
    rd_sweep_slurm *s = ctx;
    char *argv[] = {"squeue", "-h", "-r", "-j", (char *)job_id, "-o", "%i %T", NULL};
    rd_spawn_result res;
    memset(p, 0, sizeof *p);
    int rc = rd_spawn_run(argv, s->envp, TOOL_TIMEOUT_S, OUT_MAX, &res, err);
    if (rc == RD_OK && res.exit_code != 0 && !strstr(res.err, "Invalid job id"))
        rc = tool_failed("squeue", &res, err);
    size_t other = 0;
    for (char *line = rc == RD_OK && res.exit_code == 0 ? res.out : ""; *line;) {
        size_t n = strcspn(line, "\n");
        char *state = memchr(line, ' ', n);
        if (state && strncmp(state + 1, "PENDING", 7) == 0)
            p->pending++;
        else if (state && strncmp(state + 1, "RUNNING", 7) == 0)
            p->running++;
        else if (n > 0)
            other++; /* CONFIGURING, COMPLETING, SUSPENDED, ... */
        line += n + (line[n] == '\n');
    }
    if (rc == RD_OK) {
        p->gone = p->pending + p->running + other == 0;
        snprintf(p->state, sizeof p->state, "%zu running, %zu pending%s", p->running, p->pending,
                 other ? ", others ending" : "");
        if (p->gone)
            snprintf(p->state, sizeof p->state, "no task pending or running");
    }
    rd_spawn_result_cleanup(&res);
    return rc;
}

/* Field `key` ("JobState=") of one `scontrol show job -o` line, into buf. */
static void field(const char *line, size_t n, const char *key, char *buf, size_t cap)
{
    buf[0] = '\0';
    for (const char *p = line; p && p < line + n; p = memchr(p, ' ', (size_t)(line + n - p))) {
        p += *p == ' ';
        if (strncmp(p, key, strlen(key)) == 0) {
            size_t len = strcspn(p + strlen(key), " \n");
            snprintf(buf, cap, "%.*s", (int)len, p + strlen(key));
            return;
        }
    }
}

/* The last non-empty line of a task's log (the ringdyn error), into buf. */
static void log_tail(const char *dir, const char *job_id, const char *task, char *buf, size_t cap)
{
    char path[4200], text[LOG_TAIL + 1];
    snprintf(path, sizeof path, "%s/logs/%s_%s.log", dir, job_id, task);
    buf[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f)
        return;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, size > LOG_TAIL ? size - LOG_TAIL : 0, SEEK_SET);
    size_t n = fread(text, 1, LOG_TAIL, f);
    fclose(f);
    while (n > 0 && isspace((unsigned char)text[n - 1]))
        n--;
    text[n] = '\0';
    char *last = strrchr(text, '\n');
    snprintf(buf, cap, "%.300s", last ? last + 1 : text);
}

/* One task that ended without its chunk, as `why`. */
static void explain_task(const char *dir, const char *job_id, const char *line, size_t n,
                         rd_error *why)
{
    char task[32], state[64], code[32], tail[320];
    field(line, n, "ArrayTaskId=", task, sizeof task);
    field(line, n, "JobState=", state, sizeof state);
    field(line, n, "ExitCode=", code, sizeof code);
    log_tail(dir, job_id, task, tail, sizeof tail);
    int exit_code = atoi(code);
    if (strcmp(state, "CANCELLED") == 0)
        rd_error_set(why, RD_ECANCELED, "",
                     "Array task %s of Slurm job %s was cancelled outside the service (JobState "
                     "CANCELLED): its chunk is missing; submit the sweep again.",
                     task, job_id);
    else
        rd_error_set(why, exit_code == 2 ? RD_EINVAL : RD_EINTERNAL, "",
                     "Array task %s of Slurm job %s ended %s with exit code %s (%s): %s", task,
                     job_id, state, code,
                     exit_code == 2   ? "invalid input, retrying cannot help"
                     : exit_code == 1 ? "the run could not finish; submit the sweep again"
                                      : "see its log",
                     tail[0] ? tail : "(its log is empty or unreadable)");
}

static void slurm_explain(void *ctx, const char *dir, const char *job_id, size_t missing,
                          rd_error *why)
{
    rd_sweep_slurm *s = ctx;
    char *argv[] = {"scontrol", "show", "job", "-o", (char *)job_id, NULL};
    rd_spawn_result res;
    rd_error err;
    rd_error_init(&err);
    int rc = rd_spawn_run(argv, s->envp, TOOL_TIMEOUT_S, OUT_MAX, &res, &err);
    for (char *line = rc == RD_OK && res.exit_code == 0 ? res.out : ""; *line;) {
        size_t n = strcspn(line, "\n");
        char state[64];
        field(line, n, "JobState=", state, sizeof state);
        if (n > 0 && strcmp(state, "COMPLETED") != 0) {
            explain_task(dir, job_id, line, n, why);
            rd_spawn_result_cleanup(&res);
            return;
        }
        line += n + (line[n] == '\n');
    }
    if (rc == RD_OK && res.exit_code == 0)
        rd_error_set(why, RD_EINTERNAL, "",
                     "Every task of Slurm job %s completed, yet chunk %zu is not in %s: is that "
                     "directory shared with the nodes?",
                     job_id, missing, dir);
    else
        rd_error_set(why, RD_EINTERNAL, "",
                     "Slurm no longer knows job %s (cancelled or purged outside the service) and "
                     "chunk %zu is missing: submit the sweep again.",
                     job_id, missing);
    rd_spawn_result_cleanup(&res);
}

static int slurm_cancel(void *ctx, const char *job_id, rd_error *err)
{
    rd_sweep_slurm *s = ctx;
    char *argv[] = {"scancel", (char *)job_id, NULL};
    rd_spawn_result res;
    int rc = rd_spawn_run(argv, s->envp, TOOL_TIMEOUT_S, 4096, &res, err);
    if (rc == RD_OK && res.exit_code != 0)
        rc = tool_failed("scancel", &res, err);
    rd_spawn_result_cleanup(&res);
    return rc;
}

int rd_sweep_slurm_create(const rd_sweep_slurm_config *cfg, rd_sweep_slurm **out,
                          rd_sweep_exec *exec, rd_error *err)
{
    *out = NULL;
    rd_sweep_slurm *s = calloc(1, sizeof *s);
    if (s) {
        s->script = strdup(cfg->script);
        s->ringdyn = strdup(cfg->ringdyn);
        s->max_running = cfg->max_running;
        s->envp = make_env(cfg->ringdyn);
    }
    if (!s || !s->script || !s->ringdyn || !s->envp) {
        rd_sweep_slurm_free(s);
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    }
    *exec = (rd_sweep_exec){.name = "slurm",
                            .ctx = s,
                            .submit = slurm_submit,
                            .poll = slurm_poll,
                            .explain = slurm_explain,
                            .cancel = slurm_cancel};
    *out = s;
    return RD_OK;
}

void rd_sweep_slurm_free(rd_sweep_slurm *s)
{
    if (!s)
        return;
    free(s->script);
    free(s->ringdyn);
    free_env(s->envp);
    free(s);
}
