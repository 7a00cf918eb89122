/*
 * The F28335 firmware (start-up, control ISR, background loop) on the host:
 * the real drive application and control core over the register-level HAL
 * running against RAM register frames.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_pu.h"
#include "fw.h"
#include "measure/profile.h"
#include "measure/stack_watch.h"
#include "test_support.h"

#define R (f28335_host_regs)

extern uint16_t fw_host_ramfuncs_load[4];
extern uint16_t fw_host_ramfuncs_run[4];
extern uint16_t fw_host_ramconsts_load[3];
extern uint16_t fw_host_ramconsts_run[3];

/* DC-link word the emulated conversions return (counts; 2765 = 540 V). */
static uint16_t dc_link_counts;

static int setup(void **state)
{
    (void)state;
    dc_link_counts = 2765u;
    f28335_host_regs_reset();
    R.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO; /* TZ1 inactive */
    return 0;
}

/* One end of conversion: zero current on every phase, the DC link at dc_link_counts. */
static void adc_sequence_done(void)
{
    int i;
    for (i = 0; i < 6; i++) {
        R.adc.ADCRESULT[i] = (uint16_t)(2048u << 4);
    }
    R.adc.ADCRESULT[6] = (uint16_t)(dc_link_counts << 4);
    R.adc.ADCST = ADC_ST_INT_SEQ1;
}

static void isr_periods(int n)
{
    int i;
    for (i = 0; i < n; i++) {
        adc_sequence_done();
        fw_adc_isr();
    }
}

/* Send a request over the emulated SCI-A and return the decoded reply. */
static sxl_rx_t transact_frame(uint16_t cmd, const uint16_t *payload, uint16_t len,
                               sxl_frame_t *reply)
{
    uint16_t frame[SXL_MAX_FRAME];
    uint16_t tx[256];
    sxl_decoder_t dec;
    uint16_t n = sxl_encode(cmd, payload, len, frame, (uint16_t)SXL_MAX_FRAME);
    uint16_t i;
    int pass;
    sxl_rx_t r = SXL_RX_NONE;
    assert_true(n > 0u);
    f28335_host_sci_rx_inject(frame, n);
    for (pass = 0; pass < 8; pass++) {
        fw_background_step();
    }
    n = f28335_host_sci_tx_take(tx, 256u);
    sxl_decoder_init(&dec);
    for (i = 0u; i < n; i++) {
        const sxl_rx_t x = sxl_decoder_push(&dec, tx[i], reply);
        if (x != SXL_RX_NONE) {
            r = x;
        }
    }
    return r;
}

/* As the host tool sends it: a command that moves the motor in a session armed just before. */
static sxl_rx_t transact(uint16_t cmd, const uint16_t *payload, uint16_t len, sxl_frame_t *reply)
{
    uint16_t armed[SXL_MAX_PAYLOAD];
    uint16_t i;
    if (!SXL_ARMED_COMMAND(cmd)) {
        return transact_frame(cmd, payload, len, reply);
    }
    assert_int_equal(transact_frame(SXL_CMD_ARM, NULL, 0u, reply), SXL_RX_FRAME);
    assert_int_equal(reply->payload[0], SXL_OK);
    for (i = 0u; i < SXL_TOKEN_BYTES; i++) {
        armed[i] = reply->payload[1u + i];
    }
    for (i = 0u; i < len; i++) {
        armed[SXL_TOKEN_BYTES + i] = payload[i];
    }
    return transact_frame(cmd, armed, (uint16_t)(len + SXL_TOKEN_BYTES), reply);
}

/* The whole start-up writes EALLOW-protected registers only between EALLOW and EDIS (the
 * host watch, f28335_regs.h). ePWM's HRCNFG and trip-zone registers start from values a
 * previous configuration may have left, so that writing them changes something to see. */
static void test_startup_writes_protected_registers_inside_eallow(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < F28335_EPWM_COUNT; i++) {
        R.epwm[i].HRCNFG = 0x00A5u;
        R.epwm[i].TZSEL = 0x5A5Au;
        R.epwm[i].TZCTL = 0x000Fu;
        R.epwm[i].TZEINT = 0x0006u;
    }
    f28335_host_eallow_watch_start();
    assert_true(fw_startup());
    assert_int_equal(f28335_host_eallow_violations(), 0u);
}

static void test_startup_configures_everything(void **state)
{
    int i;
    (void)state;
    assert_true(fw_startup());
    /* vectors: SEQ1INT -> control ISR, everything else -> unexpected */
    assert_ptr_equal(R.pievect.vector[PIE_VECTOR_INDEX(1u, 1u)], fw_adc_isr);
    assert_ptr_equal(R.pievect.vector[PIE_VECTOR_INDEX(1u, 7u)], fw_unexpected_isr);
    assert_ptr_equal(R.pievect.vector[13], fw_unexpected_isr);
    assert_int_equal(R.piectrl.group[0].IER, 0x0001u);
    assert_int_equal(f28335_host_core.ier, CPU_IER_INT1);
    assert_int_equal(f28335_host_core.intm, 0u);
    assert_int_equal(f28335_host_core.eallow, 0u);
    /* clocks, flash, watchdog on at the end */
    assert_int_equal(R.sysctrl.PLLCR, 10u);
    assert_int_equal(R.flash.FBANKWAIT, 0x0505u);
    assert_int_equal(R.sysctrl.WDCR, WDCR_ENABLE_DIV64);
    for (i = 0; i < 4; i++) {
        assert_int_equal(fw_host_ramfuncs_run[i], fw_host_ramfuncs_load[i]);
    }
    for (i = 0; i < 3; i++) {
        assert_int_equal(fw_host_ramconsts_run[i], fw_host_ramconsts_load[i]);
    }
    /* the stack painted above the part in use (the host's stand-in region) */
    assert_ptr_equal(drive_stack.base, fw_host_stack);
    assert_int_equal(drive_stack.words, FW_HOST_STACK_WORDS);
    assert_int_equal(fw_host_stack[FW_HOST_STACK_IN_USE], STACK_WATCH_PATTERN);
    assert_int_equal(fw_host_stack[FW_HOST_STACK_WORDS - 1u], STACK_WATCH_PATTERN);
    /* peripherals */
    assert_int_equal(R.epwm[0].TBPRD, 7500u);
    assert_int_equal(R.epwm[5].DBFED, 300u);
    assert_int_equal(R.epwm[2].TZFRC & EPWM_TZ_OST, EPWM_TZ_OST);
    assert_int_equal(R.adc.ADCMAXCONV, 6u);
    assert_int_equal(R.eqep1.QPOSMAX, 4u * HAL_BOARD_ENCODER_LINES - 1u);
    assert_int_equal(R.scia.SCILBAUD, 40u);
    /* drive calibrating with PWM off */
    assert_int_equal(fw_drive.state, DRIVE_STATE_CALIBRATE);
}

static void test_isr_calibrates_then_runs_on_serial_command(void **state)
{
    sxl_frame_t rep;
    int i;
    (void)state;
    assert_true(fw_startup());
    R.eqep1.QEPSTS = EQEP_STS_FIMF; /* index seen */
    isr_periods(DRIVE_CALIBRATION_SAMPLES);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);
    assert_int_equal(fw_drive.isr_count, (uint32_t)DRIVE_CALIBRATION_SAMPLES);
    assert_int_equal(R.piectrl.PIEACK, 0x0001u); /* group 1 acknowledged */
    assert_int_equal(R.adc.ADCTRL2 & ADC_CTRL2_RST_SEQ1, ADC_CTRL2_RST_SEQ1);

    assert_int_equal(transact(SXL_CMD_RUN, NULL, 0u, &rep), SXL_RX_FRAME);
    assert_int_equal(rep.cmd, SXL_CMD_RUN | SXL_REPLY);
    assert_int_equal(rep.payload[0], SXL_OK);
    for (i = 0; i < 6; i++) {
        R.epwm[i].TZCLR = 0u;
        R.epwm[i].CMPA = 0xFFFFu;
    }
    isr_periods(1);
    assert_int_equal(fw_drive.state, DRIVE_STATE_RUN);
    for (i = 0; i < 6; i++) {
        assert_int_equal(R.epwm[i].TZCLR & EPWM_TZ_OST, EPWM_TZ_OST); /* outputs released */
        assert_true(R.epwm[i].CMPA <= 7501u);                         /* a duty was written */
    }
    isr_periods(20);
    assert_int_equal(fw_drive.state, DRIVE_STATE_RUN);

    /* status over the link */
    assert_int_equal(transact(SXL_CMD_GET_STATUS, NULL, 0u, &rep), SXL_RX_FRAME);
    assert_int_equal(rep.payload[0], SXL_OK);
    assert_int_equal(rep.payload[1 + SXL_ST_STATE], DRIVE_STATE_RUN);
    assert_int_equal(rep.payload[1 + SXL_ST_FAULT], DRIVE_FAULT_NONE);
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_ST_ISR_COUNT]),
                     (uint32_t)DRIVE_CALIBRATION_SAMPLES + 21u);
    /* the stack's mark: nothing runs on the stand-in region, so its in-use part */
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_ST_STACK_USED]), FW_HOST_STACK_IN_USE);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_ST_STACK_WORDS]), FW_HOST_STACK_WORDS);

    /* stop */
    assert_int_equal(transact(SXL_CMD_STOP, NULL, 0u, &rep), SXL_RX_FRAME);
    isr_periods(1);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);
}

/* A parameter change sent in READY takes effect at the next period start, not at the first
 * RUN period, and everything derived from the set follows it: the controller, the speed
 * scaling of the measurements and the protection limits. */
static void test_parameter_change_reaches_everything_at_the_next_period(void **state)
{
    sxl_frame_t rep;
    uint16_t payload[5];
    ctl_params_t p;
    const double wb = CTL_BASE_OMEGA_RAD_S;
    (void)state;
    assert_true(fw_startup());
    isr_periods(DRIVE_CALIBRATION_SAMPLES);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);

    payload[0] = SXL_CONTROLLER_MPTC13;
    sxl_put_u32(&payload[1], 20000u); /* 20 N*m/Wb */
    assert_int_equal(transact(SXL_CMD_SET_CONTROLLER, payload, 5u, &rep), SXL_RX_FRAME);
    assert_int_equal(rep.payload[0], SXL_OK);
    isr_periods(1);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);
    assert_false(ctl_config_pending(&fw_drive.ctl));
    assert_int_equal(ctl_params(&fw_drive.ctl)->controller, CTL_CONTROLLER_MPTC13);
    assert_true(ctl_params(&fw_drive.ctl)->lambda_nm_per_wb == 20.0f);

    p = fw_drive.params_bg;
    p.pole_pairs = 2;
    p.protect.overspeed_rpm = 1000.0f;
    assert_int_equal(drive_request_params(&fw_drive, &p), CTL_PARAM_OK);
    isr_periods(1);
    assert_near((double)ctl_to_float(ctl_config(&fw_drive.ctl)->protect.overspeed),
                1000.0 * 2.0 * CTL_TWO_PI / 60.0 / wb, 1e-6);
    assert_near((double)ctl_to_float(ctl_config(&fw_drive.ctl)->omega_pu_per_rev_s),
                CTL_TWO_PI * 2.0 / wb, 1e-6);
}

static uint16_t status_field(uint16_t offset)
{
    sxl_frame_t rep;
    assert_int_equal(transact(SXL_CMD_GET_STATUS, NULL, 0u, &rep), SXL_RX_FRAME);
    assert_int_equal(rep.payload[0], SXL_OK);
    return rep.payload[1u + offset];
}

static uint16_t command(uint16_t cmd)
{
    sxl_frame_t rep;
    assert_int_equal(transact(cmd, NULL, 0u, &rep), SXL_RX_FRAME);
    return rep.payload[0];
}

static void assert_outputs_forced_off(void)
{
    int i;
    for (i = 0; i < 6; i++) {
        assert_int_equal(R.epwm[i].TZFRC & EPWM_TZ_OST, EPWM_TZ_OST);
        R.epwm[i].TZFRC = 0u; /* re-armed: the next force shows again */
    }
}

/* The bring-up of docs/porting.md section 8, step by step, on the firmware as flashed. */
static void test_bring_up_steps_of_the_porting_guide(void **state)
{
    ctl_params_t bench;
    (void)state;
    /* 1. DC link off, gate drivers unpowered: calibrate, then wait in READY, no fault. */
    dc_link_counts = 0u;
    assert_true(fw_startup());
    isr_periods(1);
    assert_int_equal(status_field(SXL_ST_STATE), DRIVE_STATE_CALIBRATE);
    isr_periods(DRIVE_CALIBRATION_SAMPLES - 1);
    assert_int_equal(status_field(SXL_ST_STATE), DRIVE_STATE_READY);
    assert_int_equal(status_field(SXL_ST_FAULT), DRIVE_FAULT_NONE);
    assert_int_equal(drive_faults_latched(&fw_drive), 0u);
    assert_outputs_forced_off();
    isr_periods(2000); /* and it stays there */
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);

    /* 2. One turn of the shaft: the index is seen, the encoder reads healthy. */
    R.eqep1.QEPSTS = EQEP_STS_FIMF;
    isr_periods(1);
    assert_int_equal(status_field(SXL_ST_FLAGS) & SXL_FLAG_ENCODER_OK, SXL_FLAG_ENCODER_OK);

    /* 3. run with the link off: refused with the reason, outputs stay off. */
    assert_int_equal(command(SXL_CMD_RUN), SXL_ERR_REFUSED);
    assert_int_equal(status_field(SXL_ST_RUN_REFUSAL), DRIVE_RUN_REFUSED_UNDERVOLTAGE);
    isr_periods(5);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);
    assert_int_equal(R.epwm[0].TZCLR & EPWM_TZ_OST, 0u);
    /* ... the gate check on the bench image (FW_BENCH_DC_UNDERVOLTAGE_V=0: the same set) */
    bench = fw_drive.params_bg;
    bench.protect.dc_undervoltage_v = 0.0f;
    assert_int_equal(drive_request_params(&fw_drive, &bench), CTL_PARAM_OK);
    isr_periods(1);
    assert_int_equal(command(SXL_CMD_RUN), SXL_OK);
    isr_periods(3);
    assert_int_equal(fw_drive.state, DRIVE_STATE_RUN);
    assert_int_equal(R.epwm[0].TZCLR & EPWM_TZ_OST, EPWM_TZ_OST); /* pulses out */
    assert_int_equal(command(SXL_CMD_STOP), SXL_OK);
    isr_periods(1);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);
    assert_outputs_forced_off();
    /* GPIO12 low: hardware trip, all outputs off, no clear while it stays low */
    assert_int_equal(command(SXL_CMD_RUN), SXL_OK);
    isr_periods(2);
    R.gpiodata.GPADAT = 0u;
    isr_periods(1);
    assert_int_equal(status_field(SXL_ST_FAULT), DRIVE_FAULT_HW_TRIP);
    assert_outputs_forced_off();
    assert_int_equal(command(SXL_CMD_CLEAR_FAULT), SXL_OK);
    isr_periods(2);
    assert_int_equal(fw_drive.state, DRIVE_STATE_FAULT);
    R.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO;
    assert_int_equal(command(SXL_CMD_CLEAR_FAULT), SXL_OK);
    isr_periods(2);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);

    /* 5. Back to the normal limits: 300 V refuses RUN, 540 V runs. */
    bench.protect.dc_undervoltage_v = 350.0f;
    assert_int_equal(drive_request_params(&fw_drive, &bench), CTL_PARAM_OK);
    dc_link_counts = 1536u; /* 300 V */
    isr_periods(1);
    assert_int_equal(command(SXL_CMD_RUN), SXL_ERR_REFUSED);
    assert_int_equal(status_field(SXL_ST_RUN_REFUSAL), DRIVE_RUN_REFUSED_UNDERVOLTAGE);
    dc_link_counts = 2765u; /* 540 V */
    isr_periods(1);
    assert_int_equal(command(SXL_CMD_RUN), SXL_OK);
    isr_periods(2);
    assert_int_equal(fw_drive.state, DRIVE_STATE_RUN);
}

static void test_overrun_is_a_fault(void **state)
{
    (void)state;
    assert_true(fw_startup());
    R.eqep1.QEPSTS = EQEP_STS_FIMF;
    isr_periods(DRIVE_CALIBRATION_SAMPLES);
    assert_int_equal(fw_drive.state, DRIVE_STATE_READY);
    f28335_host_cycles_per_read = FW_ISR_BUDGET_CYCLES + 1000u; /* a slow ISR */
    R.epwm[1].TZFRC = 0u;
    isr_periods(1);
    assert_int_equal(fw_drive.state, DRIVE_STATE_FAULT);
    assert_int_equal(fw_drive.fault, DRIVE_FAULT_OVERRUN);
    /* the host counter advances by the same amount at every reading; the ISR reads it
     * several times (overrun check and the stage profile) */
    assert_true(fw_drive.isr_cycles_max >= FW_ISR_BUDGET_CYCLES + 1000u);
    assert_int_equal(fw_drive.isr_cycles_max % (FW_ISR_BUDGET_CYCLES + 1000u), 0);
    assert_int_equal(drive_profile.overruns, 1);
    assert_int_equal(R.epwm[1].TZFRC & EPWM_TZ_OST, EPWM_TZ_OST);
}

static void test_malformed_frames_counted(void **state)
{
    uint16_t bad[8];
    sxl_frame_t rep;
    uint16_t n;
    int pass;
    (void)state;
    assert_true(fw_startup());
    n = sxl_encode(SXL_CMD_PING, NULL, 0u, bad, 8u);
    bad[n - 1u] ^= 0x55u; /* CRC error: dropped, no reply */
    f28335_host_sci_rx_inject(bad, n);
    for (pass = 0; pass < 4; pass++) {
        fw_background_step();
    }
    assert_int_equal(f28335_host_sci_tx_take(bad, 8u), 0u);
    assert_int_equal(transact(SXL_CMD_GET_STATUS, NULL, 0u, &rep), SXL_RX_FRAME);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_ST_RX_ERRORS]), 1u);
    assert_int_equal(transact(SXL_CMD_PING, NULL, 0u, &rep), SXL_RX_FRAME);
    assert_int_equal(rep.payload[1], SXL_VERSION);
}

/* The virtual board's shutdown is not a board command: the board answers "unknown" and goes on
 * serving. */
static void test_board_answers_the_simulator_shutdown_unknown(void **state)
{
    sxl_frame_t rep;
    (void)state;
    assert_true(fw_startup());
    assert_int_equal(command(SXL_CMD_SIM_SHUTDOWN), SXL_ERR_UNKNOWN);
    assert_int_equal(transact(SXL_CMD_PING, NULL, 0u, &rep), SXL_RX_FRAME);
    assert_int_equal(rep.payload[0], SXL_OK);
}

static void test_unexpected_interrupt_and_startup_failure(void **state)
{
    (void)state;
    assert_true(fw_startup());
    R.epwm[0].TZFRC = 0u;
    fw_unexpected_isr();
    assert_int_equal(fw_state.unexpected_isr, 1u);
    assert_int_equal(R.epwm[0].TZFRC & EPWM_TZ_OST, EPWM_TZ_OST);

    f28335_host_regs_reset();
    R.sysctrl.PLLSTS = PLLSTS_MCLKSTS; /* oscillator missing: limp mode */
    assert_false(fw_startup());
    assert_int_equal(fw_drive.state, DRIVE_STATE_FAULT);
    assert_int_equal(fw_drive.fault, DRIVE_FAULT_STARTUP);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_startup_configures_everything, setup),
        cmocka_unit_test_setup(test_startup_writes_protected_registers_inside_eallow, setup),
        cmocka_unit_test_setup(test_isr_calibrates_then_runs_on_serial_command, setup),
        cmocka_unit_test_setup(test_parameter_change_reaches_everything_at_the_next_period, setup),
        cmocka_unit_test_setup(test_bring_up_steps_of_the_porting_guide, setup),
        cmocka_unit_test_setup(test_overrun_is_a_fault, setup),
        cmocka_unit_test_setup(test_malformed_frames_counted, setup),
        cmocka_unit_test_setup(test_board_answers_the_simulator_shutdown_unknown, setup),
        cmocka_unit_test_setup(test_unexpected_interrupt_and_startup_failure, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
