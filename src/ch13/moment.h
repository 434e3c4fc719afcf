/* moment.h: one moment on the wall clock and the processor clock
 * (chapter 1). */
#ifndef MOMENT_H
#define MOMENT_H

#include <time.h>
/* <<moment includes>> ch12 */
#include <pthread.h>
#include <unistd.h> /* _POSIX_CLOCK_SELECTION */

typedef struct {
    double wall; /* seconds on the monotonic clock */
    double cpu;  /* seconds of processor time, on every core */
} moment;

static inline double moment_seconds_of(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline moment moment_now(void)
{
    return (moment){moment_seconds_of(CLOCK_MONOTONIC),
                    moment_seconds_of(CLOCK_PROCESS_CPUTIME_ID)};
}

/* <<waiting on the monotonic clock>> ch12 */
#if defined(_POSIX_CLOCK_SELECTION) && _POSIX_CLOCK_SELECTION >= 0
#define MOMENT_WAIT_CLOCK CLOCK_MONOTONIC
static inline void moment_choose_clock(pthread_condattr_t *a)
{
    pthread_condattr_setclock(a, MOMENT_WAIT_CLOCK);
}
#else /* a condition waits on the calendar's clock */
#define MOMENT_WAIT_CLOCK CLOCK_REALTIME
static inline void moment_choose_clock(pthread_condattr_t *a) { (void)a; }
#endif

/* pthread_cond_init for a condition whose timed waits end at moments on
 * MOMENT_WAIT_CLOCK: the monotonic clock wherever a system can choose. */
static inline int moment_condition_init(pthread_cond_t *c)
{
    pthread_condattr_t a;
    int error = pthread_condattr_init(&a);
    if (error != 0)
        return error;
    moment_choose_clock(&a);
    error = pthread_cond_init(c, &a);
    pthread_condattr_destroy(&a);
    return error;
}

/* seconds from now on MOMENT_WAIT_CLOCK, for pthread_cond_timedwait. */
static inline struct timespec moment_deadline(double seconds)
{
    struct timespec t;
    clock_gettime(MOMENT_WAIT_CLOCK, &t);
    long long ns = t.tv_nsec + (long long)(seconds * 1e9);
    t.tv_sec += (time_t)(ns / 1000000000), t.tv_nsec = ns % 1000000000;
    return t;
}

#endif
