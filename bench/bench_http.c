/*
 * bench_http — many concurrent clients against a live ringdyn-server.
 *
 *   bench_http PORT CLIENTS SECONDS SERVER_PID [SCENE_JSON [MODE]]
 *
 * MODE "close" (the default) is described below.  MODE "keepalive" and
 * "keepalive-nocache": each client keeps one connection open and submits
 * on it again and again (HTTP/1.1 keep-alive); "keepalive" lets the result
 * cache answer (all but the first submission are hits), "keepalive-nocache"
 * sends Cache-Control: no-cache so that every submission is computed.
 *
 * CLIENTS threads, client i bound to source address 127.0.0.(2 + i % 50)
 * (loopback; so the server's per-address limit sees 50 addresses, as it
 * would see many machines), each looping for SECONDS: POST the scene
 * (default {"analysis":"modal"}) to /api/v1/jobs?wait=60 on a fresh
 * connection and read the whole answer.  A 429 is honoured as a polite
 * client would: wait its Retry-After, then submit again.  Prints one line of
 * key=value: finished jobs per second, latency percentiles of the answered
 * submissions (200: the job finished within the wait), the count of each
 * outcome, the server's peak RSS (VmHWM of SERVER_PID) and the CPU time
 * it used (user + system) with the answers per CPU second: on a shared,
 * loaded machine the latter says what the server costs, the rate only what
 * it got.
 */
#define _GNU_SOURCE /* strcasestr */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "bench_util.h"

/* Latencies kept per client: enough for 60 s of 10 ms answers. */
#define LAT_MAX 20000
/* A whole answer (the job with its result) fits: the default modal result is
 * about 10 kB. */
#define ANSWER_MAX (1 << 20)

struct client {
    pthread_t thread;
    int index;
    double *lat;
    int nlat;
    long ok, accepted, busy, other, failed;
};

static void sleep_s(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

static int port;
static double end_time;
static const char *scene = "{\"analysis\":\"modal\"}";
static int keepalive; /* MODE keepalive*: one connection per client */
static int nocache;   /* MODE keepalive-nocache */

static int connect_from(int index)
{
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return -1;
    struct sockaddr_in a = {.sin_family = AF_INET};
    char source[32];
    snprintf(source, sizeof source, "127.0.0.%d", 2 + index % 50);
    inet_pton(AF_INET, source, &a.sin_addr);
    if (bind(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        close(fd);
        return -1;
    }
    a.sin_port = htons((uint16_t)port);
    inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
    if (connect(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

/* One submission; the status (0 on a transport failure) and Retry-After. */
static int submit(int index, char *buf, int *retry_after)
{
    int fd = connect_from(index);
    if (fd < 0)
        return 0;
    char head[256];
    size_t body_len = strlen(scene);
    int n = snprintf(head, sizeof head,
                     "POST /api/v1/jobs?wait=60 HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     "Content-Type: application/json\r\nContent-Length: %zu\r\n"
                     "Connection: close\r\n\r\n",
                     body_len);
    if (send(fd, head, (size_t)n, MSG_NOSIGNAL) != n ||
        send(fd, scene, body_len, MSG_NOSIGNAL) != (ssize_t)body_len) {
        close(fd);
        return 0;
    }
    size_t got = 0;
    ssize_t r;
    while (got < ANSWER_MAX - 1 && (r = recv(fd, buf + got, ANSWER_MAX - 1 - got, 0)) > 0)
        got += (size_t)r;
    close(fd);
    buf[got] = '\0';
    int status = 0;
    if (sscanf(buf, "HTTP/1.1 %d", &status) != 1)
        return 0;
    const char *ra = strstr(buf, "Retry-After: ");
    *retry_after = ra ? atoi(ra + 13) : 1;
    return status;
}

/* Reads one answer (headers, then Content-Length bytes) from a kept
 * connection; the status, or 0 on a transport failure. */
static int read_answer(int fd, char *buf)
{
    size_t got = 0;
    char *end = NULL;
    while (!end) {
        ssize_t r = recv(fd, buf + got, ANSWER_MAX - 1 - got, 0);
        if (r <= 0)
            return 0;
        got += (size_t)r;
        buf[got] = '\0';
        end = strstr(buf, "\r\n\r\n");
        if (!end && got >= ANSWER_MAX - 1)
            return 0;
    }
    const char *cl = strcasestr(buf, "\r\nContent-Length: ");
    size_t want = (size_t)(end + 4 - buf) + (cl ? strtoul(cl + 18, NULL, 10) : 0);
    if (want >= ANSWER_MAX)
        return 0;
    while (got < want) {
        ssize_t r = recv(fd, buf + got, want - got, 0);
        if (r <= 0)
            return 0;
        got += (size_t)r;
    }
    int status = 0;
    return sscanf(buf, "HTTP/1.1 %d", &status) == 1 ? status : 0;
}

/* One submission on the kept connection *fd (opened when -1, closed and
 * set to -1 after a failure). */
static int submit_kept(int index, int *fd, char *buf)
{
    if (*fd < 0 && (*fd = connect_from(index)) < 0)
        return 0;
    /* One send: head and body in two would meet Nagle and delayed ACK (40 ms). */
    char request[4096];
    size_t body_len = strlen(scene);
    int n = snprintf(request, sizeof request,
                     "POST /api/v1/jobs?wait=60 HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     "Content-Type: application/json\r\nContent-Length: %zu\r\n%s\r\n%s",
                     body_len, nocache ? "Cache-Control: no-cache\r\n" : "", scene);
    int status = 0;
    if (n > 0 && (size_t)n < sizeof request && send(*fd, request, (size_t)n, MSG_NOSIGNAL) == n)
        status = read_answer(*fd, buf);
    if (status == 0) {
        close(*fd);
        *fd = -1;
    }
    return status;
}

static void *client_main(void *arg)
{
    struct client *c = arg;
    char *buf = malloc(ANSWER_MAX);
    if (!buf)
        return NULL;
    int fd = -1;
    while (bench_now() < end_time) {
        int retry = 1;
        double t0 = bench_now();
        int status = keepalive ? submit_kept(c->index, &fd, buf) : submit(c->index, buf, &retry);
        double t1 = bench_now();
        if (status == 200) {
            c->ok++;
            if (c->nlat < LAT_MAX)
                c->lat[c->nlat++] = t1 - t0;
        } else if (status == 202) {
            c->accepted++;
        } else if (status == 429) {
            c->busy++;
            double until = t1 + (retry > 0 ? retry : 1);
            while (bench_now() < until && bench_now() < end_time)
                sleep_s(0.05);
        } else if (status == 0) {
            c->failed++;
            sleep_s(0.01);
        } else {
            c->other++;
        }
    }
    if (fd >= 0)
        close(fd);
    free(buf);
    return NULL;
}

static long peak_rss_kb(const char *pid)
{
    char path[64], line[256];
    snprintf(path, sizeof path, "/proc/%s/status", pid);
    FILE *f = fopen(path, "r");
    long kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (strncmp(line, "VmHWM:", 6) == 0)
            kb = atol(line + 6);
    if (f)
        fclose(f);
    return kb;
}

/* CPU seconds (user + system) the process has used so far; -1 unknown. */
static double cpu_seconds(const char *pid)
{
    char path[64], line[1024];
    snprintf(path, sizeof path, "/proc/%s/stat", pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char *ok = fgets(line, sizeof line, f);
    fclose(f);
    const char *p = ok ? strrchr(line, ')') : NULL; /* the command may hold spaces */
    unsigned long long ut = 0, st = 0;
    if (!p || sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &ut, &st) != 2)
        return -1;
    return (double)(ut + st) / (double)sysconf(_SC_CLK_TCK);
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: %s PORT CLIENTS SECONDS SERVER_PID [SCENE_JSON [MODE]]\n", argv[0]);
        return 2;
    }
    port = atoi(argv[1]);
    int nclients = atoi(argv[2]);
    double seconds = atof(argv[3]);
    if (argc > 5)
        scene = argv[5];
    if (argc > 6) {
        keepalive = strncmp(argv[6], "keepalive", 9) == 0;
        nocache = strcmp(argv[6], "keepalive-nocache") == 0;
        if (!keepalive && strcmp(argv[6], "close") != 0)
            return 2;
    }
    if (port <= 0 || nclients < 1 || !(seconds > 0))
        return 2;
    struct client *cs = calloc((size_t)nclients, sizeof *cs);
    if (!cs)
        return 1;
    double cpu0 = cpu_seconds(argv[4]);
    double t0 = bench_now();
    end_time = t0 + seconds;
    for (int i = 0; i < nclients; i++) {
        cs[i].index = i;
        cs[i].lat = malloc(LAT_MAX * sizeof *cs[i].lat);
        if (!cs[i].lat || pthread_create(&cs[i].thread, NULL, client_main, &cs[i]) != 0)
            return 1;
    }
    long ok = 0, accepted = 0, busy = 0, other = 0, failed = 0;
    int nlat = 0;
    double *lat = malloc((size_t)nclients * LAT_MAX * sizeof *lat);
    if (!lat)
        return 1;
    for (int i = 0; i < nclients; i++) {
        pthread_join(cs[i].thread, NULL);
        ok += cs[i].ok;
        accepted += cs[i].accepted;
        busy += cs[i].busy;
        other += cs[i].other;
        failed += cs[i].failed;
        memcpy(lat + nlat, cs[i].lat, (size_t)cs[i].nlat * sizeof *lat);
        nlat += cs[i].nlat;
        free(cs[i].lat);
    }
    double elapsed = bench_now() - t0;
    double cpu = cpu_seconds(argv[4]) - cpu0;
    double p50 = 0, p99 = 0;
    if (nlat > 0) {
        bench_median(lat, nlat); /* sorts */
        p50 = lat[nlat / 2];
        p99 = lat[(int)(0.99 * (nlat - 1))];
    }
    printf("clients=%d seconds=%.1f jobs_per_s=%.1f p50_ms=%.3f p99_ms=%.3f ok_200=%ld "
           "accepted_202=%ld busy_429=%ld other=%ld failed=%ld peak_rss_mb=%.1f server_cpu_s=%.2f "
           "jobs_per_server_cpu_s=%.1f\n",
           nclients, elapsed, (double)ok / elapsed, 1e3 * p50, 1e3 * p99, ok, accepted, busy, other,
           failed, peak_rss_kb(argv[4]) / 1024.0, cpu, cpu > 0 ? (double)ok / cpu : 0.0);
    free(lat);
    free(cs);
    return 0;
}
