/* Serial commands of the drive (firmware/app/drive_link.c), mocked HAL/core. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_pu.h"
#include "drive_link.h"
#include "profile.h"
#include "mock_hal_ctl.h"

static drive_t d;
static sxl_frame_t req;
static sxl_frame_t rep;

static int setup(void **state)
{
    ctl_params_t p;
    (void)state;
    mock_reset();
    ctl_params_default(&p);
    will_return(ctl_init, true);
    drive_init(&d, &p);
    req.len = 0u;
    return 0;
}

static uint16_t send(uint16_t cmd)
{
    req.cmd = cmd;
    drive_link_handle(&d, &req, &rep, 7u);
    assert_int_equal(rep.cmd, cmd | SXL_REPLY);
    assert_true(rep.len >= 1u);
    return rep.payload[0];
}

static void calibrate(void)
{
    int i;
    for (i = 0; i < DRIVE_CALIBRATION_SAMPLES; i++) {
        will_return(hal_adc_read, true);
        drive_control_isr(&d);
    }
    assert_int_equal(d.state, DRIVE_STATE_READY);
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

static void test_status(void **state)
{
    const uint16_t *st;
    (void)state;
    d.encoder.mech_speed_q16 = 25 << 16; /* 25 rev/s = 1500 r/min */
    d.encoder.healthy = true;
    d.isr_count = 123456u;
    d.isr_cycles_max = 4321u;
    mock_diag.torque_est = ctl_from_float((float)(2.0 / CTL_BASE_TORQUE_NM));
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
    assert_int_equal(sxl_get_u32(&st[SXL_ST_LAMBDA]), 500u);
    assert_int_equal(sxl_get_u32(&st[SXL_ST_ISR_COUNT]), 123456u);
    assert_int_equal(sxl_get_u32(&st[SXL_ST_ISR_MAX]), 4321u);
    assert_int_equal(sxl_get_u16(&st[SXL_ST_RX_ERRORS]), 7u);
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
    calibrate();
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

    req.payload[0] = 3u;
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_VALUE);
    req.payload[0] = SXL_CONTROLLER_DDC;
    sxl_put_u32(&req.payload[1], 2000001u);
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_VALUE);
    sxl_put_u32(&req.payload[1], 100u);
    mock_params_valid = false; /* core rejects the set */
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_VALUE);
    req.len = 4u;
    assert_int_equal(send(SXL_CMD_SET_CONTROLLER), SXL_ERR_LENGTH);
    assert_int_equal(mock_rec.request_params, 1u);
}

/* Stage profile over the link: after calibration periods the ISR total has been timed on the
 * mocked counter; bad stage numbers and lengths are refused. */
static void test_profile(void **state)
{
    (void)state;
    calibrate();
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_ping_and_unknown, setup),
        cmocka_unit_test_setup(test_status, setup),
        cmocka_unit_test_setup(test_speed_and_torque, setup),
        cmocka_unit_test_setup(test_run_stop_clear, setup),
        cmocka_unit_test_setup(test_set_controller, setup),
        cmocka_unit_test_setup(test_profile, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
