/*
 * Fault injection for `sixphase-sim run --scenario fault-<name>`: the drive runs the
 * steady scenario (1500 r/min, rated load) and at the injection time one thing goes
 * wrong in the plant, the inverter, a sensor or the platform. The firmware is not told:
 * it has to find the fault through its own protection, exactly as on the bench.
 *
 * Each injection acts where the real fault would: a DC-link surge changes the DC link
 * the inverter switches and the ADC measures; a cut encoder cable freezes the position
 * the encoder interface sees (the speed estimate then decays by itself); a dead phase
 * connection is a series resistance in the plant. Only the overrun is injected at the
 * platform level (a longer ISR), because the simulator does not model execution time.
 */
#ifndef SIM_FAULT_INJECT_H
#define SIM_FAULT_INJECT_H

#include <stdbool.h>
#include <stdint.h>

#include "hal_adc.h"
#include "hal_encoder.h"
#include "plant.h"

typedef enum {
    SIM_FAULT_NONE = 0,
    SIM_FAULT_OVERCURRENT,
    SIM_FAULT_DC_OVERVOLTAGE,
    SIM_FAULT_DC_UNDERVOLTAGE,
    SIM_FAULT_OVERSPEED,
    SIM_FAULT_ENCODER_LOSS,
    SIM_FAULT_ENCODER_JUMP,
    SIM_FAULT_ENCODER_INDEX,
    SIM_FAULT_ADC_RAIL,
    SIM_FAULT_ADC_STUCK,
    SIM_FAULT_ADC_OFFSET,
    SIM_FAULT_CURRENT_SUM,
    SIM_FAULT_OPEN_PHASE,
    SIM_FAULT_OVERRUN,
    SIM_FAULT_COUNT
} sim_fault_t;

typedef struct {
    const char *name;       /* the scenario is "fault-<name>" */
    const char *injection;  /* what the simulator does, one line */
    int expected_fault;     /* drive_fault_t the firmware must report */
    double detect_bound_ms; /* injection to detection, asserted by tests/sim/test_sim_faults.c */
} sim_fault_info_t;

/* Default injection time on the scenario clock, and the run length of a fault scenario. */
#define SIM_FAULT_INJECT_S 0.25
#define SIM_FAULT_DURATION_S 0.40

/* NULL for SIM_FAULT_NONE or out of range. */
const sim_fault_info_t *sim_fault_info(sim_fault_t f);

/* "fault-overcurrent" -> SIM_FAULT_OVERCURRENT; SIM_FAULT_NONE if the name is not a fault
 * scenario. */
sim_fault_t sim_fault_from_scenario(const char *scenario);

/* Faults present from power-up (found by the offset calibration, not mid-run). */
bool sim_fault_at_power_up(sim_fault_t f);

typedef struct {
    sim_fault_t kind;
    double t_inject; /* s, scenario clock */
    bool active;
    int open_phase;   /* SIM_FAULT_OPEN_PHASE: the phase that opens (default 2, C) */
    bool open_exact;  /* the connection opens for good (plant_params_t.phase_open) instead of
                       * the 2 kohm series resistance (with its small RK4 step) */
    int second_phase; /* a second phase that opens later, -1: none */
    double t_second;  /* s, scenario clock */
    bool second_active;
    /* state the injections keep */
    hal_adc_sample_t frozen_adc;
    bool adc_frozen;
    double frozen_theta_m;
    bool encoder_frozen;
    bool encoder_rehomed; /* the drive re-homed after the slip: the index reset the count */
} sim_fault_state_t;

void sim_fault_begin(sim_fault_state_t *s, sim_fault_t kind, double t_inject);

/* SIM_FAULT_OPEN_PHASE: which phase opens (0..5), and a second one (-1: none) at t_second;
 * exact: as an open circuit rather than 2 kohm. */
void sim_fault_open_phases(sim_fault_state_t *s, int phase, int second_phase, double t_second,
                           bool exact);

/* Activate at the injection time (or at once for power-up faults); true in the period the
 * fault (or a second open phase) becomes active. */
bool sim_fault_update(sim_fault_state_t *s, double t);

/* The plant as the fault leaves it: DC link, phase connections, integration step (constant
 * once active: call when sim_fault_update reports the activation), with the legs the drive
 * isolated (bit k: leg k) switched off. An isolated leg whose connection the fault broke is an
 * open phase (plant_params_t.phase_open; the 2 kohm then carry nothing); the others float on
 * their diodes (inverter_set_floating): returned, bit k for leg k, and the plant is integrated
 * with RK4 for them. */
uint16_t sim_fault_plant(const sim_fault_state_t *s, const plant_params_t *healthy,
                         uint16_t isolated, plant_params_t *p);

/* Load torque on the shaft (N*m) with the fault. */
double sim_fault_load(const sim_fault_state_t *s, double load_nm);

/* Conversion results as the ADC delivers them. */
void sim_fault_adc(sim_fault_state_t *s, hal_adc_sample_t *a);

/* Mechanical angle the encoder interface sees (rad). */
double sim_fault_encoder_angle(sim_fault_state_t *s, double theta_m);

/* The encoder interface's reading after the fault. */
void sim_fault_encoder(const sim_fault_state_t *s, hal_encoder_sample_t *e);

/* The index passed while the drive waited for it (hal_encoder_rehome after a clear): the count
 * starts again from the index, so a slipped reading is right from now on. */
void sim_fault_encoder_rehomed(sim_fault_state_t *s);

/* Leg duties the inverter actually applies (a gate fault overrides a leg). */
void sim_fault_duty(const sim_fault_state_t *s, bool forced_off, double duty[6]);

/* True when the control ISR of this period ran past its budget. */
bool sim_fault_overrun(const sim_fault_state_t *s);

#endif /* SIM_FAULT_INJECT_H */
