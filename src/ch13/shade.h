/* shade.h: the Phong model, lights and tone mapping (chapter 3).
 *
 * Vectors: n is the unit surface normal, l the unit vector towards a light,
 * v the unit vector towards the viewer. The highlight functions assume
 * <n, l> > 0 (the caller skips lights behind the surface) and return values
 * in [0, 1]. */
#ifndef SHADE_H
#define SHADE_H

#include "scene.h"

/* What a light delivers at a point: the unit direction towards it, the
 * distance to it (INFINITY for a directional light), and the intensity
 * after attenuation and the spot's cone. */
typedef struct {
    vec3 l;
    double distance;
    vec3 intensity;
} light_sample;

/* <<shading functions>> ch03 */
/* <r, v> with r = 2n<n,l> - l, clamped at 0. */
double phong_cosine(vec3 n, vec3 l, vec3 v);
/* <n, h> with h = (l + v) / |l + v|, clamped at 0; 0 when v = -l. */
double blinn_cosine(vec3 n, vec3 l, vec3 v);
/* The sheet's highlights: <r, v>^k and <n, h>^(4k). */
double specular_phong(vec3 n, vec3 l, vec3 v, double k);
double specular_blinn(vec3 n, vec3 l, vec3 v, double k);

/* 1 / (a1 + a2 r + a3 r^2) at distance r. */
double light_attenuation(const light *L, double r);
/* A spot's factor max(<-l, d>, 0)^k inside its cone, 0 outside. */
double spot_falloff(const light *L, vec3 l);
light_sample light_toward(const light *L, vec3 point);

/* min(alpha I^beta, 1) for I >= 0; 0 for I <= 0 or NaN. */
double tone_map(double I, double alpha, double beta);

/* The local light at the hit h seen from the unit direction v: emission,
 * ambient, and each light's diffuse and specular terms. */
vec3 shade(const scene *s, const hit *h, vec3 v, render_stats *stats);

#endif
