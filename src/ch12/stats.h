/* stats.h: counts of the work a render does, for --stats (chapter 1).
 *
 * Each chapter adds the counters of its work to the hook. All members are
 * counts, so that two render_stats add member by member. */
#ifndef STATS_H
#define STATS_H

typedef struct {
    long long primary_rays;
    /* <<statistics counters>> ch02 */
    long long hits; /* searches for the nearest hit that found one */
    long long sphere_tests;
    /* <<statistics counters>> += ch04 */
    long long triangle_tests;
    long long box_tests;
    /* <<statistics counters>> += ch05 */
    long long object_space_rays;
    long long triangles_stored, triangles_instanced; /* of the scene */
    /* <<statistics counters>> += ch06 */
    long long light_tests;          /* a point and a light: a possible ray */
    long long shadow_rays;          /* cast */
    long long shadow_rays_blocked;  /* of those, the ones that hit something */
    long long shadow_skipped_dark;  /* the light arrives with no intensity */
    long long shadow_skipped_alone; /* nothing in the scene could block it */
    long long shadow_objects_skipped; /* untested: the ray was blocked already */
    long long reflection_rays;
    long long reflection_skipped_depth;  /* at the depth limit */
    long long reflection_skipped_weight; /* below the contribution cutoff */
    long long ray_trees_cut; /* trees of rays that ran out of budget */
    long long light_samples_cut; /* area light samples the budget took away */
    /* <<statistics counters>> += ch07 */
    long long refraction_rays;
    long long refraction_skipped_depth;  /* at the depth limit */
    long long refraction_skipped_weight; /* below the contribution cutoff */
    long long total_reflections; /* glass hits with no refracted ray at all */
    /* <<statistics counters>> += ch08 */
    long long kd_nodes; /* kd-tree nodes visited */
    long long mesh_occlusion_tests; /* meshes asked for any hit, not nearest */
    /* <<statistics counters>> += ch09 */
    long long bvh_nodes; /* BVH nodes whose children a ray tested */
} render_stats;

#endif
