/*
 * Background loop: services the watchdog, the serial link (firmware/app/service/link_service.c,
 * the same service the virtual board runs) and the drive's background share (drive_background).
 */
#include "fw.h"

void fw_background_step(void)
{
    f28335_watchdog_service();
    link_service_step(&fw_state.link, &fw_drive);
    drive_background(&fw_drive); /* the post-fault set after an isolated leg */
}
