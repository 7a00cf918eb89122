/* Helpers shared by the F28335 driver files (not part of any public API). */
#ifndef F28335_INTERNAL_H
#define F28335_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#define F28335_GPIO_MUX_GPIO 0u
#define F28335_GPIO_MUX_PERIPH1 1u
#define F28335_GPIO_QSEL_SYNC 0u
#define F28335_GPIO_QSEL_ASYNC 3u

/* Port A (GPIO0..31) only; callers pass constants. EALLOW handled inside. */
void f28335_gpio_set_mux(uint16_t pin, uint16_t func);
void f28335_gpio_set_qsel(uint16_t pin, uint16_t qsel);
void f28335_gpio_set_pullup(uint16_t pin, bool enabled);
bool f28335_gpio_read(uint16_t pin);

#endif
