/* bench_util.h: the older timing interface, kept only until every bench is
 * on the shared harness (timing.h). now_ns reads the thread's CPU time, as
 * the harness does; median sorts. New benches use timing.h directly. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <time.h>
#include "timing.h"

/* The thread's CPU time in nanoseconds. */
static inline double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

/* The median of values[0..n), which it sorts. */
static inline double median(double *values, int n) { return bench_median(values, n); }

#endif
