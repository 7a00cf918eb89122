/*
 * The drive application (firmware/app/drive/drive.c) on the mocked HAL and control core
 * (mock_hal_ctl.h): a drive initialised with the default parameters, run period by period,
 * calibrated, or running. The test keeps its drive_t and passes it in. Include after cmocka.h.
 */
#ifndef DRIVE_FIXTURE_H
#define DRIVE_FIXTURE_H

#include <stdint.h>

#include "drive/drive.h"
#include "mock_hal_ctl.h"

/* Called before each period fixture_run_isr runs, to set the ADC words (mock_adc); NULL (the
 * default after fixture_init): the words stay as the test left them. */
typedef void (*fixture_inputs_fn)(void);
extern fixture_inputs_fn fixture_inputs;
/* Periods fixture_run_isr has run since fixture_init. */
extern uint32_t fixture_periods;

/* Mocks reset (mock_reset), the default parameters, ctl_init succeeding, drive_init: the drive
 * in CALIBRATE with its outputs off. */
void fixture_init(drive_t *d);
/* n control periods, each with a fresh conversion. */
void fixture_run_isr(drive_t *d, int n);
/* The calibration's periods (DRIVE_CALIBRATION_SAMPLES); where it ends is the test's to check. */
void fixture_calibrate(drive_t *d);
/* Calibrated, and READY. */
void fixture_ready(drive_t *d);
/* Calibrated, the core's command enabled, RUN requested and taken: in RUN. */
void fixture_start_running(drive_t *d);

#endif /* DRIVE_FIXTURE_H */
