/* timing.h: the timing harness of every benchmark in bench/.
 *
 * Describe each thing a chart times as a bench_case, then time them all
 * together:
 *
 *     static void run_pow(void *ctx, long reps) { ...reps operations... }
 *     bench_case cases[] = {{"pow", "double", run_pow, NULL, N_INPUTS}, ...};
 *     bench_timing t[N];
 *     bench_time_cases(cases, N, t);       t[k].median: ns per operation
 *
 * run(ctx, reps) performs reps operations (one encoded value, one ray-sphere
 * call, one ray against a whole mesh: what the chart calls an operation) and
 * feeds their results to bench_sink, so that the compiler cannot drop them.
 * cycle is the size of the case's input set: every batch is a whole number
 * of passes over it, so that every batch sees the same inputs (1: no cycle,
 * only for operations that all cost the same: calibration would otherwise
 * size the batches from the cheap first few, and every batch would differ).
 *
 * What bench_time_cases does:
 *   1. Calibrates each case: reps grows until one batch takes at least
 *      BENCH_MIN_BATCH_NS (20 ms) of CPU time; then one more batch, a warm-up.
 *   2. Runs bench_rounds() rounds (21, or $BENCH_ROUNDS, odd, 5..201). In
 *      each round every case runs one batch, the cases INTERLEAVED and the
 *      order rotated by one each round (A B C, B C A, C A B, A B C, ...), so
 *      that drift, other processes and clock changes hit all cases alike.
 *   3. Measures each batch in thread CPU time (CLOCK_THREAD_CPUTIME_ID: time
 *      the scheduler gives to other processes is not counted) and wall time
 *      (CLOCK_MONOTONIC), and reports, in ns per operation of CPU time, the
 *      median over the rounds, the lower and upper quartiles, and the 95%
 *      confidence interval of the median from order statistics (with 21
 *      rounds that interval is exactly the quartiles: the 6th and 16th of 21
 *      batches, 97% coverage); and the median wall time.
 *
 * CSV rows (bench_csv_header, bench_row) have the columns
 *     method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns
 * preceded by one comment line, "# machine: CPU, compiler and flags, date"
 * (bench_print_machine), which the chart scripts print under each chart and
 * which gnuplot and tools/checks/check_quotes.sh skip. */
#ifndef BENCH_TIMING_H
#define BENCH_TIMING_H

#define NOINLINE __attribute__((noinline)) /* one call per operation, as in the renderer */

#define BENCH_MIN_BATCH_NS 20e6

/* Where every benchmark puts its results, so that no work is optimised away. */
extern volatile double bench_sink;

typedef struct {
    const char *method, *param;        /* the CSV's first two columns */
    void (*run)(void *ctx, long reps); /* performs reps operations */
    void *ctx;
    long cycle; /* reps is a multiple of this; 0 or 1: any reps */
} bench_case;

typedef struct {
    double median, q1, q3; /* ns per operation, thread CPU time */
    double ci_lo, ci_hi;   /* 95% confidence interval of the median */
    double wall_median;    /* ns per operation, wall clock */
    long reps;             /* operations per batch */
    int rounds;            /* batches measured */
} bench_timing;

/* The number of rounds: 21, or $BENCH_ROUNDS when that is odd and in 5..201. */
int bench_rounds(void);

/* Times the n cases together; out[k] is case k's timing. */
void bench_time_cases(const bench_case *cases, int n, bench_timing *out);

/* The same with a stated number of rounds (odd, 5..201), for cases whose
 * one batch takes a tenth of a second or more, where 21 rounds would take
 * minutes.
 * $BENCH_ROUNDS does not change it. With 5 to 7 rounds the median's 95%
 * interval is the whole range (ci_lo, ci_hi: the fastest and slowest). */
void bench_time_cases_rounds(const bench_case *cases, int n, int rounds,
                             bench_timing *out);

/* The timing of n samples measured elsewhere, in ns per operation (a phase
 * that a child process reports, say): the same median, quartiles and
 * interval as bench_time_cases gives; wall_median is the median, reps 1.
 * Sorts ns. */
void bench_timing_of_samples(double *ns, int n, bench_timing *out);

/* t with every time multiplied by factor: per pixel from per image, say. */
bench_timing bench_timing_scaled(bench_timing t, double factor);

/* "# machine: ..." on a line of its own: print it first. */
void bench_print_machine(void);

/* The CSV's column names, on a line of its own. */
void bench_csv_header(void);

/* One CSV row; error is printed with error_format (a printf format for one
 * double). With no timing (t NULL) the time columns are left empty. */
void bench_row(const char *method, const char *param, const bench_timing *t,
               const char *error_format, double error, const char *kind);

/* The median of values[0..n), which it sorts. */
double bench_median(double *values, int n);

/* qsort's comparison for doubles, ascending. */
int bench_compare_doubles(const void *a, const void *b);

#endif
