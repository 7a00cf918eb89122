/*
 * What the candidate searches share: the prediction horizon k+1 -> k+2 and
 * the cost J = |Te(k+2) - Tref| + lambda |psi_s(k+2) - psi_ref|.
 *
 * The k+2 currents are linear in the candidate's voltage, so the response to
 * zero voltage (the free response) is computed once per step and each
 * candidate only adds its forced part (c_d u_d, c_q u_q).
 */
#ifndef CTL_SEARCH_H
#define CTL_SEARCH_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_predict.h"
#include "ctl_q.h"
#include "ctl_vsd.h"

typedef struct {
    const ctl_model_t *model;
    ctl_q id2_free; /* k+2 currents with zero voltage over k+1 -> k+2 */
    ctl_q iq2_free;
    ctl_q sin1;   /* rotor angle at which the k+1 -> k+2 voltage enters the prediction: k+1, or */
    ctl_q cos1;   /* the middle of that period (ctl_params_t.mid_period_angle) */
    ctl_q sin_k1; /* rotor angle at k+1 (where the predicted flux is) */
    ctl_q cos_k1;
    ctl_q vdc;
    ctl_q torque_ref;
    ctl_q flux_ref;
    ctl_q lambda;
    /* Set by ctl_horizon_prepare (fixed-point build): forced k+2 currents per unit of
     * alpha/beta voltage (per unit of Vdc), c_d/c_q times Vdc times the rotation. */
    ctl_q kd_alpha;
    ctl_q kd_beta;
    ctl_q kq_alpha;
    ctl_q kq_beta;
} ctl_horizon_t;

/* Completes a horizon whose model, angle, Vdc, references and weight are set. */
static inline void ctl_horizon_prepare(ctl_horizon_t *h)
{
#if CTL_MATH_FLOAT
    (void)h; /* the float build's forced response keeps the model's product order */
#else
    const ctl_q cd = ctl_mul_bnd(h->model->c_d, h->vdc); /* bounded: ctl_model_init */
    const ctl_q cq = ctl_mul_bnd(h->model->c_q, h->vdc);
    h->kd_alpha = ctl_mul_bnd(cd, h->cos1);
    h->kd_beta = ctl_mul_bnd(cd, h->sin1);
    h->kq_alpha = ctl_sub_bnd(CTL_Q(0.0), ctl_mul_bnd(cq, h->sin1));
    h->kq_beta = ctl_mul_bnd(cq, h->cos1);
#endif
}

typedef struct {
    int16_t vector; /* active switching state */
    ctl_q duty;     /* fraction of the period it is applied */
    ctl_q cost;
    ctl_q torque; /* predicted at k+2 */
    ctl_q flux;
    int16_t candidates;
    int16_t flux_sector;
    int16_t xy_sector;
    bool braking;
} ctl_choice_t;

/* Forced part of the k+2 currents for a full-period switching state: (c_d u_d, c_q u_q)
 * with u = Vdc * vector voltage rotated to the rotor frame at k+1. */
static inline void ctl_horizon_forced(const ctl_horizon_t *h, const ctl_vsd_t *vec, ctl_q *did,
                                      ctl_q *diq)
{
#if CTL_MATH_FLOAT
    /* float: the product order of the model (a coefficient form rounds differently) */
    ctl_q ud;
    ctl_q uq;
    ctl_park(ctl_mul(vec->alpha, h->vdc), ctl_mul(vec->beta, h->vdc), h->sin1, h->cos1, &ud, &uq);
    *did = ctl_mul(h->model->c_d, ud);
    *diq = ctl_mul(h->model->c_q, uq);
#else
    /* fixed: two multiplies per axis with the coefficients of ctl_horizon_prepare (the same
     * commands on the benchmark's points, a quarter of the work) */
    *did = ctl_mul_add_bnd(h->kd_alpha, vec->alpha, h->kd_beta, vec->beta);
    *diq = ctl_mul_add_bnd(h->kq_alpha, vec->alpha, h->kq_beta, vec->beta);
#endif
}

/* Cost of a k+2 state from its torque and flux magnitude. */
static inline ctl_q ctl_horizon_cost_of(const ctl_horizon_t *h, ctl_q torque, ctl_q flux)
{
    return ctl_add(ctl_abs(ctl_sub(torque, h->torque_ref)),
                   ctl_mul(h->lambda, ctl_abs_diff_nonneg(flux, h->flux_ref)));
}

/* Cost of the k+2 currents (id2, iq2); fills torque and flux. */
static inline ctl_q ctl_horizon_cost(const ctl_horizon_t *h, ctl_q id2, ctl_q iq2, ctl_q *torque,
                                     ctl_q *flux)
{
    ctl_torque_flux(h->model, id2, iq2, torque, flux);
    return ctl_horizon_cost_of(h, *torque, *flux);
}

/* One full-period candidate of an exhaustive search (MPTC): its k+2 currents are the free
 * response plus (did, diq); it replaces the best so far in out when its cost is lower. The cost
 * is at least the torque error (both terms >= 0, the add saturates), so a candidate whose torque
 * error alone reaches the best cost cannot win: its flux root is skipped, as the DDC's level
 * search does, and the choice is the same as without the test. */
static inline void ctl_choice_consider(const ctl_horizon_t *h, ctl_q did, ctl_q diq, int16_t vector,
                                       ctl_choice_t *out)
{
    ctl_q psi_d;
    ctl_q psi_q;
    ctl_q flux;
    ctl_q cost;
    const ctl_q torque = ctl_torque_psi(h->model, ctl_add_bnd(h->id2_free, did),
                                        ctl_add_bnd(h->iq2_free, diq), &psi_d, &psi_q);
    if (!(ctl_abs(ctl_sub(torque, h->torque_ref)) < out->cost)) {
        return;
    }
    flux = ctl_flux_magnitude(psi_d, psi_q);
    cost = ctl_horizon_cost_of(h, torque, flux);
    if (cost < out->cost) {
        out->cost = cost;
        out->vector = vector;
        out->torque = torque;
        out->flux = flux;
    }
}

#endif /* CTL_SEARCH_H */
