/*
 * Unit tests of the control-core arithmetic (ctl_q.h, ctl_qmath.h / ctl_qmath.c), built twice:
 * test_q_fixed (Q24, CTL_MATH_FLOAT = 0) and test_q_float (CTL_MATH_FLOAT = 1).
 *
 * Every expectation is computed here from the defining formula in double (or
 * long double where an exact 64-bit product is needed), never by re-running the
 * library's own algorithm.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_support.h"

#include <float.h>
#include <math.h>

#include "ctl_q.h"
#include "ctl_qmath.h"
#include "q24_exact.h" /* qd, dq, Q24_LSB */
#include "test_rng.h"

#define TWO_PI 6.283185307179586476925

/* ---------------------------------------------------------------- helpers */

static test_rng_t rng = {0x12345678u};
static uint32_t rng_u32(void) { return test_rng_u32(&rng); }
static double rng_range(double lo, double hi) { return test_rng_range(&rng, lo, hi); }

static void expect_i32(int32_t got, int32_t want, const char *what)
{
    if (got != want) {
        print_error("%s: got %ld, want %ld\n", what, (long)got, (long)want);
        fail();
    }
}

/* Signed distance between two angles in turns, folded into [-0.5, 0.5). */
static double turn_diff(double a, double b)
{
    double d = fmod(a - b, 1.0);
    if (d >= 0.5) {
        d -= 1.0;
    }
    if (d < -0.5) {
        d += 1.0;
    }
    return d;
}

/* ------------------------------------------------- add / sub saturation */

static void test_add_sub(void **state)
{
    (void)state;
    /* In-range values are exact in both arithmetics (all dyadic). */
    expect_close(qd(ctl_add(CTL_Q(1.5), CTL_Q(-0.25))), 1.25, 0.0, "add", 1.5);
    expect_close(qd(ctl_sub(CTL_Q(-3.0), CTL_Q(0.75))), -3.75, 0.0, "sub", -3.0);
    expect_close(qd(ctl_add(CTL_Q(100.0), CTL_Q(27.5))), 127.5, 0.0, "add", 100.0);
#if CTL_MATH_FLOAT
    /* Float: no saturation, just the correct value. */
    expect_close(qd(ctl_add(CTL_Q(100.0), CTL_Q(100.0))), 200.0, 0.0, "add", 100.0);
    expect_close(qd(ctl_sub(CTL_Q(-100.0), CTL_Q(100.0))), -200.0, 0.0, "sub", -100.0);
#else
    expect_i32(ctl_add(INT32_MAX, 1), INT32_MAX, "add MAX+1");
    expect_i32(ctl_add(INT32_MAX, INT32_MAX), INT32_MAX, "add MAX+MAX");
    expect_i32(ctl_add(INT32_MIN, -1), INT32_MIN, "add MIN-1");
    expect_i32(ctl_add(INT32_MIN, INT32_MIN), INT32_MIN, "add MIN+MIN");
    expect_i32(ctl_add(CTL_Q(100.0), CTL_Q(100.0)), INT32_MAX, "add 100+100");
    expect_i32(ctl_add(CTL_Q(-100.0), CTL_Q(-100.0)), INT32_MIN, "add -100-100");
    expect_i32(ctl_add(INT32_MAX, INT32_MIN), -1, "add MAX+MIN");
    expect_i32(ctl_add(INT32_MAX - 5, 5), INT32_MAX, "add exactly MAX");
    expect_i32(ctl_sub(INT32_MIN, 1), INT32_MIN, "sub MIN-1");
    expect_i32(ctl_sub(INT32_MAX, -1), INT32_MAX, "sub MAX+1");
    expect_i32(ctl_sub(0, INT32_MIN), INT32_MAX, "sub 0-MIN");
    expect_i32(ctl_sub(-1, INT32_MIN), INT32_MAX, "sub -1-MIN");
    expect_i32(ctl_sub(-2, INT32_MAX), INT32_MIN, "sub -2-MAX");
    expect_i32(ctl_sub(CTL_Q(-100.0), CTL_Q(100.0)), INT32_MIN, "sub -100-100");
    expect_i32(ctl_sub(CTL_Q(100.0), CTL_Q(-100.0)), INT32_MAX, "sub 100+100");
#endif
}

/* --------------------------------------------------- mul and its rounding */

static void test_mul(void **state)
{
    (void)state;
    expect_close(qd(ctl_mul(CTL_Q(1.5), CTL_Q(-2.0))), -3.0, 0.0, "mul", 1.5);
    expect_close(qd(ctl_mul(CTL_Q(-0.5), CTL_Q(-0.25))), 0.125, 0.0, "mul", -0.5);
    expect_close(qd(ctl_mul(CTL_Q(11.0), CTL_Q(11.5))), 126.5, 0.0, "mul", 11.0);
#if CTL_MATH_FLOAT
    expect_close(qd(ctl_mul(CTL_Q(16.0), CTL_Q(16.0))), 256.0, 0.0, "mul", 16.0);
    expect_close(qd(ctl_mul(CTL_Q(-16.0), CTL_Q(16.0))), -256.0, 0.0, "mul", -16.0);
#else
    expect_i32(ctl_mul(CTL_Q(16.0), CTL_Q(16.0)), INT32_MAX, "mul 16*16");
    expect_i32(ctl_mul(CTL_Q(-16.0), CTL_Q(16.0)), INT32_MIN, "mul -16*16");
    expect_i32(ctl_mul(CTL_Q(-16.0), CTL_Q(-16.0)), INT32_MAX, "mul -16*-16");
    expect_i32(ctl_mul(INT32_MIN, INT32_MIN), INT32_MAX, "mul MIN*MIN");
    expect_i32(ctl_mul(INT32_MAX, INT32_MIN), INT32_MIN, "mul MAX*MIN");
    expect_i32(ctl_mul(INT32_MIN, CTL_Q(1.0)), INT32_MIN, "mul MIN*1 (no saturation)");
    expect_i32(ctl_mul(INT32_MAX, CTL_Q(1.0)), INT32_MAX, "mul MAX*1");
    expect_i32(ctl_mul(INT32_MIN, CTL_Q(-1.0)), INT32_MAX, "mul MIN*-1");

    /* Rounding: round half up (towards +inf) at 2^-25. */
    expect_i32(ctl_mul(1, CTL_Q(0.5)), 1, "mul +0.5 LSB");            /* +0.5 -> 1 */
    expect_i32(ctl_mul(-1, CTL_Q(0.5)), 0, "mul -0.5 LSB");           /* -0.5 -> 0 */
    expect_i32(ctl_mul(3, CTL_Q(0.5)), 2, "mul +1.5 LSB");            /* +1.5 -> 2 */
    expect_i32(ctl_mul(-3, CTL_Q(0.5)), -1, "mul -1.5 LSB");          /* -1.5 -> -1 */
    expect_i32(ctl_mul(1, CTL_Q(0.5) - 1), 0, "mul just below half"); /* 0.49999994 -> 0 */
    expect_i32(ctl_mul(-1, CTL_Q(0.5) + 1), -1, "mul just below -half");
    expect_i32(ctl_mul(1, CTL_Q(0.5) + 1), 1, "mul just above half");

    /* Random sweep against round-half-up of the exact product (long double holds the
     * 62-bit product exactly on x86-64). */
    if (LDBL_MANT_DIG >= 64) {
        int32_t i;
        for (i = 0; i < 200000; i++) {
            const int32_t a = (int32_t)rng_u32();
            const int32_t b = (i & 1) ? (int32_t)rng_u32() : (int32_t)rng_u32() >> 8;
            const long double exact = (long double)a * (long double)b / 16777216.0L;
            long double r = floorl(exact + 0.5L);
            int32_t want;
            if (r > 2147483647.0L) {
                r = 2147483647.0L;
            }
            if (r < -2147483648.0L) {
                r = -2147483648.0L;
            }
            want = (int32_t)r;
            if (ctl_mul(a, b) != want) {
                print_error("mul(%ld, %ld) = %ld, want %ld\n", (long)a, (long)b,
                            (long)ctl_mul(a, b), (long)want);
                fail();
            }
        }
    }
#endif
}

#if !CTL_MATH_FLOAT
/* Round half up of an exact Q48 value to Q24, saturated (long double holds 64 bits). */
static int32_t round_q48(long double exact_q48)
{
    long double r = floorl(exact_q48 / 16777216.0L + 0.5L);
    if (r > 2147483647.0L) {
        return INT32_MAX;
    }
    if (r < -2147483648.0L) {
        return INT32_MIN;
    }
    return (int32_t)r;
}
#endif

/* The fused forms round the exact sum once: a*b + c*d, a*b - c*d, acc + a*b, acc - a*b,
 * including the one sum of two Q48 products that does not fit int64 (both MIN * MIN). */
static void test_fused_mul(void **state)
{
    (void)state;
    expect_close(qd(ctl_mul_add(CTL_Q(1.5), CTL_Q(2.0), CTL_Q(-0.5), CTL_Q(4.0))), 1.0, 0.0,
                 "mul_add", 1.5);
    expect_close(qd(ctl_mul_sub(CTL_Q(1.5), CTL_Q(2.0), CTL_Q(-0.5), CTL_Q(4.0))), 5.0, 0.0,
                 "mul_sub", 1.5);
    expect_close(qd(ctl_mul_acc(CTL_Q(0.25), CTL_Q(0.5), CTL_Q(0.5))), 0.5, 0.0, "mul_acc", 0.25);
    expect_close(qd(ctl_mul_dec(CTL_Q(0.25), CTL_Q(0.5), CTL_Q(0.5))), 0.0, 0.0, "mul_dec", 0.25);
#if !CTL_MATH_FLOAT
    expect_i32(ctl_mul_add(INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN), INT32_MAX, "MIN^2+MIN^2");
    expect_i32(ctl_mul_sub(INT32_MIN, INT32_MIN, INT32_MIN, INT32_MAX), INT32_MAX, "MIN^2-MIN*MAX");
    expect_i32(ctl_mul_sub(INT32_MIN, INT32_MAX, INT32_MIN, INT32_MIN), INT32_MIN, "MIN*MAX-MIN^2");
    expect_i32(ctl_mul_acc(INT32_MIN, INT32_MIN, INT32_MAX), INT32_MIN, "MIN+MIN*MAX");
    expect_i32(ctl_mul_dec(INT32_MAX, INT32_MIN, INT32_MAX), INT32_MAX, "MAX-MIN*MAX");
    if (LDBL_MANT_DIG >= 64) {
        int32_t i;
        for (i = 0; i < 200000; i++) {
            const int32_t a = (int32_t)rng_u32();
            const int32_t b = (i & 1) ? (int32_t)rng_u32() : (int32_t)rng_u32() >> 8;
            const int32_t c = (int32_t)rng_u32() >> (i % 9);
            const int32_t d = (int32_t)rng_u32() >> (i % 7);
            const long double ab = (long double)a * (long double)b;
            const long double cd = (long double)c * (long double)d;
            const long double acc = (long double)c * 16777216.0L;
            if (ctl_mul_add(a, b, c, d) != round_q48(ab + cd) ||
                ctl_mul_sub(a, b, c, d) != round_q48(ab - cd) ||
                ctl_mul_acc(c, a, b) != round_q48(acc + ab) ||
                ctl_mul_dec(c, a, b) != round_q48(acc - ab)) {
                print_error("fused(%ld, %ld, %ld, %ld) off\n", (long)a, (long)b, (long)c, (long)d);
                fail();
            }
        }
    }
#endif
}

static void test_mul_int(void **state)
{
    (void)state;
    expect_close(qd(ctl_mul_int(CTL_Q(1.25), 3)), 3.75, 0.0, "mul_int", 1.25);
    expect_close(qd(ctl_mul_int(CTL_Q(-0.75), -100)), 75.0, 0.0, "mul_int", -0.75);
    expect_close(qd(ctl_mul_int(CTL_Q(0.5), 0)), 0.0, 0.0, "mul_int", 0.5);
#if CTL_MATH_FLOAT
    expect_close(qd(ctl_mul_int(CTL_Q(100.0), 2)), 200.0, 0.0, "mul_int", 100.0);
    expect_close(qd(ctl_mul_int(CTL_Q(100.0), -2)), -200.0, 0.0, "mul_int", 100.0);
    expect_close(qd(ctl_mul_int(CTL_Q(1.0), INT16_MIN)), -32768.0, 0.0, "mul_int", 1.0);
#else
    expect_i32(ctl_mul_int(CTL_Q(100.0), 2), INT32_MAX, "mul_int 100*2");
    expect_i32(ctl_mul_int(CTL_Q(100.0), -2), INT32_MIN, "mul_int 100*-2");
    expect_i32(ctl_mul_int(INT32_MIN, -1), INT32_MAX, "mul_int MIN*-1");
    expect_i32(ctl_mul_int(INT32_MIN, 1), INT32_MIN, "mul_int MIN*1");
    expect_i32(ctl_mul_int(CTL_Q(1.0), INT16_MIN), INT32_MIN, "mul_int 1*-32768");
    expect_i32(ctl_mul_int(CTL_Q(1.0), INT16_MAX), INT32_MAX, "mul_int 1*32767");
    expect_i32(ctl_mul_int(CTL_Q(-1.0), 128), INT32_MIN, "mul_int -1*128 (exactly MIN)");
    expect_i32(ctl_mul_int(CTL_Q(1.0), 127), CTL_Q(127.0), "mul_int 1*127");
#endif
}

/* ------------------------------------------------------------------- div */

static void test_div(void **state)
{
    (void)state;
    expect_close(qd(ctl_div(CTL_Q(3.0), CTL_Q(-4.0))), -0.75, 0.0, "div", 3.0);
    expect_close(qd(ctl_div(CTL_Q(-1.0), CTL_Q(-0.125))), 8.0, 0.0, "div", -1.0);
    expect_close(qd(ctl_div(CTL_Q(1.0), CTL_Q(3.0))), 1.0 / 3.0, CTL_MATH_FLOAT ? 1e-7 : Q24_LSB,
                 "div", 1.0);

    /* Division by zero: +-max by the sign of the dividend; 0/0 counts as positive. */
    expect_close(qd(ctl_div(CTL_Q(1.0), CTL_Q(0.0))), qd(CTL_Q_MAX), 0.0, "div 1/0", 1.0);
    expect_close(qd(ctl_div(CTL_Q(-1.0), CTL_Q(0.0))), qd(CTL_Q_MIN), 0.0, "div -1/0", -1.0);
    expect_close(qd(ctl_div(CTL_Q(0.0), CTL_Q(0.0))), qd(CTL_Q_MAX), 0.0, "div 0/0", 0.0);
#if CTL_MATH_FLOAT
    expect_close(qd(ctl_div(CTL_Q(1.0), CTL_Q(0.0))), 128.0, 0.0, "div 1/0", 1.0);
    expect_close(qd(ctl_div(CTL_Q(-1.0), CTL_Q(0.0))), -128.0, 0.0, "div -1/0", -1.0);
    expect_close(qd(ctl_div(CTL_Q(100.0), CTL_Q(0.5))), 200.0, 0.0, "div", 100.0);
    expect_close(qd(ctl_div(CTL_Q(-100.0), CTL_Q(0.5))), -200.0, 0.0, "div", -100.0);
#else
    expect_i32(ctl_div(CTL_Q(1.0), 0), INT32_MAX, "div 1/0");
    expect_i32(ctl_div(INT32_MAX, 0), INT32_MAX, "div MAX/0");
    expect_i32(ctl_div(CTL_Q(-1.0), 0), INT32_MIN, "div -1/0");
    expect_i32(ctl_div(INT32_MIN, 0), INT32_MIN, "div MIN/0");
    expect_i32(ctl_div(CTL_Q(100.0), CTL_Q(0.5)), INT32_MAX, "div 100/0.5");
    expect_i32(ctl_div(CTL_Q(-100.0), CTL_Q(0.5)), INT32_MIN, "div -100/0.5");
    expect_i32(ctl_div(CTL_Q(100.0), CTL_Q(-0.5)), INT32_MIN, "div 100/-0.5");
    expect_i32(ctl_div(INT32_MIN, -1), INT32_MAX, "div MIN/-LSB");
    expect_i32(ctl_div(INT32_MAX, 1), INT32_MAX, "div MAX/LSB");
    expect_i32(ctl_div(1, INT32_MAX), 0, "div LSB/MAX");
    expect_i32(ctl_div(CTL_Q(64.0), CTL_Q(0.5)), INT32_MAX, "div 64/0.5 (= 128)");
    expect_i32(ctl_div(CTL_Q(-64.0), CTL_Q(0.5)), INT32_MIN, "div -64/0.5 (= -128 = MIN)");

    /* Random sweep: error below one LSB of the exact quotient, or saturated. */
    if (LDBL_MANT_DIG >= 64) {
        int32_t i;
        for (i = 0; i < 200000; i++) {
            const int32_t a = (int32_t)rng_u32() >> (rng_u32() % 24u);
            const int32_t b = (int32_t)rng_u32() >> (rng_u32() % 31u);
            const ctl_q got = (b == 0) ? 0 : ctl_div(a, b);
            long double exact;
            if (b == 0) {
                continue;
            }
            exact = (long double)a * 16777216.0L / (long double)b;
            if (exact >= 2147483647.0L) {
                expect_i32(got, INT32_MAX, "div saturates high");
            } else if (exact <= -2147483648.0L) {
                expect_i32(got, INT32_MIN, "div saturates low");
            } else if (!(fabsl((long double)got - exact) < 1.0L)) {
                print_error("div(%ld, %ld) = %ld, exact %.3Lf\n", (long)a, (long)b, (long)got,
                            exact);
                fail();
            }
        }
    }
#endif
}

/* ------------------------------------------------------------------- abs */

static void test_abs(void **state)
{
    (void)state;
    expect_close(qd(ctl_abs(CTL_Q(-0.5))), 0.5, 0.0, "abs", -0.5);
    expect_close(qd(ctl_abs(CTL_Q(3.25))), 3.25, 0.0, "abs", 3.25);
    expect_close(qd(ctl_abs(CTL_Q(0.0))), 0.0, 0.0, "abs", 0.0);
#if CTL_MATH_FLOAT
    expect_close(qd(ctl_abs(CTL_Q_MIN)), 128.0, 0.0, "abs", -128.0);
#else
    expect_i32(ctl_abs(INT32_MIN), INT32_MAX, "abs MIN saturates");
    expect_i32(ctl_abs(INT32_MIN + 1), INT32_MAX, "abs MIN+1");
    expect_i32(ctl_abs(INT32_MAX), INT32_MAX, "abs MAX");
    expect_i32(ctl_abs(-1), 1, "abs -LSB");
#endif
}

/* ------------------------------------------------------- float conversion */

static void test_from_float(void **state)
{
    (void)state;
    /* Exactly representable values convert exactly. */
    expect_close(qd(ctl_from_float(1.0f)), 1.0, 0.0, "from_float", 1.0);
    expect_close(qd(ctl_from_float(-0.375f)), -0.375, 0.0, "from_float", -0.375);
    expect_close(qd(ctl_from_float(100.5f)), 100.5, 0.0, "from_float", 100.5);
    expect_close((double)ctl_to_float(CTL_Q(-2.5)), -2.5, 0.0, "to_float", -2.5);
#if CTL_MATH_FLOAT
    /* Float build: identity, no saturation. (NaN is passed through unchanged in the float
     * build; only the fixed build maps it to 0, see the fixed-point branch.) */
    expect_close(qd(ctl_from_float(200.0f)), 200.0, 0.0, "from_float", 200.0);
    expect_close(qd(ctl_from_float(0.1f)), (double)0.1f, 0.0, "from_float", 0.1);
#else
    expect_i32(ctl_from_float(0.1f), CTL_Q(0.1), "from_float 0.1");
    expect_i32(ctl_from_float(-0.1f), CTL_Q(-0.1), "from_float -0.1");
    /* Rounding to nearest, halves away from zero (the conversion's own rule). */
    expect_i32(ctl_from_float(1.5f * (float)Q24_LSB), 2, "from_float 1.5 LSB");
    expect_i32(ctl_from_float(-1.5f * (float)Q24_LSB), -2, "from_float -1.5 LSB");
    expect_i32(ctl_from_float(1.25f * (float)Q24_LSB), 1, "from_float 1.25 LSB");
    expect_i32(ctl_from_float(-1.25f * (float)Q24_LSB), -1, "from_float -1.25 LSB");
    /* Saturation. */
    expect_i32(ctl_from_float(128.0f), INT32_MAX, "from_float 128");
    /* 127.99999f is 128 - 2^-17 = raw 2^31 - 128: the conversion saturates from there on
     * (at most 127 LSB above the exact raw value). */
    assert_true(ctl_from_float(127.99999f) >= INT32_MAX - 127);
    expect_i32(ctl_from_float(127.99f), (int32_t)((double)127.99f * 16777216.0),
               "from_float 127.99");
    expect_i32(ctl_from_float(200.0f), INT32_MAX, "from_float 200");
    expect_i32(ctl_from_float(1.0e30f), INT32_MAX, "from_float 1e30");
    expect_i32(ctl_from_float(INFINITY), INT32_MAX, "from_float +inf");
    expect_i32(ctl_from_float(-128.0f), INT32_MIN, "from_float -128");
    expect_i32(ctl_from_float(-200.0f), INT32_MIN, "from_float -200");
    expect_i32(ctl_from_float(-INFINITY), INT32_MIN, "from_float -inf");
    expect_i32(ctl_from_float(NAN), 0, "from_float NaN");
    expect_i32(ctl_from_float(-NAN), 0, "from_float -NaN");
    {
        /* Sweep: within half an LSB plus the float's own rounding of x * 2^24. */
        int32_t i;
        for (i = 0; i < 100000; i++) {
            const float x = (float)rng_range(-127.9, 127.9);
            const double want = (double)x * 16777216.0;
            const double got = (double)ctl_from_float(x);
            const double tol = 0.5 + fabs(want) * (double)FLT_EPSILON;
            expect_close(got, want, tol, "from_float sweep (raw)", (double)x);
        }
    }
#endif
}

static void test_to_qn(void **state)
{
    (void)state;
    expect_i32(ctl_to_qn(CTL_Q(1.0), 12), 4096, "to_qn 1.0 Q12");
    expect_i32(ctl_to_qn(CTL_Q(-1.0), 12), -4096, "to_qn -1.0 Q12");
    expect_i32(ctl_to_qn(CTL_Q(0.75), 0), 1, "to_qn 0.75 Q0");
    expect_i32(ctl_to_qn(CTL_Q(0.25), 0), 0, "to_qn 0.25 Q0");
    expect_i32(ctl_to_qn(CTL_Q(-0.75), 0), -1, "to_qn -0.75 Q0");
    expect_i32(ctl_to_qn(CTL_Q(-0.25), 0), 0, "to_qn -0.25 Q0");
    expect_i32(ctl_to_qn(CTL_Q(2.5), 0), 3, "to_qn 2.5 Q0 (tie up)");
    expect_i32(ctl_to_qn(CTL_Q(3.5), 0), 4, "to_qn 3.5 Q0 (tie up)");
    expect_i32(ctl_to_qn(CTL_Q(100.4), 0), 100, "to_qn 100.4 Q0");
    expect_i32(ctl_to_qn(CTL_Q(1.0) / 3, 15), 10923, "to_qn 1/3 Q15"); /* 10922.67 */
    expect_i32(ctl_to_qn(CTL_Q(-1.0) / 3, 15), -10923, "to_qn -1/3 Q15");
    expect_i32(ctl_to_qn(CTL_Q(0.5), 24), 8388608, "to_qn 0.5 Q24");
    expect_i32(ctl_to_qn(CTL_Q(-0.5), 24), -8388608, "to_qn -0.5 Q24");
#if CTL_MATH_FLOAT
    /* Negative ties: the float build rounds halves away from zero ... */
    expect_i32(ctl_to_qn(CTL_Q(-2.5), 0), -3, "to_qn -2.5 Q0 (float: away from zero)");
    /* ... and saturates at the int32 limits, NaN -> 0. */
    expect_i32(ctl_to_qn(CTL_Q(200.0), 24), INT32_MAX, "to_qn 200 Q24");
    expect_i32(ctl_to_qn(CTL_Q(-200.0), 24), INT32_MIN, "to_qn -200 Q24");
    expect_i32(ctl_to_qn(NAN, 12), 0, "to_qn NaN");
#else
    /* ... while the fixed build rounds halves up (towards +inf): -2.5 -> -2. */
    expect_i32(ctl_to_qn(CTL_Q(-2.5), 0), -2, "to_qn -2.5 Q0 (fixed: half up)");
    expect_i32(ctl_to_qn(0x800, 12), 1, "to_qn +half LSB Q12");
    expect_i32(ctl_to_qn(0x7FF, 12), 0, "to_qn below half Q12");
    expect_i32(ctl_to_qn(-0x800, 12), 0, "to_qn -half LSB Q12");
    expect_i32(ctl_to_qn(-0x801, 12), -1, "to_qn below -half Q12");
    expect_i32(ctl_to_qn(INT32_MAX, 24), INT32_MAX, "to_qn MAX Q24");
    expect_i32(ctl_to_qn(INT32_MIN, 24), INT32_MIN, "to_qn MIN Q24");
    expect_i32(ctl_to_qn(INT32_MAX, 0), 128, "to_qn MAX Q0");
    expect_i32(ctl_to_qn(INT32_MIN, 0), -128, "to_qn MIN Q0");
    {
        /* Sweep: |result - x 2^n| <= 1/2 for every n. */
        int32_t i;
        for (i = 0; i < 100000; i++) {
            const ctl_q x = (ctl_q)rng_u32();
            const int16_t n = (int16_t)(rng_u32() % 25u);
            const double want = qd(x) * ldexp(1.0, n);
            expect_close((double)ctl_to_qn(x, n), want, 0.5, "to_qn sweep", qd(x));
        }
    }
#endif
}

static void test_from_turn_u32(void **state)
{
    int32_t i;
    (void)state;
    expect_close(qd(ctl_from_turn_u32(0u)), 0.0, 0.0, "from_turn_u32", 0.0);
    expect_close(qd(ctl_from_turn_u32(0x80000000u)), 0.5, 0.0, "from_turn_u32", 0.5);
    expect_close(qd(ctl_from_turn_u32(0x40000000u)), 0.25, 0.0, "from_turn_u32", 0.25);
    expect_close(qd(ctl_from_turn_u32(0xC0000000u)), 0.75, 0.0, "from_turn_u32", 0.75);
#if !CTL_MATH_FLOAT
    /* Truncation of the low 8 bits. */
    expect_i32(ctl_from_turn_u32(0x100u), 1, "from_turn_u32 one LSB");
    expect_i32(ctl_from_turn_u32(0xFFu), 0, "from_turn_u32 below one LSB");
    expect_i32(ctl_from_turn_u32(0xFFFFFFFFu), CTL_Q_ONE - 1, "from_turn_u32 max");
#endif
    /* The whole range: within one Q24 LSB of turn / 2^32, and it wraps into [0, 1). */
    for (i = 0; i < 100000; i++) {
        const uint32_t t = (i == 0) ? 0xFFFFFFFFu : rng_u32();
        const double want = (double)t / 4294967296.0;
        const ctl_q got = ctl_from_turn_u32(t);
        const double w = qd(ctl_wrap_turn(got));
        expect_close(qd(got), want, Q24_LSB, "from_turn_u32", want);
        assert_true(w >= 0.0 && w < 1.0);
        expect_close(turn_diff(w, want), 0.0, Q24_LSB, "wrap(from_turn_u32)", want);
    }
}

static void test_mul_q16(void **state)
{
    int32_t i;
    (void)state;
    expect_close(qd(ctl_mul_q16(65536, CTL_Q(1.5))), 1.5, 0.0, "mul_q16", 1.0);
    expect_close(qd(ctl_mul_q16(3 * 65536, CTL_Q(0.25))), 0.75, 0.0, "mul_q16", 3.0);
    expect_close(qd(ctl_mul_q16(-2 * 65536, CTL_Q(0.125))), -0.25, 0.0, "mul_q16", -2.0);
    expect_close(qd(ctl_mul_q16(32768, CTL_Q(-1.0))), -0.5, 0.0, "mul_q16", 0.5);
#if CTL_MATH_FLOAT
    expect_close(qd(ctl_mul_q16(INT32_MAX, CTL_Q(1.0))), 32768.0, 1e-2, "mul_q16", 32768.0);
#else
    expect_i32(ctl_mul_q16(INT32_MAX, CTL_Q(1.0)), INT32_MAX, "mul_q16 saturates high");
    expect_i32(ctl_mul_q16(INT32_MIN, CTL_Q(1.0)), INT32_MIN, "mul_q16 saturates low");
    expect_i32(ctl_mul_q16(-65536 * 200, CTL_Q(1.0)), INT32_MIN, "mul_q16 -200");
#endif
    /* Sweep: raw Q16 values of +-64 and factors of +-1.9, product inside the range. */
    for (i = 0; i < 100000; i++) {
        const int32_t raw = (int32_t)rng_u32() >> 9;
        const ctl_q k = dq(rng_range(-1.9, 1.9));
        const double want = (double)raw / 65536.0 * qd(k);
        const double got = qd(ctl_mul_q16(raw, k));
        if (fabs(want) >= 127.0) {
            continue;
        }
        /* fixed: truncating shift, error in (-1, 0] LSB; float: a few float roundings. */
        expect_close(got, want, CTL_MATH_FLOAT ? fabs(want) * 3e-7 : Q24_LSB, "mul_q16 sweep",
                     (double)raw);
    }
}

/* ------------------------------------------------------------------ sqrt */

static void test_sqrt_exact(void **state)
{
    int32_t k;
    (void)state;
    /* Negative input gives 0, zero gives 0. */
    expect_close(qd(ctl_sqrt(CTL_Q(-1.0))), 0.0, 0.0, "sqrt", -1.0);
    expect_close(qd(ctl_sqrt(CTL_Q(-0.001))), 0.0, 0.0, "sqrt", -0.001);
    expect_close(qd(ctl_sqrt(CTL_Q_MIN)), 0.0, 0.0, "sqrt", qd(CTL_Q_MIN));
    expect_close(qd(ctl_sqrt(CTL_Q(0.0))), 0.0, 0.0, "sqrt", 0.0);
    /* Small exact squares: k^2 for k = 1..11 and (k/16)^2 for k = 1..180. */
    for (k = 1; k <= 11; k++) {
        expect_close(qd(ctl_sqrt(dq((double)(k * k)))), (double)k, 0.0, "sqrt k^2",
                     (double)(k * k));
    }
    for (k = 1; k <= 180; k++) {
        const double r = (double)k / 16.0;
        expect_close(qd(ctl_sqrt(dq(r * r))), r, 0.0, "sqrt (k/16)^2", r * r);
    }
#if !CTL_MATH_FLOAT
    expect_i32(ctl_sqrt(-1), 0, "sqrt -LSB");
    /* Every raw perfect square m^2 (value m^2 2^-24) has the exact root m 2^12 raw. */
    for (k = 1; k <= 46340; k++) {
        if (ctl_sqrt(k * k) != k * 4096) {
            print_error("sqrt(raw %ld) = %ld, want %ld\n", (long)(k * k), (long)ctl_sqrt(k * k),
                        (long)(k * 4096));
            fail();
        }
    }
    /* Largest input: sqrt(128 - 2^-24) = 11.3137..., floor in raw. */
    expect_close(qd(ctl_sqrt(INT32_MAX)), sqrt(qd(INT32_MAX)), Q24_LSB, "sqrt MAX", qd(INT32_MAX));
#endif
}

static void test_sqrt_sweep(void **state)
{
    double max_abs = 0.0;
    double max_rel = 0.0; /* for inputs >= 1e-4 */
    double worst_in = 0.0;
    double x;
    int32_t i;
    (void)state;
    /* Geometric sweep over the whole positive range plus uniform random values. */
    for (i = 0; i < 300000; i++) {
        ctl_q a;
        double want;
        double got;
        double err;
        if (i < 200000) {
            x = 1e-7 * pow(127.99 / 1e-7, (double)i / 199999.0);
        } else {
            x = rng_range(0.0, 127.99);
        }
        a = dq(x);
        want = sqrt(qd(a));
        got = qd(ctl_sqrt(a));
        err = fabs(got - want);
        if (err > max_abs) {
            max_abs = err;
        }
        if (qd(a) >= 1e-4 && err / want > max_rel) {
            max_rel = err / want;
            worst_in = qd(a);
        }
#if CTL_MATH_FLOAT
        /* float: relative error within 2 float ulps (2^-22). */
        expect_close(got, want, want * 2.4e-7, "sqrt sweep", qd(a));
#else
        /* fixed: integer root truncated, error in (-1, 0] LSB. */
        expect_close(got, want, Q24_LSB, "sqrt sweep", qd(a));
        assert_true(got <= want);
#endif
    }
    print_message("ctl_sqrt: max abs err %.3g, max rel err (x >= 1e-4) %.3g at x = %.6g\n", max_abs,
                  max_rel, worst_in);
    /* Relative bound over x >= 1e-4: fixed 1 LSB / 0.01 = 6e-6, float 2.4e-7. */
    assert_true(max_rel < (CTL_MATH_FLOAT ? 2.4e-7 : 6.0e-6));
}

static void test_sqrtf(void **state)
{
    double max_rel = 0.0;
    double worst_in = 0.0;
    int32_t i;
    (void)state;
    assert_true(ctl_sqrtf(0.0f) == 0.0f);
    assert_true(ctl_sqrtf(-4.0f) == 0.0f);
    assert_true(ctl_sqrtf(-INFINITY) == 0.0f);
    assert_true(ctl_sqrtf(NAN) == 0.0f);
    assert_true(ctl_sqrtf(INFINITY) == INFINITY);
    for (i = 1; i <= 4096; i++) {
        /* Exact squares of integers up to 4096 (exact in float). */
        const float k = (float)i;
        if (ctl_sqrtf(k * k) != k) {
            print_error("ctl_sqrtf(%g) = %.9g, want %g\n", (double)(k * k),
                        (double)ctl_sqrtf(k * k), (double)k);
            fail();
        }
    }
    /* Geometric sweep over every normal float magnitude, FLT_MIN .. FLT_MAX. */
    for (i = 0; i < 400000; i++) {
        const double xd =
            (double)FLT_MIN * pow((double)FLT_MAX / (double)FLT_MIN, (double)i / 399999.0);
        const float x = (i == 399999) ? FLT_MAX : (float)xd;
        const double want = sqrt((double)x);
        const double got = (double)ctl_sqrtf(x);
        const double rel = fabs(got - want) / want;
        if (rel > max_rel) {
            max_rel = rel;
            worst_in = (double)x;
        }
    }
    print_message("ctl_sqrtf: max rel err over normal floats %.3g at x = %.6g\n", max_rel,
                  worst_in);
    /* Two float ulps. */
    if (!(max_rel <= 2.4e-7)) {
        print_error("ctl_sqrtf: max rel err %.3g at x = %.9g\n", max_rel, worst_in);
        fail();
    }
}

/* ------------------------------------------------------------- sin / cos */

#define SINCOS_TOL 1.0e-5

static void check_sincos(ctl_q a, double *max_err, double *worst)
{
    const double ang = TWO_PI * qd(a);
    const double es = fabs(qd(ctl_sin_pu(a)) - sin(ang));
    const double ec = fabs(qd(ctl_cos_pu(a)) - cos(ang));
    ctl_q s;
    ctl_q c;
    ctl_sincos_pu(a, &s, &c);
    if (s != ctl_sin_pu(a) || c != ctl_cos_pu(a)) {
        print_error("ctl_sincos_pu(%.10g) differs from ctl_sin_pu/ctl_cos_pu\n", qd(a));
        fail();
    }
    /* the cosine is the sine a quarter turn on, to the last bit (one wrap serves both), where
     * that angle is exact (float: the cosine keeps the low bits that adding 0.25 rounds off) */
    const ctl_q on = ctl_wrap_turn(a) + CTL_Q(0.25);
    if (on - CTL_Q(0.25) == ctl_wrap_turn(a) && c != ctl_sin_pu(on)) {
        print_error("ctl_cos_pu(%.10g) is not the sine a quarter turn on\n", qd(a));
        fail();
    }
    if (es > *max_err) {
        *max_err = es;
        *worst = qd(a);
    }
    if (ec > *max_err) {
        *max_err = ec;
        *worst = qd(a);
    }
    if (!(es < SINCOS_TOL && ec < SINCOS_TOL)) {
        print_error("angle %.10g turn: sin err %.3g, cos err %.3g (tol %.1g); sin %.9g cos %.9g\n",
                    qd(a), es, ec, SINCOS_TOL, qd(ctl_sin_pu(a)), qd(ctl_cos_pu(a)));
        fail();
    }
}

static void test_sin_cos(void **state)
{
    double max_err = 0.0;
    double worst = 0.0;
    int32_t i;
    (void)state;
    /* Cardinal points. */
    expect_close(qd(ctl_sin_pu(CTL_Q(0.0))), 0.0, 1e-7, "sin_pu", 0.0);
    expect_close(qd(ctl_sin_pu(CTL_Q(0.25))), 1.0, 1e-7, "sin_pu", 0.25);
    expect_close(qd(ctl_sin_pu(CTL_Q(0.5))), 0.0, 1e-7, "sin_pu", 0.5);
    expect_close(qd(ctl_sin_pu(CTL_Q(0.75))), -1.0, 1e-7, "sin_pu", 0.75);
    expect_close(qd(ctl_cos_pu(CTL_Q(0.0))), 1.0, 1e-7, "cos_pu", 0.0);
    expect_close(qd(ctl_cos_pu(CTL_Q(-0.5))), -1.0, 1e-7, "cos_pu", -0.5);
    expect_close(qd(ctl_sin_pu(CTL_Q(-0.25))), -1.0, 1e-7, "sin_pu", -0.25);
    expect_close(qd(ctl_sin_pu(CTL_Q(2.25))), 1.0, 1e-7, "sin_pu", 2.25);
    /* Dense sweep over [-2, 3) turn: negative angles and more than one turn. */
#if CTL_MATH_FLOAT
    for (i = 0; i < 1000000; i++) {
        check_sincos(dq(-2.0 + 5.0 * (double)i / 1000000.0), &max_err, &worst);
    }
#else
    for (i = 2 * INT32_C(-16777216); i < 3 * INT32_C(16777216); i += 97) {
        check_sincos(i, &max_err, &worst);
    }
#endif
    /* Random angles over the whole representable range. */
    for (i = 0; i < 200000; i++) {
        check_sincos(dq(rng_range(-127.999, 127.999)), &max_err, &worst);
    }
    /* The last quarter turn below +128 and above -128 turn (cos adds a quarter turn). */
    for (i = 0; i < 20000; i++) {
        check_sincos(dq(127.75 + 0.2499 * (double)i / 20000.0), &max_err, &worst);
        check_sincos(dq(-128.0 + 0.2499 * (double)i / 20000.0), &max_err, &worst);
    }
#if !CTL_MATH_FLOAT
    check_sincos(INT32_MAX, &max_err, &worst);
    check_sincos(INT32_MIN, &max_err, &worst);
#endif
    print_message("ctl_sin_pu/ctl_cos_pu: max abs err %.3g at %.9g turn\n", max_err, worst);
}

/* ----------------------------------------------------------------- atan2 */

#define ATAN2_TOL_TURN 1.0e-6

static void check_atan2(ctl_q y, ctl_q x, double *max_err, double *worst)
{
    const ctl_q got_q = ctl_atan2_pu(y, x);
    const double got = qd(got_q);
    double want = atan2(qd(y), qd(x)) / TWO_PI;
    double err;
    if (want < 0.0) {
        want += 1.0;
    }
    err = fabs(turn_diff(got, want));
    if (err > *max_err) {
        *max_err = err;
        *worst = want;
    }
    if (!(got >= 0.0 && got < 1.0 && err < ATAN2_TOL_TURN)) {
        print_error("atan2_pu(y %.10g, x %.10g) = %.10g turn, want %.10g (err %.3g)\n", qd(y),
                    qd(x), got, want, err);
        fail();
    }
}

static void test_atan2_axes(void **state)
{
    static const double radii[] = {1e-6, 0.01, 1.0, 3.0, 60.0}; /* 2r stays in range */
    int32_t i;
    (void)state;
    /* atan2(0, 0) = 0 by definition. */
    expect_close(qd(ctl_atan2_pu(CTL_Q(0.0), CTL_Q(0.0))), 0.0, 0.0, "atan2_pu(0,0)", 0.0);
    for (i = 0; i < 5; i++) {
        const ctl_q r = dq(radii[i]);
        const ctl_q m = dq(-radii[i]);
        /* Axes: exact. */
        expect_close(qd(ctl_atan2_pu(CTL_Q(0.0), r)), 0.0, 0.0, "atan2_pu +x axis", radii[i]);
        expect_close(qd(ctl_atan2_pu(r, CTL_Q(0.0))), 0.25, 0.0, "atan2_pu +y axis", radii[i]);
        expect_close(qd(ctl_atan2_pu(CTL_Q(0.0), m)), 0.5, 0.0, "atan2_pu -x axis", radii[i]);
        expect_close(qd(ctl_atan2_pu(m, CTL_Q(0.0))), 0.75, 0.0, "atan2_pu -y axis", radii[i]);
        /* Diagonals. */
        expect_close(qd(ctl_atan2_pu(r, r)), 0.125, ATAN2_TOL_TURN, "atan2_pu Q1 diag", radii[i]);
        expect_close(qd(ctl_atan2_pu(r, m)), 0.375, ATAN2_TOL_TURN, "atan2_pu Q2 diag", radii[i]);
        expect_close(qd(ctl_atan2_pu(m, m)), 0.625, ATAN2_TOL_TURN, "atan2_pu Q3 diag", radii[i]);
        expect_close(qd(ctl_atan2_pu(m, r)), 0.875, ATAN2_TOL_TURN, "atan2_pu Q4 diag", radii[i]);
        /* One point inside each quadrant, both octants: atan2(1, 2) = 0.0737918 turn. */
        expect_close(qd(ctl_atan2_pu(r, ctl_mul_int(r, 2))), 0.07379180882521663, ATAN2_TOL_TURN,
                     "atan2_pu Q1", radii[i]);
        expect_close(qd(ctl_atan2_pu(ctl_mul_int(r, 2), r)), 0.25 - 0.07379180882521663,
                     ATAN2_TOL_TURN, "atan2_pu Q1 upper octant", radii[i]);
        expect_close(qd(ctl_atan2_pu(r, ctl_mul_int(m, 2))), 0.5 - 0.07379180882521663,
                     ATAN2_TOL_TURN, "atan2_pu Q2", radii[i]);
        expect_close(qd(ctl_atan2_pu(m, ctl_mul_int(m, 2))), 0.5 + 0.07379180882521663,
                     ATAN2_TOL_TURN, "atan2_pu Q3", radii[i]);
        expect_close(qd(ctl_atan2_pu(m, ctl_mul_int(r, 2))), 1.0 - 0.07379180882521663,
                     ATAN2_TOL_TURN, "atan2_pu Q4", radii[i]);
    }
#if !CTL_MATH_FLOAT
    /* Extreme raw values (abs saturates on INT32_MIN). */
    expect_close(qd(ctl_atan2_pu(0, INT32_MIN)), 0.5, 0.0, "atan2_pu(0, MIN)", 0.0);
    expect_close(qd(ctl_atan2_pu(INT32_MIN, 0)), 0.75, 0.0, "atan2_pu(MIN, 0)", 0.0);
    expect_close(qd(ctl_atan2_pu(INT32_MIN, INT32_MIN)), 0.625, ATAN2_TOL_TURN,
                 "atan2_pu(MIN, MIN)", 0.0);
    expect_close(qd(ctl_atan2_pu(INT32_MAX, INT32_MIN)), 0.375, ATAN2_TOL_TURN,
                 "atan2_pu(MAX, MIN)", 0.0);
    expect_close(qd(ctl_atan2_pu(1, 1)), 0.125, ATAN2_TOL_TURN, "atan2_pu(LSB, LSB)", 0.0);
#endif
}

static void test_atan2_sweep(void **state)
{
    static const double radii[] = {1e-4, 0.01, 0.3, 1.0, 5.0, 90.0};
    double max_err = 0.0;
    double worst = 0.0;
    int32_t r;
    int32_t i;
    (void)state;
    for (r = 0; r < 6; r++) {
        for (i = 0; i < 100000; i++) {
            const double th = TWO_PI * (double)i / 100000.0;
            check_atan2(dq(radii[r] * sin(th)), dq(radii[r] * cos(th)), &max_err, &worst);
        }
    }
    for (i = 0; i < 200000; i++) {
        check_atan2(dq(rng_range(-127.0, 127.0)), dq(rng_range(-127.0, 127.0)), &max_err, &worst);
    }
    print_message("ctl_atan2_pu: max err %.3g turn (%.3g deg) near %.6g turn\n", max_err,
                  max_err * 360.0, worst);
}

/* --------------------------------------------------------- wrap / sector */

static void test_wrap_turn(void **state)
{
    int32_t i;
    (void)state;
    expect_close(qd(ctl_wrap_turn(CTL_Q(1.25))), 0.25, 0.0, "wrap", 1.25);
    expect_close(qd(ctl_wrap_turn(CTL_Q(-0.25))), 0.75, 0.0, "wrap", -0.25);
    expect_close(qd(ctl_wrap_turn(CTL_Q(-3.0))), 0.0, 0.0, "wrap", -3.0);
    expect_close(qd(ctl_wrap_turn(CTL_Q(1.0))), 0.0, 0.0, "wrap", 1.0);
    expect_close(qd(ctl_wrap_turn(CTL_Q(0.0))), 0.0, 0.0, "wrap", 0.0);
    expect_close(qd(ctl_wrap_turn(CTL_Q(-2.625))), 0.375, 0.0, "wrap", -2.625);
    expect_close(qd(ctl_wrap_turn(CTL_Q(100.5))), 0.5, 0.0, "wrap", 100.5);
#if CTL_MATH_FLOAT
    /* A tiny negative angle rounds to 1.0 after +1 and must come back as 0. */
    expect_close(qd(ctl_wrap_turn(-1.0e-9f)), 0.0, 1e-8, "wrap", -1e-9);
    expect_close(qd(ctl_wrap_turn(NAN)), 0.0, 0.0, "wrap", 0.0);
#else
    expect_i32(ctl_wrap_turn(INT32_MIN), 0, "wrap MIN");
    expect_i32(ctl_wrap_turn(INT32_MAX), CTL_Q_ONE - 1, "wrap MAX");
    expect_i32(ctl_wrap_turn(-1), CTL_Q_ONE - 1, "wrap -LSB");
#endif
    /* Sweep: result in [0, 1) and differs from the input by a whole number of turns. */
    for (i = 0; i < 200000; i++) {
        const ctl_q a = dq(rng_range(-127.9, 127.9));
        const double w = qd(ctl_wrap_turn(a));
        const double d = w - qd(a);
        /* fixed: exact; float: w = x + whole turns rounds to the float grid near w. */
        if (!(w >= 0.0 && w < 1.0 && fabs(d - floor(d + 0.5)) <= (CTL_MATH_FLOAT ? 6e-8 : 0.0))) {
            print_error("wrap(%.10g) = %.10g\n", qd(a), w);
            fail();
        }
    }
}

static void test_turn_sector(void **state)
{
    int16_t n;
    (void)state;
    for (n = 1; n <= 64; n++) {
        int16_t k;
        for (k = 0; k < n; k++) {
            const double b = (double)k / (double)n;
            const int16_t below = (int16_t)((k + n - 1) % n);
            int32_t m;
            /* 1e-6 turn either side of the boundary k/n, also 1..3 turns away (negative
             * angles wrap). */
            for (m = -3; m <= 3; m++) {
                const double base = b + (double)m;
                assert_int_equal(ctl_turn_sector(dq(base + 1e-6), n), k);
                assert_int_equal(ctl_turn_sector(dq(base - 1e-6), n), below);
            }
            /* Middle of the sector. */
            assert_int_equal(ctl_turn_sector(dq(b + 0.5 / (double)n), n), k);
            assert_int_equal(ctl_turn_sector(dq(b + 0.5 / (double)n - 5.0), n), k);
#if CTL_MATH_FLOAT
            if (k > 0) {
                /* Floats around the boundary, from 3 ulps below the float nearest k/n to 3
                 * above it. Expected floor(w n) of the exact product: an angle at or above
                 * k/n is sector k, an angle below k/n by more than one rounding of w n is
                 * k - 1. Within one rounding below k/n the float product w * n may round up
                 * to k: that 1-ulp band is the only place either answer is accepted. */
                float w = (float)k / (float)n;
                int32_t u;
                for (u = 0; u < 3; u++) {
                    w = nextafterf(w, 0.0f);
                }
                for (u = 0; u < 7; u++) {
                    const double exact = (double)w * (double)n;
                    const int16_t got = ctl_turn_sector(w, n);
                    if (exact >= (double)k) {
                        assert_int_equal(got, k);
                    } else if (exact < (double)k * (1.0 - 1.0 / 8388608.0)) {
                        assert_int_equal(got, k - 1);
                    } else {
                        assert_true(got == k || got == k - 1);
                    }
                    w = nextafterf(w, 1.0f);
                }
            }
#else
            {
                /* Exact boundary: the smallest Q24 angle >= k/n is sector k, one LSB less is
                 * sector k - 1. */
                const int32_t q = (int32_t)(((int64_t)k * 16777216 + n - 1) / n);
                assert_int_equal(ctl_turn_sector(q, n), k);
                assert_int_equal(ctl_turn_sector(q - 1, n), below);
                assert_int_equal(ctl_turn_sector(q - 16777216, n), k);
                assert_int_equal(ctl_turn_sector(q - 1 - 3 * 16777216, n), below);
            }
#endif
        }
    }
    /* Powers of two: k/n exactly representable in both arithmetics. */
    for (n = 1; n <= 64; n = (int16_t)(n * 2)) {
        int16_t k;
        for (k = 0; k < n; k++) {
            assert_int_equal(ctl_turn_sector(dq((double)k / (double)n), n), k);
            assert_int_equal(ctl_turn_sector(dq((double)k / (double)n - 2.0), n), k);
        }
    }
    /* Twelve alpha-beta sectors: 0.99 turn is the last one, -0.01 turn too. */
    assert_int_equal(ctl_turn_sector(CTL_Q(0.99), 12), 11);
    assert_int_equal(ctl_turn_sector(CTL_Q(-0.01), 12), 11);
    assert_int_equal(ctl_turn_sector(CTL_Q(-1.0), 12), 0);
#if !CTL_MATH_FLOAT
    assert_int_equal(ctl_turn_sector(INT32_MAX, 64), 63);
    assert_int_equal(ctl_turn_sector(INT32_MIN, 64), 0);
    assert_int_equal(ctl_turn_sector(-1, 24), 23);
#endif
}

/* ctl_sector24 by comparisons agrees with the angle: sector k holds [15k, 15k + 15) deg.
 * Sampled on circles of several radii, skipping a 1e-4 deg band around each boundary. */
static void test_sector24(void **state)
{
    static const double radii[4] = {0.002, 0.05, 0.5, 20.0};
    int32_t n;
    int16_t r;
    (void)state;
    assert_int_equal(ctl_sector24(CTL_Q(0.0), CTL_Q(0.0)), 0);
    assert_int_equal(ctl_sector24(CTL_Q(0.0), CTL_Q(1.0)), 0);
    assert_int_equal(ctl_sector24(CTL_Q(1.0), CTL_Q(0.0)), 6);
    assert_int_equal(ctl_sector24(CTL_Q(0.0), CTL_Q(-1.0)), 12);
    assert_int_equal(ctl_sector24(CTL_Q(-1.0), CTL_Q(0.0)), 18);
    for (r = 0; r < 4; r++) {
        for (n = 0; n < 36000; n++) {
            const double deg = ((double)n + 0.5) / 100.0;
            const double rel = fmod(deg, 15.0);
            const double rad = deg * 3.14159265358979323846 / 180.0;
            if (rel < 1e-4 || rel > 15.0 - 1e-4) {
                continue;
            }
            assert_int_equal(ctl_sector24(ctl_from_float((float)(radii[r] * sin(rad))),
                                          ctl_from_float((float)(radii[r] * cos(rad)))),
                             (int16_t)(deg / 15.0));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_add_sub),       cmocka_unit_test(test_mul),
        cmocka_unit_test(test_fused_mul),     cmocka_unit_test(test_mul_int),
        cmocka_unit_test(test_div),           cmocka_unit_test(test_abs),
        cmocka_unit_test(test_from_float),    cmocka_unit_test(test_to_qn),
        cmocka_unit_test(test_from_turn_u32), cmocka_unit_test(test_mul_q16),
        cmocka_unit_test(test_sqrt_exact),    cmocka_unit_test(test_sqrt_sweep),
        cmocka_unit_test(test_sqrtf),         cmocka_unit_test(test_sin_cos),
        cmocka_unit_test(test_atan2_axes),    cmocka_unit_test(test_atan2_sweep),
        cmocka_unit_test(test_wrap_turn),     cmocka_unit_test(test_turn_sector),
        cmocka_unit_test(test_sector24),
    };
    print_message("arithmetic: %s\n", CTL_MATH_FLOAT ? "float" : "Q24 fixed point");
    return cmocka_run_group_tests(tests, NULL, NULL);
}
