/* box.c: the ray-box test (chapter 4). */
#include "box.h"

#include <float.h>

/* pbrt's gamma(3) = 3u / (1 - 3u), u = 2^-53: the bound of 3 roundings */
#define GAMMA3 (3 * (DBL_EPSILON / 2) / (1 - 3 * (DBL_EPSILON / 2)))

bool box_clip(const box *b, vec3 origin, vec3 inv, double *t_min,
              double *t_max)
{
    const double o[3] = {origin.x, origin.y, origin.z};
    const double i[3] = {inv.x, inv.y, inv.z};
    const double l[3] = {b->lo.x, b->lo.y, b->lo.z};
    const double h[3] = {b->hi.x, b->hi.y, b->hi.z};
    for (int k = 0; k < 3; k++) {
        double near = (l[k] - o[k]) * i[k], far = (h[k] - o[k]) * i[k];
        if (near > far) {
            double swap = near;
            near = far, far = swap;
        }
        far *= 1 + 2 * GAMMA3; /* rounding must never cull a grazing ray */
        /* a NaN compares false and leaves the interval alone */
        *t_min = near > *t_min ? near : *t_min;
        *t_max = far < *t_max ? far : *t_max;
        if (*t_min > *t_max)
            return false;
    }
    return true;
}

bool box_hit(vec3 lo, vec3 hi, ray r, double t_min, double t_max)
{
    box b = {lo, hi};
    return box_clip(&b, r.origin, ray_inverse_dir(r), &t_min, &t_max);
}
