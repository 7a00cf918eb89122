/* FOC-VSD's configuration (ctl_foc.h), built with the rest of a set's outside the ISR. */
#include "ctl_foc.h"

#include "ctl_pu.h"

/* Gains by pole-zero cancellation ("technical optimum" of a first-order plant L s + R): the PI
 * zero Ki / Kp = R / L cancels the plant's pole, and the open loop Kp / (L s) crosses over at
 * w_c = Kp / L, a first-order closed loop of bandwidth w_c (before the delays). */
void ctl_foc_config_build(ctl_foc_config_t *f, const ctl_params_t *p, const ctl_model_t *model)
{
    const float l_d = p->ld_h / CTL_BASE_INDUCTANCE_H_F;
    const float l_q = p->lq_h / CTL_BASE_INDUCTANCE_H_F;
    const float l_xy = p->l_xy_h / CTL_BASE_INDUCTANCE_H_F;
    const float r = p->resistance_ohm / CTL_BASE_IMPEDANCE_OHM_F;
    const float ts = p->sample_time_s / CTL_BASE_TIME_S_F;
    const float l_max = (l_d > l_q) ? ((l_d > l_xy) ? l_d : l_xy) : ((l_q > l_xy) ? l_q : l_xy);
    float wc = CTL_TWO_PI_F / (CTL_FOC_BANDWIDTH_RATIO * p->sample_time_s) / CTL_BASE_OMEGA_RAD_S_F;
    const ctl_flux_ref_machine_t m = {p->ld_h, p->lq_h, p->pm_flux_wb, p->pole_pairs};
    (void)model;
    if (l_max * wc > CTL_FOC_GAIN_MAX) {
        wc = CTL_FOC_GAIN_MAX / l_max;
    }
    f->kp_d = ctl_from_float(l_d * wc);
    f->kp_q = ctl_from_float(l_q * wc);
    f->kp_xy = ctl_from_float(l_xy * wc);
    f->ki_ts = ctl_from_float(r * wc * ts);
    /* back-calculation with the tracking time constant T_t = T_i = Kp / Ki = L / R */
    f->kt_d = ctl_from_float(r * ts / l_d);
    f->kt_q = ctl_from_float(r * ts / l_q);
    f->kt_xy = ctl_from_float(r * ts / l_xy);
    f->advance = ctl_from_float(1.5f * ts);
    ctl_flux_ref_currents(f->id_ref, CTL_FOC_REF_POINTS, p->flux_ref_mode, &m, p->torque_limit_nm,
                          p->light_load_current_a);
}
