/*
 * Speed PI producing the torque reference. Anti-windup by clamping: the
 * integrator is held inside the torque limit and is not moved further into
 * saturation while the output is saturated in the same direction.
 */
#ifndef CTL_SPEED_PI_H
#define CTL_SPEED_PI_H

#include "ctl_q.h"

typedef struct {
    ctl_q kp;    /* per unit torque per per-unit electrical speed */
    ctl_q ki_ts; /* ki * Ts, per step */
    ctl_q limit; /* |output| and |integrator| bound, per unit torque */
    ctl_q integ;
} ctl_speed_pi_t;

void ctl_speed_pi_init(ctl_speed_pi_t *pi, ctl_q kp, ctl_q ki_ts, ctl_q limit);
void ctl_speed_pi_reset(ctl_speed_pi_t *pi);
ctl_q ctl_speed_pi_run(ctl_speed_pi_t *pi, ctl_q ref, ctl_q meas);

#endif /* CTL_SPEED_PI_H */
