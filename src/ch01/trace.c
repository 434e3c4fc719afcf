/* trace.c: what a ray sees (chapter 1). See trace.h. */
#include "trace.h"



vec3 background_color(const background *bg, vec3 dir)
{
    if (bg->kind == BACKGROUND_SOLID)
        return bg->bottom;
    double t = 0.5 * (dir.y + 1.0); /* dir.y in [-1, 1] -> t in [0, 1] */
    return vec3_lerp(bg->bottom, bg->top, t);
}

vec3 trace(const scene *s, ray r, int depth, render_stats *stats)
{
    /* <<trace a ray>> ch01 */
    (void)depth, (void)stats; /* no bounces and nothing to count yet */
    return background_color(&s->bg, r.dir);
}
