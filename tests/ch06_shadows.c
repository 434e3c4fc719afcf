/* ch06_shadows.c: shadow rays, ray offsets, the area light, reflection and
 * the end of the recursion (chapter 06).
 *
 * Expected values are closed forms (stated beside each), computed here in
 * long double, or counts of rays that the scene's geometry decides. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "render.h"
#include "sample.h"
#include "scene.h"
#include "offset.h"
#include "search.h"
#include "shade.h"
#include "test_util.h"

#define DEG (M_PI / 180.0)

/* A scene parsed from text; fails the test on a parse error. */
static void scene_of(scene *s, const char *text)
{
    scene_error err;
    ck_assert_msg(parse_text(s, text, &err), "%s:%d:%d: %s", err.file, err.line,
                  err.col, err.message);
}

/* What the ray from the eye at the origin towards target sees. */
static vec3 color_towards(const scene *s, vec3 target, render_stats *stats)
{
    ray r = {{0, 0, 0}, vec3_normalize(target)};
    return trace(s, r, 0, stats);
}

/* The hit of the ray from origin towards target; fails if it misses. */
static hit hit_towards(const scene *s, vec3 origin, vec3 target)
{
    render_stats stats = {0};
    hit h;
    ray r = {origin, vec3_normalize(vec3_sub(target, origin))};
    ck_assert(scene_intersect(s, r, 0, INFINITY, &h, &stats));
    return h;
}

/* Is the light of direction l (towards it), at distance d, blocked for h? */
static bool blocked(const scene *s, const hit *h, vec3 l, double d)
{
    render_stats stats = {0};
    return scene_occluded(s, ray_leaving(h, l), 0, d, &stats);
}

/* ------------------------------------------------------------ shadows */

/* A floor y = -1 of two triangles, a point light at (0, 3, 5), a unit
 * sphere at (0, 0.5, 5) between them: the floor under it is in shadow. */
static const char SHADOW_SCENE[] =
    "ambient 0.2 0.2 0.2\n"
    "material m ambient 0.5 diffuse 0.8 specular 0\n"
    "triangle a -20 -1 0  b 20 -1 0  c -20 -1 40 material m color 1 1 1\n"
    "triangle a 20 -1 0  b 20 -1 40  c -20 -1 40 material m color 1 1 1\n"
    "sphere center 0 0.5 5 radius 1 material m\n"
    "light point position 0 3 5 intensity 1 1 1\n";

START_TEST(test_point_behind_an_occluder_is_in_shadow)
{
    scene s;
    scene_of(&s, SHADOW_SCENE);
    hit under = hit_towards(&s, (vec3){0, 0, 0}, (vec3){0, -1, 5});
    hit beside = hit_towards(&s, (vec3){0, 0, 0}, (vec3){4, -1, 5});
    light_sample a = light_toward(&s.lights[0], under.point);
    light_sample b = light_toward(&s.lights[0], beside.point);
    ck_assert(blocked(&s, &under, a.l, a.distance));
    ck_assert(!blocked(&s, &beside, b.l, b.distance));
    scene_free(&s);
}
END_TEST

START_TEST(test_occluder_beyond_the_light_casts_no_shadow)
{
    /* The same floor point, with the sphere moved above the light: the
     * shadow ray ends at the light, before it. */
    scene s;
    scene_of(&s, "triangle a -20 -1 0  b 20 -1 0  c -20 -1 40\n"
                 "triangle a 20 -1 0  b 20 -1 40  c -20 -1 40\n"
                 "sphere center 0 6 5 radius 1\n"
                 "light point position 0 3 5\n");
    hit under = hit_towards(&s, (vec3){0, 0, 0}, (vec3){0, -1, 5});
    light_sample ls = light_toward(&s.lights[0], under.point);
    ck_assert(!blocked(&s, &under, ls.l, ls.distance));
    ck_assert(blocked(&s, &under, ls.l, INFINITY)); /* it is on the line */
    scene_free(&s);
}
END_TEST

START_TEST(test_directional_light_is_blocked_along_its_whole_direction)
{
    /* A sphere 1000 units up shadows the floor under it from the sun. */
    scene s;
    scene_of(&s, "triangle a -20 -1 0  b 20 -1 0  c -20 -1 40\n"
                 "triangle a 20 -1 0  b 20 -1 40  c -20 -1 40\n"
                 "sphere center 0 1000 5 radius 1\n"
                 "light directional direction 0 -1 0\n");
    hit under = hit_towards(&s, (vec3){0, 0, 0}, (vec3){0, -1, 5});
    hit beside = hit_towards(&s, (vec3){0, 0, 0}, (vec3){3, -1, 5});
    light_sample ls = light_toward(&s.lights[0], under.point);
    ck_assert(isinf(ls.distance));
    ck_assert(blocked(&s, &under, ls.l, ls.distance));
    ck_assert(!blocked(&s, &beside, ls.l, ls.distance));
    scene_free(&s);
}
END_TEST

START_TEST(test_shadow_keeps_ambient_and_emission)
{
    /* In shadow the point shows exactly I_e + rho_a C I_a: s_j multiplies
     * the light's own terms only. Colour 1, rho_a 0.5, I_a 0.2: 0.1, and
     * an emission of 0.05 added. */
    scene s;
    scene_of(&s, SHADOW_SCENE);
    s.materials[0].emission = (vec3){0.05, 0.05, 0.05};
    render_stats stats = {0};
    vec3 c = color_towards(&s, (vec3){0, -1, 5}, &stats);
    ck_assert_double_eq_tol(c.x, 0.05 + 0.5 * 0.2, 4 * DBL_EPSILON);
    ck_assert(c.y == c.x);
    ck_assert_int_eq(stats.shadow_rays_blocked, 1);
    scene_free(&s);
}
END_TEST

START_TEST(test_no_shadow_ray_where_the_light_cannot_contribute)
{
    /* A point below the horizon of every light, a spot pointing away, a
     * light of intensity 0: light tests, but no shadow ray. */
    scene s;
    scene_of(&s, "triangle a -20 -1 0  b 20 -1 0  c -20 -1 40\n"
                 "triangle a 20 -1 0  b 20 -1 40  c -20 -1 40\n"
                 "sphere center 0 5 5 radius 1\n"
                 "light point position 0 -5 5\n"
                 "light spot position 0 3 5 direction 0 1 0 angle 10\n"
                 "light point position 0 3 5 intensity 0 0 0\n");
    render_stats stats = {0};
    color_towards(&s, (vec3){0, -1, 5}, &stats);
    ck_assert_int_eq(stats.light_tests, 3);
    ck_assert_int_eq(stats.shadow_rays, 0);
    ck_assert_int_eq(stats.shadow_skipped_dark, 2); /* the spot, the dark */
    scene_free(&s);
}
END_TEST

START_TEST(test_no_shadow_ray_when_nothing_can_block)
{
    /* One sphere seen from outside, one triangle: they cannot shadow
     * themselves. Two objects, or a mesh, can. */
    const char *alone[] = {"sphere center 0 0 5 radius 1\n",
                           "triangle a -1 -1 5  b 1 -1 5  c 0 1 5\n"};
    for (int k = 0; k < 2; k++) {
        scene s;
        scene_of(&s, alone[k]);
        render_stats stats = {0};
        color_towards(&s, (vec3){0, 0, 1}, &stats);
        ck_assert_int_eq(stats.light_tests, 1);
        ck_assert_int_eq(stats.shadow_rays, 0);
        ck_assert_int_eq(stats.shadow_skipped_alone, 1);
        scene_free(&s);
    }
    scene s;
    scene_of(&s,
             "sphere center 0 0 5 radius 1\nsphere center 9 9 9 radius 1\n");
    render_stats stats = {0};
    color_towards(&s, (vec3){0, 0, 1}, &stats);
    ck_assert_int_eq(stats.shadow_rays, 1);
    scene_free(&s);
}
END_TEST

START_TEST(test_lone_sphere_shadows_its_own_inside)
{
    /* The eye inside a sphere, a light outside: the inner surface facing
     * the light is shadowed by the sphere itself, so a ray must be cast;
     * and this is where skipping the primitive would be wrong. */
    scene s;
    scene_of(&s,
             "sphere center 0 0 0 radius 10\nlight point position 0 0 -50\n");
    hit h = hit_towards(&s, (vec3){0, 0, 0}, (vec3){0, 0, 1});
    ck_assert(h.inside);
    ck_assert(scene_can_shadow(&s, &h));
    light_sample ls = light_toward(&s.lights[0], h.point);
    ck_assert(blocked(&s, &h, ls.l, ls.distance));
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ acne */

/* The floor and sphere of SHADOW_SCENE, every coordinate times scale. */
static void scaled_scene(scene *s, double scale)
{
    char text[1024];
    double k = scale;
    snprintf(text, sizeof text,
             "triangle a %.17g %.17g %.17g  b %.17g %.17g %.17g  c %.17g %.17g "
             "%.17g\n"
             "triangle a %.17g %.17g %.17g  b %.17g %.17g %.17g  c %.17g %.17g "
             "%.17g\n"
             "sphere center %.17g %.17g %.17g radius %.17g\n",
             k * -20, -k, k, k * 20, -k, k, k * -20, -k, k * 40, k * 20, -k, k,
             k * 20, -k, k * 40, k * -20, -k, k * 40, 0.0, k * 0.5, k * 6, k);
    scene_of(s, text);
}

/* The same scene built at scale 1 and placed by a transform that scales it
 * by scale: the hit points are computed in object space, then moved. */
static void placed_scene(scene *s, double scale)
{
    char text[1024];
    snprintf(
        text, sizeof text,
        "triangle a -20 -1 1  b 20 -1 1  c -20 -1 40 transform scale %.17g "
        "%.17g %.17g\n"
        "triangle a 20 -1 1  b 20 -1 40  c -20 -1 40 transform scale %.17g "
        "%.17g %.17g\n"
        "sphere center 0 0.5 6 radius 1 transform scale %.17g %.17g %.17g\n",
        scale, scale, scale, scale, scale, scale, scale, scale, scale);
    scene_of(s, text);
}

/* Of the shadow rays from lit points of the floor and the sphere's top,
 * towards a light straight above, how many report a hit, starting as the
 * program does (fixed_epsilon 0) or at the hit point with t > epsilon,
 * the point rounded to float as a float renderer has it. */
static int self_hits_in(void (*build)(scene *, double), double scale,
                        double fixed_epsilon)
{
    scene s;
    build(&s, scale);
    int count = 0;
    vec3 up = {0, 1, 0};
    render_stats stats = {0};
    for (int k = 0; k < 400; k++) {
        double x = -9 + 18 * (k % 20) / 20.0, z = 12 + (k / 20);
        vec3 target =
            k % 2
                ? (vec3){x * scale, -scale, z * scale}
                : vec3_scale((vec3){0.02 * x, 1.3, 6 + 0.02 * (z - 21)}, scale);
        hit h = hit_towards(&s, (vec3){0, 0, 0}, target);
        if (vec3_dot(h.normal, up) <= 0)
            continue; /* the sphere's underside, where the floor was aimed at */
        ray r = ray_leaving(&h, up);
        double t_min = 0;
        if (fixed_epsilon > 0) {
            vec3 p = h.point;
            r.origin = (vec3){(float)p.x, (float)p.y, (float)p.z};
            t_min = fixed_epsilon;
        }
        count += scene_occluded(&s, r, t_min, INFINITY, &stats);
    }
    scene_free(&s);
    return count;
}

static int self_hits(double scale, double fixed_epsilon)
{
    return self_hits_in(scaled_scene, scale, fixed_epsilon);
}

START_TEST(test_placed_objects_have_no_acne)
{
    /* The bound travels with the point through the object's matrix: without
     * it, the object-space bound of a scaled-up floor is far too small. */
    const double scales[] = {1, 1e2, 1e4, 1e6};
    for (int k = 0; k < 4; k++)
        ck_assert_msg(self_hits_in(placed_scene, scales[k], 0) == 0,
                      "self-hits at scale %g", scales[k]);
    /* The control: the same rays from the float-rounded point with a fixed
     * t > 1e-4 do hit the placed floor, so the count above can see them. */
    ck_assert_int_gt(self_hits_in(placed_scene, 1e4, 1e-4), 20);
}
END_TEST

START_TEST(test_fixed_epsilon_shows_acne_at_1e4)
{
    /* At 1e4 a float coordinate is rounded by up to 2^-11 ~ 5e-4: far more
     * than t > 1e-4 can hide. (At scale 1 the same epsilon hides it.) */
    ck_assert_int_eq(self_hits(1, 1e-4), 0);
    ck_assert_int_gt(self_hits(1e4, 1e-4), 20);
}
END_TEST

START_TEST(test_program_offset_has_no_acne_at_1e4)
{
    const double scales[] = {1, 1e2, 1e4, 1e6, 1e12};
    for (int k = 0; k < 5; k++)
        ck_assert_msg(self_hits(scales[k], 0) == 0, "self-hits at scale %g",
                      scales[k]);
}
END_TEST

START_TEST(test_contact_shadow_is_kept)
{
    /* A card leaning on the floor: floor points x = 1e-9 ... 1e-5 from
     * where it touches are x/3 below it, in its shadow under a light
     * straight above. The program keeps every one; t > 1e-4 loses all. */
    scene s;
    scene_of(&s, "triangle a -20 -1 0  b 20 -1 0  c -20 -1 40\n"
                 "triangle a 20 -1 0  b 20 -1 40  c -20 -1 40\n"
                 "triangle a -1 -1 5  b 1 -1 5  c 1 -0.5 6.5\n"
                 "triangle a -1 -1 5  b 1 -0.5 6.5  c -1 -0.5 6.5\n");
    render_stats stats = {0};
    for (int k = 0; k <= 8; k++) {
        double x = pow(10, -9 + 0.5 * k);
        hit h = hit_towards(&s, (vec3){0, -0.8, 6.8}, (vec3){0.1, -1, 5 + x});
        ck_assert_double_eq_tol(h.point.y, -1, 1e-15);
        vec3 up = {0, 1, 0};
        ck_assert_msg(
            scene_occluded(&s, ray_leaving(&h, up), 0, INFINITY, &stats),
            "contact shadow lost at x = %g", x);
        ck_assert(
            !scene_occluded(&s, (ray){h.point, up}, 1e-4, INFINITY, &stats));
    }
    scene_free(&s);
}
END_TEST

START_TEST(test_offset_origin_is_on_the_side_the_ray_leaves_by)
{
    /* With an error bound e and normal (0, 1, 0), the origin moves by at
     * least e.y, up for a ray going up and down for one going down, and
     * never sideways. */
    vec3 p = {1e4, 3, -2}, e = {1e-9, 2e-12, 1e-9}, n = {0, 1, 0};
    vec3 up = offset_origin(p, e, n, vec3_normalize((vec3){1, 1, 0}));
    vec3 down = offset_origin(p, e, n, vec3_normalize((vec3){1, -1, 0}));
    ck_assert(up.y - p.y >= e.y && p.y - down.y >= e.y);
    ck_assert(up.y - p.y < 4 * e.y); /* just past the bound, not far */
    ck_assert(up.x == p.x && up.z == p.z && down.x == p.x && down.z == p.z);
}
END_TEST

/* ------------------------------------------------------------ area light */

/* The cells of the counts the tests use, as the task describes them and
 * worked out by hand: floor(sqrt(n)) rows, the first n % rows of them one
 * cell wider; here, how many cells each row holds, top row first (0
 * ends the list). Each row is as tall as its share of the cells. */
static const struct {
    int n, row_cells[9];
} CELLS[] = {{1, {1, 0}},          {2, {2, 0}},
             {3, {3, 0}},          {8, {4, 4, 0}},
             {37, {7, 6, 6, 6, 6, 6, 0}},
             {64, {8, 8, 8, 8, 8, 8, 8, 8, 0}}};

/* Cell k of n from the table: [x0, x0 + w) x [y0, y0 + h). */
static void described_cell(int k, int n, double *x0, double *y0, double *w,
                           double *h)
{
    for (size_t c = 0; c < sizeof CELLS / sizeof CELLS[0]; c++) {
        if (CELLS[c].n != n)
            continue;
        int before = 0;
        for (const int *cols = CELLS[c].row_cells; *cols > 0; cols++) {
            if (k < before + *cols) {
                *w = 1.0 / *cols, *h = (double)*cols / n;
                *x0 = (k - before) * *w, *y0 = (double)before / n;
                return;
            }
            before += *cols;
        }
    }
    ck_abort_msg("no cell %d of %d in the table", k, n);
}

/* Sample k of n lies in cell k: one in each cell, none left empty. */
static void expect_one_sample_a_cell(int pattern, int n, sample_stream *g)
{
    const double slack = 4e-16; /* a few roundings of numbers below 1 */
    for (int k = 0; k < n; k++) {
        double u, v, x0, y0, w, h;
        sample_square(pattern, k, n, g, &u, &v);
        described_cell(k, n, &x0, &y0, &w, &h);
        ck_assert_msg(u >= x0 - slack && u < x0 + w + slack &&
                          v >= y0 - slack && v < y0 + h + slack,
                      "%s, n = %d: sample %d at (%g, %g) is outside its "
                      "cell [%g, %g) x [%g, %g): each of the n cells must "
                      "hold one sample",
                      pattern == SAMPLE_GRID ? "grid" : "stratified", n, k, u,
                      v, x0, x0 + w, y0, y0 + h);
    }
}

/* Every one of the six coordinates seeds the stream: two pairs of points
 * that differ in one coordinate only, by one bit, start different
 * streams (the same pixel's points seed it; its neighbour's differ in
 * any coordinate). */
START_TEST(test_every_coordinate_seeds_the_stream)
{
    double xs[6] = {1, 2, 3, 4, 5, 6};
    sample_stream g = sample_stream_at((vec3){1, 2, 3}, (vec3){4, 5, 6});
    double first = sample_next(&g);
    for (int k = 0; k < 6; k++) {
        double ys[6];
        memcpy(ys, xs, sizeof ys);
        ys[k] = nextafter(ys[k], INFINITY);
        sample_stream h = sample_stream_at((vec3){ys[0], ys[1], ys[2]},
                                           (vec3){ys[3], ys[4], ys[5]});
        ck_assert_msg(sample_next(&h) != first,
                      "coordinate %d of the six changed, and the stream did "
                      "not: every coordinate's bits must seed it", k + 1);
    }
}
END_TEST

/* The stream of one pair of points repeats, another pair's differs, and
 * its numbers lie in [0, 1) with the mean of a uniform variable, 1/2, to
 * within 5 standard errors, 1 / sqrt(12 n). */
START_TEST(test_the_sample_stream_repeats_and_spreads)
{
    vec3 a = {1, 2, 3}, b = {4, 5, 6};
    sample_stream g = sample_stream_at(a, b), same = sample_stream_at(a, b),
                  other = sample_stream_at(b, a);
    const int n = 100000;
    double sum = 0;
    int differ = 0;
    for (int k = 0; k < n; k++) {
        double x = sample_next(&g);
        ck_assert_msg(x >= 0 && x < 1, "%.17g is not in [0, 1)", x);
        ck_assert_msg(x == sample_next(&same),
                      "number %d differs from the same points' stream", k);
        differ += x != sample_next(&other);
        sum += x;
    }
    ck_assert_msg(differ > n / 2, "the points swapped give the same stream");
    ck_assert_msg(fabs(sum / n - 0.5) <= 5 / sqrt(12.0 * n), "mean %g, not 1/2",
                  sum / n);
}
END_TEST

/* Stratified and grid: exactly one sample in each of n cells of area 1/n;
 * uniform: anywhere in the square. */
START_TEST(test_square_samples_fall_one_a_cell)
{
    sample_stream g = sample_stream_at((vec3){0, 0, 0}, (vec3){0, 0, 0});
    const int counts[] = {1, 2, 3, 8, 37, 64};
    for (int c = 0; c < 6; c++)
        for (int pattern = SAMPLE_STRATIFIED; pattern <= SAMPLE_GRID; pattern++)
            expect_one_sample_a_cell(pattern, counts[c], &g);
    for (int k = 0; k < 1000; k++) {
        double u, v;
        sample_square(SAMPLE_UNIFORM, k, 1000, &g, &u, &v);
        ck_assert_msg(u >= 0 && u < 1 && v >= 0 && v < 1,
                      "uniform sample at (%g, %g)", u, v);
    }
}
END_TEST

/* A point of the disc lies in its plane, within its radius, at the radius
 * that leaves the share u of the disc's area inside it (R sqrt(u)), and
 * at the angle 2 pi v, on the far side for v + 1/2. */
START_TEST(test_disc_points_cover_the_disc_area_for_area)
{
    const vec3 axes[] = {{0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 2, 3}};
    const vec3 c = {1, 2, 3};
    const double R = 2, tolerance = 16 * DBL_EPSILON * R;
    for (int k = 0; k < 4; k++) {
        vec3 axis = vec3_normalize(axes[k]);
        for (int j = 0; j < 8; j++) {
            double u = j / 8.0, v = j / 16.0;
            vec3 d = vec3_sub(disc_point(c, axis, R, u, v), c),
                 far = vec3_sub(disc_point(c, axis, R, u, v + 0.5), c);
            ck_assert_msg(fabs(vec3_dot(d, axis)) <= tolerance,
                          "axis %d: %g out of the disc's plane", k,
                          vec3_dot(d, axis));
            ck_assert_msg(fabs(vec3_length(d) - R * sqrt(u)) <= tolerance,
                          "axis %d, u = %g: radius %g, not R sqrt(u) = %g", k,
                          u, vec3_length(d), R * sqrt(u));
            ck_assert_msg(vec3_length(vec3_add(d, far)) <= 2 * tolerance,
                          "axis %d: v and v + 1/2 not opposite", k);
        }
    }
}
END_TEST

START_TEST(test_area_light_samples_cover_the_disc_evenly)
{
    /* Every pattern: every sample on the disc, carrying 1/n of the light.
     * The mean of many uniform samples' squared radius is R^2 / 2 (area
     * for area). */
    const int n = 37;
    light L = {.kind = LIGHT_AREA,
               .position = {1, 2, 3},
               .direction = {0, -1, 0},
               .radius = 2,
               .samples = n,
               .intensity = {1, 1, 1},
               .attenuation = {1, 0, 0}};
    for (int pattern = SAMPLE_UNIFORM; pattern <= SAMPLE_GRID; pattern++) {
        L.pattern = pattern;
        sample_stream g = sample_stream_at((vec3){0, 0, 0}, L.position);
        for (int k = 0; k < n; k++) {
            light p = area_light_point(&L, k, &g);
            vec3 d = vec3_sub(p.position, L.position);
            ck_assert(fabs(d.y) < 1e-15 && vec3_length(d) <= 2 * (1 + 1e-15));
            ck_assert_double_eq_tol(p.intensity.x, 1.0 / n, 1e-17);
        }
    }
    sample_stream g = sample_stream_at((vec3){0, 0, 0}, (vec3){0, 0, 0});
    double sum = 0;
    L.pattern = SAMPLE_UNIFORM;
    for (int k = 0; k < 100000; k++) {
        light p = area_light_point(&L, 0, &g);
        vec3 d = vec3_sub(p.position, L.position);
        sum += vec3_dot(d, d);
    }
    /* mean of R^2 u, u uniform: R^2/2 = 2, with a standard error of
     * R^2 / sqrt(12 * 1e5) ~ 0.004; 5 standard errors */
    ck_assert_double_eq_tol(sum / 100000, 2, 0.02);
}
END_TEST

START_TEST(test_area_light_gives_a_penumbra_and_is_reproducible)
{
    /* Under the sphere the floor is dark (umbra), far away lit, and in
     * between partly lit; a second render is the same to the bit. */
    scene s;
    scene_of(&s, "triangle a -20 -1 0  b 20 -1 0  c -20 -1 40\n"
                 "triangle a 20 -1 0  b 20 -1 40  c -20 -1 40\n"
                 "sphere center 0 0.5 5 radius 1\n"
                 "light area position 0 3 5 radius 0.5 samples 64\n");
    render_stats st = {0};
    double umbra = color_towards(&s, (vec3){0, -1, 5}, &st).x;
    double lit = color_towards(&s, (vec3){6, -1, 5}, &st).x;
    double edge = 0;
    for (double x = 0; x < 6; x += 0.01) {
        double c = color_towards(&s, (vec3){x, -1, 5}, &st).x;
        if (c > umbra + 0.01 && c < 0.9 * lit)
            edge++;
    }
    ck_assert(umbra < 0.25 * lit);
    ck_assert(edge > 10); /* a soft edge, not a step */
    vec3 a = color_towards(&s, (vec3){1.7, -1, 5}, &st);
    vec3 b = color_towards(&s, (vec3){1.7, -1, 5}, &st);
    ck_assert(memcmp(&a, &b, sizeof a) == 0);
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ reflection */

START_TEST(test_reflection_angle_equals_incidence_in_the_plane)
{
    /* For many i and n: <n, r> = -<n, i>, |r| = 1, and r lies in the plane
     * of i and n: <r, i x n> = 0. Checked in long double against the
     * computed r; tolerance 8 ulps of 1, a few roundings. */
    for (int k = 0; k < 1000; k++) {
        double a = 0.0061 * k, b = 0.0037 * k + 0.3;
        vec3 n = {sin(a) * cos(b), cos(a), sin(a) * sin(b)};
        vec3 i = vec3_normalize(
            (vec3){cos(3.1 * k), -0.4 - sin(0.7 * k), sin(1.3 * k)});
        vec3 r = vec3_reflect(i, n);
        long double ni = (long double)n.x * i.x + (long double)n.y * i.y +
                         (long double)n.z * i.z;
        long double nr = (long double)n.x * r.x + (long double)n.y * r.y +
                         (long double)n.z * r.z;
        vec3 c = vec3_cross(i, n);
        long double in_plane = (long double)r.x * c.x + (long double)r.y * c.y +
                               (long double)r.z * c.z;
        ck_assert(fabsl(nr + ni) < 8 * DBL_EPSILON);
        ck_assert(fabsl(in_plane) < 8 * DBL_EPSILON);
        ck_assert(fabs(vec3_length(r) - 1) < 8 * DBL_EPSILON);
        vec3 r2 = vec3_reflect(i, vec3_scale(n, -1)); /* either normal */
        ck_assert(fabs(r2.x - r.x) + fabs(r2.y - r.y) + fabs(r2.z - r.z) <
                  8 * DBL_EPSILON);
    }
    /* 30 degrees in, 30 degrees out: i = (sin 30, -cos 30, 0), n = y. */
    vec3 r = vec3_reflect((vec3){0.5, -sqrt(0.75), 0}, (vec3){0, 1, 0});
    ck_assert_double_eq_tol(r.x, 0.5, DBL_EPSILON);
    ck_assert_double_eq_tol(r.y, sqrt(0.75), DBL_EPSILON);
}
END_TEST

START_TEST(test_perfect_mirror_shows_the_lit_sphere)
{
    /* A mirror of reflectivity 1 at z = 10 facing the eye, a red diffuse
     * sphere behind the eye lit from the eye's side: looking at the mirror
     * straight ahead, the eye sees what a ray from the mirror sees, the
     * sphere's colour exactly. */
    const char *text =
        "material mirror ambient 0 diffuse 0 specular 0 reflect 1\n"
        "material red ambient 0.2 diffuse 0.8 specular 0\n"
        "triangle a -50 -50 10  b 50 -50 10  c 0 50 10 material mirror\n"
        "sphere center 0 0 -5 radius 1 color 1 0 0 material red\n"
        "light point position 0 0 3 intensity 1 1 1\n";
    scene s;
    scene_of(&s, text);
    render_stats st = {0};
    vec3 seen = color_towards(&s, (vec3){0, 0, 1}, &st);
    /* the sphere's point (0, 0, -4) from (0, 0, 10): ambient 0.2 + diffuse
     * 0.8 <n, l> with n = l = +z, the light 7 away, no attenuation */
    vec3 direct = trace(&s, (ray){{0, 0, 9}, {0, 0, -1}}, 0, &st);
    ck_assert_double_eq_tol(direct.x, 1.0, 4 * DBL_EPSILON);
    ck_assert_double_eq_tol(seen.x, direct.x, 4 * DBL_EPSILON);
    ck_assert(seen.y == 0 && seen.z == 0);
    ck_assert_int_eq(st.reflection_rays, 1);
    scene_free(&s);
}
END_TEST

START_TEST(test_recursion_ends_between_parallel_mirrors)
{
    /* Two perfect mirrors facing each other, the eye between them looking
     * straight at one: without a cutoff only the depth limit ends it, after
     * exactly depth reflection rays. With reflectivity 0.5 and cutoff 0.01
     * the weight 0.5^k falls below it at k = 7: 6 rays. */
    const char *text =
        "material mirror ambient 0.1 diffuse 0.5 specular 0 reflect %s\n"
        "triangle a -50 -50 10  b 50 -50 10  c 0 50 10 material mirror\n"
        "triangle a -50 -50 -10  b 0 50 -10  c 50 -50 -10 material mirror\n"
        "recursion depth %d cutoff %s\n";
    char buf[512];
    snprintf(buf, sizeof buf, text, "1", 37, "0");
    scene s;
    scene_of(&s, buf);
    render_stats st = {0};
    color_towards(&s, (vec3){0, 0, 1}, &st);
    ck_assert_int_eq(st.reflection_rays, 37);
    ck_assert_int_eq(st.reflection_skipped_depth, 1);
    scene_free(&s);
    snprintf(buf, sizeof buf, text, "0.5", 100, "0.01");
    scene_of(&s, buf);
    st = (render_stats){0};
    color_towards(&s, (vec3){0, 0, 1}, &st);
    ck_assert_int_eq(st.reflection_rays, 6);
    ck_assert_int_eq(st.reflection_skipped_weight, 1);
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ bad input */

START_TEST(test_bad_reflectivity_samples_radius_and_recursion)
{
    expect_parse_error("material m reflect 1.5\n", 1, 20,
                       "reflectivity from 0 to 1");
    expect_parse_error("material m reflect -0.1\n", 1, 20,
                       "reflectivity from 0 to 1");
    expect_parse_error("material m reflect nan\n", 1, 20, "reflectivity");
    expect_parse_error("light area samples 0\n", 1, 20, "from 1 to 1024");
    expect_parse_error("light area samples -3\n", 1, 20, "from 1 to 1024");
    expect_parse_error("light area samples 2.5\n", 1, 20, "whole number");
    expect_parse_error("light area samples 1025\n", 1, 20, "from 1 to 1024");
    /* a whole number too large for its type is out of range all the same */
    expect_parse_error("light area samples 18446744073709551632\n", 1, 20,
                       "from 1 to 1024");
    expect_parse_error("light area radius 0\n", 1, 19, "greater than 0");
    expect_parse_error("light area radius -1\n", 1, 19, "greater than 0");
    expect_parse_error("light area radius inf\n", 1, 19, "finite");
    expect_parse_error("light area radius 1e51\n", 1, 19, "at most 1e50");
    expect_parse_error("light area pattern halton\n", 1, 20,
                       "'uniform', 'stratified'");
    expect_parse_error("light area angle 30\n", 1, 12,
                       "position, direction, radius");
    expect_parse_error("light disc\n", 1, 7, "area");
    expect_parse_error("recursion depth -1\n", 1, 17, "from 0 to 100");
    expect_parse_error("recursion depth 101\n", 1, 17, "from 0 to 100");
    expect_parse_error("recursion depth 3.5\n", 1, 17, "whole number");
    expect_parse_error("recursion depth 1e300\n", 1, 17, "from 0 to 100");
    expect_parse_error("recursion cutoff 2\n", 1, 18, "from 0 to 1");
    expect_parse_error("recursion cutoff -0.5\n", 1, 18, "from 0 to 1");
    expect_parse_error("recursion\n", 1, 10, "'depth' or 'cutoff'");
    expect_parse_error("recursion bounces 3\n", 1, 11, "'depth' or 'cutoff'");
}
END_TEST

START_TEST(test_cli_rejects_bad_area_light_and_writes_nothing)
{
    make_tmpdir();
    const char *path =
        write_file("bad.scene", "sphere\nlight area radius 0 samples 4\n");
    char scene_path[256], errors[1024];
    snprintf(scene_path, sizeof scene_path, "%s", path);
    const char *out = tmp_path("out.png");
    char out_path[256];
    snprintf(out_path, sizeof out_path, "%s", out);
    const char *args[] = {scene_path, "-o", out_path, NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 1);
    ck_assert_msg(strstr(errors, "bad.scene:2:19: error:") != NULL, "%s",
                  errors);
    ck_assert(!file_exists(out_path));
    remove_tmpdir();
}
END_TEST

Suite *ch06_shadows_suite(void)
{
    Suite *s = suite_create("ch06 shadows");
    TCase *shadows = tcase_create("shadows");
    tcase_add_test(shadows, test_point_behind_an_occluder_is_in_shadow);
    tcase_add_test(shadows, test_occluder_beyond_the_light_casts_no_shadow);
    tcase_add_test(shadows,
                   test_directional_light_is_blocked_along_its_whole_direction);
    tcase_add_test(shadows, test_shadow_keeps_ambient_and_emission);
    tcase_add_test(shadows,
                   test_no_shadow_ray_where_the_light_cannot_contribute);
    tcase_add_test(shadows, test_no_shadow_ray_when_nothing_can_block);
    tcase_add_test(shadows, test_lone_sphere_shadows_its_own_inside);
    suite_add_tcase(s, shadows);
    TCase *acne = tcase_create("edge cases");
    tcase_add_test(acne, test_fixed_epsilon_shows_acne_at_1e4);
    tcase_add_test(acne, test_program_offset_has_no_acne_at_1e4);
    tcase_add_test(acne, test_placed_objects_have_no_acne);
    tcase_add_test(acne, test_contact_shadow_is_kept);
    tcase_add_test(acne, test_offset_origin_is_on_the_side_the_ray_leaves_by);
    suite_add_tcase(s, acne);
    TCase *formulas = tcase_create("formulas");
    tcase_add_test(formulas, test_the_sample_stream_repeats_and_spreads);
    tcase_add_test(formulas, test_square_samples_fall_one_a_cell);
    tcase_add_test(formulas, test_every_coordinate_seeds_the_stream);
    tcase_add_test(formulas, test_disc_points_cover_the_disc_area_for_area);
    tcase_add_test(formulas, test_area_light_samples_cover_the_disc_evenly);
    tcase_add_test(formulas,
                   test_area_light_gives_a_penumbra_and_is_reproducible);
    tcase_add_test(formulas,
                   test_reflection_angle_equals_incidence_in_the_plane);
    tcase_add_test(formulas, test_perfect_mirror_shows_the_lit_sphere);
    tcase_add_test(formulas, test_recursion_ends_between_parallel_mirrors);
    suite_add_tcase(s, formulas);
    TCase *bad = tcase_create("bad input");
    tcase_add_checked_fixture(bad, NULL, NULL);
    tcase_add_test(bad, test_bad_reflectivity_samples_radius_and_recursion);
    tcase_add_test(bad, test_cli_rejects_bad_area_light_and_writes_nothing);
    suite_add_tcase(s, bad);
    return s;
}
