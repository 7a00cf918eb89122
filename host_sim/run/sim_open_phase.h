/*
 * Open-phase operation in a run (docs/faults.md, docs/simulator.md): the drive's background
 * share once per period after its ISR (as the board's background loop would run it), an
 * isolation command at a set time, the plant following the legs the drive isolated (their phases
 * open, plant_params_t.phase_open, the currents commutated at once as the all-off model does),
 * and the metrics of the transition and of five-leg operation. Its state is the run's
 * (sim_open_phase_t, sim_run_state.h). Internal to host_sim.
 */
#ifndef SIM_OPEN_PHASE_H
#define SIM_OPEN_PHASE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "bridge/sim_ctl.h"
#include "sim_config.h"

struct sim_run;

/* The band the speed must stay in to count as recovered (brief §7's transient band). */
#define SIM_OPEN_PHASE_BAND 0.02

/* At set-up, after the plan and the fault: when the event comes (a fault-open-phase injection or
 * an isolation command) and the second open phase. 0, or -1 with a one-line message in err when
 * a time lies outside the run (or the second fault before the first). */
int sim_open_phase_begin(struct sim_run *rs, char *err, size_t err_len);

/* After the ISR of period k at time t: the isolation command, the background, the plant's legs,
 * the first isolation and the first period on five legs. */
void sim_open_phase_period(struct sim_run *rs, sim_result_t *r, double t,
                           const sim_ctl_status_t *st);

/* Speed dip and recovery, one control period at a time. */
void sim_open_phase_track(struct sim_run *rs, double t, double speed_rpm, double speed_ref_rpm,
                          const double i_phase[6]);

/* The results into r: dip, recovery, the phases' rms and peak over the analysis window against
 * the current the healthy limit allows, the torque limit in force. */
void sim_open_phase_finish(const struct sim_run *rs, sim_result_t *r);

/* metrics.json's "open_phase" block (nothing when the run had no such event). */
void sim_open_phase_json(FILE *f, const sim_config_t *c, const sim_result_t *r);

#endif /* SIM_OPEN_PHASE_H */
