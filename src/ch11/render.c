/* render.c: rendering a scene into an image, band by band (chapter 1). */
#include "render.h"

#include <assert.h>
/* <<render includes>> ch03 */
#include "shade.h"
/* <<render includes>> += ch08 */
#include "search.h"

/* What the pixel whose primary ray is r shows. */
static vec3 pixel_color(const scene *s, ray r, render_stats *stats)
{
    /* <<show something other than light>> ch08 */
    if (s->heatmap > 0) { /* the kdtree statement's heat map: work, not light */
        long long before = stats->kd_nodes;
        hit h;
        scene_intersect(s, r, 0, INFINITY, &h, stats);
        double x = fmin((double)(stats->kd_nodes - before) / s->heatmap, 1);
        return (vec3){fmin(3 * x, 1), fmin(fmax(3 * x - 1, 0), 1),
                      fmax(3 * x - 2, 0)}; /* black, red, yellow, white */
    }
    vec3 c = trace(s, r, 0, stats);
    /* <<map the pixel's light for display>> ch03 */
    if (s->tone.alpha != 1 || s->tone.beta != 1) /* the defaults only clip */
        c = (vec3){tone_map(c.x, s->tone.alpha, s->tone.beta),
                   tone_map(c.y, s->tone.alpha, s->tone.beta),
                   tone_map(c.z, s->tone.alpha, s->tone.beta)};
    return c;
}

void render_rows(const scene *s, image *img, int first, int last,
                 render_stats *stats)
{
    /* the contract, checked: a caller's mistake, not bad input */
    assert(img->width == s->cam.width && img->height == s->cam.height);
    assert(0 <= first && first <= last && last <= img->height);
    camera_view view = camera_view_of(&s->cam);
    for (int j = first; j < last; j++) {
        for (int i = 0; i < img->width; i++) {
            ray r = camera_view_ray(&view, i, j);
            stats->primary_rays++;
            image_set(img, i, j, pixel_color(s, r, stats));
        }
    }
}

void render(const scene *s, image *img, render_stats *stats)
{
    render_rows(s, img, 0, img->height, stats);
}

/* <<rendering in bands>> ch01 */
void render_in_bands(const scene *s, image *img, const render_settings *how,
                     render_stats *stats)
{
    for (int first = 0; first < img->height; first += BAND_ROWS) {
        int last = first + BAND_ROWS < img->height ? first + BAND_ROWS
                                                   : img->height;
        render_rows(s, img, first, last, stats);
        if (how->progress != NULL)
            how->progress(how->progress_context, last, img->height,
                          stats->primary_rays);
    }
}
