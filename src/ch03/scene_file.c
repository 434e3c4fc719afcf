/* scene_file.c: the statements of a scene file (chapter 1). */
#include "scene_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"
/* <<scene file includes>> ch03 */
#include "material_statement.h"
#include "light_statement.h"

/* <<readers of settings>> ch03 */

static bool read_material_name(parser *p, const scene *s, int *material)
{
    if (!parse_next_token(p) ||
        (*material = material_statement_find(s, p)) < 0)
        return parse_expected(p, "expected the name of a material defined "
                                 "above");
    return true;
}

/* <<statements>> ch01 */
static bool parse_camera(parser *p, scene *s)
{
    if (!parse_next_token(p))
        return parse_expected(p, "expected a camera setting such as 'fov'");
    do {
        if (parse_token_is(p, "fov")) {
            double fov;
            if (!parse_number(p, "a field of view in degrees", &fov))
                return false;
            if (!(fov > 0 && fov < 180))
                return parse_expected(p, "expected a field of view between "
                                         "0 and 180 degrees");
            s->cam.fov_deg = fov;
        }
        else
            return parse_expected(p, "expected a camera setting such as "
                                     "'fov'");
    } while (parse_next_token(p));
    return true;
}

/* <<image statement>> ch01 */
static bool parse_image(parser *p, scene *s)
{
    long w = 0, h = 0; /* set by parse_int_in before any use */
    if (!parse_int_in(p, "an image width", 1, IMAGE_MAX_SIDE, &w) ||
        !parse_int_in(p, "an image height", 1, IMAGE_MAX_SIDE, &h))
        return false;
    if (w * h > IMAGE_MAX_PIXELS)
        return parse_expected(p, "expected at most %ld pixels in all "
                                 "(%ldx%ld is %ld)",
                              IMAGE_MAX_PIXELS, w, h, w * h);
    s->cam.width = (int)w;
    s->cam.height = (int)h;
    s->image_line = p->line_number;
    return true;
}

/* <<background statement>> ch01 */
static bool parse_background(parser *p, scene *s)
{
    const char *rest = p->next;
    if (parse_next_token(p) && parse_token_is(p, "gradient")) {
        s->bg.kind = BACKGROUND_GRADIENT;
        return parse_color(p, "a bottom colour component", &s->bg.bottom) &&
               parse_color(p, "a top colour component", &s->bg.top);
    }
    p->next = rest; /* not "gradient": read that token again as a number */
    s->bg.kind = BACKGROUND_SOLID;
    return parse_color(p, "a colour component", &s->bg.bottom);
}
/* <<statements>> += ch02 */

/* The settings every object statement accepts, for error messages. */
static const char object_setting_names[] =
    "color"
    /* <<names of object settings>> ch03 */
    ", material"
    ;

/* Reads the setting the token just read names, if every object has it:
 * *known says whether it was one; false on bad input. */
static bool parse_object_setting(parser *p, scene *s, object *o, bool *known)
{
    (void)s; /* chapter 3 looks materials up in the scene */
    *known = true;
    if (parse_token_is(p, "color"))
        return parse_color(p, "a colour component", &o->color);
    /* <<object settings>> ch03 */
    if (parse_token_is(p, "material"))
        return read_material_name(p, s, &o->material);
    *known = false;
    return true;
}

static bool parse_sphere(parser *p, scene *s)
{
    object o = {.kind = SHAPE_SPHERE, .sphere = {{0, 0, 5}, 1},
                .color = {0.8, 0.8, 0.8}};
    while (parse_next_token(p)) {
        bool ok, known = true;
        if (parse_token_is(p, "center"))
            ok = parse_point(p, "a centre coordinate", &o.sphere.center);
        else if (parse_token_is(p, "radius"))
            ok = parse_number_in(p, "a radius", 1e-50, 1e50,
                                 &o.sphere.radius);
        else
            ok = parse_object_setting(p, s, &o, &known);
        if (!known)
            return parse_expected(p, "expected a sphere setting "
                                     "(center, radius, %s)",
                                  object_setting_names);
        if (!ok)
            return false;
    }
    if (!scene_add_object(s, o))
        return parse_no_room(p, p->line, s->object_count, SCENE_MAX_OBJECTS,
                             "objects");
    return true;
}
/* <<statements>> += ch03 */

static bool parse_ambient(parser *p, scene *s)
{
    return parse_color(p, "an ambient intensity", &s->ambient);
}

/* <<the tonemap statement>> ch03 */
static bool parse_tonemap(parser *p, scene *s)
{
    if (!parse_next_token(p))
        return parse_expected(p, "expected 'alpha' or 'beta'");
    do {
        if (parse_token_is(p, "alpha")) {
            if (!parse_positive(p, "an exposure alpha", &s->tone.alpha))
                return false;
        } else if (parse_token_is(p, "beta")) {
            if (!parse_positive(p, "a compression beta", &s->tone.beta))
                return false;
        } else {
            return parse_expected(p, "expected 'alpha' or 'beta'");
        }
    } while (parse_next_token(p));
    return true;
}

/* <<the statement loop>> ch01 */
typedef bool (*statement_parser)(parser *p, scene *s);

static const struct {
    const char *keyword;
    statement_parser parse;
} statements[] = {
    {"camera", parse_camera},
    {"image", parse_image},
    {"background", parse_background},
    /* <<scene keywords>> ch02 */
    {"sphere", parse_sphere},
    /* <<scene keywords>> += ch03 */
    {"ambient", parse_ambient},
    {"tonemap", parse_tonemap},
    {"material", material_statement_parse},
    {"light", light_statement_parse},
};

static bool parse_statement(parser *p, void *target)
{
    scene *s = target;
    if (!parse_next_token(p))
        return true; /* a blank line or a comment */
    for (size_t k = 0; k < sizeof statements / sizeof statements[0]; k++) {
        if (parse_token_is(p, statements[k].keyword)) {
            if (!statements[k].parse(p, s))
                return false;
            return parse_next_token(p) ? parse_expected(p, "expected end of "
                                                           "line")
                                       : true;
        }
    }
    return parse_expected(p, "expected a statement keyword");
}


bool scene_parse(scene *s, const char *text, size_t length, const char *name,
                 scene_error *err)
{
    if (!parse_lines(text, length, name, err, parse_statement, s))
        return false;
    return true;
}

bool scene_load(scene *s, const char *path, scene_error *err)
{
    char *text;
    size_t length;
    scene_phase(s, "reading the scene"); /* its meshes too, from chapter 4 */
    if (!parse_read_file(path, SCENE_MAX_BYTES, &text, &length, err))
        return false;
    bool ok = scene_parse(s, text, length, path, err);
    free(text);
    return ok;
}
