/* bench_util.h: timing helpers shared by the benchmarks in bench/.
 *
 * A benchmark times a batch of work several times and keeps the median, so
 * that a batch interrupted by the operating system does not move the result.
 * Results go through a volatile sink so that the compiler cannot drop work
 * whose result is never printed. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <stdlib.h>
#include <time.h>

#define NOINLINE __attribute__((noinline)) /* one call per operation, as in the renderer */

static volatile double bench_sink;

/* The monotonic clock in nanoseconds: immune to changes of the system time. */
static inline double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

static inline int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of values[0..n), which it sorts. */
static inline double median(double *values, int n)
{
    qsort(values, (size_t)n, sizeof values[0], compare_doubles);
    return values[n / 2];
}

#endif
