/* render.c: tracing rays and rendering an image (chapter 01). */
#include "render.h"


vec3 background_color(const background *bg, vec3 dir)
{
    if (bg->kind == BACKGROUND_SOLID)
        return bg->bottom;
    double t = 0.5 * (dir.y + 1.0); /* dir.y in [-1, 1] -> t in [0, 1] */
    return vec3_lerp(bg->bottom, bg->top, t);
}

vec3 trace(const scene *s, ray r, render_stats *stats)
{
    (void)stats; /* nothing to count yet but the primary rays */
    return background_color(&s->bg, r.dir);
}

void render(const scene *s, image *img, render_stats *stats)
{
    for (int j = 0; j < img->height; j++) {
        for (int i = 0; i < img->width; i++) {
            ray r = camera_ray(&s->cam, i, j);
            stats->primary_rays++;
            vec3 c = trace(s, r, stats);
            image_set(img, i, j, c);
        }
    }
}
