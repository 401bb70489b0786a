/*
 * rd_clock — the server's clocks: monotonic seconds for timeouts and
 * latencies, absolute monotonic deadlines for pthread_cond_timedwait (the
 * condition variables are created with CLOCK_MONOTONIC), and the ISO 8601
 * UTC text of a wall-clock time for the job and sweep documents.
 */
#ifndef RD_CLOCK_H
#define RD_CLOCK_H

#include <stddef.h>
#include <time.h>

/* CLOCK_MONOTONIC now, in s. */
double rd_clock_mono_s(void);
/* The absolute CLOCK_MONOTONIC time `seconds` (>= 0) from now. */
struct timespec rd_clock_mono_deadline(double seconds);
/* "2026-11-23T10:56:14.714Z" for a CLOCK_REALTIME time into buf (at least
 * 32 bytes); returns 0, or -1 for the zero time (never set) or a time
 * gmtime_r cannot convert. */
int rd_clock_iso8601(const struct timespec *ts, char *buf, size_t size);

#endif
