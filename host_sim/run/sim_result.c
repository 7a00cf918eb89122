/* A finished run's result record, see sim_run_state.h. */
#include <stdio.h>

#include "plant/inverter_loss.h"
#include "sim_open_phase.h"
#include "sim_run_state.h"

static void result_identity(const sim_run_t *rs, sim_result_t *r)
{
    const sim_config_t *c = rs->cfg;
    (void)snprintf(r->controller, sizeof r->controller, "%s", sim_controller_name(c->controller));
    (void)snprintf(r->arith, sizeof r->arith, "%s", rs->ops->arith);
    if (c->fault != SIM_FAULT_NONE) {
        (void)snprintf(r->scenario, sizeof r->scenario, "fault-%s", sim_fault_info(c->fault)->name);
        if (r->fault_inject_s < 0.0) {
            r->fault_inject_s = rs->fault.t_inject; /* injected, never detected */
        }
    } else {
        (void)snprintf(r->scenario, sizeof r->scenario, "%s", sim_scenario_name(c->scenario));
    }
    r->lambda = c->lambda;
    r->fs_hz = c->fs_hz;
    r->speed_ref_rpm = rs->plan.speed;
    r->load_nm = rs->plan.load;
    r->duration_s = (double)rs->n_periods * rs->ts;
    r->window_start_s = (double)rs->k_win * rs->ts;
    r->window_end_s = (double)rs->n_periods * rs->ts;
    {
        sim_ctl_machine_t m;
        sim_ctl_machine_resolve(c, &m);
        r->ctl_r_ohm = m.r_ohm;
        r->ctl_ld_h = m.ld_h;
        r->ctl_lq_h = m.lq_h;
        r->ctl_lxy_h = m.lxy_h;
        r->ctl_psi_f_wb = m.psi_f_wb;
        r->ctl_pole_pairs = m.pole_pairs;
        r->ctl_encoder_offset_deg = m.encoder_offset_rad * (180.0 / 3.14159265358979323846);
    }
}

/* The drive at the end: state, faults, its first fault record, the parameters in force. */
static void result_drive(const sim_run_t *rs, sim_result_t *r)
{
    sim_ctl_status_t st;
    sim_fault_record_t rec;
    rs->ops->status(&st);
    r->final_state = st.state;
    if (r->fault_time_s < 0.0) {
        r->fault = st.fault;
        r->outputs_off = false; /* nothing detected: nothing to be off for */
    }
    r->faults_latched = st.faults_latched;
    r->fault_records = st.fault_records;
    r->torque_limited_stopped = st.torque_limited_stopped != 0; /* kept until the next run */
    r->have_first_record = rs->ops->read_fault_record(&rec) != 0;
    if (r->have_first_record) {
        r->first_record = rec;
        /* protection period n (1-based) is ISR call n: calibration calls come first */
        r->first_record_t_s = ((double)rec.period - 1.0 - (double)rs->cal_isr_calls) * rs->ts;
    }
    r->p_speed_kp = st.p_speed_kp;
    r->p_speed_ki = st.p_speed_ki;
    r->p_torque_limit = st.p_torque_limit;
    r->p_flux_ref_wb = st.p_flux_ref_wb;
    r->p_duty_levels = st.p_duty_levels;
    r->p_ddc_direction = st.p_ddc_direction;
    r->p_flux_ref_mode = st.p_flux_ref_mode;
    r->p_ddc_torque_guard = st.p_ddc_torque_guard;
    r->p_mid_period_angle = st.p_mid_period_angle;
    r->p_pulse_pattern = st.p_pulse_pattern;
    r->p_flux_tie_band = st.p_flux_tie_band;
}

void sim_result_fill(sim_run_t *rs, sim_result_t *r)
{
    result_identity(rs, r);
    result_drive(rs, r);
    if (rs->cfg->scenario == SIM_SCEN_COMMISSION) { /* no analysis window: the sequence */
        r->wall_s = rs->wall1_s - rs->wall0_s;
        r->realtime_factor = (r->wall_s > 0.0) ? r->duration_s / r->wall_s : 0.0;
        r->thd_percent = r->thd50_percent = r->transient_ms = -1.0;
        r->speed_settle_ms = r->speed_peak_error_rpm = -1.0;
        return;
    }
    r->wall_s = rs->wall1_s - rs->wall0_s;
    r->realtime_factor = (r->wall_s > 0.0) ? r->duration_s / r->wall_s : 0.0;
    r->isr_mean_us = (rs->isr_timed > 0) ? 1e6 * rs->isr_wall_s / (double)rs->isr_timed : 0.0;
    r->adc_clipped = rs->adc.clipped;
    r->switching_freq_hz =
        (double)rs->inv.transitions / 2.0 / 6.0 / (r->window_end_s - r->window_start_s);
    sim_metrics_finish(&rs->metrics, r);
    r->switching_loss_w = inv_loss_switching_w(rs->inv.switched_amps, rs->cfg->plant.vdc_v,
                                               r->window_end_s - r->window_start_s);
    r->inverter_loss_w = inv_loss_conduction_w(r->phase_current_rms_a) + r->switching_loss_w;
    sim_open_phase_finish(rs, r);
}
