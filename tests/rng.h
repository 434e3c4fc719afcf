/* rng.h: the one pseudo-random generator of tests/ and bench/.
 *
 *   rng_state r = {SEED};      a generator; a fixed seed gives the same
 *                              numbers on every run and every machine
 *   rng_uniform01(&r)          a double in [0, 1), 53 random bits
 *   rng_uniform(&r, lo, hi)    a double in [lo, hi)
 *   rng_unit_vector(&r, min)   a unit vector, from a point in the unit
 *                              ball at least min from its centre
 *   rng_near_direction(&r, a)  a unit vector within 60 degrees of the
 *                              unit vector a
 *
 * A 64-bit linear congruential generator (Knuth's MMIX constants) whose top
 * 53 bits make the double: the low bits of such a generator are weak, the
 * top ones are fine for spreading rays and inputs. It is the generator the
 * benchmarks and tests used before they shared it, so the same seeds give
 * the same inputs, and the accuracy numbers the chapters quote do not move.
 * Header only; it lives with the tests, whose fixed seeds it serves, and
 * the benchmarks include it as "../tests/rng.h". */
#ifndef RNG_H
#define RNG_H

#include <math.h>
#include <stdint.h>

#include "vec.h" /* every chapter's program has it */

typedef struct {
    uint64_t state;
} rng_state;

static inline uint64_t rng_next(rng_state *r)
{
    r->state = r->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return r->state;
}

static inline double rng_uniform01(rng_state *r)
{
    return (double)(rng_next(r) >> 11) / 9007199254740992.0; /* / 2^53 */
}

static inline double rng_uniform(rng_state *r, double lo, double hi)
{
    return lo + (hi - lo) * rng_uniform01(r);
}

/* A unit vector, uniform over the sphere: a point drawn in the cube until it
 * falls in the unit ball, farther than min_length from the centre (a point
 * too near it would lose its direction to rounding), pushed out. */
static inline vec3 rng_unit_vector(rng_state *r, double min_length)
{
    for (;;) {
        double x = rng_uniform(r, -1, 1), y = rng_uniform(r, -1, 1);
        vec3 v = {x, y, rng_uniform(r, -1, 1)};
        double l = vec3_length(v);
        if (l > min_length && l <= 1)
            return vec3_scale(v, 1 / l);
    }
}

/* A unit vector within 60 degrees of the unit vector axis: a point drawn in
 * the cube until it falls in the unit ball, pushed out to the sphere, kept
 * if near enough to axis. */
static inline vec3 rng_near_direction(rng_state *r, vec3 axis)
{
    for (;;) {
        double x = 2 * rng_uniform01(r) - 1, y = 2 * rng_uniform01(r) - 1;
        vec3 v = {x, y, 2 * rng_uniform01(r) - 1};
        double len2 = vec3_dot(v, v);
        if (len2 > 1 || len2 < 1e-6)
            continue;
        v = vec3_scale(v, 1 / sqrt(len2));
        if (vec3_dot(v, axis) > 0.5)
            return v;
    }
}

#endif
