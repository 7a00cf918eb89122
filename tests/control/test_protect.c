/* Protection: each fault's threshold and filter, latching, records, clearing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_machine.h"
#include "ctl_protect.h"
#include "ctl_pu.h"
#include "hal_board.h"
#include "test_support.h"
#include "vsd_reference.h"
#include "ctl_qmath.h"

static ctl_protect_t prot;
static ctl_protect_limits_t limits;
static ctl_model_t model; /* the reference machine's: the inputs' torque */

/* The board's control period and ADC scaling (hal_board.h). */
#define TS_S (1.0 / HAL_BOARD_PWM_HZ)
#define ADC_ZERO ((int16_t)HAL_BOARD_CURRENT_ZERO_COUNTS)

static int setup(void **state)
{
    ctl_protect_settings_t s;
    (void)state;
    ctl_protect_settings_default(&s);
    assert_true(ctl_model_init(&model, (float)CTL_MACHINE_R_OHM, (float)CTL_MACHINE_LD_H,
                               (float)CTL_MACHINE_LQ_H, (float)CTL_MACHINE_LXY_H,
                               (float)CTL_MACHINE_PSI_F_WB, CTL_MACHINE_POLE_PAIRS, (float)TS_S));
    ctl_protect_limits_build(&limits, &s, (float)TS_S, 3, 0.01f);
    ctl_protect_init(&prot);
    return 0;
}

static ctl_q amps(double a) { return ctl_from_float((float)(a / CTL_BASE_CURRENT_A)); }

/* The q-axis current (i_d = 0) of the reference machine that gives torque_nm: Te = 3 Pn psi_f i_q
 * (T_b = 3 psi_b I_b per pole pair, ctl_pu.h). */
static ctl_q iq_for_torque(double torque_nm)
{
    return amps(torque_nm / (3.0 * CTL_MACHINE_POLE_PAIRS * CTL_MACHINE_PSI_F_WB));
}

/* A healthy running sample: balanced 3 A currents at angle theta, 540 V, 1500 r/min. */
static ctl_protect_input_t healthy(int32_t n)
{
    ctl_protect_input_t in;
    const double w = 1500.0 * TEST_PI / 30.0 * 3.0;
    const double theta = w * TS_S * (double)n;
    int16_t k;
    for (k = 0; k < 6; k++) {
        const double i = 3.0 * cos(theta - vsd_ref_phase_deg[k] * TEST_PI / 180.0);
        in.i_phase[k] = amps(i);
        in.raw_phase[k] =
            (int16_t)(HAL_BOARD_CURRENT_ZERO_COUNTS + i / HAL_BOARD_CURRENT_A_PER_COUNT);
    }
    in.vdc = ctl_from_float((float)(540.0 / CTL_BASE_VOLTAGE_V));
    in.raw_vdc = (int16_t)(540.0 / HAL_BOARD_VDC_V_PER_COUNT);
    in.theta_e = ctl_wrap_turn(ctl_from_float((float)fmod(theta / (2.0 * TEST_PI), 1.0)));
    in.omega_e = ctl_from_float((float)(w / CTL_BASE_OMEGA_RAD_S));
    in.i_d = CTL_Q(0.0);
    in.i_q = iq_for_torque(7.0);
    in.model = &model;
    in.encoder_healthy = true;
    in.overrun = false;
    in.hw_trip = false;
    in.running = true;
    in.currents_calibrated = true;
    in.xy_held = false; /* the windowed check alone; the fast one has tests of its own */
    return in;
}

/* Run healthy periods, then the faulty ones from `modify`; return the period (1-based, from
 * the first faulty one) at which `fault` was first reported, or -1. */
typedef void (*modify_fn)(ctl_protect_input_t *in, int32_t n);

static int32_t periods_to_detect(modify_fn modify, uint16_t fault, int32_t max_periods)
{
    int32_t n;
    for (n = 0; n < 500; n++) {
        const ctl_protect_input_t in = healthy(n);
        assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)), 0);
    }
    for (n = 0; n < max_periods; n++) {
        ctl_protect_input_t in = healthy(500 + n);
        modify(&in, n);
        if ((ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)) & fault) != 0u) {
            return n + 1;
        }
    }
    return -1;
}

static void overcurrent(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->i_phase[2] = amps(-15.2);
}
static void dc_over(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->vdc = ctl_from_float((float)(730.0 / CTL_BASE_VOLTAGE_V));
}
static void dc_under(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->vdc = ctl_from_float((float)(340.0 / CTL_BASE_VOLTAGE_V));
}
static void overspeed(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->omega_e = ctl_from_float((float)(2100.0 * TEST_PI / 30.0 * 3.0 / CTL_BASE_OMEGA_RAD_S));
}
static void sum_error(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->i_phase[4] = ctl_add(in->i_phase[4], amps(2.5));
}
static void sum_error_uncalibrated(ctl_protect_input_t *in, int32_t n)
{
    sum_error(in, n);
    in->running = false;
    in->currents_calibrated = false;
}
static void rail(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->raw_phase[5] = 4095;
}
static void dc_link_rail(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->raw_vdc = 4095;
}
/* a DC link that is off: 0 V, 0 counts, at standstill */
static void dc_link_off(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->raw_vdc = 0;
    in->vdc = CTL_Q(0.0);
    in->running = false;
}
static ctl_q frozen_theta;
static void stopped_encoder(ctl_protect_input_t *in, int32_t n)
{
    if (n == 0) {
        frozen_theta = in->theta_e;
    }
    in->theta_e = frozen_theta;
    in->omega_e = CTL_Q(0.0);
}
static void angle_jump(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->theta_e = ctl_wrap_turn(ctl_add(in->theta_e, CTL_Q(0.25)));
}
static void unhealthy_encoder(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->encoder_healthy = false;
}
static void stuck_adc(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    in->raw_phase[1] = 2500;
}
static void open_phase(ctl_protect_input_t *in, int32_t n)
{
    (void)n;
    /* phase D open: E and F carry equal and opposite currents */
    in->i_phase[4] = ctl_sub(in->i_phase[4], ctl_mul(in->i_phase[3], CTL_Q(-0.5)));
    in->i_phase[5] = ctl_sub(CTL_Q(0.0), in->i_phase[4]);
    in->i_phase[3] = CTL_Q(0.0);
}
static void overrun(ctl_protect_input_t *in, int32_t n) { in->overrun = n == 3; }

static void test_detection_latency_of_each_fault(void **state)
{
    (void)state;
    /* threshold and filter per fault: the period of detection is the filter length */
    assert_int_equal(periods_to_detect(overcurrent, CTL_FAULT_OVERCURRENT, 10), 1);
    setup(NULL);
    assert_int_equal(periods_to_detect(dc_over, CTL_FAULT_DC_OVERVOLTAGE, 10), 3);
    setup(NULL);
    assert_int_equal(periods_to_detect(dc_under, CTL_FAULT_DC_UNDERVOLTAGE, 20), 10);
    setup(NULL);
    assert_int_equal(periods_to_detect(overspeed, CTL_FAULT_OVERSPEED, 10), 5);
    setup(NULL);
    assert_int_equal(periods_to_detect(sum_error, CTL_FAULT_CURRENT_SUM, 10), 5);
    setup(NULL);
    /* during the offset calibration a set's sum is the offset error: left to ADC_OFFSET */
    assert_int_equal(periods_to_detect(sum_error_uncalibrated, CTL_FAULT_CURRENT_SUM, 100), -1);
    setup(NULL);
    assert_int_equal(periods_to_detect(rail, CTL_FAULT_ADC_RAIL, 10), 3);
    setup(NULL);
    assert_int_equal(periods_to_detect(dc_link_rail, CTL_FAULT_ADC_RAIL, 10), 3);
    setup(NULL);
    /* bring-up with the link off: no fault of any kind, the drive may calibrate and wait */
    assert_int_equal(periods_to_detect(dc_link_off, 0xFFFFu, 2000), -1);
    setup(NULL);
    assert_int_equal(periods_to_detect(unhealthy_encoder, CTL_FAULT_ENCODER, 10), 1);
    setup(NULL);
    assert_int_equal(periods_to_detect(angle_jump, CTL_FAULT_ENCODER, 10), 1);
    setup(NULL);
    /* stuck: 50 repeats of the same word, i.e. the 51st frozen sample */
    assert_int_equal(periods_to_detect(stuck_adc, CTL_FAULT_ADC_STUCK, 1000), 51);
    setup(NULL);
    assert_int_equal(periods_to_detect(overrun, CTL_FAULT_OVERRUN, 10), 4);
}

/* A stopped encoder under 7 N m: a free rotor (J = 0.01) turns 90 electrical degrees in
 * about 37 ms; detection must come by then (plus one window of margin: 45 ms). */
static void test_stopped_encoder_under_torque(void **state)
{
    int32_t n;
    (void)state;
    n = periods_to_detect(stopped_encoder, CTL_FAULT_ENCODER, 2000);
    print_message("stopped encoder detected after %d periods\n", n);
    assert_in_range(n, 300, 450);
}

/* Open phase: detected at the end of the first full 40 ms window after the fault. */
static void test_open_phase(void **state)
{
    int32_t n;
    (void)state;
    n = periods_to_detect(open_phase, CTL_FAULT_OPEN_PHASE, 2000);
    assert_in_range(n, 1, 2 * CTL_PROTECT_OPEN_PHASE_WINDOW);
}

/* The detection names the open phase (the drive isolates that leg to ride through). */
static void test_open_phase_names_the_phase(void **state)
{
    (void)state;
    assert_in_range(periods_to_detect(open_phase, CTL_FAULT_OPEN_PHASE, 2000), 1,
                    2 * CTL_PROTECT_OPEN_PHASE_WINDOW);
    assert_int_equal(ctl_protect_open_phase(&prot), 3);
}

/* Phase A isolated, minimum-loss currents: 3 A alpha-beta current, the x-y currents' forced part
 * only, so the healthy phases carry 0.61 to 1.27 times as much as a healthy phase would. A second
 * open phase (D: E and F then carry equal and opposite currents) is set by second_open. */
static int32_t second_open = -1;
static void postfault_currents(ctl_protect_input_t *in, int32_t n)
{
    const double theta = 1500.0 * TEST_PI / 30.0 * 3.0 * TS_S * (double)(500 + n);
    const double ia = 3.0 * cos(theta);
    const double ib = 3.0 * sin(theta);
    double i[6];
    int k;
    for (k = 0; k < 6; k++) {
        const double th = vsd_ref_phase_deg[k] * TEST_PI / 180.0;
        /* i_x = -i_alpha, i_y = 0 (phase A's c_xy is (1, 0)) */
        i[k] = ia * cos(th) + ib * sin(th) - ia * cos(5.0 * th);
    }
    if (second_open >= 0 && n >= second_open) {
        i[4] += 0.5 * i[3];
        i[5] = -i[4];
        i[3] = 0.0;
    }
    for (k = 0; k < 6; k++) {
        in->i_phase[k] = amps(i[k]);
    }
}

/* With phase A isolated the check judges the other five against their own mean: the unequal
 * post-fault currents pass, a second open phase is found and named. */
static void test_isolated_phase_is_not_judged(void **state)
{
    int32_t n;
    (void)state;
    ctl_protect_quiet(&prot, 0x01u);
    second_open = -1;
    assert_int_equal(periods_to_detect(postfault_currents, CTL_FAULT_OPEN_PHASE,
                                       10 * CTL_PROTECT_OPEN_PHASE_WINDOW),
                     -1);
    setup(NULL);
    ctl_protect_quiet(&prot, 0x01u);
    second_open = 3 * CTL_PROTECT_OPEN_PHASE_WINDOW;
    n = periods_to_detect(postfault_currents, CTL_FAULT_OPEN_PHASE,
                          10 * CTL_PROTECT_OPEN_PHASE_WINDOW);
    assert_in_range(n, second_open + 1, second_open + 2 * CTL_PROTECT_OPEN_PHASE_WINDOW);
    assert_int_equal(ctl_protect_open_phase(&prot), 3);
    /* without the isolated phase ignored, A would have been found at once */
    setup(NULL);
    second_open = -1;
    assert_in_range(periods_to_detect(postfault_currents, CTL_FAULT_OPEN_PHASE, 2000), 1,
                    2 * CTL_PROTECT_OPEN_PHASE_WINDOW);
    assert_int_equal(ctl_protect_open_phase(&prot), 0);
}

/* An isolated phase's sensor may read one word for good (no current, little noise): that is
 * neither a stuck converter nor, for the clear, a dead one. Healthy sensors still are judged. */
static void test_isolated_phase_word_may_rest(void **state)
{
    int32_t n;
    (void)state;
    ctl_protect_quiet(&prot, 0x01u);
    second_open = -1;
    for (n = 0; n < 2000; n++) {
        ctl_protect_input_t in = healthy(500 + n);
        postfault_currents(&in, n);
        in.raw_phase[0] = ADC_ZERO; /* phase A's word at rest */
        assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)), 0);
    }
    assert_true(ctl_protect_converter_alive(&prot));
    for (n = 0; n < 60; n++) {
        ctl_protect_input_t in = healthy(2500 + n);
        postfault_currents(&in, n);
        in.raw_phase[0] = ADC_ZERO;
        in.raw_phase[3] = 2500; /* a healthy phase's word frozen: stuck */
        if (ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)) != 0u) {
            break;
        }
    }
    assert_int_equal(prot.latched, CTL_FAULT_ADC_STUCK);
}

/* The outputs are off after an ADC_STUCK trip: the frozen channel keeps its word, the others
 * read their offsets with noise. */
static ctl_protect_input_t stopped_with_frozen_word(int32_t n)
{
    ctl_protect_input_t in = healthy(0);
    int16_t k;
    for (k = 0; k < 6; k++) {
        in.i_phase[k] = CTL_Q(0.0);
        in.raw_phase[k] = (int16_t)(ADC_ZERO + (n + k) % 3 - 1);
    }
    in.raw_phase[1] = 2500;
    in.running = false;
    return in;
}

/* A dead converter is never cleared back into RUN: the clear leaves the channels' history
 * alone, and the converter counts as alive only once every word changed since the trip.
 * Before: the clear reset the history, so the frozen word counted as a fresh change and the
 * drive could be cleared and restarted into 50 blind periods again and again. */
static void test_frozen_converter_stays_dead_across_clears(void **state)
{
    int32_t n, cycle;
    (void)state;
    assert_int_equal(periods_to_detect(stuck_adc, CTL_FAULT_ADC_STUCK, 1000), 51);
    for (cycle = 0; cycle < 20; cycle++) {
        for (n = 0; n < 10; n++) {
            const ctl_protect_input_t in = stopped_with_frozen_word(n);
            (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.0), 0, CTL_Q(0.0));
        }
        assert_false(ctl_protect_converter_alive(&prot));
        assert_true(ctl_protect_clear(&prot)); /* nothing active: the drive asks the converter */
        assert_int_equal(prot.latched, 0u);
    }
    /* the word moves again (a converter that recovered): alive */
    for (n = 0; n < 3; n++) {
        ctl_protect_input_t in = stopped_with_frozen_word(n);
        in.raw_phase[1] = (int16_t)(2047 + n);
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.0), 0, CTL_Q(0.0));
    }
    assert_true(ctl_protect_converter_alive(&prot));
}

/* RUN at standstill with no torque, phase B's word frozen, the others noisy. */
static ctl_protect_input_t running_with_frozen_word(int32_t n)
{
    ctl_protect_input_t in = stopped_with_frozen_word(n);
    in.running = true;
    in.omega_e = CTL_Q(0.0);
    in.i_d = CTL_Q(0.0);
    in.i_q = CTL_Q(0.0);
    return in;
}

/* A converter that froze while no current flowed (the drive idle or at no load) reads no
 * current afterwards either: the stuck check judges the phases an active state drove in the
 * last period (their windings saw at least a third of the link), not only those measured to
 * carry current. Before, nothing was judged: in the simulator, at no load with the ADC frozen
 * at 0.1 s the drive ran blind (phase currents up to 16 A, torque swinging +-10 N m, no fault;
 * now ADC_STUCK 8.7 ms after the freeze). A zero state, a set at rest or a short active part
 * is no evidence. */
static void test_frozen_at_idle_found_by_the_driven_phases(void **state)
{
    int32_t n;
    uint16_t f = 0u;
    (void)state;
    for (n = 0; n < 200; n++) { /* zero states, and set ABC at rest with DEF driven, long */
        const ctl_protect_input_t in = running_with_frozen_word(n);
        assert_int_equal(
            ctl_protect_check(&prot, &limits, &in, CTL_Q(0.0), (n & 1) ? 0 : 077, CTL_Q(1.0)), 0u);
        assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.0), 004, CTL_Q(1.0)),
                         0u); /* phase B (set ABC) frozen, ABC at rest: not judged */
        assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.0), 040, CTL_Q(0.05)),
                         0u); /* active for 5 % of the period only */
    }
    for (n = 0; n < 60 && f == 0u; n++) {
        const ctl_protect_input_t in = running_with_frozen_word(n);
        f = ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
    }
    assert_int_equal(f, CTL_FAULT_ADC_STUCK);
    assert_int_equal(n, 50); /* the word was frozen already: 50 judged repeats */
}

/* A fault the drive rode through is unlatched; the next one is a new root cause with a record of
 * its own (the first one's record stays). */
static void test_accepted_fault_records_again(void **state)
{
    ctl_fault_record_t r;
    (void)state;
    assert_true(periods_to_detect(open_phase, CTL_FAULT_OPEN_PHASE, 2000) > 0);
    assert_int_equal(ctl_protect_log_pending(&prot), 1);
    ctl_protect_accept(&prot, CTL_FAULT_OPEN_PHASE);
    assert_int_equal(prot.latched, 0u);
    assert_true(periods_to_detect(open_phase, CTL_FAULT_OPEN_PHASE, 2000) > 0);
    assert_int_equal(ctl_protect_log_pending(&prot), 2);
    assert_true(ctl_protect_read_record(&prot, &r));
    assert_int_equal(r.faults, CTL_FAULT_OPEN_PHASE);
    assert_true(ctl_protect_read_record(&prot, &r));
    assert_int_equal(r.faults, CTL_FAULT_OPEN_PHASE);
}

/* Near standstill under torque (a reversal crossing zero speed: 5 r/min, 7 A at right angles to
 * phase A's axis) phase A carries almost nothing and the current vector barely turns: no phase is
 * judged open until the window spans an electrical turn; a window that never does is dropped. */
static void slow_stationary_vector(ctl_protect_input_t *in, int32_t n)
{
    const double w = 5.0 * TEST_PI / 30.0 * 3.0; /* electrical rad/s */
    const double theta = 1.5707963 + w * TS_S * (double)n;
    int k;
    for (k = 0; k < 6; k++) {
        in->i_phase[k] = amps(7.0 * cos(theta - vsd_ref_phase_deg[k] * TEST_PI / 180.0));
    }
    in->theta_e = ctl_wrap_turn(ctl_from_float((float)fmod(theta / (2.0 * TEST_PI), 1.0)));
    in->omega_e = ctl_from_float((float)(w / CTL_BASE_OMEGA_RAD_S));
}

/* Commissioning's mechanics step: the current vector stands with phase A at right angles to it
 * (0.2 s, the rotor at rest), then the current is switched off while the rotor coasts at
 * 300 r/min. The rotor's turn is not the current's: before, the window completed its turn on the
 * coasting rotor and judged the standing part (OPEN_PHASE, phase A); now a turn counts only while
 * current flows. */
static void stand_then_coast(ctl_protect_input_t *in, int32_t n)
{
    int k;
    for (k = 0; k < 6; k++) { /* at rest at 90 degrees: phase A carries nothing */
        in->i_phase[k] = amps(7.0 * cos((90.0 - vsd_ref_phase_deg[k]) * TEST_PI / 180.0));
    }
    in->omega_e = CTL_Q(0.0);
    if (n >= 2000) {
        in->omega_e =
            ctl_from_float((float)(300.0 / 60.0 * 2.0 * TEST_PI * 3.0 / CTL_BASE_OMEGA_RAD_S));
        for (k = 0; k < 6; k++) {
            in->i_phase[k] = amps((k % 2 == 0) ? 0.01 : -0.01); /* the sensors' noise */
        }
    }
}

static void test_open_phase_needs_the_current_to_turn(void **state)
{
    (void)state;
    assert_int_equal(periods_to_detect(stand_then_coast, CTL_FAULT_OPEN_PHASE,
                                       20 * CTL_PROTECT_OPEN_PHASE_WINDOW),
                     -1);
}

static void test_open_phase_not_judged_without_a_turn(void **state)
{
    (void)state;
    /* phase A's current ~ cos(90 deg): under 0.3 A of 7 A for the whole 20 * window */
    assert_int_equal(periods_to_detect(slow_stationary_vector, CTL_FAULT_OPEN_PHASE,
                                       20 * CTL_PROTECT_OPEN_PHASE_WINDOW),
                     -1);
}

/* The fast check (the x-y residual, with the DDC's six-leg step in force): a reversal's zero
 * crossing, the current vector at rest, phase D opening. The windowed check cannot judge without
 * a turn; the fast one finds D in its third window, whatever the speed. */
static void stationary_xy_held(ctl_protect_input_t *in, int32_t n)
{
    slow_stationary_vector(in, n);
    in->xy_held = true;
}

static void stationary_open_d(ctl_protect_input_t *in, int32_t n)
{
    stationary_xy_held(in, n);
    open_phase(in, n);
}

static void stationary_open_d_free(ctl_protect_input_t *in, int32_t n)
{
    stationary_open_d(in, n);
    in->xy_held = false;
}

/* Periods of `modify` (from the first) until OPEN_PHASE, or -1; nothing before them. */
static int32_t periods_to_open_phase(modify_fn modify, int32_t max_periods)
{
    int32_t n;
    for (n = 0; n < max_periods; n++) {
        ctl_protect_input_t in = healthy(n);
        modify(&in, n);
        if ((ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)) &
             CTL_FAULT_OPEN_PHASE) != 0u) {
            return n + 1;
        }
    }
    return -1;
}

static void test_fast_open_phase_without_a_turn(void **state)
{
    int32_t n;
    (void)state;
    assert_int_equal(
        periods_to_open_phase(stationary_xy_held, 20 * CTL_PROTECT_OPEN_PHASE_FAST_WINDOW),
        -1); /* healthy: nothing */
    n = periods_to_open_phase(stationary_open_d, 1000);
    print_message("fast check: D found after %ld periods\n", (long)n);
    assert_true(n > 0 && n <= (CTL_PROTECT_OPEN_PHASE_FAST_WINDOWS + 1) *
                                  CTL_PROTECT_OPEN_PHASE_FAST_WINDOW);
    assert_int_equal(ctl_protect_open_phase(&prot), 3);
}

/* Without the DDC's step in force (a phase check's x-y test current, an MPTC baseline) or with a
 * leg isolated, the fast check judges nothing. */
static void test_fast_open_phase_needs_the_xy_held(void **state)
{
    (void)state;
    assert_int_equal(
        periods_to_open_phase(stationary_open_d_free, 20 * CTL_PROTECT_OPEN_PHASE_FAST_WINDOW), -1);
    ctl_protect_quiet(&prot, 1u); /* A isolated */
    assert_int_equal(
        periods_to_open_phase(stationary_open_d, 20 * CTL_PROTECT_OPEN_PHASE_FAST_WINDOW), -1);
}

/* Healthy operation over a long run never reports anything (no false trips). */
static void test_no_false_trip(void **state)
{
    int32_t n;
    (void)state;
    for (n = 0; n < 20000; n++) {
        ctl_protect_input_t in = healthy(n);
        in.xy_held = (n >= 10000); /* the windowed check alone, then both */
        assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)), 0);
    }
    assert_int_equal(prot.latched, 0);
}

/* Faults in one period all latch and go into one record; a full log keeps the oldest. */
static void test_records_and_latch(void **state)
{
    ctl_protect_input_t in = healthy(0);
    ctl_fault_record_t r;
    uint16_t f;
    int16_t k;
    (void)state;
    in.i_phase[0] = amps(16.0);
    in.overrun = true;
    in.hw_trip = true;
    f = ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
    assert_int_equal(f & (CTL_FAULT_OVERCURRENT | CTL_FAULT_OVERRUN | CTL_FAULT_HW_TRIP),
                     CTL_FAULT_OVERCURRENT | CTL_FAULT_OVERRUN | CTL_FAULT_HW_TRIP);
    assert_int_equal(ctl_protect_log_pending(&prot), 1);
    /* the same faults again: latched already, no new record */
    (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
    assert_int_equal(ctl_protect_log_pending(&prot), 1);
    /* while a condition is active the latch cannot be cleared */
    assert_false(ctl_protect_clear(&prot));
    in = healthy(1);
    (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
    assert_true(ctl_protect_clear(&prot));
    assert_int_equal(prot.latched, 0);
    /* fill the log: 8 kept, the rest counted as dropped */
    for (k = 0; k < CTL_PROTECT_LOG_SIZE + 3; k++) {
        in = healthy(2 + k);
        in.overrun = true;
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
        in = healthy(2 + k);
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
        assert_true(ctl_protect_clear(&prot));
    }
    assert_int_equal(ctl_protect_log_pending(&prot), CTL_PROTECT_LOG_SIZE);
    assert_int_equal(prot.log_dropped, 4);
    assert_true(ctl_protect_read_record(&prot, &r));
    assert_int_equal(r.faults & CTL_FAULT_OVERCURRENT, CTL_FAULT_OVERCURRENT);
    assert_int_equal(r.faults & CTL_FAULT_HW_TRIP, CTL_FAULT_HW_TRIP);
    assert_int_equal(r.vector, 044);
    assert_int_equal(r.i_phase[0], amps(16.0));
    assert_int_equal(r.period, 1);
    for (k = 1; k < CTL_PROTECT_LOG_SIZE; k++) {
        assert_true(ctl_protect_read_record(&prot, &r));
        assert_int_equal(r.faults, CTL_FAULT_OVERRUN);
    }
    assert_false(ctl_protect_read_record(&prot, &r));
}

/* A full log still records a fault that is new since the last clear (it replaces the newest
 * record; the oldest, the first root cause, stays); the drop counter saturates. */
static void test_full_log_keeps_a_new_root_cause(void **state)
{
    ctl_protect_input_t in;
    ctl_fault_record_t r;
    int32_t k;
    (void)state;
    for (k = 0; k < 9; k++) { /* nine over-voltage episodes, each cleared, nothing read */
        in = healthy(k);
        in.vdc = ctl_from_float((float)(760.0 / CTL_BASE_VOLTAGE_V));
        in.raw_vdc = 3891;
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
        in = healthy(k);
        (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
        assert_true(ctl_protect_clear(&prot));
    }
    in = healthy(100);
    in.hw_trip = true;
    assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)),
                     CTL_FAULT_HW_TRIP);
    assert_int_equal(ctl_protect_log_pending(&prot), CTL_PROTECT_LOG_SIZE);
    assert_int_equal(prot.log_dropped, 2);
    assert_true(ctl_protect_read_record(&prot, &r));
    assert_int_equal(r.faults, CTL_FAULT_DC_OVERVOLTAGE); /* the first root cause */
    for (k = 1; k < CTL_PROTECT_LOG_SIZE; k++) {
        assert_true(ctl_protect_read_record(&prot, &r));
    }
    assert_int_equal(r.faults, CTL_FAULT_HW_TRIP); /* the new one, newest */
    assert_false(ctl_protect_read_record(&prot, &r));

    /* 70000 more episodes with a full log: the counter stops at its maximum */
    in = healthy(101);
    (void)ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6));
    for (k = 0; k < CTL_PROTECT_LOG_SIZE; k++) {
        ctl_protect_raise(&prot, (uint16_t)(1u << k), &in);
    }
    for (k = 0; k < 70000; k++) {
        assert_true(ctl_protect_clear(&prot));
        ctl_protect_raise(&prot, CTL_FAULT_ADC_OFFSET, &in);
    }
    assert_int_equal(prot.log_dropped, UINT16_MAX);
}

static void test_raise_from_outside(void **state)
{
    const ctl_protect_input_t in = healthy(0);
    ctl_fault_record_t r;
    (void)state;
    ctl_protect_raise(&prot, CTL_FAULT_ADC_OFFSET, &in);
    assert_int_equal(prot.latched, CTL_FAULT_ADC_OFFSET);
    assert_true(ctl_protect_read_record(&prot, &r));
    assert_int_equal(r.faults, CTL_FAULT_ADC_OFFSET);
    assert_true(ctl_protect_clear(&prot));
}

static void test_not_a_number(void **state)
{
    ctl_protect_input_t in = healthy(0);
    (void)state;
#if CTL_MATH_FLOAT
    in.i_phase[3] = (float)NAN;
    assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)) &
                         CTL_FAULT_MEASUREMENT,
                     CTL_FAULT_MEASUREMENT);
#else
    assert_int_equal(ctl_protect_check(&prot, &limits, &in, CTL_Q(0.3), 044, CTL_Q(0.6)), 0);
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_detection_latency_of_each_fault, setup),
        cmocka_unit_test_setup(test_stopped_encoder_under_torque, setup),
        cmocka_unit_test_setup(test_open_phase, setup),
        cmocka_unit_test_setup(test_open_phase_not_judged_without_a_turn, setup),
        cmocka_unit_test_setup(test_open_phase_needs_the_current_to_turn, setup),
        cmocka_unit_test_setup(test_open_phase_names_the_phase, setup),
        cmocka_unit_test_setup(test_isolated_phase_is_not_judged, setup),
        cmocka_unit_test_setup(test_accepted_fault_records_again, setup),
        cmocka_unit_test_setup(test_isolated_phase_word_may_rest, setup),
        cmocka_unit_test_setup(test_frozen_converter_stays_dead_across_clears, setup),
        cmocka_unit_test_setup(test_frozen_at_idle_found_by_the_driven_phases, setup),
        cmocka_unit_test_setup(test_no_false_trip, setup),
        cmocka_unit_test_setup(test_fast_open_phase_without_a_turn, setup),
        cmocka_unit_test_setup(test_fast_open_phase_needs_the_xy_held, setup),
        cmocka_unit_test_setup(test_records_and_latch, setup),
        cmocka_unit_test_setup(test_full_log_keeps_a_new_root_cause, setup),
        cmocka_unit_test_setup(test_raise_from_outside, setup),
        cmocka_unit_test_setup(test_not_a_number, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
