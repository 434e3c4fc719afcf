/* ch01_srgb.c: how fast and how exact is each way to encode sRGB bytes?
 *
 *   build/rel/bench/ch01_srgb > figures/ch01-srgb.csv     (make charts)
 *
 * Every method turns a linear value in [0, 1] into an 8-bit code. Speed: the
 * time per value over a fixed pseudo-random array of 2^20 values, every
 * method timed in the same interleaved rounds (bench/timing.h).
 * Accuracy: the code each method gives against the correctly rounded code of
 * the exact sRGB curve evaluated in long double: the largest difference over
 * 2^20 + 1 evenly spaced values and both sides of every boundary between two
 * codes (where a method that is slightly off flips a code), and the fraction
 * of the evenly spaced values that get a wrong code. CSV: a machine line,
 * then method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns, one row
 * per method and error kind. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "../tests/rng.h"
#include "timing.h"


/* ---------------------------------------------------------------- the methods */

static long double srgb_long(long double L)
{
    return L <= 0.0031308L ? 12.92L * L : 1.055L * powl(L, 1 / 2.4L) - 0.055L;
}

static unsigned char to_byte(double encoded)
{
    if (!(encoded > 0))
        return 0;
    return encoded >= 1 ? 255 : (unsigned char)(255 * encoded + 0.5);
}

/* The program's own: exact formula, double pow (image.c). */
static NOINLINE unsigned char by_pow(double L) { return srgb_to_byte(L); }

/* The exact formula in float: half the bits, faster pow on some machines. */
static NOINLINE unsigned char by_powf(double L)
{
    float x = (float)L;
    if (!(x > 0))
        return 0;
    return to_byte(x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1 / 2.4f) - 0.055f);
}

/* The sheet's model with gamma 2.2. */
static NOINLINE unsigned char by_gamma22(double L) { return to_byte(gamma_encode(L, 2.2)); }

/* Gamma 2.0: a square root, the cheapest curve with the right shape. */
static NOINLINE unsigned char by_sqrt(double L) { return to_byte(L > 0 ? sqrt(L) : 0); }

/* A fit of sRGB by roots of L (Ian Taylor's coefficients, published on
 * chilliant.com, "sRGB approximations for HLSL"): three square roots, no pow. */
static NOINLINE unsigned char by_root_fit(double L)
{
    if (!(L > 0))
        return 0;
    double s1 = sqrt(L), s2 = sqrt(s1), s3 = sqrt(s2);
    return to_byte(0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * L);
}

#ifdef YOURS_SRGB
/* make chart-ch01 WORKBOOK=1: the reader's srgb_to_byte (exercise 1.2),
 * renamed in a copy of the workbook's image.o, timed among the others. */
unsigned char yours_srgb_to_byte(double linear);
static NOINLINE unsigned char by_yours(double L) { return yours_srgb_to_byte(L); }
#define YOURS_COUNT 1
#else
#define YOURS_COUNT 0
#endif

/* A table of codes indexed by L rounded to one of lut_size steps. The chart
 * has four sizes, each its own table; lut points to the one in use. */
enum { N_LUTS = 4 };
static const int lut_sizes[N_LUTS] = {256, 1024, 4096, 65536};
static unsigned char luts[N_LUTS][65536];
static const unsigned char *lut;
static int lut_size;

static void lut_fill(int which)
{
    int size = lut_sizes[which];
    for (int k = 0; k < size; k++)
        luts[which][k] = (unsigned char)lroundl(255 * srgb_long((long double)k / (size - 1)));
}

static void lut_use(int which)
{
    lut = luts[which];
    lut_size = lut_sizes[which];
}

static NOINLINE unsigned char by_lut(double L)
{
    if (!(L > 0))
        return lut[0];
    return L >= 1 ? lut[lut_size - 1] : lut[(int)(L * (lut_size - 1) + 0.5)];
}

/* ---------------------------------------------------------------- accuracy */

typedef unsigned char (*method_fn)(double);

typedef struct {
    int max_code_error;
    double wrong_fraction;
} accuracy;

static int code_error(method_fn f, double L)
{
    return abs((int)f(L) - (int)lroundl(255 * srgb_long(L)));
}

static accuracy measure_accuracy(method_fn f)
{
    accuracy a = {0, 0};
    long wrong = 0;
    for (long k = 0; k <= (1L << 20); k++) {
        int error = code_error(f, (double)k / (1L << 20));
        a.max_code_error = error > a.max_code_error ? error : a.max_code_error;
        wrong += error != 0;
    }
    a.wrong_fraction = (double)wrong / ((1L << 20) + 1);
    for (int code = 0; code < 255; code++) {
        /* The L where the exact curve crosses code + 1/2 (sRGB inverted),
         * approached from both sides to within a relative 1e-9: closer than
         * that, a double result may round either way, whatever the method. */
        long double e = (code + 0.5L) / 255;
        long double L = e <= 0.04045L ? e / 12.92L : powl((e + 0.055L) / 1.055L, 2.4L);
        for (int side = -1; side <= 1; side += 2) {
            int error = code_error(f, (double)(L * (1 + side * 1e-9L)));
            a.max_code_error = error > a.max_code_error ? error : a.max_code_error;
        }
    }
    return a;
}

/* ---------------------------------------------------------------- speed */

#define N_INPUTS (1 << 20)

static double inputs[N_INPUTS];

static void fill_inputs(void)
{
    rng_state rng = {0x2545F4914F6CDD1DULL}; /* fixed seed: the same inputs every run */
    for (int k = 0; k < N_INPUTS; k++)
        inputs[k] = rng_uniform01(&rng);
}

/* reps encodings, whole passes over the inputs (the case's cycle). */
static void run_method(void *ctx, long reps)
{
    method_fn f = *(method_fn *)ctx;
    for (long done = 0; done < reps; done += N_INPUTS) {
        unsigned sum = 0;
        for (int k = 0; k < N_INPUTS; k++)
            sum += f(inputs[k]);
        bench_sink += sum;
    }
}

static void run_lut(void *ctx, long reps)
{
    lut_use(*(const int *)ctx);
    run_method(&(method_fn){by_lut}, reps);
}

/* ---------------------------------------------------------------- report */

enum { N_FORMULAS = 5 + YOURS_COUNT, N_CASES = N_FORMULAS + N_LUTS };

int main(void)
{
    static const struct {
        const char *name, *param;
        method_fn f;
    } formulas[N_FORMULAS] = {
        {"pow", "double", by_pow},         {"powf", "float", by_powf},
        {"gamma", "2.2", by_gamma22},      {"sqrt", "2.0", by_sqrt},
        {"root-fit", "3 sqrt", by_root_fit},
#ifdef YOURS_SRGB
        {"yours", "exercise 1.2", by_yours},
#endif
    };
    static method_fn fns[N_FORMULAS];
    static int which[N_LUTS];
    static char lut_params[N_LUTS][16];
    bench_case cases[N_CASES];
    fill_inputs();
    for (int m = 0; m < N_FORMULAS; m++) {
        fns[m] = formulas[m].f;
        cases[m] = (bench_case){formulas[m].name, formulas[m].param, run_method, &fns[m], N_INPUTS};
    }
    for (int t = 0; t < N_LUTS; t++) {
        lut_fill(t);
        which[t] = t;
        snprintf(lut_params[t], sizeof lut_params[t], "%d", lut_sizes[t]);
        cases[N_FORMULAS + t] = (bench_case){"lut", lut_params[t], run_lut, &which[t], N_INPUTS};
    }
    bench_timing timing[N_CASES];
    bench_time_cases(cases, N_CASES, timing);

    bench_print_machine();
    bench_csv_header();
    for (int c = 0; c < N_CASES; c++) {
        method_fn f = c < N_FORMULAS ? fns[c] : by_lut;
        if (c >= N_FORMULAS)
            lut_use(c - N_FORMULAS);
        accuracy a = measure_accuracy(f);
        bench_row(cases[c].method, cases[c].param, &timing[c], "%.0f", a.max_code_error,
                  "max_code_error");
        bench_row(cases[c].method, cases[c].param, &timing[c], "%.6f", a.wrong_fraction,
                  "wrong_code_fraction");
    }
    return 0;
}
