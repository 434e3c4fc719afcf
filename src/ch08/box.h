/* box.h: axis-aligned boxes and the ray-box test (chapter 4). */
#ifndef BOX_H
#define BOX_H

#include <stdbool.h>
#include "vec.h"

typedef struct {
    vec3 lo, hi;
} box;

/* 1 / d per component: +-infinity where d has a zero component. */
static inline vec3 ray_inverse_dir(ray r)
{
    return (vec3){1.0 / r.dir.x, 1.0 / r.dir.y, 1.0 / r.dir.z};
}

/* Narrows [*t_min, *t_max] to where origin + t d is inside b, given
 * inv = 1 / d; false when nothing is left. Never loses a ray that touches
 * the box. */
bool box_clip(const box *b, vec3 origin, vec3 inv, double *t_min,
              double *t_max);

/* Does r meet the box [lo, hi] for some t in (t_min, t_max)? */
bool box_hit(vec3 lo, vec3 hi, ray r, double t_min, double t_max);

#endif
