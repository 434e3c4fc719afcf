/* sample.c: seeded random numbers and points on an area light
 * (chapter 6). See sample.h. */
#include "sample.h"

#include <string.h>

/* <<the random stream>> ch06 */
/* One SplitMix64 step: advance by the golden ratio, then mix the bits. */
static uint64_t splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

sample_stream sample_stream_at(vec3 a, vec3 b)
{
    double xs[6] = {a.x, a.y, a.z, b.x, b.y, b.z};
    uint64_t state = 0;
    for (int k = 0; k < 6; k++) {
        uint64_t bits;
        memcpy(&bits, &xs[k], sizeof bits); /* the coordinate's bits */
        state ^= bits;
        state = splitmix64(&state); /* mixed in before the next one */
    }
    return (sample_stream){state};
}

double sample_next(sample_stream *g)
{
    /* the top 53 bits: every double in [0, 1) that is a multiple of 2^-53 */
    return (double)(splitmix64(&g->state) >> 11) * 0x1p-53;
}

/* <<points in the unit square>> ch06 */
/* Cell k of n equal cells: m rows, the first n % m of them one cell
 * wider; row r is as tall as its share of the cells. */
static void cell_of(int k, int n, double *x0, double *y0, double *w,
                    double *h)
{
    int m = (int)sqrt((double)n), small = n / m, extra = n % m;
    int big = small + 1, first; /* first: cells before this row */
    int cols, col;
    if (k < extra * big)
        cols = big, first = k / big * big, col = k % big;
    else
        cols = small, col = (k - extra * big) % small, first = k - col;
    *w = 1.0 / cols, *h = (double)cols / n;
    *x0 = col * *w, *y0 = (double)first / n;
}

void sample_square(enum sample_pattern pattern, int k, int n,
                   sample_stream *g, double *u, double *v)
{
    if (pattern == SAMPLE_UNIFORM) {
        *u = sample_next(g), *v = sample_next(g);
        return;
    }
    double x0, y0, w, h;
    cell_of(k, n, &x0, &y0, &w, &h);
    double jx = 0.5, jy = 0.5; /* the grid: the cell's centre */
    if (pattern == SAMPLE_STRATIFIED)
        jx = sample_next(g), jy = sample_next(g);
    *u = x0 + jx * w, *v = y0 + jy * h;
}

/* <<points on the disc>> ch06 */
vec3 disc_point(vec3 center, vec3 axis, double radius, double u, double v)
{
    double sign = copysign(1.0, axis.z);
    double a = -1.0 / (sign + axis.z), b = axis.x * axis.y * a;
    vec3 e1 = {1 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x};
    vec3 e2 = {b, sign + axis.y * axis.y * a, -axis.y};
    double r = radius * sqrt(u), phi = 2 * M_PI * v; /* area for area */
    return vec3_add(center, vec3_add(vec3_scale(e1, r * cos(phi)),
                                     vec3_scale(e2, r * sin(phi))));
}

light area_light_point(const light *L, int k, sample_stream *g)
{
    double u, v;
    sample_square(L->pattern, k, L->samples, g, &u, &v);
    light point = *L;
    point.kind = LIGHT_POINT;
    point.position = disc_point(L->position, L->direction, L->radius, u, v);
    point.intensity = vec3_scale(L->intensity, 1.0 / L->samples);
    return point;
}
