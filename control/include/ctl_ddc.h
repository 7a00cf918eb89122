/*
 * Discrete-duty-cycle MPTC (the paper's proposed method):
 *   1. table 1: alpha-beta flux sector at k+1 and torque demand -> four candidates
 *      (the torque-raising half is the paper's table; the torque-lowering half is
 *      its mirror, used when even the zero vector leaves Te(k+2) above Tref);
 *   2. table 2: x-y flux sector at k+1 -> the candidate whose x-y voltage shrinks
 *      the x-y flux (two readings, see ctl_ddc_direction_t);
 *   3. duty search: the vector applied for d*Ts and a zero vector for the rest,
 *      d over the discrete levels, cost J over the two-step prediction.
 */
#ifndef CTL_DDC_H
#define CTL_DDC_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_ddc_types.h"
#include "ctl_q.h"
#include "ctl_search.h"

typedef struct {
    ctl_q psi_alpha; /* stator flux at k+1, alpha-beta */
    ctl_q psi_beta;
    ctl_q psi_mag_sq; /* |psi_s|^2 at k+1 */
    ctl_q psi_x;      /* x-y flux at k+1 */
    ctl_q psi_y;
} ctl_ddc_flux_t;

/* Fills cfg; n_levels in 2..CTL_DDC_LEVELS_MAX and tie_band (a fraction of one level, 0: off)
 * in 0..1 (the caller has checked them). */
void ctl_ddc_config_init(ctl_ddc_config_t *cfg, int16_t direction, int16_t n_levels,
                         bool torque_guard, float tie_band);

/* stage_hook (profiling, 0: none) is told when the table stage ends. */
void ctl_ddc_select(const ctl_horizon_t *h, const ctl_ddc_flux_t *flux, const ctl_ddc_config_t *cfg,
                    void (*stage_hook)(int16_t stage), ctl_choice_t *out);

#endif /* CTL_DDC_H */
