/* ch06_robustness.c: shaded points that would ask for more shadow rays
 * than a render can afford (chapter 06).
 *
 * Every light and every sample count below is within its own limit; the
 * budget of shadow rays for one shaded point, over all lights (4,096, as
 * many as a scene may have lights), bounds them together, and the budget
 * of rays of one primary ray's tree counts them too. */
#include <check.h>
#include <math.h>
#include <string.h>

#include "render.h"
#include "scene.h"
#include "trace.h"
#include "test_util.h"

#define BUDGET 4096 /* shadow rays a shaded point, as chapter 6 states */

/* A scene of n area lights of the given samples each, above a sphere that
 * fills the view; the text is malloc'ed. */
static char *many_lights(int n, int samples)
{
    size_t size = 64 + (size_t)n * 96;
    char *text = malloc(size);
    ck_assert_ptr_nonnull(text);
    int at = snprintf(text, size, "sphere center 0 0 1e4 radius 9990\n");
    for (int k = 0; k < n; k++)
        at += snprintf(text + at, size - (size_t)at,
                       "light area position %d 5 0 radius 0.5 samples %d\n",
                       k % 50, samples);
    return text;
}

/* The samples of the scene's area lights, added up. */
static long long samples_of(const scene *s)
{
    long long sum = 0;
    for (int k = 0; k < s->light_count; k++)
        sum += s->lights[k].samples;
    return sum;
}

START_TEST(test_the_lights_of_a_point_fit_the_shadow_budget)
{
    /* 5 x 1024 = 5,120 asked: each light's 1,023 samples beyond its first
     * are cut to 1,023 x (4,096 - 5) / (5,120 - 5), rounded down: 818 */
    scene s;
    scene_error err;
    char *text = many_lights(5, 1024);
    ck_assert_msg(parse_text(&s, text, &err), "%s", err.message);
    for (int k = 0; k < 5; k++)
        ck_assert_int_eq(s.lights[k].samples, 1 + 818);
    render_stats st = {0};
    trace(&s, (ray){{0, 0, 0}, {0, 0, 1}}, 0, &st);
    ck_assert_int_le(st.light_tests, BUDGET);
    ck_assert_int_eq(st.light_samples_cut, 5120 - 5 * 819);
    scene_free(&s);
    free(text);
    /* 4,095 lights of 1,024 samples (hours for a small picture): one each */
    text = many_lights(4095, 1024);
    ck_assert_msg(parse_text(&s, text, &err), "%s", err.message);
    ck_assert_int_eq(samples_of(&s), 4095);
    scene_free(&s);
    free(text);
    /* within the budget nothing changes */
    text = many_lights(4, 1024);
    ck_assert_msg(parse_text(&s, text, &err), "%s", err.message);
    ck_assert_int_eq(samples_of(&s), 4096);
    scene_free(&s);
    free(text);
}
END_TEST

START_TEST(test_stats_count_the_samples_the_budget_took)
{
    char scene_path[192], errors[4096];
    char *text = many_lights(5, 1024);
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("lights.scene", text));
    free(text);
    const char *args[] = {scene_path, "--size",          "2x2", "--stats",
                          "-o",       tmp_path("o.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    /* four pixels, each one shaded point: 4 x (5,120 - 4,095) */
    ck_assert_msg(
        strstr(errors, "light samples cut  4100 at the shadow-ray budget"),
        "%s", errors);
}
END_TEST

START_TEST(test_a_tree_counts_its_shadow_rays_in_the_ray_budget)
{
    /* The eye inside a mirror ball: without a cutoff each ray reflects
     * until the depth limit, 100, and each of the 101 hits casts 1,024
     * shadow rays: 103,524 rays, more than the tree's budget of 65,536
     * (chapter 6). Counted, the primary ray's hit takes its 1,024 first,
     * and each reflection costs 1 + 1,024: 62 of them fit, and the tree
     * is cut. */
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s,
                             "recursion depth 100 cutoff 0\n"
                             "material m reflect 1\n"
                             "sphere center 0 0 0 radius 10 material m\n"
                             "light area position 0 5 0 radius 0.5 "
                             "samples 1024\n",
                             &err),
                  "%s", err.message);
    render_stats st = {0};
    vec3 seen = trace(
        &s, (ray){{0, 0, 0}, vec3_normalize((vec3){0.1, 0.05, 1})}, 0, &st);
    long long rays = st.reflection_rays + st.shadow_rays +
                     st.shadow_skipped_alone + st.shadow_skipped_dark;
    ck_assert_int_eq(st.reflection_rays, (65536 - 1024) / (1 + 1024));
    ck_assert_msg(rays <= 65536, "%lld rays", rays);
    ck_assert_int_eq(st.ray_trees_cut, 1);
    ck_assert(isfinite(seen.x) && isfinite(seen.y) && isfinite(seen.z));
    scene_free(&s);
}
END_TEST

Suite *ch06_robustness_suite(void)
{
    Suite *s = suite_create("ch06 robustness");
    TCase *lights = tcase_create("edge cases");
    tcase_add_checked_fixture(lights, make_tmpdir, remove_tmpdir);
    tcase_add_test(lights, test_the_lights_of_a_point_fit_the_shadow_budget);
    tcase_add_test(lights, test_stats_count_the_samples_the_budget_took);
    tcase_add_test(lights,
                   test_a_tree_counts_its_shadow_rays_in_the_ray_budget);
    suite_add_tcase(s, lights);
    return s;
}
