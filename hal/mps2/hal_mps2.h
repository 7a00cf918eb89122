/* The MPS2 AN386's HAL part of a processor-in-the-loop image (README.md). */
#ifndef HAL_MPS2_H
#define HAL_MPS2_H

#include <stdbool.h>
#include <stdint.h>

#define HAL_MPS2_PCLK_HZ 25000000UL /* the peripheral clock the UART and timers run on */

/* UART0 and timer 0 set up. */
void hal_mps2_init(void);

/* A byte waits in UART0's receiver. */
bool hal_mps2_serial_pending(void);

#endif /* HAL_MPS2_H */
