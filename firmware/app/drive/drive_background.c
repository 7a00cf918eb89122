/* The background's share of the drive: drive_background and the open-phase commands
 * (drive.h, drive_open_phase.h). Background only, so it stays in flash on the target. */
#include "drive.h"

/* The speed loop at its torque limit in RUN: flagged after DRIVE_TORQUE_LIMITED_FLAG_S, and with
 * the stop action the run stops after the set time. Timed on the ISR's period count. */
static void drive_torque_limit_watch(drive_t *d)
{
    const ctl_q limit = d->ctl.speed_pi.limit;
    float seconds;
    if (d->state != DRIVE_STATE_RUN || d->phase_verifying || d->ctl.loop_mode != CTL_LOOP_SPEED ||
        !(limit > CTL_Q(0.0)) || ctl_abs(d->ctl.diag.torque_ref) < ctl_mul(limit, CTL_Q(0.99))) {
        d->at_limit = false;
        d->torque_limited = false;
        if (d->state == DRIVE_STATE_RUN) {
            d->torque_limited_stopped = false; /* a new run, off the limit */
        }
        return;
    }
    if (!d->at_limit) {
        d->at_limit = true;
        d->at_limit_since = d->isr_count;
    }
    seconds =
        (float)(uint32_t)(d->isr_count - d->at_limit_since) * ctl_params(&d->ctl)->sample_time_s;
    d->torque_limited = seconds >= DRIVE_TORQUE_LIMITED_FLAG_S;
    if (d->torque_limited_action == (int16_t)DRIVE_TORQUE_LIMITED_STOP &&
        seconds >= d->torque_limited_stop_s) {
        d->torque_limited_stopped = true;
        drive_request_stop(d);
    }
}

void drive_background(drive_t *d)
{
    /* every 16th period: 1.6 ms steps are fine for a flag after 0.1 s, and the other periods'
     * passes cost nothing (the simulator's per-period budget) */
    if ((d->isr_count % DRIVE_TORQUE_LIMITED_EVERY) == 0u && d->ctl.initialised) {
        drive_torque_limit_watch(d);
    }
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

bool drive_set_torque_limited_action(drive_t *d, int16_t action, float stop_s)
{
    if ((action != (int16_t)DRIVE_TORQUE_LIMITED_CONTINUE &&
         action != (int16_t)DRIVE_TORQUE_LIMITED_STOP) ||
        !(stop_s > 0.0f && stop_s <= DRIVE_TORQUE_LIMITED_STOP_MAX_S)) {
        return false;
    }
    d->torque_limited_action = action;
    d->torque_limited_stop_s = stop_s;
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
