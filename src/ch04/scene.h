/* scene.h: what to render, and the scene file parser (chapter 01).
 *
 * scene_init fills in the defaults; scene_parse and scene_load apply a scene
 * file on top of them. A parser never prints: on bad input it returns false
 * and describes the first problem in a scene_error. */
#ifndef SCENE_H
#define SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include "camera.h"
#include "sphere.h"
#include "shade.h"
#include "mesh.h"

typedef enum { BACKGROUND_SOLID, BACKGROUND_GRADIENT } background_kind;

typedef struct {
    background_kind kind;
    vec3 bottom, top; /* a solid background uses bottom only */
} background;

typedef struct {
    camera cam;
    background bg;
    sphere *spheres;
    int sphere_count, sphere_capacity;
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
} scene;

#define SCENE_MAX_BYTES (16L << 20) /* a scene file is text, not data */

typedef struct {
    char file[256];
    int line, col; /* 1-based; line 0: the problem is the file as a whole */
    char message[256];
} scene_error;

#define SCENE_MAX_SPHERES (1 << 20) /* a million: far beyond what ch02 can render */
#define SCENE_MAX_MATERIALS 4096
#define SCENE_MAX_LIGHTS 4096 /* every light costs every shaded point */
#define SCENE_MAX_MESHES 65536 /* each mesh is tested by every ray: keep them few */
#define OBJ_MAX_BYTES (512L << 20)

void scene_init(scene *s);
void scene_free(scene *s);

/* Reads statements from text[0..length); name is the file name for errors. */
bool scene_parse(scene *s, const char *text, size_t length, const char *name,
                 scene_error *err);

/* Reads the scene file at path (at most SCENE_MAX_BYTES) and parses it. */
bool scene_load(scene *s, const char *path, scene_error *err);

/* Appends sp; false when out of memory or SCENE_MAX_SPHERES is reached. */
bool scene_add_sphere(scene *s, sphere sp);

/* The material with the given index: 0 is the default material. */
const material *scene_material(const scene *s, int index);
/* Append a material or a light; false when out of memory or at the limit. */
bool scene_add_material(scene *s, material m);
bool scene_add_light(scene *s, light L);

/* Reads the OBJ file at path into the zeroed mesh m; on bad input fills err
 * (the OBJ file's line and column) and returns false, m then holding what
 * was read so far for mesh_free. */
bool mesh_load_obj(mesh *m, const char *path, scene_error *err);

/* The same for OBJ text already in memory, text[0..length), called name. */
bool mesh_parse_obj(mesh *m, const char *text, size_t length, const char *name,
                    scene_error *err);
bool scene_add_mesh(scene *s, mesh m);

#endif
