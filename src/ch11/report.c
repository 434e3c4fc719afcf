/* report.c: what --stats prints on standard error (chapter 1). */
#include "report.h"

#include <stdio.h>
/* <<report includes>> ch08 */
#include "trees.h"

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
    /* <<print statistics>> += ch07 */
    fprintf(stderr, "refraction rays    %lld\n", st->refraction_rays);
    fprintf(stderr,
            "  not traced       %lld at the depth limit, %lld below the "
            "cutoff,\n                   %lld totally reflected\n",
            st->refraction_skipped_depth, st->refraction_skipped_weight,
            st->total_reflections);
    /* <<print statistics>> += ch08 */
    fprintf(stderr, "kd-tree nodes      %lld (%.1f a primary ray)\n", st->kd_nodes,
            (double)st->kd_nodes / (st->primary_rays ? st->primary_rays : 1));
    fprintf(stderr, "any-hit mesh tests %lld\n", st->mesh_occlusion_tests);
    /* <<print statistics>> += ch09 */
    fprintf(stderr, "bvh nodes          %lld (%.1f a primary ray)\n",
            st->bvh_nodes,
            (double)st->bvh_nodes / (st->primary_rays ? st->primary_rays : 1));
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
/* <<other reports>> ch08 */

void report_trees(const scene *s)
{
    scene_tree_summary t = scene_trees(s);
    fprintf(stderr, "kd-trees           %d: %lld nodes, %lld leaves, depth "
                    "%d, %.2f references an item\n",
            t.trees, t.nodes, t.leaves, t.depth,
            t.items ? (double)t.references / t.items : 0.0);
    fprintf(stderr, "trees built in     %.1f ms\n", 1e3 * s->tree_seconds);
}

/* The densest need of the chapter's chart: triangles per covered pixel. */
#define MESH_HINT_TRIANGLES_PER_PIXEL 167

void report_mesh_hints(const scene *s)
{
    for (int k = 0; k < s->object_count; k++) {
        const object *o = &s->objects[k];
        if (o->kind != SHAPE_MESH)
            continue;
        double pixels = scene_object_pixels(s, o);
        if (pixels > 0 && pixels < 1)
            pixels = 1; /* what shows at all takes a whole pixel */
        int triangles = s->meshes[o->mesh].triangle_count;
        if (pixels > 0 && triangles > MESH_HINT_TRIANGLES_PER_PIXEL * pixels)
            fprintf(stderr, "hint: object %d, a mesh of %d triangles, covers "
                            "at most %.0f pixel%s: %.0f triangles a pixel, "
                            "finer than the image can show\n",
                    k + 1, triangles, pixels, pixels == 1 ? "" : "s",
                    triangles / pixels);
    }
}
/* <<other reports>> += ch09 */

void report_bvhs(const scene *s)
{
    scene_bvh_summary b = scene_bvhs(s);
    if (b.trees == 0)
        return;
    /* <<the line of the BVHs>> ch11 */
    const bvh *first = NULL; /* the instructions of the first one's walk */
    for (int k = 0; k < s->mesh_count && first == NULL; k++)
        if (s->meshes[k].bvh.node_count > 0)
            first = &s->meshes[k].bvh;
    fprintf(stderr, "bvhs               %d, %d wide (%s): %lld nodes, %lld "
                    "leaves, %.1f bytes a triangle\n",
            b.trees, b.width, bvh_vector_width_name(first), b.nodes, b.leaves,
            (double)b.bytes / (double)b.triangles);
}
