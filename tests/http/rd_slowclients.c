/*
 * rd-slowclients — slow-header clients against a live server, and one normal
 * client timing its answers meanwhile (tests/http/slow.sh).
 *
 *   rd-slowclients PORT NSLOW NADDR SECONDS
 *
 * Opens NSLOW connections to 127.0.0.1:PORT, connection i bound to source
 * address 127.0.0.(2 + i % NADDR) (all of 127/8 is loopback on Linux), so
 * that a per-address limit can be tested apart from the total.  Each sends
 * the start of a request and then one more header byte every second, never
 * finishing it (a slowloris).  Meanwhile a second thread, from 127.0.0.1,
 * sends GET /api/v1/health every 100 ms on a fresh connection and times the
 * whole answer.  After SECONDS it prints one line:
 *
 *   open_after_1s=N closed=M normal_ok=K normal_total=T normal_max_ms=X
 *
 * open_after_1s: slow connections still open 1 s after the last connect;
 * closed: slow connections the server had closed at the end (refused at
 * accept, or shut by the request deadline).  Exit 0 unless the tool itself
 * fails.
 */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

/* Longest wait for one normal answer before it counts as failed. */
#define NORMAL_TIMEOUT_MS 5000

static int port;
static _Atomic int stop;

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int connect_from(const char *source)
{
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return -1;
    struct sockaddr_in a = {.sin_family = AF_INET};
    if (source) {
        inet_pton(AF_INET, source, &a.sin_addr);
        if (bind(fd, (struct sockaddr *)&a, sizeof a) != 0) {
            close(fd);
            return -1;
        }
    }
    a.sin_port = htons((uint16_t)port);
    inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
    if (connect(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

/* Has the server closed (or reset) this connection?  Never blocks. */
static int is_closed(int fd)
{
    struct pollfd p = {.fd = fd, .events = POLLIN};
    if (poll(&p, 1, 0) <= 0)
        return 0;
    char buf[256];
    ssize_t n = recv(fd, buf, sizeof buf, MSG_DONTWAIT);
    return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK);
}

struct normal_stats {
    int ok, total;
    double max_ms;
};

/* One GET /api/v1/health with Connection: close; 1 if the answer was 200. */
static int one_normal(double *ms)
{
    double t0 = now_s();
    int fd = connect_from(NULL);
    if (fd < 0)
        return 0;
    static const char req[] =
        "GET /api/v1/health HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
    int ok = send(fd, req, sizeof req - 1, MSG_NOSIGNAL) == (ssize_t)(sizeof req - 1);
    char buf[4096];
    size_t got = 0;
    while (ok) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        int left = NORMAL_TIMEOUT_MS - (int)((now_s() - t0) * 1000);
        if (left <= 0 || poll(&p, 1, left) <= 0) {
            ok = 0;
            break;
        }
        ssize_t n = recv(fd, buf + got, sizeof buf - 1 - got, 0);
        if (n <= 0)
            break;
        got += (size_t)n;
        if (got == sizeof buf - 1)
            break;
    }
    close(fd);
    buf[got] = '\0';
    *ms = (now_s() - t0) * 1000;
    return ok && strncmp(buf, "HTTP/1.1 200", 12) == 0;
}

static void *normal_main(void *arg)
{
    struct normal_stats *st = arg;
    while (!stop) {
        double ms = 0;
        int ok = one_normal(&ms);
        st->total++;
        st->ok += ok;
        if (ms > st->max_ms)
            st->max_ms = ms;
        sleep_ms(100);
    }
    return NULL;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s PORT NSLOW NADDR SECONDS\n", argv[0]);
        return 2;
    }
    port = atoi(argv[1]);
    int nslow = atoi(argv[2]), naddr = atoi(argv[3]);
    double seconds = atof(argv[4]);
    if (port <= 0 || nslow < 0 || naddr < 1 || naddr > 250 || !(seconds > 0))
        return 2;
    int *fds = calloc((size_t)nslow + 1, sizeof *fds);
    if (!fds)
        return 1;

    struct normal_stats st = {0};
    pthread_t normal;
    if (pthread_create(&normal, NULL, normal_main, &st) != 0)
        return 1;

    static const char start[] = "GET /api/v1/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ";
    for (int i = 0; i < nslow; i++) {
        char source[32];
        snprintf(source, sizeof source, "127.0.0.%d", 2 + i % naddr);
        fds[i] = connect_from(source);
        if (fds[i] >= 0 && send(fds[i], start, sizeof start - 1, MSG_NOSIGNAL) < 0) {
            close(fds[i]);
            fds[i] = -1;
        }
    }
    double t0 = now_s();
    int open_after_1s = -1;
    while (now_s() - t0 < seconds) {
        sleep_ms(250);
        static double last_byte;
        if (now_s() - last_byte >= 1.0) { /* one more header byte a second */
            last_byte = now_s();
            for (int i = 0; i < nslow; i++)
                if (fds[i] >= 0 && !is_closed(fds[i]))
                    send(fds[i], "a", 1, MSG_NOSIGNAL);
        }
        if (open_after_1s < 0 && now_s() - t0 >= 1.0) {
            open_after_1s = 0;
            for (int i = 0; i < nslow; i++)
                open_after_1s += fds[i] >= 0 && !is_closed(fds[i]);
        }
    }
    int closed = 0;
    for (int i = 0; i < nslow; i++) {
        closed += fds[i] < 0 || is_closed(fds[i]);
        if (fds[i] >= 0)
            close(fds[i]);
    }
    stop = 1;
    pthread_join(normal, NULL);
    printf("open_after_1s=%d closed=%d normal_ok=%d normal_total=%d normal_max_ms=%.0f\n",
           open_after_1s < 0 ? 0 : open_after_1s, closed, st.ok, st.total, st.max_ms);
    free(fds);
    return 0;
}
