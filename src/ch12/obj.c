/* obj.c: the OBJ reader (chapter 4). See obj.h. */
#include "obj.h"

#include <limits.h>
#include <stdlib.h>
#include "array.h"
/* <<OBJ reader includes>> ch12 */
#include <string.h>
#include <sys/stat.h>
#include "moment.h"
#include "pool.h"

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
/* <<reading an OBJ file>> += ch12 */

/* <<a part of the text>> ch12 */
/* One part of the text, whole lines, and what its job found. */
typedef struct {
    const char *text, *name;
    size_t length;
    long long vertices, normals, texcoords, triangles; /* counted */
    mesh m; /* the whole mesh's arrays, from the parts before it on */
    parse_error err;
    bool ok;
} obj_part;

/* What a job of run_parts does: work on parts[k]. */
typedef struct {
    obj_part *parts;
    void (*work)(obj_part *);
} obj_work;

static void part_job(void *context, int k)
{
    obj_work *w = context;
    w->work(&w->parts[k]);
}

/* Runs work on every part, on threads threads (0: one per core). */
static void run_parts(obj_part *parts, int n, int threads,
                      void (*work)(obj_part *))
{
    obj_work w = {parts, work};
    pool_for(n, threads, part_job, &w);
}

/* <<counting a part>> ch12 */
static bool count_obj_statement(parser *p, void *target)
{
    obj_part *part = target;
    if (parse_next_token(p)) {
        bool point = parse_token_is(p, "v") || parse_token_is(p, "vn");
        int numbers = point ? 3 : parse_token_is(p, "vt");
        if (p->end - p->line < OBJ_LONG_NUMBER)
            numbers = 0; /* a line this short has no long number */
        part->vertices += parse_token_is(p, "v");
        part->normals += parse_token_is(p, "vn");
        part->texcoords += parse_token_is(p, "vt");
        if (parse_token_is(p, "f")) {
            int corners = 0;
            while (parse_next_token(p))
                corners++;
            part->triangles += corners > 2 ? corners - 2 : 0;
        }
        for (int k = 0; k < numbers && parse_next_token(p); k++)
            if (p->token_length >= OBJ_LONG_NUMBER)
                return false; /* not for this part: chapter 4's reader */
    }
    p->next = p->end; /* the numbers are the reading's */
    return true;
}

static void count_part(obj_part *t)
{
    t->ok = parse_lines(t->text, t->length, t->name, &t->err,
                        count_obj_statement, t);
}

static void read_part(obj_part *t)
{
    /* no bytes to grow: every array was made to measure */
    obj_reader r = {&t->m, {MESH_MAX_TRIANGLES, 0}};
    t->ok = parse_lines(t->text, t->length, t->name, &t->err,
                        parse_obj_statement, &r);
}

/* <<the arrays made to measure>> ch12 */
/* The capacity that growing an array one item at a time, to at most
 * max, gives count items; its bytes added to *bytes. */
static int grown_capacity(long long count, int max, size_t size,
                          long long *bytes)
{
    int capacity = 0;
    while (capacity < count)
        capacity = array_next_capacity(capacity, max);
    *bytes += (long long)capacity * (long long)size;
    return capacity;
}

/* An array of capacity items of size; NULL for none, as chapter 4's
 * reader leaves it, or when there is no memory. */
static void *made(int capacity, size_t size)
{
    return capacity > 0 ? memory_alloc((size_t)capacity, size) : NULL;
}

/* m's arrays for the parts' counts, within budget; false when the serial
 * reader would stop (a limit, the budget, memory). */
static bool make_arrays(mesh *m, const obj_part *parts, int n,
                        mesh_budget budget)
{
    long long v = 0, vn = 0, vt = 0, t = 0, bytes = 0;
    for (int k = 0; k < n; k++)
        v += parts[k].vertices, vn += parts[k].normals,
            vt += parts[k].texcoords, t += parts[k].triangles;
    if (v > MESH_MAX_VERTICES || vn > MESH_MAX_VERTICES ||
        vt > MESH_MAX_VERTICES || t > MESH_MAX_TRIANGLES ||
        t > budget.triangles)
        return false;
    int vs = grown_capacity(v, MESH_MAX_VERTICES, sizeof(vec3), &bytes);
    int ns = grown_capacity(vn, MESH_MAX_VERTICES, sizeof(vec3), &bytes);
    int ts = grown_capacity(t, MESH_MAX_TRIANGLES, sizeof(mesh_triangle),
                            &bytes);
    bytes += (long long)ts * (long long)sizeof(mesh_triangle); /* normals */
    if (bytes > budget.bytes)
        return false; /* before a byte is taken */
    m->vertex_capacity = vs, m->normal_capacity = ns;
    m->triangle_capacity = m->triangle_normals_capacity = ts;
    m->vertices = made(vs, sizeof(vec3)), m->normals = made(ns, sizeof(vec3));
    m->triangles = made(ts, sizeof(mesh_triangle));
    m->triangle_normals = made(ts, sizeof(mesh_triangle));
    return (m->vertices || !vs) && (m->normals || !ns) &&
           (m->triangles || !ts) && (m->triangle_normals || !ts);
}

/* <<each part's view of the arrays>> ch12 */
/* Each part's view of m: the counts before it, its items' end; m's
 * counts those of the whole text. */
static void share_arrays(mesh *m, obj_part *parts, int n)
{
    mesh at = *m; /* the counts so far */
    for (int k = 0; k < n; k++) {
        mesh *p = &parts[k].m;
        *p = at;
        p->vertex_capacity = (int)(at.vertex_count + parts[k].vertices);
        p->normal_capacity = (int)(at.normal_count + parts[k].normals);
        p->triangle_capacity =
            (int)(at.triangle_count + parts[k].triangles);
        p->triangle_normals_capacity = p->triangle_capacity;
        at.vertex_count = p->vertex_capacity;
        at.normal_count = p->normal_capacity;
        at.triangle_count = p->triangle_capacity;
        at.texcoord_count += (int)parts[k].texcoords;
    }
    m->vertex_count = at.vertex_count, m->normal_count = at.normal_count;
    m->triangle_count = at.triangle_count;
    m->texcoord_count = at.texcoord_count;
}

/* <<where a part begins>> ch12 */
static bool starts_with_mark(const char *text, size_t length)
{
    return length >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0;
}

/* Where part k of n begins: the first line that starts at or after k/n
 * of the text, and not with a byte order mark. */
static size_t part_start(const char *text, size_t length, int k, int n)
{
    if (k == 0)
        return 0;
    size_t at = (size_t)((unsigned long long)length * (unsigned)k /
                         (unsigned)n);
    for (at = at > 0 ? at : 1; at < length; at++)
        if (text[at - 1] == '\n' &&
            !starts_with_mark(text + at, length - at))
            break;
    return at < length ? at : length; /* no line starts there: the end */
}

/* <<the parts read and checked>> ch12 */
/* Did each part fill what it counted, and end where the parts before it
 * and its own counts say? */
static bool parts_filled(const obj_part *parts, int n)
{
    long long v = 0, vn = 0, vt = 0, t = 0;
    for (int k = 0; k < n; k++) {
        const obj_part *p = &parts[k];
        v += p->vertices, vn += p->normals;
        vt += p->texcoords, t += p->triangles;
        if (p->m.vertex_count != v || p->m.normal_count != vn ||
            p->m.texcoord_count != vt || p->m.triangle_count != t)
            return false;
    }
    return true;
}

/* The parts counted, the arrays made, the parts read and checked: false
 * when the serial reader must say what is wrong, or read it. */
static bool read_in_parts(mesh *m, obj_part *parts, int n, int threads,
                          mesh_budget budget)
{
    run_parts(parts, n, threads, count_part);
    for (int k = 0; k < n; k++)
        if (!parts[k].ok)
            return false;
    double start = moment_now().wall;
    if (!make_arrays(m, parts, n, budget))
        return false;
    share_arrays(m, parts, n);
    m->arrays_seconds = moment_now().wall - start;
    run_parts(parts, n, threads, read_part);
    for (int k = 0; k < n; k++)
        if (!parts[k].ok)
            return false;
    return parts_filled(parts, n);
}

bool mesh_parse_obj_in_parts(mesh *m, const char *text, size_t length,
                             const char *name, mesh_budget budget,
                             int parts, int threads, parse_error *err)
{
    int n = parts < 1 ? 1 : parts < OBJ_MAX_PARTS ? parts : OBJ_MAX_PARTS;
    obj_part *part = memory_alloc_zeroed((size_t)n, sizeof *part);
    for (int k = 0; part != NULL && k < n; k++) {
        size_t b = part_start(text, length, k, n);
        part[k].text = text + b, part[k].name = name;
        part[k].length = part_start(text, length, k + 1, n) - b;
    }
    bool ok = part != NULL && read_in_parts(m, part, n, threads, budget);
    free(part);
    if (ok)
        return m->parts = n, true;
    mesh_free(m); /* chapter 4's reader, from the start, says why */
    return parse_obj_within(m, text, length, name, budget, err);
}

/* <<a file read in parts>> ch12 */
void (*obj_test_after_reading)(const char *path);

/* The file at path read into memory, refused when its size or its time
 * of change moved meanwhile. */
static bool read_unchanged(const char *path, char **text, size_t *length,
                           parse_error *err)
{
    struct stat before, after;
    bool seen = stat(path, &before) == 0;
    if (!parse_read_file(path, OBJ_MAX_BYTES, text, length, err))
        return false;
    if (obj_test_after_reading != NULL)
        obj_test_after_reading(path);
    bool still = seen && stat(path, &after) == 0;
    if (still && after.st_size == before.st_size &&
        after.st_mtime == before.st_mtime)
        return true;
    free(*text), *text = NULL;
    if (still && after.st_size == before.st_size)
        return parse_fail_on_line(err, path, 0, PARSE_CANNOT_READ,
                                  "the file changed while it was read "
                                  "(its time of change moved)");
    return parse_fail_on_line(
        err, path, 0, PARSE_CANNOT_READ,
        "the file changed while it was read (%lld bytes before, %s)",
        seen ? (long long)before.st_size : 0LL,
        still ? "another size after" : "gone after");
}

bool mesh_load_obj_on(mesh *m, const char *path, mesh_budget budget,
                      int threads, parse_error *err)
{
    char *text;
    size_t length;
    double start = moment_now().wall;
    if (!read_unchanged(path, &text, &length, err))
        return false;
    double read_in = moment_now().wall - start;
    size_t most = 1 + length / OBJ_MIN_PART_BYTES;
    size_t wanted = (size_t)pool_threads(threads) * OBJ_PARTS_A_THREAD;
    int parts = (int)(wanted < most ? wanted : most);
    bool ok = mesh_parse_obj_in_parts(m, text, length, path, budget, parts,
                                      threads, err);
    free(text);
    m->file_seconds = read_in;
    return ok;
}
