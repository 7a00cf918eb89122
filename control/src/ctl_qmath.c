#include "ctl_qmath.h"

#include "ctl_constants.h"
#include "ctl_tables.h"
#include "ctl_placement.h"

#if defined(CTL_COUNT_OPS)
uint32_t ctl_op_counts[CTL_OP_KINDS];
#endif

#define SMALLEST_NORMAL_FLOAT 1.17549435e-38f /* FLT_MIN */
#define LARGEST_FLOAT 3.40282347e38f          /* FLT_MAX */

bool ctl_float_in_range(float x, float lo, float hi)
{
    const bool normal = (x == 0.0f) || (x >= SMALLEST_NORMAL_FLOAT && x <= LARGEST_FLOAT) ||
                        (x <= -SMALLEST_NORMAL_FLOAT && x >= -LARGEST_FLOAT);
    return normal && x >= lo && x <= hi; /* NaN fails every comparison */
}

CTL_RAMFUNC_FLOAT float ctl_sqrtf(float x)
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
    if (x > LARGEST_FLOAT) { /* only +inf: Newton would give inf/inf */
        return x;
    }
    /* 1/sqrt(x) from the exponent-halving guess (3.4 % error) and three Newton steps
     * y <- y (1.5 - 0.5 x y^2), then sqrt(x) = x / sqrt(x); no division. */
    v.f = x;
    v.u = 0x5F3759DFu - (v.u >> 1);
    y = v.f;
    for (i = 0; i < 2; i++) {
        y = y * (1.5f - 0.5f * x * y * y);
    }
    /* r = x y, then one Newton step on r itself (y ~ 1/r): removes the last-ulp error. */
    v.f = x * y;
    return v.f + 0.5f * y * (x - v.f * v.f);
}

#if CTL_MATH_FLOAT

SIXPHASE_RAMFUNC ctl_q ctl_sqrt(ctl_q a)
{
    CTL_COUNT_OP(CTL_OP_SQRT);
    return ctl_sqrtf(a);
}

SIXPHASE_RAMFUNC ctl_q ctl_wrap_turn(ctl_q angle_turn)
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

/* Table segment and interpolation fraction of an angle already wrapped into [0, 1): pos is
 * w * 1024 exactly (a power of two), so the fraction is exact. */
SIXPHASE_RAMFUNC static int32_t sin_segment(ctl_q w, float *frac)
{
    const float pos = w * (float)CTL_SIN_SEGMENTS;
    int32_t k = (int32_t)pos;
    if (k >= CTL_SIN_SEGMENTS) {
        k = CTL_SIN_SEGMENTS - 1;
    }
    *frac = pos - (float)k;
    return k;
}

/* The table interpolated in segment k (0..CTL_SIN_SEGMENTS - 1). */
SIXPHASE_RAMFUNC static ctl_q sin_interpolated(int32_t k, float frac)
{
    CTL_COUNT_OP(CTL_OP_SIN);
    return ctl_sin_table[k] + frac * (ctl_sin_table[k + 1] - ctl_sin_table[k]);
}

/* A quarter turn on in segments, wrapped: the cosine's segment with the sine's exact fraction
 * (adding 0.25 to the angle itself would round away its low bits below a quarter turn). */
SIXPHASE_RAMFUNC static int32_t quarter_turn_on(int32_t k)
{
    return (k + CTL_SIN_SEGMENTS / 4) & (CTL_SIN_SEGMENTS - 1);
}

SIXPHASE_RAMFUNC static ctl_q sin_of_wrapped(ctl_q w)
{
    float frac;
    const int32_t k = sin_segment(w, &frac);
    return sin_interpolated(k, frac);
}

SIXPHASE_RAMFUNC static void sincos_of_wrapped(ctl_q w, ctl_q *s, ctl_q *c)
{
    float frac;
    const int32_t k = sin_segment(w, &frac);
    *s = sin_interpolated(k, frac);
    *c = sin_interpolated(quarter_turn_on(k), frac);
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

/* Position of the highest set bit of a non-zero value: the compiler's count-leading-zeros
 * where there is one (gcc, clang), a binary search elsewhere (cl2000; the C28x's own
 * instruction would be the intrinsic __norm32, left to a target-specific build). */
SIXPHASE_RAMFUNC static int16_t top_bit(uint32_t v)
{
#if defined(__GNUC__) && !defined(__TMS320C2000__)
    return (int16_t)(63 - __builtin_clzll((unsigned long long)v));
#else
    int16_t p = 0;
    if (v >= 0x10000u) {
        v >>= 16;
        p = (int16_t)(p + 16);
    }
    if (v >= 0x100u) {
        v >>= 8;
        p = (int16_t)(p + 8);
    }
    if (v >= 0x10u) {
        v >>= 4;
        p = (int16_t)(p + 4);
    }
    if (v >= 0x4u) {
        v >>= 2;
        p = (int16_t)(p + 2);
    }
    if (v >= 0x2u) {
        p = (int16_t)(p + 1);
    }
    return p;
#endif
}

SIXPHASE_RAMFUNC ctl_q ctl_sqrt(ctl_q a)
{
    /* Normalise by an even shift e to x = (a << e) / 2^32 in [0.25, 1); then
     * sqrt(a / 2^24) = sqrt(x) * 2^((8 - e) / 2). sqrt(x) = x / sqrt(x) with 1/sqrt(x) from a
     * 192-entry seed (at most 0.4 % error) and two Newton steps y <- y (3 - x y^2) / 2,
     * which need no division (relative error 2.3e-5 after one, 1e-9 after two, with the
     * Q30 truncations); a final integer check makes the result the exact floor, as a
     * bit-by-bit root would. */
    int16_t p;
    int16_t e;
    uint32_t x;
    uint64_t y;
    int16_t it;
    uint64_t root;
    int16_t shift;
    CTL_COUNT_OP(CTL_OP_SQRT);
    if (a <= 0) {
        return 0;
    }
    p = top_bit((uint32_t)a);
    e = (int16_t)(((30 - p) % 2 == 0) ? (30 - p) : (31 - p));
    x = (uint32_t)a << e;
    y = ctl_rsqrt_seed[(x >> 24) - 64u]; /* Q30 */
    for (it = 0; it < 2; it++) {
        const uint64_t y2 = (y * y) >> 30;             /* Q30 */
        const uint64_t xy2 = ((uint64_t)x * y2) >> 32; /* Q30, about 1 */
        const uint64_t t = ((uint64_t)3u << 30) - xy2; /* Q30 */
        y = (y * t) >> 31;                             /* Q30 */
    }
    root = ((uint64_t)x * y) >> 32; /* sqrt(x), Q30 */
    shift = (int16_t)((e + 4) / 2);
    root = (root + ((uint64_t)1 << (shift - 1))) >> shift;
    {
        /* Exact floor of the root of a * 2^24: the estimate is within one unit, so one
         * correction each way settles it. */
        const uint64_t target = (uint64_t)(uint32_t)a << CTL_Q_FRAC_BITS;
        if (root * root > target) {
            root--;
        } else if ((root + 1u) * (root + 1u) <= target) {
            root++;
        }
    }
    return (ctl_q)root;
}

SIXPHASE_RAMFUNC ctl_q ctl_wrap_turn(ctl_q angle_turn)
{
    return (ctl_q)((uint32_t)angle_turn & (uint32_t)(CTL_Q_ONE - 1));
}

/* Sine of an angle already wrapped into [0, 1). */
SIXPHASE_RAMFUNC static ctl_q sin_of_wrapped(ctl_q angle_wrapped)
{
    /* 10 index bits, 14 interpolation bits of the 24-bit turn fraction. */
    const uint32_t w = (uint32_t)angle_wrapped;
    const uint32_t k = w >> 14;
    CTL_COUNT_OP(CTL_OP_SIN);
    const int32_t frac = (int32_t)(w & 0x3FFFu);
    const int32_t y0 = ctl_sin_table[k];
    const int32_t dy = ctl_sin_table[k + 1u] - y0;
    return y0 + (int32_t)(((int64_t)dy * frac + 0x2000) >> 14);
}

/* The wrapped angle plus a quarter turn, wrapped again. */
SIXPHASE_RAMFUNC static ctl_q quarter_turn_on(ctl_q w) { return ctl_wrap_turn(w + CTL_Q(0.25)); }

SIXPHASE_RAMFUNC static void sincos_of_wrapped(ctl_q w, ctl_q *s, ctl_q *c)
{
    *s = sin_of_wrapped(w);
    *c = sin_of_wrapped(quarter_turn_on(w));
}

int16_t ctl_turn_sector(ctl_q angle_turn, int16_t n)
{
    const int64_t w = (int64_t)ctl_wrap_turn(angle_turn);
    return (int16_t)((w * (int64_t)n) >> CTL_Q_FRAC_BITS);
}

#endif /* CTL_MATH_FLOAT */

ctl_q ctl_sin_pu(ctl_q angle_turn) { return sin_of_wrapped(ctl_wrap_turn(angle_turn)); }

ctl_q ctl_cos_pu(ctl_q angle_turn)
{
    ctl_q s;
    ctl_q c;
    sincos_of_wrapped(ctl_wrap_turn(angle_turn), &s, &c);
    return c;
}

/* One wrap for both: the same results as ctl_sin_pu and ctl_cos_pu. */
SIXPHASE_RAMFUNC void ctl_sincos_pu(ctl_q angle_turn, ctl_q *s, ctl_q *c)
{
    sincos_of_wrapped(ctl_wrap_turn(angle_turn), s, c);
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
