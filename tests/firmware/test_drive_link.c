/* Serial commands of the drive (firmware/app/service/drive_link.c), mocked HAL/core. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "ctl_pu.h"
#include "service/drive_link.h"
#include "measure/profile.h"
#include "measure/stack_watch.h"
#include "drive_fixture.h"

static drive_t d;
static sxl_frame_t req;
static sxl_frame_t rep;

static int setup(void **state)
{
    (void)state;
    fixture_init(&d);
    req.len = 0u;
    return 0;
}

static uint16_t send_raw(uint16_t cmd)
{
    req.cmd = cmd;
    drive_link_handle(&d, &req, &rep, 7u);
    assert_int_equal(rep.cmd, cmd | SXL_REPLY);
    assert_true(rep.len >= 1u);
    return rep.payload[0];
}

/* A session armed, its token in front of req's payload. */
static uint32_t arm_into_request(void)
{
    sxl_frame_t arm = {SXL_CMD_ARM, 0u, {0}};
    sxl_frame_t arm_reply;
    uint32_t token;
    uint16_t i;
    drive_link_handle(&d, &arm, &arm_reply, 7u);
    assert_int_equal(arm_reply.payload[0], SXL_OK);
    assert_int_equal(arm_reply.len, 1u + SXL_TOKEN_BYTES);
    token = sxl_get_u32(&arm_reply.payload[1]);
    assert_true(token != 0u);
    for (i = req.len; i > 0u; i--) {
        req.payload[i - 1u + SXL_TOKEN_BYTES] = req.payload[i - 1u];
    }
    sxl_put_u32(req.payload, token);
    req.len = (uint16_t)(req.len + SXL_TOKEN_BYTES);
    return token;
}

/* A request as the host tool sends it: a command that moves the motor in an armed session. */
static uint16_t send(uint16_t cmd)
{
    if (SXL_ARMED_COMMAND(cmd)) {
        (void)arm_into_request();
    }
    return send_raw(cmd);
}

/* periods of the background loop, the ISR's period count advanced as the ISR would */
static void background_periods(uint32_t periods)
{
    uint32_t k;
    for (k = 0u; k < periods; k++) {
        d.isr_count++;
        drive_background(&d);
    }
}

/* The dispatch is the command list (sxlink_commands.h): every listed code is answered, at its
 * listed length only, with the token exactly where the list says; every code off the list, the
 * virtual board's own included, is unknown. */
#define LISTED_ROW(name, code, handler, armed, request, reply, notes)                              \
    {code, (uint16_t)request##_SIZE, (armed) != 0},
static const struct {
    uint16_t code, len;
    bool armed;
} listed[] = {SXL_COMMAND_LIST(LISTED_ROW)};
#undef LISTED_ROW

static int listed_index(uint16_t code)
{
    uint16_t k;
    for (k = 0u; k < (uint16_t)(sizeof listed / sizeof listed[0]); k++) {
        if (listed[k].code == code) {
            return (int)k;
        }
    }
    return -1;
}

static void test_the_dispatch_is_the_command_list(void **state)
{
    uint16_t code;
    (void)state;
    fixture_ready(&d);
    assert_int_equal(sizeof listed / sizeof listed[0], SXL_COMMAND_COUNT);
    for (code = 0u; code < SXL_REPLY; code++) {
        const int k = listed_index(code);
        uint16_t result;
        memset(req.payload, 0, sizeof req.payload);
        req.len = (k < 0) ? 0u : (uint16_t)(listed[k].len + 1u); /* one byte too many */
        if (k < 0) {
            assert_int_equal(send_raw(code), SXL_ERR_UNKNOWN);
            continue;
        }
        assert_int_equal(send(code), SXL_ERR_LENGTH);
        req.len = listed[k].len;
        if (listed[k].armed) { /* the listed length, no token */
            assert_int_equal(send_raw(code), SXL_ERR_NOT_ARMED);
            req.len = listed[k].len;
        }
        result = send(code); /* the listed length, with the token where listed */
        assert_true(result != SXL_ERR_UNKNOWN && result != SXL_ERR_LENGTH &&
                    result != SXL_ERR_NOT_ARMED);
        assert_int_equal(SXL_ARMED_COMMAND(code), listed[k].armed);
    }
    assert_int_equal(listed_index(SXL_CMD_SIM_SHUTDOWN), -1);
}

/* Commands that move the motor need the armed session's token (protocol 7): none, a wrong
 * one, one replaced by a new ARM or taken back by DISARM: refused as NOT_ARMED, nothing moves.
 * Before, a noise frame that passed its CRC could carry RUN. */
static void test_motion_commands_need_the_armed_token(void **state)
{
    static const uint16_t motion[4] = {SXL_CMD_RUN, SXL_CMD_COMMISSION_START, SXL_CMD_ISOLATE_LEG,
                                       SXL_CMD_RESTORE_LEGS};
    uint32_t token;
    uint16_t k;
    (void)state;
    fixture_ready(&d);
    for (k = 0u; k < 4u; k++) {
        req.len = 0u;
        assert_int_equal(send_raw(motion[k]), SXL_ERR_NOT_ARMED);
        req.len = SXL_TOKEN_BYTES; /* a token, but not the session's */
        sxl_put_u32(req.payload, 0x12345678u);
        assert_int_equal(send_raw(motion[k]), SXL_ERR_NOT_ARMED);
    }
    req.len = 0u;
    token = arm_into_request();
    (void)arm_into_request(); /* a new session: the first token is void */
    sxl_put_u32(req.payload, token);
    req.len = SXL_TOKEN_BYTES;
    assert_int_equal(send_raw(SXL_CMD_RUN), SXL_ERR_NOT_ARMED);
    req.len = 0u;
    (void)arm_into_request();
    {
        sxl_frame_t disarm = {SXL_CMD_DISARM, 0u, {0}};
        sxl_frame_t r;
        drive_link_handle(&d, &disarm, &r, 7u);
        assert_int_equal(r.payload[0], SXL_OK);
    }
    assert_int_equal(send_raw(SXL_CMD_RUN), SXL_ERR_NOT_ARMED);
    assert_false(d.run_requested);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_RUN), SXL_OK); /* armed: taken */
    assert_true(d.run_requested);
}

static void test_ping_and_unknown(void **state)
{
    (void)state;
    assert_int_equal(send(SXL_CMD_PING), SXL_OK);
    assert_int_equal(rep.len, 2u);
    assert_int_equal(rep.payload[1], SXL_VERSION);
    assert_int_equal(send(0x7Fu), SXL_ERR_UNKNOWN);
    assert_int_equal(rep.len, 1u);
    req.len = 1u;
    assert_int_equal(send(SXL_CMD_PING), SXL_ERR_LENGTH);
}

/* The q-axis current (i_d = 0) at which the set in force estimates torque_nm: Te = 3 Pn psi_f i_q
 * (T_b = 3 psi_b I_b per pole pair, ctl_pu.h). */
static ctl_q iq_for_torque(double torque_nm)
{
    const ctl_params_t *p = ctl_params(&d.ctl);
    return ctl_from_float(
        (float)(torque_nm / (3.0 * p->pole_pairs * (double)p->pm_flux_wb) / CTL_BASE_CURRENT_A));
}

static void test_status(void **state)
{
    const uint16_t *st;
    (void)state;
    d.encoder.mech_speed_q16 = 25 << 16; /* 25 rev/s = 1500 r/min */
    d.encoder.healthy = true;
    d.isr_count = 123456u;
    d.isr_cycles_max = 4321u;
    mock_diag.i_d = CTL_Q(0.0);
    mock_diag.i_q = iq_for_torque(2.0);
    mock_diag.torque_ref = ctl_from_float((float)(-1.5 / CTL_BASE_TORQUE_NM));
    drive_set_speed_ref_rpm(&d, 1500.5f);
    mock_rec.pwm_off = true;
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_ST_SIZE);
    st = &rep.payload[1];
    assert_int_equal(st[SXL_ST_STATE], DRIVE_STATE_CALIBRATE);
    assert_int_equal(st[SXL_ST_FAULT], DRIVE_FAULT_NONE);
    assert_int_equal(st[SXL_ST_FLAGS], SXL_FLAG_ENCODER_OK | SXL_FLAG_PWM_OFF);
    assert_int_equal(st[SXL_ST_CONTROLLER], SXL_CONTROLLER_DDC);
    assert_int_equal(sxl_get_i32(&st[SXL_ST_SPEED]), 15000);
    assert_int_equal(sxl_get_i32(&st[SXL_ST_SPEED_REF]), 15005);
    assert_true(sxl_get_i32(&st[SXL_ST_TORQUE]) >= 1999 && sxl_get_i32(&st[SXL_ST_TORQUE]) <= 2001);
    assert_true(sxl_get_i32(&st[SXL_ST_TORQUE_REF]) >= -1501 &&
                sxl_get_i32(&st[SXL_ST_TORQUE_REF]) <= -1499);
    assert_int_equal(sxl_get_u32(&st[SXL_ST_LAMBDA]), 100000u); /* default 100 N*m/Wb */
    assert_int_equal(sxl_get_u32(&st[SXL_ST_ISR_COUNT]), 123456u);
    assert_int_equal(sxl_get_u32(&st[SXL_ST_ISR_MAX]), 4321u);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_RX_ERRORS]), 7u);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_FAULTS]), 0u);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_RECORDS]), 0u);
    {
        uint16_t i;
        for (i = 0u; i < rep.len; i++) {
            assert_true(rep.payload[i] <= 0xFFu);
        }
    }
}

static void test_speed_and_torque(void **state)
{
    (void)state;
    req.len = 4u;
    sxl_put_i32(req.payload, 30000); /* 3000.0 r/min = 1 pu at Pn = 3 */
    assert_int_equal(send(SXL_CMD_SET_SPEED), SXL_OK);
    assert_int_equal(mock_rec.loop_mode, CTL_LOOP_SPEED);
    assert_true(mock_rec.speed_ref > CTL_Q(0.999) && mock_rec.speed_ref < CTL_Q(1.001));
    sxl_put_i32(req.payload, -200001);
    assert_int_equal(send(SXL_CMD_SET_SPEED), SXL_ERR_VALUE);
    req.len = 3u;
    assert_int_equal(send(SXL_CMD_SET_SPEED), SXL_ERR_LENGTH);

    req.len = 4u;
    sxl_put_i32(req.payload, -2500); /* -2.5 N*m */
    assert_int_equal(send(SXL_CMD_SET_TORQUE), SXL_OK);
    assert_int_equal(mock_rec.loop_mode, CTL_LOOP_TORQUE);
    assert_true(ctl_to_float(mock_rec.torque_ref) < -0.14f &&
                ctl_to_float(mock_rec.torque_ref) > -0.15f);
    sxl_put_i32(req.payload, 1000001);
    assert_int_equal(send(SXL_CMD_SET_TORQUE), SXL_ERR_VALUE);
}

static void test_run_stop_clear(void **state)
{
    (void)state;
    assert_int_equal(send(SXL_CMD_RUN), SXL_ERR_REFUSED); /* calibrating */
    assert_false(d.run_requested);
    fixture_ready(&d);
    d.encoder.healthy = false;
    assert_int_equal(send(SXL_CMD_RUN), SXL_ERR_REFUSED);
    d.encoder.healthy = true;
    assert_int_equal(send(SXL_CMD_RUN), SXL_OK);
    assert_true(d.run_requested);
    assert_int_equal(send(SXL_CMD_STOP), SXL_OK);
    assert_true(d.stop_requested);
    assert_int_equal(send(SXL_CMD_CLEAR_FAULT), SXL_ERR_REFUSED); /* no fault */
    drive_trip(&d, DRIVE_FAULT_OVERRUN);
    assert_int_equal(send(SXL_CMD_CLEAR_FAULT), SXL_OK);
    assert_true(d.clear_requested);
}

static void test_set_controller(void **state)
{
    (void)state;
    req.len = 5u;
    req.payload[0] = SXL_CONTROLLER_MPTC49;
    sxl_put_u32(&req.payload[1], 1250u); /* 1.25 N*m/Wb */
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_OK);
    assert_int_equal(mock_rec.request_params, 1u);
    assert_int_equal(mock_rec.requested.controller, CTL_CONTROLLER_MPTC49);
    assert_true(mock_rec.requested.lambda_nm_per_wb > 1.2499f &&
                mock_rec.requested.lambda_nm_per_wb < 1.2501f);
    assert_int_equal(mock_rec.requested.pole_pairs, 3); /* rest of the set kept */

    req.payload[0] = (uint16_t)CTL_CONTROLLER_COUNT; /* the first id not in the list */
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_VALUE);
    req.payload[0] = SXL_CONTROLLER_DDC;
    sxl_put_u32(&req.payload[1], 2000001u);
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_VALUE);
    sxl_put_u32(&req.payload[1], 100u);
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_BUSY); /* the first one waits */
    mock_request_result = CTL_PARAM_LAMBDA;                       /* core rejects the set */
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_VALUE);
    req.len = 4u;
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_LENGTH);
    assert_int_equal(mock_rec.request_params, 3u);
}

/* Stage profile over the link: after calibration periods the ISR total has been timed on the
 * mocked counter; bad stage numbers and lengths are refused. */
static void test_profile(void **state)
{
    (void)state;
    fixture_ready(&d);
    req.len = 1u;
    req.payload[0] = PROF_TOTAL;
    assert_int_equal(send(SXL_CMD_GET_PROFILE), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_PF_SIZE);
    assert_int_equal(rep.payload[1 + SXL_PF_STAGE], PROF_TOTAL);
    /* the mocked counter advances 10 per reading and nothing else reads it while
     * calibrating: the ISR total is exactly the subtracted reading cost */
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_PF_READ_COST]), 10u);
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_PF_MAX]), 0u);
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_PF_MIN]), 0u);
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_PF_PERIOD]), 15000u); /* 100 us */
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_PF_CYCLES_PER_US]), 150u);
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_PF_OVERRUNS]), 0u);
    req.payload[0] = PROF_STAGES;
    assert_int_equal(send(SXL_CMD_GET_PROFILE), SXL_ERR_VALUE);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_GET_PROFILE), SXL_ERR_LENGTH);
}

/* Each reply byte is a byte (the C28x keeps them in 16-bit words). */
static void assert_reply_bytes(void)
{
    uint16_t i;
    for (i = 0u; i < rep.len; i++) {
        assert_true(rep.payload[i] <= 0xFFu);
    }
}

static void assert_near(int32_t value, int32_t expected, int32_t tolerance)
{
    if (value < expected - tolerance || value > expected + tolerance) {
        fail_msg("%ld not within %ld of %ld", (long)value, (long)tolerance, (long)expected);
    }
}

/* GET_FAULT_RECORD; returns the record payload (after the result byte). */
static const uint16_t *get_record(void)
{
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_GET_FAULT_RECORD), SXL_OK);
    assert_true(rep.len == 1u + SXL_FR_HEADER_SIZE || rep.len == 1u + SXL_FR_SIZE);
    assert_reply_bytes();
    return &rep.payload[1];
}

#define OVER_LIMIT_COUNTS 1700 /* 16.60 A: above the 15 A limit */

/* Running, then an over-current (with the controller's state the record should report) and
 * an overrun in the next period; the over-current's period. */
static uint32_t trip_overcurrent_then_overrun(void)
{
    uint32_t period;
    mock_encoder.elec_angle = 0x40000000u; /* 0.25 turn, steady: no encoder jump */
    fixture_ready(&d);
    mock_cmd.enable = true;
    assert_int_equal(send(SXL_CMD_RUN), SXL_OK);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_RUN);

    /* what the controller had in force, as the record should report it */
    d.ctl.diag.i_d = CTL_Q(0.0);
    d.ctl.diag.i_q = iq_for_torque(7.1);
    d.ctl.diag.torque_ref = ctl_from_float((float)(-8.4 / CTL_BASE_TORQUE_NM));
    d.ctl.applied_vector = 45;
    d.ctl.applied_duty = CTL_Q(0.6);
    mock_encoder.mech_speed_q16 = 25 << 16; /* 1500 r/min */
    mock_adc.phase[0] = (uint16_t)(MOCK_ADC_ZERO + OVER_LIMIT_COUNTS);
    mock_adc.phase[1] = (uint16_t)(MOCK_ADC_ZERO - OVER_LIMIT_COUNTS);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_FAULT);
    period = d.protect.period;
    fixture_run_isr(&d, 1); /* still over the limit: already latched, no new record */
    drive_trip(&d, DRIVE_FAULT_OVERRUN);
    return period;
}

/* The over-current's record: period, scaled measurements, the controller's state. */
static void check_overcurrent_record(const uint16_t *fr, uint32_t period)
{
    assert_int_equal(rep.len, 1u + SXL_FR_SIZE);
    assert_int_equal(fr[SXL_FR_PRESENT], 1u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_PENDING]), 1u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_DROPPED]), 0u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_FAULTS]), CTL_FAULT_OVERCURRENT);
    assert_int_equal(sxl_get_u32(&fr[SXL_FR_PERIOD]), period);
    assert_near(sxl_get_i16(&fr[SXL_FR_I_PHASE]), 1660, 1); /* 1700 counts * 40 A / 4096 */
    assert_near(sxl_get_i16(&fr[SXL_FR_I_PHASE + 2u]), -1660, 1);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_I_PHASE + 4u]), 0);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_I_PHASE + 10u]), 0);
    assert_near(sxl_get_i16(&fr[SXL_FR_VDC]), 5400, 1); /* 2765 counts * 800 V / 4096 */
    assert_near(sxl_get_u16(&fr[SXL_FR_THETA]), 16384, 1);
    assert_near(sxl_get_i32(&fr[SXL_FR_SPEED]), 15000, 1);
    assert_near(sxl_get_i32(&fr[SXL_FR_TORQUE]), 7100, 1);
    assert_near(sxl_get_i32(&fr[SXL_FR_TORQUE_REF]), -8400, 1);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_VECTOR]), 45);
    assert_near(sxl_get_u16(&fr[SXL_FR_DUTY]), 19661, 1); /* 0.6 in Q15 */
}

/* The stack's high-water mark and size (protocol 6): "not measured" (size 0) until the platform
 * paints, then the highest word written since the paint, read by the status request itself. */
static void test_status_stack(void **state)
{
    static volatile uint16_t region[100];
    const uint16_t *st = &rep.payload[1];
    (void)state;
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_STACK_WORDS]), SXL_STACK_NOT_MEASURED);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_STACK_USED]), 0u);
    stack_watch_paint(&drive_stack, region, 100u, 12u);
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_STACK_USED]), 12u);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_STACK_WORDS]), 100u);
    region[59] = 0u; /* a deeper call reached word 59 */
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_ST_SIZE);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_STACK_USED]), 60u);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_STACK_WORDS]), 100u);
    assert_reply_bytes();
    drive_stack.words = 0u; /* back to "not measured" for the other tests */
    drive_stack.used = 0u;
}

/* An over-current while running, then an overrun reported in the next period: the status
 * carries the first code, both latched bits and the two unread records; the records come
 * back oldest first, scaled, then the log reads empty. */
static void test_fault_status_and_records(void **state)
{
    const uint16_t *st;
    const uint16_t *fr;
    const uint32_t period = trip_overcurrent_then_overrun();
    (void)state;
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_ST_SIZE);
    assert_reply_bytes();
    st = &rep.payload[1];
    assert_int_equal(st[SXL_ST_STATE], DRIVE_STATE_FAULT);
    assert_int_equal(st[SXL_ST_FAULT], DRIVE_FAULT_OVERCURRENT);
    assert_string_equal(sxl_fault_name(st[SXL_ST_FAULT]), "OVERCURRENT");
    assert_int_equal(sxl_get_u16(&st[SXL_ST_FAULTS]), CTL_FAULT_OVERCURRENT | CTL_FAULT_OVERRUN);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_RECORDS]), 2u);

    fr = get_record(); /* the over-current, oldest */
    check_overcurrent_record(fr, period);

    fr = get_record(); /* the overrun, raised outside the periodic check */
    assert_int_equal(fr[SXL_FR_PRESENT], 1u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_PENDING]), 0u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_FAULTS]), CTL_FAULT_OVERRUN);
    assert_int_equal(sxl_get_u32(&fr[SXL_FR_PERIOD]), period + 1u);
    assert_near(sxl_get_i16(&fr[SXL_FR_I_PHASE]), 1660, 1);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_VECTOR]), 0);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_DUTY]), 0u);

    fr = get_record(); /* empty */
    assert_int_equal(rep.len, 1u + SXL_FR_HEADER_SIZE);
    assert_int_equal(fr[SXL_FR_PRESENT], 0u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_PENDING]), 0u);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_DROPPED]), 0u);

    /* the latch is untouched by reading the log */
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_ST_FAULTS]),
                     CTL_FAULT_OVERCURRENT | CTL_FAULT_OVERRUN);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_ST_RECORDS]), 0u);

    req.len = 1u;
    req.payload[0] = 0u;
    assert_int_equal(send(SXL_CMD_GET_FAULT_RECORD), SXL_ERR_LENGTH);
    assert_int_equal(rep.len, 1u);
}

/* More faults than the log holds: the oldest are kept, in order, and the rest counted. */
static void test_fault_log_order_and_dropped(void **state)
{
    uint16_t code;
    uint16_t i;
    (void)state;
    for (code = 1u; code <= 10u; code++) {
        drive_trip(&d, (drive_fault_t)code); /* a new bit each time: one record each */
    }
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_int_equal(rep.payload[1 + SXL_ST_FAULT], DRIVE_FAULT_PARAMS);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_ST_RECORDS]), CTL_PROTECT_LOG_SIZE);
    for (i = 0u; i < (uint16_t)CTL_PROTECT_LOG_SIZE; i++) {
        const uint16_t *fr = get_record();
        assert_int_equal(fr[SXL_FR_PRESENT], 1u);
        assert_int_equal(sxl_get_u16(&fr[SXL_FR_FAULTS]),
                         drive_fault_to_mask((drive_fault_t)(i + 1u)));
        assert_int_equal(sxl_get_u16(&fr[SXL_FR_PENDING]), CTL_PROTECT_LOG_SIZE - 1u - i);
        assert_int_equal(sxl_get_u16(&fr[SXL_FR_DROPPED]), 2u);
    }
    assert_int_equal(get_record()[SXL_FR_PRESENT], 0u);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_FR_DROPPED]), 2u);
}

/* Out-of-range values saturate instead of wrapping; the angle wraps into one turn. */
static void test_fault_record_saturates(void **state)
{
    const uint16_t *fr;
    (void)state;
    d.protect_in.i_phase[0] = CTL_Q_MAX;
    d.protect_in.i_phase[1] = CTL_Q_MIN;
    d.protect_in.vdc = CTL_Q_MAX;
    d.protect_in.theta_e = CTL_Q(-0.25);
    d.protect_in.omega_e = CTL_Q_MIN;
    d.protect_in.i_d = CTL_Q(0.0);
    d.protect_in.i_q = CTL_Q_MAX; /* the estimate holds it to the range analysis' 4 per unit */
    d.protect_in.model = &ctl_config(&d.ctl)->model;
    d.params_bg.pole_pairs = 0; /* unusable set: read as one pole pair, no division by 0 */
    drive_trip(&d, DRIVE_FAULT_OVERRUN);
    fr = get_record();
    assert_int_equal(fr[SXL_FR_PRESENT], 1u);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_I_PHASE]), INT16_MAX);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_I_PHASE + 2u]), -INT16_MAX);
    assert_int_equal(sxl_get_i16(&fr[SXL_FR_VDC]), INT16_MAX);
    assert_int_equal(sxl_get_u16(&fr[SXL_FR_THETA]), 49152u); /* 0.75 turn */
    assert_near(sxl_get_i32(&fr[SXL_FR_SPEED]), -128 * 90000, 2);
    /* 3 Pn psi_f i_q at i_q = 40 A (the domain's edge), in mN*m */
    assert_near(sxl_get_i32(&fr[SXL_FR_TORQUE]),
                (int32_t)(3.0 * ctl_params(&d.ctl)->pole_pairs *
                          (double)ctl_params(&d.ctl)->pm_flux_wb * CTL_RANGE_CURRENT *
                          CTL_BASE_CURRENT_A * 1000.0),
                100);
}

/* The protocol's names agree with the drive's codes and their protection bits. */
/* The open-phase commands: the option, an isolation and its details, the refusals, the flag. */
static void test_open_phase_commands(void **state)
{
    const uint16_t *op = &rep.payload[1];
    (void)state;
    fixture_ready(&d);
    assert_int_equal(send(SXL_CMD_GET_OPEN_PHASE), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_OP_SIZE);
    assert_int_equal(op[SXL_OP_ACTION], 0u);
    assert_int_equal(op[SXL_OP_LEG], 0xFFu);
    assert_int_equal(op[SXL_OP_IN_FORCE], 1u);
    assert_int_equal(sxl_get_i32(&op[SXL_OP_TORQUE_LIMIT]), 7000);
    req.len = 2u;
    req.payload[0] = 2u; /* no such action */
    req.payload[1] = 0u;
    assert_int_equal(send(SXL_CMD_SET_OPEN_PHASE_ACTION), SXL_ERR_VALUE);
    req.payload[0] = 1u;
    req.payload[1] = 1u;
    assert_int_equal(send(SXL_CMD_SET_OPEN_PHASE_ACTION), SXL_OK);
    assert_int_equal(d.open_phase_action, DRIVE_OPEN_PHASE_RIDE_THROUGH);
    assert_int_equal(d.postfault_strategy, (int16_t)CTL_POSTFAULT_MAX_TORQUE);
    req.len = 1u;
    req.payload[0] = 6u;
    assert_int_equal(send(SXL_CMD_ISOLATE_LEG), SXL_ERR_VALUE);
    req.payload[0] = 1u;
    assert_int_equal(send(SXL_CMD_ISOLATE_LEG), SXL_OK);
    fixture_run_isr(&d, 1);
    assert_int_equal(send(SXL_CMD_ISOLATE_LEG), SXL_ERR_REFUSED); /* one already */
    drive_background(&d);
    fixture_run_isr(&d, 1);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_GET_OPEN_PHASE), SXL_OK);
    assert_int_equal(op[SXL_OP_ACTION], 1u);
    assert_int_equal(op[SXL_OP_STRATEGY], 1u);
    assert_int_equal(op[SXL_OP_LEG], 1u);
    assert_int_equal(op[SXL_OP_CAUSE], DRIVE_ISOLATION_COMMAND);
    assert_int_equal(op[SXL_OP_IN_FORCE], 1u);
    assert_int_equal(sxl_get_i32(&op[SXL_OP_TORQUE_LIMIT]), 4041); /* 7 / sqrt(3) */
    assert_int_equal(sxl_get_u32(&op[SXL_OP_PERIOD]), d.isolation_period);
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_true((rep.payload[1 + SXL_ST_FLAGS] & SXL_FLAG_LEG_ISOLATED) != 0u);
    assert_true((rep.payload[1 + SXL_ST_FLAGS] & SXL_FLAG_TORQUE_LIMITED) == 0u);
    d.torque_limited = true; /* the background's watch (test_drive_sm) */
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_true((rep.payload[1 + SXL_ST_FLAGS] & SXL_FLAG_TORQUE_LIMITED) != 0u);
    d.torque_limited = false;
    d.state = DRIVE_STATE_RUN;
    assert_int_equal(send(SXL_CMD_RESTORE_LEGS), SXL_ERR_REFUSED); /* READY only */
    d.state = DRIVE_STATE_READY;
    assert_int_equal(send(SXL_CMD_RESTORE_LEGS), SXL_OK);
    fixture_run_isr(&d, 1);
    assert_int_equal(send(SXL_CMD_RESTORE_LEGS), SXL_ERR_REFUSED); /* none isolated */
    assert_int_equal(d.isolated_leg, -1);
}

/* What the drive does when the speed cannot be held, over the link (protocol 8): read back,
 * the refusals (nothing changed), and the stop action set by the link stopping a run at the
 * torque limit after the time it carried. */
static const uint16_t *get_torque_limited(void)
{
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_GET_TORQUE_LIMITED), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_TL_SIZE);
    return &rep.payload[1];
}

static uint16_t set_torque_limited(uint16_t action, uint16_t stop_ms)
{
    req.len = SXL_TL_SET_SIZE;
    req.payload[SXL_TL_ACTION] = action;
    sxl_put_u16(&req.payload[SXL_TL_STOP_MS], stop_ms);
    return send(SXL_CMD_SET_TORQUE_LIMITED_ACTION);
}

static void assert_torque_limited_choice(uint16_t action, uint16_t stop_ms)
{
    const uint16_t *tl = get_torque_limited();
    assert_int_equal(tl[SXL_TL_ACTION], action);
    assert_int_equal(sxl_get_u16(&tl[SXL_TL_STOP_MS]), stop_ms);
}

static void test_torque_limited_action_commands(void **state)
{
    (void)state;
    /* the build default, which the host tool sends with continue */
    assert_true(DRIVE_TORQUE_LIMITED_STOP_S * 1000.0f == (float)SXL_TL_STOP_MS_DEFAULT);
    assert_torque_limited_choice(SXL_TL_CONTINUE, SXL_TL_STOP_MS_DEFAULT);
    assert_int_equal(get_torque_limited()[SXL_TL_STOPPED], 0u);
    req.len = 2u; /* the time cut short */
    assert_int_equal(send(SXL_CMD_SET_TORQUE_LIMITED_ACTION), SXL_ERR_LENGTH);
    assert_int_equal(set_torque_limited(2u, 200u), SXL_ERR_VALUE); /* no such action */
    assert_int_equal(set_torque_limited(0xFFu, 200u), SXL_ERR_VALUE);
    assert_int_equal(set_torque_limited(SXL_TL_STOP, 0u), SXL_ERR_VALUE);
    assert_int_equal(set_torque_limited(SXL_TL_STOP, SXL_TL_STOP_MS_MAX + 1u), SXL_ERR_VALUE);
    assert_int_equal(set_torque_limited(SXL_TL_STOP, 0xFFFFu), SXL_ERR_VALUE);
    assert_torque_limited_choice(SXL_TL_CONTINUE, SXL_TL_STOP_MS_DEFAULT); /* nothing changed */
    assert_int_equal(set_torque_limited(SXL_TL_STOP, SXL_TL_STOP_MS_MAX), SXL_OK);
    assert_torque_limited_choice(SXL_TL_STOP, SXL_TL_STOP_MS_MAX);
    assert_int_equal(set_torque_limited(SXL_TL_CONTINUE, SXL_TL_STOP_MS_MIN), SXL_OK);
    assert_torque_limited_choice(SXL_TL_CONTINUE, SXL_TL_STOP_MS_MIN);
    assert_int_equal(d.torque_limited_action, DRIVE_TORQUE_LIMITED_CONTINUE);
    /* not a command that moves the motor: no armed session */
    assert_int_equal(set_torque_limited(SXL_TL_STOP, 200u), SXL_OK);
    assert_torque_limited_choice(SXL_TL_STOP, 200u);

    /* RUN in the speed loop, its reference at the limit (the background's watch, every 16th
     * period, test_drive_sm): stopped after 0.2 s at it, not before */
    d.ctl.initialised = true;
    d.ctl.config_active = 0;
    d.ctl.config[0].params.sample_time_s = 1.0e-4f;
    d.ctl.loop_mode = CTL_LOOP_SPEED;
    d.ctl.speed_pi.limit = CTL_Q(0.4);
    d.ctl.diag.torque_ref = CTL_Q(0.4);
    d.state = DRIVE_STATE_RUN;
    background_periods(1990u);
    assert_false(d.stop_requested);
    assert_int_equal(send(SXL_CMD_GET_STATUS), SXL_OK);
    assert_true((rep.payload[1 + SXL_ST_FLAGS] & SXL_FLAG_TORQUE_LIMITED) != 0u);
    assert_int_equal(get_torque_limited()[SXL_TL_STOPPED], 0u);
    background_periods(42u);
    assert_true(d.stop_requested);
    assert_int_equal(get_torque_limited()[SXL_TL_STOPPED], 1u);
}

static void test_fault_names_match_masks(void **state)
{
    uint16_t code;
    (void)state;
    for (code = 1u; code < (uint16_t)DRIVE_FAULT_COUNT; code++) {
        const uint16_t mask = drive_fault_to_mask((drive_fault_t)code);
        uint16_t bit = 0u;
        assert_true(mask != 0u && (mask & (uint16_t)(mask - 1u)) == 0u); /* one bit */
        while ((mask >> bit) != 1u) {
            bit++;
        }
        if (code == DRIVE_FAULT_STARTUP) {
            assert_string_equal(sxl_fault_bit_name(bit), "PLATFORM");
        } else {
            assert_string_equal(sxl_fault_bit_name(bit), sxl_fault_name(code));
        }
    }
    assert_string_equal(sxl_state_name(DRIVE_STATE_FAULT), "FAULT");
}

/* Commissioning (0x40..0x43): lengths, values and states checked; results on the wire. */
static void test_commission_start_validates(void **state)
{
    (void)state;
    req.len = 2u;
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_LENGTH);
    req.len = SXL_CC_SIZE;
    req.payload[SXL_CC_MASK] = 0x3Fu;
    sxl_put_u16(&req.payload[SXL_CC_CURRENT], 400u);
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_REFUSED); /* calibrating */
    fixture_ready(&d);
    req.payload[SXL_CC_MASK] = 0xFFu; /* an unknown step */
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_VALUE);
    req.payload[SXL_CC_MASK] = 0x05u; /* R without the encoder step */
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_VALUE);
    req.payload[SXL_CC_MASK] = 0x3Fu;
    sxl_put_u16(&req.payload[SXL_CC_CURRENT], 900u);
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_VALUE);
    sxl_put_u16(&req.payload[SXL_CC_CURRENT], 400u);
    mock_adc.vdc = 1000u; /* 195 V: below the under-voltage limit */
    fixture_run_isr(&d, 1);
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_REFUSED);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_COMMISSION_STATUS), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_CT_SIZE);
    assert_int_equal(rep.payload[1 + SXL_CT_STATE], SXL_COMM_STATE_IDLE);
    assert_int_equal(rep.payload[1 + SXL_CT_REASON], SXL_COMM_REASON_UNDERVOLTAGE);
    mock_adc.vdc = MOCK_ADC_VDC_540V;
    fixture_run_isr(&d, 1);
    req.len = SXL_CC_SIZE;
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_OK);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_COMMISSION);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_COMMISSION_STATUS), SXL_OK);
    assert_int_equal(rep.payload[1 + SXL_CT_STATE], SXL_COMM_STATE_RUNNING);
    assert_int_equal(rep.payload[1 + SXL_CT_STEP], SXL_COMM_STEP_PHASES);
    assert_int_equal(rep.payload[1 + SXL_CT_MASK], 0x3Fu);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_CT_CURRENT]), 400u);
    assert_int_equal(sxl_get_u32(&rep.payload[1 + SXL_CT_PERIODS]), 1u);
    assert_int_equal(send(SXL_CMD_COMMISSION_APPLY), SXL_ERR_REFUSED); /* still running */
    req.len = SXL_CC_SIZE;
    assert_int_equal(send(SXL_CMD_COMMISSION_START), SXL_ERR_REFUSED); /* not READY */
    assert_int_equal(send(SXL_CMD_STOP), SXL_ERR_LENGTH);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_STOP), SXL_OK);
    fixture_run_isr(&d, 1);
    assert_int_equal(d.state, DRIVE_STATE_READY);
    assert_int_equal(send(SXL_CMD_COMMISSION_STATUS), SXL_OK);
    assert_int_equal(rep.payload[1 + SXL_CT_STATE], SXL_COMM_STATE_ABORTED);
    assert_int_equal(rep.payload[1 + SXL_CT_REASON], SXL_COMM_REASON_ABORTED);
}

static void test_commission_results_and_apply(void **state)
{
    ident_result_t *res = d.comm.x.result;
    uint16_t applied;
    (void)state;
    fixture_ready(&d);
    req.len = 0u;
    assert_int_equal(send(SXL_CMD_COMMISSION_APPLY), SXL_ERR_REFUSED); /* nothing identified */
    req.len = 1u;
    req.payload[0] = SXL_COMM_QUANTITY_COUNT;
    assert_int_equal(send(SXL_CMD_COMMISSION_RESULT), SXL_ERR_VALUE);
    /* a finished sequence's results, as the steps leave them */
    d.comm.state = COMM_STATE_DONE;
    res[COMM_Q_R] = (ident_result_t){2.5f, 0.01f, 0.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_LD] = (ident_result_t){0.04f, 1e-5f, 3.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_LQ] =
        (ident_result_t){0.06f, 0.01f, 30.0f, COMM_QUALITY_POOR, COMM_REASON_ROTOR_MOVED};
    res[COMM_Q_OFFSET] = (ident_result_t){90.5f, 0.1f, 0.25f, COMM_QUALITY_OK, COMM_REASON_NONE};
    d.comm.x.offset_abs = 0x405B05B0u;
    req.payload[0] = SXL_COMM_Q_LQ;
    assert_int_equal(send(SXL_CMD_COMMISSION_RESULT), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_CR2_SIZE);
    assert_int_equal(rep.payload[1 + SXL_CR2_QUANTITY], SXL_COMM_Q_LQ);
    assert_int_equal(rep.payload[1 + SXL_CR2_QUALITY], SXL_COMM_QUALITY_POOR);
    assert_int_equal(rep.payload[1 + SXL_CR2_REASON], SXL_COMM_REASON_ROTOR_MOVED);
    assert_int_equal(sxl_get_i32(&rep.payload[1 + SXL_CR2_VALUE]), 60000000); /* nH */
    assert_int_equal(sxl_get_i32(&rep.payload[1 + SXL_CR2_SIGMA]), 10000000);
    assert_int_equal(sxl_get_i32(&rep.payload[1 + SXL_CR2_EXTRA]), 30);
    req.payload[0] = SXL_COMM_Q_OFFSET;
    assert_int_equal(send(SXL_CMD_COMMISSION_RESULT), SXL_OK);
    assert_int_equal(sxl_get_i32(&rep.payload[1 + SXL_CR2_VALUE]), 90500); /* mdeg */
    assert_int_equal(sxl_get_i32(&rep.payload[1 + SXL_CR2_EXTRA]), 250);
    /* APPLY: the OK values into the parameter set requested, the offset into the HAL */
    req.len = 0u;
    mock_request_result = CTL_PARAM_BUSY;
    assert_int_equal(send(SXL_CMD_COMMISSION_APPLY), SXL_ERR_BUSY);
    assert_int_equal(mock_encoder_offset, 0u); /* nothing half applied */
    mock_request_result = CTL_PARAM_OK;
    assert_int_equal(send(SXL_CMD_COMMISSION_APPLY), SXL_OK);
    assert_int_equal(rep.len, 1u + SXL_CA2_SIZE);
    applied = sxl_get_u16(&rep.payload[1 + SXL_CA2_APPLIED]);
    assert_int_equal(applied,
                     (1u << SXL_COMM_Q_R) | (1u << SXL_COMM_Q_LD) | (1u << SXL_COMM_Q_OFFSET));
    assert_true(mock_rec.requested.resistance_ohm == 2.5f);
    assert_true(mock_rec.requested.ld_h == 0.04f);
    assert_true(mock_rec.requested.lq_h == 0.055f); /* POOR: the set in force kept */
    assert_int_equal(mock_encoder_offset, 0x405B05B0u);
    /* outside READY: refused */
    drive_trip(&d, DRIVE_FAULT_OVERRUN);
    assert_int_equal(send(SXL_CMD_COMMISSION_APPLY), SXL_ERR_REFUSED);
}

/* The weak-magnet machine of issue 25: every step done, psi_f poor (no_speed) at 0.0672 Wb
 * against the 0.225 Wb in force. APPLY took R, L_d, L_q, L_xy and the offset and kept 0.225 Wb:
 * the drive lost the speed at rated load, no fault. Now a kept value its measurement
 * contradicts, or the flux group (L_d, L_q, psi_f) taken in part while a member has no number,
 * refuses the whole APPLY with mixed_set; a poor value that agrees with the one kept, a failed
 * R or L_xy, or a step not selected do not. */
static void comm_results_all_ok(void)
{
    ident_result_t *res = d.comm.x.result;
    d.comm.state = COMM_STATE_DONE;
    d.comm.reason = COMM_REASON_NONE;
    d.comm.mask = SXL_COMM_STEPS_ALL;
    res[COMM_Q_OFFSET] = (ident_result_t){90.5f, 0.1f, 0.25f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_R] = (ident_result_t){2.5f, 0.01f, 0.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_LD] = (ident_result_t){0.04f, 2e-4f, 3.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_LQ] = (ident_result_t){0.06f, 3e-4f, 3.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_LXY] = (ident_result_t){0.011f, 6e-5f, 3.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    res[COMM_Q_PSI_F] = (ident_result_t){0.2f, 1e-3f, 600.0f, COMM_QUALITY_OK, COMM_REASON_NONE};
    d.comm.x.offset_abs = 0x405B05B0u;
    mock_encoder_offset = 0u;
    mock_rec.request_params = 0u;
    ctl_params_default(&d.params_bg); /* the set in force: the reference machine */
    d.ctl.config_ready = 0;           /* the ISR took the last set */
}

static uint16_t comm_apply(void)
{
    req.len = 0u;
    return send(SXL_CMD_COMMISSION_APPLY);
}

static void check_refused_mixed(void)
{
    assert_int_equal(comm_apply(), SXL_ERR_REFUSED);
    assert_int_equal(mock_rec.request_params, 0u); /* nothing applied */
    assert_int_equal(mock_encoder_offset, 0u);
    assert_int_equal(send(SXL_CMD_COMMISSION_STATUS), SXL_OK);
    assert_int_equal(rep.payload[1 + SXL_CT_STATE], SXL_COMM_STATE_DONE);
    assert_int_equal(rep.payload[1 + SXL_CT_REASON], SXL_COMM_REASON_MIXED_SET);
}

static void check_applied(uint16_t quantities)
{
    assert_int_equal(comm_apply(), SXL_OK);
    assert_int_equal(sxl_get_u16(&rep.payload[1 + SXL_CA2_APPLIED]), quantities);
}

static void test_commission_apply_refuses_a_mixed_set(void **state)
{
    ident_result_t *res = d.comm.x.result;
    const uint16_t all = (1u << SXL_COMM_Q_OFFSET) | (uint16_t)SXL_COMM_MODEL_QUANTITIES;
    (void)state;
    fixture_ready(&d);
    /* psi_f poor, 170 sigma from the 0.225 Wb kept */
    comm_results_all_ok();
    res[COMM_Q_PSI_F] =
        (ident_result_t){0.0672f, 9e-4f, 560.0f, COMM_QUALITY_POOR, COMM_REASON_NO_SPEED};
    check_refused_mixed();
    /* with L_d poor too (rotor_moved, the reproducer's run): still refused */
    res[COMM_Q_LD] =
        (ident_result_t){0.0349f, 2e-4f, 14.0f, COMM_QUALITY_POOR, COMM_REASON_ROTOR_MOVED};
    check_refused_mixed();
    /* R poor and 25 % off the 2 ohm kept: refused as well */
    comm_results_all_ok();
    res[COMM_Q_R] = (ident_result_t){2.5f, 0.05f, 0.0f, COMM_QUALITY_POOR, COMM_REASON_SCATTER};
    check_refused_mixed();
    /* psi_f failed (no number) while L_d and L_q are taken: refused */
    comm_results_all_ok();
    res[COMM_Q_PSI_F] =
        (ident_result_t){0.0f, 0.0f, 0.0f, COMM_QUALITY_FAILED, COMM_REASON_TIMEOUT};
    check_refused_mixed();
    /* ... and with the whole flux group without a number: R, L_xy and the offset taken */
    res[COMM_Q_LD].quality = res[COMM_Q_LQ].quality = COMM_QUALITY_FAILED;
    check_applied((1u << SXL_COMM_Q_OFFSET) | (1u << SXL_COMM_Q_R) | (1u << SXL_COMM_Q_LXY));
    /* psi_f poor but within 3 sigma of the 0.225 Wb kept: no contradiction */
    comm_results_all_ok();
    res[COMM_Q_PSI_F] =
        (ident_result_t){0.2235f, 1e-3f, 560.0f, COMM_QUALITY_POOR, COMM_REASON_NO_SPEED};
    check_applied((uint16_t)(all & ~(1u << SXL_COMM_Q_PSI_F)));
    assert_true(mock_rec.requested.pm_flux_wb == 0.225f);
    /* R failed: its term is the set's own, taken alone */
    comm_results_all_ok();
    res[COMM_Q_R] = (ident_result_t){0.0f, 0.0f, 0.0f, COMM_QUALITY_FAILED, COMM_REASON_SCATTER};
    check_applied((uint16_t)(all & ~(1u << SXL_COMM_Q_R)));
    /* psi_f not selected: L_d and L_q are taken with the psi_f in force */
    comm_results_all_ok();
    d.comm.mask = SXL_COMM_STEPS_ALL & ~(1u << SXL_COMM_STEP_FLUX);
    res[COMM_Q_PSI_F] = (ident_result_t){0.0f, 0.0f, 0.0f, COMM_QUALITY_NOT_RUN, COMM_REASON_NONE};
    check_applied((uint16_t)(all & ~(1u << SXL_COMM_Q_PSI_F)));
    /* everything ok */
    comm_results_all_ok();
    check_applied(all);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_ping_and_unknown, setup),
        cmocka_unit_test_setup(test_motion_commands_need_the_armed_token, setup),
        cmocka_unit_test_setup(test_status, setup),
        cmocka_unit_test_setup(test_status_stack, setup),
        cmocka_unit_test_setup(test_speed_and_torque, setup),
        cmocka_unit_test_setup(test_run_stop_clear, setup),
        cmocka_unit_test_setup(test_set_controller, setup),
        cmocka_unit_test_setup(test_profile, setup),
        cmocka_unit_test_setup(test_fault_status_and_records, setup),
        cmocka_unit_test_setup(test_fault_log_order_and_dropped, setup),
        cmocka_unit_test_setup(test_fault_record_saturates, setup),
        cmocka_unit_test_setup(test_fault_names_match_masks, setup),
        cmocka_unit_test_setup(test_open_phase_commands, setup),
        cmocka_unit_test_setup(test_torque_limited_action_commands, setup),
        cmocka_unit_test_setup(test_commission_start_validates, setup),
        cmocka_unit_test_setup(test_commission_results_and_apply, setup),
        cmocka_unit_test_setup(test_commission_apply_refuses_a_mixed_set, setup),
        cmocka_unit_test_setup(test_the_dispatch_is_the_command_list, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
