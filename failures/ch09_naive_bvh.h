/* ch09_naive_bvh.h: chapter 9's BVH made naive, for its failure figure
 * (ch09_boxes.c) and its benchmark (bench/ch09_bvh.c).
 *
 * The naive BVH is the program's tree, built by mesh_build_bvh, with every
 * node's box computed again around its triangles in double and rounded to
 * the NEAREST float, with no pad (naive_bvh_boxes); and its search rounds
 * the ray's origin to the nearest float too, with the interval not widened
 * (naive_bvh_nearest). The walk (bvh.h's) and the leaves' tests
 * (triangle_hit_prepared, the lower index winning a tie) are the
 * program's: the two differ only in the rounding of the boxes and of the
 * origin, which is what the figure and the chart show. */
#ifndef CH09_NAIVE_BVH_H
#define CH09_NAIVE_BVH_H

#include <stdlib.h>
#include "mesh.h"

static inline box naive_box_around(box a, box b)
{
    return (box){vec3_min(a.lo, b.lo), vec3_max(a.hi, b.hi)};
}

static inline box naive_triangle_box(const mesh *m, int k)
{
    const int *v = m->triangles[k].v;
    vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
    return (box){vec3_min(a, vec3_min(b, c)), vec3_max(a, vec3_max(b, c))};
}

/* The box around the triangles of node k of m's BVH, in double; node k and
 * every node below it store theirs rounded to the nearest float, no pad. */
static inline box naive_bvh_boxes(mesh *m, uint32_t k)
{
    bvh_node *n = &m->bvh.nodes[k];
    box b;
    if (n->count > 0) { /* a leaf: its triangles */
        b = naive_triangle_box(m, m->bvh.items[n->index]);
        for (int i = 1; i < n->count; i++)
            b = naive_box_around(
                b, naive_triangle_box(m, m->bvh.items[n->index + i]));
    } else {
        b = naive_box_around(naive_bvh_boxes(m, k + 1),
                             naive_bvh_boxes(m, n->index));
    }
    for (int a = 0; a < 3; a++) {
        n->box[a] = (float)vec3_axis(b.lo, a);
        n->box[a + 3] = (float)vec3_axis(b.hi, a);
    }
    return b;
}

/* The nearest triangle of leaf hit in (0, t_max], a hit at t_max itself
 * only when its index is below best: as the program's leaves are tested. */
static inline int naive_leaf_nearest(const mesh *m, const watertight_ray *w,
                                     bvh_leaf leaf, double t_max, int best,
                                     triangle_hit *out)
{
    int nearest = -1;
    double reach = nextafter(t_max, INFINITY); /* t_max itself, for a tie */
    for (int k = 0; k < leaf.count; k++) {
        int i = m->bvh.items[leaf.first + k];
        const int *v = m->triangles[i].v;
        triangle_hit th;
        if (triangle_hit_prepared(w, m->vertices[v[0]], m->vertices[v[1]],
                                  m->vertices[v[2]], 0, reach, &th) &&
            (th.t < t_max || i < best)) {
            *out = th, t_max = th.t, best = i, nearest = i;
            reach = nextafter(t_max, INFINITY);
        }
    }
    return nearest;
}

/* mesh_nearest over (0, infinity) through m's naive BVH, with the ray's
 * origin rounded to the nearest float: the nearest triangle and its hit
 * in *out, or -1. */
static inline int naive_bvh_nearest(const mesh *m, const mesh_ray *mr,
                                    triangle_hit *out, render_stats *stats)
{
    double near = 0, far = INFINITY;
    if (!box_clip(&m->bounds, mr->r.origin, mr->inv_dir, &near, &far))
        return -1;
    bvh_ray r;
    if (!bvh_ray_of(mr->r.origin, mr->inv_dir, 0, INFINITY, &r))
        abort(); /* no ray of the figure or the chart is beyond float */
    for (int a = 0; a < 3; a++) /* the origin rounded to nearest */
        r.o_near[a] = r.o_far[a] = (float)vec3_axis(mr->r.origin, a);
    r.t_min = 0, r.t_max = INFINITY;
    bvh_walk w;
    bvh_leaf leaf;
    int found = -1;
    double t_max = INFINITY;
    watertight_ray shear = watertight_ray_of(mr->r);
    bvh_walk_start(&w, &m->bvh, &r);
    while (bvh_walk_next(&w, t_max, &leaf)) {
        stats->triangle_tests += leaf.count;
        int k = naive_leaf_nearest(m, &shear, leaf, t_max, found, out);
        if (k >= 0)
            found = k, t_max = out->t;
    }
    stats->bvh_nodes += w.visited;
    return found;
}

#endif
