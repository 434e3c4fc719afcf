/* trace.c: what a ray sees (chapter 01). See trace.h. */
#include "trace.h"

#include "shade.h"


vec3 background_color(const background *bg, vec3 dir)
{
    if (bg->kind == BACKGROUND_SOLID)
        return bg->bottom;
    double t = 0.5 * (dir.y + 1.0); /* dir.y in [-1, 1] -> t in [0, 1] */
    return vec3_lerp(bg->bottom, bg->top, t);
}

vec3 trace(const scene *s, ray r, int depth, render_stats *stats)
{
    (void)depth; /* one bounce only, until chapter 06 */
    hit h;
    if (!scene_intersect(s, r, 0.0, INFINITY, &h, stats))
        return background_color(&s->bg, r.dir);
    vec3 color = shade(s, &h, vec3_scale(r.dir, -1), stats);
    return color;
}
