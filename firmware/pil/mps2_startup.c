/*
 * Start-up of the MPS2 AN386 PIL image (Cortex-M4F): the vector table, .data copied and .bss
 * zeroed (symbols of mps2_an386.ld), the FPU enabled, then main. Faults stop in a loop the
 * host sees as a target that no longer answers.
 */
#include <stdint.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
int main(void);
void mps2_reset(void);

static void mps2_fault(void)
{
    for (;;) {
    }
}

#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u)

void mps2_reset(void)
{
    uint32_t *src = &_sidata;
    uint32_t *dst;
    for (dst = &_sdata; dst < &_edata;) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss;) {
        *dst++ = 0u;
    }
    SCB_CPACR |= (0xFu << 20); /* CP10, CP11: the FPU, full access */
    __asm__ volatile("dsb\n\tisb");
    (void)main();
    mps2_fault();
}

/* Initial stack, reset, then every exception to the fault loop. */
__attribute__((section(".vectors"), used)) static void (*const mps2_vectors[16])(void) = {
    (void (*)(void))(uintptr_t)&_estack,
    mps2_reset,
    mps2_fault,
    mps2_fault,
    mps2_fault,
    mps2_fault,
    mps2_fault,
    0,
    0,
    0,
    0,
    mps2_fault,
    mps2_fault,
    0,
    mps2_fault,
    mps2_fault};
