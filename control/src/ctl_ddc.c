#include "ctl_ddc.h"

#include "ctl_tables.h"
#include "ctl_vectors.h"

/* Best duty for one vector: the forced response scales with the duty; duty 0 is the zero
 * vector, whose evaluation the caller already has. */
static void duty_search(const ctl_horizon_t *h, const ctl_ddc_config_t *cfg, int16_t vector,
                        const ctl_choice_t *zero, ctl_choice_t *out)
{
    ctl_q torque[CTL_DDC_LEVELS_MAX];
    ctl_q flux_mag[CTL_DDC_LEVELS_MAX];
    ctl_q cost[CTL_DDC_LEVELS_MAX];
    ctl_q did;
    ctl_q diq;
    int16_t k;
    ctl_horizon_forced(h, &ctl_vector_vsd[vector], &did, &diq);
    for (k = 0; k < cfg->n_levels; k++) {
        const ctl_q d = cfg->levels[k];
        torque[k] = zero->torque;
        flux_mag[k] = zero->flux;
        cost[k] = (d == CTL_Q(0.0)) ? zero->cost
                                    : ctl_horizon_cost(h, ctl_add(h->id2_free, ctl_mul(d, did)),
                                                       ctl_add(h->iq2_free, ctl_mul(d, diq)),
                                                       &torque[k], &flux_mag[k]);
    }
    if (cfg->torque_guard) {
        /* Improvement: flux weighting may move the duty at most one level away from the level
         * that best meets the torque reference, so a large lambda cannot trade torque for flux
         * beyond the resolution of the duty set. (A band in torque units would put the
         * neighbour on the far side exactly on its edge, torque being nearly linear in duty.) */
        int16_t best = 0;
        ctl_q best_err = CTL_Q_MAX;
        for (k = 0; k < cfg->n_levels; k++) {
            const ctl_q err = ctl_abs(ctl_sub(torque[k], h->torque_ref));
            if (err < best_err) {
                best_err = err;
                best = k;
            }
        }
        for (k = 0; k < cfg->n_levels; k++) {
            if (k < best - 1 || k > best + 1) {
                cost[k] = CTL_Q_MAX;
            }
        }
    }
    out->vector = vector;
    out->cost = CTL_Q_MAX;
    out->duty = CTL_Q(0.0);
    out->torque = zero->torque;
    out->flux = zero->flux;
    for (k = 0; k < cfg->n_levels; k++) {
        if (cost[k] < out->cost) {
            out->cost = cost[k];
            out->duty = cfg->levels[k];
            out->torque = torque[k];
            out->flux = flux_mag[k];
        }
    }
}

void ctl_ddc_select(const ctl_horizon_t *h, const ctl_ddc_flux_t *flux, const ctl_ddc_config_t *cfg,
                    ctl_choice_t *out)
{
    /* Flux sector s spans [30s - 15, 30s + 15) deg, i.e. the 15-degree sectors 2s - 1, 2s. */
    const int16_t sector =
        (int16_t)(((ctl_sector24(flux->psi_beta, flux->psi_alpha) + 1) / 2) % CTL_SECTORS);
    const int16_t xy_sector = ctl_sector24(flux->psi_y, flux->psi_x);
    ctl_choice_t zero = {0};
    int16_t torque_half;
    int16_t vector;

    /* Table 1 half: the zero vector alone (duty 0) already overshoots a lower reference
     * -> the torque-lowering mirror set (paper Eq. 10 compares Te under zero against Tref). */
    zero.cost = ctl_horizon_cost(h, h->id2_free, h->iq2_free, &zero.torque, &zero.flux);
    torque_half = (zero.torque > h->torque_ref) ? 1 : 0;

    if (cfg->direction == 1) {
        vector = ctl_ddc_table2_xy[sector][torque_half][xy_sector];
    } else {
        /* |psi| >= psi_ref compared as squares: both are non-negative, no root needed */
        const int16_t lower_flux = (flux->psi_mag_sq >= ctl_mul(h->flux_ref, h->flux_ref)) ? 1 : 0;
        vector = ctl_ddc_table2_flux[sector][torque_half][lower_flux][xy_sector];
    }
    if (cfg->stage_hook != 0) {
        cfg->stage_hook(2); /* CTL_STAGE_TABLE */
    }
    duty_search(h, cfg, vector, &zero, out);
    out->candidates = cfg->n_levels;
    out->flux_sector = sector;
    out->xy_sector = xy_sector;
    out->braking = torque_half == 1;
}
