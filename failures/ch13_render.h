/* ch13_render.h: what chapter 13's failure figures share: a scene kept as
 * text, rendered with pixel settings of the figure's choosing, and the
 * difference of two renders in 8-bit codes. */
#ifndef CH10_RENDER_H
#define CH10_RENDER_H

#include <stdio.h>
#include <stdlib.h>
#include "render.h"
#include "scene_file.h"

/* The checkered floor of scenes/ch13-checker.scene through a narrow lens
 * tilted down a little, so that the far floor, its checks finer than the
 * pixels, fills the frame (ch13_moire.c, ch13_corners.c). */
static const char FAR_FLOOR[] =
    "camera fov 20 position 0 0 0 look_at 0 -0.07 1\n"
    "image 200 120\n"
    "background 0.75 0.8 0.9\n"
    "ambient 0.4 0.4 0.4\n"
    "material floor diffuse 0.6 specular 0\n"
    "triangle a -2000 -1 0.5  b 2000 -1 0.5  c 0 -1 4000 color 0.9 0.9 0.9 "
    "material floor checker 0.1 0.1 0.1 tile 1\n"
    "light directional direction 0.3 -1 0.5 intensity 0.6 0.6 0.6\n";

/* scene_init, then the scene text; a figure whose own scene does not
 * parse stops with the located error. */
static inline void load_text(scene *s, const char *text, const char *name)
{
    scene_error err;
    scene_init(s);
    if (!scene_parse(s, text, strlen(text), name, &err)) {
        fprintf(stderr, "%s:%d:%d: error: %s\n", err.file, err.line,
                err.col, err.message);
        exit(2);
    }
}

/* Renders s with the pixel settings ps into img (made here); the work. */
static inline render_stats render_pixels(scene *s, pixel_sampling ps,
                                         image *img)
{
    s->pixels = ps;
    if (!image_init(img, s->cam.width, s->cam.height)) {
        fprintf(stderr, "error: out of memory\n");
        exit(2);
    }
    render_stats st = {0};
    render(s, img, &st);
    return st;
}

/* The largest difference of the 8-bit codes of two colours. */
static inline int code_difference(vec3 p, vec3 q)
{
    int d[3] = {abs(srgb_to_byte(p.x) - srgb_to_byte(q.x)),
                abs(srgb_to_byte(p.y) - srgb_to_byte(q.y)),
                abs(srgb_to_byte(p.z) - srgb_to_byte(q.z))};
    int m = d[0] > d[1] ? d[0] : d[1];
    return m > d[2] ? m : d[2];
}

/* The rms difference of a and b in 8-bit codes, over the channels of the
 * pixels [x0, x1) x [y0, y1), after averaging each block x block square
 * of both (block 1: none): a stripe survives the average, grain does
 * not. */
static inline double block_rms(const image *a, const image *b, int block)
{
    double sum = 0;
    int n = 0;
    for (int y = 0; y + block <= a->height; y += block)
        for (int x = 0; x + block <= a->width; x += block) {
            double d[3] = {0, 0, 0};
            for (int j = y; j < y + block; j++)
                for (int i = x; i < x + block; i++) {
                    vec3 p = a->pixels[(size_t)j * a->width + i];
                    vec3 q = b->pixels[(size_t)j * a->width + i];
                    d[0] += 255.0 * (srgb_encode(p.x) - srgb_encode(q.x));
                    d[1] += 255.0 * (srgb_encode(p.y) - srgb_encode(q.y));
                    d[2] += 255.0 * (srgb_encode(p.z) - srgb_encode(q.z));
                }
            for (int c = 0; c < 3; c++)
                sum += d[c] * d[c] / ((double)block * block * block * block);
            n += 3;
        }
    return sqrt(sum / n);
}

#endif
