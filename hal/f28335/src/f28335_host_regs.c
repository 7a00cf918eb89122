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

/* The EALLOW-protected registers, copied out of the frames. */
typedef struct {
    f28335_sysctrl_t sysctrl;
    f28335_flash_t flash;
    f28335_gpioctrl_t gpioctrl;
    f28335_pievect_t pievect;
    uint16_t epwm_tz[F28335_EPWM_COUNT][6]; /* TZSEL, TZCTL, TZEINT, TZCLR, TZFRC, HRCNFG */
} host_protected_t;

static host_protected_t host_protected_snapshot;
static uint32_t host_eallow_violations;

static void host_protected_copy(host_protected_t *p)
{
    int16_t i;
    memset(p, 0, sizeof *p);
    memcpy(&p->sysctrl, (const void *)(uintptr_t)&f28335_host_regs.sysctrl, sizeof p->sysctrl);
    memcpy(&p->flash, (const void *)(uintptr_t)&f28335_host_regs.flash, sizeof p->flash);
    memcpy(&p->gpioctrl, (const void *)(uintptr_t)&f28335_host_regs.gpioctrl, sizeof p->gpioctrl);
    memcpy(&p->pievect, (const void *)(uintptr_t)&f28335_host_regs.pievect, sizeof p->pievect);
    for (i = 0; i < F28335_EPWM_COUNT; i++) {
        const volatile f28335_epwm_t *e = &f28335_host_regs.epwm[i];
        p->epwm_tz[i][0] = e->TZSEL;
        p->epwm_tz[i][1] = e->TZCTL;
        p->epwm_tz[i][2] = e->TZEINT;
        p->epwm_tz[i][3] = e->TZCLR;
        p->epwm_tz[i][4] = e->TZFRC;
        p->epwm_tz[i][5] = e->HRCNFG;
    }
}

/* Protected registers changed since the last snapshot: counted, the snapshot moves on. */
static void host_protected_compare(void)
{
    host_protected_t now;
    host_protected_copy(&now);
    if (memcmp(&now, &host_protected_snapshot, sizeof now) != 0) {
        host_eallow_violations++;
    }
    host_protected_snapshot = now;
}

void f28335_host_eallow(void)
{
    if (f28335_host_core.eallow == 0u) {
        host_protected_compare();
    }
    f28335_host_core.eallow = 1u;
    f28335_host_core.eallow_count++;
}

void f28335_host_edis(void)
{
    f28335_host_core.eallow = 0u;
    host_protected_copy(&host_protected_snapshot);
}

void f28335_host_eallow_watch_start(void)
{
    host_protected_copy(&host_protected_snapshot);
    host_eallow_violations = 0u;
}

uint32_t f28335_host_eallow_violations(void)
{
    if (f28335_host_core.eallow == 0u) {
        host_protected_compare();
    }
    return host_eallow_violations;
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
    f28335_host_eallow_watch_start();
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
