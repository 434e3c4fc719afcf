/* search.h: what a ray hits (chapter 2).
 *
 * scene_intersect finds the object nearest along a ray and fills the hit
 * record of that one only. Chapter 6 adds the any-hit query of shadow rays
 * and chapter 8 a tree over the objects; every query uses the one search. */
#ifndef SEARCH_H
#define SEARCH_H

#include "scene.h"

/* The nearest hit along r with t in (t_min, t_max), filled into h. */
bool scene_intersect(const scene *s, ray r, double t_min, double t_max,
                     hit *h, render_stats *stats);
/* <<search declarations>> ch06 */

/* Is there any hit along r with t in (t_min, t_max)? Stops at the first. */
bool scene_occluded(const scene *s, ray r, double t_min, double t_max,
                    render_stats *stats);

#endif
