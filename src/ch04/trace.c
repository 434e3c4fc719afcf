/* trace.c: what a ray sees (chapter 1). See trace.h. */
#include "trace.h"

/* <<trace includes>> ch02 */
#include "search.h"
/* <<trace includes>> += ch03 */
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
    /* <<trace a ray>> ch02 */
    (void)depth; /* one bounce only, until chapter 6 */
    hit h;
    if (!scene_intersect(s, r, 0.0, INFINITY, &h, stats))
        return background_color(&s->bg, r.dir);
    /* <<shade the hit>> ch03 */
    vec3 color = shade(s, &h, vec3_scale(r.dir, -1), stats);
    return color;
}
