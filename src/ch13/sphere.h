/* sphere.h: spheres and ray-sphere intersection (chapter 2).
 *
 * The sphere_roots_* functions solve |o + t d - center| = radius for t. Each
 * returns the number of roots, 0 or 2 (a tangent gives two equal roots),
 * and stores them in t[0] <= t[1]; roots behind the origin are included.
 * _geometric needs |d| = 1; the others take any d != 0. The _float
 * versions compute in float and exist to be measured against. */
#ifndef SPHERE_H
#define SPHERE_H

#include <stdbool.h>
#include "hit.h"

typedef struct {
    vec3 center;
    double radius; /* > 0 */
} sphere;

typedef int (*sphere_roots_fn)(vec3 center, double radius, ray r,
                               double t[2]);

int sphere_roots_geometric(vec3 center, double radius, ray r, double t[2]);
int sphere_roots_quadratic(vec3 center, double radius, ray r, double t[2]);
int sphere_roots_robust(vec3 center, double radius, ray r, double t[2]);
int sphere_roots_geometric_float(vec3 center, double radius, ray r,
                                 double t[2]);
int sphere_roots_quadratic_float(vec3 center, double radius, ray r,
                                 double t[2]);
int sphere_roots_robust_float(vec3 center, double radius, ray r,
                              double t[2]);

/* The six forms by name ("geometric", "quadratic", "robust") and
 * precision ("double", "float"). */
typedef struct {
    const char *name, *precision;
    sphere_roots_fn roots;
} sphere_roots_method;

#define SPHERE_ROOTS_METHOD_COUNT 6
extern const sphere_roots_method
    SPHERE_ROOTS_METHODS[SPHERE_ROOTS_METHOD_COUNT];

/* The nearest root in (t_min, t_max), by the robust form; false if none. */
bool sphere_hit_t(const sphere *sp, ray r, double t_min, double t_max,
                  double *t);

/* Fills the geometry of h for the hit at t: t, point, normals, side. */
void sphere_fill_hit(const sphere *sp, ray r, double t, hit *h);
/* <<declaring the sphere's hit-point bound>> ch06 */

/* Moves the point of h, a hit on sp, back onto the sphere and sets its
 * error bound. */
void sphere_refine_hit(const sphere *sp, hit *h);

#endif
