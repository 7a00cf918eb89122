/*
 * The control period's code and tables copied from flash to RAM (F28335_flash.cmd's ramfuncs and
 * ramconsts), before anything runs them: the product's start-up (fw_startup.c) and the PIL
 * image's (firmware/pil/f28335_pil_main.c) both begin with it.
 */
#include <stdint.h>

#include "fw.h"

#if F28335_TARGET
/* Defined by the linker command file (F28335_flash.cmd). */
extern uint16_t RamfuncsLoadStart;
extern uint16_t RamfuncsLoadEnd;
extern uint16_t RamfuncsRunStart;
extern uint16_t RamconstsLoadStart;
extern uint16_t RamconstsLoadEnd;
extern uint16_t RamconstsRunStart;
#else
/* Host: stand-in sections so the copies run and can be checked. */
uint16_t fw_host_ramfuncs_load[4] = {0x1234u, 0x5678u, 0x9ABCu, 0xDEF0u};
uint16_t fw_host_ramfuncs_run[4];
uint16_t fw_host_ramconsts_load[3] = {0x0BADu, 0xCAFEu, 0xF00Du};
uint16_t fw_host_ramconsts_run[3];
#endif

void fw_copy_words(uint16_t *dst, const uint16_t *src, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        dst[i] = src[i];
    }
}

void fw_ramfuncs_copy(void)
{
#if F28335_TARGET
    fw_copy_words(&RamfuncsRunStart, &RamfuncsLoadStart,
                  (uint32_t)((uintptr_t)&RamfuncsLoadEnd - (uintptr_t)&RamfuncsLoadStart));
    fw_copy_words(&RamconstsRunStart, &RamconstsLoadStart,
                  (uint32_t)((uintptr_t)&RamconstsLoadEnd - (uintptr_t)&RamconstsLoadStart));
#else
    fw_copy_words(fw_host_ramfuncs_run, fw_host_ramfuncs_load, 4u);
    fw_copy_words(fw_host_ramconsts_run, fw_host_ramconsts_load, 3u);
#endif
}
