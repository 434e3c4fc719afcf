/* scene.h: what to render (chapter 1).
 *
 * scene_init fills in the defaults, scene_free releases what the scene
 * owns. Later chapters add objects, materials, lights, meshes and
 * transforms. The scene neither reads files (scene_file.h does) nor finds
 * what a ray hits (search.h does, from chapter 2). */
#ifndef SCENE_H
#define SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include "camera.h"
#include "stats.h"
/* <<scene includes>> ch02 */
#include "sphere.h"
/* <<scene includes>> += ch03 */
#include "light.h"
#include "material.h"
/* <<scene includes>> += ch04 */
#include "mesh.h"

typedef enum { BACKGROUND_SOLID, BACKGROUND_GRADIENT } background_kind;

typedef struct {
    background_kind kind;
    vec3 bottom, top; /* a solid background uses bottom only */
} background;

/* <<scene types>> ch02 */
typedef enum {
    SHAPE_SPHERE,
    /* <<shape kinds>> ch04 */
    SHAPE_TRIANGLE,
    SHAPE_MESH,
} shape_kind;

/* An object: a shape, and how it looks. Zero means default: a zeroed
 * object with a shape set is a valid object. */
typedef struct {
    shape_kind kind;
    union {
        sphere sphere; /* SHAPE_SPHERE */
        /* <<shapes of an object>> ch04 */
        vec3 corners[3]; /* SHAPE_TRIANGLE */
        int mesh;        /* SHAPE_MESH: index into the scene's meshes */
    };
    vec3 color;
    /* <<object members>> ch03 */
    int material; /* 0: the scene's default material; k: the scene's k-th */
    /* <<object members>> += ch05 */
    int transform; /* 0: none, its space is the world; k: the scene's k-th */
    /* <<object members>> += ch07 */
    bool checkered; /* color and checker alternate in cubes of side tile */
    vec3 checker;
    double tile; /* > 0; 0 means 1 */
} object;

typedef struct {
    camera cam;
    background bg;
    /* told when a phase of the loading begins ("reading the scene"), for
     * the progress line; NULL: no one is told */
    void (*on_phase)(void *context, const char *phase);
    void *phase_context;
    int image_line; /* the line of the image statement; 0: none */
    /* <<scene members>> ch02 */
    object *objects;
    int object_count, object_capacity;
    /* <<scene members>> += ch03 */
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
    /* <<scene members>> += ch04 */
    mesh *meshes;
    int mesh_count, mesh_capacity;
    long long triangle_budget, geometry_budget; /* for all meshes together */
    long long triangle_total, geometry_total;   /* what the meshes take now */
    mesh_index mesh_index; /* the meshes by source */
    /* <<scene members>> += ch05 */
    transform *transforms;
    int transform_count, transform_capacity;
    int camera_placed_on; /* the line of the last statement that placed the
                             camera; 0: none did */
    /* <<scene members>> += ch06 */
    int max_depth; /* reflections deeper than this are not traced */
    double cutoff; /* nor those whose weight would fall below this */
    /* <<scene members>> += ch08 */
    kdtree_params tree_params; /* as the kdtree statement sets them */
    kdtree object_tree;        /* no nodes: the objects are a list */
    int heatmap;               /* > 0: draw kd-tree nodes visited, white at
                                  this many, instead of light */
    double tree_seconds;       /* spent building the trees */
    /* <<scene members>> += ch09 */
    mesh_accelerator accelerator;        /* the accelerator statement's */
    mesh_accelerator accelerator_option; /* --accelerator's, which wins */
    int accelerator_line;                /* of the accelerator statement */
    bvh_params bvh_settings;             /* zero: the defaults */
} scene;

void scene_init(scene *s);
void scene_free(scene *s);

/* Tells s->on_phase, if there is one, that the loading now does what. */
void scene_phase(const scene *s, const char *what);

/* <<scene array declarations>> ch02 */
/* A million: far beyond what a renderer without a tree can draw. */
#define SCENE_MAX_OBJECTS (1 << 20)

/* Appends o; false when out of memory or SCENE_MAX_OBJECTS is reached. */
bool scene_add_object(scene *s, object o);
/* <<scene array declarations>> += ch03 */

#define SCENE_MAX_MATERIALS 4096
#define SCENE_MAX_LIGHTS 4096 /* every light costs every shaded point */

/* The material with the given index: 0 is the default material. */
const material *scene_material(const scene *s, int index);
/* Append a material or a light; false when out of memory or at the limit. */
bool scene_add_material(scene *s, material m);
bool scene_add_light(scene *s, light L);
/* <<scene array declarations>> += ch04 */

#define SCENE_MAX_MESHES 65536 /* meshes loaded; objects may share them */
#define SCENE_MAX_TRIANGLES (1LL << 24)       /* of all meshes together */
#define SCENE_MAX_GEOMETRY_BYTES (1LL << 30) /* 1 GiB of mesh arrays */

/* Takes m over and returns its index in the scene, or -1 (out of memory,
 * or SCENE_MAX_MESHES reached: m is then the caller's to free). Adds what
 * m takes to the scene's totals; keeping to the budget is the caller's
 * part. */
int scene_add_mesh(scene *s, mesh m);

/* The index of a mesh with that source, or -1. */
int scene_find_mesh(const scene *s, const mesh_source *source);
/* <<scene array declarations>> += ch05 */

#define SCENE_MAX_TRANSFORMS SCENE_MAX_OBJECTS /* at most one per object */

/* Appends t and returns its index k >= 1, for object.transform; -1 when
 * out of memory or at the limit. */
int scene_add_transform(scene *s, transform t);
/* The transform with index k >= 1. */
const transform *scene_transform(const scene *s, int k);

/* <<whole-scene question declarations>> ch05 */

/* The triangles the scene stores (in its meshes and lone triangles) and
 * the triangles its objects draw (a mesh counts once per object). */
void scene_count_triangles(const scene *s, long long *stored,
                           long long *instanced);
/* <<whole-scene question declarations>> += ch06 */

/* Could anything in s block a shadow ray leaving the hit h towards a light
 * above its surface? False only for a lone sphere hit from outside and a
 * lone triangle, which cannot shadow themselves. */
bool scene_can_shadow(const scene *s, const hit *h);

/* The shadow rays one shaded point may cast: one a light, an area light's
 * samples. */
long scene_shadow_rays(const scene *s);

#endif
