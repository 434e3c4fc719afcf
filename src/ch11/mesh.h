/* mesh.h: indexed triangle meshes and their intersection (chapter 4).
 *
 * A mesh owns its arrays; mesh_free releases them. Triangles index into
 * vertices; triangle_normals, when not NULL, gives for each triangle the
 * indices of its corners' normals (-1: none). */
#ifndef MESH_H
#define MESH_H

#include "box.h"
#include "hit.h"
#include "stats.h"
#include "triangle.h"
/* <<mesh includes>> ch08 */
#include "kdtree.h"
/* <<mesh includes>> += ch09 */
#include "bvh.h"
/* <<mesh includes>> += ch10 */
#include "triangle_packet.h"

#define MESH_MAX_VERTICES (1 << 22)  /* 4.2 million: 100 MB of vertices */
#define MESH_MAX_TRIANGLES (1 << 23) /* 8.4 million */

/* Where a mesh was read from and how it was placed: two meshes that agree
 * on all of it but the line are the same mesh. path is NULL for a mesh
 * made in code. */
typedef struct {
    char *path; /* owned by the mesh */
    double scale;
    vec3 offset;
    bool smooth;
    int line; /* of the scene statement that first named it, for errors */
} mesh_source;

typedef struct {
    vec3 *vertices;
    int vertex_count, vertex_capacity;
    vec3 *normals;
    int normal_count, normal_capacity;
    mesh_triangle *triangles;
    int triangle_count, triangle_capacity;
    mesh_triangle *triangle_normals; /* NULL: flat shading */
    int triangle_normals_capacity;
    int texcoord_count; /* only counted: OBJ indices must refer to them */
    box bounds;         /* of the vertices */
    mesh_source source;
    /* <<mesh members>> ch08 */
    kdtree tree;                    /* no nodes: no tree, brute force */
    triangle_corners *leaf_corners; /* tree.items' triangles, leaf by leaf */
    /* <<mesh members>> += ch09 */
    bvh bvh; /* no nodes: no BVH */
    /* <<mesh members>> += ch10 */
    triangle_packet *bvh_packets; /* the BVH's leaves' triangles, leaf by leaf */
    int bvh_packet_count;
    bool bvh_in_float; /* its leaves decided in float alone (bvh-float) */
    bool bvh_corners_in_float; /* every corner a float: the packets' exact */
    /* <<mesh members>> += ch11 */
    unsigned char bvh_walk; /* its walk: 0 binary, 2 plain, 4 AVX2, 6 AVX-512 */
} mesh;

void mesh_free(mesh *m);
void mesh_compute_bounds(mesh *m);

/* The bytes that m's arrays take, as allocated. */
long long mesh_bytes(const mesh *m);

/* Do a and b name the same file, placed the same way? */
bool mesh_source_equal(const mesh_source *a, const mesh_source *b);

/* Gives every vertex the area-weighted sum of its triangles' normals and
 * makes every triangle use them; false when out of memory. */
bool mesh_smooth_normals(mesh *m);

/* <<the mesh index declarations>> ch04 */
/* An index of meshes by their source, so that a file named twice is read
 * once: a hash table of slots holding 1 + a mesh's position in an array of
 * meshes, 0 when empty. Zero is an empty index. */
typedef struct {
    int *slots;
    int size; /* a power of two, more than twice the meshes indexed */
} mesh_index;

/* Room in x for one more than the count meshes it indexes, rebuilt from
 * meshes when it grows; false when out of memory (x is then unchanged). */
bool mesh_index_reserve(mesh_index *x, const mesh *meshes, int count);

/* Adds meshes[k], which has room (mesh_index_reserve), to x; a mesh made
 * in code, with no path, is not indexed. */
void mesh_index_add(mesh_index *x, const mesh *meshes, int k);

/* The position in meshes of a mesh with that source, or -1. */
int mesh_index_find(const mesh_index *x, const mesh *meshes,
                    const mesh_source *source);

void mesh_index_free(mesh_index *x);

/* <<mesh intersection declarations>> ch04 */
/* The hit record of a hit at th on the triangle (a, b, c): flat shaded. */
void triangle_fill_hit(vec3 a, vec3 b, vec3 c, ray r, double t, hit *h);

/* The hit record of a hit th on triangle k of m. */
void mesh_fill_hit(const mesh *m, int k, ray r, const triangle_hit *th,
                   hit *h);

/* A ray with what every box test of a mesh needs of it, computed once
 * per ray; its shear for the triangles is watertight_ray_of(r), made by
 * a search once the ray is inside the box. */
typedef struct {
    ray r;
    vec3 inv_dir; /* 1 / r.dir, for the boxes */
} mesh_ray;

mesh_ray mesh_ray_of(ray r);

/* The nearest triangle of m that mr hits in (t_min, t_max): its index and
 * its hit in *out; or -1. Counts the tests in stats. */
int mesh_nearest(const mesh *m, const mesh_ray *mr, double t_min,
                 double t_max, triangle_hit *out, render_stats *stats);

/* The nearest hit on m, filled into h: mesh_nearest and mesh_fill_hit for
 * a single ray; *tests counts the triangles tested. */
bool mesh_intersect(const mesh *m, ray r, double t_min, double t_max, hit *h,
                    long long *tests);
/* <<mesh intersection declarations>> += ch06 */

/* Rebuilds the point of h, a hit on the triangle (a, b, c) at barycentric
 * coordinates w, and sets its error bound, widened by the error of the
 * test that could meet the triangle again. */
void triangle_refine_hit(vec3 a, vec3 b, vec3 c, const double w[3], hit *h);

/* triangle_refine_hit for a hit on triangle k of m at w, the bound widened
 * for the test that m's rays make. */
void mesh_refine_hit(const mesh *m, int k, const double w[3], hit *h);
/* <<mesh intersection declarations>> += ch08 */

/* Builds m's tree with p (none for fewer than MESH_TREE_MIN_TRIANGLES);
 * false when out of memory, and then m has no tree. */
bool mesh_build_tree(mesh *m, const kdtree_params *p);

/* Frees m's tree, if it has one; m stays a mesh, searched by brute force. */
void mesh_free_tree(mesh *m);

/* The bytes m's tree holds: its nodes and items, and the corners copied
 * leaf by leaf. */
long long mesh_tree_bytes(const mesh *m);

/* Below this many triangles a mesh is searched by brute force: the
 * crossover of the chapter's chart. */
#define MESH_TREE_MIN_TRIANGLES 8

/* Does mr hit any triangle of m in (t_min, t_max)? For shadow rays. */
bool mesh_occluded(const mesh *m, const mesh_ray *mr, double t_min,
                   double t_max, render_stats *stats);

/* The walk of m's tree by mr over [near, far], the ray's interval inside
 * m's box: the nearest triangle hit in (t_min, t_max) and its hit in *out,
 * or -1; with out NULL, any triangle hit will do. */
int mesh_search_tree(const mesh *m, const mesh_ray *mr, double near,
                     double far, double t_min, double t_max,
                     triangle_hit *out, render_stats *stats);

/* mesh_nearest by the recursive walk, for the tests and the benchmark. */
int mesh_nearest_recursive(const mesh *m, const mesh_ray *mr, double t_min,
                           double t_max, triangle_hit *out,
                           render_stats *stats);
/* <<mesh intersection declarations>> += ch09 */

/* The tree a scene gives its meshes; 0: the default. */
typedef enum {
    MESH_ACCELERATOR_DEFAULT,
    MESH_ACCELERATOR_KDTREE,
    MESH_ACCELERATOR_BVH,
    /* <<more accelerators>> ch10 */
    MESH_ACCELERATOR_BVH_FLOAT, /* the BVH, its leaves decided in float */
    MESH_ACCELERATORS /* the number of names, and one more */
} mesh_accelerator;

/* <<the meshes' default tree>> ch11 */
#define MESH_DEFAULT_ACCELERATOR MESH_ACCELERATOR_BVH

/* The name of an accelerator in the scene ("kdtree", "bvh", ...);
 * "default" for MESH_ACCELERATOR_DEFAULT. */
const char *mesh_accelerator_name(mesh_accelerator a);

/* Builds m's BVH with p, in place of any tree it had (none for fewer
 * than MESH_TREE_MIN_TRIANGLES); false when out of memory, and then m
 * has no tree. */
bool mesh_build_bvh(mesh *m, const bvh_params *p);

/* The walk of m's BVH by mr: the nearest triangle hit in (t_min, t_max)
 * by the kd-tree's tie rule and its hit in *out, or -1; with out NULL,
 * any triangle hit will do. */
int mesh_search_bvh(const mesh *m, const mesh_ray *mr, double t_min,
                    double t_max, triangle_hit *out, render_stats *stats);
/* <<mesh intersection declarations>> += ch10 */

/* The bytes a triangle that a mesh's BVH holds at most, on meshes of
 * triangles of like sizes (the bunny, the teapot): packets of 44 bytes a
 * lane with a leaf's last packet partly empty, 4 for its item, and the
 * nodes. A copy of the double corners alone would be 72. */
#define MESH_BVH_MAX_BYTES_PER_TRIANGLE 100

/* triangle_refine_hit for a hit that chapter 4's test in float alone
 * found (bvh-float): the bound widened by what that test may err when it
 * meets the triangle again. */
void triangle_refine_float_hit(vec3 a, vec3 b, vec3 c, const double w[3],
                               hit *h);

#endif
