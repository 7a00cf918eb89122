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
        const int16_t v = candidates[i];
        ctl_q did;
        ctl_q diq;
        ctl_q torque;
        ctl_q flux;
        ctl_q cost;
        ctl_horizon_forced(h, &ctl_vector_vsd[v], &did, &diq);
        cost = ctl_horizon_cost(h, ctl_add(h->id2_free, did), ctl_add(h->iq2_free, diq), &torque,
                                &flux);
        if (cost < out->cost) {
            out->cost = cost;
            out->vector = v;
            out->torque = torque;
            out->flux = flux;
        }
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
