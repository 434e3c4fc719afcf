/* material.h: the finish of a surface (chapter 3). */
#ifndef MATERIAL_H
#define MATERIAL_H

#include "vec.h"
/* <<material includes>> ch07 */
#include "optics.h"

typedef enum { HIGHLIGHT_PHONG, HIGHLIGHT_BLINN } highlight_model;

typedef struct {
    char name[32];
    int line;      /* where the scene defined it; 0: built in */
    vec3 emission; /* I_e */
    double ambient, diffuse, specular; /* rho_a, rho_d, rho_s in [0, 1] */
    double shininess;                  /* k >= 1 */
    highlight_model highlight;
    /* <<material members>> ch06 */
    double reflect; /* alpha_reflect in [0, 1]: 0 (the default) not a mirror */
    /* <<material members>> += ch07 */
    double ior;          /* refractive index of the inside relative to the
                            outside, 0.001 to 1000 */
    double transparency; /* in [0, 1]: 0 opaque, 1 clear */
    int fresnel;         /* FRESNEL_EXACT (0) or FRESNEL_SCHLICK, optics.h */
} material;

/* The built-in finish: the scene's default material, and where every
 * material statement starts from. */
static inline material material_default(void)
{
    material m = {.name = "default", .ambient = 0.1, .diffuse = 0.8,
                  .specular = 0.3, .shininess = 20,
                  .highlight = HIGHLIGHT_PHONG};
    /* <<material defaults>> ch07 */
    m.ior = 1.5; /* crown glass */
    return m;
}

#endif
