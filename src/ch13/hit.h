/* hit.h: what a ray hit (chapter 2).
 *
 * Every shape fills the same record. Normals are unit vectors pointing out
 * of the surface (for a closed shape, away from its inside), whichever way
 * the ray came from. */
#ifndef HIT_H
#define HIT_H

#include <stdbool.h>
#include "vec.h"

typedef struct {
    double t;              /* distance along the ray */
    vec3 point;            /* o + t d */
    vec3 normal;           /* the shading normal: unit, out of the surface */
    vec3 geometric_normal; /* the surface's own normal: unit, outward */
    bool inside;           /* the ray arrived from inside: <d, n_g> > 0 */
    vec3 color;
    /* <<hit members>> ch03 */
    int material;
    /* <<hit members>> += ch06 */
    vec3 error; /* |point - the true surface point| <= error, per coordinate */
} hit;

#endif
