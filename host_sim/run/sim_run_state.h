/*
 * Everything one simulation run owns, shared by the files that make up sim_run(): set-up and
 * calibration (sim_setup.c), the period loop (sim_loop.c), the results (sim_result.c), the
 * commissioning and open-phase parts (sim_commission.c, sim_open_phase.c).
 * Internal to host_sim.
 */
#ifndef SIM_RUN_STATE_H
#define SIM_RUN_STATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bridge/sim_ctl.h"
#include "plant/fault_inject.h"
#include "plant/inverter.h"
#include "plant/plant.h"
#include "plant/sim_adc.h"
#include "plant/sim_encoder.h"
#include "record/metrics.h"
#include "record/recorder.h"
#include "scenario.h"
#include "sim_config.h"
#include "sim_metrics.h"

/* The open-phase part's state (sim_open_phase.h) */
typedef struct {
    uint16_t isolated_seen; /* legs the plant treats as switched off */
    bool command_sent;
    double t_event; /* the fault's injection or the isolation command, scenario clock; < 0 none */
    double t_isolated; /* the first isolation, scenario clock; < 0 none yet */
    double min_speed_rpm;
    double peak_a; /* largest |i| of any phase from the event on */
    metrics_settle_t settle;
} sim_open_phase_t;

typedef struct sim_run {
    const sim_config_t *cfg;
    const sim_ctl_ops_t *ops;
    bool pil_open; /* ops are the PIL session's (sim_pil_open): closed at the run's end */
    sim_plan_t plan;
    plant_params_t plant; /* the plant as any injected fault leaves it */
    sim_fault_state_t fault;
    sim_adc_t adc;
    sim_encoder_t encoder;
    inverter_t inv;
    plant_state_t x;
    sim_recorder_t rec;
    sim_metrics_t metrics;
    double ts;
    uint32_t ts_ns; /* the period in the simulated clock's nanoseconds (hal_sim.h) */
    long n_periods, k_win;
    int n_fine;
    double *fine_times; /* the fine sampling instants within a period */
    double t_period;    /* start of the period being integrated */
    double duty[6];     /* leg duties loaded at the last period boundary */
    int applied_vector; /* the command in force in this period (trace) */
    double applied_duty;
    long k_detect;      /* first period in FAULT; -1: none */
    long cal_isr_calls; /* drive ISR calls of the calibration */
    double isr_wall_s;  /* host time in the timed drive ISR calls */
    long isr_timed;
    double wall0_s, wall1_s;
    sim_open_phase_t open_phase; /* open-phase operation (sim_open_phase.h) */
} sim_run_t;

/* Plan, buffers, output files, HAL and controller; 0 or a one-line message in err. */
int sim_setup(sim_run_t *rs, const sim_config_t *c, char *err, size_t err_len);

/* The drive's ADC offset calibration before the scenario clock (rotor held), then RUN. */
int sim_setup_calibrate(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len);

/* Release what sim_setup took; ok false deletes partial output files. */
void sim_teardown(sim_run_t *rs, bool ok);

/* One control period k (events, sensors, the drive's ISR, the plant over the period, the
 * recorder and metrics); -1 when the plant diverged. */
int sim_loop_period(sim_run_t *rs, sim_result_t *r, long k);

/* The PIL session failed (the run stops): why, with the period's time, into err. */
bool sim_loop_pil_failed(const sim_run_t *rs, long k, char *err, size_t err_len);

/* After period k: 0, or -1 with a one-line message when the output files reached their size
 * limit (the run or session stops there; the files end at the last whole row). */
int sim_loop_out_limit(const sim_run_t *rs, long k, char *err, size_t err_len);

/* The commissioning scenario after the calibration: the sequence until the drive leaves
 * COMMISSION, its results into r (sim_commission.c). */
int sim_commission_loop(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len);

/* The scenario: every control period. */
int sim_loop_run(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len);

/* Identity, drive status, timing and metrics of the finished run into r. */
void sim_result_fill(sim_run_t *rs, sim_result_t *r);

/* The controller's pole pairs (sim_ctl_machine_t: set, or the reference machine's). */
int sim_ctl_pole_pairs(const sim_config_t *c);
/* The controller's whole machine: each field set, or the reference machine's. */
void sim_ctl_machine_resolve(const sim_config_t *c, sim_ctl_machine_t *m);
/* The controller as the firmware's parameter set would configure it for a run: the controller's
 * machine (sim_ctl_machine_t), its inertia the reference machine's unless set; p the plant (its
 * sensors' span), ts_s the period, torque_limit_nm the scenario's (0: the core's). */
void sim_controller_config(const sim_config_t *c, const plant_params_t *p, double ts_s,
                           double torque_limit_nm, sim_ctl_config_t *cc);

/* Monotonic wall clock, s. */
double sim_wall_now(void);

#endif /* SIM_RUN_STATE_H */
