/*
 * The capture buffer (firmware/app/capture/capture.c) on synthetic signals: the immediate trigger
 * records from the next period; a rising or falling level trigger keeps the pre-trigger share
 * before the crossing and the rest after it, samples in order; decimation keeps every Nth
 * period; the fault trigger freezes the last samples before a trip (post-mortem), also when
 * the trip comes before the pre-trigger share filled; bad setups are refused with their
 * reasons and a running capture cannot be re-armed until stopped.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "capture/capture.h"

static capture_t cap;

static capture_setup_t setup_of(capture_trigger_t trigger, uint16_t length, uint16_t pre)
{
    capture_setup_t s;
    s.n_channels = 2;
    s.signal[0] = CAPTURE_I_A;
    s.signal[1] = CAPTURE_TORQUE;
    s.signal[2] = s.signal[3] = 0;
    s.length = length;
    s.decimation = 1u;
    s.trigger = trigger;
    s.trigger_signal = CAPTURE_I_A;
    s.trigger_level = 100;
    s.pre_percent = pre;
    return s;
}

/* Period p: channel 0 is p (a ramp, the trigger signal), channel 1 is -p. */
static void run_periods(uint32_t from, uint32_t to, uint32_t fault_at)
{
    uint32_t p;
    for (p = from; p < to; p++) {
        int16_t v[CAPTURE_CHANNELS] = {(int16_t)p, (int16_t) - (int32_t)p, 0, 0};
        if (capture_due(&cap)) {
            capture_sample(&cap, v, (int16_t)p, p, p >= fault_at);
        }
    }
}

static void test_immediate(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_IMMEDIATE, 50u, 40u);
    uint16_t j;
    (void)state;
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    run_periods(10u, 100u, 0xFFFFFFFFu);
    assert_int_equal(cap.state, CAPTURE_DONE);
    assert_int_equal(cap.count, 50);
    assert_int_equal(cap.trigger_index, 0); /* immediate: nothing before */
    assert_int_equal(cap.first_period, 10u);
    for (j = 0; j < 50u; j++) {
        assert_int_equal(capture_read(&cap, 0, j), 10 + j);
        assert_int_equal(capture_read(&cap, 1, j), -(10 + j));
    }
}

static void test_rising_with_pre_trigger(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_RISING, 100u, 25u);
    uint16_t j;
    (void)state;
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    run_periods(0u, 1000u, 0xFFFFFFFFu); /* the ramp crosses 100 at period 100 */
    assert_int_equal(cap.state, CAPTURE_DONE);
    assert_int_equal(cap.count, 100);
    assert_int_equal(cap.trigger_index, 25);
    assert_int_equal(capture_read(&cap, 0, 25), 100); /* the trigger sample */
    assert_int_equal(cap.first_period, 75u);
    for (j = 0; j < 100u; j++) {
        assert_int_equal(capture_read(&cap, 0, j), 75 + j);
    }
}

static void test_falling_never_met_keeps_recording(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_FALLING, 64u, 50u);
    (void)state;
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    run_periods(0u, 500u, 0xFFFFFFFFu); /* a rising ramp never falls through 100 */
    assert_int_equal(cap.state, CAPTURE_ARMED);
    assert_int_equal(capture_read(&cap, 0, 63), 499); /* the latest samples so far */
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_ERR_BUSY);
    capture_stop(&cap);
    assert_int_equal(cap.state, CAPTURE_IDLE);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
}

static void test_decimation(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_IMMEDIATE, 20u, 0u);
    uint16_t j;
    (void)state;
    s.decimation = 7u;
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    run_periods(0u, 1000u, 0xFFFFFFFFu);
    assert_int_equal(cap.state, CAPTURE_DONE);
    for (j = 0; j < 20u; j++) {
        assert_int_equal(capture_read(&cap, 0, j), 7 * j);
    }
}

/* Post-mortem: recording until the trip, the last 90 % before it kept. */
static void test_fault_post_mortem(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_FAULT, 200u, 90u);
    (void)state;
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    run_periods(0u, 5000u, 3000u);
    assert_int_equal(cap.state, CAPTURE_DONE);
    assert_int_equal(cap.trigger_index, 180);
    assert_int_equal(capture_read(&cap, 0, 180), 3000);
    assert_int_equal(capture_read(&cap, 0, 0), 2820);
    assert_int_equal(capture_read(&cap, 0, 199), 3019);
    /* a trip before the pre-trigger share filled: never missed, fewer samples before it */
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    run_periods(0u, 1000u, 50u);
    assert_int_equal(cap.state, CAPTURE_DONE);
    assert_int_equal(cap.trigger_index, 50);
    assert_int_equal(capture_read(&cap, 0, 50), 50);
    assert_int_equal(cap.count, 70);
}

/* Armed while the drive is in FAULT: no record of that fault; the next trip triggers. */
static void test_fault_trigger_needs_a_new_trip(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_FAULT, 100u, 50u);
    uint32_t p;
    (void)state;
    capture_init(&cap);
    assert_int_equal(capture_arm(&cap, &s), CAPTURE_OK);
    for (p = 0; p < 3000u; p++) { /* in FAULT until 1000, healthy until 2000, then a trip */
        int16_t v[CAPTURE_CHANNELS] = {(int16_t)p, 0, 0, 0};
        if (capture_due(&cap)) {
            capture_sample(&cap, v, 0, p, p < 1000u || p >= 2000u);
        }
        if (p == 1500u) {
            assert_int_equal(cap.state, CAPTURE_ARMED);
        }
    }
    assert_int_equal(cap.state, CAPTURE_DONE);
    assert_int_equal(capture_read(&cap, 0, cap.trigger_index), 2000);
}

static void test_bad_setups(void **state)
{
    capture_setup_t s = setup_of(CAPTURE_TRIGGER_IMMEDIATE, 100u, 10u);
    capture_setup_t b;
    (void)state;
    capture_init(&cap);
    b = s;
    b.signal[1] = CAPTURE_SIGNAL_COUNT;
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_SIGNAL);
    b = s;
    b.n_channels = 0;
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_SIGNAL);
    b = s;
    b.n_channels = 5;
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_SIGNAL);
    b = s;
    b.decimation = 0u;
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_SETTING);
    b = s;
    b.pre_percent = 101u;
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_SETTING);
    b = s;
    b.trigger = CAPTURE_TRIGGER_MODES;
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_SETTING);
    b = s;
    b.length = CAPTURE_BUFFER_WORDS; /* x 2 channels */
    assert_int_equal(capture_arm(&cap, &b), CAPTURE_ERR_NO_ROOM);
    assert_int_equal(cap.state, CAPTURE_IDLE); /* nothing armed by a refused setup */
    assert_int_equal(capture_read(&cap, 0, 0), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_immediate),
        cmocka_unit_test(test_rising_with_pre_trigger),
        cmocka_unit_test(test_falling_never_met_keeps_recording),
        cmocka_unit_test(test_decimation),
        cmocka_unit_test(test_fault_post_mortem),
        cmocka_unit_test(test_fault_trigger_needs_a_new_trip),
        cmocka_unit_test(test_bad_setups),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
