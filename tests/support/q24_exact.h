/* Exact conversions between the control core's numbers (ctl_q) and double, independent of the
 * library's own ctl_to_float / ctl_from_float: the Q24 raw value times or over 2^24 (the float
 * build: the float itself). And random ctl_q values, rounded by ctl_from_float as a caller of
 * the core would. Include after ctl_q.h's build settings (CTL_MATH_FLOAT) are fixed. */
#ifndef Q24_EXACT_H
#define Q24_EXACT_H

#include <math.h>
#include <stdint.h>

#include "ctl_q.h"
#include "test_rng.h"

/* One least significant bit of the fixed-point format, in per unit. */
#define Q24_LSB (1.0 / 16777216.0)

#if CTL_MATH_FLOAT
static inline double qd(ctl_q x) { return (double)x; }
static inline ctl_q dq(double x) { return (float)x; }
#else
/* The raw value in per unit, exactly (every int32_t is a double). */
static inline double qd(ctl_q x) { return (double)x * Q24_LSB; }
/* Nearest Q24 value (half up), saturated to the int32_t range. */
static inline ctl_q dq(double x)
{
    const double r = floor(x * 16777216.0 + 0.5);
    if (r >= 2147483647.0) {
        return INT32_MAX;
    }
    if (r <= -2147483648.0) {
        return INT32_MIN;
    }
    return (ctl_q)r;
}
#endif

/* ctl_from_float of a uniform value in [lo, hi), drawn by either generator of test_rng.h. */
static inline ctl_q test_rng_q(test_rng_t *r, double lo, double hi)
{
    return ctl_from_float((float)test_rng_range(r, lo, hi));
}
static inline ctl_q test_lcg_q(uint32_t *state, double lo, double hi)
{
    return ctl_from_float((float)test_lcg_range(state, lo, hi));
}

#endif /* Q24_EXACT_H */
