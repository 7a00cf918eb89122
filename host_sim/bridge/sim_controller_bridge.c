/*
 * Bridge between the simulator and one build of the control core + drive
 * application. Compiled twice: SIM_BRIDGE_FLOAT=0 against ctl_fixed /
 * drive_fixed, SIM_BRIDGE_FLOAT=1 against ctl_float / drive_float. In the
 * float build every global symbol of (bridge + ctl_float + drive_float) gets
 * the prefix "simflt_" at build time, so both live in one binary.
 */
#include <stddef.h>

#include "ctl.h"
#include "ctl_pu.h"
#include "drive/drive.h"
#include "drive/drive_commission.h"
#include "hal_cycles.h"
#include "service/link_service.h"
#include "measure/profile.h"
#include "sim_ctl.h"

#if SIM_BRIDGE_FLOAT
#define SIM_BRIDGE_OPS sim_ctl_ops_float
#define SIM_BRIDGE_ARITH "float"
#else
#define SIM_BRIDGE_OPS sim_ctl_ops_fixed
#define SIM_BRIDGE_ARITH "fixed"
#endif

static drive_t bridge_drive;
static link_service_t bridge_link;
static bool bridge_board;    /* serving as the virtual board: the ISR is timed and profiled */
static bool bridge_shutdown; /* the host sent SXL_CMD_SIM_SHUTDOWN */

/* Thresholds no measurement can reach: the simulator's way of watching a controller that
 * would trip the drive. An ordinary parameter set (the firmware accepts the same values over
 * its parameter path); the largest thresholds saturate the per-unit limits. */
static void bridge_protect_out_of_reach(ctl_protect_settings_t *s)
{
    const float big = 1.0e6f;
    s->overcurrent_a = big;
    s->dc_overvoltage_v = big;
    s->dc_undervoltage_v = 0.0f;
    s->overspeed_rpm = big;
    s->current_sum_a = big;
    s->adc_rail_low_counts = -1;
    s->adc_rail_high_counts = INT16_MAX;
    s->stuck_min_current_a = big;
    s->encoder_torque_nm = big;
    s->encoder_jump_turns = big;
    s->open_phase_min_current_a = big;
    s->open_phase_fast_min_a = big;
}

/* The speed loop's gains and torque limit: designed from the inertia, or given, or the core's. */
static void bridge_speed_loop(const sim_ctl_config_t *cfg, ctl_params_t *p)
{
    if (cfg->speed_gains_from_j) {
        ctl_speed_gains_from_inertia(p);
    } else {
        if (cfg->speed_kp > 0.0) {
            p->speed_kp_nm_per_rad_s = (float)cfg->speed_kp;
        }
        if (cfg->speed_ki > 0.0) {
            p->speed_ki_nm_per_rad = (float)cfg->speed_ki;
        }
    }
    if (cfg->torque_limit_nm > 0.0) {
        p->torque_limit_nm = (float)cfg->torque_limit_nm;
    }
}

static int bridge_init(const sim_ctl_config_t *cfg, const char **why)
{
    ctl_params_t p;
    ctl_param_error_t e;
    ctl_params_default(&p);
    p.resistance_ohm = (float)cfg->r_ohm;
    p.ld_h = (float)cfg->ld_h;
    p.lq_h = (float)cfg->lq_h;
    p.l_xy_h = (float)cfg->lxy_h;
    p.pm_flux_wb = (float)cfg->psi_f_wb;
    p.pole_pairs = (int16_t)cfg->pole_pairs;
    if (cfg->j_kgm2 > 0.0) {
        p.inertia_kg_m2 = (float)cfg->j_kgm2;
    }
    p.sample_time_s = (float)cfg->ts_s;
    p.controller = (ctl_controller_t)cfg->controller;
    p.lambda_nm_per_wb = (float)cfg->lambda;
    if (cfg->duty_levels > 0) {
        p.duty_levels = (int16_t)cfg->duty_levels;
    }
    if (cfg->ddc_direction >= 0) {
        p.ddc_direction = (ctl_ddc_direction_t)cfg->ddc_direction;
    }
    if (cfg->mid_period_angle >= 0) {
        p.mid_period_angle = (cfg->mid_period_angle != 0);
    }
    if (cfg->pulse_pattern >= 0) {
        p.pulse_pattern = (ctl_pulse_pattern_t)cfg->pulse_pattern;
    }
    if (cfg->flux_tie_band >= 0.0) {
        p.ddc_flux_tie_band = (float)cfg->flux_tie_band;
    }
    if (cfg->ddc_torque_guard >= 0) {
        p.ddc_torque_guard = (cfg->ddc_torque_guard != 0);
    }
    if (cfg->flux_ref_mode >= 0) {
        p.flux_ref_mode = (ctl_flux_ref_mode_t)cfg->flux_ref_mode;
    }
    if (cfg->light_load_current_a >= 0.0) {
        p.light_load_current_a = (float)cfg->light_load_current_a;
    }
    if (cfg->flux_ref_wb > 0.0) {
        p.flux_ref_wb = (float)cfg->flux_ref_wb;
    }
    bridge_speed_loop(cfg, &p);
    if (!cfg->protect) {
        bridge_protect_out_of_reach(&p.protect);
    }
    if (cfg->postfault_strategy >= 0) {
        p.postfault_strategy = (int16_t)cfg->postfault_strategy;
    }
    e = ctl_params_check(&p);
    if (e != CTL_PARAM_OK) {
        *why = ctl_param_error_text(e);
        return 1;
    }
    *why = "the drive refused a setting (open-phase or torque-limited action, current span)";
    drive_init(&bridge_drive, &p);
    if (cfg->open_phase_action >= 0 &&
        !drive_set_open_phase_action(&bridge_drive, (int16_t)cfg->open_phase_action,
                                     p.postfault_strategy)) {
        return 1;
    }
    if (cfg->torque_limited_action >= 0 &&
        !drive_set_torque_limited_action(&bridge_drive, (int16_t)cfg->torque_limited_action,
                                         (cfg->torque_limited_stop_s > 0.0)
                                             ? (float)cfg->torque_limited_stop_s
                                             : DRIVE_TORQUE_LIMITED_STOP_S)) {
        return 1;
    }
    if (!drive_set_current_span(&bridge_drive, (float)cfg->current_full_span_a)) {
        return 1;
    }
    return (bridge_drive.state == DRIVE_STATE_FAULT) ? 2 : 0;
}

/* On the virtual board the ISR is timed as fw_isr times it on the board, in hal_cycles (host
 * nanoseconds), for the status and profile readouts. */
static void bridge_isr(void)
{
    uint32_t dt;
    uint32_t t0;
    if (!bridge_board) {
        drive_control_isr(&bridge_drive);
        return;
    }
    t0 = hal_cycles_now();
    drive_control_isr(&bridge_drive);
    dt = (uint32_t)(hal_cycles_now() - t0);
    bridge_drive.isr_cycles_last = dt;
    if (dt > bridge_drive.isr_cycles_max) {
        bridge_drive.isr_cycles_max = dt;
    }
}
static void bridge_request_run(void) { drive_request_run(&bridge_drive); }
static void bridge_request_clear(void) { drive_request_clear_fault(&bridge_drive); }
static void bridge_set_speed_rpm(double rpm) { drive_set_speed_ref_rpm(&bridge_drive, (float)rpm); }
static void bridge_set_torque_nm(double nm) { drive_set_torque_ref_nm(&bridge_drive, (float)nm); }

static double q2d(ctl_q v) { return (double)ctl_to_float(v); }

static void bridge_report_overrun(void) { drive_report_overrun(&bridge_drive); }

static int bridge_read_fault_record(sim_fault_record_t *out)
{
    ctl_fault_record_t r;
    int k;
    if (!drive_read_fault_record(&bridge_drive, &r)) {
        return 0;
    }
    out->faults = r.faults;
    out->period = (unsigned long)r.period;
    for (k = 0; k < 6; k++) {
        out->i_phase_a[k] = q2d(r.i_phase[k]) * CTL_BASE_CURRENT_A;
    }
    out->vdc_v = q2d(r.vdc) * CTL_BASE_VOLTAGE_V;
    out->speed_rpm =
        q2d(r.omega_e) * CTL_BASE_OMEGA_RAD_S * 60.0 / CTL_TWO_PI /
        (double)((bridge_drive.params_bg.pole_pairs > 0) ? bridge_drive.params_bg.pole_pairs : 1);
    out->torque_est_nm = q2d(r.torque_est) * CTL_BASE_TORQUE_NM;
    out->torque_ref_nm = q2d(r.torque_ref) * CTL_BASE_TORQUE_NM;
    out->vector = (int)r.vector;
    out->duty = q2d(r.duty);
    return 1;
}

static void bridge_period_status(sim_ctl_status_t *st)
{
    const ctl_diag_t *dg = &bridge_drive.ctl.diag;
    st->state = (int)bridge_drive.state;
    st->ready = bridge_drive.state == DRIVE_STATE_READY;
    st->running = bridge_drive.state == DRIVE_STATE_RUN;
    st->faulted = bridge_drive.state == DRIVE_STATE_FAULT;
    st->commissioning = bridge_drive.state == DRIVE_STATE_COMMISSION;
    st->phase_verifying = bridge_drive.phase_verifying;
    st->fault = (int)bridge_drive.fault;
    st->torque_ref_nm = q2d(dg->torque_ref) * CTL_BASE_TORQUE_NM;
    st->flux_ref_wb = q2d(dg->flux_ref) * CTL_BASE_FLUX_WB;
    st->vector = (int)bridge_drive.cmd.vector;
    st->duty = q2d(bridge_drive.cmd.duty);
    st->enable = bridge_drive.cmd.enable ? 1 : 0;
    st->isolated_leg = (int)bridge_drive.isolated_leg;
    st->torque_limited = bridge_drive.torque_limited ? 1 : 0;
    st->postfault_in_force =
        (bridge_drive.isolated_leg >= 0 &&
         ctl_postfault_config(&bridge_drive.ctl)->open_leg == bridge_drive.isolated_leg)
            ? 1
            : 0;
}

static void bridge_status(sim_ctl_status_t *st)
{
    const ctl_t *c = &bridge_drive.ctl;
    const ctl_params_t *prm = ctl_params(c);
    const ctl_diag_t *dg = &c->diag;
    bridge_period_status(st);
    st->torque_est_nm = q2d(ctl_diag_torque_est(c)) * CTL_BASE_TORQUE_NM;
    st->flux_est_wb = q2d(ctl_diag_flux_est(c)) * CTL_BASE_FLUX_WB;
    st->candidates = (int)dg->candidates;
    st->braking = dg->braking ? 1 : 0;
    st->p_lambda = (double)prm->lambda_nm_per_wb;
    st->p_speed_kp = (double)prm->speed_kp_nm_per_rad_s;
    st->p_speed_ki = (double)prm->speed_ki_nm_per_rad;
    st->p_torque_limit = (double)prm->torque_limit_nm;
    st->p_flux_ref_wb = (double)prm->flux_ref_wb;
    st->p_duty_levels = (int)prm->duty_levels;
    st->p_ddc_direction = (int)prm->ddc_direction;
    st->p_flux_ref_mode = (int)prm->flux_ref_mode;
    st->p_ddc_torque_guard = prm->ddc_torque_guard ? 1 : 0;
    st->p_mid_period_angle = prm->mid_period_angle ? 1 : 0;
    st->p_pulse_pattern = (int)prm->pulse_pattern;
    st->p_flux_tie_band = (double)prm->ddc_flux_tie_band;
    st->faults_latched = (unsigned)drive_faults_latched(&bridge_drive);
    st->fault_records = (int)ctl_protect_log_pending(&bridge_drive.protect);
    st->run_refusal = (int)bridge_drive.run_refusal;
    st->run_refused = (unsigned)bridge_drive.run_refused;
    st->torque_limit_nm = q2d(ctl_config(c)->torque_limit) * CTL_BASE_TORQUE_NM;
    st->torque_limited_stopped = bridge_drive.torque_limited_stopped ? 1 : 0;
}

/* The virtual board's own command (a board answers it "unknown"): SXL_CMD_SIM_SHUTDOWN is
 * answered OK, then the simulator stops once the reply is out. */
static bool bridge_platform(void *ctx, const sxl_frame_t *req, sxl_frame_t *reply)
{
    (void)ctx;
    if (req->cmd != SXL_CMD_SIM_SHUTDOWN) {
        return false;
    }
    reply->cmd = (uint16_t)(SXL_CMD_SIM_SHUTDOWN | SXL_REPLY);
    reply->len = 1u;
    reply->payload[0] = (uint16_t)((req->len == 0u) ? SXL_OK : SXL_ERR_LENGTH);
    bridge_shutdown = bridge_shutdown || req->len == 0u;
    return true;
}

/* The ISR timed and its stages marked, as fw_startup sets the board up. */
static void bridge_profile(void)
{
    bridge_board = true;
    ctl_set_stage_hook(&bridge_drive.ctl, prof_ctl_stage);
}

/* A partial frame older than gap_s (of hal_cycles, host time on the simulator) is dropped. */
static void bridge_link_init(double gap_s)
{
    link_service_init(&bridge_link, (uint32_t)(gap_s * (double)hal_cycles_per_second()));
    link_service_set_platform(&bridge_link, bridge_platform, NULL);
    bridge_shutdown = false;
    bridge_profile();
}
static void bridge_link_step(void) { link_service_step(&bridge_link, &bridge_drive); }

static int bridge_commission_start(unsigned mask, unsigned permille)
{
    return (int)drive_request_commission(&bridge_drive, (uint16_t)mask, (uint16_t)permille);
}

static void bridge_commission_status(sim_comm_status_t *st)
{
    const comm_t *c = &bridge_drive.comm;
    int q;
    st->state = (int)c->state;
    st->step = (int)c->step;
    st->reason = (int)c->reason;
    st->progress = (int)comm_progress_percent(c);
    st->periods = (unsigned long)c->periods;
    for (q = 0; q < SIM_CTL_COMM_QUANTITIES && q < (int)COMM_Q_COUNT; q++) {
        const ident_result_t *r = &c->x.result[q];
        st->value[q] = (double)r->value;
        st->sigma[q] = (double)r->sigma;
        st->extra[q] = (double)r->extra;
        st->quality[q] = (int)r->quality;
        st->reason_q[q] = (int)r->reason;
    }
}

static int bridge_commission_apply(unsigned *applied, double speed_gains[2])
{
    uint16_t a = 0u;
    const int rc = (int)drive_commission_apply(&bridge_drive, &a);
    const ctl_params_t *p = (a != 0u) ? &bridge_drive.params_req : ctl_params(&bridge_drive.ctl);
    *applied = (unsigned)a;
    speed_gains[0] = (double)p->speed_kp_nm_per_rad_s;
    speed_gains[1] = (double)p->speed_ki_nm_per_rad;
    return rc;
}
static unsigned long bridge_link_frames(void) { return (unsigned long)bridge_link.frames_handled; }
static int bridge_link_shutdown(void)
{
    return (bridge_shutdown && link_service_sent(&bridge_link)) ? 1 : 0;
}
static void bridge_background(void) { drive_background(&bridge_drive); }
static int bridge_isolate_leg(int leg)
{
    return drive_request_isolate_leg(&bridge_drive, (int16_t)leg) ? 1 : 0;
}

const sim_ctl_ops_t SIM_BRIDGE_OPS = {SIM_BRIDGE_ARITH,
                                      bridge_init,
                                      bridge_isr,
                                      bridge_request_run,
                                      bridge_set_speed_rpm,
                                      bridge_set_torque_nm,
                                      bridge_status,
                                      bridge_report_overrun,
                                      bridge_read_fault_record,
                                      bridge_link_init,
                                      bridge_link_step,
                                      bridge_link_frames,
                                      bridge_link_shutdown,
                                      bridge_period_status,
                                      bridge_request_clear,
                                      bridge_background,
                                      bridge_isolate_leg,
                                      bridge_commission_start,
                                      bridge_commission_status,
                                      bridge_commission_apply,
                                      bridge_profile};
