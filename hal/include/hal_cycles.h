/*
 * Free-running cycle counter for profiling: counts up, wraps at 2^32.
 * Differences of two readings (unsigned subtraction) are elapsed cycles.
 */
#ifndef HAL_CYCLES_H
#define HAL_CYCLES_H

#include <stdint.h>

void hal_cycles_init(void);
uint32_t hal_cycles_now(void);
uint32_t hal_cycles_per_second(void);

#endif /* HAL_CYCLES_H */
