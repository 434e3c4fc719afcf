/* ch08_rays.h: the rays and the meshes that chapter 08's benchmarks share.
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
 * so that both programs intersect the same triangles. */
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

#endif
