/*
 * Discrete model of the machine for two-step prediction (forward Euler of the
 * rotor-frame model, the brief's corrected form of the paper's Eq. 17):
 *
 *   i_d(k+1) = (1 - R Ts/L_d) i_d + (L_q/L_d) Ts w i_q + (Ts/L_d) u_d
 *   i_q(k+1) = (1 - R Ts/L_q) i_q - (L_d/L_q) Ts w i_d - (psi_f/L_q) Ts w + (Ts/L_q) u_q
 *   i_x(k+1) = (1 - R Ts/L_1) i_x + (Ts/L_1) u_x        (likewise y)
 *
 * All coefficients are computed once from SI parameters (float, init time);
 * the per-step path has no division. Everything here is per unit.
 */
#ifndef CTL_PREDICT_H
#define CTL_PREDICT_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_q.h"
#include "ctl_qmath.h"

typedef struct {
    ctl_q a_d;  /* 1 - R Ts / L_d */
    ctl_q b_d;  /* L_q / L_d * Ts     (times w i_q) */
    ctl_q c_d;  /* Ts / L_d           (times u_d) */
    ctl_q a_q;  /* 1 - R Ts / L_q */
    ctl_q b_q;  /* L_d / L_q * Ts     (times w i_d) */
    ctl_q e_q;  /* psi_f / L_q * Ts   (times w) */
    ctl_q c_q;  /* Ts / L_q           (times u_q) */
    ctl_q a_xy; /* 1 - R Ts / L_1 */
    ctl_q c_xy; /* Ts / L_1 */
    ctl_q ld;
    ctl_q lq;
    ctl_q lxy;
    ctl_q psi_f;
    ctl_q ts;        /* sample time, per unit */
    ctl_q omega_max; /* the range analysis' speed for this sample time (ctl_range.h) */
    int16_t pole_pairs;
} ctl_model_t;

/* SI parameters in, per-unit coefficients out. False if a parameter is not
 * positive or a coefficient would not fit the number format. */
bool ctl_model_init(ctl_model_t *m, float r_ohm, float ld_h, float lq_h, float lxy_h,
                    float psi_f_wb, int16_t pole_pairs, float ts_s);

/* The predictions, fluxes and forced responses below use the bounded forms: ctl_model_init
 * admits a model only when they stay below CTL_RANGE_BOUND for inputs of the domain
 * (ctl_range.h, docs/range-analysis.md). */

/* One Euler step of the d-q currents under an average voltage (u_d, u_q). */
static inline void ctl_predict_dq(const ctl_model_t *m, ctl_q id, ctl_q iq, ctl_q w, ctl_q ud,
                                  ctl_q uq, ctl_q *id_next, ctl_q *iq_next)
{
    const ctl_q w_id = ctl_mul_bnd(w, id);
    const ctl_q w_iq = ctl_mul_bnd(w, iq);
    ctl_q d = ctl_mul_add_bnd(m->a_d, id, m->b_d, w_iq);
    ctl_q q = ctl_mul_sub_bnd(m->a_q, iq, m->b_q, w_id);
    d = ctl_mul_acc_bnd(d, m->c_d, ud);
    q = ctl_mul_dec_bnd(q, m->e_q, w);
    q = ctl_mul_acc_bnd(q, m->c_q, uq);
    *id_next = d;
    *iq_next = q;
}

/* The same step with no voltage (the free response): the voltage terms are zero, left out. */
static inline void ctl_predict_dq_free(const ctl_model_t *m, ctl_q id, ctl_q iq, ctl_q w,
                                       ctl_q *id_next, ctl_q *iq_next)
{
    const ctl_q w_id = ctl_mul_bnd(w, id);
    const ctl_q w_iq = ctl_mul_bnd(w, iq);
    *id_next = ctl_mul_add_bnd(m->a_d, id, m->b_d, w_iq);
    *iq_next = ctl_mul_dec_bnd(ctl_mul_sub_bnd(m->a_q, iq, m->b_q, w_id), m->e_q, w);
}

/* One Euler step of one x-y current component. */
static inline ctl_q ctl_predict_xy(const ctl_model_t *m, ctl_q i, ctl_q u)
{
    return ctl_mul_add_bnd(m->a_xy, i, m->c_xy, u);
}

/* Stator flux components from rotor-frame currents. */
static inline ctl_q ctl_flux_d(const ctl_model_t *m, ctl_q id)
{
    return ctl_mul_acc_bnd(m->psi_f, m->ld, id);
}
static inline ctl_q ctl_flux_q(const ctl_model_t *m, ctl_q iq) { return ctl_mul_bnd(m->lq, iq); }

/* Te = Pn (psi_d i_q - psi_q i_d), per unit (torque base is per pole pair), from rotor-frame
 * currents, saturated once at the end (no bound: Pn up to 64 times products near the bound);
 * psi_d and psi_q out for the flux magnitude, whose root is left to the caller (the searches
 * take it only where they need it). */
static inline ctl_q ctl_torque_psi(const ctl_model_t *m, ctl_q id, ctl_q iq, ctl_q *psi_d,
                                   ctl_q *psi_q)
{
    *psi_d = ctl_flux_d(m, id);
    *psi_q = ctl_flux_q(m, iq);
    return ctl_mul_sub_int(*psi_d, iq, *psi_q, id, m->pole_pairs); /* saturated: see above */
}

/* |psi_s| from its rotor-frame components. */
static inline ctl_q ctl_flux_magnitude(ctl_q psi_d, ctl_q psi_q)
{
    return ctl_sqrt(ctl_mul_add(psi_d, psi_d, psi_q, psi_q));
}

/* Te and |psi_s| of rotor-frame currents of any size (a record's, a reference): held to the range
 * analysis' current first (ctl_range.h; the bounded forms of the fluxes take no more, and an
 * estimate beyond 40 A is above every threshold that reads one). */
static inline ctl_q ctl_current_held(ctl_q i)
{
    return ctl_clamp(i, -CTL_Q(CTL_RANGE_CURRENT), CTL_Q(CTL_RANGE_CURRENT));
}
static inline ctl_q ctl_torque_held(const ctl_model_t *m, ctl_q id, ctl_q iq)
{
    ctl_q psi_d;
    ctl_q psi_q;
    return ctl_torque_psi(m, ctl_current_held(id), ctl_current_held(iq), &psi_d, &psi_q);
}
static inline ctl_q ctl_flux_held(const ctl_model_t *m, ctl_q id, ctl_q iq)
{
    return ctl_flux_magnitude(ctl_flux_d(m, ctl_current_held(id)),
                              ctl_flux_q(m, ctl_current_held(iq)));
}

/* Te and |psi_s| from rotor-frame currents; both from the same psi_d, psi_q. */
static inline void ctl_torque_flux(const ctl_model_t *m, ctl_q id, ctl_q iq, ctl_q *torque,
                                   ctl_q *flux)
{
    ctl_q pd;
    ctl_q pq;
    *torque = ctl_torque_psi(m, id, iq, &pd, &pq);
    *flux = ctl_flux_magnitude(pd, pq);
}

#endif /* CTL_PREDICT_H */
