/*
 * The simulator's random numbers: one splitmix64 stream per run, seeded from --seed, so the
 * same seed gives the same run. Uniform numbers for the ADC's offsets and gain errors, Gaussian
 * numbers for its noise (every conversion of every channel, seven per control period).
 */
#ifndef SIM_RNG_H
#define SIM_RNG_H

#include <stdint.h>

typedef struct {
    uint64_t s;
} sim_rng_t;

void sim_rng_seed(sim_rng_t *r, uint64_t seed);

/* splitmix64's next output (inline: the Gaussian draws call it seven times a period). */
static inline uint64_t sim_rng_next(sim_rng_t *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in the open interval (0, 1). */
double sim_rng_uniform(sim_rng_t *r);

/* Standard normal (mean 0, variance 1): Marsaglia and Tsang's ziggurat with 128 layers in
 * Doornik's form (layer and abscissa from separate bits of one draw). About 99 % of the numbers
 * cost one draw, a compare and a multiply; the Box-Muller transform it replaces cost a log, a
 * square root and a sine and cosine per pair. */
double sim_rng_gauss(sim_rng_t *r);

#endif /* SIM_RNG_H */
