/*
 * The control interrupt: ADC SEQ1 end of sequence (PIE INT1.1), once per PWM
 * period, shortly after counter zero. All control maths is in
 * drive_control_isr (firmware/app) and the control core (control/).
 *
 * Overrun detection: the ISR is late or too long if, when it ends, either
 *   - the next sequence has already completed (SEQ1 flag set again), or
 *   - it took more than FW_ISR_BUDGET_CYCLES.
 * Either is a drive fault (DRIVE_FAULT_OVERRUN): PWM forced off, latched.
 */
#include "fw.h"
#include "hal_cycles.h"
#include "hal_pwm.h"
#include "sixphase_placement.h"

SIXPHASE_RAMFUNC F28335_INTERRUPT void fw_adc_isr(void)
{
    const uint32_t t0 = hal_cycles_now();
    uint32_t dt;

    /* period start (counter zero, ADC start) to here: conversion plus interrupt entry */
    fw_drive.isr_latency_cycles = f28335_pwm_time_base();
    drive_control_isr(&fw_drive);

    dt = (uint32_t)(hal_cycles_now() - t0);
    fw_drive.isr_cycles_last = dt;
    if (dt > fw_drive.isr_cycles_max) {
        fw_drive.isr_cycles_max = dt;
    }
    if (f28335_adc_sequence_pending() || dt > FW_ISR_BUDGET_CYCLES) {
        drive_report_overrun(&fw_drive);
    }
    f28335_adc_isr_ack();
}

F28335_INTERRUPT void fw_unexpected_isr(void)
{
    hal_pwm_force_off();
    fw_state.unexpected_isr++;
#if F28335_TARGET
    for (;;) {
        /* halt here; the watchdog (once enabled) resets the device */
    }
#endif
}
