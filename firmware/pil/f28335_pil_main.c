/*
 * The processor-in-the-loop image of a TMS320F28335 board (firmware/f28335/CMakeLists.txt with
 * SIXPHASE_FW_PIL=ON, docs/profiling.md): the product's clock, RAM copy and flash set-up, then
 * the PIL service on SCI-A and CPU timer 1 instead of the ADC interrupt. The board needs no
 * inverter, motor or encoder: the period's inputs come in the frames, its PWM is not driven
 * (hal_sim.c stands in for ePWM, ADC and eQEP; the pins stay inputs).
 */
#include "f28335_hal.h"
#include "fw.h"
#include "hal_cycles.h"
#include "pil_target.h"

/* The line's speed: `--pil serial:PORT@921600` on the host (an FTDI-type adapter, docs). */
#define PIL_SCI_BAUD ((uint32_t)921600u)

static pil_target_t pil;

int main(void)
{
    bool ok;
    f28335_interrupts_disable_global();
    f28335_watchdog_disable();
    ok = f28335_clock_init();
    fw_ramfuncs_copy();
    f28335_flash_init();
    hal_cycles_init();
    ok = f28335_sci_init(PIL_SCI_BAUD) && ok;
    if (!ok) {
        for (;;) { /* no clock or no line: nothing to answer (the host times out on HELLO) */
        }
    }
    pil_target_init(&pil, &PIL_TARGET_OPS, PIL_TARGET_ARITH, SXL_PIL_TARGET_F28335);
    for (;;) {
        pil_target_poll(&pil);
    }
}
