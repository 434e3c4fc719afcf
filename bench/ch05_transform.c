/* ch05_transform.c: normals, inverses and drift of transforms, speed against
 * accuracy.
 *
 *   build/rel/bench/ch05_transform > figures/ch05-transform.csv
 *
 * Normals. For each transform (a rotation, a uniform scale with a rotation,
 * the scales diag(2,1,1) and diag(10,1,0.1), the shears S_xz(1, 0) and
 * S_xz(5, 0)), 20,000 random unit normals n are transformed by the sheet's
 * M n, by the inverse transpose (M^-1)^T n with M^-1 kept beside M, by the
 * cofactor matrix C n (C kept too; its sign follows det), and by the
 * inverse transpose with the inverse recomputed for every normal
 * (Gauss-Jordan), each normalised. The truth is the long double cross
 * product of two transformed tangents, (A t1) x (A t2), signed by det A:
 *   METHOD,TRANSFORM,ns_per_normal,largest angle error (degrees),max_angle_deg
 *
 * Inverses. M = T R_a S R_b with S = diag(sqrt k, 1, 1/sqrt k) (condition
 * number k in the 2-norm, k = 1 ... 1e12) and random rotations, built in
 * double by transform_then. Gauss-Jordan and the affine (cofactor) inverse
 * invert the double matrix M; the closed form is the inverse composed from
 * the steps' own inverses. Over 200 transforms per k:
 *   METHOD,k,ns_per_inverse,largest ||M X - I|| (max row sum, in __float128),residual
 *   METHOD,k,ns_per_inverse,largest ||X - X*|| / ||X*||,forward
 * where X* is the inverse of the exact product of the double steps,
 * computed in __float128 (113 bits).
 *
 * The 24 normal cases (method and transform) and the 21 inverse cases
 * (method and k), the two halves of the speed-accuracy chart, are timed
 * together in the same interleaved rounds (bench/timing.h): an operation is
 * one normal, or one inverse, over whole passes of the 20,000 normals or
 * the 200 transforms.
 *
 * Drift. A rotation by 0.7 degrees about (1, 2, 3) composed with itself N
 * times, as an animation's frame loop would, in float and double; and two
 * cures: Gram-Schmidt re-orthonormalisation after every frame, and the
 * rotation recomputed from the frame number (angle 0.7 N) every frame:
 *   drift-PRECISION-HOW,N,ns_per_frame,largest |angle between axes - 90|,orthogonality_deg
 *   drift-PRECISION-HOW,N,ns_per_frame,largest angle to the exact R(0.7 N),angle_deg
 *   drift-PRECISION-HOW,all,ns_per_frame,first N off by more than 0.01 degree,frames_to_0.01deg
 *     (0 when it never is, up to the largest N)
 * The errors come from one run of ten million frames, measured as it goes;
 * the time per frame from the six loops alone, without the measuring, timed
 * together in their own interleaved rounds (each batch starts again at frame
 * 1); it is the same in every row of a method.
 *
 * CSV: a machine line, then the columns
 * method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tests/rng.h"
#include "vec.h"
#include "timing.h"

typedef __float128 quad;

static rng_state rng = {0x2545F4914F6CDD1DULL}; /* fixed seed */

static double uniform(double lo, double hi)
{
    return rng_uniform(&rng, lo, hi);
}

/* The angle between a and b in degrees, by atan2 so that tiny angles keep
 * their digits. */
static double degrees_between_l(const long double a[3], const long double b[3])
{
    long double x[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                        a[0] * b[1] - a[1] * b[0]};
    long double cross = sqrtl(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    long double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return (double)(atan2l(cross, dot) * 180 / acosl(-1));
}

/* ---------------------------------------------------------------- normals */

typedef struct {
    mat4 m, inv, cof;
    double sign; /* of det: the cofactor matrix flips normals for a mirror */
} normal_matrices;

typedef vec3 (*normal_method)(const normal_matrices *t, vec3 n);

static NOINLINE vec3 normal_sheet(const normal_matrices *t, vec3 n)
{
    return vec3_normalize(mat4_mul_dir(t->m, n));
}

static NOINLINE vec3 normal_inverse_transpose(const normal_matrices *t, vec3 n)
{
    return vec3_normalize(mat4_mul_normal(t->inv, n));
}

static NOINLINE vec3 normal_cofactor(const normal_matrices *t, vec3 n)
{
    return vec3_normalize(vec3_scale(mat4_mul_dir(t->cof, n), t->sign));
}

static NOINLINE vec3 normal_inverse_each_time(const normal_matrices *t, vec3 n)
{
    mat4 inv;
    if (!mat4_inverse(t->m, &inv))
        return n;
    return vec3_normalize(mat4_mul_normal(inv, n));
}

static const struct {
    const char *name;
    normal_method transform;
} normal_methods[] = {
    {"sheet-Mn", normal_sheet},
    {"inverse-transpose", normal_inverse_transpose},
    {"cofactor", normal_cofactor},
    {"inverse-each-time", normal_inverse_each_time},
};
#define N_NORMAL_METHODS (int)(sizeof normal_methods / sizeof normal_methods[0])

enum { NORMALS = 20000 };
static vec3 normals[NORMALS];

/* The true transformed normal of n: (A t1) x (A t2) for tangents t1, t2
 * with t1 x t2 along n, signed by det A; in long double. */
static void true_normal(mat4 a, vec3 n, long double out[3])
{
    long double nn[3] = {n.x, n.y, n.z};
    long double helper[3] = {0, 0, 0};
    helper[fabs(n.x) < 0.5 ? 0 : 1] = 1; /* any axis not along n */
    long double t1[3] = {helper[1] * nn[2] - helper[2] * nn[1], helper[2] * nn[0] - helper[0] * nn[2],
                         helper[0] * nn[1] - helper[1] * nn[0]};
    long double t2[3] = {nn[1] * t1[2] - nn[2] * t1[1], nn[2] * t1[0] - nn[0] * t1[2],
                         nn[0] * t1[1] - nn[1] * t1[0]}; /* n x t1: t1 x t2 along n */
    long double at1[3], at2[3];
    for (int i = 0; i < 3; i++) {
        at1[i] = at2[i] = 0;
        for (int j = 0; j < 3; j++)
            at1[i] += (long double)a.m[i][j] * t1[j], at2[i] += (long double)a.m[i][j] * t2[j];
    }
    long double sign = mat4_det3(a) < 0 ? -1 : 1;
    out[0] = sign * (at1[1] * at2[2] - at1[2] * at2[1]);
    out[1] = sign * (at1[2] * at2[0] - at1[0] * at2[2]);
    out[2] = sign * (at1[0] * at2[1] - at1[1] * at2[0]);
}

enum { N_TRANSFORMS = 6 };
static const char *transform_names[N_TRANSFORMS] = {
    "rotation", "uniform-scale", "scale-2-1-1", "scale-10-1-0.1", "shear-1", "shear-5",
};
static normal_matrices normal_cases[N_TRANSFORMS];
static double normal_error[N_TRANSFORMS][N_NORMAL_METHODS]; /* largest angle, degrees */

/* One timed case: a method on one transform. */
typedef struct {
    normal_method method;
    const normal_matrices *t;
} normal_case;

/* reps normals: whole passes over the 20,000. */
static void run_normals(void *ctx, long reps)
{
    const normal_case *c = ctx;
    for (long done = 0; done < reps; done += NORMALS) {
        double sum = 0;
        for (int k = 0; k < NORMALS; k++)
            sum += c->method(c->t, normals[k]).x;
        bench_sink += sum;
    }
}

/* The normals, the transforms and every method's largest error. */
static void measure_normals(void)
{
    for (int k = 0; k < NORMALS; k++)
        normals[k] = rng_unit_vector(&rng, 0.1);
    vec3 axis = vec3_normalize((vec3){1, 2, 3});
    transform cases[N_TRANSFORMS] = {
        transform_rotate(axis, 40),
        transform_then(transform_scale((vec3){3, 3, 3}), transform_rotate(axis, 40)),
        transform_scale((vec3){2, 1, 1}),
        transform_scale((vec3){10, 1, 0.1}),
        transform_shear(mat4_shear_xz(1, 0)),
        transform_shear(mat4_shear_xz(5, 0)),
    };
    for (int c = 0; c < N_TRANSFORMS; c++) {
        normal_matrices t = {cases[c].m, cases[c].inv, mat4_cofactor3(cases[c].m),
                             mat4_det3(cases[c].m) < 0 ? -1 : 1};
        normal_cases[c] = t;
        for (int m = 0; m < N_NORMAL_METHODS; m++) {
            double worst = 0;
            for (int k = 0; k < NORMALS; k++) {
                vec3 got = normal_methods[m].transform(&t, normals[k]);
                long double g[3] = {got.x, got.y, got.z}, want[3];
                true_normal(t.m, normals[k], want);
                double e = degrees_between_l(g, want);
                worst = e > worst ? e : worst;
            }
            normal_error[c][m] = worst;
        }
    }
}

/* ---------------------------------------------------------------- inverses */

typedef struct {
    quad m[4][4];
} qmat;

static qmat qmat_of(mat4 a)
{
    qmat q;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            q.m[i][j] = a.m[i][j];
    return q;
}

static qmat qmat_mul(qmat a, qmat b)
{
    qmat c;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            c.m[i][j] = 0;
            for (int k = 0; k < 4; k++)
                c.m[i][j] += a.m[i][k] * b.m[k][j];
        }
    return c;
}

static quad qabs(quad x) { return x < 0 ? -x : x; }

/* Gauss-Jordan with partial pivoting in 113 bits: the reference. */
static qmat qmat_inverse(qmat a)
{
    qmat inv = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    for (int col = 0; col < 4; col++) {
        int p = col;
        for (int r = col + 1; r < 4; r++)
            if (qabs(a.m[r][col]) > qabs(a.m[p][col]))
                p = r;
        for (int k = 0; k < 4; k++) {
            quad t = a.m[col][k];
            a.m[col][k] = a.m[p][k], a.m[p][k] = t;
            t = inv.m[col][k], inv.m[col][k] = inv.m[p][k], inv.m[p][k] = t;
        }
        quad s = 1 / a.m[col][col];
        for (int k = 0; k < 4; k++)
            a.m[col][k] *= s, inv.m[col][k] *= s;
        for (int r = 0; r < 4; r++) {
            if (r == col)
                continue;
            quad f = a.m[r][col];
            for (int k = 0; k < 4; k++)
                a.m[r][k] -= f * a.m[col][k], inv.m[r][k] -= f * inv.m[col][k];
        }
    }
    return inv;
}

/* Largest row sum of |entries|, over all four rows and columns. */
static quad qnorm(qmat a)
{
    quad largest = 0;
    for (int i = 0; i < 4; i++) {
        quad row = 0;
        for (int j = 0; j < 4; j++)
            row += qabs(a.m[i][j]);
        largest = row > largest ? row : largest;
    }
    return largest;
}

static double residual_of(mat4 m, mat4 x)
{
    qmat p = qmat_mul(qmat_of(m), qmat_of(x));
    for (int i = 0; i < 4; i++)
        p.m[i][i] -= 1;
    return (double)qnorm(p);
}

static double forward_error(mat4 x, qmat exact)
{
    qmat d = qmat_of(x);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            d.m[i][j] -= exact.m[i][j];
    return (double)(qnorm(d) / qnorm(exact));
}

/* The steps of one test transform: T R_a S R_b, applied R_b first. */
typedef struct {
    transform steps[4];
} test_transform;

static transform compose(const test_transform *t)
{
    transform all = t->steps[0];
    for (int k = 1; k < 4; k++)
        all = transform_then(all, t->steps[k]);
    return all;
}

typedef mat4 (*inverse_method)(const test_transform *t, mat4 m);

static NOINLINE mat4 inverse_gauss_jordan(const test_transform *t, mat4 m)
{
    (void)t;
    mat4 x;
    return mat4_inverse(m, &x) ? x : m;
}

static NOINLINE mat4 inverse_affine(const test_transform *t, mat4 m)
{
    (void)t;
    mat4 x;
    return mat4_inverse_affine(m, &x) ? x : m;
}

/* The inverse the program keeps: each step's own inverse, composed in the
 * opposite order (timed with the products it costs, not the steps'). */
static NOINLINE mat4 inverse_closed_form(const test_transform *t, mat4 m)
{
    (void)m;
    mat4 x = t->steps[0].inv;
    for (int k = 1; k < 4; k++)
        x = mat4_mul(x, t->steps[k].inv);
    return x;
}

#ifdef YOURS_PRODUCTS
/* make chart-ch05 WORKBOOK=1: the closed form composed by the reader's
 * products (exercise 5.3), mat4_mul renamed yours_mat4_mul in a copy of the
 * workbook's mat4.o, timed among the others as "yours-closed-form". */
mat4 yours_mat4_mul(mat4 a, mat4 b);
static NOINLINE mat4 inverse_yours_closed_form(const test_transform *t, mat4 m)
{
    (void)m;
    mat4 x = t->steps[0].inv;
    for (int k = 1; k < 4; k++)
        x = yours_mat4_mul(x, t->steps[k].inv);
    return x;
}
#endif

static const struct {
    const char *name;
    inverse_method invert;
} inverse_methods[] = {
    {"gauss-jordan", inverse_gauss_jordan},
    {"affine-cofactor", inverse_affine},
    {"closed-form", inverse_closed_form},
#ifdef YOURS_PRODUCTS
    {"yours-closed-form", inverse_yours_closed_form},
#endif
};
#define N_INVERSE_METHODS (int)(sizeof inverse_methods / sizeof inverse_methods[0])

enum { TRANSFORMS = 200, N_KAPPAS = 7 }; /* k = 10^0, 10^2, ..., 10^12 */
static test_transform tests[N_KAPPAS][TRANSFORMS];
static mat4 composed[N_KAPPAS][TRANSFORMS];
static double residual_error[N_KAPPAS][N_INVERSE_METHODS]; /* largest ||M X - I|| */
static double forward_err[N_KAPPAS][N_INVERSE_METHODS];    /* largest ||X - X*|| / ||X*|| */

/* One timed case: a method on the 200 transforms of one k. */
typedef struct {
    inverse_method invert;
    int kappa;
} inverse_case;

/* reps inverses: whole passes over the 200 transforms. */
static void run_inverses(void *ctx, long reps)
{
    const inverse_case *c = ctx;
    for (long done = 0; done < reps; done += TRANSFORMS) {
        double sum = 0;
        for (int k = 0; k < TRANSFORMS; k++)
            sum += c->invert(&tests[c->kappa][k], composed[c->kappa][k]).m[0][0];
        bench_sink += sum;
    }
}

/* The test transforms of every k and every method's largest errors. */
static void measure_inverses(void)
{
    static qmat exact[TRANSFORMS];
    for (int e = 0; e < N_KAPPAS; e++) {
        double kappa = pow(10, 2 * e), root = sqrt(kappa);
        for (int k = 0; k < TRANSFORMS; k++) {
            test_transform *t = &tests[e][k];
            t->steps[0] = transform_rotate(rng_unit_vector(&rng, 0.1), uniform(-180, 180));
            t->steps[1] = transform_scale((vec3){root, 1, 1 / root});
            t->steps[2] = transform_rotate(rng_unit_vector(&rng, 0.1), uniform(-180, 180));
            t->steps[3] = transform_translate((vec3){uniform(-10, 10), uniform(-10, 10), uniform(-10, 10)});
            composed[e][k] = compose(t).m;
            qmat product = qmat_of(t->steps[0].m); /* the exact steps, multiplied in 113 bits */
            for (int s = 1; s < 4; s++)
                product = qmat_mul(qmat_of(t->steps[s].m), product);
            exact[k] = qmat_inverse(product);
        }
        for (int m = 0; m < N_INVERSE_METHODS; m++) {
            double worst_residual = 0, worst_forward = 0;
            for (int k = 0; k < TRANSFORMS; k++) {
                mat4 x = inverse_methods[m].invert(&tests[e][k], composed[e][k]);
                worst_residual = fmax(worst_residual, residual_of(composed[e][k], x));
                worst_forward = fmax(worst_forward, forward_error(x, exact[k]));
            }
            residual_error[e][m] = worst_residual;
            forward_err[e][m] = worst_forward;
        }
    }
}

/* Both halves of the speed-accuracy chart, timed in the same rounds; then
 * their rows. */
static void time_and_print_speed_accuracy(void)
{
    enum { N_NORMAL_CASES = N_TRANSFORMS * N_NORMAL_METHODS,
           N_INVERSE_CASES = N_KAPPAS * N_INVERSE_METHODS,
           N_CASES = N_NORMAL_CASES + N_INVERSE_CASES };
    static normal_case normal_ctx[N_NORMAL_CASES];
    static inverse_case inverse_ctx[N_INVERSE_CASES];
    static char kappa_names[N_KAPPAS][8];
    bench_case cases[N_CASES];
    bench_timing timing[N_CASES];
    int n = 0;
    for (int c = 0; c < N_TRANSFORMS; c++)
        for (int m = 0; m < N_NORMAL_METHODS; m++, n++) {
            normal_ctx[n] = (normal_case){normal_methods[m].transform, &normal_cases[c]};
            cases[n] = (bench_case){normal_methods[m].name, transform_names[c], run_normals,
                                    &normal_ctx[n], NORMALS};
        }
    for (int e = 0; e < N_KAPPAS; e++) {
        snprintf(kappa_names[e], sizeof kappa_names[e], "1e%d", 2 * e);
        for (int m = 0; m < N_INVERSE_METHODS; m++, n++) {
            inverse_ctx[n - N_NORMAL_CASES] = (inverse_case){inverse_methods[m].invert, e};
            cases[n] = (bench_case){inverse_methods[m].name, kappa_names[e], run_inverses,
                                    &inverse_ctx[n - N_NORMAL_CASES], TRANSFORMS};
        }
    }
    bench_time_cases(cases, N_CASES, timing); /* all 45 take turns */
    n = 0;
    for (int c = 0; c < N_TRANSFORMS; c++)
        for (int m = 0; m < N_NORMAL_METHODS; m++, n++)
            bench_row(cases[n].method, cases[n].param, &timing[n], "%.6g", normal_error[c][m],
                      "max_angle_deg");
    for (int e = 0; e < N_KAPPAS; e++)
        for (int m = 0; m < N_INVERSE_METHODS; m++, n++) {
            bench_row(cases[n].method, cases[n].param, &timing[n], "%.6g", residual_error[e][m],
                      "residual");
            bench_row(cases[n].method, cases[n].param, &timing[n], "%.6g", forward_err[e][m],
                      "forward");
        }
}

/* ---------------------------------------------------------------- drift */

/* A 3x3 rotation in either precision, composed frame after frame. */
#define DRIFT_STEP_DEG 0.7
#define DRIFT_FRAMES 10000000L
#define DRIFT_LIMIT_DEG 0.01

/* Gram-Schmidt on the columns: x normalised, y made perpendicular to x,
 * z = x cross y. In precision T. */
#define DEFINE_DRIFT(T, SUFFIX, SQRT)                                                       \
    typedef struct {                                                                        \
        T m[3][3];                                                                          \
    } mat3##SUFFIX;                                                                         \
    static mat3##SUFFIX mul3##SUFFIX(const mat3##SUFFIX *a, const mat3##SUFFIX *b)          \
    {                                                                                       \
        mat3##SUFFIX c;                                                                     \
        for (int i = 0; i < 3; i++)                                                         \
            for (int j = 0; j < 3; j++)                                                     \
                c.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] +             \
                            a->m[i][2] * b->m[2][j];                                        \
        return c;                                                                           \
    }                                                                                       \
    static void orthonormalize##SUFFIX(mat3##SUFFIX *a)                                     \
    {                                                                                       \
        T x[3] = {a->m[0][0], a->m[1][0], a->m[2][0]}, y[3] = {a->m[0][1], a->m[1][1],      \
                                                               a->m[2][1]};                 \
        T lx = SQRT(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);                               \
        for (int i = 0; i < 3; i++)                                                         \
            x[i] /= lx;                                                                     \
        T d = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];                                      \
        for (int i = 0; i < 3; i++)                                                         \
            y[i] -= d * x[i];                                                               \
        T ly = SQRT(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);                               \
        for (int i = 0; i < 3; i++)                                                         \
            y[i] /= ly;                                                                     \
        T z[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],                     \
                  x[0] * y[1] - x[1] * y[0]};                                               \
        for (int i = 0; i < 3; i++)                                                         \
            a->m[i][0] = x[i], a->m[i][1] = y[i], a->m[i][2] = z[i];                        \
    }                                                                                       \
    static mat3##SUFFIX of_mat4##SUFFIX(mat4 r)                                             \
    {                                                                                       \
        mat3##SUFFIX a;                                                                     \
        for (int i = 0; i < 3; i++)                                                         \
            for (int j = 0; j < 3; j++)                                                     \
                a.m[i][j] = (T)r.m[i][j];                                                   \
        return a;                                                                           \
    }

DEFINE_DRIFT(float, f, sqrtf)
DEFINE_DRIFT(double, d2, sqrt)

/* The exact rotation by deg about the unit axis, in long double. */
static void exact_rotation(vec3 axis, long double deg, long double r[3][3])
{
    long double th = fmodl(deg, 360) * acosl(-1) / 180, s = sinl(th), c = cosl(th);
    long double u[3] = {axis.x, axis.y, axis.z};
    long double cross[3][3] = {{0, -u[2], u[1]}, {u[2], 0, -u[0]}, {-u[1], u[0], 0}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[i][j] = (i == j ? c : 0) + (1 - c) * u[i] * u[j] + s * cross[i][j];
}

/* The two errors of a composed rotation a (columns as long double). */
static void drift_errors(long double a[3][3], vec3 axis, long frames, double *ortho, double *angle)
{
    long double col[3][3], exact[3][3];
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++)
            col[j][i] = a[i][j];
    *ortho = 0;
    for (int p = 0; p < 3; p++) {
        double e = fabs(degrees_between_l(col[p], col[(p + 1) % 3]) - 90);
        *ortho = e > *ortho ? e : *ortho;
    }
    exact_rotation(axis, (long double)DRIFT_STEP_DEG * frames, exact);
    *angle = 0;
    for (int j = 0; j < 3; j++) {
        long double want[3] = {exact[0][j], exact[1][j], exact[2][j]};
        double e = degrees_between_l(col[j], want);
        *angle = e > *angle ? e : *angle;
    }
}

typedef enum { COMPOSED, REORTHONORMALIZED, FROM_ANGLE } drift_cure;

enum { DRIFT_REPORTS = 8 }; /* N = 1, 10, ..., 10^7 */

typedef struct {
    double ortho[DRIFT_REPORTS], angle[DRIFT_REPORTS];
    long crossed; /* first frame off by more than DRIFT_LIMIT_DEG; 0: none */
} drift_result;

/* In precision SUFFIX: one frame, the next r from the previous; the errors
 * of ten million frames; and reps frames timed, from frame 1 again. */
#define RUN_DRIFT(SUFFIX)                                                                      \
    static void next_frame_##SUFFIX(drift_cure cure, vec3 axis, const mat3##SUFFIX *step,       \
                                    mat3##SUFFIX *r, long frame)                               \
    {                                                                                          \
        if (cure == FROM_ANGLE)                                                                \
            *r = of_mat4##SUFFIX(mat4_rotate(axis, fmod(DRIFT_STEP_DEG * frame, 360)));         \
        else                                                                                   \
            *r = mul3##SUFFIX(step, r);                                                        \
        if (cure == REORTHONORMALIZED)                                                         \
            orthonormalize##SUFFIX(r);                                                         \
    }                                                                                          \
    static void measure_drift_##SUFFIX(drift_cure cure, drift_result *out)                     \
    {                                                                                          \
        vec3 axis = vec3_normalize((vec3){1, 2, 3});                                           \
        mat3##SUFFIX step = of_mat4##SUFFIX(mat4_rotate(axis, DRIFT_STEP_DEG)), r = step;       \
        long next_report = 1, crossed = 0;                                                      \
        int reported = 0;                                                                      \
        for (long frame = 1; frame <= DRIFT_FRAMES; frame++) {                                  \
            if (frame > 1)                                                                     \
                next_frame_##SUFFIX(cure, axis, &step, &r, frame);                             \
            bool report = frame == next_report;                                                \
            bool probe = crossed == 0 && (frame < 100000 || frame % 97 == 0);                   \
            if (!report && !probe)                                                             \
                continue;                                                                      \
            long double a[3][3];                                                               \
            for (int i = 0; i < 3; i++)                                                        \
                for (int j = 0; j < 3; j++)                                                    \
                    a[i][j] = r.m[i][j];                                                       \
            double ortho, angle;                                                               \
            drift_errors(a, axis, frame, &ortho, &angle);                                      \
            if (crossed == 0 && fmax(ortho, angle) > DRIFT_LIMIT_DEG)                          \
                crossed = frame;                                                               \
            if (report) {                                                                      \
                out->ortho[reported] = ortho, out->angle[reported] = angle;                    \
                reported++;                                                                    \
                next_report *= 10;                                                             \
            }                                                                                  \
        }                                                                                      \
        out->crossed = crossed;                                                                \
    }                                                                                          \
    static void run_drift_##SUFFIX(void *ctx, long reps)                                       \
    {                                                                                          \
        drift_cure cure = *(const drift_cure *)ctx;                                            \
        vec3 axis = vec3_normalize((vec3){1, 2, 3});                                           \
        mat3##SUFFIX step = of_mat4##SUFFIX(mat4_rotate(axis, DRIFT_STEP_DEG)), r = step;       \
        double sum = 0; /* every frame's matrix is used */                                     \
        for (long frame = 2; frame <= reps + 1; frame++) {                                      \
            next_frame_##SUFFIX(cure, axis, &step, &r, frame);                                 \
            sum += r.m[0][0];                                                                  \
        }                                                                                      \
        bench_sink += sum;                                                                     \
    }

RUN_DRIFT(f)
RUN_DRIFT(d2)

/* The six loops' errors, then their times in the same rounds; then their rows. */
static void measure_drift(void)
{
    enum { N_DRIFTS = 6 };
    static const char *how[3] = {"composed", "reorthonormalized", "from-angle"};
    static char names[N_DRIFTS][64];
    static drift_cure cures[N_DRIFTS];
    drift_result results[N_DRIFTS];
    bench_case cases[N_DRIFTS];
    bench_timing timing[N_DRIFTS];
    for (int n = 0; n < N_DRIFTS; n++) {
        bool is_float = n % 2 == 0;
        cures[n] = (drift_cure)(n / 2);
        snprintf(names[n], sizeof names[n], "drift-%s-%s", is_float ? "float" : "double",
                 how[n / 2]);
        if (is_float)
            measure_drift_f(cures[n], &results[n]);
        else
            measure_drift_d2(cures[n], &results[n]);
        cases[n] = (bench_case){names[n], "all", is_float ? run_drift_f : run_drift_d2,
                                &cures[n], 1};
    }
    bench_time_cases(cases, N_DRIFTS, timing); /* the six loops take turns */
    for (int n = 0; n < N_DRIFTS; n++) {
        long frames = 1;
        char param[32];
        for (int k = 0; k < DRIFT_REPORTS; k++, frames *= 10) {
            snprintf(param, sizeof param, "%ld", frames);
            bench_row(names[n], param, &timing[n], "%.6g", results[n].ortho[k],
                      "orthogonality_deg");
            bench_row(names[n], param, &timing[n], "%.6g", results[n].angle[k], "angle_deg");
        }
        bench_row(names[n], "all", &timing[n], "%.0f", (double)results[n].crossed,
                  "frames_to_0.01deg");
    }
}

int main(void)
{
    measure_normals();
    measure_inverses();
    bench_print_machine();
    bench_csv_header();
    time_and_print_speed_accuracy();
    measure_drift();
    return 0;
}
