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

#include <stdbool.h>
#include <stdint.h>

#include "capture.h"
#include "commission.h"
#include "ctl.h"
#include "ctl_protect.h"
#include "hal_adc.h"
#include "hal_encoder.h"
#include "drive_faults.h"
#include "drive_states.h"

#define DRIVE_CALIBRATION_SAMPLES 1024
/* Offsets further than this from mid scale mean a broken sensor or front end. */
#define DRIVE_OFFSET_TOLERANCE_COUNTS 200

/* The states and the run refusals, from their lists (drive_states.h). */
#define DRIVE_LIST_ENUM_(id, number, name) id = number,
typedef enum { DRIVE_STATE_LIST(DRIVE_LIST_ENUM_) } drive_state_t;
typedef enum { DRIVE_RUN_REFUSAL_LIST(DRIVE_LIST_ENUM_) } drive_run_refusal_t;
#undef DRIVE_LIST_ENUM_

/* Drive fault codes, from the one fault list (drive_faults.h). */
#define DRIVE_FAULT_ENUM(name, code, bit_name, bit, text) DRIVE_FAULT_##name = code,
typedef enum { DRIVE_FAULT_NONE = 0, DRIVE_FAULT_LIST(DRIVE_FAULT_ENUM) } drive_fault_t;
#undef DRIVE_FAULT_ENUM

#define DRIVE_FAULT_COUNT ((int16_t)DRIVE_FAULT_CODE_COUNT)

/* What the drive does on OPEN_PHASE (drive_open_phase.h); DRIVE_OPEN_PHASE_DEFAULT is the
 * build default, drive_set_open_phase_action changes it at run time. */
typedef enum {
    DRIVE_OPEN_PHASE_STOP = 0,        /* a fault like any other */
    DRIVE_OPEN_PHASE_RIDE_THROUGH = 1 /* isolate the open phase's leg and run on five */
} drive_open_phase_action_t;

#ifndef DRIVE_OPEN_PHASE_DEFAULT
#define DRIVE_OPEN_PHASE_DEFAULT DRIVE_OPEN_PHASE_STOP
#endif

/* What the drive does when the speed loop stays at its torque limit: the speed cannot be held (a
 * load above the limit, or the derated limit after an open phase). Either way the status flag
 * SXL_FLAG_TORQUE_LIMITED says so once at the limit for DRIVE_TORQUE_LIMITED_FLAG_S;
 * DRIVE_TORQUE_LIMITED_DEFAULT is the build default, drive_set_torque_limited_action changes it. */
typedef enum {
    DRIVE_TORQUE_LIMITED_CONTINUE = 0, /* run on at the limit: the load sets the speed */
    DRIVE_TORQUE_LIMITED_STOP = 1      /* at the limit for the set time: stop (RUN -> READY) */
} drive_torque_limited_action_t;

#ifndef DRIVE_TORQUE_LIMITED_DEFAULT
#define DRIVE_TORQUE_LIMITED_DEFAULT DRIVE_TORQUE_LIMITED_CONTINUE
#endif
#define DRIVE_TORQUE_LIMITED_FLAG_S 0.1f /* at the limit this long: flagged */
#define DRIVE_TORQUE_LIMITED_STOP_S 0.5f /* default time before the stop action stops */
#define DRIVE_TORQUE_LIMITED_STOP_MAX_S 60.0f
#define DRIVE_TORQUE_LIMITED_EVERY 16u /* the watch runs in every 16th period */

/* Why a leg is isolated. */
typedef enum {
    DRIVE_ISOLATION_NONE = 0,
    DRIVE_ISOLATION_FAULT = 1,  /* an OPEN_PHASE ridden through */
    DRIVE_ISOLATION_COMMAND = 2 /* an isolate command */
} drive_isolation_cause_t;

typedef struct {
    ctl_t ctl;
    ctl_protect_t protect;
    ctl_protect_input_t protect_in; /* this period's protection inputs (also the record) */
    drive_state_t state;
    drive_fault_t fault; /* first fault since the last clear; protect.latched has them all */
    bool run_requested;
    bool stop_requested;
    bool clear_requested;
    /* ADC calibration */
    int32_t offset_sum[HAL_ADC_PHASES];
    int16_t offset_counts[HAL_ADC_PHASES];
    int16_t calibration_samples;
    /* scaling of the board's ADC, per unit per count (the speed scaling follows the
     * parameter set in force: ctl_config_t) */
    ctl_q current_pu_per_count;
    ctl_q vdc_pu_per_count;
    /* while no valid parameter set was ever in force: the reference machine's */
    ctl_protect_limits_t fallback_limits;
    ctl_q fallback_omega_pu_per_rev_s;
    /* last step */
    hal_adc_sample_t adc;
    hal_encoder_sample_t encoder;
    ctl_meas_t meas;
    ctl_cmd_t cmd;
    uint32_t isr_count;
    /* bookkeeping for the background side (commands, telemetry) */
    bool calibrated;                 /* offsets calibrated successfully at least once */
    uint16_t run_refused;            /* run requests dropped (wrong state, encoder, DC link) */
    drive_run_refusal_t run_refusal; /* reason of the last refused run request */
    uint16_t clear_blocked;          /* ctl_fault_t conditions that refused the last clear */
    ctl_params_t params_bg;          /* last parameter set requested (background copy) */
    float speed_ref_rpm;             /* last speed reference set */
    float torque_ref_nm;             /* last torque reference set */
    /* the link's armed session (SXL_CMD_ARM): the token commands that move the motor must
     * carry, 0 while disarmed; and how many sessions were armed (the next token's seed) */
    uint32_t link_token;
    uint32_t link_sessions;
    /* the set being requested (drive_request_params and the commands that build one): here,
     * not on the stack, where it was the largest object of the background's deepest path */
    ctl_params_t params_req;
    /* ISR timing, filled by the platform's ISR wrapper (0 where unused) */
    uint32_t isr_cycles_last;
    uint32_t isr_cycles_max;
    /* period start to ISR entry, set by the platform before each drive_control_isr call
     * (cycles; 0 where it cannot be measured); goes into the profile (profile.h) */
    uint32_t isr_latency_cycles;
    /* the capture buffer (oscilloscope): recorded by the ISR, armed and read over the link */
    capture_t capture;
    /* open-phase operation (drive_open_phase.h) */
    int16_t open_phase_action;        /* drive_open_phase_action_t (background) */
    int16_t postfault_strategy;       /* ctl_postfault_strategy_t of post-fault sets (background) */
    volatile int16_t isolated_leg;    /* 0..5 (A..F) off for good, -1 none (ISR) */
    volatile int16_t isolation_cause; /* drive_isolation_cause_t (ISR) */
    uint32_t isolation_period;        /* isr_count at the isolation (ISR) */
    volatile int16_t isolate_request; /* leg to isolate by command, -1 none (background -> ISR) */
    volatile bool restore_request;    /* end the isolation (background -> ISR) */
    bool open_phase_paused; /* RUN with the outputs off until the set in force fits the legs */
    /* commissioning (drive_commission.h): the sequence, its results; and the phase check a run
     * must pass after an OPEN_PHASE fault was cleared */
    comm_t comm;
    bool phase_check_pending; /* an OPEN_PHASE fault was cleared: check before RUN controls */
    bool phase_verifying;     /* RUN is running that check */
    /* torque-limited operation (drive_torque_limited_action_t; background only) */
    int16_t torque_limited_action;
    float torque_limited_stop_s; /* at the limit this long: the stop action stops */
    bool at_limit;               /* the speed loop was at its limit at the last pass */
    uint32_t at_limit_since;     /* isr_count when it got there */
    bool torque_limited;         /* at the limit for DRIVE_TORQUE_LIMITED_FLAG_S or more */
    bool torque_limited_stopped; /* the stop action stopped the last run */
} drive_t;

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

/* Background side only: check a new parameter set and build its configuration (controller,
 * protection limits, speed scaling) outside the ISR; the ISR switches to it at the start of
 * its next period, in every state. CTL_PARAM_OK when queued; CTL_PARAM_BUSY while the
 * previous set waits for that period; else the reason, and the set in force stays. */
ctl_param_error_t drive_request_params(drive_t *d, const ctl_params_t *p);

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

/* Force the drive into FAULT with the given code (PWM off, latched). */
void drive_trip(drive_t *d, drive_fault_t fault);

/* The protection limits in force (the reference machine's until a valid set is). */
const ctl_protect_limits_t *drive_protect_limits(const drive_t *d);

/* ISR: one period of normal control in RUN (the control step and the PWM write). */
void drive_run_period(drive_t *d);

/* Per-unit duty to the HAL's unsigned Q15 duty. */
uint16_t drive_duty_to_hal(ctl_q duty);

#endif /* DRIVE_H */
