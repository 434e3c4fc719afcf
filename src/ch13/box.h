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
/* <<box operations>> ch08 */

/* The area of b's surface. */
static inline double box_area(const box *b)
{
    vec3 e = vec3_sub(b->hi, b->lo);
    return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

/* Is b a box, not the empty result of a cut (lo beyond hi somewhere)? */
static inline bool box_is_valid(const box *b)
{
    return b->lo.x <= b->hi.x && b->lo.y <= b->hi.y && b->lo.z <= b->hi.z;
}

/* a cut to the box b (empty when they do not meet: see box_is_valid). */
static inline box box_cut(const box *a, const box *b)
{
    return (box){vec3_max(a->lo, b->lo), vec3_min(a->hi, b->hi)};
}

/* The part of b below (side 0) or above (side 1) the plane x on the axis. */
static inline box box_child(const box *b, int axis, double x, int side)
{
    box c = *b;
    vec3_set_axis(side == 0 ? &c.hi : &c.lo, axis, x);
    return c;
}

#endif
