/* progress.h: what the program is doing and how far it has come, on
 * standard error (chapter 1). */
#ifndef PROGRESS_H
#define PROGRESS_H

#include <stdbool.h>
/* <<progress includes>> ch12 */
#include <pthread.h>
#include <signal.h>

typedef struct {
    double start;       /* when the program began, on the monotonic clock */
    double phase_start; /* when the phase in hand (or the render) began */
    double next_line;   /* not on a terminal: when the next line is due */
    const char *phase;  /* the phase in hand ("reading the scene"); NULL:
                           none, or the render, which has lines of its own */
    int drawn;          /* on a terminal: the width of the line drawn */
    bool closed;        /* standard error refused a line: no more lines */
    /* <<progress members>> ch12 */
    pthread_t watcher;    /* redraws the phase in hand while it lasts */
    pthread_mutex_t lock; /* one line at a time; guards all the rest */
    pthread_cond_t wake;  /* the watcher's, when the program ends */
    bool watching, ending;
    int rows_done, rows;  /* the render's, as last shown (rows 0: none yet) */
    long long rays_done;
    double shown_at;      /* when they were shown */
} progress;

/* The program begins now. progress_end must follow. */
void progress_begin(progress *p);

/* The program now does what ("reading the scene"); NULL: nothing that a
 * line should show, and a line drawn on a terminal is ended. For the
 * scene's on_phase, with context a progress. */
void progress_phase(void *context, const char *what);

/* The render begins now. */
void progress_render(progress *p);

/* rows_done of rows are drawn, and rays_done rays traced. For
 * render_settings, with context a progress. */
void progress_show(void *context, int rows_done, int rows,
                   long long rays_done);

/* No more lines: one drawn on a terminal is ended. */
void progress_end(progress *p);

#endif
