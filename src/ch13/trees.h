/* trees.h: the kd-trees of a scene, built within its geometry budget,
 * timed and summed up (chapter 8). */
#ifndef TREES_H
#define TREES_H

#include "scene.h"

/* <<scene tree declarations>> ch08 */
/* Why scene_build_trees failed. */
typedef struct {
    bool over_budget; /* the trees pass the geometry budget; else memory
                         ran out */
    int mesh;         /* the mesh whose tree it was; -1: the objects' */
} scene_tree_failure;

/* Builds every mesh's tree and the tree over the objects by
 * s->tree_params, adding their bytes to s->geometry_total; false (with why
 * filled, if not NULL, and no trees) when out of memory or when they would
 * pass s->geometry_budget. */
bool scene_build_trees(scene *s, scene_tree_failure *why);

/* Below this many objects a scene keeps them in a list: the crossover of
 * the chapter's chart. */
#define SCENE_TREE_MIN_OBJECTS 26

/* What the scene's trees hold, for --stats. */
typedef struct {
    int trees, depth;
    long long nodes, leaves, items, references;
} scene_tree_summary;

scene_tree_summary scene_trees(const scene *s);

/* How many pixels of the image the box around object o covers at most:
 * camera_box_pixels of its box in the world. */
double scene_object_pixels(const scene *s, const object *o);
/* <<scene tree declarations>> += ch09 */

/* The tree the scene's meshes get: --accelerator's, else the accelerator
 * statement's, else MESH_DEFAULT_ACCELERATOR. */
mesh_accelerator scene_mesh_accelerator(const scene *s);

/* What the meshes' BVHs hold, for --stats. */
typedef struct {
    int trees, width;
    long long nodes, leaves, bytes, triangles;
} scene_bvh_summary;

scene_bvh_summary scene_bvhs(const scene *s);

#endif
