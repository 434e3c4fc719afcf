/* scene_file.c: the statements of a scene file (chapter 1). */
#include "scene_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"
/* <<scene file includes>> ch03 */
#include "material_statement.h"
#include "light_statement.h"
/* <<scene file includes>> += ch04 */
#include "mesh_load.h"
/* <<scene file includes>> += ch05 */
#include "transform_parse.h"
/* <<scene file includes>> += ch08 */
#include "trees.h"

/* <<readers of settings>> ch03 */

static bool read_material_name(parser *p, const scene *s, int *material)
{
    if (!parse_next_token(p) ||
        (*material = material_statement_find(s, p)) < 0)
        return parse_expected(p, "expected the name of a material defined "
                                 "above");
    return true;
}
/* <<readers of settings>> += ch05 */

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

/* Stores t as the object's transform: a new one, or its own, replaced. */
static bool store_transform(parser *p, scene *s, object *o, transform t)
{
    if (o->transform != 0) {
        s->transforms[o->transform - 1] = t;
        return true;
    }
    if ((o->transform = scene_add_transform(s, t)) < 0)
        return parse_no_room(p, p->line, s->transform_count,
                             SCENE_MAX_TRANSFORMS, "transforms");
    return true;
}

/* 'transform STEP...': the steps, in the order written, after the
 * object's transform so far. */
static bool read_transform(parser *p, scene *s, object *o)
{
    transform t = o->transform != 0 ? *scene_transform(s, o->transform)
                                    : transform_identity();
    return transform_parse_steps(p, &t) && store_transform(p, s, o, t);
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
        /* a coordinate (at most 1e50) over the tile stays finite */
        return parse_number_in(p, "a tile size", 1e-50, 1e50, &o->tile);
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
/* <<the mesh statement's settings>> ch04 */
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
        return parse_number_in(p, "a scale", 1e-100, 1e100, &m->scale);
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

static bool parse_mesh(parser *p, scene *s)
{
    object o = {.kind = SHAPE_MESH, .color = {0.8, 0.8, 0.8}};
    mesh_settings m = {.scale = 1};
    char path[PARSE_MAX_NAME];
    if (!read_mesh_settings(p, s, &m, &o))
        return false;
    if (!resolve_path(p, m.file, m.file_length, path, sizeof path))
        return parse_fail_at(p, m.file, "the mesh file's path is too long");
    mesh_source source = {path, m.scale, m.offset, m.smooth, p->line_number};
    o.mesh = scene_find_mesh(s, &source); /* the file, read already? */
    if (o.mesh < 0 && (o.mesh = mesh_load_into(p, s, m.file, &source)) < 0)
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
            if (!parse_int_in(p, "a recursion depth", 0, SCENE_MAX_DEPTH,
                              &depth))
                return false;
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

/* A whole number from lo to hi into *out, an int. */
static bool read_int_in(parser *p, const char *what, long lo, long hi,
                        int *out)
{
    long n;
    if (!parse_int_in(p, what, lo, hi, &n))
        return false;
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
        return parse_number_in(p, "a traversal cost", 1e-6, 1e6,
                               &k->traversal_cost);
    if (parse_token_is(p, "intersection_cost"))
        return parse_number_in(p, "an intersection cost", 1e-6, 1e6,
                               &k->intersection_cost);
    if (parse_token_is(p, "empty_bonus"))
        return parse_number_below(p, "an empty bonus", 0, 1,
                                  &k->empty_bonus);
    if (parse_token_is(p, "max_depth"))
        return read_int_in(p, "a maximum depth", 1, KDTREE_MAX_DEPTH,
                           &k->max_depth);
    if (parse_token_is(p, "heatmap"))
        return read_int_in(p, "a number of nodes", 1, 1000000,
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
/* <<statements>> += ch09 */

static bool parse_accelerator(parser *p, scene *s)
{
    if (s->accelerator_line > 0)
        return parse_fail_at(p, p->token, "expected one accelerator "
                             "statement, found a second (the first is on "
                             "line %d)", s->accelerator_line);
    if (parse_next_token(p))
        for (int k = MESH_ACCELERATOR_KDTREE; k < MESH_ACCELERATORS; k++)
            if (parse_token_is(p, mesh_accelerator_name(k))) {
                s->accelerator = (mesh_accelerator)k;
                s->accelerator_line = p->line_number;
                return true;
            }
    /* <<the accelerators in words>> ch10 */
    const char *words = "kdtree, bvh, bvh-float"; /* for the message */
    return parse_expected(p, "expected an accelerator (%s)", words);
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
    /* <<scene keywords>> += ch04 */
    {"triangle", parse_triangle},
    {"mesh", parse_mesh},
    /* <<scene keywords>> += ch06 */
    {"recursion", parse_recursion},
    /* <<scene keywords>> += ch08 */
    {"kdtree", parse_kdtree},
    /* <<scene keywords>> += ch09 */
    {"accelerator", parse_accelerator},
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

/* <<what the scene needs once it is read>> ch06 */

/* One shaded point's shadow rays, over all lights: one for each light a
 * scene may have, so that every light keeps one. */
#define SCENE_SHADOW_RAY_BUDGET SCENE_MAX_LIGHTS

/* Cuts the area lights' samples in proportion until one shaded point asks
 * for no more than SCENE_SHADOW_RAY_BUDGET shadow rays. */
static void fit_shadow_budget(scene *s)
{
    long long lights = s->light_count, asked = scene_shadow_rays(s);
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
/* <<what the scene needs once it is read>> += ch08 */

/* The error of a failed build of the trees, in err; false. */
static bool tree_error(const scene *s, const char *name,
                       const scene_tree_failure *why, scene_error *err)
{
    parse_error_kind kind = why->over_budget ? PARSE_OVER_BUDGET
                                             : PARSE_NO_MEMORY;
    const char *problem = why->over_budget
                              ? "would pass the scene's budget of"
                              : "ran out of memory within the budget of";
    if (why->mesh < 0)
        return parse_fail_on_line(err, name, 0, kind, "the objects' kd-tree "
                                  "%s %lld bytes of geometry", problem,
                                  s->geometry_budget);
    const mesh_source *m = &s->meshes[why->mesh].source;
    const char *tree = "kd-tree";
    /* <<the name of the meshes' tree>> ch09 */
    if (scene_mesh_accelerator(s) != MESH_ACCELERATOR_KDTREE)
        tree = "BVH";
    return parse_fail_on_line(err, name, m->line, kind,
                              "the %s of mesh file '%s' %s %lld bytes "
                              "of geometry", tree, m->path, problem,
                              s->geometry_budget);
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
    scene_tree_failure why;
    scene_phase(s, "building the trees");
    if (!scene_build_trees(s, &why))
        return tree_error(s, name, &why, err);
    /* <<finish the scene>> += ch09 */
    if (s->heatmap > 0 && scene_mesh_accelerator(s) != MESH_ACCELERATOR_KDTREE)
        return parse_fail_on_line(
            err, name, s->accelerator_option ? 0 : s->accelerator_line,
            PARSE_BAD_INPUT, "the kdtree statement's heat map draws kd-tree "
            "nodes, and %s%s gives the meshes BVHs",
            s->accelerator_option ? "--accelerator " : "this statement",
            s->accelerator_option ? mesh_accelerator_name(s->accelerator_option)
                                  : "");
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
