/* ch07_robustness.c: trees of rays that must end, however the scene sets
 * its materials and limits (chapter 07).
 *
 * A glass surface splits a path in two, so the tree of one primary ray can
 * grow like 2^depth. These scenes, valid in every way, once never finished:
 * the tests trace one ray into each and read the counts. A scene that hangs
 * again fails by the test case's timeout. */
#include <check.h>
#include <math.h>
#include <string.h>

#include "render.h"
#include "scene.h"
#include "trace.h"
#include "test_util.h"

/* The secondary-ray budget of one primary ray, as chapter 6 states it. */
#define BUDGET 65536

/* Three parallel squares, 100 wide, at z = 2, 3 and 4, of material m. */
#define THREE_SHEETS                                                   \
    "triangle a -50 -50 2 b 50 -50 2 c 50 50 2 material m\n"           \
    "triangle a -50 -50 2 b 50 50 2 c -50 50 2 material m\n"           \
    "triangle a -50 -50 3 b 50 -50 3 c 50 50 3 material m\n"           \
    "triangle a -50 -50 3 b 50 50 3 c -50 50 3 material m\n"           \
    "triangle a -50 -50 4 b 50 -50 4 c 50 50 4 material m\n"           \
    "triangle a -50 -50 4 b 50 50 4 c -50 50 4 material m\n"

static void scene_of(scene *s, const char *text)
{
    scene_error err;
    ck_assert_msg(parse_text(s, text, &err), "%s:%d:%d: %s", err.file, err.line,
                  err.col, err.message);
}

/* The counts and the colour of the ray from the eye along d. */
static render_stats trace_once(const char *text, vec3 d, vec3 *seen)
{
    scene s;
    scene_of(&s, text);
    render_stats st = {0};
    *seen = trace(&s, (ray){{0, 0, 0}, vec3_normalize(d)}, 0, &st);
    scene_free(&s);
    return st;
}

static long long secondary_rays(render_stats st)
{
    return st.reflection_rays + st.refraction_rays;
}

START_TEST(test_a_clear_mirror_traces_no_mirror_ray)
{
    /* reflect 1 under transparency 1: the mirror's share of the pixel is
     * 1 x (1 - 1) = 0, so the scene is the clear glass alone, ray for ray
     * and bit for bit. Weighed by reflect alone the tree grew 1.55 times a
     * level and this did not end. */
    const vec3 dirs[] = {{0, 0, 1}, {0.3, -0.2, 1}};
    for (int k = 0; k < 2; k++) {
        vec3 both, glass;
        render_stats a = trace_once(
            "material m reflect 1 transparency 1 ior 1.5\n" THREE_SHEETS,
            dirs[k], &both);
        render_stats b =
            trace_once("material m transparency 1 ior 1.5\n" THREE_SHEETS,
                       dirs[k], &glass);
        ck_assert_int_eq(a.reflection_rays, b.reflection_rays);
        ck_assert_int_eq(a.refraction_rays, b.refraction_rays);
        ck_assert_int_eq(a.ray_trees_cut, 0);
        ck_assert(memcmp(&both, &glass, sizeof both) == 0);
    }
}
END_TEST

START_TEST(test_a_half_clear_mirror_weighs_its_share)
{
    /* reflect 0.5 under transparency 0.5: the mirror's ray weighs
     * 0.5 x (1 - 0.5) = 0.25, traced at the cutoff 0.25 and cut just
     * above it (0.26), where reflect alone (0.5) would still trace it. */
    vec3 seen;
    render_stats at = trace_once("material m reflect 0.5 transparency 0.5\n"
                                 "sphere center 0 0 5 radius 1 material m\n"
                                 "recursion cutoff 0.25 depth 1\n",
                                 (vec3){0, 0, 1}, &seen);
    render_stats above = trace_once("material m reflect 0.5 transparency 0.5\n"
                                    "sphere center 0 0 5 radius 1 material m\n"
                                    "recursion cutoff 0.26 depth 1\n",
                                    (vec3){0, 0, 1}, &seen);
    /* head-on F = 0.04: the glass's reflection (0.02) is cut in both */
    ck_assert_int_eq(at.reflection_rays, 1);
    ck_assert_int_eq(above.reflection_rays, 0);
    ck_assert_int_eq(above.reflection_skipped_weight, 2);
}
END_TEST

START_TEST(test_glass_without_a_cutoff_stops_at_the_budget)
{
    /* With cutoff 0 only the depth bounds a tree, and glass doubles it
     * at every hit: 2^100 rays. The budget stops each at BUDGET rays. */
    const char *scenes[] = {
        "recursion depth 100 cutoff 0\nmaterial m transparency 1 ior "
        "1.5\n" THREE_SHEETS,
        "recursion depth 100 cutoff 0\nmaterial m transparency 1 ior 1000\n"
        "sphere center 0 0 5 radius 2 material m\nsphere center 0 0 5 radius 1 "
        "material m\n",
    };
    for (int k = 0; k < 2; k++) {
        vec3 seen;
        render_stats st = trace_once(scenes[k], (vec3){0.1, 0.05, 1}, &seen);
        ck_assert_msg(secondary_rays(st) == BUDGET, "scene %d: %lld rays", k,
                      secondary_rays(st));
        ck_assert_int_eq(st.ray_trees_cut, 1);
        ck_assert(isfinite(seen.x) && isfinite(seen.y) && isfinite(seen.z));
    }
    /* A clear mirror ball: inside, each hit sends one ray out and one on,
     * a chain of at most 100 that the budget never cuts. */
    vec3 seen;
    render_stats st = trace_once("recursion depth 100 cutoff 0\n"
                                 "material m transparency 1 reflect 1\n"
                                 "sphere center 0 0 5 radius 2 material m\n",
                                 (vec3){0.1, 0.05, 1}, &seen);
    ck_assert_int_le(secondary_rays(st), 2 * 101);
    ck_assert_int_eq(st.ray_trees_cut, 0);
}
END_TEST

START_TEST(test_cli_renders_the_endless_scenes_and_counts_the_cuts)
{
    /* The first scene of the hangs, whole, through the binary: the cutoff
     * alone bounds it now, and --stats says that no tree was cut. */
    char scene_path[192], out[192], errors[4096];
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file(
                 "sheets.scene",
                 "material m reflect 1 transparency 1 ior 1.5\n" THREE_SHEETS));
    snprintf(out, sizeof out, "%s", tmp_path("out.png"));
    const char *args[] = {scene_path, "-o",      out, "--size",
                          "64x48",    "--stats", NULL};
    int status = run_bin_limited(args, errors, sizeof errors,
                                 (run_limits){.alarm_seconds = 30});
    ck_assert_msg(status == 0, "status %d: %s", status, errors);
    ck_assert_msg(strstr(errors, "ray trees cut      0 at the budget"), "%s",
                  errors);
    /* without a cutoff, 2 x 2 pixels: each tree is cut at the budget */
    snprintf(scene_path, sizeof scene_path, "%s",
             write_file("nocut.scene",
                        "recursion depth 100 cutoff 0\n"
                        "material m transparency 1 ior 1.5\n" THREE_SHEETS));
    const char *small[] = {scene_path, "-o",      out, "--size",
                           "2x2",      "--stats", NULL};
    status = run_bin_limited(small, errors, sizeof errors,
                             (run_limits){.alarm_seconds = 30});
    ck_assert_msg(status == 0, "status %d: %s", status, errors);
    ck_assert_msg(strstr(errors, "ray trees cut      4 at the budget"), "%s",
                  errors);
}
END_TEST

Suite *ch07_robustness_suite(void)
{
    Suite *s = suite_create("ch07 robustness");
    TCase *trees = tcase_create("edge cases");
    tcase_add_checked_fixture(trees, make_tmpdir, remove_tmpdir);
    tcase_set_timeout(trees, 60); /* a tree that does not end fails here */
    tcase_add_test(trees, test_a_clear_mirror_traces_no_mirror_ray);
    tcase_add_test(trees, test_a_half_clear_mirror_weighs_its_share);
    tcase_add_test(trees, test_glass_without_a_cutoff_stops_at_the_budget);
    tcase_add_test(trees,
                   test_cli_renders_the_endless_scenes_and_counts_the_cuts);
    suite_add_tcase(s, trees);
    return s;
}
