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

/* <<show the progress>> ch01 */
/* "rendering: row j of h" once the render has taken 1 s: redrawn on a
 * terminal, elsewhere a line of its own every 10 s at most. */
void progress_show(void *context, int rows_done, int rows,
                   long long rays_done)
{
    progress *p = context;
    double elapsed = moment_now().wall - p->start;
    (void)rays_done; /* chapter 11 gives their rate */
    if (elapsed < 1.0)
        return;
    if (isatty(STDERR_FILENO)) {
        fprintf(stderr, "\rrendering: row %d of %d", rows_done, rows);
        if (rows_done == rows)
            fputc('\n', stderr);
    } else if (elapsed >= p->next_line && rows_done < rows) {
        fprintf(stderr, "rendering: row %d of %d, %.0f s\n", rows_done, rows,
                elapsed);
        p->next_line = elapsed + 10;
    }
}
