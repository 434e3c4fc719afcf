/* report.c: what --stats prints on standard error (chapter 1). */
#include "report.h"

#include <stdio.h>

/* <<the statistics report>> ch01 */
void report_stats(const render_stats *st, const moment at[4])
{
    fprintf(stderr, "primary rays       %lld\n", st->primary_rays);
    /* <<print statistics>> ch02 */
    fprintf(stderr, "hits               %lld\n", st->hits);
    fprintf(stderr, "sphere tests       %lld\n", st->sphere_tests);
    double render_s = at[2].wall - at[1].wall;
    if (render_s > 0)
        fprintf(stderr, "primary rays/s     %.3g\n",
                st->primary_rays / render_s);
    fprintf(stderr,
            "time               scene %.1f ms, render %.1f ms, write %.1f ms\n",
            1e3 * (at[1].wall - at[0].wall), 1e3 * render_s,
            1e3 * (at[3].wall - at[2].wall));
    fprintf(stderr,
            "processor time     scene %.1f ms, render %.1f ms, write %.1f ms\n",
            1e3 * (at[1].cpu - at[0].cpu), 1e3 * (at[2].cpu - at[1].cpu),
            1e3 * (at[3].cpu - at[2].cpu));
}
