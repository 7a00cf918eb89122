/* The background's share of the drive: drive_background and the open-phase commands
 * (drive.h, drive_open_phase.h). Background only, so it stays in flash on the target. */
#include "drive.h"

void drive_background(drive_t *d)
{
    if ((d->params_bg.open_phase != d->isolated_leg ||
         d->params_bg.postfault_strategy != d->postfault_strategy) &&
        !ctl_config_pending(&d->ctl)) {
        (void)drive_request_params(d, &d->params_bg); /* sets both; BUSY: next pass */
    }
}

bool drive_set_open_phase_action(drive_t *d, int16_t action, int16_t strategy)
{
    if ((action != (int16_t)DRIVE_OPEN_PHASE_STOP &&
         action != (int16_t)DRIVE_OPEN_PHASE_RIDE_THROUGH) ||
        (strategy != (int16_t)CTL_POSTFAULT_MIN_LOSS &&
         strategy != (int16_t)CTL_POSTFAULT_MAX_TORQUE)) {
        return false;
    }
    d->open_phase_action = action;
    d->postfault_strategy = strategy;
    return true;
}

bool drive_request_isolate_leg(drive_t *d, int16_t leg)
{
    if (leg < 0 || leg > 5 || d->isolated_leg >= 0 ||
        !(d->state == DRIVE_STATE_READY || d->state == DRIVE_STATE_RUN)) {
        return false;
    }
    d->isolate_request = leg;
    return true;
}

bool drive_request_restore_legs(drive_t *d)
{
    if (d->state != DRIVE_STATE_READY || d->isolated_leg < 0) {
        return false;
    }
    d->restore_request = true;
    return true;
}
