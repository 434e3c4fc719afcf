/* mesh.h: indexed triangle meshes and their intersection (chapter 04).
 *
 * A mesh owns its arrays; mesh_free releases them. Triangles index into
 * vertices and, where the file gave them, into normals. */
#ifndef MESH_H
#define MESH_H

#include "sphere.h"
#include "triangle.h"

#define MESH_MAX_VERTICES (1 << 22)  /* 4.2 million: 100 MB of vertices */
#define MESH_MAX_TRIANGLES (1 << 23) /* 8.4 million */

typedef struct {
    vec3 *vertices;
    int vertex_count, vertex_capacity;
    vec3 *normals;
    int normal_count, normal_capacity;
    mesh_triangle *triangles;
    int triangle_count, triangle_capacity;
    int texcoord_count; /* only counted: OBJ indices must refer to them */
    vec3 lo, hi;        /* the bounding box of the vertices */
    vec3 color;
    int material;
} mesh;

void mesh_free(mesh *m);
void mesh_compute_bounds(mesh *m);

/* Gives every vertex the area-weighted mean of its triangles' normals and
 * makes every triangle use them; false when out of memory. */
bool mesh_smooth_normals(mesh *m);

/* Does r meet the box [lo, hi] for some t in (t_min, t_max)? Never says no
 * for a ray that touches the box. */
bool box_hit(vec3 lo, vec3 hi, ray r, double t_min, double t_max);

/* The nearest hit on m with t in (t_min, t_max), by the watertight test,
 * filled into h; *tests counts the triangles tested. */
bool mesh_intersect(const mesh *m, ray r, double t_min, double t_max, hit *h,
                    long long *tests);

#endif
