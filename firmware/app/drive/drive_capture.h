/*
 * The drive's signals as the capture buffer records them (firmware/link/capture_signals.h):
 * this period's value of a signal as its 16-bit sample, and the per-period hook the control
 * ISR calls.
 */
#ifndef DRIVE_CAPTURE_H
#define DRIVE_CAPTURE_H

#include <stdint.h>

#include "drive_core.h"

/* The sample of one signal in this period (0 for an unknown id). */
int16_t drive_capture_value(const drive_t *d, int16_t signal);

/* ISR, after the period's control step: records into d->capture when it is due. */
void drive_capture_period(drive_t *d);

#endif /* DRIVE_CAPTURE_H */
