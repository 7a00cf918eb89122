/*
 * The drive application: the control-period ISR body and the drive state
 * machine, written against the HAL only. The F28335 firmware calls it from
 * the ADC interrupt; the simulator calls it through the simulated HAL, so
 * the simulated loop is the firmware's loop.
 *
 * Protection (ctl_protect) runs in every period that brings a fresh conversion, in
 * every state after INIT, before the control step: a fault forces the PWM off in that
 * same period, before any new command reaches the compare registers, latches a code
 * and appends a record to the fault log, which survives a clear until it is read. A
 * period without a fresh conversion is ADC_MISSING in every state after INIT (the ADC
 * converts with the outputs off too), and such a period never clears a fault.
 *
 * States: INIT -> CALIBRATE (PWM off, ADC offsets averaged) -> READY
 *         READY -> RUN on a run command; RUN -> READY on stop;
 *         READY -> COMMISSION on a commissioning request (drive_commission.h), back to READY
 *         when the sequence ends or on stop, never entered from RUN (it runs with the
 *         protection active, as RUN does);
 *         any -> FAULT (PWM forced off, latched) ; FAULT -> READY on a clear
 *         command when nothing stands against it in that period
 *         (drive_clear_blockers; FAULT -> CALIBRATE if the offsets were never
 *         calibrated successfully).
 * A run request is acted on in READY only: made in any other state it is
 * refused (dropped and counted), never deferred. READY -> RUN also needs a
 * healthy encoder and a DC link above the under-voltage limit: with the link
 * off the drive calibrates and waits in READY, and a run request is refused
 * with that reason (drive_run_check). Likewise a clear request outside FAULT
 * is dropped, so it can never clear a later fault.
 */
#ifndef DRIVE_H
#define DRIVE_H

#include "drive_core.h"

/* Configure the controller; HAL peripherals must be initialised already. */
void drive_init(drive_t *d, const ctl_params_t *p);

/* One control period: sample, state machine, control step, PWM write. */
void drive_control_isr(drive_t *d);

/* What stands against leaving FAULT in this period, as ctl_fault_t bits (0: a clear may go
 * ahead). Judged on the period's own evaluation, never on an older one: a period without a
 * fresh conversion blocks (ADC_MISSING); so does any condition active in this period's check,
 * the trip pin, a parameter or platform fault, and a latched fault of a check that runs only
 * while the motor turns if it can be seen to persist at standstill (encoder unhealthy, DC link
 * below the under-voltage limit, a current channel whose word stopped changing). */
uint16_t drive_clear_blockers(const drive_t *d, bool fresh);

/* Why a run request would be refused now (DRIVE_RUN_ACCEPTED if it would not): READY, a
 * healthy encoder and a DC link at or above the under-voltage limit are needed. */
drive_run_refusal_t drive_run_check(const drive_t *d);

/* Phase-current sensor spans a board may have (full span, A: -span/2 .. +span/2 over the
 * ADC's 0..4095 counts, zero at mid scale; the reference board's is hal_board.h's 40 A). */
#define DRIVE_CURRENT_SPAN_MIN_A 4.0f
#define DRIVE_CURRENT_SPAN_MAX_A 400.0f

/* Background side: the phase-current scaling of a board whose sensors span full_span_a instead
 * of the reference board's. Taken outside RUN only (the ISR reads the scaling every period);
 * false, and nothing changed, in RUN or for a span outside DRIVE_CURRENT_SPAN_MIN_A..MAX_A. */
bool drive_set_current_span(drive_t *d, float full_span_a);

/* Background-side commands, acted on by the next ISR. */
void drive_request_run(drive_t *d);
void drive_request_stop(drive_t *d);
void drive_request_clear_fault(drive_t *d);
void drive_set_speed_ref_rpm(drive_t *d, float rpm);
void drive_set_torque_ref_nm(drive_t *d, float torque_nm);

/* The background loop's share of the drive, called once per pass (the firmware's background
 * loop; the simulator once per control period after the ISR): asks for the parameter set the
 * isolated legs need (drive_open_phase.h) until the ISR has one. */
void drive_background(drive_t *d);

/* Background: what OPEN_PHASE does (drive_open_phase_action_t) and the post-fault strategy
 * (ctl_postfault_strategy_t) for the next post-fault set; false, nothing changed, for an
 * unknown value. */
bool drive_set_open_phase_action(drive_t *d, int16_t action, int16_t strategy);

/* Background: what the drive does when the speed cannot be held (drive_torque_limited_action_t)
 * and, for the stop, after how long at the limit (0 < s <= DRIVE_TORQUE_LIMITED_STOP_MAX_S);
 * false, nothing changed, for a bad value. */
bool drive_set_torque_limited_action(drive_t *d, int16_t action, float stop_s);

/* Background: isolate leg 0..5 by command (tests of open-phase operation on a healthy machine),
 * in READY or RUN with no leg isolated; false if refused. The ISR acts in its next period. */
bool drive_request_isolate_leg(drive_t *d, int16_t leg);

/* Background: end the isolation, in READY only; false if refused (not READY, none isolated). */
bool drive_request_restore_legs(drive_t *d);

/* Oldest unread fault record; false when none. Background side (lock-free with the ISR). */
bool drive_read_fault_record(drive_t *d, ctl_fault_record_t *r);

/* Faults latched since the last clear (ctl_fault_t bits). */
uint16_t drive_faults_latched(const drive_t *d);

/* The drive code for a set of ctl_fault_t bits: the most severe one (hardware trip,
 * over-current and over-voltage first). DRIVE_FAULT_NONE for 0. */
drive_fault_t drive_fault_from_mask(uint16_t faults);

/* The ctl_fault_t bit recorded for a drive code (0 for none). */
uint16_t drive_fault_to_mask(drive_fault_t fault);

/* The platform detected that the control ISR overran its period: fault. */
void drive_report_overrun(drive_t *d);

/* Per-unit duty to the HAL's unsigned Q15 duty. */
uint16_t drive_duty_to_hal(ctl_q duty);

#endif /* DRIVE_H */
