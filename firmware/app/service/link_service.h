/*
 * The serial link as the background loop serves it: bytes from the serial port through the
 * frame decoder, one request handled at a time (drive_link), its reply sent before the next
 * request is read (the port's receive FIFO holds the next bytes meanwhile), and a partial
 * frame older than the gap dropped. Portable: the board's background loop and the virtual
 * board (the simulator) run the same code over their hal_serial.
 */
#ifndef LINK_SERVICE_H
#define LINK_SERVICE_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "sxlink.h"

/* A platform's own commands, answered before the drive's: true when it filled reply. The board
 * has none (the drive answers every command, an unknown one with SXL_ERR_UNKNOWN); the
 * virtual board answers SXL_CMD_SIM_SHUTDOWN (host_sim). */
typedef bool (*link_platform_fn)(void *ctx, const sxl_frame_t *req, sxl_frame_t *reply);

typedef struct {
    sxl_decoder_t rx;
    sxl_frame_t req;
    sxl_frame_t reply;
    uint16_t tx[SXL_MAX_FRAME];
    uint16_t tx_len;
    uint16_t tx_pos;
    uint32_t last_rx_cycles;
    uint32_t gap_cycles; /* a partial frame older than this is dropped */
    uint32_t frames_handled;
    link_platform_fn platform; /* NULL: none */
    void *platform_ctx;
} link_service_t;

/* gap_cycles: hal_cycles_now() counts after which a partial frame is stale (20 ms). No
 * platform commands. */
void link_service_init(link_service_t *s, uint32_t gap_cycles);

/* Platform commands from now on (fn NULL: none). */
void link_service_set_platform(link_service_t *s, link_platform_fn fn, void *ctx);

/* True when no reply is waiting for room in the serial port. */
bool link_service_sent(const link_service_t *s);

/* One pass: send what is pending, receive and handle at most what the port holds, send. */
void link_service_step(link_service_t *s, drive_t *d);

#endif /* LINK_SERVICE_H */
