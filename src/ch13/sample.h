/* sample.h: seeded random numbers and points on an area light
 * (chapter 6).
 *
 * A sample_stream is a SplitMix64 generator; sample_stream_at seeds one
 * from two points, so that a shaded point always gets the same samples. */
#ifndef SAMPLE_H
#define SAMPLE_H

#include <stdint.h>
#include "light.h"

typedef struct {
    uint64_t state;
} sample_stream;

sample_stream sample_stream_at(vec3 a, vec3 b);
/* The next number, uniform in [0, 1), a multiple of 2^-53. */
double sample_next(sample_stream *g);

/* Point k of n in the unit square by the pattern: in [0, 1)^2. */
void sample_square(enum sample_pattern pattern, int k, int n,
                   sample_stream *g, double *u, double *v);

/* The point (u, v) of the unit square on the disc (center, unit axis,
 * radius), area for area. */
vec3 disc_point(vec3 center, vec3 axis, double radius, double u, double v);

/* Point light k of the area light L's samples. */
light area_light_point(const light *L, int k, sample_stream *g);

#endif
