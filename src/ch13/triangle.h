/* triangle.h: ray-triangle intersection (chapter 4).
 *
 * Each triangle_hit_* function tests the ray r against the triangle
 * (a, b, c). On a hit with t_min < t < t_max it returns true and fills
 * *out with t and the barycentric coordinates b[0..2] of the hit point
 * (weights of a, b, c; each >= 0, summing to 1). Points on an edge count
 * as inside. A ray parallel to the plane and a degenerate (zero-area)
 * triangle give false. The _float versions compute in float and exist to
 * be measured against. */
#ifndef TRIANGLE_H
#define TRIANGLE_H

#include <stdbool.h>
#include "vec.h"

typedef struct {
    double t;
    double b[3];
} triangle_hit;

typedef bool (*triangle_method)(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                                double t_max, triangle_hit *out);

bool triangle_hit_sheet(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                        double t_max, triangle_hit *out);
bool triangle_hit_moller_trumbore(vec3 a, vec3 b, vec3 c, ray r,
                                  double t_min, double t_max,
                                  triangle_hit *out);
bool triangle_hit_watertight(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                             double t_max, triangle_hit *out);
bool triangle_hit_sheet_float(vec3 a, vec3 b, vec3 c, ray r, double t_min,
                              double t_max, triangle_hit *out);
bool triangle_hit_moller_trumbore_float(vec3 a, vec3 b, vec3 c, ray r,
                                        double t_min, double t_max,
                                        triangle_hit *out);
bool triangle_hit_watertight_float(vec3 a, vec3 b, vec3 c, ray r,
                                   double t_min, double t_max,
                                   triangle_hit *out);

/* The six methods by name ("sheet", "moller-trumbore", "watertight") and
 * precision ("double", "float"). */
typedef struct {
    const char *name, *precision;
    triangle_method hit;
} triangle_method_entry;

#define TRIANGLE_METHOD_COUNT 6
extern const triangle_method_entry TRIANGLE_METHODS[TRIANGLE_METHOD_COUNT];

/* <<the watertight test for one ray and many triangles>> ch04 */
/* The watertight test's per-ray constants: which axis the ray runs along
 * (kz) and the shear that makes it the z axis. */
typedef struct {
    int kx, ky, kz;
    double sx, sy, sz;
    vec3 origin;
} watertight_ray;

watertight_ray watertight_ray_of(ray r);

/* triangle_hit_watertight with the ray's constants computed already. */
bool triangle_hit_prepared(const watertight_ray *w, vec3 a, vec3 b, vec3 c,
                           double t_min, double t_max, triangle_hit *out);

/* A triangle of a mesh: three indices into an array of points. */
typedef struct {
    int v[3];
} mesh_triangle;

/* The nearest of count triangles that the ray hits in (t_min, t_max): its
 * index, its hit in *out; or -1. */
int triangle_nearest_watertight(const watertight_ray *w, const vec3 *vertices,
                                const mesh_triangle *triangles, int count,
                                double t_min, double t_max,
                                triangle_hit *out);
/* <<the watertight test for one ray and many triangles>> += ch08 */

/* A triangle's corners, stored whole: a tree keeps its triangles this way,
 * in the order of its leaves, so that a leaf's tests read one block. */
typedef struct {
    vec3 p[3];
} triangle_corners;

/* triangle_nearest_watertight for count triangles given by their corners:
 * the index of the nearest hit in (t_min, t_max), its hit in *out; or -1. */
int triangle_nearest_corners(const watertight_ray *w,
                             const triangle_corners *triangles, int count,
                             double t_min, double t_max, triangle_hit *out);

/* triangle_nearest_corners for the triangles of a tree's leaf, whose
 * indices in their mesh are items, keeping the tie rule across leaves: a
 * hit at t_max itself wins when its index is below best, the index of the
 * nearest hit found so far (-1: none, and t_max is excluded). */
int triangle_nearest_of_leaf(const watertight_ray *w,
                             const triangle_corners *triangles,
                             const int *items, int count, double t_min,
                             double t_max, int best, triangle_hit *out);

/* Does the ray hit any of the triangles in (t_min, t_max)? */
bool triangle_any_corners(const watertight_ray *w,
                          const triangle_corners *triangles, int count,
                          double t_min, double t_max);
/* <<the watertight test for one ray and many triangles>> += ch10 */

/* triangle_hit_prepared, tightened as a leaf's tests are: the same t and
 * barycentric coordinates to the last bit. */
bool triangle_hit_tightened(const watertight_ray *w, const vec3 *a,
                            const vec3 *b, const vec3 *c, double t_min,
                            double t_max, triangle_hit *out);

#endif
