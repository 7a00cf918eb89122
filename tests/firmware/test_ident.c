/*
 * The identification's building blocks (firmware/app/commission/ident_excite.c, ident_stats.c):
 * block statistics keep their precision over many samples and give the standard error; the VSD and
 * its inverse are one another's inverse; the modulator's duties; the commanded angle's ramp;
 * the regulator's hold and its conditional integration at the voltage limit.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "commission/ident_excite.h"
#include "commission/ident_stats.h"

/* Half a million samples of a large mean with a small alternating part: the block mean keeps
 * the small part (a float running sum would have lost it), and the spread of the blocks is
 * the standard error of their mean. */
static void test_blocks_keep_precision(void **state)
{
    ident_blocks_t b;
    int32_t k;
    double sum = 0.0, sum2 = 0.0;
    (void)state;
    ident_blocks_init(&b, 500);
    for (k = 0; k < 500000; k++) {
        ident_blocks_add(&b, 1000.0f + ((k & 1) ? 0.25f : -0.25f) + 0.001f * (float)(k / 500 % 7));
    }
    assert_int_equal(b.blocks, 1000);
    assert_true(fabs((double)ident_blocks_mean(&b) - (1000.0 + 0.003)) < 2e-4);
    for (k = 0; k < 1000; k++) { /* the block means: 1000 + 0.001 (k mod 7) */
        const double m = 0.001 * (double)(k % 7);
        sum += m;
        sum2 += m * m;
    }
    {
        const double var = (sum2 - sum * sum / 1000.0) / 999.0;
        const double se = sqrt(var / 1000.0);
        assert_true(fabs((double)ident_blocks_sigma(&b) - se) < 0.05 * se + 1e-6);
    }
    ident_blocks_init(&b, 10);
    assert_true(ident_blocks_sigma(&b) == 0.0f);
    ident_blocks_add_block(&b, 3.0f);
    assert_true(ident_blocks_mean(&b) == 3.0f && ident_blocks_sigma(&b) == 0.0f);
}

static void test_vsd_round_trip(void **state)
{
    const float v[4] = {1.5f, -0.7f, 0.3f, 0.9f};
    float phase[IDENT_PHASES], back[4];
    int16_t k;
    (void)state;
    for (k = 0; k < IDENT_PHASES; k++) {
        phase[k] = ident_vsd_phase(v, k);
    }
    /* each set sums to zero (isolated neutrals) */
    assert_true(fabsf(phase[0] + phase[1] + phase[2]) < 1e-5f);
    assert_true(fabsf(phase[3] + phase[4] + phase[5]) < 1e-5f);
    ident_vsd(phase, back);
    for (k = 0; k < 4; k++) {
        assert_true(fabsf(back[k] - v[k]) < 1e-5f);
    }
}

static void test_modulator(void **state)
{
    const float u[4] = {54.0f, 0.0f, 0.0f, 0.0f}; /* phase A +54 V on 540 V: duty 0.6 */
    const float big[4] = {600.0f, 0.0f, 0.0f, 0.0f};
    uint16_t duty[IDENT_PHASES];
    (void)state;
    ident_modulate(u, 540.0f, duty);
    assert_int_equal(duty[0], 19661u); /* 0.6 x 32768 */
    assert_int_equal(duty[1], 14746u); /* -27 V: 0.45 */
    assert_int_equal(duty[5], 16384u); /* F has no alpha share */
    ident_modulate(big, 540.0f, duty);
    assert_int_equal(duty[0], HAL_PWM_DUTY_ONE); /* clamped */
    assert_int_equal(duty[1], 0u);
    ident_modulate(u, 0.0f, duty); /* no DC link: half duty everywhere, no division by zero */
    assert_int_equal(duty[0], 16384u);
}

static void test_angle_ramp(void **state)
{
    ident_traj_t t;
    int32_t k;
    (void)state;
    ident_traj_reset(&t, -0.25f);
    assert_true(fabsf(t.angle - 0.75f) < 1e-6f);
    t.target = 1.0f;
    t.accel = 4.0f;
    for (k = 0; k < 2500; k++) { /* 0.25 s at 10 kHz: up to speed */
        ident_traj_step(&t, 1.0e-4f);
    }
    assert_true(fabsf(t.speed - 1.0f) < 1e-4f);
    assert_true(fabsf(t.travel - 0.125f) < 1e-3f); /* half of speed x time while ramping */
    for (k = 0; k < 10000; k++) {
        ident_traj_step(&t, 1.0e-4f);
    }
    assert_true(fabsf(t.travel - 1.125f) < 2e-3f);
    assert_true(t.angle >= 0.0f && t.angle < 1.0f);
    assert_true(fabsf(ident_wrap_half(0.9f) + 0.1f) < 1e-6f);
    assert_true(fabsf(ident_wrap_half(-0.7f) - 0.3f) < 1e-6f);
}

static void test_regulator_hold_and_limit(void **state)
{
    ident_reg_t r;
    const float ref[2] = {10.0f, 0.0f}, zero[2] = {0.0f, 0.0f};
    int16_t k;
    (void)state;
    ident_reg_init(&r, 0.045f, 0.01f, 942.0f, 1.0e-4f, 20.0f, 5.0f);
    for (k = 0; k < 100; k++) { /* a current that never comes: the output stays at the limit */
        ident_reg_step(&r, 0.0f, 1.0f, ref, zero, zero, zero);
    }
    assert_true(r.saturated);
    assert_true(fabsf(r.u[0] - 20.0f) < 1e-3f);
    assert_true(r.d.integ < 20.0f); /* no wind-up beyond the limit */
    ident_reg_hold(&r, IDENT_HOLD_D, 3.0f);
    r.inject_dq[0] = 1.5f;
    ident_reg_step(&r, 0.0f, 1.0f, ref, zero, zero, zero);
    assert_true(fabsf(r.u[0] - 4.5f) < 1e-5f); /* held output plus the injection */
    r.hold = 0u;
    r.inject_dq[0] = 0.0f;
    ident_reg_step(&r, 0.0f, 1.0f, ref, ref, zero, zero); /* no error: the held value goes on */
    assert_true(fabsf(r.u[0] - 3.0f) < 1e-5f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blocks_keep_precision),
        cmocka_unit_test(test_vsd_round_trip),
        cmocka_unit_test(test_modulator),
        cmocka_unit_test(test_angle_ramp),
        cmocka_unit_test(test_regulator_hold_and_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
