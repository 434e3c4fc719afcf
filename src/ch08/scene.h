/* scene.h: what to render (chapter 01).
 *
 * scene_init fills in the defaults, scene_free releases what the scene
 * owns. Later chapters add objects, materials, lights, and the queries that
 * find what a ray hits. The scene does not read files: scene_file.h does. */
#ifndef SCENE_H
#define SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include "camera.h"
#include "stats.h"
#include "sphere.h"
#include "light.h"
#include "material.h"
#include "mesh.h"

typedef enum { BACKGROUND_SOLID, BACKGROUND_GRADIENT } background_kind;

typedef struct {
    background_kind kind;
    vec3 bottom, top; /* a solid background uses bottom only */
} background;

typedef enum {
    SHAPE_SPHERE,
    SHAPE_TRIANGLE,
    SHAPE_MESH,
} shape_kind;

/* An object: a shape, and how it looks. Zero means default: a zeroed
 * object with a shape set is a valid object. */
typedef struct {
    shape_kind kind;
    union {
        sphere sphere; /* SHAPE_SPHERE */
        vec3 corners[3]; /* SHAPE_TRIANGLE */
        int mesh;        /* SHAPE_MESH: index into the scene's meshes */
    };
    vec3 color;
    int material; /* 0: the scene's default material; k: the scene's k-th */
} object;

typedef struct {
    camera cam;
    background bg;
    object *objects;
    int object_count, object_capacity;
    vec3 ambient; /* I_a */
    struct {
        double alpha, beta;
    } tone;
    material default_material;
    material *materials;
    int material_count, material_capacity;
    light default_light; /* used only when the scene has no light */
    light *lights;
    int light_count, light_capacity;
    mesh *meshes;
    int mesh_count, mesh_capacity;
    kdtree_params tree_params; /* as the kdtree statement sets them */
    kdtree object_tree;        /* no nodes: the objects are a list */
    int heatmap;               /* > 0: draw kd-tree nodes visited, white at
                                  this many, instead of light */
    double tree_seconds;       /* spent building the trees */
} scene;

void scene_init(scene *s);
void scene_free(scene *s);

/* A million: far beyond what a renderer without a tree can draw. */
#define SCENE_MAX_OBJECTS (1 << 20)

/* Appends o; false when out of memory or SCENE_MAX_OBJECTS is reached. */
bool scene_add_object(scene *s, object o);

/* The nearest hit along r with t in (t_min, t_max), filled into h. */
bool scene_intersect(const scene *s, ray r, double t_min, double t_max,
                     hit *h, render_stats *stats);

#define SCENE_MAX_MATERIALS 4096
#define SCENE_MAX_LIGHTS 4096 /* every light costs every shaded point */

/* The material with the given index: 0 is the default material. */
const material *scene_material(const scene *s, int index);
/* Append a material or a light; false when out of memory or at the limit. */
bool scene_add_material(scene *s, material m);
bool scene_add_light(scene *s, light L);

#define SCENE_MAX_MESHES 65536 /* meshes loaded; objects may share them */

/* Takes m over and returns its index in the scene, or -1 (out of memory,
 * or SCENE_MAX_MESHES reached: m is then the caller's to free). */
int scene_add_mesh(scene *s, mesh m);

/* Builds every mesh's tree and the tree over the objects by
 * s->tree_params; false when out of memory. */
bool scene_build_trees(scene *s);

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
 * the rectangle around its corners' images, cut to the image; 0 when a
 * corner is at or behind the eye (no estimate then). */
double scene_object_pixels(const scene *s, const object *o);

#endif
