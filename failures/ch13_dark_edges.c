/* ch13_dark_edges.c: dark spheres on a darker background, the adaptive
 * pattern's corners compared in linear light and as displayed.
 *
 *   build/rel/failures/ch13_dark_edges figures/ch13-failure-dark-edges.png
 *
 * Three spheres of linear light 0.02 to 0.05 on a background of 0.004:
 * steps of at most 0.05 in linear light, below the threshold 0.05, but of
 * 0.1 to 0.2 on the display, where sRGB spreads the dark values apart. On
 * the left the corners are compared in linear light: no pixel of the
 * edges is divided, and they come out as staircases. On the right, as the
 * program compares them, in sRGB: the edges are divided and smooth. Prints
 * the rms error of each against 256 jittered rays a pixel, in 8-bit codes,
 * and exits 1 unless the linear comparison's is at least twice the sRGB
 * one's.
 *
 * Built by `make failures` against the objects of chapter 13's program
 * but main.o; `make test` checks the committed PNG. */
#include <math.h>
#include <string.h>

#include "failure_util.h"
#include "ch13_render.h"

#define SCALE 3

static const char SCENE[] =
    "camera fov 36\n"
    "image 140 90\n"
    "background 0.004 0.004 0.004\n"
    "ambient 1 1 1\n"
    "material default ambient 1 diffuse 0 specular 0\n"
    "sphere center -1.3 0.2 8 radius 0.9 color 0.02 0.02 0.02\n"
    "sphere center 0.2 -0.3 8 radius 1 color 0.035 0.03 0.025\n"
    "sphere center 1.6 0.4 8 radius 0.8 color 0.05 0.05 0.05\n";

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    load_text(&s, SCENE, "dark edges");
    pixel_sampling ps = PIXEL_DEFAULTS;
    ps.pattern = PIXEL_ADAPTIVE;
    image linear, displayed, reference;
    ps.linear = true;
    render_stats a = render_pixels(&s, ps, &linear);
    ps.linear = false;
    render_stats b = render_pixels(&s, ps, &displayed);
    render_pixels(&s,
                  (pixel_sampling){.pattern = PIXEL_JITTERED, .side = 16},
                  &reference);
    double el = block_rms(&linear, &reference, 1);
    double es = block_rms(&displayed, &reference, 1);
    printf("%s: against 256 jittered rays: linear %.2f codes rms (%lld "
           "rays), sRGB %.2f (%lld rays)\n", path, el, a.primary_rays, es,
           b.primary_rays);
    bool ok = write_side_by_side(&linear, &displayed, SCALE, path);
    image_free(&linear), image_free(&displayed), image_free(&reference);
    scene_free(&s);
    if (ok && !(el >= 2 * es))
        fprintf(stderr, "%s: error: the failure no longer shows\n", path);
    return ok && el >= 2 * es ? 0 : 1;
}
