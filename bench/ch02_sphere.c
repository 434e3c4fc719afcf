/* ch02_sphere.c: the three ray-sphere forms, in float and double, against
 * the distance of the sphere.
 *
 *   build/rel/bench/ch02_sphere > figures/ch02-sphere.csv     (make charts)
 *
 * A unit sphere sits at distance D (1.8 to 1e7 radii, four steps a decade)
 * from the origin in a direction off every axis. Rays leave the origin
 * towards points spread evenly over a disc 1.2 radii wide around the centre,
 * so about 70% hit. The reference is the robust form evaluated in quad
 * precision (__float128, or long double where that is already 128 bits) from
 * the same double inputs. For each form, precision and distance the CSV has:
 *   t_rel_median, t_rel_max  relative error of the visible root t, over rays
 *                            that both the form and the reference see hit
 *   misclassified            share of rays called hit when they miss or
 *                            miss when they hit
 * and, once per form (param "all"), fails_at: the smallest distance at which
 * it misclassifies more than 1 ray in 1000 (inf if it never does),
 * and ns_per_op, the time of one call on rays at D = 100, all six forms
 * timed in the same interleaved rounds (bench/timing.h; the same in every
 * row of a method). CSV: a machine line, then the columns
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns (param = D
 * in radii). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "sphere.h"
#include "../tests/rng.h"
#include "timing.h"

#if defined(__SIZEOF_FLOAT128__) && LDBL_MANT_DIG < 113
typedef __float128 quad; /* x86-64: 113-bit significand, in software */
#else
typedef long double quad; /* already 128-bit on e.g. aarch64 */
#endif

typedef sphere_roots_fn roots_fn;

#if defined(YOURS_GEOMETRIC) || defined(YOURS_QUADRATIC) || defined(YOURS_ROBUST)
/* make chart-ch02 WORKBOOK=1 defines YOURS_NAME for each form the reader has
 * started (exercises 2.1-2.3): their functions, renamed yours_... in copies
 * of the workbook's objects, are measured and timed in the same rounds as
 * the book's six, as "yours-NAME". */
#define YOURS_FORMS
#define Y(name) int yours_sphere_roots_##name(vec3, double, ray, double[2]); \
                int yours_sphere_roots_##name##_float(vec3, double, ray, double[2]);
Y(geometric) Y(quadratic) Y(robust)
#undef Y
#define Y(name) {"yours-" #name, "double", yours_sphere_roots_##name}, \
                {"yours-" #name, "float", yours_sphere_roots_##name##_float},
static const sphere_roots_method yours[] = {
#ifdef YOURS_GEOMETRIC
    Y(geometric)
#endif
#ifdef YOURS_QUADRATIC
    Y(quadratic)
#endif
#ifdef YOURS_ROBUST
    Y(robust)
#endif
};
#undef Y
#define N_FORMS (SPHERE_ROOTS_METHOD_COUNT + (int)(sizeof yours / sizeof yours[0]))
static sphere_roots_method forms[N_FORMS]; /* the book's six, then yours */
#else
/* The six forms as chapter 2 lists them: name, precision, function. */
#define forms SPHERE_ROOTS_METHODS
#define N_FORMS SPHERE_ROOTS_METHOD_COUNT
#endif
#define N_RAYS 20000

/* ---------------------------------------------------------------- reference */

/* sqrt in quad by two Newton steps from the long double root. */
static quad quad_sqrt(quad x)
{
    if (x <= 0)
        return 0;
    quad y = sqrtl((long double)x);
    y = (y + x / y) / 2;
    return (y + x / y) / 2;
}

/* The visible root (smallest t > 0) in quad; false if the ray misses. */
static bool reference_t(vec3 c, double radius, ray r, quad *t)
{
    quad f[3] = {(quad)r.origin.x - c.x, (quad)r.origin.y - c.y, (quad)r.origin.z - c.z};
    quad d[3] = {r.dir.x, r.dir.y, r.dir.z};
    quad a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    quad beta = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    quad perp2 = 0, ff = 0;
    for (int k = 0; k < 3; k++) {
        quad p = f[k] - d[k] * (beta / a);
        perp2 += p * p;
        ff += f[k] * f[k];
    }
    quad rr = (quad)radius * radius, delta = rr - perp2;
    if (delta < 0)
        return false;
    quad s = quad_sqrt(a * delta), q = beta > 0 ? -beta - s : -beta + s;
    quad t0 = q / a, t1 = q != 0 ? (ff - rr) / q : t0;
    if (t0 > t1) {
        quad tmp = t0;
        t0 = t1, t1 = tmp;
    }
    *t = t0 > 0 ? t0 : t1;
    return *t > 0;
}

/* ---------------------------------------------------------------- rays */

/* Fixed seeds: the same rays every run. The distance study's seed is the
 * state its generator reached when the timing, which ran first, drew
 * 6 x 4096 rays from the other seed: the rays, and the accuracy numbers the
 * chapter quotes, are those of every earlier version of this benchmark. */
static rng_state timing_rng = {0x9E3779B97F4A7C15ULL};
static rng_state distance_rng = {0x5F02A0E6D8F53C15ULL};

/* Rays from the origin towards a disc of 1.2 radii around a centre at D. */
static void make_rays(rng_state *rng, double D, vec3 *center, ray *rays, int n)
{
    vec3 axis = vec3_normalize((vec3){0.3, 0.4, 1.0});
    vec3 e1 = vec3_normalize((vec3){1.0, 0.0, -0.3});        /* perpendicular to axis */
    vec3 e2 = {axis.y * e1.z - axis.z * e1.y, axis.z * e1.x - axis.x * e1.z,
               axis.x * e1.y - axis.y * e1.x};               /* axis x e1 */
    *center = vec3_scale(axis, D);
    for (int k = 0; k < n; k++) {
        double radius = 1.2 * sqrt(rng_uniform01(rng));
        double angle = 2 * M_PI * rng_uniform01(rng);
        vec3 offset = vec3_add(vec3_scale(e1, radius * cos(angle)),
                               vec3_scale(e2, radius * sin(angle)));
        rays[k] = (ray){{0, 0, 0}, vec3_normalize(vec3_add(*center, offset))};
    }
}

/* ---------------------------------------------------------------- measuring */

/* The visible root of a form's answer; false for a miss. */
static bool form_t(roots_fn roots, vec3 c, ray r, double *t)
{
    double ts[2];
    if (roots(c, 1.0, r, ts) == 0)
        return false;
    *t = ts[0] > 0 ? ts[0] : ts[1];
    return *t > 0; /* a NaN root is no hit */
}

enum { T_REL_MEDIAN, T_REL_MAX, MISCLASSIFIED, N_KINDS };
static const char *const kind_names[N_KINDS] = {"t_rel_median", "t_rel_max", "misclassified"};

#define N_DISTANCES 28 /* 10^(k/4), k = 1..28 */
static double results[N_FORMS][N_DISTANCES][N_KINDS];

static void measure_distance(int step, double D)
{
    static ray rays[N_RAYS];
    static quad ref_t[N_RAYS];
    static bool ref_hit[N_RAYS];
    static double errors[N_RAYS];
    vec3 c;
    make_rays(&distance_rng, D, &c, rays, N_RAYS);
    for (int k = 0; k < N_RAYS; k++)
        ref_hit[k] = reference_t(c, 1.0, rays[k], &ref_t[k]);
    for (int f = 0; f < N_FORMS; f++) {
        int n_errors = 0, wrong = 0;
        for (int k = 0; k < N_RAYS; k++) {
            double t;
            bool hit = form_t(forms[f].roots, c, rays[k], &t);
            if (hit != ref_hit[k])
                wrong++;
            else if (hit)
                errors[n_errors++] = (double)fabsl((long double)((t - ref_t[k]) / ref_t[k]));
        }
        qsort(errors, (size_t)n_errors, sizeof errors[0], bench_compare_doubles);
        results[f][step][T_REL_MEDIAN] = n_errors ? errors[n_errors / 2] : NAN;
        results[f][step][T_REL_MAX] = n_errors ? errors[n_errors - 1] : NAN;
        results[f][step][MISCLASSIFIED] = (double)wrong / N_RAYS;
    }
}

static double distance_of(int step) { return pow(10.0, (step + 1) / 4.0); }

/* Rows grouped by form (its fails_at first), then kind, so that each chart
 * line is contiguous. */
static void print_results(const bench_timing timing[N_FORMS])
{
    bench_print_machine();
    bench_csv_header();
    for (int f = 0; f < N_FORMS; f++) {
        char method[32], param[32];
        snprintf(method, sizeof method, "%s-%s", forms[f].name, forms[f].precision);
        double fails_at = INFINITY;
        for (int step = N_DISTANCES - 1; step >= 0; step--)
            if (results[f][step][MISCLASSIFIED] > 0.001)
                fails_at = distance_of(step);
        bench_row(method, "all", &timing[f], "%g", fails_at, "fails_at");
        for (int kind = 0; kind < N_KINDS; kind++)
            for (int step = 0; step < N_DISTANCES; step++) {
                snprintf(param, sizeof param, "%g", distance_of(step));
                bench_row(method, param, &timing[f], "%.4e", results[f][step][kind],
                          kind_names[kind]);
            }
    }
}

/* ---------------------------------------------------------------- speed */

enum { TIMED_RAYS = 4096 };
static ray timed_rays[TIMED_RAYS];
static vec3 timed_center;

/* reps calls of one form, whole passes over the rays at D = 100. */
static void run_form(void *ctx, long reps)
{
    roots_fn roots = *(const roots_fn *)ctx;
    for (long done = 0; done < reps; done += TIMED_RAYS) {
        double sum = 0, t[2];
        for (int k = 0; k < TIMED_RAYS; k++)
            sum += roots(timed_center, 1.0, timed_rays[k], t) ? t[0] : 0;
        bench_sink += sum;
    }
}

int main(void)
{
    static roots_fn fns[N_FORMS];
    static char names[N_FORMS][32];
    bench_case cases[N_FORMS];
    bench_timing timing[N_FORMS];
#ifdef YOURS_FORMS
    for (int f = 0; f < N_FORMS; f++)
        forms[f] = f < SPHERE_ROOTS_METHOD_COUNT
                       ? SPHERE_ROOTS_METHODS[f]
                       : yours[f - SPHERE_ROOTS_METHOD_COUNT];
#endif
    make_rays(&timing_rng, 100.0, &timed_center, timed_rays, TIMED_RAYS);
    for (int f = 0; f < N_FORMS; f++) {
        fns[f] = forms[f].roots;
        snprintf(names[f], sizeof names[f], "%s-%s", forms[f].name, forms[f].precision);
        cases[f] = (bench_case){names[f], "all", run_form, &fns[f], TIMED_RAYS};
    }
    bench_time_cases(cases, N_FORMS, timing);
    for (int step = 0; step < N_DISTANCES; step++)
        measure_distance(step, distance_of(step));
    print_results(timing);
    return 0;
}
