/* The drive on the mocked HAL and core (drive_fixture.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "drive_fixture.h"

fixture_inputs_fn fixture_inputs;
uint32_t fixture_periods;

void fixture_init(drive_t *d)
{
    ctl_params_t p;
    mock_reset();
    fixture_inputs = NULL;
    fixture_periods = 0u;
    ctl_params_default(&p);
    will_return(ctl_init, true);
    drive_init(d, &p);
}

void fixture_run_isr(drive_t *d, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        if (fixture_inputs != NULL) {
            fixture_inputs();
        }
        will_return(hal_adc_read, true);
        drive_control_isr(d);
        fixture_periods++;
    }
}

void fixture_calibrate(drive_t *d) { fixture_run_isr(d, DRIVE_CALIBRATION_SAMPLES); }

void fixture_ready(drive_t *d)
{
    fixture_calibrate(d);
    assert_int_equal(d->state, DRIVE_STATE_READY);
}

void fixture_start_running(drive_t *d)
{
    fixture_calibrate(d);
    mock_cmd.enable = true;
    drive_request_run(d);
    fixture_run_isr(d, 2);
    assert_int_equal(d->state, DRIVE_STATE_RUN);
}
