#include "ctl_q.h"

#include "ctl_tables.h"

float ctl_sqrtf(float x)
{
    union {
        float f;
        uint32_t u;
    } v;
    float y;
    int16_t i;
    if (!(x > 0.0f)) { /* negative, zero or NaN */
        return 0.0f;
    }
    if (x > 3.40282347e38f) { /* only +inf (literal = FLT_MAX); Newton would give inf/inf */
        return x;
    }
    /* Halving the exponent gives a first guess within a few percent. */
    v.f = x;
    v.u = (v.u >> 1) + 0x1FC00000u;
    y = v.f;
    for (i = 0; i < 4; i++) {
        y = 0.5f * (y + x / y);
    }
    return y;
}

#if CTL_MATH_FLOAT

ctl_q ctl_sqrt(ctl_q a) { return ctl_sqrtf(a); }

ctl_q ctl_wrap_turn(ctl_q angle_turn)
{
    int32_t whole;
    ctl_q w;
    if (!(angle_turn > -1.0e6f && angle_turn < 1.0e6f)) { /* NaN or absurd: no UB in the cast */
        return 0.0f;
    }
    whole = (int32_t)angle_turn;
    w = angle_turn - (float)whole;
    if (w < 0.0f) {
        w += 1.0f;
    }
    if (w >= 1.0f) {
        w = 0.0f;
    }
    return w;
}

ctl_q ctl_sin_pu(ctl_q angle_turn)
{
    const float pos = ctl_wrap_turn(angle_turn) * (float)CTL_SIN_SEGMENTS;
    int32_t k = (int32_t)pos;
    float frac;
    if (k >= CTL_SIN_SEGMENTS) {
        k = CTL_SIN_SEGMENTS - 1;
    }
    frac = pos - (float)k;
    return ctl_sin_table[k] + frac * (ctl_sin_table[k + 1] - ctl_sin_table[k]);
}

int16_t ctl_turn_sector(ctl_q angle_turn, int16_t n)
{
    int16_t s = (int16_t)(ctl_wrap_turn(angle_turn) * (float)n);
    if (s >= n) {
        s = (int16_t)(n - 1);
    }
    if (s < 0) {
        s = 0;
    }
    return s;
}

#else /* fixed point */

ctl_q ctl_sqrt(ctl_q a)
{
    /* sqrt(a / 2^24) * 2^24 = isqrt(a * 2^24); bit-by-bit integer root. */
    uint64_t rem;
    uint64_t root = 0;
    uint64_t bit = (uint64_t)1 << 54;
    if (a <= 0) {
        return 0;
    }
    rem = (uint64_t)(uint32_t)a << CTL_Q_FRAC_BITS;
    while (bit > rem) {
        bit >>= 2;
    }
    while (bit != 0u) {
        if (rem >= root + bit) {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (ctl_q)root; /* < 2^28 */
}

ctl_q ctl_wrap_turn(ctl_q angle_turn)
{
    return (ctl_q)((uint32_t)angle_turn & (uint32_t)(CTL_Q_ONE - 1));
}

ctl_q ctl_sin_pu(ctl_q angle_turn)
{
    /* 10 index bits, 14 interpolation bits of the 24-bit turn fraction. */
    const uint32_t w = (uint32_t)ctl_wrap_turn(angle_turn);
    const uint32_t k = w >> 14;
    const int32_t frac = (int32_t)(w & 0x3FFFu);
    const int32_t y0 = ctl_sin_table[k];
    const int32_t dy = ctl_sin_table[k + 1u] - y0;
    return y0 + (int32_t)(((int64_t)dy * frac + 0x2000) >> 14);
}

int16_t ctl_turn_sector(ctl_q angle_turn, int16_t n)
{
    const int64_t w = (int64_t)ctl_wrap_turn(angle_turn);
    return (int16_t)((w * (int64_t)n) >> CTL_Q_FRAC_BITS);
}

#endif /* CTL_MATH_FLOAT */

ctl_q ctl_cos_pu(ctl_q angle_turn) { return ctl_sin_pu(ctl_wrap_turn(angle_turn) + CTL_Q(0.25)); }

void ctl_sincos_pu(ctl_q angle_turn, ctl_q *s, ctl_q *c)
{
    *s = ctl_sin_pu(angle_turn);
    *c = ctl_cos_pu(angle_turn);
}

/* atan(t) in turns for t in [0, 1] by table interpolation. */
static ctl_q ctl_atan_unit(ctl_q t)
{
#if CTL_MATH_FLOAT
    const float pos = t * (float)CTL_ATAN_SEGMENTS;
    int32_t k = (int32_t)pos;
    float frac;
    if (k >= CTL_ATAN_SEGMENTS) {
        k = CTL_ATAN_SEGMENTS - 1;
    }
    if (k < 0) {
        k = 0;
    }
    frac = pos - (float)k;
    return ctl_atan_table[k] + frac * (ctl_atan_table[k + 1] - ctl_atan_table[k]);
#else
    /* t is Q24 in [0, 2^24]: 8 index bits, 16 interpolation bits. */
    uint32_t k = (uint32_t)t >> 16;
    int32_t frac = (int32_t)((uint32_t)t & 0xFFFFu);
    int32_t y0;
    if (k >= (uint32_t)CTL_ATAN_SEGMENTS) {
        k = (uint32_t)CTL_ATAN_SEGMENTS - 1u;
        frac = 0x10000;
    }
    y0 = ctl_atan_table[k];
    return y0 + (int32_t)(((int64_t)(ctl_atan_table[k + 1u] - y0) * frac + 0x8000) >> 16);
#endif
}

ctl_q ctl_atan2_pu(ctl_q y, ctl_q x)
{
    const ctl_q ax = ctl_abs(x);
    const ctl_q ay = ctl_abs(y);
    ctl_q a;
    if (ax == ay && ax == CTL_Q(0.0)) {
        return CTL_Q(0.0);
    }
    /* First-octant angle, then reflect into the right quadrant. */
    if (ay <= ax) {
        a = ctl_atan_unit(ctl_div(ay, ax));
    } else {
        a = ctl_sub(CTL_Q(0.25), ctl_atan_unit(ctl_div(ax, ay)));
    }
    if (x < CTL_Q(0.0)) {
        a = ctl_sub(CTL_Q(0.5), a);
    }
    if (y < CTL_Q(0.0)) {
        a = ctl_sub(CTL_Q(1.0), a);
    }
    return ctl_wrap_turn(a);
}
