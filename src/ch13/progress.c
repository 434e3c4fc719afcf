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
    /* <<hold the progress>> ch12 */
    pthread_mutex_lock(&p->lock);
}

static void release(progress *p)
{
    (void)p;
    /* <<release the progress>> ch12 */
    pthread_mutex_unlock(&p->lock);
}

/* <<the watcher>> ch12 */
static void draw_bar(progress *p, double now);

/* The watcher's life: the phase in hand, or the render's bar, four times
 * a second, until the program ends. */
static void *watch(void *context)
{
    progress *p = context;
    pthread_mutex_lock(&p->lock);
    while (!p->ending) {
        struct timespec until = moment_deadline(0.25);
        pthread_cond_timedwait(&p->wake, &p->lock, &until);
        if (p->ending)
            break;
        if (p->phase == NULL && p->rows > 0) /* the render's bar */
            draw_bar(p, moment_now().wall);
        else
            draw_phase(p, moment_now().wall);
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

void progress_begin(progress *p)
{
    double now = moment_now().wall;
    *p = (progress){.start = now, .phase_start = now, .next_line = now};
    /* <<start watching>> ch12 */
    pthread_mutex_init(&p->lock, NULL);
    moment_condition_init(&p->wake);
    sigset_t all, before; /* the watcher starts with every signal held */
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &before);
    p->watching = pthread_create(&p->watcher, NULL, watch, p) == 0;
    pthread_sigmask(SIG_SETMASK, &before, NULL);
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
    /* <<stop watching>> ch12 */
    pthread_mutex_lock(&p->lock);
    p->ending = true;
    pthread_cond_signal(&p->wake);
    pthread_mutex_unlock(&p->lock);
    if (p->watching)
        pthread_join(p->watcher, NULL);
    pthread_mutex_destroy(&p->lock), pthread_cond_destroy(&p->wake);
}

/* <<show the progress>> ch12 */
/* rays a second, three digits and the unit that fits: "2.31 Mrays/s",
 * "840 krays/s", "12 rays/s". */
static void rate_text(char *text, size_t size, double rate)
{
    static const char prefixes[] = " kMGT";
    int k = 0;
    while (rate >= 999.5 && k < 4) /* what %.3g would round to 1000 */
        rate /= 1000, k++;
    snprintf(text, size, "%.3g %.*srays/s", rate, k > 0, &prefixes[k]);
}

/* "[#####     ]  50%  2.31 Mrays/s  3 s left" from the numbers last
 * shown, once the program has run for a second and if a line is due: the
 * rate over the time until they were shown, the time left from now. */
static void draw_bar(progress *p, double now)
{
    int rows_done = p->rows_done, rows = p->rows;
    double elapsed = now - p->phase_start;
    double counted = p->shown_at - p->phase_start; /* when rays_done held */
    if (!line_due(p, now) || (rows_done == rows && p->drawn == 0))
        return;
    static const char bar[] = "##############################"; /* 30 */
    int filled = 30 * rows_done / rows;
    char rate[32], left[32] = "time left not known yet";
    rate_text(rate, sizeof rate,
              (double)p->rays_done / (counted > 0 ? counted : elapsed));
    if (rows_done > 0) /* the rows to come, at the pace of those done */
        snprintf(left, sizeof left, "%.0f s left",
                 elapsed * (rows - rows_done) / rows_done);
    draw_line(p, now, "[%.*s%*s] %3d%%  %s  %s", filled, bar, 30 - filled,
              "", 100 * rows_done / rows, rate, left);
}

/* The render's numbers kept for the watcher, and its bar drawn. */
void progress_show(void *context, int rows_done, int rows,
                   long long rays_done)
{
    progress *p = context;
    hold(p);
    double now = moment_now().wall;
    p->rows_done = rows_done, p->rows = rows, p->rays_done = rays_done;
    p->shown_at = now;
    draw_bar(p, now);
    if (rows_done == rows)
        end_line(p); /* on a terminal: the whole image's bar stays */
    release(p);
}
