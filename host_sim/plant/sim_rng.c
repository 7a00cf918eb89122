/* splitmix64 and the ziggurat Gaussian, see sim_rng.h. */
#include "sim_rng.h"

#include <math.h>
#include <stdbool.h>

#define ZIG_LAYERS 128
#define ZIG_R 3.442619855899      /* start of the tail */
#define ZIG_V 9.91256303526217e-3 /* area of each layer */

#if defined(__GNUC__)
#define ZIG_NOINLINE __attribute__((noinline))
#else
#define ZIG_NOINLINE
#endif

static double zig_x[ZIG_LAYERS + 1]; /* layer edges, zig_x[0] the base strip's equivalent width */
static double zig_ratio[ZIG_LAYERS]; /* zig_x[i + 1] / zig_x[i]: inside the layer's core box */
static bool zig_ready;

/* The layer edges depend on nothing but the constants: built once per process, identically in
 * every process (reproduce's forked workers included). */
static void zig_build(void)
{
    double f = exp(-0.5 * ZIG_R * ZIG_R);
    int i;
    zig_x[0] = ZIG_V / f;
    zig_x[1] = ZIG_R;
    zig_x[ZIG_LAYERS] = 0.0;
    for (i = 2; i < ZIG_LAYERS; i++) {
        zig_x[i] = sqrt(-2.0 * log(ZIG_V / zig_x[i - 1] + f));
        f = exp(-0.5 * zig_x[i] * zig_x[i]);
    }
    for (i = 0; i < ZIG_LAYERS; i++) {
        zig_ratio[i] = zig_x[i + 1] / zig_x[i];
    }
    zig_ready = true;
}

void sim_rng_seed(sim_rng_t *r, uint64_t seed)
{
    r->s = seed * 0x2545F4914F6CDD1Dull + 0x1234567ull;
    if (!zig_ready) {
        zig_build();
    }
}

double sim_rng_uniform(sim_rng_t *r)
{
    return ((double)(sim_rng_next(r) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/* Abscissa in (-1, 1) from the 53 high bits, independent of the layer's 7 low bits:
 * 2 ((b + 1/2) 2^-53) - 1 written as (b + 1/2) 2^-52 - 1 (the same double: scaling by 2 is
 * exact), b converted as a signed integer (it is below 2^53; one instruction on x86-64, where
 * the unsigned conversion takes a branch and several). */
static inline double zig_abscissa(uint64_t bits)
{
    return ((double)(int64_t)(bits >> 11) + 0.5) * (1.0 / 4503599627370496.0) - 1.0;
}

/* Beyond ZIG_R (Marsaglia's exponential rejection). */
static double zig_tail(sim_rng_t *r, bool negative)
{
    double x, y;
    do {
        x = log(sim_rng_uniform(r)) / ZIG_R;
        y = log(sim_rng_uniform(r));
    } while (-2.0 * y < x * x);
    return negative ? x - ZIG_R : ZIG_R - x;
}

/* The rare draws outside the core boxes: the base layer's tail, or the wedge between a layer's
 * core box and the curve (then a fresh draw when the point falls above the curve). Kept out of
 * sim_rng_gauss so the common path needs no stack frame. */
ZIG_NOINLINE static double zig_outside_core(sim_rng_t *r, unsigned layer, double u)
{
    for (;;) {
        double x, f_inner, f_outer;
        if (layer == 0u) {
            return zig_tail(r, u < 0.0);
        }
        x = u * zig_x[layer];
        f_inner = exp(-0.5 * (zig_x[layer] * zig_x[layer] - x * x));
        f_outer = exp(-0.5 * (zig_x[layer + 1] * zig_x[layer + 1] - x * x));
        if (f_outer + sim_rng_uniform(r) * (f_inner - f_outer) < 1.0) {
            return x;
        }
        {
            const uint64_t bits = sim_rng_next(r);
            layer = (unsigned)(bits & (ZIG_LAYERS - 1u));
            u = zig_abscissa(bits);
            if (fabs(u) < zig_ratio[layer]) {
                return u * zig_x[layer];
            }
        }
    }
}

double sim_rng_gauss(sim_rng_t *r)
{
    const uint64_t bits = sim_rng_next(r);
    const unsigned layer = (unsigned)(bits & (ZIG_LAYERS - 1u));
    const double u = zig_abscissa(bits);
    if (fabs(u) < zig_ratio[layer]) {
        return u * zig_x[layer];
    }
    return zig_outside_core(r, layer, u);
}
