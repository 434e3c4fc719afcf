/* obj.c: the OBJ reader (chapter 04). See obj.h. */
#include "obj.h"

#include <stdlib.h>
#include "array.h"

static bool add_vec3(parser *p, vec3 **items, int *count, int *capacity,
                     int max, const char *plural, vec3 value)
{
    vec3 *grown = array_grow(*items, *count, capacity, max, sizeof value);
    if (grown == NULL)
        return parse_fail_at(p, p->line, "more than %d %s (or out of memory)",
                             max, plural);
    *items = grown;
    (*items)[(*count)++] = value;
    return true;
}

static bool obj_vertex(parser *p, mesh *m)
{
    vec3 v;
    if (!parse_point(p, "a vertex coordinate", &v))
        return false;
    p->next = p->end; /* an optional w (or vertex colour) is ignored */
    return add_vec3(p, &m->vertices, &m->vertex_count, &m->vertex_capacity,
                    MESH_MAX_VERTICES, "vertices", v);
}

static bool obj_normal(parser *p, mesh *m)
{
    vec3 n;
    if (!parse_point(p, "a normal coordinate", &n))
        return false;
    return add_vec3(p, &m->normals, &m->normal_count, &m->normal_capacity,
                    MESH_MAX_VERTICES, "normals", n);
}

static bool obj_texcoord(parser *p, mesh *m)
{
    double u;
    if (!parse_number(p, "a texture coordinate", &u))
        return false;
    p->next = p->end; /* v and w are optional and unused */
    if (m->texcoord_count >= MESH_MAX_VERTICES)
        return parse_fail_at(p, p->line, "more than %d texture coordinates",
                             MESH_MAX_VERTICES);
    m->texcoord_count++;
    return true;
}

/* One OBJ index at *at, resolved against count definitions so far. */
static bool read_obj_index(parser *p, const char **at, int count,
                           const char *what, int *out)
{
    const char *c = *at;
    bool negative = c < p->end && *c == '-';
    const char *digits = c += negative;
    long k = 0;
    for (; c < p->end && *c >= '0' && *c <= '9'; c++)
        if (k < MESH_MAX_VERTICES) /* past every count; stops the growth */
            k = 10 * k + (*c - '0');
    if (c == digits ||
        !(c == p->end || *c == '/' || parse_is_blank(*c) || *c == '#'))
        return parse_fail_at(p, *at, "expected a %s index (a whole number)",
                             what);
    if (k == 0)
        return parse_fail_at(p, *at, "%s index 0: OBJ indices start at 1",
                             what);
    if (k > count)
        return parse_fail_at(
            p, *at, "%s index %.*s is out of range (%d defined so far)", what,
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
        !read_obj_index(p, &at, m->texcoord_count, "texture coordinate",
                        &unused))
        return false; /* v/vt */
    if (at == p->end || *at != '/')
        return true;
    at++;
    return read_obj_index(p, &at, m->normal_count, "normal",
                          &c->n); /* v//vn or v/vt/vn */
}

/* Appends the triangle (a, b, c) and its corners' normal indices. */
static bool add_triangle(parser *p, mesh *m, obj_corner a, obj_corner b,
                         obj_corner c)
{
    int capacity = m->triangle_capacity;
    mesh_triangle *grown = array_grow(m->triangles, m->triangle_count,
                                      &capacity, MESH_MAX_TRIANGLES,
                                      sizeof *grown);
    if (grown == NULL)
        return parse_fail_at(p, p->token, "more than %d triangles (or out of "
                                          "memory)", MESH_MAX_TRIANGLES);
    m->triangles = grown;
    mesh_triangle *normals =
        array_grow(m->triangle_normals, m->triangle_count,
                   &m->triangle_normals_capacity, MESH_MAX_TRIANGLES,
                   sizeof *normals);
    m->triangle_capacity = capacity;
    if (normals == NULL)
        return parse_fail_at(p, p->token, "out of memory for %d triangles",
                             m->triangle_count + 1);
    m->triangle_normals = normals;
    m->triangles[m->triangle_count] = (mesh_triangle){{a.v, b.v, c.v}};
    normals[m->triangle_count++] = (mesh_triangle){{a.n, b.n, c.n}};
    return true;
}

static bool obj_face(parser *p, mesh *m)
{
    obj_corner first = {0, -1}, previous = first, corner;
    int corners = 0;
    while (parse_next_token(p)) {
        if (!read_obj_corner(p, m, &corner))
            return false;
        if (++corners >= 3 && !add_triangle(p, m, first, previous, corner))
            return false;
        if (corners == 1)
            first = corner;
        previous = corner;
    }
    if (corners < 3)
        return parse_expected(p, "expected a face corner (a face needs at "
                                 "least 3)");
    return true;
}

static bool parse_obj_statement(parser *p, void *target)
{
    mesh *m = target;
    if (!parse_next_token(p))
        return true;
    if (parse_token_is(p, "v"))
        return obj_vertex(p, m);
    if (parse_token_is(p, "vn"))
        return obj_normal(p, m);
    if (parse_token_is(p, "vt"))
        return obj_texcoord(p, m);
    if (parse_token_is(p, "f"))
        return obj_face(p, m);
    p->next = p->end; /* o, g, s, usemtl, mtllib, l, p, ...: not ours */
    return true;
}

bool mesh_parse_obj(mesh *m, const char *text, size_t length,
                    const char *name, parse_error *err)
{
    return parse_lines(text, length, name, err, parse_obj_statement, m);
}

bool mesh_load_obj(mesh *m, const char *path, parse_error *err)
{
    char *text;
    size_t length;
    if (!parse_read_file(path, OBJ_MAX_BYTES, &text, &length, err))
        return false;
    bool ok = mesh_parse_obj(m, text, length, path, err);
    free(text);
    return ok;
}
