/*
 * Virtual-vector MPTC (VV-MPTC): the conventional MPTC's two-step prediction and cost J over
 * 13 candidates, the zero vector and 12 virtual vectors. A virtual vector combines, within one
 * period, the G4 (large) and the G3 (medium-large) state of the same alpha-beta direction
 * 15 + 30 k deg, the G4 state for sqrt(3) - 1 = 0.732 of the period and the G3 state for
 * 2 - sqrt(3) = 0.268: their x-y voltages (0.173 and 0.471 Vdc, opposite) cancel over the
 * period, the alpha-beta voltage is 0.598 Vdc. The cost has no x-y term: the candidates
 * themselves apply no x-y volt-seconds. docs/design.md, "Virtual-vector MPTC".
 *
 * Realised as per-leg duties (ctl.h command semantics): each leg is on for its share of the
 * two states, one pulse centred in the period.
 */
#ifndef CTL_VVMPTC_H
#define CTL_VVMPTC_H

#include <stdint.h>

#include "ctl_search.h"

#define CTL_VVMPTC_CANDIDATES 13 /* the zero vector and CTL_VV_COUNT virtual vectors */

/* The least-cost candidate: returns its virtual vector 0..CTL_VV_COUNT - 1 (out->vector its
 * large state, duty 1), or CTL_VV_NONE for the zero vector (out->vector u00 or u77, the one
 * closer to the state in force, as the MPTC baselines). The same pruning as MPTC's
 * (ctl_choice_consider): a candidate's flux root only where its torque error can still win. */
int16_t ctl_vvmptc_select(const ctl_horizon_t *h, int16_t vector_in_force, ctl_choice_t *out);

#endif /* CTL_VVMPTC_H */
