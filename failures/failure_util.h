/* failure_util.h: what the failure figures in failures/ share.
 *
 * A failure figure is two renders of one scene side by side: on the left
 * what the naive method draws, on the right what the program draws. Each
 * program renders both halves into images of one size and hands them to
 * write_side_by_side, which magnifies them (nearest neighbour, so that a
 * single wrong pixel stays one sharp square) and writes one PNG. */
#ifndef FAILURE_UTIL_H
#define FAILURE_UTIL_H

#include <stdio.h>
#include "image.h"

#define FAILURE_GAP 8 /* white columns between the halves, after magnifying */

/* Pixel (i, j) of src drawn as a scale x scale square at column x0 of dst. */
static inline void paste_magnified(image *dst, const image *src, int x0,
                                   int scale)
{
    for (int j = 0; j < dst->height; j++)
        for (int i = 0; i < src->width * scale; i++) {
            size_t from = (size_t)(j / scale) * src->width + i / scale;
            image_set(dst, x0 + i, j, src->pixels[from]);
        }
}

/* Writes left and right, of one size, side by side into the PNG at path,
 * each pixel magnified scale times; false, saying why on stderr, if not. */
static inline bool write_side_by_side(const image *left, const image *right,
                                      int scale, const char *path)
{
    int w = left->width * scale, h = left->height * scale;
    image both;
    if (!image_init(&both, 2 * w + FAILURE_GAP, h)) {
        fprintf(stderr, "%s: error: out of memory\n", path);
        return false;
    }
    for (int j = 0; j < h; j++) /* the gap: white, as the page */
        for (int i = w; i < w + FAILURE_GAP; i++)
            image_set(&both, i, j, (vec3){1, 1, 1});
    paste_magnified(&both, left, 0, scale);
    paste_magnified(&both, right, w + FAILURE_GAP, scale);
    char why[256];
    bool ok = image_write_png(&both, path, why, sizeof why);
    if (!ok)
        fprintf(stderr, "%s: error: %s\n", path, why);
    image_free(&both);
    return ok;
}

/* Writes the n images, of one size, in a row into the PNG at path, white
 * gaps between them, each pixel magnified scale times; false, saying why
 * on stderr, if not. */
static inline bool write_in_a_row(const image *const *images, int n,
                                  int scale, const char *path)
{
    int w = images[0]->width * scale, h = images[0]->height * scale;
    image row;
    if (!image_init(&row, n * w + (n - 1) * FAILURE_GAP, h)) {
        fprintf(stderr, "%s: error: out of memory\n", path);
        return false;
    }
    for (int k = 1; k < n; k++) /* the gaps: white, as the page */
        for (int j = 0; j < h; j++)
            for (int i = 0; i < FAILURE_GAP; i++)
                image_set(&row, k * (w + FAILURE_GAP) - FAILURE_GAP + i, j,
                          (vec3){1, 1, 1});
    for (int k = 0; k < n; k++)
        paste_magnified(&row, images[k], k * (w + FAILURE_GAP), scale);
    char why[256];
    bool ok = image_write_png(&row, path, why, sizeof why);
    if (!ok)
        fprintf(stderr, "%s: error: %s\n", path, why);
    image_free(&row);
    return ok;
}

/* The output path from the command line, or NULL after printing usage. */
static inline const char *output_path(int argc, char **argv)
{
    if (argc == 2)
        return argv[1];
    fprintf(stderr, "usage: %s OUTPUT.png\n", argv[0]);
    return NULL;
}

#endif
