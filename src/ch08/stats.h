/* stats.h: counts of the work a render does, for --stats (chapter 01).
 *
 * Each chapter adds the counters of its work to the hook. All members are
 * counts, so that two render_stats add member by member. */
#ifndef STATS_H
#define STATS_H

typedef struct {
    long long primary_rays;
    long long sphere_tests;
    long long triangle_tests;
    long long box_tests;
    long long kd_nodes; /* kd-tree nodes visited */
} render_stats;

#endif
