/* Stage profiler (firmware/app/measure/profile.c) against a scripted cycle counter, and the control
 * core's stage hook driving it through a real control step. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl.h"
#include "hal_cycles.h"
#include "measure/profile.h"
#include "test_rng.h"

/* Each reading advances the counter by `step`, plus `extra` once when armed. */
static uint32_t counter;
static uint32_t step = 7u;
static uint32_t extra;
void hal_cycles_init(void) { counter = 0u; }
uint32_t hal_cycles_now(void)
{
    counter += step + extra;
    extra = 0u;
    return counter;
}
uint32_t hal_cycles_per_second(void) { return 150000000u; }

static void test_read_cost_is_measured_and_subtracted(void **state)
{
    (void)state;
    step = 7u;
    prof_init(15000u, 150000000u);
    assert_int_equal(drive_profile.read_cost, 7u);
    assert_int_equal(drive_profile.cycles_per_us, 150u);
    prof_begin(900u);
    extra = 100u; /* the stage's work shows up at the next reading */
    prof_mark(PROF_ADC);
    assert_int_equal(drive_profile.stage[PROF_ADC].last, 100u);
    prof_mark(PROF_TRANSFORMS); /* nothing in between: zero after subtraction */
    assert_int_equal(drive_profile.stage[PROF_TRANSFORMS].last, 0u);
    extra = 2000u;
    prof_end();
    /* TOTAL spans begin..end: the work (100 + 2000) and the readings in between */
    assert_true(drive_profile.stage[PROF_TOTAL].last >= 2100u);
    assert_true(drive_profile.stage[PROF_TOTAL].last <= 2100u + 6u * 7u);
    assert_int_equal(drive_profile.stage[PROF_LATENCY].last, 900u);
    /* load = (latency + total) / period */
    assert_int_equal(drive_profile.load_permille_last,
                     (uint16_t)((900u + drive_profile.stage[PROF_TOTAL].last) * 1000u / 15000u));
}

static void test_min_max_mean(void **state)
{
    static const uint32_t work[6] = {100u, 300u, 200u, 200u, 50u, 400u};
    int16_t k;
    (void)state;
    step = 7u;
    prof_init(15000u, 150000000u);
    for (k = 0; k < 6; k++) {
        prof_begin(0u);
        extra = work[k];
        prof_mark(PROF_SEARCH);
        prof_end();
    }
    assert_int_equal(drive_profile.stage[PROF_SEARCH].min, 50u);
    assert_int_equal(drive_profile.stage[PROF_SEARCH].max, 400u);
    assert_int_equal(drive_profile.stage[PROF_SEARCH].last, 400u);
    assert_int_equal(drive_profile.stage[PROF_SEARCH].count, 6u);
    /* exponential mean from 100 moving 1/64 toward each new value */
    assert_in_range(prof_mean(&drive_profile.stage[PROF_SEARCH]), 100u, 115u);
    prof_count_overrun();
    assert_int_equal(drive_profile.overruns, 1u);
    assert_true(drive_profile.load_permille_max >= drive_profile.load_permille_last);
}

/* The core reports its four stages once per step, in order, through the hook. */
static int16_t seen[8];
static int16_t seen_count;
static void record_stage(int16_t stage)
{
    if (seen_count < 8) {
        seen[seen_count] = stage;
    }
    seen_count++;
    prof_ctl_stage(stage);
}

static void test_core_stage_hook(void **state)
{
    static const ctl_controller_t controllers[3] = {CTL_CONTROLLER_DDC, CTL_CONTROLLER_MPTC49,
                                                    CTL_CONTROLLER_MPTC13};
    int16_t which;
    (void)state;
    for (which = 0; which < 3; which++) {
        ctl_params_t p;
        ctl_t c;
        ctl_meas_t m = {
            {CTL_Q(0.1), CTL_Q(-0.05), CTL_Q(-0.05), CTL_Q(0.08), CTL_Q(-0.1), CTL_Q(0.02)},
            CTL_Q(1.0),
            CTL_Q(0.3),
            CTL_Q(0.4)};
        ctl_cmd_t cmd;
        ctl_params_default(&p);
        p.controller = controllers[which];
        assert_true(ctl_init(&c, &p));
        ctl_set_stage_hook(&c, record_stage);
        prof_init(15000u, 150000000u);
        seen_count = 0;
        prof_begin(0u);
        ctl_step(&c, &m, &cmd);
        prof_end();
        assert_int_equal(seen_count, 4);
        assert_int_equal(seen[0], CTL_STAGE_TRANSFORMS);
        assert_int_equal(seen[1], CTL_STAGE_PREDICT);
        assert_int_equal(seen[2], CTL_STAGE_TABLE);
        assert_int_equal(seen[3], CTL_STAGE_SEARCH);
        assert_int_equal(drive_profile.stage[PROF_TRANSFORMS].count, 1u);
        assert_int_equal(drive_profile.stage[PROF_SEARCH].count, 1u);
        ctl_set_stage_hook(&c, 0);
        seen_count = 0;
        ctl_step(&c, &m, &cmd);
        assert_int_equal(seen_count, 0);
    }
}

/* The ISR's statistics use 32-bit arithmetic only (no 64-bit run-time library on the C28x):
 * the running mean equals the 64-bit form it replaced for every sample below 2^24 cycles, and
 * the load in permille is floor(busy * 1000 / period) while busy < 2^16 cycles, and within
 * busy / 2^16 + 1 below it beyond, saturated at 65535. Busy is the latency alone here (the
 * counter does not move: TOTAL is 0). */
static uint32_t lcg = 12345u;

static void test_32bit_mean_and_load(void **state)
{
    const uint32_t period = 15000u;
    uint32_t ref_mean = 0u;
    long k;
    (void)state;
    step = 0u;
    prof_init(period, 150000000u);
    prof_begin(
        0x7FFFFFFFu); /* a first sample beyond 2^24 cycles: the mean is clamped, not wrapped */
    assert_int_equal(drive_profile.stage[PROF_LATENCY].mean_x256, 0x00FFFFFFu << 8);
    prof_init(period, 150000000u);
    for (k = 0; k < 200000; k++) {
        const uint32_t r = test_lcg_next(&lcg);
        const uint32_t busy = (k < 100000) ? (r >> 16) : (r >> (8u + (r & 7u)));
        const uint32_t exact = (uint32_t)(((uint64_t)busy * 1000u) / period);
        uint32_t got;
        prof_begin(busy);
        prof_end();
        if (k == 0) {
            ref_mean = busy << 8;
        } else {
            ref_mean =
                (uint32_t)((int64_t)ref_mean + (((int64_t)busy * 256 - (int64_t)ref_mean) / 64));
        }
        assert_int_equal(drive_profile.stage[PROF_LATENCY].mean_x256, ref_mean);
        got = drive_profile.load_permille_last;
        if (busy < 65536u) {
            assert_int_equal(got, exact);
        } else if (exact >= 65535u) {
            assert_int_equal(got, 65535u);
        } else {
            assert_true(got <= exact && exact - got <= (busy >> 16) + 1u);
        }
    }
    step = 7u;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_cost_is_measured_and_subtracted),
        cmocka_unit_test(test_min_max_mean),
        cmocka_unit_test(test_core_stage_hook),
        cmocka_unit_test(test_32bit_mean_and_load),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
