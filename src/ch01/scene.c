/* scene.c: the scene as a container: its defaults, what it owns, and the
 * arrays that hold its contents (chapter 1). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

void scene_init(scene *s)
{
    memset(s, 0, sizeof *s);
    s->cam.fov_deg = 60.0;
    s->cam.width = 320;
    s->cam.height = 240;
    s->bg.kind = BACKGROUND_GRADIENT;
    s->bg.bottom = (vec3){1.0, 1.0, 1.0};
    s->bg.top = (vec3){0.3, 0.5, 1.0};
}

void scene_free(scene *s)
{
    memset(s, 0, sizeof *s); /* a second scene_free finds nothing to free */
}

void scene_phase(const scene *s, const char *what)
{
    if (s->on_phase != NULL)
        s->on_phase(s->phase_context, what);
}


