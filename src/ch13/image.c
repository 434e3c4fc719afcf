/* image.c: image buffer, sRGB encoding and PNG output (chapter 1). */
#define _XOPEN_SOURCE 700 /* realpath: X/Open's part of POSIX */
#include "image.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h> /* NAME_MAX */
#include <png.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "memory.h"

bool image_init(image *img, int width, int height)
{
    img->width = img->height = 0;
    img->pixels = NULL;
    if (width < 1 || height < 1 || width > IMAGE_MAX_SIDE ||
        height > IMAGE_MAX_SIDE)
        return false;
    if ((long)width * height > IMAGE_MAX_PIXELS)
        return false;
    img->pixels = memory_alloc_zeroed((size_t)width * height,
                                      sizeof *img->pixels);
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

/* <<colour encoding>> ch01 */
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

/* <<PNG output>> ch01 */
/* The 8-bit sRGB bytes of the whole image, row by row, into bytes (room
 * for 3 * width * height; that cannot overflow: image_init capped it at
 * 3 * 2^24). */
static void encode_rows(const image *img, unsigned char *bytes)
{
    size_t n = (size_t)img->width * img->height;
    for (size_t k = 0; k < n; k++) {
        bytes[3 * k + 0] = srgb_to_byte(img->pixels[k].x);
        bytes[3 * k + 1] = srgb_to_byte(img->pixels[k].y);
        bytes[3 * k + 2] = srgb_to_byte(img->pixels[k].z);
    }
}

/* <<write bytes to a PNG stream>> ch01 */
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

/* The image as a PNG on out, its bytes encoded into bytes. */
static bool write_png_with(const image *img, FILE *out, unsigned char *bytes,
                           char *why, size_t why_size)
{
    encode_rows(img, bytes);
    return write_png_stream(out, img, bytes, why, why_size);
}

bool image_write_png_stream(const image *img, FILE *out, char *why,
                            size_t why_size)
{
    unsigned char *bytes =
        memory_alloc((size_t)img->width * img->height, 3);
    bool ok = bytes != NULL && write_png_with(img, out, bytes, why, why_size);
    if (bytes == NULL)
        snprintf(why, why_size, "out of memory");
    free(bytes);
    return ok;
}

/* Puts the formatted reason in why; returns false. */
static bool explain(char *why, size_t why_size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(why, why_size, format, args);
    va_end(args);
    return false;
}

/* <<open the output>> ch01 */
#define TEMPORARY_SUFFIX ".tmp-XXXXXX" /* mkstemp's X's make it unique */

/* target's name with the suffix, the name cut short so that it stays
 * within NAME_MAX bytes whenever target's own name does. */
static void temporary_name(char *out, const char *target)
{
    const char *name = strrchr(target, '/');
    name = name != NULL ? name + 1 : target;
    size_t keep = strlen(name), room = NAME_MAX - strlen(TEMPORARY_SUFFIX);
    sprintf(out, "%.*s%.*s" TEMPORARY_SUFFIX, (int)(name - target), target,
            (int)(keep < room ? keep : room), name);
}

static bool open_temporary(png_output *o, const char *target, mode_t mode,
                           char *why, size_t why_size)
{
    o->target = memory_copy_string(target);
    o->temporary = memory_alloc(strlen(target) + sizeof TEMPORARY_SUFFIX, 1);
    if (o->target == NULL || o->temporary == NULL)
        return explain(why, why_size, "out of memory");
    temporary_name(o->temporary, target);
    int fd = mkstemp(o->temporary);
    if (fd < 0) {
        explain(why, why_size, "cannot create %s: %s", o->temporary,
                strerror(errno));
        free(o->temporary), o->temporary = NULL; /* nothing to remove */
        return false;
    }
    o->owns_out = true;
    if (fchmod(fd, mode) != 0 || (o->out = fdopen(fd, "wb")) == NULL) {
        int error = errno;
        close(fd);
        return explain(why, why_size, "cannot write %s: %s", o->temporary,
                       strerror(error));
    }
    return true;
}

static mode_t new_file_mode(void)
{
    mode_t mask = umask(0); /* reading the umask means setting it */
    umask(mask);
    return 0666 & ~mask;
}

/* path names nothing (stat failed with error): a new file, unless it is a
 * link that leads nowhere. */
static bool open_new(png_output *o, const char *path, int error, char *why,
                     size_t why_size)
{
    struct stat st;
    if (error != ENOENT)
        return explain(why, why_size, "cannot write %s: %s", path,
                       strerror(error));
    if (lstat(path, &st) == 0)
        return explain(why, why_size, "cannot write %s: a link that leads "
                                      "nowhere", path);
    return open_temporary(o, path, new_file_mode(), why, why_size);
}

/* path leads to a regular file: the file is replaced, keeping its
 * permissions, unless the user may not write it. */
static bool open_replacement(png_output *o, const char *path, mode_t mode,
                             char *why, size_t why_size)
{
    char *target = realpath(path, NULL); /* through links: they stay */
    if (target == NULL)
        return explain(why, why_size, "cannot write %s: %s", path,
                       strerror(errno));
    bool ok = open_temporary(o, target, mode & 0777, why, why_size);
    if (ok && faccessat(AT_FDCWD, target, W_OK, AT_EACCESS) != 0)
        ok = explain(why, why_size, "will not replace %s: it is read-only",
                     target);
    free(target);
    return ok;
}

static bool open_in_place(png_output *o, const char *path, char *why,
                          size_t why_size)
{
    int fd = open(path, O_WRONLY | O_NOCTTY | O_NONBLOCK);
    if (fd < 0 && errno == ENXIO)
        return explain(why, why_size, "cannot write %s: no program reads "
                                      "from it", path);
    int flags = fd < 0 ? -1 : fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0 ||
        (o->out = fdopen(fd, "wb")) == NULL) {
        int error = errno;
        if (fd >= 0)
            close(fd);
        return explain(why, why_size, "cannot write %s: %s", path,
                       strerror(error));
    }
    o->owns_out = true;
    return true;
}

bool png_output_open(png_output *o, const char *path, char *why,
                     size_t why_size)
{
    struct stat st;
    *o = (png_output){0};
    if (strcmp(path, "-") == 0)
        o->out = stdout;
    else if (stat(path, &st) != 0)
        return open_new(o, path, errno, why, why_size);
    else if (S_ISDIR(st.st_mode))
        return explain(why, why_size, "cannot write %s: %s", path,
                       strerror(EISDIR));
    else if (S_ISREG(st.st_mode))
        return open_replacement(o, path, st.st_mode, why, why_size);
    else if (!open_in_place(o, path, why, why_size))
        return false;
    return !isatty(fileno(o->out)) ||
           explain(why, why_size, "will not write a PNG to a terminal");
}

/* <<finish the output>> ch01 */
bool png_output_reserve(png_output *o, int width, int height)
{
    size_t n = (size_t)width * (size_t)height;
    if (o->pixels < n) {
        free(o->bytes);
        o->bytes = memory_alloc(n, 3);
        o->pixels = o->bytes != NULL ? n : 0;
    }
    return o->bytes != NULL;
}

bool png_output_finish(png_output *o, const image *img, char *why,
                       size_t why_size)
{
    bool reserved = o->pixels >= (size_t)img->width * img->height;
    bool ok = reserved ? write_png_with(img, o->out, o->bytes, why, why_size)
                       : image_write_png_stream(img, o->out, why, why_size);
    if (o->owns_out && fclose(o->out) != 0 && ok) /* a full disk, say */
        ok = explain(why, why_size, "cannot write: %s", strerror(errno));
    o->out = NULL;
    if (ok && o->temporary != NULL && rename(o->temporary, o->target) != 0)
        ok = explain(why, why_size, "cannot rename to %s: %s", o->target,
                     strerror(errno));
    if (ok)
        free(o->temporary), o->temporary = NULL; /* it is the target now */
    return ok;
}

void png_output_free(png_output *o)
{
    if (o->out != NULL && o->owns_out)
        fclose(o->out);
    if (o->temporary != NULL)
        unlink(o->temporary);
    free(o->temporary);
    free(o->target);
    free(o->bytes);
    *o = (png_output){0};
}

bool image_write_png(const image *img, const char *path, char *why,
                     size_t why_size)
{
    png_output o;
    bool ok = png_output_open(&o, path, why, why_size) &&
              png_output_finish(&o, img, why, why_size);
    png_output_free(&o);
    return ok;
}
