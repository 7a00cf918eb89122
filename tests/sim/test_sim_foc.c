/*
 * FOC-VSD in closed loop: the real core (fixed and float) through the firmware's drive ISR and the
 * simulator's plant (dead time, PM flux harmonics, ADC and encoder errors), as the predictive
 * controllers in test_sim_closed_loop.c.
 *
 * Bands (the figures of docs/design.md, "FOC-VSD", with margin):
 *   steady state, 1500 r/min, rated load   speed within 5 r/min, torque within 0.1 N m of the
 *                                          load's, x-y current below 0.7 A rms (0.50 A measured:
 *                                          the PM flux's 5th and 7th harmonics, which the
 *                                          stationary x-y PIs reject only in part), torque ripple
 *                                          below 0.15 N m, switching frequency the 10 kHz
 *                                          carrier's (one pulse per leg and period)
 *   without PM harmonics and dead time     x-y current below 0.1 A rms (0.04 A measured)
 *   fixed vs float                         speed within 2 r/min, torque within 0.05 N m, THD and
 *                                          ripple within 10 % of each other
 *   rated load step                        Te reaches 90 % of the load within 1..20 ms
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "run/sim.h"
#include "sim_run_checked.h"

#define FOC 3

static void run(int arith, sim_scenario_t scen, bool ideal, sim_result_t *r)
{
    sim_config_t c;
    sim_config_default(&c);
    c.controller = FOC;
    c.arith = arith;
    c.scenario = scen;
    if (ideal) {
        c.plant.dead_time_on = c.plant.harmonics_on = false;
    }
    sim_run_quiet(&c, r);
    print_message("foc %-5s %-9s%s: speed %7.1f r/min, Te %.3f N m, THD %5.1f %% (h50 %5.1f %%), "
                  "ripple %.3f N m, xy %.3f A, f_sw %.0f Hz, transient %.1f ms\n",
                  r->arith, r->scenario, ideal ? " (no dead time, no PM harmonics)" : "",
                  r->speed_mean_rpm, r->torque_mean_nm, r->thd_percent, r->thd50_percent,
                  r->torque_ripple_nm, r->xy_current_rms_a, r->switching_freq_hz, r->transient_ms);
}

static void check_steady(const sim_result_t *r)
{
    const double load = 7.0 + 0.001 * 1500.0 * 2.0 * 3.14159265 / 60.0; /* friction too */
    assert_int_equal(r->final_state, 3);                                /* RUN */
    assert_int_equal(r->fault, 0);
    assert_true(fabs(r->speed_mean_rpm - 1500.0) < 5.0);
    assert_true(fabs(r->torque_mean_nm - load) < 0.1);
    assert_true(r->xy_current_rms_a < 0.7);
    assert_true(r->torque_ripple_nm < 0.15);
    assert_true(fabs(r->switching_freq_hz - 10000.0) < 200.0);
}

static void test_steady_both_arithmetics(void **state)
{
    sim_result_t fx;
    sim_result_t fl;
    (void)state;
    run(0, SIM_SCEN_STEADY, false, &fx);
    run(1, SIM_SCEN_STEADY, false, &fl);
    check_steady(&fx);
    check_steady(&fl);
    assert_true(fabs(fx.speed_mean_rpm - fl.speed_mean_rpm) < 2.0);
    assert_true(fabs(fx.torque_mean_nm - fl.torque_mean_nm) < 0.05);
    assert_true(fabs(fx.thd_percent - fl.thd_percent) < 0.1 * fl.thd_percent);
    assert_true(fabs(fx.torque_ripple_nm - fl.torque_ripple_nm) < 0.1 * fl.torque_ripple_nm);
}

static void test_xy_without_disturbances(void **state)
{
    sim_result_t r;
    (void)state;
    run(0, SIM_SCEN_STEADY, true, &r);
    check_steady(&r);
    assert_true(r.xy_current_rms_a < 0.1);
}

static void test_load_step(void **state)
{
    sim_result_t r;
    (void)state;
    run(0, SIM_SCEN_LOAD_STEP, false, &r);
    assert_int_equal(r.fault, 0);
    assert_true(fabs(r.speed_mean_rpm - 1500.0) < 5.0);
    assert_true(r.transient_ms >= 1.0 && r.transient_ms <= 20.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_steady_both_arithmetics),
        cmocka_unit_test(test_xy_without_disturbances),
        cmocka_unit_test(test_load_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
