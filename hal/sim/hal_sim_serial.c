/* Simulator HAL: the serial port (hal_serial.h) as two FIFOs on the bus, and their line side
 * (hal_sim.h). */
#include "hal_serial.h"
#include "hal_sim.h"

/* ---- hal_serial.h and its line side ---- */

bool hal_sim_uart_arrive(uint16_t byte)
{
    hal_sim_bus_t *b = &hal_sim_bus;
    if (b->uart_rx_count >= HAL_SIM_UART_FIFO) {
        b->uart_rx_overruns++;
        return false;
    }
    b->uart_rx[(b->uart_rx_head + b->uart_rx_count) % HAL_SIM_UART_FIFO] = (uint16_t)(byte & 0xFFu);
    b->uart_rx_count++;
    return true;
}

bool hal_serial_read(uint16_t *byte)
{
    hal_sim_bus_t *b = &hal_sim_bus;
    if (b->uart_rx_count == 0u) {
        return false;
    }
    *byte = b->uart_rx[b->uart_rx_head];
    b->uart_rx_head = (uint16_t)((b->uart_rx_head + 1u) % HAL_SIM_UART_FIFO);
    b->uart_rx_count--;
    return true;
}

bool hal_serial_write(uint16_t byte)
{
    hal_sim_bus_t *b = &hal_sim_bus;
    if (b->uart_tx_count >= HAL_SIM_UART_FIFO) {
        return false;
    }
    b->uart_tx[(b->uart_tx_head + b->uart_tx_count) % HAL_SIM_UART_FIFO] = (uint16_t)(byte & 0xFFu);
    b->uart_tx_count++;
    return true;
}

bool hal_sim_uart_depart(uint16_t *byte)
{
    hal_sim_bus_t *b = &hal_sim_bus;
    if (b->uart_tx_count == 0u) {
        return false;
    }
    *byte = b->uart_tx[b->uart_tx_head];
    b->uart_tx_head = (uint16_t)((b->uart_tx_head + 1u) % HAL_SIM_UART_FIFO);
    b->uart_tx_count--;
    return true;
}
