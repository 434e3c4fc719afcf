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
} render_stats;

#endif
