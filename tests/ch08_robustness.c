/* ch08_robustness.c: --stats hints on images too small for their meshes
 * (chapter 08). */
#include <check.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "test_util.h"

START_TEST(test_a_mesh_within_a_pixel_gets_a_sensible_hint)
{
    /* The bunny 600 units away on a 1 x 1 image: its box covers a small
     * part of the one pixel. The hint may not claim 0 pixels, nor more
     * triangles a pixel than the mesh has. */
    link_meshes();
    char scene_path[192], errors[4096];
    snprintf(
        scene_path, sizeof scene_path, "%s",
        write_file("far.scene",
                   "mesh file meshes/bunny.obj scale 12 offset 0 0 600\n"));
    const char *args[] = {scene_path, "--size",          "1x1", "--stats",
                          "-o",       tmp_path("b.png"), NULL};
    ck_assert_int_eq(run_bin(args, errors, sizeof errors), 0);
    const char *hint = strstr(errors, "hint: object 1, a mesh of ");
    ck_assert_msg(hint != NULL, "%s", errors);
    long triangles =
        strtol(hint + strlen("hint: object 1, a mesh of "), NULL, 10);
    char expected[128];
    snprintf(expected, sizeof expected,
             "covers at most 1 pixel: %ld triangles a pixel,", triangles);
    ck_assert_msg(strstr(hint, expected) != NULL, "'%s' lacks '%s'", hint,
                  expected);
}
END_TEST

Suite *ch08_robustness_suite(void)
{
    Suite *s = suite_create("ch08 robustness");
    TCase *hints = tcase_create("edge cases");
    tcase_add_checked_fixture(hints, make_tmpdir, remove_tmpdir);
    tcase_add_test(hints, test_a_mesh_within_a_pixel_gets_a_sensible_hint);
    suite_add_tcase(s, hints);
    return s;
}
