/*
 * The DDC's duty search for one vector, shared by the healthy step (ctl_ddc.c) and the
 * open-phase step (ctl_postfault.c), which differ only in the forced response they give it.
 * Static inline and called once in each: each step keeps it inlined (the healthy step's
 * instruction count), the source is written once.
 */
#ifndef CTL_DDC_LEVELS_H
#define CTL_DDC_LEVELS_H

#include "ctl_ddc_types.h"
#include "ctl_search.h"

/* The levels that compete: those in [*first, *last] whose torque error is at most *bound. All
 * of them in the paper's search. Two improvements (docs/improvements.md), each relative to the
 * level that best meets the torque reference, so a large lambda cannot trade torque for flux
 * beyond the resolution of the duty set:
 *   torque guard: that level and its neighbours (an index band: a band in torque units at one
 *     level would put the neighbour on the far side exactly on its edge, torque being nearly
 *     linear in duty);
 *   flux tie band: levels whose torque error is within a fraction of one level's torque step
 *     of the best, so the flux term only breaks near-ties (the step from the levels' span).
 * Only the competing levels need a flux root. */
static inline void ctl_ddc_competing_levels(const ctl_ddc_config_t *cfg, const ctl_q *torque,
                                            int16_t best, ctl_q best_err, int16_t *first,
                                            int16_t *last, ctl_q *bound)
{
    *first = 0;
    *last = (int16_t)(cfg->n_levels - 1);
    *bound = CTL_Q_MAX;
    if (cfg->torque_guard) {
        *first = (best > 0) ? (int16_t)(best - 1) : 0;
        *last = (best < *last) ? (int16_t)(best + 1) : *last;
    }
    if (cfg->tie_per_span != CTL_Q(0.0)) { /* levels 1 first, 0 last */
        const ctl_q span = ctl_abs(ctl_sub(torque[0], torque[cfg->n_levels - 1]));
        *bound = ctl_add(best_err, ctl_mul(span, cfg->tie_per_span));
    }
}

/* Best duty for one vector: the forced response (did, diq at full duty) scales with the duty;
 * duty 0 is the zero vector, whose state the caller already has. */
static inline void ctl_ddc_levels_search(const ctl_horizon_t *h, const ctl_ddc_config_t *cfg,
                                         int16_t vector, ctl_q did, ctl_q diq,
                                         const ctl_ddc_state_t *zero, ctl_choice_t *out)
{
    ctl_q torque[CTL_DDC_LEVELS_MAX];
    ctl_q torque_err[CTL_DDC_LEVELS_MAX]; /* |Te(k+2) - Tref|, the cost's first term */
    ctl_q psi_d[CTL_DDC_LEVELS_MAX];
    ctl_q psi_q[CTL_DDC_LEVELS_MAX];
    int16_t first;
    int16_t last;
    ctl_q bound;
    int16_t k;
    const int16_t zero_level = (int16_t)(cfg->n_levels - 1); /* levels 1 first, 0 last */
    int16_t best = zero_level;
    ctl_q best_err;
    torque[zero_level] = zero->torque;
    psi_d[zero_level] = zero->psi_d;
    psi_q[zero_level] = zero->psi_q;
    torque_err[zero_level] = ctl_abs(ctl_sub(zero->torque, h->torque_ref));
    best_err = torque_err[zero_level];
    for (k = (int16_t)(zero_level - 1); k >= 0; k--) { /* ties: the larger duty, as before */
        const ctl_q d = cfg->levels[k];
        torque[k] = ctl_torque_psi(h->model, ctl_mul_acc_bnd(h->id2_free, d, did),
                                   ctl_mul_acc_bnd(h->iq2_free, d, diq), &psi_d[k], &psi_q[k]);
        torque_err[k] = ctl_abs(ctl_sub(torque[k], h->torque_ref));
        if (torque_err[k] <= best_err) {
            best_err = torque_err[k];
            best = k;
        }
    }
    ctl_ddc_competing_levels(cfg, torque, best, best_err, &first, &last, &bound);
    out->vector = vector;
    out->cost = CTL_Q_MAX;
    out->duty = CTL_Q(0.0);
    out->torque = zero->torque;
    out->flux = -1; /* none chosen yet */
    for (k = first; k <= last; k++) {
        ctl_q flux;
        ctl_q cost;
        if (torque_err[k] > bound) {
            continue;
        }
        flux = ctl_flux_magnitude(psi_d[k], psi_q[k]);
        cost = ctl_add(torque_err[k], ctl_mul(h->lambda, ctl_abs_diff_nonneg(flux, h->flux_ref)));
        if (cost < out->cost) {
            out->cost = cost;
            out->duty = cfg->levels[k];
            out->torque = torque[k];
            out->flux = flux;
        }
    }
    if (out->flux < CTL_Q(0.0)) { /* every cost saturated: the zero vector stands */
        out->flux = ctl_flux_magnitude(zero->psi_d, zero->psi_q);
    }
}

#endif /* CTL_DDC_LEVELS_H */
