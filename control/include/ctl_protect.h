/*
 * Protection: fault detection with stated thresholds and filters, a latched fault
 * mask, and a log of fault records that survives until read. Pure logic: the drive
 * feeds it each control period and forces the outputs off (PWM trip) in the same
 * period when it reports a fault.
 *
 * Filters count consecutive control periods a condition holds; a condition that
 * clears resets its counter. Several faults in one period are all latched and go
 * into one record (its mask has every bit). A full log keeps the oldest records (the
 * root cause) and counts what it had to drop, except that the first record after a
 * clear (a new root cause) always goes in: it replaces the newest record held.
 *
 * The log is a single-producer single-consumer ring: the control ISR only advances
 * log_write, the background reader only advances log_read (16-bit stores, atomic on
 * C28x), so a record is read while the ISR may append without a critical section. A
 * compiler barrier (ctl_barrier.h) orders each record's fields before the index that
 * publishes or frees it. The ISR replaces the newest record only when the log is full,
 * where the reader, copying the oldest, cannot be on it.
 */
#ifndef CTL_PROTECT_H
#define CTL_PROTECT_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_predict.h"
#include "ctl_q.h"

/* Fault bits (uint16_t: 0x8000 does not fit the 16-bit int of the C28x, so no enum). */
#define CTL_FAULT_OVERCURRENT ((uint16_t)0x0001u)     /* |i_phase| above limit */
#define CTL_FAULT_DC_OVERVOLTAGE ((uint16_t)0x0002u)  /* Vdc above limit */
#define CTL_FAULT_DC_UNDERVOLTAGE ((uint16_t)0x0004u) /* Vdc below limit while running */
#define CTL_FAULT_OVERSPEED ((uint16_t)0x0008u)       /* |speed| above limit */
#define CTL_FAULT_ENCODER ((uint16_t)0x0010u)         /* unhealthy, stopped under torque, or jump */
#define CTL_FAULT_ADC_RAIL ((uint16_t)0x0020u)        /* a conversion at the rail */
#define CTL_FAULT_ADC_STUCK ((uint16_t)0x0040u)       /* a channel frozen while current flows */
#define CTL_FAULT_ADC_OFFSET ((uint16_t)0x0080u)      /* calibration offset out of range */
#define CTL_FAULT_OVERRUN ((uint16_t)0x0100u)     /* control step not finished within the period */
#define CTL_FAULT_CURRENT_SUM ((uint16_t)0x0200u) /* a three-phase set does not sum to zero */
#define CTL_FAULT_OPEN_PHASE ((uint16_t)0x0400u)  /* one phase carries no current, others do */
#define CTL_FAULT_HW_TRIP ((uint16_t)0x0800u)     /* hardware over-current trip zone */
#define CTL_FAULT_PARAMS ((uint16_t)0x1000u)      /* controller parameters unusable */
#define CTL_FAULT_MEASUREMENT ((uint16_t)0x2000u) /* a measurement is not a number (float) */
#define CTL_FAULT_ADC_MISSING ((uint16_t)0x4000u) /* no new conversion in a control period */
#define CTL_FAULT_PLATFORM ((uint16_t)0x8000u)    /* a peripheral failed to initialise */

#define CTL_PROTECT_LOG_SIZE 8
/* A current channel counts as converting if its word changed within this many periods
 * (sensor noise moves a live 12-bit word every few periods even at zero current). */
#define CTL_PROTECT_ALIVE_PERIODS 1000
/* An active state's least duty that makes the stuck-ADC check judge the phases it drives. */
#define CTL_PROTECT_DRIVEN_DUTY CTL_Q(0.1)
/* Shortest open-phase window (periods: 40 ms at 10 kHz); it also spans an electrical turn. */
#define CTL_PROTECT_OPEN_PHASE_WINDOW 400
/* The fast open-phase check's window (periods: 2 ms at 10 kHz), judged on the x-y residual. */
#define CTL_PROTECT_OPEN_PHASE_FAST_WINDOW 20
/* Consecutive fast windows that must find the same phase open. */
#define CTL_PROTECT_OPEN_PHASE_FAST_WINDOWS 3

/* Thresholds and filters as a user sets them, in SI units; part of the parameter set
 * (ctl_params_t), so the per-unit limits below follow every applied set. Defaults in
 * ctl_protect_settings_default, reasons in docs/faults.md. */
typedef struct {
    float overcurrent_a; /* |i_phase| limit */
    int16_t overcurrent_periods;
    float dc_overvoltage_v;
    int16_t dc_overvoltage_periods;
    float dc_undervoltage_v; /* RUN refused below it; a fault below it while running */
    int16_t dc_undervoltage_periods;
    float overspeed_rpm;
    int16_t overspeed_periods;
    float current_sum_a; /* |i_a + i_b + i_c| limit per three-phase set */
    int16_t current_sum_periods;
    int16_t adc_rail_low_counts;  /* a phase-current word at or below: at the rail (the DC
                                   * link's 0 counts is 0 V, a link that is off) */
    int16_t adc_rail_high_counts; /* any word at or above: at the rail */
    int16_t adc_rail_periods;
    int16_t adc_stuck_periods;      /* identical word this long while current flows */
    float stuck_min_current_a;      /* "current flows": largest |i_phase| above this */
    float encoder_torque_nm;        /* |Te| above this accumulates expected motion */
    float encoder_expected_turns;   /* electrical turns expected with no count -> fault */
    float encoder_jump_turns;       /* |angle step - omega Ts| above this -> fault */
    float open_phase_min_current_a; /* mean |i| that makes the windowed check meaningful */
    float open_phase_ratio;         /* a phase below this fraction of the mean is open */
    float open_phase_fast_min_a;    /* fast check: mean |share of the alpha-beta current| a phase
                                     * must be expected to carry over its window to be judged */
    float open_phase_fast_ratio;    /* fast check: a phase carrying less than this fraction of
                                     * its share of the alpha-beta current is open */
} ctl_protect_settings_t;

/* Thresholds and filters in per unit, built from the settings (ctl_protect_limits_build). */
typedef struct {
    ctl_q overcurrent; /* |i| limit */
    int16_t overcurrent_periods;
    ctl_q dc_overvoltage;
    int16_t dc_overvoltage_periods;
    ctl_q dc_undervoltage;
    int16_t dc_undervoltage_periods;
    ctl_q overspeed; /* |omega_e| limit */
    int16_t overspeed_periods;
    ctl_q current_sum; /* |i_a + i_b + i_c| limit per set */
    int16_t current_sum_periods;
    int16_t adc_rail_low; /* raw counts at or below: at the rail */
    int16_t adc_rail_high;
    int16_t adc_rail_periods;
    int16_t adc_stuck_periods;   /* identical raw value this long while current flows */
    ctl_q stuck_min_current;     /* "current flows": largest |i_phase| above this */
    ctl_q encoder_torque;        /* |Te| above this accumulates expected motion */
    ctl_q encoder_expected_turn; /* expected electrical motion (turns) with no counts -> fault */
    ctl_q encoder_jump;          /* |angle step - omega Ts| above this (turns) -> fault */
    ctl_q torque_to_dspeed;      /* Ts * Pn / J in per unit: d omega_e per period per unit torque */
    ctl_q ts_turns;              /* Ts * w_b / (2 pi): angle advance in turns per unit speed */
    ctl_q open_phase_min_mean;   /* mean |i| over phases that makes the check meaningful */
    ctl_q open_phase_ratio;      /* a phase below this fraction of the mean is open */
    ctl_q open_phase_fast_ratio; /* fast check: below this fraction of its share: open */
    ctl_q open_phase_fast_min;   /* fast check: a window's deficit above this is open (ratio
                                  * times the expected current that makes a phase judged) */
    ctl_q open_phase_fast_keep;  /* fast check: a suspect not judged in a window stays one
                                  * while its deficit is above this (-4 x the minimum) */
} ctl_protect_limits_t;

/* One control period's inputs. Raw counts are the ADC's (0..4095), per unit values the
 * drive's scaled measurements. */
typedef struct {
    ctl_q i_phase[6];
    ctl_q vdc;
    ctl_q theta_e;
    ctl_q omega_e;
    ctl_q i_d, i_q;           /* measured, rotor frame (the step's diagnostics) */
    const ctl_model_t *model; /* the machine's in force, for the torque of i_d, i_q when the
                               * encoder check or a record needs it (0: none, no torque) */
    int16_t raw_phase[6];
    int16_t raw_vdc;
    bool encoder_healthy;
    bool overrun;
    bool hw_trip;
    bool running; /* PWM enabled this period (under-voltage, stuck, encoder, open phase need it) */
    bool currents_calibrated; /* offsets measured: before, a set's sum is the offset error, which
                               * the calibration itself judges (ADC_OFFSET) */
    bool xy_held; /* the six-leg control step runs and holds the x-y currents near zero: each
                   * phase carries about its share of the alpha-beta current (the fast check) */
} ctl_protect_input_t;

typedef struct {
    uint16_t faults; /* every fault detected in that period */
    uint32_t period; /* control-period count at detection */
    ctl_q i_phase[6];
    ctl_q vdc;
    ctl_q theta_e;
    ctl_q omega_e;
    ctl_q torque_est; /* from the measured currents, estimated when recorded */
    ctl_q torque_ref;
    int16_t vector; /* command in force */
    ctl_q duty;
} ctl_fault_record_t;

typedef struct {
    uint16_t latched; /* faults since the last successful clear */
    uint16_t active;  /* faults whose condition held in the last period */
    uint32_t period;
    /* filter counters */
    int16_t n_overcurrent;
    int16_t n_overvoltage;
    int16_t n_undervoltage;
    int16_t n_overspeed;
    int16_t n_sum;
    int16_t n_rail;
    int16_t n_stuck[7];
    int16_t last_raw[7];
    int16_t word_age[6];       /* periods since each current channel's word last changed */
    uint32_t stuck_latched_at; /* period count when ADC_STUCK last latched */
    ctl_q expected_speed;      /* electrical speed the torque should have built up without counts */
    ctl_q expected_angle;      /* and the angle (turns) it should have turned through */
    ctl_q last_theta;
    bool have_last;
    ctl_q open_sum[6];     /* sum of |i| / 64 per phase over the window */
    int16_t open_count;    /* periods in the window */
    ctl_q open_turns;      /* electrical turns the window spans */
    ctl_q fast_deficit[6]; /* fast check: sum of ratio * |share of the alpha-beta current| - |i|
                            * per phase over its window */
    int16_t fast_count;    /* periods in the fast window */
    int16_t fast_suspect;  /* the phase with the largest deficit in the last window, -1 none */
    int16_t fast_strikes;  /* consecutive windows it was */
    uint16_t quiet;     /* bit k: phase k carries no current by design (an isolated leg, open-phase
                         * operation): the open-phase check judges the others (ctl_protect_quiet) */
    ctl_q inv_judged;   /* 1 / the number of phases judged */
    int16_t open_phase; /* the phase the last OPEN_PHASE found (0..5), -1 if several were */
    /* log */
    ctl_fault_record_t log[CTL_PROTECT_LOG_SIZE];
    volatile uint16_t log_write;   /* records appended (ISR side), modulo 2^16 */
    volatile uint16_t log_read;    /* records read (background side), modulo 2^16 */
    volatile uint16_t log_dropped; /* saturates at 65535 */
    bool episode_recorded;         /* the first fault since the last clear has a record */
} ctl_protect_t;

/* Settings of the reference drive: 15 A, 720 V / 350 V, 2000 r/min, ... */
void ctl_protect_settings_default(ctl_protect_settings_t *s);
/* True when every setting is a normal number in its range (thresholds up to 1e6 in SI, which
 * saturates the per-unit limit: "out of reach"). */
bool ctl_protect_settings_valid(const ctl_protect_settings_t *s);
/* Per-unit limits of valid settings for one sample time, pole-pair count and inertia. */
void ctl_protect_limits_build(ctl_protect_limits_t *l, const ctl_protect_settings_t *s,
                              float sample_time_s, int16_t pole_pairs, float inertia_kg_m2);

void ctl_protect_init(ctl_protect_t *p);

/* Run the detection for one period against the limits in force; returns the faults detected
 * in this period (0: none). On a non-zero return the caller must force the outputs off in
 * this same period. torque_ref, vector and duty only go into the record. */
uint16_t ctl_protect_check(ctl_protect_t *p, const ctl_protect_limits_t *l,
                           const ctl_protect_input_t *in, ctl_q torque_ref, int16_t vector,
                           ctl_q duty);

/* The phases in quiet (bit k: phase k, A = bit 0) carry no current by design, as with an isolated
 * leg: from now on the open-phase check judges the other phases only (0: all six, the default).
 * The window in progress starts again when the set changes. */
void ctl_protect_quiet(ctl_protect_t *p, uint16_t quiet);

/* The phase (0..5) the last OPEN_PHASE detection found below the others, or -1 when more than
 * one was (then no phase can be named and the drive cannot ride through). */
int16_t ctl_protect_open_phase(const ctl_protect_t *p);

/* The caller handled these faults without stopping (open-phase ride-through): they are no longer
 * latched, their record stays in the log, and a new occurrence is a new root cause with a record
 * of its own. */
void ctl_protect_accept(ctl_protect_t *p, uint16_t faults);

/* Latch a fault found outside the periodic check (calibration, parameters). */
void ctl_protect_raise(ctl_protect_t *p, uint16_t faults, const ctl_protect_input_t *in);

/* Clear the latch if no fault condition is active; true on success. The log is kept. */
bool ctl_protect_clear(ctl_protect_t *p);

/* Every current channel's word changed since ADC_STUCK last latched, and within
 * CTL_PROTECT_ALIVE_PERIODS: the converter runs. Judged in every state (the ADC converts with
 * the outputs off), so a latched ADC_STUCK can be re-verified at standstill before a clear;
 * a clear keeps the channels' history, so a frozen word never passes as a fresh one. */
bool ctl_protect_converter_alive(const ctl_protect_t *p);

/* Oldest unread record; false when the log is empty. Background side. */
bool ctl_protect_read_record(ctl_protect_t *p, ctl_fault_record_t *r);

/* Records waiting to be read. */
uint16_t ctl_protect_log_pending(const ctl_protect_t *p);

#endif /* CTL_PROTECT_H */
