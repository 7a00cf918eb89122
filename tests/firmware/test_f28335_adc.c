/* ADC driver against RAM register frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "f28335_hal.h"
#include "hal_adc.h"

#define R (f28335_host_regs)

static int setup(void **state)
{
    (void)state;
    f28335_host_regs_reset();
    return 0;
}

static void test_init_clock_power_sequence(void **state)
{
    (void)state;
    assert_true(hal_adc_init());
    assert_int_equal(R.sysctrl.PCLKCR0 & PCLKCR0_ADCENCLK, PCLKCR0_ADCENCLK);
    assert_int_equal(R.sysctrl.HISPCP, 3);              /* HSPCLK = 25 MHz */
    assert_int_equal(R.adc_cal_calls, 1);               /* factory trim loaded */
    assert_int_equal(R.adc.ADCTRL3 & 0x00E0u, 0x00E0u); /* band gap, reference, ADC powered */
    assert_int_equal((R.adc.ADCTRL3 >> 1) & 0xFu, 1u);  /* ADCCLK = 12.5 MHz */
    assert_int_equal(R.adc.ADCTRL3 & 1u, 0u);           /* sequential sampling */
}

static void test_init_sequence(void **state)
{
    (void)state;
    assert_true(hal_adc_init());
    /* cascaded, start-stop, CPS = 0, ACQ_PS = 3 */
    assert_int_equal(R.adc.ADCTRL1 & ADC_CTRL1_SEQ_CASC, ADC_CTRL1_SEQ_CASC);
    assert_int_equal(R.adc.ADCTRL1 & ADC_CTRL1_CONT_RUN, 0);
    assert_int_equal(R.adc.ADCTRL1 & ADC_CTRL1_CPS, 0);
    assert_int_equal((R.adc.ADCTRL1 >> 8) & 0xFu, 3u);
    assert_int_equal(R.adc.ADCMAXCONV, 6); /* 7 conversions */
    /* CONV00..03 = A0..A3, CONV04..06 = A4, A5, B0 (channel code 8) */
    assert_int_equal(R.adc.ADCCHSELSEQ[0], 0x3210u);
    assert_int_equal(R.adc.ADCCHSELSEQ[1], 0x0854u);
    /* SEQ1 started by ePWM SOCA, interrupt every end of sequence */
    assert_int_equal(R.adc.ADCTRL2 & ADC_CTRL2_EPWM_SOCA_SEQ1, ADC_CTRL2_EPWM_SOCA_SEQ1);
    assert_int_equal(R.adc.ADCTRL2 & ADC_CTRL2_INT_ENA_SEQ1, ADC_CTRL2_INT_ENA_SEQ1);
    assert_int_equal(R.adc.ADCTRL2 & ADC_CTRL2_INT_MOD_SEQ1, 0);
    assert_int_equal(f28335_adc_channels[F28335_ADC_SLOT_VDC], 8);
}

static void test_read_new_and_stale(void **state)
{
    hal_adc_sample_t s;
    int i;
    (void)state;
    assert_true(hal_adc_init());
    assert_false(hal_adc_read(&s)); /* nothing converted yet */

    for (i = 0; i < 6; i++) {
        R.adc.ADCRESULT[i] = (uint16_t)((1000u + 100u * (uint16_t)i) << 4); /* left-justified */
    }
    R.adc.ADCRESULT[6] = (uint16_t)(4095u << 4);
    R.adc.ADCST = ADC_ST_INT_SEQ1;
    R.adc.ADCTRL2 = 0u;
    assert_true(f28335_adc_sequence_pending());
    assert_true(hal_adc_read(&s));
    for (i = 0; i < 6; i++) {
        assert_int_equal(s.phase[i], 1000 + 100 * i);
    }
    assert_int_equal(s.vdc, 4095);
    /* flag cleared (write 1 to INT_SEQ1_CLR), sequencer reset, config kept */
    assert_int_equal(R.adc.ADCST, ADC_ST_INT_SEQ1_CLR);
    assert_int_equal(R.adc.ADCTRL2 & ADC_CTRL2_RST_SEQ1, ADC_CTRL2_RST_SEQ1);
    assert_int_equal(R.adc.ADCTRL2 & ADC_CTRL2_EPWM_SOCA_SEQ1, ADC_CTRL2_EPWM_SOCA_SEQ1);

    /* no new completion: false, latest values repeated */
    R.adc.ADCST = 0u;
    R.adc.ADCRESULT[0] = 0u;
    assert_false(f28335_adc_sequence_pending());
    assert_false(hal_adc_read(&s));
    assert_int_equal(s.phase[0], 1000);
}

static void test_isr_ack(void **state)
{
    (void)state;
    f28335_adc_isr_ack();
    assert_int_equal(R.piectrl.PIEACK, 0x0001u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_init_clock_power_sequence, setup),
        cmocka_unit_test_setup(test_init_sequence, setup),
        cmocka_unit_test_setup(test_read_new_and_stale, setup),
        cmocka_unit_test_setup(test_isr_ack, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
