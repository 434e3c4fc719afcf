/* progress.h: how far a render has come, on standard error (chapter 1). */
#ifndef PROGRESS_H
#define PROGRESS_H

typedef struct {
    double start;     /* when the render began, on the monotonic clock */
    double next_line; /* not on a terminal: when the next line is due */
} progress;

/* A render begins now. */
progress progress_start(void);

/* rows_done of rows are drawn, and rays_done rays traced. For
 * render_settings, with context a progress. */
void progress_show(void *context, int rows_done, int rows,
                   long long rays_done);

#endif
