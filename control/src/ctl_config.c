#include "ctl_config.h"

#include "ctl_foc_config.h"
#include "ctl_postfault_config.h"
#include "ctl_pu.h"

ctl_param_error_t ctl_config_build(ctl_config_t *cfg, const ctl_params_t *p)
{
    const ctl_param_error_t e = ctl_params_check(p);
    if (e != CTL_PARAM_OK) {
        return e;
    }
    cfg->params = *p;
    /* checked above: neither can fail */
    (void)ctl_model_init(&cfg->model, p->resistance_ohm, p->ld_h, p->lq_h, p->l_xy_h, p->pm_flux_wb,
                         p->pole_pairs, p->sample_time_s);
    {
        const ctl_flux_ref_machine_t m = {p->ld_h, p->lq_h, p->pm_flux_wb, p->pole_pairs};
        ctl_flux_ref_init(&cfg->flux_ref, p->flux_ref_mode, p->flux_ref_wb, &m, p->torque_limit_nm,
                          p->light_load_current_a,
                          (p->controller == CTL_CONTROLLER_FOC) ? cfg->ctrl.foc.id_ref : 0);
    }
    cfg->lambda = ctl_from_float(p->lambda_nm_per_wb * (CTL_BASE_FLUX_WB_F / CTL_BASE_TORQUE_NM_F));
    /* With an open phase the same alpha-beta current drives the healthy phases to peak_ratio
     * times the healthy peak (1.80 with minimum loss): the limit shrinks by that ratio, so they
     * stay within the current the healthy limit allows. */
    cfg->torque_limit = ctl_from_float(
        p->torque_limit_nm / CTL_BASE_TORQUE_NM_F /
        ctl_postfault_peak_ratio(p->open_phase, (ctl_postfault_strategy_t)p->postfault_strategy));
    cfg->speed_kp = ctl_from_float(ctl_speed_gain_pu(p->speed_kp_nm_per_rad_s, p->pole_pairs));
    /* integrator gain per step: ki in N*m per mechanical rad, so ki * Ts per (rad/s) */
    cfg->speed_ki_ts =
        ctl_from_float(ctl_speed_gain_pu(p->speed_ki_nm_per_rad, p->pole_pairs) * p->sample_time_s);
    /* With an open phase the torque guard is always on: without it the flux term chose the
     * levels on the five legs' weaker voltages and the torque was lost (the paper's DDC with C
     * open at 3.5 N m fell to 570 r/min). */
    if (p->controller == CTL_CONTROLLER_FOC) {
        ctl_foc_config_build(&cfg->ctrl.foc, p);
    } else {
        ctl_ddc_config_init(&cfg->ctrl.ddc, (int16_t)p->ddc_direction, p->duty_levels,
                            p->ddc_torque_guard || p->open_phase != CTL_POSTFAULT_NO_LEG,
                            p->ddc_flux_tie_band);
    }
    cfg->omega_pu_per_rev_s =
        ctl_from_float((CTL_TWO_PI_F / CTL_BASE_OMEGA_RAD_S_F) * (float)p->pole_pairs);
    ctl_protect_limits_build(&cfg->protect, &p->protect, p->sample_time_s, p->pole_pairs,
                             p->inertia_kg_m2);
    return CTL_PARAM_OK;
}
