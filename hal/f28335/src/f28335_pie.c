/* PIE: vector table, group enables, acknowledge; CPU interrupt masks. */
#include "f28335_hal.h"

void f28335_pie_init(f28335_isr_t default_isr)
{
    volatile f28335_piectrl_t *pie = F28335_PIECTRL;
    volatile f28335_pievect_t *vect = F28335_PIEVECT;
    uint16_t g;

    F28335_DINT();
    F28335_IER_CLEAR(0xFFFFu);
    F28335_IFR_CLEAR_ALL();
    pie->PIECTRL = 0u; /* vectors fetched from boot ROM while filling the table */
    for (g = 0u; g < 12u; g++) {
        pie->group[g].IER = 0u;
        pie->group[g].IFR = 0u;
    }
    F28335_EALLOW();
    for (g = 0u; g < 128u; g++) {
        vect->vector[g] = default_isr;
    }
    F28335_EDIS();
    pie->PIEACK = 0xFFFFu;
    pie->PIECTRL = PIE_CTRL_ENPIE;
}

void f28335_pie_install(uint16_t group, uint16_t index, f28335_isr_t isr)
{
    if (group < 1u || group > 12u || index < 1u || index > 8u) {
        return;
    }
    F28335_EALLOW();
    F28335_PIEVECT->vector[PIE_VECTOR_INDEX(group, index)] = isr;
    F28335_EDIS();
}

void f28335_pie_enable(uint16_t group, uint16_t index)
{
    if (group < 1u || group > 12u || index < 1u || index > 8u) {
        return;
    }
    F28335_PIECTRL->group[group - 1u].IER |= (uint16_t)(1u << (index - 1u));
    F28335_IER_SET(1u << (group - 1u));
}

void f28335_pie_ack(uint16_t group)
{
    if (group < 1u || group > 12u) {
        return;
    }
    F28335_PIECTRL->PIEACK = PIE_GROUP_ACK(group);
}

void f28335_interrupts_enable_global(void)
{
    F28335_EINT();
    F28335_ERTM();
}

void f28335_interrupts_disable_global(void) { F28335_DINT(); }
