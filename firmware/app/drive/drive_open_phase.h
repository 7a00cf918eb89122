/*
 * Open-phase operation of the drive (docs/faults.md, "Riding through an open phase").
 *
 * With the option DRIVE_OPEN_PHASE_RIDE_THROUGH, OPEN_PHASE in RUN with one phase named by the
 * protection (ctl_protect_open_phase) and no other fault in that period does not stop the
 * drive: the ISR isolates that leg for good (hal_pwm_isolate_leg), forces the other outputs off,
 * unlatches the fault (its record stays in the log) and stays in RUN. The background then asks
 * for the post-fault parameter set (drive_background -> drive_request_params, which always sets
 * open_phase to the isolated leg); until the ISR takes it the outputs stay off, then the control
 * step runs on five legs (ctl_postfault.h) with the derated torque limit. A command can isolate a
 * leg the same way (for tests on a healthy machine), in READY or RUN.
 *
 * A second OPEN_PHASE while a leg is isolated stops the drive (FAULT) with a record of its own.
 * FAULT -> READY and STOP -> READY keep the leg isolated, and a later RUN runs on five legs
 * again; only a restore command in READY ends the isolation (then the background asks for the
 * healthy set). With the option DRIVE_OPEN_PHASE_STOP (the build default) OPEN_PHASE stops the
 * drive as every other fault does.
 *
 * Ownership: the ISR writes isolated_leg and the isolation's cause and period; the background
 * writes the option, the strategy and the requests; each is a 16-bit store.
 */
#ifndef DRIVE_OPEN_PHASE_H
#define DRIVE_OPEN_PHASE_H

#include <stdbool.h>
#include <stdint.h>

#include "drive_core.h"

/* The ISR: what the period's faults leave after a ride-through (the faults to latch). */
uint16_t drive_open_phase_faults(drive_t *d, uint16_t faults);

void drive_open_phase_update(drive_t *d);
bool drive_open_phase_gate_update(drive_t *d);

/* The ISR, every period after the protection: acts on an isolation or restore command and keeps
 * the protection's quiet phases those of the isolation in force. (Inline, the usual period in
 * one test: six legs and nothing asked.) */
static inline void drive_open_phase_period(drive_t *d)
{
    if (d->isolate_request >= 0 || d->restore_request || d->isolated_leg >= 0) {
        drive_open_phase_update(d);
    }
}

/* The ISR, in RUN before the control step: false while the configuration in force does not
 * match the legs (a post-fault set on its way, or a healthy one after a restore): the outputs
 * are then off. When they match again the controller restarts and the outputs come back.
 * (Inline, the usual period in one test: six legs and the healthy set in force.) */
static inline bool drive_open_phase_gate(drive_t *d)
{
    return (d->isolated_leg < 0 && d->ctl.healthy_step && !d->open_phase_paused) ||
           drive_open_phase_gate_update(d);
}

/* The post-fault set of the isolated leg (or the healthy set after a restore) is in force. */
bool drive_open_phase_in_force(const drive_t *d);

#endif /* DRIVE_OPEN_PHASE_H */
