/* png.h for the page (chapter 13): the picture as the width and the
 * height (32 bits each, in the machine's order), then its pixels,
 * four bytes each: red, green, blue, 255. */
#ifndef PAGE_PNG_H
#define PAGE_PNG_H

#include <stdint.h>
#include <stdio.h>

typedef uint32_t png_uint_32;
typedef struct {
    png_uint_32 version, width, height, format;
    char message[64];
} png_image;
enum { PNG_IMAGE_VERSION = 1, PNG_FORMAT_RGB = 1 };

static inline int png_image_write_to_stdio(png_image *img, FILE *out,
                                           int convert_to_8bit,
                                           const void *rgb, int32_t stride,
                                           const void *colormap)
{
    (void)convert_to_8bit, (void)stride, (void)colormap;
    const unsigned char *byte = rgb;
    png_uint_32 size[2] = {img->width, img->height};
    fwrite(size, sizeof size, 1, out);
    for (size_t k = 0; k < (size_t)img->width * img->height; k++)
        fwrite((unsigned char[4]){byte[3 * k], byte[3 * k + 1],
                                  byte[3 * k + 2], 255}, 4, 1, out);
    return !ferror(out);
}

static inline void png_image_free(png_image *img) { (void)img; }

#endif
