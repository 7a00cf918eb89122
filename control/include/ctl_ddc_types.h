/*
 * The DDC's settings (ctl_ddc_config_t) and its k+2 zero-vector state, below ctl_ddc.h: the
 * duty search ctl_ddc.c shares with the open-phase step (ctl_ddc_levels.h) takes them from here,
 * not from the module that includes it.
 */
#ifndef CTL_DDC_TYPES_H
#define CTL_DDC_TYPES_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_q.h"

#define CTL_DDC_LEVELS_MAX 11

/* The search's settings, built once per parameter set (ctl_config_t), outside the ISR. */
typedef struct {
    int16_t direction; /* 0 flux-error reading, 1 x-y-table reading (ctl_ddc_direction_t) */
    int16_t n_levels;  /* 2..CTL_DDC_LEVELS_MAX */
    bool torque_guard; /* improvement: flux weighting moves the duty at most one level */
    /* improvement: the flux term decides only between levels whose torque errors are within
     * this times |Te(d=1) - Te(d=0)| of the best (the tie band over the levels' count); 0: off */
    ctl_q tie_per_span;
    ctl_q levels[CTL_DDC_LEVELS_MAX]; /* 1, (n-2)/(n-1), ..., 0; unused entries 0 */
} ctl_ddc_config_t;

/* The k+2 state under the zero vector: torque and flux components (the root on demand). */
typedef struct {
    ctl_q torque;
    ctl_q psi_d;
    ctl_q psi_q;
} ctl_ddc_state_t;

#endif /* CTL_DDC_TYPES_H */
