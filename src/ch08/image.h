/* image.h: a linear RGB image and its PNG output (chapter 01).
 *
 * Pixels hold linear light (not yet gamma encoded), row by row from the top.
 * image_write_png encodes them as 8-bit sRGB. */
#ifndef IMAGE_H
#define IMAGE_H

#include <assert.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include "vec.h"

/* Limits that keep width * height * sizeof(vec3) far from overflow. */
#define IMAGE_MAX_SIDE 16384
#define IMAGE_MAX_PIXELS (1L << 24) /* 16.7 million pixels: 400 MB of vec3 */

typedef struct {
    int width, height;
    vec3 *pixels;
} image;

/* Allocates a black image; false if the size is out of the limits above
 * or memory runs out. */
bool image_init(image *img, int width, int height);
void image_free(image *img);

/* A NaN or an infinity in a pixel is a bug upstream, never bad input: the
 * parsers keep every number finite and bounded. The check goes away with
 * -DNDEBUG. */
static inline void image_set(image *img, int i, int j, vec3 c)
{
    assert(isfinite(c.x) && isfinite(c.y) && isfinite(c.z));
    img->pixels[(size_t)j * img->width + i] = c;
}

/* The sRGB transfer function: linear light in [0, 1] to encoded [0, 1].
 * Values below 0 (and NaN) give 0, values above 1 give 1. */
double srgb_encode(double linear);

/* The 8-bit code of srgb_encode(linear), rounded to nearest. */
unsigned char srgb_to_byte(double linear);

/* The sheet's model, linear^(1/gamma), clamped like srgb_encode. */
double gamma_encode(double linear, double gamma);

/* Writes img as an 8-bit sRGB PNG. The file appears whole or not at all: it
 * is written under a temporary name and renamed. On failure returns false
 * and puts the reason in why[why_size]. */
bool image_write_png(const image *img, const char *path, char *why,
                     size_t why_size);

/* Encodes img as PNG into the open stream out and flushes it; false, with
 * the reason, when encoding or writing fails (a full disk, say). */
bool image_write_png_stream(const image *img, FILE *out, char *why,
                            size_t why_size);

#endif
