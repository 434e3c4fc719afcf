/* offset.c: where a secondary ray starts (chapter 6). See offset.h. */
#include "offset.h"

/* x moved one more double in the direction of the offset, so that the
 * rounding of the sum cannot take back part of it. */
static double round_away(double x, double offset)
{
    if (offset > 0)
        return nextafter(x, INFINITY);
    if (offset < 0)
        return nextafter(x, -INFINITY);
    return x;
}

vec3 offset_origin(vec3 point, vec3 error, vec3 n_g, vec3 dir)
{
    double d = vec3_dot(vec3_abs(n_g), error); /* the error's reach */
    vec3 offset = vec3_scale(n_g, vec3_dot(dir, n_g) < 0 ? -d : d);
    vec3 o = vec3_add(point, offset);
    return (vec3){round_away(o.x, offset.x), round_away(o.y, offset.y),
                  round_away(o.z, offset.z)};
}

ray ray_leaving(const hit *h, vec3 dir)
{
    return (ray){offset_origin(h->point, h->error, h->geometric_normal, dir),
                 dir};
}
