/* FOC-VSD's configuration (ctl_foc.h), built with the rest of a set's outside the ISR. */
#include "ctl_foc_config.h"

#include "ctl_pu.h"

/* Gains by pole-zero cancellation ("technical optimum" of a first-order plant L s + R): the PI
 * zero Ki / Kp = R / L cancels the plant's pole, and the open loop Kp / (L s) crosses over at
 * w_c = Kp / L, a first-order closed loop of bandwidth w_c (before the delays). */
void ctl_foc_config_build(ctl_foc_config_t *f, const ctl_params_t *p)
{
    const float l_d = p->ld_h / CTL_BASE_INDUCTANCE_H_F;
    const float l_q = p->lq_h / CTL_BASE_INDUCTANCE_H_F;
    const float l_xy = p->l_xy_h / CTL_BASE_INDUCTANCE_H_F;
    const float l_max = (l_d > l_q) ? ((l_d > l_xy) ? l_d : l_xy) : ((l_q > l_xy) ? l_q : l_xy);
    float wc = CTL_TWO_PI_F / (CTL_FOC_BANDWIDTH_RATIO * p->sample_time_s) / CTL_BASE_OMEGA_RAD_S_F;
    if (l_max * wc > CTL_FOC_GAIN_MAX) {
        wc = CTL_FOC_GAIN_MAX / l_max;
    }
    f->wc = ctl_from_float(wc); /* the i_d table is filled by ctl_flux_ref_init */
}
