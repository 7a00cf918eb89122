/*
 * Conventional MPTC: every candidate of a set held for the whole period,
 * minimum of the same cost J. The zero candidate is realised as u00 or u77,
 * whichever is closer (fewer leg changes) to the state in force.
 */
#ifndef CTL_MPTC_H
#define CTL_MPTC_H

#include <stdint.h>

#include "ctl_search.h"

void ctl_mptc_select(const ctl_horizon_t *h, const int16_t *candidates, int16_t count,
                     int16_t vector_in_force, ctl_choice_t *out);

#endif /* CTL_MPTC_H */
