/* obj.c: the OBJ reader (chapter 4). See obj.h. */
#include "obj.h"

#include <limits.h>
#include <stdlib.h>
#include "array.h"

typedef struct {
    mesh *m;
    mesh_budget left; /* what the mesh may still take */
} obj_reader;

/* <<reading OBJ statements>> ch04 */
/* Room for one more of count items, within max and the bytes left; NULL,
 * with the error filled, when there is none. */
static void *grow(parser *p, obj_reader *r, void *items, int count,
                  int *capacity, int max, size_t size, const char *plural)
{
    if (count < *capacity)
        return items;
    int more = array_next_capacity(*capacity, max) - *capacity;
    long long bytes = (long long)more * (long long)size;
    if (count < max && bytes > r->left.bytes) {
        parse_fail_with(p, PARSE_OVER_BUDGET, p->line,
                        "%s past the %lld bytes the budget has left", plural,
                        r->left.bytes);
        return NULL;
    }
    void *grown = array_grow(items, count, capacity, max, size);
    if (grown == NULL)
        parse_no_room(p, p->line, count, max, plural);
    else
        r->left.bytes -= bytes;
    return grown;
}

static bool add_vec3(parser *p, obj_reader *r, vec3 **items, int *count,
                     int *capacity, const char *plural, vec3 value)
{
    vec3 *grown = grow(p, r, *items, *count, capacity, MESH_MAX_VERTICES,
                       sizeof value, plural);
    if (grown == NULL)
        return false;
    *items = grown;
    (*items)[(*count)++] = value;
    return true;
}

static bool obj_vertex(parser *p, obj_reader *r)
{
    vec3 v;
    mesh *m = r->m;
    if (!parse_point(p, "a vertex coordinate", &v))
        return false;
    p->next = p->end; /* an optional w (or vertex colour) is ignored */
    return add_vec3(p, r, &m->vertices, &m->vertex_count,
                    &m->vertex_capacity, "vertices", v);
}

static bool obj_normal(parser *p, obj_reader *r)
{
    vec3 n;
    mesh *m = r->m;
    if (!parse_point(p, "a normal coordinate", &n))
        return false;
    return add_vec3(p, r, &m->normals, &m->normal_count,
                    &m->normal_capacity, "normals", n);
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

/* One OBJ index at *at, resolved against count definitions so far; it
 * ends at a '/' or at the end of the token. */
static bool read_obj_index(parser *p, const char **at, int count,
                           const char *what, int *out)
{
    const char *c = *at, *end = p->token + p->token_length;
    bool negative = c < end && *c == '-';
    const char *digits = c += negative;
    long k = 0;
    for (; c < end && *c >= '0' && *c <= '9'; c++)
        if (k < MESH_MAX_VERTICES) /* past every count; stops the growth */
            k = 10 * k + (*c - '0');
    if (c == digits || (c < end && *c != '/'))
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
    const char *at = p->token, *end = p->token + p->token_length;
    int unused;
    c->n = -1;
    if (!read_obj_index(p, &at, m->vertex_count, "vertex", &c->v))
        return false;
    if (at == end)
        return true; /* v */
    at++;
    if ((at == end || *at != '/') &&
        !read_obj_index(p, &at, m->texcoord_count, "texture coordinate",
                        &unused))
        return false;
    if (at == end)
        return true; /* v/vt */
    at++;
    if (!read_obj_index(p, &at, m->normal_count, "normal", &c->n))
        return false; /* v//vn or v/vt/vn */
    return at == end ||
           parse_fail_at(p, at, "expected the end of the face corner (v, "
                                "v/vt, v//vn or v/vt/vn)");
}

/* Appends the triangle (a, b, c) and its corners' normal indices. */
static bool add_triangle(parser *p, obj_reader *r, obj_corner a,
                         obj_corner b, obj_corner c)
{
    mesh *m = r->m;
    if (m->triangle_count < MESH_MAX_TRIANGLES &&
        m->triangle_count >= r->left.triangles)
        return parse_fail_with(p, PARSE_OVER_BUDGET, p->token,
                               "more than the %ld triangles the budget "
                               "allows", r->left.triangles);
    mesh_triangle *grown =
        grow(p, r, m->triangles, m->triangle_count, &m->triangle_capacity,
             MESH_MAX_TRIANGLES, sizeof *grown, "triangles");
    if (grown == NULL)
        return false;
    m->triangles = grown;
    mesh_triangle *normals = grow(
        p, r, m->triangle_normals, m->triangle_count,
        &m->triangle_normals_capacity, MESH_MAX_TRIANGLES, sizeof *normals,
        "triangles");
    if (normals == NULL)
        return false;
    m->triangle_normals = normals;
    m->triangles[m->triangle_count] = (mesh_triangle){{a.v, b.v, c.v}};
    normals[m->triangle_count++] = (mesh_triangle){{a.n, b.n, c.n}};
    return true;
}

static bool obj_face(parser *p, obj_reader *r)
{
    obj_corner first = {0, -1}, previous = first, corner;
    int corners = 0;
    while (parse_next_token(p)) {
        if (!read_obj_corner(p, r->m, &corner))
            return false;
        if (++corners >= 3 && !add_triangle(p, r, first, previous, corner))
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
    obj_reader *r = target;
    if (!parse_next_token(p))
        return true;
    if (parse_token_is(p, "v"))
        return obj_vertex(p, r);
    if (parse_token_is(p, "vn"))
        return obj_normal(p, r);
    if (parse_token_is(p, "vt"))
        return obj_texcoord(p, r->m);
    if (parse_token_is(p, "f"))
        return obj_face(p, r);
    p->next = p->end; /* o, g, s, usemtl, mtllib, l, p, ...: not ours */
    return true;
}

/* <<reading an OBJ file>> ch04 */
static const mesh_budget no_budget = {MESH_MAX_TRIANGLES, LLONG_MAX};

static bool parse_obj_within(mesh *m, const char *text, size_t length,
                             const char *name, mesh_budget budget,
                             parse_error *err)
{
    obj_reader r = {m, budget};
    return parse_lines(text, length, name, err, parse_obj_statement, &r);
}

bool mesh_parse_obj(mesh *m, const char *text, size_t length,
                    const char *name, parse_error *err)
{
    return parse_obj_within(m, text, length, name, no_budget, err);
}

bool mesh_load_obj_within(mesh *m, const char *path, mesh_budget budget,
                          parse_error *err)
{
    char *text;
    size_t length;
    if (!parse_read_file(path, OBJ_MAX_BYTES, &text, &length, err))
        return false;
    bool ok = parse_obj_within(m, text, length, path, budget, err);
    free(text);
    return ok;
}

bool mesh_load_obj(mesh *m, const char *path, parse_error *err)
{
    return mesh_load_obj_within(m, path, no_budget, err);
}
