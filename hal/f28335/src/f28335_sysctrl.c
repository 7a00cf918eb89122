/*
 * Clocks, flash wait states and the watchdog.
 *
 * Watchdog policy: disabled by the code-start stub before the C start-up
 * (large .ebss initialisation could outlast it) and during init; enabled
 * (reset mode, slowest prescaler, about 280 ms) just before the background
 * loop, which services it every pass. A background loop starved by an
 * overrunning ISR or stuck therefore resets the device; after reset the PWM
 * pins are inputs and the gate drivers' pull-downs keep the switches off.
 */
#include "f28335_hal.h"
#include "sixphase_placement.h"

#define PLL_DIV_X10 10u
#define HISPCP_DIV6 3u /* HSPCLK = 150 / 6 = 25 MHz */
#define LOSPCP_DIV4 2u /* LSPCLK = 150 / 4 = 37.5 MHz */
#define FLASH_PAGEWAIT 5u
#define FLASH_RANDWAIT 5u
#define FLASH_OTPWAIT 8u
#define FLASH_STDBYWAIT 0x01FFu
#define FLASH_ACTIVEWAIT 0x01FFu

void f28335_watchdog_disable(void)
{
    F28335_EALLOW();
    F28335_SYSCTRL->WDCR = WDCR_DISABLE;
    F28335_EDIS();
}

void f28335_watchdog_enable(void)
{
    volatile f28335_sysctrl_t *sys = F28335_SYSCTRL;
    F28335_EALLOW();
    sys->SCSR = 0x0000u; /* WDENINT = 0: watchdog resets the device */
    sys->WDKEY = WDKEY_1;
    sys->WDKEY = WDKEY_2;
    sys->WDCR = WDCR_ENABLE_DIV64;
    F28335_EDIS();
}

void f28335_watchdog_service(void)
{
    volatile f28335_sysctrl_t *sys = F28335_SYSCTRL;
    F28335_EALLOW();
    sys->WDKEY = WDKEY_1;
    sys->WDKEY = WDKEY_2;
    F28335_EDIS();
}

bool f28335_clock_init(void)
{
    volatile f28335_sysctrl_t *sys = F28335_SYSCTRL;
    bool ok = true;

    if ((sys->PLLSTS & PLLSTS_MCLKSTS) != 0u) {
        /* Missing oscillator: limp mode. Leave the PLL alone. */
        ok = false;
    } else if ((sys->PLLCR & PLLCR_DIV_MASK) != PLL_DIV_X10) {
        F28335_EALLOW();
        /* DIVSEL must be 0 before PLLCR changes; no missing-clock detection meanwhile. */
        sys->PLLSTS &= (uint16_t)~PLLSTS_DIVSEL_MASK;
        sys->PLLSTS |= PLLSTS_MCLKOFF;
        sys->PLLCR = PLL_DIV_X10;
        F28335_EDIS();
#if F28335_TARGET
        while ((sys->PLLSTS & PLLSTS_PLLLOCKS) == 0u) {
            /* lock takes about 131072 OSCCLK cycles; the watchdog is off */
        }
#endif
        F28335_EALLOW();
        sys->PLLSTS &= (uint16_t)~PLLSTS_MCLKOFF;
        F28335_EDIS();
    }
    if (ok) {
        F28335_EALLOW();
        sys->PLLSTS =
            (uint16_t)((sys->PLLSTS & (uint16_t)~PLLSTS_DIVSEL_MASK) | PLLSTS_DIVSEL_DIV2);
        F28335_EDIS();
    }

    F28335_EALLOW();
    sys->HISPCP = HISPCP_DIV6;
    sys->LOSPCP = LOSPCP_DIV4;
    sys->PCLKCR0 = (uint16_t)(PCLKCR0_ADCENCLK | PCLKCR0_SCIAENCLK); /* TBCLKSYNC stays 0 */
    sys->PCLKCR1 = (uint16_t)(PCLKCR1_EPWM_ALL | PCLKCR1_EQEP1ENCLK);
    sys->PCLKCR3 = (uint16_t)(PCLKCR3_CPUTIMER0ENCLK | PCLKCR3_CPUTIMER1ENCLK |
                              PCLKCR3_CPUTIMER2ENCLK | PCLKCR3_GPIOINENCLK);
    F28335_EDIS();
    return ok;
}

/* Must run from RAM: the flash cannot be read while its wait states change. */
SIXPHASE_RAMFUNC void f28335_flash_init(void)
{
    volatile f28335_flash_t *f = F28335_FLASH;
    F28335_EALLOW();
    f->FOPT = FOPT_ENPIPE;
    f->FBANKWAIT = (uint16_t)((FLASH_PAGEWAIT << FBANKWAIT_PAGEWAIT_SHIFT) | FLASH_RANDWAIT);
    f->FOTPWAIT = FLASH_OTPWAIT;
    f->FSTDBYWAIT = FLASH_STDBYWAIT;
    f->FACTIVEWAIT = FLASH_ACTIVEWAIT;
    F28335_EDIS();
    F28335_FLUSH_PIPELINE();
}
