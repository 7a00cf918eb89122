/* Setting up a run and calibrating the drive before the scenario clock, see sim_run_state.h. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ctl_machine.h"
#include "hal_cycles.h"
#include "hal_sim.h"
#include "sim_open_phase.h"
#include "sim_run_state.h"
#include "sxlink.h"

/* The drive calibrates for DRIVE_CALIBRATION_SAMPLES (1024) periods; this bounds the wait. */
#define SIM_CAL_PERIODS_MAX 4096

double sim_wall_now(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int setup_fail(char *err, size_t len, const char *msg)
{
    (void)snprintf(err, len, "%s", msg);
    return -1;
}

/* A controller machine value: the one set, else the reference machine's. */
static double setup_ctl_value(double set, double reference)
{
    return (set >= 0.0) ? set : reference;
}

int sim_ctl_pole_pairs(const sim_config_t *c)
{
    return (c->ctl.pole_pairs > 0) ? c->ctl.pole_pairs : CTL_MACHINE_POLE_PAIRS;
}

void sim_ctl_machine_resolve(const sim_config_t *c, sim_ctl_machine_t *m)
{
    m->r_ohm = setup_ctl_value(c->ctl.r_ohm, CTL_MACHINE_R_OHM);
    m->ld_h = setup_ctl_value(c->ctl.ld_h, CTL_MACHINE_LD_H);
    m->lq_h = setup_ctl_value(c->ctl.lq_h, CTL_MACHINE_LQ_H);
    m->lxy_h = setup_ctl_value(c->ctl.lxy_h, CTL_MACHINE_LXY_H);
    m->psi_f_wb = setup_ctl_value(c->ctl.psi_f_wb, CTL_MACHINE_PSI_F_WB);
    m->pole_pairs = sim_ctl_pole_pairs(c);
    m->encoder_offset_rad = c->ctl.encoder_offset_rad;
    m->j_kgm2 = setup_ctl_value(c->ctl.j_kgm2, CTL_MACHINE_INERTIA_KG_M2);
    m->speed_kp = c->ctl.speed_kp;
    m->speed_ki = c->ctl.speed_ki;
    m->speed_gains_from_j = c->ctl.speed_gains_from_j;
}

void sim_controller_config(const sim_config_t *c, const plant_params_t *p, double ts_s,
                           double torque_limit_nm, sim_ctl_config_t *cc)
{
    memset(cc, 0, sizeof *cc);
    cc->controller = c->controller;
    cc->lambda = c->lambda;
    cc->ts_s = ts_s;
    cc->duty_levels = c->duty_levels;
    cc->ddc_direction = c->ddc_direction;
    cc->flux_ref_mode = c->flux_ref_mode;
    cc->ddc_torque_guard = c->ddc_torque_guard;
    cc->mid_period_angle = c->mid_period_angle;
    cc->pulse_pattern = c->pulse_pattern;
    cc->flux_tie_band = c->flux_tie_band;
    cc->light_load_current_a = c->light_load_current_a;
    cc->flux_ref_wb = 0.0;
    sim_ctl_machine_t m;
    sim_ctl_machine_resolve(c, &m);
    cc->r_ohm = m.r_ohm;
    cc->ld_h = m.ld_h;
    cc->lq_h = m.lq_h;
    cc->lxy_h = m.lxy_h;
    cc->psi_f_wb = m.psi_f_wb;
    cc->pole_pairs = m.pole_pairs;
    cc->j_kgm2 = m.j_kgm2;
    cc->speed_kp = m.speed_kp;
    cc->speed_ki = m.speed_ki;
    cc->speed_gains_from_j = m.speed_gains_from_j;
    cc->torque_limit_nm = torque_limit_nm;
    cc->protect = c->protect ? 1 : 0;
    cc->current_full_span_a = 2.0 * p->current_sensor_span_a;
    cc->open_phase_action = c->open_phase_action;
    cc->postfault_strategy = c->postfault_strategy;
    cc->torque_limited_action = c->torque_limited_action;
    cc->torque_limited_stop_s = c->torque_limited_stop_s;
}

/* Periods, window and fine sampling of the run. */
static int setup_timing(sim_run_t *rs, char *err, size_t err_len)
{
    const sim_config_t *c = rs->cfg;
    int j;
    rs->ts = 1.0 / c->fs_hz;
    rs->ts_ns = (uint32_t)lround(1e9 * rs->ts);
    rs->n_periods = lround(rs->plan.duration / rs->ts);
    if (rs->n_periods < 10) {
        return setup_fail(err, err_len, "duration shorter than 10 control periods");
    }
    rs->k_win = rs->n_periods - lround(rs->plan.window / rs->ts);
    if (rs->k_win < 0) {
        rs->k_win = 0;
    }
    rs->n_fine = (int)ceil(
        ((c->fine_rate_hz > 0.0) ? c->fine_rate_hz : SIM_DEFAULT_FINE_RATE_HZ) / c->fs_hz - 1e-9);
    if (rs->n_fine < 4) {
        rs->n_fine = 4;
    }
    rs->fine_times = (double *)calloc((size_t)rs->n_fine, sizeof(double));
    if (!rs->fine_times) {
        return setup_fail(err, err_len, "out of memory");
    }
    for (j = 0; j < rs->n_fine; j++) {
        rs->fine_times[j] = rs->ts * (double)j / (double)rs->n_fine;
    }
    return 0;
}

/* HAL and controller, as the firmware's main would set them up. */
static int setup_drive(sim_run_t *rs, char *err, size_t err_len)
{
    const plant_params_t *p = &rs->plant;
    const double offset_turns = rs->cfg->ctl.encoder_offset_rad / (2.0 * 3.14159265358979323846);
    const uint32_t offset =
        (uint32_t)(int64_t)llround((offset_turns - floor(offset_turns)) * 4294967296.0);
    sim_ctl_config_t cc;
    const char *why = "";
    hal_sim_reset();
    if (!hal_pwm_init((uint32_t)lround(rs->cfg->fs_hz),
                      (uint32_t)lround((p->dead_time_on ? p->dead_time_s : 0.0) * 1e9)) ||
        !hal_adc_init() ||
        !hal_encoder_init(p->encoder_lines, (uint16_t)sim_ctl_pole_pairs(rs->cfg), offset)) {
        return setup_fail(err, err_len, "simulator HAL refused its configuration");
    }
    hal_cycles_init();
    sim_controller_config(rs->cfg, &rs->plant, rs->ts, rs->plan.torque_limit, &cc);
    if (rs->ops->init(&cc, &why) != 0) {
        (void)snprintf(err, err_len, "control core rejected the parameters: %s", why);
        return -1;
    }
    return 0;
}

/* Processor in the loop: the drive's periods on the target, this build beside it. */
static int setup_pil(sim_run_t *rs, char *err, size_t err_len)
{
    char csv[1200];
    const char *dir = rs->cfg->out_dir;
    if (dir) {
        (void)snprintf(csv, sizeof csv, "%s/pil.csv", dir);
    }
    rs->ops = sim_pil_open(rs->ops, rs->cfg->pil_target, 1.0 / rs->cfg->fs_hz, dir ? csv : NULL,
                           err, err_len);
    if (!rs->ops) {
        return -1;
    }
    rs->pil_open = true;
    return 0;
}

int sim_setup(sim_run_t *rs, const sim_config_t *c, char *err, size_t err_len)
{
    memset(rs, 0, sizeof *rs);
    rs->cfg = c;
    rs->ops = (c->arith == 1) ? &simflt_sim_ctl_ops_float : &sim_ctl_ops_fixed;
    if (c->pil_target && setup_pil(rs, err, err_len) != 0) {
        return -1;
    }
    rs->plant = c->plant;
    rs->k_detect = -1;
    sim_plan(c, &rs->plan);
    sim_fault_begin(&rs->fault, c->fault,
                    (c->fault_time_s > 0.0) ? c->fault_time_s : SIM_FAULT_INJECT_S);
    if (sim_open_phase_begin(rs, err, err_len) != 0) {
        return -1;
    }
    if (c->fault != SIM_FAULT_NONE && !sim_fault_at_power_up(c->fault) &&
        !(rs->fault.t_inject < rs->plan.duration)) {
        return setup_fail(err, err_len, "fault injection time must be inside the run");
    }
    if (setup_timing(rs, err, err_len) != 0) {
        return -1;
    }
    {
        const size_t win = (size_t)(rs->n_periods - rs->k_win);
        if (sim_metrics_open(&rs->metrics, win * (size_t)rs->n_fine + 4u, win) != 0) {
            return setup_fail(err, err_len, "out of memory");
        }
    }
    if (sim_recorder_open(&rs->rec, c->out_dir, c->write_trace, c->write_fine, c->out_limit_mb, err,
                          err_len) != 0 ||
        setup_drive(rs, err, err_len) != 0) {
        return -1;
    }
    inverter_init(&rs->inv, &rs->plant, rs->ts);
    rs->x.omega_m = rs->plan.speed0 * 2.0 * 3.14159265358979323846 / 60.0;
    rs->x.theta_m = rs->plan.theta0_rad;
    plant_sync_angle(&rs->plant, &rs->x);
    sim_adc_init(&rs->adc, &rs->plant, c->seed);
    sim_encoder_init(&rs->encoder, rs->ts);
    /* commissioning finds the index itself; every other scenario starts homed */
    sim_encoder_power_up(&rs->encoder, &rs->plant, &rs->x, c->scenario != SIM_SCEN_COMMISSION);
    return 0;
}

/* Calibration periods until the drive is READY (or FAULT); returns the drive's status. */
static void calibrate_periods(sim_run_t *rs, sim_ctl_status_t *st)
{
    long cal;
    rs->ops->period_status(st);
    for (cal = 0; cal < SIM_CAL_PERIODS_MAX && !st->ready; cal++) {
        if (rs->pil_open && sim_pil_error()) {
            break; /* the target is gone: sim_setup_calibrate says so */
        }
        double iph[6];
        hal_sim_clock_advance(rs->ts_ns);
        plant_phase_currents(&rs->plant, &rs->x, iph);
        sim_adc_sample(&rs->adc, &rs->plant, iph, &rs->fault);
        sim_encoder_sample(&rs->encoder, &rs->plant, &rs->x,
                           (double)(cal - SIM_CAL_PERIODS_MAX) * rs->ts, rs->ts, &rs->fault);
        rs->ops->isr();
        (void)inverter_run_period(&rs->inv, &rs->plant, &rs->x, rs->duty, true, 0.0, true, NULL, 0,
                                  NULL, NULL);
        rs->ops->period_status(st);
        if (st->faulted) {
            rs->cal_isr_calls = cal + 1;
            return;
        }
    }
    rs->cal_isr_calls = cal;
}

int sim_setup_calibrate(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len)
{
    sim_ctl_status_t st;
    calibrate_periods(rs, &st);
    if (sim_loop_pil_failed(rs, 0, err, err_len)) {
        return -1;
    }
    if (st.faulted && sim_fault_at_power_up(rs->cfg->fault)) {
        /* found by the calibration: the latency is the calibration itself */
        r->fault_inject_s = 0.0;
        r->fault_detect_ms = 1e3 * (double)rs->cal_isr_calls * rs->ts;
        r->fault = st.fault;
        rs->k_detect = 0;
    } else if (st.faulted) {
        (void)snprintf(err, err_len,
                       "the drive stopped in fault %s during its ADC calibration, before the "
                       "scenario (the operating point is beyond a protection limit: "
                       "docs/faults.md; --no-protect lifts them)",
                       sxl_fault_name((uint16_t)st.fault));
        return -1;
    } else if (!st.ready) {
        return setup_fail(err, err_len, "drive did not finish ADC calibration");
    }
    rs->x.theta_m = rs->plan.theta0_rad;
    plant_sync_angle(&rs->plant, &rs->x);
    sim_encoder_restart(&rs->encoder);
    if (rs->cfg->scenario != SIM_SCEN_COMMISSION) { /* it asks for its sequence instead */
        rs->ops->set_speed_rpm(rs->plan.speed0);
        rs->ops->request_run(); /* refused by a drive already in FAULT */
    }
    rs->adc.clipped = 0;
    r->outputs_off = true;
    r->fault_time_s = (rs->k_detect == 0) ? 0.0 : -1.0;
    r->trip_time_s = -1.0;
    return 0;
}

void sim_teardown(sim_run_t *rs, bool ok)
{
    if (!ok) {
        sim_recorder_discard(&rs->rec);
    }
    sim_metrics_close(&rs->metrics);
    inverter_free(&rs->inv);
    free(rs->fine_times);
    rs->fine_times = NULL;
}
