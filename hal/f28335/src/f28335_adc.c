/*
 * hal_adc on the F28335: one cascaded SEQ1 sequence per PWM period, started
 * by ePWM1 SOCA at counter zero; its end-of-sequence interrupt (SEQ1INT,
 * PIE INT1.1) runs the control ISR.
 *
 *   slot  quantity      input     slot  quantity     input
 *   0     phase A       ADCINA0   4     phase E      ADCINA4
 *   1     phase B       ADCINA1   5     phase F      ADCINA5
 *   2     phase C       ADCINA2   6     DC link      ADCINB0
 *   3     phase D       ADCINA3
 *
 * ADC clock: HSPCLK 25 MHz (HISPCP = 3) / 2 (ADCCLKPS = 1) = 12.5 MHz;
 * sample window ACQ_PS + 1 = 4 ADC clocks (320 ns). ADCRESULTn are
 * left-justified 12-bit values: shifted right by 4.
 */
#include "f28335_hal.h"
#include "hal_adc.h"
#include "sixphase_placement.h"

#define ADC_ACQ_PS 3u
#define ADC_CLKPS 1u
#define ADC_HISPCP 3u
#define ADC_POWER_UP_DELAY_US 5000u

const uint16_t f28335_adc_channels[F28335_ADC_CONVERSIONS] = {0u, 1u, 2u, 3u, 4u, 5u, 8u};

static const uint16_t adc_ctrl2_cfg = (uint16_t)(ADC_CTRL2_EPWM_SOCA_SEQ1 | ADC_CTRL2_INT_ENA_SEQ1);
static hal_adc_sample_t adc_last;

static void adc_factory_calibration(void)
{
#if F28335_TARGET
    /* TI's ADC_cal in OTP writes the factory ADCREFSEL/ADCOFFTRIM trim; it
     * needs the ADC clock on. Called through its fixed address.
     * indirect-call: adc_factory_calibration, hal_adc_init -> external ADC_cal */
    void (*const adc_cal)(void) = (void (*)(void))F28335_ADC_CAL_ADDR;
    adc_cal();
#else
    f28335_host_regs.adc_cal_calls++;
#endif
}

static uint16_t adc_chsel_word(uint16_t first_slot)
{
    uint16_t w = 0u;
    uint16_t k;
    for (k = 0u; k < 4u; k++) {
        const uint16_t slot = (uint16_t)(first_slot + k);
        const uint16_t ch = (slot < F28335_ADC_CONVERSIONS) ? f28335_adc_channels[slot] : 0u;
        w = (uint16_t)(w | (uint16_t)((ch & 0xFu) << (4u * k)));
    }
    return w;
}

bool hal_adc_init(void)
{
    volatile f28335_sysctrl_t *sys = F28335_SYSCTRL;
    volatile f28335_adc_t *a = F28335_ADC;
    int16_t i;

    F28335_EALLOW();
    sys->HISPCP = ADC_HISPCP;
    sys->PCLKCR0 |= PCLKCR0_ADCENCLK;
    adc_factory_calibration();
    F28335_EDIS();

    /* Band gap, reference and ADC on, then the 5 ms power-up delay. */
    a->ADCTRL3 = (uint16_t)(ADC_CTRL3_POWER_UP | (ADC_CLKPS << ADC_CTRL3_ADCCLKPS_SHIFT));
    f28335_delay_us(ADC_POWER_UP_DELAY_US);

    /* Cascaded sequencer, start-stop mode, CPS = 0. */
    a->ADCTRL1 = (uint16_t)(ADC_CTRL1_SEQ_CASC | (ADC_ACQ_PS << ADC_CTRL1_ACQ_PS_SHIFT));
    a->ADCMAXCONV = (uint16_t)(F28335_ADC_CONVERSIONS - 1u);
    a->ADCCHSELSEQ[0] = adc_chsel_word(0u);
    a->ADCCHSELSEQ[1] = adc_chsel_word(4u);
    a->ADCCHSELSEQ[2] = 0u;
    a->ADCCHSELSEQ[3] = 0u;
    a->ADCTRL2 = (uint16_t)(adc_ctrl2_cfg | ADC_CTRL2_RST_SEQ1);
    a->ADCST = ADC_ST_INT_SEQ1_CLR;

    for (i = 0; i < HAL_ADC_PHASES; i++) {
        adc_last.phase[i] = (uint16_t)(HAL_ADC_FULL_SCALE / 2u + 1u);
    }
    adc_last.vdc = 0u;
    return true;
}

SIXPHASE_RAMFUNC bool f28335_adc_sequence_pending(void)
{
    return (F28335_ADC->ADCST & ADC_ST_INT_SEQ1) != 0u;
}

SIXPHASE_RAMFUNC bool hal_adc_read(hal_adc_sample_t *s)
{
    volatile f28335_adc_t *a = F28335_ADC;
    const bool fresh = (a->ADCST & ADC_ST_INT_SEQ1) != 0u;
    if (fresh) {
        int16_t i;
        for (i = 0; i < HAL_ADC_PHASES; i++) {
            adc_last.phase[i] = (uint16_t)(a->ADCRESULT[i] >> 4);
        }
        adc_last.vdc = (uint16_t)(a->ADCRESULT[F28335_ADC_SLOT_VDC] >> 4);
        /* Sequencer back to CONV00 for the next SOCA, then clear the flag. */
        a->ADCTRL2 = (uint16_t)(adc_ctrl2_cfg | ADC_CTRL2_RST_SEQ1);
        a->ADCST = ADC_ST_INT_SEQ1_CLR;
    }
    *s = adc_last;
    return fresh;
}

SIXPHASE_RAMFUNC void f28335_adc_isr_ack(void) { F28335_PIECTRL->PIEACK = PIE_GROUP_ACK(1u); }
