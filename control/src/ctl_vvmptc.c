#include "ctl_vvmptc.h"

#include "ctl_vectors.h"
#include "ctl_placement.h"

CTL_RAMFUNC_FLOAT int16_t ctl_vvmptc_select(const ctl_horizon_t *h, int16_t vector_in_force,
                                            ctl_choice_t *out)
{
    int16_t k;
    out->cost = CTL_Q_MAX;
    out->vector = CTL_VV_NONE;
    out->torque = CTL_Q(0.0);
    out->flux = CTL_Q(0.0);
    /* the zero candidate first (as MPTC's sets, no forced response), then the virtual vectors;
     * one call of the (inline) candidate test, so that it is inlined here */
    for (k = CTL_VV_NONE; k < CTL_VV_COUNT; k++) {
        ctl_q did = CTL_Q(0.0);
        ctl_q diq = CTL_Q(0.0);
        if (k != CTL_VV_NONE) {
            ctl_horizon_forced(h, &ctl_vv_vsd[k], &did, &diq);
        }
        ctl_choice_consider(h, did, diq, k, out);
    }
    k = out->vector;
    if (k == CTL_VV_NONE) {
        out->vector = (ctl_vector_ones(vector_in_force) > 3) ? 077 : 0;
    } else {
        out->vector = ctl_vv_states[k][0];
    }
    out->duty = CTL_Q(1.0);
    out->candidates = CTL_VVMPTC_CANDIDATES;
    out->flux_sector = -1;
    out->xy_sector = -1;
    out->braking = false;
    return k;
}
