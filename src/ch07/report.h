/* report.h: what --stats prints on standard error (chapter 1). */
#ifndef REPORT_H
#define REPORT_H

#include "moment.h"
#include "scene.h"

/* The counts in st and the phases between at[0..3]: the start, and the
 * ends of loading, rendering and writing. */
void report_stats(const render_stats *st, const moment at[4]);

#endif
