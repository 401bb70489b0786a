/*
 * rd_spawn — runs a command-line tool (sbatch, squeue, scancel, scontrol)
 * with posix_spawn and an argument vector: no shell, so nothing a client
 * sent is ever parsed as shell text.  Its standard output and error are
 * captured up to a bound each (the rest is read and dropped), standard
 * input is /dev/null, the signal mask and SIGPIPE are reset for the child,
 * and a child still running at the deadline is killed (SIGKILL) and reaped.
 * Blocks the calling thread for at most `timeout_s`: call it from a
 * thread of its own, never from an HTTP thread.
 */
#ifndef RD_SPAWN_H
#define RD_SPAWN_H

#include <stddef.h>

#include "rd_error.h"

typedef struct rd_spawn_result {
    int exit_code; /* the exit status, or 128 + signal, or -1 when killed at the deadline */
    char *out;     /* standard output, NUL-terminated, at most out_max bytes (malloc'd) */
    char *err;     /* standard error, likewise */
} rd_spawn_result;

/* Runs argv[0] (searched in PATH) with `envp` (NULL: the server's
 * environment).  RD_OK once the child ran and was reaped, whatever its exit
 * status; RD_EINTERNAL (with the reason) when it could not be started.
 * The caller cleans up `res` in both cases. */
int rd_spawn_run(char *const argv[], char *const envp[], double timeout_s, size_t out_max,
                 rd_spawn_result *res, rd_error *err);

void rd_spawn_result_cleanup(rd_spawn_result *res);

#endif
