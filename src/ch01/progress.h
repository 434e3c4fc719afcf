/* progress.h: how far a render has come, on standard error (chapter 1). */
#ifndef PROGRESS_H
#define PROGRESS_H

typedef struct {
    double start;     /* when the render began, on the monotonic clock */
    int width;        /* pixels a row: the rate of pixels follows */
    double next_line; /* not on a terminal: when the next line is due */
} progress;

/* A render of rows width pixels wide begins now. */
progress progress_start(int width);

/* After a band: rows_done of rows are drawn. For render_settings, with
 * context a progress. */
void progress_show(void *context, int rows_done, int rows);

#endif
