/*
 * ADC: one conversion sequence per control period, started by the PWM at
 * counter zero: the period boundary, the symmetry point of the centred pulses.
 * A leg is low there unless its duty is 100 %, so the inverter need not be in
 * its all-low state when the currents are sampled. Raw 12-bit results; scaling
 * to physical units uses hal_board.h, scaling to per unit is the application's.
 */
#ifndef HAL_ADC_H
#define HAL_ADC_H

#include <stdbool.h>
#include <stdint.h>

#define HAL_ADC_PHASES 6
#define HAL_ADC_FULL_SCALE 4095u

typedef struct {
    uint16_t phase[HAL_ADC_PHASES]; /* A..F current sensors, counts 0..4095 */
    uint16_t vdc;                   /* DC-link divider, counts 0..4095 */
} hal_adc_sample_t;

bool hal_adc_init(void);

/* Latest completed sequence. False if no new sequence completed since the last call. */
bool hal_adc_read(hal_adc_sample_t *s);

#endif /* HAL_ADC_H */
