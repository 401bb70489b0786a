/*
 * rd_cli — what the ringdyn commands share: exit statuses, the error JSON on
 * stderr, and stopping a run on SIGINT/SIGTERM through core's monitor.
 */
#ifndef RD_CLI_H
#define RD_CLI_H

#include "rd_error.h"

/* Exit statuses: 0 success, 2 invalid input (what the contract answers with a
 * 4xx), 1 the run failed (did not converge, interrupted, out of memory). */
enum { RD_CLI_EXIT_RUN = 1, RD_CLI_EXIT_INPUT = 2 };

/* Prints err as the server's error JSON on stderr; returns the exit status. */
int rd_cli_fail(const rd_error *err);

/* From now on SIGINT (and SIGTERM when `term`) ask the running computation
 * to stop instead of killing the process. */
void rd_cli_catch_signals(int term);

/* Monitor callback (rd_monitor.report): non-zero once a caught signal came. */
int rd_cli_stop_requested(void *ctx, double fraction);

#endif
