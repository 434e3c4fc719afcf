/* ch09_meshes.h: the meshes that chapter 9's benchmarks make for
 * themselves, beside the bunny and the teapot of ch08_rays.h.
 *
 *   terrain_mesh(n)      a rolling landscape on an n x n grid: 2 n^2
 *                        triangles of about the same size, from 1k to 2M
 *                        for the build's chart (n = 23 .. 1000);
 *   subdivided(m, l)     m with every triangle cut into four at its edges'
 *                        midpoints, l times: the same surface in 4^l times
 *                        as many triangles (the bunny, 69,451 triangles,
 *                        becomes a 277,804-triangle scanned mesh at l = 1);
 *   needles_mesh(n, w)   n needles: triangles w wide that run right across
 *                        the unit cube, each in a random direction;
 *   slivers_mesh(n)      a cylinder of radius 1 and height 2 whose side is
 *                        n slivers, each as tall as the cylinder and
 *                        4 pi / n wide.
 *
 * All of them have float vertices (to_float), as the benchmarks give both
 * programs the same triangles, and their bounds computed. They exit on
 * running out of memory. */
#ifndef CH09_MESHES_H
#define CH09_MESHES_H

#include "../tests/rng.h"
#include "ch08_rays.h"

/* A mesh with room for the given numbers of vertices and triangles. */
static inline mesh mesh_with_room(long vertices, long triangles)
{
    mesh m = {0};
    m.vertices = malloc((size_t)vertices * sizeof *m.vertices);
    m.triangles = malloc((size_t)triangles * sizeof *m.triangles);
    if (m.vertices == NULL || m.triangles == NULL)
        exit(1);
    m.vertex_capacity = (int)vertices, m.triangle_capacity = (int)triangles;
    return m;
}

static inline void add_vertex(mesh *m, vec3 p)
{
    m->vertices[m->vertex_count++] = (vec3){to_float(p.x), to_float(p.y), to_float(p.z)};
}

static inline void add_triangle(mesh *m, int a, int b, int c)
{
    m->triangles[m->triangle_count++] = (mesh_triangle){{a, b, c}};
}

/* A smooth height in [-1, 1] at (x, z) in the unit square: a sum of waves
 * of falling size, so that the landscape has hills at every scale. */
static inline double terrain_height(double x, double z)
{
    double h = 0, amplitude = 0.5, frequency = 3;
    for (int octave = 0; octave < 5; octave++) {
        h += amplitude * sin(frequency * x + 1.7 * octave) * cos(frequency * z - 0.9 * octave);
        amplitude *= 0.5, frequency *= 2.1;
    }
    return h;
}

static inline mesh terrain_mesh(int n)
{
    mesh m = mesh_with_room((long)(n + 1) * (n + 1), 2L * n * n);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = (double)i / n, z = (double)j / n;
            add_vertex(&m, (vec3){x, 0.15 * terrain_height(x, z), z});
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            add_triangle(&m, a, c, b);
            add_triangle(&m, b, c, d);
        }
    mesh_compute_bounds(&m);
    return m;
}

/* The index of the vertex halfway along (a, b), made once for both
 * triangles that share the edge (a hash table of edges). */
static inline int flat_midpoint(mesh *m, edge_entry *table, long size, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    unsigned long h = ((unsigned long)lo * 2654435761u ^ (unsigned long)hi * 40503u) % (unsigned long)size;
    while (table[h].mid >= 0 && !(table[h].a == lo && table[h].b == hi))
        h = (h + 1) % (unsigned long)size;
    if (table[h].mid < 0) {
        add_vertex(m, vec3_scale(vec3_add(m->vertices[lo], m->vertices[hi]), 0.5));
        table[h] = (edge_entry){lo, hi, m->vertex_count - 1};
    }
    return table[h].mid;
}

static inline void subdivide_once(mesh *m)
{
    long n = m->triangle_count, size = 6 * n + 1;
    edge_entry *table = malloc((size_t)size * sizeof *table);
    mesh_triangle *next = malloc(4 * (size_t)n * sizeof *next);
    vec3 *vertices = realloc(m->vertices, ((size_t)m->vertex_count + 3 * (size_t)n) *
                                              sizeof *vertices);
    if (table == NULL || next == NULL || vertices == NULL)
        exit(1);
    m->vertices = vertices;
    for (long k = 0; k < size; k++)
        table[k].mid = -1;
    for (long f = 0; f < n; f++) {
        const int *v = m->triangles[f].v;
        int ab = flat_midpoint(m, table, size, v[0], v[1]);
        int bc = flat_midpoint(m, table, size, v[1], v[2]);
        int ca = flat_midpoint(m, table, size, v[2], v[0]);
        next[4 * f] = (mesh_triangle){{v[0], ab, ca}};
        next[4 * f + 1] = (mesh_triangle){{ab, v[1], bc}};
        next[4 * f + 2] = (mesh_triangle){{ca, bc, v[2]}};
        next[4 * f + 3] = (mesh_triangle){{ab, bc, ca}};
    }
    free(m->triangles), free(table);
    m->triangles = next;
    m->triangle_count = m->triangle_capacity = (int)(4 * n);
    m->vertex_capacity = m->vertex_count;
}

static inline void subdivided(mesh *m, int levels)
{
    for (int l = 0; l < levels; l++)
        subdivide_once(m);
    mesh_compute_bounds(m);
}

/* A point on the surface of the unit cube [0, 1]^3, chosen at random. */
static inline vec3 point_on_cube(rng_state *r)
{
    double p[3] = {rng_uniform01(r), rng_uniform01(r), rng_uniform01(r)};
    int face = (int)(rng_next(r) >> 61) % 3;
    p[face] = rng_next(r) >> 63 ? 1.0 : 0.0;
    return (vec3){p[0], p[1], p[2]};
}

static inline mesh needles_mesh(int n, double width)
{
    rng_state r = {20261201};
    mesh m = mesh_with_room(3L * n, n);
    for (int k = 0; k < n; k++) {
        vec3 a = point_on_cube(&r), b = point_on_cube(&r);
        vec3 side = vec3_scale(rng_unit_vector(&r, 0.1), width);
        add_vertex(&m, a), add_vertex(&m, b), add_vertex(&m, vec3_add(a, side));
        add_triangle(&m, 3 * k, 3 * k + 1, 3 * k + 2);
    }
    mesh_compute_bounds(&m);
    return m;
}

static inline mesh slivers_mesh(int n)
{
    int strips = n / 2; /* two slivers each */
    mesh m = mesh_with_room(2L * strips, 2L * strips);
    for (int k = 0; k < strips; k++) {
        double a = 2 * M_PI * k / strips;
        add_vertex(&m, (vec3){cos(a), -1, sin(a)});
        add_vertex(&m, (vec3){cos(a), 1, sin(a)});
    }
    for (int k = 0; k < strips; k++) {
        int b0 = 2 * k, t0 = b0 + 1, b1 = 2 * ((k + 1) % strips), t1 = b1 + 1;
        add_triangle(&m, b0, t0, b1);
        add_triangle(&m, t0, t1, b1);
    }
    mesh_compute_bounds(&m);
    return m;
}

#endif
