/*
 * Commissioning end to end (issue 15): the drive's own sequence (`--scenario commission`)
 * against plants that differ from the controller's reference machine, with every
 * non-ideality on (dead time, ADC offset, gain and noise, encoder quantisation, PM harmonics).
 *   - five plants (R -40..+40 %, L_d, L_q, L_xy and psi_f -30..+30 %, encoder offsets anywhere),
 *     in the fixed-point and the float build of the drive: R within 3 %, L_d and L_q within 5 %,
 *     L_xy within 10 %, psi_f within 3 %, the offset within 2 electrical degrees, every result OK,
 *     and the set applied;
 *   - a wrong pole-pair count (the plant's 2 or 4, the controller's 3; or the controller's 4)
 *     and swapped channels are found every time, with the pole pairs the count implies;
 *   - refusals: a stuck encoder (NO_MOTION), the DC link below the under-voltage limit, a
 *     request while the drive runs.
 */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, rmdir */

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
#include "ctl_pu.h"
#include "hal_sim.h"
#include "run/sim.h"
#include "sim_run_checked.h"
#include "sxlink.h"
#include "run/sim_run_state.h"
#include "sxlink_commission.h"

typedef struct {
    double r, ld, lq, lxy, psi_f, offset_deg;
    uint64_t seed;
} plant_t;

static const plant_t plants[] = {
    {1.2, 0.0455, 0.0385, 0.008, 0.26, 37.0, 1u},    /* R -40 %, L_d +30 %, L_q -30 % */
    {2.8, 0.0245, 0.0715, 0.013, 0.1575, 123.0, 2u}, /* R +40 %, L_xy +30 %, psi_f -30 % */
    {1.2, 0.040, 0.060, 0.007, 0.2925, -70.0, 5u},   /* L_xy -30 %, psi_f +30 % */
    {2.4, 0.030, 0.0715, 0.012, 0.20, 200.0, 7u},    /* L_q +30 % */
    {1.6, 0.0245, 0.0385, 0.009, 0.25, 301.0, 3u},   /* L_d and L_q -30 % */
};

static void config(sim_config_t *c, const plant_t *p, int arith)
{
    sim_config_default(c);
    c->scenario = SIM_SCEN_COMMISSION;
    c->arith = arith;
    c->out_dir = NULL;
    if (p) {
        c->plant.r_ohm = p->r;
        c->plant.ld_h = p->ld;
        c->plant.lq_h = p->lq;
        c->plant.lxy_h = p->lxy;
        c->plant.psi_f_wb = p->psi_f;
        c->plant.encoder_offset_rad = p->offset_deg * 3.14159265358979323846 / 180.0;
        c->seed = p->seed;
    }
}

static void run(const sim_config_t *c, sim_result_t *r)
{
    sim_run_checked(c, r);
    assert_true(r->comm.ran);
}

static double rel_error(const sim_result_t *r, int q)
{
    return fabs(r->comm.value[q] / r->comm.truth[q] - 1.0);
}

static double offset_error_deg(const sim_result_t *r)
{
    return fabs(
        fmod(r->comm.value[SXL_COMM_Q_OFFSET] - r->comm.truth[SXL_COMM_Q_OFFSET] + 540.0, 360.0) -
        180.0);
}

/* The error in units of the reported 1-sigma uncertainty (the offset's in degrees). */
static double error_sigmas(const sim_result_t *r, int q)
{
    const double e =
        (q == SXL_COMM_Q_OFFSET) ? offset_error_deg(r) : fabs(r->comm.value[q] - r->comm.truth[q]);
    return e / r->comm.sigma[q];
}

/* The reported uncertainty means what it says: each error within 3 sigma. */
static void check_uncertainty(const sim_result_t *r)
{
    static const int quantities[] = {SXL_COMM_Q_OFFSET, SXL_COMM_Q_R,   SXL_COMM_Q_LD,
                                     SXL_COMM_Q_LQ,     SXL_COMM_Q_LXY, SXL_COMM_Q_PSI_F};
    size_t k;
    print_message("      error / sigma: offset %.2f R %.2f Ld %.2f Lq %.2f Lxy %.2f psi %.2f\n",
                  error_sigmas(r, SXL_COMM_Q_OFFSET), error_sigmas(r, SXL_COMM_Q_R),
                  error_sigmas(r, SXL_COMM_Q_LD), error_sigmas(r, SXL_COMM_Q_LQ),
                  error_sigmas(r, SXL_COMM_Q_LXY), error_sigmas(r, SXL_COMM_Q_PSI_F));
    for (k = 0; k < sizeof quantities / sizeof quantities[0]; k++) {
        assert_true(r->comm.sigma[quantities[k]] > 0.0);
        assert_true(error_sigmas(r, quantities[k]) < 3.0);
    }
}

static void check_plant(const plant_t *p, int arith)
{
    sim_config_t c;
    sim_result_t r;
    int q;
    config(&c, p, arith);
    run(&c, &r);
    print_message("%-5s R %+.2f%% Ld %+.2f%% Lq %+.2f%% Lxy %+.2f%% psi %+.2f%% offset %+.3f deg "
                  "(%.1f s)\n",
                  r.arith, 100.0 * (r.comm.value[3] / r.comm.truth[3] - 1.0),
                  100.0 * (r.comm.value[4] / r.comm.truth[4] - 1.0),
                  100.0 * (r.comm.value[5] / r.comm.truth[5] - 1.0),
                  100.0 * (r.comm.value[6] / r.comm.truth[6] - 1.0),
                  100.0 * (r.comm.value[7] / r.comm.truth[7] - 1.0),
                  fmod(r.comm.value[2] - r.comm.truth[2] + 540.0, 360.0) - 180.0,
                  r.comm.duration_s);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
    assert_int_equal(r.fault, 0);
    for (q = 0; q < SIM_COMM_QUANTITIES; q++) {
        assert_int_equal(r.comm.quality[q], SXL_COMM_QUALITY_OK);
    }
    assert_true(rel_error(&r, SXL_COMM_Q_R) < 0.03);
    assert_true(rel_error(&r, SXL_COMM_Q_LD) < 0.05);
    assert_true(rel_error(&r, SXL_COMM_Q_LQ) < 0.05);
    assert_true(rel_error(&r, SXL_COMM_Q_LXY) < 0.10);
    assert_true(rel_error(&r, SXL_COMM_Q_PSI_F) < 0.03);
    assert_true(offset_error_deg(&r) < 2.0);
    assert_true(rel_error(&r, SXL_COMM_Q_COUNTS) < 0.01);
    check_uncertainty(&r);
    /* the serial APPLY's call: the machine and the offset taken */
    assert_int_equal(r.comm.apply_result, 0);
    assert_int_equal(r.comm.applied, (1u << SXL_COMM_Q_OFFSET) | (1u << SXL_COMM_Q_R) |
                                         (1u << SXL_COMM_Q_LD) | (1u << SXL_COMM_Q_LQ) |
                                         (1u << SXL_COMM_Q_LXY) | (1u << SXL_COMM_Q_PSI_F) |
                                         (1u << SXL_COMM_Q_INERTIA));
}

static void test_five_plants_fixed(void **state)
{
    size_t k;
    (void)state;
    for (k = 0; k < sizeof plants / sizeof plants[0]; k++) {
        check_plant(&plants[k], 0);
    }
}

static void test_five_plants_float(void **state)
{
    size_t k;
    (void)state;
    for (k = 0; k < sizeof plants / sizeof plants[0]; k++) {
        check_plant(&plants[k], 1);
    }
}

/* The encoder step ends the sequence with reason, having counted what it counted. */
static void check_encoder_error(int plant_pn, int ctl_pn, bool reversed, bool stuck, int reason,
                                int implied)
{
    sim_config_t c;
    sim_result_t r;
    config(&c, &plants[4], 0);
    c.plant.pole_pairs = plant_pn;
    c.ctl.pole_pairs = ctl_pn;
    c.plant.encoder_reversed = reversed;
    c.plant.encoder_stuck = stuck;
    run(&c, &r);
    print_message("plant Pn %d, controller Pn %d, reversed %d, stuck %d: %s, counts %.1f, "
                  "implied Pn %.0f\n",
                  plant_pn, ctl_pn, reversed ? 1 : 0, stuck ? 1 : 0,
                  r.comm.reason == reason ? "detected" : "MISSED", r.comm.value[SXL_COMM_Q_COUNTS],
                  r.comm.extra[SXL_COMM_Q_COUNTS]);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_FAILED);
    assert_int_equal(r.comm.reason, reason);
    assert_int_equal(r.comm.quality[SXL_COMM_Q_COUNTS], SXL_COMM_QUALITY_FAILED);
    assert_int_equal(r.comm.reason_q[SXL_COMM_Q_R], SXL_COMM_REASON_SKIPPED);
    assert_int_equal(r.fault, 0);        /* a failed step is a result, not a fault */
    assert_true(hal_sim_bus.forced_off); /* and the sequence left every leg off */
    if (implied > 0) {
        assert_int_equal((int)r.comm.extra[SXL_COMM_Q_COUNTS], implied);
    }
    assert_int_equal(r.final_state, 2); /* READY: outputs off, nothing left running */
}

static void test_wrong_pole_pairs_and_swapped_channels(void **state)
{
    (void)state;
    check_encoder_error(2, 3, false, false, SXL_COMM_REASON_POLE_PAIRS, 2);
    check_encoder_error(4, 3, false, false, SXL_COMM_REASON_POLE_PAIRS, 4);
    check_encoder_error(3, 4, false, false, SXL_COMM_REASON_POLE_PAIRS, 3);
    check_encoder_error(3, 2, false, false, SXL_COMM_REASON_POLE_PAIRS, 3);
    check_encoder_error(3, 3, true, false, SXL_COMM_REASON_REVERSED, 0);
    check_encoder_error(4, 3, true, false, SXL_COMM_REASON_REVERSED, 0);
    check_encoder_error(3, 3, false, true, SXL_COMM_REASON_NO_MOTION, 0);
}

/* The amplitude limit: the test current is at most a quarter of the software over-current
 * limit (15 A); the first alignment's swing, i_q beside i_d in the psi_f step and the x-y
 * harmonics take the phase peak to 1.3..1.65 times it. A weak magnet in plant and
 * controller (0.1 Wb: rated 7.8 A) at 80 % of rated asks for 6.2 A and gets 3.75 A; the
 * plant's phase currents stay below 40 % of the limit, and the sequence is still done. */
static void test_current_within_a_fraction_of_the_trip_level(void **state)
{
    sim_config_t c;
    sim_result_t r;
    (void)state;
    config(&c, &plants[4], 0);
    c.plant.psi_f_wb = 0.1;
    c.ctl.psi_f_wb = 0.1;
    c.commission_permille = 800;
    run(&c, &r);
    print_message("weak magnet, 80 %%: phase peak %.2f A (%.1f %% of 15 A)\n", r.comm.phase_peak_a,
                  100.0 * r.comm.phase_peak_a / 15.0);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
    assert_true(r.comm.phase_peak_a > 0.25 * 15.0); /* the cap's current flowed */
    assert_true(r.comm.phase_peak_a < 0.40 * 15.0);
    config(&c, &plants[4], 0); /* the default current: 40 % of 3.46 A, peaks below the cap */
    run(&c, &r);
    print_message("default: phase peak %.2f A\n", r.comm.phase_peak_a);
    assert_true(r.comm.phase_peak_a > 0.4 * 3.46 && r.comm.phase_peak_a < 0.25 * 15.0);
}

/* A failed sequence writes no motor parameter file into --out DIR: one of nothing would be
 * built as the reference machine. */
static void test_failed_sequence_writes_no_file(void **state)
{
    char dir[] = "/tmp/sixphase-comm-fail-XXXXXX";
    char path[64];
    sim_config_t c;
    sim_result_t r;
    FILE *f;
    (void)state;
    assert_non_null(mkdtemp(dir));
    config(&c, &plants[4], 0);
    c.plant.encoder_reversed = true;
    c.out_dir = dir;
    c.write_trace = false;
    c.write_fine = false;
    run(&c, &r);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_FAILED);
    (void)snprintf(path, sizeof path, "%s/motor_params.h", dir);
    f = fopen(path, "r");
    if (f) {
        (void)fclose(f);
    }
    assert_null(f);
    (void)snprintf(path, sizeof path, "%s/metrics.json", dir);
    (void)remove(path);
    assert_int_equal(rmdir(dir), 0); /* nothing else was written */
}

/* A load torque on the shaft (0.5 N m against the 2.8 N m the test current holds): the offset
 * would be off by its lag (about 10 electrical degrees); the load check finds it, the sequence
 * stops there with the outputs off. */
static void test_load_torque_found(void **state)
{
    sim_config_t c;
    sim_result_t r;
    (void)state;
    config(&c, &plants[1], 0);
    c.load_nm = 0.5;
    run(&c, &r);
    print_message("load 0.5 N m: %s, load lag %.2f deg\n",
                  sxl_comm_reason_name((uint16_t)r.comm.reason), r.comm.extra[SXL_COMM_Q_OFFSET]);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_FAILED);
    assert_int_equal(r.comm.reason, SXL_COMM_REASON_LOAD_TORQUE);
    assert_int_equal(r.comm.quality[SXL_COMM_Q_OFFSET], SXL_COMM_QUALITY_FAILED);
    assert_true(fabs(r.comm.extra[SXL_COMM_Q_OFFSET]) > 2.0);
    assert_int_equal(r.comm.reason_q[SXL_COMM_Q_PSI_F], SXL_COMM_REASON_SKIPPED);
    assert_int_equal(r.final_state, 2);
}

/* A load the test current cannot hold (2.8 N m at the default current; 1.4 N m at the load
 * check's half current) drags the rotor through its poles while the field stands or turns
 * slowly. The open-phase check then sees a current vector that stands while the rotor turns
 * and found the phase across it open (OPEN_PHASE at 2 and 3 N m, OVERSPEED at 7 N m, REVERSED
 * or POLE_PAIRS at 5 N m before the slip check): the sequence must find the load itself, stop
 * with LOAD_TORQUE, the outputs off and the drive READY. */
static void test_dragged_rotor_is_a_load(void **state)
{
    static const double loads_nm[] = {2.0, 3.0, 5.0, 7.0, -3.0};
    size_t k;
    (void)state;
    for (k = 0; k < sizeof loads_nm / sizeof loads_nm[0]; k++) {
        sim_config_t c;
        sim_result_t r;
        config(&c, NULL, 0);
        c.load_nm = loads_nm[k];
        run(&c, &r);
        print_message("load %+.1f N m: %s / %s after %.3f s, fault %d, slip %.0f deg\n",
                      loads_nm[k], sxl_comm_state_name((uint16_t)r.comm.state),
                      sxl_comm_reason_name((uint16_t)r.comm.reason), r.comm.duration_s, r.fault,
                      r.comm.extra[SXL_COMM_Q_OFFSET]);
        assert_int_equal(r.fault, 0);
        assert_int_equal(r.comm.state, SXL_COMM_STATE_FAILED);
        assert_int_equal(r.comm.reason, SXL_COMM_REASON_LOAD_TORQUE);
        assert_int_equal(r.comm.quality[SXL_COMM_Q_OFFSET], SXL_COMM_QUALITY_FAILED);
        assert_int_equal(r.comm.reason_q[SXL_COMM_Q_PSI_F], SXL_COMM_REASON_SKIPPED);
        assert_int_equal(r.final_state, 2);
    }
}

/* The DC link below the under-voltage limit (300 V against 350 V): refused, nothing runs. */
static void test_refused_with_the_dc_link_low(void **state)
{
    sim_config_t c;
    sim_result_t r;
    int q;
    (void)state;
    config(&c, NULL, 0);
    c.plant.vdc_v = 300.0;
    run(&c, &r);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_IDLE);
    assert_int_equal(r.comm.reason, SXL_COMM_REASON_UNDERVOLTAGE);
    for (q = 0; q < SIM_COMM_QUANTITIES; q++) {
        assert_int_equal(r.comm.quality[q], SXL_COMM_QUALITY_NOT_RUN);
    }
    assert_int_equal(r.final_state, 2);
}

/* The run set up and the drive calibrated, for a test that steps it period by period. */
static void start_stepwise(sim_run_t *rs, const sim_config_t *c, sim_result_t *r)
{
    char err[200] = "";
    memset(r, 0, sizeof *r);
    if (sim_setup(rs, c, err, sizeof err) != 0 ||
        sim_setup_calibrate(rs, r, err, sizeof err) != 0) {
        print_error("set-up failed: %s\n", err);
        fail();
    }
}

/* A rotor still turning (here 30 r/min, 1.5 electrical turns/s) when the sequence is asked
 * for: refused with rotor_turning, the drive stays READY with its outputs off; once the rotor
 * stands, the same request is taken. */
static void test_refused_with_the_rotor_turning(void **state)
{
    sim_config_t c;
    sim_result_t r;
    sim_run_t rs;
    sim_ctl_status_t st;
    sim_comm_status_t cs;
    long k;
    (void)state;
    config(&c, NULL, 0);
    start_stepwise(&rs, &c, &r);
    rs.x.omega_m = 0.5 * 2.0 * 3.14159265358979323846;
    for (k = 0; k < 200; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
    }
    assert_int_not_equal(rs.ops->commission_start(SXL_COMM_STEPS_ALL, 400u), 0);
    rs.ops->commission_status(&cs);
    assert_int_equal(cs.reason, SXL_COMM_REASON_ROTOR_TURNING);
    assert_int_equal(cs.state, SXL_COMM_STATE_IDLE);
    rs.ops->status(&st);
    assert_true(st.ready && !st.commissioning);
    assert_true(hal_sim_bus.forced_off);
    rs.x.omega_m = 0.0;
    for (; k < 400; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
    }
    assert_int_equal(rs.ops->commission_start(SXL_COMM_STEPS_ALL, 400u), 0);
    sim_teardown(&rs, true);
}

/* A request while the drive runs (the steady scenario): refused, the drive keeps running. */
static void test_refused_while_running(void **state)
{
    sim_config_t c;
    sim_result_t r;
    sim_run_t rs;
    sim_ctl_status_t st;
    sim_comm_status_t cs;
    long k;
    (void)state;
    sim_config_default(&c);
    c.duration_s = 0.05;
    start_stepwise(&rs, &c, &r);
    for (k = 0; k < 100; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
    }
    rs.ops->status(&st);
    assert_true(st.running);
    assert_int_not_equal(rs.ops->commission_start(SXL_COMM_STEPS_ALL, 400u), 0);
    for (; k < 200; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
        rs.ops->status(&st);
        assert_true(st.running && !st.commissioning);
    }
    rs.ops->commission_status(&cs);
    assert_int_equal(cs.reason, SXL_COMM_REASON_NOT_READY);
    assert_int_equal(cs.state, SXL_COMM_STATE_IDLE);
    sim_teardown(&rs, true);
}

/* Closed loop after commissioning: the second plant identified, then the product's DDC at
 * 1500 r/min and rated load with the identified set: THD and torque ripple (means over seeds
 * 1..3: one run's THD moves by about 1 % from seed to seed) within 5 % of the runs with the
 * exact parameters and offset; with the reference set the speed is not held. */
static void steady_on_plant(const plant_t *p, const double ctl[5], double offset_deg, double *thd,
                            double *ripple, double *speed)
{
    uint64_t seed;
    *thd = *ripple = *speed = 0.0;
    for (seed = 1u; seed <= 3u; seed++) {
        char err[200] = "";
        sim_config_t c;
        sim_result_t r;
        config(&c, p, 0);
        c.scenario = SIM_SCEN_STEADY;
        c.seed = seed;
        c.ctl.r_ohm = ctl[0];
        c.ctl.ld_h = ctl[1];
        c.ctl.lq_h = ctl[2];
        c.ctl.lxy_h = ctl[3];
        c.ctl.psi_f_wb = ctl[4];
        c.ctl.encoder_offset_rad = offset_deg * 3.14159265358979323846 / 180.0;
        assert_int_equal(sim_run(&c, &r, err, sizeof err), 0);
        *thd += r.thd_percent / 3.0;
        *ripple += r.torque_ripple_nm / 3.0;
        *speed += r.speed_mean_rpm / 3.0;
    }
}

static void test_closed_loop_after_commissioning(void **state)
{
    const plant_t *p = &plants[1];
    const double exact[5] = {p->r, p->ld, p->lq, p->lxy, p->psi_f};
    const double reference[5] = {2.0, 0.035, 0.055, 0.010, 0.225};
    double identified[5], e[3], i[3], d[3];
    sim_config_t c;
    sim_result_t r;
    int q;
    (void)state;
    config(&c, p, 0);
    run(&c, &r);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
    for (q = 0; q < 5; q++) {
        identified[q] = r.comm.value[SXL_COMM_Q_R + q];
    }
    steady_on_plant(p, exact, p->offset_deg, &e[0], &e[1], &e[2]);
    steady_on_plant(p, identified, r.comm.value[SXL_COMM_Q_OFFSET], &i[0], &i[1], &i[2]);
    steady_on_plant(p, reference, p->offset_deg, &d[0], &d[1], &d[2]);
    print_message("THD %.2f / %.2f / %.2f %%, ripple %.3f / %.3f / %.3f N m, speed %.1f / %.1f / "
                  "%.1f r/min (exact / identified / reference)\n",
                  e[0], i[0], d[0], e[1], i[1], d[1], e[2], i[2], d[2]);
    assert_true(fabs(i[0] / e[0] - 1.0) < 0.05);
    assert_true(fabs(i[1] / e[1] - 1.0) < 0.05);
    assert_true(fabs(i[2] - 1500.0) < 5.0);
    assert_true(fabs(d[2] - 1500.0) > 50.0); /* the reference set cannot hold it */
}

/* fault-open-phase (2 kohm in phase C from 0.25 s): detected; cleared; a run checks the phases
 * first, finds phase C open and goes back to FAULT OPEN_PHASE without a single period of normal
 * control, with the outputs off from then on. */
static void test_open_phase_checked_again_after_clear(void **state)
{
    sim_config_t c;
    sim_result_t r;
    sim_run_t rs;
    sim_ctl_status_t st;
    char err[200] = "";
    long k, verify_periods = 0;
    (void)state;
    sim_config_default(&c);
    c.fault = SIM_FAULT_OPEN_PHASE;
    c.duration_s = 1.0;
    memset(&r, 0, sizeof r);
    r.fault_time_s = -1.0;
    assert_int_equal(sim_setup(&rs, &c, err, sizeof err), 0);
    assert_int_equal(sim_setup_calibrate(&rs, &r, err, sizeof err), 0);
    for (k = 0; k < 4000 && r.fault_time_s < 0.0; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
    }
    assert_int_equal(r.fault, 15); /* OPEN_PHASE */
    for (; k < 5000; k++) {        /* the rotor coasts down; clear once it is nearly still */
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
    }
    rs.ops->request_clear();
    assert_int_equal(sim_loop_period(&rs, &r, k++), 0);
    rs.ops->status(&st);
    assert_true(st.ready);
    rs.ops->request_run();
    for (; k < 6000; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
        rs.ops->status(&st);
        assert_false(st.running && !st.phase_verifying); /* never a normal control period */
        verify_periods += st.phase_verifying ? 1 : 0;
        if (st.faulted) {
            break;
        }
    }
    print_message("phase check: %ld periods, then fault %d\n", verify_periods, st.fault);
    assert_true(st.faulted);
    assert_int_equal(st.fault, 15);
    assert_true(verify_periods > 0 && verify_periods < 600);
    for (k++; k < 6100; k++) {
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
        assert_true(hal_sim_bus.forced_off);
    }
    sim_teardown(&rs, true);
}

/* Phase C opens during each step of the sequence (the reference machine; the steps run 0 to
 * 0.048 s, to 14.4 s, 17.2 s, 18.2 s, 19.2 s and 22.7 s): every step watches, the sequence ends
 * FAILED with reason open_phase within 100 ms, and APPLY takes nothing (results measured before
 * the opening are not trusted either: when it opened is unknown); the mechanics' step (22.7 to
 * 29.6 s) likewise in its runs (while its speed loop holds a speed only the friction's few mA
 * flow, and an opening there is found at the runs, 0.4 s later). Before, only the first 45 ms
 * were watched: the sequence ended "done" with R, L_q and L_xy off, or failed on load_torque. */
/* Quantity q ok, within the relative limit and within 3 of its sigmas. */
static void check_within(const sim_result_t *r, int q, double limit)
{
    assert_int_equal(r->comm.quality[q], SXL_COMM_QUALITY_OK);
    assert_true(rel_error(r, q) < limit);
    assert_true(error_sigmas(r, q) < 3.0);
}

/* A weak magnet (psi_f 0.3 and 0.45 x the reference): the speed loop's gain and the test current's
 * torque come from the parameter set's flux, so the rotor reaches the flux step's speed late, and
 * its back-EMF is small against the same noise. The step waits for the speed and measures more
 * turns: psi_f within 2 %, its sigma covering the error, quality ok, both arithmetics. Before,
 * the measurement started on the ramp's time and took ten turns: poor (no_speed, then scatter). */
static void test_weak_magnet(void **state)
{
    static const double psi[2] = {0.0675, 0.10};
    int k;
    (void)state;
    for (k = 0; k < 4; k++) {
        sim_config_t c;
        sim_result_t r;
        config(&c, NULL, k % 2);
        c.plant.psi_f_wb = psi[k / 2];
        run(&c, &r);
        print_message("psi_f %.4f Wb (%s): %.5f Wb, sigma %.5f, quality %d, reason %d\n",
                      psi[k / 2], (k % 2) ? "float" : "fixed", r.comm.value[SXL_COMM_Q_PSI_F],
                      r.comm.sigma[SXL_COMM_Q_PSI_F], r.comm.quality[SXL_COMM_Q_PSI_F],
                      r.comm.reason_q[SXL_COMM_Q_PSI_F]);
        check_within(&r, SXL_COMM_Q_PSI_F, 0.02);
    }
}

/* R on a low-inductance machine (L_d, L_q 0.6 x) and on six pole pairs: the switching ripple
 * touches zero in a phase at the low level for an instant, which made R poor (scatter) while it
 * was within 0.6 %; the check now takes each phase's mean: ok, within 2 % and 3 sigma. */
static void test_resistance_ripple_is_not_a_sign_change(void **state)
{
    int k;
    (void)state;
    for (k = 0; k < 4; k++) {
        sim_config_t c;
        sim_result_t r;
        config(&c, NULL, k % 2);
        if (k < 2) {
            c.plant.ld_h = 0.021;
            c.plant.lq_h = 0.033;
        } else {
            c.plant.pole_pairs = 6;
            c.ctl.pole_pairs = 6;
        }
        run(&c, &r);
        print_message("%s (%s): R %.4f ohm, quality %d\n", (k < 2) ? "L 0.6 x" : "6 pole pairs",
                      (k % 2) ? "float" : "fixed", r.comm.value[SXL_COMM_Q_R],
                      r.comm.quality[SXL_COMM_Q_R]);
        check_within(&r, SXL_COMM_Q_R, 0.02);
    }
}

/* A small load on the shaft (0.02 .. 0.1 N m, below the load check's 2 degrees): its lag is the
 * same in both directions, so the two sweeps' mean carried it (1.0 degree at 0.05 N m, 37
 * sigma). The half-current sweep measures it; it is now taken out, and the sigma holds the
 * stiffness ratio's uncertainty: within 0.25 degree and 3 sigma, both arithmetics. */
static void test_small_load_lag_taken_out(void **state)
{
    static const double loads[3] = {0.02, 0.05, 0.1};
    int k;
    (void)state;
    for (k = 0; k < 6; k++) {
        sim_config_t c;
        sim_result_t r;
        config(&c, NULL, k % 2);
        c.load_nm = loads[k / 2];
        run(&c, &r);
        print_message("load %.2f N m (%s): offset error %.3f deg, sigma %.3f deg\n", loads[k / 2],
                      (k % 2) ? "float" : "fixed", offset_error_deg(&r),
                      r.comm.sigma[SXL_COMM_Q_OFFSET]);
        assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
        assert_int_equal(r.comm.quality[SXL_COMM_Q_OFFSET], SXL_COMM_QUALITY_OK);
        assert_true(fabs(offset_error_deg(&r)) < 0.25);
        assert_true(error_sigmas(&r, SXL_COMM_Q_OFFSET) < 3.0);
    }
}

static void test_open_phase_in_each_step(void **state)
{
    /* in each step where the watch can judge: the encoder's spin (not its alignment) and the
     * mechanics' runs (not its friction points, where the phases carry a few mA):
     * docs/commissioning.md section 1 */
    static const double opens_s[SXL_COMM_STEP_COUNT] = {0.02, 2.0, 18.6, 20.8, 21.8, 23.6, 36.6};
    int step;
    (void)state;
    for (step = 0; step < (int)SXL_COMM_STEP_COUNT; step++) {
        sim_config_t c;
        sim_result_t r;
        config(&c, NULL, step % 2);
        c.fault = SIM_FAULT_OPEN_PHASE;
        c.fault_phase = 2;
        c.fault_time_s = opens_s[step];
        run(&c, &r);
        print_message("C opens at %.2f s (step %s, %s): %s / %s after %.1f ms, apply %d (applied "
                      "0x%x), fault %d\n",
                      opens_s[step], sxl_comm_step_name((uint16_t)step), r.arith,
                      sxl_comm_state_name((uint16_t)r.comm.state),
                      sxl_comm_reason_name((uint16_t)r.comm.reason),
                      1e3 * (r.comm.duration_s - opens_s[step]), r.comm.apply_result,
                      r.comm.applied, r.fault);
        assert_int_equal(r.comm.state, SXL_COMM_STATE_FAILED);
        assert_int_equal(r.comm.reason, SXL_COMM_REASON_OPEN_PHASE);
        assert_true(r.comm.duration_s > opens_s[step] && r.comm.duration_s < opens_s[step] + 0.1);
        assert_int_equal(r.comm.apply_result, 2); /* DRIVE_COMM_REFUSED */
        assert_int_equal(r.comm.applied, 0u);
    }
}

/* A weak magnet (psi_f 0.0675 Wb, 0.3 x the reference; issue 25). Before, psi_f ended poor
 * (no_speed), APPLY took R, L_q, L_xy and the offset and kept 0.225 Wb, and --out wrote that set:
 * the speed collapsed at rated load. Then APPLY refused the mix. Now psi_f is measured (the flux
 * step waits for its speed and takes more turns): the set with it is applied and written; L_d,
 * poor here (rotor_moved) but within 3 sigma of the kept value, is kept (docs/commissioning.md
 * 3.1). The mixed-set refusal itself: test_commission_apply_refuses_a_mixed_set. */
static void test_weak_magnet_applied(void **state)
{
    char dir[] = "/tmp/sixphase-comm-weak-XXXXXX";
    char path[64];
    char text[4096];
    size_t n;
    sim_config_t c;
    sim_result_t r;
    FILE *f;
    (void)state;
    assert_non_null(mkdtemp(dir));
    config(&c, NULL, 0);
    c.plant.psi_f_wb = 0.0675;
    c.seed = 7u;
    c.out_dir = dir;
    c.write_trace = false;
    c.write_fine = false;
    run(&c, &r);
    print_message("weak magnet: psi_f %.4f Wb %s (%s), apply %d, applied 0x%x\n",
                  r.comm.value[SXL_COMM_Q_PSI_F],
                  sxl_comm_quality_name((uint16_t)r.comm.quality[SXL_COMM_Q_PSI_F]),
                  sxl_comm_reason_name((uint16_t)r.comm.reason_q[SXL_COMM_Q_PSI_F]),
                  r.comm.apply_result, r.comm.applied);
    assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
    assert_int_equal(r.comm.quality[SXL_COMM_Q_PSI_F], SXL_COMM_QUALITY_OK);
    assert_true(rel_error(&r, SXL_COMM_Q_PSI_F) < 0.02);
    assert_int_equal(r.comm.apply_result, 0);
    assert_true((r.comm.applied & (1u << SXL_COMM_Q_PSI_F)) != 0u);
    (void)snprintf(path, sizeof path, "%s/motor_params.h", dir);
    f = fopen(path, "r");
    assert_non_null(f);
    n = fread(text, 1, sizeof text - 1u, f);
    (void)fclose(f);
    text[n] = '\0';
    assert_non_null(strstr(text, "PSI_F_WB"));
    (void)remove(path);
    (void)snprintf(path, sizeof path, "%s/metrics.json", dir);
    (void)remove(path);
    assert_int_equal(rmdir(dir), 0);
}

/* The square wave's resistive droop and its amplitude (issue 25, item 1): a low L_xy (3 mH,
 * 0.3 x the set's) at R 1, 2 and 4 ohm, with L_d = L_q = 21 mH (0.6 x the set's L_d) beside the
 * issue's own machine (the set's L_d and L_q). Before, the method took the current's change
 * over a half period as if R were 0: L_xy read +3.8, +8.2 and +21.4 % (R 4: +14 % of it the
 * droop, x / tanh x with x = R N T / (2 L) = 0.67), with quality ok; and the amplitude came from
 * the set's inductance: 3.3 times the ripple, currents crossing zero (the rest). Now the droop
 * is taken out with the resistance step's R and the amplitude sized from a first block's
 * estimate: L_xy within 5 %, L_d and L_q within 3 %, each within 3 sigma, both arithmetics. */
static void test_droop_and_amplitude(void **state)
{
    static const plant_t low[] = {
        {1.0, 0.021, 0.021, 0.003, 0.225, 0.0, 7u},
        {2.0, 0.021, 0.021, 0.003, 0.225, 0.0, 7u},
        {4.0, 0.021, 0.021, 0.003, 0.225, 0.0, 7u},
        {4.0, 0.035, 0.055, 0.003, 0.225, 0.0, 7u}, /* the reproducer */
    };
    size_t k;
    int arith;
    (void)state;
    for (arith = 0; arith < 2; arith++) {
        for (k = 0; k < sizeof low / sizeof low[0]; k++) {
            sim_config_t c;
            sim_result_t r;
            config(&c, &low[k], arith);
            run(&c, &r);
            print_message("%-5s R %.0f, L_d %.0f mH, L_xy 3 mH: Ld %+.2f%% Lq %+.2f%% Lxy %+.2f%% "
                          "(%.1f / %.1f / %.1f sigma)\n",
                          r.arith, low[k].r, 1e3 * low[k].ld,
                          100.0 * (r.comm.value[4] / r.comm.truth[4] - 1.0),
                          100.0 * (r.comm.value[5] / r.comm.truth[5] - 1.0),
                          100.0 * (r.comm.value[6] / r.comm.truth[6] - 1.0),
                          error_sigmas(&r, SXL_COMM_Q_LD), error_sigmas(&r, SXL_COMM_Q_LQ),
                          error_sigmas(&r, SXL_COMM_Q_LXY));
            assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
            assert_true(rel_error(&r, SXL_COMM_Q_LXY) < 0.05);
            assert_true(rel_error(&r, SXL_COMM_Q_LD) < 0.03);
            assert_true(rel_error(&r, SXL_COMM_Q_LQ) < 0.03);
            assert_true(error_sigmas(&r, SXL_COMM_Q_LXY) < 3.0);
            assert_true(error_sigmas(&r, SXL_COMM_Q_LD) < 3.0);
            assert_true(error_sigmas(&r, SXL_COMM_Q_LQ) < 3.0);
        }
    }
}

/* ---- inertia and friction (issue 25, item 4) ---- */

#define MECH_STEPS                                                                                 \
    ((1u << SXL_COMM_STEP_PHASES) | (1u << SXL_COMM_STEP_ENCODER) | (1u << SXL_COMM_STEP_MECH))
#define REF_J 0.01  /* the reference machine's, kg m^2 */
#define REF_B 0.001 /* the plant's default viscous friction, N m s/rad */

/* The mechanics' step alone (phase check and encoder before it) on a plant with inertia j and
 * friction b, the controller keeping the reference machine. */
static void run_mech(double j, double b, int arith, sim_result_t *r)
{
    sim_config_t c;
    config(&c, NULL, arith);
    c.plant.j_kgm2 = j;
    c.plant.b_nms = b;
    c.commission_steps = (int)MECH_STEPS;
    run(&c, r);
}

/* The gains ctl_speed_gains_from_inertia designs (ctl_params.h), in double: kp = J w_c,
 * ki = kp w_c / 4, w_c = 150 rad/s unless kp would pass 90 per unit (3 pole pairs). */
static void designed_gains(double j, double *kp, double *ki, double *wc)
{
    const double kp_max =
        (double)CTL_SPEED_DESIGN_KP_PU_MAX * 3.0 * CTL_BASE_TORQUE_NM / CTL_BASE_OMEGA_RAD_S;
    *wc = (j * 150.0 > kp_max) ? kp_max / j : 150.0;
    *kp = j * *wc;
    *ki = *kp * *wc / 4.0;
}

/* J within 5 %, B within 20 % or 2e-4 N m s/rad, on plants with 0.2 and 10 times the reference
 * inertia and 0, 1 and 10 times its friction, in both arithmetics; the inertia applied with the
 * speed gains designed for it. Before: no such step (the mask was refused, nothing measured). */
static void test_inertia_and_friction_over_the_range(void **state)
{
    static const double js[] = {0.2 * REF_J, 10.0 * REF_J};
    static const double bs[] = {0.0, REF_B, 10.0 * REF_B};
    size_t a, k, m;
    (void)state;
    for (a = 0; a < 2; a++) {
        for (k = 0; k < sizeof js / sizeof js[0]; k++) {
            for (m = 0; m < sizeof bs / sizeof bs[0]; m++) {
                sim_result_t r;
                const double *v = r.comm.value;
                double kp, ki, wc;
                run_mech(js[k], bs[m], (int)a, &r);
                print_message(
                    "%-5s J %.3g B %.3g: J %+.2f %% (sigma %.2f %%), B %+.2e (sigma %.1e, "
                    "Tc %+.1e N m), kp %.3g ki %.3g (%.1f s)\n",
                    r.arith, js[k], bs[m], 100.0 * (v[SXL_COMM_Q_INERTIA] / js[k] - 1.0),
                    100.0 * r.comm.sigma[SXL_COMM_Q_INERTIA] / js[k],
                    v[SXL_COMM_Q_FRICTION] - bs[m], r.comm.sigma[SXL_COMM_Q_FRICTION],
                    r.comm.extra[SXL_COMM_Q_FRICTION], r.comm.speed_kp, r.comm.speed_ki,
                    r.comm.duration_s);
                assert_int_equal(r.comm.state, SXL_COMM_STATE_DONE);
                assert_int_equal(r.fault, 0);
                assert_int_equal(r.comm.quality[SXL_COMM_Q_INERTIA], SXL_COMM_QUALITY_OK);
                assert_int_equal(r.comm.quality[SXL_COMM_Q_FRICTION], SXL_COMM_QUALITY_OK);
                assert_true(fabs(v[SXL_COMM_Q_INERTIA] / js[k] - 1.0) < 0.05);
                assert_true(fabs(v[SXL_COMM_Q_FRICTION] - bs[m]) < fmax(0.2 * bs[m], 2e-4));
                assert_true(r.comm.sigma[SXL_COMM_Q_INERTIA] > 0.0);
                assert_true((r.comm.applied & (1u << SXL_COMM_Q_INERTIA)) != 0u);
                designed_gains(v[SXL_COMM_Q_INERTIA], &kp, &ki, &wc);
                assert_true(fabs(r.comm.speed_kp / kp - 1.0) < 1e-4);
                assert_true(fabs(r.comm.speed_ki / ki - 1.0) < 1e-4);
            }
        }
    }
}

/* Each quantity within its limit (issue 25: R 2 %, L 3 %, L_xy 5 %, psi_f 2 %, J 5 %, B 20 % or
 * 2e-4 N m s/rad) and within 3 of its own sigma. */
static void check_limits(const sim_result_t *r)
{
    static const struct {
        int q;
        double limit;
    } lim[] = {{SXL_COMM_Q_R, 0.02},       {SXL_COMM_Q_LD, 0.03},    {SXL_COMM_Q_LQ, 0.03},
               {SXL_COMM_Q_LXY, 0.05},     {SXL_COMM_Q_PSI_F, 0.02}, {SXL_COMM_Q_INERTIA, 0.05},
               {SXL_COMM_Q_FRICTION, 0.20}};
    size_t k;
    assert_int_equal(r->comm.state, SXL_COMM_STATE_DONE);
    for (k = 0; k < sizeof lim / sizeof lim[0]; k++) {
        const int q = lim[k].q;
        const double err = fabs(r->comm.value[q] - r->comm.truth[q]);
        print_message("  %-9s %+.2f %% (%.2f sigma)\n", sxl_comm_quantity_name((uint16_t)q),
                      100.0 * (r->comm.value[q] / r->comm.truth[q] - 1.0), error_sigmas(r, q));
        assert_int_equal(r->comm.quality[q], SXL_COMM_QUALITY_OK);
        assert_true(err <= lim[k].limit * r->comm.truth[q] ||
                    (q == SXL_COMM_Q_FRICTION && err <= 2e-4));
        assert_true(error_sigmas(r, q) < 3.0);
    }
}

/* Issue 25's grid, the whole sequence in both arithmetics. A rotor ten times the set's inertia:
 * before, L_d and L_q ended poor (rotor_moved: its slow swing about the held angle, which biased
 * neither), and psi_f and J read 3.6 % high (the encoder step's measured counts per electrical
 * turn, 3.4 % off on the swinging rotor, scaled every later speed). Ten times the reference
 * friction: before, B read 5.4 % high at 1.5 % sigma (the x-y currents of the magnet's 5th and
 * 7th harmonics made a drag the fundamental's torque leaves out). */
static void test_heavy_rotor_and_harmonic_drag(void **state)
{
    int a;
    (void)state;
    for (a = 0; a < 2; a++) {
        sim_config_t c;
        sim_result_t r;
        config(&c, NULL, a);
        c.plant.j_kgm2 = 10.0 * REF_J;
        run(&c, &r);
        print_message("%s, J 10 x:\n", r.arith);
        check_limits(&r);
        config(&c, NULL, a);
        c.plant.b_nms = 10.0 * REF_B;
        run(&c, &r);
        print_message("%s, friction 10 x:\n", r.arith);
        check_limits(&r);
    }
}

/* A speed step at 1000 r/min, no load, the product's DDC: overshoot (%) and the time until the
 * speed (2 ms means of the plant's: the light rotor's speed carries +-0.6 r/min of the torque's
 * ripple) stays within 5 % of the step. */
static void speed_step(double j, double step_rpm, double kp, double ki, double *overshoot,
                       double *settle_s)
{
    const double to_rpm = 60.0 / (2.0 * 3.14159265358979323846);
    const long before = 10000, after = 15000, block = 20;
    sim_config_t c;
    sim_result_t r;
    sim_run_t rs;
    double peak = 0.0, sum = 0.0;
    long k, last_out = 0;
    config(&c, NULL, 0);
    c.scenario = SIM_SCEN_STEADY;
    c.speed_rpm = 1000.0;
    c.load_nm = 0.0;
    c.duration_s = (double)(before + after) * 1e-4;
    c.plant.j_kgm2 = j;
    c.ctl.j_kgm2 = j;
    c.ctl.speed_kp = kp;
    c.ctl.speed_ki = ki;
    start_stepwise(&rs, &c, &r);
    for (k = 0; k < before + after; k++) {
        if (k == before) {
            rs.ops->set_speed_rpm(1000.0 + step_rpm);
        }
        assert_int_equal(sim_loop_period(&rs, &r, k), 0);
        sum += rs.x.omega_m * to_rpm;
        if (k >= before && (k + 1) % block == 0) {
            const double rise = sum / (double)block - 1000.0;
            peak = fmax(peak, rise);
            last_out = (fabs(rise - step_rpm) > 0.05 * step_rpm) ? k + 1 : last_out;
        }
        sum = ((k + 1) % block == 0) ? 0.0 : sum;
    }
    sim_teardown(&rs, true);
    *overshoot = 100.0 * (peak - step_rpm) / step_rpm;
    *settle_s = (double)(last_out - before) * 1e-4;
}

/* The speed loop on 0.2 and 10 times the reference inertia: the gains designed from the
 * identified inertia against today's fixed ones (1.5 N m s/rad, 60 N m/rad). The design (a
 * double pole at -w_c/2, a zero at -w_c/4) overshoots 13.6 % and settles within 5 % after
 * 8.3 / w_c; the targets (docs/commissioning.md): overshoot at most 20 %, settling within
 * 10 / w_c, at both inertias. The fixed gains meet neither on the heavy rotor. */
static void test_speed_step_with_designed_gains(void **state)
{
    static const double js[] = {0.2 * REF_J, 10.0 * REF_J};
    /* steps no gain here turns into more than 7 N m (the torque limit): linear responses */
    static const double steps_rpm[] = {40.0, 10.0};
    size_t k;
    (void)state;
    for (k = 0; k < sizeof js / sizeof js[0]; k++) {
        sim_result_t r;
        double kp, ki, wc, os_d, ts_d, os_f, ts_f;
        run_mech(js[k], REF_B, 0, &r);
        assert_int_equal(r.comm.quality[SXL_COMM_Q_INERTIA], SXL_COMM_QUALITY_OK);
        designed_gains(r.comm.value[SXL_COMM_Q_INERTIA], &kp, &ki, &wc);
        speed_step(js[k], steps_rpm[k], r.comm.speed_kp, r.comm.speed_ki, &os_d, &ts_d);
        speed_step(js[k], steps_rpm[k], 1.5, 60.0, &os_f, &ts_f);
        print_message("J %.3g kg m^2, %.0f r/min step: designed kp %.3g ki %.4g (w_c %.1f rad/s): "
                      "overshoot %.1f %%, settling %.1f ms; fixed kp 1.5 ki 60: overshoot %.1f %%, "
                      "settling %.1f ms\n",
                      js[k], steps_rpm[k], r.comm.speed_kp, r.comm.speed_ki, wc, os_d, 1e3 * ts_d,
                      os_f, 1e3 * ts_f);
        assert_true(os_d < 20.0);
        assert_true(ts_d < 10.0 / wc);
        if (js[k] > REF_J) {
            assert_true(os_f > 20.0 && ts_f > 10.0 / wc);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_five_plants_fixed),
        cmocka_unit_test(test_five_plants_float),
        cmocka_unit_test(test_droop_and_amplitude),
        cmocka_unit_test(test_closed_loop_after_commissioning),
        cmocka_unit_test(test_wrong_pole_pairs_and_swapped_channels),
        cmocka_unit_test(test_load_torque_found),
        cmocka_unit_test(test_dragged_rotor_is_a_load),
        cmocka_unit_test(test_failed_sequence_writes_no_file),
        cmocka_unit_test(test_weak_magnet_applied),
        cmocka_unit_test(test_current_within_a_fraction_of_the_trip_level),
        cmocka_unit_test(test_refused_with_the_dc_link_low),
        cmocka_unit_test(test_refused_with_the_rotor_turning),
        cmocka_unit_test(test_refused_while_running),
        cmocka_unit_test(test_open_phase_checked_again_after_clear),
        cmocka_unit_test(test_open_phase_in_each_step),
        cmocka_unit_test(test_weak_magnet),
        cmocka_unit_test(test_small_load_lag_taken_out),
        cmocka_unit_test(test_heavy_rotor_and_harmonic_drag),
        cmocka_unit_test(test_resistance_ripple_is_not_a_sign_change),
        cmocka_unit_test(test_inertia_and_friction_over_the_range),
        cmocka_unit_test(test_speed_step_with_designed_gains),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
