/* mesh.c: bounding boxes and ray-mesh intersection (chapter 04). */
#include "mesh.h"

#include <float.h>
#include <stdlib.h>

void mesh_free(mesh *m)
{
    free(m->vertices);
    free(m->normals);
    free(m->triangles);
    m->vertices = m->normals = NULL;
    m->triangles = NULL;
    m->vertex_count = m->normal_count = m->triangle_count = 0;
}

void mesh_compute_bounds(mesh *m)
{
    m->lo = (vec3){INFINITY, INFINITY, INFINITY};
    m->hi = (vec3){-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < m->vertex_count; k++) {
        vec3 v = m->vertices[k];
        m->lo = (vec3){fmin(m->lo.x, v.x), fmin(m->lo.y, v.y), fmin(m->lo.z, v.z)};
        m->hi = (vec3){fmax(m->hi.x, v.x), fmax(m->hi.y, v.y), fmax(m->hi.z, v.z)};
    }
}

/* pbrt's gamma(3) = 3u / (1 - 3u), u = 2^-53: the error bound of 3 roundings. */
#define GAMMA3 (3 * (DBL_EPSILON / 2) / (1 - 3 * (DBL_EPSILON / 2)))

bool box_hit(vec3 lo, vec3 hi, ray r, double t_min, double t_max)
{
    const double o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.dir.x, r.dir.y, r.dir.z};
    const double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int k = 0; k < 3; k++) {
        double inv = 1.0 / d[k]; /* +-infinity for a ray parallel to the slab */
        double near = (l[k] - o[k]) * inv, far = (h[k] - o[k]) * inv;
        if (near > far) {
            double swap = near;
            near = far, far = swap;
        }
        far *= 1 + 2 * GAMMA3; /* rounding must never cull a grazing ray */
        t_min = near > t_min ? near : t_min; /* a NaN leaves the interval alone */
        t_max = far < t_max ? far : t_max;
        if (t_min > t_max)
            return false;
    }
    return true;
}

/* (p1 - p0) x (p2 - p0): the sheet's n, twice the area long. */
static vec3 triangle_normal(const mesh *m, const mesh_triangle *tri)
{
    vec3 p0 = m->vertices[tri->v[0]];
    return vec3_cross(vec3_sub(m->vertices[tri->v[1]], p0), vec3_sub(m->vertices[tri->v[2]], p0));
}

bool mesh_smooth_normals(mesh *m)
{
    vec3 *normals = calloc((size_t)m->vertex_count + 1, sizeof *normals);
    if (normals == NULL)
        return false;
    for (int k = 0; k < m->triangle_count; k++) {
        vec3 n = triangle_normal(m, &m->triangles[k]);
        for (int i = 0; i < 3; i++)
            normals[m->triangles[k].v[i]] = vec3_add(normals[m->triangles[k].v[i]], n);
        for (int i = 0; i < 3; i++)
            m->triangles[k].n[i] = m->triangles[k].v[i];
    }
    free(m->normals);
    m->normals = normals;
    m->normal_count = m->normal_capacity = m->vertex_count;
    return true;
}

static vec3 shading_normal(const mesh *m, const mesh_triangle *tri, const double b[3])
{
    if (tri->n[0] >= 0 && tri->n[1] >= 0 && tri->n[2] >= 0) {
        vec3 n = {0, 0, 0};
        for (int i = 0; i < 3; i++)
            n = vec3_add(n, vec3_scale(m->normals[tri->n[i]], b[i]));
        double length = vec3_length(n);
        if (length > 0 && isfinite(length))
            return vec3_scale(n, 1 / length);
    }
    vec3 n = triangle_normal(m, tri);
    double length = vec3_length(n);
    return length > 0 && isfinite(length) ? vec3_scale(n, 1 / length) : (vec3){0, 0, 0};
}

static void mesh_fill_hit(const mesh *m, int k, ray r, const triangle_hit *th, hit *h)
{
    h->t = th->t;
    h->point = ray_at(r, th->t);
    h->normal = shading_normal(m, &m->triangles[k], th->b);
    if (h->normal.x == 0 && h->normal.y == 0 && h->normal.z == 0)
        h->normal = vec3_scale(r.dir, -1); /* too small for a normal: face the ray */
    h->color = m->color;
    h->material = m->material;
}

bool mesh_intersect(const mesh *m, ray r, double t_min, double t_max, hit *h,
                    long long *tests)
{
    if (!box_hit(m->lo, m->hi, r, t_min, t_max))
        return false; /* missing the box, the ray misses every triangle */
    *tests += m->triangle_count;
    triangle_hit best;
    int nearest = triangle_nearest_watertight(m->vertices, m->triangles, m->triangle_count, r,
                                              t_min, t_max, &best);
    if (nearest < 0)
        return false;
    mesh_fill_hit(m, nearest, r, &best, h);
    return true;
}
