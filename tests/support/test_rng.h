/* Deterministic pseudo-random numbers for test points: two generators, each test keeps the one
 * (and the seed) it was written with, so its points do not move. Header only, no cmocka. */
#ifndef TEST_RNG_H
#define TEST_RNG_H

#include <stdint.h>

/* xorshift32 (Marsaglia): state never 0. */
typedef struct {
    uint32_t state;
} test_rng_t;

static inline uint32_t test_rng_u32(test_rng_t *r)
{
    uint32_t x = r->state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    r->state = x;
    return x;
}

/* Uniform in [lo, hi), from all 32 bits. */
static inline double test_rng_range(test_rng_t *r, double lo, double hi)
{
    return lo + (hi - lo) * ((double)test_rng_u32(r) * (1.0 / 4294967296.0));
}

/* The linear congruential generator of Numerical Recipes: x' = 1664525 x + 1013904223
 * (mod 2^32). Returns the new state. */
static inline uint32_t test_lcg_next(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state;
}

/* Uniform in [lo, hi), from the top 24 bits of the next state (the low bits of an LCG are
 * poor). */
static inline double test_lcg_range(uint32_t *state, double lo, double hi)
{
    return lo + (hi - lo) * (double)(test_lcg_next(state) >> 8) / 16777216.0;
}

#endif /* TEST_RNG_H */
