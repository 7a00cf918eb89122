/*
 * hal_cycles on the F28335: CPU timer 1 as a free-running SYSCLKOUT counter.
 * The timer counts down from PRD = 0xFFFFFFFF with prescale 1, so
 * ~TIM counts up and wraps at 2^32 (28.6 s at 150 MHz). Its interrupt is off.
 */
#include "f28335_hal.h"
#include "hal_cycles.h"
#include "sixphase_placement.h"

static bool cycles_running;

void hal_cycles_init(void)
{
    volatile f28335_sysctrl_t *sys = F28335_SYSCTRL;
    volatile f28335_cputimer_t *t = F28335_CPUTIMER(F28335_CYCLES_TIMER);

    F28335_EALLOW();
    sys->PCLKCR3 |= PCLKCR3_CPUTIMER1ENCLK;
    F28335_EDIS();

    t->TCR = TIMER_TCR_TSS; /* stop */
    t->PRD = 0xFFFFFFFFuL;
    t->TPR = 0u; /* prescale 1 */
    t->TPRH = 0u;
    /* reload, keep running on emulation halt (FREE), no interrupt, start */
    t->TCR = (uint16_t)(TIMER_TCR_TRB | TIMER_TCR_FREE | TIMER_TCR_SOFT);
    cycles_running = true;
}

SIXPHASE_RAMFUNC uint32_t hal_cycles_now(void)
{
    F28335_HOST_TIME_PASSES();
    return ~F28335_CPUTIMER(F28335_CYCLES_TIMER)->TIM;
}

uint32_t hal_cycles_per_second(void) { return F28335_SYSCLK_HZ; }

void f28335_delay_us(uint32_t us)
{
#if F28335_TARGET
    uint32_t start;
    const uint32_t wait = us * (F28335_SYSCLK_HZ / 1000000u);
    if (!cycles_running) {
        hal_cycles_init();
    }
    start = hal_cycles_now();
    while ((uint32_t)(hal_cycles_now() - start) < wait) {
    }
#else
    (void)us; /* host: no time passes in the register frames */
    if (!cycles_running) {
        hal_cycles_init();
    }
#endif
}
