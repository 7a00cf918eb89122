/*
 * The simulated ADC: six phase-current channels and the DC link, converted once per control
 * period with the board's scaling (hal_board.h: 12 bit, 0..800 V; the current sensors' span
 * from plant_params_t, the board's +-20 A by default), a random offset
 * and gain error per channel (drawn once per run from the seed) and Gaussian noise on every
 * conversion. A fault injection may then corrupt the words before they reach the HAL.
 */
#ifndef SIM_ADC_H
#define SIM_ADC_H

#include "fault_inject.h"
#include "hal_adc.h"
#include "plant.h"
#include "sim_rng.h"

typedef struct {
    double offset_a[HAL_ADC_PHASES]; /* A */
    double gain[HAL_ADC_PHASES];
    double vdc_offset_v, vdc_gain;
    double span_full_a, a_per_count; /* the phase-current sensors' span (plant_params_t) */
    sim_rng_t rng;
    long clipped; /* phase-current conversions at a rail (0 or 4095 counts) since the reset */
} sim_adc_t;

/* Offsets and gain errors of this run (the seed's first 14 uniform numbers). */
void sim_adc_init(sim_adc_t *adc, const plant_params_t *p, uint64_t seed);

/* Convert the phase currents and the DC link of this instant, let the fault corrupt them and
 * post them to the simulator HAL. */
void sim_adc_sample(sim_adc_t *adc, const plant_params_t *p, const double i_phase[HAL_ADC_PHASES],
                    sim_fault_state_t *fs);

#endif /* SIM_ADC_H */
