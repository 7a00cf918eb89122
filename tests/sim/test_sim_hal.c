/* Simulator HAL: board scaling of the ADC counts, shadow-loaded duties,
 * force-off latch and trip input, fresh-sample flag. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "hal_board.h"
#include "hal_cycles.h"
#include "hal_sim.h"

static void test_adc_scaling_and_clamping(void **state)
{
    (void)state;
    assert_int_equal(hal_sim_current_to_counts(0.0, HAL_BOARD_CURRENT_FULL_SPAN_A), 2048);
    /* 9.765625 mA per count */
    assert_int_equal(hal_sim_current_to_counts(1.0, HAL_BOARD_CURRENT_FULL_SPAN_A), 2048 + 102);
    assert_int_equal(hal_sim_current_to_counts(-1.0, HAL_BOARD_CURRENT_FULL_SPAN_A), 2048 - 102);
    assert_int_equal(hal_sim_current_to_counts(19.99, HAL_BOARD_CURRENT_FULL_SPAN_A), 4095);
    assert_int_equal(hal_sim_current_to_counts(25.0, HAL_BOARD_CURRENT_FULL_SPAN_A), 4095);
    assert_int_equal(hal_sim_current_to_counts(-25.0, HAL_BOARD_CURRENT_FULL_SPAN_A), 0);
    assert_int_equal(hal_sim_current_to_counts(25.0, 100.0), 2048 + 1024); /* a +-50 A sensor */
    assert_int_equal(hal_sim_current_to_counts(60.0, 100.0), 4095);
    assert_int_equal(hal_sim_vdc_to_counts(540.0), 2765); /* 540 / 0.1953125 = 2764.8 */
    assert_int_equal(hal_sim_vdc_to_counts(1000.0), 4095);
    assert_int_equal(hal_sim_vdc_to_counts(-5.0), 0);
    assert_int_equal(hal_sim_current_to_counts(1e300, HAL_BOARD_CURRENT_FULL_SPAN_A), 4095);
}

static void test_adc_fresh_flag(void **state)
{
    hal_adc_sample_t in = {{1, 2, 3, 4, 5, 6}, 7}, out;
    (void)state;
    hal_sim_reset();
    assert_true(hal_adc_init());
    assert_false(hal_adc_read(&out));
    hal_sim_post_adc(&in);
    assert_true(hal_adc_read(&out));
    assert_int_equal(out.phase[5], 6);
    assert_int_equal(out.vdc, 7);
    assert_false(hal_adc_read(&out)); /* consumed */
}

static void test_pwm_shadow_and_force_off(void **state)
{
    const uint16_t d[6] = {0, 16384, 32768, 40000, 1, 32767};
    (void)state;
    hal_sim_reset();
    assert_false(hal_pwm_init(0u, 2000u));
    assert_true(hal_pwm_init(10000u, 2000u));
    assert_true(hal_pwm_is_off()); /* outputs forced off after init */
    hal_pwm_write(d);
    assert_true(hal_sim_duty_fraction(1) == 0.5);
    assert_true(hal_sim_duty_fraction(2) == 1.0);
    assert_true(hal_sim_duty_fraction(3) == 1.0); /* clamped */
    assert_true(hal_sim_duty_fraction(-1) == 0.0 && hal_sim_duty_fraction(6) == 0.0);
    hal_pwm_enable();
    assert_false(hal_pwm_is_off());
    hal_pwm_force_off();
    assert_true(hal_pwm_is_off());
    hal_pwm_enable();
    assert_false(hal_pwm_is_off());
    /* a hardware trip keeps the outputs off until it clears */
    hal_sim_bus.hw_trip = true;
    hal_sim_bus.forced_off = true;
    assert_true(hal_pwm_hw_trip_seen());
    hal_pwm_enable();
    assert_true(hal_pwm_is_off());
}

/* An isolated leg reads 0 % (its switches are off) through writes and enables until restored. */
static void test_pwm_isolated_leg(void **state)
{
    const uint16_t d[HAL_PWM_LEGS] = {16384u, 16384u, 16384u, 16384u, 16384u, 16384u};
    (void)state;
    hal_sim_reset();
    assert_true(hal_pwm_init(10000u, 2000u));
    assert_false(hal_pwm_isolate_leg(6));
    assert_true(hal_pwm_isolate_leg(3));
    hal_pwm_write(d);
    hal_pwm_enable();
    assert_false(hal_pwm_is_off());
    assert_int_equal(hal_pwm_isolated_legs(), 1u << 3);
    assert_true(hal_sim_duty_fraction(3) == 0.0);
    assert_true(hal_sim_duty_fraction(2) == 0.5);
    hal_pwm_restore_legs();
    assert_true(hal_sim_duty_fraction(3) == 0.5);
}

static void test_encoder_and_cycles(void **state)
{
    hal_encoder_sample_t e = {0x40000000u, 65536, true, 12345, true}, out;
    uint32_t c0, c1;
    (void)state;
    hal_sim_reset();
    assert_false(hal_encoder_init(0u, 3u, 0u));
    assert_true(hal_encoder_init(HAL_BOARD_ENCODER_LINES, 3u, 0u));
    hal_sim_post_encoder(&e);
    hal_encoder_read(&out);
    assert_true(out.elec_angle == 0x40000000u && out.mech_speed_q16 == 65536 && out.healthy);
    assert_true(out.position == 12345 && out.index_seen);
    assert_int_equal(hal_encoder_counts_per_turn(), 4u * HAL_BOARD_ENCODER_LINES);
    assert_int_equal(hal_encoder_offset(), 0u);
    hal_encoder_set_offset(0x12345678u);
    assert_int_equal(hal_encoder_offset(), 0x12345678u);
    assert_int_equal(hal_sim_bus.encoder_elec_offset, 0x12345678u);
    /* re-homing: unhealthy, whatever the plant posts, until the plant reports the index */
    hal_encoder_rehome();
    hal_sim_post_encoder(&e);
    hal_encoder_read(&out);
    assert_false(out.healthy || out.index_seen);
    hal_sim_post_encoder_index();
    hal_encoder_read(&out);
    assert_true(out.healthy);
    hal_cycles_init();
    /* simulated time: no time passes between readings, a period per advance */
    c0 = hal_cycles_now();
    assert_int_equal(hal_cycles_now(), c0);
    hal_sim_clock_advance(100000u);
    assert_int_equal((uint32_t)(hal_cycles_now() - c0), 100000u);
    hal_sim_reset();
    assert_int_equal(hal_cycles_now(), 0u);
    /* the host's clock (the virtual board): moves on its own, in nanoseconds */
    hal_sim_use_host_clock(true);
    c0 = hal_cycles_now();
    hal_sim_clock_advance(1000000000u);
    do {
        c1 = hal_cycles_now();
    } while (c1 == c0);
    assert_true((uint32_t)(c1 - c0) < hal_cycles_per_second() / 10u);
    hal_sim_use_host_clock(false);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_adc_scaling_and_clamping), cmocka_unit_test(test_adc_fresh_flag),
        cmocka_unit_test(test_pwm_shadow_and_force_off), cmocka_unit_test(test_pwm_isolated_leg),
        cmocka_unit_test(test_encoder_and_cycles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
