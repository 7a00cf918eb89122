/* Drive state machine (firmware/app/drive/drive.c) against the mocked HAL and core. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "hal_board.h"

#include "ctl_pu.h"
#include "drive/drive.h"
#include "drive/drive_open_phase.h"
#include "drive_fixture.h"
#include "test_support.h"
#include "vsd_reference.h"

static drive_t d;

static int setup(void **state)
{
    (void)state;
    fixture_init(&d);
    return 0;
}

static void test_init_calibrates_with_pwm_off(void **state)
{
    (void)state;
    assert_int_equal(d.state, DRIVE_STATE_CALIBRATE);
    assert_true(mock_rec.force_off >= 1u);
    fixture_run_isr(&d, 10);
    assert_int_equal(d.state, DRIVE_STATE_CALIBRATE);
    assert_int_equal(mock_rec.enable, 0u);
    assert_int_equal(mock_rec.write, 0u);
}

static void test_calibration_averages_offsets(void **state)
{
    int n;
    int i;
    (void)state;
    /* phase i alternates around mid scale (2048) + 10 i - 30 by +-5 counts */
    for (n = 0; n < DRIVE_CALIBRATION_SAMPLES; n++) {
        for (i = 0; i < HAL_ADC_PHASES; i++) {
            mock_adc.phase[i] = (uint16_t)(MOCK_ADC_ZERO + 10 * i - 30 + ((n & 1) ? 5 : -5));
        }
        fixture_run_isr(&d, 1);
        if (n < DRIVE_CALIBRATION_SAMPLES - 1) {
            assert_int_equal(d.state, DRIVE_STATE_CALIBRATE);
        }
    }
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_true(d.calibrated);
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        assert_int_equal(d.offset_counts[i], MOCK_ADC_ZERO + 10 * i - 30);
    }
    assert_int_equal(mock_rec.enable, 0u); /* PWM stayed off */
}

static void test_offset_out_of_range_faults(void **state)
{
    (void)state;
    mock_adc.phase[4] = (uint16_t)(MOCK_ADC_ZERO + DRIVE_OFFSET_TOLERANCE_COUNTS + 1);
    fixture_calibrate(&d);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_ADC_OFFSET);
    assert_true(mock_rec.pwm_off);
    assert_false(d.calibrated);
    /* clearing restarts the calibration instead of going READY */
    mock_adc.phase[4] = MOCK_ADC_ZERO;
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_CALIBRATE);
    assert_int_equal(d.fault, DRIVE_FAULT_NONE);
    fixture_calibrate(&d);
    assert_int_equal(d.state, DRIVE_STATE_READY);
}

static void test_offset_low_side_faults(void **state)
{
    (void)state;
    mock_adc.phase[0] = (uint16_t)(MOCK_ADC_ZERO - DRIVE_OFFSET_TOLERANCE_COUNTS - 1);
    fixture_calibrate(&d);
    assert_int_equal(d.fault, DRIVE_FAULT_ADC_OFFSET);
}

static void test_run_refused_until_calibrated(void **state)
{
    (void)state;
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_CALIBRATE);
    assert_int_equal(d.run_refused, 1u);
    fixture_calibrate(&d);
    /* the early request was dropped, not deferred */
    assert_int_equal(d.state, DRIVE_STATE_READY);
    fixture_run_isr(&d, 5);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(mock_rec.enable, 0u);
    assert_int_equal(mock_rec.ctl_step, 0u);
}

static void test_run_and_stop(void **state)
{
    int i;
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    for (i = 0; i < CTL_PHASES; i++) {
        mock_cmd.leg_duty[i] = CTL_Q(0.5);
    }
    mock_cmd.leg_duty[5] = CTL_Q(1.0);
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_int_equal(mock_rec.enable, 1u);
    assert_int_equal(mock_rec.ctl_reset, 1u);
    assert_int_equal(mock_rec.ctl_step, 1u);
    assert_int_equal(mock_rec.duty[0], 16384u);
    assert_int_equal(mock_rec.duty[5], HAL_PWM_DUTY_ONE);
    fixture_run_isr(&d, 3);
    assert_int_equal(mock_rec.ctl_step, 4u);
    assert_int_equal(mock_rec.write, 4u);

    /* the core disabling its outputs switches everything off */
    mock_cmd.enable = false;
    fixture_run_isr(&d, 1);
    assert_true(mock_rec.pwm_off);
    mock_cmd.enable = true;

    drive_request_stop(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_true(mock_rec.pwm_off);
}

static void test_run_refused_without_encoder(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_encoder.healthy = false;
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(d.run_refused, 1u);
    assert_int_equal(mock_rec.enable, 0u);
}

static void test_fault_forces_off_and_latches(void **state)
{
    uint32_t off_before;
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    fixture_run_isr(&d, 2);
    assert_int_equal(d.state, DRIVE_STATE_RUN);

    off_before = mock_rec.force_off;
    mock_rec.hw_trip = true;
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_HW_TRIP);
    assert_true(mock_rec.force_off > off_before);
    assert_true(mock_rec.pwm_off);

    /* latched: trip gone, still FAULT; run refused; PWM kept off */
    mock_rec.hw_trip = false;
    drive_request_run(&d);
    fixture_run_isr(&d, 5);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_true(mock_rec.pwm_off);

    /* clear refused while the trip input is active */
    mock_rec.hw_trip = true;
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    /* clear accepted when healthy, back to READY (calibrated) */
    mock_rec.hw_trip = false;
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(d.fault, DRIVE_FAULT_NONE);
    assert_true(mock_rec.pwm_off); /* enabled only by a new run */
}

static void test_stale_clear_does_not_clear_later_fault(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    drive_request_clear_fault(&d); /* no fault yet: dropped */
    fixture_run_isr(&d, 1);
    assert_false(d.clear_requested);
    drive_report_overrun(&d);
    fixture_run_isr(&d, 3);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERRUN);
}

static void test_missing_conversion_faults_in_run(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    will_return(hal_adc_read, false);
    drive_control_isr(&d);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_ADC_MISSING);
    assert_true(mock_rec.pwm_off);
}

/* n control periods without a conversion (a dead ADC) */
static void run_isr_without_conversion(int n)
{
    int i;
    for (i = 0; i < n; i++) {
        will_return(hal_adc_read, false);
        drive_control_isr(&d);
    }
}

/* n periods in which the current words move by one count, as a live converter's do */
static void run_isr_live_words(int n)
{
    int i;
    int k;
    for (i = 0; i < n; i++) {
        for (k = 0; k < HAL_ADC_PHASES; k++) {
            mock_adc.phase[k] = (uint16_t)(MOCK_ADC_ZERO + (i & 1));
        }
        fixture_run_isr(&d, 1);
    }
}

/* A dead ADC is a fault in READY too, and a clear is never judged on an older period's
 * check: without a fresh conversion the drive stays in FAULT, with the reason. */
static void test_dead_adc_faults_in_ready_and_blocks_the_clear(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    run_isr_without_conversion(1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_ADC_MISSING);
    drive_request_clear_fault(&d);
    run_isr_without_conversion(1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.clear_blocked & CTL_FAULT_ADC_MISSING, CTL_FAULT_ADC_MISSING);
    drive_request_run(&d);
    run_isr_without_conversion(1000);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(mock_rec.enable, 0u);
    /* the converter back: a clear in a period with a fresh, clean check succeeds */
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(d.clear_blocked, 0u);
}

/* A fault of a check that runs only while the motor turns is re-verified before a clear:
 * an under-voltage cannot be cleared while the link is still low, a stuck converter not
 * while its words stay frozen. */
static void test_running_only_faults_block_the_clear_while_present(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    mock_adc.vdc = 1536u; /* 300 V */
    fixture_run_isr(&d, 10);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_DC_UNDERVOLTAGE);
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.clear_blocked, CTL_FAULT_DC_UNDERVOLTAGE);
    mock_adc.vdc = MOCK_ADC_VDC_540V;
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);

    /* a converter whose words froze while current flowed */
    drive_trip(&d, DRIVE_FAULT_ADC_STUCK);
    fixture_run_isr(&d, CTL_PROTECT_ALIVE_PERIODS); /* the mock's words do not move */
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.clear_blocked, CTL_FAULT_ADC_STUCK);
    run_isr_live_words(2);
    drive_request_clear_fault(&d);
    run_isr_live_words(1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
}

static void test_overrun_and_encoder_faults(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    drive_report_overrun(&d);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERRUN);
    assert_true(mock_rec.pwm_off);
    /* a second fault keeps the first code */
    drive_trip(&d, DRIVE_FAULT_HW_TRIP);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERRUN);

    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    mock_encoder.healthy = false;
    fixture_run_isr(&d, 1);
    assert_int_equal(d.fault, DRIVE_FAULT_ENCODER);
    /* clear needs the encoder healthy again */
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    mock_encoder.healthy = true;
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
}

/* A jump of the position reading latches ENCODER while the encoder still reports healthy: the
 * clear is accepted, but it drops the homing, and RUN is refused for the encoder until the
 * HAL has seen the index again (the count may be wrong until then). */
static void test_encoder_clear_needs_the_index_again(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    fixture_run_isr(&d, 2);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    mock_encoder.elec_angle += 0x40000000u; /* a quarter electrical turn at standstill */
    fixture_run_isr(&d, 1);
    assert_int_equal(d.fault, DRIVE_FAULT_ENCODER);
    assert_true(mock_encoder.healthy); /* nothing else says the count is wrong */

    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(mock_rec.rehome, 1u);
    drive_request_run(&d);
    fixture_run_isr(&d, 10);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(d.run_refusal, DRIVE_RUN_REFUSED_ENCODER);
    assert_int_equal(mock_rec.enable, 1u); /* only the first run */

    mock_encoder.healthy = true; /* the index passed */
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_int_equal(mock_rec.enable, 2u);

    /* a clear of another fault keeps the homing */
    drive_trip(&d, DRIVE_FAULT_OVERRUN);
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(mock_rec.rehome, 1u);
}

static void test_params_rejected_at_init(void **state)
{
    ctl_params_t p;
    (void)state;
    mock_reset();
    ctl_params_default(&p);
    will_return(ctl_init, false);
    drive_init(&d, &p);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_PARAMS);
    assert_true(mock_rec.pwm_off);
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 3);
    assert_int_equal(d.state, DRIVE_STATE_FAULT); /* not clearable */

    /* a startup fault is not clearable either */
    will_return(ctl_init, true);
    drive_init(&d, &p);
    drive_trip(&d, DRIVE_FAULT_STARTUP);
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
}

static void test_request_params(void **state)
{
    ctl_params_t p = d.params_bg;
    (void)state;
    p.controller = CTL_CONTROLLER_MPTC13;
    assert_int_equal(drive_request_params(&d, &p), CTL_PARAM_OK);
    assert_int_equal(mock_rec.request_params, 1u);
    assert_int_equal(mock_rec.requested.controller, CTL_CONTROLLER_MPTC13);
    mock_request_result = CTL_PARAM_LAMBDA;
    p.controller = CTL_CONTROLLER_MPTC49;
    assert_int_equal(drive_request_params(&d, &p), CTL_PARAM_LAMBDA);
    assert_int_equal(d.params_bg.controller, CTL_CONTROLLER_MPTC13);
}

/* Everything derived from a parameter set follows the set in force, which the ISR takes at
 * the start of a period in any state (here READY): the speed scaling of the measurements and
 * the protection limits. */
static void test_applied_set_rescales_speed_and_limits(void **state)
{
    ctl_params_t p = d.params_bg;
    const double wb = CTL_BASE_OMEGA_RAD_S;
    (void)state;
    fixture_calibrate(&d);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    mock_encoder.mech_speed_q16 = 10 * 65536; /* 10 rev/s = 600 r/min */
    fixture_run_isr(&d, 1);
    assert_near((double)ctl_to_float(d.meas.omega_e), 10.0 * CTL_TWO_PI * 3.0 / wb, 1e-5);

    p.pole_pairs = 2;
    p.protect.overspeed_rpm = 500.0f;
    assert_int_equal(drive_request_params(&d, &p), CTL_PARAM_OK);
    fixture_run_isr(&d, 1);
    assert_near((double)ctl_to_float(d.meas.omega_e), 10.0 * CTL_TWO_PI * 2.0 / wb, 1e-5);
    fixture_run_isr(&d, 5); /* the new 500 r/min limit, 5-period filter */
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERSPEED);
}

static void test_duty_conversion(void **state)
{
    (void)state;
    assert_int_equal(drive_duty_to_hal(CTL_Q(0.0)), 0u);
    assert_int_equal(drive_duty_to_hal(CTL_Q(-0.25)), 0u);
    assert_int_equal(drive_duty_to_hal(CTL_Q(0.5)), 16384u);
    assert_int_equal(drive_duty_to_hal(CTL_Q(1.0)), 32768u);
    assert_int_equal(drive_duty_to_hal(CTL_Q(1.5)), 32768u);
}

static void test_references(void **state)
{
    (void)state;
    drive_set_speed_ref_rpm(&d, 3000.0f); /* 3000 r/min at Pn = 3 is 1.0 pu */
    assert_int_equal(mock_rec.loop_mode, CTL_LOOP_SPEED);
    assert_true(mock_rec.speed_ref > CTL_Q(0.999) && mock_rec.speed_ref < CTL_Q(1.001));
    drive_set_torque_ref_nm(&d, 0.0f);
    assert_int_equal(mock_rec.loop_mode, CTL_LOOP_TORQUE);
    assert_int_equal(mock_rec.torque_ref, 0);
}

/* 1700 counts from mid scale is 16.6 A: over the 15 A software limit, inside the sensors */
#define OVER_LIMIT_COUNTS 1700

static void test_overcurrent_forces_off_before_any_write(void **state)
{
    ctl_fault_record_t r;
    uint32_t writes;
    (void)state;
    fixture_start_running(&d);
    writes = mock_rec.write;
    /* A and B opposite: the set still sums to zero, only the magnitude is wrong */
    mock_adc.phase[0] = (uint16_t)(MOCK_ADC_ZERO + OVER_LIMIT_COUNTS);
    mock_adc.phase[1] = (uint16_t)(MOCK_ADC_ZERO - OVER_LIMIT_COUNTS);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERCURRENT);
    assert_int_equal(drive_faults_latched(&d), CTL_FAULT_OVERCURRENT);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(mock_rec.write, writes); /* the faulted period wrote no compare value */

    /* clear refused while the current is still high; the record stays */
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    mock_adc.phase[0] = MOCK_ADC_ZERO;
    mock_adc.phase[1] = MOCK_ADC_ZERO;
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(drive_faults_latched(&d), 0u);

    /* the record survived the clear and describes the faulted period */
    assert_true(drive_read_fault_record(&d, &r));
    assert_int_equal(r.faults, CTL_FAULT_OVERCURRENT);
    assert_true(r.i_phase[0] > ctl_from_float(16.0f / 10.0f));
    assert_true(r.i_phase[1] < ctl_from_float(-16.0f / 10.0f));
    assert_false(drive_read_fault_record(&d, &r));
}

/* A board with +-50 A sensors: 500 counts above mid scale read 12.2 A (4.9 A with the reference
 * board's +-20 A scaling). The span is taken outside RUN only and within
 * DRIVE_CURRENT_SPAN_MIN_A..MAX_A. */
static void test_current_span_scales_the_phase_currents(void **state)
{
    const ctl_q per_count_20a = d.current_pu_per_count;
    (void)state;
    assert_false(drive_set_current_span(&d, 3.9f));
    assert_false(drive_set_current_span(&d, 400.5f));
    assert_false(drive_set_current_span(&d, 0.0f / 0.0f));
    assert_int_equal(d.current_pu_per_count, per_count_20a);
    assert_true(drive_set_current_span(&d, 100.0f));
    assert_int_equal(d.current_pu_per_count, ctl_from_float(100.0f / 4096.0f / 10.0f));
    fixture_start_running(&d);
    assert_false(drive_set_current_span(&d, 40.0f)); /* not while running */
    mock_adc.phase[0] = (uint16_t)(MOCK_ADC_ZERO + 500);
    mock_adc.phase[1] = (uint16_t)(MOCK_ADC_ZERO - 500);
    fixture_run_isr(&d, 1);
    assert_true(d.meas.i_phase[0] > ctl_from_float(1.21f) &&
                d.meas.i_phase[0] < ctl_from_float(1.23f));
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    mock_adc.phase[0] = (uint16_t)(MOCK_ADC_ZERO + OVER_LIMIT_COUNTS); /* 41.5 A */
    mock_adc.phase[1] = (uint16_t)(MOCK_ADC_ZERO - OVER_LIMIT_COUNTS);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERCURRENT);
}

static void test_simultaneous_faults_one_record_all_bits(void **state)
{
    ctl_fault_record_t r;
    (void)state;
    fixture_start_running(&d);
    mock_adc.phase[3] = (uint16_t)(MOCK_ADC_ZERO + OVER_LIMIT_COUNTS);
    mock_adc.phase[4] = (uint16_t)(MOCK_ADC_ZERO - OVER_LIMIT_COUNTS);
    mock_rec.hw_trip = true;
    fixture_run_isr(&d, 1);
    assert_int_equal(d.fault, DRIVE_FAULT_HW_TRIP); /* the most severe code names it */
    assert_int_equal(drive_faults_latched(&d), CTL_FAULT_HW_TRIP | CTL_FAULT_OVERCURRENT);
    assert_true(drive_read_fault_record(&d, &r));
    assert_int_equal(r.faults, CTL_FAULT_HW_TRIP | CTL_FAULT_OVERCURRENT);
    assert_false(drive_read_fault_record(&d, &r));

    /* a later fault of another kind while latched: logged, the first code kept */
    drive_report_overrun(&d);
    assert_int_equal(d.fault, DRIVE_FAULT_HW_TRIP);
    assert_true(drive_read_fault_record(&d, &r));
    assert_int_equal(r.faults, CTL_FAULT_OVERRUN);
}

static void test_dc_overvoltage_faults_when_idle(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_adc.vdc = 3800u; /* 742 V, over the 720 V limit */
    fixture_run_isr(&d, 2);
    assert_int_equal(d.state, DRIVE_STATE_READY); /* filtered: 3 periods */
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_DC_OVERVOLTAGE);
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(mock_rec.enable, 0u);
}

/* ---- open-phase operation (drive_open_phase.h) ---- */

static double op_theta; /* electrical angle of the test currents, rad */

/* n periods at 1500 r/min with 3 A balanced currents, the phases in `open` carrying none (their
 * words move by a count, as a live sensor's do) and the encoder turning with them. */
static void run_rotating(int n, unsigned open)
{
    const double step = 2.0 * TEST_PI * 75.0 * 1.0e-4;
    int i;
    int k;
    mock_encoder.mech_speed_q16 = 25 * 65536;
    for (i = 0; i < n; i++) {
        double amps[6];
        for (k = 0; k < 6; k++) {
            amps[k] = 3.0 * cos(op_theta - vsd_ref_phase_deg[k] * TEST_PI / 180.0);
        }
        for (k = 0; k < 6; k++) { /* the set's other two carry equal and opposite currents */
            if ((open >> k) & 1u) {
                const int s = (k < 3) ? 0 : 3;
                const int a = s + (k - s + 1) % 3;
                const int b = s + (k - s + 2) % 3;
                const double half = 0.5 * (amps[a] - amps[b]);
                amps[a] = ((open >> a) & 1u) ? 0.0 : half;
                amps[b] = ((open >> b) & 1u) ? 0.0 : -half;
                amps[k] = 0.0;
            }
        }
        for (k = 0; k < 6; k++) {
            mock_adc.phase[k] =
                (uint16_t)(HAL_BOARD_CURRENT_ZERO_COUNTS + 0.5 +
                           amps[k] / HAL_BOARD_CURRENT_A_PER_COUNT + (double)(i & 1));
        }
        mock_encoder.elec_angle = (uint32_t)(fmod(op_theta / (2.0 * TEST_PI), 1.0) * 4294967296.0);
        fixture_run_isr(&d, 1);
        op_theta += step;
    }
}

static void start_rotating(void)
{
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    run_rotating(450, 0u);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
}

/* Ride-through: OPEN_PHASE isolates the phase's leg, logs the record, keeps RUN with the outputs
 * off until the background's post-fault set is in force, then runs on five legs. */
static void test_open_phase_ride_through(void **state)
{
    uint32_t steps;
    ctl_fault_record_t r;
    (void)state;
    assert_false(drive_set_open_phase_action(&d, 2, 0));
    assert_false(drive_set_open_phase_action(&d, 1, 2));
    assert_true(drive_set_open_phase_action(&d, DRIVE_OPEN_PHASE_RIDE_THROUGH,
                                            (int16_t)CTL_POSTFAULT_MIN_LOSS));
    start_rotating();
    run_rotating(2 * CTL_PROTECT_OPEN_PHASE_WINDOW, 1u << 2);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_int_equal(d.fault, DRIVE_FAULT_NONE);
    assert_int_equal(d.isolated_leg, 2);
    assert_int_equal(d.isolation_cause, DRIVE_ISOLATION_FAULT);
    assert_int_equal(mock_rec.isolated, 1u << 2);
    assert_int_equal(drive_faults_latched(&d), 0u);
    assert_true(drive_read_fault_record(&d, &r));
    assert_int_equal(r.faults, CTL_FAULT_OPEN_PHASE);
    /* outputs off and no control step until the set of the isolated leg is in force */
    assert_true(mock_rec.pwm_off);
    steps = mock_rec.ctl_step;
    run_rotating(3, 1u << 2);
    assert_int_equal(mock_rec.ctl_step, steps);
    drive_background(&d);
    assert_int_equal(mock_rec.requested.open_phase, 2);
    drive_background(&d); /* waiting for the ISR: nothing asked twice */
    assert_int_equal(mock_rec.request_params, 1u);
    run_rotating(1, 1u << 2);
    assert_int_equal(ctl_postfault_config(&d.ctl)->open_leg, 2);
    assert_int_equal(mock_rec.ctl_step, steps + 1u);
    assert_int_equal(mock_rec.ctl_reset_command, 1u);
    assert_false(mock_rec.pwm_off);
    /* five-leg currents do not trip the check that ignores the isolated phase */
    run_rotating(3 * CTL_PROTECT_OPEN_PHASE_WINDOW, 1u << 2);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
}

/* A second open phase stops the drive, both records in the log; FAULT -> READY -> RUN keeps the
 * leg isolated and runs on five legs again. */
static void test_second_open_phase_stops(void **state)
{
    ctl_fault_record_t r;
    (void)state;
    (void)drive_set_open_phase_action(&d, DRIVE_OPEN_PHASE_RIDE_THROUGH, 0);
    start_rotating();
    run_rotating(2 * CTL_PROTECT_OPEN_PHASE_WINDOW, 1u << 5);
    drive_background(&d);
    run_rotating(CTL_PROTECT_OPEN_PHASE_WINDOW, 1u << 5);
    assert_int_equal(d.isolated_leg, 5);
    run_rotating(2 * CTL_PROTECT_OPEN_PHASE_WINDOW, (1u << 5) | (1u << 1));
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OPEN_PHASE);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(ctl_protect_log_pending(&d.protect), 2u);
    assert_true(drive_read_fault_record(&d, &r));
    assert_true(drive_read_fault_record(&d, &r));
    assert_int_equal(r.faults, CTL_FAULT_OPEN_PHASE);
    assert_int_equal(ctl_protect_open_phase(&d.protect), 1);
    drive_request_clear_fault(&d);
    run_rotating(1, 0u);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(d.isolated_leg, 5);
    assert_int_equal(mock_rec.isolated, 1u << 5);
    drive_request_run(&d);
    run_rotating(2, 1u << 5);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_false(mock_rec.pwm_off); /* the five-leg set is still in force: no pause */
}

/* The build default stops on OPEN_PHASE like on any fault; so does OPEN_PHASE with another
 * fault in the same period. */
static void test_open_phase_stops_by_default(void **state)
{
    (void)state;
    assert_int_equal(d.open_phase_action, DRIVE_OPEN_PHASE_STOP);
    start_rotating();
    run_rotating(2 * CTL_PROTECT_OPEN_PHASE_WINDOW, 1u << 3);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OPEN_PHASE);
    assert_int_equal(d.isolated_leg, -1);
    assert_int_equal(mock_rec.isolated, 0u);
}

/* An isolation command (READY or RUN), refused when a leg is isolated already or for a bad leg;
 * a restore command in READY only; after it the healthy set comes back before the outputs do. */
static void test_isolate_and_restore_commands(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    assert_false(drive_request_isolate_leg(&d, 6));
    assert_false(drive_request_restore_legs(&d)); /* none isolated */
    assert_true(drive_request_isolate_leg(&d, 4));
    fixture_run_isr(&d, 1);
    assert_int_equal(d.isolated_leg, 4);
    assert_int_equal(d.isolation_cause, DRIVE_ISOLATION_COMMAND);
    assert_false(drive_request_isolate_leg(&d, 1)); /* one at a time */
    drive_background(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(ctl_postfault_config(&d.ctl)->open_leg, 4);
    mock_cmd.enable = true;
    drive_request_run(&d);
    run_rotating(5, 1u << 4);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_false(mock_rec.pwm_off);
    assert_false(drive_request_restore_legs(&d)); /* not in RUN */
    drive_request_stop(&d);
    fixture_run_isr(&d, 1);
    assert_true(drive_request_restore_legs(&d));
    fixture_run_isr(&d, 1);
    assert_int_equal(d.isolated_leg, -1);
    assert_int_equal(mock_rec.isolated, 0u);
    /* RUN before the healthy set arrives: outputs held off */
    drive_request_run(&d);
    run_rotating(2, 0u);
    assert_true(mock_rec.pwm_off);
    drive_background(&d);
    assert_int_equal(mock_rec.requested.open_phase, -1);
    run_rotating(2, 0u);
    assert_false(mock_rec.pwm_off);
}

/* Whatever set a caller hands over, the open phase in it is the drive's isolated leg. */
static void test_requested_set_carries_the_isolated_leg(void **state)
{
    ctl_params_t p = d.params_bg;
    (void)state;
    fixture_calibrate(&d);
    p.open_phase = 3;
    assert_int_equal(drive_request_params(&d, &p), CTL_PARAM_OK);
    assert_int_equal(mock_rec.requested.open_phase, -1);
    fixture_run_isr(&d, 1);
    assert_int_equal(ctl_postfault_config(&d.ctl)->open_leg, CTL_POSTFAULT_NO_LEG);
}

static void test_fault_mask_mapping_round_trips(void **state)
{
    int16_t code;
    (void)state;
    assert_int_equal(drive_fault_from_mask(0u), DRIVE_FAULT_NONE);
    assert_int_equal(drive_fault_to_mask(DRIVE_FAULT_NONE), 0u);
    for (code = 1; code < DRIVE_FAULT_COUNT; code++) {
        const uint16_t bit = drive_fault_to_mask((drive_fault_t)code);
        assert_int_not_equal(bit, 0u);
        assert_int_equal(drive_fault_from_mask(bit), code);
    }
}

/* The speed loop at its torque limit in RUN (the background's watch, timed on the ISR count):
 * flagged after 0.1 s; with the stop action the run is asked to stop after the set time; off the
 * limit the flag clears. */
static void at_limit_for(uint32_t periods)
{
    uint32_t k;
    for (k = 0; k < periods; k++) {
        d.isr_count++;
        drive_background(&d);
    }
}

static void test_torque_limited_flag_and_stop(void **state)
{
    (void)state;
    d.ctl.initialised = true;
    d.ctl.config_active = 0;
    d.ctl.config[0].params.sample_time_s = 1.0e-4f;
    d.ctl.loop_mode = CTL_LOOP_SPEED;
    d.ctl.speed_pi.limit = CTL_Q(0.4);
    d.ctl.diag.torque_ref = CTL_Q(-0.4);
    d.state = DRIVE_STATE_RUN;
    /* the watch runs every 16th period: flagged between 0.1 and 0.1032 s at the limit */
    at_limit_for(990);
    assert_false(d.torque_limited);
    at_limit_for(42);
    assert_true(d.torque_limited);
    assert_false(d.stop_requested); /* the default: run on at the limit */
    d.ctl.diag.torque_ref = CTL_Q(0.3);
    at_limit_for(DRIVE_TORQUE_LIMITED_EVERY);
    assert_false(d.torque_limited);
    assert_false(drive_set_torque_limited_action(&d, 2, 0.5f));
    assert_false(drive_set_torque_limited_action(&d, DRIVE_TORQUE_LIMITED_STOP, 0.0f));
    assert_true(drive_set_torque_limited_action(&d, DRIVE_TORQUE_LIMITED_STOP, 0.2f));
    d.ctl.diag.torque_ref = CTL_Q(0.4);
    at_limit_for(1990);
    assert_false(d.stop_requested);
    at_limit_for(42);
    assert_true(d.stop_requested);
    assert_true(d.torque_limited_stopped);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_torque_limited_flag_and_stop, setup),
        cmocka_unit_test_setup(test_init_calibrates_with_pwm_off, setup),
        cmocka_unit_test_setup(test_calibration_averages_offsets, setup),
        cmocka_unit_test_setup(test_offset_out_of_range_faults, setup),
        cmocka_unit_test_setup(test_offset_low_side_faults, setup),
        cmocka_unit_test_setup(test_run_refused_until_calibrated, setup),
        cmocka_unit_test_setup(test_run_and_stop, setup),
        cmocka_unit_test_setup(test_run_refused_without_encoder, setup),
        cmocka_unit_test_setup(test_fault_forces_off_and_latches, setup),
        cmocka_unit_test_setup(test_stale_clear_does_not_clear_later_fault, setup),
        cmocka_unit_test_setup(test_missing_conversion_faults_in_run, setup),
        cmocka_unit_test_setup(test_overrun_and_encoder_faults, setup),
        cmocka_unit_test_setup(test_encoder_clear_needs_the_index_again, setup),
        cmocka_unit_test_setup(test_params_rejected_at_init, setup),
        cmocka_unit_test_setup(test_request_params, setup),
        cmocka_unit_test_setup(test_dead_adc_faults_in_ready_and_blocks_the_clear, setup),
        cmocka_unit_test_setup(test_running_only_faults_block_the_clear_while_present, setup),
        cmocka_unit_test_setup(test_applied_set_rescales_speed_and_limits, setup),
        cmocka_unit_test_setup(test_duty_conversion, setup),
        cmocka_unit_test_setup(test_references, setup),
        cmocka_unit_test_setup(test_overcurrent_forces_off_before_any_write, setup),
        cmocka_unit_test_setup(test_current_span_scales_the_phase_currents, setup),
        cmocka_unit_test_setup(test_simultaneous_faults_one_record_all_bits, setup),
        cmocka_unit_test_setup(test_dc_overvoltage_faults_when_idle, setup),
        cmocka_unit_test_setup(test_fault_mask_mapping_round_trips, setup),
        cmocka_unit_test_setup(test_open_phase_ride_through, setup),
        cmocka_unit_test_setup(test_second_open_phase_stops, setup),
        cmocka_unit_test_setup(test_open_phase_stops_by_default, setup),
        cmocka_unit_test_setup(test_isolate_and_restore_commands, setup),
        cmocka_unit_test_setup(test_requested_set_carries_the_isolated_leg, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
