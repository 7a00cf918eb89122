/*
 * The serial link's byte port (the board's SCI-A, the simulator's virtual UART): one byte
 * (0..255 in a uint16_t, the C28x has no 8-bit type) at a time, never blocking.
 */
#ifndef HAL_SERIAL_H
#define HAL_SERIAL_H

#include <stdbool.h>
#include <stdint.h>

/* The next received byte into *byte; false when none is waiting. */
bool hal_serial_read(uint16_t *byte);

/* Queue one byte for sending; false when the transmitter cannot take it now. */
bool hal_serial_write(uint16_t byte);

#endif /* HAL_SERIAL_H */
