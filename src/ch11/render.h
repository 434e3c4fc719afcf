/* render.h: rendering a scene into an image, band by band (chapter 1). */
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

/* How render_in_bands draws; zero means the default. */
typedef struct {
    /* called after bands are drawn, with the rows and the rays done so
     * far, never by two threads at once; NULL: none */
    void (*progress)(void *context, int rows_done, int rows,
                     long long rays_done);
    void *progress_context;
} render_settings;

/* Renders the whole image in bands of BAND_ROWS rows, as how says. */
void render_in_bands(const scene *s, image *img, const render_settings *how,
                     render_stats *stats);

enum { BAND_ROWS = 8 }; /* small enough for smooth progress and a fair
                           share of the work, large enough to cost
                           nothing */

#endif
