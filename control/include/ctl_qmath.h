/*
 * The control core's number functions on ctl_q (ctl_q.h): square roots, sine and cosine, angle
 * and sector, the float range test. Separate from the number type so that the generated tables
 * and constants they read (ctl_tables.h, ctl_constants.h), which take the type from ctl_q.h, form
 * no include cycle with it (tools/include_graph.py).
 */
#ifndef CTL_QMATH_H
#define CTL_QMATH_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_constants.h"
#include "ctl_q.h"

/* True for a normal finite float (or exactly zero) within [lo, hi]: NaN, infinities and
 * denormals are out, whatever the bounds. For checking parameters before they are used. */
bool ctl_float_in_range(float x, float lo, float hi);

/* Square root; negative input gives 0. */
ctl_q ctl_sqrt(ctl_q a);

/* Sine and cosine of an angle in per unit of one turn (any value, wrapped). */
ctl_q ctl_sin_pu(ctl_q angle_turn);
ctl_q ctl_cos_pu(ctl_q angle_turn);
void ctl_sincos_pu(ctl_q angle_turn, ctl_q *s, ctl_q *c);

/* Angle of (x, y) in per unit of one turn, in [0, 1). atan2(0, 0) = 0. */
ctl_q ctl_atan2_pu(ctl_q y, ctl_q x);

/* Wrap an angle into [0, 1) turn. */
ctl_q ctl_wrap_turn(ctl_q angle_turn);

/* Index of the n-th part of a turn that holds the angle: floor(wrap(angle) * n),
 * in [0, n). n must be in 1..64. Sector boundaries are therefore at k/n turn. */
int16_t ctl_turn_sector(ctl_q angle_turn, int16_t n);

/* Index k in 0..23 of the 15-degree sector [15k, 15k + 15) deg that holds the vector (x, y),
 * by comparisons against tan(15 deg) multiples (no atan, no division). (0, 0) gives 0. */
static inline int16_t ctl_sector24(ctl_q y, ctl_q x)
{
    /* First-quadrant angle phi of (|x|, |y|): phi >= 15j deg <=> |y| >= |x| tan(15j deg). */
    const ctl_q ax = ctl_abs(x);
    const ctl_q ay = ctl_abs(y);
    int16_t s;
    /* On the axes the reflections below would land on the wrong side of a boundary. Tested as
     * "not above zero" (ax, ay are not negative): a float NaN takes the same defined way, and
     * the compare needs no unordered test. */
    if (!(ay > CTL_Q(0.0))) {
        return (int16_t)((x < CTL_Q(0.0)) ? 12 : 0);
    }
    if (!(ax > CTL_Q(0.0))) {
        return (int16_t)((y > CTL_Q(0.0)) ? 6 : 18);
    }
    if (ay >= ax) { /* tan 45 deg = 1: ax itself, as ctl_mul(ax, 1) gives it */
        s = (ay >= ctl_mul(ax, CTL_K_TAN_60_DEG)) ? ((ay >= ctl_mul(ax, CTL_K_TAN_75_DEG)) ? 5 : 4)
                                                  : 3;
    } else {
        s = (ay >= ctl_mul(ax, CTL_K_TAN_30_DEG)) ? 2
                                                  : ((ay >= ctl_mul(ax, CTL_K_TAN_15_DEG)) ? 1 : 0);
    }
    if (x < CTL_Q(0.0)) {
        return (int16_t)((y < CTL_Q(0.0)) ? 12 + s : 11 - s);
    }
    return (int16_t)((y < CTL_Q(0.0)) ? 23 - s : s);
}

/* Index s in 0..11 of the 30-degree sector [30s - 15, 30s + 15) deg that holds (x, y): a pair of
 * ctl_sector24's, the last half of sector 0 wrapping round (a shift and a test, no division). */
static inline int16_t ctl_sector12(ctl_q y, ctl_q x)
{
    const int16_t half = (int16_t)((uint16_t)(ctl_sector24(y, x) + 1) >> 1);
    return (half == 12) ? 0 : half;
}

/* sqrt on float without libm. */
float ctl_sqrtf(float x);

#endif /* CTL_QMATH_H */
