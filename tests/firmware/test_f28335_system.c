/* PIE, clocks, flash, watchdog, cycle counter and SCI-A against RAM frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "f28335_hal.h"
#include "hal_cycles.h"

#define R (f28335_host_regs)

static int setup(void **state)
{
    (void)state;
    f28335_host_regs_reset();
    return 0;
}

static void default_isr(void) {}
static void adc_isr(void) {}

static void test_pie_vectors_and_enables(void **state)
{
    int i;
    (void)state;
    R.piectrl.group[0].IFR = 0x00FFu;
    f28335_pie_init(default_isr);
    for (i = 0; i < 128; i++) {
        assert_ptr_equal(R.pievect.vector[i], default_isr);
    }
    assert_int_equal(R.piectrl.PIECTRL & PIE_CTRL_ENPIE, PIE_CTRL_ENPIE);
    assert_int_equal(R.piectrl.group[0].IFR, 0u);
    assert_int_equal(f28335_host_core.intm, 1u);

    f28335_pie_install(1u, 1u, adc_isr);
    f28335_pie_enable(1u, 1u);
    /* INT1.1 (SEQ1INT) at table entry 32 = word offset 0x40 (address 0x0D40) */
    assert_ptr_equal(R.pievect.vector[32], adc_isr);
    assert_ptr_equal(R.pievect.vector[33], default_isr);
    assert_int_equal(R.piectrl.group[0].IER, 0x0001u);
    assert_int_equal(f28335_host_core.ier, CPU_IER_INT1);
    assert_int_equal(PIE_VECTOR_INDEX(1u, 7u), 38u);                    /* TINT0 at 0x0D4C */
    assert_int_equal(PIE_VECTOR_INDEX(5u, 1u) * 2u + 0x0D00u, 0x0D80u); /* eQEP1 */

    f28335_interrupts_enable_global();
    assert_int_equal(f28335_host_core.intm, 0u);
    f28335_pie_ack(1u);
    assert_int_equal(R.piectrl.PIEACK, 0x0001u);
    f28335_pie_ack(5u);
    assert_int_equal(R.piectrl.PIEACK, 0x0010u);
    /* out-of-range requests are ignored */
    f28335_pie_install(13u, 1u, adc_isr);
    f28335_pie_enable(1u, 9u);
    assert_int_equal(R.piectrl.group[0].IER, 0x0001u);
}

static void test_clock_init(void **state)
{
    (void)state;
    assert_true(f28335_clock_init());
    assert_int_equal(R.sysctrl.PLLCR, 10u);
    assert_int_equal(R.sysctrl.PLLSTS & PLLSTS_DIVSEL_MASK, PLLSTS_DIVSEL_DIV2);
    assert_int_equal(R.sysctrl.PLLSTS & PLLSTS_MCLKOFF, 0u); /* detection back on */
    assert_int_equal(R.sysctrl.HISPCP, 3u);
    assert_int_equal(R.sysctrl.LOSPCP, 2u);
    assert_int_equal(R.sysctrl.PCLKCR0 & PCLKCR0_TBCLKSYNC, 0u);
    assert_int_equal(R.sysctrl.PCLKCR1, PCLKCR1_EPWM_ALL | PCLKCR1_EQEP1ENCLK);
    assert_int_equal(R.sysctrl.PCLKCR0 & (PCLKCR0_ADCENCLK | PCLKCR0_SCIAENCLK),
                     PCLKCR0_ADCENCLK | PCLKCR0_SCIAENCLK);

    /* missing clock: PLL left alone, reported */
    f28335_host_regs_reset();
    R.sysctrl.PLLSTS = PLLSTS_MCLKSTS;
    assert_false(f28335_clock_init());
    assert_int_equal(R.sysctrl.PLLCR, 0u);
}

static void test_flash_and_watchdog(void **state)
{
    (void)state;
    f28335_flash_init();
    assert_int_equal(R.flash.FOPT, FOPT_ENPIPE);
    assert_int_equal(R.flash.FBANKWAIT, 0x0505u); /* PAGEWAIT 5, RANDWAIT 5 */
    assert_int_equal(R.flash.FOTPWAIT, 8u);
    assert_int_equal(f28335_host_core.nop_count, 8u); /* pipeline flushed */

    f28335_watchdog_disable();
    assert_int_equal(R.sysctrl.WDCR, 0x0068u);
    f28335_watchdog_enable();
    assert_int_equal(R.sysctrl.WDCR, 0x002Fu);
    assert_int_equal((R.sysctrl.WDCR >> 3) & 7u, 5u); /* WDCHK = 101 */
    R.sysctrl.WDKEY = 0u;
    f28335_watchdog_service();
    assert_int_equal(R.sysctrl.WDKEY, 0x00AAu); /* 0x55 then 0xAA */
}

static void test_cycle_counter(void **state)
{
    (void)state;
    hal_cycles_init();
    assert_int_equal(R.cputimer[1].PRD, 0xFFFFFFFFu);
    assert_int_equal(R.cputimer[1].TPR, 0u);
    assert_int_equal(R.cputimer[1].TCR & TIMER_TCR_TSS, 0u); /* running */
    assert_int_equal(R.cputimer[1].TCR & TIMER_TCR_TIE, 0u); /* no interrupt */
    assert_int_equal(R.sysctrl.PCLKCR3 & PCLKCR3_CPUTIMER1ENCLK, PCLKCR3_CPUTIMER1ENCLK);
    assert_int_equal(hal_cycles_per_second(), 150000000u);
    /* down-counter read as up-counter, wrapping */
    R.cputimer[1].TIM = 0xFFFFFFFFu;
    assert_int_equal(hal_cycles_now(), 0u);
    R.cputimer[1].TIM = 0xFFFFFFFFu - 1500u;
    assert_int_equal(hal_cycles_now(), 1500u);
    R.cputimer[1].TIM = 5u;
    {
        const uint32_t before = hal_cycles_now();
        R.cputimer[1].TIM = 0xFFFFFFF0u; /* wrapped */
        assert_int_equal((uint32_t)(hal_cycles_now() - before), 21u);
    }
}

static void test_sci(void **state)
{
    uint16_t b = 0u;
    (void)state;
    assert_int_equal(f28335_sci_brr_for(115200u), 40u); /* 37.5 MHz / (8 * 41) = 114329 */
    assert_int_equal(f28335_sci_brr_for(9600u), 487u);
    assert_int_equal(f28335_sci_brr_for(0u), 0u);
    assert_int_equal(f28335_sci_brr_for(4000000u), 0u); /* unreachable within 3 % */
    assert_true(f28335_sci_init(115200u));
    assert_false(f28335_sci_init(0u));
    assert_int_equal(R.scia.SCICCR, 0x0007u);
    assert_int_equal(R.scia.SCIHBAUD, 0u);
    assert_int_equal(R.scia.SCILBAUD, 40u);
    assert_int_equal(R.scia.SCICTL1, 0x0023u); /* RX, TX, out of reset */
    assert_int_equal(R.scia.SCIFFTX & 0xE000u, 0xE000u);
    assert_int_equal(R.sysctrl.PCLKCR0 & PCLKCR0_SCIAENCLK, PCLKCR0_SCIAENCLK);
    assert_int_equal((R.gpioctrl.GPAMUX2 >> 24) & 0xFu, 0x5u); /* GPIO28, 29 on mux 1 */

    /* receive */
    R.scia.SCIFFRX = 0u;
    assert_false(f28335_sci_read(&b));
    R.scia.SCIFFRX = (uint16_t)(1u << 8);
    R.scia.SCIRXBUF = 0x00A5u;
    assert_true(f28335_sci_read(&b));
    assert_int_equal(b, 0xA5u);
    /* overflow and receive error are counted and recovered */
    R.scia.SCIFFRX = SCI_FFRX_RXFFOVF;
    R.scia.SCIRXST = SCI_RXST_RXERROR;
    assert_false(f28335_sci_read(&b));
    assert_int_equal(f28335_sci_errors(), 2u);
    assert_int_equal(R.scia.SCICTL1 & SCI_CTL1_SWRESET, SCI_CTL1_SWRESET);

    /* transmit: FIFO full refuses */
    R.scia.SCIFFTX = (uint16_t)(0xE000u | (16u << 8));
    assert_false(f28335_sci_write(0x55u));
    R.scia.SCIFFTX = 0xE000u;
    assert_true(f28335_sci_write(0x1FFu));
    assert_int_equal(R.scia.SCITXBUF, 0xFFu);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_pie_vectors_and_enables, setup),
        cmocka_unit_test_setup(test_clock_init, setup),
        cmocka_unit_test_setup(test_flash_and_watchdog, setup),
        cmocka_unit_test_setup(test_cycle_counter, setup),
        cmocka_unit_test_setup(test_sci, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
