/* The control-step API: parameters, shadow copy, and command invariants for any input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl.h"
#include "ctl_constants.h"
#include "ctl_pu.h"
#include "ctl_vectors.h"
#include "q24_exact.h" /* test_lcg_q */
#include "test_rng.h"
#include "test_support.h"

static uint32_t rng = 2024u;

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
    bad = p, bad.ddc_flux_tie_band = 1.5f;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_FLUX_TIE_BAND);
    bad = p, bad.ddc_flux_tie_band = -0.25f;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_FLUX_TIE_BAND);
    bad = p, bad.pulse_pattern = (ctl_pulse_pattern_t)3;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_PULSE_PATTERN);
    bad = p, bad.pulse_pattern = (ctl_pulse_pattern_t)-1;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_PULSE_PATTERN);
}

/* Not a normal number is refused with the field's reason, whatever its range: a denormal
 * torque limit (5.6e-45) once passed and made the MTPA table position NaN. */
static void test_non_normal_parameters_are_refused_with_a_reason(void **state)
{
    ctl_params_t p;
    ctl_params_t bad;
    const float denormal = 5.6e-45f;
    const float inf = 1.0e38f * 10.0f;
    const float nan = inf - inf;
    (void)state;
    ctl_params_default(&p);
    bad = p, bad.torque_limit_nm = denormal;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_TORQUE_LIMIT);
    bad = p, bad.lambda_nm_per_wb = denormal;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_LAMBDA);
    bad = p, bad.lambda_nm_per_wb = nan;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_LAMBDA);
    bad = p, bad.ddc_flux_tie_band = nan;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_FLUX_TIE_BAND);
    bad = p, bad.resistance_ohm = inf;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_RESISTANCE);
    bad = p, bad.lq_h = nan;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_INDUCTANCE);
    bad = p, bad.sample_time_s = 0.02f;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_SAMPLE_TIME);
    bad = p, bad.sample_time_s = 2.0e-3f; /* R Ts / L too large for Euler */
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_MODEL);
    bad = p, bad.speed_ki_nm_per_rad = -denormal;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_SPEED_GAINS);
    bad = p, bad.protect.overcurrent_a = nan;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_PROTECTION);
    bad = p, bad.protect.dc_undervoltage_v = 800.0f; /* above the overvoltage limit */
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_PROTECTION);
    bad = p, bad.protect.adc_stuck_periods = 0;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_PROTECTION);
    assert_int_equal(ctl_params_check(&p), CTL_PARAM_OK);
}

/* The per-unit bases are literals (no double expression to fold differently on a 32-bit
 * double target): each must equal its definition. */
static void test_per_unit_literals_match_their_definitions(void **state)
{
    const double wb = 2.0 * TEST_PI * 150.0;
    (void)state;
    assert_near(CTL_BASE_OMEGA_RAD_S / wb, 1.0, 1e-15);
    assert_near(CTL_BASE_TIME_S * wb, 1.0, 1e-15);
    assert_near(CTL_BASE_FLUX_WB / (CTL_BASE_VOLTAGE_V / wb), 1.0, 1e-15);
    assert_near(CTL_BASE_IMPEDANCE_OHM, CTL_BASE_VOLTAGE_V / CTL_BASE_CURRENT_A, 1e-14);
    assert_near(CTL_BASE_INDUCTANCE_H / (CTL_BASE_IMPEDANCE_OHM / wb), 1.0, 1e-15);
    assert_near(CTL_BASE_TORQUE_NM / (3.0 * CTL_BASE_FLUX_WB * CTL_BASE_CURRENT_A), 1.0, 1e-15);
    assert_near(CTL_TWO_PI / (2.0 * TEST_PI), 1.0, 1e-15);
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

/* A parameter change is built in the background and published; the control step switches to
 * it at its start. Until then the set in force stays; a second request while one waits is
 * BUSY; an invalid one is refused with its reason, counted, and the set in force stays. */
static void test_parameter_hand_off(void **state)
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
    assert_int_equal(ctl_request_params(&c, &change), CTL_PARAM_OK);
    assert_true(ctl_config_pending(&c));
    assert_near((double)ctl_params(&c)->lambda_nm_per_wb, 100.0, 1e-6);
    assert_int_equal(ctl_params(&c)->controller, CTL_CONTROLLER_DDC);
    assert_int_equal(ctl_request_params(&c, &p), CTL_PARAM_BUSY);
    ctl_step(&c, &m, &cmd);
    assert_false(ctl_config_pending(&c));
    assert_near((double)ctl_params(&c)->lambda_nm_per_wb, 20.0, 1e-6);
    assert_int_equal(ctl_params(&c)->controller, CTL_CONTROLLER_MPTC49);
    assert_int_equal(ctl_diag(&c)->candidates, CTL_MPTC49_CANDIDATES);
    assert_near((double)ctl_to_float(ctl_config(&c)->lambda),
                20.0 * CTL_BASE_FLUX_WB / CTL_BASE_TORQUE_NM, 1e-5);
    assert_false(ctl_config_take(&c)); /* nothing waits: a second take is harmless */

    change.duty_levels = 0;
    assert_int_equal(ctl_request_params(&c, &change), CTL_PARAM_DUTY_LEVELS);
    assert_false(ctl_config_pending(&c));
    ctl_step(&c, &m, &cmd);
    assert_int_equal(c.params_rejected, 1);
    assert_int_equal(c.params_last_error, CTL_PARAM_DUTY_LEVELS);
    assert_int_equal(ctl_params(&c)->duty_levels, 6);
    assert_true(cmd.enable);
}

/* The hand-off alternates buffers: the background only ever writes the buffer the ISR does not
 * read, whatever the sequence of requests and takes. */
static void test_hand_off_never_writes_the_buffer_in_force(void **state)
{
    ctl_params_t p;
    ctl_t c;
    int16_t k;
    (void)state;
    ctl_params_default(&p);
    assert_true(ctl_init(&c, &p));
    for (k = 0; k < 6; k++) {
        const ctl_config_t *in_force = ctl_config(&c);
        const ctl_config_t before = *in_force;
        p.lambda_nm_per_wb = 10.0f * (float)(k + 1);
        assert_int_equal(ctl_request_params(&c, &p), CTL_PARAM_OK);
        assert_memory_equal(in_force, &before, sizeof before);
        assert_true(ctl_config_take(&c));
        assert_ptr_not_equal(ctl_config(&c), in_force);
        assert_near((double)ctl_params(&c)->lambda_nm_per_wb, 10.0 * (k + 1), 1e-6);
    }
}

/* The expected duty of a leg at 1 or 0 in the active state and in the zero state. */
static ctl_q leg_duty(bool active, bool zero, ctl_q d)
{
    if (active == zero) {
        return zero ? CTL_Q(1.0) : CTL_Q(0.0);
    }
    return active ? d : ctl_sub(CTL_Q(1.0), d);
}

/* Leg duties realise "active state (cmd->vector) for d, a zero state for the rest" with centred
 * pulses, each three-phase set with its zero state 000 or 111 (ctl_pulse.h): a leg high for d
 * in the middle, for 1 - d in the middle, or all period at the zero state. A zero command
 * (duty 0) is a zero state: each set at 000 or 111, every leg at it. */
static void check_command(const ctl_cmd_t *cmd)
{
    int16_t set;
    assert_true(cmd->enable);
    assert_in_range(cmd->vector, 0, 63);
    assert_true(cmd->duty >= CTL_Q(0.0) && cmd->duty <= CTL_Q(1.0));
    for (set = 0; set < 2; set++) {
        const int16_t bits = (int16_t)((cmd->vector >> (3 - 3 * set)) & 07);
        bool matched = false;
        int16_t zero;
        if (cmd->duty == CTL_Q(0.0)) {
            assert_true(bits == 0 || bits == 07);
        }
        for (zero = 0; zero < 2 && !matched; zero++) {
            const bool z = (cmd->duty == CTL_Q(0.0)) ? bits != 0 : zero != 0;
            int16_t leg;
            matched = true;
            for (leg = (int16_t)(3 * set); leg < 3 * set + 3; leg++) {
                const ctl_q d = cmd->leg_duty[leg];
                assert_true(d >= CTL_Q(0.0) && d <= CTL_Q(1.0));
                matched =
                    matched && d == leg_duty(ctl_vector_leg(cmd->vector, leg) != 0, z, cmd->duty);
            }
        }
        assert_true(matched);
    }
}

/* A virtual vector's command (VV-MPTC): reported as its large state with duty 1, each leg on for
 * its share of the large and the medium-large state, and the period-average phase voltages of
 * those leg duties (each set's mean removed: isolated neutrals) have no x-y part. */
static void check_virtual_command(const ctl_cmd_t *cmd)
{
    const ctl_q medium_share = ctl_sub(CTL_Q(1.0), CTL_K_VV_LARGE_SHARE);
    ctl_q v[6];
    ctl_vsd_t u;
    int16_t k = 0;
    int16_t leg;
    assert_true(cmd->enable);
    assert_true(cmd->duty == CTL_Q(1.0));
    while (k < CTL_VV_COUNT && ctl_vv_states[k][0] != cmd->vector) {
        k++;
    }
    assert_true(k < CTL_VV_COUNT);
    for (leg = 0; leg < 6; leg++) {
        const bool in_large = ctl_vector_leg(ctl_vv_states[k][0], leg) != 0;
        const bool in_medium = ctl_vector_leg(ctl_vv_states[k][1], leg) != 0;
        const ctl_q want = ctl_add(in_large ? CTL_K_VV_LARGE_SHARE : CTL_Q(0.0),
                                   in_medium ? medium_share : CTL_Q(0.0));
        assert_true(cmd->leg_duty[leg] == want);
    }
    for (leg = 0; leg < 6; leg++) {
        const int16_t first = (int16_t)(leg - leg % 3);
        const ctl_q mean = ctl_mul(ctl_add(ctl_add(cmd->leg_duty[first], cmd->leg_duty[first + 1]),
                                           cmd->leg_duty[first + 2]),
                                   CTL_K_ONE_THIRD);
        v[leg] = ctl_sub(cmd->leg_duty[leg], mean);
    }
    ctl_vsd_forward(v, &u);
    assert_near((double)ctl_to_float(u.x), 0.0, 1e-6);
    assert_near((double)ctl_to_float(u.y), 0.0, 1e-6);
    assert_near((double)ctl_to_float(ctl_abs(u.alpha)) + (double)ctl_to_float(ctl_abs(u.beta)),
                fabs((double)ctl_to_float(ctl_vv_vsd[k].alpha)) +
                    fabs((double)ctl_to_float(ctl_vv_vsd[k].beta)),
                1e-6);
}

/* Whatever the measurements (saturated currents, zero or negative DC link, any angle and
 * speed), every controller returns a valid command, whatever the pulse pattern. */
static void test_command_invariants_for_any_input(void **state)
{
    static const ctl_controller_t controllers[4] = {CTL_CONTROLLER_DDC, CTL_CONTROLLER_MPTC49,
                                                    CTL_CONTROLLER_MPTC13, CTL_CONTROLLER_VVMPTC};
    int16_t which;
    (void)state;
    for (which = 0; which < 12; which++) { /* every controller with every pulse pattern */
        ctl_params_t p;
        ctl_t c;
        int32_t n;
        ctl_params_default(&p);
        p.controller = controllers[which % 4];
        p.pulse_pattern = (ctl_pulse_pattern_t)(which / 4);
        assert_true(ctl_init(&c, &p));
        ctl_set_speed_ref(&c, CTL_Q(0.5));
        for (n = 0; n < 3000; n++) {
            ctl_meas_t m;
            ctl_cmd_t cmd;
            int16_t k;
            const bool extreme = (n % 10) == 0;
            for (k = 0; k < 6; k++) {
                m.i_phase[k] =
                    extreme ? (ctl_q)(int32_t)test_lcg_next(&rng) : test_lcg_q(&rng, -0.5, 0.5);
            }
            m.vdc = extreme ? (ctl_q)(int32_t)test_lcg_next(&rng) : test_lcg_q(&rng, 0.0, 1.5);
            m.theta_e = (ctl_q)(int32_t)test_lcg_next(&rng);
            m.omega_e = extreme ? (ctl_q)(int32_t)test_lcg_next(&rng) : test_lcg_q(&rng, -1.0, 1.0);
#if CTL_MATH_FLOAT
            if (extreme) { /* random bit patterns are integers here: scale into a wide range */
                for (k = 0; k < 6; k++) {
                    m.i_phase[k] = test_lcg_q(&rng, -120.0, 120.0);
                }
                m.vdc = test_lcg_q(&rng, -120.0, 120.0);
                m.omega_e = test_lcg_q(&rng, -120.0, 120.0);
            }
#endif
            ctl_step(&c, &m, &cmd);
            if (p.controller == CTL_CONTROLLER_VVMPTC && c.applied_virtual != CTL_VV_NONE) {
                check_virtual_command(&cmd);
                continue;
            }
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

/* A step records what it applied: after VV-MPTC, FOC-VSD's carrier-PWM periods leave no virtual
 * vector in force, so a predictive controller taken next compensates its delay for a zero
 * vector, not for the last virtual vector VV-MPTC chose before FOC ran. */
static void test_foc_step_leaves_no_virtual_vector_in_force(void **state)
{
    ctl_params_t p;
    ctl_t c;
    ctl_meas_t m = {
        {CTL_Q(0.1), CTL_Q(-0.05), CTL_Q(-0.05), CTL_Q(0.1), CTL_Q(-0.05), CTL_Q(-0.05)},
        CTL_Q(1.0),
        CTL_Q(0.0),
        CTL_Q(0.1)};
    ctl_cmd_t cmd;
    int16_t n;
    (void)state;
    ctl_params_default(&p);
    p.controller = CTL_CONTROLLER_VVMPTC;
    assert_true(ctl_init(&c, &p));
    ctl_set_loop_mode(&c, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(&c, CTL_Q(0.5));
    for (n = 0; n < 50 && c.applied_virtual == CTL_VV_NONE; n++) {
        m.theta_e = ctl_add(m.theta_e, CTL_Q(0.01));
        ctl_step(&c, &m, &cmd);
    }
    assert_true(c.applied_virtual != CTL_VV_NONE);
    p.controller = CTL_CONTROLLER_FOC;
    assert_int_equal(ctl_request_params(&c, &p), CTL_PARAM_OK);
    ctl_step(&c, &m, &cmd); /* takes the FOC set and runs FOC's step */
    assert_int_equal(c.applied_virtual, CTL_VV_NONE);
    assert_int_equal(c.applied_vector, 0);
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
        m.theta_e = test_lcg_q(&rng, 0.0, 1.0);
        ctl_set_torque_ref(&c, test_lcg_q(&rng, -0.4, 0.4));
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

/* The speed loop sees the speed as measured, also beyond the range analysis' omega_max (which
 * only the prediction is held to): at the reference, no torque is asked for, in every step. */
static void test_speed_loop_takes_the_measured_speed(void **state)
{
    int16_t controller;
    (void)state;
    for (controller = 0; controller < CTL_CONTROLLER_COUNT; controller++) {
        ctl_params_t p;
        ctl_t c;
        ctl_meas_t m = {{0}, CTL_Q(1.0), CTL_Q(0.0), CTL_Q(6.0)};
        ctl_cmd_t cmd;
        int16_t open;
        ctl_params_default(&p);
        p.controller = (ctl_controller_t)controller;
        for (open = CTL_POSTFAULT_NO_LEG; open <= 2; open = (int16_t)(open + 3)) {
            p.open_phase = open;
            assert_true(ctl_init(&c, &p));
            assert_true(m.omega_e > ctl_config(&c)->model.omega_max);
            ctl_set_loop_mode(&c, CTL_LOOP_SPEED);
            ctl_set_speed_ref(&c, m.omega_e);
            ctl_step(&c, &m, &cmd);
            assert_int_equal(ctl_diag(&c)->torque_ref, CTL_Q(0.0));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_parameters_are_valid),
        cmocka_unit_test(test_invalid_parameters_are_rejected),
        cmocka_unit_test(test_non_normal_parameters_are_refused_with_a_reason),
        cmocka_unit_test(test_per_unit_literals_match_their_definitions),
        cmocka_unit_test(test_failed_init_commands_all_off),
        cmocka_unit_test(test_parameter_hand_off),
        cmocka_unit_test(test_hand_off_never_writes_the_buffer_in_force),
        cmocka_unit_test(test_command_invariants_for_any_input),
        cmocka_unit_test(test_foc_step_leaves_no_virtual_vector_in_force),
        cmocka_unit_test(test_duty_levels_parameter),
        cmocka_unit_test(test_torque_mode_clamps_reference),
        cmocka_unit_test(test_speed_loop_takes_the_measured_speed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
