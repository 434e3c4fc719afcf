/* image.c: image buffer, sRGB encoding and PNG output (chapter 01). */
#include "image.h"

#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool image_init(image *img, int width, int height)
{
    img->width = img->height = 0;
    img->pixels = NULL;
    if (width < 1 || height < 1 || width > IMAGE_MAX_SIDE ||
        height > IMAGE_MAX_SIDE)
        return false;
    if ((long)width * height > IMAGE_MAX_PIXELS)
        return false;
    img->pixels = calloc((size_t)width * height, sizeof *img->pixels);
    if (img->pixels == NULL)
        return false;
    img->width = width;
    img->height = height;
    return true;
}

void image_free(image *img)
{
    free(img->pixels);
    img->pixels = NULL;
}

double srgb_encode(double linear)
{
    if (!(linear > 0.0)) /* also catches NaN */
        return 0.0;
    if (linear >= 1.0)
        return 1.0;
    if (linear <= 0.0031308)
        return 12.92 * linear;
    return 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

unsigned char srgb_to_byte(double linear)
{
    return (unsigned char)(255.0 * srgb_encode(linear) + 0.5);
}

double gamma_encode(double linear, double gamma)
{
    if (!(linear > 0.0))
        return 0.0;
    return linear >= 1.0 ? 1.0 : pow(linear, 1.0 / gamma);
}

/* 8-bit sRGB bytes of the whole image, row by row; NULL if out of memory.
 * 3 * width * height cannot overflow: image_init capped it at 3 * 2^24. */
static unsigned char *encode_rows(const image *img)
{
    size_t n = (size_t)img->width * img->height;
    unsigned char *bytes = malloc(3 * n);
    for (size_t k = 0; bytes != NULL && k < n; k++) {
        bytes[3 * k + 0] = srgb_to_byte(img->pixels[k].x);
        bytes[3 * k + 1] = srgb_to_byte(img->pixels[k].y);
        bytes[3 * k + 2] = srgb_to_byte(img->pixels[k].z);
    }
    return bytes;
}

/* Encodes the bytes as PNG into an open stream. */
static bool write_png_stream(FILE *out, const image *img,
                             const unsigned char *bytes, char *why,
                             size_t why_size)
{
    png_image info;
    memset(&info, 0, sizeof info);
    info.version = PNG_IMAGE_VERSION;
    info.width = (png_uint_32)img->width;
    info.height = (png_uint_32)img->height;
    info.format = PNG_FORMAT_RGB;
    /* convert_to_8bit = 0: the bytes are already sRGB codes. */
    if (!png_image_write_to_stdio(&info, out, 0, bytes, 0, NULL)) {
        if (ferror(out)) /* the stream failed (a full disk), not the encoder */
            snprintf(why, why_size, "cannot write: %s", strerror(errno));
        else
            snprintf(why, why_size, "cannot encode PNG: %s", info.message);
        png_image_free(&info);
        return false;
    }
    /* a full disk shows here, or at fclose */
    if (fflush(out) != 0 || ferror(out)) {
        snprintf(why, why_size, "cannot write: %s", strerror(errno));
        return false;
    }
    return true;
}

bool image_write_png_stream(const image *img, FILE *out, char *why,
                            size_t why_size)
{
    unsigned char *bytes = encode_rows(img);
    bool ok = bytes != NULL && write_png_stream(out, img, bytes, why, why_size);
    if (bytes == NULL)
        snprintf(why, why_size, "out of memory");
    free(bytes);
    return ok;
}

bool image_write_png(const image *img, const char *path, char *why,
                     size_t why_size)
{
    unsigned char *bytes = encode_rows(img);
    char *tmp = malloc(strlen(path) + sizeof ".tmp-XXXXXX");
    int fd = -1;
    FILE *out = NULL;
    bool ok = false;
    if (bytes == NULL || tmp == NULL) {
        snprintf(why, why_size, "out of memory");
        goto done;
    }
    sprintf(tmp, "%s.tmp-XXXXXX", path);
    if ((fd = mkstemp(tmp)) < 0 || (out = fdopen(fd, "wb")) == NULL) {
        snprintf(why, why_size, "cannot create %s: %s", tmp, strerror(errno));
        goto done;
    }
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    ok = write_png_stream(out, img, bytes, why, why_size);
    if (fclose(out) != 0 && ok) /* a full disk may only show here */
        ok = (snprintf(why, why_size, "cannot write %s: %s", path,
                       strerror(errno)),
              false);
    out = NULL;
    if (ok && rename(tmp, path) != 0)
        ok = (snprintf(why, why_size, "cannot rename to %s: %s", path,
                       strerror(errno)),
              false);
done:
    if (out == NULL && fd >= 0 && !ok)
        unlink(tmp); /* the temporary never replaces the target */
    else if (out != NULL)
        fclose(out), unlink(tmp);
    free(tmp);
    free(bytes);
    return ok;
}
