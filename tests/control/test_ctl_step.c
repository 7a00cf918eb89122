/* The control-step API: parameters, shadow copy, and command invariants for any input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl.h"
#include "ctl_pu.h"
#include "ctl_vectors.h"
#include "test_support.h"

static uint32_t rng = 2024u;
static uint32_t next_random(void)
{
    rng = rng * 1664525u + 1013904223u;
    return rng;
}
static ctl_q random_q(double lo, double hi)
{
    return ctl_from_float((float)(lo + (hi - lo) * (double)(next_random() >> 8) / 16777216.0));
}

static void test_default_parameters_are_valid(void **state)
{
    ctl_params_t p;
    ctl_t c;
    (void)state;
    ctl_params_default(&p);
    assert_true(ctl_params_valid(&p));
    assert_true(ctl_init(&c, &p));
    assert_int_equal(p.duty_levels, 6);
    assert_near((double)p.torque_limit_nm, 7.0, 1e-6);
}

static void test_invalid_parameters_are_rejected(void **state)
{
    ctl_params_t p;
    ctl_params_t bad;
    (void)state;
    ctl_params_default(&p);
    bad = p, bad.duty_levels = 1;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.duty_levels = CTL_DUTY_LEVELS_MAX + 1;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.lambda_nm_per_wb = -1.0f;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.controller = (ctl_controller_t)7;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.ddc_direction = (ctl_ddc_direction_t)5;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.ld_h = 0.0f;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.sample_time_s = 0.0f;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.torque_limit_nm = 0.0f;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.speed_kp_nm_per_rad_s = -1.0f;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.flux_ref_mode = CTL_FLUX_REF_CONSTANT, bad.flux_ref_wb = -0.2f;
    assert_false(ctl_params_valid(&bad));
    bad = p, bad.pole_pairs = 0;
    assert_false(ctl_params_valid(&bad));
}

static ctl_meas_t rated_measurement(void)
{
    ctl_meas_t m;
    int16_t k;
    for (k = 0; k < 6; k++) {
        m.i_phase[k] = CTL_Q(0.0);
    }
    m.vdc = CTL_Q(1.0);
    m.theta_e = CTL_Q(0.1);
    m.omega_e = CTL_Q(0.5);
    return m;
}

static void test_failed_init_commands_all_off(void **state)
{
    ctl_params_t p;
    ctl_t c;
    ctl_cmd_t cmd;
    const ctl_meas_t m = rated_measurement();
    int16_t k;
    (void)state;
    ctl_params_default(&p);
    p.ld_h = -1.0f;
    assert_false(ctl_init(&c, &p));
    ctl_step(&c, &m, &cmd);
    assert_false(cmd.enable);
    for (k = 0; k < 6; k++) {
        assert_int_equal(cmd.leg_duty[k], CTL_Q(0.0));
    }
}

/* A parameter change requested between steps takes effect at the start of the next step;
 * an invalid one is refused, counted, and the parameters in force stay. */
static void test_shadow_parameters(void **state)
{
    ctl_params_t p;
    ctl_params_t change;
    ctl_t c;
    ctl_cmd_t cmd;
    const ctl_meas_t m = rated_measurement();
    (void)state;
    ctl_params_default(&p);
    assert_true(ctl_init(&c, &p));
    change = p;
    change.lambda_nm_per_wb = 20.0f;
    change.controller = CTL_CONTROLLER_MPTC49;
    ctl_request_params(&c, &change);
    assert_near((double)c.params.lambda_nm_per_wb, 100.0, 1e-6);
    assert_int_equal(c.params.controller, CTL_CONTROLLER_DDC);
    ctl_step(&c, &m, &cmd);
    assert_near((double)c.params.lambda_nm_per_wb, 20.0, 1e-6);
    assert_int_equal(c.params.controller, CTL_CONTROLLER_MPTC49);
    assert_int_equal(ctl_diag(&c)->candidates, CTL_MPTC49_CANDIDATES);
    assert_near((double)ctl_to_float(c.lambda_pu), 20.0 * CTL_BASE_FLUX_WB / CTL_BASE_TORQUE_NM,
                1e-5);

    change.duty_levels = 0;
    ctl_request_params(&c, &change);
    ctl_step(&c, &m, &cmd);
    assert_int_equal(ctl_diag(&c)->params_rejected, 1);
    assert_int_equal(c.params.duty_levels, 6);
    assert_true(cmd.enable);
}

/* Leg duties realise "vector for d, zero vector for the rest" with centred pulses. */
static void check_command(const ctl_cmd_t *cmd)
{
    int16_t leg;
    const bool zero = cmd->vector == 0 || cmd->vector == 077;
    assert_true(cmd->enable);
    assert_in_range(cmd->vector, 0, 63);
    assert_true(cmd->duty >= CTL_Q(0.0) && cmd->duty <= CTL_Q(1.0));
    for (leg = 0; leg < 6; leg++) {
        const ctl_q d = cmd->leg_duty[leg];
        const bool on = ctl_vector_leg(cmd->vector, leg) != 0;
        assert_true(d >= CTL_Q(0.0) && d <= CTL_Q(1.0));
        if (zero) {
            assert_int_equal(d, on ? CTL_Q(1.0) : CTL_Q(0.0));
        } else if (ctl_vector_ones(cmd->vector) > 3) {
            assert_true(on ? d == CTL_Q(1.0) : d == ctl_sub(CTL_Q(1.0), cmd->duty));
        } else {
            assert_true(on ? d == cmd->duty : d == CTL_Q(0.0));
        }
    }
}

/* Whatever the measurements (saturated currents, zero or negative DC link, any angle and
 * speed), every controller returns a valid command. */
static void test_command_invariants_for_any_input(void **state)
{
    static const ctl_controller_t controllers[3] = {CTL_CONTROLLER_DDC, CTL_CONTROLLER_MPTC49,
                                                    CTL_CONTROLLER_MPTC13};
    int16_t which;
    (void)state;
    for (which = 0; which < 3; which++) {
        ctl_params_t p;
        ctl_t c;
        int32_t n;
        ctl_params_default(&p);
        p.controller = controllers[which];
        assert_true(ctl_init(&c, &p));
        ctl_set_speed_ref(&c, CTL_Q(0.5));
        for (n = 0; n < 3000; n++) {
            ctl_meas_t m;
            ctl_cmd_t cmd;
            int16_t k;
            const bool extreme = (n % 10) == 0;
            for (k = 0; k < 6; k++) {
                m.i_phase[k] = extreme ? (ctl_q)(int32_t)next_random() : random_q(-0.5, 0.5);
            }
            m.vdc = extreme ? (ctl_q)(int32_t)next_random() : random_q(0.0, 1.5);
            m.theta_e = (ctl_q)(int32_t)next_random();
            m.omega_e = extreme ? (ctl_q)(int32_t)next_random() : random_q(-1.0, 1.0);
#if CTL_MATH_FLOAT
            if (extreme) { /* random bit patterns are integers here: scale into a wide range */
                for (k = 0; k < 6; k++) {
                    m.i_phase[k] = random_q(-120.0, 120.0);
                }
                m.vdc = random_q(-120.0, 120.0);
                m.omega_e = random_q(-120.0, 120.0);
            }
#endif
            ctl_step(&c, &m, &cmd);
            check_command(&cmd);
            if (p.controller == CTL_CONTROLLER_DDC) {
                const int32_t fifths = ctl_to_qn(ctl_mul_int(cmd.duty, 5), 0);
                assert_near((double)ctl_to_float(cmd.duty), (double)fifths / 5.0, 1e-6);
            } else {
                assert_true(cmd.duty == CTL_Q(0.0) || cmd.duty == CTL_Q(1.0));
            }
        }
    }
}

static void test_duty_levels_parameter(void **state)
{
    ctl_params_t p;
    ctl_t c;
    int32_t n;
    bool seen_half = false;
    (void)state;
    ctl_params_default(&p);
    p.duty_levels = 3;
    assert_true(ctl_init(&c, &p));
    ctl_set_loop_mode(&c, CTL_LOOP_TORQUE);
    for (n = 0; n < 2000; n++) {
        ctl_meas_t m = rated_measurement();
        ctl_cmd_t cmd;
        m.theta_e = random_q(0.0, 1.0);
        ctl_set_torque_ref(&c, random_q(-0.4, 0.4));
        ctl_step(&c, &m, &cmd);
        assert_true(cmd.duty == CTL_Q(0.0) || cmd.duty == CTL_Q(0.5) || cmd.duty == CTL_Q(1.0));
        seen_half = seen_half || cmd.duty == CTL_Q(0.5);
    }
    assert_true(seen_half);
}

static void test_torque_mode_clamps_reference(void **state)
{
    ctl_params_t p;
    ctl_t c;
    ctl_cmd_t cmd;
    const ctl_meas_t m = rated_measurement();
    (void)state;
    ctl_params_default(&p);
    assert_true(ctl_init(&c, &p));
    ctl_set_loop_mode(&c, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(&c, CTL_Q(3.0));
    ctl_step(&c, &m, &cmd);
    assert_near((double)ctl_to_float(ctl_diag(&c)->torque_ref) * CTL_BASE_TORQUE_NM, 7.0, 1e-4);
    ctl_set_torque_ref(&c, CTL_Q(-3.0));
    ctl_step(&c, &m, &cmd);
    assert_near((double)ctl_to_float(ctl_diag(&c)->torque_ref) * CTL_BASE_TORQUE_NM, -7.0, 1e-4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_parameters_are_valid),
        cmocka_unit_test(test_invalid_parameters_are_rejected),
        cmocka_unit_test(test_failed_init_commands_all_off),
        cmocka_unit_test(test_shadow_parameters),
        cmocka_unit_test(test_command_invariants_for_any_input),
        cmocka_unit_test(test_duty_levels_parameter),
        cmocka_unit_test(test_torque_mode_clamps_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
