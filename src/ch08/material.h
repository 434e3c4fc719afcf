/* material.h: the finish of a surface (chapter 03). */
#ifndef MATERIAL_H
#define MATERIAL_H

#include "vec.h"

typedef enum { HIGHLIGHT_PHONG, HIGHLIGHT_BLINN } highlight_model;

typedef struct {
    char name[32];
    int line;      /* where the scene defined it; 0: built in */
    vec3 emission; /* I_e */
    double ambient, diffuse, specular; /* rho_a, rho_d, rho_s in [0, 1] */
    double shininess;                  /* k >= 1 */
    highlight_model highlight;
} material;

/* The built-in finish: the scene's default material, and where every
 * material statement starts from. */
static inline material material_default(void)
{
    material m = {.name = "default", .ambient = 0.1, .diffuse = 0.8,
                  .specular = 0.3, .shininess = 20,
                  .highlight = HIGHLIGHT_PHONG};
    return m;
}

#endif
