/*
 * Closed-loop regression tests: the real control core (fixed and float, both
 * linked into this one process) through the firmware's drive ISR and the
 * simulator HAL, on short runs of the paper's scenarios.
 *
 * Tolerance bands (stated here, justified in docs/simulator.md):
 *   speed tracking       |mean speed - reference| < 5 r/min in the steady window (DDC, and the
 *                        MPTC-49 / MPTC-13 baselines at lambda 100)
 *   DDC vs MPTC-49       DDC THD and torque ripple below MPTC-49's at lambda 20, 100, 200
 *   DDC over lambda      max/min of DDC THD over lambda 20..200 <= 1.3 (paper: 13.5/12.8 = 1.05)
 *                        and DDC tracks speed at every lambda: the paper's method (core default)
 *                        and, separately, with the core's optional torque guard
 *   transients           acceleration 0->800 r/min 110..200 ms (paper 125/130; the 7 N m limit
 *                        and J give >= 120 ms), reversal 220..380 ms (paper 240; the 8.4 N m
 *                        limit and J give >= 200 ms; MPTC-49, whose torque ripples by 2-3 N m,
 *                        settles in 300..353 ms over seeds 1..6 with either plant integrator),
 *                        rated load step
 *                        1..40 ms (paper 16)
 *   fixed vs float       mean speed within 2 r/min, mean torque within 0.05 N m, THD and torque
 *                        ripple within 25 % of each other
 *   seed                 identical output files for an identical seed; different for another
 *   VV-MPTC              rated load at 1500 r/min (lambda 100, core defaults), both arithmetics:
 *                        speed within 5 r/min, x-y current rms below half MPTC-13's at the same
 *                        point (measured 0.63 against 1.98 A); rated load step 1..40 ms
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "ctl_params.h"
#include "run/sim.h"
#include "sim_run_checked.h"

/* DDC variant for run_case: 0 the paper's method, every improvement off (the regression
 * group); < 0 the core's defaults (the product's DDC, the robustness group); 1 the torque guard
 * on, the other improvements at the core's defaults */
static int guard_on = 0;

static void case_config(int controller, int arith, sim_scenario_t scen, double lambda,
                        sim_config_t *c)
{
    sim_config_default(c);
    c->ddc_torque_guard = guard_on;
    if (guard_on == 0) {
        c->mid_period_angle = 0;
        c->pulse_pattern = 0;
        c->flux_tie_band = 0.0;
        c->light_load_current_a = 0.0;
    }
    c->controller = controller;
    c->arith = arith;
    c->scenario = scen;
    c->lambda = lambda;
    c->out_dir = NULL;
    /* MPTC-49 overloads the drive (peaks near 30 A): watched with the protection out of
     * reach, as in the reproduce comparison; test_sim_faults checks that it trips */
    c->protect = (controller != 1);
}

static void run_case(int controller, int arith, sim_scenario_t scen, double lambda, sim_result_t *r)
{
    sim_config_t c;
    case_config(controller, arith, scen, lambda, &c);
    sim_run_checked(&c, r);
    print_message(
        "%-7s %-5s %-9s lambda %5.0f: speed %7.1f r/min, Te %.3f N m, THD %6.1f %% (h50 %5.1f %%), "
        "ripple %.3f N m, xy %.2f A, f_sw %.0f Hz, transient %.1f ms, %.0fx real time\n",
        r->controller, r->arith, r->scenario, lambda, r->speed_mean_rpm, r->torque_mean_nm,
        r->thd_percent, r->thd50_percent, r->torque_ripple_nm, r->xy_current_rms_a,
        r->switching_freq_hz, r->transient_ms, r->realtime_factor);
}

/* As run_case, with every plant non-ideality off (no dead time, PM harmonics, ADC errors,
 * encoder quantisation). */
static void run_case_ideal(int controller, sim_scenario_t scen, double lambda, sim_result_t *r)
{
    sim_config_t c;
    case_config(controller, 0, scen, lambda, &c);
    c.plant.dead_time_on = c.plant.harmonics_on = c.plant.adc_offset_on = false;
    c.plant.adc_gain_on = c.plant.adc_noise_on = c.plant.encoder_quant_on = false;
    sim_run_checked(&c, r);
}

/* Side by side at lambda 200: the paper's duty search falls into the heavy-flux-weighting trap
 * (torque slides, the speed sags far below the reference); the torque guard keeps it. */
static void test_paper_trap_and_torque_guard(void **state)
{
    sim_result_t paper, guarded;
    (void)state;
    const int saved = guard_on;
    guard_on = 0;
    run_case(0, 0, SIM_SCEN_STEADY, 200.0, &paper);
    guard_on = 1;
    run_case(0, 0, SIM_SCEN_STEADY, 200.0, &guarded);
    guard_on = saved;
    assert_true(paper.speed_mean_rpm < 1400.0);
    assert_true(paper.torque_ripple_nm > 1.0);
    assert_true(fabs(guarded.speed_mean_rpm - 1500.0) < 5.0);
    assert_true(guarded.torque_ripple_nm < 0.4);
}

static void test_speed_tracking(void **state)
{
    sim_result_t r;
    (void)state;
    run_case(0, 0, SIM_SCEN_STEADY, 100.0, &r);
    assert_true(fabs(r.speed_mean_rpm - 1500.0) < 5.0);
    assert_true(fabs(r.torque_mean_nm - (7.0 + 0.001 * 1500.0 * 2.0 * 3.14159265 / 60.0)) < 0.1);
    assert_int_equal(r.final_state, 3); /* RUN */
    assert_int_equal(r.fault, 0);
}

/* The baselines hold rated load at 1500 r/min (the paper ran them there): MPTC-13 at lambda
 * 100, MPTC-49 at lambda 20. At lambda 100 and 200 MPTC-49's x-y currents (12 A rms) turn
 * the PM flux harmonics into a braking torque and the speed sags (1481 and 1379 r/min,
 * docs/results.md); that is the plant, not a controller fault: in the ideal plant it holds. */
static void test_speed_tracking_baselines(void **state)
{
    sim_result_t r13, r49, r49_ideal;
    (void)state;
    run_case(2, 0, SIM_SCEN_STEADY, 100.0, &r13);
    run_case(1, 0, SIM_SCEN_STEADY, 20.0, &r49);
    assert_true(fabs(r13.speed_mean_rpm - 1500.0) < 5.0);
    assert_true(fabs(r49.speed_mean_rpm - 1500.0) < 5.0);
    run_case_ideal(1, SIM_SCEN_STEADY, 100.0, &r49_ideal);
    assert_true(fabs(r49_ideal.speed_mean_rpm - 1500.0) < 5.0);
}

static void test_ddc_beats_mptc49_at_each_lambda(void **state)
{
    static const double lambdas[3] = {20.0, 100.0, 200.0};
    int i;
    (void)state;
    for (i = 0; i < 3; i++) {
        sim_result_t d, m;
        run_case(0, 0, SIM_SCEN_STEADY, lambdas[i], &d);
        run_case(1, 0, SIM_SCEN_STEADY, lambdas[i], &m);
        assert_true(d.thd_percent > 0.0 && m.thd_percent > 0.0);
        assert_true(d.thd_percent < m.thd_percent);
        assert_true(d.torque_ripple_nm < m.torque_ripple_nm);
    }
}

static void test_ddc_tracks_speed_at_each_lambda(void **state)
{
    static const double lambdas[3] = {20.0, 100.0, 200.0};
    int i;
    (void)state;
    for (i = 0; i < 3; i++) {
        sim_result_t d;
        run_case(0, 0, SIM_SCEN_STEADY, lambdas[i], &d);
        assert_true(fabs(d.speed_mean_rpm - 1500.0) <
                    5.0); /* torque control kept at every lambda */
    }
}

static void test_ddc_thd_flat_across_lambda(void **state)
{
    static const double lambdas[3] = {20.0, 100.0, 200.0};
    double lo = 1e30, hi = 0.0;
    int i;
    (void)state;
    for (i = 0; i < 3; i++) {
        sim_result_t d;
        run_case(0, 0, SIM_SCEN_STEADY, lambdas[i], &d);
        lo = fmin(lo, d.thd_percent);
        hi = fmax(hi, d.thd_percent);
    }
    print_message("DDC THD over lambda: %.1f .. %.1f %% (ratio %.2f, band <= 1.3)\n", lo, hi,
                  hi / lo);
    assert_true(hi / lo <= 1.3);
}

static void test_transients_in_bands(void **state)
{
    int ctl;
    (void)state;
    for (ctl = 0; ctl < 2; ctl++) {
        sim_result_t a, v, l;
        run_case(ctl, 0, SIM_SCEN_ACCEL, 100.0, &a);
        assert_true(a.transient_ms >= 110.0 && a.transient_ms <= 200.0);
        run_case(ctl, 0, SIM_SCEN_REVERSAL, 100.0, &v);
        assert_true(v.transient_ms >= 220.0 && v.transient_ms <= 380.0);
        run_case(ctl, 0, SIM_SCEN_LOAD_STEP, 100.0, &l);
        assert_true(l.transient_ms >= 1.0 && l.transient_ms <= 40.0);
        /* the speed's own transient (issue 27): the load step's dip and its recovery, the
         * reversal's overshoot beyond -800 r/min and its settling (the DDC's; MPTC-49 on the
         * board's clipping sensors dips further and may not settle in the run) */
        assert_true(l.speed_peak_error_rpm > 5.0);
        assert_true(v.speed_settle_ms >= v.transient_ms - 1e-9);
        if (ctl == 0) {
            assert_true(l.speed_peak_error_rpm < 100.0);
            assert_true(l.speed_settle_ms >= 0.0 && l.speed_settle_ms < 100.0);
            assert_true(v.speed_peak_error_rpm >= 0.0 && v.speed_peak_error_rpm < 80.0);
        }
    }
}

/* The board's +-20 A sensors clip MPTC-49's phase currents (peaks near 30 A); with a +-50 A
 * span (--sensor-span 50, the drive told the same) no conversion reaches a rail. */
static void test_sensor_span_removes_clipping(void **state)
{
    sim_config_t c;
    sim_result_t board, wide;
    (void)state;
    case_config(1, 0, SIM_SCEN_STEADY, 100.0, &c);
    sim_run_checked(&c, &board);
    c.plant.current_sensor_span_a = 50.0;
    sim_run_checked(&c, &wide);
    print_message("MPTC-49 clipped conversions: %ld at +-20 A, %ld at +-50 A (peak %.1f A)\n",
                  board.adc_clipped, wide.adc_clipped, wide.phase_current_peak_a);
    assert_true(board.adc_clipped > 100);
    assert_int_equal(wide.adc_clipped, 0);
    assert_true(wide.phase_current_peak_a > 20.0);
}

/* Both arithmetics in one process (the float core's symbols are renamed at
 * build time), run one after the other, agreeing within the stated bands. */
static void test_fixed_and_float_in_one_process(void **state)
{
    sim_result_t fx, fl;
    (void)state;
    run_case(0, 0, SIM_SCEN_STEADY, 100.0, &fx);
    run_case(0, 1, SIM_SCEN_STEADY, 100.0, &fl);
    assert_string_equal(fx.arith, "fixed");
    assert_string_equal(fl.arith, "float");
    /* really two different builds: Q24 and float round differently somewhere */
    assert_true(fx.thd_percent != fl.thd_percent || fx.torque_ripple_nm != fl.torque_ripple_nm ||
                fx.switching_freq_hz != fl.switching_freq_hz);
    assert_true(fabs(fx.speed_mean_rpm - fl.speed_mean_rpm) < 2.0);
    assert_true(fabs(fx.torque_mean_nm - fl.torque_mean_nm) < 0.05);
    assert_true(fabs(fx.thd_percent - fl.thd_percent) <
                0.25 * fmax(fx.thd_percent, fl.thd_percent));
    assert_true(fabs(fx.torque_ripple_nm - fl.torque_ripple_nm) <
                0.25 * fmax(fx.torque_ripple_nm, fl.torque_ripple_nm));
    /* and the fixed build again after the float one: state fully re-initialised */
    {
        sim_result_t fx2;
        run_case(0, 0, SIM_SCEN_STEADY, 100.0, &fx2);
        assert_true(fx2.thd_percent == fx.thd_percent);
        assert_true(fx2.torque_ripple_nm == fx.torque_ripple_nm);
    }
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long n;
    if (!f) {
        return NULL;
    }
    (void)fseek(f, 0, SEEK_END);
    n = ftell(f);
    (void)fseek(f, 0, SEEK_SET);
    buf = (char *)malloc((size_t)n + 1u);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    (void)fclose(f);
    *len = (size_t)n;
    return buf;
}

static void run_to_dir(const char *dir, uint64_t seed)
{
    sim_config_t c;
    sim_result_t r;
    char err[200] = "";
    sim_config_default(&c);
    c.scenario = SIM_SCEN_LOAD_STEP;
    c.duration_s = 0.3;
    c.seed = seed;
    c.out_dir = dir;
    assert_int_equal(sim_run(&c, &r, err, sizeof err), 0);
}

static void test_same_seed_identical_output(void **state)
{
    char tmpl[] = "/tmp/sixphase-seed-XXXXXX";
    char d1[600], d2[600], d3[600], p1[700], p2[700], p3[700];
    const char *base = mkdtemp(tmpl);
    static const char *files[2] = {"trace.csv", "fine.csv"};
    int i;
    (void)state;
    assert_non_null(base);
    (void)snprintf(d1, sizeof d1, "%s/a", base);
    (void)snprintf(d2, sizeof d2, "%s/b", base);
    (void)snprintf(d3, sizeof d3, "%s/c", base);
    run_to_dir(d1, 7u);
    run_to_dir(d2, 7u);
    run_to_dir(d3, 8u);
    for (i = 0; i < 2; i++) {
        size_t n1 = 0, n2 = 0, n3 = 0;
        char *b1, *b2, *b3;
        (void)snprintf(p1, sizeof p1, "%s/%s", d1, files[i]);
        (void)snprintf(p2, sizeof p2, "%s/%s", d2, files[i]);
        (void)snprintf(p3, sizeof p3, "%s/%s", d3, files[i]);
        b1 = slurp(p1, &n1);
        b2 = slurp(p2, &n2);
        b3 = slurp(p3, &n3);
        assert_non_null(b1);
        assert_non_null(b2);
        assert_non_null(b3);
        assert_true(n1 > 1000u);
        assert_true(n1 == n2 && memcmp(b1, b2, n1) == 0);
        assert_true(n1 != n3 || memcmp(b1, b3, n1) != 0);
        free(b1);
        free(b2);
        free(b3);
        (void)unlink(p1);
        (void)unlink(p2);
        (void)unlink(p3);
    }
    for (i = 0; i < 3; i++) {
        const char *d = (i == 0) ? d1 : ((i == 1) ? d2 : d3);
        char pm[700];
        (void)snprintf(pm, sizeof pm, "%s/metrics.json", d);
        (void)unlink(pm);
        (void)rmdir(d);
    }
    (void)rmdir(base);
}

/* The core's optional torque guard (docs/improvements.md): with it, DDC must keep torque
 * control, a flat THD and its lead over MPTC-49 at every lambda. */
static void test_ddc_torque_guard_over_lambda(void **state)
{
    static const double lambdas[3] = {20.0, 100.0, 200.0};
    double lo = 1e30, hi = 0.0;
    int i;
    (void)state;
    for (i = 0; i < 3; i++) {
        sim_result_t d, m;
        const int saved = guard_on;
        guard_on = 1;
        run_case(0, 0, SIM_SCEN_STEADY, lambdas[i], &d);
        guard_on = saved;
        run_case(1, 0, SIM_SCEN_STEADY, lambdas[i], &m);
        assert_true(fabs(d.speed_mean_rpm - 1500.0) < 5.0);
        assert_true(d.thd_percent < m.thd_percent);
        assert_true(d.torque_ripple_nm < m.torque_ripple_nm);
        lo = fmin(lo, d.thd_percent);
        hi = fmax(hi, d.thd_percent);
    }
    print_message("DDC + torque guard THD over lambda: %.1f .. %.1f %% (ratio %.2f, band <= 1.3)\n",
                  lo, hi, hi / lo);
    assert_true(hi / lo <= 1.3);
}

/* The zero-vector arrangement with the fewest transitions (docs/improvements.md section 3)
 * against the earlier rule, both with the torque guard, mean of seeds 1..3: six-phase THD
 * lower at lambda 20, 100 and 200 (measured 0.8-1.6 pp), switching frequency within 2 %. */
static void test_fewest_transitions_lowers_thd(void **state)
{
    static const double lambdas[3] = {20.0, 100.0, 200.0};
    int i, fewest, seed;
    (void)state;
    for (i = 0; i < 3; i++) {
        double thd[2] = {0.0, 0.0}, fsw[2] = {0.0, 0.0};
        for (fewest = 0; fewest <= 1; fewest++) {
            for (seed = 1; seed <= 3; seed++) {
                sim_config_t c;
                sim_result_t r;
                case_config(0, 0, SIM_SCEN_STEADY, lambdas[i], &c);
                c.ddc_torque_guard = 1;
                c.mid_period_angle = 0;
                c.pulse_pattern = fewest; /* by ones, or fewest transitions (u00 or u77) */
                c.seed = (uint64_t)seed;
                sim_run_checked(&c, &r);
                thd[fewest] += r.thd_percent / 3.0;
                fsw[fewest] += r.switching_freq_hz / 3.0;
            }
        }
        print_message("lambda %3.0f: THD %.2f -> %.2f %%, f_sw %.0f -> %.0f Hz\n", lambdas[i],
                      thd[0], thd[1], fsw[0], fsw[1]);
        assert_true(thd[1] < thd[0]);
        assert_true(fabs(fsw[1] - fsw[0]) < 0.02 * fsw[0]);
    }
}

/* Issue 13's goals for the product's DDC at 1500 r/min, rated load, 10 kHz, lambda 20..200 in
 * steps of 20, each figure the mean of seeds 1..3 (docs/reproduce/report.md section 8): speed
 * held, torque ripple <= 0.22 N m, six-phase THD within 1.0 pp over lambda, THD and ripple
 * below the paper's DDC at every lambda, and a switching frequency not above the paper's
 * DDC's where that one keeps torque control (lambda 20..80, its ripple 0.21..0.28 N m; from
 * lambda 100 on its ripple is 0.39 N m or more and it switches less because it has lost it). */
static void test_product_ddc_goals_over_lambda(void **state)
{
    double thd_lo = 1e30, thd_hi = 0.0;
    int li, variant, seed;
    (void)state;
    for (li = 1; li <= 10; li++) {
        double thd[2] = {0.0, 0.0}, ripple[2] = {0.0, 0.0}, fsw[2] = {0.0, 0.0}, slowest = 1e30;
        for (variant = 0; variant <= 1; variant++) { /* 0 the paper's, 1 the product's */
            for (seed = 1; seed <= 3; seed++) {
                sim_config_t c;
                sim_result_t r;
                const int saved = guard_on;
                guard_on = variant ? -1 : 0;
                case_config(0, 0, SIM_SCEN_STEADY, 20.0 * li, &c);
                guard_on = saved;
                /* the THD improvements on trial, not the light-load current (it acts below 1 N m
                 * only; over seeds 1..12 at lambda 40 THD 24.80 % with it, 24.82 % without, the
                 * paper's 24.89 %: its start-up moves a 3-seed mean by noise of 0.4 pp) */
                c.light_load_current_a = 0.0;
                c.seed = (uint64_t)seed;
                sim_run_checked(&c, &r);
                thd[variant] += r.thd_percent / 3.0;
                ripple[variant] += r.torque_ripple_nm / 3.0;
                fsw[variant] += r.switching_freq_hz / 3.0;
                if (variant == 1) {
                    slowest = fmin(slowest, r.speed_mean_rpm);
                }
            }
        }
        print_message("lambda %3d: paper THD %.2f %% ripple %.3f N m f_sw %.0f Hz; product THD "
                      "%.2f %% ripple %.3f N m f_sw %.0f Hz, slowest %.1f r/min\n",
                      20 * li, thd[0], ripple[0], fsw[0], thd[1], ripple[1], fsw[1], slowest);
        assert_true(fabs(slowest - 1500.0) < 5.0);
        assert_true(ripple[1] <= 0.22);
        assert_true(thd[1] < thd[0]);
        assert_true(ripple[1] < ripple[0]);
        if (li <= 4) {
            assert_true(fsw[1] <= fsw[0]);
        }
        thd_lo = fmin(thd_lo, thd[1]);
        thd_hi = fmax(thd_hi, thd[1]);
    }
    print_message("product THD over lambda %.2f .. %.2f %% (spread %.2f pp, goal <= 1.0)\n", thd_lo,
                  thd_hi, thd_hi - thd_lo);
    assert_true(thd_hi - thd_lo <= 1.0);
}

/* Built twice (tests/sim/CMakeLists.txt): group 1 = regression of the simulator with the
 * core and the paper's method (test_sim_closed_loop), group 2 = the paper's robustness
 * claims checked on the product's DDC, and the paper's method beside it
 * (test_sim_lambda_robustness), so CTest shows them separately. */
/* VV-MPTC at rated load, both arithmetics: the speed held, the x-y currents well below
 * MPTC-13's (whose candidates apply the G4 states' x-y voltage); the rated load step. */
static void test_vvmptc_rated_load(void **state)
{
    int arith;
    sim_result_t step;
    (void)state;
    for (arith = 0; arith < 2; arith++) {
        sim_result_t vv;
        sim_result_t m13;
        run_case(CTL_CONTROLLER_VVMPTC, arith, SIM_SCEN_STEADY, 100.0, &vv);
        run_case(CTL_CONTROLLER_MPTC13, arith, SIM_SCEN_STEADY, 100.0, &m13);
        assert_true(fabs(vv.speed_mean_rpm - 1500.0) < 5.0);
        assert_int_equal(vv.final_state, 3); /* RUN */
        assert_int_equal(vv.fault, 0);
        assert_true(vv.xy_current_rms_a < 0.5 * m13.xy_current_rms_a);
        assert_true(vv.thd_percent < m13.thd_percent);
    }
    run_case(CTL_CONTROLLER_VVMPTC, 0, SIM_SCEN_LOAD_STEP, 100.0, &step);
    assert_true(step.transient_ms >= 1.0 && step.transient_ms <= 40.0);
    assert_int_equal(step.fault, 0);
}

#ifndef SIM_TEST_GROUP
#define SIM_TEST_GROUP 1
#endif

int main(void)
{
#if SIM_TEST_GROUP == 1
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_speed_tracking),
        cmocka_unit_test(test_sensor_span_removes_clipping),
        cmocka_unit_test(test_fixed_and_float_in_one_process),
        cmocka_unit_test(test_same_seed_identical_output),
        cmocka_unit_test(test_transients_in_bands),
        cmocka_unit_test(test_ddc_beats_mptc49_at_each_lambda),
        cmocka_unit_test(test_ddc_torque_guard_over_lambda),
    };
    (void)test_ddc_tracks_speed_at_each_lambda;
    (void)test_ddc_thd_flat_across_lambda;
    (void)test_speed_tracking_baselines;
    (void)test_paper_trap_and_torque_guard;
    (void)test_fewest_transitions_lowers_thd;
    (void)test_product_ddc_goals_over_lambda;
    (void)test_vvmptc_rated_load;
#else
    /* the product's DDC (core defaults: torque guard on) against the paper's claims */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ddc_tracks_speed_at_each_lambda),
        cmocka_unit_test(test_ddc_thd_flat_across_lambda),
        cmocka_unit_test(test_speed_tracking_baselines),
        cmocka_unit_test(test_paper_trap_and_torque_guard),
        cmocka_unit_test(test_fewest_transitions_lowers_thd),
        cmocka_unit_test(test_product_ddc_goals_over_lambda),
        cmocka_unit_test(test_vvmptc_rated_load),
    };
    (void)test_sensor_span_removes_clipping;
    guard_on = -1;
    (void)test_speed_tracking;
    (void)test_fixed_and_float_in_one_process;
    (void)test_same_seed_identical_output;
    (void)test_transients_in_bands;
    (void)test_ddc_beats_mptc49_at_each_lambda;
    (void)test_ddc_torque_guard_over_lambda;
#endif
    return cmocka_run_group_tests(tests, NULL, NULL);
}
