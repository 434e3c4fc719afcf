/* timing.c: the timing harness of bench/; timing.h is its manual. */
#include "timing.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifndef BENCH_FLAGS
#define BENCH_FLAGS "(flags unknown)" /* the Makefile passes its -O and CFLAGS */
#endif

volatile double bench_sink;

/* ---------------------------------------------------------------- clocks */

static double clock_ns(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

/* One batch of reps operations: its thread CPU time and wall time, in ns. */
static void time_batch(const bench_case *c, long reps, double *cpu, double *wall)
{
    double wall0 = clock_ns(CLOCK_MONOTONIC), cpu0 = clock_ns(CLOCK_THREAD_CPUTIME_ID);
    c->run(c->ctx, reps);
    *cpu = clock_ns(CLOCK_THREAD_CPUTIME_ID) - cpu0;
    *wall = clock_ns(CLOCK_MONOTONIC) - wall0;
}

/* ---------------------------------------------------------------- statistics */

int bench_compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *values, int n)
{
    qsort(values, (size_t)n, sizeof values[0], bench_compare_doubles);
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

/* The p-quantile of sorted[0..n), interpolating between order statistics. */
static double quantile(const double *sorted, int n, double p)
{
    double h = p * (n - 1);
    int below = (int)h;
    return below + 1 < n ? sorted[below] + (h - below) * (sorted[below + 1] - sorted[below])
                         : sorted[n - 1];
}

/* The m for which the m-th smallest and m-th largest of n values bound the
 * median with at least 95% confidence: the largest m with P(B < m) <= 2.5%,
 * B binomial(n, 1/2). 0 when n is too small for any. */
static int median_ci_rank(int n)
{
    double pmf = 1, below = 0; /* P(B = j), P(B < j) */
    for (int j = 0; j < n; j++)
        pmf /= 2;
    int m = 0;
    for (int j = 0; j <= n / 2; j++) {
        if (below > 0.025)
            break;
        m = j;
        below += pmf;
        pmf = pmf * (n - j) / (j + 1);
    }
    return m;
}

/* The statistics of n batches of reps operations, from their thread CPU
 * times (or, for bench_timing_of_samples, the samples) and wall times. */
static void summarise(double *cpu, double *wall, int n, long reps, bench_timing *t)
{
    qsort(cpu, (size_t)n, sizeof cpu[0], bench_compare_doubles);
    int m = median_ci_rank(n);
    t->median = quantile(cpu, n, 0.5) / reps;
    t->q1 = quantile(cpu, n, 0.25) / reps;
    t->q3 = quantile(cpu, n, 0.75) / reps;
    t->ci_lo = (m > 0 ? cpu[m - 1] : cpu[0]) / reps;
    t->ci_hi = (m > 0 ? cpu[n - m] : cpu[n - 1]) / reps;
    t->wall_median = bench_median(wall, n) / reps;
    t->reps = reps;
    t->rounds = n;
}

/* ---------------------------------------------------------------- timing */

int bench_rounds(void)
{
    const char *text = getenv("BENCH_ROUNDS");
    if (!text)
        return 21;
    long rounds = strtol(text, NULL, 10);
    if (rounds < 5 || rounds > 201 || rounds % 2 == 0) {
        fprintf(stderr, "bench: BENCH_ROUNDS=%s is not an odd number in 5..201: using 21\n", text);
        return 21;
    }
    return (int)rounds;
}

static long round_up(long reps, long cycle)
{
    return cycle > 1 ? (reps + cycle - 1) / cycle * cycle : reps;
}

/* The batch size of a case: grown until a batch takes BENCH_MIN_BATCH_NS. */
static long calibrate(const bench_case *c)
{
    long reps = round_up(1, c->cycle);
    for (;;) {
        double cpu, wall;
        time_batch(c, reps, &cpu, &wall);
        if (cpu >= BENCH_MIN_BATCH_NS)
            return reps;
        double grow = cpu > 0 ? 1.25 * BENCH_MIN_BATCH_NS / cpu : 100;
        grow = grow < 2 ? 2 : grow > 100 ? 100 : grow;
        reps = round_up((long)((double)reps * grow), c->cycle);
    }
}

void bench_time_cases(const bench_case *cases, int n, bench_timing *out)
{
    bench_time_cases_rounds(cases, n, bench_rounds(), out);
}

void bench_timing_of_samples(double *ns, int n, bench_timing *out)
{
    double *copy = malloc((size_t)n * sizeof *copy);
    if (!copy) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    memcpy(copy, ns, (size_t)n * sizeof *copy);
    summarise(ns, copy, n, 1, out);
    free(copy);
}

void bench_time_cases_rounds(const bench_case *cases, int n, int rounds, bench_timing *out)
{
    if (rounds < 5 || rounds > 201 || rounds % 2 == 0) {
        fprintf(stderr, "bench: %d rounds is not an odd number in 5..201\n", rounds);
        exit(1);
    }
    long *reps = malloc((size_t)n * sizeof *reps);
    double *cpu = malloc((size_t)n * (size_t)rounds * sizeof *cpu);
    double *wall = malloc((size_t)n * (size_t)rounds * sizeof *wall);
    if (!reps || !cpu || !wall) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    double start = clock_ns(CLOCK_MONOTONIC);
    for (int k = 0; k < n; k++) {
        double ignored_cpu, ignored_wall;
        reps[k] = calibrate(&cases[k]);
        time_batch(&cases[k], reps[k], &ignored_cpu, &ignored_wall); /* warm-up */
    }
    for (int r = 0; r < rounds; r++)
        for (int j = 0; j < n; j++) {
            int k = (r + j) % n;
            time_batch(&cases[k], reps[k], &cpu[k * rounds + r], &wall[k * rounds + r]);
        }
    for (int k = 0; k < n; k++)
        summarise(&cpu[k * rounds], &wall[k * rounds], rounds, reps[k], &out[k]);
    fprintf(stderr, "bench: %d cases from %s,%s: %d interleaved rounds, %.1f s\n", n,
            cases[0].method, cases[0].param, rounds, (clock_ns(CLOCK_MONOTONIC) - start) / 1e9);
    free(reps);
    free(cpu);
    free(wall);
}

bench_timing bench_timing_scaled(bench_timing t, double factor)
{
    t.median *= factor, t.q1 *= factor, t.q3 *= factor;
    t.ci_lo *= factor, t.ci_hi *= factor, t.wall_median *= factor;
    return t;
}

/* ---------------------------------------------------------------- output */

/* The processor's name from /proc/cpuinfo, or "unknown CPU". */
static void cpu_model(char *name, size_t size)
{
    snprintf(name, size, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[256];
    while (fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (colon && (!strncmp(line, "model name", 10) || !strncmp(line, "Model", 5))) {
            colon += 1 + strspn(colon + 1, " \t");
            colon[strcspn(colon, "\n")] = '\0';
            snprintf(name, size, "%s", colon);
            break;
        }
    }
    fclose(f);
}

void bench_print_machine(void)
{
    char cpu[128], date[32], load[16] = "?";
    cpu_model(cpu, sizeof cpu);
    time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", gmtime(&now));
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%15s", load) != 1)
            snprintf(load, sizeof load, "?");
        fclose(f);
    }
#if defined(__clang__) || !defined(__GNUC__)
    const char *compiler = "";
#else
    const char *compiler = "gcc ";
#endif
    printf("# machine: %s, %ld CPUs (load %s); %s%s %s; %s\n", cpu, sysconf(_SC_NPROCESSORS_ONLN),
           load, compiler, __VERSION__, BENCH_FLAGS, date);
}

void bench_csv_header(void)
{
    printf("method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns\n");
}

void bench_row(const char *method, const char *param, const bench_timing *t,
               const char *error_format, double error, const char *kind)
{
    printf("%s,%s,", method, param);
    if (t)
        printf("%.3f", t->median);
    printf(",");
    printf(error_format, error);
    printf(",%s,", kind);
    if (t)
        printf("%.3f,%.3f,%.3f", t->q1, t->q3, t->wall_median);
    else
        printf(",,");
    printf("\n");
}
