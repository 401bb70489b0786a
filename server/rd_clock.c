/* rd_clock.c — the server's clocks (contract in rd_clock.h). */
#include "rd_clock.h"

#include <math.h>
#include <stdio.h>

double rd_clock_mono_s(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

struct timespec rd_clock_mono_deadline(double seconds)
{
    struct timespec ts = {0, 0};
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return ts;
    double whole = floor(seconds);
    ts.tv_sec += (time_t)whole;
    ts.tv_nsec += (long)((seconds - whole) * 1e9);
    if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
    }
    return ts;
}

int rd_clock_iso8601(const struct timespec *ts, char *buf, size_t size)
{
    if (ts->tv_sec == 0 && ts->tv_nsec == 0)
        return -1;
    struct tm tm;
    time_t t = ts->tv_sec;
    if (!gmtime_r(&t, &tm))
        return -1;
    snprintf(buf, size, "%04d-%02d-%02dT%02d:%02d:%02d.%03ldZ", tm.tm_year + 1900, tm.tm_mon + 1,
             tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, ts->tv_nsec / 1000000L);
    return 0;
}
