/*
 * rd_http_conn — connections and suspended requests (rd_http_int.h): the
 * list of open connections, the request deadline, the requests waiting for
 * their job, and the timer thread that resumes them and returns freed
 * memory to the kernel when the server goes idle.
 */
#include "rd_http_int.h"

#include <netinet/in.h>
#include <pthread.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

#include "rd_clock.h"

/* The timer thread's period: the latest a waiter is resumed after its
 * deadline, and the resolution of the request deadline. */
#define TICK_S 0.1
/* A connection over a limit is answered 429/503 on its first request, which
 * must arrive within this (then it is shut without an answer). */
#define OVER_DEADLINE_S 0.5
/* How often the store's age limit is applied. */
#define EXPIRE_EVERY_S 60.0
/* Freed memory goes back to the kernel once no request has been in flight
 * for this long (release_idle_memory). */
#define IDLE_TRIM_S 1.0

/* The request on this connection is complete (being answered): the
 * deadline no longer applies until the next one starts. */
void rd_http_set_busy(rd_http *h, struct request *rq)
{
    if (!rq->conn)
        return;
    pthread_mutex_lock(&h->mu);
    rq->conn->busy = 1;
    pthread_mutex_unlock(&h->mu);
}

/* The client's address of connection c into k (family 0 when unknown). */
static void take_address(struct MHD_Connection *c, struct conn *k)
{
    const union MHD_ConnectionInfo *info =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_CLIENT_ADDRESS);
    const struct sockaddr *sa = info ? info->client_addr : NULL;
    if (sa && sa->sa_family == AF_INET) {
        k->family = AF_INET;
        memcpy(k->addr, &((const struct sockaddr_in *)(const void *)sa)->sin_addr, 4);
    } else if (sa && sa->sa_family == AF_INET6) {
        k->family = AF_INET6;
        memcpy(k->addr, &((const struct sockaddr_in6 *)(const void *)sa)->sin6_addr, 16);
    }
}

/* 429 when k's address already holds --max-per-ip connections, 503 when
 * the server holds --max-connections, else 0 (mu held, k not yet listed).
 * libmicrohttpd's own limits stand RD_HTTP_OVER_SLACK above these and
 * close what comes past them without an answer. */
static int over_limit_locked(const rd_http *h, const struct conn *k)
{
    if (h->nconns - h->nover >= (size_t)h->limits.connections_max)
        return MHD_HTTP_SERVICE_UNAVAILABLE;
    if (!k->family)
        return 0;
    size_t len = k->family == AF_INET ? 4 : 16;
    int same = 0;
    for (const struct conn *o = h->conns; o; o = o->next)
        same += o->family == k->family && !o->over && memcmp(o->addr, k->addr, len) == 0;
    return same >= h->limits.per_ip_max ? MHD_HTTP_TOO_MANY_REQUESTS : 0;
}

/* MHD_OPTION_NOTIFY_CONNECTION: keeps rd_http.conns.  MHD calls CLOSED
 * before it closes the socket, and the timer thread shuts sockets down only
 * under `mu` while the connection is listed, so it never touches a
 * descriptor that has been reused. */
void rd_http_on_connection(void *cls, struct MHD_Connection *c, void **socket_context,
                           enum MHD_ConnectionNotificationCode code)
{
    rd_http *h = cls;
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        const union MHD_ConnectionInfo *info =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
        struct conn *k = calloc(1, sizeof *k);
        if (!k || !info) { /* not tracked: then only the idle timeout applies */
            free(k);
            *socket_context = NULL;
            return;
        }
        k->fd = info->connect_fd;
        k->since = rd_clock_mono_s();
        take_address(c, k);
        pthread_mutex_lock(&h->mu);
        k->over = over_limit_locked(h, k);
        k->next = h->conns;
        if (h->conns)
            h->conns->prev = k;
        h->conns = k;
        h->nconns++;
        h->nover += k->over != 0;
        pthread_mutex_unlock(&h->mu);
        *socket_context = k;
        return;
    }
    struct conn *k = *socket_context;
    if (!k)
        return;
    pthread_mutex_lock(&h->mu);
    if (k->prev)
        k->prev->next = k->next;
    else
        h->conns = k->next;
    if (k->next)
        k->next->prev = k->prev;
    h->nconns--;
    h->nover -= k->over != 0;
    pthread_mutex_unlock(&h->mu);
    free(k);
    *socket_context = NULL;
}

/* Shuts down the sockets whose request is overdue (mu held).  MHD sees the
 * socket end and closes the connection in its own thread. */
static void enforce_deadline_locked(rd_http *h, double now)
{
    for (struct conn *k = h->conns; k; k = k->next)
        if (!k->busy && !k->shut &&
            now - k->since > (k->over ? OVER_DEADLINE_S : h->limits.request_deadline_s)) {
            shutdown(k->fd, SHUT_RDWR);
            k->shut = 1;
            h->deadline_closed++;
        }
}

/* Suspends a request until job `id` ends or `seconds` pass; the timer
 * thread resumes it, and MHD then calls on_request again (rd_routes_answer_waiter). */
enum MHD_Result rd_http_suspend_for(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                    enum wait_kind kind, const char *id, double seconds)
{
    rd_http_set_busy(h, rq);
    rq->waiting = kind;
    rq->until = rd_clock_mono_s() + seconds;
    memcpy(rq->job_id, id, sizeof rq->job_id);
    MHD_suspend_connection(c);
    pthread_mutex_lock(&h->mu);
    rq->prev = NULL;
    rq->next = h->waiters;
    if (h->waiters)
        h->waiters->prev = rq;
    h->waiters = rq;
    h->poked = 1; /* the job may have ended before the request was listed */
    pthread_cond_signal(&h->wake);
    pthread_mutex_unlock(&h->mu);
    return MHD_YES;
}

/* Takes the waiters that may go on (job final, time up, or `all`) off the
 * list (mu held) and returns them chained through `next`; the caller resumes
 * them after unlocking (MHD takes its own locks in MHD_resume_connection). */
static struct request *take_ready_locked(rd_http *h, double now, int all)
{
    struct request *ready = NULL, *rq = h->waiters;
    while (rq) {
        struct request *next = rq->next;
        int final = rq->waiting == WAIT_SWEEP ? rd_sweeps_is_final(h->sweeps, rq->job_id)
                                              : rd_jobs_is_final(h->jobs, rq->job_id);
        if (all || now >= rq->until || final) {
            if (rq->prev)
                rq->prev->next = rq->next;
            else
                h->waiters = rq->next;
            if (rq->next)
                rq->next->prev = rq->prev;
            rq->prev = NULL;
            rq->next = ready;
            ready = rq;
        }
        rq = next;
    }
    return ready;
}

static void resume_all(struct request *ready)
{
    while (ready) {
        struct request *next = ready->next;
        ready->next = NULL;
        ready->resumed = 1;
        MHD_resume_connection(ready->c);
        ready = next;
    }
}

/* Hands the arenas' free pages back to the kernel once the server has been
 * idle (no request in flight) for IDLE_TRIM_S after serving something (mu
 * held; released around the trim).  main.c keeps up to 32 MiB free at the
 * top of each arena so that small jobs reuse their pages, and glibc never
 * returns free pages below an arena's top on its own: after a burst of
 * 1 MiB bodies (each buffered, then parsed by jansson into many small
 * blocks, on up to --http-threads threads and their arenas) RSS stayed at
 * ~540 MB for good.  malloc_trim(0) releases every whole free page of every
 * arena; it runs once per idle spell, never under load, and costs ~1 ms on
 * a small heap.  Elsewhere than glibc, nothing to do. */
static void release_idle_memory(rd_http *h, double now)
{
    if (!h->trim_due || h->in_flight > 0 || now - h->idle_since < IDLE_TRIM_S)
        return;
    h->trim_due = 0;
#if defined(__GLIBC__)
    pthread_mutex_unlock(&h->mu);
    (void)malloc_trim(0);
    pthread_mutex_lock(&h->mu);
#endif
}

/* The timer thread: resumes waiters, enforces the request deadline, applies
 * the job store's age limit; wakes on rd_http_job_ended or every TICK_S. */
void *rd_http_timer_main(void *arg)
{
    rd_http *h = arg;
    double next_expire = rd_clock_mono_s() + EXPIRE_EVERY_S;
    pthread_mutex_lock(&h->mu);
    while (!h->stop) {
        if (!h->poked) {
            struct timespec tick = rd_clock_mono_deadline(TICK_S);
            pthread_cond_timedwait(&h->wake, &h->mu, &tick);
        }
        h->poked = 0;
        double now = rd_clock_mono_s();
        struct request *ready = take_ready_locked(h, now, 0);
        enforce_deadline_locked(h, now);
        release_idle_memory(h, now);
        pthread_mutex_unlock(&h->mu);
        resume_all(ready);
        if (now >= next_expire) {
            rd_jobs_expire(h->jobs);
            next_expire = now + EXPIRE_EVERY_S;
        }
        pthread_mutex_lock(&h->mu);
    }
    struct request *ready = take_ready_locked(h, 0, 1);
    pthread_mutex_unlock(&h->mu);
    resume_all(ready);
    return NULL;
}

void rd_http_job_ended(void *http)
{
    rd_http *h = http;
    pthread_mutex_lock(&h->mu);
    h->poked = 1;
    pthread_cond_signal(&h->wake);
    pthread_mutex_unlock(&h->mu);
}
