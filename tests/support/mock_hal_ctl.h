/*
 * CMocka mocks of the HAL and of the control core API, for testing the drive
 * application (firmware/app) alone.
 *   hal_adc_read   returns mock() (queue with will_return); on true copies
 *                  mock_adc into the sample
 *   ctl_init       returns mock() (queue with will_return); on true builds the real
 *                  configuration
 *   ctl_request_params returns mock_request_result when not CTL_PARAM_OK, else follows
 *                  the real hand-off (build, publish; ctl_config_take switches)
 *   everything else records calls and arguments in mock_rec
 */
#ifndef MOCK_HAL_CTL_H
#define MOCK_HAL_CTL_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl.h"
#include "hal_adc.h"
#include "hal_board.h"
#include "hal_encoder.h"
#include "hal_pwm.h"

typedef struct {
    uint32_t force_off;
    uint32_t enable;
    uint32_t write;
    uint16_t duty[HAL_PWM_LEGS];
    bool pwm_off;      /* returned by hal_pwm_is_off */
    bool hw_trip;      /* returned by hal_pwm_hw_trip_seen */
    uint32_t rehome;   /* hal_encoder_rehome calls */
    uint16_t isolated; /* hal_pwm_isolate_leg's legs */
    uint32_t ctl_reset;
    uint32_t ctl_reset_command;
    uint32_t ctl_step;
    uint32_t request_params;
    uint32_t config_take;
    ctl_params_t requested;
    ctl_loop_mode_t loop_mode;
    ctl_q speed_ref;
    ctl_q torque_ref;
} mock_record_t;

extern mock_record_t mock_rec;
extern hal_adc_sample_t mock_adc;
extern hal_encoder_sample_t mock_encoder;
extern uint32_t mock_encoder_offset; /* hal_encoder_offset / hal_encoder_set_offset */
extern ctl_cmd_t mock_cmd;           /* what ctl_step returns */
extern ctl_diag_t mock_diag;         /* what ctl_diag returns */
extern ctl_param_error_t mock_request_result;

/* mock_reset's ADC words, from the board's scaling: no current (mid scale), a 540 V DC link. */
#define MOCK_ADC_ZERO ((uint16_t)HAL_BOARD_CURRENT_ZERO_COUNTS)
#define MOCK_ADC_VDC_540V ((uint16_t)(540.0 / HAL_BOARD_VDC_V_PER_COUNT + 0.5)) /* 2765 */

void mock_reset(void);

#endif
