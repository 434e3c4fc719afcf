/* ch02_spheres.c: ray-sphere intersection, the nearest hit, and the sphere
 * statement (chapter 02).
 *
 * Expected roots are worked out by hand (stated beside each) or computed by
 * this file's own long double version of the robust form. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "render.h"
#include "scene.h"
#include "search.h"
#include "test_util.h"
#include "sphere.h"
#include "rng.h"

typedef int (*roots_fn)(vec3, double, ray, double[2]);

static const struct {
    const char *name;
    roots_fn roots;
} forms[] = {
    {"geometric", sphere_roots_geometric},
    {"quadratic", sphere_roots_quadratic},
    {"robust", sphere_roots_robust},
    {"geometric float", sphere_roots_geometric_float},
    {"quadratic float", sphere_roots_quadratic_float},
    {"robust float", sphere_roots_robust_float},
};
#define N_FORMS (int)(sizeof forms / sizeof forms[0])

/* The tests that every form must pass run once a form, as Check's loop
 * tests: iteration _i is the form of exercise 2.(_i + 1), forms[_i] in
 * double and forms[_i + FORMS_OF_EXERCISES] in float, so that each
 * exercise's tests call its own code only. */
#define FORMS_OF_EXERCISES 3
#define EACH_BUILD_OF_THIS_FORM(f)                                           \
    for (int f = _i; f < N_FORMS; f += FORMS_OF_EXERCISES)

static const vec3 ORIGIN = {0, 0, 0};
static const vec3 PLUS_Z = {0, 0, 1};

/* fixed seed: the same rays every run */
static const rng_state RNG_START = {12345};
static rng_state rng;

/* Each test draws the same numbers, whichever tests ran before it. */
static void reseed(void) { rng = RNG_START; }

static double uniform(double lo, double hi)
{
    return rng_uniform(&rng, lo, hi);
}

/* ------------------------------------------------------------ roots */

START_TEST(test_two_hits_at_4_and_6)
{
    /* Unit sphere 5 ahead: enters at 4, leaves at 6, exact in float too. */
    EACH_BUILD_OF_THIS_FORM(f) {
        double t[2];
        ck_assert_int_eq(
            forms[f].roots((vec3){0, 0, 5}, 1, (ray){ORIGIN, PLUS_Z}, t), 2);
        ck_assert_msg(t[0] == 4 && t[1] == 6, "%s: %g %g", forms[f].name, t[0],
                      t[1]);
    }
}
END_TEST

START_TEST(test_tangent_ray_gives_a_double_root)
{
    /* The line x = 1 touches the unit sphere at (1, 0, 5). */
    EACH_BUILD_OF_THIS_FORM(f) {
        double t[2];
        ck_assert_int_eq(
            forms[f].roots((vec3){0, 0, 5}, 1, (ray){{1, 0, 0}, PLUS_Z}, t), 2);
        ck_assert_msg(t[0] == 5 && t[1] == 5,
                      "%s: %g %g, not 5 5: measure from the ray's "
                      "origin, c - o, not from (0, 0, 0) as sheet 1.4 does",
                      forms[f].name, t[0], t[1]);
    }
}
END_TEST

START_TEST(test_ray_beside_the_sphere_misses)
{
    EACH_BUILD_OF_THIS_FORM(f) {
        double t[2];
        int n =
            forms[f].roots((vec3){0, 0, 5}, 1, (ray){{1.5, 0, 0}, PLUS_Z}, t);
        ck_assert_msg(
            n == 0,
            "%s: %d roots for a ray from (1.5, 0, 0) that passes beside "
            "the sphere: measure from the ray's origin, c - o, not from (0, 0, "
            "0) "
            "as sheet 1.4 does",
            forms[f].name, n);
    }
}
END_TEST

START_TEST(test_sphere_behind_the_origin_is_not_seen)
{
    sphere sp = {.center = {0, 0, -5}, .radius = 1};
    double t[2], seen;
    ck_assert_int_eq(
        sphere_roots_robust(sp.center, 1, (ray){ORIGIN, PLUS_Z}, t), 2);
    ck_assert(t[0] == -6 && t[1] == -4);
    ck_assert(!sphere_hit_t(&sp, (ray){ORIGIN, PLUS_Z}, 0, INFINITY, &seen));
}
END_TEST

START_TEST(test_the_nearer_root_is_the_hit)
{
    /* roots 4 and 6: the ray meets the sphere first at 4 */
    sphere sp = {.center = {0, 0, 5}, .radius = 1};
    ray r = {ORIGIN, PLUS_Z};
    double t = 0;
    ck_assert(sphere_hit_t(&sp, r, 0, INFINITY, &t));
    ck_assert_msg(t == 4, "t = %g: the nearer root is 4, where the ray first "
                          "meets the sphere", t);
    ck_assert_msg(sphere_hit_t(&sp, r, 4.5, INFINITY, &t) && t == 6,
                  "t_min 4.5: the nearer root is behind it, the hit is 6");
    ck_assert_msg(!sphere_hit_t(&sp, r, 0, 3.9, &t),
                  "t_max 3.9: both roots lie beyond it, no hit");
}
END_TEST

START_TEST(test_origin_inside_sees_the_far_side)
{
    sphere sp = {.center = {0, 0, 0}, .radius = 2};
    ray r = {ORIGIN, PLUS_Z};
    double t;
    ck_assert(sphere_hit_t(&sp, r, 0, INFINITY, &t));
    ck_assert(t == 2); /* roots -2 and 2: the one in front */
    hit h = {.inside = false};
    sphere_fill_hit(&sp, r, t, &h);
    ck_assert(h.normal.x == 0 && h.normal.y == 0 &&
              h.normal.z == 1); /* outward */
    ck_assert_msg(h.inside, "a ray from the centre hits the sphere from "
                            "inside: the hit must say so (inside)");
    /* and a ray from outside, the other way */
    ray from_outside = {{0, 0, -5}, PLUS_Z};
    ck_assert(sphere_hit_t(&sp, from_outside, 0, INFINITY, &t));
    h.inside = true;
    sphere_fill_hit(&sp, from_outside, t, &h);
    ck_assert_msg(!h.inside, "a ray from outside: inside must be false");
}
END_TEST

START_TEST(test_roots_are_ordered)
{
    int two_roots[N_FORMS] = {0};
    for (int k = 0; k < 2000; k++) {
        vec3 c = vec3_scale(rng_unit_vector(&rng, 1e-3), uniform(0, 20));
        ray r = {vec3_scale(rng_unit_vector(&rng, 1e-3), uniform(0, 20)),
                 rng_unit_vector(&rng, 1e-3)};
        double radius = uniform(0.1, 5);
        EACH_BUILD_OF_THIS_FORM(f) {
            double t[2];
            if (forms[f].roots(c, radius, r, t) == 2) {
                two_roots[f]++;
                ck_assert_msg(t[0] <= t[1], "%s: %g > %g", forms[f].name, t[0],
                              t[1]);
            }
        }
    }
    /* Every form must have been tested: a sphere of radius up to 5 within
     * 20 of a random ray's origin is crossed by about one ray in ten. */
    EACH_BUILD_OF_THIS_FORM(f)
        ck_assert_msg(two_roots[f] >= 50, "%s: only %d rays with two roots",
                      forms[f].name, two_roots[f]);
}
END_TEST

START_TEST(test_negative_d_squared_from_rounding_is_a_hit)
{
    /* Aimed exactly at the centre; found by search: |c|^2 - <c,d>^2 rounds
     * to about -2.3e-13 in double instead of 0. */
    vec3 c = {0.60000000000000009, 2.5, 45};
    double n = sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
    vec3 d = {c.x / n, c.y / n, c.z / n};
    double along = c.x * d.x + c.y * d.y + c.z * d.z;
    double D2 = c.x * c.x + c.y * c.y + c.z * c.z - along * along;
    ck_assert_msg(D2 < 0, "precondition: D^2 = %g should round below 0", D2);
    ck_assert(
        isnan(sqrt(D2))); /* the sheet's D: every comparison with it is false */
    double sheet_D = sqrt(D2);
    ck_assert(
        !(sheet_D <=
          1)); /* so the sheet's "D <= r: a hit" misses this head-on ray */
    bool robust = forms[_i].roots == sphere_roots_robust;
    double t_hit;
    sphere sp = {c, 1};
    if (robust) /* the program, through the robust form, hits */
        ck_assert(sphere_hit_t(&sp, (ray){ORIGIN, d}, 0, INFINITY, &t_hit));
    double t[2]; /* the form's double build */
    ck_assert_int_eq(forms[_i].roots(c, 1, (ray){ORIGIN, d}, t), 2);
    /* Head-on: t = |c| -+ 1. The naive forms err by about eps |c|^2 / r
     * (the cancellation the chapter derives), the robust one by eps |c|. */
    double tolerance = (robust ? 8 : 4 * n) * DBL_EPSILON * n;
    ck_assert_msg(fabs(t[0] - (n - 1)) <= tolerance &&
                      fabs(t[1] - (n + 1)) <= tolerance,
                  "%s: %.17g %.17g, not |c| -+ 1 = %.17g %.17g", forms[_i].name,
                  t[0], t[1], n - 1, n + 1);
}
END_TEST

/* ------------------------------------------------------------ where forms fail
 */

/* |o + t d - c|^2 in long double: the squared distance from the centre
 * of the point at t along the ray. */
static long double distance_squared(const long double f[3],
                                    const long double d[3], long double t)
{
    long double sum = 0;
    for (int k = 0; k < 3; k++)
        sum += (f[k] + t * d[k]) * (f[k] + t * d[k]);
    return sum;
}

/* The visible hit of a ray from outside the sphere, found without any of
 * the chapter's formulas: the point of the ray nearest the centre by a
 * ternary search, then each root by bisection on its side of it, all in
 * long double (the distance is convex along the ray, so each side is
 * monotone). False on a miss. *gap: how far the ray's line passes from
 * the silhouette, in radii. */
static bool reference_t(vec3 c, double radius, ray r, long double *t,
                        long double *gap)
{
    long double f[3] = {(long double)r.origin.x - c.x,
                        (long double)r.origin.y - c.y,
                        (long double)r.origin.z - c.z};
    long double d[3] = {r.dir.x, r.dir.y, r.dir.z};
    long double rr = (long double)radius * radius;
    long double lo = 0, hi = 2 * sqrtl(distance_squared(f, d, 0)) + 2;
    for (int k = 0; k < 200; k++) { /* the nearest point, in [lo, hi] */
        long double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
        if (distance_squared(f, d, a) < distance_squared(f, d, b))
            hi = b;
        else
            lo = a;
    }
    long double nearest = (lo + hi) / 2;
    long double perp2 = distance_squared(f, d, nearest);
    *gap = fabsl(sqrtl(perp2) - radius) / radius;
    if (perp2 > rr)
        return false;
    long double in = 0, out = nearest; /* outside at 0, inside at nearest */
    for (int k = 0; k < 200; k++) {
        long double mid = (in + out) / 2;
        if (distance_squared(f, d, mid) > rr)
            in = mid;
        else
            out = mid;
    }
    *t = (in + out) / 2;
    return *t > 0;
}

typedef struct {
    int misclassified;
    double max_rel_error;
} form_score;

/* A ray grazing the silhouette closer than this (in radii) may be called a
 * hit or a miss: rounding the direction to float (2^-24 per component)
 * already moves the line by up to 1e-4 radii at 10^3 radii; 2e-4 leaves a
 * factor 2. The naive forms' band is eps D^2 / 2 = 0.03 radii there. */
#define GRAZING 2e-4

/* Rays from the origin over a disc of 1.2 radii around a unit sphere at D;
 * misclassified counts the rays that are not grazing. */
static form_score score_form(roots_fn roots, double D, int n_rays)
{
    form_score s = {0, 0};
    vec3 axis = vec3_normalize((vec3){0.3, 0.4, 1.0});
    vec3 c = vec3_scale(axis, D);
    vec3 e1 = vec3_normalize((vec3){1.0, 0.0, -0.3});
    vec3 e2 = {axis.y * e1.z - axis.z * e1.y, axis.z * e1.x - axis.x * e1.z,
               axis.x * e1.y - axis.y * e1.x};
    rng.state = 777;
    for (int k = 0; k < n_rays; k++) {
        double u = uniform(-1.2, 1.2), v = uniform(-1.2, 1.2);
        ray r = {ORIGIN,
                 vec3_normalize(vec3_add(
                     c, vec3_add(vec3_scale(e1, u), vec3_scale(e2, v))))};
        long double ref, gap;
        bool ref_hit = reference_t(c, 1, r, &ref, &gap);
        double t[2];
        bool hit = roots(c, 1, r, t) == 2 && (t[0] > 0 || t[1] > 0);
        if (hit != ref_hit) {
            s.misclassified += gap > GRAZING;
        } else if (hit) {
            double seen = t[0] > 0 ? t[0] : t[1];
            s.max_rel_error =
                fmax(s.max_rel_error, (double)fabsl((seen - ref) / ref));
        }
    }
    return s;
}

START_TEST(test_naive_forms_fail_in_float_where_robust_holds)
{
    /* 10^3 radii: the chapter's chart shows the naive float forms failing,
     * the robust one holding; each form's own float build is checked */
    int f = _i + FORMS_OF_EXERCISES;
    form_score s = score_form(forms[f].roots, 1e3, 4000);
    if (forms[_i].roots != sphere_roots_robust)
        ck_assert_msg(s.misclassified > 0 || s.max_rel_error > 1e-3,
                      "%s: %d misclassified, max error %g, where the "
                      "chapter's chart shows it failing: is the form "
                      "written in real, the type its float build uses?",
                      forms[f].name, s.misclassified, s.max_rel_error);
    else {
        ck_assert_int_eq(s.misclassified, 0);
        ck_assert_msg(s.max_rel_error < 1e-5, "robust float: %g",
                      s.max_rel_error);
    }
}
END_TEST

START_TEST(test_double_forms_are_exact_near_and_robust_far)
{
    form_score s = score_form(forms[_i].roots, 10, 2000);
    ck_assert_int_eq(s.misclassified, 0);
    ck_assert_msg(s.max_rel_error < 1e-13, "%s: %g", forms[_i].name,
                  s.max_rel_error);
    if (forms[_i].roots != sphere_roots_robust)
        return;
    form_score far = score_form(sphere_roots_robust, 1e7, 2000);
    ck_assert_int_eq(far.misclassified, 0);
    ck_assert_msg(far.max_rel_error < 1e-14, "robust at 1e7: %g",
                  far.max_rel_error);
}
END_TEST

/* ------------------------------------------------------------ hits */

START_TEST(test_normals_are_unit_and_outward)
{
    const double distances[] = {3, 1e3, 1e6};
    for (int k = 0; k < 3; k++) {
        sphere sp = {
            .center = vec3_scale(vec3_normalize((vec3){1, 2, 3}), distances[k]),
            .radius = 1};
        for (int n = 0; n < 500; n++) {
            vec3 aim = vec3_add(sp.center,
                                vec3_scale(rng_unit_vector(&rng, 1e-3), 0.9));
            ray r = {ORIGIN, vec3_normalize(aim)};
            double t;
            ck_assert(sphere_hit_t(&sp, r, 0, INFINITY, &t));
            hit h;
            sphere_fill_hit(&sp, r, t, &h);
            ck_assert_double_eq_tol(vec3_length(h.normal), 1.0,
                                    4 * DBL_EPSILON);
            ck_assert(vec3_dot(h.normal, vec3_sub(h.point, sp.center)) > 0);
            ck_assert(vec3_dot(h.normal, r.dir) <
                      0); /* seen from outside: facing us */
            /* The point is on the sphere to the ray's own rounding error. */
            ck_assert_double_eq_tol(vec3_length(vec3_sub(h.point, sp.center)),
                                    1.0, 8 * DBL_EPSILON * distances[k]);
        }
    }
}
END_TEST

START_TEST(test_nearest_of_several_spheres_wins)
{
    scene s;
    scene_init(&s);
    const double zs[] = {10, 5, 20};
    for (int k = 0; k < 3; k++)
        ck_assert(scene_add_object(&s, (object){.kind = SHAPE_SPHERE,
                                                .sphere = {{0, 0, zs[k]}, 1},
                                                .color = {k, 0, 0}}));
    render_stats stats = {0};
    hit h;
    ray r = {ORIGIN, PLUS_Z};
    ck_assert(scene_intersect(&s, r, 0, INFINITY, &h, &stats));
    ck_assert(h.t == 4 && h.color.x == 1); /* the sphere at 5, listed second */
    ck_assert(!scene_intersect(&s, r, 0, 3, &h, &stats));
    ck_assert(scene_intersect(&s, r, 4.5, INFINITY, &h, &stats));
    ck_assert(h.t == 6); /* leaving the sphere at 5 */
    ck_assert_int_eq(stats.sphere_tests, 9);
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ the statement */


START_TEST(test_sphere_statement_defaults_and_settings)
{
    scene s;
    scene_error err;
    ck_assert(parse_text(
        &s, "sphere\nsphere radius 2 color 0 0.5 1 center -1 2.5 1e3\n", &err));
    ck_assert_int_eq(s.object_count, 2);
    ck_assert(s.objects[0].kind == SHAPE_SPHERE &&
              s.objects[1].kind == SHAPE_SPHERE);
    ck_assert(s.objects[0].sphere.radius == 1 &&
              s.objects[0].sphere.center.z == 5);
    ck_assert(
        s.objects[1].sphere.radius == 2 && s.objects[1].sphere.center.x == -1 &&
        s.objects[1].sphere.center.z == 1000 && s.objects[1].color.z == 1);
    scene_free(&s);
    ck_assert_ptr_null(s.objects);
}
END_TEST


START_TEST(test_sphere_statement_rejects_bad_radii)
{
    expect_parse_error("sphere radius 0", 1, 15,
                       "radius from 1e-50 to 1e50, found '0'");
    expect_parse_error("sphere radius -1", 1, 15, "found '-1'");
    expect_parse_error("sphere radius nan", 1, 15, "finite");
    expect_parse_error("sphere radius inf", 1, 15, "finite");
    expect_parse_error("sphere radius 1e-60", 1, 15, "from 1e-50 to 1e50");
    expect_parse_error("sphere radius 1e60", 1, 15, "from 1e-50 to 1e50");
    expect_parse_error("sphere radius", 1, 14, "found end of line");
}
END_TEST

START_TEST(test_sphere_statement_rejects_bad_centres_and_settings)
{
    expect_parse_error("sphere center 1 nan 3", 1, 17, "finite");
    expect_parse_error("sphere center 1 2", 1, 18, "found end of line");
    expect_parse_error("sphere center 1 2 1e60", 1, 19,
                       "between -1e50 and 1e50");
    expect_parse_error("sphere center 1 2 3 size 4", 1, 21,
                       "expected a sphere setting");
    expect_parse_error("\n\nsphere color 1 -1 0", 3, 16, "from 0 to 1e6");
}
END_TEST

START_TEST(test_scene_add_object_grows)
{
    scene s;
    scene_init(&s);
    for (int k = 0; k < 1000; k++)
        ck_assert(scene_add_object(&s, (object){.kind = SHAPE_SPHERE,
                                                .sphere = {{k, 0, 0}, 1}}));
    ck_assert_int_eq(s.object_count, 1000);
    ck_assert(s.objects[999].sphere.center.x == 999);
    scene_free(&s);
}
END_TEST

START_TEST(test_the_method_table_names_each_form)
{
    ck_assert_int_eq(SPHERE_ROOTS_METHOD_COUNT, N_FORMS);
    for (int f = 0; f < N_FORMS; f++) {
        const sphere_roots_method *m = &SPHERE_ROOTS_METHODS[f];
        char name[48];
        snprintf(name, sizeof name, "%s%s", m->name,
                 strcmp(m->precision, "float") == 0 ? " float" : "");
        ck_assert_msg(m->roots == forms[f].roots &&
                          strcmp(name, forms[f].name) == 0,
                      "entry %d is %s", f, name);
    }
}
END_TEST

Suite *ch02_spheres_suite(void)
{
    Suite *s = suite_create("ch02 spheres");
    TCase *roots = tcase_create("formulas");
    tcase_add_checked_fixture(roots, reseed, NULL);
    tcase_add_loop_test(roots, test_two_hits_at_4_and_6, 0,
                        FORMS_OF_EXERCISES);
    tcase_add_loop_test(roots, test_tangent_ray_gives_a_double_root, 0,
                        FORMS_OF_EXERCISES);
    tcase_add_loop_test(roots, test_ray_beside_the_sphere_misses, 0,
                        FORMS_OF_EXERCISES);
    tcase_add_test(roots, test_sphere_behind_the_origin_is_not_seen);
    tcase_add_test(roots, test_the_nearer_root_is_the_hit);
    tcase_add_test(roots, test_origin_inside_sees_the_far_side);
    tcase_add_loop_test(roots, test_roots_are_ordered, 0,
                        FORMS_OF_EXERCISES);
    tcase_add_test(roots, test_the_method_table_names_each_form);
    tcase_add_test(roots, test_normals_are_unit_and_outward);
    tcase_add_test(roots, test_nearest_of_several_spheres_wins);
    suite_add_tcase(s, roots);

    TCase *edges = tcase_create("edge cases");
    tcase_add_checked_fixture(edges, reseed, NULL);
    tcase_add_loop_test(edges, test_negative_d_squared_from_rounding_is_a_hit,
                        0, FORMS_OF_EXERCISES);
    tcase_add_loop_test(edges,
                        test_naive_forms_fail_in_float_where_robust_holds, 0,
                        FORMS_OF_EXERCISES);
    tcase_add_loop_test(edges,
                        test_double_forms_are_exact_near_and_robust_far, 0,
                        FORMS_OF_EXERCISES);
    suite_add_tcase(s, edges);

    TCase *bad = tcase_create("bad input");
    tcase_add_checked_fixture(bad, reseed, NULL);
    tcase_add_test(bad, test_sphere_statement_defaults_and_settings);
    tcase_add_test(bad, test_sphere_statement_rejects_bad_radii);
    tcase_add_test(bad, test_sphere_statement_rejects_bad_centres_and_settings);
    tcase_add_test(bad, test_scene_add_object_grows);
    suite_add_tcase(s, bad);
    return s;
}
