/* scene_fuzz.c: libFuzzer target for the scene parser of the latest chapter.
 *
 * Each input is parsed as a scene file; a scene that parses is rendered at
 * 8 x 6 pixels, so that the numbers the parser let through also reach the
 * intersection and shading code, and every pixel must be finite (image_set
 * asserts it). Mesh files named by a scene are looked up relative to the
 * current folder, which `make fuzz` makes an empty scratch folder. */
#include <stdint.h>
#include <stdlib.h>

#include "render.h"
#include "scene_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    scene s;
    scene_error err;
    scene_init(&s);
    if (scene_parse(&s, (const char *)data, size, "fuzz.scene", &err)) {
        s.cam.width = 8, s.cam.height = 6;
        image img;
        render_stats stats = {0};
        if (!image_init(&img, s.cam.width, s.cam.height))
            abort();
        render(&s, &img, &stats);
        image_free(&img);
    }
    scene_free(&s);
    return 0;
}
