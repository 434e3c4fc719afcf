/* ch03_robustness.c: directions of any finite length but zero (chapter 03).
 *
 * A direction is normalised from what the scene says; the squares of very
 * short vectors underflow, so the parser must not square them as they
 * are. Expected directions are those of the same vectors written at
 * length about 1, parsed the same way: scaling a vector by a power of ten
 * does not change its direction. */
#include <check.h>
#include <string.h>

#include "scene.h"
#include "test_util.h"

/* The direction of the scene's first light, as parsed from text. */
static vec3 light_direction(const char *text)
{
    scene s;
    scene_error err;
    ck_assert_msg(parse_text(&s, text, &err), "%s: %d:%d %s", text, err.line,
                  err.col, err.message);
    ck_assert_int_eq(s.light_count, 1);
    vec3 d = s.lights[0].direction;
    scene_free(&s);
    return d;
}

START_TEST(test_a_tiny_direction_is_a_direction)
{
    /* (1e-170)^2 is 0, (2e-162)^2 a subnormal with one bit: each must give
     * the unit vector of 1 -1 0 (or 1 1 0), to the bit, since dividing by
     * the largest component gives exactly 1 -1 0 */
    const char *tiny[][2] = {
        {"light directional direction 1e-170 -1e-170 0\n",
         "light directional direction 1 -1 0\n"},
        {"light directional direction 2e-162 2e-162 0\n",
         "light directional direction 1 1 0\n"},
        {"light spot direction 0 -4.9e-324 0\n",
         "light spot direction 0 -1 0\n"},
    };
    for (int k = 0; k < 3; k++) {
        vec3 a = light_direction(tiny[k][0]), b = light_direction(tiny[k][1]);
        ck_assert_msg(memcmp(&a, &b, sizeof a) == 0, "%s: %.17g %.17g %.17g",
                      tiny[k][0], a.x, a.y, a.z);
    }
    /* zero is still no direction */
    expect_parse_error("light directional direction 0 0 -0\n", 1, 29,
                       "non-zero length");
}
END_TEST

Suite *ch03_robustness_suite(void)
{
    Suite *s = suite_create("ch03 robustness");
    TCase *edges = tcase_create("edge cases");
    tcase_add_test(edges, test_a_tiny_direction_is_a_direction);
    suite_add_tcase(s, edges);
    return s;
}
