/* report.h: what --stats prints on standard error (chapter 1). */
#ifndef REPORT_H
#define REPORT_H

#include "moment.h"
#include "scene.h"

/* The counts in st and the phases between at[0..3]: the start, and the
 * ends of loading, rendering and writing. */
void report_stats(const render_stats *st, const moment at[4]);
/* <<report declarations>> ch08 */

/* The kd-trees of s (their nodes, leaves and depth), and the time that
 * building all of s's trees took. */
void report_trees(const scene *s);

/* A hint for each mesh of s with more triangles than the pixels it covers
 * can show. */
void report_mesh_hints(const scene *s);
/* <<report declarations>> += ch09 */

/* The BVHs of s's meshes: their nodes, leaves and bytes a triangle. */
void report_bvhs(const scene *s);
/* <<report declarations>> += ch12 */

/* "meshes read": how the scene's OBJ files were read, and the loading's
 * steps on one thread. */
void report_loading(const scene *s);

#endif
