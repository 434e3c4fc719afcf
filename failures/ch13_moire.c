/* ch13_moire.c: a checkered floor to the horizon, drawn with a regular
 * grid of rays, with jittered rays, and the reference.
 *
 *   build/rel/failures/ch13_moire figures/ch13-failure-moire.png
 *
 * The floor of scenes/ch13-checker.scene through a narrow lens tilted
 * down a little, so that the far floor fills the frame: 16 rays a pixel on
 * a regular 4 x 4 grid (left), 16 jittered rays (middle), and 256
 * jittered rays (right, the reference). Where many checks fall in one
 * pixel, the grid's rays see the same pattern in every pixel, and its
 * error is large stripes: moire; the jittered rays' error is grain. The
 * program measures both errors against the reference after averaging 8
 * x 8 blocks of pixels (stripes survive the average, grain does not),
 * prints them and exits 1 unless the grid's is at least twice the
 * jittered pattern's: then the figure no longer shows the failure. It
 * also measures, not drawn, the same 16 jittered rays with the tent
 * filter against 256 jittered rays with the tent: the tent's aliasing
 * by the same measure.
 *
 * Built by `make failures` against the objects of chapter 13's program
 * but main.o; `make test` checks the committed PNG. */
#include <math.h>
#include <string.h>

#include "failure_util.h"
#include "ch13_render.h"

#define SCALE 2 /* pixels magnified, so that the stripes and grain show */
#define BLOCK 8 /* pixels averaged a side before the errors are compared */

int main(int argc, char **argv)
{
    const char *path = output_path(argc, argv);
    if (path == NULL)
        return 2;
    scene s;
    load_text(&s, FAR_FLOOR, "moire");
    image grid, jittered, reference;
    render_pixels(&s, (pixel_sampling){.pattern = PIXEL_GRID, .side = 4},
                  &grid);
    render_pixels(&s, (pixel_sampling){.pattern = PIXEL_JITTERED, .side = 4},
                  &jittered);
    render_pixels(&s,
                  (pixel_sampling){.pattern = PIXEL_JITTERED, .side = 16},
                  &reference);
    double g = block_rms(&grid, &reference, BLOCK);
    double j = block_rms(&jittered, &reference, BLOCK);
    image tent, tent_reference;
    render_pixels(&s, (pixel_sampling){.pattern = PIXEL_JITTERED, .side = 4,
                                       .filter = FILTER_TENT},
                  &tent);
    render_pixels(&s, (pixel_sampling){.pattern = PIXEL_JITTERED, .side = 16,
                                       .filter = FILTER_TENT},
                  &tent_reference);
    double t = block_rms(&tent, &tent_reference, BLOCK);
    image_free(&tent), image_free(&tent_reference);
    printf("%s: against 256 jittered rays, %dx%d blocks averaged: grid "
           "%.2f codes rms, jittered %.2f; with the tent, jittered %.2f "
           "against the tent's own\n", path, BLOCK, BLOCK, g, j, t);
    const image *row[] = {&grid, &jittered, &reference};
    bool ok = write_in_a_row(row, 3, SCALE, path);
    image_free(&grid), image_free(&jittered), image_free(&reference);
    scene_free(&s);
    if (ok && !(g >= 2 * j))
        fprintf(stderr, "%s: error: the grid no longer shows moire\n", path);
    return ok && g >= 2 * j ? 0 : 1;
}
