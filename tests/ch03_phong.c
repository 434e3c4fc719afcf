/* ch03_phong.c: the Phong model term by term, lights, tone mapping and the
 * new scene statements (chapter 03).
 *
 * Expected values are worked out by hand from the formulas (stated beside
 * each) or computed here in long double. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "render.h"
#include "scene.h"
#include "test_util.h"
#include "shade.h"

#define DEG (M_PI / 180.0)

static const vec3 UP = {0, 0, 1}; /* the surface normal of every test hit */

/* A scene with one white directional light arriving from direction l (unit,
 * towards the light), no ambient light, and a default material with the
 * given finish. */
static void one_light_scene(scene *s, vec3 l, double ambient, double diffuse,
                            double specular, double shininess)
{
    scene_init(s);
    s->ambient = (vec3){0, 0, 0};
    s->default_material.ambient = ambient;
    s->default_material.diffuse = diffuse;
    s->default_material.specular = specular;
    s->default_material.shininess = shininess;
    ck_assert(scene_add_light(s, (light){.kind = LIGHT_DIRECTIONAL,
                                          .direction = vec3_scale(l, -1),
                                          .intensity = {1, 1, 1}}));
}

static hit white_hit_at_origin(void)
{
    return (hit){.t = 1,
                 .point = {0, 0, 0},
                 .normal = UP,
                 .color = {1, 1, 1},
                 .material = 0};
}

static vec3 shade_at_origin(const scene *s, vec3 v)
{
    hit h = white_hit_at_origin();
    render_stats stats = {0};
    return shade(s, &h, v, &stats);
}

/* ------------------------------------------------------------ each term */

START_TEST(test_diffuse_term_follows_lamberts_cosine)
{
    /* Light 60 degrees from the normal: cos 60 = 1/2 of the light arrives. */
    scene s;
    one_light_scene(&s, (vec3){sin(60 * DEG), 0, cos(60 * DEG)}, 0, 1, 0, 1);
    vec3 c = shade_at_origin(&s, UP);
    ck_assert_double_eq_tol(c.x, 0.5, 4 * DBL_EPSILON);
    ck_assert(c.x == c.y && c.y == c.z);
    scene_free(&s);
}
END_TEST

START_TEST(test_ambient_and_emission_terms_alone)
{
    scene s;
    one_light_scene(&s, (vec3){0, 0, -1}, 0.25, 0, 0,
                    1); /* the light is below: no direct term */
    s.ambient = (vec3){0.4, 0.8, 1.2};
    s.default_material.emission = (vec3){0.5, 0, 0.125};
    hit h = white_hit_at_origin();
    h.color = (vec3){1, 0.5, 0.25};
    render_stats stats = {0};
    vec3 c = shade(&s, &h, UP, &stats);
    /* I_e + rho_a C I_a = (0.5 + 0.1, 0 + 0.1, 0.125 + 0.075) */
    ck_assert_double_eq_tol(c.x, 0.6, 1e-15);
    ck_assert_double_eq_tol(c.y, 0.1, 1e-15);
    ck_assert_double_eq_tol(c.z, 0.2, 1e-15);
    scene_free(&s);
}
END_TEST

START_TEST(test_phong_highlight_at_the_mirror_direction_is_rho_s)
{
    vec3 l = {sin(30 * DEG), 0, cos(30 * DEG)}, mirror = {-l.x, 0, l.z};
    ck_assert_double_eq_tol(specular_phong(UP, l, mirror, 50), 1,
                            8 * DBL_EPSILON);
    scene s;
    one_light_scene(&s, l, 0, 0, 0.75, 50);
    ck_assert_double_eq_tol(shade_at_origin(&s, mirror).y, 0.75,
                            8 * DBL_EPSILON);
    scene_free(&s);
}
END_TEST

START_TEST(test_phong_highlight_is_cos_alpha_to_the_k)
{
    /* l at 30 degrees, v 10 degrees past the mirror direction: <r,v> = cos 10.
     */
    vec3 l = {sin(30 * DEG), 0, cos(30 * DEG)},
         v = {-sin(40 * DEG), 0, cos(40 * DEG)};
    long double expected = powl(cosl(10 * (long double)DEG), 20);
    ck_assert_double_eq_tol(specular_phong(UP, l, v, 20), (double)expected,
                            1e-14);
}
END_TEST

START_TEST(test_blinn_agrees_with_phong_at_the_mirror_direction)
{
    for (int angle = 0; angle < 90; angle += 7) {
        vec3 l = {sin(angle * DEG), 0, cos(angle * DEG)}, v = {-l.x, 0, l.z};
        ck_assert_double_eq_tol(specular_blinn(UP, l, v, 10), 1,
                                8 * DBL_EPSILON);
        ck_assert_double_eq_tol(specular_phong(UP, l, v, 10), 1,
                                8 * DBL_EPSILON);
    }
}
END_TEST

START_TEST(test_blinn_highlight_uses_the_unit_half_vector)
{
    /* l at 60 degrees, v along n: h is 30 degrees from n, so <n,h>^(4k) =
     * cos^40 30. */
    vec3 l = {sin(60 * DEG), 0, cos(60 * DEG)};
    long double expected = powl(cosl(30 * (long double)DEG), 40);
    double got = specular_blinn(UP, l, UP, 10);
    ck_assert_msg(fabs(got - (double)expected) < 1e-15,
                  "<n,h>^40 = %g, not cos^40 30 = %g: h is the unit vector (l "
                  "+ v) / |l + v|, "
                  "not the sheet's (l + v) / 2 (sheet 2.4)",
                  got, (double)expected);
}
END_TEST

START_TEST(test_sheet_half_vector_kills_the_highlight_at_90_degrees)
{
    /* l and v 45 degrees either side of n: the true h is n, a full highlight.
     * The sheet's h = (l + v)/2 has length cos 45, and cos^40 45 = 2^-20. */
    vec3 l = {sin(45 * DEG), 0, cos(45 * DEG)}, v = {-l.x, 0, l.z};
    ck_assert_double_eq_tol(specular_blinn(UP, l, v, 10), 1, 8 * DBL_EPSILON);
    vec3 sheet_h = vec3_scale(vec3_add(l, v), 0.5);
    double sheet = pow(vec3_dot(UP, sheet_h), 40);
    ck_assert_double_eq_tol(sheet, 1.0 / (1 << 20), 1e-18);
}
END_TEST

/* ------------------------------------------------------------ the clamps */

START_TEST(test_light_behind_the_surface_adds_nothing)
{
    scene s;
    one_light_scene(&s, vec3_normalize((vec3){0.3, 0, -1}), 0, 1, 1, 10);
    vec3 c = shade_at_origin(&s, UP);
    ck_assert(c.x == 0 && c.y == 0 && c.z == 0); /* not negative: nothing */
    scene_free(&s);
}
END_TEST

START_TEST(test_no_highlight_from_a_light_below_the_horizon)
{
    /* l 10 degrees below the horizon; v low on the far side. r and v agree
     * (<r,v> = 0.97), so an unclamped sum would show a highlight. */
    vec3 l = {sin(100 * DEG), 0, cos(100 * DEG)},
         v = vec3_normalize((vec3){-1, 0, 0.05});
    ck_assert(phong_cosine(UP, l, v) > 0.9);
    scene s;
    one_light_scene(&s, l, 0, 0, 1, 10);
    vec3 c = shade_at_origin(&s, v);
    ck_assert(c.x == 0 && c.y == 0 && c.z == 0);
    scene_free(&s);
}
END_TEST

START_TEST(test_back_of_a_surface_is_shaded_like_its_front)
{
    /* Viewer and light both below: the normal is turned towards the viewer. */
    scene s;
    one_light_scene(&s, (vec3){0, 0, -1}, 0, 1, 0, 1);
    vec3 c = shade_at_origin(&s, (vec3){0, 0, -1});
    ck_assert_double_eq_tol(c.x, 1, 1e-15);
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ lights */


START_TEST(test_spot_intensity_inside_at_and_beyond_the_cone)
{
    scene s;
    scene_error err;
    ck_assert(parse_text(
        &s, "light spot position 0 0 0 direction 0 0 1 angle 60 exponent 2\n",
        &err));
    const light *L = &s.lights[0];
    /* Points at distance 2, at angles from the axis; attenuation is 1. */
    double inside = 59.9 * DEG, outside = 60.1 * DEG;
    vec3 p_in = {2 * sin(inside), 0, 2 * cos(inside)},
         p_out = {2 * sin(outside), 0, 2 * cos(outside)};
    ck_assert_double_eq_tol(light_toward(L, p_in).intensity.x,
                            pow(cos(inside), 2), 1e-15);
    ck_assert(light_toward(L, p_out).intensity.x == 0);
    /* Exactly on the edge: -l . direction is the cut-off's cosine, c,
     * with no rounding (direction is the z axis); the edge belongs to the
     * cone: c^2, about 1/4. */
    double c = L->cos_cutoff;
    double edge = spot_falloff(L, (vec3){-sqrt(1 - c * c), 0, -c});
    ck_assert_msg(fabs(c - 0.5) < 1e-15 && fabs(edge - c * c) < 1e-15,
                  "a point on the cone's edge gets %.17g, not cos^2 = 1/4: "
                  "the edge is inside the cone (0 only beyond it)", edge);
    /* Behind the light: nothing, even though cos^2 of it would be positive. */
    ck_assert(light_toward(L, (vec3){0, 0, -2}).intensity.x == 0);
    scene_free(&s);
}
END_TEST

START_TEST(test_attenuation_values)
{
    light L = {.kind = LIGHT_POINT,
               .attenuation = {1, 0.5, 0.25},
               .intensity = {1, 1, 1}};
    ck_assert(light_attenuation(&L, 0) == 1);
    ck_assert_double_eq_tol(light_attenuation(&L, 2), 1.0 / 3,
                            1e-16); /* 1 + 1 + 1 */
    ck_assert_double_eq_tol(light_attenuation(&L, 4), 1.0 / 7,
                            1e-16); /* 1 + 2 + 4 */
    light near_physical = {.kind = LIGHT_POINT, .attenuation = {0.01, 0, 1}};
    ck_assert_double_eq_tol(light_attenuation(&near_physical, 0), 100,
                            1e-12); /* finite */
    light_sample at_two = light_toward(&L, (vec3){2, 0, 0});
    ck_assert_double_eq_tol(at_two.intensity.y, 1.0 / 3, 1e-16);
    ck_assert(at_two.distance == 2 && at_two.l.x == -1);
}
END_TEST

START_TEST(test_a_directional_light_is_infinitely_far)
{
    /* Nothing lies beyond a directional light: its distance is infinite,
     * so that a shadow ray looks for occluders all the way (chapter 6). */
    light L = {.kind = LIGHT_DIRECTIONAL,
               .direction = {0, -1, 0},
               .intensity = {1, 1, 1},
               .attenuation = {1, 0, 0}};
    light_sample got = light_toward(&L, (vec3){3, 4, 5});
    ck_assert_msg(got.distance == INFINITY,
                  "a directional light at distance %.17g, not infinity",
                  got.distance);
    ck_assert(got.l.x == 0 && got.l.y == 1 && got.l.z == 0);
    ck_assert(got.intensity.x == 1); /* no attenuation, no cone */
}
END_TEST

START_TEST(test_point_at_the_light_is_finite)
{
    scene s;
    one_light_scene(&s, UP, 0.1, 0.9, 0.5, 10);
    s.lights[0] = (light){.kind = LIGHT_POINT,
                          .position = {0, 0, 0},
                          .intensity = {1, 1, 1},
                          .attenuation = {1, 0, 0}};
    vec3 c = shade_at_origin(&s, UP);
    ck_assert(isfinite(c.x) && isfinite(c.y) && isfinite(c.z));
    ck_assert(
        c.x ==
        0); /* no ambient light in this scene, no direction to the light */
    scene_free(&s);
}
END_TEST

START_TEST(test_default_light_when_the_scene_has_none)
{
    scene s;
    scene_init(&s);
    ck_assert_int_eq(s.light_count, 0);
    hit h = white_hit_at_origin();
    h.normal = vec3_normalize((vec3){-1, 1, -1}); /* facing the default light */
    render_stats stats = {0};
    vec3 c = shade(&s, &h, h.normal, &stats);
    ck_assert(c.x > 0.5); /* diffuse 0.8 at cos 1, plus ambient and highlight */
    scene_free(&s);
}
END_TEST

/* ------------------------------------------------------------ tone mapping */

START_TEST(test_tone_map_keeps_values_below_one_below_one)
{
    const double betas[] = {0.5, 0.85, 1, 2};
    for (int b = 0; b < 4; b++) {
        for (double I = 0.001; I < 1; I += 0.001)
            ck_assert_msg(tone_map(I, 1, betas[b]) < 1,
                          "I %g beta %g maps to %g: the tone map is min(alpha "
                          "I^beta, 1), "
                          "not the sheet's max (sheet 3.2), which makes every "
                          "pixel white",
                          I, betas[b], tone_map(I, 1, betas[b]));
        for (double I = 1; I < 1e6; I *= 1.7)
            ck_assert(tone_map(I, 1, betas[b]) == 1);
        /* The sheet's max((I^beta)^(1/2.2), 1) is never below 1: all white. */
        ck_assert(fmax(pow(pow(0.25, betas[b]), 1 / 2.2), 1.0) == 1.0);
    }
    ck_assert_double_eq_tol(tone_map(0.25, 2, 0.5), 1.0, 1e-15); /* 2 * 0.5 */
    ck_assert_double_eq_tol(tone_map(0.0625, 2, 0.5), 0.5, 1e-15);
    ck_assert(tone_map(NAN, 1, 1) == 0 && tone_map(-1, 1, 1) == 0);
}
END_TEST

/* ------------------------------------------------------------ statements */

START_TEST(test_material_light_and_tonemap_statements)
{
    scene s;
    scene_error err;
    const char *text =
        "ambient 0.1 0.2 0.3\n"
        "tonemap beta 0.8 alpha 1.5\n"
        "material shiny specular 0.9 shininess 80 highlight blinn emission 1 0 "
        "0\n"
        "material default diffuse 0.5\n"
        "sphere material shiny\n"
        "sphere\n"
        "light point position 1 2 3 intensity 2 2 2 attenuation 1 0.5 0.25\n"
        "light directional direction 0 -2 0\n";
    ck_assert_msg(parse_text(&s, text, &err), "%d:%d %s", err.line, err.col,
                  err.message);
    ck_assert(s.ambient.z == 0.3 && s.tone.alpha == 1.5 && s.tone.beta == 0.8);
    ck_assert_int_eq(s.material_count, 1);
    const material *shiny = scene_material(&s, s.objects[0].material);
    ck_assert_str_eq(shiny->name, "shiny");
    ck_assert(shiny->specular == 0.9 && shiny->shininess == 80 &&
              shiny->highlight == HIGHLIGHT_BLINN && shiny->emission.x == 1);
    ck_assert(shiny->diffuse ==
              0.8); /* the built-in default, not the redefined one */
    ck_assert(scene_material(&s, s.objects[1].material)->diffuse == 0.5);
    ck_assert_int_eq(s.light_count, 2);
    ck_assert(s.lights[0].attenuation[1] == 0.5 &&
              s.lights[0].attenuation[2] == 0.25);
    ck_assert(s.lights[1].direction.y == -1);    /* normalised */
    scene_free(&s);
}
END_TEST


START_TEST(test_scene_rejects_unknown_and_duplicate_materials)
{
    expect_parse_error("sphere material shiny", 1, 17,
                       "material defined above, found 'shiny'");
    expect_parse_error("sphere material", 1, 16, "found end of line");
    expect_parse_error("material a\nsphere\nmaterial a specular 1", 3, 10,
                       "defined on line 1");
    expect_parse_error("material default\nmaterial default", 2, 10,
                       "defined on line 1");
    expect_parse_error("material abcdefghijabcdefghijabcdefghijxy", 1, 10,
                       "1 to 31 characters");
}
END_TEST

START_TEST(test_scene_rejects_bad_coefficients)
{
    expect_parse_error("material m diffuse -0.1", 1, 20,
                       "from 0 to 1, found '-0.1'");
    expect_parse_error("material m specular 1.5", 1, 21, "from 0 to 1");
    expect_parse_error("material m ambient nan", 1, 20, "finite");
    expect_parse_error("material m emission 1 inf 0", 1, 23, "finite");
    expect_parse_error("material m emission 1 -1 0", 1, 23, "from 0 to 1e6");
    expect_parse_error("material m shininess 0.5", 1, 22, "at least 1");
    expect_parse_error("material m highlight torrance", 1, 22,
                       "'phong' or 'blinn'");
    expect_parse_error("material m gloss 1", 1, 12,
                       "expected a material setting");
}
END_TEST

START_TEST(test_scene_rejects_bad_lights)
{
    expect_parse_error("light", 1, 6, "kind of light");
    expect_parse_error("light laser", 1, 7, "kind of light");
    expect_parse_error("light point angle 30", 1, 13,
                       "(position, intensity, attenuation)");
    expect_parse_error("light directional position 0 0 0", 1, 19,
                       "(direction, intensity)");
    expect_parse_error("light spot angle 0", 1, 18, "between 0 and 180");
    expect_parse_error("light spot angle 180", 1, 18, "between 0 and 180");
    expect_parse_error("light spot angle -20", 1, 18, "between 0 and 180");
    expect_parse_error("light spot exponent -1", 1, 21, "at least 0");
    expect_parse_error("light directional direction 0 0 0", 1, 29,
                       "non-zero length");
    expect_parse_error("light spot direction -0 0 -0", 1, 22,
                       "non-zero length");
    expect_parse_error("light point intensity -1 1 1", 1, 23, "from 0 to 1e6");
}
END_TEST

START_TEST(test_scene_rejects_attenuation_that_reaches_zero)
{
    expect_parse_error("light point attenuation 0 0 1", 1, 25,
                       "a1 from 1e-6 to 1e6");
    expect_parse_error("light point attenuation -1 0 1", 1, 25, "a1 from 1e-6");
    expect_parse_error("light point attenuation 1e-300 0 1", 1, 25,
                       "a1 from 1e-6");
    expect_parse_error("light point attenuation 1 0 -0.01", 1, 29,
                       "a3 from 0 to 1e6");
    expect_parse_error("light point attenuation 1 -1 0", 1, 27,
                       "a2 from 0 to 1e6");
    /* (1 - r)^2 is 0 at r = 1; 1 - 1.9r + r^2 > 0 only by a rounding-sized
     * margin */
    expect_parse_error("light spot attenuation 1 -2 1", 1, 26, "a2 from 0");
    expect_parse_error("light spot attenuation 1 -1.9 1", 1, 26, "a2 from 0");
    expect_parse_error("light point attenuation 1 1e7 0", 1, 27,
                       "a2 from 0 to 1e6");
    expect_parse_error("light point attenuation 1 0 nan", 1, 29, "finite");
}
END_TEST

START_TEST(test_scene_rejects_bad_tone_maps_and_ambient)
{
    expect_parse_error("tonemap", 1, 8, "'alpha' or 'beta'");
    expect_parse_error("tonemap gamma 2.2", 1, 9, "'alpha' or 'beta'");
    expect_parse_error("tonemap alpha 0", 1, 15, "greater than 0");
    expect_parse_error("tonemap beta -1", 1, 14, "greater than 0");
    expect_parse_error("ambient 1 1", 1, 12, "found end of line");
}
END_TEST

Suite *ch03_phong_suite(void)
{
    Suite *s = suite_create("ch03 phong");
    TCase *terms = tcase_create("formulas");
    tcase_add_test(terms, test_diffuse_term_follows_lamberts_cosine);
    tcase_add_test(terms, test_ambient_and_emission_terms_alone);
    tcase_add_test(terms,
                   test_phong_highlight_at_the_mirror_direction_is_rho_s);
    tcase_add_test(terms, test_phong_highlight_is_cos_alpha_to_the_k);
    tcase_add_test(terms, test_blinn_agrees_with_phong_at_the_mirror_direction);
    tcase_add_test(terms, test_blinn_highlight_uses_the_unit_half_vector);
    tcase_add_test(terms, test_attenuation_values);
    tcase_add_test(terms, test_tone_map_keeps_values_below_one_below_one);
    tcase_add_test(terms, test_default_light_when_the_scene_has_none);
    suite_add_tcase(s, terms);

    TCase *edges = tcase_create("edge cases");
    tcase_add_test(edges,
                   test_sheet_half_vector_kills_the_highlight_at_90_degrees);
    tcase_add_test(edges, test_light_behind_the_surface_adds_nothing);
    tcase_add_test(edges, test_no_highlight_from_a_light_below_the_horizon);
    tcase_add_test(edges, test_back_of_a_surface_is_shaded_like_its_front);
    tcase_add_test(edges, test_spot_intensity_inside_at_and_beyond_the_cone);
    tcase_add_test(edges, test_point_at_the_light_is_finite);
    tcase_add_test(edges, test_a_directional_light_is_infinitely_far);
    suite_add_tcase(s, edges);

    TCase *bad = tcase_create("bad input");
    tcase_add_test(bad, test_material_light_and_tonemap_statements);
    tcase_add_test(bad, test_scene_rejects_unknown_and_duplicate_materials);
    tcase_add_test(bad, test_scene_rejects_bad_coefficients);
    tcase_add_test(bad, test_scene_rejects_bad_lights);
    tcase_add_test(bad, test_scene_rejects_attenuation_that_reaches_zero);
    tcase_add_test(bad, test_scene_rejects_bad_tone_maps_and_ambient);
    suite_add_tcase(s, bad);
    return s;
}
