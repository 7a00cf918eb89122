/*
 * The drive's state (drive_t, its states, faults and actions) and the services of drive.c its
 * parts call: the commissioning (drive_commission.h) runs the control period and trips when a
 * phase check fails, takes the protection limits and requests the identified parameter set.
 * drive.h, the drive's whole interface, includes this one; the parts' headers include only this
 * one, so drive.c may include theirs.
 */
#ifndef DRIVE_CORE_H
#define DRIVE_CORE_H

#include <stdbool.h>
#include <stdint.h>

#include "capture/capture.h"
#include "commission/commission.h"
#include "ctl.h"
#include "ctl_protect.h"
#include "hal_adc.h"
#include "hal_encoder.h"
#include "lists/drive_faults.h"
#include "lists/drive_states.h"

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

/* Background side only: check a new parameter set and build its configuration (controller,
 * protection limits, speed scaling) outside the ISR; the ISR switches to it at the start of
 * its next period, in every state. CTL_PARAM_OK when queued; CTL_PARAM_BUSY while the
 * previous set waits for that period; else the reason, and the set in force stays. */
ctl_param_error_t drive_request_params(drive_t *d, const ctl_params_t *p);

/* Force the drive into FAULT with the given code (PWM off, latched). */
void drive_trip(drive_t *d, drive_fault_t fault);

/* The protection limits in force (the reference machine's until a valid set is). */
const ctl_protect_limits_t *drive_protect_limits(const drive_t *d);

/* ISR: one period of normal control in RUN (the control step and the PWM write). */
void drive_run_period(drive_t *d);

#endif /* DRIVE_CORE_H */
