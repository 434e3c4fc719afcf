/* antialias.c: where a pixel's rays go (chapter 13). See antialias.h. */
#include "antialias.h"

#include <math.h>
#include <stdint.h>
#include "image.h"

/* <<the sample hash>> ch13 */
/* SplitMix64's finaliser: every output bit depends on every input bit. */
static uint64_t mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15u;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

double pixel_random(int i, int j, int k, int axis)
{
    uint64_t h = mix64((uint64_t)(uint32_t)i << 32 | (uint32_t)j);
    h = mix64(h ^ ((uint64_t)(uint32_t)k << 1 | (uint64_t)(axis & 1)));
    return (double)(h >> 11) * 0x1p-53; /* 53 bits: [0, 1) exactly */
}

/* <<sample positions>> ch13 */
int pixel_sample_count(const pixel_sampling *ps)
{
    bool sampled = ps->pattern == PIXEL_GRID ||
                   ps->pattern == PIXEL_JITTERED;
    return sampled ? ps->side * ps->side : 1;
}

void pixel_sample_at(const pixel_sampling *ps, int i, int j, int k,
                     double *u, double *v)
{
    int n = ps->pattern == PIXEL_CENTER ? 1 : ps->side;
    bool jitter = ps->pattern == PIXEL_JITTERED;
    double x = (k % n + (jitter ? pixel_random(i, j, k, 0) : 0.5)) / n;
    double y = (k / n + (jitter ? pixel_random(i, j, k, 1) : 0.5)) / n;
    if (ps->filter == FILTER_TENT && ps->pattern != PIXEL_CENTER)
        x = 0.5 + tent_warp(x), y = 0.5 + tent_warp(y);
    *u = i + x, *v = j + y;
}

/* <<point positions>> ch13 */

/* The spacing, in steps of the finest division of n steps a side, of
 * the coarsest division that has point (a, b) for a corner. */
static int point_spacing(int a, int b, int n)
{
    int h = n;
    while (a % h != 0 || b % h != 0)
        h /= 2;
    return h;
}

void pixel_point_at(const pixel_sampling *ps, int i, int j, int a, int b,
                    double *u, double *v)
{
    int n = 1 << ps->depth;
    *u = i + (double)a / n, *v = j + (double)b / n;
    if (!ps->jittered_corners)
        return;
    int gi = i * n + a, gj = j * n + b; /* the same from every side */
    double h = (double)point_spacing(a, b, n) / n;
    *u += (pixel_random(gi, gj, PIXEL_MAX_RAYS, 0) - 0.5) * h;
    *v += (pixel_random(gi, gj, PIXEL_MAX_RAYS, 1) - 0.5) * h;
}

/* <<the tent warp>> ch13 */
double tent_warp(double x)
{
    return x < 0.5 ? sqrt(2 * x) - 1 : 1 - sqrt(2 - 2 * x);
}

/* <<corners that differ>> ch13 */
/* A channel as compared: displayed, or linear light (the failure). */
static double compared(const pixel_sampling *ps, double linear)
{
    return ps->linear ? fmin(fmax(linear, 0), 1) : srgb_encode(linear);
}

bool pixel_corners_differ(const pixel_sampling *ps, const vec3 c[4])
{
    for (int axis = 0; axis < 3; axis++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < 4; k++) {
            double x = compared(ps, axis == 0   ? c[k].x
                                    : axis == 1 ? c[k].y
                                                : c[k].z);
            lo = fmin(lo, x), hi = fmax(hi, x);
        }
        if (hi - lo > ps->threshold)
            return true;
    }
    return false;
}

/* <<the worst case>> ch13 */
long long pixel_worst_rays(const pixel_sampling *ps, int width,
                           int height)
{
    long long pixels = (long long)width * height;
    if (ps->pattern != PIXEL_ADAPTIVE)
        return pixels * pixel_sample_count(ps);
    long long side = (1LL << ps->depth) + 1; /* points of a pixel a side */
    return (long long)(width + 1) * (height + 1) +
           pixels * (side * side - 4);
}
