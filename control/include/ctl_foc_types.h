/*
 * FOC-VSD's settings (ctl_foc_config_t, built once per parameter set into ctl_config_t) and its
 * state between periods (ctl_foc_state_t, in ctl_t), below ctl_foc.h so that the configuration
 * and the controller's state take the types without the step's functions.
 */
#ifndef CTL_FOC_TYPES_H
#define CTL_FOC_TYPES_H

#include "ctl_flux_ref.h"
#include "ctl_q.h"
#include "ctl_vsd.h"

/* The current loops' bandwidth: w_c = 2 pi f_s / CTL_FOC_BANDWIDTH_RATIO (500 Hz, 3142 rad/s at
 * the 10 kHz sampling rate), lowered only where a per-unit gain would pass
 * CTL_FOC_GAIN_MAX (an inductance far above the reference machine's). */
#define CTL_FOC_BANDWIDTH_RATIO 20.0f
#define CTL_FOC_GAIN_MAX 64.0f
/* |integrator| bound of every current PI, per unit voltage (twice the 540 V base: beyond what
 * any DC link the drive accepts can apply). */
#define CTL_FOC_INTEG_LIMIT CTL_Q(2.0)
/* The i_d reference's table: every fourth point of the flux reference's (0, 1/8, .. 1 of its
 * span), i_q from the torque equation. Nine points, not 33, for the RAM of the 16-bit-int proxy
 * (tools/avr_proxy, two configurations in ctl_t). */
#define CTL_FOC_REF_POINTS CTL_FLUX_REF_CURRENT_POINTS

/* What a FOC set adds to its configuration (beside the model, from which the step takes the
 * gains: Kp = L w_c, Ki Ts = R w_c Ts, the tracking Ts / T_i = R Ts / L = 1 - a). It shares its
 * place with the DDC's settings (ctl_config_t.ctrl), which a FOC set never uses. */
typedef struct {
    ctl_q wc; /* the current loops' bandwidth, per unit */
    /* i_d references at the flux reference's torque points (ctl_flux_ref_init fills them) */
    ctl_q id_ref[CTL_FOC_REF_POINTS];
} ctl_foc_config_t;

typedef struct {
    ctl_q integ_d, integ_q, integ_x, integ_y; /* the PIs' integrators, per unit voltage */
    ctl_vsd_t v_in_force; /* the voltage the command in force applies (period average, after the
                           * duties' clamp), per unit: the k -> k+1 prediction's */
} ctl_foc_state_t;

/* Clears the integrators and the voltage in force (ctl_reset_command, and a change of
 * controller). */
static inline void ctl_foc_reset(ctl_foc_state_t *s)
{
    s->integ_d = CTL_Q(0.0);
    s->integ_q = CTL_Q(0.0);
    s->integ_x = CTL_Q(0.0);
    s->integ_y = CTL_Q(0.0);
    s->v_in_force.alpha = CTL_Q(0.0);
    s->v_in_force.beta = CTL_Q(0.0);
    s->v_in_force.x = CTL_Q(0.0);
    s->v_in_force.y = CTL_Q(0.0);
}

#endif /* CTL_FOC_TYPES_H */
