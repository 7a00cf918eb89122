#include "ctl_ddc.h"

#include "ctl_ddc_levels.h"
#include "ctl_tables.h"
#include "ctl_vectors.h"
#include "ctl_placement.h"
#include "ctl_qmath.h"

void ctl_ddc_config_init(ctl_ddc_config_t *cfg, int16_t direction, int16_t n_levels,
                         bool torque_guard, float tie_band)
{
    int16_t k;
    cfg->direction = direction;
    cfg->n_levels = n_levels;
    cfg->torque_guard = torque_guard;
    cfg->tie_per_span = ctl_from_float(tie_band / (float)(n_levels - 1));
    /* the paper's {1, 0.8, 0.6, 0.4, 0.2, 0} for n = 6 */
    for (k = 0; k < CTL_DDC_LEVELS_MAX; k++) {
        cfg->levels[k] = (k < n_levels)
                             ? ctl_from_float((float)(n_levels - 1 - k) / (float)(n_levels - 1))
                             : CTL_Q(0.0);
    }
}

SIXPHASE_RAMFUNC void ctl_ddc_select(const ctl_horizon_t *h, const ctl_ddc_flux_t *flux,
                                     const ctl_ddc_config_t *cfg, void (*stage_hook)(int16_t stage),
                                     ctl_choice_t *out)
{
    /* Flux sector s spans [30s - 15, 30s + 15) deg, i.e. the 15-degree sectors 2s - 1, 2s. */
    const int16_t sector = ctl_sector12(flux->psi_beta, flux->psi_alpha);
    const int16_t xy_sector = ctl_sector24(flux->psi_y, flux->psi_x);
    ctl_ddc_state_t zero;
    int16_t torque_half;
    int16_t vector;

    /* Table 1 half: the zero vector alone (duty 0) already overshoots a lower reference
     * -> the torque-lowering mirror set (paper Eq. 10 compares Te under zero against Tref). */
    zero.torque = ctl_torque_psi(h->model, h->id2_free, h->iq2_free, &zero.psi_d, &zero.psi_q);
    torque_half = (zero.torque > h->torque_ref) ? 1 : 0;

    if (cfg->direction == 1) {
        vector = ctl_ddc_table2_xy[sector][torque_half][xy_sector];
    } else {
        /* |psi| >= psi_ref compared as squares: both are non-negative, no root needed */
        const int16_t lower_flux = (flux->psi_mag_sq >= ctl_mul(h->flux_ref, h->flux_ref)) ? 1 : 0;
        vector = ctl_ddc_table2_flux[sector][torque_half][lower_flux][xy_sector];
    }
    if (stage_hook != 0) {
        stage_hook(2); /* CTL_STAGE_TABLE */
    }
    {
        ctl_q did;
        ctl_q diq;
        ctl_horizon_forced(h, &ctl_vector_vsd[vector], &did, &diq);
        ctl_ddc_levels_search(h, cfg, vector, did, diq, &zero, out);
    }
    out->candidates = cfg->n_levels;
    out->flux_sector = sector;
    out->xy_sector = xy_sector;
    out->braking = torque_half == 1;
}
