/*
 * FOC-VSD: field-oriented current control in the VSD coordinates of the six-phase machine
 * (docs/design.md, "FOC-VSD"), the linear baseline beside the predictive controllers.
 *
 *   references   i_d, i_q from the torque reference at the flux reference's operating points
 *                (MTPA, or i_d = 0 in constant-flux mode); i_x = i_y = 0
 *   prediction   the currents at k+1 under the voltage in force (the MPC's delay compensation)
 *   current PIs  d-q in the rotor frame with decoupling (v_d -= w L_q i_q,
 *                v_q += w (L_d i_d + psi_f)); x-y in the stationary frame; gains by pole-zero
 *                cancellation, Kp = L w_c, Ki = R w_c; back-calculation anti-windup against
 *                the voltage the duties realise
 *   modulation   inverse Park at the angle advanced 1.5 periods, inverse VSD to six phase
 *                voltages, per three-phase set its own min-max zero sequence (isolated
 *                neutrals), leg duties clamped to [0, 1]: one centred pulse per leg and period
 *                (carrier at the sampling frequency)
 */
#ifndef CTL_FOC_H
#define CTL_FOC_H

#include <stdint.h>

#include "ctl.h"
#include "ctl_config.h"
#include "ctl_foc_types.h"
#include "ctl_predict.h"
#include "ctl_q.h"
#include "ctl_vsd.h"

/* The PIs' gains, per unit, from the bandwidth and the model (a few products per period). */
typedef struct {
    ctl_q kp_d, kp_q, kp_xy; /* L w_c */
    ctl_q ki_ts;             /* R w_c Ts (every axis) */
    ctl_q kt_d, kt_q, kt_xy; /* anti-windup tracking Ts / T_i = R Ts / L = 1 - a */
} ctl_foc_gains_t;

static inline void ctl_foc_gains(const ctl_foc_config_t *f, const ctl_model_t *m,
                                 ctl_foc_gains_t *g)
{
    g->kp_d = ctl_mul(m->ld, f->wc);
    g->kp_q = ctl_mul(m->lq, f->wc);
    g->kp_xy = ctl_mul(m->lxy, f->wc);
    g->kt_d = ctl_sub(CTL_Q(1.0), m->a_d);
    g->kt_q = ctl_sub(CTL_Q(1.0), m->a_q);
    g->kt_xy = ctl_sub(CTL_Q(1.0), m->a_xy);
    g->ki_ts = ctl_mul(g->kt_d, g->kp_d);
}

/* The current references of a torque reference (per unit). */
void ctl_foc_current_ref(const ctl_foc_config_t *f, const ctl_flux_ref_t *span,
                         const ctl_model_t *model, ctl_q torque_ref, ctl_q *id_ref, ctl_q *iq_ref);

/* One PI with back-calculation: out = kp e + integ; returns out. */
static inline ctl_q ctl_foc_pi(ctl_q kp, ctl_q integ, ctl_q err)
{
    return ctl_mul_acc(integ, kp, err);
}

/* The integrator after a period, back-calculation with tracking time constant T_t = T_i:
 * integ + ki_ts e + kt (realised - requested), kt = Ts / T_i, bounded. Held in saturation it
 * settles where its own output, the error gone, would ask for what the modulator could apply
 * (integ + ki_ts e + kt (realised - kp e - integ) = integ at integ = realised), so it never
 * winds up beyond the voltage limit and the output leaves the limit as soon as the error turns. */
static inline ctl_q ctl_foc_integrate(ctl_q integ, ctl_q ki_ts, ctl_q kt, ctl_q err,
                                      ctl_q requested, ctl_q realised, ctl_q limit)
{
    const ctl_q next =
        ctl_mul_acc(ctl_mul_acc(integ, ki_ts, err), kt, ctl_sub(realised, requested));
    return ctl_clamp(next, -limit, limit);
}

/* Six leg duties (centred pulses, [0, 1]) from a VSD voltage (per unit) at the DC link vdc (per
 * unit), each three-phase set with its own min-max zero sequence. A request beyond the linear
 * range (a set's phase voltages spread wider than Vdc) is scaled down as a whole, all four axes
 * by the same factor, so that the wider set just fits: the directions in both planes are kept and
 * no clamp distortion lands in x-y. The voltage the duties realise goes to realised. Returns the
 * legs high at the period boundary (duty 1; S_A is bit 5). */
int16_t ctl_foc_modulate(const ctl_vsd_t *v, ctl_q vdc, ctl_q duty[6], ctl_vsd_t *realised);

/* ctl_step's healthy period when the set in force is FOC-VSD (all six legs): measurement, speed
 * loop and references as the predictive controllers', then the current loops above. The command
 * is the six leg duties; its vector and duty are 0 (no one switching state stands for it). */
void ctl_foc_healthy_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd);

#endif /* CTL_FOC_H */
