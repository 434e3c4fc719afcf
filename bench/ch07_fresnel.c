/* ch07_fresnel.c: three Fresnel reflectances against the exact one.
 *
 *   build/rel/bench/ch07_fresnel > figures/ch07-fresnel.csv    (make charts)
 *
 * Methods, each a function of cos theta1 and the two indices:
 *   exact        fresnel_exact: the sheet's formula, 1 under total
 *                internal reflection (the program's default)
 *   schlick      F0 + (1 - F0)(1 - cos theta1)^5 from either side
 *   schlick-tir  Schlick with the angle in the less dense medium and 1
 *                past the critical angle (the program's `fresnel schlick`)
 * Media: water 1.33, glass 1.5, diamond 2.42, light arriving from outside
 * (eta1 = 1, eta2 = n) and from inside (eta1 = n, eta2 = 1): param
 * "n:outside" or "n:inside". The reference is the exact formula in long
 * double from the same double cosine. Angles: 90,001 evenly spaced from 0
 * to 90 degrees. Rows (columns method,param,ns_per_op,error,error_kind):
 *   max_abs, rms     the error over all angles
 *   max_abs_at       the angle of the largest error, in degrees
 *   reflectance      for glass, param "1.5:side:angle": the method's F_R
 *                    every half degree (ns_per_op 0), for the lower panel
 * ns_per_op is the time of one evaluation, the function called through a
 * pointer from another file as the renderer calls it; all eighteen method,
 * medium and side cases are timed in the same interleaved rounds
 * (bench/timing.h). CSV: a machine line, then the columns
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "optics.h"
#include "timing.h"

#define N_ANGLES 90001

typedef double (*fresnel_fn)(double cos_i, double eta1, double eta2);

#ifdef YOURS_FRESNEL
/* make chart-ch07 WORKBOOK=1: the reader's reflectances (exercise 7.3),
 * renamed yours_... in a copy of the workbook's optics.o, timed among the
 * others as "yours-exact", "yours-schlick" and "yours-schlick-tir". */
double yours_fresnel_exact(double cos_i, double eta1, double eta2);
double yours_fresnel_schlick(double cos_i, double eta1, double eta2);
double yours_fresnel_schlick_tir(double cos_i, double eta1, double eta2);
#endif

static const struct {
    const char *name;
    fresnel_fn f;
} methods[] = {
    {"exact", fresnel_exact},
    {"schlick", fresnel_schlick},
    {"schlick-tir", fresnel_schlick_tir},
#ifdef YOURS_FRESNEL
    {"yours-exact", yours_fresnel_exact},
    {"yours-schlick", yours_fresnel_schlick},
    {"yours-schlick-tir", yours_fresnel_schlick_tir},
#endif
};
#define N_METHODS (int)(sizeof methods / sizeof methods[0])

static double cosines[N_ANGLES];

/* The exact reflectance in long double, with F_R = 1 under total
 * internal reflection. */
static long double reference(long double c1, long double eta1, long double eta2)
{
    long double s2 = eta1 / eta2 * sqrtl(1 - c1 * c1);
    if (s2 >= 1)
        return 1;
    long double c2 = sqrtl(1 - s2 * s2);
    long double par = (eta2 * c1 - eta1 * c2) / (eta2 * c1 + eta1 * c2);
    long double perp = (eta1 * c1 - eta2 * c2) / (eta1 * c1 + eta2 * c2);
    return (par * par + perp * perp) / 2;
}

typedef struct {
    double max_abs, rms, max_at_deg;
} error_stats;

static error_stats errors(fresnel_fn f, double eta1, double eta2)
{
    error_stats e = {0, 0, 0};
    double sum2 = 0;
    for (int k = 0; k < N_ANGLES; k++) {
        double d = (double)fabsl(f(cosines[k], eta1, eta2) - reference(cosines[k], eta1, eta2));
        if (d > e.max_abs)
            e.max_abs = d, e.max_at_deg = 90.0 * k / (N_ANGLES - 1);
        sum2 += d * d;
    }
    e.rms = sqrt(sum2 / N_ANGLES);
    return e;
}

/* One timed case: a method, and the two indices. */
typedef struct {
    fresnel_fn f;
    double eta1, eta2;
} fresnel_case;

/* reps evaluations, whole passes over the angles. */
static void run_fresnel_case(void *ctx, long reps)
{
    const fresnel_case *c = ctx;
    for (long done = 0; done < reps; done += N_ANGLES) {
        double sum = 0;
        for (int k = 0; k < N_ANGLES; k++)
            sum += c->f(cosines[k], c->eta1, c->eta2);
        bench_sink += sum;
    }
}

enum { N_MEDIA = 3, N_CASES = N_MEDIA * 2 * N_METHODS };

static void report(const bench_case *c, const fresnel_case *fc,
                   const bench_timing *t)
{
    error_stats e = errors(fc->f, fc->eta1, fc->eta2);
    bench_row(c->method, c->param, t, "%.4e", e.max_abs, "max_abs");
    bench_row(c->method, c->param, t, "%.4e", e.rms, "rms");
    bench_row(c->method, c->param, t, "%.2f", e.max_at_deg, "max_abs_at");
}

/* Glass's reflectance by each method every half degree, both sides. */
static void curves(void)
{
    for (int side = 0; side < 2; side++)
        for (int m = 0; m < N_METHODS; m++)
            for (int a = 0; a <= 180; a++) {
                double c = cos(a * 0.5 * M_PI / 180);
                double F = side ? methods[m].f(c, 1.5, 1)
                                : methods[m].f(c, 1, 1.5);
                char param[48];
                snprintf(param, sizeof param, "1.5:%s:%g",
                         side ? "inside" : "outside", a * 0.5);
                bench_row(methods[m].name, param, NULL, "%.6f", F,
                          "reflectance");
            }
}

int main(void)
{
    for (int k = 0; k < N_ANGLES; k++)
        cosines[k] = cos((M_PI / 2) * k / (N_ANGLES - 1));
    static const double media[N_MEDIA] = {1.33, 1.5, 2.42};
    static char params[N_MEDIA * 2][32];
    static fresnel_case timed[N_CASES];
    bench_case cases[N_CASES];
    bench_timing timing[N_CASES];
    int n = 0;
    for (int k = 0; k < N_MEDIA; k++)
        for (int side = 0; side < 2; side++) {
            char *param = params[2 * k + side];
            snprintf(param, sizeof params[0], "%g:%s", media[k],
                     side ? "inside" : "outside");
            for (int m = 0; m < N_METHODS; m++, n++) {
                timed[n] = (fresnel_case){methods[m].f, side ? media[k] : 1,
                                          side ? 1 : media[k]};
                cases[n] = (bench_case){methods[m].name, param,
                                        run_fresnel_case, &timed[n],
                                        N_ANGLES};
            }
        }
    bench_time_cases(cases, N_CASES, timing);

    bench_print_machine();
    bench_csv_header();
    for (int c = 0; c < N_CASES; c++)
        report(&cases[c], &timed[c], &timing[c]);
    curves();
    return 0;
}
