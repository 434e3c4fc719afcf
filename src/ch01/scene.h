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

typedef enum { BACKGROUND_SOLID, BACKGROUND_GRADIENT } background_kind;

typedef struct {
    background_kind kind;
    vec3 bottom, top; /* a solid background uses bottom only */
} background;


typedef struct {
    camera cam;
    background bg;
    /* told when a phase of the loading begins ("reading the scene"), for
     * the progress line; NULL: no one is told */
    void (*on_phase)(void *context, const char *phase);
    void *phase_context;
    int image_line; /* the line of the image statement; 0: none */
} scene;

void scene_init(scene *s);
void scene_free(scene *s);

/* Tells s->on_phase, if there is one, that the loading now does what. */
void scene_phase(const scene *s, const char *what);



#endif
