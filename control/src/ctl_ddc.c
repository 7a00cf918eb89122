#include "ctl_ddc.h"

#include "ctl_tables.h"
#include "ctl_vectors.h"

void ctl_ddc_select(const ctl_horizon_t *h, const ctl_ddc_flux_t *flux, int16_t direction,
                    const ctl_q *levels, int16_t n_levels, ctl_choice_t *out)
{
    /* Flux sector s spans [30s - 15, 30s + 15) deg, i.e. the 15-degree sectors 2s - 1, 2s. */
    const int16_t sector =
        (int16_t)(((ctl_sector24(flux->psi_beta, flux->psi_alpha) + 1) / 2) % CTL_SECTORS);
    const int16_t xy_sector = ctl_sector24(flux->psi_y, flux->psi_x);
    ctl_q torque_zero;
    ctl_q flux_zero;
    ctl_q cost_zero;
    int16_t torque_half;
    int16_t vector;
    ctl_q did;
    ctl_q diq;
    int16_t k;

    /* Table 1 half: the zero vector alone (duty 0) already overshoots a lower reference
     * -> the torque-lowering mirror set (paper Eq. 10 compares Te under zero against Tref). */
    cost_zero = ctl_horizon_cost(h, h->id2_free, h->iq2_free, &torque_zero, &flux_zero);
    torque_half = (torque_zero > h->torque_ref) ? 1 : 0;

    if (direction == 1) {
        vector = ctl_ddc_table2_xy[sector][torque_half][xy_sector];
    } else {
        /* |psi| >= psi_ref compared as squares: both are non-negative, no root needed */
        const int16_t lower_flux = (flux->psi_mag_sq >= ctl_mul(h->flux_ref, h->flux_ref)) ? 1 : 0;
        vector = ctl_ddc_table2_flux[sector][torque_half][lower_flux][xy_sector];
    }

    /* Duty search: the forced response scales with the duty. */
    ctl_horizon_forced(h, &ctl_vector_vsd[vector], &did, &diq);
    out->cost = CTL_Q_MAX;
    out->duty = CTL_Q(0.0);
    out->torque = torque_zero;
    out->flux = flux_zero;
    for (k = 0; k < n_levels; k++) {
        const ctl_q d = levels[k];
        ctl_q torque = torque_zero;
        ctl_q flux_mag = flux_zero;
        /* duty 0 is the zero vector, already evaluated for the table-1 half */
        const ctl_q cost =
            (d == CTL_Q(0.0))
                ? cost_zero
                : ctl_horizon_cost(h, ctl_add(h->id2_free, ctl_mul(d, did)),
                                   ctl_add(h->iq2_free, ctl_mul(d, diq)), &torque, &flux_mag);
        if (cost < out->cost) {
            out->cost = cost;
            out->duty = d;
            out->torque = torque;
            out->flux = flux_mag;
        }
    }
    out->vector = vector;
    out->candidates = n_levels;
    out->flux_sector = sector;
    out->xy_sector = xy_sector;
    out->braking = torque_half == 1;
}
