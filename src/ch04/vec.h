/* vec.h: 3-vectors and rays (chapter 1).
 *
 * A vec3 is a point, a direction or a linear RGB colour; the function's name
 * says which it expects. All functions take and return values, never
 * pointers, and never fail. */
#ifndef VEC_H
#define VEC_H

#include <math.h>

typedef struct {
    double x, y, z;
} vec3;

/* <<vector operations>> ch01 */
static inline vec3 vec3_add(vec3 a, vec3 b)
{
    return (vec3){a.x + b.x, a.y + b.y, a.z + b.z};
}

static inline vec3 vec3_sub(vec3 a, vec3 b)
{
    return (vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}

static inline vec3 vec3_scale(vec3 a, double s)
{
    return (vec3){a.x * s, a.y * s, a.z * s};
}

/* Component by component: how a surface colour filters a light colour. */
static inline vec3 vec3_mul(vec3 a, vec3 b)
{
    return (vec3){a.x * b.x, a.y * b.y, a.z * b.z};
}

static inline double vec3_dot(vec3 a, vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline double vec3_length(vec3 a) { return sqrt(vec3_dot(a, a)); }

/* a scaled to length 1; a must not be the zero vector. */
static inline vec3 vec3_normalize(vec3 a)
{
    return vec3_scale(a, 1.0 / vec3_length(a));
}

/* (1 - t) a + t b: a at t = 0, b at t = 1. */
static inline vec3 vec3_lerp(vec3 a, vec3 b, double t)
{
    return vec3_add(vec3_scale(a, 1.0 - t), vec3_scale(b, t));
}

/* <<math constants>> ch01 */
#ifndef M_PI
#define M_PI 3.14159265358979323846 /* POSIX has it; strict C11 does not */
#endif
/* <<vector operations>> += ch03 */

/* Is a finite and not zero: a direction that can be normalised? */
static inline int vec3_is_direction(vec3 a)
{
    int finite = isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
    return finite && (a.x != 0 || a.y != 0 || a.z != 0);
}

/* The unit vector along a, for any a that vec3_is_direction accepts. */
static inline vec3 vec3_normalize_scaled(vec3 a)
{
    double d = vec3_dot(a, a);
    if (d >= 0x1p-900 && d <= 0x1p900)
        return vec3_normalize(a); /* no square lost a bit that matters */
    double m = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    return vec3_normalize((vec3){a.x / m, a.y / m, a.z / m});
}
/* <<vector operations>> += ch04 */

static inline vec3 vec3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                  a.x * b.y - a.y * b.x};
}

/* <<ray type>> ch01 */
/* The half-line origin + t dir, t >= 0. Rays made by the renderer have
 * |dir| = 1, so that t is a distance. */
typedef struct {
    vec3 origin, dir;
} ray;

static inline vec3 ray_at(ray r, double t)
{
    return vec3_add(r.origin, vec3_scale(r.dir, t));
}


#endif
