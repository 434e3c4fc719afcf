/* progress.c: how far a render has come, on standard error (chapter 1). */
#include "progress.h"

#include <stdio.h>
#include <unistd.h>
#include "moment.h"

progress progress_start(int width)
{
    return (progress){.start = moment_now().wall, .width = width};
}

/* <<show the progress>> ch08 */
/* "[#####     ]  50%  2.31 Mrays/s  3 s left" on a terminal, once the
 * render has taken a second. */
void progress_show(void *context, int rows_done, int rows)
{
    const progress *p = context;
    double elapsed = moment_now().wall - p->start;
    if (elapsed < 1.0 || !isatty(STDERR_FILENO))
        return;
    static const char bar[] = "##############################"; /* 30 */
    int filled = 30 * rows_done / rows;
    double left = rows_done ? elapsed * (rows - rows_done) / rows_done : 0;
    fprintf(stderr, "\r[%.*s%*s] %3d%%  %.2f Mrays/s  %.0f s left ", filled,
            bar, 30 - filled, "", 100 * rows_done / rows,
            1e-6 * rows_done * (double)p->width / elapsed, left);
    if (rows_done == rows)
        fputc('\n', stderr);
}
