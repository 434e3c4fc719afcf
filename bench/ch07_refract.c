/* ch07_refract.c: the refracted direction by the standard form and by the
 * sheet's construction, near grazing incidence and near the critical angle.
 *
 *   build/rel/bench/ch07_refract > figures/ch07-refract.csv    (make charts)
 *
 * Methods: standard (refract_standard, the program's) and sheet
 * (refract_sheet, corrected as in the chapter). For each input the
 * reference is the standard form in long double from the same double
 * vectors, normalised. Errors (columns method,param,ns_per_op,error,
 * error_kind):
 *   snell   |sin theta2 - (eta1/eta2) sin theta1|, the sines of the computed
 *           t and of i measured in long double: how far t breaks Snell's law
 *   unit    | |t| - 1 |
 *   angle   the angle between t and the reference direction, in radians
 *   nan     the share of inputs whose t has a NaN component
 *   wrong   the share of inputs whose total reflection the method decides
 *           differently from the reference
 * Each a maximum over the inputs of a row (nan and wrong: shares). Rows:
 *   param "grazing:L"   into glass (eta = 1/1.5) with cos theta1 = 10^L,
 *                       from 1 down to 1e-16, 2,000 randomly turned frames
 *   param "axis:L"      the same with the normal along y, so that cos
 *                       theta1 can be as small as 1e-304 exactly; "axis:zero"
 *                       exactly grazing
 *   param "critical:L"  out of glass (eta = 1.5) at theta_c - 10^L radians,
 *                       from 0.1 down to 1e-16, 2,000 frames
 *   param "all"         into and out of glass, 200,000 angles evenly over
 *                       [0, 90) degrees in turned frames, with the time
 *                       per refraction, both forms timed in the same
 *                       interleaved rounds (bench/timing.h)
 * CSV: a machine line, then the columns
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns; the sweeps'
 * rows have no times. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "optics.h"
#include "../tests/rng.h"
#include "timing.h"

#define N_FRAMES 2000
#define N_ALL 200000

typedef refraction (*refract_fn)(vec3 i, vec3 n, double eta);

/* make chart-ch07 WORKBOOK=1 defines YOURS_STANDARD and YOURS_SHEET for
 * the forms the reader has started (exercises 7.1, 7.2): renamed yours_...
 * in a copy of the workbook's optics.o, measured and timed beside the book's
 * as "yours-standard" and "yours-sheet". */
#if defined(YOURS_STANDARD) || defined(YOURS_SHEET)
refraction yours_refract_standard(vec3 i, vec3 n, double eta);
refraction yours_refract_sheet(vec3 i, vec3 n, double eta);
#endif

static const struct {
    const char *name;
    refract_fn refract;
} methods[] = {
    {"standard", refract_standard}, {"sheet", refract_sheet},
#ifdef YOURS_STANDARD
    {"yours-standard", yours_refract_standard},
#endif
#ifdef YOURS_SHEET
    {"yours-sheet", yours_refract_sheet},
#endif
};
#define N_METHODS (int)(sizeof methods / sizeof methods[0])

/* ---------------------------------------------------------------- inputs */

static rng_state rng = {0x2545F4914F6CDD1DULL}; /* fixed seed */

static double uniform01(void) { return rng_uniform01(&rng); }

typedef struct {
    vec3 n, u; /* unit normal, unit tangent */
} frame;

static frame random_frame(void)
{
    double z = 2 * uniform01() - 1, phi = 2 * M_PI * uniform01(), s = sqrt(1 - z * z);
    vec3 n = {s * cos(phi), s * sin(phi), z};
    vec3 helper = fabs(n.x) < 0.5 ? (vec3){1, 0, 0} : (vec3){0, 1, 0};
    return (frame){n, vec3_normalize(vec3_cross(n, helper))};
}

/* The direction with cos theta1 = c and sin theta1 = s in the frame. */
static vec3 incident(frame f, double c, double s)
{
    return vec3_sub(vec3_scale(f.u, s), vec3_scale(f.n, c));
}

/* ---------------------------------------------------------------- reference */

typedef struct {
    long double x, y, z;
} lvec;

static lvec lv(vec3 a) { return (lvec){a.x, a.y, a.z}; }
static long double ldot(lvec a, lvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static lvec lscale(lvec a, long double s) { return (lvec){a.x * s, a.y * s, a.z * s}; }
static lvec ladd(lvec a, lvec b) { return (lvec){a.x + b.x, a.y + b.y, a.z + b.z}; }
static lvec lunit(lvec a) { return lscale(a, 1 / sqrtl(ldot(a, a))); }
static long double lsine(lvec a, lvec b) /* of unit vectors */
{
    lvec c = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return sqrtl(ldot(c, c));
}

/* The standard form in long double; false under total reflection. */
static bool reference(vec3 i, vec3 n, double eta, lvec *t)
{
    lvec li = lunit(lv(i)), ln = lunit(lv(n));
    long double c1 = -ldot(ln, li), s2sq = (long double)eta * eta * (1 - c1 * c1);
    if (s2sq >= 1)
        return false;
    long double c2 = sqrtl(1 - s2sq);
    *t = ladd(lscale(li, eta), lscale(ln, eta * c1 - c2));
    return true;
}

/* ---------------------------------------------------------------- errors */

typedef struct {
    double snell, unit, angle; /* largest */
    int nan, wrong, count, measured;
} error_stats;

static void measure(refract_fn f, vec3 i, vec3 n, double eta, error_stats *e)
{
    lvec want = {0, 0, 0};
    bool refracts = reference(i, n, eta, &want);
    refraction r = f(i, n, eta);
    e->count++;
    if (isnan(r.dir.x) || isnan(r.dir.y) || isnan(r.dir.z)) {
        e->nan++;
        return;
    }
    if (r.total == refracts) {
        e->wrong++;
        return;
    }
    if (r.total)
        return;
    lvec t = lv(r.dir), ln = lunit(lv(n));
    long double length = sqrtl(ldot(t, t));
    double snell = (double)fabsl(lsine(lscale(t, 1 / length), ln) - eta * lsine(lunit(lv(i)), ln));
    double unit = (double)fabsl(length - 1);
    double angle = (double)lsine(lscale(t, 1 / length), lunit(want));
    e->snell = snell > e->snell ? snell : e->snell;
    e->unit = unit > e->unit ? unit : e->unit;
    e->angle = angle > e->angle ? angle : e->angle;
    e->measured++;
}

/* Rows are kept and printed at the end, each series (method, kind and
 * sweep) on consecutive lines, so that a chart can join them. */
typedef struct {
    char method[16], param[32], kind[8];
    const bench_timing *t; /* NULL: not timed */
    double error;
    int order;
} row;

static row rows[4096];
static int row_count;

static void add_row(const char *method, const char *param,
                    const bench_timing *t, double error, const char *kind)
{
    if (row_count == (int)(sizeof rows / sizeof rows[0]))
        abort(); /* more rows than this program makes */
    row *r = &rows[row_count];
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->param, sizeof r->param, "%s", param);
    snprintf(r->kind, sizeof r->kind, "%s", kind);
    r->t = t, r->error = error, r->order = row_count++;
}

/* A largest error over no refracted ray at all (every one NaN, wrongly
 * decided or reflected) is NaN: nothing to draw. */
static void report(const char *method, const char *param,
                   const bench_timing *t, const error_stats *e)
{
    bool none = e->measured == 0;
    add_row(method, param, t, none ? NAN : e->snell, "snell");
    add_row(method, param, t, none ? NAN : e->unit, "unit");
    add_row(method, param, t, none ? NAN : e->angle, "angle");
    add_row(method, param, t, (double)e->nan / e->count, "nan");
    add_row(method, param, t, (double)e->wrong / e->count, "wrong");
}

/* The sweep a row belongs to: its param up to the colon. */
static int sweep_compare(const char *a, const char *b)
{
    size_t la = strcspn(a, ":"), lb = strcspn(b, ":");
    int c = strncmp(a, b, la < lb ? la : lb);
    return c ? c : (la > lb) - (la < lb);
}

static int row_compare(const void *pa, const void *pb)
{
    const row *a = pa, *b = pb;
    int c = sweep_compare(a->param, b->param);
    if (c == 0)
        c = strcmp(a->method, b->method);
    if (c == 0)
        c = strcmp(a->kind, b->kind);
    return c ? c : a->order - b->order;
}

static void print_rows(void)
{
    qsort(rows, (size_t)row_count, sizeof rows[0], row_compare);
    bench_print_machine();
    bench_csv_header();
    for (int k = 0; k < row_count; k++)
        bench_row(rows[k].method, rows[k].param, rows[k].t, "%.4e",
                  rows[k].error, rows[k].kind);
}

/* ---------------------------------------------------------------- sweeps */

static void sweep_grazing(void)
{
    const double eta = 1 / 1.5;
    for (int k = 0; k <= 64; k++) {
        double c = pow(10, -k / 4.0), s = sqrt((1 - c) * (1 + c));
        char param[64];
        snprintf(param, sizeof param, "grazing:%.2f", -k / 4.0);
        for (int m = 0; m < N_METHODS; m++) {
            error_stats e = {0};
            rng.state = 12345; /* the same frames for both methods */
            for (int j = 0; j < N_FRAMES; j++) {
                frame f = random_frame();
                measure(methods[m].refract, incident(f, c, s), f.n, eta, &e);
            }
            report(methods[m].name, param, NULL, &e);
        }
    }
    for (int k = 16; k <= 312; k += 8) {
        double c = k < 312 ? pow(10, -k) : 0; /* the last: exactly grazing */
        char param[64];
        if (c > 0)
            snprintf(param, sizeof param, "axis:%d", -k);
        else
            snprintf(param, sizeof param, "axis:zero");
        for (int m = 0; m < N_METHODS; m++) {
            error_stats e = {0};
            measure(methods[m].refract, (vec3){1, -c, 0}, (vec3){0, 1, 0}, eta, &e);
            report(methods[m].name, param, NULL, &e);
        }
    }
}

static void sweep_critical(void)
{
    const double eta = 1.5, theta_c = asin(1 / 1.5);
    for (int k = 4; k <= 64; k++) {
        double d = pow(10, -k / 4.0), theta = theta_c - d;
        char param[64];
        snprintf(param, sizeof param, "critical:%.2f", -k / 4.0);
        for (int m = 0; m < N_METHODS; m++) {
            error_stats e = {0};
            rng.state = 54321;
            for (int j = 0; j < N_FRAMES; j++) {
                frame f = random_frame();
                measure(methods[m].refract, incident(f, cos(theta), sin(theta)), f.n, eta, &e);
            }
            report(methods[m].name, param, NULL, &e);
        }
    }
}

/* ---------------------------------------------------------------- speed */

static vec3 all_i[N_ALL], all_n[N_ALL];
static double all_eta[N_ALL];

/* reps refractions by the form f, whole passes over the inputs. */
static void run_refraction(void *ctx, long reps)
{
    refract_fn f = *(const refract_fn *)ctx;
    for (long done = 0; done < reps; done += N_ALL) {
        double sum = 0;
        for (int k = 0; k < N_ALL; k++)
            sum += f(all_i[k], all_n[k], all_eta[k]).dir.y;
        bench_sink += sum;
    }
}

static void all_angles(void)
{
    rng.state = 777;
    for (int k = 0; k < N_ALL; k++) {
        double theta = (M_PI / 2) * (k / 2) / (N_ALL / 2); /* below 90 degrees */
        frame f = random_frame();
        all_i[k] = incident(f, cos(theta), sin(theta));
        all_n[k] = f.n;
        all_eta[k] = k % 2 ? 1.5 : 1 / 1.5; /* out of and into glass */
    }
    static refract_fn forms[N_METHODS];
    static bench_timing timing[N_METHODS];
    bench_case cases[N_METHODS];
    for (int m = 0; m < N_METHODS; m++) {
        forms[m] = methods[m].refract;
        cases[m] = (bench_case){methods[m].name, "all", run_refraction,
                                &forms[m], N_ALL};
    }
    bench_time_cases(cases, N_METHODS, timing);
    for (int m = 0; m < N_METHODS; m++) {
        error_stats e = {0};
        for (int k = 0; k < N_ALL; k++)
            measure(methods[m].refract, all_i[k], all_n[k], all_eta[k], &e);
        report(methods[m].name, "all", &timing[m], &e);
    }
}

int main(void)
{
    all_angles();
    sweep_grazing();
    sweep_critical();
    print_rows();
    return 0;
}
