/*
 * Host build only: the register frames as RAM, so the drivers run on a PC and
 * tests can inspect and preset every register.
 */
#include "f28335_regs.h"

#if defined(F28335_HOST_REGS)

#include <string.h>

volatile f28335_host_regs_t f28335_host_regs;
f28335_host_core_t f28335_host_core;
uint32_t f28335_host_cycles_per_read;

#define HOST_SCI_QUEUE 512u
static uint16_t host_rx[HOST_SCI_QUEUE];
static uint16_t host_rx_head;
static uint16_t host_rx_count;
static uint16_t host_tx[HOST_SCI_QUEUE];
static uint16_t host_tx_count;

static void host_sci_update_rx(void)
{
    const uint16_t st = (host_rx_count > 16u) ? 16u : host_rx_count;
    f28335_host_regs.scia.SCIFFRX =
        (uint16_t)((f28335_host_regs.scia.SCIFFRX & (uint16_t)~SCI_FF_ST_MASK) |
                   (uint16_t)(st << SCI_FF_ST_SHIFT));
    if (host_rx_count > 0u) {
        f28335_host_regs.scia.SCIRXBUF = host_rx[host_rx_head];
    }
}

void f28335_host_regs_reset(void)
{
    memset((void *)(uintptr_t)&f28335_host_regs, 0, sizeof(f28335_host_regs));
    memset(&f28335_host_core, 0, sizeof(f28335_host_core));
    f28335_host_core.intm = 1u;
    f28335_host_cycles_per_read = 0u;
    host_rx_head = 0u;
    host_rx_count = 0u;
    host_tx_count = 0u;
}

void f28335_host_sci_rx_inject(const uint16_t *bytes, uint16_t n)
{
    uint16_t i;
    for (i = 0u; i < n && host_rx_count < HOST_SCI_QUEUE; i++) {
        host_rx[(uint16_t)((host_rx_head + host_rx_count) % HOST_SCI_QUEUE)] = bytes[i];
        host_rx_count++;
    }
    host_sci_update_rx();
}

void f28335_host_sci_rx_popped(void)
{
    if (host_rx_count > 0u) {
        host_rx_head = (uint16_t)((host_rx_head + 1u) % HOST_SCI_QUEUE);
        host_rx_count--;
        host_sci_update_rx();
    } else {
        /* a test preset RXFFST by hand: one byte consumed */
        const uint16_t st =
            (uint16_t)((f28335_host_regs.scia.SCIFFRX & SCI_FF_ST_MASK) >> SCI_FF_ST_SHIFT);
        if (st > 0u) {
            f28335_host_regs.scia.SCIFFRX =
                (uint16_t)((f28335_host_regs.scia.SCIFFRX & (uint16_t)~SCI_FF_ST_MASK) |
                           (uint16_t)((st - 1u) << SCI_FF_ST_SHIFT));
        }
    }
}

void f28335_host_sci_tx_pushed(void)
{
    if (host_tx_count < HOST_SCI_QUEUE) {
        host_tx[host_tx_count] = f28335_host_regs.scia.SCITXBUF;
        host_tx_count++;
    }
}

uint16_t f28335_host_sci_tx_take(uint16_t *out, uint16_t cap)
{
    uint16_t i;
    const uint16_t n = (host_tx_count < cap) ? host_tx_count : cap;
    for (i = 0u; i < n; i++) {
        out[i] = host_tx[i];
    }
    host_tx_count = 0u;
    return n;
}

#endif
