/* light_statement.c: the light statement of a scene file (chapter 3). */
#include "light_statement.h"

#include <math.h>

/* <<lights of other kinds>> ch06 */

#define AREA_LIGHT_MAX_SAMPLES 1024 /* shadow rays per point and light */

static bool read_light_setting(parser *p, light *L); /* chapter 3 */

static bool read_sample_pattern(parser *p, light *L)
{
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "uniform"))
        L->pattern = SAMPLE_UNIFORM;
    else if (named && parse_token_is(p, "stratified"))
        L->pattern = SAMPLE_STRATIFIED;
    else if (named && parse_token_is(p, "grid"))
        L->pattern = SAMPLE_GRID;
    else
        return parse_expected(p, "expected 'uniform', 'stratified' or "
                                 "'grid'");
    return true;
}

static bool read_area_setting(parser *p, light *L)
{
    if (parse_token_is(p, "radius")) {
        if (!parse_positive(p, "a disc radius", &L->radius))
            return false;
        return L->radius <= PARSE_MAX_COORDINATE ||
               parse_expected(p, "expected a disc radius of at most 1e50");
    }
    if (parse_token_is(p, "samples")) {
        long n;
        if (!parse_int_in(p, "a number of samples", 1, AREA_LIGHT_MAX_SAMPLES,
                          &n))
            return false;
        L->samples = (int)n;
        return true;
    }
    if (parse_token_is(p, "pattern"))
        return read_sample_pattern(p, L);
    return read_light_setting(p, L);
}

static bool parse_area_light(parser *p, scene *s, light L)
{
    L.kind = LIGHT_AREA, L.radius = 1, L.samples = 16;
    L.pattern = SAMPLE_STRATIFIED;
    while (parse_next_token(p))
        if (!read_area_setting(p, &L))
            return false;
    if (!scene_add_light(s, L))
        return parse_no_room(p, p->line, s->light_count, SCENE_MAX_LIGHTS,
                             "lights");
    return true;
}

/* <<the light statement>> ch03 */
/* <<reading attenuation>> ch03 */
static bool read_attenuation(parser *p, double a[3])
{
    const char *where[3];
    int length[3];
    for (int k = 0; k < 3; k++) {
        if (!parse_number(p, "an attenuation coefficient", &a[k]))
            return false;
        where[k] = p->token, length[k] = p->token_length;
    }
    const char *problem = NULL;
    int bad = 0;
    if (!(a[0] >= 1e-6 && a[0] <= 1e6))
        bad = 0,
        problem =
            "a1 from 1e-6 to 1e6, so that the light is finite at its position";
    else if (!(a[1] >= 0 && a[1] <= 1e6))
        bad = 1,
        problem = "a2 from 0 to 1e6, so that the denominator stays at least a1";
    else if (!(a[2] >= 0 && a[2] <= 1e6))
        bad = 2,
        problem = "a3 from 0 to 1e6, so that the denominator stays at least a1";
    if (problem == NULL)
        return true;
    p->token = where[bad], p->token_length = length[bad];
    return parse_expected(p, "expected %s", problem);
}

static bool read_spot_setting(parser *p, light *L)
{
    double value;
    if (parse_token_is(p, "angle")) {
        if (!parse_number(p, "a cone angle", &value))
            return false;
        if (!(value > 0 && value < 180))
            return parse_expected(
                p, "expected a cone angle between 0 and 180 degrees");
        L->cos_cutoff = cos(value * (M_PI / 180.0));
        return true;
    }
    if (!parse_number(p, "a spot exponent", &L->exponent))
        return false;
    return L->exponent >= 0 ||
           parse_expected(p, "expected a spot exponent of at least 0");
}

static bool read_light_setting(parser *p, light *L)
{
    static const char *const settings[] = {
        [LIGHT_POINT] = "position, intensity, attenuation",
        [LIGHT_DIRECTIONAL] = "direction, intensity",
        /* one string on two lines, in parentheses so that no compiler
         * takes it for two with a comma missing */
        [LIGHT_SPOT] = ("position, direction, angle, exponent, intensity, "
                        "attenuation"),
        /* <<the settings of other kinds of light>> ch06 */
        [LIGHT_AREA] = "position, direction, radius, samples, pattern, intensity, "
                       "attenuation",
    };
    bool placed = L->kind != LIGHT_DIRECTIONAL, aimed = L->kind != LIGHT_POINT;
    if (parse_token_is(p, "intensity"))
        return parse_color(p, "a light intensity", &L->intensity);
    if (placed && parse_token_is(p, "position"))
        return parse_point(p, "a light position", &L->position);
    if (aimed && parse_token_is(p, "direction"))
        return parse_direction(p, "a light direction", &L->direction);
    if (placed && parse_token_is(p, "attenuation"))
        return read_attenuation(p, L->attenuation);
    if (L->kind == LIGHT_SPOT &&
        (parse_token_is(p, "angle") || parse_token_is(p, "exponent")))
        return read_spot_setting(p, L);
    return parse_expected(p, "expected a setting of this light (%s)",
                          settings[L->kind]);
}

static const char other_light_kinds[] = ""
    /* <<names of other kinds of light>> ch06 */
    ", area"
    ;

bool light_statement_parse(parser *p, scene *s)
{
    light L = {.position = {0, 0, 0},
               .direction = {0, -1, 0},
               .intensity = {1, 1, 1},
               .attenuation = {1, 0, 0},
               .cos_cutoff = cos(30 * (M_PI / 180.0)),
               .exponent = 2};
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "point"))
        L.kind = LIGHT_POINT;
    else if (named && parse_token_is(p, "directional"))
        L.kind = LIGHT_DIRECTIONAL;
    else if (named && parse_token_is(p, "spot"))
        L.kind = LIGHT_SPOT;
    /* <<other kinds of light>> ch06 */
    else if (named && parse_token_is(p, "area"))
        return parse_area_light(p, s, L);
    else
        return parse_expected(p, "expected a kind of light (point, "
                                 "directional, spot%s)", other_light_kinds);
    while (parse_next_token(p))
        if (!read_light_setting(p, &L))
            return false;
    if (!scene_add_light(s, L))
        return parse_no_room(p, p->line, s->light_count, SCENE_MAX_LIGHTS,
                             "lights");
    return true;
}
