/* render.h: rendering a scene into an image (chapter 1). */
#ifndef RENDER_H
#define RENDER_H

#include "image.h"
#include "trace.h"

/* Renders rows first <= j < last of s into img, which must be
 * s->cam.width by s->cam.height, adding the work done to stats. */
void render_rows(const scene *s, image *img, int first, int last,
                 render_stats *stats);

/* Renders the whole image. */
void render(const scene *s, image *img, render_stats *stats);

#endif
