#include "f28335_internal.h"
#include "f28335_regs.h"
#include "sixphase_placement.h"

/* Two-bit field of pin (0..31) in the 16-pin MUX1/MUX2 or QSEL1/QSEL2 pair. */
static uint32_t two_bit_field_mask(uint16_t pin) { return (uint32_t)3u << (2u * (pin & 15u)); }
static uint32_t two_bit_field(uint16_t pin, uint16_t v)
{
    return (uint32_t)(v & 3u) << (2u * (pin & 15u));
}

void f28335_gpio_set_mux(uint16_t pin, uint16_t func)
{
    volatile f28335_gpioctrl_t *g = F28335_GPIOCTRL;
    if (pin > 31u) {
        return;
    }
    F28335_EALLOW();
    if (pin < 16u) {
        g->GPAMUX1 = (g->GPAMUX1 & ~two_bit_field_mask(pin)) | two_bit_field(pin, func);
    } else {
        g->GPAMUX2 = (g->GPAMUX2 & ~two_bit_field_mask(pin)) | two_bit_field(pin, func);
    }
    F28335_EDIS();
}

void f28335_gpio_set_qsel(uint16_t pin, uint16_t qsel)
{
    volatile f28335_gpioctrl_t *g = F28335_GPIOCTRL;
    if (pin > 31u) {
        return;
    }
    F28335_EALLOW();
    if (pin < 16u) {
        g->GPAQSEL1 = (g->GPAQSEL1 & ~two_bit_field_mask(pin)) | two_bit_field(pin, qsel);
    } else {
        g->GPAQSEL2 = (g->GPAQSEL2 & ~two_bit_field_mask(pin)) | two_bit_field(pin, qsel);
    }
    F28335_EDIS();
}

void f28335_gpio_set_pullup(uint16_t pin, bool enabled)
{
    volatile f28335_gpioctrl_t *g = F28335_GPIOCTRL;
    const uint32_t bit = (uint32_t)1u << (pin & 31u);
    if (pin > 31u) {
        return;
    }
    F28335_EALLOW();
    if (enabled) {
        g->GPAPUD &= ~bit; /* GPAPUD: 1 disables the pull-up */
    } else {
        g->GPAPUD |= bit;
    }
    F28335_EDIS();
}

SIXPHASE_RAMFUNC bool f28335_gpio_read(uint16_t pin)
{
    if (pin > 31u) {
        return false;
    }
    return (F28335_GPIODATA->GPADAT & ((uint32_t)1u << pin)) != 0u;
}
