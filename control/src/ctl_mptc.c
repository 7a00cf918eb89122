#include "ctl_mptc.h"

#include "ctl_vectors.h"
#include "ctl_placement.h"

CTL_RAMFUNC_FLOAT void ctl_mptc_select(const ctl_horizon_t *h, const int16_t *candidates,
                                       int16_t count, int16_t vector_in_force, ctl_choice_t *out)
{
    int16_t i;
    out->cost = CTL_Q_MAX;
    out->vector = 0;
    out->torque = CTL_Q(0.0);
    out->flux = CTL_Q(0.0);
    for (i = 0; i < count; i++) {
        ctl_q did;
        ctl_q diq;
        ctl_horizon_forced(h, &ctl_vector_vsd[candidates[i]], &did, &diq);
        ctl_choice_consider(h, did, diq, candidates[i], out);
    }
    if (out->vector == 0 && ctl_vector_ones(vector_in_force) > 3) {
        out->vector = 077;
    }
    out->duty = CTL_Q(1.0);
    out->candidates = count;
    out->flux_sector = -1;
    out->xy_sector = -1;
    out->braking = false;
}
