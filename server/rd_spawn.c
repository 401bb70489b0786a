/*
 * rd_spawn — a command-line tool run with posix_spawn, its output captured
 * within bounds and within a deadline (rd_spawn.h).
 */
#define _GNU_SOURCE

#include "rd_spawn.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "rd_clock.h"

extern char **environ;

struct sink {
    int fd;
    char *text;
    size_t len, max;
};

/* Reads what fd has; keeps up to max bytes.  Returns 0 at end of file. */
static int drain(struct sink *s)
{
    char buf[4096];
    ssize_t n = read(s->fd, buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN))
        return 1;
    if (n <= 0)
        return 0;
    size_t keep = s->len < s->max ? s->max - s->len : 0;
    keep = (size_t)n < keep ? (size_t)n : keep;
    memcpy(s->text + s->len, buf, keep);
    s->len += keep;
    s->text[s->len] = '\0';
    return 1;
}

/* Reads both pipes until both end or the deadline passes; 0 when they ended. */
static int collect(struct sink *s, double deadline)
{
    int open_fds = 2;
    while (open_fds > 0) {
        struct pollfd p[2];
        int np = 0;
        for (int i = 0; i < 2; i++)
            if (s[i].fd >= 0)
                p[np++] = (struct pollfd){.fd = s[i].fd, .events = POLLIN};
        double left = deadline - rd_clock_mono_s();
        if (left <= 0)
            return -1;
        int r = poll(p, (nfds_t)np, (int)(left * 1000) + 1);
        if (r < 0 && errno != EINTR)
            return -1;
        for (int j = 0; r > 0 && j < np; j++) {
            if (!p[j].revents)
                continue;
            struct sink *k = s[0].fd == p[j].fd ? &s[0] : &s[1];
            if (!drain(k)) {
                close(k->fd);
                k->fd = -1;
                open_fds--;
            }
        }
    }
    return 0;
}

static int start(char *const argv[], char *const envp[], int out_fd, int err_fd, pid_t *pid)
{
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t attr;
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGINT);
    int e = posix_spawn_file_actions_init(&fa);
    if (e != 0)
        return e;
    e = posix_spawnattr_init(&attr);
    if (e == 0) {
        posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_adddup2(&fa, out_fd, 1);
        posix_spawn_file_actions_adddup2(&fa, err_fd, 2);
        posix_spawnattr_setsigmask(&attr, &none);
        posix_spawnattr_setsigdefault(&attr, &defaults);
        posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
        e = posix_spawnp(pid, argv[0], &fa, &attr, argv, envp ? envp : environ);
        posix_spawnattr_destroy(&attr);
    }
    posix_spawn_file_actions_destroy(&fa);
    return e;
}

int rd_spawn_run(char *const argv[], char *const envp[], double timeout_s, size_t out_max,
                 rd_spawn_result *res, rd_error *err)
{
    memset(res, 0, sizeof *res);
    res->exit_code = -1;
    struct sink s[2] = {{.fd = -1, .max = out_max}, {.fd = -1, .max = out_max}};
    int po[2] = {-1, -1}, pe[2] = {-1, -1};
    res->out = s[0].text = calloc(out_max + 1, 1);
    res->err = s[1].text = calloc(out_max + 1, 1);
    if (!res->out || !res->err)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    if (pipe2(po, O_CLOEXEC) != 0 || pipe2(pe, O_CLOEXEC) != 0) {
        int e = errno;
        for (int i = 0; i < 2; i++) {
            if (po[i] >= 0)
                close(po[i]);
            if (pe[i] >= 0)
                close(pe[i]);
        }
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot run %s: %s.", argv[0], strerror(e));
    }
    pid_t pid;
    int e = start(argv, envp, po[1], pe[1], &pid);
    close(po[1]);
    close(pe[1]);
    s[0].fd = po[0];
    s[1].fd = pe[0];
    int timed_out = e == 0 && collect(s, rd_clock_mono_s() + timeout_s) != 0;
    if (timed_out)
        kill(pid, SIGKILL);
    for (int i = 0; i < 2; i++)
        if (s[i].fd >= 0)
            close(s[i].fd);
    if (e != 0)
        return rd_error_set(err, RD_EINTERNAL, "", "Cannot run %s: %s.", argv[0], strerror(e));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (timed_out)
        res->exit_code = -1;
    else if (WIFEXITED(status))
        res->exit_code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status))
        res->exit_code = 128 + WTERMSIG(status);
    return RD_OK;
}

void rd_spawn_result_cleanup(rd_spawn_result *res)
{
    free(res->out);
    free(res->err);
    res->out = res->err = NULL;
}
