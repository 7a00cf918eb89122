#include "ctl_speed_pi.h"
#include "ctl_placement.h"

void ctl_speed_pi_init(ctl_speed_pi_t *pi, ctl_q kp, ctl_q ki_ts, ctl_q limit)
{
    pi->kp = kp;
    pi->ki_ts = ki_ts;
    pi->limit = ctl_abs(limit);
    pi->integ = CTL_Q(0.0);
}

SIXPHASE_RAMFUNC void ctl_speed_pi_reset(ctl_speed_pi_t *pi) { pi->integ = CTL_Q(0.0); }

SIXPHASE_RAMFUNC ctl_q ctl_speed_pi_run(ctl_speed_pi_t *pi, ctl_q ref, ctl_q meas)
{
    const ctl_q err = ctl_sub(ref, meas);
    const ctl_q prop = ctl_mul(pi->kp, err);
    const ctl_q unclamped = ctl_add(prop, pi->integ);
    const ctl_q step = ctl_mul(pi->ki_ts, err);
    /* Clamping anti-windup: integrate only while that does not push a saturated output
     * further into saturation. */
    const bool high = unclamped >= pi->limit && step > CTL_Q(0.0);
    const bool low = unclamped <= -pi->limit && step < CTL_Q(0.0);
    if (!high && !low) {
        pi->integ = ctl_clamp(ctl_add(pi->integ, step), -pi->limit, pi->limit);
    }
    return ctl_clamp(ctl_add(prop, pi->integ), -pi->limit, pi->limit);
}
