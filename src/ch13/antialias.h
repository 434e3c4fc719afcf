/* antialias.h: where a pixel's rays go, and where Whitted's adaptive
 * scheme divides (chapter 13).
 *
 * Positions are in the image's pixel coordinates: u from 0 at the left
 * edge to width at the right, v from 0 at the top to height; pixel (i, j)
 * is [i, i + 1) x [j, j + 1). Everything here is a function of its
 * arguments alone: the same pixel gets the same rays on any thread. */
#ifndef ANTIALIAS_H
#define ANTIALIAS_H

#include "pixel.h"
#include "vec.h"

/* A number in [0, 1) that depends only on pixel (i, j), sample k, axis. */
double pixel_random(int i, int j, int k, int axis);

/* How many rays the grid and jittered patterns (and the centre's one)
 * give a pixel. */
int pixel_sample_count(const pixel_sampling *ps);

/* Where sample k of pixel (i, j) goes: inside the pixel for the box
 * filter, within one pixel of its centre for the tent. */
void pixel_sample_at(const pixel_sampling *ps, int i, int j, int k,
                     double *u, double *v);

/* Where the adaptive pattern traces point (a, b) of pixel (i, j), the
 * point (i + a/2^depth, j + b/2^depth) of its finest division: there, or
 * with ps->jittered_corners moved at random by less than half the
 * spacing of the coarsest division it belongs to; the same place for
 * every pixel that shares it. */
void pixel_point_at(const pixel_sampling *ps, int i, int j, int a, int b,
                    double *u, double *v);

/* x in [0, 1) to an offset in (-1, 1) distributed as the tent 1 - |t|. */
double tent_warp(double x);

/* Do the four colours (linear light) differ by more than ps->threshold
 * in a channel, compared as displayed (sRGB) or, if ps->linear, as they
 * are? */
bool pixel_corners_differ(const pixel_sampling *ps, const vec3 c[4]);

/* The most primary rays a width x height image may take with ps. */
long long pixel_worst_rays(const pixel_sampling *ps, int width,
                           int height);

#endif
