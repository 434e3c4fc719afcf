/* render.h: tracing rays and rendering an image (chapter 01). */
#ifndef RENDER_H
#define RENDER_H

#include "image.h"
#include "scene.h"

/* Counts of the work done, for --stats. */
typedef struct {
    long long primary_rays;
    long long sphere_tests;
    long long triangle_tests;
} render_stats;

/* The colour of the background in the unit direction dir. */
vec3 background_color(const background *bg, vec3 dir);

/* The linear colour seen along the ray r. */
vec3 trace(const scene *s, ray r, render_stats *stats);

/* Renders s into img, which must be s->cam.width by s->cam.height. */
void render(const scene *s, image *img, render_stats *stats);

/* The nearest hit along r with t in (t_min, t_max), filled into h. */
bool scene_intersect(const scene *s, ray r, double t_min, double t_max, hit *h,
                     render_stats *stats);

/* The Phong model at the hit h seen from the unit direction v. */
vec3 shade(const scene *s, const hit *h, vec3 v, render_stats *stats);

#endif
