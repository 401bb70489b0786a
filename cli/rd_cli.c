/* rd_cli.c — exit statuses, error output and signals of the commands (rd_cli.h). */
#include "rd_cli.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rd_api.h"

static volatile sig_atomic_t interrupted;

static void on_signal(int sig)
{
    (void)sig;
    interrupted = 1;
}

int rd_cli_fail(const rd_error *err)
{
    char *json = rd_api_error_json(err);
    fprintf(stderr, "%s\n", json ? json : "{\"error\":{\"code\":\"out_of_memory\"}}");
    free(json);
    int status = rd_api_http_status(err->code);
    return status >= 400 && status < 500 ? RD_CLI_EXIT_INPUT : RD_CLI_EXIT_RUN;
}

void rd_cli_catch_signals(int term)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    if (term)
        sigaction(SIGTERM, &sa, NULL);
}

int rd_cli_stop_requested(void *ctx, double fraction)
{
    (void)ctx;
    (void)fraction;
    return interrupted != 0;
}
