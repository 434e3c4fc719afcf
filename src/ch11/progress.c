/* progress.c: how far a render has come, on standard error (chapter 1). */
#include "progress.h"

#include <stdbool.h>
#include <stdio.h>
#include <unistd.h>
#include "moment.h"

progress progress_start(void)
{
    return (progress){.start = moment_now().wall, .next_line = 1.0};
}

/* <<show the progress>> ch11 */
/* "[#####     ]  50%  2.31 Mrays/s  3 s left" on a terminal, once the
 * render has taken a second; elsewhere a line every 10 s at most. */
void progress_show(void *context, int rows_done, int rows,
                   long long rays_done)
{
    progress *p = context;
    double elapsed = moment_now().wall - p->start;
    bool terminal = isatty(STDERR_FILENO);
    if (elapsed < 1.0 || (!terminal && (elapsed < p->next_line ||
                                        rows_done == rows)))
        return;
    static const char bar[] = "##############################"; /* 30 */
    int filled = 30 * rows_done / rows;
    fprintf(stderr, "%s[%.*s%*s] %3d%%  %.2f Mrays/s  ",
            terminal ? "\r" : "", filled, bar, 30 - filled, "",
            100 * rows_done / rows, 1e-6 * (double)rays_done / elapsed);
    if (rows_done > 0) /* the rows to come, at the pace of those done */
        fprintf(stderr, "%.0f s left", elapsed * (rows - rows_done) /
                                           rows_done);
    else
        fprintf(stderr, "time left not known yet");
    fputs(terminal ? " " : "\n", stderr);
    p->next_line = elapsed + 10;
    if (terminal && rows_done == rows)
        fputc('\n', stderr);
}
