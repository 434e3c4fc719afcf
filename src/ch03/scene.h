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

typedef enum { BACKGROUND_SOLID, BACKGROUND_GRADIENT } background_kind;

typedef struct {
    background_kind kind;
    vec3 bottom, top; /* a solid background uses bottom only */
} background;

/* <<scene types>> ch02 */
typedef enum {
    SHAPE_SPHERE,
} shape_kind;

/* An object: a shape, and how it looks. Zero means default: a zeroed
 * object with a shape set is a valid object. */
typedef struct {
    shape_kind kind;
    union {
        sphere sphere; /* SHAPE_SPHERE */
    };
    vec3 color;
    /* <<object members>> ch03 */
    int material; /* 0: the scene's default material; k: the scene's k-th */
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


#endif
