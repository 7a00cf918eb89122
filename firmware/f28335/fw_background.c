/*
 * Background loop: services the watchdog and the serial link. One request
 * frame is handled at a time; its reply is sent before the next request is
 * read (the SCI FIFO holds the next 16 bytes meanwhile).
 */
#include "drive_link.h"
#include "fw.h"
#include "hal_cycles.h"

static void fw_link_send_pending(void)
{
    while (fw_state.tx_pos < fw_state.tx_len && f28335_sci_write(fw_state.tx[fw_state.tx_pos])) {
        fw_state.tx_pos++;
    }
}

static void fw_link_receive(void)
{
    uint16_t byte;
    const uint32_t now = hal_cycles_now();

    if (!sxl_decoder_idle(&fw_state.rx) &&
        (uint32_t)(now - fw_state.last_rx_cycles) > FW_LINK_GAP_CYCLES) {
        sxl_decoder_reset(&fw_state.rx); /* stale partial frame */
    }
    while (fw_state.tx_pos >= fw_state.tx_len && f28335_sci_read(&byte)) {
        fw_state.last_rx_cycles = now;
        if (sxl_decoder_push(&fw_state.rx, byte, &fw_state.req) == SXL_RX_FRAME) {
            drive_link_handle(&fw_drive, &fw_state.req, &fw_state.reply, fw_state.rx.errors);
            fw_state.tx_len = sxl_encode(fw_state.reply.cmd, fw_state.reply.payload,
                                         fw_state.reply.len, fw_state.tx, (uint16_t)SXL_MAX_FRAME);
            fw_state.tx_pos = 0u;
            fw_state.frames_handled++;
        }
    }
}

void fw_background_step(void)
{
    f28335_watchdog_service();
    fw_link_send_pending();
    fw_link_receive();
    fw_link_send_pending();
}
