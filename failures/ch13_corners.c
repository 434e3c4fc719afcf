/* ch13_corners.c: the adaptive pattern on a checkered floor to the
 * horizon, where its corners alias, and its two remedies.
 *
 *   build/rel/failures/ch13_corners figures/ch13-failure-corners.png
 *
 * The far floor of ch13_moire.c (FAR_FLOOR, ch13_render.h), drawn four
 * ways: the adaptive pattern at its defaults (threshold 0.05, depth 3),
 * whose corners, points of a
 * regular grid, often fall on checks of one colour in a pixel that holds
 * both, so that the pixel is never divided (left); with `min_depth 2`,
 * every pixel divided to squares a quarter of a pixel wide (second);
 * with jittered corners and `min_depth 1` (third); and the reference, 256
 * jittered rays (right). The program measures each against the reference
 * after averaging 8 x 8 blocks of pixels (what survives the average is
 * aliasing, not grain), prints the errors and the rays a pixel, and exits
 * 1 unless the defaults' error is at least twice that of the jittered
 * corners: then the figure no longer shows the failure.
 *
 * Built by `make failures` against the objects of chapter 13's program
 * but main.o; `make test` checks the committed PNG. */
#include <math.h>
#include <string.h>

#include "failure_util.h"
#include "ch13_render.h"

#define SCALE 2 /* pixels magnified, so that the stripes and grain show */
#define BLOCK 8 /* pixels averaged a side before the errors are compared */

/* The adaptive pattern at its defaults, with minimum depth m and its
 * points jittered or not. */
static pixel_sampling adaptive(int m, bool jittered)
{
    return (pixel_sampling){.pattern = PIXEL_ADAPTIVE,
                            .threshold = PIXEL_DEFAULT_THRESHOLD,
                            .depth = 3, .min_depth = m,
                            .jittered_corners = jittered};
}

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    load_text(&s, FAR_FLOOR, "corners");
    static const char *const names[] = {"defaults", "min_depth 2",
                                        "jittered corners, min_depth 1"};
    pixel_sampling ways[] = {adaptive(0, false), adaptive(2, false),
                             adaptive(1, true)};
    image img[4];
    double rays[3], error[3];
    render_pixels(&s,
                  (pixel_sampling){.pattern = PIXEL_JITTERED, .side = 16},
                  &img[3]);
    long pixels = (long)img[3].width * img[3].height;
    for (int k = 0; k < 3; k++) {
        render_stats st = render_pixels(&s, ways[k], &img[k]);
        rays[k] = (double)st.primary_rays / pixels;
        error[k] = block_rms(&img[k], &img[3], BLOCK);
        printf("%s: adaptive, %s: %.2f rays a pixel, %.2f codes rms "
               "against 256 jittered rays, %dx%d blocks averaged\n",
               path, names[k], rays[k], error[k], BLOCK, BLOCK);
    }
    const image *row[] = {&img[0], &img[1], &img[2], &img[3]};
    bool ok = write_in_a_row(row, 4, SCALE, path);
    for (int k = 0; k < 4; k++)
        image_free(&img[k]);
    scene_free(&s);
    bool shows = error[0] >= 2 * error[2];
    if (ok && !shows)
        fprintf(stderr, "%s: error: the default corners no longer alias\n",
                path);
    return ok && shows ? 0 : 1;
}
