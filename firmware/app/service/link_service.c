/* The serial link's background service, see link_service.h. */
#include "link_service.h"

#include "drive_link.h"
#include "hal_cycles.h"
#include "hal_serial.h"

void link_service_init(link_service_t *s, uint32_t gap_cycles)
{
    sxl_decoder_init(&s->rx);
    s->tx_len = 0u;
    s->tx_pos = 0u;
    s->frames_handled = 0u;
    s->gap_cycles = gap_cycles;
    s->last_rx_cycles = hal_cycles_now();
    s->platform = 0;
    s->platform_ctx = 0;
}

/* indirect-call: link_service_step, link_receive -> nothing (the board sets no platform hook;
 * the simulator's virtual board does) */
void link_service_set_platform(link_service_t *s, link_platform_fn fn, void *ctx)
{
    s->platform = fn;
    s->platform_ctx = ctx;
}

bool link_service_sent(const link_service_t *s) { return s->tx_pos >= s->tx_len; }

static void link_send_pending(link_service_t *s)
{
    while (s->tx_pos < s->tx_len && hal_serial_write(s->tx[s->tx_pos])) {
        s->tx_pos++;
    }
}

static void link_receive(link_service_t *s, drive_t *d)
{
    uint16_t byte;
    const uint32_t now = hal_cycles_now();
    if (!sxl_decoder_idle(&s->rx) && (uint32_t)(now - s->last_rx_cycles) > s->gap_cycles) {
        sxl_decoder_abandon(&s->rx); /* stale partial frame: counted, dropped */
    }
    while (s->tx_pos >= s->tx_len && hal_serial_read(&byte)) {
        s->last_rx_cycles = now;
        if (sxl_decoder_push(&s->rx, byte, &s->req) == SXL_RX_FRAME) {
            if (!(s->platform && s->platform(s->platform_ctx, &s->req, &s->reply))) {
                drive_link_handle(d, &s->req, &s->reply, s->rx.errors);
            }
            s->tx_len = sxl_encode(s->reply.cmd, s->reply.payload, s->reply.len, s->tx,
                                   (uint16_t)SXL_MAX_FRAME);
            s->tx_pos = 0u;
            s->frames_handled++;
        }
    }
}

void link_service_step(link_service_t *s, drive_t *d)
{
    link_send_pending(s);
    link_receive(s, d);
    link_send_pending(s);
}
