/* trees.c: the scene's kd-trees: built once the scene is read, within its
 * budget, timed, and summed up for --stats (chapter 8). */
#include "trees.h"

#include <stdlib.h>
#include <time.h>
#include "memory.h"
#include "offset.h"

/* <<moving a box into the world>> ch08 */
/* The world box around b's eight corners moved by t, widened by the
 * rounding of the move: gamma_4 times the sum of the magnitudes of the
 * terms mat4_mul_point adds, at the largest coordinates of b. */
static box box_to_world(const transform *t, box b)
{
    const double(*m)[4] = t->m.m;
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = vec3_scale(lo, -1);
    for (int k = 0; k < 8; k++) {
        vec3 p = mat4_mul_point(t->m, (vec3){k & 1 ? b.hi.x : b.lo.x,
                                             k & 2 ? b.hi.y : b.lo.y,
                                             k & 4 ? b.hi.z : b.lo.z});
        lo = vec3_min(lo, p), hi = vec3_max(hi, p);
    }
    vec3 far = vec3_max(vec3_abs(b.lo), vec3_abs(b.hi)); /* |p_j| at most */
    double pad[3];
    for (int i = 0; i < 3; i++)
        pad[i] = gamma_bound(4) * (fabs(m[i][0]) * far.x +
                                   fabs(m[i][1]) * far.y +
                                   fabs(m[i][2]) * far.z + fabs(m[i][3]));
    vec3 d = {pad[0], pad[1], pad[2]};
    return (box){vec3_sub(lo, d), vec3_add(hi, d)};
}

/* <<the object's box in the world>> ch08 */
/* The box around o, in the world. */
static box object_bounds(const scene *s, const object *o)
{
    box b = {{0, 0, 0}, {0, 0, 0}};
    switch (o->kind) {
    case SHAPE_SPHERE: {
        double r = o->sphere.radius;
        vec3 c = o->sphere.center, e = {r, r, r};
        b = (box){vec3_sub(c, e), vec3_add(c, e)};
        break;
    }
    case SHAPE_TRIANGLE: {
        const vec3 *p = o->corners;
        b = (box){vec3_min(p[0], vec3_min(p[1], p[2])),
                  vec3_max(p[0], vec3_max(p[1], p[2]))};
        break;
    }
    case SHAPE_MESH:
        b = s->meshes[o->mesh].bounds;
        break;
    }
    /* <<move the object's box into the world>> ch08 */
    if (o->transform != 0)
        b = box_to_world(scene_transform(s, o->transform), b);
    return b;
}

/* <<building the objects' tree>> ch08 */
/* An object cut to a cell: its box cut to the cell (context: the boxes). */
static bool clip_object(const void *context, int item, const box *cell,
                        box *out)
{
    const box *b = (const box *)context + item;
    *out = (box){vec3_max(b->lo, cell->lo), vec3_min(b->hi, cell->hi)};
    return out->lo.x <= out->hi.x && out->lo.y <= out->hi.y &&
           out->lo.z <= out->hi.z;
}

static bool build_object_tree(scene *s)
{
    kdtree_params p = s->tree_params;
    p.min_items = p.min_items > 0 ? p.min_items : SCENE_TREE_MIN_OBJECTS;
    box *bounds = memory_alloc((size_t)s->object_count, sizeof *bounds);
    for (int k = 0; bounds != NULL && k < s->object_count; k++)
        bounds[k] = object_bounds(s, &s->objects[k]);
    bool ok = bounds != NULL && kdtree_build(&s->object_tree, s->object_count,
                                             bounds, clip_object, bounds, &p);
    free(bounds);
    return ok;
}

/* <<building the scene's trees>> ch08 */
/* Builds mesh m's tree as the scene asks; false when out of memory. */
static bool build_mesh_tree(const scene *s, mesh *m)
{
    /* <<the scene's other trees of a mesh>> ch09 */
    if (scene_mesh_accelerator(s) == MESH_ACCELERATOR_BVH)
        return mesh_build_bvh(m, &s->bvh_settings);
    /* <<the scene's other trees of a mesh>> += ch10 */
    if (scene_mesh_accelerator(s) == MESH_ACCELERATOR_BVH_FLOAT) {
        bool built = mesh_build_bvh(m, &s->bvh_settings);
        m->bvh_in_float = built;
        return built;
    }
    return mesh_build_tree(m, &s->tree_params);
}

/* Adds bytes to the scene's geometry; false when that passes the budget. */
static bool count_tree(scene *s, long long bytes)
{
    s->geometry_total += bytes;
    return s->geometry_total <= s->geometry_budget;
}

/* Builds the trees, stopping at the first that fails, the failure in why. */
static bool build_all(scene *s, scene_tree_failure *why)
{
    for (int k = 0; k < s->mesh_count; k++) {
        mesh *m = &s->meshes[k];
        *why = (scene_tree_failure){.mesh = k};
        if (!build_mesh_tree(s, m))
            return false;
        if (!count_tree(s, mesh_tree_bytes(m)))
            return why->over_budget = true, false;
    }
    *why = (scene_tree_failure){.mesh = -1};
    if (!build_object_tree(s))
        return false;
    return count_tree(s, kdtree_bytes(&s->object_tree)) ||
           (why->over_budget = true, false);
}

bool scene_build_trees(scene *s, scene_tree_failure *why)
{
    struct timespec start, end;
    scene_tree_failure failure;
    clock_gettime(CLOCK_MONOTONIC, &start);
    long long before = s->geometry_total;
    bool ok = build_all(s, &failure);
    if (!ok) { /* no trees: the scene is as it was before */
        for (int k = 0; k < s->mesh_count; k++)
            mesh_free_tree(&s->meshes[k]);
        kdtree_free(&s->object_tree);
        s->geometry_total = before;
        if (why != NULL)
            *why = failure;
    }
    clock_gettime(CLOCK_MONOTONIC, &end);
    s->tree_seconds = (double)(end.tv_sec - start.tv_sec) +
                      1e-9 * (double)(end.tv_nsec - start.tv_nsec);
    return ok;
}

/* <<what the trees hold>> ch08 */
static void add_tree(scene_tree_summary *sum, const kdtree *t)
{
    if (t->node_count == 0)
        return;
    sum->trees++;
    sum->nodes += t->node_count;
    sum->leaves += t->leaf_count;
    sum->references += t->item_count;
    sum->depth = t->depth > sum->depth ? t->depth : sum->depth;
}

scene_tree_summary scene_trees(const scene *s)
{
    scene_tree_summary sum = {0};
    for (int k = 0; k < s->mesh_count; k++) {
        add_tree(&sum, &s->meshes[k].tree);
        sum.items += s->meshes[k].tree.node_count ? s->meshes[k].triangle_count
                                                  : 0;
    }
    add_tree(&sum, &s->object_tree);
    sum.items += s->object_tree.node_count ? s->object_count : 0;
    return sum;
}
/* <<what the trees hold>> += ch09 */

mesh_accelerator scene_mesh_accelerator(const scene *s)
{
    if (s->accelerator_option || s->accelerator)
        return s->accelerator_option ? s->accelerator_option
                                     : s->accelerator;
    /* the heat map draws kd-tree nodes: it asks for kd-trees */
    return s->heatmap > 0 ? MESH_ACCELERATOR_KDTREE
                          : MESH_DEFAULT_ACCELERATOR;
}

scene_bvh_summary scene_bvhs(const scene *s)
{
    scene_bvh_summary sum = {0};
    for (int k = 0; k < s->mesh_count; k++) {
        const mesh *m = &s->meshes[k];
        if (m->bvh.node_count == 0)
            continue;
        sum.trees++, sum.width = m->bvh.width;
        sum.nodes += m->bvh.node_count, sum.leaves += m->bvh.leaf_count;
        sum.bytes += mesh_tree_bytes(m), sum.triangles += m->triangle_count;
    }
    return sum;
}

/* <<the object's size on the image>> ch08 */
double scene_object_pixels(const scene *s, const object *o)
{
    box b = object_bounds(s, o);
    return camera_box_pixels(&s->cam, b.lo, b.hi);
}
