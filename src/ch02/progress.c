/* progress.c: what the program is doing and how far it has come, on
 * standard error (chapter 1). */
#include "progress.h"

#include <stdarg.h>
#include <stdio.h>
#include <unistd.h>
#include "moment.h"

/* <<drawing a line>> ch01 */
/* Whether a line is due at now: none once standard error has refused
 * one, none in the program's first second; then on a terminal every
 * time (it is redrawn), elsewhere every 10 s at most. */
static bool line_due(const progress *p, double now)
{
    return !p->closed && now - p->start >= 1.0 &&
           (isatty(STDERR_FILENO) || now >= p->next_line);
}

/* The formatted line: redrawn in place on a terminal, elsewhere a line of
 * its own. A standard error that refuses it gets no more. */
static void draw_line(progress *p, double now, const char *format, ...)
{
    char line[128];
    va_list args;
    va_start(args, format);
    int n = vsnprintf(line, sizeof line, format, args);
    va_end(args);
    n = n < 0 ? 0 : n < (int)sizeof line ? n : (int)sizeof line - 1;
    if (isatty(STDERR_FILENO)) /* blanks over the rest of a longer line */
        fprintf(stderr, "\r%s%*s", line, p->drawn > n ? p->drawn - n : 0,
                "");
    else
        fprintf(stderr, "%s\n", line);
    p->drawn = isatty(STDERR_FILENO) ? n : 0;
    p->next_line = now + 10;
    if (ferror(stderr)) /* a closed pipe (EPIPE), a full disk */
        p->closed = true;
}

/* Ends a line drawn on a terminal, so that what follows has its own. */
static void end_line(progress *p)
{
    if (p->drawn > 0 && !p->closed)
        fputc('\n', stderr);
    p->drawn = 0;
}

/* <<the progress of a phase>> ch01 */
/* "reading the scene, 3 s" (only the name as the phase begins), if a
 * line is due. */
static void draw_phase(progress *p, double now)
{
    double taken = now - p->phase_start;
    if (p->phase == NULL || !line_due(p, now))
        return;
    if (taken < 0.5)
        draw_line(p, now, "%s", p->phase);
    else
        draw_line(p, now, "%s, %.0f s", p->phase, taken);
}

/* One thread at a time: from chapter 12, which has others, a lock. */
static void hold(progress *p)
{
    (void)p;
}

static void release(progress *p)
{
    (void)p;
}


void progress_begin(progress *p)
{
    double now = moment_now().wall;
    *p = (progress){.start = now, .phase_start = now, .next_line = now};
}

void progress_phase(void *context, const char *what)
{
    progress *p = context;
    double now = moment_now().wall;
    hold(p);
    p->phase = what, p->phase_start = now;
    if (what == NULL)
        end_line(p);
    draw_phase(p, now);
    release(p);
}

void progress_render(progress *p)
{
    progress_phase(p, NULL);
    hold(p);
    p->phase_start = moment_now().wall;
    release(p);
}

void progress_end(progress *p)
{
    progress_phase(p, NULL);
}

/* <<show the progress>> ch01 */
/* "rendering: row j of h, 3 s" once the program has taken 1 s: redrawn on
 * a terminal, elsewhere a line of its own every 10 s at most. */
void progress_show(void *context, int rows_done, int rows,
                   long long rays_done)
{
    progress *p = context;
    double now = moment_now().wall;
    (void)rays_done; /* chapter 12 gives their rate */
    if (line_due(p, now) && (rows_done < rows || p->drawn > 0))
        draw_line(p, now, "rendering: row %d of %d, %.0f s", rows_done,
                  rows, now - p->phase_start);
    if (rows_done == rows)
        end_line(p);
}
