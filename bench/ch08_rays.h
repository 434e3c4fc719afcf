/* ch08_rays.h: the rays and the meshes that chapter 8's benchmarks share.
 *
 * The rays: the bounding box lo, hi of a mesh's vertices (in float),
 * c = (lo + hi) / 2, diag = |hi - lo|, the eye at c + (0, 0, K diag);
 * pixel (px, py) of a side x side image (py = 0 the top row), with
 * tx = ty = tan(30 degrees), looks along normalize(dx, dy, -1), where
 * dx = (2 (px + 0.5) / side - 1) tx and dy = (1 - 2 (py + 0.5) / side) ty;
 * t runs from 0 to infinity. Rays are kept in float, as Embree takes them,
 * and this program traces the same numbers in double.
 *
 * The meshes are read from OBJ files and their vertices rounded to float,
 * so that both programs intersect the same triangles; or made here, as
 * icospheres (unit_icosphere). */
#ifndef CH08_RAYS_H
#define CH08_RAYS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "mesh.h"
#include "obj.h"

/* A ray as Embree takes it. */
typedef struct {
    float o[3], d[3];
} float_ray;

/* x rounded to float. Through a volatile: GCC 12's vectorizer at -O2
 * drops a double-float-double round trip of two neighbouring fields. */
static inline double to_float(double x)
{
    volatile float f = (float)x;
    return f;
}

/* Reads the OBJ file at path into m with float vertices; exits on error. */
static inline void load_float_mesh(const char *path, mesh *m)
{
    parse_error err;
    *m = (mesh){0};
    if (!mesh_load_obj(m, path, &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line, err.col,
                err.message);
        exit(1);
    }
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = m->vertices[k];
        m->vertices[k] = (vec3){to_float(v.x), to_float(v.y), to_float(v.z)};
    }
    mesh_compute_bounds(m);
}

/* The side x side rays of the benchmark for m's box and the distance K. */
static inline float_ray *make_rays(const mesh *m, double K, int side)
{
    float_ray *rays = malloc((size_t)side * side * sizeof *rays);
    if (rays == NULL)
        exit(1);
    vec3 lo = m->bounds.lo, hi = m->bounds.hi; /* floats already */
    vec3 c = vec3_scale(vec3_add(lo, hi), 0.5);
    double diag = vec3_length(vec3_sub(hi, lo));
    vec3 eye = {c.x, c.y, c.z + K * diag};
    double t = tan(M_PI / 6);
    for (int py = 0; py < side; py++)
        for (int px = 0; px < side; px++) {
            double dx = (2 * (px + 0.5) / side - 1) * t;
            double dy = (1 - 2 * (py + 0.5) / side) * t;
            vec3 d = vec3_normalize((vec3){dx, dy, -1});
            float_ray *r = &rays[(size_t)py * side + px];
            *r = (float_ray){{(float)eye.x, (float)eye.y, (float)eye.z},
                             {(float)d.x, (float)d.y, (float)d.z}};
        }
    return rays;
}

static inline ray ray_of(const float_ray *f)
{
    return (ray){{f->o[0], f->o[1], f->o[2]}, {f->d[0], f->d[1], f->d[2]}};
}

/* ---------------------------------------------------------------- an icosphere */

typedef struct {
    int a, b, mid;
} edge_entry;

/* The vertex halfway along the edge (a, b), pushed out to the unit sphere,
 * made once for both triangles that share the edge (a hash of edges). */
static inline int icosphere_midpoint(mesh *m, edge_entry *table, int size, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    unsigned h = ((unsigned)lo * 2654435761u ^ (unsigned)hi * 40503u) % (unsigned)size;
    while (table[h].mid >= 0 && !(table[h].a == lo && table[h].b == hi))
        h = (h + 1) % (unsigned)size;
    if (table[h].mid < 0) {
        vec3 p = vec3_normalize(vec3_add(m->vertices[lo], m->vertices[hi]));
        m->vertices[m->vertex_count] = p;
        table[h] = (edge_entry){lo, hi, m->vertex_count++};
    }
    return table[h].mid;
}

/* Cuts every triangle of m into four at its edges' midpoints. */
static inline void icosphere_subdivide(mesh *m)
{
    int n = m->triangle_count, size = 6 * n + 1;
    edge_entry *table = malloc((size_t)size * sizeof *table);
    mesh_triangle *next = malloc(4 * (size_t)n * sizeof *next);
    if (table == NULL || next == NULL)
        exit(1);
    for (int k = 0; k < size; k++)
        table[k].mid = -1;
    for (int f = 0; f < n; f++) {
        int a = m->triangles[f].v[0], b = m->triangles[f].v[1], c = m->triangles[f].v[2];
        int ab = icosphere_midpoint(m, table, size, a, b);
        int bc = icosphere_midpoint(m, table, size, b, c);
        int ca = icosphere_midpoint(m, table, size, c, a);
        next[4 * f] = (mesh_triangle){{a, ab, ca}};
        next[4 * f + 1] = (mesh_triangle){{ab, b, bc}};
        next[4 * f + 2] = (mesh_triangle){{ca, bc, c}};
        next[4 * f + 3] = (mesh_triangle){{ab, bc, ca}};
    }
    free(m->triangles);
    m->triangles = next;
    m->triangle_count = m->triangle_capacity = 4 * n;
    free(table);
}

/* The unit icosphere of 20 4^level triangles: an icosahedron whose
 * triangles are cut into four, level times, the new vertices pushed out to
 * the unit sphere and shared by the triangles that meet there. No bounds
 * yet: the caller may still move the vertices. */
static inline mesh unit_icosphere(int level)
{
    mesh m = {0};
    int faces = 20 << (2 * level), vertices = faces / 2 + 2;
    m.vertices = malloc((size_t)vertices * sizeof *m.vertices);
    m.triangles = malloc(20 * sizeof *m.triangles);
    if (m.vertices == NULL || m.triangles == NULL)
        exit(1);
    double g = (1 + sqrt(5.0)) / 2; /* the golden ratio */
    const double c[12][3] = {{-1, g, 0}, {1, g, 0},   {-1, -g, 0}, {1, -g, 0},
                             {0, -1, g}, {0, 1, g},   {0, -1, -g}, {0, 1, -g},
                             {g, 0, -1}, {g, 0, 1},   {-g, 0, -1}, {-g, 0, 1}};
    const int ico[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int k = 0; k < 12; k++)
        m.vertices[k] = vec3_normalize((vec3){c[k][0], c[k][1], c[k][2]});
    for (int f = 0; f < 20; f++)
        m.triangles[f] = (mesh_triangle){{ico[f][0], ico[f][1], ico[f][2]}};
    m.vertex_count = 12, m.triangle_count = 20;
    for (int l = 0; l < level; l++)
        icosphere_subdivide(&m);
    return m;
}

#endif
