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
 * and ns_per_op, the median time of one call over batches of rays at
 * D = 100 (the same in every row of a method).
 * Columns: method,param,ns_per_op,error,error_kind (param = D in radii). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "sphere.h"
#include "bench_util.h"

#if defined(__SIZEOF_FLOAT128__) && LDBL_MANT_DIG < 113
typedef __float128 quad; /* x86-64: 113-bit significand, in software */
#else
typedef long double quad; /* already 128-bit on e.g. aarch64 */
#endif

typedef int (*roots_fn)(vec3, double, ray, double[2]);

static const struct {
    const char *name, *precision;
    roots_fn roots;
} forms[] = {
    {"geometric", "double", sphere_roots_geometric},
    {"quadratic", "double", sphere_roots_quadratic},
    {"robust", "double", sphere_roots_robust},
    {"geometric", "float", sphere_roots_geometric_float},
    {"quadratic", "float", sphere_roots_quadratic_float},
    {"robust", "float", sphere_roots_robust_float},
};
#define N_FORMS (int)(sizeof forms / sizeof forms[0])
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

static uint64_t rng_state = 0x9E3779B97F4A7C15ULL; /* fixed seed: same rays every run */

static double uniform01(void)
{
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* Rays from the origin towards a disc of 1.2 radii around a centre at D. */
static void make_rays(double D, vec3 *center, ray *rays, int n)
{
    vec3 axis = vec3_normalize((vec3){0.3, 0.4, 1.0});
    vec3 e1 = vec3_normalize((vec3){1.0, 0.0, -0.3});        /* perpendicular to axis */
    vec3 e2 = {axis.y * e1.z - axis.z * e1.y, axis.z * e1.x - axis.x * e1.z,
               axis.x * e1.y - axis.y * e1.x};               /* axis x e1 */
    *center = vec3_scale(axis, D);
    for (int k = 0; k < n; k++) {
        double radius = 1.2 * sqrt(uniform01()), angle = 2 * M_PI * uniform01();
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
    make_rays(D, &c, rays, N_RAYS);
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
        qsort(errors, (size_t)n_errors, sizeof errors[0], compare_doubles);
        results[f][step][T_REL_MEDIAN] = n_errors ? errors[n_errors / 2] : NAN;
        results[f][step][T_REL_MAX] = n_errors ? errors[n_errors - 1] : NAN;
        results[f][step][MISCLASSIFIED] = (double)wrong / N_RAYS;
    }
}

static double distance_of(int step) { return pow(10.0, (step + 1) / 4.0); }

/* Rows grouped by form, then kind, so that each chart line is contiguous. */
static void print_results(const double ns[N_FORMS])
{
    printf("method,param,ns_per_op,error,error_kind\n");
    for (int f = 0; f < N_FORMS; f++) {
        for (int kind = 0; kind < N_KINDS; kind++)
            for (int step = 0; step < N_DISTANCES; step++)
                printf("%s-%s,%g,%.3f,%.4e,%s\n", forms[f].name, forms[f].precision,
                       distance_of(step), ns[f], results[f][step][kind], kind_names[kind]);
        double fails_at = INFINITY;
        for (int step = N_DISTANCES - 1; step >= 0; step--)
            if (results[f][step][MISCLASSIFIED] > 0.001)
                fails_at = distance_of(step);
        printf("%s-%s,all,%.3f,%g,fails_at\n", forms[f].name, forms[f].precision, ns[f],
               fails_at);
    }
}

/* Median time of one call, over 11 batches of 100 passes over 4096 rays. */
static double time_form(roots_fn roots)
{
    enum { RAYS = 4096, PASSES = 100, BATCHES = 11 };
    static ray rays[RAYS];
    vec3 c;
    make_rays(100.0, &c, rays, RAYS);
    double batch[BATCHES];
    for (int b = 0; b < BATCHES; b++) {
        double start = now_ns(), sum = 0, t[2];
        for (int p = 0; p < PASSES; p++)
            for (int k = 0; k < RAYS; k++)
                sum += roots(c, 1.0, rays[k], t) ? t[0] : 0;
        bench_sink += sum;
        batch[b] = (now_ns() - start) / (RAYS * PASSES);
    }
    return median(batch, BATCHES);
}

int main(void)
{
    double ns[N_FORMS];
    for (int f = 0; f < N_FORMS; f++)
        ns[f] = time_form(forms[f].roots);
    for (int step = 0; step < N_DISTANCES; step++)
        measure_distance(step, distance_of(step));
    print_results(ns);
    return 0;
}
