/*
 * SCI-A byte driver for the serial link: 8N1, 16-deep FIFOs, polled from the
 * background loop (no interrupts). SCIRXDA = GPIO28, SCITXDA = GPIO29.
 * Bytes travel as uint16_t holding 0..255 (a char is 16 bits on the C28x).
 */
#include "f28335_hal.h"
#include "f28335_internal.h"
#include "hal_serial.h"

#define SCI_RXBUF_FE 0x8000u /* SCIFFFE: framing error of this FIFO entry */
#define SCI_RXBUF_PE 0x4000u /* SCIFFPE: parity error of this FIFO entry */

static uint16_t sci_error_count;

uint16_t f28335_sci_brr_for(uint32_t baud)
{
    uint32_t div;
    uint32_t actual;
    uint32_t err;
    if (baud == 0u || baud > F28335_LSPCLK_HZ / 8u) {
        return 0u;
    }
    div = (F28335_LSPCLK_HZ + 4u * baud) / (8u * baud); /* BRR + 1, rounded */
    if (div < 2u || div > 65536u) {
        return 0u;
    }
    actual = F28335_LSPCLK_HZ / (8u * div);
    err = (actual > baud) ? actual - baud : baud - actual;
    if (err * 100u > baud * 3u) {
        return 0u;
    }
    return (uint16_t)(div - 1u);
}

bool f28335_sci_init(uint32_t baud)
{
    volatile f28335_sci_t *s = F28335_SCIA;
    const uint16_t brr = f28335_sci_brr_for(baud);
    if (brr == 0u) {
        return false;
    }
    sci_error_count = 0u;

    F28335_EALLOW();
    F28335_SYSCTRL->PCLKCR0 |= PCLKCR0_SCIAENCLK;
    F28335_EDIS();
    f28335_gpio_set_pullup(F28335_SCI_RX_GPIO, true);
    f28335_gpio_set_pullup(F28335_SCI_TX_GPIO, true);
    f28335_gpio_set_qsel(F28335_SCI_RX_GPIO, F28335_GPIO_QSEL_ASYNC);
    f28335_gpio_set_mux(F28335_SCI_RX_GPIO, F28335_GPIO_MUX_PERIPH1);
    f28335_gpio_set_mux(F28335_SCI_TX_GPIO, F28335_GPIO_MUX_PERIPH1);

    s->SCIFFTX = (uint16_t)(SCI_FFTX_SCIRST | SCI_FFTX_SCIFFENA | SCI_FFTX_TXFIFORESET |
                            SCI_FFTX_TXFFINTCLR);
    s->SCIFFRX = (uint16_t)(SCI_FFRX_RXFFOVRCLR | SCI_FFRX_RXFIFORESET | SCI_FFRX_RXFFINTCLR);
    s->SCIFFCT = 0u;
    s->SCICCR = SCI_CCR_8N1;
    s->SCICTL1 = (uint16_t)(SCI_CTL1_RXENA | SCI_CTL1_TXENA); /* held in reset */
    s->SCICTL2 = 0u;
    s->SCIHBAUD = (uint16_t)(brr >> 8);
    s->SCILBAUD = (uint16_t)(brr & 0xFFu);
    s->SCIPRI = SCI_PRI_FREE;
    s->SCICTL1 = (uint16_t)(SCI_CTL1_RXENA | SCI_CTL1_TXENA | SCI_CTL1_SWRESET);
    return true;
}

bool f28335_sci_read(uint16_t *byte)
{
    volatile f28335_sci_t *s = F28335_SCIA;
    if ((s->SCIFFRX & SCI_FFRX_RXFFOVF) != 0u) {
        sci_error_count++;
        s->SCIFFRX = (uint16_t)(s->SCIFFRX | SCI_FFRX_RXFFOVRCLR);
    }
    if ((s->SCIRXST & SCI_RXST_RXERROR) != 0u) {
        /* A break or framing error stops the receiver until a software reset. */
        sci_error_count++;
        s->SCICTL1 = (uint16_t)(SCI_CTL1_RXENA | SCI_CTL1_TXENA);
        s->SCICTL1 = (uint16_t)(SCI_CTL1_RXENA | SCI_CTL1_TXENA | SCI_CTL1_SWRESET);
    }
    while ((s->SCIFFRX & SCI_FF_ST_MASK) != 0u) {
        const uint16_t raw = s->SCIRXBUF;
        F28335_SCI_RX_POPPED();
        if ((raw & (SCI_RXBUF_FE | SCI_RXBUF_PE)) != 0u) {
            sci_error_count++;
            continue;
        }
        *byte = (uint16_t)(raw & 0xFFu);
        return true;
    }
    return false;
}

bool f28335_sci_write(uint16_t byte)
{
    volatile f28335_sci_t *s = F28335_SCIA;
    if (((s->SCIFFTX & SCI_FF_ST_MASK) >> SCI_FF_ST_SHIFT) >= SCI_FIFO_DEPTH) {
        return false;
    }
    s->SCITXBUF = (uint16_t)(byte & 0xFFu);
    F28335_SCI_TX_PUSHED();
    return true;
}

uint16_t f28335_sci_errors(void) { return sci_error_count; }

/* hal_serial.h on the board: SCI-A. */
bool hal_serial_read(uint16_t *byte) { return f28335_sci_read(byte); }
bool hal_serial_write(uint16_t byte) { return f28335_sci_write(byte); }
