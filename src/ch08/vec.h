/* vec.h: 3-vectors and rays (chapter 01).
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

#ifndef M_PI
#define M_PI 3.14159265358979323846 /* POSIX has it; strict C11 does not */
#endif

static inline vec3 vec3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                  a.x * b.y - a.y * b.x};
}

/* Component axis (0: x, 1: y, 2: z) of v. */
static inline double vec3_axis(vec3 v, int axis)
{
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

static inline void vec3_set_axis(vec3 *v, int axis, double value)
{
    *(axis == 0 ? &v->x : axis == 1 ? &v->y : &v->z) = value;
}

/* Component by component: the corners of the box around a and b. */
static inline vec3 vec3_min(vec3 a, vec3 b)
{
    return (vec3){a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y,
                  a.z < b.z ? a.z : b.z};
}

static inline vec3 vec3_max(vec3 a, vec3 b)
{
    return (vec3){a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y,
                  a.z > b.z ? a.z : b.z};
}

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
