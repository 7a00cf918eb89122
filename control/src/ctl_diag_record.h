/*
 * What a control step leaves in its diagnostics, shared by the healthy step (ctl.c) and the
 * open-phase step (ctl_postfault.c), which differ only in where their sampled currents come
 * from. Static inline and called once in each (as ctl_ddc_levels.h).
 */
#ifndef CTL_DIAG_RECORD_H
#define CTL_DIAG_RECORD_H

#include "ctl_diag.h"
#include "ctl_search.h"

/* The sampled d-q and x-y currents, the references of the horizon and the choice, into dg (the
 * controller's ctl_t.diag); the estimates from the currents are their readers' (ctl.h). */
static inline void ctl_diag_record(ctl_diag_t *dg, ctl_q id, ctl_q iq, ctl_q ix, ctl_q iy,
                                   const ctl_horizon_t *h, const ctl_choice_t *choice)
{
    dg->i_d = id;
    dg->i_q = iq;
    dg->i_x = ix;
    dg->i_y = iy;
    dg->torque_ref = h->torque_ref;
    dg->flux_ref = h->flux_ref;
    dg->torque_pred = choice->torque;
    dg->flux_pred = choice->flux;
    dg->cost = choice->cost;
    dg->flux_sector = choice->flux_sector;
    dg->xy_sector = choice->xy_sector;
    dg->candidates = choice->candidates;
    dg->braking = choice->braking;
}

#endif /* CTL_DIAG_RECORD_H */
