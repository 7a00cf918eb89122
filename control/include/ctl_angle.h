/*
 * The rotor angle advanced over part of a control period, as the prediction needs it.
 */
#ifndef CTL_ANGLE_H
#define CTL_ANGLE_H

#include "ctl_constants.h"
#include "ctl_q.h"
#include "ctl_qmath.h"

/* Sine and cosine of the sample angle theta_e (turns; sine s0, cosine c0) advanced by delta
 * (rad). For |delta| <= 0.5 rad (7 times rated speed at 10 kHz) a rotation by short series of
 * sin/cos delta (error < 2e-5 there, < 1e-8 at rated speed); beyond that a new table look-up.
 * (ctl.c has the same rotation inline, kept there for the healthy step's instruction count.) */
static inline void ctl_angle_advance(ctl_q theta_e, ctl_q s0, ctl_q c0, ctl_q delta, ctl_q *s,
                                     ctl_q *c)
{
    if (ctl_abs(delta) <= CTL_Q(0.5)) {
        const ctl_q d2 = ctl_mul(delta, delta);
        const ctl_q sd = ctl_mul(delta, ctl_mul_dec(CTL_Q(1.0), d2, CTL_K_ONE_SIXTH));
        const ctl_q cd = ctl_mul_dec(CTL_Q(1.0), ctl_mul(d2, CTL_Q(0.5)),
                                     ctl_mul_dec(CTL_Q(1.0), d2, CTL_K_ONE_TWELFTH));
        *s = ctl_mul_add(s0, cd, c0, sd);
        *c = ctl_mul_sub(c0, cd, s0, sd);
    } else {
        ctl_sincos_pu(ctl_add(theta_e, ctl_mul(delta, CTL_K_INV_TWO_PI)), s, c);
    }
}

#endif /* CTL_ANGLE_H */
