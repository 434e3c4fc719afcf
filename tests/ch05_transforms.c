/* ch05_transforms.c: homogeneous coordinates, matrices, inverses, normals,
 * objects in their own space, instances, the placed camera, and the
 * transform statements (chapter 05).
 *
 * Expected values are worked out by hand (stated beside each) or computed
 * independently in long double from closed forms. Tolerances are relative
 * errors or degrees, each with its reason. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rng.h"
#include "render.h"
#include "scene.h"
#include "scene_file.h"
#include "search.h"
#include "test_util.h"

#define U (DBL_EPSILON / 2) /* the unit roundoff of double, 2^-53 */

static double degrees_between(vec3 a, vec3 b)
{
    double c = vec3_dot(a, b) / (vec3_length(a) * vec3_length(b));
    vec3 x = vec3_cross(a, b); /* atan2 keeps small angles exact */
    return atan2(vec3_length(x) / (vec3_length(a) * vec3_length(b)), c) * 180 /
           M_PI;
}

static void expect_vec3(vec3 got, vec3 want, double tolerance, const char *what)
{
    ck_assert_msg(fabs(got.x - want.x) <= tolerance &&
                      fabs(got.y - want.y) <= tolerance &&
                      fabs(got.z - want.z) <= tolerance,
                  "%s: (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)",
                  what, got.x, got.y, got.z, want.x, want.y, want.z);
}

#define expect_exact(got, want, what) expect_vec3((got), (want), 0, (what))

/* fixed seed: the same cases on every run */
static const rng_state RNG_START = {0x9E3779B97F4A7C15ULL};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

static double uniform(double lo, double hi)
{
    return rng_uniform(&rng, lo, hi);
}

/* A transform of every kind of step: scale, shear, rotation, translation. */
static transform random_transform(double largest_scale)
{
    transform t =
        transform_scale((vec3){uniform(1, largest_scale), uniform(0.5, 2),
                               -uniform(1 / largest_scale, 1)});
    t = transform_then(
        t, transform_shear(mat4_shear_xz(uniform(-1, 1), uniform(-1, 1))));
    t = transform_then(
        t, transform_rotate(rng_unit_vector(&rng, 0.1), uniform(-180, 180)));
    return transform_then(
        t, transform_translate(
               (vec3){uniform(-9, 9), uniform(-9, 9), uniform(-9, 9)}));
}

/* ||A B - I|| over all 16 entries, the products summed in long double so
 * that only a and b's own errors show. */
static double residual(mat4 a, mat4 b)
{
    double worst = 0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            long double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += (long double)a.m[i][k] * b.m[k][j];
            double e = (double)fabsl(sum - (i == j));
            worst = e > worst ? e : worst;
        }
    return worst;
}

/* ------------------------------------------------------------ homogeneous
 * coordinates */

START_TEST(test_point_plus_point_is_neither_point_nor_vector)
{
    vec4 p = vec4_point((vec3){1, 2, 3}), q = vec4_point((vec3){5, -1, 0});
    vec4 v = vec4_vector((vec3){0, 1, 0});
    vec4 sum = vec4_add(p, q); /* the sheet's p + p: w = 2 */
    ck_assert(sum.w == 2 && !vec4_is_point(sum) && !vec4_is_vector(sum));
    ck_assert(vec4_is_point(vec4_add(p, v)));                  /* 1 + 0 */
    ck_assert(vec4_is_vector(vec4_add(p, vec4_scale(q, -1)))); /* 1 - 1 */
    ck_assert(vec4_is_vector(vec4_add(v, v)));                 /* 0 + 0 */
    ck_assert(vec4_is_point(
        vec4_add(vec4_scale(p, 0.5), vec4_scale(q, 0.5)))); /* weights 1 */
}
END_TEST

/* ------------------------------------------------------------ the standard
 * matrices */

START_TEST(test_standard_matrices_move_points_and_vectors)
{
    vec3 p = {1, 2, 3};
    mat4 t = mat4_translate((vec3){10, 20, 30});
    expect_exact(mat4_mul_point(t, p), ((vec3){11, 22, 33}),
                 "a translated point");
    expect_exact(mat4_mul_dir(t, p), p, "a translated vector does not move");
    vec4 h = mat4_mul_vec4(t, vec4_vector(p));
    ck_assert(vec4_is_vector(h) && h.x == 1);
    expect_exact(mat4_mul_point(mat4_scale((vec3){2, -1, 0.5}), p),
                 ((vec3){2, -2, 1.5}), "scale");
    expect_exact(mat4_mul_dir(mat4_shear_yz(2, 3), p), ((vec3){1, 4, 6}),
                 "S_yz: y += 2x, z += 3x");
    expect_exact(mat4_mul_dir(mat4_shear_xz(2, 3), p), ((vec3){5, 2, 9}),
                 "S_xz: x += 2y, z += 3y");
    expect_exact(mat4_mul_dir(mat4_shear_xy(2, 3), p), ((vec3){7, 11, 3}),
                 "S_xy: x += 2z, y += 3z");
    /* A rotation by 30 degrees about z: (1, 0, 0) -> (cos 30, sin 30, 0) =
     * (sqrt3/2, 1/2, 0), to within the rounding of sin and cos (a few ulps). */
    expect_vec3(mat4_mul_dir(mat4_rotate_z(30), (vec3){1, 0, 0}),
                ((vec3){sqrt(3) / 2, 0.5, 0}), 4 * U, "rotate z 30");
}
END_TEST

START_TEST(test_rotations_turn_the_way_the_chapter_says)
{
    /* Quarter turns are exact: y -> z about x, z -> x about y, x -> y about z.
     */
    expect_exact(mat4_mul_dir(mat4_rotate_x(90), (vec3){0, 1, 0}),
                 ((vec3){0, 0, 1}), "R_x");
    expect_exact(mat4_mul_dir(mat4_rotate_y(90), (vec3){0, 0, 1}),
                 ((vec3){1, 0, 0}), "R_y");
    expect_exact(mat4_mul_dir(mat4_rotate_z(90), (vec3){1, 0, 0}),
                 ((vec3){0, 1, 0}), "R_z");
    expect_exact(mat4_mul_dir(mat4_rotate_z(-270), (vec3){1, 0, 0}),
                 ((vec3){0, 1, 0}), "-270");
    expect_exact(mat4_mul_dir(mat4_rotate_y(180), (vec3){0, 0, 1}),
                 ((vec3){0, 0, -1}), "180");
    /* Four quarter turns are the identity, exactly. */
    mat4 r = mat4_identity();
    for (int k = 0; k < 4; k++)
        r = mat4_mul(mat4_rotate_x(90), r);
    ck_assert(residual(r, mat4_identity()) == 0);
    /* Rodrigues about (1,1,1)/sqrt3 by 120 degrees permutes the axes x -> y ->
     * z -> x: the same sense as the named rotations, to within a few ulps. */
    vec3 diagonal = vec3_normalize((vec3){1, 1, 1});
    expect_vec3(mat4_mul_dir(mat4_rotate(diagonal, 120), (vec3){1, 0, 0}),
                ((vec3){0, 1, 0}), 8 * U, "x -> y");
    expect_vec3(mat4_mul_dir(mat4_rotate(diagonal, 120), (vec3){0, 1, 0}),
                ((vec3){0, 0, 1}), 8 * U, "y -> z");
    /* About a coordinate axis it is the sheet's matrix itself, bit for bit. */
    mat4 a = mat4_rotate((vec3){0, 1, 0}, 37), b = mat4_rotate_y(37);
    ck_assert(memcmp(&a, &b, sizeof a) == 0);
}
END_TEST

START_TEST(test_positive_z_rotation_turns_the_picture_counter_clockwise)
{
    /* A small sphere right of the view's centre, turned +90 degrees about z,
     * appears above the centre: right -> up is counter-clockwise in the
     * picture. */
    scene s;
    scene_error err;
    ck_assert(parse_text(
        &s,
        "image 11 11\nsphere center 1 0 5 radius 0.3 transform rotate z 90\n",
        &err));
    camera_view view = camera_view_of(&s.cam);
    render_stats stats = {0};
    hit h;
    vec3 up = {0, 1, 5}, right = {1, 0, 5};
    ck_assert(scene_intersect(&s, (ray){{0, 0, 0}, vec3_normalize(up)}, 0,
                              INFINITY, &h, &stats));
    ck_assert(!scene_intersect(&s, (ray){{0, 0, 0}, vec3_normalize(right)}, 0,
                               INFINITY, &h, &stats));
    /* and the top-centre pixel's ray is the one that sees it */
    ray top = camera_view_ray(&view, 5, 0);
    ck_assert(top.dir.y > 0 && top.dir.x == 0);
    scene_free(&s);
}
END_TEST

START_TEST(test_composition_applies_the_right_factor_first)
{
    vec3 p = {1, 0, 0};
    mat4 r = mat4_rotate_z(90), t = mat4_translate((vec3){1, 0, 0});
    expect_exact(mat4_mul_point(mat4_mul(t, r), p), ((vec3){1, 1, 0}),
                 "T R p: rotate first");
    expect_exact(mat4_mul_point(mat4_mul(r, t), p), ((vec3){0, 2, 0}),
                 "R T p: move first");
    /* transform_then(first, next) is next.m first.m */
    transform both = transform_then(transform_rotate((vec3){0, 0, 1}, 90),
                                    transform_translate((vec3){1, 0, 0}));
    expect_exact(mat4_mul_point(both.m, p), ((vec3){1, 1, 0}), "then");
    expect_exact(mat4_mul_point(both.inv, (vec3){1, 1, 0}), p, "its inverse");
}
END_TEST

START_TEST(test_shear_has_determinant_one_and_changes_angles)
{
    mat4 s = mat4_shear_xz(1, 0); /* x += y */
    ck_assert(mat4_det3(s) == 1);
    vec3 x = mat4_mul_dir(s, (vec3){1, 0, 0}),
         y = mat4_mul_dir(s, (vec3){0, 1, 0});
    /* the axes, 90 degrees apart, end 45 degrees apart: det = 1 kept no angle
     */
    ck_assert_double_eq_tol(degrees_between(x, y), 45, 1e-12);
    ck_assert_double_eq_tol(vec3_length(y), sqrt(2), 2 * U * sqrt(2));
    /* A^T A = I is what keeps angles: a rotation's Gram matrix is I to a few
     * ulps */
    mat4 r = mat4_rotate(vec3_normalize((vec3){1, 2, 3}), 33);
    mat4 g = mat4_mul(mat4_transpose(r), r);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            ck_assert_double_eq_tol(g.m[i][j], i == j, 8 * U);
}
END_TEST

/* ------------------------------------------------------------ inverses */

START_TEST(test_inverses_give_the_identity)
{
    for (int k = 0; k < 200; k++) {
        transform t = random_transform(10);
        mat4 gj, affine;
        ck_assert(mat4_inverse(t.m, &gj) && mat4_inverse_affine(t.m, &affine));
        /* kappa = ||A|| ||A^-1||; a backward-stable inverse leaves a residual
         * of about n u kappa (n = 4 rows), times (1 + |t|) in the translation
         * column, where the translation t is carried through A^-1. 8 n u allows
         * for building M itself. */
        double kappa = mat4_norm3(t.m) * mat4_norm3(t.inv);
        double shift =
            fmax(fabs(t.m.m[0][3]), fmax(fabs(t.m.m[1][3]), fabs(t.m.m[2][3])));
        double bound = 8 * 4 * U * kappa * (1 + shift);
        ck_assert_msg(residual(t.m, t.inv) <= bound, "closed form: %g > %g",
                      residual(t.m, t.inv), bound);
        ck_assert_msg(residual(t.m, gj) <= bound, "Gauss-Jordan: %g",
                      residual(t.m, gj));
        ck_assert_msg(residual(t.m, affine) <= bound, "affine: %g",
                      residual(t.m, affine));
    }
    mat4 singular = mat4_scale((vec3){1, 0, 1}), out;
    ck_assert(!mat4_inverse(singular, &out) &&
              !mat4_inverse_affine(singular, &out));
}
END_TEST

START_TEST(test_cofactors_are_the_inverse_transpose_times_the_determinant)
{
    /* 3x3 with integer entries: every cofactor and det = -3 are exact. */
    mat4 a = mat4_identity();
    const double rows[3][3] = {{2, 1, 0}, {1, 3, 1}, {0, 1, 1}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            a.m[i][j] = rows[i][j];
    ck_assert(mat4_det3(a) == 2 * (3 - 1) - 1 * (1 - 0)); /* = 3 */
    mat4 c = mat4_cofactor3(a), inv;
    ck_assert(mat4_inverse(a, &inv));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            ck_assert_double_eq_tol(c.m[i][j], 3 * inv.m[j][i], 16 * U);
    /* by hand: C_01 = -(1*1 - 1*0) = -1, C_11 = 2*1 - 0*0 = 2 */
    ck_assert(c.m[0][1] == -1 && c.m[1][1] == 2);
}
END_TEST

/* ------------------------------------------------------------ normals */

START_TEST(test_sheet_normal_is_36_9_degrees_off_for_a_scale)
{
    transform t = transform_scale((vec3){2, 1, 1});
    vec3 n = vec3_normalize((vec3){1, 1, 0});
    vec3 sheet = mat4_mul_dir(t.m, n), right = mat4_mul_normal(t.inv, n);
    /* closed form: cos = 0.8, acos(0.8) = 36.869897645844 degrees */
    double expected = acos(0.8) * 180 / M_PI;
    ck_assert_double_eq_tol(degrees_between(sheet, right), expected, 1e-9);
    ck_assert(fabs(expected - 36.8698976458) < 1e-9);
    /* the right one is perpendicular to the transformed tangent (1, -1, 0) */
    vec3 tangent = mat4_mul_dir(t.m, (vec3){1, -1, 0});
    ck_assert(vec3_dot(right, tangent) ==
              0); /* exact here: (1/2, 1) . (2, -1) */
    ck_assert(fabs(vec3_dot(sheet, tangent)) >
              0.5); /* M n: (2, 1) . (2, -1) = 3 */
}
END_TEST

START_TEST(test_sheet_normal_is_wrong_for_a_shear_of_determinant_one)
{
    transform t = transform_shear(mat4_shear_xz(1, 0));
    ck_assert(mat4_det3(t.m) == 1);
    vec3 n = {0, 1, 0}; /* the plane y = 0, which the shear leaves in place */
    ck_assert_double_eq_tol(degrees_between(mat4_mul_dir(t.m, n), n), 45,
                            1e-12);
    expect_exact(mat4_mul_normal(t.inv, n), n,
                 "the inverse transpose keeps it");
}
END_TEST

START_TEST(test_inverse_transpose_keeps_normals_perpendicular)
{
    for (int k = 0; k < 500; k++) {
        transform t = random_transform(100);
        vec3 n = rng_unit_vector(&rng, 0.1);
        vec3 tangent = vec3_cross(
            n, rng_unit_vector(&rng, 0.1)); /* any vector perpendicular to n */
        if (vec3_length(tangent) < 0.1)
            continue;
        vec3 moved = mat4_mul_dir(t.m, tangent);
        vec3 normal = mat4_mul_normal(t.inv, n);
        /* the cosine between them is a sum of products with relative errors of
         * a few u, amplified at most by kappa: |cos| <= 16 u kappa */
        double kappa = mat4_norm3(t.m) * mat4_norm3(t.inv);
        double c = vec3_dot(normal, moved) /
                   (vec3_length(normal) * vec3_length(moved));
        ck_assert_msg(fabs(c) <= 16 * U * kappa,
                      "the moved normal is not perpendicular to the moved "
                      "surface (cos %g, "
                      "kappa %g): a normal moves by (M^-1)^T n, not by M n as "
                      "sheet 5.3 has it",
                      c, kappa);
        /* and the cofactor matrix points the same way, up to det's sign */
        vec3 cof = mat4_mul_dir(mat4_cofactor3(t.m), n);
        double sign = mat4_det3(t.m) < 0 ? -1 : 1;
        ck_assert(degrees_between(vec3_scale(cof, sign), normal) <
                  1e-9 * kappa);
    }
    /* with a scale of 100 the sheet's M n is far off for most normals */
    transform t = transform_scale((vec3){100, 1, 1});
    vec3 n = vec3_normalize((vec3){1, 1, 1});
    ck_assert(degrees_between(mat4_mul_dir(t.m, n), mat4_mul_normal(t.inv, n)) >
              45);
}
END_TEST

START_TEST(test_cofactor_matrix_gives_normals_of_a_singular_transform)
{
    mat4 flat = mat4_scale((vec3){1, 0, 1}),
         out; /* a sphere squashed into a disc */
    ck_assert(!mat4_inverse(flat, &out));
    vec3 n = vec3_normalize((vec3){1, 1, 0});
    vec3 c = mat4_mul_dir(mat4_cofactor3(flat), n);
    expect_exact(vec3_normalize(c), ((vec3){0, 1, 0}), "the disc's normal");
    /* a mirror: det < 0 and C n points the other way from (M^-1)^T n */
    transform mirror = transform_scale((vec3){-1, 2, 1});
    vec3 m = vec3_normalize((vec3){1, 2, 3});
    ck_assert(vec3_dot(mat4_mul_dir(mat4_cofactor3(mirror.m), m),
                       mat4_mul_normal(mirror.inv, m)) < 0);
}
END_TEST

/* ------------------------------------------------------------ objects in their
 * own space */

/* The nearest hit of r in a scene parsed from text; fails the test on a parse
 * error. */
static bool hit_of(const char *text, ray r, hit *h)
{
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s, text, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    render_stats stats = {0};
    bool found = scene_intersect(&s, r, 0, INFINITY, h, &stats);
    scene_free(&s);
    return found;
}

/* sum ((qo + t qd)_i / s_i)^2 - 1: where the point at t along the ray
 * lies with respect to the ellipsoid (< 0 inside), in long double. */
static long double ellipsoid_at(const long double qo[3],
                                const long double qd[3],
                                const long double sc[3], long double t)
{
    long double sum = -1;
    for (int i = 0; i < 3; i++)
        sum += (qo[i] + t * qd[i]) * (qo[i] + t * qd[i]) / (sc[i] * sc[i]);
    return sum;
}

START_TEST(test_ellipsoid_hit_and_normal_match_the_closed_form)
{
    /* The unit sphere scaled by (a, b, c), turned by th about y, moved to m. In
     * long double: q = R^T (p - m) satisfies sum (q_i / s_i)^2 = 1, found
     * along the ray by search and bisection (not by a quadratic's formula),
     * and the normal is the gradient R (q_i / s_i^2). */
    const long double a = 2, b = 0.5L, c = 1.25L, th = 35 * acosl(-1) / 180;
    const long double m[3] = {0.5L, -0.25L, 7};
    char text[256];
    snprintf(
        text, sizeof text,
        "sphere center 0 0 0 radius 1 transform scale 2 0.5 1.25 rotate y 35 "
        "translate 0.5 -0.25 7\n");
    for (int k = 0; k < 200; k++) {
        vec3 o = {uniform(-3, 3), uniform(-3, 3), uniform(-4, 0)};
        vec3 aim = {(double)m[0] + uniform(-1.5, 1.5),
                    (double)m[1] + uniform(-0.4, 0.4), (double)m[2]};
        ray r = {o, vec3_normalize(vec3_sub(aim, o))};
        long double oo[3] = {o.x - m[0], o.y - m[1], o.z - m[2]},
                    dd[3] = {r.dir.x, r.dir.y, r.dir.z};
        /* R_y(th)^T: x' = cos x - sin z, z' = sin x + cos z */
        long double s = sinl(th), co = cosl(th);
        long double qo[3] = {co * oo[0] - s * oo[2], oo[1],
                             s * oo[0] + co * oo[2]};
        long double qd[3] = {co * dd[0] - s * dd[2], dd[1],
                             s * dd[0] + co * dd[2]};
        long double sc[3] = {a, b, c}, lo = 0, hi = 30; /* past it */
        for (int step = 0; step < 200; step++) { /* the deepest point */
            long double u = lo + (hi - lo) / 3, v = hi - (hi - lo) / 3;
            if (ellipsoid_at(qo, qd, sc, u) < ellipsoid_at(qo, qd, sc, v))
                hi = v;
            else
                lo = u;
        }
        long double deepest = ellipsoid_at(qo, qd, sc, (lo + hi) / 2);
        hit h;
        bool found = hit_of(text, r, &h);
        if (fabsl(deepest) < 1e-7L)
            continue; /* grazing: hit or miss is decided by rounding */
        ck_assert_int_eq(found, deepest < 0);
        if (!found)
            continue;
        long double out = 0, in = (lo + hi) / 2; /* the origin is outside */
        for (int step = 0; step < 200; step++) {
            long double mid = (out + in) / 2;
            if (ellipsoid_at(qo, qd, sc, mid) > 0)
                out = mid;
            else
                in = mid;
        }
        long double t = (out + in) / 2;
        /* t: a few u of relative error per step (the transform, the robust
         * roots) */
        ck_assert_msg(fabsl(h.t - t) <= 1e-13L * t, "t %.17g vs %.17Lg", h.t,
                      t);
        long double q[3], g[3];
        for (int i = 0; i < 3; i++)
            q[i] = qo[i] + t * qd[i], g[i] = q[i] / (sc[i] * sc[i]);
        vec3 normal = {(double)(co * g[0] + s * g[2]), (double)g[1],
                       (double)(-s * g[0] + co * g[2])};
        /* the normal to within 1e-10 degrees: rounding scaled by kappa = 4 */
        ck_assert_msg(degrees_between(h.normal, normal) < 1e-10,
                      "normal off by %g degrees",
                      degrees_between(h.normal, normal));
        ck_assert(fabs(vec3_length(h.normal) - 1) <= 4 * U);
        ck_assert(!h.inside && vec3_dot(h.normal, r.dir) < 0);
    }
}
END_TEST

START_TEST(test_ray_in_object_space_keeps_t)
{
    /* A unit sphere scaled by 3 at z = 10: seen head on from the origin, hit at
     * t = 7 */
    hit h;
    ck_assert(
        hit_of("sphere center 0 0 0 transform scale 3 3 3 translate 0 0 10\n",
               (ray){{0, 0, 0}, {0, 0, 1}}, &h));
    ck_assert(h.t == 7);
    expect_exact(h.point, ((vec3){0, 0, 7}), "the world point");
    expect_exact(h.normal, ((vec3){0, 0, -1}), "the world normal");
    /* a nearer unplaced sphere still wins, and a farther one loses: one t for
     * all */
    ck_assert(
        hit_of("sphere center 0 0 0 transform scale 3 3 3 translate 0 0 10\n"
               "sphere center 0 0 6 radius 0.5\n",
               (ray){{0, 0, 0}, {0, 0, 1}}, &h));
    ck_assert(h.t == 5.5);
    ck_assert(
        hit_of("sphere center 0 0 8 radius 0.5\n"
               "sphere center 0 0 0 transform scale 3 3 3 translate 0 0 10\n",
               (ray){{0, 0, 0}, {0, 0, 1}}, &h));
    ck_assert(h.t == 7);
}
END_TEST

START_TEST(test_transform_steps_apply_in_the_order_written)
{
    scene s;
    scene_error err;
    ck_assert(parse_text(
        &s,
        "sphere transform rotate z 90 translate 1 0 0\n"
        "sphere transform translate 1 0 0 rotate z 90\n"
        "sphere transform rotate z 90 color 1 0 0 transform translate 1 0 0\n",
        &err));
    vec3 p = {1, 0, 0};
    expect_exact(
        mat4_mul_point(scene_transform(&s, s.objects[0].transform)->m, p),
        ((vec3){1, 1, 0}), "rotate, then translate: T R");
    expect_exact(
        mat4_mul_point(scene_transform(&s, s.objects[1].transform)->m, p),
        ((vec3){0, 2, 0}), "translate, then rotate: R T");
    expect_exact(
        mat4_mul_point(scene_transform(&s, s.objects[2].transform)->m, p),
        ((vec3){1, 1, 0}), "two transform settings continue");
    ck_assert(s.objects[2].color.x == 1 && s.transform_count == 3);
    /* an object without a transform has none, and costs no transform */
    scene_free(&s);
    ck_assert(parse_text(&s, "sphere\ntriangle\n", &err));
    ck_assert(s.objects[0].transform == 0 && s.transform_count == 0);
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ instances */

static const char OCTAHEDRON[] =
    "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\n"
    "f 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

START_TEST(test_instanced_mesh_hits_equal_the_mesh_transformed_in_world_space)
{
    /* The same octahedron, once placed by a transform, once with its vertices
     * moved by the same matrix before it is written: every ray must see the
     * same surface. */
    transform t =
        transform_then(transform_scale((vec3){1.5, 0.5, 1}),
                       transform_rotate(vec3_normalize((vec3){1, 2, 0.5}), 40));
    t = transform_then(t, transform_translate((vec3){0.3, -0.2, 6}));
    write_file("octa.obj", OCTAHEDRON);
    char moved[1024] = "", line[128];
    const vec3 corners[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                             {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (int k = 0; k < 6; k++) {
        vec3 v = mat4_mul_point(t.m, corners[k]);
        snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", v.x, v.y, v.z);
        strcat(moved, line);
    }
    strcat(moved, strstr(OCTAHEDRON, "f "));
    write_file("moved.obj", moved);
    char placed_text[256], world_text[64], placed_path[192], world_path[192];
    snprintf(placed_text, sizeof placed_text,
             "mesh file octa.obj transform scale 1.5 0.5 1 rotate 1 2 0.5 40 "
             "translate 0.3 -0.2 6\n");
    snprintf(world_text, sizeof world_text, "mesh file moved.obj\n");
    snprintf(placed_path, sizeof placed_path, "%s", tmp_path("placed.scene"));
    snprintf(world_path, sizeof world_path, "%s", tmp_path("world.scene"));
    scene placed, world;
    scene_error err;
    ck_assert_msg(parse_named(&placed, placed_text, strlen(placed_text),
                              placed_path, &err),
                  "%s", err.message);
    ck_assert_msg(
        parse_named(&world, world_text, strlen(world_text), world_path, &err),
        "%s", err.message);
    int compared = 0;
    for (int k = 0; k < 2000; k++) {
        /* aimed inside a random face, away from its edges (barycentrics >=
         * 0.05) */
        const int *f = placed.meshes[0].triangles[k % 8].v;
        double l1 = uniform(0.05, 0.9), l2 = uniform(0.05, 0.95 - l1),
               l0 = 1 - l1 - l2;
        vec3 target = vec3_add(
            vec3_add(vec3_scale(mat4_mul_point(t.m, corners[f[0]]), l0),
                     vec3_scale(mat4_mul_point(t.m, corners[f[1]]), l1)),
            vec3_scale(mat4_mul_point(t.m, corners[f[2]]), l2));
        vec3 o = {uniform(-4, 4), uniform(-4, 4), uniform(-2, 1)};
        ray r = {o, vec3_normalize(vec3_sub(target, o))};
        render_stats stats = {0};
        hit a, b;
        bool ha = scene_intersect(&placed, r, 0, INFINITY, &a, &stats);
        bool hb = scene_intersect(&world, r, 0, INFINITY, &b, &stats);
        ck_assert_int_eq(ha, hb);
        if (!ha)
            continue;
        compared++;
        /* t to 1e-12 relative and normals to 1e-9 degrees: the two paths round
         * differently (a transform of the ray against a transform of the
         * vertices, each a few u, amplified by kappa = 3 and by how obliquely
         * the ray meets the face) */
        ck_assert_msg(fabs(a.t - b.t) <= 1e-12 * b.t, "t %.17g vs %.17g", a.t,
                      b.t);
        ck_assert_msg(degrees_between(a.normal, b.normal) < 1e-9,
                      "normals %g degrees apart",
                      degrees_between(a.normal, b.normal));
        ck_assert_int_eq(a.inside, b.inside);
    }
    ck_assert(compared > 1000);
    scene_free(&placed);
    scene_free(&world);
}
END_TEST

START_TEST(test_mesh_statements_share_one_mesh)
{
    write_file("octa.obj", OCTAHEDRON);
    char path[192];
    snprintf(path, sizeof path, "%s", tmp_path("share.scene"));
    const char *text =
        "mesh file octa.obj transform translate -2 0 6\n"
        "mesh file octa.obj transform rotate y 45 translate 2 0 6\n"
        "mesh file octa.obj color 1 0 0\n"
        "mesh file octa.obj smooth\n"
        "mesh file octa.obj scale 2\n"
        "triangle\n";
    scene s;
    scene_error err;
    ck_assert_msg(parse_named(&s, text, strlen(text), path, &err), "%s",
                  err.message);
    ck_assert_int_eq(s.object_count, 6);
    ck_assert_int_eq(s.mesh_count, 3); /* plain, smooth, and scaled as read */
    ck_assert(s.objects[0].mesh == s.objects[1].mesh &&
              s.objects[1].mesh == s.objects[2].mesh);
    ck_assert(s.objects[3].mesh != s.objects[0].mesh &&
              s.objects[4].mesh != s.objects[0].mesh);
    long long stored, instanced;
    scene_count_triangles(&s, &stored, &instanced);
    ck_assert_int_eq(stored, 3 * 8 + 1);
    ck_assert_int_eq(instanced, 5 * 8 + 1);
    scene_free(&s);
}
END_TEST

/* The number after label at the start of a line of errors; 0 when the
 * program prints no such line (a chapter before the one that counts it). */
static long long stat_of(const char *errors, const char *label)
{
    for (const char *line = errors; line != NULL && *line != '\0';) {
        if (strncmp(line, label, strlen(label)) == 0)
            return atoll(line + strlen(label));
        line = strchr(line, '\n');
        line = line ? line + 1 : NULL;
    }
    return 0;
}

START_TEST(test_stats_show_triangles_stored_and_instanced)
{
    write_file("octa.obj", OCTAHEDRON);
    const char *scene_path = write_file(
        "stats.scene", "image 16 12\n"
                       "mesh file octa.obj transform translate -2 0 6\n"
                       "mesh file octa.obj transform translate 2 0 6\n");
    char scene_copy[192], out[192], errors[2048];
    snprintf(scene_copy, sizeof scene_copy, "%s", scene_path);
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    const char *args[] = {scene_copy, "-o", out, "--stats", NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    ck_assert_msg(strstr(errors, "triangles          8 stored, 16 instanced") !=
                      NULL,
                  "%s", errors);
    /* Every ray that reaches the objects is taken into both instances'
     * spaces: 2 x 192 primary rays, and from chapter 6 on its shadow and
     * mirror rays too. */
    long long rays = stat_of(errors, "primary rays") +
                     stat_of(errors, "shadow rays") +
                     stat_of(errors, "reflection rays");
    ck_assert_int_eq(stat_of(errors, "primary rays"), 192);
    ck_assert_msg(stat_of(errors, "object-space rays") == 2 * rays, "%s",
                  errors);
}
END_TEST

/* ------------------------------------------------------------ the placed
 * camera */

static camera placed_camera(vec3 eye, vec3 target, vec3 up)
{
    return (camera){.fov_deg = 50,
                    .width = 101,
                    .height = 75,
                    .is_placed = true,
                    .position = eye,
                    .look_at = target,
                    .up = up};
}

START_TEST(test_default_camera_is_the_identity)
{
    scene s;
    scene_error err;
    ck_assert(
        parse_text(&s, "camera position 0 0 0 look_at 0 0 1 up 0 1 0\n", &err));
    camera_view placed = camera_view_of(&s.cam);
    ck_assert(placed.is_placed);
    ck_assert(residual(placed.to_world, mat4_identity()) == 0); /* exactly I */
    scene_free(&s);
    /* unplaced, the camera's rays are chapter 01's, bit for bit */
    ck_assert(parse_text(&s, "camera fov 50\n", &err));
    camera_view view = camera_view_of(&s.cam);
    ck_assert(!view.is_placed);
    for (int j = 0; j < s.cam.height; j += 7)
        for (int i = 0; i < s.cam.width; i += 5) {
            ray r = camera_view_ray(&view, i, j);
            vec3 on_plane = camera_image_point(&s.cam, i + 0.5, j + 0.5);
            ck_assert(r.origin.x == 0 && r.origin.y == 0 && r.origin.z == 0);
            expect_exact(r.dir, vec3_normalize(on_plane), "chapter 01's ray");
        }
    scene_free(&s);
}
END_TEST

START_TEST(test_look_at_centre_ray_hits_the_look_at_point)
{
    const vec3 eyes[] = {{3, 2, -4}, {0, 10, 0.001}, {-7, -1, 20}, {1e6, 0, 0}};
    const vec3 targets[] = {{0, 1, 5}, {0, 0, 0}, {2, 2, 2}, {0, 0, 1}};
    for (int k = 0; k < 4; k++) {
        camera cam = placed_camera(eyes[k], targets[k], (vec3){0, 1, 0});
        camera_view view = camera_view_of(&cam);
        ck_assert(view.is_placed);
        ray r =
            camera_view_ray(&view, 50, 37); /* the centre pixel of 101 x 75 */
        expect_vec3(r.origin, eyes[k], 0, "the ray starts at the eye");
        /* the target's distance from the ray, relative to its distance from the
         * eye: the rounding of a rotation and a normalisation, a few u */
        vec3 to = vec3_sub(targets[k], eyes[k]);
        double along = vec3_dot(to, r.dir);
        double off = vec3_length(vec3_sub(to, vec3_scale(r.dir, along)));
        ck_assert_msg(off <= 16 * U * vec3_length(to), "%g off",
                      off / vec3_length(to));
        ck_assert(fabs(vec3_length(r.dir) - 1) <= 4 * U);
    }
}
END_TEST

START_TEST(test_look_at_keeps_up_up)
{
    camera cam =
        placed_camera((vec3){3, 2, -4}, (vec3){0, 1, 5}, (vec3){0, 1, 0});
    camera_view view = camera_view_of(&cam);
    ray centre = camera_view_ray(&view, 50, 37),
        top = camera_view_ray(&view, 50, 0);
    ray left = camera_view_ray(&view, 0, 37);
    /* the top-centre ray is higher (world y) than the centre ray, and in the
     * plane of the view and up: no component along the camera's right */
    ck_assert(top.dir.y > centre.dir.y);
    vec3 right = {view.to_world.m[0][0], view.to_world.m[1][0],
                  view.to_world.m[2][0]};
    ck_assert(fabs(vec3_dot(top.dir, right)) <= 8 * U);
    ck_assert(right.y == 0); /* right is horizontal when up is the world's up */
    ck_assert(vec3_dot(left.dir, right) < 0);
    /* a tilted up rolls the picture: up = (1, 1, 0) turns the top towards +x */
    cam.up = (vec3){1, 1, 0};
    cam.position = (vec3){0, 0, 0}, cam.look_at = (vec3){0, 0, 1};
    view = camera_view_of(&cam);
    top = camera_view_ray(&view, 50, 0);
    ck_assert(top.dir.x > 0 && top.dir.y > 0);
    ck_assert_double_eq_tol(
        degrees_between((vec3){top.dir.x, top.dir.y, 0}, (vec3){1, 1, 0}), 0,
        1e-9);
}
END_TEST

START_TEST(test_look_at_is_a_rotation_not_a_mirror)
{
    for (int k = 0; k < 300; k++) {
        vec3 eye = {uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
        vec3 target = vec3_add(
            eye, vec3_scale(rng_unit_vector(&rng, 0.1), uniform(0.1, 100)));
        mat4 m;
        if (!mat4_look_at(eye, target, rng_unit_vector(&rng, 0.1), &m))
            continue;
        /* det +1 and orthonormal columns, to a few u */
        ck_assert_double_eq_tol(mat4_det3(m), 1, 16 * U);
        mat4 g = mat4_mul(mat4_transpose(m), m);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                ck_assert_double_eq_tol(g.m[i][j], i == j, 16 * U);
    }
    /* Turned around to look down -z, the camera sees the world's -x on its
     * right: a half turn about y, as a person turns, not a mirror image. */
    camera cam =
        placed_camera((vec3){0, 0, 10}, (vec3){0, 0, 0}, (vec3){0, 1, 0});
    camera_view view = camera_view_of(&cam);
    ray right_edge = camera_view_ray(&view, 100, 37);
    ck_assert(right_edge.dir.x < 0 && right_edge.dir.z < 0);
}
END_TEST

/* ------------------------------------------------------------ bad input */

START_TEST(test_transform_statements_reject_bad_input)
{
    expect_parse_error("sphere transform", 1, 17, "expected a transform step");
    expect_parse_error("sphere transform spin 30", 1, 18,
                       "expected a transform step");
    expect_parse_error("sphere transform color 1 0 0", 1, 18,
                       "expected a transform step");
    expect_parse_error("sphere transform translate 1 2", 1, 31,
                       "found end of line");
    expect_parse_error("sphere transform translate 1 2 inf", 1, 32,
                       "a finite number");
    expect_parse_error("sphere transform translate 1 nan 2", 1, 30,
                       "a finite number");
    expect_parse_error("sphere transform scale 0 1 1", 1, 18, "singular");
    expect_parse_error("sphere transform scale 1e-300 1 1", 1, 18, "singular");
    expect_parse_error("sphere transform scale 1e-13 1 1", 1, 18, "singular");
    expect_parse_error("sphere transform scale 1e13 1 1", 1, 18, "stretch");
    expect_parse_error("sphere transform scale 1e6 1 1 scale 1e7 1 1", 1, 32,
                       "stretch");
    expect_parse_error("sphere transform rotate 0 0 0 30", 1, 25,
                       "non-zero length");
    expect_parse_error("sphere transform rotate w 30", 1, 25,
                       "expected a rotation axis");
    expect_parse_error("sphere transform rotate x", 1, 26, "expected an angle");
    expect_parse_error("sphere transform shear zx 1 1", 1, 24,
                       "plane of a shear");
    expect_parse_error("sphere transform shear xy 1", 1, 28,
                       "expected a shear factor");
    expect_parse_error("sphere transform shear xy 1e13 0", 1, 18, "stretch");
    expect_parse_error("sphere transform matrix 1 0 0 0 0 1 0 0 0 0 0 0", 1, 18,
                       "singular");
    expect_parse_error("sphere transform matrix 1 0 0 0 0 1 0 0 1 1 0", 1, 46,
                       "matrix entry");
    expect_parse_error("sphere transform matrix 1 0 0 0 0 inf 0 0 0 0 1 0", 1,
                       35, "a finite number");
    expect_parse_error("sphere transform matrix 1 0 0 0 0 1 0 0 0 0 1e-300 0",
                       1, 18, "singular");
    expect_parse_error("sphere transform translate 1e50 0 0 translate 1e50 0 0",
                       1, 37, "beyond 1e50");
    expect_parse_error("sphere center 0 0 0 transform scale 1 1 1 radius 0", 1,
                       50, "radius from 1e-50");
    expect_parse_error("triangle transform shear", 1, 25, "plane of a shear");
    expect_parse_error("sphere transform rotate z 30 centre 0 0 0", 1, 30,
                       "expected a sphere setting");
    expect_parse_error("sphere colour 1 0 0", 1, 8, "transform");
}
END_TEST

START_TEST(test_camera_placement_rejects_bad_input)
{
    expect_parse_error("camera up 0 0 0", 1, 11, "non-zero length");
    expect_parse_error("camera position 0 0 1", 1, 1,
                       "look_at point is its position");
    expect_parse_error("camera position 1 2 3 look_at 1 2 3", 1, 1,
                       "look_at point is its position");
    expect_parse_error("camera look_at 0 5 0", 1, 1,
                       "up is (nearly) along its view");
    expect_parse_error("camera position 0 0 0 look_at 0 0 5 up 0 0 -2", 1, 1,
                       "along its view");
    expect_parse_error("camera look_at 0 1e6 1e-1", 1, 1,
                       "along its view"); /* sin 1e-7 */
    expect_parse_error("camera position nan 0 0", 1, 17, "a finite number");
    expect_parse_error("camera look_at 0 0", 1, 19, "found end of line");
    expect_parse_error("camera position 2e50 0 0", 1, 17,
                       "between -1e50 and 1e50");
    /* a later statement is checked with what the earlier ones set */
    expect_parse_error("camera look_at 0 0 9\ncamera position 0 0 9", 2, 1,
                       "its position");
    scene s;
    scene_error err;
    ck_assert(
        parse_text(&s, "camera look_at 0 0 9\ncamera position 0 0 -9\n", &err));
    ck_assert(s.cam.look_at.z == 9 && s.cam.position.z == -9 &&
              s.cam.is_placed);
    scene_free(&s);
    /* nearly along the view, but not within 1e-6: accepted */
    ck_assert(parse_text(&s, "camera look_at 0 1e4 1\n", &err));
    scene_free(&s);
}
END_TEST

START_TEST(test_cli_rejects_bad_transforms_and_writes_no_file)
{
    const char *cases[][2] = {
        {"sphere transform scale 1 0 1\n",
         "bad.scene:1:18: error: this step makes the transform singular"},
        {"image 8 8\nsphere transform rotate 0 0 0 1\n",
         "bad.scene:2:25: error: expected a rotation axis"},
        {"camera look_at 0 0 0\n",
         "bad.scene:1:1: error: the camera's look_at point is its position"},
        {"mesh file none.obj transform translate 0 0 5\n",
         "bad.scene:1:11: error: cannot read mesh"},
    };
    for (int k = 0; k < 4; k++) {
        const char *scene_path = write_file("bad.scene", cases[k][0]);
        char scene_copy[192], out[192], errors[2048];
        snprintf(scene_copy, sizeof scene_copy, "%s", scene_path);
        snprintf(out, sizeof out, "%s", tmp_path("out.png"));
        const char *args[] = {scene_copy, "-o", out, NULL};
        ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
        ck_assert_msg(strstr(errors, cases[k][1]) != NULL, "stderr: %s",
                      errors);
        ck_assert(!file_exists(out));
    }
}
END_TEST

START_TEST(test_extreme_accepted_transforms_give_no_nan_pixel)
{
    /* At the limits the scene file accepts: every pixel is a finite colour. */
    const char *text =
        "image 48 36\ncamera position 1e3 2e3 -1e3 look_at 0 0 5 up 0 1 0\n"
        "sphere center 0 0 0 transform scale 1e-6 1e6 1 rotate 1 2 3 17 "
        "translate 0 0 5\n"
        "sphere center 0 0 0 transform shear xy 9e11 0 translate 1 1 5\n"
        "sphere center 0 0 0 radius 1e40 transform scale 1e-12 1e-12 1e-12 "
        "translate 0 -3 9\n"
        "triangle transform matrix 1e6 0 0 0 0 1e-6 0 0 0 0 1 5 rotate z "
        "1e300\n"
        "light point position 0 10 0\n";
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s, text, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    image img = {0};
    ck_assert(image_init(&img, s.cam.width, s.cam.height));
    render_stats stats = {0};
    render(&s, &img, &stats);
    for (int k = 0; k < img.width * img.height; k++)
        ck_assert(isfinite(img.pixels[k].x) && isfinite(img.pixels[k].y) &&
                  isfinite(img.pixels[k].z));
    ck_assert(stats.object_space_rays > 0);
    image_free(&img);
    scene_free(&s);
}
END_TEST

START_TEST(test_help_says_in_which_order_transforms_apply)
{
    const char *bin = getenv("CHAPTER_BIN");
    ck_assert(bin != NULL);
    char command[512], text[2048];
    snprintf(command, sizeof command, "'%s' --help", bin);
    FILE *p = popen(command, "r");
    ck_assert_ptr_nonnull(p);
    size_t n = fread(text, 1, sizeof text - 1, p);
    text[n] = '\0';
    ck_assert_int_eq(pclose(p), 0);
    ck_assert_msg(strstr(text, "apply in the order written") != NULL, "%s",
                  text);
    ck_assert(strstr(text, "(T R S)") != NULL);
}
END_TEST

Suite *ch05_transforms_suite(void)
{
    Suite *s = suite_create("ch05 transforms");
    TCase *formulas = tcase_create("formulas");
    tcase_add_checked_fixture(formulas, reseed, NULL);
    tcase_add_test(formulas, test_point_plus_point_is_neither_point_nor_vector);
    tcase_add_test(formulas, test_standard_matrices_move_points_and_vectors);
    tcase_add_test(formulas, test_rotations_turn_the_way_the_chapter_says);
    tcase_add_test(
        formulas, test_positive_z_rotation_turns_the_picture_counter_clockwise);
    tcase_add_test(formulas, test_composition_applies_the_right_factor_first);
    tcase_add_test(formulas, test_shear_has_determinant_one_and_changes_angles);
    tcase_add_test(formulas, test_inverses_give_the_identity);
    tcase_add_test(
        formulas,
        test_cofactors_are_the_inverse_transpose_times_the_determinant);
    tcase_add_test(formulas, test_sheet_normal_is_36_9_degrees_off_for_a_scale);
    tcase_add_test(formulas,
                   test_sheet_normal_is_wrong_for_a_shear_of_determinant_one);
    tcase_add_test(formulas,
                   test_inverse_transpose_keeps_normals_perpendicular);
    tcase_add_test(formulas,
                   test_cofactor_matrix_gives_normals_of_a_singular_transform);
    tcase_add_test(formulas,
                   test_ellipsoid_hit_and_normal_match_the_closed_form);
    tcase_add_test(formulas, test_ray_in_object_space_keeps_t);
    tcase_add_test(formulas, test_transform_steps_apply_in_the_order_written);
    tcase_add_test(formulas, test_default_camera_is_the_identity);
    tcase_add_test(formulas, test_look_at_centre_ray_hits_the_look_at_point);
    tcase_add_test(formulas, test_look_at_keeps_up_up);
    tcase_add_test(formulas, test_look_at_is_a_rotation_not_a_mirror);
    suite_add_tcase(s, formulas);

    TCase *instances = tcase_create("instances");
    tcase_add_checked_fixture(instances, reseed, NULL);
    tcase_add_checked_fixture(instances, make_tmpdir, remove_tmpdir);
    tcase_add_test(
        instances,
        test_instanced_mesh_hits_equal_the_mesh_transformed_in_world_space);
    tcase_add_test(instances, test_mesh_statements_share_one_mesh);
    tcase_add_test(instances, test_stats_show_triangles_stored_and_instanced);
    suite_add_tcase(s, instances);

    TCase *bad = tcase_create("bad input");
    tcase_add_checked_fixture(bad, reseed, NULL);
    tcase_add_checked_fixture(bad, make_tmpdir, remove_tmpdir);
    tcase_add_test(bad, test_transform_statements_reject_bad_input);
    tcase_add_test(bad, test_camera_placement_rejects_bad_input);
    tcase_add_test(bad, test_cli_rejects_bad_transforms_and_writes_no_file);
    tcase_add_test(bad, test_extreme_accepted_transforms_give_no_nan_pixel);
    tcase_add_test(bad, test_help_says_in_which_order_transforms_apply);
    suite_add_tcase(s, bad);
    return s;
}
