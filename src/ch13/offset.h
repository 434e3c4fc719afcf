/* offset.h: where a secondary ray starts (chapter 6).
 *
 * A ray that leaves a surface starts at the hit point moved along the
 * geometric normal, to the side the ray leaves by, just past the bound of
 * the point's rounding error: never on the wrong side of the surface, and
 * never farther from it than the rounding requires. */
#ifndef OFFSET_H
#define OFFSET_H

#include <float.h>
#include "hit.h"

/* gamma_n = n u / (1 - n u): n roundings to the unit u change a value by
 * at most this factor (Higham 2002, lemma 3.1). */
static inline double gamma_of_unit(int n, double u)
{
    double nu = n * u;
    return nu / (1 - nu);
}

/* gamma_n for double's roundings, u = 2^-53. */
static inline double gamma_bound(int n)
{
    return gamma_of_unit(n, DBL_EPSILON / 2);
}

static inline vec3 vec3_abs(vec3 a)
{
    return (vec3){fabs(a.x), fabs(a.y), fabs(a.z)};
}

/* The origin of a ray leaving point (error bound error, geometric normal
 * n_g) towards dir. */
vec3 offset_origin(vec3 point, vec3 error, vec3 n_g, vec3 dir);

/* The ray that leaves the hit h in the unit direction dir. */
ray ray_leaving(const hit *h, vec3 dir);

#endif
