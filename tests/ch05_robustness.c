/* ch05_robustness.c: rotation axes of any finite length, and a camera
 * frame made by several statements (chapter 05). */
#include <check.h>
#include <string.h>

#include "render.h"
#include "scene.h"
#include "test_util.h"

static void scene_of(scene *s, const char *text)
{
    scene_error err;
    ck_assert_msg(parse_text(s, text, &err), "%s:%d:%d: %s", err.file, err.line,
                  err.col, err.message);
}

START_TEST(test_a_tiny_rotation_axis_is_the_same_rotation)
{
    /* The axis 2e-162 2e-162 0 is the axis 1 1 0: the same transform to
     * the bit (a rotation whose axis was normalised to 0.9 is no rotation,
     * and its transpose is not its inverse). */
    const char *tiny =
        "sphere radius 1 transform scale 2 1 1 rotate 2e-162 2e-162 0 60 "
        "translate 0 0 5\n";
    const char *unit = "sphere radius 1 transform scale 2 1 1 rotate 1 1 0 60 "
                       "translate 0 0 5\n";
    scene a, b;
    scene_of(&a, tiny), scene_of(&b, unit);
    ck_assert_int_eq(a.object_count, 1);
    const transform *ta = scene_transform(&a, a.objects[0].transform);
    const transform *tb = scene_transform(&b, b.objects[0].transform);
    ck_assert(memcmp(ta, tb, sizeof *ta) == 0);
    scene_free(&a), scene_free(&b);
}
END_TEST

START_TEST(test_the_camera_frame_is_checked_once_the_scene_is_read)
{
    /* up along the default view, then a look_at that makes a frame */
    scene s;
    scene_of(&s, "camera up 0 0 1\ncamera look_at 0 5 0\n");
    ck_assert(s.cam.is_placed);
    scene_free(&s);
    scene_of(&s,
             "camera look_at 0 0 9\nimage 8 6\ncamera position 1e-300 0 0\n");
    scene_free(&s);
    /* a look_at 1e-200 from the eye is still a direction to look in */
    scene_of(&s, "camera look_at 1e-200 0 1e-200\n");
    scene_free(&s);
    /* the error is at the last statement that placed the camera */
    expect_parse_error(
        "camera look_at 0 5 0\nimage 8 6\ncamera up 0 1 0\nimage 4 3\n", 3, 1,
        "up is (nearly) along its view");
    expect_parse_error("camera up 0 0 1\nimage 8 6\n", 1, 1, "along its view");
    expect_parse_error(
        "camera position 0 0 5\ncamera fov 30\ncamera look_at 0 0 5 fov 20\n",
        3, 1, "look_at point is its position");
}
END_TEST

Suite *ch05_robustness_suite(void)
{
    Suite *s = suite_create("ch05 robustness");
    TCase *edges = tcase_create("edge cases");
    tcase_add_test(edges, test_a_tiny_rotation_axis_is_the_same_rotation);
    tcase_add_test(edges,
                   test_the_camera_frame_is_checked_once_the_scene_is_read);
    suite_add_tcase(s, edges);
    return s;
}
