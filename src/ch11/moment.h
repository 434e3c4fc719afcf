/* moment.h: one moment on the wall clock and the processor clock
 * (chapter 1). */
#ifndef MOMENT_H
#define MOMENT_H

#include <time.h>

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


#endif
