/*
 * The firmware built with a motor parameter file (docs/examples/motor_params_example.h, which
 * `sixphase-link identify --out` wrote against the virtual board): the start-up configures the
 * controller with the file's machine instead of the reference one, and the encoder HAL with
 * its index offset (firmware_f28335_host_params, host build over RAM register frames).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "fw.h"
#include "hal_encoder.h"

static void test_startup_takes_the_motor_parameter_file(void **state)
{
    const ctl_params_t *p;
    (void)state;
    f28335_host_regs_reset();
    f28335_host_regs.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO; /* TZ1 inactive */
    (void)fw_startup();
    p = &fw_drive.params_bg;
    assert_true(p->resistance_ohm == SIXPHASE_MOTOR_R_OHM);
    assert_true(p->ld_h == SIXPHASE_MOTOR_LD_H);
    assert_true(p->lq_h == SIXPHASE_MOTOR_LQ_H);
    assert_true(p->l_xy_h == SIXPHASE_MOTOR_LXY_H);
    assert_true(p->pm_flux_wb == SIXPHASE_MOTOR_PSI_F_WB);
    assert_int_equal(p->pole_pairs, SIXPHASE_MOTOR_POLE_PAIRS);
    assert_true(p->resistance_ohm != 2.0f); /* not the reference machine's */
    assert_true(ctl_params(&fw_drive.ctl)->pm_flux_wb == SIXPHASE_MOTOR_PSI_F_WB); /* in force */
    assert_int_equal(hal_encoder_offset(), (uint32_t)SIXPHASE_MOTOR_ENCODER_OFFSET);
    assert_int_equal(FW_ENCODER_OFFSET, (uint32_t)SIXPHASE_MOTOR_ENCODER_OFFSET);
    assert_int_equal(fw_drive.state, DRIVE_STATE_CALIBRATE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_startup_takes_the_motor_parameter_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
