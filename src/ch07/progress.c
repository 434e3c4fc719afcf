/* progress.c: how far a render has come, on standard error (chapter 1). */
#include "progress.h"

#include <stdio.h>
#include <unistd.h>
#include "moment.h"

progress progress_start(int width)
{
    return (progress){.start = moment_now().wall, .width = width};
}

/* <<show the progress>> ch01 */
/* "rendering: row j of h" on a terminal, once the render has taken 1 s. */
void progress_show(void *context, int rows_done, int rows)
{
    const progress *p = context;
    if (moment_now().wall - p->start < 1.0 || !isatty(STDERR_FILENO))
        return;
    fprintf(stderr, "\rrendering: row %d of %d", rows_done, rows);
    if (rows_done == rows)
        fputc('\n', stderr);
}
