/* trace.h: what a ray sees (chapter 1).
 *
 * trace returns the linear colour that arrives along r. depth counts the
 * bounces that led to r (0 for a primary ray); from chapter 6 on, trace
 * calls itself for secondary rays with depth + 1. */
#ifndef TRACE_H
#define TRACE_H

#include "scene.h"

/* The colour of the background in the unit direction dir. */
vec3 background_color(const background *bg, vec3 dir);

vec3 trace(const scene *s, ray r, int depth, render_stats *stats);

#endif
