/* The simulated ADC, see sim_adc.h. */
#include "sim_adc.h"

#include "hal_board.h"
#include "hal_sim.h"

void sim_adc_init(sim_adc_t *adc, const plant_params_t *p, uint64_t seed)
{
    int k;
    double uo, ug;
    adc->span_full_a = 2.0 * p->current_sensor_span_a;
    adc->a_per_count = adc->span_full_a / (double)(HAL_ADC_FULL_SCALE + 1u);
    sim_rng_seed(&adc->rng, seed);
    for (k = 0; k < HAL_ADC_PHASES; k++) {
        uo = 2.0 * sim_rng_uniform(&adc->rng) - 1.0;
        ug = 2.0 * sim_rng_uniform(&adc->rng) - 1.0;
        adc->offset_a[k] = p->adc_offset_on ? uo * p->adc_offset_counts * adc->a_per_count : 0.0;
        adc->gain[k] = p->adc_gain_on ? 1.0 + ug * p->adc_gain_error : 1.0;
    }
    uo = 2.0 * sim_rng_uniform(&adc->rng) - 1.0;
    ug = 2.0 * sim_rng_uniform(&adc->rng) - 1.0;
    adc->vdc_offset_v =
        p->adc_offset_on ? uo * p->adc_offset_counts * HAL_BOARD_VDC_V_PER_COUNT : 0.0;
    adc->vdc_gain = p->adc_gain_on ? 1.0 + ug * p->adc_gain_error : 1.0;
    adc->clipped = 0;
}

void sim_adc_sample(sim_adc_t *adc, const plant_params_t *p, const double i_phase[HAL_ADC_PHASES],
                    sim_fault_state_t *fs)
{
    hal_adc_sample_t a;
    int k;
    double v;
    for (k = 0; k < HAL_ADC_PHASES; k++) {
        v = i_phase[k] * adc->gain[k] + adc->offset_a[k];
        if (p->adc_noise_on) {
            v += sim_rng_gauss(&adc->rng) * p->adc_noise_counts * adc->a_per_count;
        }
        a.phase[k] = hal_sim_current_to_counts(v, adc->span_full_a);
        if (a.phase[k] == 0u || a.phase[k] >= HAL_ADC_FULL_SCALE) {
            adc->clipped++;
        }
    }
    v = p->vdc_v * adc->vdc_gain + adc->vdc_offset_v;
    if (p->adc_noise_on) {
        v += sim_rng_gauss(&adc->rng) * p->adc_noise_counts * HAL_BOARD_VDC_V_PER_COUNT;
    }
    a.vdc = hal_sim_vdc_to_counts(v);
    sim_fault_adc(fs, &a);
    hal_sim_post_adc(&a);
}
