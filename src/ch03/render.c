/* render.c: tracing rays and rendering an image (chapter 01). */
#include "render.h"

bool scene_intersect(const scene *s, ray r, double t_min, double t_max, hit *h,
                     render_stats *stats)
{
    const sphere *nearest = NULL;
    double t;
    for (int k = 0; k < s->sphere_count; k++) {
        stats->sphere_tests++;
        if (sphere_hit_t(&s->spheres[k], r, t_min, t_max, &t)) {
            t_max = t; /* from now on only nearer hits count */
            nearest = &s->spheres[k];
        }
    }
    bool found = false; /* set when another kind of shape is hit nearer, and fills h */
    if (!found && nearest != NULL)
        sphere_fill_hit(nearest, r, t_max, h);
    return found || nearest != NULL;
}

vec3 background_color(const background *bg, vec3 dir)
{
    if (bg->kind == BACKGROUND_SOLID)
        return bg->bottom;
    double t = 0.5 * (dir.y + 1.0); /* dir.y in [-1, 1] -> t in [0, 1] */
    return vec3_lerp(bg->bottom, bg->top, t);
}

vec3 trace(const scene *s, ray r, render_stats *stats)
{
    hit h;
    if (!scene_intersect(s, r, 0.0, INFINITY, &h, stats))
        return background_color(&s->bg, r.dir);
    return shade(s, &h, vec3_scale(r.dir, -1), stats);
}

void render(const scene *s, image *img, render_stats *stats)
{
    for (int j = 0; j < img->height; j++) {
        for (int i = 0; i < img->width; i++) {
            ray r = camera_ray(&s->cam, i, j);
            stats->primary_rays++;
            vec3 c = trace(s, r, stats);
            if (s->tone.alpha != 1 || s->tone.beta != 1) /* the defaults only clip */
                c = (vec3){tone_map(c.x, s->tone.alpha, s->tone.beta),
                           tone_map(c.y, s->tone.alpha, s->tone.beta),
                           tone_map(c.z, s->tone.alpha, s->tone.beta)};
            image_set(img, i, j, c);
        }
    }
}
