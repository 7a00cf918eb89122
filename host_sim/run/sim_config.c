/* A run's configuration: defaults and names, see sim_config.h. */
#include "sim_config.h"

#include <string.h>

#include "ctl_params.h"
#include "sxlink_commission.h"

#define SIM_FINE_RATE_HZ 100000.0

const char *sim_controller_name(int controller) { return ctl_controller_name(controller); }

const char *sim_scenario_name(sim_scenario_t s)
{
    switch (s) {
    case SIM_SCEN_STEADY:
        return "steady";
    case SIM_SCEN_LOAD_STEP:
        return "load-step";
    case SIM_SCEN_ACCEL:
        return "accel";
    case SIM_SCEN_REVERSAL:
        return "reversal";
    case SIM_SCEN_COMMISSION:
        return "commission";
    default:
        return "?";
    }
}

void sim_config_default(sim_config_t *c)
{
    memset(c, 0, sizeof *c);
    c->controller = 0;
    c->arith = 0;
    c->scenario = SIM_SCEN_STEADY;
    c->lambda = 100.0;
    c->fs_hz = 10000.0;
    c->speed_rpm = SIM_UNSET;
    c->load_nm = SIM_UNSET;
    c->duration_s = 0.0;
    c->seed = 1u;
    c->duty_levels = 0;
    c->ddc_direction = -1;
    c->flux_ref_mode = -1;
    c->ddc_torque_guard = -1;
    c->mid_period_angle = -1;
    c->pulse_pattern = -1;
    c->flux_tie_band = -1.0;
    c->light_load_current_a = -1.0;
    c->protect = true;
    c->fault = SIM_FAULT_NONE;
    c->fault_time_s = 0.0;
    c->open_phase_action = -1;
    c->postfault_strategy = -1;
    c->torque_limited_action = -1;
    c->torque_limited_stop_s = 0.0;
    c->fault_phase = -1;
    c->open_model = 0;
    c->second_fault_phase = -1;
    c->second_fault_s = 0.0;
    c->isolate_leg = -1;
    c->isolate_s = 0.0;
    plant_params_default(&c->plant);
    c->ctl.r_ohm = c->ctl.ld_h = c->ctl.lq_h = c->ctl.lxy_h = c->ctl.psi_f_wb = -1.0;
    c->ctl.pole_pairs = 0;
    c->ctl.j_kgm2 = c->ctl.speed_kp = c->ctl.speed_ki = -1.0;
    c->ctl.encoder_offset_rad = 0.0;
    c->commission_steps = SXL_COMM_STEPS_ALL;
    c->commission_permille = SXL_COMM_CURRENT_DEFAULT_PERMILLE;
    c->out_dir = NULL;
    c->write_trace = true;
    c->out_limit_mb = SIM_DEFAULT_OUT_LIMIT_MB;
    c->write_fine = true;
    c->fine_rate_hz = SIM_FINE_RATE_HZ;
    c->observer = NULL;
}
