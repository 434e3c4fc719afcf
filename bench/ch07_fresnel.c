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
 * ns_per_op is the median over batches of the time per evaluation, the
 * function called through a pointer as a renderer would call it. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "optics.h"
#include "bench_util.h"

#define N_ANGLES 90001

typedef double (*fresnel_fn)(double cos_i, double eta1, double eta2);

static const struct {
    const char *name;
    fresnel_fn f;
} methods[] = {
    {"exact", fresnel_exact},
    {"schlick", fresnel_schlick},
    {"schlick-tir", fresnel_schlick_tir},
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

/* The time of one evaluation: the median over batches of all the angles.
 * (One method at a time; the only place that reads the clock.) */
static double time_per_evaluation(fresnel_fn f, double eta1, double eta2)
{
    enum { BATCHES = 15 };
    double batch[BATCHES];
    for (int b = 0; b < BATCHES; b++) {
        double start = now_ns(), sum = 0;
        for (int k = 0; k < N_ANGLES; k++)
            sum += f(cosines[k], eta1, eta2);
        bench_sink += sum;
        batch[b] = (now_ns() - start) / N_ANGLES;
    }
    return median(batch, BATCHES);
}

int main(void)
{
    for (int k = 0; k < N_ANGLES; k++)
        cosines[k] = cos((M_PI / 2) * k / (N_ANGLES - 1));
    printf("method,param,ns_per_op,error,error_kind\n");
    const double media[] = {1.33, 1.5, 2.42};
    for (int k = 0; k < 3; k++)
        for (int side = 0; side < 2; side++) {
            double eta1 = side ? media[k] : 1, eta2 = side ? 1 : media[k];
            const char *where = side ? "inside" : "outside";
            for (int m = 0; m < N_METHODS; m++) {
                double ns = time_per_evaluation(methods[m].f, eta1, eta2);
                error_stats e = errors(methods[m].f, eta1, eta2);
                printf("%s,%g:%s,%.3f,%.4e,max_abs\n", methods[m].name, media[k], where, ns,
                       e.max_abs);
                printf("%s,%g:%s,%.3f,%.4e,rms\n", methods[m].name, media[k], where, ns, e.rms);
                printf("%s,%g:%s,%.3f,%.2f,max_abs_at\n", methods[m].name, media[k], where, ns,
                       e.max_at_deg);
            }
        }
    for (int side = 0; side < 2; side++)
        for (int m = 0; m < N_METHODS; m++)
            for (int a = 0; a <= 180; a++) {
                double theta = a * 0.5 * M_PI / 180;
                double F = side ? methods[m].f(cos(theta), 1.5, 1) : methods[m].f(cos(theta), 1, 1.5);
                printf("%s,1.5:%s:%g,0,%.6f,reflectance\n", methods[m].name,
                       side ? "inside" : "outside", a * 0.5, F);
            }
    return 0;
}
