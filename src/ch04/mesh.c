/* mesh.c: meshes, their normals, and ray-mesh intersection (chapter 4),
 * through a tree of the mesh from chapter 8 on. */
#include "mesh.h"

#include <stdlib.h>
#include <string.h>
#include "memory.h"

/* <<mesh storage>> ch04 */
void mesh_free(mesh *m)
{
    free(m->vertices);
    free(m->normals);
    free(m->triangles);
    free(m->triangle_normals);
    free(m->source.path);
    *m = (mesh){0};
}

long long mesh_bytes(const mesh *m)
{
    long long points = (long long)m->vertex_capacity + m->normal_capacity;
    long long corners =
        (long long)m->triangle_capacity + m->triangle_normals_capacity;
    return points * (long long)sizeof(vec3) +
           corners * (long long)sizeof(mesh_triangle);
}

bool mesh_source_equal(const mesh_source *a, const mesh_source *b)
{
    return a->scale == b->scale && a->offset.x == b->offset.x &&
           a->offset.y == b->offset.y && a->offset.z == b->offset.z &&
           a->smooth == b->smooth && a->path != NULL && b->path != NULL &&
           strcmp(a->path, b->path) == 0;
}

void mesh_compute_bounds(mesh *m)
{
    vec3 lo = {INFINITY, INFINITY, INFINITY};
    vec3 hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = m->vertices[k];
        lo = (vec3){fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z)};
        hi = (vec3){fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z)};
    }
    m->bounds = (box){lo, hi};
}

/* <<the mesh index>> ch04 */
/* FNV-1a over n bytes, continuing from h. */
static unsigned long long fnv1a(unsigned long long h, const void *bytes,
                                size_t n)
{
    const unsigned char *b = bytes;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 1099511628211ULL;
    return h;
}

/* Where the index starts looking for source. */
static size_t first_slot(const mesh_source *source, int size)
{
    const mesh_source *c = source; /* + 0.0: -0.0 hashes as 0.0, its equal */
    double numbers[4] = {c->scale + 0.0, c->offset.x + 0.0,
                         c->offset.y + 0.0, c->offset.z + 0.0};
    unsigned long long h = fnv1a(14695981039346656037ULL, c->path,
                                 strlen(c->path));
    h = fnv1a(h, numbers, sizeof numbers);
    h = fnv1a(h, &c->smooth, sizeof c->smooth);
    return (size_t)(h & (unsigned long long)(size - 1));
}

static size_t next_slot(const mesh_index *x, size_t slot)
{
    return (slot + 1) & (size_t)(x->size - 1);
}

void mesh_index_add(mesh_index *x, const mesh *meshes, int k)
{
    if (meshes[k].source.path == NULL)
        return; /* made in code: no source to find it by */
    size_t slot = first_slot(&meshes[k].source, x->size);
    while (x->slots[slot] != 0)
        slot = next_slot(x, slot);
    x->slots[slot] = k + 1;
}

bool mesh_index_reserve(mesh_index *x, const mesh *meshes, int count)
{
    if (2 * (count + 1) < x->size)
        return true;
    int size = x->size ? 2 * x->size : 64;
    int *slots = memory_alloc_zeroed((size_t)size, sizeof *slots);
    if (slots == NULL)
        return false;
    free(x->slots);
    x->slots = slots, x->size = size;
    for (int k = 0; k < count; k++)
        mesh_index_add(x, meshes, k);
    return true;
}

int mesh_index_find(const mesh_index *x, const mesh *meshes,
                    const mesh_source *source)
{
    if (x->size == 0 || source->path == NULL)
        return -1;
    size_t slot = first_slot(source, x->size);
    for (; x->slots[slot] != 0; slot = next_slot(x, slot)) {
        int k = x->slots[slot] - 1;
        if (mesh_source_equal(&meshes[k].source, source))
            return k;
    }
    return -1;
}

void mesh_index_free(mesh_index *x)
{
    free(x->slots);
    *x = (mesh_index){0};
}

/* <<smooth normals>> ch04 */
/* (b - a) x (c - a): the sheet's n, twice the area long. */
static vec3 face_normal(vec3 a, vec3 b, vec3 c)
{
    return vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
}

static vec3 triangle_normal(const mesh *m, const mesh_triangle *tri)
{
    const vec3 *p = m->vertices;
    return face_normal(p[tri->v[0]], p[tri->v[1]], p[tri->v[2]]);
}

bool mesh_smooth_normals(mesh *m)
{
    size_t count = (size_t)m->vertex_count + 1,
           faces = (size_t)m->triangle_count;
    vec3 *normals = memory_alloc_zeroed(count, sizeof *normals);
    mesh_triangle *corners = memory_alloc(faces, sizeof *corners);
    if (normals == NULL || corners == NULL) {
        free(normals), free(corners);
        return false;
    }
    for (int k = 0; k < m->triangle_count; k++) {
        const int *v = m->triangles[k].v;
        vec3 n = triangle_normal(m, &m->triangles[k]);
        for (int i = 0; i < 3; i++)
            normals[v[i]] = vec3_add(normals[v[i]], n);
        corners[k] = m->triangles[k]; /* vertex i uses normal i */
    }
    free(m->normals), free(m->triangle_normals);
    m->normals = normals;
    m->normal_count = m->normal_capacity = m->vertex_count;
    m->triangle_normals = corners;
    m->triangle_normals_capacity = m->triangle_count;
    return true;
}

/* <<intersecting a mesh>> ch04 */
/* n normalised, or the zero vector when it has no usable length. */
static vec3 unit_or_zero(vec3 n)
{
    double length = vec3_length(n);
    return length > 0 && isfinite(length) ? vec3_scale(n, 1 / length)
                                          : (vec3){0, 0, 0};
}

static bool is_zero(vec3 n) { return n.x == 0 && n.y == 0 && n.z == 0; }

static vec3 blended_normal(const mesh *m, int k, const double b[3])
{
    if (m->triangle_normals == NULL)
        return (vec3){0, 0, 0};
    const int *n = m->triangle_normals[k].v;
    if (n[0] < 0 || n[1] < 0 || n[2] < 0)
        return (vec3){0, 0, 0};
    vec3 sum = {0, 0, 0};
    for (int i = 0; i < 3; i++)
        sum = vec3_add(sum, vec3_scale(m->normals[n[i]], b[i]));
    return unit_or_zero(sum);
}

/* Point, normals and side for a hit with geometric normal n_g and shading
 * normal n (either may be zero: unusable). */
static void fill_triangle_hit(vec3 n_g, vec3 n, ray r, double t, hit *h)
{
    h->t = t;
    h->point = ray_at(r, t);
    if (is_zero(n_g))
        n_g = vec3_scale(r.dir, -1); /* too small for a normal: face the ray */
    h->geometric_normal = n_g;
    h->normal = is_zero(n) ? n_g : n;
    h->inside = vec3_dot(r.dir, n_g) > 0;
}

void triangle_fill_hit(vec3 a, vec3 b, vec3 c, ray r, double t, hit *h)
{
    fill_triangle_hit(unit_or_zero(face_normal(a, b, c)), (vec3){0, 0, 0},
                      r, t, h);
}

void mesh_fill_hit(const mesh *m, int k, ray r, const triangle_hit *th,
                   hit *h)
{
    vec3 n_g = unit_or_zero(triangle_normal(m, &m->triangles[k]));
    fill_triangle_hit(n_g, blended_normal(m, k, th->b), r, th->t, h);
}

mesh_ray mesh_ray_of(ray r)
{
    return (mesh_ray){r, ray_inverse_dir(r)};
}

int mesh_nearest(const mesh *m, const mesh_ray *mr, double t_min,
                 double t_max, triangle_hit *out, render_stats *stats)
{
    stats->box_tests++;
    double near = t_min, far = t_max;
    if (!box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far))
        return -1; /* missing the box, the ray misses every triangle */
    stats->triangle_tests += m->triangle_count;
    watertight_ray shear = watertight_ray_of(mr->r); /* inside the box */
    return triangle_nearest_watertight(&shear, m->vertices, m->triangles,
                                       m->triangle_count, t_min, t_max, out);
}

bool mesh_intersect(const mesh *m, ray r, double t_min, double t_max, hit *h,
                    long long *tests)
{
    mesh_ray mr = mesh_ray_of(r);
    render_stats stats = {0};
    triangle_hit th;
    int k = mesh_nearest(m, &mr, t_min, t_max, &th, &stats);
    *tests += stats.triangle_tests;
    if (k < 0)
        return false;
    mesh_fill_hit(m, k, r, &th, h);
    return true;
}

