/*
 * The processor-in-the-loop image of an Arm MPS2 AN386 (Cortex-M4F; under QEMU here,
 * firmware/pil/README.md): the PIL service on UART0 and timer 0, the drive through the
 * simulator's bridge of this image's arithmetic.
 */
#include "hal_mps2.h"
#include "pil_target.h"

static pil_target_t pil;

int main(void)
{
    hal_mps2_init();
    pil_target_init(&pil, &PIL_TARGET_OPS, PIL_TARGET_ARITH, SXL_PIL_TARGET_MPS2);
    for (;;) {
        pil_target_poll(&pil);
    }
}
