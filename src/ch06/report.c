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
    /* <<print statistics>> += ch04 */
    fprintf(stderr, "triangle tests     %lld\n", st->triangle_tests);
    fprintf(stderr, "box tests          %lld\n", st->box_tests);
    /* <<print statistics>> += ch05 */
    fprintf(stderr, "object-space rays  %lld\n", st->object_space_rays);
    fprintf(stderr, "triangles          %lld stored, %lld instanced\n",
            st->triangles_stored, st->triangles_instanced);
    /* <<print statistics>> += ch06 */
    long long facing = st->shadow_rays + st->shadow_skipped_dark +
                       st->shadow_skipped_alone;
    fprintf(stderr, "shadow rays        %lld (%lld blocked)\n", st->shadow_rays,
            st->shadow_rays_blocked);
    fprintf(stderr,
            "  not cast         %lld light behind the surface, %lld no light "
            "to block,\n                   %lld nothing that could block\n",
            st->light_tests - facing, st->shadow_skipped_dark,
            st->shadow_skipped_alone);
    fprintf(stderr, "  objects skipped  %lld, the ray blocked already\n",
            st->shadow_objects_skipped);
    fprintf(stderr, "reflection rays    %lld\n", st->reflection_rays);
    fprintf(stderr, "  not traced       %lld at the depth limit, %lld below "
                    "the cutoff\n",
            st->reflection_skipped_depth, st->reflection_skipped_weight);
    fprintf(stderr, "ray trees cut      %lld at the budget\n", st->ray_trees_cut);
    fprintf(stderr, "light samples cut  %lld at the shadow-ray budget\n",
            st->light_samples_cut);
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
