/*
 * The drive's side of commissioning (docs/commissioning.md): the start request and its
 * refusals, the periods of the state COMMISSION, the phase check a run must pass after an
 * OPEN_PHASE fault was cleared, and applying the identified values. The sequence itself is
 * commission.h's.
 */
#ifndef DRIVE_COMMISSION_H
#define DRIVE_COMMISSION_H

#include <stdbool.h>
#include <stdint.h>

#include "drive_core.h"

typedef enum {
    DRIVE_COMM_OK = 0,
    DRIVE_COMM_INVALID = 1, /* the mask or the current is not valid */
    DRIVE_COMM_REFUSED = 2, /* not in this state (the reason in d->comm.reason) */
    DRIVE_COMM_BUSY = 3,    /* the previous parameter set still waits for the ISR */
    DRIVE_COMM_REJECTED = 4 /* the control core refused the identified set */
} drive_comm_result_t;

/* Test current of the phase check before RUN after an OPEN_PHASE clear, per mille of rated. */
#define DRIVE_PHASE_VERIFY_PERMILLE 300u

/* Background: ask for the sequence with these steps (commission_lists.h) and test current.
 * Refused outside READY, with the DC link below the under-voltage limit, or with an encoder
 * error (an index seen, then the interface unhealthy); the encoder's index need not have been
 * seen. The ISR starts it in its next period (READY -> COMMISSION). */
drive_comm_result_t drive_request_commission(drive_t *d, uint16_t mask, uint16_t permille);

/* Background, READY: the identified values whose quality is OK into a parameter set (the one
 * in force otherwise), requested through the parameter hand-off, and the encoder offset into
 * the HAL. *applied: the quantities applied (bit per comm_quantity_t). */
drive_comm_result_t drive_commission_apply(drive_t *d, uint16_t *applied);

/* The machine as the parameter set in force describes it (ISR side). */
void drive_commission_machine(const drive_t *d, ident_machine_t *m);

/* ISR, READY: a start request that still stands goes to COMMISSION. */
void drive_commission_begin(drive_t *d);

/* ISR, COMMISSION: one period; back to READY with the outputs off when it ends or is
 * stopped. */
void drive_commission_period(drive_t *d);

/* ISR, READY -> RUN after an OPEN_PHASE clear: the phase check first. */
void drive_phase_verify_start(drive_t *d);

/* ISR, RUN while verifying: one period of the check; normal control only once it passed, a
 * failure goes back to FAULT OPEN_PHASE. */
void drive_phase_verify_period(drive_t *d);

/* The protection's angle in COMMISSION: from the unwrapped count, continuous across the
 * index's reset of the angle (per unit turn). */
ctl_q drive_commission_angle(const drive_t *d);

#endif /* DRIVE_COMMISSION_H */
