/*
 * Background loop: services the watchdog and the serial link (firmware/app/link_service.c,
 * the same service the virtual board runs).
 */
#include "fw.h"

void fw_background_step(void)
{
    f28335_watchdog_service();
    link_service_step(&fw_state.link, &fw_drive);
}
