/* rng.h: the one pseudo-random generator of bench/ and tests/.
 *
 *   bench_rng r = {SEED};            a generator; a fixed seed gives the same
 *                                    numbers on every run and every machine
 *   bench_rng_uniform01(&r)          a double in [0, 1), 53 random bits
 *   bench_rng_uniform(&r, lo, hi)    a double in [lo, hi)
 *
 * A 64-bit linear congruential generator (Knuth's MMIX constants) whose top
 * 53 bits make the double: the low bits of such a generator are weak, the
 * top ones are fine for spreading rays and inputs. It is the generator the
 * benchmarks and tests used before they shared it, so the same seeds give
 * the same inputs, and the accuracy numbers the chapters quote do not move.
 * Header only, so that the suites in tests/ include it as "../bench/rng.h". */
#ifndef BENCH_RNG_H
#define BENCH_RNG_H

#include <stdint.h>

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

#endif
