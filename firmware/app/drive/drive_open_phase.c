/* Open-phase operation of the drive, see drive_open_phase.h. */
#include "drive_open_phase.h"

#include "hal_pwm.h"
#include "sixphase_placement.h"

/* Both switches of the leg off for good, the others off until the set that fits arrives. */
static void drive_isolate(drive_t *d, int16_t leg, drive_isolation_cause_t cause)
{
    (void)hal_pwm_isolate_leg(leg);
    hal_pwm_force_off();
    d->isolated_leg = leg;
    d->isolation_cause = (int16_t)cause;
    d->isolation_period = d->isr_count;
}

uint16_t drive_open_phase_faults(drive_t *d, uint16_t faults)
{
    const int16_t leg = ctl_protect_open_phase(&d->protect);
    if (faults != CTL_FAULT_OPEN_PHASE || d->open_phase_action != DRIVE_OPEN_PHASE_RIDE_THROUGH ||
        d->state != DRIVE_STATE_RUN || d->isolated_leg >= 0 || leg < 0) {
        return faults; /* another fault with it, the option off, a second phase, none named */
    }
    drive_isolate(d, leg, DRIVE_ISOLATION_FAULT);
    ctl_protect_accept(&d->protect, CTL_FAULT_OPEN_PHASE); /* its record stays in the log */
    return 0u;
}

SIXPHASE_RAMFUNC bool drive_open_phase_in_force(const drive_t *d)
{
    return ctl_postfault_config(&d->ctl)->open_leg == d->isolated_leg;
}

/* Not the usual period (drive_open_phase_period): a request, or a leg isolated. With six legs
 * and nothing asked the protection judges all phases, as set here at a restore. */
SIXPHASE_RAMFUNC void drive_open_phase_update(drive_t *d)
{
    const bool ready_or_run = d->state == DRIVE_STATE_READY || d->state == DRIVE_STATE_RUN;
    uint16_t quiet = 0u;
    if (d->isolate_request >= 0) {
        const int16_t leg = d->isolate_request;
        d->isolate_request = -1;
        if (ready_or_run && d->isolated_leg < 0) {
            drive_isolate(d, leg, DRIVE_ISOLATION_COMMAND);
        }
    }
    if (d->restore_request) {
        d->restore_request = false;
        if (d->state == DRIVE_STATE_READY && d->isolated_leg >= 0) {
            hal_pwm_restore_legs(); /* the outputs are off in READY; RUN enables them */
            d->isolated_leg = -1;
            d->isolation_cause = (int16_t)DRIVE_ISOLATION_NONE;
        }
    }
    if (d->isolated_leg >= 0) {
        /* the isolated phase, and what the strategy in force keeps at zero with it */
        quiet = (uint16_t)(1u << d->isolated_leg);
        if (drive_open_phase_in_force(d)) {
            quiet |= ctl_postfault_config(&d->ctl)->quiet;
        }
    }
    ctl_protect_quiet(&d->protect, quiet);
}

/* Not the usual period (drive_open_phase_gate). */
SIXPHASE_RAMFUNC bool drive_open_phase_gate_update(drive_t *d)
{
    if (!drive_open_phase_in_force(d)) {
        hal_pwm_force_off();
        d->open_phase_paused = true;
        return false;
    }
    if (d->open_phase_paused) {
        /* nothing was applied while paused: the prediction must not assume the old command;
         * the speed loop's integrator is kept (within the new limit) */
        d->open_phase_paused = false;
        ctl_reset_command(&d->ctl);
        hal_pwm_enable();
    }
    return true;
}
