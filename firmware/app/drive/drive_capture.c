/* The drive's capture signals, see drive_capture.h. */
#include "drive_capture.h"

#include "ctl.h"
#include "sixphase_placement.h"

#define CAPTURE_EXPONENT(id, name, unit, base, exponent) (int16_t)(exponent),
SIXPHASE_RAMCONST static const int16_t capture_exponent[CAPTURE_SIGNAL_COUNT] = {
    CAPTURE_SIGNAL_LIST(CAPTURE_EXPONENT)};
#undef CAPTURE_EXPONENT

/* A per-unit value as a sample: value * 2^(15 - exponent), saturated to 16 bits. */
SIXPHASE_RAMFUNC static int16_t capture_scale(ctl_q value, int16_t signal)
{
    const int32_t s = ctl_to_qn(value, (int16_t)(15 - capture_exponent[signal]));
    return (int16_t)((s > INT16_MAX) ? INT16_MAX : ((s < INT16_MIN) ? INT16_MIN : s));
}

/* The per-unit value of a signal other than the vector. */
SIXPHASE_RAMFUNC static ctl_q capture_pu(const drive_t *d, int16_t signal)
{
    const ctl_diag_t *g = &d->ctl.diag;
    if (signal >= CAPTURE_I_A && signal <= CAPTURE_I_F) {
        return d->meas.i_phase[signal - CAPTURE_I_A];
    }
    switch (signal) {
    case CAPTURE_ID:
        return g->i_d;
    case CAPTURE_IQ:
        return g->i_q;
    case CAPTURE_IX:
        return g->i_x;
    case CAPTURE_IY:
        return g->i_y;
    case CAPTURE_TORQUE:
        return ctl_diag_torque_est(&d->ctl);
    case CAPTURE_TORQUE_REF:
        return g->torque_ref;
    case CAPTURE_FLUX:
        return ctl_diag_flux_est(&d->ctl);
    case CAPTURE_FLUX_REF:
        return g->flux_ref;
    case CAPTURE_SPEED:
        return d->meas.omega_e;
    case CAPTURE_SPEED_REF:
        return d->ctl.speed_ref;
    case CAPTURE_DUTY:
        return d->cmd.duty;
    case CAPTURE_COST:
        return g->cost;
    case CAPTURE_VDC:
        return d->meas.vdc;
    default:
        return CTL_Q(0.0);
    }
}

SIXPHASE_RAMFUNC int16_t drive_capture_value(const drive_t *d, int16_t signal)
{
    if (signal < 0 || signal >= CAPTURE_SIGNAL_COUNT) {
        return 0;
    }
    if (signal == CAPTURE_VECTOR) {
        return d->cmd.vector;
    }
    return capture_scale(capture_pu(d, signal), signal);
}

SIXPHASE_RAMFUNC void drive_capture_period(drive_t *d)
{
    int16_t v[CAPTURE_CHANNELS] = {0, 0, 0, 0};
    int16_t k;
    if (!capture_due(&d->capture)) {
        return;
    }
    for (k = 0; k < d->capture.setup.n_channels; k++) {
        v[k] = drive_capture_value(d, d->capture.setup.signal[k]);
    }
    capture_sample(&d->capture, v, drive_capture_value(d, d->capture.setup.trigger_signal),
                   d->isr_count, d->state == DRIVE_STATE_FAULT);
}
