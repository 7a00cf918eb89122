/*
 * Arithmetic of the control core: one global per-unit number type, ctl_q.
 *
 * Fixed-point build (default): ctl_q is int32_t in Q24 (IQmath GLOBAL_Q = 24).
 *   range       [-128, 128 - 2^-24]   (every per-unit quantity stays below 20)
 *   resolution  2^-24 = 5.96e-8
 *   add/sub     saturating
 *   mul         64-bit intermediate, rounded, saturated
 *   div         64-bit intermediate, saturated, x/0 = +-max
 * Float build (CTL_MATH_FLOAT=1): ctl_q is float; the same source computes in
 * single precision. It is the reference the fixed build is compared with and
 * a real option on the F28335 FPU.
 *
 * Angles are ctl_q per unit of one turn; any value is accepted and wrapped.
 */
#ifndef CTL_Q_H
#define CTL_Q_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_range.h"

#ifndef CTL_MATH_FLOAT
#define CTL_MATH_FLOAT 0
#endif

/* Branch hint for the saturation tests: the in-range result is the path taken (a saturation is
 * the exception), so compilers that take hints keep the rest off the straight line. */
#if defined(__GNUC__) && !defined(__TMS320C2000__)
#define CTL_LIKELY(x) __builtin_expect(!!(x), 1)
#else
#define CTL_LIKELY(x) (x)
#endif

/* Operation counting for the target-time estimate (tools/bench): a build with
 * CTL_COUNT_OPS defined counts every arithmetic primitive; normal builds compile it away. */
typedef enum {
    CTL_OP_ADD = 0, /* saturating add or subtract */
    CTL_OP_MUL,     /* multiply (Q x Q, or Q x integer) */
    CTL_OP_DIV,     /* divide */
    CTL_OP_SQRT,    /* square root */
    CTL_OP_SIN,     /* sine table interpolation (a cosine is one too) */
    CTL_OP_KINDS
} ctl_op_t;

#if defined(CTL_COUNT_OPS)
extern uint32_t ctl_op_counts[CTL_OP_KINDS];
#define CTL_COUNT_OP(kind) (ctl_op_counts[(kind)]++)
#else
#define CTL_COUNT_OP(kind) ((void)0)
#endif

/*
 * Constants: CTL_Q(x) only for values exact in binary (k / 2^n, such as 0.5 or 0.25): it
 * folds x in double, which is 32 bits on the C28x, so any other value would round there
 * differently than on the host. Every other constant is generated (tools/gen_tables.py,
 * ctl_constants.h and the tables) as CTL_QK(Q24 integer, float literal): the fixed build
 * takes the integer, the float build the literal, and no build depends on double.
 */
#if CTL_MATH_FLOAT

typedef float ctl_q;

#define CTL_Q(x) ((float)(x))
#define CTL_QK(q24, f) (f)
#define CTL_Q_MAX (128.0f)
#define CTL_Q_MIN (-128.0f)

static inline ctl_q ctl_add(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
    return a + b;
}
static inline ctl_q ctl_sub(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
    return a - b;
}
static inline ctl_q ctl_mul(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    return a * b;
}
static inline ctl_q ctl_mul_int(ctl_q a, int16_t n)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    return a * (float)n;
}
static inline ctl_q ctl_mul_add(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return a * b + c * d;
}
static inline ctl_q ctl_mul_sub(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return a * b - c * d;
}
static inline ctl_q ctl_mul_acc(ctl_q acc, ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return acc + a * b;
}
static inline ctl_q ctl_mul_dec(ctl_q acc, ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return acc - a * b;
}
static inline ctl_q ctl_div(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_DIV);
    if (b == 0.0f) {
        return (a >= 0.0f) ? CTL_Q_MAX : CTL_Q_MIN;
    }
    return a / b;
}
/* |a|: one instruction where the compiler has it (the C28x's ABSF32 and x86's mask); the two
 * forms differ only in the sign of a zero, which no comparison or sum sees. */
static inline ctl_q ctl_abs(ctl_q a)
{
#if defined(__GNUC__) && !defined(__TMS320C2000__)
    return __builtin_fabsf(a);
#else
    return (a < 0.0f) ? -a : a;
#endif
}

/* The bounded forms (below, fixed point) are the plain operations in float. */
static inline ctl_q ctl_mul_bnd(ctl_q a, ctl_q b) { return ctl_mul(a, b); }
static inline ctl_q ctl_add_bnd(ctl_q a, ctl_q b) { return ctl_add(a, b); }
static inline ctl_q ctl_sub_bnd(ctl_q a, ctl_q b) { return ctl_sub(a, b); }
static inline ctl_q ctl_mul_add_bnd(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    return ctl_mul_add(a, b, c, d);
}
static inline ctl_q ctl_mul_sub_bnd(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    return ctl_mul_sub(a, b, c, d);
}
static inline ctl_q ctl_mul_acc_bnd(ctl_q acc, ctl_q a, ctl_q b) { return ctl_mul_acc(acc, a, b); }
static inline ctl_q ctl_mul_dec_bnd(ctl_q acc, ctl_q a, ctl_q b) { return ctl_mul_dec(acc, a, b); }
static inline ctl_q ctl_mul_sub_int(ctl_q a, ctl_q b, ctl_q c, ctl_q d, int16_t n)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    CTL_COUNT_OP(CTL_OP_MUL);
    return (a * b - c * d) * (float)n;
}
static inline ctl_q ctl_abs_diff_nonneg(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_abs(a - b);
}
/* The held forms (below, fixed point) hold nothing in float: single precision has no range to
 * protect there. */
static inline ctl_q ctl_mul_dec_held(ctl_q acc, ctl_q a, ctl_q b, ctl_q lim)
{
    (void)lim;
    return ctl_mul_dec(acc, a, b);
}
static inline ctl_q ctl_dot4_held(ctl_q a, ctl_q b, ctl_q c, ctl_q d, ctl_q e, ctl_q f, ctl_q g,
                                  ctl_q h, ctl_q lim)
{
    (void)lim;
    return ctl_add(ctl_mul_add(a, b, c, d), ctl_mul_add(e, f, g, h));
}
static inline float ctl_to_float(ctl_q a) { return a; }
static inline ctl_q ctl_from_float(float x) { return x; }

#else /* fixed point */

typedef int32_t ctl_q;

#define CTL_Q_FRAC_BITS 24
#define CTL_Q_ONE ((int32_t)1 << CTL_Q_FRAC_BITS)
#define CTL_Q_MAX INT32_MAX
#define CTL_Q_MIN INT32_MIN
/* Compile-time constant conversion of a value exact in binary (see above). */
#define CTL_Q(x) ((ctl_q)((x)*16777216.0 + (((x) >= 0) ? 0.5 : -0.5)))
#define CTL_QK(q24, f) ((ctl_q)(q24))

static inline ctl_q ctl_sat64(int64_t v)
{
    /* One unsigned compare on the common path: v fits in int32 exactly when v + 2^31 lies in
     * [0, 2^32). Every caller passes |v| < 2^62 (a Q48 product at most), so the add cannot
     * overflow; the sign picks the limit otherwise. */
    if (CTL_LIKELY((uint64_t)(v + (int64_t)0x80000000) <= (uint64_t)0xFFFFFFFFu)) {
        return (ctl_q)v;
    }
    return (v < 0) ? INT32_MIN : INT32_MAX;
}

/* Saturating add and subtract: with gcc and clang the overflow flag of a 32-bit add (same
 * result, a third of the instructions); elsewhere exactly in 64 bits, then saturated. */
static inline ctl_q ctl_add(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
#if defined(__GNUC__) && !defined(__TMS320C2000__)
    {
        int32_t r;
        if (!CTL_LIKELY(!__builtin_add_overflow(a, b, &r))) {
            return (a < 0) ? INT32_MIN : INT32_MAX;
        }
        return r;
    }
#else
    return ctl_sat64((int64_t)a + (int64_t)b);
#endif
}
static inline ctl_q ctl_sub(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
#if defined(__GNUC__) && !defined(__TMS320C2000__)
    {
        int32_t r;
        if (!CTL_LIKELY(!__builtin_sub_overflow(a, b, &r))) {
            return (a < 0) ? INT32_MIN : INT32_MAX;
        }
        return r;
    }
#else
    return ctl_sat64((int64_t)a - (int64_t)b);
#endif
}

/* A Q48 value rounded half up to Q24, kept in 64 bits: the one rounding of every product and
 * sum of products below, which then saturate, bound-check or hold it. */
static inline int64_t ctl_q48_round(int64_t p)
{
    return (p + ((int64_t)1 << (CTL_Q_FRAC_BITS - 1))) >> CTL_Q_FRAC_BITS;
}

static inline ctl_q ctl_mul(ctl_q a, ctl_q b)
{
    /* Q24 * Q24 = Q48; round half up, then back to Q24. */
    int64_t p = (int64_t)a * (int64_t)b;
    CTL_COUNT_OP(CTL_OP_MUL);
    return ctl_sat64(ctl_q48_round(p));
}

static inline ctl_q ctl_mul_int(ctl_q a, int16_t n)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    return ctl_sat64((int64_t)a * (int64_t)n);
}

/* Q48 to Q24, rounded half up, saturated. */
static inline ctl_q ctl_q48_to_q24(int64_t p) { return ctl_sat64(ctl_q48_round(p)); }

/* a*b + c*d and a*b - c*d with one rounding and one saturation (the exact sum of the Q48
 * products, rounded once). A Q48 product lies in (-2^62, 2^62], the top only for
 * INT32_MIN * INT32_MIN, so a difference always fits int64 and a sum overflows only when both
 * products are 2^62: that one case saturates. */
static inline ctl_q ctl_mul_add(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    const int64_t p1 = (int64_t)a * (int64_t)b;
    const int64_t p2 = (int64_t)c * (int64_t)d;
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    if (p1 == ((int64_t)1 << 62) && p2 == ((int64_t)1 << 62)) { /* the one overflow */
        return INT32_MAX;
    }
    return ctl_q48_to_q24(p1 + p2);
}
static inline ctl_q ctl_mul_sub(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24((int64_t)a * (int64_t)b - (int64_t)c * (int64_t)d);
}

/* acc + a*b with one saturation: acc moved to Q48 is a multiple of 2^24, so the sum rounds
 * exactly like ctl_add(acc, ctl_mul(a, b)) whenever that product does not saturate; |acc 2^24|
 * < 2^55 and a product lies in (-2^62, 2^62], so the sum fits int64. */
static inline ctl_q ctl_mul_acc(ctl_q acc, ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24((int64_t)acc * (int64_t)CTL_Q_ONE + (int64_t)a * (int64_t)b);
}
/* acc - a*b likewise (the negated product also lies within +-2^62). */
static inline ctl_q ctl_mul_dec(ctl_q acc, ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24((int64_t)acc * (int64_t)CTL_Q_ONE - (int64_t)a * (int64_t)b);
}

/* (a*b - c*d) * n with one saturation, at the end: the difference of two Q48 products lies
 * within (-2^63, 2^63), rounded to Q24 it is below 2^39 and times n (|n| <= 2^15) below 2^54,
 * so nothing before the last step can overflow. The same value as
 * ctl_mul_int(ctl_mul_sub(a, b, c, d), n) for n > 0, one saturation test instead of two. */
static inline ctl_q ctl_mul_sub_int(ctl_q a, ctl_q b, ctl_q c, ctl_q d, int16_t n)
{
    const int64_t diff = (int64_t)a * (int64_t)b - (int64_t)c * (int64_t)d;
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    CTL_COUNT_OP(CTL_OP_MUL);
    return ctl_sat64(ctl_q48_round(diff) * (int64_t)n);
}

/*
 * Bounded forms (CMSIS-DSP's way: a wide accumulator, no saturation test): the same rounding as
 * the saturating operation of the same name without _bnd, for operands whose result the range
 * analysis (docs/range-analysis.md) proves inside the Q24 range: the step's inputs clamped into
 * the domain of ctl_range.h, the parameter set refused by ctl_model_init unless its model keeps
 * every bounded quantity below CTL_RANGE_BOUND. Never undefined: a result outside int32 would
 * be converted modulo 2^32 (implementation-defined, not UB). A build with CTL_RANGE_CHECK counts
 * every bounded result above CTL_RANGE_BOUND in ctl_range_violations (tests/control/test_range.c).
 * Each product has an operand far below 2^30 in magnitude (a coefficient, a sine, a bounded
 * current), so a sum of two Q48 products cannot overflow int64 either.
 */
#if defined(CTL_RANGE_CHECK)
extern uint32_t ctl_range_violations;
static inline ctl_q ctl_bnd_of(int64_t v)
{
    const int64_t bound = (int64_t)CTL_RANGE_BOUND * CTL_Q_ONE;
    if (v > bound || v < -bound) {
        ctl_range_violations++;
    }
    return (ctl_q)v;
}
#else
static inline ctl_q ctl_bnd_of(int64_t v) { return (ctl_q)v; }
#endif
static inline ctl_q ctl_q48_to_q24_bnd(int64_t p) { return ctl_bnd_of(ctl_q48_round(p)); }
static inline ctl_q ctl_mul_bnd(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    return ctl_q48_to_q24_bnd((int64_t)a * (int64_t)b);
}
static inline ctl_q ctl_add_bnd(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_bnd_of((int64_t)a + (int64_t)b);
}
static inline ctl_q ctl_sub_bnd(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_bnd_of((int64_t)a - (int64_t)b);
}
static inline ctl_q ctl_mul_add_bnd(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24_bnd((int64_t)a * (int64_t)b + (int64_t)c * (int64_t)d);
}
static inline ctl_q ctl_mul_sub_bnd(ctl_q a, ctl_q b, ctl_q c, ctl_q d)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24_bnd((int64_t)a * (int64_t)b - (int64_t)c * (int64_t)d);
}
static inline ctl_q ctl_mul_acc_bnd(ctl_q acc, ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24_bnd((int64_t)acc * (int64_t)CTL_Q_ONE + (int64_t)a * (int64_t)b);
}
static inline ctl_q ctl_mul_dec_bnd(ctl_q acc, ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_q48_to_q24_bnd((int64_t)acc * (int64_t)CTL_Q_ONE - (int64_t)a * (int64_t)b);
}

/* |a - b| of two non-negative values (a flux magnitude and its reference): their difference
 * always fits int32 and is never INT32_MIN, so no saturation test can be needed. */
static inline ctl_q ctl_abs_diff_nonneg(ctl_q a, ctl_q b)
{
    const ctl_q d = a - b;
    CTL_COUNT_OP(CTL_OP_ADD);
    return (d < 0) ? -d : d;
}

/* Held forms: an expression ended by a clamp to [-lim, lim] (lim > 0, below 2^30) in place of
 * the saturation to Q24's range, where the range analysis needs a smaller bound than Q24's
 * (the open-phase step's projections, docs/range-analysis.md). The same values as the
 * saturating form whenever that lies inside [-lim, lim]. */
static inline ctl_q ctl_held(int64_t v, ctl_q lim)
{
    return (ctl_q)((v > lim) ? lim : ((v < -(int64_t)lim) ? -lim : v));
}
/* acc - a*b, rounded as ctl_mul_dec. */
static inline ctl_q ctl_mul_dec_held(ctl_q acc, ctl_q a, ctl_q b, ctl_q lim)
{
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_held(ctl_q48_round((int64_t)acc * (int64_t)CTL_Q_ONE - (int64_t)a * (int64_t)b),
                    lim);
}
/* (a*b + c*d) + (e*f + g*h), each pair rounded as ctl_mul_add rounds it, the sum held. */
static inline ctl_q ctl_dot4_held(ctl_q a, ctl_q b, ctl_q c, ctl_q d, ctl_q e, ctl_q f, ctl_q g,
                                  ctl_q h, ctl_q lim)
{
    const int64_t ab = ctl_q48_round((int64_t)a * (int64_t)b + (int64_t)c * (int64_t)d);
    const int64_t ef = ctl_q48_round((int64_t)e * (int64_t)f + (int64_t)g * (int64_t)h);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_MUL);
    CTL_COUNT_OP(CTL_OP_ADD);
    CTL_COUNT_OP(CTL_OP_ADD);
    CTL_COUNT_OP(CTL_OP_ADD);
    return ctl_held(ab + ef, lim);
}

static inline ctl_q ctl_div(ctl_q a, ctl_q b)
{
    CTL_COUNT_OP(CTL_OP_DIV);
    if (b == 0) {
        return (a >= 0) ? CTL_Q_MAX : CTL_Q_MIN;
    }
    /* Shift in 64 bits; |a| < 2^31 so a * 2^24 < 2^55 cannot overflow. */
    return ctl_sat64(((int64_t)a * (int64_t)CTL_Q_ONE) / (int64_t)b);
}

static inline ctl_q ctl_abs(ctl_q a) { return (a < 0) ? ((a == INT32_MIN) ? INT32_MAX : -a) : a; }

static inline float ctl_to_float(ctl_q a) { return (float)a * (1.0f / 16777216.0f); }

static inline ctl_q ctl_from_float(float x)
{
    const float scaled = x * 16777216.0f;
    if (!(scaled == scaled)) { /* NaN */
        return 0;
    }
    if (scaled >= 2147483520.0f) { /* largest float below 2^31 */
        return INT32_MAX;
    }
    if (scaled <= -2147483648.0f) {
        return INT32_MIN;
    }
    return (ctl_q)((scaled >= 0.0f) ? (scaled + 0.5f) : (scaled - 0.5f));
}

#endif /* CTL_MATH_FLOAT */

/* A turn fraction held in 32 bits (2^32 = one turn) as a per-unit angle. */
static inline ctl_q ctl_from_turn_u32(uint32_t turn)
{
#if CTL_MATH_FLOAT
    return (float)turn * (1.0f / 4294967296.0f);
#else
    return (ctl_q)(turn >> (32 - CTL_Q_FRAC_BITS));
#endif
}

/* raw * k where raw is a Q16 integer quantity and k a per-unit factor. */
static inline ctl_q ctl_mul_q16(int32_t raw_q16, ctl_q k)
{
#if CTL_MATH_FLOAT
    return (float)raw_q16 * (1.0f / 65536.0f) * k;
#else
    return ctl_sat64(((int64_t)raw_q16 * (int64_t)k) >> 16);
#endif
}

/* x * 2^n rounded to an integer and saturated to int32 (n in 0..24). */
static inline int32_t ctl_to_qn(ctl_q x, int16_t n)
{
#if CTL_MATH_FLOAT
    float scaled = x * (float)((int32_t)1 << n);
    if (!(scaled == scaled)) {
        return 0;
    }
    if (scaled >= 2147483520.0f) {
        return INT32_MAX;
    }
    if (scaled <= -2147483648.0f) {
        return INT32_MIN;
    }
    return (int32_t)((scaled >= 0.0f) ? (scaled + 0.5f) : (scaled - 0.5f));
#else
    const int16_t shift = (int16_t)(CTL_Q_FRAC_BITS - n);
    if (shift <= 0) {
        return x;
    }
    return (int32_t)(((int64_t)x + ((int64_t)1 << (shift - 1))) >> shift);
#endif
}

static inline ctl_q ctl_min(ctl_q a, ctl_q b) { return (a < b) ? a : b; }
static inline ctl_q ctl_max(ctl_q a, ctl_q b) { return (a > b) ? a : b; }
static inline ctl_q ctl_clamp(ctl_q x, ctl_q lo, ctl_q hi) { return ctl_min(ctl_max(x, lo), hi); }

#endif /* CTL_Q_H */
