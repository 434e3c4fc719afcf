/* image.h: a linear RGB image and its PNG output (chapter 1).
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
 * parsers keep every number finite and bounded; so is a pixel outside the
 * image. The checks go away with -DNDEBUG. */
static inline void image_set(image *img, int i, int j, vec3 c)
{
    assert(i >= 0 && i < img->width && j >= 0 && j < img->height);
    assert(isfinite(c.x) && isfinite(c.y) && isfinite(c.z));
    img->pixels[(size_t)j * img->width + i] = c;
}

/* <<colour encoding declarations>> ch01 */
/* The sRGB transfer function: linear light in [0, 1] to encoded [0, 1].
 * Values below 0 (and NaN) give 0, values above 1 give 1. */
double srgb_encode(double linear);

/* The 8-bit code of srgb_encode(linear), rounded to nearest. */
unsigned char srgb_to_byte(double linear);

/* The sheet's model, linear^(1/gamma), clamped like srgb_encode. */
double gamma_encode(double linear, double gamma);

/* Writes img as an 8-bit sRGB PNG to path, which png_output_open (below)
 * opens: a file appears whole or not at all. On failure returns false and
 * puts the reason in why[why_size]. */
bool image_write_png(const image *img, const char *path, char *why,
                     size_t why_size);

/* Encodes img as PNG into the open stream out and flushes it; false, with
 * the reason, when encoding or writing fails (a full disk, say). */
bool image_write_png_stream(const image *img, FILE *out, char *why,
                            size_t why_size);
/* <<PNG output declarations>> ch01 */

/* Where a PNG goes: opened before the render, finished after it. */
typedef struct {
    FILE *out;
    bool owns_out;   /* false for standard output, which stays open */
    char *temporary; /* NULL when the target is written in place */
    char *target;    /* the file that the temporary replaces */
    unsigned char *bytes; /* the sRGB bytes, reserved; NULL: not yet */
    size_t pixels;        /* how many pixels bytes has room for */
} png_output;

/* Opens path for a PNG as the table above says ("-": standard output);
 * false with the reason in why. Free o with png_output_free either way. */
bool png_output_open(png_output *o, const char *path, char *why,
                     size_t why_size);

/* Takes now the memory that finishing a width x height PNG needs, so
 * that a lack of it shows before the render; false if there is none. */
bool png_output_reserve(png_output *o, int width, int height);

/* Writes img to o and, for a file, renames the temporary over the target;
 * false with the reason in why. */
bool png_output_finish(png_output *o, const image *img, char *why,
                       size_t why_size);

/* Closes o and removes its temporary file if it is still there (the PNG
 * was not finished). */
void png_output_free(png_output *o);

#endif
