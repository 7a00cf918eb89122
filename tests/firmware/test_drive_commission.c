/*
 * The drive's COMMISSION state and the phase check before RUN (firmware/app/drive/drive.c,
 * drive_commission.c), against the mocked HAL and core of test_drive_sm: entered from READY
 * only, by a request that is checked; refused elsewhere, below the under-voltage limit and
 * with an encoder error; left to READY (outputs off) on stop, to FAULT on a protection trip;
 * never enters RUN. After an OPEN_PHASE fault is cleared, a run passes the phase check before
 * any control step, and a failed check is FAULT OPEN_PHASE again, with a record.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "hal_board.h"

#include "ctl_pu.h"
#include "drive/drive.h"
#include "drive/drive_commission.h"
#include "drive_fixture.h"

static drive_t d;

/* Phase currents in A as the ADC's words (a live converter: the last bit alternates with the
 * period). */
static void set_currents(const float amps[6])
{
    int k;
    for (k = 0; k < 6; k++) {
        const float counts = (float)HAL_BOARD_CURRENT_ZERO_COUNTS +
                             amps[k] / (float)HAL_BOARD_CURRENT_A_PER_COUNT +
                             (float)(fixture_periods & 1u);
        mock_adc.phase[k] = (uint16_t)(counts + 0.5f);
    }
}

/* The fixture's inputs: no current in any phase. */
static void no_current(void)
{
    const float zero[6] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    set_currents(zero);
}

/* A perfect machine for the phase check: each phase carries exactly its share of the x-y
 * current reference the sequence asks for. */
static void following_current(void)
{
    const float v[4] = {0.0f, 0.0f, d.comm.x.ref_xy[0], d.comm.x.ref_xy[1]};
    float amps[6];
    int k;
    for (k = 0; k < 6; k++) {
        amps[k] = ident_vsd_phase(v, (int16_t)k);
    }
    set_currents(amps);
}

static int setup(void **state)
{
    (void)state;
    fixture_init(&d);
    fixture_inputs = no_current;
    return 0;
}

static void run_isr_following(int n)
{
    fixture_inputs = following_current;
    fixture_run_isr(&d, n);
    fixture_inputs = no_current;
}

static void test_requests_checked_and_refused_outside_ready(void **state)
{
    (void)state;
    /* calibrating */
    assert_int_equal(drive_request_commission(&d, COMM_STEPS_ALL, 400u), DRIVE_COMM_REFUSED);
    assert_int_equal(d.comm.reason, COMM_REASON_NOT_READY);
    fixture_calibrate(&d);
    /* bad masks and currents */
    assert_int_equal(drive_request_commission(&d, 0u, 400u), DRIVE_COMM_INVALID);
    assert_int_equal(drive_request_commission(&d, 0x80u | 0x7Fu, 400u), DRIVE_COMM_INVALID);
    assert_int_equal(drive_request_commission(&d, 0x3Eu, 400u), DRIVE_COMM_INVALID); /* no phases */
    assert_int_equal(drive_request_commission(&d, 0x05u, 400u),
                     DRIVE_COMM_INVALID); /* no encoder */
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 99u), DRIVE_COMM_INVALID);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 801u), DRIVE_COMM_INVALID);
    /* the DC link low */
    mock_adc.vdc = 1000u; /* 195 V */
    fixture_run_isr(&d, 1);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_REFUSED);
    assert_int_equal(d.comm.reason, COMM_REASON_UNDERVOLTAGE);
    mock_adc.vdc = MOCK_ADC_VDC_540V;
    fixture_run_isr(&d, 1);
    /* an encoder error after its index: refused; no index yet: what the sequence is for */
    mock_encoder.index_seen = true;
    mock_encoder.healthy = false;
    fixture_run_isr(&d, 1);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_REFUSED);
    assert_int_equal(d.comm.reason, COMM_REASON_ENCODER_ERROR);
    mock_encoder.index_seen = false;
    fixture_run_isr(&d, 1);
    /* a leg isolated (open-phase operation, drive_open_phase.h): five legs, refused */
    d.isolated_leg = 2;
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_REFUSED);
    assert_int_equal(d.comm.reason, COMM_REASON_OPEN_PHASE);
    d.isolated_leg = -1;
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_OK);
    assert_int_equal(d.state, DRIVE_STATE_READY); /* the ISR takes it */
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_COMMISSION);
    assert_false(mock_rec.pwm_off);
    assert_int_equal(mock_rec.ctl_step, 0u);
    assert_int_equal(d.comm.state, COMM_STATE_RUNNING);
}

static void test_refused_while_running_and_in_fault(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    mock_cmd.enable = true;
    drive_request_run(&d);
    fixture_run_isr(&d, 2);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_REFUSED);
    assert_int_equal(d.comm.reason, COMM_REASON_NOT_READY);
    fixture_run_isr(&d, 5);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    /* a request stored before a run started is dropped when the ISR sees RUN */
    drive_trip(&d, DRIVE_FAULT_OVERRUN);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_REFUSED);
    fixture_run_isr(&d, 3);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_true(mock_rec.pwm_off);
}

static void test_stop_aborts_with_outputs_off(void **state)
{
    uint32_t off;
    (void)state;
    fixture_calibrate(&d);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_OK);
    fixture_run_isr(&d, 20);
    assert_int_equal(d.state, DRIVE_STATE_COMMISSION);
    /* a run request in COMMISSION is refused, never deferred */
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_COMMISSION);
    assert_int_equal(d.run_refusal, DRIVE_RUN_REFUSED_STATE);
    off = mock_rec.force_off;
    drive_request_stop(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_true(mock_rec.pwm_off && mock_rec.force_off > off);
    assert_int_equal(d.comm.state, COMM_STATE_ABORTED);
    assert_int_equal(d.comm.reason, COMM_REASON_ABORTED);
    fixture_run_isr(&d, 20);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(mock_rec.ctl_step, 0u);
}

static void test_protection_trip_ends_it_in_fault(void **state)
{
    float amps[6] = {20.0f, -20.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    (void)state;
    fixture_calibrate(&d);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_OK);
    fixture_run_isr(&d, 10);
    assert_int_equal(d.state, DRIVE_STATE_COMMISSION);
    set_currents(amps); /* beyond the 15 A over-current limit */
    will_return(hal_adc_read, true);
    drive_control_isr(&d);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OVERCURRENT);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(d.comm.state, COMM_STATE_ABORTED);
    assert_int_equal(d.comm.reason, COMM_REASON_FAULT);
}

/* With no current flowing (every phase open), the sequence's phase check fails at once and
 * ends it: READY, outputs off, the reason kept. */
static void test_failed_step_ends_in_ready(void **state)
{
    (void)state;
    fixture_calibrate(&d);
    assert_int_equal(drive_request_commission(&d, 0x3Fu, 400u), DRIVE_COMM_OK);
    fixture_run_isr(&d, 600);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(d.comm.state, COMM_STATE_FAILED);
    assert_int_equal(d.comm.reason, COMM_REASON_NO_CURRENT);
    assert_int_equal(d.comm.x.result[COMM_Q_PHASES].quality, COMM_QUALITY_FAILED);
    assert_int_equal(d.comm.x.result[COMM_Q_R].reason, COMM_REASON_SKIPPED);
}

/* An OPEN_PHASE fault cleared: the next run checks the phases before any control step. */
static void open_phase_cleared(void)
{
    fixture_calibrate(&d);
    drive_trip(&d, DRIVE_FAULT_OPEN_PHASE);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    drive_request_clear_fault(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_true(d.phase_check_pending);
    mock_cmd.enable = true;
    drive_request_run(&d);
}

static void test_phase_check_before_run_fails_back_to_open_phase(void **state)
{
    ctl_fault_record_t r;
    int n = 0;
    (void)state;
    open_phase_cleared();
    while (drive_read_fault_record(&d, &r)) { /* the first episode's record */
        n++;
    }
    assert_int_equal(n, 1);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_true(d.phase_verifying);
    fixture_run_isr(&d, 1000);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    assert_int_equal(d.fault, DRIVE_FAULT_OPEN_PHASE);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(mock_rec.ctl_step, 0u); /* not one normal control period */
    assert_true(drive_read_fault_record(&d, &r));
    assert_int_equal(r.faults, CTL_FAULT_OPEN_PHASE);
    assert_true(d.phase_check_pending); /* still to be verified */
}

static void test_phase_check_before_run_passes_then_controls(void **state)
{
    int i;
    (void)state;
    open_phase_cleared();
    run_isr_following(1);
    assert_true(d.phase_verifying);
    for (i = 1; i < 1000 && d.phase_verifying; i++) {
        run_isr_following(1);
        if (d.phase_verifying) {
            assert_int_equal(mock_rec.ctl_step, 0u);
        }
    }
    assert_false(d.phase_verifying);
    assert_false(d.phase_check_pending);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_int_equal(d.comm.x.result[COMM_Q_PHASES].quality, COMM_QUALITY_OK);
    assert_true(i * 1.0e-4 < 0.06);          /* a few tens of ms */
    assert_int_equal(mock_rec.ctl_step, 1u); /* control from the period the check passed */
    fixture_run_isr(&d, 5);
    assert_int_equal(mock_rec.ctl_step, 6u);
    /* the next run needs no check */
    drive_request_stop(&d);
    fixture_run_isr(&d, 1);
    drive_request_run(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_RUN);
    assert_false(d.phase_verifying);
}

static void test_stop_during_the_phase_check(void **state)
{
    (void)state;
    open_phase_cleared();
    fixture_run_isr(&d, 10);
    assert_true(d.phase_verifying);
    drive_request_stop(&d);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_false(d.phase_verifying);
    assert_true(d.phase_check_pending);
    assert_true(mock_rec.pwm_off);
    assert_int_equal(mock_rec.ctl_step, 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_requests_checked_and_refused_outside_ready, setup),
        cmocka_unit_test_setup(test_refused_while_running_and_in_fault, setup),
        cmocka_unit_test_setup(test_stop_aborts_with_outputs_off, setup),
        cmocka_unit_test_setup(test_protection_trip_ends_it_in_fault, setup),
        cmocka_unit_test_setup(test_failed_step_ends_in_ready, setup),
        cmocka_unit_test_setup(test_phase_check_before_run_fails_back_to_open_phase, setup),
        cmocka_unit_test_setup(test_phase_check_before_run_passes_then_controls, setup),
        cmocka_unit_test_setup(test_stop_during_the_phase_check, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
