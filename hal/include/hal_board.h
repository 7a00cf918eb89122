/*
 * Analogue front end of the reference inverter board: how ADC counts map to
 * amperes and volts. One place, used by the firmware's scaling and by the
 * simulator's ADC model.
 *
 * Phase currents: bipolar Hall sensors, +-20 A over 0..3 V, zero at mid scale.
 * DC link: resistive divider, 0..800 V over 0..3 V.
 */
#ifndef HAL_BOARD_H
#define HAL_BOARD_H

#define HAL_BOARD_CURRENT_FULL_SPAN_A 40.0 /* -20 A .. +20 A */
#define HAL_BOARD_CURRENT_ZERO_COUNTS 2048.0
#define HAL_BOARD_CURRENT_A_PER_COUNT (HAL_BOARD_CURRENT_FULL_SPAN_A / 4096.0)
#define HAL_BOARD_VDC_FULL_SCALE_V 800.0
#define HAL_BOARD_VDC_V_PER_COUNT (HAL_BOARD_VDC_FULL_SCALE_V / 4096.0)

#define HAL_BOARD_ENCODER_LINES 2500u
#define HAL_BOARD_PWM_HZ 10000u
#define HAL_BOARD_DEAD_TIME_NS 2000u

/* Accuracy of the front end (the board's limits: each channel's error lies within +-these).
 * The phase currents' offsets are measured at power-up (the drive's calibration); the channels'
 * gain errors and the DC link's offset are not. The simulator's ADC model draws its errors
 * within these; the commissioning states its uncertainty from them. */
#define HAL_BOARD_ADC_GAIN_TOLERANCE 0.005 /* relative, each channel */
#define HAL_BOARD_ADC_OFFSET_TOLERANCE_COUNTS 20.0

#endif /* HAL_BOARD_H */
