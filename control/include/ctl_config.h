/*
 * The derived configuration: everything the control period needs from a parameter set,
 * computed once, outside the ISR (C2000Ware's init/run split). The control step, the
 * protection check and the drive's measurement scaling read only this; nothing in it is
 * computed per period.
 *
 * Building one takes milliseconds on the target (the MTPA table alone bisects 33 points),
 * so it is done in the background into the standby half of a double buffer and handed to
 * the ISR ready-made (ctl.h: ctl_request_params / ctl_config_take).
 */
#ifndef CTL_CONFIG_H
#define CTL_CONFIG_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_ddc.h"
#include "ctl_flux_ref.h"
#include "ctl_foc_types.h"
#include "ctl_params.h"
#include "ctl_predict.h"
#include "ctl_protect.h"
#include "ctl_q.h"

typedef struct {
    ctl_params_t params; /* the SI set this was built from */
    ctl_model_t model;
    ctl_flux_ref_t flux_ref;
    ctl_q lambda;       /* per unit torque per per-unit flux */
    ctl_q torque_limit; /* with an open phase divided by ctl_postfault_peak_ratio */
    ctl_q speed_kp;
    ctl_q speed_ki_ts;
    /* the DDC search's settings and duty levels, or for a FOC-VSD set its bandwidth and current
     * references (a FOC set never runs the DDC: with an open phase it falls back to the
     * post-fault MPTC-13) */
    union {
        ctl_ddc_config_t ddc;
        ctl_foc_config_t foc;
    } ctrl;
    /* drive scaling: electrical per unit speed per mechanical rev/s */
    ctl_q omega_pu_per_rev_s;
    ctl_protect_limits_t protect;
} ctl_config_t;

/* Checks p and builds cfg from it. On a refusal cfg is left partly written and must not be
 * used. Background only: far too slow for the control period. */
ctl_param_error_t ctl_config_build(ctl_config_t *cfg, const ctl_params_t *p);

#endif /* CTL_CONFIG_H */
