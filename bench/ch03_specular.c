/* ch03_specular.c: five ways to compute a highlight, against Phong.
 *
 *   build/rel/bench/ch03_specular > figures/ch03-specular.csv    (make charts)
 *
 * Each method computes a highlight term in [0, 1] from a unit normal n, a
 * unit direction l towards the light and a unit direction v towards the
 * viewer, with shininess k (10 and 100):
 *   phong-pow       <r,v>^k with pow: the program's Phong
 *   phong-squaring  <r,v>^k by repeated squaring (k a whole number)
 *   phong-schlick   Schlick's rational x / (k - k x + x), x = <r,v>
 *   blinn-4k        <n,h>^(4k): the program's Blinn-Phong, the sheet's rule
 *   blinn-fitted    <n,h>^e with the e that minimises the rms error
 * The reference is Phong in long double. n = (0,0,1); l and v are spread
 * evenly over the hemisphere above the surface (200,000 fixed pseudo-random
 * pairs). Rows:
 *   max_abs, rms               error over the whole hemisphere
 *   max_abs_at_incidence       for blinn-4k and blinn-fitted: the largest
 *                              error over v with l at a fixed angle from n
 *                              (param "k:angle")
 *   exponent                   for blinn-fitted: the fitted e (in error)
 * ns_per_op is the time of one evaluation (cosine and power), all ten
 * method and k pairs timed in the same interleaved rounds (bench/timing.h).
 * CSV: a machine line, then the columns
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "shade.h"
#include "../tests/rng.h"
#include "timing.h"

#define N_PAIRS 200000

typedef double (*highlight_fn)(vec3 n, vec3 l, vec3 v, double k);

/* ---------------------------------------------------------------- methods */

static double power_by_squaring(double x, unsigned k)
{
    double result = 1;
    for (; k > 0; k >>= 1, x *= x)
        if (k & 1)
            result *= x;
    return result;
}

static NOINLINE double by_phong_pow(vec3 n, vec3 l, vec3 v, double k)
{
    return specular_phong(n, l, v, k);
}

static NOINLINE double by_phong_squaring(vec3 n, vec3 l, vec3 v, double k)
{
    return power_by_squaring(phong_cosine(n, l, v), (unsigned)k);
}

/* Schlick, "An inexpensive BRDF model for physically-based rendering" (1994). */
static NOINLINE double by_phong_schlick(vec3 n, vec3 l, vec3 v, double k)
{
    double x = phong_cosine(n, l, v);
    return x / (k - k * x + x);
}

static NOINLINE double by_blinn_4k(vec3 n, vec3 l, vec3 v, double k)
{
    return specular_blinn(n, l, v, k);
}

static double fitted_exponent; /* set by fit_blinn_exponent for the current k */

static NOINLINE double by_blinn_fitted(vec3 n, vec3 l, vec3 v, double k)
{
    (void)k;
    return pow(blinn_cosine(n, l, v), fitted_exponent);
}

/* ---------------------------------------------------------------- samples */

static vec3 lights[N_PAIRS], viewers[N_PAIRS];
static const vec3 NORMAL = {0, 0, 1};
static rng_state rng = {0x853C49E6748FEA9BULL}; /* fixed seed */

static double uniform01(void) { return rng_uniform01(&rng); }

/* A direction uniform over the hemisphere z > 0. */
static vec3 hemisphere_direction(void)
{
    double z = uniform01(), phi = 2 * M_PI * uniform01(), s = sqrt(1 - z * z);
    return (vec3){s * cos(phi), s * sin(phi), z > 1e-9 ? z : 1e-9};
}

static long double phong_reference(vec3 n, vec3 l, vec3 v, double k)
{
    long double nl = (long double)n.x * l.x + (long double)n.y * l.y + (long double)n.z * l.z;
    long double r[3] = {2 * nl * n.x - l.x, 2 * nl * n.y - l.y, 2 * nl * n.z - l.z};
    long double rv = r[0] * v.x + r[1] * v.y + r[2] * v.z;
    return rv > 0 ? powl(rv, k) : 0;
}

/* ---------------------------------------------------------------- errors */

typedef struct {
    double max_abs, rms;
} error_stats;

static error_stats hemisphere_error(highlight_fn f, double k, int n_pairs)
{
    double worst = 0, sum2 = 0;
    for (int i = 0; i < n_pairs; i++) {
        double e = (double)fabsl(f(NORMAL, lights[i], viewers[i], k) -
                                 phong_reference(NORMAL, lights[i], viewers[i], k));
        worst = e > worst ? e : worst;
        sum2 += e * e;
    }
    return (error_stats){worst, sqrt(sum2 / n_pairs)};
}

/* Largest error over the viewer directions with the light theta from n. */
static double error_at_incidence(highlight_fn f, double k, double theta_deg)
{
    double t = theta_deg * M_PI / 180, worst = 0;
    vec3 l = {sin(t), 0, cos(t)};
    for (int i = 0; i < N_PAIRS / 4; i++) {
        double e = (double)fabsl(f(NORMAL, l, viewers[i], k) -
                                 phong_reference(NORMAL, l, viewers[i], k));
        worst = e > worst ? e : worst;
    }
    return worst;
}

/* Golden-section search for the Blinn exponent with the smallest rms error
 * on a subset of the pairs (the largest error is near 1 at grazing angles
 * whatever the exponent, so it cannot guide a fit). */
static void fit_blinn_exponent(double k)
{
    const double g = (sqrt(5.0) - 1) / 2;
    double lo = k, hi = 8 * k;
    for (int step = 0; step < 40; step++) {
        double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        fitted_exponent = a;
        double ea = hemisphere_error(by_blinn_fitted, k, 20000).rms;
        fitted_exponent = b;
        double eb = hemisphere_error(by_blinn_fitted, k, 20000).rms;
        if (ea < eb)
            hi = b;
        else
            lo = a;
    }
    fitted_exponent = (lo + hi) / 2;
}

/* ---------------------------------------------------------------- speed */

typedef struct {
    highlight_fn f;
    double k, exponent; /* exponent: blinn-fitted's for this k */
} timed_method;

/* reps evaluations, whole passes over the pairs. */
static void run_method(void *ctx, long reps)
{
    const timed_method *m = ctx;
    fitted_exponent = m->exponent;
    for (long done = 0; done < reps; done += N_PAIRS) {
        double sum = 0;
        for (int i = 0; i < N_PAIRS; i++)
            sum += m->f(NORMAL, lights[i], viewers[i], m->k);
        bench_sink += sum;
    }
}

/* ---------------------------------------------------------------- report */

#ifdef YOURS_HIGHLIGHTS
/* make chart-ch03 WORKBOOK=1: the reader's highlights (exercise 3.1),
 * renamed in a copy of the workbook's shade.o, timed among the others. */
double yours_specular_phong(vec3 n, vec3 l, vec3 v, double k);
double yours_specular_blinn(vec3 n, vec3 l, vec3 v, double k);
static NOINLINE double by_yours_phong(vec3 n, vec3 l, vec3 v, double k)
{
    return yours_specular_phong(n, l, v, k);
}
static NOINLINE double by_yours_blinn(vec3 n, vec3 l, vec3 v, double k)
{
    return yours_specular_blinn(n, l, v, k);
}
#endif

static const struct {
    const char *name;
    highlight_fn f;
} methods[] = {
    {"phong-pow", by_phong_pow},         {"phong-squaring", by_phong_squaring},
    {"phong-schlick", by_phong_schlick}, {"blinn-4k", by_blinn_4k},
    {"blinn-fitted", by_blinn_fitted},
#ifdef YOURS_HIGHLIGHTS
    {"yours-phong", by_yours_phong},     {"yours-blinn", by_yours_blinn},
#endif
};
enum { N_METHODS = sizeof methods / sizeof methods[0], N_K = 2, N_CASES = N_METHODS * N_K };

static void report(const bench_case *c, const timed_method *m, const bench_timing *t)
{
    fitted_exponent = m->exponent;
    error_stats e = hemisphere_error(m->f, m->k, N_PAIRS);
    bench_row(c->method, c->param, t, "%.4e", e.max_abs, "max_abs");
    bench_row(c->method, c->param, t, "%.4e", e.rms, "rms");
    if (m->f == by_blinn_4k || m->f == by_blinn_fitted)
        for (int theta = 0; theta <= 88; theta += 4) {
            char param[32];
            snprintf(param, sizeof param, "%g:%d", m->k, theta);
            bench_row(c->method, param, t, "%.4e", error_at_incidence(m->f, m->k, theta),
                      "max_abs_at_incidence");
        }
}

int main(void)
{
    static const double shininess[N_K] = {10, 100};
    static char params[N_K][16];
    static timed_method timed[N_CASES];
    bench_case cases[N_CASES];
    bench_timing timing[N_CASES];
    for (int i = 0; i < N_PAIRS; i++) {
        lights[i] = hemisphere_direction();
        viewers[i] = hemisphere_direction();
    }
    for (int s = 0; s < N_K; s++) {
        fit_blinn_exponent(shininess[s]);
        snprintf(params[s], sizeof params[s], "%g", shininess[s]);
        for (int m = 0; m < N_METHODS; m++) {
            int c = s * N_METHODS + m;
            timed[c] = (timed_method){methods[m].f, shininess[s], fitted_exponent};
            cases[c] = (bench_case){methods[m].name, params[s], run_method, &timed[c], N_PAIRS};
        }
    }
    bench_time_cases(cases, N_CASES, timing);

    bench_print_machine();
    bench_csv_header();
    for (int s = 0; s < N_K; s++) {
        for (int m = 0; m < N_METHODS; m++) {
            int c = s * N_METHODS + m;
            report(&cases[c], &timed[c], &timing[c]);
        }
        bench_row("blinn-fitted", params[s], NULL, "%.4f", timed[s * N_METHODS].exponent,
                  "exponent");
    }
    return 0;
}
