/* scene_file.c: the statements of a scene file (chapter 1). */
#include "scene_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"

/* <<statement helpers>> ch03 */

/* The index of the material named by the token just read: 0 for "default",
 * k for the scene's k-th material, -1 if there is none of that name. */
static int find_material(const scene *s, const parser *p)
{
    if (parse_token_is(p, "default"))
        return 0;
    for (int k = 0; k < s->material_count; k++)
        if (parse_token_is(p, s->materials[k].name))
            return k + 1;
    return -1;
}

static bool read_material_name(parser *p, const scene *s, int *material)
{
    if (!parse_next_token(p) || (*material = find_material(s, p)) < 0)
        return parse_expected(p, "expected the name of a material defined "
                                 "above");
    return true;
}
/* <<statement helpers>> += ch04 */
#include "obj.h"
/* <<statement helpers>> += ch05 */

/* false, with err at the start of the camera statement that placed the
 * camera last, when its position, look_at and up make no frame. */
static bool check_camera_frame(const scene *s, const char *name,
                               scene_error *err)
{
    mat4 frame;
    const camera *cam = &s->cam;
    const char *why = "the camera's up is (nearly) along its view: up "
                      "cannot be told";
    if (!vec3_is_direction(vec3_sub(cam->look_at, cam->position)))
        why = "the camera's look_at point is its position: no direction "
              "to look in";
    else if (mat4_look_at(cam->position, cam->look_at, cam->up, &frame))
        return true;
    parse_copy_name(err->file, sizeof err->file, name);
    err->line = s->camera_placed_on, err->col = 1;
    err->kind = PARSE_BAD_INPUT;
    snprintf(err->message, sizeof err->message, "%s", why);
    return false;
}

static const char transform_step_names[] =
    "translate, scale, rotate, shear, matrix";

static bool read_rotation(parser *p, transform *step)
{
    vec3 axis;
    const char *rest = p->next;
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "x"))
        axis = (vec3){1, 0, 0};
    else if (named && parse_token_is(p, "y"))
        axis = (vec3){0, 1, 0};
    else if (named && parse_token_is(p, "z"))
        axis = (vec3){0, 0, 1};
    else {
        p->next = rest; /* not x, y or z: the axis as three numbers */
        if (!parse_direction(p, "a rotation axis (x, y, z or 3 numbers)",
                             &axis))
            return false;
    }
    double deg;
    if (!parse_number(p, "an angle in degrees", &deg))
        return false;
    *step = transform_rotate(axis, deg);
    return true;
}

static bool read_shear(parser *p, transform *step)
{
    bool named = parse_next_token(p);
    bool yz = named && parse_token_is(p, "yz"),
         xz = named && parse_token_is(p, "xz"),
         xy = named && parse_token_is(p, "xy");
    if (!yz && !xz && !xy)
        return parse_expected(p, "expected the plane of a shear: yz, xz or "
                                 "xy");
    double a, b;
    if (!parse_number(p, "a shear factor", &a) ||
        !parse_number(p, "a shear factor", &b))
        return false;
    *step = transform_shear(yz   ? mat4_shear_yz(a, b)
                            : xz ? mat4_shear_xz(a, b)
                                 : mat4_shear_xy(a, b));
    return true;
}

static bool read_matrix(parser *p, const char *at, transform *step)
{
    mat4 m = mat4_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            if (!parse_number(p, "a matrix entry (3 rows of 4 numbers)",
                              &m.m[i][j]))
                return false;
    if (!transform_of_matrix(m, step))
        return parse_fail_at(p, at, "the matrix is singular: its "
                                    "determinant is 0 or not finite");
    return true;
}

/* The step the token just read names, into *step; *known is false when it
 * names none. */
static bool read_step(parser *p, const char *at, transform *step,
                      bool *known)
{
    vec3 v;
    *known = true;
    if (parse_token_is(p, "translate") || parse_token_is(p, "scale")) {
        bool moves = parse_token_is(p, "translate");
        if (!parse_point(p, moves ? "a translation" : "a scale factor", &v))
            return false;
        *step = moves ? transform_translate(v) : transform_scale(v);
        return true;
    }
    if (parse_token_is(p, "rotate"))
        return read_rotation(p, step);
    if (parse_token_is(p, "shear"))
        return read_shear(p, step);
    if (parse_token_is(p, "matrix"))
        return read_matrix(p, at, step);
    *known = false;
    return true;
}

/* Why the scene cannot use t, or NULL when it can. */
static const char *transform_problem(const transform *t)
{
    if (!mat4_is_finite(t->m) || !(mat4_norm3(t->m) <= SCENE_MAX_STRETCH))
        return "this step makes the transform stretch some direction by "
               "more than 1e12";
    if (!mat4_is_finite(t->inv) ||
        !(mat4_norm3(t->inv) <= SCENE_MAX_STRETCH))
        return "this step makes the transform singular or nearly so: it "
               "shrinks some direction by more than 1e12";
    for (int i = 0; i < 3; i++)
        if (!(fabs(t->m.m[i][3]) <= PARSE_MAX_COORDINATE))
            return "this step moves the object's origin beyond 1e50";
    return NULL;
}

/* Stores t as the object's transform: a new one, or its own, replaced. */
static bool store_transform(parser *p, scene *s, object *o, transform t)
{
    if (o->transform != 0) {
        s->transforms[o->transform - 1] = t;
        return true;
    }
    if ((o->transform = scene_add_transform(s, t)) < 0)
        return parse_fail_at(p, p->line, "more than %d transforms (or out "
                                         "of memory)", SCENE_MAX_TRANSFORMS);
    return true;
}

/* 'transform STEP...': the steps, in the order written, after the
 * object's transform so far. */
static bool read_transform(parser *p, scene *s, object *o)
{
    transform t = o->transform != 0 ? *scene_transform(s, o->transform)
                                    : transform_identity();
    int steps = 0;
    for (;; steps++) {
        const char *rest = p->next;
        if (!parse_next_token(p))
            break;
        const char *at = p->token;
        transform step;
        bool known;
        if (!read_step(p, at, &step, &known))
            return false;
        if (!known) {
            p->next = rest; /* not a step: the statement's next setting */
            break;
        }
        t = transform_then(t, step);
        const char *problem = transform_problem(&t);
        if (problem != NULL)
            return parse_fail_at(p, at, "%s", problem);
    }
    if (steps == 0)
        return parse_expected(p, "expected a transform step (%s)",
                              transform_step_names);
    return store_transform(p, s, o, t);
}
/* <<statement helpers>> += ch06 */

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
        if (!parse_int(p, "a number of samples", &n))
            return false;
        if (n < 1 || n > AREA_LIGHT_MAX_SAMPLES)
            return parse_expected(p, "expected a number of samples from 1 "
                                     "to %d", AREA_LIGHT_MAX_SAMPLES);
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
        return parse_fail_at(p, p->line, "more than %d lights",
                             SCENE_MAX_LIGHTS);
    return true;
}

/* One shaded point's shadow rays, over all lights: one for each light a
 * scene may have, so that every light keeps one. */
#define SCENE_SHADOW_RAY_BUDGET SCENE_MAX_LIGHTS

/* Cuts the area lights' samples in proportion until one shaded point asks
 * for no more than SCENE_SHADOW_RAY_BUDGET shadow rays. */
static void fit_shadow_budget(scene *s)
{
    long long lights = s->light_count, asked = 0;
    for (int k = 0; k < s->light_count; k++)
        asked += s->lights[k].kind == LIGHT_AREA ? s->lights[k].samples : 1;
    if (asked <= SCENE_SHADOW_RAY_BUDGET)
        return;
    long long spare = SCENE_SHADOW_RAY_BUDGET - lights; /* beyond one each */
    for (int k = 0; k < s->light_count; k++) {
        light *L = &s->lights[k];
        if (L->kind != LIGHT_AREA)
            continue;
        int kept = 1 + (int)((L->samples - 1) * spare / (asked - lights));
        L->samples_cut += L->samples - kept;
        L->samples = kept;
    }
}
/* <<statement helpers>> += ch07 */

static bool read_ior(parser *p, double *ior)
{
    if (!parse_number(p, "a refractive index", ior))
        return false;
    if (!(*ior >= 1e-3 && *ior <= 1e3)) /* eta^2 stays far from overflow */
        return parse_expected(
            p, "expected a refractive index from 0.001 to 1000");
    return true;
}

static bool read_fresnel_model(parser *p, int *model)
{
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "exact"))
        *model = FRESNEL_EXACT;
    else if (named && parse_token_is(p, "schlick"))
        *model = FRESNEL_SCHLICK;
    else
        return parse_expected(p, "expected 'exact' or 'schlick'");
    return true;
}

static bool read_tile(parser *p, double *tile)
{
    if (!parse_number(p, "a tile size", tile))
        return false;
    /* a coordinate (at most 1e50) over the tile stays finite */
    if (!(*tile >= 1e-50 && *tile <= 1e50))
        return parse_expected(p, "expected a tile size between 1e-50 and "
                                 "1e50");
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
        /* <<camera settings>> ch05 */
        else if (parse_token_is(p, "position")) {
            if (!parse_point(p, "a camera position coordinate", &s->cam.position))
                return false;
            s->camera_placed_on = p->line_number;
        }
        else if (parse_token_is(p, "look_at")) {
            if (!parse_point(p, "a look_at coordinate", &s->cam.look_at))
                return false;
            s->camera_placed_on = p->line_number;
        }
        else if (parse_token_is(p, "up")) {
            if (!parse_direction(p, "an up direction", &s->cam.up))
                return false;
            s->camera_placed_on = p->line_number;
        }
        else
            return parse_expected(p, "expected a camera setting such as "
                                     "'fov'");
    } while (parse_next_token(p));
    return true;
}

/* <<image statement>> ch01 */
static bool read_side(parser *p, const char *what, int *out)
{
    long n = 0;
    if (!parse_int(p, what, &n))
        return false;
    if (n < 1 || n > IMAGE_MAX_SIDE)
        return parse_expected(p, "expected %s from 1 to %d pixels", what,
                              IMAGE_MAX_SIDE);
    *out = (int)n;
    return true;
}

static bool parse_image(parser *p, scene *s)
{
    int w = 0, h = 0; /* set by read_side before any use */
    if (!read_side(p, "an image width", &w) ||
        !read_side(p, "an image height", &h))
        return false;
    if ((long)w * h > IMAGE_MAX_PIXELS)
        return parse_expected(p, "expected at most %ld pixels in all "
                                 "(%dx%d is %ld)",
                              IMAGE_MAX_PIXELS, w, h, (long)w * h);
    s->cam.width = w;
    s->cam.height = h;
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
    /* <<names of object settings>> += ch05 */
    ", transform"
    /* <<names of object settings>> += ch07 */
    ", checker, tile"
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
    /* <<object settings>> += ch05 */
    if (parse_token_is(p, "transform"))
        return read_transform(p, s, o);
    /* <<object settings>> += ch07 */
    if (parse_token_is(p, "checker")) {
        o->checkered = true;
        return parse_color(p, "a checker colour component", &o->checker);
    }
    if (parse_token_is(p, "tile"))
        return read_tile(p, &o->tile);
    *known = false;
    return true;
}

static bool read_radius(parser *p, double *radius)
{
    if (!parse_number(p, "a radius", radius))
        return false;
    if (!(*radius >= 1e-50 && *radius <= 1e50))
        return parse_expected(p, "expected a radius between 1e-50 and 1e50");
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
            ok = read_radius(p, &o.sphere.radius);
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

static const char material_setting_names[] =
    "emission, ambient, diffuse, specular, shininess, highlight"
    /* <<names of material settings>> ch06 */
    ", reflect"
    /* <<names of material settings>> += ch07 */
    ", ior, transparency, fresnel"
    ;

static bool read_highlight_model(parser *p, material *m)
{
    bool named = parse_next_token(p);
    if (named && parse_token_is(p, "phong"))
        m->highlight = HIGHLIGHT_PHONG;
    else if (named && parse_token_is(p, "blinn"))
        m->highlight = HIGHLIGHT_BLINN;
    else
        return parse_expected(p, "expected 'phong' or 'blinn'");
    return true;
}

static bool read_material_setting(parser *p, material *m)
{
    if (parse_token_is(p, "emission"))
        return parse_color(p, "an emitted intensity", &m->emission);
    if (parse_token_is(p, "ambient"))
        return parse_coefficient(p, "an ambient coefficient", &m->ambient);
    if (parse_token_is(p, "diffuse"))
        return parse_coefficient(p, "a diffuse coefficient", &m->diffuse);
    if (parse_token_is(p, "specular"))
        return parse_coefficient(p, "a specular coefficient", &m->specular);
    if (parse_token_is(p, "shininess")) {
        if (!parse_number(p, "a shininess", &m->shininess))
            return false;
        return m->shininess >= 1 ||
               parse_expected(p, "expected a shininess of at least 1");
    }
    if (parse_token_is(p, "highlight"))
        return read_highlight_model(p, m);
    /* <<material settings>> ch06 */
    if (parse_token_is(p, "reflect"))
        return parse_coefficient(p, "a reflectivity", &m->reflect);
    /* <<material settings>> += ch07 */
    if (parse_token_is(p, "ior"))
        return read_ior(p, &m->ior);
    if (parse_token_is(p, "transparency"))
        return parse_coefficient(p, "a transparency", &m->transparency);
    if (parse_token_is(p, "fresnel"))
        return read_fresnel_model(p, &m->fresnel);
    return parse_expected(p, "expected a material setting (%s)",
                          material_setting_names);
}

/* <<the material statement>> ch03 */
static bool parse_material(parser *p, scene *s)
{
    material m = material_default();
    if (!parse_next_token(p) || p->token_length >= (int)sizeof m.name)
        return parse_expected(p,
                              "expected a material name of 1 to %d characters",
                              (int)sizeof m.name - 1);
    int existing = find_material(s, p);
    bool redefining_default = existing == 0 && s->default_material.line == 0;
    if (existing >= 0 && !redefining_default)
        return parse_expected(
            p, "expected a new material name (defined on line %d)",
            scene_material(s, existing)->line);
    memcpy(m.name, p->token, (size_t)p->token_length);
    m.name[p->token_length] = '\0';
    m.line = p->line_number;
    while (parse_next_token(p))
        if (!read_material_setting(p, &m))
            return false;
    if (redefining_default)
        s->default_material = m;
    else if (!scene_add_material(s, m))
        return parse_no_room(p, p->line, s->material_count,
                             SCENE_MAX_MATERIALS, "materials");
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
        [LIGHT_SPOT] = "position, direction, angle, exponent, intensity, "
                       "attenuation",
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

static bool parse_light(parser *p, scene *s)
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
/* <<statements>> += ch04 */

/* <<the triangle statement>> ch04 */
static bool parse_triangle(parser *p, scene *s)
{
    object o = {.kind = SHAPE_TRIANGLE, .color = {0.8, 0.8, 0.8},
                .corners = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}}};
    while (parse_next_token(p)) {
        int k = parse_token_is(p, "a")   ? 0
                : parse_token_is(p, "b") ? 1
                : parse_token_is(p, "c") ? 2
                                         : -1;
        bool ok, known = true;
        if (k >= 0)
            ok = parse_point(p, "a corner coordinate", &o.corners[k]);
        else
            ok = parse_object_setting(p, s, &o, &known);
        if (!known)
            return parse_expected(p, "expected a triangle setting "
                                     "(a, b, c, %s)", object_setting_names);
        if (!ok)
            return false;
    }
    if (!scene_add_object(s, o))
        return parse_no_room(p, p->line, s->object_count, SCENE_MAX_OBJECTS,
                             "objects");
    return true;
}

/* <<the mesh statement>> ch04 */
/* PATH of the token, relative to the folder of the file being parsed. */
static bool resolve_path(const parser *p, const char *token, int length,
                         char *out, size_t size)
{
    const char *slash = strrchr(p->name, '/');
    int folder =
        token[0] == '/' || slash == NULL ? 0 : (int)(slash - p->name) + 1;
    return snprintf(out, size, "%.*s%.*s", folder, p->name, length, token) <
           (int)size;
}

/* What the scene's budget leaves for one more mesh. */
static mesh_budget budget_left(const scene *s)
{
    long long triangles = s->triangle_budget - s->triangle_total;
    long long bytes = s->geometry_budget - s->geometry_total;
    triangles = triangles < MESH_MAX_TRIANGLES ? triangles
                                               : MESH_MAX_TRIANGLES;
    return (mesh_budget){triangles > 0 ? (long)triangles : 0,
                         bytes > 0 ? bytes : 0};
}

/* Moves an error that is not the OBJ text's fault to the scene line that
 * named the file (at file); false. */
static bool mesh_file_error(parser *p, const scene *s, const char *file,
                            const char *path)
{
    parse_error *err = p->err;
    char why[sizeof err->message];
    snprintf(why, sizeof why, "%s", err->message);
    int line = err->line;
    if (err->kind == PARSE_CANNOT_READ)
        return parse_fail_with(p, err->kind, file,
                               "cannot read mesh file '%s': %s", path, why);
    if (err->kind == PARSE_OVER_BUDGET)
        return parse_fail_with(
            p, err->kind, file,
            "mesh file '%s' would pass the scene's budget of %lld triangles "
            "and %lld bytes of geometry: at its line %d, %s",
            path, s->triangle_budget, s->geometry_budget, line, why);
    if (line == 0)
        return parse_fail_with(p, PARSE_NO_MEMORY, file, "mesh file '%s': %s",
                               path, why);
    return parse_fail_with(p, PARSE_NO_MEMORY, file,
                           "mesh file '%s': %s (at its line %d)", path, why,
                           line);
}

static bool load_mesh_file(parser *p, const scene *s, const char *file,
                           const char *path, mesh *m)
{
    if (mesh_load_obj_within(m, path, budget_left(s), p->err))
        return true;
    if (p->err->kind == PARSE_BAD_INPUT)
        return false; /* the OBJ file's own line and column */
    return mesh_file_error(p, s, file, path);
}

/* <<placing a mesh>> ch04 */
static bool read_scale(parser *p, double *scale)
{
    if (!parse_number(p, "a scale", scale))
        return false;
    return (*scale >= 1e-100 && *scale <= 1e100) ||
           parse_expected(p, "expected a scale between 1e-100 and 1e100");
}

static bool smooth_within_budget(parser *p, const scene *s, mesh *m)
{
    long long normals = ((long long)m->vertex_count + 1) * sizeof(vec3);
    long long corners =
        ((long long)m->triangle_count + 1) * sizeof(mesh_triangle);
    if (mesh_bytes(m) + normals + corners > budget_left(s).bytes)
        return parse_fail_with(p, PARSE_OVER_BUDGET, p->line,
                               "the mesh's smooth normals would pass the "
                               "scene's budget of %lld bytes of geometry",
                               s->geometry_budget);
    return mesh_smooth_normals(m) ||
           parse_fail_with(p, PARSE_NO_MEMORY, p->line,
                           "out of memory for the mesh's normals");
}

static bool place_mesh(parser *p, const scene *s, mesh *m,
                       const mesh_source *source)
{
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = vec3_add(vec3_scale(m->vertices[k], source->scale),
                          source->offset);
        double largest = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
        if (!(largest <= PARSE_MAX_COORDINATE))
            return parse_fail_at(
                p, p->line,
                "vertex %d of the mesh lies beyond 1e50 once placed", k + 1);
        m->vertices[k] = v;
    }
    if (source->smooth && m->normal_count == 0 &&
        !smooth_within_budget(p, s, m))
        return false;
    mesh_compute_bounds(m);
    return true;
}

/* Reads, places and adds the mesh of source, named by the token at file:
 * its index in the scene, or -1 with the error filled. */
static int add_mesh_file(parser *p, scene *s, const char *file,
                         const mesh_source *source)
{
    mesh m = {0};
    int k = -1;
    if (load_mesh_file(p, s, file, source->path, &m) &&
        place_mesh(p, s, &m, source)) {
        m.source = *source;
        if ((m.source.path = strdup(source->path)) == NULL)
            parse_fail_with(p, PARSE_NO_MEMORY, p->line, "out of memory");
        else if ((k = scene_add_mesh(s, m)) < 0)
            parse_no_room(p, p->line, s->mesh_count, SCENE_MAX_MESHES,
                          "meshes");
    }
    if (k < 0)
        mesh_free(&m);
    return k;
}

/* The settings of a mesh statement that are not every object's. */
typedef struct {
    const char *file; /* the token naming the file; NULL: none yet */
    int file_length;
    double scale;
    vec3 offset;
    bool smooth;
} mesh_settings;

static bool read_mesh_setting(parser *p, mesh_settings *m, bool *known)
{
    *known = true;
    if (parse_token_is(p, "file")) {
        if (!parse_next_token(p))
            return parse_expected(p, "expected the name of an OBJ file");
        m->file = p->token, m->file_length = p->token_length;
        return true;
    }
    if (parse_token_is(p, "scale"))
        return read_scale(p, &m->scale);
    if (parse_token_is(p, "offset"))
        return parse_point(p, "an offset coordinate", &m->offset);
    if (parse_token_is(p, "smooth"))
        return m->smooth = true;
    *known = false;
    return true;
}

static bool read_mesh_settings(parser *p, scene *s, mesh_settings *m,
                               object *o)
{
    while (parse_next_token(p)) {
        bool known;
        bool ok = read_mesh_setting(p, m, &known);
        if (!known)
            ok = parse_object_setting(p, s, o, &known);
        if (!known)
            return parse_expected(p, "expected a mesh setting (file, scale, "
                                     "offset, smooth, %s)",
                                  object_setting_names);
        if (!ok)
            return false;
    }
    return m->file != NULL ||
           parse_expected(p, "expected 'file PATH': a mesh needs an OBJ "
                             "file");
}

static bool parse_mesh(parser *p, scene *s)
{
    object o = {.kind = SHAPE_MESH, .color = {0.8, 0.8, 0.8}};
    mesh_settings m = {.scale = 1};
    char path[PARSE_MAX_NAME];
    if (!read_mesh_settings(p, s, &m, &o))
        return false;
    if (!resolve_path(p, m.file, m.file_length, path, sizeof path))
        return parse_fail_at(p, m.file, "the mesh file's path is too long");
    mesh_source source = {path, m.scale, m.offset, m.smooth};
    o.mesh = scene_find_mesh(s, &source); /* the file, read already? */
    if (o.mesh < 0 && (o.mesh = add_mesh_file(p, s, m.file, &source)) < 0)
        return false;
    if (s->meshes[o.mesh].triangle_count == 0)
        return true; /* nothing to see: no object, no box to test */
    if (!scene_add_object(s, o))
        return parse_no_room(p, p->line, s->object_count, SCENE_MAX_OBJECTS,
                             "objects");
    return true;
}
/* <<statements>> += ch06 */

#define SCENE_MAX_DEPTH 100 /* a guarantee, not a budget: see chapter 6 */

static bool parse_recursion(parser *p, scene *s)
{
    if (!parse_next_token(p))
        return parse_expected(p, "expected 'depth' or 'cutoff'");
    do {
        if (parse_token_is(p, "depth")) {
            long depth;
            if (!parse_int(p, "a recursion depth", &depth))
                return false;
            if (depth < 0 || depth > SCENE_MAX_DEPTH)
                return parse_expected(p, "expected a recursion depth from "
                                         "0 to %d", SCENE_MAX_DEPTH);
            s->max_depth = (int)depth;
        } else if (parse_token_is(p, "cutoff")) {
            if (!parse_coefficient(p, "a contribution cutoff", &s->cutoff))
                return false;
        } else {
            return parse_expected(p, "expected 'depth' or 'cutoff'");
        }
    } while (parse_next_token(p));
    return true;
}
/* <<statements>> += ch08 */

/* <<the kdtree statement>> ch08 */
static bool read_build_method(parser *p, kdtree_method *method)
{
    /* in the order of kdtree_method */
    static const char *names[] = {"sah", "sorting", "median", "none"};
    if (parse_next_token(p))
        for (int k = 0; k < 4; k++)
            if (parse_token_is(p, names[k]))
                return *method = (kdtree_method)k, true;
    return parse_expected(p, "expected a build method (sah, sorting, "
                             "median, none)");
}

/* A number in [lo, hi] (in [lo, hi) when open_hi) into *out. */
static bool read_in_range(parser *p, const char *what, double lo, double hi,
                          bool open_hi, double *out)
{
    double x;
    if (!parse_number(p, what, &x))
        return false;
    if (!(x >= lo && (open_hi ? x < hi : x <= hi)))
        return parse_expected(p, "expected %s from %g to %g%s", what, lo, hi,
                              open_hi ? " (not included)" : "");
    *out = x;
    return true;
}

static bool read_whole_in_range(parser *p, const char *what, long lo,
                                long hi, int *out)
{
    long n;
    if (!parse_int(p, what, &n))
        return false;
    if (n < lo || n > hi)
        return parse_expected(p, "expected %s from %ld to %ld", what, lo, hi);
    *out = (int)n;
    return true;
}

static bool read_kdtree_setting(parser *p, scene *s, bool *known)
{
    kdtree_params *k = &s->tree_params;
    *known = true;
    if (parse_token_is(p, "build"))
        return read_build_method(p, &k->method);
    if (parse_token_is(p, "traversal_cost")) /* a cost is relative: > 0 */
        return read_in_range(p, "a traversal cost", 1e-6, 1e6, false,
                             &k->traversal_cost);
    if (parse_token_is(p, "intersection_cost"))
        return read_in_range(p, "an intersection cost", 1e-6, 1e6, false,
                             &k->intersection_cost);
    if (parse_token_is(p, "empty_bonus"))
        return read_in_range(p, "an empty bonus", 0, 1, true,
                             &k->empty_bonus);
    if (parse_token_is(p, "max_depth"))
        return read_whole_in_range(p, "a maximum depth", 1,
                                   KDTREE_MAX_DEPTH, &k->max_depth);
    if (parse_token_is(p, "heatmap"))
        return read_whole_in_range(p, "a number of nodes", 1, 1000000,
                                   &s->heatmap);
    *known = false;
    return true;
}

static bool parse_kdtree(parser *p, scene *s)
{
    bool known = false;
    while (parse_next_token(p)) {
        if (!read_kdtree_setting(p, s, &known))
            return false;
        if (!known)
            break;
    }
    if (known)
        return true;
    return parse_expected(p, "expected a kd-tree setting (build, "
                             "traversal_cost, intersection_cost, "
                             "empty_bonus, max_depth, heatmap)");
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
    {"material", parse_material},
    {"light", parse_light},
    /* <<scene keywords>> += ch04 */
    {"triangle", parse_triangle},
    {"mesh", parse_mesh},
    /* <<scene keywords>> += ch06 */
    {"recursion", parse_recursion},
    /* <<scene keywords>> += ch08 */
    {"kdtree", parse_kdtree},
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
    /* <<finish the scene>> ch05 */
    s->cam.is_placed = s->camera_placed_on > 0;
    if (s->cam.is_placed && !check_camera_frame(s, name, err))
        return false;
    /* <<finish the scene>> += ch06 */
    fit_shadow_budget(s);
    /* <<finish the scene>> += ch08 */
    if (!scene_build_trees(s)) {
        snprintf(err->file, sizeof err->file, "%s", name);
        err->line = err->col = 0;
        snprintf(err->message, sizeof err->message,
                 "out of memory for the kd-trees");
        return false;
    }
    return true;
}

bool scene_load(scene *s, const char *path, scene_error *err)
{
    char *text;
    size_t length;
    if (!parse_read_file(path, SCENE_MAX_BYTES, &text, &length, err))
        return false;
    bool ok = scene_parse(s, text, length, path, err);
    free(text);
    return ok;
}
