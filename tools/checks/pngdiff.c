/* pngdiff.c: do two PNG images show the same picture?
 *
 *   pngdiff [--tolerance N] EXPECTED.png ACTUAL.png
 *
 * Reads both through libpng as 8-bit RGB and compares them channel by
 * channel. Exit status 0 when they have the same size and no channel differs
 * by more than N codes (default 0), 1 when they differ, 2 on an unreadable
 * file or bad arguments. Used by `make test` to check that each committed
 * figure is what the chapter's binary renders now. */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    png_image info;
    png_bytep pixels;
} rgb_image;

/* Reads PATH as 8-bit RGB; returns 0 and prints why on failure. */
static int read_rgb(const char *path, rgb_image *img)
{
    memset(img, 0, sizeof *img);
    img->info.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img->info, path)) {
        fprintf(stderr, "%s: error: %s\n", path, img->info.message);
        return 0;
    }
    img->info.format = PNG_FORMAT_RGB;
    img->pixels = malloc(PNG_IMAGE_SIZE(img->info));
    if (img->pixels == NULL ||
        !png_image_finish_read(&img->info, NULL, img->pixels, 0, NULL)) {
        fprintf(stderr, "%s: error: cannot decode: %s\n", path, img->info.message);
        png_image_free(&img->info);
        free(img->pixels);
        return 0;
    }
    return 1;
}

/* Largest channel difference, and the pixel where it first occurs. */
static int max_difference(const rgb_image *a, const rgb_image *b, size_t *where)
{
    size_t n = (size_t)a->info.width * a->info.height * 3;
    int worst = 0;
    *where = 0;
    for (size_t k = 0; k < n; k++) {
        int d = abs((int)a->pixels[k] - (int)b->pixels[k]);
        if (d > worst) {
            worst = d;
            *where = k / 3;
        }
    }
    return worst;
}

int main(int argc, char **argv)
{
    int tolerance = 0;
    int arg = 1;
    if (argc == 5 && strcmp(argv[1], "--tolerance") == 0) {
        tolerance = atoi(argv[2]);
        arg = 3;
    } else if (argc != 3) {
        fprintf(stderr, "usage: pngdiff [--tolerance N] EXPECTED.png ACTUAL.png\n");
        return 2;
    }
    rgb_image a, b;
    if (!read_rgb(argv[arg], &a))
        return 2;
    if (!read_rgb(argv[arg + 1], &b)) {
        free(a.pixels);
        return 2;
    }
    int status = 0;
    if (a.info.width != b.info.width || a.info.height != b.info.height) {
        printf("%s: error: size %ux%u, but %s is %ux%u\n", argv[arg + 1], b.info.width,
               b.info.height, argv[arg], a.info.width, a.info.height);
        status = 1;
    } else {
        size_t where;
        int worst = max_difference(&a, &b, &where);
        if (worst > tolerance) {
            printf("%s: error: differs from %s by %d codes at pixel (%zu, %zu)\n",
                   argv[arg + 1], argv[arg], worst, where % a.info.width,
                   where / a.info.width);
            status = 1;
        } else {
            printf("%s: matches %s (largest difference %d codes)\n", argv[arg + 1],
                   argv[arg], worst);
        }
    }
    free(a.pixels);
    free(b.pixels);
    return status;
}
