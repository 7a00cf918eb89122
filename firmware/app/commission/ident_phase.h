/*
 * Identification step 1, the phase check: a test current along the x axis of the x-y plane,
 * then along its y axis (x-y currents make no torque: the rotor stays where it is), regulated
 * in closed loop. Each phase's share of such a current is cos 5th_k or sin 5th_k; every phase
 * has a share of at least one half in one of the two tests. A phase whose mean current is
 * below the protection's open-phase ratio (20 %) of its share is open (reason OPEN_PHASE, the
 * phase in the result's extra); nothing flowing at all is NO_CURRENT; a phase above twice the
 * test current ends the check at once (CURRENT_LIMIT, or OPEN_PHASE if a phase is then below
 * its ratio: an open phase pushes the others). About 45 ms. The drive also runs it alone
 * before RUN after an OPEN_PHASE fault was cleared (docs/faults.md).
 */
#ifndef IDENT_PHASE_H
#define IDENT_PHASE_H

#include "ident.h"

typedef struct {
    int16_t axis;            /* 0: x, 1: y */
    float sum[IDENT_PHASES]; /* of each phase's current over the measuring window */
    int32_t n;               /* samples in it */
    float min_ratio;         /* smallest ratio of a judged phase so far */
    float max_ratio;         /* largest */
    int16_t min_phase;       /* its phase */
} ident_phase_t;

void ident_phase_begin(ident_ctx_t *x, ident_phase_t *s);
ident_status_t ident_phase_step(ident_ctx_t *x, ident_phase_t *s, const ident_input_t *in);

/* Nominal duration, s (progress). */
#define IDENT_PHASE_SECONDS 0.045f

#endif /* IDENT_PHASE_H */
