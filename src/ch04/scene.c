/* scene.c: scene defaults and the scene file parser (chapter 01). */
#include "scene.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"

typedef struct {
    const char *name;        /* file name, for errors */
    const char *line, *end;  /* current line [line, end) */
    const char *next;        /* where the next token search starts */
    int line_number;
    const char *token;       /* last token read: [token, token + token_length) */
    int token_length;
    scene_error *err;
} parser;

static int column_of(const parser *p, const char *at) { return (int)(at - p->line) + 1; }

static bool fail_at(parser *p, const char *at, const char *format, ...)
{
    scene_error *err = p->err;
    snprintf(err->file, sizeof err->file, "%s", p->name);
    err->line = p->line_number;
    err->col = column_of(p, at);
    va_list args;
    va_start(args, format);
    vsnprintf(err->message, sizeof err->message, format, args);
    va_end(args);
    return false;
}

/* "EXPECTATION, found 'TOKEN'", located at the token just read. */
static bool expected(parser *p, const char *format, ...)
{
    char what[160];
    va_list args;
    va_start(args, format);
    vsnprintf(what, sizeof what, format, args);
    va_end(args);
    if (p->token_length == 0)
        return fail_at(p, p->token, "%s, found end of line", what);
    int shown = p->token_length > 40 ? 40 : p->token_length;
    return fail_at(p, p->token, "%s, found '%.*s%s'", what, shown, p->token,
                   shown < p->token_length ? "..." : "");
}

static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

static bool next_token(parser *p)
{
    const char *c = p->next;
    while (c < p->end && is_blank(*c))
        c++;
    p->token = c;
    p->token_length = 0;
    if (c == p->end || *c == '#')
        return false;
    while (c < p->end && !is_blank(*c))
        c++;
    p->token_length = (int)(c - p->token);
    p->next = c;
    return true;
}

static bool token_is(const parser *p, const char *word)
{
    return (size_t)p->token_length == strlen(word) &&
           memcmp(p->token, word, (size_t)p->token_length) == 0;
}

/* Reads the next token as a finite number; what names it in errors. */
static bool read_number(parser *p, const char *what, double *out)
{
    char text[64];
    if (!next_token(p) || p->token_length >= (int)sizeof text)
        return expected(p, "expected %s", what);
    memcpy(text, p->token, (size_t)p->token_length);
    text[p->token_length] = '\0';
    char *stop;
    double value = strtod(text, &stop);
    if (stop == text || *stop != '\0')
        return expected(p, "expected %s", what);
    if (!isfinite(value))
        return expected(p, "expected %s (a finite number)", what);
    *out = value;
    return true;
}

static bool read_int(parser *p, const char *what, long *out)
{
    double value;
    if (!read_number(p, what, &value))
        return false;
    if (value != floor(value) || fabs(value) > 1e15) /* 1e15: exact in a double */
        return expected(p, "expected %s (a whole number)", what);
    *out = (long)value;
    return true;
}

/* Light adds up and is multiplied; keeping every colour and intensity at
 * most 1e6 keeps any sum of products far from overflowing to infinity. */
#define SCENE_MAX_INTENSITY 1e6

static bool read_color(parser *p, const char *what, vec3 *out)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        if (!read_number(p, what, &c[k]))
            return false;
        if (!(c[k] >= 0 && c[k] <= SCENE_MAX_INTENSITY))
            return expected(p, "expected %s from 0 to 1e6", what);
    }
    *out = (vec3){c[0], c[1], c[2]};
    return true;
}

#define SCENE_MAX_COORDINATE 1e50 /* fourth powers of coordinates stay finite */

static bool read_point(parser *p, const char *what, vec3 *out)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        if (!read_number(p, what, &c[k]))
            return false;
        if (fabs(c[k]) > SCENE_MAX_COORDINATE)
            return expected(p, "expected %s between -1e50 and 1e50", what);
    }
    *out = (vec3){c[0], c[1], c[2]};
    return true;
}

/* A coefficient rho in [0, 1], as the sheet requires of rho_a, rho_d, rho_s. */
static bool read_coefficient(parser *p, const char *what, double *out)
{
    if (!read_number(p, what, out))
        return false;
    if (!(*out >= 0 && *out <= 1))
        return expected(p, "expected %s from 0 to 1", what);
    return true;
}

/* The index of the material named by the token just read: 0 for "default",
 * k for the scene's k-th material, -1 if there is none of that name. */
static int find_material(const scene *s, const parser *p)
{
    if (token_is(p, "default"))
        return 0;
    for (int k = 0; k < s->material_count; k++)
        if (token_is(p, s->materials[k].name))
            return k + 1;
    return -1;
}

/* A direction: three numbers, not all zero, returned as a unit vector. */
static bool read_direction(parser *p, const char *what, vec3 *out)
{
    const char *first = p->next;
    if (!read_point(p, what, out))
        return false;
    while (is_blank(*first))
        first++;
    if (!(vec3_dot(*out, *out) > 0)) /* also too short to square */
        return fail_at(p, first, "expected %s of non-zero length", what);
    *out = vec3_normalize(*out);
    return true;
}

static bool read_material_name(parser *p, const scene *s, int *material)
{
    if (!next_token(p) || (*material = find_material(s, p)) < 0)
        return expected(p, "expected the name of a material defined above");
    return true;
}

/* Room for one more element: returns items (moved if it had to grow), or
 * NULL, leaving items as they were, at max or when memory runs out. */
static void *grow_array(void *items, int count, int *capacity, int max, size_t size)
{
    if (count < *capacity)
        return items;
    if (*capacity >= max)
        return NULL;
    int wanted = *capacity ? 2 * *capacity : 8;
    wanted = wanted < max ? wanted : max;
    void *grown = realloc(items, (size_t)wanted * size);
    if (grown != NULL)
        *capacity = wanted;
    return grown;
}

bool scene_add_sphere(scene *s, sphere sp)
{
    sphere *grown = grow_array(s->spheres, s->sphere_count, &s->sphere_capacity,
                               SCENE_MAX_SPHERES, sizeof sp);
    if (grown == NULL)
        return false;
    s->spheres = grown;
    s->spheres[s->sphere_count++] = sp;
    return true;
}

const material *scene_material(const scene *s, int index)
{
    return index == 0 ? &s->default_material : &s->materials[index - 1];
}

bool scene_add_material(scene *s, material m)
{
    material *grown = grow_array(s->materials, s->material_count, &s->material_capacity,
                                 SCENE_MAX_MATERIALS, sizeof m);
    if (grown == NULL)
        return false;
    s->materials = grown;
    s->materials[s->material_count++] = m;
    return true;
}

bool scene_add_light(scene *s, light L)
{
    light *grown = grow_array(s->lights, s->light_count, &s->light_capacity, SCENE_MAX_LIGHTS,
                              sizeof L);
    if (grown == NULL)
        return false;
    s->lights = grown;
    s->lights[s->light_count++] = L;
    return true;
}

bool scene_add_mesh(scene *s, mesh m)
{
    mesh *grown = grow_array(s->meshes, s->mesh_count, &s->mesh_capacity, SCENE_MAX_MESHES,
                             sizeof m);
    if (grown == NULL)
        return false;
    s->meshes = grown;
    s->meshes[s->mesh_count++] = m;
    return true;
}

static bool parse_camera(parser *p, scene *s)
{
    if (!next_token(p))
        return expected(p, "expected a camera setting such as 'fov'");
    do {
        if (token_is(p, "fov")) {
            double fov;
            if (!read_number(p, "a field of view in degrees", &fov))
                return false;
            if (!(fov > 0 && fov < 180))
                return expected(p, "expected a field of view between 0 and 180 degrees");
            s->cam.fov_deg = fov;
        }
        else
            return expected(p, "expected a camera setting such as 'fov'");
    } while (next_token(p));
    return true;
}

static bool read_side(parser *p, const char *what, int *out)
{
    long n = 0;
    if (!read_int(p, what, &n))
        return false;
    if (n < 1 || n > IMAGE_MAX_SIDE)
        return expected(p, "expected %s from 1 to %d pixels", what, IMAGE_MAX_SIDE);
    *out = (int)n;
    return true;
}

static bool parse_image(parser *p, scene *s)
{
    int w, h;
    if (!read_side(p, "an image width", &w) || !read_side(p, "an image height", &h))
        return false;
    if ((long)w * h > IMAGE_MAX_PIXELS)
        return expected(p, "expected at most %ld pixels in all (%dx%d is %ld)",
                        IMAGE_MAX_PIXELS, w, h, (long)w * h);
    s->cam.width = w;
    s->cam.height = h;
    return true;
}

static bool parse_background(parser *p, scene *s)
{
    const char *rest = p->next;
    if (next_token(p) && token_is(p, "gradient")) {
        s->bg.kind = BACKGROUND_GRADIENT;
        return read_color(p, "a bottom colour component", &s->bg.bottom) &&
               read_color(p, "a top colour component", &s->bg.top);
    }
    p->next = rest; /* not "gradient": read that token again as a number */
    s->bg.kind = BACKGROUND_SOLID;
    return read_color(p, "a colour component", &s->bg.bottom);
}

static bool read_radius(parser *p, double *radius)
{
    if (!read_number(p, "a radius", radius))
        return false;
    if (!(*radius >= 1e-50 && *radius <= 1e50))
        return expected(p, "expected a radius between 1e-50 and 1e50");
    return true;
}

static bool parse_sphere(parser *p, scene *s)
{
    sphere sp = {.center = {0, 0, 5}, .radius = 1, .color = {0.8, 0.8, 0.8}};
    while (next_token(p)) {
        if (token_is(p, "center")) {
            if (!read_point(p, "a centre coordinate", &sp.center))
                return false;
        } else if (token_is(p, "radius")) {
            if (!read_radius(p, &sp.radius))
                return false;
        } else if (token_is(p, "color")) {
            if (!read_color(p, "a colour component", &sp.color))
                return false;
        }
        else if (token_is(p, "material")) {
            if (!read_material_name(p, s, &sp.material))
                return false;
        }
        else
            return expected(p, "expected a sphere setting (center, radius, color)");
    }
    if (!scene_add_sphere(s, sp))
        return fail_at(p, p->line, "more than %d spheres", SCENE_MAX_SPHERES);
    return true;
}

static material default_finish(void)
{
    return (material){.name = "default", .ambient = 0.1, .diffuse = 0.8, .specular = 0.3,
                      .shininess = 20, .highlight = HIGHLIGHT_PHONG};
}

static bool read_material_setting(parser *p, material *m)
{
    if (token_is(p, "emission"))
        return read_color(p, "an emitted intensity", &m->emission);
    if (token_is(p, "ambient"))
        return read_coefficient(p, "an ambient coefficient", &m->ambient);
    if (token_is(p, "diffuse"))
        return read_coefficient(p, "a diffuse coefficient", &m->diffuse);
    if (token_is(p, "specular"))
        return read_coefficient(p, "a specular coefficient", &m->specular);
    if (token_is(p, "shininess")) {
        if (!read_number(p, "a shininess", &m->shininess))
            return false;
        return m->shininess >= 1 || expected(p, "expected a shininess of at least 1");
    }
    if (token_is(p, "highlight")) {
        bool named = next_token(p);
        if (named && token_is(p, "phong"))
            m->highlight = HIGHLIGHT_PHONG;
        else if (named && token_is(p, "blinn"))
            m->highlight = HIGHLIGHT_BLINN;
        else
            return expected(p, "expected 'phong' or 'blinn'");
        return true;
    }
    return expected(p, "expected a material setting (emission, ambient, diffuse, specular, "
                       "shininess, highlight)");
}

static bool parse_material(parser *p, scene *s)
{
    material m = default_finish();
    if (!next_token(p) || p->token_length >= (int)sizeof m.name)
        return expected(p, "expected a material name of 1 to %d characters",
                        (int)sizeof m.name - 1);
    int existing = find_material(s, p);
    bool redefining_default = existing == 0 && s->default_material.line == 0;
    if (existing >= 0 && !redefining_default)
        return expected(p, "expected a new material name (defined on line %d)",
                        scene_material(s, existing)->line);
    memcpy(m.name, p->token, (size_t)p->token_length);
    m.name[p->token_length] = '\0';
    m.line = p->line_number;
    while (next_token(p))
        if (!read_material_setting(p, &m))
            return false;
    if (redefining_default)
        s->default_material = m;
    else if (!scene_add_material(s, m))
        return fail_at(p, p->line, "more than %d materials", SCENE_MAX_MATERIALS);
    return true;
}

static bool read_attenuation(parser *p, double a[3])
{
    const char *where[3];
    int length[3];
    for (int k = 0; k < 3; k++) {
        if (!read_number(p, "an attenuation coefficient", &a[k]))
            return false;
        where[k] = p->token, length[k] = p->token_length;
    }
    const char *problem = NULL;
    int bad = 0;
    if (!(a[0] >= 1e-6 && a[0] <= 1e6))
        bad = 0, problem = "a1 from 1e-6 to 1e6, so that the light is finite at its position";
    else if (!(a[1] >= 0 && a[1] <= 1e6))
        bad = 1, problem = "a2 from 0 to 1e6, so that the denominator stays at least a1";
    else if (!(a[2] >= 0 && a[2] <= 1e6))
        bad = 2, problem = "a3 from 0 to 1e6, so that the denominator stays at least a1";
    if (problem == NULL)
        return true;
    p->token = where[bad], p->token_length = length[bad];
    return expected(p, "expected %s", problem);
}

static bool read_spot_setting(parser *p, light *L)
{
    double value;
    if (token_is(p, "angle")) {
        if (!read_number(p, "a cone angle", &value))
            return false;
        if (!(value > 0 && value < 180))
            return expected(p, "expected a cone angle between 0 and 180 degrees");
        L->cos_cutoff = cos(value * (M_PI / 180.0));
        return true;
    }
    if (!read_number(p, "a spot exponent", &L->exponent))
        return false;
    return L->exponent >= 0 || expected(p, "expected a spot exponent of at least 0");
}

static bool read_light_setting(parser *p, light *L)
{
    static const char *const settings[] = {
        [LIGHT_POINT] = "position, intensity, attenuation",
        [LIGHT_DIRECTIONAL] = "direction, intensity",
        [LIGHT_SPOT] = "position, direction, angle, exponent, intensity, attenuation"};
    bool placed = L->kind != LIGHT_DIRECTIONAL, aimed = L->kind != LIGHT_POINT;
    if (token_is(p, "intensity"))
        return read_color(p, "a light intensity", &L->intensity);
    if (placed && token_is(p, "position"))
        return read_point(p, "a light position", &L->position);
    if (aimed && token_is(p, "direction"))
        return read_direction(p, "a light direction", &L->direction);
    if (placed && token_is(p, "attenuation"))
        return read_attenuation(p, L->attenuation);
    if (L->kind == LIGHT_SPOT && (token_is(p, "angle") || token_is(p, "exponent")))
        return read_spot_setting(p, L);
    return expected(p, "expected a setting of this light (%s)", settings[L->kind]);
}

static bool parse_light(parser *p, scene *s)
{
    light L = {.position = {0, 0, 0}, .direction = {0, -1, 0}, .intensity = {1, 1, 1},
               .attenuation = {1, 0, 0}, .cos_cutoff = cos(30 * (M_PI / 180.0)),
               .exponent = 2};
    bool named = next_token(p);
    if (named && token_is(p, "point"))
        L.kind = LIGHT_POINT;
    else if (named && token_is(p, "directional"))
        L.kind = LIGHT_DIRECTIONAL;
    else if (named && token_is(p, "spot"))
        L.kind = LIGHT_SPOT;
    else
        return expected(p, "expected a kind of light (point, directional, spot)");
    while (next_token(p))
        if (!read_light_setting(p, &L))
            return false;
    if (!scene_add_light(s, L))
        return fail_at(p, p->line, "more than %d lights", SCENE_MAX_LIGHTS);
    return true;
}

static bool parse_ambient(parser *p, scene *s)
{
    return read_color(p, "an ambient intensity", &s->ambient);
}

static bool read_positive(parser *p, const char *what, double *out)
{
    if (!read_number(p, what, out))
        return false;
    return *out > 0 || expected(p, "expected %s greater than 0", what);
}

static bool parse_tonemap(parser *p, scene *s)
{
    if (!next_token(p))
        return expected(p, "expected 'alpha' or 'beta'");
    do {
        if (token_is(p, "alpha")) {
            if (!read_positive(p, "an exposure alpha", &s->tone.alpha))
                return false;
        } else if (token_is(p, "beta")) {
            if (!read_positive(p, "a compression beta", &s->tone.beta))
                return false;
        } else {
            return expected(p, "expected 'alpha' or 'beta'");
        }
    } while (next_token(p));
    return true;
}

static bool add_vec3(parser *p, vec3 **items, int *count, int *capacity, int max,
                     const char *plural, vec3 value)
{
    vec3 *grown = grow_array(*items, *count, capacity, max, sizeof value);
    if (grown == NULL)
        return fail_at(p, p->line, "more than %d %s (or out of memory)", max, plural);
    *items = grown;
    (*items)[(*count)++] = value;
    return true;
}

static bool obj_vertex(parser *p, mesh *m)
{
    vec3 v;
    if (!read_point(p, "a vertex coordinate", &v))
        return false;
    p->next = p->end; /* an optional w (or vertex colour) is ignored */
    return add_vec3(p, &m->vertices, &m->vertex_count, &m->vertex_capacity, MESH_MAX_VERTICES,
                    "vertices", v);
}

static bool obj_normal(parser *p, mesh *m)
{
    vec3 n;
    if (!read_point(p, "a normal coordinate", &n))
        return false;
    return add_vec3(p, &m->normals, &m->normal_count, &m->normal_capacity, MESH_MAX_VERTICES,
                    "normals", n);
}

static bool obj_texcoord(parser *p, mesh *m)
{
    double u;
    if (!read_number(p, "a texture coordinate", &u))
        return false;
    p->next = p->end; /* v and w are optional and unused */
    if (m->texcoord_count >= MESH_MAX_VERTICES)
        return fail_at(p, p->line, "more than %d texture coordinates", MESH_MAX_VERTICES);
    m->texcoord_count++;
    return true;
}

/* One OBJ index at *at, resolved against count definitions so far. */
static bool read_obj_index(parser *p, const char **at, int count, const char *what, int *out)
{
    const char *c = *at;
    bool negative = c < p->end && *c == '-';
    const char *digits = c += negative;
    long k = 0;
    for (; c < p->end && *c >= '0' && *c <= '9'; c++)
        if (k < MESH_MAX_VERTICES) /* past every count; stops the growth */
            k = 10 * k + (*c - '0');
    if (c == digits || !(c == p->end || *c == '/' || is_blank(*c) || *c == '#'))
        return fail_at(p, *at, "expected a %s index (a whole number)", what);
    if (k == 0)
        return fail_at(p, *at, "%s index 0: OBJ indices start at 1", what);
    if (k > count)
        return fail_at(p, *at, "%s index %.*s is out of range (%d defined so far)", what,
                       (int)(c - *at), *at, count);
    *out = negative ? count - (int)k : (int)k - 1;
    *at = c;
    return true;
}

typedef struct {
    int v, n; /* n = -1: no normal */
} obj_corner;

static bool read_obj_corner(parser *p, const mesh *m, obj_corner *c)
{
    const char *at = p->token;
    int unused;
    c->n = -1;
    if (!read_obj_index(p, &at, m->vertex_count, "vertex", &c->v))
        return false;
    if (at == p->end || *at != '/')
        return true; /* v */
    at++;
    if ((at == p->end || *at != '/') &&
        !read_obj_index(p, &at, m->texcoord_count, "texture coordinate", &unused))
        return false; /* v/vt */
    if (at == p->end || *at != '/')
        return true;
    at++;
    return read_obj_index(p, &at, m->normal_count, "normal", &c->n); /* v//vn or v/vt/vn */
}

static bool obj_face(parser *p, mesh *m)
{
    obj_corner first = {0, -1}, previous = first, corner;
    int corners = 0;
    while (next_token(p)) {
        if (!read_obj_corner(p, m, &corner))
            return false;
        if (++corners >= 3) {
            mesh_triangle tri = {{first.v, previous.v, corner.v}, {first.n, previous.n, corner.n}};
            mesh_triangle *grown = grow_array(m->triangles, m->triangle_count,
                                              &m->triangle_capacity, MESH_MAX_TRIANGLES,
                                              sizeof tri);
            if (grown == NULL)
                return fail_at(p, p->token, "more than %d triangles (or out of memory)",
                               MESH_MAX_TRIANGLES);
            m->triangles = grown;
            m->triangles[m->triangle_count++] = tri;
        }
        if (corners == 1)
            first = corner;
        previous = corner;
    }
    if (corners < 3)
        return expected(p, "expected a face corner (a face needs at least 3)");
    return true;
}

static bool parse_obj_statement(parser *p, void *target)
{
    mesh *m = target;
    if (!next_token(p))
        return true;
    if (token_is(p, "v"))
        return obj_vertex(p, m);
    if (token_is(p, "vn"))
        return obj_normal(p, m);
    if (token_is(p, "vt"))
        return obj_texcoord(p, m);
    if (token_is(p, "f"))
        return obj_face(p, m);
    p->next = p->end; /* o, g, s, usemtl, mtllib, l, p, ...: not ours */
    return true;
}

/* A mesh of the given vertices and one triangle; false when out of memory. */
static bool one_triangle_mesh(mesh *m, const vec3 corners[3])
{
    m->vertices = malloc(3 * sizeof *m->vertices);
    m->triangles = malloc(sizeof *m->triangles);
    if (m->vertices == NULL || m->triangles == NULL)
        return false;
    memcpy(m->vertices, corners, 3 * sizeof *corners);
    m->vertex_count = m->vertex_capacity = 3;
    m->triangles[0] = (mesh_triangle){{0, 1, 2}, {-1, -1, -1}};
    m->triangle_count = m->triangle_capacity = 1;
    mesh_compute_bounds(m);
    return true;
}

static bool parse_triangle(parser *p, scene *s)
{
    vec3 corners[3] = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}};
    mesh m = {.color = {0.8, 0.8, 0.8}};
    while (next_token(p)) {
        int k = token_is(p, "a") ? 0 : token_is(p, "b") ? 1 : token_is(p, "c") ? 2 : -1;
        bool ok = k >= 0                       ? read_point(p, "a corner coordinate", &corners[k])
                  : token_is(p, "color")       ? read_color(p, "a colour component", &m.color)
                  : token_is(p, "material")    ? read_material_name(p, s, &m.material)
                  : expected(p, "expected a triangle setting (a, b, c, color, material)");
        if (!ok)
            return false;
    }
    if (!one_triangle_mesh(&m, corners) || !scene_add_mesh(s, m)) {
        mesh_free(&m);
        return fail_at(p, p->line, "out of memory, or more than %d meshes", SCENE_MAX_MESHES);
    }
    return true;
}

/* PATH of the token, relative to the folder of the file being parsed. */
static bool resolve_path(const parser *p, const char *token, int length, char *out, size_t size)
{
    const char *slash = strrchr(p->name, '/');
    int folder = token[0] == '/' || slash == NULL ? 0 : (int)(slash - p->name) + 1;
    return snprintf(out, size, "%.*s%.*s", folder, p->name, length, token) < (int)size;
}

static bool load_mesh_file(parser *p, const char *file, int length, mesh *m)
{
    char path[4096];
    if (!resolve_path(p, file, length, path, sizeof path))
        return fail_at(p, file, "the mesh file's path is too long");
    if (mesh_load_obj(m, path, p->err))
        return true;
    if (p->err->line == 0) { /* unreadable: say which scene line asked for it */
        char why[sizeof p->err->message];
        snprintf(why, sizeof why, "%s", p->err->message);
        return fail_at(p, file, "cannot read mesh file '%s': %s", path, why);
    }
    return false; /* the OBJ file's own line and column */
}

static bool read_scale(parser *p, double *scale)
{
    if (!read_number(p, "a scale", scale))
        return false;
    return (*scale >= 1e-100 && *scale <= 1e100) ||
           expected(p, "expected a scale between 1e-100 and 1e100");
}

static bool place_mesh(parser *p, mesh *m, double scale, vec3 offset, bool smooth)
{
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = vec3_add(vec3_scale(m->vertices[k], scale), offset);
        if (!(fabs(v.x) <= SCENE_MAX_COORDINATE && fabs(v.y) <= SCENE_MAX_COORDINATE &&
              fabs(v.z) <= SCENE_MAX_COORDINATE))
            return fail_at(p, p->line, "vertex %d of the mesh lies beyond 1e50 once placed",
                           k + 1);
        m->vertices[k] = v;
    }
    if (smooth && m->normal_count == 0 && !mesh_smooth_normals(m))
        return fail_at(p, p->line, "out of memory for the mesh's normals");
    mesh_compute_bounds(m);
    return true;
}

static bool parse_mesh(parser *p, scene *s)
{
    mesh m = {.color = {0.8, 0.8, 0.8}};
    const char *file = NULL;
    int file_length = 0;
    double scale = 1;
    vec3 offset = {0, 0, 0};
    bool smooth = false;
    while (next_token(p)) {
        bool ok = true;
        if (token_is(p, "file")) {
            ok = next_token(p) || expected(p, "expected the name of an OBJ file");
            file = p->token, file_length = p->token_length;
        } else if (token_is(p, "scale"))
            ok = read_scale(p, &scale);
        else if (token_is(p, "offset"))
            ok = read_point(p, "an offset coordinate", &offset);
        else if (token_is(p, "smooth"))
            smooth = true;
        else if (token_is(p, "color"))
            ok = read_color(p, "a colour component", &m.color);
        else if (token_is(p, "material"))
            ok = read_material_name(p, s, &m.material);
        else
            ok = expected(p, "expected a mesh setting "
                             "(file, scale, offset, smooth, color, material)");
        if (!ok)
            return false;
    }
    if (file == NULL)
        return expected(p, "expected 'file PATH': a mesh needs an OBJ file");
    if (!load_mesh_file(p, file, file_length, &m) || !place_mesh(p, &m, scale, offset, smooth)) {
        mesh_free(&m);
        return false;
    }
    if (!scene_add_mesh(s, m)) {
        mesh_free(&m);
        return fail_at(p, p->line, "more than %d meshes (or out of memory)", SCENE_MAX_MESHES);
    }
    return true;
}

void scene_init(scene *s)
{
    memset(s, 0, sizeof *s);
    s->cam.fov_deg = 60.0;
    s->cam.width = 320;
    s->cam.height = 240;
    s->bg.kind = BACKGROUND_GRADIENT;
    s->bg.bottom = (vec3){1.0, 1.0, 1.0};
    s->bg.top = (vec3){0.3, 0.5, 1.0};
    s->ambient = (vec3){1, 1, 1};
    s->tone.alpha = s->tone.beta = 1;
    s->default_material = default_finish();
    s->default_light = (light){.kind = LIGHT_DIRECTIONAL,
                               .direction = vec3_normalize((vec3){1, -1, 1}),
                               .intensity = {1, 1, 1}};
}

void scene_free(scene *s)
{
    (void)s; /* nothing is allocated yet */
    free(s->spheres);
    s->spheres = NULL;
    s->sphere_count = s->sphere_capacity = 0;
    free(s->materials);
    free(s->lights);
    s->materials = NULL;
    s->lights = NULL;
    s->material_count = s->material_capacity = s->light_count = s->light_capacity = 0;
    for (int k = 0; k < s->mesh_count; k++)
        mesh_free(&s->meshes[k]);
    free(s->meshes);
    s->meshes = NULL;
    s->mesh_count = s->mesh_capacity = 0;
}

typedef bool (*statement_parser)(parser *p, scene *s);

static const struct {
    const char *keyword;
    statement_parser parse;
} statements[] = {
    {"camera", parse_camera},
    {"image", parse_image},
    {"background", parse_background},
    {"sphere", parse_sphere},
    {"ambient", parse_ambient},
    {"tonemap", parse_tonemap},
    {"material", parse_material},
    {"light", parse_light},
    {"triangle", parse_triangle},
    {"mesh", parse_mesh},
};

static bool parse_statement(parser *p, void *target)
{
    scene *s = target;
    if (!next_token(p))
        return true; /* a blank line or a comment */
    for (size_t k = 0; k < sizeof statements / sizeof statements[0]; k++) {
        if (token_is(p, statements[k].keyword)) {
            if (!statements[k].parse(p, s))
                return false;
            return next_token(p) ? expected(p, "expected end of line") : true;
        }
    }
    return expected(p, "expected a statement keyword");
}

typedef bool (*line_parser)(parser *p, void *target);

/* Calls parse_line on every line of text[0..length), stopping at the first error. */
static bool parse_lines(parser *p, const char *text, size_t length, line_parser parse_line,
                        void *target)
{
    const char *end = text + length;
    const char *line = text;
    while (line < end) {
        const char *eol = memchr(line, '\n', (size_t)(end - line));
        if (eol == NULL)
            eol = end;
        p->line = p->next = line;
        p->end = eol;
        p->line_number++;
        const char *nul = memchr(line, '\0', (size_t)(eol - line));
        if (nul != NULL)
            return fail_at(p, nul, "unexpected NUL byte: this is not a text file");
        if (!parse_line(p, target))
            return false;
        line = eol < end ? eol + 1 : end;
    }
    return true;
}

bool scene_parse(scene *s, const char *text, size_t length, const char *name,
                 scene_error *err)
{
    parser p = {.name = name, .err = err};
    return parse_lines(&p, text, length, parse_statement, s);
}

static bool file_error(scene_error *err, const char *path, const char *message)
{
    snprintf(err->file, sizeof err->file, "%s", path);
    err->line = err->col = 0;
    snprintf(err->message, sizeof err->message, "%s", message);
    return false;
}

/* Reads from in until the end, growing *text by doubling; false when it
 * would pass max_bytes or memory runs out. */
static bool read_all(FILE *in, long max_bytes, char **text, size_t *length)
{
    size_t capacity = 4096;
    *text = malloc(capacity);
    *length = 0;
    while (*text != NULL) {
        *length += fread(*text + *length, 1, capacity - *length, in);
        if (*length < capacity || *length > (size_t)max_bytes)
            return *length <= (size_t)max_bytes; /* the end, or too much */
        char *grown = realloc(*text, 2 * capacity);
        if (grown == NULL) {
            free(*text);
            *text = NULL; /* says "out of memory" to the caller */
            break;
        }
        *text = grown;
        capacity *= 2;
    }
    return false;
}

/* The whole file at path, at most max_bytes, in a malloc'ed *text that is
 * NUL-terminated (a last stop for strtol and friends). */
static bool read_file(const char *path, long max_bytes, char **text, size_t *length,
                      scene_error *err)
{
    FILE *in = fopen(path, "rb");
    if (in == NULL)
        return file_error(err, path, strerror(errno));
    bool ok = read_all(in, max_bytes, text, length);
    if (ferror(in))
        ok = file_error(err, path, strerror(errno));
    else if (!ok)
        file_error(err, path, *text ? "larger than such a file may be" : "out of memory");
    fclose(in);
    if (ok) {
        (*text)[*length] = '\0'; /* there is room: length < capacity */
    } else {
        free(*text);
        *text = NULL;
    }
    return ok;
}

bool scene_load(scene *s, const char *path, scene_error *err)
{
    char *text;
    size_t length;
    if (!read_file(path, SCENE_MAX_BYTES, &text, &length, err))
        return false;
    bool ok = scene_parse(s, text, length, path, err);
    free(text);
    return ok;
}

bool mesh_parse_obj(mesh *m, const char *text, size_t length, const char *name,
                    scene_error *err)
{
    parser p = {.name = name, .err = err};
    return parse_lines(&p, text, length, parse_obj_statement, m);
}

bool mesh_load_obj(mesh *m, const char *path, scene_error *err)
{
    char *text;
    size_t length;
    if (!read_file(path, OBJ_MAX_BYTES, &text, &length, err))
        return false;
    bool ok = mesh_parse_obj(m, text, length, path, err);
    free(text);
    return ok;
}
