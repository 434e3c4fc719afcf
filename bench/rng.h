/* rng.h: the one pseudo-random generator of bench/ and tests/.
 *
 *   bench_rng r = {SEED};            a generator; a fixed seed gives the same
 *                                    numbers on every run and every machine
 *   bench_rng_uniform01(&r)          a double in [0, 1), 53 random bits
 *   bench_rng_uniform(&r, lo, hi)    a double in [lo, hi)
 *   bench_rng_unit_vector(&r, min)   a unit vector, from a point in the unit
 *                                    ball at least min from its centre
 *   bench_rng_near_direction(&r, a)  a unit vector within 60 degrees of the
 *                                    unit vector a
 *
 * A 64-bit linear congruential generator (Knuth's MMIX constants) whose top
 * 53 bits make the double: the low bits of such a generator are weak, the
 * top ones are fine for spreading rays and inputs. It is the generator the
 * benchmarks and tests used before they shared it, so the same seeds give
 * the same inputs, and the accuracy numbers the chapters quote do not move.
 * Header only, so that the suites in tests/ include it as "../bench/rng.h". */
#ifndef BENCH_RNG_H
#define BENCH_RNG_H

#include <math.h>
#include <stdint.h>

#include "vec.h" /* every chapter's program has it */

typedef struct {
    uint64_t state;
} bench_rng;

static inline uint64_t bench_rng_next(bench_rng *r)
{
    r->state = r->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return r->state;
}

static inline double bench_rng_uniform01(bench_rng *r)
{
    return (double)(bench_rng_next(r) >> 11) / 9007199254740992.0; /* / 2^53 */
}

static inline double bench_rng_uniform(bench_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * bench_rng_uniform01(r);
}

/* A unit vector, uniform over the sphere: a point drawn in the cube until it
 * falls in the unit ball, farther than min_length from the centre (a point
 * too near it would lose its direction to rounding), pushed out. */
static inline vec3 bench_rng_unit_vector(bench_rng *r, double min_length)
{
    for (;;) {
        double x = bench_rng_uniform(r, -1, 1), y = bench_rng_uniform(r, -1, 1);
        vec3 v = {x, y, bench_rng_uniform(r, -1, 1)};
        double l = vec3_length(v);
        if (l > min_length && l <= 1)
            return vec3_scale(v, 1 / l);
    }
}

/* A unit vector within 60 degrees of the unit vector axis: a point drawn in
 * the cube until it falls in the unit ball, pushed out to the sphere, kept
 * if near enough to axis. */
static inline vec3 bench_rng_near_direction(bench_rng *r, vec3 axis)
{
    for (;;) {
        double x = 2 * bench_rng_uniform01(r) - 1, y = 2 * bench_rng_uniform01(r) - 1;
        vec3 v = {x, y, 2 * bench_rng_uniform01(r) - 1};
        double len2 = vec3_dot(v, v);
        if (len2 > 1 || len2 < 1e-6)
            continue;
        v = vec3_scale(v, 1 / sqrt(len2));
        if (vec3_dot(v, axis) > 0.5)
            return v;
    }
}

#endif
