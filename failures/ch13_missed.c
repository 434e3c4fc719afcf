/* ch13_missed.c: small far spheres that fall between the corners of the
 * pixels, drawn by the adaptive pattern without and with a minimum depth.
 *
 *   build/rel/failures/ch13_missed figures/ch13-failure-missed.png
 *
 * A field of 60 spheres, each 0.75 pixel across, scattered (by the
 * chapter's hash, so always alike) over a dark background. On the left
 * the adaptive pattern at its defaults (min_depth 0): a sphere whose disc
 * covers no corner of any pixel leaves every corner alike, no pixel is
 * divided, and the sphere is not drawn. On the right min_depth 1: every
 * pixel traces its centre and the middles of its sides too, points half a
 * pixel apart, and a disc 0.75 pixel across, wider than the diagonal of
 * half a pixel (0.71), always covers one. Counts the spheres each side
 * draws, and exits 1 unless the left misses some and the right draws them
 * all.
 *
 * Built by `make failures` against the objects of chapter 13's program
 * but main.o; `make test` checks the committed PNG. */
#include <math.h>
#include <string.h>

#include "failure_util.h"
#include "ch13_render.h"
#include "antialias.h"

#define W 120
#define H 80
#define SPHERES 60
#define ACROSS 0.75 /* a sphere's width in pixels */
#define SCALE 4

static const vec3 BACKGROUND = {0.05, 0.05, 0.08};

/* The scene: the spheres at distance 20 along rays through random points
 * of the image, their pixel positions in u[], v[]. */
static void write_scene(char *text, size_t size, double *u, double *v)
{
    scene probe;
    scene_init(&probe);
    probe.cam.width = W, probe.cam.height = H;
    camera_view view = camera_view_of(&probe.cam);
    double radius = 0.5 * ACROSS * 20 * view.pixel_size;
    int n = snprintf(text, size, "image %d %d\nbackground %g %g %g\n"
                     "ambient 1 1 1\nmaterial default ambient 1 diffuse 0 "
                     "specular 0\n", W, H, BACKGROUND.x, BACKGROUND.y,
                     BACKGROUND.z);
    for (int k = 0; k < SPHERES; k++) {
        u[k] = 2 + (W - 4) * pixel_random(k, 10, 0, 0);
        v[k] = 2 + (H - 4) * pixel_random(k, 10, 0, 1);
        vec3 c = vec3_scale(camera_view_ray_at(&view, u[k], v[k]).dir, 20);
        n += snprintf(text + n, size - n, "sphere center %.17g %.17g %.17g "
                      "radius %.17g color 1 0.9 0.6\n", c.x, c.y, c.z,
                      radius);
    }
    scene_free(&probe);
}

/* Is the sphere at (u, v) drawn: a pixel around it not the background? */
static bool drawn(const image *img, double u, double v)
{
    for (int j = (int)v - 1; j <= (int)v + 1; j++)
        for (int i = (int)u - 1; i <= (int)u + 1; i++) {
            vec3 c = img->pixels[(size_t)j * img->width + i];
            if (c.x != BACKGROUND.x || c.y != BACKGROUND.y)
                return true;
        }
    return false;
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    static char text[SPHERES * 160 + 256];
    double u[SPHERES], v[SPHERES];
    write_scene(text, sizeof text, u, v);
    scene s;
    load_text(&s, text, "missed");
    pixel_sampling ps = PIXEL_DEFAULTS;
    ps.pattern = PIXEL_ADAPTIVE;
    image naive, fixed;
    render_pixels(&s, ps, &naive);
    ps.min_depth = 1;
    render_pixels(&s, ps, &fixed);
    int left = 0, right = 0;
    for (int k = 0; k < SPHERES; k++)
        left += drawn(&naive, u[k], v[k]), right += drawn(&fixed, u[k], v[k]);
    printf("%s: %d spheres of %.2f pixel: %d drawn at min_depth 0, %d at "
           "min_depth 1\n", path, SPHERES, ACROSS, left, right);
    bool ok = write_side_by_side(&naive, &fixed, SCALE, path);
    image_free(&naive), image_free(&fixed);
    scene_free(&s);
    bool shows = left < SPHERES && right == SPHERES;
    if (ok && !shows)
        fprintf(stderr, "%s: error: the failure no longer shows\n", path);
    return ok && shows ? 0 : 1;
}
