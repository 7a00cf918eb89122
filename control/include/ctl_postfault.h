/*
 * The control step with one phase open (ctl_params_t.open_phase >= 0): ctl_step hands the period
 * to it when the configuration in force has an open phase. Same timing, references and cost as
 * the healthy step (ctl.h); what differs (docs/design.md, "Open-phase operation"):
 *
 *   prediction  each forward-Euler step of the healthy model is followed by the projection
 *               onto "no current in the open phase" at the step's end angle, along M^-1 c_k (the
 *               direction the open terminal's unknown voltage moves the currents):
 *                 i' = i - g (c . i) / (c . g),  g = (Ts/L_d c_d, Ts/L_q c_q, Ts/L_xy c_x, ..)
 *               in the rotor frame, where c_d, c_q turn with the rotor. The projection is linear,
 *               so the k+2 free response is projected once per period and every candidate's
 *               forced part (now with its x-y part) through eight per-period coefficients;
 *   candidates  the 32 states of the five healthy legs (ctl_postfault_config_t): DDC from the
 *               post-fault table, the free x-y flux's error against its reference picking the
 *               sign of the free x-y voltage; MPTC-49 all distinct effective vectors, MPTC-13
 *               the largest;
 *   command     the open leg's duty is always 0 (its switches are off for good anyway).
 */
#ifndef CTL_POSTFAULT_H
#define CTL_POSTFAULT_H

#include "ctl.h"

/* One control period with the open phase of the configuration in force (which must have one);
 * all-off while no valid set was ever in force (ctl_step calls it for both). */
void ctl_postfault_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd);

/* The prediction's projection on its own (tests): the rotor-frame currents (i_d, i_q) and x-y
 * currents moved along M^-1 c_k until the open phase carries none at the rotor angle whose sine
 * and cosine are s, co. */
void ctl_postfault_project(const ctl_model_t *model, const ctl_postfault_config_t *pf, ctl_q s,
                           ctl_q co, ctl_q *id, ctl_q *iq, ctl_q *ix, ctl_q *iy);

#endif /* CTL_POSTFAULT_H */
