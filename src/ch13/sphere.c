/* sphere.c: the ray-sphere hit used by the renderer (chapter 2). */
#include "sphere.h"
/* <<sphere.c includes>> ch06 */
#include "offset.h"

const sphere_roots_method SPHERE_ROOTS_METHODS[SPHERE_ROOTS_METHOD_COUNT] = {
    {"geometric", "double", sphere_roots_geometric},
    {"quadratic", "double", sphere_roots_quadratic},
    {"robust", "double", sphere_roots_robust},
    {"geometric", "float", sphere_roots_geometric_float},
    {"quadratic", "float", sphere_roots_quadratic_float},
    {"robust", "float", sphere_roots_robust_float},
};

bool sphere_hit_t(const sphere *sp, ray r, double t_min, double t_max,
                  double *t)
{
    double roots[2];
    if (sphere_roots_robust(sp->center, sp->radius, r, roots) == 0)
        return false;
    double nearest = roots[0] > t_min ? roots[0] : roots[1];
    if (!(nearest > t_min && nearest < t_max))
        return false;
    *t = nearest;
    return true;
}

void sphere_fill_hit(const sphere *sp, ray r, double t, hit *h)
{
    h->t = t;
    h->point = ray_at(r, t);
    /* Normalised rather than divided by the radius: unit length even when
     * the point carries the rounding error of a long ray. */
    vec3 out = vec3_sub(h->point, sp->center);
    double length = vec3_length(out);
    /* A sphere far smaller than the rounding of its distance can put the hit
     * point exactly on its centre; facing the ray is then the best guess. */
    h->normal = length > 0 ? vec3_scale(out, 1 / length)
                           : vec3_scale(r.dir, -1);
    h->geometric_normal = h->normal;
    h->inside = vec3_dot(r.dir, h->normal) > 0;
}
/* <<the sphere's hit-point bound>> ch06 */

void sphere_refine_hit(const sphere *sp, hit *h)
{
    vec3 out = vec3_sub(h->point, sp->center);
    double length = vec3_length(out);
    if (!(length > 0)) { /* on the centre: no direction to push along */
        h->error = vec3_scale(vec3_abs(h->point), gamma_bound(8));
        return;
    }
    vec3 q = vec3_scale(out, sp->radius / length); /* 5 roundings */
    h->point = vec3_add(sp->center, q);            /* and 1 more */
    h->error = vec3_add(vec3_scale(vec3_abs(q), gamma_bound(5)),
                        vec3_scale(vec3_abs(h->point), gamma_bound(1)));
}
