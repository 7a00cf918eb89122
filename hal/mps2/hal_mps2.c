#include "hal_mps2.h"

#include "hal_cycles.h"
#include "hal_serial.h"

/* CMSDK APB UART (ARM DDI 0479C, section 4.3) and timer (section 4.1) of the AN386 memory map. */
#define UART0_BASE 0x40004000u
#define TIMER0_BASE 0x40000000u
#define REG(base, offset) (*(volatile uint32_t *)((base) + (offset)))
#define UART_DATA REG(UART0_BASE, 0x00u)
#define UART_STATE REG(UART0_BASE, 0x04u)
#define UART_CTRL REG(UART0_BASE, 0x08u)
#define UART_BAUDDIV REG(UART0_BASE, 0x10u)
#define UART_STATE_TX_FULL 0x1u
#define UART_STATE_RX_FULL 0x2u
#define UART_CTRL_TX_RX 0x3u
#define TIMER_CTRL REG(TIMER0_BASE, 0x00u)
#define TIMER_VALUE REG(TIMER0_BASE, 0x04u)
#define TIMER_RELOAD REG(TIMER0_BASE, 0x08u)
#define TIMER_CTRL_ENABLE 0x1u

void hal_mps2_init(void)
{
    UART_BAUDDIV = 16u; /* the smallest divider the UART takes: 1.5625 Mbaud at 25 MHz */
    UART_CTRL = UART_CTRL_TX_RX;
    hal_cycles_init();
}

bool hal_mps2_serial_pending(void) { return (UART_STATE & UART_STATE_RX_FULL) != 0u; }

bool hal_serial_read(uint16_t *byte)
{
    if (!hal_mps2_serial_pending()) {
        return false;
    }
    *byte = (uint16_t)(UART_DATA & 0xFFu);
    return true;
}

bool hal_serial_write(uint16_t byte)
{
    if ((UART_STATE & UART_STATE_TX_FULL) != 0u) {
        return false;
    }
    UART_DATA = (uint32_t)(byte & 0xFFu);
    return true;
}

void hal_cycles_init(void)
{
    TIMER_CTRL = 0u;
    TIMER_RELOAD = 0xFFFFFFFFu;
    TIMER_VALUE = 0xFFFFFFFFu;
    TIMER_CTRL = TIMER_CTRL_ENABLE;
}

/* The timer counts down: its complement counts up, wrapping at 2^32 as hal_cycles.h wants. */
uint32_t hal_cycles_now(void) { return ~TIMER_VALUE; }

uint32_t hal_cycles_per_second(void) { return HAL_MPS2_PCLK_HZ; }
