/* ch07_schlick.c: a glass ball with Schlick's reflectance and with the
 * exact one, and the difference.
 *
 *   build/rel/failures/ch07_schlick figures/ch07-failure-schlick.png
 *
 * One glass ball (eta = 1.5, clear) over a checkered floor, rendered twice
 * by chapter 7's program (render): on the left with the material's
 * `fresnel schlick` (Schlick with the angle in the thinner medium and 1
 * past the critical angle), in the middle with `fresnel exact`, the
 * program's default. On the right, the difference of the two in linear
 * light, |exact - Schlick| per channel, magnified DIFF_GAIN times, on
 * black. Prints the largest difference and the share of pixels whose
 * 8-bit sRGB codes differ by more than the 2 codes that the figure checks
 * allow between machines, and exits 1 unless the difference shows: some
 * pixel must differ by more than MIN_VISIBLE in linear light.
 *
 * Built by `make failures` (rule $(B)/failures/ch07_%) against the objects
 * of chapter 7's program but main.o; `make test` checks the committed PNG. */
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "scene_file.h"
#include "failure_util.h"

#define DIFF_GAIN 10      /* the difference image, magnified */
#define MIN_VISIBLE 0.01  /* in linear light: a few steps of the display */

static const char SCENE[] =
    "camera fov 36\n"
    "image 240 200\n"
    "background gradient 0.95 0.95 1  0.2 0.35 0.7\n"
    "ambient 0.3 0.3 0.32\n"
    "material floor diffuse 0.8 specular 0\n"
    "material glass ambient 0 diffuse 0 specular 0 transparency 1 ior 1.5\n"
    "triangle a -40 -1 0  b 40 -1 0  c -40 -1 60 color 0.9 0.88 0.8 "
    "checker 0.15 0.2 0.35 tile 0.5 material floor\n"
    "triangle a 40 -1 0  b 40 -1 60  c -40 -1 60 color 0.9 0.88 0.8 "
    "checker 0.15 0.2 0.35 tile 0.5 material floor\n"
    "sphere center 0 0.1 5 radius 1.1 material glass\n"
    "light point position -3 4 2 intensity 0.9 0.85 0.8\n";

/* Renders the scene with every material's reflectance set to model. */
static bool render_with(scene *s, int model, image *img)
{
    s->default_material.fresnel = model;
    for (int k = 0; k < s->material_count; k++)
        s->materials[k].fresnel = model;
    if (!image_init(img, s->cam.width, s->cam.height))
        return false;
    render(s, img, &(render_stats){0});
    return true;
}

/* The largest difference of the 8-bit codes of p and q, over the channels. */
static int code_difference(vec3 p, vec3 q)
{
    int dx = abs(srgb_to_byte(p.x) - srgb_to_byte(q.x));
    int dy = abs(srgb_to_byte(p.y) - srgb_to_byte(q.y));
    int dz = abs(srgb_to_byte(p.z) - srgb_to_byte(q.z));
    return dx > dy ? (dx > dz ? dx : dz) : (dy > dz ? dy : dz);
}

/* |a - b| * DIFF_GAIN, per channel; the largest |a - b| and the share of
 * pixels more than 2 codes apart go to *largest and *visible. */
static bool difference(const image *a, const image *b, image *d,
                       double *largest, double *visible)
{
    if (!image_init(d, a->width, a->height))
        return false;
    long beyond = 0, n = (long)a->width * a->height;
    *largest = 0;
    for (long k = 0; k < n; k++) {
        vec3 p = a->pixels[k], q = b->pixels[k];
        vec3 e = {fabs(p.x - q.x), fabs(p.y - q.y), fabs(p.z - q.z)};
        double m = fmax(e.x, fmax(e.y, e.z));
        *largest = fmax(*largest, m);
        beyond += code_difference(p, q) > 2;
        image_set(d, (int)(k % a->width), (int)(k / a->width),
                  vec3_scale(e, DIFF_GAIN));
    }
    *visible = (double)beyond / n;
    return true;
}

/* Three images of one size in a row, white gaps between, into path. */
static bool write_three(const image *a, const image *b, const image *c,
                        const char *path)
{
    int w = a->width, h = a->height;
    image row;
    if (!image_init(&row, 3 * w + 2 * FAILURE_GAP, h))
        return false;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < row.width; i++)
            image_set(&row, i, j, (vec3){1, 1, 1});
    paste_magnified(&row, a, 0, 1);
    paste_magnified(&row, b, w + FAILURE_GAP, 1);
    paste_magnified(&row, c, 2 * (w + FAILURE_GAP), 1);
    char why[256];
    bool ok = image_write_png(&row, path, why, sizeof why);
    if (!ok)
        fprintf(stderr, "%s: error: %s\n", path, why);
    image_free(&row);
    return ok;
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    scene_error err;
    scene_init(&s);
    image schlick = {0}, exact = {0}, diff = {0};
    double largest = 0, visible = 0;
    bool ok = scene_parse(&s, SCENE, strlen(SCENE), "SCENE", &err) &&
              render_with(&s, FRESNEL_SCHLICK, &schlick) &&
              render_with(&s, FRESNEL_EXACT, &exact) &&
              difference(&exact, &schlick, &diff, &largest, &visible) &&
              write_three(&schlick, &exact, &diff, path);
    if (ok)
        printf("%s: largest difference %.4f in linear light; %.1f%% of the "
               "pixels differ by more than 2 codes\n",
               path, largest, 100 * visible);
    else
        fprintf(stderr, "%s: error: cannot make the figure\n", path);
    ok = ok && largest > MIN_VISIBLE;
    image_free(&schlick), image_free(&exact), image_free(&diff);
    scene_free(&s);
    return ok ? 0 : 1;
}
