/* render_util.h: what the benchmarks that render whole scenes share (from
 * chapter 6 on): parsing a scene kept in the bench as text, rendering with
 * the recursion's limits, and the rms difference of two renders. Needs the
 * chapter's scene_file.h, render.h and image.h. */
#ifndef BENCH_RENDER_UTIL_H
#define BENCH_RENDER_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "image.h"
#include "render.h"
#include "scene_file.h"

/* scene_init, then the scene text[0..length) called name; a bench whose own
 * scene does not parse stops with the located error. */
static inline void bench_load_scene(scene *s, const char *text, size_t length,
                                    const char *name)
{
    scene_error err;
    scene_init(s);
    if (!scene_parse(s, text, length, name, &err)) {
        fprintf(stderr, "%s:%d:%d: %s\n", err.file, err.line, err.col, err.message);
        exit(1);
    }
}

/* Renders s into img with the recursion limited to depth and cutoff (from
 * chapter 6 on); returns the work done. */
static inline render_stats bench_render_with_limits(scene *s, image *img,
                                                    int depth, double cutoff)
{
    s->max_depth = depth, s->cutoff = cutoff;
    render_stats st = {0};
    render(s, img, &st);
    return st;
}

/* The root mean square of the difference of a and b over every channel of
 * every pixel, in linear light. */
static inline double image_rms(const image *a, const image *b)
{
    double sum = 0;
    size_t n = (size_t)a->width * a->height;
    for (size_t k = 0; k < n; k++) {
        vec3 d = vec3_sub(a->pixels[k], b->pixels[k]);
        sum += vec3_dot(d, d);
    }
    return sqrt(sum / (3.0 * n));
}

#endif
